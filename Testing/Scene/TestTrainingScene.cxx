// The training scene in lock-step: the shipped meniscus examination replayed
// from its recording (the hook presses the inner border onto the plateau and
// lets go: wrinkles), deterministic bit for bit, with metrics; scenario and
// recording files validated with the file and the key named.
#include "MeshImport.h"
#include "MouseHapticDevice.h"
#include "ScriptedHapticDevice.h"
#include "ThinSheetModel.h"
#include "ThinTissueError.h"
#include "ThinTissueTestSupport.h"
#include "TissueBundle.h"
#include "TrainingScene.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

using namespace thintissue;

namespace
{

const std::string Data = THINTISSUE_SOURCE_DATA;

/// A shipped recording with its scenario, ready to replay (the meniscus
/// examination unless named).
struct Replay
{
  explicit Replay(const std::string& name = "meniscus-examination.json")
    : recording(readSceneRecording(Data + "/Recordings/" + name))
  {
  }
  SceneRecording recording;
  ScenarioDescription scenario = readScenario(recording.scenario);
  ScriptedHapticDevice scope{ recording.scope };
  ScriptedHapticDevice instrument{ recording.instrument };
  TrainingScene scene{ scenario, scope, instrument };
};

std::string messageOf(const std::string& json)
{
  try
  {
    parseScenario(json, "bad.json");
  }
  catch (const InvalidInputError& e)
  {
    return e.what();
  }
  return "";
}

} // namespace

TEST(TrainingScene, TheShippedExaminationPressesAndWrinklesTheMeniscus)
{
  Replay run;
  EXPECT_EQ(run.scenario.name, "Meniscus examination");
  ASSERT_TRUE(run.scene.runTo(run.scenario.duration)) << run.scene.lastError();
  const SceneMetrics& m = run.scene.metrics();
  EXPECT_NEAR(m.time, run.scenario.duration, 1e-9);
  EXPECT_GT(m.instrumentPathLength, 10.0);
  EXPECT_GT(m.cameraPathLength, 0.5);
  EXPECT_GT(m.peakForce, 0.0);
  EXPECT_GT(m.wrinklingSteps, 0);
  EXPECT_EQ(run.scene.visualPositions().size(), run.scene.tissue().visual.vertexCount());
  std::cout << run.scene.metricsJson() << "\n";
}

TEST(TrainingScene, ReplaysAreBitForBit)
{
  Replay a, b;
  for (const double t : { 1.0, 2.6, 3.0 })
  {
    ASSERT_TRUE(a.scene.runTo(t));
    ASSERT_TRUE(b.scene.runTo(t));
    EXPECT_EQ(a.scene.visualPositions(), b.scene.visualPositions()) << "at " << t << " s";
    EXPECT_EQ(a.scene.instrumentPose().translation, b.scene.instrumentPose().translation);
  }
  // A recording written and read back replays the same.
  const std::string path = (thintissue::testing::temporaryDirectory() / "replay.json").string();
  SceneRecording copy = a.recording;
  copy.scenario = Data + "/Scenarios/meniscus-examination.json";
  writeSceneRecording(path, copy);
  const SceneRecording back = readSceneRecording(path);
  ASSERT_EQ(back.instrument.samples.size(), a.recording.instrument.samples.size());
  for (std::size_t k = 0; k < back.instrument.samples.size(); ++k)
  {
    EXPECT_TRUE(back.instrument.samples[k] == a.recording.instrument.samples[k]) << k;
  }
}

