// The servo loop's parts, stepped by hand: the latest-value exchange, the
// portal (fulcrum) mapping, the local contact model, the force safety
// stage, and the servo with two scripted devices.
#include "HapticServo.h"
#include "ScriptedHapticDevice.h"
#include "ServoThread.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <thread>

using namespace thintissue;

namespace
{

HapticTrajectory stillAt(const Vector3& position, double duration = 10.0)
{
  HapticTrajectory t;
  t.samples.push_back(HapticSample{ 0.0, position, Eigen::Quaterniond::Identity(), 0 });
  t.samples.push_back(HapticSample{ duration, position, Eigen::Quaterniond::Identity(), 0 });
  return t;
}

/// A contact pushing the instrument along +z with stiffness k, `depth` deep.
void publishPush(HapticServo& servo, std::size_t slot, double time, double k, double depth)
{
  LocalContactModel& model = servo.contactModelToFill(slot);
  model.time = time;
  model.count = 0;
  model.toolPose = RigidPose{};
  model.toolPose = servo.latestToolState(slot).pose;
  model.add(LocalContact{ Vector3::Zero(), Vector3::UnitZ(), depth, k });
  servo.publishContactModel(slot);
}

ForceSafetySettings noRamp()
{
  ForceSafetySettings s;
  s.rampIn = 0.0;
  s.maximumRate = 1e9;
  return s;
}

} // namespace

TEST(LatestValue, TheConsumerSeesTheNewestPublishedValueWhole)
{
  LatestValue<int> single(7);
  EXPECT_EQ(single.latest(), 7);
  single.back() = 1;
  single.publish();
  single.back() = 2;
  single.publish();
  EXPECT_EQ(single.latest(), 2);
  EXPECT_EQ(single.latest(), 2);

  // Two threads: pairs written whole, sequence never going back.
  struct Pair
  {
    long a = 0;
    long b = 0;
  };
  LatestValue<Pair> exchange;
  constexpr long Count = 200000;
  std::thread producer(
    [&]
    {
      for (long i = 1; i <= Count; ++i)
      {
        exchange.back() = Pair{ i, -i };
        exchange.publish();
      }
    });
  long last = 0;
  bool torn = false, backwards = false;
  while (last < Count)
  {
    const Pair& p = exchange.latest();
    torn = torn || p.a != -p.b;
    backwards = backwards || p.a < last;
    last = p.a;
  }
  producer.join();
  EXPECT_FALSE(torn);
  EXPECT_FALSE(backwards);
}

TEST(PortalMapping, TheShaftPassesThroughThePortalForAnyStylusPose)
{
  PortalSettings s;
  s.portal = Vector3(10.0, -5.0, 40.0);
  s.inward = Vector3(-0.2, 0.3, -1.0);
  s.deviceToWorld = Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized()).toRotationMatrix();
  s.scale = 0.5;
  const PortalMapping portal(s);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> position(-80.0, 80.0), angle(-M_PI, M_PI);
  for (int k = 0; k < 2000; ++k)
  {
    HapticDeviceState stylus;
    stylus.position = Vector3(position(random), position(random), 0.5 * position(random));
    stylus.orientation = Eigen::AngleAxisd(
      angle(random), Vector3(position(random), position(random), 1.0).normalized())
                           .toRotationMatrix();
    const RigidPose pose = portal.instrumentPose(stylus);
    const Vector3 z = pose.rotation.col(2);
    const Vector3 toPortal = s.portal - pose.translation;
    // The portal lies on the shaft, handle side of the tip.
    EXPECT_LT((toPortal - toPortal.dot(z) * z).norm(), 1e-9);
    EXPECT_GE(toPortal.dot(z), s.minimumInsertion - 1e-9);
    EXPECT_LT(
      (pose.rotation.transpose() * pose.rotation - Eigen::Matrix3d::Identity()).norm(), 1e-9);
    EXPECT_GT(pose.rotation.determinant(), 0.0);
    // The tip follows the stylus unless it had to keep the minimum insertion.
    const Vector3 mapped = portal.mappedTip(stylus.position);
    if ((mapped - s.portal).norm() > s.minimumInsertion)
    {
      EXPECT_LT((pose.translation - mapped).norm(), 1e-9);
    }
  }
  // The inverse places a point near the tip where asked.
  for (int k = 0; k < 200; ++k)
  {
    const Vector3 target = s.portal + 30.0 * s.inward.normalized() +
                           0.2 * Vector3(position(random), position(random), position(random));
    const Eigen::Matrix3d orientation =
      Eigen::AngleAxisd(angle(random), Vector3(1.0, 2.0, position(random)).normalized())
        .toRotationMatrix();
    const Vector3 point(1.5, -0.5, 2.0);
    HapticDeviceState placed;
    placed.orientation = orientation;
    placed.position = portal.stylusPositionPlacing(point, target, orientation);
    EXPECT_LT((portal.instrumentPose(placed) * point - target).norm(), 1e-8) << k;
  }
  // Roll: turning the stylus about the shaft turns the working side with it.
  HapticDeviceState stylus;
  stylus.position = Vector3(3.0, 4.0, 0.0);
  const RigidPose a = portal.instrumentPose(stylus);
  const Vector3 shaftInDevice = s.deviceToWorld.transpose() * a.rotation.col(2);
  stylus.orientation = Eigen::AngleAxisd(0.5, shaftInDevice).toRotationMatrix();
  const RigidPose b = portal.instrumentPose(stylus);
  EXPECT_NEAR(
    std::acos(std::clamp(a.rotation.col(0).dot(b.rotation.col(0)), -1.0, 1.0)), 0.5, 1e-9);
  // Settings checked.
  PortalSettings bad = s;
  bad.scale = 0.0;
  EXPECT_THROW(PortalMapping{ bad }, InvalidInputError);
  bad = s;
  bad.deviceToWorld(0, 0) = 2.0;
  EXPECT_THROW(PortalMapping{ bad }, InvalidInputError);
}

