// Indexed triangle mesh: the visual and collision surfaces of a tissue.
//
// Positions are welded: one vertex per surface point, so that adjacency,
// binding (thesis 5.2) and cutting (5.3) see the true topology. Texture
// coordinates are kept per triangle corner (`textureCorners` indexes
// `textureCoordinates`) because a texture seam must not split the surface.
#ifndef TriangleMesh_h
#define TriangleMesh_h

#include "ThinTissueCoreModule.h"
#include "VertexAttributes.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <string>
#include <vector>

namespace thintissue
{

using Vector2 = Eigen::Vector2d;
using Vector3 = Eigen::Vector3d;
using Triangle = std::array<int, 3>;
using BoundingBox = Eigen::AlignedBox3d;

/// Axis-aligned box of a point set (empty for no points).
THINTISSUECORE_EXPORT BoundingBox boundingBoxOf(const std::vector<Vector3>& points);

/// Indexed triangle surface with optional normals, texture coordinates and
/// named per-vertex attributes. Plain data with documented invariants;
/// `checkConsistency` verifies them.
class THINTISSUECORE_EXPORT TriangleMesh
{
public:
  /// Human-readable name (usually the file it came from) used in messages.
  std::string name;
  std::vector<Vector3> positions;
  std::vector<Triangle> triangles;
  /// Per-vertex unit normals; empty or one per vertex.
  std::vector<Vector3> normals;
  /// Distinct texture coordinates; `textureCorners[t][k]` indexes this list
  /// for corner k of triangle t. Both empty when the mesh has no texture.
  std::vector<Vector2> textureCoordinates;
  std::vector<Triangle> textureCorners;
  /// Named per-vertex arrays (e.g. "Radius" on collision meshes).
  VertexAttributes pointAttributes;

  std::size_t vertexCount() const { return positions.size(); }
  std::size_t triangleCount() const { return triangles.size(); }
  bool hasNormals() const { return !normals.empty(); }
  bool hasTextureCoordinates() const { return !textureCorners.empty(); }

  BoundingBox boundingBox() const;
  double triangleArea(std::size_t t) const;
  Vector3 triangleNormal(std::size_t t) const; ///< unit, counter-clockwise; zero if degenerate
  double surfaceArea() const;
  /// Signed enclosed volume (divergence theorem); positive for a closed
  /// surface whose triangles face outward.
  double signedVolume() const;

  /// Flips every triangle (and the normals): turns an inward-facing closed
  /// surface outward. Texture corners follow their triangles.
  void reverseOrientation();

  /// Area-weighted vertex normals from the triangles.
  void computeVertexNormals();

  /// Throws InvalidInputError naming `name` on: a vertex index out of range,
  /// a non-finite coordinate, normals/texture arrays of the wrong size, an
  /// attribute array of the wrong length.
  void checkConsistency() const;

  /// Appends `other` (indices shifted); texture data is kept only when both
  /// meshes have it.
  void append(const TriangleMesh& other);
};

} // namespace thintissue

#endif
