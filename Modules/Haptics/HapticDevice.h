// A haptic device as the servo loop sees it (thesis 4.1: two Touch styluses,
// one for the arthroscope, one for the instrument): its state each tick in
// its own frame (millimetres, seconds), the force it should output (newtons),
// and what it can do. Backends: OpenHapticsSystem (HD API loaded at run
// time), ScriptedHapticDevice (recorded trajectories), and the mouse and
// keyboard in the VTK layer.
#ifndef HapticDevice_h
#define HapticDevice_h

#include "ThinTissueHapticsModule.h"
#include "TriangleMesh.h"

#include <Eigen/Geometry>

#include <string>

namespace thintissue
{

/// The stylus at one tick, in the device frame.
struct HapticDeviceState
{
  /// Stylus tip position (mm) and orientation (columns: the stylus frame's
  /// axes in the device frame).
  Vector3 position = Vector3::Zero();
  Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();
  /// mm/s.
  Vector3 velocity = Vector3::Zero();
  /// Bit 0 and bit 1: the stylus's two buttons.
  unsigned buttons = 0;
  bool calibrated = true;
};

struct HapticDeviceInfo
{
  std::string name = "Default Device";
  /// Newtons. Defaults: the Touch's nominal figures.
  double nominalContinuousForce = 0.88;
  double peakForce = 3.3;
  /// Usable workspace in the device frame (mm).
  BoundingBox workspace = BoundingBox(Vector3(-80.0, -60.0, -35.0), Vector3(80.0, 60.0, 35.0));
};

/// Every call but info() comes from the servo thread, once per tick per
/// device; implementations neither lock nor allocate there.
class THINTISSUEHAPTICS_EXPORT HapticDevice
{
public:
  virtual ~HapticDevice();
  virtual const HapticDeviceInfo& info() const = 0;
  /// The state at `time` (seconds since the servo started).
  virtual HapticDeviceState read(double time) = 0;
  /// The force (N, device frame) to output until the next tick.
  virtual void writeForce(const Vector3& force) = 0;
};

} // namespace thintissue

#endif
