// A thread that ticks a HapticServo at a fixed period (1 kHz by default),
// for devices without a scheduler of their own (scripted, mouse); the
// OpenHaptics backend ticks the servo from the HD scheduler instead. Keeps
// the measured periods (room reserved up front) for jitter figures.
#ifndef ServoThread_h
#define ServoThread_h

#include "HapticServo.h"
#include "ThinTissueHapticsModule.h"

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace thintissue
{

class THINTISSUEHAPTICS_EXPORT ServoThread
{
public:
  /// `servo` outlives the thread. Room for `periodCapacity` periods.
  explicit ServoThread(HapticServo& servo,
    double period = 0.001,
    std::size_t periodCapacity = 20000);
  ~ServoThread();
  ServoThread(const ServoThread&) = delete;
  ServoThread& operator=(const ServoThread&) = delete;

  /// Starts ticking; the servo's clock reads `clockStart` seconds at the
  /// start (a scene resumed where it stopped).
  void start(double clockStart = 0.0);
  /// Joins the thread; safe to call twice.
  void stop();
  bool running() const { return Running.load(); }
  /// Whether the thread got a real-time (SCHED_FIFO) priority.
  bool realTime() const { return RealTime; }
  /// Seconds since start() on the servo's clock (any thread).
  double now() const;

  /// After stop(): the measured periods (seconds) and tick durations.
  const std::vector<double>& periods() const { return Periods; }
  const std::vector<double>& tickDurations() const { return Durations; }

private:
  void run();

  HapticServo& Servo;
  double Period;
  std::atomic<bool> Running{ false };
  bool RealTime = false;
  std::thread Thread;
  std::vector<double> Periods;
  std::vector<double> Durations;
  std::chrono::steady_clock::time_point Start;
  double ClockStart = 0.0;
};

} // namespace thintissue

#endif
