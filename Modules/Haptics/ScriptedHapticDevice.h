// Recorded stylus trajectories: a device that replays one (tests,
// benchmarks, image baselines, replays of a training session) and a device
// wrapper that records one from any other backend. Files are JSON
// ({"name": ..., "samples": [{"t", "position", "orientation" (quaternion
// w x y z), "buttons"}]}) with doubles written exactly, so a round trip
// gives the same trajectory bit for bit.
#ifndef ScriptedHapticDevice_h
#define ScriptedHapticDevice_h

#include "HapticDevice.h"
#include "ThinTissueHapticsModule.h"

#include <string>
#include <vector>

namespace thintissue
{

struct HapticSample
{
  double time = 0.0; ///< seconds
  Vector3 position = Vector3::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  unsigned buttons = 0;
  bool operator==(const HapticSample& o) const
  {
    return time == o.time && position == o.position &&
           orientation.coeffs() == o.orientation.coeffs() && buttons == o.buttons;
  }
};

struct HapticTrajectory
{
  std::string name = "scripted";
  std::vector<HapticSample> samples; ///< increasing times
};

/// Throws FileError naming the path when it cannot be written / read, and
/// InvalidInputError naming it when the content is not a trajectory
/// (missing fields, times not increasing, non-finite values).
THINTISSUEHAPTICS_EXPORT void writeHapticTrajectory(const std::string& path,
  const HapticTrajectory& trajectory);
THINTISSUEHAPTICS_EXPORT HapticTrajectory readHapticTrajectory(const std::string& path);
/// The same as text (one JSON object), for files that hold trajectories
/// among other things; `source` names the text in messages.
THINTISSUEHAPTICS_EXPORT std::string hapticTrajectoryText(const HapticTrajectory& trajectory);
THINTISSUEHAPTICS_EXPORT HapticTrajectory parseHapticTrajectory(const std::string& text,
  const std::string& source);

/// Replays a trajectory: position interpolated linearly and orientation
/// spherically between samples, buttons of the last sample at or before
/// the time, velocity of the segment; held at the ends. Records the forces
/// written (room for `forceCapacity` of them, kept from the start).
class THINTISSUEHAPTICS_EXPORT ScriptedHapticDevice : public HapticDevice
{
public:
  /// Throws InvalidInputError on an empty trajectory or times that do not
  /// increase.
  explicit ScriptedHapticDevice(HapticTrajectory trajectory,
    HapticDeviceInfo info = {},
    std::size_t forceCapacity = 1 << 16);
  const HapticDeviceInfo& info() const override { return Info; }
  HapticDeviceState read(double time) override;
  void writeForce(const Vector3& force) override;

  const std::vector<Vector3>& forces() const { return Forces; }
  const HapticTrajectory& trajectory() const { return Trajectory; }

private:
  HapticTrajectory Trajectory;
  HapticDeviceInfo Info;
  std::vector<Vector3> Forces;
  std::size_t Cursor = 0; ///< segment of the last read (reads go forward)
};

/// Wraps a device and records what it reads (room for `capacity` samples,
/// reserved up front; further samples are not recorded). What it returns is
/// what a replay of the recording returns at the same times (orientation
/// through the stored unit quaternion, no velocity), so a lock-step run and
/// its replay agree bit for bit.
class THINTISSUEHAPTICS_EXPORT RecordingHapticDevice : public HapticDevice
{
public:
  RecordingHapticDevice(HapticDevice& device, std::size_t capacity);
  const HapticDeviceInfo& info() const override { return Device.info(); }
  HapticDeviceState read(double time) override;
  void writeForce(const Vector3& force) override { Device.writeForce(force); }
  /// The recording (named after the device).
  HapticTrajectory trajectory() const;

private:
  HapticDevice& Device;
  std::vector<HapticSample> Samples;
};

} // namespace thintissue

#endif
