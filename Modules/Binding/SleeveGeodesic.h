// Geodesic paths through a sleeve of triangles (private to the Binding
// module; GeodesicPathFinder's default, thesis 5.2.2).
//
// A sleeve is a strip of triangles, each sharing an edge (a portal) with
// the next. Unfolded into the plane, the shortest path through it is found
// by the funnel algorithm (Lee and Preparata): straight in the strip,
// bending only at the strip's border vertices, in time linear in its
// length. The sleeve starts as an A* search over triangles (centroid to
// centroid, in the triangles a mask allows). A bend at vertex v is where a
// geodesic may run only if the surface's angle at v on the other side of
// the path is at least pi (Mitchell, Mount and Papadimitriou): otherwise
// the path is shortened by going round v on that side, so the sleeve takes
// v's other triangles instead and the funnel runs again. Each such reroute
// shortens the path, and the result is a locally shortest path: exact
// (straight across every edge, bends only where a geodesic may bend) and,
// from a sleeve found by A* near the shortest one, the shortest path,
// checked against CGAL's Xin-Wang algorithm in the tests. It costs the
// triangles along the path, not the square of a patch around it.
#ifndef SleeveGeodesic_h
#define SleeveGeodesic_h

#include "SurfacePath.h"
#include "TriangleMask.h"
#include "TriangleMeshAdjacency.h"

#include <cstddef>
#include <optional>

namespace thintissue
{

struct SleeveStatistics
{
  std::size_t searchedVertices = 0; ///< vertices the edge-path search reached
  std::size_t sleeveTriangles = 0;  ///< of the final sleeve
  int reroutes = 0;                 ///< bends moved to a vertex's other side
};

/// The locally shortest path from vertex `source` to vertex `target`
/// (source != target) through the triangles `mask` allows, as
/// GeodesicPathFinder::shortestPath reports paths (consecutive points on a
/// common triangle, edge parameters within 1e-12 of an end snapped to the
/// vertex). Nothing when no sleeve joins them or the sleeve degenerates
/// (it would visit a triangle twice, or the reroutes do not settle): the
/// caller then takes CGAL's exact path on a patch.
std::optional<SurfacePath> sleeveGeodesic(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  int source,
  int target,
  SleeveStatistics* statistics = nullptr);

} // namespace thintissue

#endif
