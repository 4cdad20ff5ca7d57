// The simulator window's devices from two Touch styluses of an
// OpenHapticsSystem (the HD library loaded at run time): the HD scheduler
// ticks each scene's servo (started and stopped with the scene), and the
// system's problems (not calibrated, over-force shut-down, ...) show with
// the device status.
#ifndef TouchDevices_h
#define TouchDevices_h

#include "OpenHapticsSystem.h"
#include "SimulatorWindow.h"

#include <string>

namespace thintissue
{

inline WindowDevices touchWindowDevices(OpenHapticsSystem& touch, const std::string& description)
{
  WindowDevices devices;
  devices.description = description;
  OpenHapticsSystem* system = &touch;
  devices.startServo = [system](HapticServo& servo) { system->start(servo); };
  devices.stopServo = [system] { system->stop(); };
  devices.problems = [system] { return system->errors(); };
  return devices;
}

} // namespace thintissue

#endif
