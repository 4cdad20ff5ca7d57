#include "ForceSafety.h"

#include "ThinTissueError.h"

#include <algorithm>
#include <cmath>

namespace thintissue
{

void checkForceSafetySettings(const ForceSafetySettings& s)
{
  const auto check = [](double value, const char* name)
  {
    if (!std::isfinite(value) || value < 0.0)
    {
      throw InvalidInputError(std::string("force safety: ") + name + " " + std::to_string(value) +
                              " must be finite and not negative");
    }
  };
  check(s.rampIn, "ramp-in time");
  check(s.staleAfter, "stale time");
  check(s.fadeOut, "fade-out time");
  check(s.maximumRate, "maximum force rate");
}

ForceSafety::ForceSafety(const ForceSafetySettings& settings, double maximumForce)
  : Settings(settings)
  , MaximumForce(maximumForce)
{
  checkForceSafetySettings(settings);
  if (!std::isfinite(maximumForce) || maximumForce < 0.0)
  {
    throw InvalidInputError(
      "force safety: maximum force " + std::to_string(maximumForce) + " must not be negative");
  }
}

void ForceSafety::enable(double time)
{
  EnabledAt = time;
}

Vector3 ForceSafety::apply(const Vector3& requested, double time, double modelAge)
{
  Vector3 f = requested.allFinite() ? requested : Vector3::Zero();
  // Ramp in, fade out when stale (a model never published is infinitely old).
  const double ramp =
    Settings.rampIn > 0.0 ? std::clamp((time - EnabledAt) / Settings.rampIn, 0.0, 1.0) : 1.0;
  double fresh = 1.0;
  if (!(modelAge <= Settings.staleAfter))
  {
    fresh = Settings.fadeOut > 0.0 && std::isfinite(modelAge)
              ? std::clamp(1.0 - (modelAge - Settings.staleAfter) / Settings.fadeOut, 0.0, 1.0)
              : 0.0;
  }
  f *= ramp * fresh;
  const double magnitude = f.norm();
  if (magnitude > MaximumForce)
  {
    f *= MaximumForce / magnitude;
  }
  // Rate limit: the step from the last force, bounded (both ends are within
  // the clamp, so the result is too).
  const double dt = std::max(0.0, time - LastTime);
  const double step = Settings.maximumRate * dt;
  const Vector3 change = f - Last;
  if (change.norm() > step)
  {
    f = Last + change * (step / change.norm());
  }
  LastTime = time;
  Last = f;
  return f;
}

} // namespace thintissue