TEST(TrainingScene, BadScenariosNameTheFileAndTheKey)
{
  const std::string good =
    R"({"version": 1, "tissue": {"model": "meniscus", "material": {"youngModulus": 150}}})";
  EXPECT_EQ(messageOf(good), "");
  EXPECT_NE(messageOf(R"({"version": 2})").find("key 'version'"), std::string::npos);
  const std::string negative =
    messageOf(R"({"version": 1, "tissue": {"material": {"youngModulus": -3}}})");
  EXPECT_NE(
    negative.find("scenario 'bad.json': key 'tissue.material.youngModulus'"), std::string::npos)
    << negative;
  const std::string tear = messageOf(R"({"version": 1, "tissue": {"tear": "zigzag"}})");
  EXPECT_NE(tear.find("key 'tissue.tear'"), std::string::npos) << tear;
  const std::string tool = messageOf(R"({"version": 1, "instrument": {"type": "spoon"}})");
  EXPECT_NE(tool.find("key 'instrument.type'"), std::string::npos) << tool;
  const std::string inward = messageOf(R"({"version": 1, "arthroscope": {"inward": [0, 0, 0]}})");
  EXPECT_NE(inward.find("key 'arthroscope.inward'"), std::string::npos) << inward;
  EXPECT_NE(messageOf("{not json").find("not JSON"), std::string::npos);
  // Tissue sources: a model by name, a file or bundle with its path, the
  // nodes held still, wrinkles only where monitor data exist.
  const std::string model = messageOf(R"({"version": 1, "tissue": {"model": "kidney"}})");
  EXPECT_NE(model.find("key 'tissue.model'"), std::string::npos) << model;
  EXPECT_NE(model.find("posterior_cruciate_ligament"), std::string::npos) << model;
  const std::string file = messageOf(R"({"version": 1, "tissue": {"model": "bundle"}})");
  EXPECT_NE(file.find("key 'tissue.file'"), std::string::npos) << file;
  const std::string fixed =
    messageOf(R"({"version": 1, "tissue": {"model": "sheet", "fixed": "glued"}})");
  EXPECT_NE(fixed.find("key 'tissue.fixed'"), std::string::npos) << fixed;
  const std::string target =
    messageOf(R"({"version": 1, "task": {"target": {"centre": [0, 0, 0], "radius": -1}}})");
  EXPECT_NE(target.find("key 'task.target.radius'"), std::string::npos) << target;
  const std::string wrinkles =
    messageOf(R"({"version": 1, "tissue": {"model": "sheet", "wrinkles": true}})");
  EXPECT_NE(wrinkles.find("key 'tissue.wrinkles'"), std::string::npos) << wrinkles;
  const std::string thickness =
    messageOf(R"({"version": 1, "tissue": {"model": "file", "file": "a.obj", "thickness": -2}})");
  EXPECT_NE(thickness.find("key 'tissue.thickness'"), std::string::npos) << thickness;
  EXPECT_THROW(readScenario(Data + "/Scenarios/no-such-scenario.json"), FileError);
  const std::string path =
    (thintissue::testing::temporaryDirectory() / "bad-recording.json").string();
  std::ofstream(path) << R"({"version": 1, "scenario": "x.json", "scope": {}, "instrument": {}})";
  try
  {
    readSceneRecording(path);
    FAIL();
  }
  catch (const InvalidInputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("key 'scope'"), std::string::npos) << e.what();
  }
}

TEST(TrainingScene, EveryShippedTornMeniscusExaminationRunsAndWrinkles)
{
  const SceneRecording recording =
    readSceneRecording(Data + "/Recordings/meniscus-examination.json");
  for (const char* tear : { "longitudinal", "radial", "flap", "horizontal-cleavage" })
  {
    SCOPED_TRACE(tear);
    const ScenarioDescription scenario =
      readScenario(Data + "/Scenarios/meniscus-examination-" + std::string(tear) + ".json");
    EXPECT_EQ(scenario.tear, meniscusTearTypeFromName(tear));
    ScriptedHapticDevice scope(recording.scope);
    ScriptedHapticDevice instrument(recording.instrument);
    TrainingScene scene(scenario, scope, instrument);
    ASSERT_TRUE(scene.runTo(scenario.duration)) << scene.lastError();
    EXPECT_GT(scene.metrics().peakForce, 0.0);
    EXPECT_GT(scene.metrics().wrinklingSteps, 0);
  }
}

TEST(TrainingScene, ARunRecordedFromLiveDevicesReplaysBitForBit)
{
  // Live devices (the mouse's, set between steps as a GUI would) recorded,
  // then the recording replayed: the same meshes.
  const ScenarioDescription scenario = readScenario(Data + "/Scenarios/meniscus-examination.json");
  MouseHapticDevice scopeMouse, instrumentMouse;
  RecordingHapticDevice scope(scopeMouse, 10000), instrument(instrumentMouse, 10000);
  TrainingScene live(scenario, scope, instrument);
  HapticDeviceState stylus;
  for (int k = 0; k < 600; ++k)
  {
    stylus.position = Vector3(0.01 * k, -0.004 * k, -0.02 * k);
    stylus.orientation =
      Eigen::AngleAxisd(0.003 * k, Vector3(0.2, 0.1, 1.0).normalized()).toRotationMatrix();
    stylus.buttons = k > 300 ? 1u : 0u;
    instrumentMouse.setState(stylus);
    ASSERT_TRUE(live.step());
  }
  SceneRecording recording;
  recording.scenario = scenario.source;
  recording.scope = scope.trajectory();
  recording.instrument = instrument.trajectory();
  const std::string path = (thintissue::testing::temporaryDirectory() / "live.json").string();
  writeSceneRecording(path, recording);
  const SceneRecording back = readSceneRecording(path);
  ScriptedHapticDevice scopeReplay(back.scope), instrumentReplay(back.instrument);
  TrainingScene replay(readScenario(back.scenario), scopeReplay, instrumentReplay);
  ASSERT_TRUE(replay.runTo(live.time()));
  EXPECT_EQ(replay.instrumentPose().translation, live.instrumentPose().translation);
  EXPECT_EQ(replay.instrumentPose().rotation, live.instrumentPose().rotation);
  EXPECT_EQ(replay.visualPositions(), live.visualPositions());
  EXPECT_GT(live.metrics().instrumentPathLength, 1.0);
}

