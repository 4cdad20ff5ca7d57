#include "RealTimeLoop.h"

#include "ServoThread.h"

namespace thintissue
{

RealTimeLoop::RealTimeLoop(TrainingScene& scene, const RealTimeLoopSettings& settings)
  : Scene(scene)
  , Settings(settings)
{
  if (Settings.servo == LoopServo::Thread)
  {
    Servo = std::make_unique<ServoThread>(Scene.servo(), 0.001, 0);
  }
}

RealTimeLoop::~RealTimeLoop()
{
  stop();
}

void RealTimeLoop::start()
{
  if (Running.exchange(true))
  {
    return;
  }
  Scene.setServoTicking(
    Settings.servo == LoopServo::LockStep ? ServoTicking::LockStep : ServoTicking::Elsewhere);
  Finished.store(false);
  Error.clear();
  Steps.store(0);
  // The first snapshot from this thread, before physics owns the scene
  // (thread creation orders it before everything the thread does).
  Scene.snapshot(Snapshots.back());
  Snapshots.publish();
  Wanted.store(false);
  if (Servo)
  {
    Servo->start(Scene.servoTime());
  }
  Physics = std::thread([this] { run(); });
}

void RealTimeLoop::stop()
{
  Running.store(false);
  if (Physics.joinable())
  {
    Physics.join();
  }
  if (Servo)
  {
    Servo->stop();
  }
}

const SceneSnapshot& RealTimeLoop::latest()
{
  const SceneSnapshot& newest = Snapshots.latest();
  Wanted.store(true, std::memory_order_release);
  return newest;
}

void RealTimeLoop::publish()
{
  Scene.snapshot(Snapshots.back());
  Snapshots.publish();
}

void RealTimeLoop::waitForStep(double sceneStart, std::chrono::steady_clock::time_point& wallStart)
{
  using Clock = std::chrono::steady_clock;
  const double due = Scene.time() + Scene.scenario().timeStep - sceneStart;
  const auto when =
    wallStart + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(due));
  const auto now = Clock::now();
  if (now < when)
  {
    std::this_thread::sleep_until(when);
  }
  else if (now - when > std::chrono::milliseconds(100))
  {
    // Far behind (a slow cut, a stalled machine): carry on from now rather
    // than running a burst of steps to catch up.
    wallStart += now - when;
  }
}

void RealTimeLoop::run()
{
  const double sceneStart = Scene.time();
  auto wallStart = std::chrono::steady_clock::now();
  while (Running.load(std::memory_order_relaxed))
  {
    if (Scene.time() + 0.5 * Scene.scenario().timeStep >= Settings.endTime)
    {
      break;
    }
    if (Settings.pacedToWallClock)
    {
      waitForStep(sceneStart, wallStart);
    }
    if (!Scene.step())
    {
      Error = Scene.lastError();
      break;
    }
    Steps.fetch_add(1, std::memory_order_relaxed);
    if (Wanted.exchange(false, std::memory_order_acq_rel))
    {
      publish();
    }
  }
  publish(); // the last state, whatever stopped the loop
  // Finished on its own, not asked to stop.
  Finished.store(Running.load(), std::memory_order_release);
}

} // namespace thintissue
