// The OpenHaptics (HD API) backend for 3D Systems Touch devices, loaded at
// run time: the HD library is dlopen()ed (the SDK is no Debian package, so
// the build never needs it). Both devices are opened by their configured
// names before the one scheduler starts; its 1 kHz callback ticks the
// HapticServo, whose reads and writes run hdBeginFrame / hdEndFrame on each
// device: read HD_CURRENT_TRANSFORM, HD_CURRENT_VELOCITY, HD_CURRENT_BUTTONS,
// write HD_CURRENT_FORCE. HD errors become messages that name the device
// and the problem. Values and calls: TOOLCHAIN.md (OpenHaptics HD API).
#ifndef OpenHapticsSystem_h
#define OpenHapticsSystem_h

#include "HapticDevice.h"
#include "ThinTissueError.h"
#include "ThinTissueHapticsModule.h"

#include <memory>
#include <string>
#include <vector>

namespace thintissue
{

class HapticServo;

/// An HD failure: the device and the problem in the message.
class THINTISSUEHAPTICS_EXPORT HapticDeviceError : public Error
{
public:
  explicit HapticDeviceError(const std::string& message);
};

struct OpenHapticsSettings
{
  /// The HD library: a file name (searched as dlopen does) or a path.
  std::string library = "libHD.so";
  /// Device names as configured in the Touch setup; "Default Device" opens
  /// the default device.
  std::vector<std::string> deviceNames{ "Default Device" };
};

class THINTISSUEHAPTICS_EXPORT OpenHapticsSystem
{
public:
  /// Loads the library, opens every device (force output enabled) and
  /// reads its nominal forces and workspace. Throws HapticDeviceError: the
  /// library or one of its functions missing, a device not found (named),
  /// an HD error. Devices opened before a failure are closed again.
  explicit OpenHapticsSystem(const OpenHapticsSettings& settings);
  /// Stops the scheduler and closes the devices; no HD call after that.
  ~OpenHapticsSystem();
  OpenHapticsSystem(const OpenHapticsSystem&) = delete;
  OpenHapticsSystem& operator=(const OpenHapticsSystem&) = delete;

  std::size_t deviceCount() const;
  /// The devices, in the order of the settings' names, for HapticSlots.
  HapticDevice& device(std::size_t index);

  /// Schedules the servo's tick on the HD scheduler and starts it. Throws
  /// HapticDeviceError when the scheduler fails.
  void start(HapticServo& servo);
  /// Stops the scheduler (the callback does not run after this returns).
  void stop();
  bool running() const;

  /// Errors the callback met (e.g. an over-force shut-down, which stops
  /// the scheduler's callback), one message each; empty if none. Call from
  /// any thread but the servo's.
  std::vector<std::string> errors() const;

  struct Library;
  struct DeviceSlot;

private:
  void open(const OpenHapticsSettings& settings);
  void closeAll();

  std::unique_ptr<Library> Hd;
  std::vector<std::unique_ptr<DeviceSlot>> Devices;
  struct Scheduling;
  std::unique_ptr<Scheduling> Scheduler;
};

} // namespace thintissue

#endif