namespace
{

struct PunchReplay : Replay
{
  PunchReplay()
    : Replay("meniscectomy-punch.json")
  {
  }
};

} // namespace

// The partial meniscectomy (thesis 6.4.2): five bites of the punch along the
// bucket-handle fragment's inner border, each when the first button closes
// the jaws; the bitten pieces go, and a replay gives the same meshes.
TEST(TrainingScene, ThePunchScenarioBitesTissueAwayAndReplaysBitForBit)
{
  PunchReplay a;
  ASSERT_NE(a.scene.cutter(), nullptr);
  EXPECT_EQ(a.scene.topologyVersion(), 0);
  const std::size_t before = a.scene.cutter()->activeTriangleCount();
  ASSERT_TRUE(a.scene.runTo(1.6)) << a.scene.lastError();
  EXPECT_EQ(a.scene.metrics().operations, 0) << "a bite before the jaws closed";
  EXPECT_EQ(a.scene.lastCutTimes().cutter.totalMilliseconds, 0.0);
  // The first bite frees its piece (it did not while the recording held the
  // fixed jaw above the border: the tilted jaws missed the tissue under the
  // bite's proximal end, and the loop stayed open).
  ASSERT_TRUE(a.scene.runTo(2.15)) << a.scene.lastError();
  EXPECT_EQ(a.scene.metrics().operations, 1);
  EXPECT_GT(a.scene.metrics().removedVolume, 3.0);
  // The bite's times, for the benchmark: its cut and the removal of its piece.
  const CutStepTimes& bite = a.scene.lastCutTimes();
  EXPECT_GT(bite.cutter.totalMilliseconds, 0.0);
  EXPECT_GT(bite.cutter.removalMilliseconds, 0.0);
  EXPECT_GE(bite.cutter.totalMilliseconds, bite.cutter.visualMilliseconds);
  EXPECT_GT(bite.scene, 0.0);
  ASSERT_TRUE(a.scene.runTo(a.scenario.duration)) << a.scene.lastError();
  const SceneMetrics& m = a.scene.metrics();
  EXPECT_EQ(m.operations, 5);
  EXPECT_EQ(a.scene.topologyVersion(), m.operations);
  EXPECT_GT(m.removedVolume, 5.0); // mm^3: pieces went
  // The bites lie in the task's target region (the torn fragment).
  EXPECT_GT(a.scenario.targetRadius, 0.0);
  EXPECT_NEAR(m.removedInTarget + m.removedOutsideTarget, m.removedVolume, 1e-9);
  EXPECT_GT(m.removedInTarget, 0.9 * m.removedVolume);
  EXPECT_NE(a.scene.cutter()->activeTriangleCount(), before);
  // Every visual vertex has a position; the drawn triangles exclude the
  // removed pieces'.
  EXPECT_EQ(a.scene.visualPositions().size(), a.scene.visualMesh().vertexCount());
  const std::vector<char> shown = a.scene.activeVisualTriangles();
  EXPECT_LT(std::count(shown.begin(), shown.end(), 1), static_cast<long>(shown.size()));
  for (const Vector3& x : a.scene.visualPositions())
  {
    ASSERT_TRUE(x.allFinite());
  }
  // A bite's visual half runs beside the contacts and the FEM step; on one
  // thread it runs when the step waits for it, after them: the same bits.
  PunchReplay b;
  bool replayed = false;
  tbb::task_arena(1).execute([&] { replayed = b.scene.runTo(a.scenario.duration); });
  ASSERT_TRUE(replayed) << b.scene.lastError();
  EXPECT_EQ(b.scene.metrics().operations, m.operations);
  EXPECT_EQ(a.scene.visualMesh().positions, b.scene.visualMesh().positions);
  EXPECT_EQ(a.scene.visualMesh().triangles, b.scene.visualMesh().triangles);
  EXPECT_EQ(a.scene.visualPositions(), b.scene.visualPositions());
  EXPECT_EQ(a.scene.metrics().removedVolume, b.scene.metrics().removedVolume);
  EXPECT_EQ(a.scene.metrics().removedInTarget, b.scene.metrics().removedInTarget);
}

