#include "MeshPrimitives.h"
#include "MeshValidation.h"

#include "TetrahedronSurfaces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <string>

using namespace thintissue;
using thintissue::testing::tetrahedronSurface;

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

// Duplicates are found through the first edge's triangles, not by sorting
// the vertex sets, and most fans by walking round the vertex: the same
// duplicate count and first location as comparing every pair, and the same
// bow-ties as grouping every vertex's triangles, on random triangles over
// few vertices (permuted and repeated triangles, triangles repeating a
// vertex, non-manifold edges) and on closed tetrahedra sharing vertices.
TEST(MeshValidation, DuplicatesAndBowTiesMatchBruteForce)
{
  std::mt19937 random(20261129);
  for (int trial = 0; trial < 200; ++trial)
  {
    TriangleMesh mesh;
    const int vertices = 4 + trial % 5;
    for (int v = 0; v < vertices; ++v)
    {
      mesh.positions.emplace_back(std::cos(v), std::sin(2.0 * v), 0.1 * v);
    }
    std::uniform_int_distribution<int> vertex(0, vertices - 1);
    if (trial % 4 == 0)
    {
      // Closed tetrahedra, each joined to the first at vertex 0 or apart.
      for (int piece = 0; piece < 1 + trial % 3; ++piece)
      {
        const int base = static_cast<int>(mesh.positions.size());
        for (int k = 0; k < 4; ++k)
          mesh.positions.emplace_back(piece + 0.3 * k, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0);
        const int apex = piece > 0 && random() % 2 == 0 ? 0 : base;
        for (const Triangle& c : tetrahedronSurface(Vector3::Zero()).triangles)
          mesh.triangles.push_back({ c[0] == 0 ? apex : base + c[0],
            c[1] == 0 ? apex : base + c[1],
            c[2] == 0 ? apex : base + c[2] });
      }
    }
    else
    {
      for (int t = 0; t < 2 + trial % 13; ++t)
        mesh.triangles.push_back({ vertex(random), vertex(random), vertex(random) });
    }
    const int triangles = static_cast<int>(mesh.triangles.size());
    auto vertexSet = [&](int t)
    {
      std::array<int, 3> sorted = mesh.triangles[t];
      std::sort(sorted.begin(), sorted.end());
      return sorted;
    };
    std::size_t count = 0;
    std::string first;
    for (int t = 0; t < triangles; ++t)
    {
      for (int u = 0; u < t; ++u)
      {
        if (vertexSet(u) == vertexSet(t))
        {
          if (count++ == 0)
          {
            first = "triangle " + std::to_string(t) + " (same vertices as triangle " +
                    std::to_string(u) + ", at vertex " + std::to_string(mesh.triangles[t][0]) + ")";
          }
          break;
        }
      }
    }
    // Bow-ties: vertices whose triangles fall into several groups joined
    // across shared edges through the vertex, grouped by relabelling.
    std::size_t bowTies = 0;
    for (int v = 0; v < static_cast<int>(mesh.positions.size()); ++v)
    {
      std::vector<int> fan;
      for (int t = 0; t < triangles; ++t)
      {
        const Triangle& c = mesh.triangles[t];
        if (c[0] == v || c[1] == v || c[2] == v)
          fan.push_back(t);
      }
      std::vector<int> group(fan.size());
      std::iota(group.begin(), group.end(), 0);
      auto throughV = [&](int t, int w)
      {
        const Triangle& c = mesh.triangles[t];
        for (int k = 0; k < 3; ++k)
        {
          const int a = c[k];
          const int b = c[(k + 1) % 3];
          if ((a == v && b == w) || (a == w && b == v))
            return true;
        }
        return false;
      };
      for (bool merged = true; merged;)
      {
        merged = false;
        for (std::size_t i = 0; i < fan.size(); ++i)
          for (std::size_t j = 0; j < fan.size(); ++j)
            for (int w = 0; w < static_cast<int>(mesh.positions.size()) && group[i] != group[j];
                 ++w)
              if (throughV(fan[i], w) && throughV(fan[j], w))
              {
                const int low = std::min(group[i], group[j]);
                group[i] = group[j] = low;
                merged = true;
              }
      }
      std::sort(group.begin(), group.end());
      bowTies += std::unique(group.begin(), group.end()) - group.begin() > 1 ? 1 : 0;
    }
    const MeshValidationReport report = validateTriangleMesh(mesh);
    EXPECT_EQ(report.nonManifoldVertices.count, bowTies) << "trial " << trial;
    EXPECT_EQ(report.duplicateTriangles.count, count) << "trial " << trial;
    EXPECT_EQ(report.duplicateTriangles.firstLocation, first) << "trial " << trial;
  }
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
  TriangleMesh mesh = tetrahedronSurface(Vector3::Zero());
  mesh.triangles.push_back({ 0, 0, 1 });            // repeated vertex
  mesh.positions.push_back(Vector3(0.5, 0.0, 0.0)); // collinear
  mesh.triangles.push_back({ 0, 1, 4 });
  const MeshValidationReport report = validateTriangleMesh(mesh);
  EXPECT_EQ(report.degenerateTriangles.count, 2u);
  EXPECT_EQ(report.degenerateTriangles.firstLocation.rfind("triangle 4", 0), 0u);
}

TEST(MeshValidation, PiecesBowTiesAndUnreferencedVertices)
{
  TriangleMesh two = tetrahedronSurface(Vector3::Zero());
  two.append(tetrahedronSurface(Vector3(3, 0, 0)));
  MeshValidationReport report = validateTriangleMesh(two);
  EXPECT_EQ(report.connectedComponents, 2u);
  EXPECT_TRUE(report.isClosedManifold());
  EXPECT_FALSE(report.isClosedOutwardSingleSurface());

  // Two tetrahedra sharing only a vertex: a bow-tie (non-manifold vertex).
  TriangleMesh bowTie = thintissue::testing::tetrahedraSharingAVertex();
  bowTie.positions.push_back(Vector3(9, 9, 9)); // unreferenced
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
