// ParametricSolid: the common generator of every tissue's three meshes.
#include "ParametricSolid.h"
#include "ThinTissueError.h"
#include "TissueModelChecks.h"

#include <gtest/gtest.h>

using namespace thintissue;
using namespace thintissue::testing;

namespace
{
ParametricSolid makeBox(double width = 20.0, double depth = 10.0, double thickness = 2.0)
{
  return ParametricSolid("box",
    [=](const ParameterPoint& p) { return Vector3(p[0] * width, p[1] * depth, p[2] * thickness); });
}

ParametricCrack throughCrackAcross()
{
  ParametricCrack crack;
  crack.normalAxis = 1;
  crack.position = 0.5;
  crack.ranges = { { { 0.25, 0.75 }, { 0.0, 1.0 } } };
  crack.opening = 0.6;
  crack.influence = 0.2;
  return crack;
}
} // namespace

TEST(ParametricSolid, BoxSurfaceIsClosedOutwardWithExpectedCounts)
{
  const auto solid = makeBox();
  const auto mesh = solid.boundarySurface({ 10, 6, 2 }, 5.0);
  EXPECT_EQ(mesh.triangleCount(), 4u * (10 * 6 + 10 * 2 + 6 * 2));
  EXPECT_EQ(mesh.vertexCount(), mesh.triangleCount() / 2 + 2);
  EXPECT_TRUE(isClosedOutwardSurface(mesh));
  EXPECT_NEAR(mesh.signedVolume(), 20.0 * 10.0 * 2.0, 1e-9);
  ASSERT_EQ(mesh.textureCorners.size(), mesh.triangleCount());
  ASSERT_EQ(mesh.normals.size(), mesh.vertexCount());
}

TEST(ParametricSolid, GridLinesHoldEveryCrackAndKeepTheCellCount)
{
  auto solid = makeBox();
  solid.addCrack(throughCrackAcross());
  const auto along = solid.gridLines(0, 10);
  ASSERT_EQ(along.size(), 11u);
  EXPECT_NE(std::find(along.begin(), along.end(), 0.25), along.end());
  EXPECT_NE(std::find(along.begin(), along.end(), 0.75), along.end());
  EXPECT_TRUE(std::is_sorted(along.begin(), along.end()));
  const auto across = solid.gridLines(1, 3);
  EXPECT_NE(std::find(across.begin(), across.end(), 0.5), across.end());
  EXPECT_THROW(solid.gridLines(0, 2), InvalidInputError); // three intervals needed
}

TEST(ParametricSolid, ThroughCrackSeparatesTheLipsInAllThreeMeshes)
{
  auto solid = makeBox();
  solid.addCrack(throughCrackAcross());
  const auto surface = solid.boundarySurface({ 20, 8, 2 }, 5.0);
  // A crack inside the solid through its thickness is a hole: genus 1.
  const auto report = validateTriangleMesh(surface);
  EXPECT_TRUE(report.isClosedOutwardSingleSurface()) << report.toString();
  const long euler = static_cast<long>(report.vertexCount) - static_cast<long>(report.edgeCount) +
                     static_cast<long>(report.triangleCount);
  EXPECT_EQ(euler, 0);

  const Vector3 low = solid.openedPoint(ParameterPoint(0.5, 0.5, 0.0), { -1 });
  const Vector3 high = solid.openedPoint(ParameterPoint(0.5, 0.5, 0.0), { 1 });
  EXPECT_NEAR((high - low).norm(), 0.6, 1e-9); // the full opening mid-way
  const double visualPath =
    pathLengthBetween(surface.positions, triangleMeshNeighbours(surface), low, high);
  EXPECT_GT(visualPath, 8.0); // around a tear front 5 units away

  const auto mid = solid.midSurface(8, 4);
  const double midPath = pathLengthBetween(mid.positions,
    triangleMeshNeighbours(mid),
    solid.openedPoint(ParameterPoint(0.5, 0.5, 0.5), { -1 }),
    solid.openedPoint(ParameterPoint(0.5, 0.5, 0.5), { 1 }));
  EXPECT_GT(midPath, 8.0);

  const auto hexahedra = solid.hexahedra({ 8, 4, 1 }, { 0.0, 0.0, 0.0 }, {});
  // Nodes on the crack inside its range are doubled: 3 along x 2 layers.
  EXPECT_EQ(hexahedra.nodeCount(), 9u * 5u * 2u + 3u * 2u);
  const double hexPath =
    pathLengthBetween(hexahedra.nodes, hexahedralMeshNeighbours(hexahedra), low, high);
  EXPECT_GT(hexPath, 8.0);
}

