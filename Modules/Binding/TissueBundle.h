// A ready tissue from a thin visual mesh alone (the collision-mesh issue,
// thesis 7.2): collision mid-surface with radii, simulation hexahedra and
// the visual-collision binding (5.2), made in one call and saved as one
// bundle file that the simulator and the VTK filters load directly.
//
// The bundle is the binding file (BindingCache.h, versioned, checksummed,
// written atomically) holding the re-meshed visual surface, the collision
// mesh with its radii, the binding, the hexahedra and a JSON metadata text
// (generator, settings, measured Hausdorff distance and thickness). The
// embeddings of the visual and collision vertices in the hexahedra are not
// stored: they are derived data, recomputed on loading in milliseconds.
#ifndef TissueBundle_h
#define TissueBundle_h

#include "CollisionMeshGeneration.h"
#include "HexahedralEmbedding.h"
#include "ThinTissueBindingModule.h"
#include "VisualCollisionBinding.h"

#include <string>

namespace thintissue
{

struct TissuePreparationSettings
{
  CollisionMeshSettings collision;
  /// Hexahedra of the simulation mesh (the nearest reachable count).
  int hexahedronCount = 76;
  VisualCollisionBindingSettings binding;
};

struct TissueBundle
{
  /// The re-meshed visual surface (binding.visual), the collision
  /// mid-surface with its "Radius" array, the hexahedra.
  TriangleMesh visual;
  TriangleMesh collision;
  HexahedralMesh simulation;
  VisualCollisionBinding binding;
  /// Visual and collision vertices in the hexahedra (rest positions).
  HexahedralEmbedding visualEmbedding;
  HexahedralEmbedding collisionEmbedding;
  /// JSON: generator, settings, counts, Hausdorff distance, thickness.
  std::string metadata;
};

/// Collision mid-surface, hexahedra and binding of `visual`; progress runs
/// from 0 to 1 over the three steps. Throws InvalidInputError naming the
/// mesh on bad input (see makeCollisionMidSurface, bindVisualToCollision),
/// GenerationAbortedError when progress returns false.
THINTISSUEBINDING_EXPORT TissueBundle prepareTissue(const TriangleMesh& visual,
  const TissuePreparationSettings& settings = {},
  const GenerationProgress& progress = {});

/// Adds `json` (a JSON value as text) to the bundle's metadata under `key`,
/// replacing what was there (e.g. "repair": what MeshRepair changed before
/// preparation). Throws InvalidInputError when `json` is not valid JSON.
THINTISSUEBINDING_EXPORT void addBundleMetadata(TissueBundle& bundle,
  const std::string& key,
  const std::string& json);

/// Writes the bundle (atomically). Throws FileError naming the file.
THINTISSUEBINDING_EXPORT void writeTissueBundle(const std::string& path,
  const TissueBundle& bundle);

/// Reads a bundle and recomputes its embeddings. Throws FileError naming
/// the file and the reason (missing, another format version, damaged, no
/// hexahedra).
THINTISSUEBINDING_EXPORT TissueBundle readTissueBundle(const std::string& path);

} // namespace thintissue

#endif
