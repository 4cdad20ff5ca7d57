// A device for users without a Touch: the GUI thread sets the stylus state
// (from mouse and keyboard events, see vtkHapticInteractorStyle) and the
// servo reads the latest one; forces are kept for display only.
#ifndef MouseHapticDevice_h
#define MouseHapticDevice_h

#include "HapticDevice.h"
#include "LatestValue.h"
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

} // namespace thintissue

#endif
