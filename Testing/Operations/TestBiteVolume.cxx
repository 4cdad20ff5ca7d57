// Issue 18 validation: the volume a punch bite removes is what its jaws
// enclosed, within the mesh resolution. The enclosed volume is computed
// here independently of the cutter: the tissue's closed visual surface (as
// built, before the bite) integrated along rays across the jaws, through
// the prism of the bite outline from below the fixed jaw to the open moving
// jaw, on a fine grid over the outline (thesis 6.4.2).
#include "BoxSurface.h"
#include "InstrumentAction.h"
#include "MeshQueries.h"
#include "OperationTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

using namespace thintissue;
using namespace thintissue::operations_test;

namespace
{

using Point2 = Eigen::Vector2d;

/// Where the line {(x, p.x, p.y)} (tool frame: x across the jaws) meets
/// triangle (a, b, c), if it does: its x.
bool lineHitsTriangle(const Point2& p,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c,
  double& x)
{
  // Barycentric coordinates of p in the triangle projected onto (y, z).
  const Point2 a2(a.y(), a.z()), b2(b.y(), b.z()), c2(c.y(), c.z());
  const double area = (b2 - a2).x() * (c2 - a2).y() - (b2 - a2).y() * (c2 - a2).x();
  if (std::abs(area) < 1e-14)
    return false;
  const double u = ((b2 - p).x() * (c2 - p).y() - (b2 - p).y() * (c2 - p).x()) / area;
  const double v = ((c2 - p).x() * (a2 - p).y() - (c2 - p).y() * (a2 - p).x()) / area;
  const double w = 1.0 - u - v;
  if (u < 0.0 || v < 0.0 || w < 0.0)
    return false;
  x = u * a.x() + v * b.x() + w * c.x();
  return true;
}

/// Volume of the closed surface `mesh` inside the prism over `outline`
/// (tool frame, in the plane x = 0) from x = `low` to x = `high`, the mesh
/// given in the tool frame: the inside length of each line across the
/// prism (the crossings taken in pairs) summed over a grid of `step`.
double enclosedVolume(const std::vector<Vector3>& positions,
  const std::vector<Triangle>& triangles,
  const std::vector<Vector3>& outline,
  double low,
  double high,
  double step)
{
  std::vector<Point2> polygon;
  Eigen::AlignedBox2d box;
  for (const Vector3& p : outline)
  {
    polygon.emplace_back(p.y(), p.z());
    box.extend(polygon.back());
  }
  // Only the triangles over the outline can be crossed.
  std::vector<Triangle> near;
  for (const Triangle& t : triangles)
  {
    Eigen::AlignedBox2d bounds;
    for (int v : t)
      bounds.extend(Point2(positions[v].y(), positions[v].z()));
    if (bounds.intersects(box))
      near.push_back(t);
  }
  double volume = 0.0;
  std::vector<double> crossings;
  // The grid offset by an odd fraction of a step: no line through a vertex.
  for (double y = box.min().x() + 0.37 * step; y < box.max().x(); y += step)
  {
    for (double z = box.min().y() + 0.61 * step; z < box.max().y(); z += step)
    {
      const Point2 p(y, z);
      if (!insidePolygon(polygon, p))
        continue;
      crossings.clear();
      double x = 0.0;
      for (const Triangle& t : near)
        if (lineHitsTriangle(p, positions[t[0]], positions[t[1]], positions[t[2]], x))
          crossings.push_back(x);
      EXPECT_EQ(crossings.size() % 2, 0u) << "the surface is closed";
      std::sort(crossings.begin(), crossings.end());
      for (std::size_t k = 0; k + 1 < crossings.size(); k += 2)
        volume += std::max(0.0, std::min(crossings[k + 1], high) - std::max(crossings[k], low));
    }
  }
  return volume * step * step;
}

} // namespace