// Piecewise removal (6.4.3): each shaving pass's visual half (the opening,
// its cut surface, the pieces) runs beside the physics step; on one thread
// it runs before the step's physics instead: the same bits.
TEST(TrainingScene, ShavingReplaysBitForBitWhateverRunsBesideThePhysics)
{
  Replay a("shaver-removal.json");
  ASSERT_TRUE(a.scene.runTo(a.scenario.duration)) << a.scene.lastError();
  EXPECT_GT(a.scene.metrics().operations, 2);
  EXPECT_GT(a.scene.metrics().removedVolume, 0.0);
  Replay b("shaver-removal.json");
  bool replayed = false;
  tbb::task_arena(1).execute([&] { replayed = b.scene.runTo(b.scenario.duration); });
  ASSERT_TRUE(replayed) << b.scene.lastError();
  EXPECT_EQ(a.scene.metrics().operations, b.scene.metrics().operations);
  EXPECT_EQ(a.scene.visualMesh().positions, b.scene.visualMesh().positions);
  EXPECT_EQ(a.scene.visualMesh().triangles, b.scene.visualMesh().triangles);
  EXPECT_EQ(a.scene.activeVisualTriangles(), b.scene.activeVisualTriangles());
  EXPECT_EQ(a.scene.visualPositions(), b.scene.visualPositions());
  EXPECT_EQ(a.scene.metrics().removedVolume, b.scene.metrics().removedVolume);
}

// Sheet cutting (thesis 5.3, fig. 5-19): the knife drawn across the sheet
// (held at its left and right edges) a little each step cuts it in two;
// the far half pressed down moves, the near half stays where it was.
TEST(TrainingScene, TheKnifeCutsTheSheetInTwoAndTheHalvesMoveApart)
{
  const SceneRecording recording = readSceneRecording(Data + "/Recordings/sheet-cutting.json");
  const ScenarioDescription scenario = readScenario(recording.scenario);
  EXPECT_FALSE(scenario.knee);
  ScriptedHapticDevice scope(recording.scope), instrument(recording.instrument);
  TrainingScene scene(scenario, scope, instrument);
  ASSERT_TRUE(scene.runTo(scenario.duration)) << scene.lastError();
  EXPECT_GT(scene.metrics().operations, 2);
  const std::vector<Vector3>& now = scene.visualPositions();
  const std::vector<Vector3>& rest = scene.visualMesh().positions;
  double near = 0.0, far = 0.0;
  for (std::size_t i = 0; i < now.size(); ++i)
  {
    const double moved = (now[i] - rest[i]).norm();
    (rest[i].x() < 0.0 ? near : far) = std::max(rest[i].x() < 0.0 ? near : far, moved);
  }
  EXPECT_GT(far, 3.0);   // mm: pressed down
  EXPECT_LT(near, 1e-6); // cut free of it
}

// Every shipped recording (Data/Recordings, not the key-frame scripts)
// replays its scenario to the end: no solver failure, every visual vertex
// finite, the instrument moved.
TEST(TrainingScene, EveryShippedRecordingReplaysToTheEnd)
{
  int replayed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(Data + "/Recordings"))
  {
    const std::string path = entry.path().string();
    if (entry.path().extension() != ".json" || path.find(".script.") != std::string::npos)
      continue;
    const SceneRecording recording = readSceneRecording(path);
    const ScenarioDescription scenario = readScenario(recording.scenario);
    ScriptedHapticDevice scope(recording.scope), instrument(recording.instrument);
    TrainingScene scene(scenario, scope, instrument);
    ASSERT_TRUE(scene.runTo(scenario.duration)) << path << ": " << scene.lastError();
    EXPECT_GT(scene.metrics().instrumentPathLength, 5.0) << path;
    for (const Vector3& x : scene.visualPositions())
      ASSERT_TRUE(x.allFinite()) << path;
    ++replayed;
  }
  EXPECT_GE(replayed, 5);
}

