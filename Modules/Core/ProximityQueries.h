// Narrow-phase proximity primitives for thick triangles (Spillmann's
// "reduced triangles with radii", thesis 2.4 and 5.1).
//
// Thick-triangle model. A collision triangle (a, b, c) whose vertices carry
// radii (ra, rb, rc) stands for the volume swept by spheres centred on the
// triangle with the barycentrically interpolated radius. The queries below
// use the standard approximation of that volume: they find the closest point
// x on the mid-surface triangle to the other primitive, and take the radius
// interpolated at x, r(x) = u ra + v rb + w rc. The exact swept-sphere
// distance would minimise |p - x| - r(x) instead; the two agree when the radii
// are equal and differ by O(|grad r| * radius) otherwise, which is far below
// the contact tolerance for the slowly varying radii of a reduced mesh.
//
// Conventions shared by every contact below:
//  - `distance` is between the mid-surface/centre-line closest points;
//  - `depth` = (sum of radii at the closest points) - distance: positive
//    when the thick volumes overlap, negative when separated;
//  - `withinContactDistance` = depth >= -contactDistance, i.e. the gap
//    between the thick surfaces is at most `contactDistance`;
//  - `normal` is unit and points from the triangle (the "B" side) toward the
//    other primitive, i.e. the direction in which the other primitive is
//    pushed out;
//  - `side` is +1 when the contact is on the positive side of the
//    triangle's oriented normal (counter-clockwise a, b, c), -1 otherwise.
//    Exactly on the plane counts as +1 unless stated otherwise.
#ifndef ProximityQueries_h
#define ProximityQueries_h

#include "ThinTissueCoreModule.h"
#include "TriangleMesh.h"

#include <array>

