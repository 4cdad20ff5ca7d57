// Edge and vertex adjacency of a triangle mesh, in compressed (CSR) form.
// Derived data: build it from a mesh when needed, rebuild after the mesh's
// topology changes.
#ifndef TriangleMeshAdjacency_h
#define TriangleMeshAdjacency_h

#include "ThinTissueCoreModule.h"
#include "TriangleMesh.h"

#include <array>
#include <vector>

namespace thintissue
{

/// Undirected edges (smaller vertex index first), the triangles around each
/// edge and vertex, and each triangle's three edges. Edge k of triangle t
/// joins its corners k and (k+1) % 3.
class THINTISSUECORE_EXPORT TriangleMeshAdjacency
{
public:
  TriangleMeshAdjacency() = default;
  explicit TriangleMeshAdjacency(const TriangleMesh& mesh);
  TriangleMeshAdjacency(std::size_t vertexCount, const std::vector<Triangle>& triangles);

  std::size_t edgeCount() const { return Edges.size(); }
  const std::array<int, 2>& edge(int e) const { return Edges[e]; }
  const std::array<int, 3>& triangleEdges(int t) const { return TriangleEdges[t]; }

  /// Number of triangles using edge e: 1 on a border, 2 inside a manifold,
  /// more on a non-manifold edge.
  int edgeTriangleCount(int e) const { return EdgeTriangleOffsets[e + 1] - EdgeTriangleOffsets[e]; }
  const int* edgeTrianglesBegin(int e) const
  {
    return EdgeTriangles.data() + EdgeTriangleOffsets[e];
  }
  const int* edgeTrianglesEnd(int e) const
  {
    return EdgeTriangles.data() + EdgeTriangleOffsets[e + 1];
  }

  int vertexTriangleCount(int v) const
  {
    return VertexTriangleOffsets[v + 1] - VertexTriangleOffsets[v];
  }
  const int* vertexTrianglesBegin(int v) const
  {
    return VertexTriangles.data() + VertexTriangleOffsets[v];
  }
  const int* vertexTrianglesEnd(int v) const
  {
    return VertexTriangles.data() + VertexTriangleOffsets[v + 1];
  }

  /// The triangle across edge k of triangle t, or -1 on a border or
  /// non-manifold edge.
  int neighbourAcross(int t, int k) const;
  /// Index of the edge joining a and b, or -1.
  int findEdge(int a, int b) const;
  bool isBorderEdge(int e) const { return edgeTriangleCount(e) == 1; }
  /// Genus of the surface, taken as closed and connected: the holes through
  /// it (a tear's gap, a segmentation's tunnels), from its Euler
  /// characteristic over the vertices that have a triangle.
  int closedSurfaceGenus() const;
  /// Fans of triangles around vertex v: its triangles grouped when they
  /// share an edge through v (1 for a manifold vertex, more at a bow-tie, 0
  /// for an unreferenced vertex). Most vertices of a closed surface are
  /// settled by walking round the vertex once; the others by union-find.
  int vertexFanCount(int v) const;

private:
  std::vector<std::array<int, 2>> Edges;
  std::vector<std::array<int, 3>> TriangleEdges;
  std::vector<int> EdgeTriangleOffsets;
  std::vector<int> EdgeTriangles;
  std::vector<int> VertexTriangleOffsets;
  std::vector<int> VertexTriangles;
};

} // namespace thintissue

#endif
