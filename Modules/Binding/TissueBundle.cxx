#include "TissueBundle.h"

#include "AtomicFileWriter.h"
#include "BandMidSurface.h"
#include "BindingCache.h"
#include "ThinTissueError.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace thintissue
{

namespace
{

/// Magic of a file of several tissues; a single tissue's file starts with
/// the binding file's magic (BindingCache.cxx).
constexpr char SeveralTissuesMagic[8] = { 'T', 'T', 'T', 'I', 'S', 'S', '\r', '\n' };
constexpr std::uint32_t SeveralTissuesVersion = 1;

void embed(TissueBundle& bundle)
{
  bundle.visualEmbedding = HexahedralEmbedding(bundle.simulation, bundle.visual.positions);
  bundle.collisionEmbedding = HexahedralEmbedding(bundle.simulation, bundle.collision.positions);
}

struct ResolvedUnits
{
  LengthUnits units;
  bool detected = false;
  std::string reason = "given";
  bool confident = true;
};

ResolvedUnits resolveUnits(const std::optional<LengthUnits>& given, double largestExtent)
{
  if (given)
  {
    return { *given, false, "given", true };
  }
  const DetectedLengthUnits detected = detectLengthUnits(largestExtent);
  return { detected.units, true, detected.reason, detected.confident };
}

nlohmann::json unitsJson(const ResolvedUnits& units)
{
  return { { "name", units.units.name },
    { "metresPerUnit", units.units.metresPerUnit },
    { "detected", units.detected },
    { "reason", units.reason } };
}

/// Units recorded in a bundle's metadata, if any.
std::optional<LengthUnits> unitsFromMetadata(const std::string& metadata)
{
  const nlohmann::json json = nlohmann::json::parse(metadata, nullptr, false);
  if (json.is_discarded() || !json.is_object() || !json.contains("units") ||
      !json["units"].is_object())
  {
    return std::nullopt;
  }
  const nlohmann::json& units = json["units"];
  const double scale = units.value("metresPerUnit", 0.0);
  if (!(scale > 0.0) || !std::isfinite(scale))
  {
    return std::nullopt;
  }
  return LengthUnits{ units.value("name", std::string()), scale };
}

/// The quality report recorded in a bundle's metadata (toJson's text), or
/// an empty text.
std::string storedQuality(const std::string& metadata)
{
  const nlohmann::json json = nlohmann::json::parse(metadata, nullptr, false);
  if (json.is_discarded() || !json.is_object() || !json.contains("quality"))
  {
    return {};
  }
  return json["quality"].dump();
}

void requireOnePiece(const TriangleMesh& visual)
{
  const std::size_t pieces = countPieces(visual);
  if (pieces > 1)
  {
    throw InvalidInputError("visual mesh '" + visual.name + "': " + std::to_string(pieces) +
                            " separate pieces; each large piece is a tissue of its own "
                            "(prepareTissues, ThinTissuePrepare)");
  }
}

nlohmann::json preparationMetadata(const TriangleMesh& visual,
  const TissuePreparationSettings& settings,
  const GeneratedCollisionMesh& generated,
  const TissueBundle& bundle)
{
  nlohmann::json metadata;
  metadata["generator"] = "ThinTissue prepareTissue";
  metadata["source"] = visual.name;
  metadata["collisionVertices"] = bundle.collision.vertexCount();
  metadata["collisionTriangles"] = bundle.collision.triangleCount();
  metadata["collisionBorderVertices"] = generated.borderVertexCount;
  metadata["hexahedra"] = bundle.simulation.hexahedronCount();
  metadata["requestedHexahedra"] = settings.hexahedronCount;
  metadata["visualVertices"] = bundle.visual.vertexCount();
  metadata["visualTriangles"] = bundle.visual.triangleCount();
  metadata["hausdorffDistance"] = generated.hausdorffDistance;
  metadata["visualToThick"] = generated.visualToThick;
  metadata["thickToVisual"] = generated.thickToVisual;
  metadata["largestThickness"] = generated.largestThickness;
  metadata["thicknessRatio"] = generated.thicknessRatio;
  metadata["thicknessAxis"] = {
    generated.thicknessAxis.x(), generated.thicknessAxis.y(), generated.thicknessAxis.z()
  };
  metadata["midSurface"] = generated.method == MidSurfaceMethod::Band ? "band" : "one axis";
  if (generated.joinedHoles > 0)
  {
    metadata["joinedHoles"] = generated.joinedHoles;
  }
  if (generated.method == MidSurfaceMethod::OneAxis)
  {
    metadata["latticePhase"] = generated.latticePhase;
  }
  if (generated.method == MidSurfaceMethod::Band)
  {
    metadata["thicknessTurnDegrees"] = generated.thicknessTurn * 180.0 / M_PI;
  }
  return metadata;
}

/// The collision mid-surfaces tried in turn until one binds, and the
/// errors of those refused (each named by what it varied).
class MidSurfaceAttempts
{
public:
  template <typename Bind>
  bool attempt(const Bind& bind, const CollisionMeshSettings& settings, const std::string& what)
  {
    try
    {
      bind(settings);
      return true;
    }
    catch (const InvalidInputError& error)
    {
      if (!first_)
        first_ = std::current_exception();
      refused_.push_back(what + ": " + error.what());
      return false;
    }
  }

  /// attempt(settings), and where holes of the outline were joined
  /// (CollisionMeshSettings::joinSeenThroughHoles) and that fails, with
  /// them filled: a joined hole can leave the collision mesh a neck one
  /// vertex wide between two lobes of a rough segmentation.
  template <typename Bind>
  bool attemptJoiningHoles(const Bind& bind,
    const CollisionMeshSettings& settings,
    const GeneratedCollisionMesh& generated,
    const std::string& what)
  {
    if (attempt(bind, settings, what))
      return true;
    if (generated.joinedHoles == 0 || !settings.joinSeenThroughHoles)
      return false;
    CollisionMeshSettings filled = settings;
    filled.joinSeenThroughHoles = false;
    return attempt(bind, filled, what + ", seen-through holes filled");
  }

  [[noreturn]] void rethrowFirst() const { std::rethrow_exception(first_); }
  const std::vector<std::string>& refused() const { return refused_; }

private:
  std::exception_ptr first_;
  std::vector<std::string> refused_;
};

/// The collision mid-surface and the binding to it, the settings' first.
/// Automatic method: when the binding refuses the one-axis mid-surface of
/// an elongated tissue (a band whose thickness direction turns: its paths
/// cross), the band's mid-surface is bound instead. Then the one-axis
/// lattice moved by a third, a half and two thirds of a cell: on a rough
/// segmentation a narrow strip can fall between two rows of the lattice (a
/// row of sliver collision triangles whose side paths cross) where the
/// lattice moved covers it. The first error when all fail; the refused
/// ones in `refused`.
void bindToMidSurface(const TriangleMesh& visual,
  const TissuePreparationSettings& settings,
  const GenerationProgress& collisionProgress,
  const BindingProgress& bindingProgress,
  GeneratedCollisionMesh& generated,
  TissueBundle& bundle,
  std::vector<std::string>& refused)
{
  VisualCollisionBindingSettings bindingSettings = settings.binding;
  bindingSettings.radiusArrayName = settings.collision.radiusArrayName;
  auto bind = [&](const CollisionMeshSettings& collisionSettings)
  {
    generated = makeCollisionMidSurface(visual, collisionSettings, collisionProgress);
    bundle.collision = generated.mesh;
    try
    {
      bundle.binding =
        bindVisualToCollision(visual, bundle.collision, bindingSettings, bindingProgress);
    }
    catch (const BindingAbortedError& aborted)
    {
      throw GenerationAbortedError(aborted.what());
    }
  };
  MidSurfaceAttempts attempts;
  const bool bound = [&]
  {
    if (attempts.attemptJoiningHoles(bind, settings.collision, generated, "as asked"))
      return true;
    // A one-axis mid-surface the binding refused (not one the generation
    // refused): the band may serve, and its lattice may move.
    const bool oneAxisRefused =
      !generated.mesh.triangles.empty() && generated.method == MidSurfaceMethod::OneAxis;
    constexpr double MinimumBandElongation = 2.0; // as makeCollisionMidSurface's
    if (settings.collision.method == MidSurfaceMethod::Automatic && oneAxisRefused &&
        elongationOf(visual) >= MinimumBandElongation)
    {
      CollisionMeshSettings band = settings.collision;
      band.method = MidSurfaceMethod::Band;
      if (attempts.attempt(bind, band, "band mid-surface"))
        return true;
    }
    if (!oneAxisRefused)
      return false;
    for (const double shift : { 1.0 / 3.0, 0.5, 2.0 / 3.0 })
    {
      CollisionMeshSettings moved = settings.collision;
      moved.method = MidSurfaceMethod::OneAxis;
      moved.latticePhase = std::fmod(settings.collision.latticePhase + shift, 1.0);
      std::ostringstream what;
      what << "one axis, lattice phase " << moved.latticePhase;
      if (attempts.attemptJoiningHoles(bind, moved, generated, what.str()))
        return true;
    }
    return false;
  }();
  refused = attempts.refused();
  if (!bound)
    attempts.rethrowFirst();
}

/// The tunnels closed before the preparation, and whether the collision
/// mesh's resolution decided some (closeSmallTunnels with its vertex count).
struct ClosedTunnels
{
  TunnelClosingReport report;
  bool forCollisionMesh = false;
};

/// prepareOne (below) on the visual surface with its tunnels closed.
TissueBundle prepareClosed(const TriangleMesh& visual,
  const ClosedTunnels& tunnels,
  const TissuePreparationSettings& settings,
  const ResolvedUnits& units,
  const nlohmann::json& extra,
  const GenerationProgress& progress,
  std::chrono::steady_clock::time_point start)
{
  // Stages: hexahedra 0-0.05, collision mesh 0.05-0.25, binding 0.25-0.95,
  // quality 0.95-1.
  auto stage = [&](double from, double to)
  {
    return [&progress, from, to](double fraction, const char* what)
    { return !progress || progress(from + (to - from) * fraction, what); };
  };
  auto announce = [&](double fraction, const char* what)
  {
    if (progress && !progress(fraction, what))
    {
      throw GenerationAbortedError(std::string("tissue preparation aborted while ") + what);
    }
  };
  TissueBundle bundle;
  announce(0.0, "making the hexahedra");
  bundle.simulation = makeSimulationHexahedra(visual, settings.hexahedronCount);
  GeneratedCollisionMesh generated;
  std::vector<std::string> refused;
  bindToMidSurface(
    visual, settings, stage(0.05, 0.25), stage(0.25, 0.95), generated, bundle, refused);
  bundle.visual = bundle.binding.visual;
  embed(bundle);
  announce(0.95, "measuring the quality");
  bundle.quality = measureTissueQuality(bundle.binding, settings.quality);
  bundle.units = units.units;
  nlohmann::json metadata = preparationMetadata(visual, settings, generated, bundle);
  metadata["units"] = unitsJson(units);
  if (!refused.empty())
  {
    metadata["refusedCollisionMeshes"] = refused;
  }
  const TunnelClosingReport& closed = tunnels.report;
  if (closed.genusBefore > 0)
  {
    metadata["tunnels"] = { { "genusBefore", closed.genusBefore },
      { "genusAfter", closed.genusAfter },
      { "found", closed.tunnels },
      { "closed", closed.closed },
      { "places", closed.changes },
      { "forCollisionMesh", tunnels.forCollisionMesh } };
  }
  metadata["quality"] = nlohmann::json::parse(bundle.quality.toJson());
  metadata.update(extra);
  metadata["preparationSeconds"] =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  bundle.metadata = metadata.dump(2);
  announce(1.0, "done");
  return bundle;
}

/// prepareTissue with the units already found; `extra` goes into the
/// metadata (the piece of several). A segmentation's tunnels through a
/// thin rim would join the two sides that the rim paths must separate:
/// they are closed first, and reported. When the preparation then fails,
/// the holes too small for the collision mesh to run around (a lace-like
/// segmentation of a sheet thinner than two slices) are closed as well and
/// it is tried again; the first error when that closes nothing more or
/// fails too. Only a failing preparation changes: on the others the holes
/// stay as the segmentation has them.
TissueBundle prepareOne(const TriangleMesh& input,
  const TissuePreparationSettings& settings,
  const ResolvedUnits& units,
  const nlohmann::json& extra,
  const GenerationProgress& progress)
{
  const auto start = std::chrono::steady_clock::now();
  ClosedTunnels tunnels;
  const TriangleMesh visual = closeSmallTunnels(input, &tunnels.report);
  try
  {
    return prepareClosed(visual, tunnels, settings, units, extra, progress, start);
  }
  catch (const InvalidInputError&)
  {
    const std::exception_ptr first = std::current_exception();
    // A disk of V vertices has about 2V triangles.
    const int collisionVertices = settings.collision.triangleCount > 0
                                    ? (settings.collision.triangleCount + 1) / 2
                                    : settings.collision.vertexCount;
    ClosedTunnels more;
    more.forCollisionMesh = true;
    const TriangleMesh closedMore = closeSmallTunnels(input, &more.report, collisionVertices);
    if (more.report.closed <= tunnels.report.closed)
      throw;
    try
    {
      return prepareClosed(closedMore, more, settings, units, extra, progress, start);
    }
    catch (const InvalidInputError&)
    {
      std::rethrow_exception(first);
    }
  }
}

/// The dropped fragments, as metadata, with a warning each.
nlohmann::json droppedPieces(const PieceSelection& pieces, std::vector<std::string>& warnings)
{
  nlohmann::json dropped = nlohmann::json::array();
  for (const MeshPiece& piece : pieces.dropped)
  {
    std::ostringstream percent;
    percent.precision(2);
    percent << 100.0 * piece.area / pieces.kept.front().area;
    warnings.push_back("dropped " + piece.description() + ": " + percent.str() +
                       "% of the largest piece's area, a fragment");
    dropped.push_back(piece.description());
  }
  return dropped;
}

} // namespace

TissueBundle prepareTissue(const TriangleMesh& visual,
  const TissuePreparationSettings& settings,
  const GenerationProgress& progress)
{
  requireOnePiece(visual);
  const ResolvedUnits units = resolveUnits(settings.units, visual.boundingBox().sizes().maxCoeff());
  return prepareOne(visual, settings, units, nlohmann::json::object(), progress);
}

PreparedTissues prepareTissues(const TriangleMesh& visual,
  const TissuePreparationSettings& settings,
  const GenerationProgress& progress)
{
  PieceSelection pieces = selectPieces(visual, settings.minimumPieceFraction);
  if (pieces.kept.empty())
  {
    throw InvalidInputError("visual mesh '" + visual.name + "' has no triangles");
  }
  PreparedTissues result;
  const ResolvedUnits units = resolveUnits(settings.units, pieces.kept.front().largestExtent);
  result.units = units.units;
  result.unitsDetected = units.detected;
  result.unitsReason = units.reason;
  if (!units.confident)
  {
    result.warnings.push_back("units: " + units.reason + "; give them if they are not");
  }
  const nlohmann::json dropped = droppedPieces(pieces, result.warnings);
  std::size_t totalVertices = 0;
  for (const MeshPiece& piece : pieces.kept)
  {
    totalVertices += piece.mesh.vertexCount();
  }
  std::size_t doneVertices = 0;
  for (const MeshPiece& piece : pieces.kept)
  {
    // Progress by pieces, in proportion to their vertices.
    const double from = static_cast<double>(doneVertices) / totalVertices;
    doneVertices += piece.mesh.vertexCount();
    const double to = static_cast<double>(doneVertices) / totalVertices;
    GenerationProgress pieceProgress = [&progress, from, to](double fraction, const char* what)
    { return !progress || progress(from + (to - from) * fraction, what); };
    nlohmann::json extra;
    extra["piece"] = { { "number", piece.number },
      { "of", pieces.kept.size() },
      { "area", piece.area },
      { "centre", { piece.centre.x(), piece.centre.y(), piece.centre.z() } } };
    extra["droppedPieces"] = dropped;
    result.tissues.push_back(prepareOne(piece.mesh, settings, units, extra, pieceProgress));
  }
  result.droppedPieces = std::move(pieces.dropped);
  return result;
}

void addBundleMetadata(TissueBundle& bundle, const std::string& key, const std::string& json)
{
  try
  {
    // A bundle from elsewhere may carry no metadata yet: start an object.
    nlohmann::json metadata =
      bundle.metadata.empty() ? nlohmann::json::object() : nlohmann::json::parse(bundle.metadata);
    metadata[key] = nlohmann::json::parse(json);
    bundle.metadata = metadata.dump(2);
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InvalidInputError("bundle metadata: cannot add '" + key + "': " + e.what());
  }
}

void convertTissueBundleUnits(TissueBundle& bundle, const LengthUnits& units)
{
  const LengthUnits from = bundle.units ? *bundle.units : *lengthUnitsNamed("mm");
  const double factor = from.metresPerUnit / units.metresPerUnit;
  if (!(factor > 0.0) || !std::isfinite(factor))
  {
    throw InvalidInputError("bundle '" + bundle.visual.name + "': cannot convert from " +
                            from.description() + " to " + units.description());
  }
  auto scale = [factor](std::vector<Vector3>& points)
  {
    for (Vector3& x : points)
      x *= factor;
  };
  scale(bundle.visual.positions);
  scale(bundle.collision.positions);
  if (bundle.collision.pointAttributes.has("Radius"))
  {
    for (double& r : bundle.collision.pointAttributes.get("Radius").values)
      r *= factor;
  }
  scale(bundle.simulation.nodes);
  VisualCollisionBinding& binding = bundle.binding;
  scale(binding.visual.positions);
  scale(binding.collisionPositions);
  for (double& r : binding.collisionRadii)
    r *= factor;
  for (BindingPath& path : binding.paths)
    path.length *= factor;
  TissueQuality& quality = bundle.quality;
  quality.hausdorffDistance *= factor;
  quality.largestThickness *= factor;
  quality.worstDeviation.distance *= factor;
  quality.worstDeviation.localThickness *= factor;
  quality.worstDeviation.point *= factor;
  quality.worstRegion.centre *= factor;
  bundle.units = units;
  // The metadata says what a file read back will be: the new units and the
  // quality in them.
  addBundleMetadata(bundle,
    "units",
    unitsJson({ units, false, "converted from " + from.description(), true }).dump());
  addBundleMetadata(bundle, "quality", quality.toJson());
  addBundleMetadata(bundle, "convertedFrom", nlohmann::json(from.description()).dump());
}

namespace
{

/// A single tissue's file content.
std::string bundleBytes(const TissueBundle& bundle)
{
  // The input checksum of a bundle is that of its own meshes: a bundle is
  // read on its own (readBindingFile), the checksum names what it holds.
  return bindingCacheBytes(bundle.binding,
    bindingInputChecksum(bundle.visual, bundle.collision, VisualCollisionBindingSettings{}),
    &bundle.simulation,
    bundle.metadata);
}

template <typename T>
void put(std::string& bytes, T value)
{
  bytes.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// `contents` of the file (or tissue) `name` as a bundle.
TissueBundle bundleOf(const std::string& path,
  const std::string& name,
  std::optional<BindingCacheContents> contents,
  const std::string& why)
{
  if (!contents)
  {
    // why: "binding file '<name>': <reason>"; the error names the path.
    const std::string prefix = "binding file '" + name + "': ";
    const std::string reason = why.rfind(prefix, 0) == 0 ? why.substr(prefix.size()) : why;
    throw FileError(path, "tissue bundle: " + (name == path ? "" : name + ": ") + reason);
  }
  if (!contents->simulation)
  {
    throw FileError(path, "tissue bundle: a binding file without hexahedra");
  }
  TissueBundle bundle;
  bundle.binding = std::move(contents->binding);
  bundle.simulation = std::move(*contents->simulation);
  bundle.metadata = std::move(contents->metadata);
  bundle.visual = bundle.binding.visual;
  bundle.collision.name = bundle.visual.name + " collision";
  bundle.collision.positions = bundle.binding.collisionPositions;
  bundle.collision.triangles = bundle.binding.collisionTriangles;
  bundle.collision.pointAttributes.set("Radius", 1, bundle.binding.collisionRadii);
  try
  {
    embed(bundle);
  }
  catch (const Error& error)
  {
    throw FileError(
      path, std::string("tissue bundle: its hexahedra do not hold its meshes: ") + error.what());
  }
  // The preparation's report, kept in the metadata; measured again only
  // for a bundle without one (it costs about as much as the rest of the
  // reading).
  if (!bundle.quality.fromJson(storedQuality(bundle.metadata)))
  {
    bundle.quality = measureTissueQuality(bundle.binding);
  }
  bundle.units = unitsFromMetadata(bundle.metadata);
  return bundle;
}

/// The whole file, when it holds several tissues (nothing otherwise).
std::optional<std::string> severalTissuesFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  char magic[sizeof(SeveralTissuesMagic)] = {};
  if (!in || std::filesystem::is_directory(path) || !in.read(magic, sizeof(magic)) ||
      std::memcmp(magic, SeveralTissuesMagic, sizeof(magic)) != 0)
  {
    return std::nullopt;
  }
  in.seekg(0);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The tissues' files inside a file of several tissues.
std::vector<std::string> tissueFiles(const std::string& path, const std::string& bytes)
{
  std::size_t at = sizeof(SeveralTissuesMagic);
  auto take = [&](std::size_t size)
  {
    if (bytes.size() - at < size)
    {
      throw FileError(
        path, "tissue bundle: damaged: truncated after " + std::to_string(at) + " bytes");
    }
    at += size;
    return bytes.substr(at - size, size);
  };
  auto number = [&](auto value)
  {
    std::memcpy(&value, take(sizeof(value)).data(), sizeof(value));
    return value;
  };
  const auto version = number(std::uint32_t());
  if (version != SeveralTissuesVersion)
  {
    throw FileError(path,
      "tissue bundle: format version " + std::to_string(version) +
        " of several tissues, expected " + std::to_string(SeveralTissuesVersion));
  }
  std::vector<std::string> files(number(std::uint32_t()));
  for (std::string& file : files)
  {
    file = take(number(std::uint64_t()));
  }
  if (at != bytes.size())
  {
    throw FileError(path, "tissue bundle: damaged: trailing bytes");
  }
  return files;
}

} // namespace

void writeTissueBundle(const std::string& path, const TissueBundle& bundle)
{
  const std::string bytes = bundleBytes(bundle);
  writeFileAtomically(path,
    [&](std::ostream& out)
    { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

void writeTissueBundles(const std::string& path, const std::vector<TissueBundle>& bundles)
{
  if (bundles.empty())
  {
    throw InvalidInputError("tissue bundle '" + path + "': no tissues to write");
  }
  if (bundles.size() == 1)
  {
    writeTissueBundle(path, bundles.front());
    return;
  }
  std::string bytes(SeveralTissuesMagic, sizeof(SeveralTissuesMagic));
  put(bytes, SeveralTissuesVersion);
  put(bytes, static_cast<std::uint32_t>(bundles.size()));
  for (const TissueBundle& bundle : bundles)
  {
    const std::string file = bundleBytes(bundle);
    put(bytes, static_cast<std::uint64_t>(file.size()));
    bytes += file;
  }
  writeFileAtomically(path,
    [&](std::ostream& out)
    { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

TissueBundle readTissueBundle(const std::string& path)
{
  if (const std::optional<std::string> several = severalTissuesFile(path))
  {
    const std::size_t count = tissueFiles(path, *several).size();
    throw FileError(path,
      "tissue bundle: holds " + std::to_string(count) +
        " tissues; read them with readTissueBundles (vtkTissueBundleReader: "
        "TissueIndex)");
  }
  std::string why;
  return bundleOf(path, path, readBindingFile(path, &why), why);
}

std::vector<TissueBundle> readTissueBundles(const std::string& path)
{
  const std::optional<std::string> several = severalTissuesFile(path);
  if (!several)
  {
    return { readTissueBundle(path) };
  }
  std::vector<TissueBundle> bundles;
  const std::vector<std::string> files = tissueFiles(path, *several);
  for (std::size_t i = 0; i < files.size(); ++i)
  {
    const std::string name =
      "tissue " + std::to_string(i + 1) + " of " + std::to_string(files.size());
    std::string why;
    bundles.push_back(bundleOf(path, name, readBindingBytes(files[i], name, &why), why));
  }
  return bundles;
}

} // namespace thintissue
