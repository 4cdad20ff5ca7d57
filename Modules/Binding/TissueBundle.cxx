#include "TissueBundle.h"

#include "BindingCache.h"
#include "ThinTissueError.h"

#include <nlohmann/json.hpp>

#include <chrono>

namespace thintissue
{

namespace
{

void embed(TissueBundle& bundle)
{
  bundle.visualEmbedding = HexahedralEmbedding(bundle.simulation, bundle.visual.positions);
  bundle.collisionEmbedding = HexahedralEmbedding(bundle.simulation, bundle.collision.positions);
}

} // namespace

TissueBundle prepareTissue(const TriangleMesh& visual,
  const TissuePreparationSettings& settings,
  const GenerationProgress& progress)
{
  const auto start = std::chrono::steady_clock::now();
  // Stages: collision mesh 0-0.2, hexahedra 0.2-0.25, binding 0.25-1.
  auto stage = [&](double from, double to)
  {
    return [&progress, from, to](double fraction, const char* what)
    { return !progress || progress(from + (to - from) * fraction, what); };
  };
  TissueBundle bundle;
  const GeneratedCollisionMesh generated =
    makeCollisionMidSurface(visual, settings.collision, stage(0.0, 0.2));
  bundle.collision = generated.mesh;
  if (progress && !progress(0.2, "making the hexahedra"))
  {
    throw GenerationAbortedError("tissue preparation aborted while making the hexahedra");
  }
  bundle.simulation = makeSimulationHexahedra(visual, settings.hexahedronCount);
  VisualCollisionBindingSettings bindingSettings = settings.binding;
  bindingSettings.radiusArrayName = settings.collision.radiusArrayName;
  const auto bindingStage = stage(0.25, 1.0);
  try
  {
    bundle.binding = bindVisualToCollision(visual, bundle.collision, bindingSettings, bindingStage);
  }
  catch (const BindingAbortedError& aborted)
  {
    throw GenerationAbortedError(aborted.what());
  }
  bundle.visual = bundle.binding.visual;
  embed(bundle);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
  metadata["preparationSeconds"] = seconds;
  bundle.metadata = metadata.dump(2);
  return bundle;
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

void writeTissueBundle(const std::string& path, const TissueBundle& bundle)
{
  // The input checksum of a bundle is that of its own meshes: a bundle is
  // read on its own (readBindingFile), the checksum names what it holds.
  writeBindingCache(path,
    bundle.binding,
    bindingInputChecksum(bundle.visual, bundle.collision, VisualCollisionBindingSettings{}),
    &bundle.simulation,
    bundle.metadata);
}

TissueBundle readTissueBundle(const std::string& path)
{
  std::string why;
  std::optional<BindingCacheContents> contents = readBindingFile(path, &why);
  if (!contents)
  {
    // why: "binding file '<path>': <reason>"; the error names the path.
    const std::string prefix = "binding file '" + path + "': ";
    throw FileError(
      path, "tissue bundle: " + (why.rfind(prefix, 0) == 0 ? why.substr(prefix.size()) : why));
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
  return bundle;
}

} // namespace thintissue
