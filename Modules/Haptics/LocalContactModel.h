// The local contact model (DESIGN.md: haptics): what the physics thread
// publishes for the 1 kHz servo loop after each step -- the instrument's
// contacts as points on the instrument, normals, depths and stiffnesses at
// the published instrument pose. Between physics steps the servo moves the
// contact points with the instrument and renders the springs linearised
// about that pose, so the force stays smooth at 1 kHz when physics runs at
// 50-100 Hz (thesis 6.3: haptic rendering needs 1 kHz).
#ifndef LocalContactModel_h
#define LocalContactModel_h

#include "RigidTool.h"
#include "ThinTissueHapticsModule.h"

#include <array>
#include <limits>

namespace thintissue
{

class CollisionScene;

struct LocalContact
{
  /// On the instrument, in its frame.
  Vector3 toolPoint = Vector3::Zero();
  /// Unit, world: the direction the contact pushes the instrument.
  Vector3 normal = Vector3::UnitZ();
  /// Overlap at the published pose (> 0 touching).
  double depth = 0.0;
  /// Newtons per unit depth.
  double stiffness = 0.0;
};

struct THINTISSUEHAPTICS_EXPORT LocalContactModel
{
  static constexpr int MaximumContacts = 256;
  /// Seconds (the servo's clock) when it was published; -infinity: never.
  double time = -std::numeric_limits<double>::infinity();
  /// Counts publications (set by HapticServo::publishContactModel).
  unsigned long sequence = 0;
  RigidPose toolPose;
  std::array<LocalContact, MaximumContacts> contacts{};
  int count = 0;

  /// The force on the instrument at `pose`: each contact point moved with
  /// the instrument, its depth changed by the motion along its normal,
  /// k max(depth, 0) along the normal. No allocation.
  Vector3 force(const RigidPose& pose) const;
  /// Appends a contact (ignored beyond MaximumContacts; returns false then).
  bool add(const LocalContact& contact);
};

/// The contacts of tool `tool` in `scene` after a step, as a local model at
/// the tool's current pose, published at `time`. The deepest
/// MaximumContacts are kept.
THINTISSUEHAPTICS_EXPORT void fillLocalContactModel(const CollisionScene& scene,
  const RigidTool& tool,
  int toolIndex,
  double time,
  LocalContactModel& model);

} // namespace thintissue

#endif
