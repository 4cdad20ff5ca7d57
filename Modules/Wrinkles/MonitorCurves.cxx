#include "MonitorCurves.h"

#include "ThinTissueError.h"

#include <unsupported/Eigen/Splines>

#include <algorithm>
#include <cmath>

namespace thintissue
{

namespace
{

using Spline3 = Eigen::Spline<double, 3>;
using PointMatrix = Eigen::Matrix<double, 3, Eigen::Dynamic>;

[[noreturn]] void refuse(const std::string& source,
  const WrinkleDataCurve& curve,
  const std::string& what)
{
  throw InvalidInputError(source + ": monitor curve '" + curve.name + "' " + what);
}

void checkCurve(const WrinkleDataCurve& curve, const std::string& source)
{
  const std::size_t n = curve.monitorPoints.size();
  if (n < 2)
  {
    refuse(source, curve, "needs at least two monitor/region data point pairs");
  }
  if (curve.regionPoints.size() != n || curve.thickness.size() != n)
  {
    refuse(source,
      curve,
      "has " + std::to_string(n) + " monitor data points, " +
        std::to_string(curve.regionPoints.size()) + " region data points and " +
        std::to_string(curve.thickness.size()) + " thickness samples (one of each per pair)");
  }
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::string pair = "pair " + std::to_string(k);
    if (!curve.monitorPoints[k].allFinite() || !curve.regionPoints[k].allFinite())
    {
      refuse(source, curve, pair + " has a non-finite point");
    }
    if (!std::isfinite(curve.thickness[k]) || curve.thickness[k] <= 0.0)
    {
      refuse(source,
        curve,
        pair + " has thickness " + std::to_string(curve.thickness[k]) + " (must be positive)");
    }
    if ((curve.regionPoints[k] - curve.monitorPoints[k]).norm() == 0.0)
    {
      refuse(source, curve, pair + " has its region point on its monitor point");
    }
    if (k > 0 && (curve.monitorPoints[k] - curve.monitorPoints[k - 1]).norm() == 0.0)
    {
      refuse(source, curve, "repeats monitor data point " + std::to_string(k));
    }
  }
}

Vector3 at(const Spline3& spline, double u)
{
  return spline(u).matrix();
}

PointMatrix asMatrix(const std::vector<Vector3>& points)
{
  PointMatrix m(3, static_cast<Eigen::Index>(points.size()));
  for (std::size_t k = 0; k < points.size(); ++k)
  {
    m.col(static_cast<Eigen::Index>(k)) = points[k];
  }
  return m;
}

/// Both splines of a curve, on the monitor points' chord-length parameters.
struct CurveSplines
{
  Spline3 monitor;
  Spline3 region;
  Eigen::RowVectorXd knots; ///< parameter of each data pair, 0 to 1
};

CurveSplines interpolate(const WrinkleDataCurve& curve)
{
  const PointMatrix monitor = asMatrix(curve.monitorPoints);
  CurveSplines s;
  Eigen::ChordLengths(monitor, s.knots);
  const Eigen::DenseIndex degree = std::min<Eigen::DenseIndex>(3, monitor.cols() - 1);
  s.monitor = Eigen::SplineFitting<Spline3>::Interpolate(monitor, degree, s.knots);
  s.region =
    Eigen::SplineFitting<Spline3>::Interpolate(asMatrix(curve.regionPoints), degree, s.knots);
  return s;
}

double thicknessAt(const WrinkleDataCurve& curve, const Eigen::RowVectorXd& knots, double u)
{
  const Eigen::Index n = knots.size();
  Eigen::Index k = 0;
  while (k + 2 < n && knots(k + 1) < u)
  {
    ++k;
  }
  const double span = knots(k + 1) - knots(k);
  const double t = span > 0.0 ? std::clamp((u - knots(k)) / span, 0.0, 1.0) : 0.0;
  return (1.0 - t) * curve.thickness[static_cast<std::size_t>(k)] +
         t * curve.thickness[static_cast<std::size_t>(k + 1)];
}

/// Parameters equally spaced along the monitor spline, `pieces` intervals,
/// from its arc length tabulated at `table` + 1 parameters.
std::vector<double> equalArcParameters(const Spline3& spline, int table, int pieces)
{
  std::vector<double> arc(static_cast<std::size_t>(table) + 1, 0.0);
  Vector3 previous = at(spline, 0.0);
  for (int i = 1; i <= table; ++i)
  {
    const Vector3 x = at(spline, static_cast<double>(i) / table);
    arc[i] = arc[i - 1] + (x - previous).norm();
    previous = x;
  }
  std::vector<double> u(static_cast<std::size_t>(pieces) + 1, 0.0);
  for (int p = 1; p <= pieces; ++p)
  {
    const double target = arc.back() * p / pieces;
    const auto above = std::lower_bound(arc.begin(), arc.end(), target);
    // (The last target may exceed the total by rounding: stay in the table.)
    const std::size_t i =
      std::clamp<std::size_t>(static_cast<std::size_t>(above - arc.begin()), 1, arc.size() - 1);
    const double span = arc[i] - arc[i - 1];
    const double t = span > 0.0 ? (target - arc[i - 1]) / span : 0.0;
    u[p] = std::clamp((static_cast<double>(i - 1) + t) / table, 0.0, 1.0);
  }
  u.back() = 1.0;
  return u;
}

double longestChord(const Spline3& spline, const std::vector<double>& u)
{
  double longest = 0.0;
  for (std::size_t k = 1; k < u.size(); ++k)
  {
    longest = std::max(longest, (at(spline, u[k]) - at(spline, u[k - 1])).norm());
  }
  return longest;
}

} // namespace

