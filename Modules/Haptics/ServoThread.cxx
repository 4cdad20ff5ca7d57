#include "ServoThread.h"

#include "ThinTissueError.h"

#include <algorithm>

#include <cmath>

#include <pthread.h>
#include <sched.h>

namespace thintissue
{

ServoThread::ServoThread(HapticServo& servo, double period, std::size_t periodCapacity)
  : Servo(servo)
  , Period(period)
{
  if (!(period > 0.0) || !std::isfinite(period))
  {
    throw InvalidInputError("servo thread: period " + std::to_string(period) + " must be positive");
  }
  Periods.reserve(periodCapacity);
  Durations.reserve(periodCapacity);
}

ServoThread::~ServoThread()
{
  stop();
}

void ServoThread::start(double clockStart)
{
  if (Running.exchange(true))
  {
    return;
  }
  ClockStart = clockStart;
  Periods.clear();
  Durations.clear();
  Start = std::chrono::steady_clock::now();
  Thread = std::thread([this] { run(); });
  // A real-time priority when the system grants it (root, or rtprio in
  // limits.conf): the period then keeps to the millisecond under load.
  sched_param parameters{};
  parameters.sched_priority = std::max(1, sched_get_priority_max(SCHED_FIFO) - 10);
  RealTime = pthread_setschedparam(Thread.native_handle(), SCHED_FIFO, &parameters) == 0;
}

void ServoThread::stop()
{
  Running.store(false);
  if (Thread.joinable())
  {
    Thread.join();
  }
}

double ServoThread::now() const
{
  return ClockStart +
         std::chrono::duration<double>(std::chrono::steady_clock::now() - Start).count();
}

void ServoThread::run()
{
  using Clock = std::chrono::steady_clock;
  const auto period =
    std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(Period));
  auto next = Start;
  auto last = Start;
  while (Running.load(std::memory_order_relaxed))
  {
    next += period;
    std::this_thread::sleep_until(next);
    const auto woke = Clock::now();
    Servo.tick(ClockStart + std::chrono::duration<double>(woke - Start).count());
    const auto done = Clock::now();
    if (Periods.size() < Periods.capacity())
    {
      Periods.push_back(std::chrono::duration<double>(woke - last).count());
      Durations.push_back(std::chrono::duration<double>(done - woke).count());
    }
    last = woke;
    if (done > next + 10 * period)
    {
      next = done; // far behind (the machine stalled): do not burst to catch up
    }
  }
}

} // namespace thintissue
