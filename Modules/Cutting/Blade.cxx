#include "Blade.h"

#include "ThinTissueError.h"

#include <algorithm>
#include <cmath>

namespace thintissue
{

Blade Blade::sweptSegment(const Vector3& a0,
  const Vector3& b0,
  const Vector3& a1,
  const Vector3& b1)
{
  Blade blade;
  blade.points = { a0, b0, b1, a1 };
  blade.triangles = { Triangle{ { 0, 1, 2 } }, Triangle{ { 0, 2, 3 } } };
  return blade;
}

Blade Blade::sweptOutline(const std::vector<Vector3>& outline0,
  const std::vector<Vector3>& outline1)
{
  if (outline0.size() < 3 || outline0.size() != outline1.size())
  {
    throw InvalidInputError("bite outline blade: both outlines need the same number (>= 3) of "
                            "points, got " +
                            std::to_string(outline0.size()) + " and " +
                            std::to_string(outline1.size()));
  }
  Blade blade;
  const int n = static_cast<int>(outline0.size());
  blade.points = outline0;
  blade.points.insert(blade.points.end(), outline1.begin(), outline1.end());
  for (int i = 0; i < n; ++i)
  {
    const int j = (i + 1) % n;
    blade.triangles.push_back(Triangle{ { i, j, n + j } });
    blade.triangles.push_back(Triangle{ { i, n + j, n + i } });
  }
  return blade;
}

Blade Blade::fromSurface(const TriangleMesh& surface)
{
  Blade blade;
  blade.points = surface.positions;
  blade.triangles = surface.triangles;
  return blade;
}

BoundingBox Blade::boundingBox() const
{
  return boundingBoxOf(points);
}

void Blade::validate(const std::string& what) const
{
  if (triangles.empty())
  {
    throw InvalidInputError(what + ": the blade has no triangle");
  }
  for (std::size_t p = 0; p < points.size(); ++p)
  {
    if (!points[p].allFinite())
    {
      throw InvalidInputError(
        what + ": blade point " + std::to_string(p) + " has a non-finite coordinate");
    }
  }
  const int count = static_cast<int>(points.size());
  bool anyArea = false;
  const double extent = boundingBox().diagonal().squaredNorm();
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    for (int v : triangles[t])
    {
      if (v < 0 || v >= count)
      {
        throw InvalidInputError(what + ": blade triangle " + std::to_string(t) +
                                " refers to point " + std::to_string(v) + " of " +
                                std::to_string(count));
      }
    }
    const Vector3& a = points[triangles[t][0]];
    const double area =
      0.5 * (points[triangles[t][1]] - a).cross(points[triangles[t][2]] - a).norm();
    anyArea = anyArea || area > 1e-12 * extent;
  }
  if (!anyArea)
  {
    throw InvalidInputError(what + ": the blade is degenerate (every triangle has zero area: "
                                   "the tool did not move, or its edge has no length)");
  }
}

double ScissorsPose::closedLength() const
{
  const double fraction = 1.0 - openingAngle / maximumOpeningAngle;
  return length * std::clamp(fraction, 0.0, 1.0);
}

namespace
{

void checkPose(const ScissorsPose& pose, const char* which)
{
  const bool finite = pose.pivot.allFinite() && pose.direction.allFinite() &&
                      pose.opening.allFinite() && std::isfinite(pose.length) &&
                      std::isfinite(pose.openingAngle) && std::isfinite(pose.maximumOpeningAngle) &&
                      std::isfinite(pose.halfHeight);
  if (!finite)
  {
    throw InvalidInputError(std::string("scissors blade: pose '") + which + "' is not finite");
  }
  if (pose.direction.norm() < 1e-12 || pose.opening.norm() < 1e-12 ||
      pose.direction.normalized().cross(pose.opening.normalized()).norm() < 1e-6 ||
      pose.length <= 0.0 || pose.maximumOpeningAngle <= 0.0 || pose.halfHeight <= 0.0)
  {
    throw InvalidInputError(
      std::string("scissors blade: pose '") + which +
      "' is degenerate (direction and opening must be independent; length, maximum opening "
      "angle and half height positive)");
  }
}

/// The closed part of the middle line, extruded across the blades' plane:
/// corners (pivot - h, pivot + h, tip + h, tip - h).
std::array<Vector3, 4> closedRectangle(const ScissorsPose& pose)
{
  const Vector3 direction = pose.direction.normalized();
  const Vector3 across = direction.cross(pose.opening).normalized() * pose.halfHeight;
  const Vector3 tip = pose.pivot + direction * pose.closedLength();
  return { pose.pivot - across, pose.pivot + across, tip + across, tip - across };
}

} // namespace

Blade scissorsBlade(const ScissorsPose& before, const ScissorsPose& after)
{
  checkPose(before, "before");
  checkPose(after, "after");
  Blade blade;
  if (after.closedLength() <= 0.0)
  {
    return blade;
  }
  const auto now = closedRectangle(after);
  const auto earlier = closedRectangle(before);
  // The closed region now, and the band its far edge swept since `before`
  // (the tool may have moved while closing).
  blade.points.assign(now.begin(), now.end());
  blade.points.insert(blade.points.end(), earlier.begin(), earlier.end());
  blade.triangles = { Triangle{ { 0, 1, 2 } },
    Triangle{ { 0, 2, 3 } },
    Triangle{ { 7, 6, 2 } },
    Triangle{ { 7, 2, 3 } } };
  return blade;
}

} // namespace thintissue
