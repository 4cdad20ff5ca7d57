// Paths that touch (thesis 5.2.3). Two geodesic paths may run along the
// same visual edges for a while (on the steak, paths leaving one collision
// vertex often share their first edges), or meet at a vertex (on a torn
// meniscus, up to seven paths pass one vertex near the tear). The region
// between them then has no width there, and a vertex there serves several
// collision elements while bound to one: a cut through it (5.3.2) finds
// nothing to split on one side, or opens one element and leaves the vertex
// pinched. After re-meshing, each touch is undone: the path is re-routed
// around the touched vertices as a polyline through points on the visual
// edges around them, on the side where no path edge lies in the way, so
// that paths meet only where they begin or end together.
#ifndef SharedPathRuns_h
#define SharedPathRuns_h

#include "SurfacePath.h"
#include "TriangleMeshAdjacency.h"

#include <vector>

namespace thintissue
{

struct SharedRunSeparation
{
  /// Every path as points of the mesh: its vertices, with the vertices of
  /// a re-routed run replaced by edge points beside them.
  std::vector<SurfacePath> paths;
  /// Per path, how many of its vertices were re-routed around, and which.
  std::vector<int> detours;
  std::vector<std::vector<int>> aroundVertices;
  /// Runs of touched vertices re-routed.
  int runsSeparated = 0;
  /// Runs left as they are: paths cross there, or a side is free only once
  /// another path around it has been re-routed (the next pass does it).
  int runsKept = 0;
};

/// `pathVertices`: paths along the edges of `mesh` (consecutive vertices
/// joined by an edge), as `insertPaths` returns them. Each inner vertex of a
/// path that another path also visits is re-routed (one path per touch;
/// its end vertices stay). The re-routed points
/// lie on the edges around each run vertex, `offsetFraction` (in (0, 0.5))
/// of the edge's length from that vertex. Give the result's paths to
/// `insertPaths` on the same mesh to make them edges again.
SharedRunSeparation separateSharedRuns(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<std::vector<int>>& pathVertices,
  double offsetFraction);

} // namespace thintissue

#endif
