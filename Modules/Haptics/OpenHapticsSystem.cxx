#include "OpenHapticsSystem.h"

#include "HapticServo.h"

#include <dlfcn.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>

namespace thintissue
{

namespace
{

// HD API types and values (TOOLCHAIN.md: OpenHaptics HD API).
using HHD = unsigned int;
using HDenum = unsigned int;
using HDerror = unsigned int;
using HDCallbackCode = unsigned int;
using HDSchedulerHandle = unsigned long;
struct HDErrorInfo
{
  HDerror errorCode;
  int internalErrorCode;
  HHD hHD;
};
using HDSchedulerCallback = HDCallbackCode (*)(void*);

constexpr HHD InvalidHandle = 0xFFFFFFFFu;
constexpr HDenum CurrentButtons = 0x2000;
constexpr HDenum CurrentVelocity = 0x2051;
constexpr HDenum CurrentTransform = 0x2052;
constexpr HDenum UsableWorkspace = 0x2551;
constexpr HDenum NominalMaxForce = 0x2603;
constexpr HDenum NominalMaxContinuousForce = 0x2604;
constexpr HDenum CurrentForce = 0x2700;
constexpr HDenum ForceOutput = 0x4000;
constexpr HDenum CalibrationOk = 0x5000;
constexpr HDCallbackCode CallbackDone = 0;
constexpr HDCallbackCode CallbackContinue = 1;
constexpr unsigned short DefaultPriority = 32767;

std::string hex(unsigned value)
{
  char text[16];
  std::snprintf(text, sizeof text, "0x%X", value);
  return text;
}

} // namespace

HapticDeviceError::HapticDeviceError(const std::string& message)
  : Error(message)
{
}

/// The HD functions, resolved from the loaded library.
struct OpenHapticsSystem::Library
{
  void* handle = nullptr;
  std::string path;
  HHD (*initDevice)(const char*) = nullptr;
  void (*disableDevice)(HHD) = nullptr;
  void (*makeCurrentDevice)(HHD) = nullptr;
  void (*beginFrame)(HHD) = nullptr;
  void (*endFrame)(HHD) = nullptr;
  void (*getDoublev)(HDenum, double*) = nullptr;
  void (*getIntegerv)(HDenum, int*) = nullptr;
  void (*setDoublev)(HDenum, const double*) = nullptr;
  void (*enable)(HDenum) = nullptr;
  HDErrorInfo (*getError)() = nullptr;
  const char* (*getErrorString)(HDerror) = nullptr;
  void (*startScheduler)() = nullptr;
  void (*stopScheduler)() = nullptr;
  HDSchedulerHandle (*scheduleAsynchronous)(HDSchedulerCallback, void*, unsigned short) = nullptr;
  void (*unschedule)(HDSchedulerHandle) = nullptr;
  HDenum (*checkCalibration)() = nullptr;

  explicit Library(const std::string& library)
    : path(library)
  {
    handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr)
    {
      const char* why = dlerror();
      throw HapticDeviceError("OpenHaptics: cannot load the HD library '" + library + "' (" +
                              (why ? why : "unknown reason") +
                              "); is the OpenHaptics runtime installed?");
    }
    resolve(initDevice, "hdInitDevice");
    resolve(disableDevice, "hdDisableDevice");
    resolve(makeCurrentDevice, "hdMakeCurrentDevice");
    resolve(beginFrame, "hdBeginFrame");
    resolve(endFrame, "hdEndFrame");
    resolve(getDoublev, "hdGetDoublev");
    resolve(getIntegerv, "hdGetIntegerv");
    resolve(setDoublev, "hdSetDoublev");
    resolve(enable, "hdEnable");
    resolve(getError, "hdGetError");
    resolve(getErrorString, "hdGetErrorString");
    resolve(startScheduler, "hdStartScheduler");
    resolve(stopScheduler, "hdStopScheduler");
    resolve(scheduleAsynchronous, "hdScheduleAsynchronous");
    resolve(unschedule, "hdUnschedule");
    resolve(checkCalibration, "hdCheckCalibration");
  }
  ~Library()
  {
    if (handle != nullptr)
    {
      dlclose(handle);
    }
  }
  Library(const Library&) = delete;
  Library& operator=(const Library&) = delete;

