// Writes a recording from key frames given in the scene's own terms: where
// a point of the instrument (its tip, the punch's bite or the middle of a
// blade's edge) or the arthroscope's tip should be, the world direction its
// working side ("up") faces, and the buttons. The styluses' positions and
// orientations follow through each portal's mapping (PortalMapping.h), so a
// recording stays right when a portal moves. Usage:
//   ThinTissueMakeRecording SCRIPT.json OUTPUT.json
// SCRIPT: {"scenario": path as written in the recording (relative to
// OUTPUT's directory), "scope": [frames], "instrument": [frames]}; a frame:
// {"t": s, "target": [x, y, z], "up": [x, y, z], "point": "tip" | "bite" |
// "edge", "buttons": n}.
#include "PortalMapping.h"
#include "TrainingScene.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>

using namespace thintissue;
using Json = nlohmann::json;

namespace
{

Vector3 vectorOf(const Json& j)
{
  return Vector3(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>());
}

Vector3 toolPoint(const SurgicalInstrumentModel& model, const std::string& point)
{
  const auto middle = [](const std::vector<Vector3>& points)
  {
    Vector3 sum = Vector3::Zero();
    for (const Vector3& p : points)
      sum += p;
    return Vector3(sum / static_cast<double>(points.size()));
  };
  if (point == "bite" && !model.biteOutline.empty())
    return middle(model.biteOutline);
  if (point == "edge" && !model.cuttingEdge.empty())
    return 0.5 * (model.cuttingEdge.front() + model.cuttingEdge.back());
  if (point != "tip")
    throw InvalidInputError("point '" + point + "' is not one of " + model.name);
  return Vector3::Zero();
}

/// The stylus sample putting tool point `local` at `target` with the
/// working side toward `up`.
HapticSample sampleFor(const PortalMapping& mapping, const Vector3& local, const Json& frame)
{
  HapticSample sample;
  sample.time = frame.at("t").get<double>();
  sample.buttons = frame.value("buttons", 0u);
  const Vector3 up = frame.contains("up") ? vectorOf(frame["up"]) : Vector3::UnitZ();
  // The stylus's working axis turned onto `up` (device frame = world here).
  sample.orientation =
    Eigen::Quaterniond::FromTwoVectors(mapping.settings().stylusUp, up.normalized());
  sample.position = mapping.stylusPositionPlacing(
    local, vectorOf(frame.at("target")), sample.orientation.toRotationMatrix());
  return sample;
}

HapticTrajectory trajectoryOf(const Json& frames,
  const PortalDescription& portal,
  const Vector3& local,
  const std::string& name)
{
  PortalSettings settings;
  settings.portal = portal.portal;
  settings.inward = portal.inward;
  const PortalMapping mapping(settings);
  HapticTrajectory trajectory;
  trajectory.name = name;
  for (const Json& frame : frames)
  {
    trajectory.samples.push_back(sampleFor(mapping, local, frame));
  }
  return trajectory;
}

} // namespace

int main(int argc, char** argv)
{
  if (argc != 3)
  {
    std::cerr << "usage: ThinTissueMakeRecording SCRIPT.json OUTPUT.json\n";
    return 2;
  }
  try
  {
    std::ifstream in(argv[1]);
    const Json script = Json::parse(in);
    SceneRecording recording;
    recording.scenario = script.at("scenario").get<std::string>();
    const std::filesystem::path outputDirectory = std::filesystem::absolute(argv[2]).parent_path();
    const ScenarioDescription scenario =
      readScenario((outputDirectory / recording.scenario).lexically_normal().string());
    const SurgicalInstrumentModel instrument = makeSurgicalInstrument(scenario.instrument);
    const std::string point = script.value("point", std::string("tip"));
    recording.scope =
      trajectoryOf(script.at("scope"), scenario.scopePortal, Vector3::Zero(), "arthroscope");
    recording.instrument = trajectoryOf(script.at("instrument"),
      scenario.instrumentPortal,
      toolPoint(instrument, point),
      "instrument");
    writeSceneRecording(argv[2], recording);
    std::cout << "recording written to " << argv[2] << "\n";
  }
  catch (const std::exception& e)
  {
    std::cerr << "ThinTissueMakeRecording: " << argv[1] << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}
