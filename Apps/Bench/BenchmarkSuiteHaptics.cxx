// Suite "haptics": the servo tick with two devices and 200 contacts in the
// local model (target 20 us: 1 kHz leaves 1,000), the jitter of the servo
// period on its thread, and the publish-to-force latency (target: at most
// one tick). The thesis gives no figure (its haptics ran in SOFA at 1 kHz).
#include "BenchmarkRegistry.h"

#include "HapticServo.h"
#include "ScriptedHapticDevice.h"
#include "ServoThread.h"

#include <algorithm>
#include <cmath>
#include <thread>

namespace
{
using namespace thintissue;
using namespace thintissue::bench;

HapticTrajectory circling(double seconds)
{
  HapticTrajectory t;
  for (int k = 0; k <= static_cast<int>(seconds * 100.0); ++k)
  {
    const double time = 0.01 * k;
    t.samples.push_back(HapticSample{ time,
      Vector3(20.0 * std::cos(time), 20.0 * std::sin(time), 5.0 * std::sin(3.0 * time)),
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * time, Vector3::UnitY())),
      0 });
  }
  return t;
}

/// 200 contacts around the instrument's tip, published at `time`.
void publishContacts(HapticServo& servo, double time)
{
  LocalContactModel& model = servo.contactModelToFill(1);
  model.time = time;
  model.count = 0;
  model.toolPose = servo.latestToolState(1).pose;
  for (int c = 0; c < 200; ++c)
  {
    const double a = 0.1 * c;
    model.add(LocalContact{ Vector3(0.3 * std::cos(a), 0.3 * std::sin(a), 0.01 * c),
      Vector3(std::cos(a), std::sin(a), 1.0).normalized(),
      0.05,
      0.25 });
  }
  servo.publishContactModel(1);
}

} // namespace

THINTISSUE_BENCHMARK_SUITE(hapticsSuite,
  "haptics",
  "servo tick with two devices and 200 contacts, servo period jitter, publish-to-force latency")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const double seconds = context.quick ? 1.0 : 10.0;
  ScriptedHapticDevice scope(circling(seconds + 1.0));
  ScriptedHapticDevice instrument(circling(seconds + 1.0));
  PortalSettings instrumentPortal;
  instrumentPortal.portal = Vector3(30.0, 0.0, 40.0);
  HapticServo servo({ HapticSlot{ &scope, PortalSettings{}, false },
    HapticSlot{ &instrument, instrumentPortal, true } });
  servo.tick(0.0);
  publishContacts(servo, 0.0);
  constexpr int Ticks = 1000;
  double time = 0.0;
  const double tick = medianSeconds(
                        [&]
                        {
                          for (int k = 0; k < Ticks; ++k)
                          {
                            time += 1e-6; // the model stays fresh
                            servo.tick(time);
                          }
                        },
                        context.quick ? 3 : 21) /
                      Ticks;
  reporter.report("servo tick, two devices, 200 contacts", "time", tick * 1e6, "us");

  // On its thread, at 1 kHz, with models published every 3.7 ms.
  HapticServo threaded({ HapticSlot{ &scope, PortalSettings{}, false },
    HapticSlot{ &instrument, instrumentPortal, true } });
  ServoThread thread(threaded, 0.001, static_cast<std::size_t>(seconds * 1000.0) + 1000);
  thread.start();
  std::vector<double> latencies;
  unsigned long published = 0;
  while (thread.now() < seconds)
  {
    std::this_thread::sleep_for(std::chrono::microseconds(3700));
    publishContacts(threaded, thread.now());
    // From the moment the model is out (a delay of this thread before it
    // published is not the servo's latency) to the first tick rendering it.
    const double publishedAt = thread.now();
    ++published;
    for (int wait = 0; wait < 100; ++wait)
    {
      const HapticToolState& state = threaded.latestToolState(1);
      if (state.modelSequence >= published)
      {
        latencies.push_back(std::max(0.0, state.modelFirstRendered - publishedAt));
        break;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
  thread.stop();
  const std::string name = std::to_string(static_cast<int>(seconds)) +
                           " s at 1 kHz, scripted devices" +
                           (thread.realTime() ? ", real-time priority" : ", normal priority");
  reporter.report(name, "period median", percentile(thread.periods(), 0.5) * 1e3, "ms");
  reporter.report(
    name, "period 99.9th percentile", percentile(thread.periods(), 0.999) * 1e3, "ms");
  reporter.report(name, "period largest", percentile(thread.periods(), 1.0) * 1e3, "ms");
  reporter.report(
    name, "tick 99.9th percentile", percentile(thread.tickDurations(), 0.999) * 1e6, "us");
  if (!latencies.empty())
  {
    reporter.report(
      name, "publish-to-force latency median", percentile(latencies, 0.5) * 1e3, "ms");
    reporter.report(
      name, "publish-to-force latency largest", percentile(latencies, 1.0) * 1e3, "ms");
  }
}