void checkWrinkleDataCurves(const std::vector<WrinkleDataCurve>& curves, const std::string& source)
{
  if (curves.empty())
  {
    throw InvalidInputError(source + ": no monitor curve");
  }
  for (const WrinkleDataCurve& curve : curves)
  {
    checkCurve(curve, source);
  }
}

int MonitorPointSet::curveOf(std::size_t point) const
{
  const auto above =
    std::upper_bound(curveStarts.begin(), curveStarts.end(), static_cast<int>(point));
  return static_cast<int>(above - curveStarts.begin()) - 1;
}

void MonitorPointSet::appendCurve(const std::vector<Vector3>& monitor,
  const std::vector<Vector3>& region,
  const std::vector<double>& curveThickness)
{
  if (region.size() != monitor.size() || curveThickness.size() != monitor.size())
  {
    throw InvalidInputError("monitor point set: a curve's pairs and thickness differ in number");
  }
  monitorPoints.insert(monitorPoints.end(), monitor.begin(), monitor.end());
  regionPoints.insert(regionPoints.end(), region.begin(), region.end());
  thickness.insert(thickness.end(), curveThickness.begin(), curveThickness.end());
  curveStarts.push_back(static_cast<int>(monitorPoints.size()));
}

std::size_t MonitorPointSet::storedBytes() const
{
  return size() * (3 + 3 + 1) * sizeof(float) + curveStarts.size() * sizeof(int);
}

MonitorPointSet resampleMonitorCurves(const std::vector<WrinkleDataCurve>& curves,
  double maxSpacing,
  const std::string& source)
{
  if (!(maxSpacing > 0.0) || !std::isfinite(maxSpacing))
  {
    throw InvalidInputError(
      source + ": monitor point spacing " + std::to_string(maxSpacing) + " (must be positive)");
  }
  checkWrinkleDataCurves(curves, source);
  MonitorPointSet set;
  for (const WrinkleDataCurve& curve : curves)
  {
    const CurveSplines splines = interpolate(curve);
    const int table = 64 * static_cast<int>(curve.monitorPoints.size());
    // The tabulated arc slightly under-estimates the spline's length: add a
    // piece until every chord is within the bound.
    double length = 0.0;
    for (int i = 1; i <= table; ++i)
    {
      length += (at(splines.monitor, static_cast<double>(i) / table) -
                 at(splines.monitor, static_cast<double>(i - 1) / table))
                  .norm();
    }
    int pieces = std::max(1, static_cast<int>(std::ceil(length / maxSpacing)));
    std::vector<double> u = equalArcParameters(splines.monitor, table, pieces);
    while (longestChord(splines.monitor, u) > maxSpacing)
    {
      u = equalArcParameters(splines.monitor, table, ++pieces);
    }
    std::vector<Vector3> monitor, region;
    std::vector<double> thickness;
    for (const double parameter : u)
    {
      monitor.push_back(at(splines.monitor, parameter));
      region.push_back(at(splines.region, parameter));
      thickness.push_back(thicknessAt(curve, splines.knots, parameter));
    }
    set.appendCurve(monitor, region, thickness);
  }
  return set;
}

std::vector<WrinkleDataCurve> wrinkleDataCurves(const std::vector<MonitorCurve>& curves)
{
  std::vector<WrinkleDataCurve> data;
  for (const MonitorCurve& c : curves)
  {
    data.push_back(WrinkleDataCurve{ c.name, c.monitorPoints, c.regionPoints, c.thickness });
  }
  return data;
}

} // namespace thintissue
