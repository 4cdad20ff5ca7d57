// Suite "simulator": the training scene in lock-step on each shipped
// scenario with its recording (physics step median and 99th percentile,
// bites and cuts included; thesis 6.4: 6.5 ms, 162 FPS for the meniscus
// examination; target 1 ms), the slowest step with a cut, and the replay
// speed with rendering off (target: at least 10 times real time).
#include "BenchmarkRegistry.h"

#include "ScriptedHapticDevice.h"
#include "TrainingScene.h"

#include <algorithm>
#include <chrono>

namespace
{
using namespace thintissue;
using namespace thintissue::bench;

/// Replays one shipped recording (its own scenario) and reports.
void replayScenario(const std::string& recordingPath,
  const BenchmarkContext& context,
  BenchmarkReporter& reporter)
{
  const SceneRecording recording = readSceneRecording(recordingPath);
  const ScenarioDescription scenario = readScenario(recording.scenario);
  ScriptedHapticDevice scope(recording.scope);
  ScriptedHapticDevice instrument(recording.instrument);
  TrainingScene scene(scenario, scope, instrument);
  const double duration = context.quick ? std::min(1.0, scenario.duration) : scenario.duration;
  std::vector<double> steps;
  double slowestCut = 0.0;
  const auto start = std::chrono::steady_clock::now();
  while (scene.time() + 0.5 * scenario.timeStep < duration)
  {
    const int version = scene.topologyVersion();
    const auto before = std::chrono::steady_clock::now();
    scene.step();
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
    steps.push_back(seconds);
    if (scene.topologyVersion() != version)
      slowestCut = std::max(slowestCut, seconds);
  }
  const double wall =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string name =
    scenario.name + ", " + std::to_string(scene.tissue().visual.triangleCount()) +
    " visual triangles, " + std::to_string(scene.tissue().simulation.hexahedronCount()) +
    " hexahedra";
  reporter.report(name, "physics step median", percentile(steps, 0.5) * 1e3, "ms", 6.5);
  reporter.report(name, "physics step 99th percentile", percentile(steps, 0.99) * 1e3, "ms");
  if (scene.cutter() && scene.metrics().operations > 0) // (a quick run may end before one)
  {
    reporter.report(name, "slowest step with a cut", slowestCut * 1e3, "ms");
    reporter.report(name, "operations", scene.metrics().operations, "cuts");
  }
  reporter.report(name, "replay speed, rendering off", duration / wall, "x real time");
}

} // namespace

THINTISSUE_BENCHMARK_SUITE(simulatorSuite,
  "simulator",
  "training scene in lock-step: physics step per scenario, replay speed")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const std::string recordings = std::string(THINTISSUE_DATA_DIR) + "/Recordings/";
  for (const char* name : { "meniscus-examination",
         "meniscectomy-punch",
         "shaver-removal",
         "sheet-cutting",
         "ligament-firmness",
         "pcl-firmness",
         "cartilage-palpation" })
  {
    replayScenario(recordings + name + ".json", context, reporter);
  }
}
