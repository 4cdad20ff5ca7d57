// The real-time loop (DESIGN.md: three threads): the scene on the physics
// thread while this thread, as the GUI would, keeps taking snapshots. With
// the servo ticked in lock-step inside the physics step the threaded run
// must give the lock-step run's meshes bit for bit, whatever the GUI read
// meanwhile; every snapshot must be whole (positions of its own topology,
// time never going back), also across cuts; with the servo on its own
// thread the scene follows a device moved by this thread. Run under
// ThreadSanitizer (THINTISSUE_ENABLE_THREAD_SANITIZER) for data races.
#include "MouseHapticDevice.h"
#include "RealTimeLoop.h"
#include "ScriptedHapticDevice.h"
#include "TrainingScene.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

using namespace thintissue;

namespace
{

const std::string Data = THINTISSUE_SOURCE_DATA;

struct Replay
{
  explicit Replay(const std::string& name)
    : recording(readSceneRecording(Data + "/Recordings/" + name + ".json"))
    , scenario(readScenario(recording.scenario))
    , scope(recording.scope)
    , instrument(recording.instrument)
    , scene(scenario, scope, instrument)
  {
  }
  SceneRecording recording;
  ScenarioDescription scenario;
  ScriptedHapticDevice scope;
  ScriptedHapticDevice instrument;
  TrainingScene scene;
};

/// What the GUI thread saw while the loop ran to its end.
struct Watched
{
  int snapshots = 0; ///< distinct ones
  int topologies = 0;
  bool whole = true;
  bool forward = true;
};

/// Takes snapshots as fast as it can until the loop finishes, checking
/// each one.
Watched watchUntilFinished(RealTimeLoop& loop)
{
  Watched w;
  double last = -1.0;
  int version = -1;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(3);
  while (!loop.finished() && std::chrono::steady_clock::now() < deadline)
  {
    const SceneSnapshot& s = loop.latest();
    w.whole = w.whole && s.topology && s.visualPositions.size() == s.topology->mesh.vertexCount() &&
              s.topology->active.size() == s.topology->mesh.triangleCount();
    w.forward = w.forward && s.time >= last;
    w.snapshots += s.time != last ? 1 : 0;
    w.topologies += s.topology && s.topology->version != version ? 1 : 0;
    version = s.topology ? s.topology->version : version;
    last = s.time;
  }
  return w;
}

} // namespace

TEST(RealTimeLoop, ThePhysicsThreadInLockStepGivesTheLockStepRunBitForBit)
{
  Replay threaded("meniscus-examination"), reference("meniscus-examination");
  RealTimeLoopSettings settings;
  settings.servo = LoopServo::LockStep;
  settings.pacedToWallClock = false;
  settings.endTime = 2.7; // through the press and the wrinkles after it
  RealTimeLoop loop(threaded.scene, settings);
  loop.start();
  const Watched w = watchUntilFinished(loop);
  ASSERT_TRUE(loop.finished());
  EXPECT_EQ(loop.error(), "");
  EXPECT_TRUE(w.whole);
  EXPECT_TRUE(w.forward);
  EXPECT_GT(w.snapshots, 2) << "the GUI should have seen the run go on";
  const SceneSnapshot& last = loop.latest();
  loop.stop();
  ASSERT_TRUE(reference.scene.runTo(2.7));
  EXPECT_EQ(loop.stepsRun(), reference.scene.metrics().steps);
  EXPECT_EQ(last.time, reference.scene.time());
  EXPECT_EQ(last.visualPositions, reference.scene.visualPositions());
  EXPECT_EQ(last.instrument.translation, reference.scene.instrumentPose().translation);
  EXPECT_EQ(last.metrics.wrinklingSteps, reference.scene.metrics().wrinklingSteps);
  EXPECT_GT(last.metrics.wrinklingSteps, 0);
}

TEST(RealTimeLoop, SnapshotsStayWholeWhileThePunchCuts)
{
  Replay run("meniscectomy-punch");
  RealTimeLoopSettings settings;
  settings.servo = LoopServo::LockStep;
  settings.pacedToWallClock = false;
  settings.endTime = 3.7; // two bites at least
  RealTimeLoop loop(run.scene, settings);
  loop.start();
  const Watched w = watchUntilFinished(loop);
  ASSERT_TRUE(loop.finished());
  EXPECT_TRUE(w.whole);
  EXPECT_TRUE(w.forward);
  const SceneSnapshot& last = loop.latest();
  EXPECT_GE(last.metrics.operations, 2);
  EXPECT_EQ(last.topology->version, last.metrics.operations);
  EXPECT_GE(w.topologies, 2) << "the GUI should have seen the tissue before and after a bite";
}

TEST(RealTimeLoop, WithTheServoOnItsOwnThreadTheSceneFollowsTheDevice)
{
  const ScenarioDescription scenario = readScenario(Data + "/Scenarios/meniscus-examination.json");
  MouseHapticDevice scope, instrument;
  TrainingScene scene(scenario, scope, instrument);
  RealTimeLoop loop(scene); // servo thread, physics paced to the wall clock
  loop.start();
  const Vector3 start = loop.latest().instrument.translation;
  // The GUI thread moves the stylus 8 mm across, a little each frame.
  for (int frame = 1; frame <= 20; ++frame)
  {
    HapticDeviceState stylus;
    stylus.position = Vector3(0.4 * frame, 0.0, 0.0);
    instrument.setState(stylus);
    std::this_thread::sleep_for(std::chrono::milliseconds(16));
    (void)loop.latest();
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  double moved = 0.0;
  while (moved < 7.9 && std::chrono::steady_clock::now() < deadline)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(16));
    moved = (loop.latest().instrument.translation - start).norm();
  }
  EXPECT_GT(loop.stepsRun(), 10) << "physics should have run beside the servo";
  EXPECT_NEAR(moved, 8.0, 0.1) << "the instrument should follow the stylus (portal scale 1)";
  EXPECT_FALSE(loop.finished()) << loop.error();
  loop.stop();
  EXPECT_FALSE(loop.running());
  // Paced to the wall clock: about one step per time step, none lost.
  EXPECT_EQ(loop.stepsRun(), scene.metrics().steps);
  EXPECT_NEAR(scene.time(), scene.metrics().steps * scenario.timeStep, 1e-9);
}
