#include "MouseHapticDevice.h"

namespace thintissue
{

MouseHapticDevice::MouseHapticDevice(HapticDeviceInfo info)
  : Info(std::move(info))
  , Forces(Vector3::Zero())
{
}

HapticDeviceState MouseHapticDevice::read(double)
{
  return States.latest();
}

void MouseHapticDevice::writeForce(const Vector3& force)
{
  Forces.back() = force;
  Forces.publish();
}

void MouseHapticDevice::setState(const HapticDeviceState& state)
{
  States.back() = state;
  States.publish();
}

Vector3 MouseHapticDevice::lastForce()
{
  return Forces.latest();
}

} // namespace thintissue