// Bites at several places along the inner border, 0.5 to 1.5 mm in from it
// (the outline reaching past the border or lying mostly in the tissue), each
// into an intact meniscus: the removed rest volume against the enclosed one.
TEST(BiteVolume, ARemovedBiteIsWhatTheJawsEnclosedWithinTheMeshResolution)
{
  const BoundMeniscus& m = boundMeniscus();
  const MonitorCurve& border = m.model.monitorCurves.front();
  const InstrumentActionSettings settings;
  const SurgicalInstrumentParameters& p =
    makeSurgicalInstrument(SurgicalInstrumentType::Punch).parameters;
  // The sweep of InstrumentAction::punchBite: below the fixed jaw's face to
  // the open moving jaw (tool frame, x across the jaws).
  const double low = -settings.biteDepthBelowJaw;
  const double high = p.biteLength * std::sin(p.jawOpeningDegrees * M_PI / 180.0) + p.jawThickness;
  // The mesh resolution: the visual surface's mean edge length.
  double edges = 0.0;
  for (const Triangle& t : m.model.visual.triangles)
    for (int k = 0; k < 3; ++k)
      edges += (m.model.visual.positions[t[k]] - m.model.visual.positions[t[(k + 1) % 3]]).norm();
  const double resolution = edges / (3.0 * m.model.visual.triangleCount());
  int bites = 0;
  double worst = 0.0;
  for (const std::size_t i : { border.monitorPoints.size() * 3 / 10,
         border.monitorPoints.size() / 2,
         border.monitorPoints.size() * 7 / 10 })
  {
    for (const double inward : { 0.5, 1.0, 1.5 })
    {
      SCOPED_TRACE("monitor point " + std::to_string(i) + ", " + std::to_string(inward) + " mm in");
      TissueCutter cutter(m.binding, m.model.simulation, nullptr, handOverPieces());
      InstrumentAction punch(makeSurgicalInstrument(SurgicalInstrumentType::Punch), settings);
      const RigidPose pose = punchOverBorder(punch.instrument(), border, i, inward);
      punch.apply(cutter, command(0.0, pose, 1.0));
      const InstrumentActionResult bite = punch.apply(cutter, command(0.1, pose, 0.0));
      ASSERT_TRUE(bite.changed()) << bite.refused;
      ASSERT_GE(bite.report.removedPieces, 1) << "the bite should free its piece";

      std::vector<Vector3> local;
      for (const Vector3& x : m.model.visual.positions)
        local.push_back(pose.rotation.transpose() * (x - pose.translation));
      const double enclosed = enclosedVolume(
        local, m.model.visual.triangles, punch.instrument().biteOutline, low, high, 0.02);
      // Within the mesh resolution: the difference at most a band a quarter
      // of a visual edge wide along the outline, through the tissue's mean
      // thickness over the outline (measured: the cut runs on average
      // 0.02-0.2 mm inside the outline, the removed volume 0-27 % short).
      double perimeter = 0.0, area = 0.0;
      const std::vector<Vector3>& outline = punch.instrument().biteOutline;
      for (std::size_t k = 0; k < outline.size(); ++k)
      {
        const Vector3& a = outline[k];
        const Vector3& b = outline[(k + 1) % outline.size()];
        perimeter += (b - a).norm();
        area += 0.5 * (a.y() * b.z() - b.y() * a.z());
      }
      const double thickness = enclosed / std::abs(area);
      const double tolerance = 0.25 * resolution * perimeter * thickness;
      std::cout << "bite at " << i << ", " << inward << " mm in: removed " << bite.removedVolume
                << " mm^3, enclosed " << enclosed << " mm^3 (tolerance " << tolerance << ")\n";
      EXPECT_GT(enclosed, 1.0);
      EXPECT_NEAR(bite.removedVolume, enclosed, tolerance);
      worst = std::max(worst, std::abs(bite.removedVolume - enclosed) / enclosed);
      ++bites;
    }
  }
  std::cout << "mesh resolution " << resolution << " mm; largest relative difference " << worst
            << "\n";
  EXPECT_EQ(bites, 9);
}

// The independent measure itself: a cube 2 mm on a side, a square outline
// over part of it, the prism clipped across.
TEST(BiteVolume, TheEnclosedVolumeOfACubeIsItsPrismPart)
{
  const TriangleMesh cube =
    thintissue::testing::boxSurface(Vector3::Zero(), Vector3::Constant(2.0));
  const std::vector<Vector3> square = {
    Vector3(0.0, 0.5, 0.5), Vector3(0.0, 1.5, 0.5), Vector3(0.0, 1.5, 1.5), Vector3(0.0, 0.5, 1.5)
  };
  EXPECT_NEAR(enclosedVolume(cube.positions, cube.triangles, square, -1.0, 1.5, 0.01), 1.5, 0.02);
  // Half the outline past the cube's side: half the volume.
  std::vector<Vector3> past = square;
  for (Vector3& x : past)
    x.y() += 1.0;
  EXPECT_NEAR(enclosedVolume(cube.positions, cube.triangles, past, -5.0, 5.0, 0.01), 1.0, 0.02);
}
