// Persistence of the visual-collision binding (thesis 5.2: pre-processed
// once, loaded before every simulation). One binary file holds the binding
// (with its re-meshed visual mesh and the collision mesh it was made for)
// and, optionally, the simulation hexahedra, so that a tissue starts from
// one file. The header carries a format version, a checksum of the inputs
// the binding was built from, and a checksum of the content: a file made
// from other meshes or settings (stale), of another version, truncated or
// damaged is detected and never trusted. Files are written to a temporary
// name and renamed, so a good file is never replaced by a half-written one.
#ifndef BindingCache_h
#define BindingCache_h

#include "HexahedralMesh.h"
#include "ThinTissueBindingModule.h"
#include "VisualCollisionBinding.h"

#include <cstdint>
#include <optional>
#include <string>

namespace thintissue
{

/// Current file format version (2: collision radii and metadata added; 4:
/// the crease visual vertices of a cleavage's junction).
constexpr std::uint32_t BindingCacheVersion = 4;

/// Checksum (64-bit FNV-1a) of everything the binding depends on: the
/// visual and collision meshes (positions, triangles, texture corners and
/// coordinates, normals, attributes) and the settings that change the result.
THINTISSUEBINDING_EXPORT std::uint64_t bindingInputChecksum(const TriangleMesh& visual,
  const TriangleMesh& collision,
  const VisualCollisionBindingSettings& settings);

struct BindingCacheContents
{
  VisualCollisionBinding binding;
  std::optional<HexahedralMesh> simulation;
  /// Free text stored with the binding (the tissue bundle's JSON).
  std::string metadata;
};

/// Writes the binding (and the hexahedra, if given) with `inputChecksum`.
/// Throws FileError naming the file when it cannot be written.
THINTISSUEBINDING_EXPORT void writeBindingCache(const std::string& path,
  const VisualCollisionBinding& binding,
  std::uint64_t inputChecksum,
  const HexahedralMesh* simulation = nullptr,
  const std::string& metadata = {});

/// The bytes writeBindingCache writes (a whole binding file), for files
/// that hold several bindings (TissueBundle.h: a bundle of several tissues).
THINTISSUEBINDING_EXPORT std::string bindingCacheBytes(const VisualCollisionBinding& binding,
  std::uint64_t inputChecksum,
  const HexahedralMesh* simulation = nullptr,
  const std::string& metadata = {});

/// Reads a binding file. Returns nothing, with the reason in `whyNot`, when
/// the file is missing, of another format version, made from other inputs
/// than `expectedInputChecksum`, or damaged (truncated, content checksum
/// wrong, inconsistent sizes).
THINTISSUEBINDING_EXPORT std::optional<BindingCacheContents> readBindingCache(
  const std::string& path,
  std::uint64_t expectedInputChecksum,
  std::string* whyNot = nullptr);

/// Reads a binding file whatever inputs it was made from (a tissue bundle
/// loaded on its own); still refuses another format version or a damaged
/// file, with the reason in `whyNot`. `inputChecksum` receives the file's.
THINTISSUEBINDING_EXPORT std::optional<BindingCacheContents> readBindingFile(
  const std::string& path,
  std::string* whyNot = nullptr,
  std::uint64_t* inputChecksum = nullptr);

/// readBindingFile on the bytes of a binding file held in memory (as
/// bindingCacheBytes makes them); `name` stands for the file in `whyNot`.
THINTISSUEBINDING_EXPORT std::optional<BindingCacheContents> readBindingBytes(
  const std::string& bytes,
  const std::string& name,
  std::string* whyNot = nullptr,
  std::uint64_t* inputChecksum = nullptr);

/// The binding from `cachePath` if the file is current and sound, else a
/// new one (bindVisualToCollision) written there for next time. `rebuilt`
/// says which happened and `whyRebuilt` why.
THINTISSUEBINDING_EXPORT VisualCollisionBinding loadOrBuildBinding(const std::string& cachePath,
  const TriangleMesh& visual,
  const TriangleMesh& collision,
  const VisualCollisionBindingSettings& settings = {},
  const BindingProgress& progress = {},
  bool* rebuilt = nullptr,
  std::string* whyRebuilt = nullptr);

} // namespace thintissue

#endif