// The settings the window's panel changes: the wrinkle and cut-surface keys
// read from a file, and the panel's changes validated as a file's are.
TEST(TrainingScene, SettingsAreReadAndValidatedByKey)
{
  const ScenarioDescription s = parseScenario(
    R"({"version": 1, "tissue": {"wrinkle": {"frequency": 9.0, "windowSize": 40}},
        "cutting": {"cutSurfaceRows": 3, "fragmentAreaFraction": 0.01}})",
    "good.json");
  EXPECT_EQ(s.wrinkle.frequency, 9.0);
  EXPECT_EQ(s.wrinkle.windowSize, 40);
  EXPECT_EQ(s.wrinkle.refreshMonitorsPerUpdate, 16); // the scenes' time-sliced default
  EXPECT_EQ(parseScenario(R"({"version": 1, "tissue": {"wrinkle": {"refreshMonitorsPerStep": 0}}})",
              "whole.json")
              .wrinkle.refreshMonitorsPerUpdate,
    0);
  const std::string budget =
    messageOf(R"({"version": 1, "tissue": {"wrinkle": {"refreshMonitorsPerStep": -2}}})");
  EXPECT_NE(budget.find("key 'tissue.wrinkle.refreshMonitorsPerStep'"), std::string::npos)
    << budget;
  EXPECT_EQ(s.cutSurfaceRows, 3);
  EXPECT_EQ(s.fragmentAreaFraction, 0.01);
  const std::string window =
    messageOf(R"({"version": 1, "tissue": {"wrinkle": {"windowSize": 1.5}}})");
  EXPECT_NE(window.find("key 'tissue.wrinkle.windowSize'"), std::string::npos) << window;
  const std::string rows = messageOf(R"({"version": 1, "cutting": {"cutSurfaceRows": -1}})");
  EXPECT_NE(rows.find("key 'cutting.cutSurfaceRows'"), std::string::npos) << rows;
  const std::string frequency =
    messageOf(R"({"version": 1, "tissue": {"wrinkle": {"frequency": 0}}})");
  EXPECT_NE(frequency.find("key 'tissue.wrinkle.frequency'"), std::string::npos) << frequency;
  // The panel: only its keys change; a bad one is refused naming it.
  const ScenarioDescription changed =
    applyScenarioSettings(s, R"({"tissue": {"material": {"youngModulus": 20}}})", "settings");
  EXPECT_EQ(changed.material.youngModulus, 20.0);
  EXPECT_EQ(changed.wrinkle.windowSize, 40);
  EXPECT_EQ(changed.tissueModel, s.tissueModel);
  try
  {
    applyScenarioSettings(s, R"({"tissue": {"material": {"poissonRatio": 0.5}}})", "settings");
    FAIL();
  }
  catch (const InvalidInputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("'settings': key 'tissue.material.poissonRatio'"),
      std::string::npos)
      << e.what();
  }
  // Applied: the wrinkle window reaches the scene's generator.
  Replay run;
  ScenarioDescription narrow = run.scenario;
  narrow.wrinkle.windowSize = 2;
  ScriptedHapticDevice scope(run.recording.scope), instrument(run.recording.instrument);
  TrainingScene narrowScene(narrow, scope, instrument);
  ASSERT_TRUE(narrowScene.runTo(2.65));
  ASSERT_TRUE(run.scene.runTo(2.65));
  EXPECT_NE(narrowScene.visualPositions(), run.scene.visualPositions());
}

// The posterior cruciate ligament behind the anterior one: the hook (its
// working side turned across the shaft, not along it, where the portal
// mapping cannot roll it) reaches the ligament's face and pushes it.
TEST(TrainingScene, TheHookPushesThePosteriorCruciateLigament)
{
  const SceneRecording recording = readSceneRecording(Data + "/Recordings/pcl-firmness.json");
  const ScenarioDescription scenario = readScenario(recording.scenario);
  EXPECT_EQ(scenario.tissueModel, "posterior_cruciate_ligament");
  ScriptedHapticDevice scope(recording.scope), instrument(recording.instrument);
  TrainingScene scene(scenario, scope, instrument);
  const std::vector<Vector3> rest = scene.tissue().visual.positions;
  ASSERT_TRUE(scene.runTo(1.8)) << scene.lastError();
  double pushed = 0.0;
  for (std::size_t i = 0; i < rest.size(); ++i)
    pushed = std::max(pushed, (scene.visualPositions()[i] - rest[i]).norm());
  EXPECT_GT(scene.metrics().peakForce, 1.0);
  EXPECT_GT(pushed, 0.3) << "the ligament should give way under the hook";
  EXPECT_FALSE(scene.contacts().contacts().empty());
  ASSERT_TRUE(scene.runTo(scenario.duration));
  EXPECT_TRUE(scene.contacts().contacts().empty()) << "the hook should have let go";
}

