// Suite "simulator": the training scene in lock-step on each shipped
// scenario with its recording (physics step median and 99th percentile,
// bites and cuts included; thesis 6.4: 6.5 ms, 162 FPS for the meniscus
// examination; target 1 ms), the slowest step with a cut, and the replay
// speed with rendering off (target: at least 10 times real time); and the
// GUI thread's frame rate at 1280x720 on this machine's OpenGL (Mesa's
// software llvmpipe under Xvfb) while the servo and physics threads run the
// meniscus examination in real time (needs a display: under xvfb-run).
#include "BenchmarkRegistry.h"

#include "RealTimeLoop.h"
#include "ScriptedHapticDevice.h"
#include "SimulatorView.h"
#include "TrainingScene.h"

#include <vtkNew.h>
#include <vtkRenderWindow.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>

namespace
{
using namespace thintissue;
using namespace thintissue::bench;

/// The steps with a cut (a punch bite, a shaving pass, a scalpel stroke):
/// their medians, whole and by stage (TrainingScene::lastCutTimes; issue
/// 18's targets: a bite at most 2 ms, a shaving pass at most 0.5 ms).
struct CutSteps
{
  int count = 0;
  std::vector<double> whole, collision, simulation, embedding, visual, visualEmbedding, removal,
    operation, scene, physics, visualAside, visualWait, rest;

  void add(const TrainingScene& scene, double seconds)
  {
    count = scene.metrics().operations;
    const CutStepTimes& t = scene.lastCutTimes();
    whole.push_back(seconds * 1e3);
    collision.push_back(t.cutter.collisionMilliseconds);
    simulation.push_back(t.cutter.simulationMilliseconds);
    embedding.push_back(t.cutter.embeddingMilliseconds);
    visual.push_back(t.cutter.visualMilliseconds);
    visualEmbedding.push_back(t.cutter.visualEmbeddingMilliseconds);
    removal.push_back(t.cutter.removalMilliseconds);
    operation.push_back(t.operation);
    this->scene.push_back(t.scene);
    physics.push_back(t.physics);
    visualAside.push_back(t.visualAside);
    visualWait.push_back(t.visualWait);
    // Wrinkles, metrics, the servo's ticks (the contacts and FEM step ran
    // beside the visual half: only the wait for it counts).
    rest.push_back(
      seconds * 1e3 - t.cutterOnStep - t.operation - t.scene - t.visualAside - t.visualWait);
  }

  void report(const std::string& name, BenchmarkReporter& reporter) const
  {
    if (whole.empty())
      return;
    const std::pair<const char*, const std::vector<double>*> stages[] = {
      { "step with a cut", &whole },
      { "cut stage: collision cut", &collision },
      { "cut stage: hexahedra and solver update", &simulation },
      { "cut stage: embeddings", &embedding },
      { "cut stage: visual cut and cut surface", &visual },
      { "cut stage: visual re-embedding", &visualEmbedding },
      { "cut stage: piece removal", &removal },
      { "operation around the cut (blade, piece volumes)", &operation },
      { "scene after the cut (collision mesh, metrics, rim)", &scene },
      { "contacts and FEM step after the cut (on a worker)", &physics },
      { "visual half beside the contacts and FEM step (visual cut, re-embedding, pieces, "
        "wrinkles)",
        &visualAside },
      { "wait for the contacts and FEM step after the visual half", &visualWait },
      { "rest of the step (wrinkles, metrics, servo)", &rest },
    };
    for (const auto& [metric, values] : stages)
      reporter.report(name, std::string(metric) + ", median", percentile(*values, 0.5), "ms");
  }
};

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
  CutSteps cuts;
  int searches = 0;
  const auto start = std::chrono::steady_clock::now();
  while (scene.time() + 0.5 * scenario.timeStep < duration)
  {
    const int version = scene.topologyVersion();
    const auto before = std::chrono::steady_clock::now();
    scene.step();
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
    steps.push_back(seconds);
    searches += scene.contacts().statistics().candidateSearches;
    if (scene.topologyVersion() != version && scene.metrics().operations != cuts.count)
    {
      slowestCut = std::max(slowestCut, seconds);
      cuts.add(scene, seconds);
    }
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
    cuts.report(name, reporter);
  }
  reporter.report(name, "replay speed, rendering off", duration / wall, "x real time");
  // The steps that pay a whole factorization (the first, after each cut,
  // and when the stale factor stopped converging): they set the 99th
  // percentile at these sizes.
  reporter.report(name,
    "factorizations inside steps per 1,000 steps",
    1e3 * scene.solver().synchronousFactorizationCount() / std::max<std::size_t>(1, steps.size()),
    "factorizations");
  // Temporal coherence (CollisionSceneParameters::candidateMarginPerRadius):
  // how often the tissue moved beyond the margin or was cut (not reported
  // without obstacles: none).
  if (searches > 0)
    reporter.report(name,
      "obstacle candidate searches per 100 steps",
      100.0 * searches / std::max<std::size_t>(1, steps.size()),
      "searches");
}

