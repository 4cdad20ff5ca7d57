// The OpenHaptics backend against the stand-in HD library (StandInHD.cxx):
// two devices opened by name, a frame per device per tick with the force
// written inside it, forces within the nominal maximum and NaN made zero,
// every HD error a message naming the device and the problem, and no HD
// call after shut-down.
#include "HapticServo.h"
#include "OpenHapticsSystem.h"

#include <gtest/gtest.h>

#include <dlfcn.h>

#include <cmath>
#include <string>

using namespace thintissue;

namespace
{

/// The stand-in's test controls, from the same loaded library the backend
/// uses.
struct StandIn
{
  void* handle = dlopen(THINTISSUE_STANDIN_HD, RTLD_NOW);
  template <typename F>
  F get(const char* name)
  {
    return reinterpret_cast<F>(dlsym(handle, name));
  }
  void reset() { get<void (*)()>("standin_reset")(); }
  void add(const char* name, bool calibrated = true, double maxContinuous = 0.88)
  {
    get<void (*)(const char*, int, double, double)>("standin_add_device")(
      name, calibrated ? 1 : 0, maxContinuous, 3.3);
  }
  void stylus(const char* name, const Vector3& at, int buttons)
  {
    double m[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, at.x(), at.y(), at.z(), 1 };
    get<void (*)(const char*, const double*, int)>("standin_set_stylus")(name, m, buttons);
  }
  void failNext(const char* call, unsigned error)
  {
    get<void (*)(const char*, unsigned)>("standin_fail_next")(call, error);
  }
  int tick(int n) { return get<int (*)(int)>("standin_tick")(n); }
  int forceCount(const char* name)
  {
    return get<int (*)(const char*)>("standin_force_count")(name);
  }
  Vector3 force(const char* name, int i)
  {
    Vector3 f;
    get<void (*)(const char*, int, double*)>("standin_force")(name, i, f.data());
    return f;
  }
  std::vector<std::string> log()
  {
    std::vector<std::string> entries;
    const int n = get<int (*)()>("standin_log_size")();
    for (int i = 0; i < n; ++i)
    {
      entries.push_back(get<const char* (*)(int)>("standin_log_entry")(i));
    }
    return entries;
  }
};

OpenHapticsSettings twoDevices()
{
  OpenHapticsSettings s;
  s.library = THINTISSUE_STANDIN_HD;
  s.deviceNames = { "Left Device", "Right Device" };
  return s;
}

ForceSafetySettings immediate()
{
  ForceSafetySettings s;
  s.rampIn = 0.0;
  s.staleAfter = 1e9;
  s.maximumRate = 1e9;
  return s;
}

/// A stiff spring along +z on the instrument (slot 1), `stiffness` N/mm.
void pushInstrument(HapticServo& servo, double stiffness)
{
  LocalContactModel& model = servo.contactModelToFill(1);
  model.time = 0.0;
  model.count = 0;
  model.toolPose = servo.latestToolState(1).pose;
  model.add(LocalContact{ Vector3::Zero(), Vector3::UnitZ(), 1.0, stiffness });
  servo.publishContactModel(1);
}

std::string messageOf(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const HapticDeviceError& e)
  {
    return e.what();
  }
  return "";
}

} // namespace

TEST(OpenHapticsSystem, TwoDevicesByNameAFrameAndAForceEachTick)
{
  StandIn hd;
  ASSERT_NE(hd.handle, nullptr);
  hd.reset();
  hd.add("Left Device", true, 0.9);
  hd.add("Right Device", true, 0.88);
  hd.stylus("Right Device", Vector3(10.0, 20.0, 30.0), 2);
  {
    OpenHapticsSystem system(twoDevices());
    ASSERT_EQ(system.deviceCount(), 2u);
    EXPECT_EQ(system.device(0).info().name, "Left Device");
    EXPECT_DOUBLE_EQ(system.device(0).info().nominalContinuousForce, 0.9);
    HapticServo servo({ HapticSlot{ &system.device(0), PortalSettings{}, false },
                        HapticSlot{ &system.device(1), PortalSettings{}, true } },
      immediate());
    system.start(servo);
    EXPECT_EQ(hd.tick(1), 1);
    pushInstrument(servo, 100.0); // 100 N asked
    EXPECT_EQ(hd.tick(9), 1);
    EXPECT_TRUE(system.errors().empty());
    ASSERT_EQ(hd.forceCount("Left Device"), 10);
    ASSERT_EQ(hd.forceCount("Right Device"), 10);
    for (int i = 1; i < 10; ++i)
    {
      EXPECT_EQ(hd.force("Left Device", i), Vector3::Zero());       // the arthroscope
      EXPECT_NEAR(hd.force("Right Device", i).norm(), 0.88, 1e-12); // clamped
    }
    const HapticToolState& state = servo.latestToolState(1);
    EXPECT_EQ(state.stylus.position, Vector3(10.0, 20.0, 30.0));
    EXPECT_EQ(state.stylus.buttons, 2u);
    // NaN from the model: zero on the device.
    pushInstrument(servo, std::nan(""));
    hd.tick(1);
    EXPECT_EQ(hd.force("Right Device", 10), Vector3::Zero());
  }
  // Order: each device's reads and force inside its own frame; nothing
  // after the devices were disabled.
  const std::vector<std::string> log = hd.log();
  int lastDisable = -1;
  for (int i = 0; i < static_cast<int>(log.size()); ++i)
  {
    EXPECT_EQ(log[i].rfind("misuse", 0), std::string::npos) << log[i];
    if (log[i].rfind("hdDisableDevice", 0) == 0)
    {
      lastDisable = i;
    }
  }
  ASSERT_GE(lastDisable, 0);
  EXPECT_EQ(lastDisable, static_cast<int>(log.size()) - 1);
  EXPECT_EQ(hd.tick(5), 0);
  EXPECT_EQ(hd.log().size(), log.size()); // no call after shut-down
}

