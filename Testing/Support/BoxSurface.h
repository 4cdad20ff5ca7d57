// A closed axis-aligned box surface for tests (header-only, not installed).
#ifndef BoxSurface_h
#define BoxSurface_h

#include "TriangleMesh.h"

namespace thintissue::testing
{

/// The box [low, high] as 8 corners (bit k of the index picks high on axis
/// k) and 12 outward triangles.
inline TriangleMesh boxSurface(const Vector3& low, const Vector3& high)
{
  TriangleMesh box;
  box.name = "box";
  for (int k = 0; k < 8; ++k)
  {
    box.positions.emplace_back(
      (k & 1) ? high.x() : low.x(), (k & 2) ? high.y() : low.y(), (k & 4) ? high.z() : low.z());
  }
  box.triangles = { { 0, 2, 1 },
    { 1, 2, 3 },
    { 4, 5, 6 },
    { 5, 7, 6 },
    { 0, 1, 4 },
    { 1, 5, 4 },
    { 2, 6, 3 },
    { 3, 6, 7 },
    { 0, 4, 2 },
    { 2, 4, 6 },
    { 1, 3, 5 },
    { 3, 7, 5 } };
  return box;
}

} // namespace thintissue::testing

#endif
