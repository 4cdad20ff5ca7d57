#include "Scenario.h"

#include "AtomicFileWriter.h"
#include "LengthUnits.h"
#include "ThinTissueError.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace thintissue
{

namespace
{

using Json = nlohmann::json;

/// Reads the keys of a scenario, naming the file and the key in every
/// complaint.
class ScenarioReader
{
public:
  ScenarioReader(const Json& root, std::string source)
    : Root(root)
    , Source(std::move(source))
  {
  }

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const
  {
    throw InvalidInputError("scenario '" + Source + "': key '" + key + "': " + problem);
  }

  /// The value at a dotted key, or null if absent.
  const Json* find(const std::string& key) const
  {
    const Json* node = &Root;
    std::istringstream parts(key);
    std::string part;
    while (std::getline(parts, part, '.'))
    {
      if (!node->is_object() || !node->contains(part))
      {
        return nullptr;
      }
      node = &(*node)[part];
    }
    return node;
  }

  double number(const std::string& key, double fallback, bool positive = true) const
  {
    const Json* value = find(key);
    if (value == nullptr)
    {
      return fallback;
    }
    if (!value->is_number() || !std::isfinite(value->get<double>()))
    {
      fail(key, "must be a number");
    }
    const double x = value->get<double>();
    if (positive && !(x > 0.0))
    {
      fail(key, "must be positive (is " + value->dump() + ")");
    }
    return x;
  }

  std::string text(const std::string& key, const std::string& fallback) const
  {
    const Json* value = find(key);
    if (value == nullptr)
    {
      return fallback;
    }
    if (!value->is_string())
    {
      fail(key, "must be a string");
    }
    return value->get<std::string>();
  }

  bool flag(const std::string& key, bool fallback) const
  {
    const Json* value = find(key);
    if (value == nullptr)
    {
      return fallback;
    }
    if (!value->is_boolean())
    {
      fail(key, "must be true or false");
    }
    return value->get<bool>();
  }

  Vector3 vector(const std::string& key, const Vector3& fallback, bool nonZero = false) const
  {
    const Json* value = find(key);
    if (value == nullptr)
    {
      return fallback;
    }
    if (!value->is_array() || value->size() != 3 || !(*value)[0].is_number() ||
        !(*value)[1].is_number() || !(*value)[2].is_number())
    {
      fail(key, "must be three numbers [x, y, z]");
    }
    const Vector3 v(
      (*value)[0].get<double>(), (*value)[1].get<double>(), (*value)[2].get<double>());
    if (!v.allFinite() || (nonZero && v.norm() == 0.0))
    {
      fail(key, nonZero ? "must be a finite, non-zero direction" : "must be finite");
    }
    return v;
  }

  /// A whole number in [lowest, highest].
  double whole(const std::string& key,
    double fallback,
    double lowest,
    double highest,
    const std::string& what) const
  {
    const double x = number(key, fallback, false);
    if (x != std::floor(x) || x < lowest || x > highest)
    {
      fail(key, "must be " + what);
    }
    return x;
  }

  template <typename Parse>
  auto named(const std::string& key, const std::string& fallback, Parse parse) const
  {
    const std::string name = text(key, fallback);
    try
    {
      return parse(name);
    }
    catch (const InvalidInputError& e)
    {
      fail(key, e.what());
    }
  }

private:
  const Json& Root;
  std::string Source;
};

/// A path relative to the scenario file's directory.
std::string besideScenario(const std::string& source, const std::string& path)
{
  const std::filesystem::path p(path);
  if (p.is_absolute() || source.empty())
    return path;
  return (std::filesystem::path(source).parent_path() / p).lexically_normal().string();
}

void readTissueSource(const ScenarioReader& r, ScenarioDescription& s)
{
  static const std::vector<std::string> models = { "meniscus",
    "anterior_cruciate_ligament",
    "posterior_cruciate_ligament",
    "tibial_cartilage",
    "sheet",
    "file",
    "bundle" };
  s.tissueModel = r.text("tissue.model", s.tissueModel);
  if (std::find(models.begin(), models.end(), s.tissueModel) == models.end())
  {
    std::string known;
    for (const std::string& m : models)
      known += (known.empty() ? "" : ", ") + m;
    r.fail("tissue.model", "unknown model '" + s.tissueModel + "' (known: " + known + ")");
  }
  const bool fromFile = s.tissueModel == "file" || s.tissueModel == "bundle";
  s.tissueFile = r.text("tissue.file", "");
  if (fromFile && s.tissueFile.empty())
  {
    r.fail("tissue.file", "a \"" + s.tissueModel + "\" tissue needs its file");
  }
  s.tissueFile = besideScenario(s.source, s.tissueFile);
  s.tissueUnits = r.text("tissue.units", "");
  if (!s.tissueUnits.empty() && !lengthUnitsNamed(s.tissueUnits))
  {
    r.fail("tissue.units", "unknown unit '" + s.tissueUnits + "' (mm, cm, m, um)");
  }
  s.tissueThickness = r.number("tissue.thickness", 0.0, false);
  if (s.tissueThickness < 0.0)
  {
    r.fail("tissue.thickness", "must not be negative (mm; 0: a closed mesh)");
  }
  s.fixedNodes = r.text("tissue.fixed", s.fixedNodes);
  if (s.fixedNodes != "model" && s.fixedNodes != "none" && s.fixedNodes != "ends" &&
      s.fixedNodes != "bottom")
  {
    r.fail("tissue.fixed", "must be \"model\", \"none\", \"ends\" or \"bottom\"");
  }
  s.sheetSize = r.vector("tissue.size", s.sheetSize);
  s.knee = r.flag("knee", s.knee);
  s.portalsFromTissueCentre = r.flag("portalsFromTissueCentre", s.portalsFromTissueCentre);
}

void readMaterial(const ScenarioReader& r, ScenarioDescription& s)
{
  s.material.youngModulus = r.number("tissue.material.youngModulus", s.material.youngModulus);
  s.material.poissonRatio =
    r.number("tissue.material.poissonRatio", s.material.poissonRatio, false);
  if (!(s.material.poissonRatio > -1.0 && s.material.poissonRatio < 0.5))
  {
    r.fail("tissue.material.poissonRatio",
      "must lie in (-1, 0.5) (0.5 is incompressible, which the FEM cannot take); is " +
        std::to_string(s.material.poissonRatio));
  }
  s.material.density = r.number("tissue.material.density", s.material.density);
  try
  {
    checkMaterial(s.material, "tissue.material");
  }
  catch (const InvalidInputError& e)
  {
    r.fail("tissue.material", e.what());
  }
}

void readWrinkleParameters(const ScenarioReader& r, ScenarioDescription& s)
{
  WrinkleParameters& w = s.wrinkle;
  w.frequency = r.number("tissue.wrinkle.frequency", w.frequency);
  w.scale = r.number("tissue.wrinkle.scale", w.scale, false);
  w.magnitudeBound = r.number("tissue.wrinkle.magnitudeBound", w.magnitudeBound, false);
  const double window = r.number("tissue.wrinkle.windowSize", w.windowSize);
  if (window != std::floor(window) || window < 2.0 || window > 10000.0)
  {
    r.fail("tissue.wrinkle.windowSize", "must be a whole number of monitor points, at least 2");
  }
  w.windowSize = static_cast<int>(window);
  const double perStep =
    r.number("tissue.wrinkle.refreshMonitorsPerStep", w.refreshMonitorsPerUpdate, false);
  if (perStep != std::floor(perStep) || perStep < 0.0 || perStep > 1e6)
  {
    r.fail("tissue.wrinkle.refreshMonitorsPerStep",
      "must be a whole number of monitor points, 0 (all at the cut) or more");
  }
  w.refreshMonitorsPerUpdate = static_cast<int>(perStep);
  try
  {
    checkWrinkleParameters(w);
  }
  catch (const InvalidInputError& e)
  {
    r.fail("tissue.wrinkle", e.what());
  }
}

void readCutting(const ScenarioReader& r, ScenarioDescription& s)
{
  s.cutSurfaceRows = static_cast<int>(
    r.whole("cutting.cutSurfaceRows", s.cutSurfaceRows, 0.0, 8.0, "a whole number from 0 to 8"));
  s.fragmentAreaFraction = r.number("cutting.fragmentAreaFraction", s.fragmentAreaFraction, false);
  if (s.fragmentAreaFraction < 0.0 || s.fragmentAreaFraction >= 1.0)
  {
    r.fail("cutting.fragmentAreaFraction", "must lie in [0, 1)");
  }
  s.jaggedAmplitude = r.number("cutting.jagged.amplitude", s.jaggedAmplitude, false);
  if (s.jaggedAmplitude < 0.0 || s.jaggedAmplitude > 2.0)
  {
    r.fail("cutting.jagged.amplitude", "must lie in [0, 2] mm");
  }
  if (s.jaggedAmplitude > 0.0 && s.cutSurfaceRows < 1)
  {
    r.fail("cutting.jagged.amplitude", "a jagged cut surface needs cutting.cutSurfaceRows >= 1");
  }
  s.jaggedWavelength = r.number("cutting.jagged.wavelength", s.jaggedWavelength);
  s.jaggedSeed = static_cast<unsigned>(
    r.whole("cutting.jagged.seed", s.jaggedSeed, 0.0, 4294967295.0, "a whole number >= 0"));
}

void readShaver(const ScenarioReader& r, ScenarioDescription& s)
{
  const bool shaver = s.instrument == SurgicalInstrumentType::SmallShaver ||
                      s.instrument == SurgicalInstrumentType::LargeShaver;
  if (!shaver && (r.find("instrument.shaverMode") || r.find("instrument.contourStrength")))
  {
    r.fail(r.find("instrument.shaverMode") ? "instrument.shaverMode" : "instrument.contourStrength",
      "only a shaver has a mode");
  }
  s.shaverMode = r.named("instrument.shaverMode",
    shaverModeName(s.shaverMode),
    [](const std::string& n) { return shaverModeFromName(n); });
  s.contourStrength = r.number("instrument.contourStrength", s.contourStrength);
  if (s.contourStrength > 1.0)
  {
    r.fail("instrument.contourStrength", "must lie in (0, 1]");
  }
}

void readPreparation(const ScenarioReader& r, ScenarioDescription& s)
{
  if (r.find("preparation.punchBites") == nullptr)
  {
    return;
  }
  if (s.tissueModel != "meniscus")
  {
    r.fail("preparation.punchBites", "bites along the inner border need the meniscus model");
  }
  s.preBites = static_cast<int>(
    r.whole("preparation.punchBites.count", 4.0, 1.0, 50.0, "a whole number from 1 to 50"));
  s.preBitesFrom = r.number("preparation.punchBites.from", s.preBitesFrom, false);
  s.preBitesTo = r.number("preparation.punchBites.to", s.preBitesTo, false);
  if (!(0.0 <= s.preBitesFrom && s.preBitesFrom <= s.preBitesTo && s.preBitesTo <= 1.0))
  {
    r.fail("preparation.punchBites", "needs 0 <= from <= to <= 1 (fractions of the border)");
  }
  s.preBitesInward = r.number("preparation.punchBites.inward", s.preBitesInward, false);
  if (s.preBitesInward < -2.0 || s.preBitesInward > 5.0)
  {
    r.fail("preparation.punchBites.inward", "must lie in [-2, 5] mm");
  }
}

/// What the settings panel may change too.
void readSettings(const ScenarioReader& r, ScenarioDescription& s)
{
  readMaterial(r, s);
  readWrinkleParameters(r, s);
  readCutting(r, s);
}

void readTissue(const ScenarioReader& r, ScenarioDescription& s)
{
  readTissueSource(r, s);
  s.tear = r.named(
    "tissue.tear", "none", [](const std::string& n) { return meniscusTearTypeFromName(n); });
  const std::string resolution = r.text("tissue.resolution", "examination");
  if (resolution != "examination" && resolution != "default")
  {
    r.fail("tissue.resolution", "must be \"examination\" or \"default\"");
  }
  s.examinationResolution = resolution == "examination";
  s.wrinkles = r.flag("tissue.wrinkles", s.tissueModel == "meniscus" && s.wrinkles);
  if (s.wrinkles && s.tissueModel != "meniscus")
  {
    r.fail("tissue.wrinkles", "only the meniscus model carries monitor data for wrinkles");
  }
  readSettings(r, s);
}

} // namespace

ScenarioDescription parseScenario(const std::string& text, const std::string& source)
{
  Json root;
  try
  {
    root = Json::parse(text);
  }
  catch (const Json::parse_error& e)
  {
    throw InvalidInputError("scenario '" + source + "': not JSON (" + e.what() + ")");
  }
  const ScenarioReader r(root, source);
  if (!root.is_object())
  {
    r.fail("(top)", "must be a JSON object");
  }
  const Json* version = r.find("version");
  if (version == nullptr || !version->is_number_integer() || version->get<int>() != ScenarioVersion)
  {
    r.fail("version", "must be " + std::to_string(ScenarioVersion));
  }
  ScenarioDescription s;
  s.source = source;
  s.name = r.text("name", source);
  s.description = r.text("description", "");
  readTissue(r, s);
  s.jointGap = r.number("jointGap", s.jointGap);
  s.instrument = r.named("instrument.type",
    "probe_hook",
    [](const std::string& n) { return parseSurgicalInstrumentType(n); });
  s.instrumentPortal.portal = r.vector("instrument.portal", s.instrumentPortal.portal);
  s.instrumentPortal.inward = r.vector("instrument.inward", s.instrumentPortal.inward, true);
  s.scopePortal.portal = r.vector("arthroscope.portal", s.scopePortal.portal);
  s.scopePortal.inward = r.vector("arthroscope.inward", s.scopePortal.inward, true);
  readShaver(r, s);
  readPreparation(r, s);
  s.viewingAngle = r.number("arthroscope.viewingAngle", s.viewingAngle, false);
  if (s.viewingAngle < 0.0 || s.viewingAngle > 90.0)
  {
    r.fail("arthroscope.viewingAngle", "must be between 0 and 90 degrees");
  }
  s.timeStep = r.number("physics.timeStep", s.timeStep);
  s.task = r.text("task.kind", s.task);
  s.duration = r.number("task.duration", s.duration);
  s.targetCentre = r.vector("task.target.centre", s.targetCentre);
  s.targetRadius = r.number("task.target.radius", s.targetRadius, false);
  if (s.targetRadius < 0.0)
  {
    r.fail("task.target.radius", "must not be negative");
  }
  return s;
}

ScenarioDescription applyScenarioSettings(const ScenarioDescription& base,
  const std::string& text,
  const std::string& source)
{
  Json root;
  try
  {
    root = Json::parse(text);
  }
  catch (const Json::parse_error& e)
  {
    throw InvalidInputError("settings '" + source + "': not JSON (" + e.what() + ")");
  }
  const ScenarioReader r(root, source);
  if (!root.is_object())
  {
    r.fail("(top)", "must be a JSON object");
  }
  ScenarioDescription s = base;
  readSettings(r, s);
  return s;
}

ScenarioDescription readScenario(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throw FileError(path, "cannot be opened for reading");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parseScenario(text.str(), path);
}

SceneRecording readSceneRecording(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throw FileError(path, "cannot be opened for reading");
  }
  Json root;
  try
  {
    root = Json::parse(in);
  }
  catch (const Json::parse_error& e)
  {
    throw InvalidInputError("recording '" + path + "': not JSON (" + e.what() + ")");
  }
  const auto fail = [&](const std::string& key, const std::string& problem)
  { throw InvalidInputError("recording '" + path + "': key '" + key + "': " + problem); };
  if (!root.is_object() || !root.contains("version") || root["version"] != 1)
  {
    fail("version", "must be 1");
  }
  SceneRecording r;
  if (!root.contains("scenario") || !root["scenario"].is_string())
  {
    fail("scenario", "must name the scenario file");
  }
  const std::filesystem::path scenario = root["scenario"].get<std::string>();
  r.scenario =
    scenario.is_absolute()
      ? scenario.string()
      : (std::filesystem::path(path).parent_path() / scenario).lexically_normal().string();
  if (root.contains("seed") && !root["seed"].is_number_unsigned())
  {
    fail("seed", "must be a non-negative integer");
  }
  r.seed = root.value("seed", 0u);
  for (const char* key : { "scope", "instrument" })
  {
    if (!root.contains(key) || !root[key].is_object())
    {
      fail(key, "must be a trajectory object");
    }
  }
  r.scope = parseHapticTrajectory(root["scope"].dump(), "recording '" + path + "', key 'scope'");
  r.instrument =
    parseHapticTrajectory(root["instrument"].dump(), "recording '" + path + "', key 'instrument'");
  return r;
}

void writeSceneRecording(const std::string& path, const SceneRecording& recording)
{
  const Json root = { { "version", 1 },
    { "scenario", recording.scenario },
    { "seed", recording.seed },
    { "scope", Json::parse(hapticTrajectoryText(recording.scope)) },
    { "instrument", Json::parse(hapticTrajectoryText(recording.instrument)) } };
  writeFileAtomically(path, [&](std::ostream& out) { out << root.dump(1) << "\n"; });
}

} // namespace thintissue
