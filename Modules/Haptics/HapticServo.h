// The servo loop (DESIGN.md: haptics; thesis 6.3): one tick per millisecond
// on its own thread. Each tick, for every device slot: read the stylus,
// map it through its portal to an instrument pose (published for the
// physics and render threads), render the force of the latest local
// contact model (published by the physics thread) at that pose, pass it
// through the safety stage, write it to the device. The exchanges are
// LatestValue triple buffers: the tick never locks and never allocates.
//
// The class is pure: tick(time) is called by whatever clock drives it (the
// OpenHaptics scheduler, ServoThread, or a test).
#ifndef HapticServo_h
#define HapticServo_h

#include "ForceSafety.h"
#include "HapticDevice.h"
#include "LatestValue.h"
#include "LocalContactModel.h"
#include "PortalMapping.h"
#include "ThinTissueHapticsModule.h"

#include <memory>
#include <vector>

namespace thintissue
{

/// One device and the instrument (or arthroscope) it drives.
struct HapticSlot
{
  HapticDevice* device = nullptr; ///< not owned; outlives the servo
  PortalSettings portal;
  /// Off for the arthroscope: it feels nothing.
  bool forceFeedback = true;
};

/// What a tick published for a slot.
struct HapticToolState
{
  double time = -1.0; ///< seconds; < 0 before the first tick
  unsigned long tick = 0;
  HapticDeviceState stylus;
  RigidPose pose;                  ///< the instrument, world
  Vector3 force = Vector3::Zero(); ///< sent to the device (device frame, N)
  /// The contact model sequence the force came from (0: none) and the tick
  /// time it was first rendered at.
  unsigned long modelSequence = 0;
  double modelFirstRendered = -1.0;
};

class THINTISSUEHAPTICS_EXPORT HapticServo
{
public:
  /// Throws InvalidInputError on a slot without device or bad settings.
  HapticServo(const std::vector<HapticSlot>& slots, const ForceSafetySettings& safety = {});
  ~HapticServo();
  HapticServo(const HapticServo&) = delete;
  HapticServo& operator=(const HapticServo&) = delete;

  std::size_t slotCount() const { return Slots.size(); }

  /// Servo thread: one tick at `time` (seconds since start).
  void tick(double time);

  /// Physics thread: the model to fill for `slot`, then publish it. Its
  /// `time` must be on the servo's clock (see latestToolState).
  LocalContactModel& contactModelToFill(std::size_t slot);
  void publishContactModel(std::size_t slot);

  /// Any one other thread: the latest tool state of `slot`.
  const HapticToolState& latestToolState(std::size_t slot);

  /// Servo thread (or before it runs): ramp the slot's force in again.
  void enable(std::size_t slot, double time);

private:
  struct SlotState;
  std::vector<HapticSlot> Slots;
  std::vector<std::unique_ptr<SlotState>> States;
};

} // namespace thintissue

#endif