TEST(LocalContactModel, SpringsLinearisedAboutThePublishedPose)
{
  LocalContactModel model;
  model.toolPose.translation = Vector3(1.0, 2.0, 3.0);
  model.add(LocalContact{ Vector3(0.0, 0.0, 1.0), Vector3::UnitZ(), 0.2, 10.0 });
  model.add(LocalContact{ Vector3(1.0, 0.0, 0.0), Vector3::UnitX(), 0.1, 5.0 });
  EXPECT_LT((model.force(model.toolPose) - Vector3(0.5, 0.0, 2.0)).norm(), 1e-12);
  // 0.1 further down: the first contact deepens; the second is unchanged.
  RigidPose lower = model.toolPose;
  lower.translation.z() -= 0.1;
  EXPECT_LT((model.force(lower) - Vector3(0.5, 0.0, 3.0)).norm(), 1e-12);
  // Lifted clear of the first; moved clear of both.
  RigidPose away = model.toolPose;
  away.translation += Vector3(1.0, 0.0, 1.0);
  EXPECT_EQ(model.force(away), Vector3::Zero());
  // Full: further contacts are refused.
  LocalContactModel full;
  for (int c = 0; c < LocalContactModel::MaximumContacts; ++c)
  {
    EXPECT_TRUE(full.add(LocalContact{}));
  }
  EXPECT_FALSE(full.add(LocalContact{}));
}

TEST(ForceSafety, ClampNanRampStaleAndRate)
{
  ForceSafetySettings s;
  s.rampIn = 0.1;
  s.staleAfter = 0.01;
  s.fadeOut = 0.003;
  s.maximumRate = 100.0; // 0.1 N per millisecond
  ForceSafety safety(s, 0.88);
  const Vector3 big(0.0, 0.0, 5.0);
  // Ramp-in and rate: never more than 0.1 N of change per tick.
  double previous = 0.0;
  for (int k = 1; k <= 200; ++k)
  {
    const double f = safety.apply(big, 0.001 * k, 0.0).norm();
    EXPECT_LE(f, 0.88 + 1e-12);
    EXPECT_LE(f - previous, 0.1 + 1e-12);
    EXPECT_LE(f, std::min(1.0, 0.001 * k / 0.1) * 5.0 + 1e-12);
    previous = f;
  }
  EXPECT_NEAR(previous, 0.88, 1e-12);
  // NaN: zero (at once: within the rate limit of a tick at the clamp).
  ForceSafety quick(noRamp(), 0.88);
  EXPECT_EQ(quick.apply(Vector3(0.0, std::nan(""), 0.0), 0.001, 0.0), Vector3::Zero());
  EXPECT_NEAR(quick.apply(big, 0.002, 0.0).norm(), 0.88, 1e-12);
  EXPECT_EQ(quick.apply(Vector3::Constant(INFINITY), 0.003, 0.0), Vector3::Zero());
  // Stale: fades to zero within 3 ticks of going stale.
  ForceSafetySettings fade = noRamp();
  fade.staleAfter = 0.01;
  fade.fadeOut = 0.003;
  ForceSafety stale(fade, 0.88);
  const double published = 0.0;
  double time = 0.001;
  for (; time - published <= 0.01 + 1e-12; time += 0.001)
  {
    EXPECT_NEAR(stale.apply(big, time, time - published).norm(), 0.88, 1e-12);
  }
  int ticks = 0;
  while (stale.apply(big, time, time - published).norm() > 0.0)
  {
    time += 0.001;
    ++ticks;
  }
  EXPECT_LE(ticks, 3);
  // A model never published: nothing.
  ForceSafety never(noRamp(), 0.88);
  EXPECT_EQ(never.apply(big, 0.001, INFINITY), Vector3::Zero());
  EXPECT_THROW(ForceSafety(ForceSafetySettings{ -1.0 }, 0.88), InvalidInputError);
}

