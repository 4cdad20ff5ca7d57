// The real-time loop of DESIGN.md: the servo at 1 kHz on its own thread
// (ServoThread, or the OpenHaptics scheduler the application started), the
// physics at the scenario's fixed step on another, and the GUI, the only
// thread that touches VTK, taking the newest SceneSnapshot at its own rate.
// Physics publishes a snapshot through a LatestValue triple buffer after
// the first step that follows the GUI's last take: no lock is held across
// a step, and the visual mesh is mapped only as often as the GUI draws.
//
// The lock-step mode (TrainingScene::step on the caller's thread) stays for
// tests, benchmarks, replays and image baselines; ServoTicking::LockStep
// here runs that deterministic stepping on the physics thread.
#ifndef RealTimeLoop_h
#define RealTimeLoop_h

#include "LatestValue.h"
#include "SceneSnapshot.h"
#include "ThinTissueSceneModule.h"
#include "TrainingScene.h"

#include <atomic>
#include <limits>
#include <memory>
#include <string>
#include <thread>

namespace thintissue
{

class ServoThread;

/// Who ticks the servo while the loop runs.
enum class LoopServo
{
  /// The loop's own ServoThread at 1 kHz.
  Thread,
  /// Someone else (the OpenHaptics scheduler started by the application).
  External,
  /// The physics step itself (TrainingScene's lock-step): deterministic.
  LockStep
};

struct RealTimeLoopSettings
{
  LoopServo servo = LoopServo::Thread;
  /// A step when its time comes on the wall clock; off: as fast as it can.
  bool pacedToWallClock = true;
  /// Physics stops at this scene time (a replay's end); infinite: never.
  double endTime = std::numeric_limits<double>::infinity();
};

class THINTISSUESCENE_EXPORT RealTimeLoop
{
public:
  /// `scene` outlives the loop and is not touched by the caller while the
  /// loop runs (only through latest()).
  RealTimeLoop(TrainingScene& scene, const RealTimeLoopSettings& settings = {});
  /// Stops the threads.
  ~RealTimeLoop();
  RealTimeLoop(const RealTimeLoop&) = delete;
  RealTimeLoop& operator=(const RealTimeLoop&) = delete;

  /// Publishes the scene as it is and starts the threads (again after
  /// stop(): the servo's clock resumes at the scene's).
  void start();
  /// Joins the threads; the scene may be used by the caller again.
  void stop();
  bool running() const { return Running.load(); }

  /// GUI thread (the one consumer): the newest snapshot; stays valid and
  /// unchanged until the next call.
  const SceneSnapshot& latest();
  /// Physics stopped on its own: the end time reached or a failed step.
  bool finished() const { return Finished.load(std::memory_order_acquire); }
  /// After finished(): the solver's message if a step failed, else "".
  const std::string& error() const { return Error; }
  /// Steps the physics thread has run since start().
  long stepsRun() const { return Steps.load(std::memory_order_relaxed); }

private:
  void run();
  void publish();
  void waitForStep(double sceneStart, std::chrono::steady_clock::time_point& wallStart);

  TrainingScene& Scene;
  RealTimeLoopSettings Settings;
  LatestValue<SceneSnapshot> Snapshots;
  std::unique_ptr<ServoThread> Servo;
  std::thread Physics;
  std::atomic<bool> Running{ false };
  std::atomic<bool> Finished{ false };
  std::atomic<bool> Wanted{ true };
  std::atomic<long> Steps{ 0 };
  std::string Error;
};

} // namespace thintissue

#endif
