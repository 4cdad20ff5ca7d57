#include "MeshPrimitives.h"
#include "MeshValidation.h"

#include <gtest/gtest.h>

using namespace thintissue;

namespace
{
TriangleMesh smallSlab()
{
  SlabSurfaceParameters p;
  p.cellsX = 3;
  p.cellsY = 3;
  TriangleMesh slab = makeSlabSurface(p);
  slab.name = "slab";
  return slab;
}

TriangleMesh tetrahedron(const Vector3& offset)
{
  TriangleMesh mesh;
  mesh.positions = {
    offset, offset + Vector3(1, 0, 0), offset + Vector3(0, 1, 0), offset + Vector3(0, 0, 1)
  };
  mesh.triangles = { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } };
  return mesh;
}
} // namespace

TEST(MeshValidation, CleanSlabIsAClosedOutwardSurface)
{
  const MeshValidationReport report = validateTriangleMesh(smallSlab());
  EXPECT_TRUE(report.isClosedManifold());
  EXPECT_TRUE(report.isClosedOutwardSingleSurface());
  EXPECT_EQ(report.connectedComponents, 1u);
  EXPECT_GT(report.signedVolume, 0.0);
  EXPECT_NE(report.toString().find("closed, manifold, outward-oriented"), std::string::npos);
}

TEST(MeshValidation, OpenBorderIsCountedAndLocated)
{
  TriangleMesh slab = smallSlab();
  const Triangle removed = slab.triangles[5];
  slab.triangles.erase(slab.triangles.begin() + 5);
  slab.textureCorners.erase(slab.textureCorners.begin() + 5);
  const MeshValidationReport report = validateTriangleMesh(slab);
  EXPECT_EQ(report.borderEdges.count, 3u);
  EXPECT_FALSE(report.isClosedManifold());
  // The first location names one of the removed triangle's vertices.
  bool named = false;
  for (int v : removed)
  {
    named |= report.borderEdges.firstLocation.find(std::to_string(v)) != std::string::npos;
  }
  EXPECT_TRUE(named) << report.borderEdges.firstLocation;
}

TEST(MeshValidation, DuplicateTriangleMakesNonManifoldEdges)
{
  TriangleMesh slab = smallSlab();
  slab.triangles.push_back(slab.triangles[7]);
  const MeshValidationReport report = validateTriangleMesh(slab);
  EXPECT_EQ(report.duplicateTriangles.count, 1u);
  EXPECT_NE(
    report.duplicateTriangles.firstLocation.find(
      "triangle " + std::to_string(slab.triangleCount() - 1) + " (same vertices as triangle 7"),
    std::string::npos)
    << report.duplicateTriangles.firstLocation;
  EXPECT_EQ(report.nonManifoldEdges.count, 3u);
  EXPECT_FALSE(report.isClosedManifold());
}

TEST(MeshValidation, FlippedTriangleIsInconsistentlyOriented)
{
  TriangleMesh slab = smallSlab();
  std::swap(slab.triangles[4][1], slab.triangles[4][2]);
  const MeshValidationReport report = validateTriangleMesh(slab);
  EXPECT_EQ(report.inconsistentlyOrientedEdges.count, 3u);
  EXPECT_EQ(report.borderEdges.count, 0u);
  EXPECT_FALSE(report.isClosedManifold());
}

TEST(MeshValidation, DegenerateTriangles)
{
  TriangleMesh mesh = tetrahedron(Vector3::Zero());
  mesh.triangles.push_back({ 0, 0, 1 });            // repeated vertex
  mesh.positions.push_back(Vector3(0.5, 0.0, 0.0)); // collinear
  mesh.triangles.push_back({ 0, 1, 4 });
  const MeshValidationReport report = validateTriangleMesh(mesh);
  EXPECT_EQ(report.degenerateTriangles.count, 2u);
  EXPECT_EQ(report.degenerateTriangles.firstLocation.rfind("triangle 4", 0), 0u);
}

TEST(MeshValidation, PiecesBowTiesAndUnreferencedVertices)
{
  TriangleMesh two = tetrahedron(Vector3::Zero());
  two.append(tetrahedron(Vector3(3, 0, 0)));
  MeshValidationReport report = validateTriangleMesh(two);
  EXPECT_EQ(report.connectedComponents, 2u);
  EXPECT_TRUE(report.isClosedManifold());
  EXPECT_FALSE(report.isClosedOutwardSingleSurface());

  // Two tetrahedra sharing only a vertex: a bow-tie (non-manifold vertex).
  TriangleMesh bowTie = tetrahedron(Vector3::Zero());
  TriangleMesh mirrored = tetrahedron(Vector3::Zero());
  for (Vector3& p : mirrored.positions)
  {
    p = -p;
  }
  mirrored.reverseOrientation();
  bowTie.append(mirrored);
  for (Triangle& tri : bowTie.triangles)
  {
    for (int& v : tri)
    {
      v = v == 4 ? 0 : v; // the mirrored apex 4 sits at vertex 0: glue them
    }
  }
  bowTie.positions[4] = Vector3(9, 9, 9); // now unreferenced
  report = validateTriangleMesh(bowTie);
  EXPECT_EQ(report.nonManifoldVertices.count, 1u);
  EXPECT_EQ(report.nonManifoldVertices.firstLocation, "vertex 0");
  EXPECT_EQ(report.unreferencedVertices.count, 1u);
  EXPECT_EQ(report.connectedComponents, 1u);
}

TEST(MeshValidation, InwardSurfaceIsReported)
{
  TriangleMesh slab = smallSlab();
  slab.reverseOrientation();
  const MeshValidationReport report = validateTriangleMesh(slab);
  EXPECT_TRUE(report.isClosedManifold());
  EXPECT_LT(report.signedVolume, 0.0);
  EXPECT_FALSE(report.isClosedOutwardSingleSurface());
  EXPECT_NE(report.toString().find("facing inward"), std::string::npos);
}
