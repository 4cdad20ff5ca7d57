// The safety stage every force passes on its way to a device, always on
// (DESIGN.md: haptics): a non-finite force becomes zero; the force ramps in
// at start and after enabling; it fades to zero when the contact model is
// stale (physics stopped publishing); its magnitude is clamped to the
// device's nominal continuous force; its change per tick is rate-limited.
#ifndef ForceSafety_h
#define ForceSafety_h

#include "ThinTissueHapticsModule.h"
#include "TriangleMesh.h"

namespace thintissue
{

struct ForceSafetySettings
{
  /// Seconds from zero to full force after start or enable().
  double rampIn = 0.5;
  /// A model older than this (seconds) is stale ...
  double staleAfter = 0.05;
  /// ... and the force fades to zero over this many seconds (3 ticks).
  double fadeOut = 0.003;
  /// Largest change of force per second (N/s).
  double maximumRate = 1000.0;
};

/// Throws InvalidInputError naming the setting on a negative or
/// non-finite value.
THINTISSUEHAPTICS_EXPORT void checkForceSafetySettings(const ForceSafetySettings& settings);

class THINTISSUEHAPTICS_EXPORT ForceSafety
{
public:
  ForceSafety() = default;
  ForceSafety(const ForceSafetySettings& settings, double maximumForce);

  /// Ramps in again from `time`.
  void enable(double time);
  /// The force to send at `time` for `requested`, computed from a model of
  /// age `modelAge` seconds.
  Vector3 apply(const Vector3& requested, double time, double modelAge);
  const Vector3& lastForce() const { return Last; }
  double maximumForce() const { return MaximumForce; }

private:
  ForceSafetySettings Settings;
  double MaximumForce = 0.88;
  double EnabledAt = 0.0;
  double LastTime = 0.0;
  Vector3 Last = Vector3::Zero();
};

} // namespace thintissue

#endif