namespace thintissue
{

/// Closest point of segment [p, q] to `point`: point = p + parameter (q - p),
/// parameter in [0, 1]. A zero-length segment gives parameter 0.
struct SegmentClosestPoint
{
  Vector3 point = Vector3::Zero();
  double parameter = 0.0;
};
THINTISSUECORE_EXPORT SegmentClosestPoint closestPointOnSegment(const Vector3& point,
  const Vector3& p,
  const Vector3& q);

/// Closest points between segments [p1, q1] and [p2, q2] (Ericson, Real-Time
/// Collision Detection 5.1.9). Parallel and zero-length segments are
/// handled: for parallel segments one of the (non-unique) closest pairs is
/// returned, with the correct distance.
struct SegmentSegmentClosestPoints
{
  Vector3 pointOnFirst = Vector3::Zero();
  Vector3 pointOnSecond = Vector3::Zero();
  double parameterOnFirst = 0.0;  ///< in [0, 1] along [p1, q1]
  double parameterOnSecond = 0.0; ///< in [0, 1] along [p2, q2]
  double distance = 0.0;
};
THINTISSUECORE_EXPORT SegmentSegmentClosestPoints closestPointsBetweenSegments(const Vector3& p1,
  const Vector3& q1,
  const Vector3& p2,
  const Vector3& q2);

/// Closest point of triangle (a, b, c) to `point`, with barycentric
/// coordinates (u, v, w): closest = u a + v b + w c, all >= 0, sum 1.
/// Degenerate (zero-area) triangles are handled through their edges.
struct TriangleClosestPoint
{
  Vector3 point = Vector3::Zero();
  Vector3 barycentric = Vector3(1.0, 0.0, 0.0);
};
THINTISSUECORE_EXPORT TriangleClosestPoint closestPointOnTriangleWithBarycentric(
  const Vector3& point,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c);

/// Unit normal of the counter-clockwise triangle; zero if degenerate.
THINTISSUECORE_EXPORT Vector3 orientedTriangleNormal(const Vector3& a,
  const Vector3& b,
  const Vector3& c);

/// Sphere (point with radius) against a thick triangle.
struct PointTriangleContact
{
  bool withinContactDistance = false;
  Vector3 trianglePoint = Vector3::Zero(); ///< closest point on the mid-surface
  Vector3 barycentric = Vector3(1.0, 0.0, 0.0);
  double triangleRadius = 0.0; ///< interpolated at `barycentric`
  Vector3 normal = Vector3::UnitZ();
  double distance = 0.0;
  double depth = 0.0;
  int side = 1; ///< side of the point w.r.t. the triangle's plane
  bool penetrating() const { return depth > 0.0; }
};
/// When the point lies on the mid-surface (distance ~ 0) the normal is the
/// triangle normal (side +1); for a degenerate triangle, +z.
THINTISSUECORE_EXPORT PointTriangleContact pointTriangleContact(const Vector3& point,
  double pointRadius,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c,
  double ra,
  double rb,
  double rc,
  double contactDistance);

/// Capsule (segment [p, q] with a radius, e.g. a tool's centre line) against
/// a thick triangle.
struct SegmentTriangleContact
{
  bool withinContactDistance = false;
  /// True when the centre line crosses the mid-surface (distance 0).
  bool crossing = false;
  double segmentParameter = 0.0; ///< segmentPoint = p + parameter (q - p)
  Vector3 segmentPoint = Vector3::Zero();
  Vector3 trianglePoint = Vector3::Zero();
  Vector3 barycentric = Vector3(1.0, 0.0, 0.0);
  double triangleRadius = 0.0;
  Vector3 normal = Vector3::UnitZ();
  double distance = 0.0;
  double depth = 0.0;
  int side = 1;
  bool penetrating() const { return depth > 0.0; }
};
/// The closest pair is the best of: the end points against the triangle and
/// the segment against the three edges (exact when the segment does not
/// cross). When the segment crosses the triangle, the contact is at the
/// crossing point with distance 0, and the normal is the triangle normal
/// oriented toward the side of the start point `p` (so a tool that moved
/// from p to q within one step is pushed back where it came from, not
/// through); `side` is that of p. If p lies on the plane, the side opposite
/// to q is used. For a segment parallel to the face the closest pair is not
/// unique; one of them is returned (the response may sample the segment).
THINTISSUECORE_EXPORT SegmentTriangleContact segmentTriangleContact(const Vector3& p,
  const Vector3& q,
  double segmentRadius,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c,
  double ra,
  double rb,
  double rc,
  double contactDistance);

/// One feature pair between thick triangles A and B.
struct TriangleTriangleContact
{
  enum class Kind
  {
    VertexOfAOnFaceOfB,
    VertexOfBOnFaceOfA,
    EdgeEdge
  };
  Kind kind = Kind::EdgeEdge;
  /// Vertex index 0..2 for a vertex, edge index k = (k, k+1 mod 3) for an
  /// edge, -1 for a face.
  int featureA = -1;
  int featureB = -1;
  bool withinContactDistance = false;
  Vector3 pointA = Vector3::Zero(); ///< closest point on A's mid-surface
  Vector3 pointB = Vector3::Zero(); ///< closest point on B's mid-surface
  Vector3 barycentricA = Vector3(1.0, 0.0, 0.0);
  Vector3 barycentricB = Vector3(1.0, 0.0, 0.0);
  double radiusA = 0.0; ///< interpolated at pointA
  double radiusB = 0.0; ///< interpolated at pointB
  /// Unit, from B toward A (the direction to push A out of B).
  Vector3 normal = Vector3::UnitZ();
  double distance = 0.0;
  double depth = 0.0;
  int sideOnA = 1; ///< +1 when B touches A from A's positive normal side
  int sideOnB = 1; ///< +1 when A touches B from B's positive normal side
};

/// Vertex-face (3 vertices of A against B, 3 of B against A) and edge-edge
/// (9 pairs) proximity between two thick triangles. `contacts` holds the
/// feature pairs within contact distance (at most 15, no allocation);
/// `deepest` indexes the one of largest depth (-1 if none).
/// `intersecting` flags mid-surfaces that cross each other (an edge of one
/// crosses the other triangle); the features then do not measure the
/// penetration, which the radii are meant to prevent.
struct TriangleTriangleProximity
{
  std::array<TriangleTriangleContact, 15> contacts;
  int count = 0;
  int deepest = -1;
  bool intersecting = false;
  bool inContact() const { return count > 0; }
};
THINTISSUECORE_EXPORT TriangleTriangleProximity triangleTriangleProximity(
  const std::array<Vector3, 3>& a,
  const std::array<double, 3>& radiiA,
  const std::array<Vector3, 3>& b,
  const std::array<double, 3>& radiiB,
  double contactDistance);

} // namespace thintissue

#endif