TEST(HapticServo, TwoDevicesAForceEachTickNeverAboveTheMaximum)
{
  ScriptedHapticDevice scope(stillAt(Vector3(0.0, 0.0, 0.0)));
  ScriptedHapticDevice instrument(stillAt(Vector3(5.0, 0.0, 0.0)));
  HapticSlot camera{ &scope, PortalSettings{}, false };
  PortalSettings instrumentPortal;
  instrumentPortal.portal = Vector3(40.0, 0.0, 30.0);
  HapticSlot tool{ &instrument, instrumentPortal, true };
  HapticServo servo({ camera, tool }, noRamp());
  double t = 0.0;
  servo.tick(t);
  // A very stiff contact: 100 N requested, 0.88 N delivered.
  publishPush(servo, 1, t, 1000.0, 0.1);
  publishPush(servo, 0, t, 1000.0, 0.1);
  for (int k = 1; k <= 20; ++k)
  {
    t = 0.001 * k;
    servo.tick(t);
  }
  ASSERT_EQ(instrument.forces().size(), 21u);
  ASSERT_EQ(scope.forces().size(), 21u);
  for (std::size_t k = 1; k < instrument.forces().size(); ++k)
  {
    EXPECT_NEAR(instrument.forces()[k].norm(), 0.88, 1e-12) << k;
    EXPECT_EQ(scope.forces()[k], Vector3::Zero()); // the arthroscope feels nothing
  }
  EXPECT_EQ(instrument.forces()[0], Vector3::Zero()); // before any model
  const HapticToolState& state = servo.latestToolState(1);
  EXPECT_EQ(state.tick, 21u);
  EXPECT_EQ(state.modelSequence, 1u);
  EXPECT_DOUBLE_EQ(state.modelFirstRendered, 0.001); // the tick after publishing
  // The force pushes the instrument along the contact normal (+z world).
  EXPECT_GT((servo.latestToolState(1).pose.rotation * Vector3::Zero() + Vector3::UnitZ())
              .dot(instrument.forces().back()),
    0.0);
  EXPECT_THROW(HapticServo({ HapticSlot{} }), InvalidInputError);
}

TEST(HapticServo, ReplaysAreDeterministicAndTheThreadTicks)
{
  HapticTrajectory path;
  for (int k = 0; k <= 100; ++k)
  {
    path.samples.push_back(HapticSample{ 0.001 * k,
      Vector3(0.1 * k, 0.0, -0.05 * k),
      Eigen::Quaterniond(Eigen::AngleAxisd(0.01 * k, Vector3::UnitZ())),
      k > 50 ? 1u : 0u });
  }
  std::vector<std::vector<Vector3>> runs;
  for (int run = 0; run < 2; ++run)
  {
    ScriptedHapticDevice device(path);
    HapticServo servo({ HapticSlot{ &device, PortalSettings{}, true } });
    for (int k = 0; k <= 100; ++k)
    {
      if (k % 10 == 0)
      {
        publishPush(servo, 0, 0.001 * k, 50.0, 0.5);
      }
      servo.tick(0.001 * k);
    }
    EXPECT_EQ(servo.latestToolState(0).stylus.buttons, 1u);
    runs.push_back(device.forces());
  }
  EXPECT_EQ(runs[0], runs[1]);
  EXPECT_GT(runs[0].back().norm(), 0.0);

  ScriptedHapticDevice device(stillAt(Vector3::Zero()));
  HapticServo servo({ HapticSlot{ &device, PortalSettings{}, true } });
  ServoThread thread(servo);
  thread.start();
  while (servo.latestToolState(0).tick < 20)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  thread.stop();
  EXPECT_GE(thread.periods().size(), 20u);
  EXPECT_EQ(device.forces().size(), servo.latestToolState(0).tick);
}

TEST(HapticServo, EnablingASlotRampsItsForceInAgain)
{
  ScriptedHapticDevice device(stillAt(Vector3::Zero()));
  ForceSafetySettings settings = noRamp();
  settings.rampIn = 0.1;
  HapticServo servo({ HapticSlot{ &device, PortalSettings{}, true } }, settings);
  // Physics publishes every 10 ms (the model stays fresh).
  const auto tick = [&](int k)
  {
    if (k % 10 == 0)
    {
      publishPush(servo, 0, 0.001 * k, 20.0, 0.1); // 2 N asked
    }
    servo.tick(0.001 * k);
  };
  for (int k = 0; k <= 200; ++k)
  {
    tick(k);
  }
  EXPECT_NEAR(device.forces().back().norm(), 0.88, 1e-12); // ramped in
  servo.enable(0, 0.2);
  tick(201);
  EXPECT_NEAR(device.forces().back().norm(), 0.02, 1e-9); // 1 ms of a 100 ms ramp
  for (int k = 202; k <= 320; ++k)
  {
    tick(k);
  }
  EXPECT_NEAR(device.forces().back().norm(), 0.88, 1e-12);
}
