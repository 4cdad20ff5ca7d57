#include "MouseHapticDevice.h"

#include <cmath>

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

ArthroscopeView arthroscopeView(const RigidPose& scope,
  double viewingAngle,
  double focalDistance,
  const Vector3& worldUp)
{
  const double a = viewingAngle * M_PI / 180.0;
  const Vector3 down = -scope.rotation.col(2); // along the shaft, into the joint
  const Vector3 lens = scope.rotation.col(0);  // the side the lens looks to
  const Vector3 direction = std::cos(a) * down + std::sin(a) * lens;
  ArthroscopeView view;
  view.eye = scope.translation;
  view.focalPoint = scope.translation + focalDistance * direction;
  // The camera head stays upright: the image's up is the world's up, as
  // far as the view direction allows.
  const Vector3 up = worldUp - worldUp.dot(direction) * direction;
  view.viewUp = up.norm() > 1e-6 * worldUp.norm()
                  ? Vector3(up.normalized())
                  : Vector3((std::cos(a) * lens - std::sin(a) * down).normalized());
  return view;
}

} // namespace thintissue
