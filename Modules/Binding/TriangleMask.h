// The triangles a geodesic search may use (private to the Binding module's
// geodesic paths: GeodesicPaths.cxx, SleeveGeodesic.cxx).
#ifndef TriangleMask_h
#define TriangleMask_h

#include "TriangleMeshAdjacency.h"

#include <algorithm>
#include <vector>

namespace thintissue
{

/// All triangles, or those marked in a mask (a path restricted to one side
/// of a thin surface, see GeodesicPathFinder::shortestPathWithin).
struct TriangleMask
{
  const std::vector<char>* allowed = nullptr;
  /// Sorted triangles allowed as well (null: none).
  const std::vector<int>* alsoAllowed = nullptr;

  bool operator()(int t) const
  {
    return allowed == nullptr || (*allowed)[t] != 0 ||
           (alsoAllowed != nullptr &&
             std::binary_search(alsoAllowed->begin(), alsoAllowed->end(), t));
  }
  /// Triangles of vertex v that may be used.
  int vertexTriangleCount(const TriangleMeshAdjacency& adjacency, int v) const
  {
    if (allowed == nullptr)
    {
      return adjacency.vertexTriangleCount(v);
    }
    int count = 0;
    for (const int* t = adjacency.vertexTrianglesBegin(v); t != adjacency.vertexTrianglesEnd(v);
         ++t)
    {
      count += (*this)(*t) ? 1 : 0;
    }
    return count;
  }
  /// Triangles of edge e that may be used.
  int edgeTriangleCount(const TriangleMeshAdjacency& adjacency, int e) const
  {
    int count = 0;
    for (const int* t = adjacency.edgeTrianglesBegin(e); t != adjacency.edgeTrianglesEnd(e); ++t)
    {
      count += (*this)(*t) ? 1 : 0;
    }
    return count;
  }
};

} // namespace thintissue

#endif
