// The three meshes of a thin tissue (thesis fig. 5-1): a fine closed visual
// surface, a coarse collision mid-surface "with radii", and the hexahedral
// simulation mesh that embeds both.
#ifndef TissueModel_h
#define TissueModel_h

#include "HexahedralMesh.h"
#include "ThinTissueModelsModule.h"
#include "TriangleMesh.h"

#include <string>

namespace thintissue
{

/// Name of the per-vertex collision radius array (half the local thickness).
constexpr const char* CollisionRadiusArrayName = "Radius";

struct THINTISSUEMODELS_EXPORT TissueModel
{
  std::string name;
  /// Closed, outward, 2-manifold surface with normals and texture coordinates.
  TriangleMesh visual;
  /// Mid-surface triangles; point attribute `Radius` (1 component).
  TriangleMesh collision;
  /// Hexahedra covering the tissue; `fixedNodes` marks the attachments.
  HexahedralMesh simulation;

  /// The collision radii (throws InvalidInputError if the array is missing).
  const std::vector<double>& collisionRadii() const;
};

} // namespace thintissue

#endif