TEST(ParametricSolid, HorizontalCrackGivesEachLeafItsOwnMidSurface)
{
  auto solid = makeBox(20.0, 10.0, 4.0);
  ParametricCrack cleavage;
  cleavage.normalAxis = 2;
  cleavage.position = 0.5;
  cleavage.ranges = { { { 0.25, 0.75 }, { 0.0, 0.5 } } };
  cleavage.opening = 0.0;
  solid.addCrack(cleavage);
  const auto mid = solid.midSurface(4, 2);
  const auto& radius = mid.pointAttributes.get("Radius").values;
  // Nodes strictly inside the cleaved region (s = 0.5 at u = 0) get two
  // copies at a quarter and three quarters of the thickness, radius 1.
  int leafVertices = 0;
  for (std::size_t v = 0; v < mid.vertexCount(); ++v)
  {
    if (std::abs(mid.positions[v].x() - 10.0) < 1e-9 && std::abs(mid.positions[v].y()) < 1e-9)
    {
      ++leafVertices;
      EXPECT_NEAR(radius[v], 1.0, 1e-9);
      EXPECT_TRUE(
        std::abs(mid.positions[v].z() - 1.0) < 1e-9 || std::abs(mid.positions[v].z() - 3.0) < 1e-9);
    }
  }
  EXPECT_EQ(leafVertices, 2);
  EXPECT_EQ(mid.triangleCount(), 2u * (4 * 2 + 2));
  EXPECT_TRUE(isClosedOutwardSurface(solid.boundarySurface({ 8, 4, 2 }, 1.0)));
}

TEST(ParametricSolid, HexahedraArePositiveAndFixedWherePredicateSays)
{
  const auto solid = makeBox();
  const auto mesh = solid.hexahedra(
    { 4, 2, 1 }, { 0.5, 0.5, 0.0 }, [](const ParameterPoint& p) { return p[0] <= 0.0; });
  ASSERT_EQ(mesh.hexahedronCount(), 8u);
  ASSERT_EQ(mesh.nodeCount(), 5u * 3u * 2u);
  EXPECT_EQ(mesh.fixedNodeCount(), 3u * 2u);
  const auto box = mesh.boundingBox();
  EXPECT_NEAR(box.min().x(), -0.5, 1e-6);
  EXPECT_NEAR(box.max().y(), 10.5, 1e-6);
  for (std::size_t h = 0; h < mesh.hexahedronCount(); ++h)
  {
    Vector3 local;
    ASSERT_TRUE(trilinearCoordinates(hexahedronCorners(mesh, h), mesh.hexahedronCentre(h), local));
    EXPECT_TRUE(isInsideUnitCube(local)) << "hexahedron " << h << " is inverted";
    EXPECT_NEAR(local.x(), 0.5, 1e-9);
  }
}

TEST(ParametricSolid, RejectsBadCracksAndLeftHandedMaps)
{
  auto solid = makeBox();
  ParametricCrack crack = throughCrackAcross();
  crack.position = 1.0;
  EXPECT_THROW(solid.addCrack(crack), InvalidInputError);
  crack = throughCrackAcross();
  crack.ranges[0] = { 0.7, 0.2 };
  EXPECT_THROW(solid.addCrack(crack), InvalidInputError);
  crack = throughCrackAcross();
  crack.opening = -1.0;
  EXPECT_THROW(solid.addCrack(crack), InvalidInputError);
  const ParametricSolid mirrored(
    "mirrored", [](const ParameterPoint& p) { return Vector3(-p[0], p[1], p[2]); });
  EXPECT_THROW(mirrored.boundarySurface({ 2, 2, 2 }, 1.0), InvalidInputError);
}
