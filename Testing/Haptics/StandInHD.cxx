// A stand-in for the OpenHaptics HD library: the same C functions, on
// devices configured by the test, recording every call, with errors
// injected on request and the scheduler stepped by the test (standin_tick),
// so that the run-time-loaded backend runs on every machine,
// deterministically. Not a model of a Touch: only what the backend uses.
#include <array>
#include <cstring>
#include <string>
#include <vector>

namespace
{

struct Device
{
  std::string name;
  bool calibrated = true;
  double maxContinuous = 0.88;
  double peak = 3.3;
  std::array<double, 16> transform{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  std::array<double, 3> velocity{};
  int buttons = 0;
  bool open = false;
  bool forceOutput = false;
  bool inFrame = false;
  std::vector<std::array<double, 3>> forces;
};

struct Scheduled
{
  unsigned (*callback)(void*);
  void* data;
  unsigned long handle;
  bool active;
};

struct StandIn
{
  std::vector<Device> devices;
  std::vector<std::string> log;
  std::string failCall;
  unsigned failError = 0;
  unsigned pendingError = 0;
  int current = -1;
  bool started = false;
  std::vector<Scheduled> scheduled;
  unsigned long nextHandle = 1;
};

StandIn& state()
{
  static StandIn s;
  return s;
}

/// Logs the call; true if it is the one to fail (its error becomes pending).
bool call(const std::string& entry, const char* name)
{
  StandIn& s = state();
  s.log.push_back(entry);
  if (!s.failCall.empty() && s.failCall == name)
  {
    s.pendingError = s.failError;
    s.failCall.clear();
    return true;
  }
  return false;
}

Device* currentDevice()
{
  StandIn& s = state();
  return s.current >= 0 && s.current < static_cast<int>(s.devices.size()) ? &s.devices[s.current]
                                                                          : nullptr;
}

Device* named(const char* name)
{
  for (Device& d : state().devices)
  {
    if (d.name == name)
    {
      return &d;
    }
  }
  return nullptr;
}

} // namespace

extern "C"
{
  struct HDErrorInfo
  {
    unsigned errorCode;
    int internalErrorCode;
    unsigned hHD;
  };

  // --- Test controls ---------------------------------------------------------
  void standin_reset()
  {
    state() = StandIn{};
  }
  void standin_add_device(const char* name, int calibrated, double maxContinuous, double peak)
  {
    Device d;
    d.name = name;
    d.calibrated = calibrated != 0;
    d.maxContinuous = maxContinuous;
    d.peak = peak;
    state().devices.push_back(d);
  }
  void standin_set_stylus(const char* name, const double* transform16, int buttons)
  {
    if (Device* d = named(name))
    {
      std::memcpy(d->transform.data(), transform16, 16 * sizeof(double));
      d->buttons = buttons;
    }
  }
  /// The next call of function `name` fails with `error`.
  void standin_fail_next(const char* name, unsigned error)
  {
    state().failCall = name;
    state().failError = error;
  }
  /// Runs the scheduled callbacks `ticks` times (while started); returns
  /// how many are still scheduled and active.
  int standin_tick(int ticks)
  {
    StandIn& s = state();
    for (int t = 0; t < ticks && s.started; ++t)
    {
      for (Scheduled& c : s.scheduled)
      {
        if (c.active && c.callback(c.data) == 0)
        {
          c.active = false;
        }
      }
    }
    int active = 0;
    for (const Scheduled& c : s.scheduled)
    {
      active += c.active ? 1 : 0;
    }
    return active;
  }
  int standin_force_count(const char* name)
  {
    const Device* d = named(name);
    return d ? static_cast<int>(d->forces.size()) : -1;
  }
  void standin_force(const char* name, int index, double* out)
  {
    const Device* d = named(name);
    std::memcpy(out, d->forces.at(static_cast<std::size_t>(index)).data(), 3 * sizeof(double));
  }
  int standin_log_size()
  {
    return static_cast<int>(state().log.size());
  }
  const char* standin_log_entry(int i)
  {
    return state().log.at(static_cast<std::size_t>(i)).c_str();
  }

  // --- HD API ------------------------------------------------------------------
  unsigned hdInitDevice(const char* name)
  {
    const std::string wanted = name ? name : "Default Device";
    if (call("hdInitDevice " + wanted, "hdInitDevice"))
    {
      return 0xFFFFFFFFu;
    }
    StandIn& s = state();
    for (std::size_t i = 0; i < s.devices.size(); ++i)
    {
      if (s.devices[i].name == wanted && !s.devices[i].open)
      {
        s.devices[i].open = true;
        s.current = static_cast<int>(i);
        return static_cast<unsigned>(i);
      }
    }
    s.pendingError = 0x300; // HD_DEVICE_FAULT
    return 0xFFFFFFFFu;
  }
  void hdDisableDevice(unsigned h)
  {
    call("hdDisableDevice " + std::to_string(h), "hdDisableDevice");
    if (h < state().devices.size())
    {
      state().devices[h].open = false;
    }
  }
  void hdMakeCurrentDevice(unsigned h)
  {
    call("hdMakeCurrentDevice " + std::to_string(h), "hdMakeCurrentDevice");
    state().current = static_cast<int>(h);
  }
  void hdBeginFrame(unsigned h)
  {
    call("hdBeginFrame " + std::to_string(h), "hdBeginFrame");
    state().current = static_cast<int>(h);
    if (Device* d = currentDevice())
    {
      d->inFrame = true;
    }
  }
  void hdEndFrame(unsigned h)
  {
    call("hdEndFrame " + std::to_string(h), "hdEndFrame");
    if (h < state().devices.size())
    {
      state().devices[h].inFrame = false;
    }
  }
  void hdGetDoublev(unsigned what, double* out)
  {
    call("hdGetDoublev " + std::to_string(what), "hdGetDoublev");
    const Device* d = currentDevice();
    if (!d)
    {
      state().pendingError = 0x104; // HD_BAD_HANDLE
      return;
    }
    switch (what)
    {
      case 0x2052:
        std::memcpy(out, d->transform.data(), 16 * sizeof(double));
        break;
      case 0x2051:
        std::memcpy(out, d->velocity.data(), 3 * sizeof(double));
        break;
      case 0x2604:
        *out = d->maxContinuous;
        break;
      case 0x2603:
        *out = d->peak;
        break;
      case 0x2551:
      {
        const double box[6] = { -80, -60, -35, 80, 60, 35 };
        std::memcpy(out, box, sizeof box);
        break;
      }
      default:
        state().pendingError = 0x100; // HD_INVALID_ENUM
    }
  }
  void hdGetIntegerv(unsigned what, int* out)
  {
    call("hdGetIntegerv " + std::to_string(what), "hdGetIntegerv");
    const Device* d = currentDevice();
    if (d && what == 0x2000)
    {
      *out = d->buttons;
    }
    else
    {
      state().pendingError = 0x100;
    }
  }
  void hdSetDoublev(unsigned what, const double* value)
  {
    const bool fail = call("hdSetDoublev " + std::to_string(what), "hdSetDoublev");
    Device* d = currentDevice();
    if (fail || !d || what != 0x2700)
    {
      return;
    }
    if (!d->inFrame)
    {
      state().log.push_back("misuse: force set outside a frame");
    }
    d->forces.push_back({ value[0], value[1], value[2] });
  }
  void hdEnable(unsigned what)
  {
    call("hdEnable " + std::to_string(what), "hdEnable");
    if (Device* d = currentDevice(); d && what == 0x4000)
    {
      d->forceOutput = true;
    }
  }
  HDErrorInfo hdGetError()
  {
    StandIn& s = state();
    HDErrorInfo e{ s.pendingError, 0, static_cast<unsigned>(s.current) };
    s.pendingError = 0;
    return e;
  }
  const char* hdGetErrorString(unsigned code)
  {
    switch (code)
    {
      case 0x201:
        return "Exceeded max force";
      case 0x300:
        return "Device fault";
      case 0x304:
        return "Timer error";
      default:
        return "HD error";
    }
  }
  void hdStartScheduler()
  {
    if (!call("hdStartScheduler", "hdStartScheduler"))
    {
      state().started = true;
    }
  }
  void hdStopScheduler()
  {
    call("hdStopScheduler", "hdStopScheduler");
    state().started = false;
  }
  unsigned long hdScheduleAsynchronous(unsigned (*callback)(void*), void* data, unsigned short)
  {
    call("hdScheduleAsynchronous", "hdScheduleAsynchronous");
    StandIn& s = state();
    s.scheduled.push_back(Scheduled{ callback, data, s.nextHandle, true });
    return s.nextHandle++;
  }
  void hdUnschedule(unsigned long handle)
  {
    call("hdUnschedule " + std::to_string(handle), "hdUnschedule");
    for (Scheduled& c : state().scheduled)
    {
      c.active = c.active && c.handle != handle;
    }
  }
  unsigned hdCheckCalibration()
  {
    call("hdCheckCalibration", "hdCheckCalibration");
    const Device* d = currentDevice();
    return d && d->calibrated ? 0x5000u : 0x5001u;
  }
}
