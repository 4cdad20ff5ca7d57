// A device for users without a Touch: the GUI thread sets the stylus state
// (from mouse and keyboard events, see vtkHapticInteractorStyle) and the
// servo reads the latest one; forces are kept for display only.
#ifndef MouseHapticDevice_h
#define MouseHapticDevice_h

#include "HapticDevice.h"
#include "LatestValue.h"
#include "RigidTool.h"
#include "ThinTissueHapticsModule.h"

#include <atomic>

namespace thintissue
{

class THINTISSUEHAPTICS_EXPORT MouseHapticDevice : public HapticDevice
{
public:
  explicit MouseHapticDevice(HapticDeviceInfo info = {});
  const HapticDeviceInfo& info() const override { return Info; }
  HapticDeviceState read(double time) override;
  void writeForce(const Vector3& force) override;

  /// GUI thread: the stylus from now on.
  void setState(const HapticDeviceState& state);
  /// GUI thread: the last force the servo wanted to render.
  Vector3 lastForce();

private:
  HapticDeviceInfo Info;
  LatestValue<HapticDeviceState> States;
  LatestValue<Vector3> Forces;
};

/// The arthroscope's view from its pose (instrument frame: tip at the
/// origin, +z along the shaft toward the handle, +x the side the lens looks
/// to): the camera at the tip, looking down the shaft turned by
/// `viewingAngle` (degrees; 30 for the usual arthroscope) toward +x, so that
/// rolling the scope sweeps the view around the shaft; the image's up is
/// `worldUp` as far as the view direction allows (the camera head is held
/// upright while the lens turns).
struct ArthroscopeView
{
  Vector3 eye = Vector3::Zero();
  Vector3 focalPoint = -Vector3::UnitZ();
  Vector3 viewUp = Vector3::UnitX();
};

THINTISSUEHAPTICS_EXPORT ArthroscopeView arthroscopeView(const RigidPose& scope,
  double viewingAngle = 30.0,
  double focalDistance = 10.0,
  const Vector3& worldUp = Vector3::UnitZ());

} // namespace thintissue

#endif
