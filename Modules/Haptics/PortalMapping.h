// From a stylus in its device frame to an instrument through a portal
// (thesis 4.1: the arthroscope and the instrument enter the knee through two
// small incisions). Fulcrum constraint: the tip follows the stylus tip
// (scaled, from the device frame to the world), and the shaft runs from the
// tip through the portal point, so that whatever the stylus does the
// instrument pivots about the portal; the insertion depth is the tip's
// distance to the portal and the rotation about the shaft follows the
// stylus's roll.
//
// The pose returned is in the instruments' frame (SurgicalInstruments.h):
// tip at the origin, +z along the shaft toward the handle (through the
// portal), +x the working side ("up").
#ifndef PortalMapping_h
#define PortalMapping_h

#include "HapticDevice.h"
#include "RigidTool.h"
#include "ThinTissueHapticsModule.h"

namespace thintissue
{

struct PortalSettings
{
  /// The fulcrum (world, mm) and the direction from it into the joint.
  Vector3 portal = Vector3::Zero();
  Vector3 inward = -Vector3::UnitZ();
  /// Device frame to world: rotation and scale (world mm per device mm).
  Eigen::Matrix3d deviceToWorld = Eigen::Matrix3d::Identity();
  double scale = 1.0;
  /// The device position whose tip lies `restInsertion` mm in along
  /// `inward` (the stylus at rest in its inkwell, say).
  Vector3 deviceCentre = Vector3::Zero();
  double restInsertion = 20.0;
  /// The tip never comes nearer the portal than this (mm).
  double minimumInsertion = 2.0;
  /// The stylus axis that gives the instrument's working side (+x).
  Vector3 stylusUp = Vector3::UnitY();
  /// Newtons on the stylus per newton on the instrument.
  double forceScale = 1.0;
};

/// Throws InvalidInputError naming the setting on a non-finite value, a
/// zero direction, a rotation that is not one, or a scale not positive.
THINTISSUEHAPTICS_EXPORT void checkPortalSettings(const PortalSettings& settings);

class THINTISSUEHAPTICS_EXPORT PortalMapping
{
public:
  PortalMapping() = default;
  explicit PortalMapping(const PortalSettings& settings);

  /// The instrument pose for a stylus state.
  RigidPose instrumentPose(const HapticDeviceState& stylus) const;
  /// A world force on the instrument as the stylus should render it
  /// (device frame).
  Vector3 deviceForce(const Vector3& worldForce) const;
  /// The inverse, for recordings made from key frames: the stylus position
  /// that puts `toolPoint` (tool frame) at `target` (world) with the stylus
  /// held at `stylusOrientation` (fixed-point iteration on instrumentPose;
  /// converges for points near the tip, a few mm, beyond the minimum
  /// insertion).
  Vector3 stylusPositionPlacing(const Vector3& toolPoint,
    const Vector3& target,
    const Eigen::Matrix3d& stylusOrientation = Eigen::Matrix3d::Identity()) const;
  /// Where the stylus tip maps before the fulcrum (world).
  Vector3 mappedTip(const Vector3& devicePosition) const;

  const PortalSettings& settings() const { return Settings; }

private:
  PortalSettings Settings;
  Vector3 Inward = -Vector3::UnitZ();
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
