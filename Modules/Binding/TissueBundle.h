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
//
// Units: meshes are never rescaled; every tolerance of the preparation is
// relative to the mesh, so the same anatomy prepares the same in any unit.
// The units (given, or detected from the size: LengthUnits.h) are recorded
// in the metadata under "units" ({"name", "metresPerUnit", "detected",
// "reason"}) and read back into TissueBundle::units.
//
// Quality: each preparation measures how well the collision mesh represents
// the visual surface (TissueQuality.h), kept in the metadata under
// "quality"; reading a bundle takes it from there (measuring it costs about
// as much as the rest of reading) and measures it again only for a bundle
// without one.
//
// Several tissues: a visual mesh of several pieces (both menisci in one
// segmentation) is prepared by prepareTissues, one tissue per large piece,
// fragments dropped with a warning each (MeshPieces.h). Several tissues go
// in one file (writeTissueBundles): a small container, magic "TTTISS\r\n",
// format version, count, then each tissue as a whole single-tissue bundle
// (with its own checksums) preceded by its size. One tissue is always
// written as a single-tissue bundle, the format older readers know;
// readTissueBundles reads both.
#ifndef TissueBundle_h
#define TissueBundle_h

#include "CollisionMeshGeneration.h"
#include "HexahedralEmbedding.h"
#include "LengthUnits.h"
#include "MeshPieces.h"
#include "ThinTissueBindingModule.h"
#include "TissueQuality.h"
#include "VisualCollisionBinding.h"

#include <optional>
#include <string>
#include <vector>

namespace thintissue
{

struct TissuePreparationSettings
{
  CollisionMeshSettings collision;
  /// Hexahedra of the simulation mesh (the nearest reachable count).
  int hexahedronCount = 76;
  VisualCollisionBindingSettings binding;
  /// The units of the visual mesh; detected from its size when not given.
  std::optional<LengthUnits> units;
  /// prepareTissues: pieces whose area is below this fraction of the
  /// largest piece's are fragments, dropped with a warning.
  double minimumPieceFraction = 0.05;
  TissueQualitySettings quality;
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
  /// JSON: generator, settings, counts, Hausdorff distance, thickness,
  /// "units", "quality" (and "piece" for one of several tissues).
  std::string metadata;
  /// From the metadata; nothing for a bundle written before units were
  /// recorded.
  std::optional<LengthUnits> units;
  TissueQuality quality;
};

/// The tissues of a visual mesh of several pieces.
struct PreparedTissues
{
  /// One per kept piece, largest first.
  std::vector<TissueBundle> tissues;
  /// The fragments left out.
  std::vector<MeshPiece> droppedPieces;
  LengthUnits units;
  bool unitsDetected = false;
  /// How the units were found: "given", or detectLengthUnits's reason.
  std::string unitsReason;
  /// One sentence per dropped fragment, and one when the units are a guess
  /// that fits no tissue size.
  std::vector<std::string> warnings;
};

/// Collision mid-surface, hexahedra, binding and quality report of
/// `visual`, a single piece; progress runs from 0 to 1 over the steps.
/// Throws InvalidInputError naming the mesh on bad input (see
/// makeCollisionMidSurface, bindVisualToCollision; a mesh of several
/// pieces: use prepareTissues), GenerationAbortedError when progress
/// returns false.
THINTISSUEBINDING_EXPORT TissueBundle prepareTissue(const TriangleMesh& visual,
  const TissuePreparationSettings& settings = {},
  const GenerationProgress& progress = {});

/// Each large piece of `visual` prepared as its own tissue (prepareTissue),
/// fragments dropped (settings.minimumPieceFraction). The units, when not
/// given, are detected once from the largest piece and recorded in every
/// tissue. Throws as prepareTissue (the message names the piece).
THINTISSUEBINDING_EXPORT PreparedTissues prepareTissues(const TriangleMesh& visual,
  const TissuePreparationSettings& settings = {},
  const GenerationProgress& progress = {});

/// Adds `json` (a JSON value as text) to the bundle's metadata under `key`,
/// replacing what was there (e.g. "repair": what MeshRepair changed before
/// preparation). Throws InvalidInputError when `json` is not valid JSON.
THINTISSUEBINDING_EXPORT void addBundleMetadata(TissueBundle& bundle,
  const std::string& key,
  const std::string& json);

/// The same tissue in other units: every length of the bundle (visual,
/// collision and binding positions, the collision radii, path lengths,
/// hexahedron nodes, the quality's distances and places) multiplied by the
/// ratio of the units, and `units` recorded (the metadata gets
/// "convertedFrom"). Parameters and embeddings do not change. A bundle
/// without recorded units is taken as millimetres (what it was made in).
THINTISSUEBINDING_EXPORT void convertTissueBundleUnits(TissueBundle& bundle,
  const LengthUnits& units);

/// Writes the bundle (atomically). Throws FileError naming the file.
THINTISSUEBINDING_EXPORT void writeTissueBundle(const std::string& path,
  const TissueBundle& bundle);

/// Writes several tissues in one file (atomically); one tissue is written
/// as writeTissueBundle does. Throws FileError naming the file,
/// InvalidInputError for no tissues.
THINTISSUEBINDING_EXPORT void writeTissueBundles(const std::string& path,
  const std::vector<TissueBundle>& bundles);

/// Reads a single-tissue bundle and recomputes its embeddings and quality.
/// Throws FileError naming the file and the reason (missing, another format
/// version, damaged, no hexahedra; several tissues: use readTissueBundles).
THINTISSUEBINDING_EXPORT TissueBundle readTissueBundle(const std::string& path);

/// Reads every tissue of a bundle file, single-tissue or several. Throws
/// FileError as readTissueBundle, naming the tissue at fault.
THINTISSUEBINDING_EXPORT std::vector<TissueBundle> readTissueBundles(const std::string& path);

} // namespace thintissue

#endif
