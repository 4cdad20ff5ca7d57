// Suite "simulator": the training scene in lock-step on its shipped
// scenarios (physics step median and 99th percentile; thesis 6.4: 6.5 ms,
// 162 FPS for the meniscus examination) and the replay speed with rendering
// off (target: at least 10 times real time).
#include "BenchmarkRegistry.h"

#include "ScriptedHapticDevice.h"
#include "TrainingScene.h"

#include <algorithm>
#include <chrono>

namespace
{
using namespace thintissue;
using namespace thintissue::bench;

} // namespace

THINTISSUE_BENCHMARK_SUITE(simulatorSuite,
  "simulator",
  "training scene in lock-step: physics step per scenario, replay speed")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const std::string recordingPath =
    std::string(THINTISSUE_DATA_DIR) + "/Recordings/meniscus-examination.json";
  const SceneRecording recording = readSceneRecording(recordingPath);
  const ScenarioDescription scenario = readScenario(recording.scenario);
  ScriptedHapticDevice scope(recording.scope);
  ScriptedHapticDevice instrument(recording.instrument);
  TrainingScene scene(scenario, scope, instrument);
  const double duration = context.quick ? 1.0 : scenario.duration;
  std::vector<double> steps;
  const auto start = std::chrono::steady_clock::now();
  while (scene.time() + 0.5 * scenario.timeStep < duration)
  {
    const auto before = std::chrono::steady_clock::now();
    scene.step();
    steps.push_back(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count());
  }
  const double wall =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string name =
    scenario.name + ", " + std::to_string(scene.tissue().visual.triangleCount()) +
    " visual triangles, " + std::to_string(scene.tissue().simulation.hexahedronCount()) +
    " hexahedra";
  reporter.report(name, "physics step median", percentile(steps, 0.5) * 1e3, "ms", 6.5);
  reporter.report(name, "physics step 99th percentile", percentile(steps, 0.99) * 1e3, "ms");
  reporter.report(name, "replay speed, rendering off", duration / wall, "x real time");
}
