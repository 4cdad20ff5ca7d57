// The cutting blade of the thesis's simulation phase (5.1): the surface a
// tool's cutting edge sweeps between two consecutive poses, as triangles in
// world (current) coordinates. A cut is the intersection of this surface
// with the tissue's collision mesh (5.3.1).
//
//  - scalpel: a straight cutting edge (segment) swept from one pose to the
//    next, a quad of two triangles;
//  - scissors: only where the two blades have closed is the tissue cut; the
//    closed part grows from the pivot as the jaws close (ScissorsPose);
//  - bite outline: a punch's jaws cut along a closed outline; swept, it is a
//    band that cuts a loop and frees the piece inside;
//  - any triangle surface (a blade given by the caller, e.g. from VTK).
#ifndef Blade_h
#define Blade_h

#include "ThinTissueCuttingModule.h"
#include "TriangleMesh.h"

#include <string>
#include <vector>

namespace thintissue
{

/// The swept cutting surface: triangles in world coordinates.
class THINTISSUECUTTING_EXPORT Blade
{
public:
  std::vector<Vector3> points;
  std::vector<Triangle> triangles;

  /// The edge (a0, b0) swept to (a1, b1): two triangles.
  static Blade sweptSegment(const Vector3& a0,
    const Vector3& b0,
    const Vector3& a1,
    const Vector3& b1);
  /// A closed outline (n >= 3 points, same count at both poses) swept from
  /// `outline0` to `outline1`: a band of 2 n triangles.
  static Blade sweptOutline(const std::vector<Vector3>& outline0,
    const std::vector<Vector3>& outline1);
  /// Any triangle surface, e.g. a blade read from a file.
  static Blade fromSurface(const TriangleMesh& surface);

  bool empty() const { return triangles.empty(); }
  BoundingBox boundingBox() const;
  /// Throws InvalidInputError naming `what` on: no triangle, an index out
  /// of range, a non-finite coordinate, or no triangle with an area above
  /// 1e-12 of the squared extent (all degenerate). Degenerate triangles
  /// among good ones are allowed (a blade that did not move there).
  void validate(const std::string& what) const;
};

/// A pair of scissors at one pose. The blades turn about `pivot` in the
/// plane spanned by `direction` (the middle line, towards the tips) and
/// `opening` (perpendicular to it, unit): each blade is at half the opening
/// angle from the middle line. Blades of length `length` close from the
/// pivot outwards: at angle `openingAngle` they have closed over
/// length * (1 - openingAngle / maximumOpeningAngle) of the middle line,
/// and only there is the tissue cut.
struct ScissorsPose
{
  Vector3 pivot = Vector3::Zero();
  Vector3 direction = Vector3::UnitX();
  Vector3 opening = Vector3::UnitY();
  double length = 10.0;
  double openingAngle = 0.0;        ///< radians
  double maximumOpeningAngle = 0.5; ///< radians, > 0
  /// Half the height of the cutting surface across the blades' plane
  /// (normal to `direction` and `opening`): it must reach through the
  /// tissue's thickness.
  double halfHeight = 5.0;

  /// Length of the middle line over which the blades have closed.
  double closedLength() const;
};

/// The surface cut by scissors going from `before` to `after`: the closed
/// part of the middle line at `after`, extruded by +-halfHeight across the
/// blades' plane, joined to that of `before` (the tool may move while it
/// closes). Empty when the blades have closed over no length at `after`.
/// Throws InvalidInputError on non-finite or degenerate poses.
THINTISSUECUTTING_EXPORT Blade scissorsBlade(const ScissorsPose& before, const ScissorsPose& after);

} // namespace thintissue

#endif
