// Vertex-against-thick-triangle contacts between two surfaces with radii
// (Spillmann's reduced triangles with radii, thesis 2.4 / 5.1): the narrow
// phase the VTK contact filter and the collision pipeline build on.
#ifndef SurfaceContacts_h
#define SurfaceContacts_h

#include "ThinTissueCoreModule.h"
#include "TriangleMesh.h"

#include <vector>

namespace thintissue
{

struct SurfaceContact
{
  /// Closest point on the other surface's mid-surface triangle.
  Vector3 point = Vector3::Zero();
  /// Unit normal from surface B toward surface A.
  Vector3 normal = Vector3::UnitZ();
  /// Sum of the radii minus the distance: > 0 when the thick volumes overlap.
  double depth = 0.0;
  /// Side of the touched triangle (+1: its counter-clockwise normal side):
  /// lower-surface contacts matter to the wrinkles (4.4).
  int side = 1;
  /// The vertex (of A when `vertexOfA`, else of B) and the triangle of the
  /// other surface.
  int vertex = -1;
  int triangle = -1;
  bool vertexOfA = true;
};

/// For every vertex of A, its deepest contact with a triangle of B within
/// `contactDistance`, and the same for every vertex of B against A. Radii may
/// be empty (zero). Throws InvalidInputError on radii of the wrong length, a
/// negative radius or contact distance.
THINTISSUECORE_EXPORT std::vector<SurfaceContact> findSurfaceContacts(const TriangleMesh& a,
  const std::vector<double>& radiiA,
  const TriangleMesh& b,
  const std::vector<double>& radiiB,
  double contactDistance);

} // namespace thintissue

#endif
