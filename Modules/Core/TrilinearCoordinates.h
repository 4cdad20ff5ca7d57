// Trilinear interpolation in a hexahedron and its inverse: the embedding of
// visual vertices, collision vertices and monitor points in the simulation
// mesh (thesis formula 4-1, section 4.3).
#ifndef TrilinearCoordinates_h
#define TrilinearCoordinates_h

#include "HexahedralMesh.h"
#include "ThinTissueCoreModule.h"

#include <array>

namespace thintissue
{

using HexahedronCorners = std::array<Vector3, 8>;

/// Corner positions of hexahedron `h` of `mesh`.
THINTISSUECORE_EXPORT HexahedronCorners hexahedronCorners(const HexahedralMesh& mesh,
  std::size_t h);

/// The eight trilinear weights of local coordinates (xi, eta, zeta) in
/// [0,1]^3, in VTK corner order.
THINTISSUECORE_EXPORT std::array<double, 8> trilinearWeights(const Vector3& local);

/// Point at local coordinates `local` of the hexahedron.
THINTISSUECORE_EXPORT Vector3 trilinearPoint(const HexahedronCorners& corners,
  const Vector3& local);

/// Local coordinates of `point` by Newton's method on the trilinear map
/// (no clamping: values outside [0,1] mean the point is outside). Returns
/// false if Newton does not converge (degenerate or badly inverted cell).
THINTISSUECORE_EXPORT bool trilinearCoordinates(const HexahedronCorners& corners,
  const Vector3& point,
  Vector3& local);

/// True if `local` lies in [-tolerance, 1 + tolerance]^3.
THINTISSUECORE_EXPORT bool isInsideUnitCube(const Vector3& local, double tolerance = 1e-9);

/// Index of a hexahedron of `mesh` that contains `point` (local coordinates
/// in [-tolerance, 1 + tolerance]^3), or -1. Linear scan: for tests and set-up.
THINTISSUECORE_EXPORT int findContainingHexahedron(const HexahedralMesh& mesh,
  const Vector3& point,
  double tolerance = 1e-9);

} // namespace thintissue

#endif
