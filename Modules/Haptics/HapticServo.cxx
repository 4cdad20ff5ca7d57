#include "HapticServo.h"

#include "ThinTissueError.h"

namespace thintissue
{

struct HapticServo::SlotState
{
  PortalMapping portal;
  ForceSafety safety;
  LatestValue<LocalContactModel> models;
  LatestValue<HapticToolState> tools;
  unsigned long ticks = 0;
  unsigned long published = 0; ///< producer's count
  unsigned long lastSequence = 0;
  double firstRendered = -1.0;
};

HapticServo::HapticServo(const std::vector<HapticSlot>& slots, const ForceSafetySettings& safety)
  : Slots(slots)
{
  checkForceSafetySettings(safety);
  for (std::size_t s = 0; s < slots.size(); ++s)
  {
    if (slots[s].device == nullptr)
    {
      throw InvalidInputError("haptic servo: slot " + std::to_string(s) + " has no device");
    }
    auto state = std::make_unique<SlotState>();
    state->portal = PortalMapping(slots[s].portal);
    state->safety = ForceSafety(safety, slots[s].device->info().nominalContinuousForce);
    States.push_back(std::move(state));
  }
}

HapticServo::~HapticServo() = default;

void HapticServo::tick(double time)
{
  for (std::size_t s = 0; s < Slots.size(); ++s)
  {
    SlotState& state = *States[s];
    HapticDevice& device = *Slots[s].device;
    HapticToolState& out = state.tools.back();
    out.time = time;
    out.tick = ++state.ticks;
    out.stylus = device.read(time);
    out.pose = state.portal.instrumentPose(out.stylus);
    const LocalContactModel& model = state.models.latest();
    if (model.sequence != state.lastSequence)
    {
      state.lastSequence = model.sequence;
      state.firstRendered = time;
    }
    // An uncalibrated stylus's pose is wrong: no force from it.
    const bool feel = Slots[s].forceFeedback && out.stylus.calibrated;
    const Vector3 world = feel ? model.force(out.pose) : Vector3::Zero();
    out.force = state.safety.apply(state.portal.deviceForce(world), time, time - model.time);
    out.modelSequence = model.sequence;
    out.modelFirstRendered = state.firstRendered;
    device.writeForce(out.force);
    state.tools.publish();
  }
}

LocalContactModel& HapticServo::contactModelToFill(std::size_t slot)
{
  return States.at(slot)->models.back();
}

void HapticServo::publishContactModel(std::size_t slot)
{
  SlotState& state = *States.at(slot);
  state.models.back().sequence = ++state.published;
  state.models.publish();
}

const HapticToolState& HapticServo::latestToolState(std::size_t slot)
{
  return States.at(slot)->tools.latest();
}

void HapticServo::enable(std::size_t slot, double time)
{
  States.at(slot)->safety.enable(time);
}

} // namespace thintissue
