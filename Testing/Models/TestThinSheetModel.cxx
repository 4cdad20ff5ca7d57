// The thin sheet of thesis section 5.4.2 (tables 5-3 to 5-6).
#include "ThinSheetModel.h"
#include "ThinTissueError.h"
#include "TissueModelChecks.h"

#include <gtest/gtest.h>

using namespace thintissue;
using namespace thintissue::testing;

TEST(ThinSheetModel, VisualResolutionsMatchTable53)
{
  const int thesisVertices[4] = { 881, 3425, 13505, 53633 };
  const int thesisTriangles[4] = { 1664, 6656, 26624, 106496 };
  for (int model = 1; model <= 4; ++model)
  {
    SCOPED_TRACE("visual model " + std::to_string(model));
    const auto sheet = makeThinSheet(thesisSheetVisualResolution(model));
    EXPECT_TRUE(isWithinFraction(sheet.visual.vertexCount(), thesisVertices[model - 1], 0.05));
    EXPECT_TRUE(isWithinFraction(sheet.visual.triangleCount(), thesisTriangles[model - 1], 0.05));
    EXPECT_TRUE(isClosedOutwardSurface(sheet.visual));
    EXPECT_EQ(sheet.visual.normals.size(), sheet.visual.vertexCount());
    EXPECT_EQ(sheet.visual.textureCorners.size(), sheet.visual.triangleCount());
  }
}

TEST(ThinSheetModel, MillionTriangleSheetBeyondTheThesis)
{
  const auto sheet = makeThinSheet(thesisSheetVisualResolution(5));
  EXPECT_TRUE(isWithinFraction(sheet.visual.triangleCount(), 1.0e6, 0.01));
  EXPECT_EQ(sheet.visual.vertexCount(), sheet.visual.triangleCount() / 2 + 2);
}

TEST(ThinSheetModel, CollisionResolutionsMatchTable55)
{
  const int thesisVertices[3] = { 65, 280, 796 };
  const int thesisTriangles[3] = { 104, 500, 1500 };
  for (int model = 1; model <= 3; ++model)
  {
    SCOPED_TRACE("collision model " + std::to_string(model));
    const auto sheet = makeThinSheet(thesisSheetCollisionResolution(model));
    EXPECT_TRUE(isWithinFraction(sheet.collision.vertexCount(), thesisVertices[model - 1], 0.05));
    EXPECT_TRUE(
      isWithinFraction(sheet.collision.triangleCount(), thesisTriangles[model - 1], 0.05));
    const auto report = validateTriangleMesh(sheet.collision);
    EXPECT_EQ(report.nonManifoldEdges.count, 0u);
    EXPECT_EQ(report.inconsistentlyOrientedEdges.count, 0u);
    EXPECT_EQ(report.degenerateTriangles.count, 0u);
    EXPECT_EQ(report.connectedComponents, 1u);
    EXPECT_NEAR(sheet.collision.surfaceArea(), 100.0 * 100.0, 1e-6);
    // Near-equilateral: no angle below 45 degrees.
    for (std::size_t t = 0; t < sheet.collision.triangleCount(); ++t)
    {
      const auto& tri = sheet.collision.triangles[t];
      for (int k = 0; k < 3; ++k)
      {
        const Vector3 e1 =
          sheet.collision.positions[tri[(k + 1) % 3]] - sheet.collision.positions[tri[k]];
        const Vector3 e2 =
          sheet.collision.positions[tri[(k + 2) % 3]] - sheet.collision.positions[tri[k]];
        const double angle = std::acos(e1.normalized().dot(e2.normalized())) * 180.0 / M_PI;
        EXPECT_GT(angle, 25.0) << "triangle " << t;
      }
    }
  }
}

TEST(ThinSheetModel, HexahedraOfTheThesisCoverTheSheetAndHoldItAtTwoEdges)
{
  const auto sheet = makeThinSheet(ThinSheetParameters{});
  EXPECT_EQ(sheet.simulation.nodeCount(), 200u);
  EXPECT_EQ(sheet.simulation.hexahedronCount(), 81u);
  EXPECT_EQ(sheet.simulation.fixedNodeCount(), 2u * 10u * 2u);
  for (std::size_t n = 0; n < sheet.simulation.nodeCount(); ++n)
  {
    const bool onAttachedEdge = std::abs(std::abs(sheet.simulation.nodes[n].x()) - 50.0) < 1e-9;
    EXPECT_EQ(sheet.simulation.isFixed(n), onAttachedEdge) << "node " << n;
  }
  EXPECT_TRUE(isCoveredByHexahedra(sheet.collision.positions, sheet.simulation));
  EXPECT_TRUE(isCoveredByHexahedra(sheet.visual.positions, sheet.simulation));
}

TEST(ThinSheetModel, CollisionMidSurfaceIsInsideWithHalfThicknessRadii)
{
  const auto sheet = makeThinSheet(thesisSheetVisualResolution(1));
  EXPECT_LT(thicknessToExtentRatio(sheet.visual), 0.05);
  EXPECT_TRUE(isInsideVolume(sheet.collision, sheet.visual));
  EXPECT_TRUE(radiiMatchHalfThickness(sheet.collision, sheet.collisionRadii(), sheet.visual, 0.10));
}

TEST(ThinSheetModel, IsDeterministic)
{
  const auto a = makeThinSheet(ThinSheetParameters{});
  const auto b = makeThinSheet(ThinSheetParameters{});
  EXPECT_EQ(a.visual.positions, b.visual.positions);
  EXPECT_EQ(a.visual.triangles, b.visual.triangles);
  EXPECT_EQ(a.collision.positions, b.collision.positions);
  EXPECT_EQ(a.simulation.nodes, b.simulation.nodes);
}

TEST(ThinSheetModel, BadParametersAreNamed)
{
  auto expectError = [](ThinSheetParameters p, const std::string& word)
  {
    try
    {
      makeThinSheet(p);
      ADD_FAILURE() << "no error for bad " << word;
    }
    catch (const InvalidInputError& error)
    {
      EXPECT_NE(std::string(error.what()).find(word), std::string::npos) << error.what();
    }
  };
  ThinSheetParameters p;
  p.width = 0.0;
  expectError(p, "width");
  p = {};
  p.depth = -3.0;
  expectError(p, "depth");
  p = {};
  p.thickness = std::nan("");
  expectError(p, "thickness");
  p = {};
  p.thickness = 150.0;
  expectError(p, "thickness");
  p = {};
  p.visualCellsX = 0;
  expectError(p, "visual cells");
  p = {};
  p.collisionRows = 0;
  expectError(p, "collision rows");
  p = {};
  p.hexahedraZ = 0;
  expectError(p, "hexahedra");
  EXPECT_THROW(thesisSheetVisualResolution(6), InvalidInputError);
  EXPECT_THROW(thesisSheetCollisionResolution(0), InvalidInputError);
}
