#include "MeshPrimitives.h"
#include "TriangleMeshAdjacency.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <utility>
#include <vector>

using namespace thintissue;

TEST(TriangleMeshAdjacency, ClosedSurfaceHasTwoTrianglesPerEdge)
{
  SlabSurfaceParameters p;
  p.cellsX = 5;
  p.cellsY = 4;
  const TriangleMesh slab = makeSlabSurface(p);
  const TriangleMeshAdjacency adjacency(slab);
  EXPECT_EQ(adjacency.edgeCount(), 3 * slab.triangleCount() / 2);
  // Euler characteristic of a sphere-like surface.
  EXPECT_EQ(static_cast<long>(slab.vertexCount()) - static_cast<long>(adjacency.edgeCount()) +
              static_cast<long>(slab.triangleCount()),
    2);
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e)
  {
    EXPECT_EQ(adjacency.edgeTriangleCount(static_cast<int>(e)), 2);
  }
  for (int t = 0; t < static_cast<int>(slab.triangleCount()); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int n = adjacency.neighbourAcross(t, k);
      ASSERT_GE(n, 0);
      // The neighbour shares the edge's two vertices.
      const int a = slab.triangles[t][k];
      const int b = slab.triangles[t][(k + 1) % 3];
      int shared = 0;
      for (int v : slab.triangles[n])
      {
        shared += (v == a || v == b) ? 1 : 0;
      }
      EXPECT_EQ(shared, 2);
    }
  }
}

TEST(TriangleMeshAdjacency, OpenTriangleAndLookups)
{
  const std::vector<Triangle> triangles = { { 0, 1, 2 }, { 0, 2, 3 } };
  const TriangleMeshAdjacency adjacency(4, triangles);
  EXPECT_EQ(adjacency.edgeCount(), 5u);
  const int diagonal = adjacency.findEdge(2, 0);
  ASSERT_GE(diagonal, 0);
  EXPECT_EQ(adjacency.edgeTriangleCount(diagonal), 2);
  EXPECT_EQ(adjacency.findEdge(1, 3), -1);
  EXPECT_TRUE(adjacency.isBorderEdge(adjacency.findEdge(0, 1)));
  EXPECT_EQ(adjacency.neighbourAcross(0, 0), -1);
  EXPECT_EQ(adjacency.neighbourAcross(0, 2), 1);
  EXPECT_EQ(adjacency.vertexTriangleCount(0), 2);
  EXPECT_EQ(adjacency.vertexTriangleCount(3), 1);
}

// Genus from the Euler characteristic: a closed octahedron has none, a
// torus (a grid wrapped both ways) one; vertices without a triangle do not
// count.
TEST(TriangleMeshAdjacency, ClosedSurfaceGenus)
{
  auto torus = [](int n, int m)
  {
    TriangleMesh mesh;
    mesh.positions.resize(static_cast<std::size_t>(n) * m, Vector3::Zero());
    auto at = [&](int i, int j) { return ((i + n) % n) * m + (j + m) % m; };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j)
      {
        mesh.triangles.push_back({ at(i, j), at(i + 1, j), at(i + 1, j + 1) });
        mesh.triangles.push_back({ at(i, j), at(i + 1, j + 1), at(i, j + 1) });
      }
    return mesh;
  };
  TriangleMesh ring = torus(6, 4);
  EXPECT_EQ(TriangleMeshAdjacency(ring).closedSurfaceGenus(), 1);
  ring.positions.push_back(Vector3::Zero()); // unreferenced: not counted
  EXPECT_EQ(TriangleMeshAdjacency(ring).closedSurfaceGenus(), 1);
  TriangleMesh octahedron;
  octahedron.positions.resize(6, Vector3::Zero());
  octahedron.triangles = { { 0, 2, 4 },
    { 2, 1, 4 },
    { 1, 3, 4 },
    { 3, 0, 4 },
    { 2, 0, 5 },
    { 1, 2, 5 },
    { 3, 1, 5 },
    { 0, 3, 5 } };
  EXPECT_EQ(TriangleMeshAdjacency(octahedron).closedSurfaceGenus(), 0);
}

// The edges come in (lower vertex, upper vertex) order, each edge's
// triangles in increasing order, and every triangle corner names its edge:
// checked against a map of every half-edge on a shuffled mesh with
// non-manifold edges (three and four triangles on one edge) and open ones.
TEST(TriangleMeshAdjacency, EdgesInVertexOrderWithTheirTrianglesAscending)
{
  std::vector<thintissue::Triangle> triangles;
  std::mt19937 random(7);
  std::uniform_int_distribution<int> vertex(0, 39);
  while (triangles.size() < 400)
  {
    const thintissue::Triangle t{ vertex(random), vertex(random), vertex(random) };
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
      triangles.push_back(t);
  }
  const thintissue::TriangleMeshAdjacency adjacency(40, triangles);
  std::map<std::pair<int, int>, std::vector<int>> expected;
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
    for (int k = 0; k < 3; ++k)
      expected[std::minmax(triangles[t][k], triangles[t][(k + 1) % 3])].push_back(t);
  ASSERT_EQ(adjacency.edgeCount(), expected.size());
  int e = 0;
  for (const auto& [ends, owners] : expected)
  {
    EXPECT_EQ(adjacency.edge(e)[0], ends.first);
    EXPECT_EQ(adjacency.edge(e)[1], ends.second);
    const std::vector<int> found(adjacency.edgeTrianglesBegin(e), adjacency.edgeTrianglesEnd(e));
    EXPECT_EQ(found, owners) << "edge " << e;
    ++e;
  }
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
    for (int k = 0; k < 3; ++k)
    {
      const auto& ends = adjacency.edge(adjacency.triangleEdges(t)[k]);
      EXPECT_EQ(
        std::minmax(ends[0], ends[1]), std::minmax(triangles[t][k], triangles[t][(k + 1) % 3]));
    }
}
