// The collision mid-surface of a band whose thickness direction turns along
// its length (a cruciate ligament twisting through 90 degrees, a curled
// strip), where one thickness axis for the whole tissue cannot serve: seen
// along any one axis, such a band's outline crosses itself.
//
// The band is followed along its centre curve (a principal curve: slab
// centroids along the length, re-fitted to the samples' projections on the
// curve a few times). At stations along the curve the local thickness
// direction is the one the two facing surfaces agree on: the dominant axis
// of the area-weighted tensor of the surface normals (n n^T does not care
// on which face a normal lies), taken across the curve's tangent. The
// mid-surface is a grid over (length, width), as the thesis's own ligament
// meshes are (ACL 4 x 4, PCL 8 x 4 cells): each row across the band at a
// point of the curve, its ends where the band's rim is, moved in by the
// local half thickness so that the border spheres reach the rim (the rows
// at the insertions likewise); each vertex is the middle of the first and
// last crossings of the line along the local thickness direction, its
// radius half their distance. Module-private (CollisionMeshGeneration).
#ifndef BandMidSurface_h
#define BandMidSurface_h

#include "ThinTissueBindingModule.h"
#include "TriangleMesh.h"

#include <string>
#include <vector>

namespace thintissue
{

struct BandMidSurface
{
  /// Grid triangles, oriented along the local thickness direction.
  TriangleMesh mesh;
  std::vector<double> radii;
  int rows = 0;    // vertices along the length
  int columns = 0; // vertices across
  int borderVertexCount = 0;
  /// Along the centre curve, between the end rows' rims.
  double length = 0.0;
  double largestThickness = 0.0;
  /// Mean of the stations' thickness directions (made to agree in sign),
  /// and the largest angle (radians) between two of them.
  Vector3 meanThicknessDirection = Vector3::UnitZ();
  double thicknessTurn = 0.0;
};

/// The band's mid-surface with about `vertexCount` vertices (the grid whose
/// count is nearest with cells closest to square), or when `triangleCount`
/// is positive the smallest grid with at least that many triangles.
/// Throws InvalidInputError naming `name` when the surface is not a band
/// (no centre curve, a line across it that misses the tissue).
THINTISSUEBINDING_EXPORT BandMidSurface makeBandMidSurface(const TriangleMesh& visual,
  int vertexCount,
  int triangleCount,
  const std::string& name);

/// How elongated the surface is: the square root of the ratio of the two
/// largest principal spreads of its area.
THINTISSUEBINDING_EXPORT double elongationOf(const TriangleMesh& visual);

} // namespace thintissue

#endif
