#include "PortalMapping.h"

#include "ThinTissueError.h"

#include <cmath>

namespace thintissue
{

namespace
{

void require(bool ok, const std::string& what)
{
  if (!ok)
  {
    throw InvalidInputError("portal settings: " + what);
  }
}

/// A unit vector perpendicular to unit `z`.
Vector3 anyPerpendicular(const Vector3& z)
{
  const Vector3 other = std::abs(z.x()) < 0.9 ? Vector3::UnitX() : Vector3::UnitY();
  return (other - other.dot(z) * z).normalized();
}

} // namespace

void checkPortalSettings(const PortalSettings& s)
{
  require(s.portal.allFinite(), "the portal point is not finite");
  require(s.inward.allFinite() && s.inward.norm() > 0.0, "the inward direction is zero");
  require(
    s.deviceToWorld.allFinite() &&
      (s.deviceToWorld * s.deviceToWorld.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-6 &&
      s.deviceToWorld.determinant() > 0.0,
    "deviceToWorld is not a rotation");
  require(std::isfinite(s.scale) && s.scale > 0.0, "scale must be positive");
  require(s.deviceCentre.allFinite(), "the device centre is not finite");
  require(
    std::isfinite(s.restInsertion) && s.restInsertion > 0.0, "the rest insertion must be positive");
  require(std::isfinite(s.minimumInsertion) && s.minimumInsertion > 0.0,
    "the minimum insertion must be positive");
  require(s.stylusUp.allFinite() && s.stylusUp.norm() > 0.0, "the stylus up axis is zero");
  require(
    std::isfinite(s.forceScale) && s.forceScale >= 0.0, "the force scale must not be negative");
}

PortalMapping::PortalMapping(const PortalSettings& settings)
  : Settings(settings)
{
  checkPortalSettings(settings);
  Inward = settings.inward.normalized();
}

Vector3 PortalMapping::mappedTip(const Vector3& devicePosition) const
{
  return Settings.portal + Settings.restInsertion * Inward +
         Settings.scale * (Settings.deviceToWorld * (devicePosition - Settings.deviceCentre));
}

RigidPose PortalMapping::instrumentPose(const HapticDeviceState& stylus) const
{
  Vector3 tip = mappedTip(stylus.position);
  Vector3 towardPortal = Settings.portal - tip;
  double depth = towardPortal.norm();
  if (!(depth >= Settings.minimumInsertion))
  {
    // Too near the portal (or on it): keep the minimum insertion, along the
    // stylus's offset if it has one, else straight in.
    const Vector3 out = depth > 0.0 ? Vector3(-towardPortal / depth) : Inward;
    tip = Settings.portal + Settings.minimumInsertion * out;
    towardPortal = Settings.portal - tip;
    depth = Settings.minimumInsertion;
  }
  const Vector3 z = towardPortal / depth;
  const Vector3 up = Settings.deviceToWorld * (stylus.orientation * Settings.stylusUp);
  Vector3 x = up - up.dot(z) * z;
  x = x.norm() > 1e-9 * up.norm() ? Vector3(x.normalized()) : anyPerpendicular(z);
  RigidPose pose;
  pose.rotation.col(0) = x;
  pose.rotation.col(1) = z.cross(x);
  pose.rotation.col(2) = z;
  pose.translation = tip;
  return pose;
}

Vector3 PortalMapping::stylusPositionPlacing(const Vector3& toolPoint,
  const Vector3& target,
  const Eigen::Matrix3d& stylusOrientation) const
{
  HapticDeviceState stylus;
  stylus.orientation = stylusOrientation;
  // The tip moves with the stylus (scaled, turned): step the stylus by the
  // world error brought back to the device frame.
  const Eigen::Matrix3d worldToDevice = Settings.deviceToWorld.transpose() / Settings.scale;
  for (int iteration = 0; iteration < 100; ++iteration)
  {
    const Vector3 error = target - instrumentPose(stylus) * toolPoint;
    stylus.position += worldToDevice * error;
    if (error.norm() < 1e-10 * (1.0 + target.norm()))
      break;
  }
  return stylus.position;
}

Vector3 PortalMapping::deviceForce(const Vector3& worldForce) const
{
  return Settings.forceScale * (Settings.deviceToWorld.transpose() * worldForce);
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