  template <typename Function>
  void resolve(Function& function, const char* name)
  {
    void* symbol = dlsym(handle, name);
    if (symbol == nullptr)
    {
      dlclose(handle);
      handle = nullptr;
      throw HapticDeviceError("OpenHaptics: the HD library '" + path + "' has no function " + name);
    }
    function = reinterpret_cast<Function>(symbol);
  }

  /// "HD error 0x201 (<HD's text>)".
  std::string describe(HDerror code) const
  {
    const char* text = getErrorString(code);
    return "HD error " + hex(code) + (text ? std::string(" (") + text + ")" : std::string());
  }
};

/// One Touch: the HapticDevice the servo reads and writes. Its calls run
/// on the scheduler thread, inside the frame of that device.
struct OpenHapticsSystem::DeviceSlot : HapticDevice
{
  Library* hd = nullptr;
  HHD handle = InvalidHandle;
  HapticDeviceInfo information;
  bool calibrated = true;
  /// First error of a frame on the scheduler thread (0: none).
  std::atomic<HDerror> error{ 0 };

  const HapticDeviceInfo& info() const override { return information; }

  HapticDeviceState read(double) override
  {
    hd->beginFrame(handle);
    std::array<double, 16> m{};
    hd->getDoublev(CurrentTransform, m.data());
    HapticDeviceState state;
    for (int c = 0; c < 3; ++c)
    {
      state.orientation.col(c) = Vector3(m[4 * c], m[4 * c + 1], m[4 * c + 2]);
    }
    state.position = Vector3(m[12], m[13], m[14]);
    hd->getDoublev(CurrentVelocity, state.velocity.data());
    int buttons = 0;
    hd->getIntegerv(CurrentButtons, &buttons);
    state.buttons = static_cast<unsigned>(buttons);
    state.calibrated = calibrated;
    noteError();
    return state;
  }

  void writeForce(const Vector3& force) override
  {
    hd->makeCurrentDevice(handle);
    hd->setDoublev(CurrentForce, force.data());
    hd->endFrame(handle);
    noteError();
  }

  void noteError()
  {
    const HDErrorInfo e = hd->getError();
    HDerror none = 0;
    if (e.errorCode != 0)
    {
      error.compare_exchange_strong(none, e.errorCode);
    }
  }
};

struct OpenHapticsSystem::Scheduling
{
  OpenHapticsSystem* system = nullptr;
  HapticServo* servo = nullptr;
  HDSchedulerHandle callback = 0;
  bool scheduled = false;
  std::atomic<bool> stopping{ false };
  std::chrono::steady_clock::time_point start;

  static HDCallbackCode tick(void* data)
  {
    auto* s = static_cast<Scheduling*>(data);
    if (s->stopping.load(std::memory_order_relaxed))
    {
      return CallbackDone;
    }
    s->servo->tick(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - s->start).count());
    for (const auto& device : s->system->Devices)
    {
      if (device->error.load(std::memory_order_relaxed) != 0)
      {
        return CallbackDone; // e.g. an over-force shut-down: no more frames
      }
    }
    return CallbackContinue;
  }
};

OpenHapticsSystem::OpenHapticsSystem(const OpenHapticsSettings& settings)
  : Hd(std::make_unique<Library>(settings.library))
  , Scheduler(std::make_unique<Scheduling>())
{
  Scheduler->system = this;
  try
  {
    open(settings);
  }
  catch (...)
  {
    closeAll();
    throw;
  }
}

OpenHapticsSystem::~OpenHapticsSystem()
{
  stop();
  closeAll();
}