// "Your own tissue": a bundle made by the preparation (here from the thin
// sheet's visual surface alone), named by the shipped scenario, replaying
// the sheet's knife strokes around wherever it lies: it is cut.
TEST(TrainingScene, YourOwnTissueFromABundleIsCut)
{
  ThinSheetParameters sheet;
  sheet.width = 60.0;
  sheet.depth = 60.0;
  TriangleMesh visual = makeThinSheet(sheet).visual;
  for (Vector3& x : visual.positions)
    x += Vector3(100.0, -40.0, 7.0); // anywhere: the portals follow its centre
  TissuePreparationSettings settings;
  settings.units = lengthUnitsNamed("mm");
  const std::string bundle =
    (thintissue::testing::temporaryDirectory() / "own-sheet.ttbundle").string();
  writeTissueBundle(bundle, prepareTissue(visual, settings));

  ScenarioDescription scenario = readScenario(Data + "/Scenarios/your-own-tissue.json");
  EXPECT_TRUE(scenario.portalsFromTissueCentre);
  scenario.tissueFile = bundle;
  const SceneRecording recording = readSceneRecording(Data + "/Recordings/sheet-cutting.json");
  ScriptedHapticDevice scope(recording.scope), instrument(recording.instrument);
  TrainingScene scene(scenario, scope, instrument);
  ASSERT_TRUE(scene.runTo(scenario.duration)) << scene.lastError();
  EXPECT_GT(scene.metrics().operations, 2);
  EXPECT_GT(scene.cutter()->collision().vertexCount(), scene.tissue().collision.vertexCount());

  // The same sheet prepared in metres (as a segmentation comes) is
  // converted to millimetres as it loads, and cuts the same way.
  TriangleMesh inMetres = visual;
  for (Vector3& x : inMetres.positions)
    x *= 0.001;
  settings.units = lengthUnitsNamed("m");
  const std::string metresBundle =
    (thintissue::testing::temporaryDirectory() / "own-sheet-metres.ttbundle").string();
  writeTissueBundle(metresBundle, prepareTissue(inMetres, settings));
  scenario.tissueFile = metresBundle;
  ScriptedHapticDevice scopeAgain(recording.scope), instrumentAgain(recording.instrument);
  TrainingScene converted(scenario, scopeAgain, instrumentAgain);
  EXPECT_NEAR(boundingBoxOf(converted.tissue().collision.positions).sizes().maxCoeff(),
    boundingBoxOf(scene.tissue().collision.positions).sizes().maxCoeff(),
    0.01);
  ASSERT_TRUE(converted.runTo(scenario.duration)) << converted.lastError();
  EXPECT_GT(converted.metrics().operations, 2);

  // A tissue segmented as one open sheet (the sheet's upper face alone, in
  // metres, as a mesh file): refused with the key that helps, then given
  // 2 mm as it loads.
  TriangleMesh face;
  face.name = "upper face";
  std::vector<int> kept(visual.vertexCount(), -1);
  for (const Triangle& t : visual.triangles)
  {
    bool upper = true;
    for (int v : t)
      upper = upper && visual.positions[v].z() > 7.0 + 0.5;
    if (!upper)
      continue;
    Triangle corners;
    for (int k = 0; k < 3; ++k)
    {
      int& index = kept[t[k]];
      if (index < 0)
      {
        index = static_cast<int>(face.positions.size());
        face.positions.push_back(0.001 * visual.positions[t[k]]);
      }
      corners[k] = index;
    }
    face.triangles.push_back(corners);
  }
  const std::string facePath = (thintissue::testing::temporaryDirectory() / "face.obj").string();
  writeObj(face, facePath);
  scenario.tissueModel = "file";
  scenario.tissueFile = facePath;
  scenario.tissueUnits = "m";
  try
  {
    TrainingScene refused(scenario, scope, instrument);
    ADD_FAILURE() << "an open sheet was prepared without a thickness";
  }
  catch (const InvalidInputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("give 'tissue.thickness' in mm"), std::string::npos)
      << e.what();
  }
  scenario.tissueThickness = 2.0;
  ScriptedHapticDevice scopeThick(recording.scope), instrumentThick(recording.instrument);
  TrainingScene thick(scenario, scopeThick, instrumentThick);
  const Vector3 size = boundingBoxOf(thick.tissue().visual.positions).sizes();
  EXPECT_NEAR(size.z(), 2.0, 0.05); // a 2 mm slab round the face, in mm
  EXPECT_GT(size.maxCoeff(), 55.0);
  scenario.tissueModel = "bundle";
  scenario.tissueThickness = 0.0;

  // A bundle that is not there is refused (the scenario and key named).
  scenario.tissueFile = Data + "/Scenarios/no-such.ttbundle";
  EXPECT_THROW(TrainingScene(scenario, scope, instrument), InvalidInputError);
}

