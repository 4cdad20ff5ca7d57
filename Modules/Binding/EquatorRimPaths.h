// The equator as the border of two labelled halves (5.2.2, for rough rims).
// The rim paths of the binding are geodesics between consecutive rim
// points; together they split the closed visual surface into its positive
// and negative halves. On a segmentation's ragged rim (a staircase, a
// notch the collision border skips, a rim thinner than two slices) two
// such geodesics may double back, enclose slivers between them, or leave a
// rim point with no triangle on one half: the halves then fall apart and
// an inner path finds its ends "not connected".
//
// The equator built the other way round cannot: every visual triangle is
// labelled by the side of the collision mid-surface it lies on (its
// vertices' signed offsets along the interpolated collision normal), each
// label is kept as one connected piece (stray islands join the other
// half), pinches where the halves touch at a single vertex are removed,
// and the border between the labels is traced as loops, one per border
// loop of the collision mesh. The rim points move onto their loop, in the
// order of the collision border (a cyclic, order-keeping assignment that
// moves them least), and the rim paths are the loop's arcs between them.
// The halves are connected and every rim point touches both by
// construction; the arcs are not shortest paths (they follow the labels).
#ifndef EquatorRimPaths_h
#define EquatorRimPaths_h

#include "TriangleMeshAdjacency.h"

#include <array>
#include <utility>
#include <vector>

namespace thintissue
{

/// What the equator is built from.
struct EquatorInput
{
  const TriangleMesh* visual = nullptr; ///< closed, manifold
  const TriangleMeshAdjacency* adjacency = nullptr;
  const TriangleMesh* collision = nullptr;                ///< a mid-surface without junctions
  const std::vector<Vector3>* collisionNormals = nullptr; ///< unit, per vertex
  /// Per rim path: the border collision vertices it joins (source, target).
  std::vector<std::array<int, 2>> rimEdges;
  /// Per collision vertex: its rim point (border vertices), else -1.
  std::vector<int> rimPoints;
  /// Visual vertices known to lie on a half: (vertex, +1 or -1).
  std::vector<std::pair<int, int>> halfVotes;
};

struct EquatorRimPaths
{
  /// Per rim path (as EquatorInput::rimEdges): visual vertices along mesh
  /// edges, from the source's rim point to the target's.
  std::vector<std::vector<int>> paths;
  /// Per collision vertex: its rim point on the equator (border vertices),
  /// else -1.
  std::vector<int> rimPoints;
  /// Visual triangles whose label was changed to keep each half one piece
  /// without pinches.
  int relabelledTriangles = 0;
};

/// The rim paths along the labelled equator. InvalidInputError when the
/// labels do not make one loop per collision border loop, or a loop has
/// fewer vertices than its border loop has rim points.
EquatorRimPaths equatorRimPaths(const EquatorInput& input);

} // namespace thintissue

#endif
