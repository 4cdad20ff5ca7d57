// Geometric queries on triangle surfaces (brute force, exact enough for
// set-up, validation and tests; the real-time paths use their own BVHs).
#ifndef MeshQueries_h
#define MeshQueries_h

#include "ThinTissueCoreModule.h"
#include "TriangleMesh.h"

#include <vector>

namespace thintissue
{

/// Generalised winding number of `point` with respect to the surface: 1
/// inside a closed outward surface, 0 outside, 1/2 on it (sum of signed
/// solid angles, Van Oosterom and Strackee).
THINTISSUECORE_EXPORT double windingNumber(const TriangleMesh& mesh, const Vector3& point);

/// Whether `point` lies inside the closed `polygon` (its last vertex joins
/// its first; either orientation; even-odd rule, so a point exactly on an
/// edge may fall either way).
THINTISSUECORE_EXPORT bool insidePolygon(const std::vector<Vector2>& polygon, const Vector2& point);

/// Closest point to `point` on triangle (a, b, c).
THINTISSUECORE_EXPORT Vector3 closestPointOnTriangle(const Vector3& point,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c);

/// Distance from `point` to the surface (0 for an empty mesh is not
/// meaningful: returns +infinity).
THINTISSUECORE_EXPORT double distanceToSurface(const TriangleMesh& mesh, const Vector3& point);

class TriangleBvh;

/// The same through `bvh`, built over the mesh's triangles (any radii and
/// margin: boxes only prune): nodes nearer than the best so far are
/// visited, nearest child first, so a query costs about a logarithm of the
/// mesh size.
THINTISSUECORE_EXPORT double distanceToSurface(const TriangleMesh& mesh,
  const TriangleBvh& bvh,
  const Vector3& point);

/// Parameter t at which the line origin + t * direction meets triangle
/// (a, b, c), with `tolerance` on the barycentric coordinates so that hits
/// on shared edges count (Möller-Trumbore); NaN when it misses or runs
/// parallel to the triangle. t may be negative.
THINTISSUECORE_EXPORT double rayTriangleHit(const Vector3& origin,
  const Vector3& direction,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c,
  double tolerance);

/// Parameters t >= 0 at which origin + t * direction meets the surface
/// (triangle edges included), sorted increasing.
THINTISSUECORE_EXPORT std::vector<double> rayHits(const TriangleMesh& mesh,
  const Vector3& origin,
  const Vector3& direction);

} // namespace thintissue

#endif