/// The simulator window's drawing (arthroscope view and overview) at
/// 1280x720 on the GUI thread, the scene on its physics and servo threads.
void frameRate(const std::string& recordingPath,
  int multiSamples,
  const BenchmarkContext& context,
  BenchmarkReporter& reporter)
{
  if (std::getenv("DISPLAY") == nullptr)
  {
    std::cerr << "bench simulator: the GUI frame rate needs a display (run under xvfb-run); "
                 "not measured\n";
    return;
  }
  const SceneRecording recording = readSceneRecording(recordingPath);
  const ScenarioDescription scenario = readScenario(recording.scenario);
  ScriptedHapticDevice scope(recording.scope);
  ScriptedHapticDevice instrument(recording.instrument);
  TrainingScene scene(scenario, scope, instrument);
  SimulatorView view(scene);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(1280, 720);
  window->SetNumberOfLayers(2);
  window->SetMultiSamples(multiSamples);
  view.renderer()->SetUseFXAA(multiSamples == 0); // as the window draws it
  window->AddRenderer(view.renderer());
  vtkRenderer* overview = view.overview();
  overview->SetViewport(0.74, 0.0, 1.0, 0.34);
  overview->SetLayer(1);
  window->AddRenderer(overview);
  RealTimeLoopSettings settings;
  settings.endTime = context.quick ? 0.5 : scenario.duration;
  RealTimeLoop loop(scene, settings);
  loop.start();
  std::vector<double> frames;
  const auto start = std::chrono::steady_clock::now();
  while (!loop.finished())
  {
    const auto before = std::chrono::steady_clock::now();
    view.update(loop.latest());
    window->Render();
    frames.push_back(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count());
  }
  const double wall =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double sceneTime = loop.latest().time;
  loop.stop();
  const std::string name = scenario.name + ", 1280x720, " +
                           (multiSamples == 0 ? std::string("FXAA (the window's)")
                                              : std::to_string(multiSamples) + "x multisampling") +
                           ", servo + physics threads running";
  reporter.report(name, "GUI frame rate", frames.size() / wall, "frames/s", 162.0);
  reporter.report(name, "GUI frame median", percentile(frames, 0.5) * 1e3, "ms");
  reporter.report(name, "GUI frame 99th percentile", percentile(frames, 0.99) * 1e3, "ms");
  // Whether physics kept real time beside the drawing (1: it did).
  reporter.report(name, "physics time per wall time", sceneTime / wall, "x real time");
}

} // namespace

THINTISSUE_BENCHMARK_SUITE(simulatorSuite,
  "simulator",
  "training scene in lock-step: physics step per scenario, replay speed; GUI frame rate "
  "at 1280x720 with the physics and servo threads running (needs a display)")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const std::string recordings = std::string(THINTISSUE_DATA_DIR) + "/Recordings/";
  // THINTISSUE_BENCH_RECORDINGS=name,name,...: only those (a profiler's run).
  const char* only = std::getenv("THINTISSUE_BENCH_RECORDINGS");
  const std::string chosen = only ? "," + std::string(only) + "," : std::string();
  for (const char* name : { "meniscus-examination",
         "meniscectomy-punch",
         "shaver-removal",
         "contouring",
         "sheet-cutting",
         "ligament-firmness",
         "pcl-firmness",
         "cartilage-palpation" })
  {
    if (chosen.empty() || chosen.find("," + std::string(name) + ",") != std::string::npos)
      replayScenario(recordings + name + ".json", context, reporter);
  }
  if (!chosen.empty())
    return;
  // The window's anti-aliasing, and the multisampling it replaced (costly
  // on a software renderer).
  frameRate(recordings + "meniscus-examination.json", 0, context, reporter);
  frameRate(recordings + "meniscus-examination.json", 8, context, reporter);
}