// Contouring of the rim (thesis 6.4.4, fig. 6-15): the scenario bites the
// inner border four times as it loads (jagged cut surface); the shaver in
// contouring mode drawn along the bitten rim evens it out pass by pass,
// removes nothing, and the metrics give the roughness before and after.
TEST(TrainingScene, TheContouringScenarioSmoothsTheBittenRimAndRemovesNothing)
{
  const SceneRecording recording = readSceneRecording(Data + "/Recordings/contouring.json");
  const ScenarioDescription scenario = readScenario(recording.scenario);
  EXPECT_EQ(scenario.shaverMode, ShaverMode::Contour);
  EXPECT_GT(scenario.jaggedAmplitude, 0.0);
  EXPECT_EQ(scenario.preBites, 4);
  ScriptedHapticDevice scope(recording.scope), instrument(recording.instrument);
  TrainingScene scene(scenario, scope, instrument);
  // The bites at load made the rim: rough, tissue gone, nothing counted.
  const std::size_t active = scene.cutter()->activeTriangleCount();
  EXPECT_LT(active, scene.cutter()->collision().triangleCount()) << "bitten pieces should be gone";
  const double start = scene.metrics().rimRoughnessAtStart;
  EXPECT_GT(start, 0.05) << "the bites at load should leave a jagged rim (mm)";
  EXPECT_EQ(scene.metrics().rimRoughness, start);
  EXPECT_EQ(scene.metrics().operations, 0);
  const std::vector<Vector3> restBefore = scene.visualMesh().positions;
  ASSERT_TRUE(scene.runTo(scenario.duration)) << scene.lastError();
  const SceneMetrics& m = scene.metrics();
  EXPECT_GT(m.contourPasses, 10);
  EXPECT_EQ(m.operations, 0);
  EXPECT_EQ(m.removedVolume, 0.0);
  EXPECT_EQ(scene.cutter()->activeTriangleCount(), active);
  EXPECT_EQ(scene.visualMesh().vertexCount(), restBefore.size()) << "contouring cuts nothing";
  EXPECT_NE(scene.visualMesh().positions, restBefore) << "the cut surface should have moved";
  EXPECT_LT(m.rimRoughness, 0.5 * start);
  EXPECT_EQ(m.rimRoughness, scene.cutter()->cutRimRoughness().rootMeanSquare);
  EXPECT_EQ(scene.topologyVersion(), m.contourPasses) << "the view draws each pass";
  const std::string json = scene.metricsJson();
  EXPECT_NE(json.find("\"rim_roughness_start_mm\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"rim_roughness_mm\""), std::string::npos) << json;
  std::cout << json << "\n";
}

// The keys of contouring: shaver mode and strength (shavers only), the
// jagged cut surface (rows needed), the bites at load (meniscus only).
TEST(TrainingScene, ContouringKeysAreValidatedByKey)
{
  const ScenarioDescription s = parseScenario(
    R"({"version": 1, "instrument": {"type": "small_shaver", "shaverMode": "contour",
        "contourStrength": 0.4}, "cutting": {"jagged": {"amplitude": 0.3, "wavelength": 0.8,
        "seed": 7}}, "preparation": {"punchBites": {"count": 3, "from": 0.4, "to": 0.5}}})",
    "good.json");
  EXPECT_EQ(s.shaverMode, ShaverMode::Contour);
  EXPECT_EQ(s.contourStrength, 0.4);
  EXPECT_EQ(s.jaggedAmplitude, 0.3);
  EXPECT_EQ(s.jaggedWavelength, 0.8);
  EXPECT_EQ(s.jaggedSeed, 7u);
  EXPECT_EQ(s.preBites, 3);
  EXPECT_EQ(s.preBitesTo, 0.5);
  const auto expectKey = [](const std::string& json, const std::string& key)
  {
    const std::string message = messageOf(json);
    EXPECT_NE(message.find("scenario 'bad.json': key '" + key + "'"), std::string::npos)
      << json << " -> " << message;
  };
  expectKey(R"({"version": 1, "instrument": {"type": "small_shaver", "shaverMode": "polish"}})",
    "instrument.shaverMode");
  expectKey(R"({"version": 1, "instrument": {"type": "punch", "shaverMode": "contour"}})",
    "instrument.shaverMode");
  expectKey(R"({"version": 1, "instrument": {"type": "small_shaver", "contourStrength": 2}})",
    "instrument.contourStrength");
  expectKey(
    R"({"version": 1, "cutting": {"jagged": {"amplitude": -0.1}}})", "cutting.jagged.amplitude");
  expectKey(R"({"version": 1, "cutting": {"cutSurfaceRows": 0, "jagged": {"amplitude": 0.2}}})",
    "cutting.jagged.amplitude");
  expectKey(
    R"({"version": 1, "cutting": {"jagged": {"wavelength": 0}}})", "cutting.jagged.wavelength");
  expectKey(R"({"version": 1, "cutting": {"jagged": {"seed": 1.5}}})", "cutting.jagged.seed");
  expectKey(R"({"version": 1, "preparation": {"punchBites": {"count": 0}}})",
    "preparation.punchBites.count");
  expectKey(R"({"version": 1, "preparation": {"punchBites": {"from": 0.7, "to": 0.2}}})",
    "preparation.punchBites");
  expectKey(R"({"version": 1, "tissue": {"model": "sheet"}, "preparation": {"punchBites": {}}})",
    "preparation.punchBites");
}

