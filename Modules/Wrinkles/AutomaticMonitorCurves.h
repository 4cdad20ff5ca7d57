// Monitor and region data points derived from a prepared tissue (beyond the
// thesis, where they were placed by hand, 4.3 step one): along the thin
// free border of the collision mid-surface (where the radius is smallest:
// the meniscus's inner rim), region data points inward on the mid-surface
// (the middle of the thickness), thickness from the radii.
#ifndef AutomaticMonitorCurves_h
#define AutomaticMonitorCurves_h

#include "MonitorCurves.h"
#include "ThinTissueWrinklesModule.h"

#include <vector>

namespace thintissue
{

struct AutomaticMonitorSettings
{
  /// A border vertex is thin when its radius is at most r_min + thinFraction
  /// (r_max - r_min), over all border vertices.
  double thinFraction = 0.35;
  /// When r_max - r_min is at most this fraction of r_max, every border
  /// vertex is thin (a border of uniform thickness).
  double uniformTolerance = 0.05;
  /// Runs are split where the border turns by more than this (radians).
  double cornerAngle = 1.0;
  /// Which part of the thin border: with `useNearPoint`, the run of thin
  /// border vertices nearest `nearPoint`; otherwise every run at least
  /// `minimumRunFraction` times as long as the longest.
  bool useNearPoint = false;
  Vector3 nearPoint = Vector3::Zero();
  double minimumRunFraction = 0.3;
  /// Distance of the region data points from the border, on the
  /// mid-surface; 0 (default): `regionDepthInRadii` times the run's mean
  /// radius.
  double regionDepth = 0.0;
  double regionDepthInRadii = 8.0;
};

/// One data curve per selected run of thin border vertices of `collision`
/// (a mid-surface with one radius per vertex), split at the border's
/// corners. A border loop that is thin all round and has no corner is
/// opened at its first vertex. Throws InvalidInputError naming
/// the mesh when it has no border, the radii do not match, or no run is
/// long enough.
THINTISSUEWRINKLES_EXPORT std::vector<WrinkleDataCurve> deriveWrinkleDataCurves(
  const TriangleMesh& collision,
  const std::vector<double>& radii,
  const AutomaticMonitorSettings& settings = {});

} // namespace thintissue

#endif
