// Monitor and region points (thesis 4.3): the points embedded near a thin
// free border (the meniscus's inner rim) that watch the coarse deformation
// and carry the wrinkles, and the region points inside the tissue that
// bound the surface area each monitor point moves.
//
// Step one gives a few data point pairs per curve with the thickness sampled
// at each monitor data point (WrinkleDataCurve); steps two and three
// interpolate each list with a cubic B-spline and sample both splines at
// the same parameters so that consecutive monitor points are at most a given
// distance apart (resampleMonitorCurves, fig. 4-7).
#ifndef MonitorCurves_h
#define MonitorCurves_h

#include "MeniscusModel.h"
#include "ThinTissueWrinklesModule.h"
#include "TriangleMesh.h"

#include <cstddef>
#include <string>
#include <vector>

namespace thintissue
{

/// Data point pairs along one border (thesis 4.3, step one): monitor data
/// points on or near the border, region data points inside the tissue
/// mid-way between its surfaces, the thickness at each monitor data point.
struct WrinkleDataCurve
{
  std::string name;
  std::vector<Vector3> monitorPoints;
  std::vector<Vector3> regionPoints;
  std::vector<double> thickness;
};

/// Throws InvalidInputError naming `source` and the curve on: fewer than two
/// pairs, lists of different sizes, a non-finite point, a thickness not
/// positive and finite, two consecutive monitor data points at the same
/// place, or a region point on its monitor point.
THINTISSUEWRINKLES_EXPORT void checkWrinkleDataCurves(const std::vector<WrinkleDataCurve>& curves,
  const std::string& source);

/// Dense monitor/region point pairs of one or several curves, at rest.
/// Curve c owns the points [curveStarts[c], curveStarts[c + 1]); the window
/// of monitor points that wrinkles (4.4.1) never leaves its curve.
struct THINTISSUEWRINKLES_EXPORT MonitorPointSet
{
  std::vector<Vector3> monitorPoints;
  std::vector<Vector3> regionPoints;
  std::vector<double> thickness;
  std::vector<int> curveStarts{ 0 };

  std::size_t size() const { return monitorPoints.size(); }
  std::size_t curveCount() const { return curveStarts.size() - 1; }
  int curveOf(std::size_t point) const;
  /// Appends a curve's pairs (sizes must match).
  void appendCurve(const std::vector<Vector3>& monitor,
    const std::vector<Vector3>& region,
    const std::vector<double>& thickness);
  /// Bytes a file needs for the set (single precision: monitor and region
  /// points, thickness, curve starts), the thesis's "12.9 KB" measure.
  std::size_t storedBytes() const;
};

/// Thesis 4.3, steps two and three: per curve, interpolating cubic B-splines
/// (quadratic or linear for three or two pairs) through the monitor data
/// points and through the region data points, both parameterised by the
/// monitor points' chord lengths, sampled at common parameters equally
/// spaced along the monitor spline so that consecutive monitor points are at
/// most `maxSpacing` apart. The thickness is interpolated linearly in the
/// parameter. Throws InvalidInputError (see checkWrinkleDataCurves, and on a
/// `maxSpacing` not positive).
THINTISSUEWRINKLES_EXPORT MonitorPointSet resampleMonitorCurves(
  const std::vector<WrinkleDataCurve>& curves,
  double maxSpacing,
  const std::string& source = "wrinkle data");

/// The data point pairs a procedural meniscus supplies (MeniscusModel's
/// monitorCurves), as wrinkle data.
THINTISSUEWRINKLES_EXPORT std::vector<WrinkleDataCurve> wrinkleDataCurves(
  const std::vector<MonitorCurve>& curves);

} // namespace thintissue

#endif