// Live settings (the window's panel): material and wrinkle parameters reach
// the running scene without building it again -- applied before the first
// step they give the run of a scene built with them, bit for bit (and not
// the run without them); applied mid-run a softer tissue gives way more
// from then on. The cut-surface settings of a tissue being cut need the
// scene built again (refused, nothing changed).
TEST(TrainingScene, MaterialAndWrinkleSettingsApplyToTheRunningScene)
{
  Replay unchanged, live;
  ScenarioDescription changed = unchanged.scenario;
  changed.material.youngModulus *= 0.5;
  changed.wrinkle.windowSize = 2;
  ScriptedHapticDevice scope(unchanged.recording.scope);
  ScriptedHapticDevice instrument(unchanged.recording.instrument);
  TrainingScene fromStart(changed, scope, instrument);
  ASSERT_TRUE(live.scene.applySettings(changed));
  EXPECT_EQ(live.scene.scenario().material.youngModulus, changed.material.youngModulus);
  ASSERT_TRUE(fromStart.runTo(2.0));
  ASSERT_TRUE(live.scene.runTo(2.0));
  ASSERT_TRUE(unchanged.scene.runTo(2.0));
  EXPECT_EQ(live.scene.visualPositions(), fromStart.visualPositions());
  EXPECT_NE(live.scene.visualPositions(), unchanged.scene.visualPositions());

  // Mid-run, during the press: the unchanged scene softened from 2 s on
  // gives way more by 2.6 s than the scene that stays stiff.
  const std::vector<Vector3> rest = unchanged.scene.tissue().visual.positions;
  const auto deepest = [&rest](const TrainingScene& scene)
  {
    double d = 0.0;
    for (std::size_t i = 0; i < rest.size(); ++i)
      d = std::max(d, (scene.visualPositions()[i] - rest[i]).norm());
    return d;
  };
  ScenarioDescription stiff = changed;
  stiff.material.youngModulus = 4.0 * unchanged.scenario.material.youngModulus;
  ASSERT_TRUE(live.scene.applySettings(stiff));
  ASSERT_TRUE(unchanged.scene.applySettings(changed));
  ASSERT_TRUE(live.scene.runTo(2.6));
  ASSERT_TRUE(unchanged.scene.runTo(2.6));
  EXPECT_GT(deepest(unchanged.scene), 1.1 * deepest(live.scene));

  // A cutting scene: the jagged cut surface applies to the cuts to come;
  // a new row count once it has cut is refused, nothing changed.
  const SceneRecording sheet = readSceneRecording(Data + "/Recordings/sheet-cutting.json");
  const ScenarioDescription knife = readScenario(sheet.scenario);
  ScriptedHapticDevice sheetScope(sheet.scope), sheetKnife(sheet.instrument);
  TrainingScene cutting(knife, sheetScope, sheetKnife);
  ScenarioDescription jagged = knife;
  jagged.jaggedAmplitude = 0.3;
  ASSERT_TRUE(cutting.applySettings(jagged));
  ASSERT_TRUE(cutting.runTo(knife.duration));
  ASSERT_GT(cutting.cutter()->visual().cutSurfaceTriangleCount(), 0u);
  EXPECT_GT(cutting.cutter()->cutRimRoughness().maximum, 0.0);
  ScenarioDescription rows = jagged;
  rows.cutSurfaceRows = knife.cutSurfaceRows + 1;
  rows.material.youngModulus = 2.0 * knife.material.youngModulus;
  EXPECT_FALSE(cutting.applySettings(rows));
  EXPECT_EQ(cutting.scenario().cutSurfaceRows, knife.cutSurfaceRows);
  EXPECT_EQ(cutting.scenario().material.youngModulus, knife.material.youngModulus);
}