TEST(OpenHapticsSystem, ErrorsNameTheDeviceAndTheProblem)
{
  StandIn hd;
  hd.reset();
  hd.add("Left Device");
  // A device that is not there; the one opened before is closed again.
  OpenHapticsSettings missing = twoDevices();
  std::string message = messageOf([&] { OpenHapticsSystem system(missing); });
  EXPECT_NE(message.find("'Right Device' not found"), std::string::npos) << message;
  EXPECT_NE(message.find("0x300"), std::string::npos) << message;
  EXPECT_EQ(hd.log().back(), "hdDisableDevice 0");
  // No library.
  OpenHapticsSettings absent;
  absent.library = "/nonexistent/libHD.so";
  message = messageOf([&] { OpenHapticsSystem system(absent); });
  EXPECT_NE(message.find("/nonexistent/libHD.so"), std::string::npos) << message;

  hd.reset();
  hd.add("Left Device");
  hd.add("Right Device", false);
  OpenHapticsSystem system(twoDevices());
  HapticServo servo({ HapticSlot{ &system.device(0), PortalSettings{}, true },
                      HapticSlot{ &system.device(1), PortalSettings{}, true } },
    immediate());
  // The scheduler does not start.
  hd.failNext("hdStartScheduler", 0x304);
  message = messageOf([&] { system.start(servo); });
  EXPECT_NE(message.find("scheduler failed"), std::string::npos) << message;
  EXPECT_FALSE(system.running());
  // Not calibrated: said, and no force from that stylus.
  system.start(servo);
  pushInstrument(servo, 100.0);
  hd.tick(3);
  EXPECT_EQ(hd.force("Right Device", 2), Vector3::Zero());
  const auto errors = system.errors();
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("'Right Device' is not calibrated"), std::string::npos) << errors[0];
  // Over-force shut-down: the callback stops, the message says so.
  hd.failNext("hdSetDoublev", 0x201);
  EXPECT_EQ(hd.tick(5), 0);
  const auto after = system.errors();
  ASSERT_EQ(after.size(), 2u);
  EXPECT_NE(after[0].find("'Left Device': over-force shut-down"), std::string::npos) << after[0];
  EXPECT_NE(after[0].find("Exceeded max force"), std::string::npos) << after[0];
}

TEST(OpenHapticsSystem, RampInAtStartAndAStaleModelFades)
{
  StandIn hd;
  hd.reset();
  hd.add("Left Device");
  hd.add("Right Device");
  OpenHapticsSystem system(twoDevices());
  // A minute of ramp-in: whatever the machine's speed, the first ticks (well
  // within a second of the start) send a small fraction of the force.
  ForceSafetySettings slowRamp;
  slowRamp.rampIn = 60.0;
  HapticServo servo({ HapticSlot{ &system.device(0), PortalSettings{}, false },
                      HapticSlot{ &system.device(1), PortalSettings{}, true } },
    slowRamp);
  system.start(servo);
  hd.tick(1);
  pushInstrument(servo, 100.0);
  hd.tick(3);
  for (int i = 1; i < 4; ++i)
  {
    EXPECT_LT(hd.force("Right Device", i).norm(), 0.05) << "tick " << i;
  }
  system.stop();
  // A model published long ago (ten seconds before the servo's clock
  // started): stale, so nothing reaches the stylus.
  ForceSafetySettings staleAfterOneTick = immediate();
  staleAfterOneTick.staleAfter = 0.001;
  HapticServo stale({ HapticSlot{ &system.device(0), PortalSettings{}, false },
                      HapticSlot{ &system.device(1), PortalSettings{}, true } },
    staleAfterOneTick);
  LocalContactModel& old = stale.contactModelToFill(1);
  old.time = -10.0;
  old.count = 0;
  old.add(LocalContact{ Vector3::Zero(), Vector3::UnitZ(), 1.0, 100.0 });
  stale.publishContactModel(1);
  const int before = hd.forceCount("Right Device");
  system.start(stale);
  hd.tick(3);
  for (int i = before; i < before + 3; ++i)
  {
    EXPECT_EQ(hd.force("Right Device", i), Vector3::Zero()) << "tick " << i - before;
  }
}