void OpenHapticsSystem::open(const OpenHapticsSettings& settings)
{
  if (settings.deviceNames.empty())
  {
    throw HapticDeviceError("OpenHaptics: no device name given");
  }
  for (const std::string& name : settings.deviceNames)
  {
    auto slot = std::make_unique<DeviceSlot>();
    slot->hd = Hd.get();
    slot->information.name = name;
    slot->handle = Hd->initDevice(name == "Default Device" ? nullptr : name.c_str());
    const HDErrorInfo e = Hd->getError();
    if (slot->handle == InvalidHandle || e.errorCode != 0)
    {
      throw HapticDeviceError("OpenHaptics: haptic device '" + name +
                              "' not found or not usable (" + Hd->describe(e.errorCode) +
                              "); check its name in the Touch setup and its cable");
    }
    Devices.push_back(std::move(slot));
    DeviceSlot& device = *Devices.back();
    Hd->makeCurrentDevice(device.handle);
    Hd->enable(ForceOutput);
    Hd->getDoublev(NominalMaxContinuousForce, &device.information.nominalContinuousForce);
    Hd->getDoublev(NominalMaxForce, &device.information.peakForce);
    std::array<double, 6> workspace{};
    Hd->getDoublev(UsableWorkspace, workspace.data());
    device.information.workspace = BoundingBox(Vector3(workspace[0], workspace[1], workspace[2]),
      Vector3(workspace[3], workspace[4], workspace[5]));
    device.calibrated = Hd->checkCalibration() == CalibrationOk;
    const HDErrorInfo after = Hd->getError();
    if (after.errorCode != 0)
    {
      throw HapticDeviceError("OpenHaptics: haptic device '" + name +
                              "' failed while being set up (" + Hd->describe(after.errorCode) +
                              ")");
    }
  }
}

void OpenHapticsSystem::closeAll()
{
  for (const auto& device : Devices)
  {
    Hd->disableDevice(device->handle);
  }
  Devices.clear();
}

std::size_t OpenHapticsSystem::deviceCount() const
{
  return Devices.size();
}

HapticDevice& OpenHapticsSystem::device(std::size_t index)
{
  return *Devices.at(index);
}

void OpenHapticsSystem::start(HapticServo& servo)
{
  if (Scheduler->scheduled)
  {
    throw HapticDeviceError("OpenHaptics: the scheduler is already running");
  }
  Scheduler->servo = &servo;
  Scheduler->stopping = false;
  Scheduler->start = std::chrono::steady_clock::now();
  Scheduler->callback =
    Hd->scheduleAsynchronous(&Scheduling::tick, Scheduler.get(), DefaultPriority);
  Hd->startScheduler();
  Scheduler->scheduled = true;
  const HDErrorInfo e = Hd->getError();
  if (e.errorCode != 0)
  {
    stop();
    throw HapticDeviceError(
      "OpenHaptics: the scheduler failed to start (" + Hd->describe(e.errorCode) + ")");
  }
}

void OpenHapticsSystem::stop()
{
  if (!Scheduler->scheduled)
  {
    return;
  }
  Scheduler->stopping = true;
  Hd->stopScheduler();
  Hd->unschedule(Scheduler->callback);
  Scheduler->scheduled = false;
}

bool OpenHapticsSystem::running() const
{
  return Scheduler->scheduled;
}

std::vector<std::string> OpenHapticsSystem::errors() const
{
  std::vector<std::string> messages;
  for (const auto& device : Devices)
  {
    const std::string name = "haptic device '" + device->information.name + "'";
    if (!device->calibrated)
    {
      messages.push_back(name + " is not calibrated: put the stylus in its inkwell (forces off)");
    }
    const HDerror code = device->error.load();
    if (code >= 0x200 && code < 0x300)
    {
      messages.push_back(
        name + ": over-force shut-down, forces stopped (" + Hd->describe(code) + ")");
    }
    else if (code != 0)
    {
      messages.push_back(name + ": " + Hd->describe(code) + ", forces stopped");
    }
  }
  return messages;
}

} // namespace thintissue
