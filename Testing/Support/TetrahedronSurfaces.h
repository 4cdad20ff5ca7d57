// Closed tetrahedron surfaces for tests (header-only, not installed).
#ifndef TetrahedronSurfaces_h
#define TetrahedronSurfaces_h

#include "TriangleMesh.h"

namespace thintissue::testing
{

/// The unit corner tetrahedron at `offset` (vertex 0 at the right-angled
/// corner), its 4 triangles facing outward.
inline TriangleMesh tetrahedronSurface(const Vector3& offset)
{
  TriangleMesh mesh;
  mesh.positions = {
    offset, offset + Vector3(1, 0, 0), offset + Vector3(0, 1, 0), offset + Vector3(0, 0, 1)
  };
  mesh.triangles = { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } };
  return mesh;
}

/// The corner tetrahedron and its point reflection through vertex 0, joined
/// only there: a closed bow-tie (vertex 0 non-manifold, each of its two
/// fans closing on itself), 7 vertices, both pieces facing outward.
inline TriangleMesh tetrahedraSharingAVertex()
{
  TriangleMesh mesh = tetrahedronSurface(Vector3::Zero());
  for (int k = 1; k < 4; ++k)
  {
    mesh.positions.push_back(-mesh.positions[k]);
  }
  // The reflection reverses orientation, so each triangle is taken reversed.
  for (int t = 0; t < 4; ++t)
  {
    Triangle mirrored = mesh.triangles[t];
    for (int& v : mirrored)
    {
      v = v == 0 ? 0 : v + 3;
    }
    mesh.triangles.push_back({ mirrored[0], mirrored[2], mirrored[1] });
  }
  return mesh;
}

} // namespace thintissue::testing

#endif
