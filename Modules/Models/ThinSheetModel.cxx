#include "ThinSheetModel.h"

#include "ModelParameterChecks.h"
#include "ParametricSolid.h"
#include "ThinTissueError.h"

#include <cmath>
#include <sstream>

namespace thintissue
{

namespace
{

const detail::ParameterChecks Checks("thin sheet");

/// Mid-surface lattice of near-equilateral triangles over the unit square:
/// rows of `columns` + 1 points alternate with rows of `columns` + 2 points
/// (shifted by half a column, plus the two ends) so that the border stays
/// straight. Adjacent rows are zipped into triangles.
void makeLattice(int columns,
  int rows,
  std::vector<Vector2>& points,
  std::vector<Triangle>& triangles)
{
  std::vector<std::vector<int>> rowPoints(rows + 1);
  for (int r = 0; r <= rows; ++r)
  {
    const double v = static_cast<double>(r) / rows;
    auto add = [&](double u)
    {
      rowPoints[r].push_back(static_cast<int>(points.size()));
      points.emplace_back(u, v);
    };
    if (r % 2 == 0)
    {
      for (int c = 0; c <= columns; ++c)
      {
        add(static_cast<double>(c) / columns);
      }
    }
    else
    {
      add(0.0);
      for (int c = 0; c < columns; ++c)
      {
        add((c + 0.5) / columns);
      }
      add(1.0);
    }
  }
  for (int r = 0; r < rows; ++r)
  {
    const auto& lower = rowPoints[r];
    const auto& upper = rowPoints[r + 1];
    std::size_t a = 0;
    std::size_t b = 0;
    // Advance along whichever row's next point is further left (on a tie,
    // the row whose current point is further left, which keeps the end
    // triangles isosceles); both triangles are counter-clockwise from +z.
    while (a + 1 < lower.size() || b + 1 < upper.size())
    {
      bool advanceLower = b + 1 >= upper.size();
      if (!advanceLower && a + 1 < lower.size())
      {
        const double nextLower = points[lower[a + 1]].x();
        const double nextUpper = points[upper[b + 1]].x();
        advanceLower = nextLower < nextUpper ||
                       (nextLower == nextUpper && points[lower[a]].x() <= points[upper[b]].x());
      }
      if (advanceLower)
      {
        triangles.push_back({ lower[a], lower[a + 1], upper[b] });
        ++a;
      }
      else
      {
        triangles.push_back({ lower[a], upper[b + 1], upper[b] });
        ++b;
      }
    }
  }
}

} // namespace

ThinSheetParameters thesisSheetVisualResolution(int model, ThinSheetParameters parameters)
{
  // Closed genus-0 surfaces have V = T/2 + 2, while the thesis's sheets have
  // V - T/2 = 49 ... 385 (open or seam-split meshes); these cell counts keep
  // both figures within 5% (table 5-3).
  static const int cells[5][2] = { { 19, 20 }, { 40, 40 }, { 80, 82 }, { 162, 163 }, { 499, 500 } };
  if (model < 1 || model > 5)
  {
    throw InvalidInputError(
      "thin sheet: thesis visual model must be 1 to 4 (table 5-3) or 5 (1M triangles), got " +
      std::to_string(model));
  }
  parameters.visualCellsX = cells[model - 1][0];
  parameters.visualCellsY = cells[model - 1][1];
  parameters.visualCellsZ = 1;
  return parameters;
}

ThinSheetParameters thesisSheetCollisionResolution(int model, ThinSheetParameters parameters)
{
  // Lattices giving 67 v / 104 t, 279 v / 493 t and 795 v / 1,479 t beside
  // the thesis's 65 / 104, 280 / 500 and 796 / 1,500 (table 5-5).
  static const int lattice[3][2] = { { 6, 8 }, { 14, 17 }, { 25, 29 } };
  if (model < 1 || model > 3)
  {
    throw InvalidInputError("thin sheet: thesis collision model must be 1 to 3 (table 5-5), got " +
                            std::to_string(model));
  }
  parameters.collisionColumns = lattice[model - 1][0];
  parameters.collisionRows = lattice[model - 1][1];
  return parameters;
}

TissueModel makeThinSheet(const ThinSheetParameters& p)
{
  Checks.requirePositive(p.width, "width");
  Checks.requirePositive(p.depth, "depth");
  Checks.requirePositive(p.thickness, "thickness");
  Checks.requirePositive(p.textureScale, "texture scale");
  if (p.thickness >= std::min(p.width, p.depth))
  {
    std::ostringstream message;
    message << "thin sheet: thickness " << p.thickness
            << " must be smaller than the width and depth (" << p.width << " x " << p.depth << ")";
    throw InvalidInputError(message.str());
  }
  Checks.requireAtLeast(p.visualCellsX, 1, "visual cells along x");
  Checks.requireAtLeast(p.visualCellsY, 1, "visual cells along y");
  Checks.requireAtLeast(p.visualCellsZ, 1, "visual cells along z");
  Checks.requireAtLeast(p.collisionColumns, 1, "collision columns");
  Checks.requireAtLeast(p.collisionRows, 1, "collision rows");
  Checks.requireAtLeast(p.hexahedraX, 1, "hexahedra along x");
  Checks.requireAtLeast(p.hexahedraY, 1, "hexahedra along y");
  Checks.requireAtLeast(p.hexahedraZ, 1, "hexahedra along z");

  const double width = p.width;
  const double depth = p.depth;
  const double thickness = p.thickness;
  const ParametricSolid solid("thin sheet",
    [=](const ParameterPoint& q)
    { return Vector3((q[0] - 0.5) * width, (q[1] - 0.5) * depth, (q[2] - 0.5) * thickness); });

  TissueModel model;
  model.name = "thin sheet";
  model.visual =
    solid.boundarySurface({ p.visualCellsX, p.visualCellsY, p.visualCellsZ }, p.textureScale);
  model.visual.name = "thin sheet visual";

  std::vector<Vector2> latticePoints;
  makeLattice(p.collisionColumns, p.collisionRows, latticePoints, model.collision.triangles);
  model.collision.name = "thin sheet collision";
  model.collision.positions.reserve(latticePoints.size());
  for (const auto& q : latticePoints)
  {
    model.collision.positions.push_back(solid.point(ParameterPoint(q.x(), q.y(), 0.5)));
  }
  model.collision.pointAttributes.set(
    CollisionRadiusArrayName, 1, std::vector<double>(latticePoints.size(), 0.5 * thickness));
  model.collision.computeVertexNormals();

  const SheetAttachment attachment = p.attachment;
  model.simulation = solid.hexahedra({ p.hexahedraX, p.hexahedraY, p.hexahedraZ },
    { 0.0, 0.0, 0.0 },
    [attachment](const ParameterPoint& q)
    {
      const bool left = q[0] <= 0.0;
      const bool right = q[0] >= 1.0;
      const bool frontOrBack = q[1] <= 0.0 || q[1] >= 1.0;
      switch (attachment)
      {
        case SheetAttachment::LeftEdge:
          return left;
        case SheetAttachment::LeftAndRightEdges:
          return left || right;
        case SheetAttachment::AllEdges:
          return left || right || frontOrBack;
        case SheetAttachment::None:
          break;
      }
      return false;
    });
  model.simulation.name = "thin sheet hexahedra";
  return model;
}

} // namespace thintissue
