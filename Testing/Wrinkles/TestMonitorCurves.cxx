// Monitor and region points (thesis 4.3): B-spline resampling of the data
// point pairs, bad data refused, the affected surface points.
#include "MonitorCurves.h"
#include "ThinTissueError.h"
#include "WrinkleInfluence.h"
#include "WrinkleTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace thintissue;
using namespace thintissue::testing;

namespace
{

double distanceToPolyline(const Vector3& x, const std::vector<Vector3>& line)
{
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < line.size(); ++k)
  {
    const Vector3 d = line[k] - line[k - 1];
    const double t = std::clamp((x - line[k - 1]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (line[k - 1] + t * d - x).norm());
  }
  return best;
}

std::string messageOf(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const InvalidInputError& e)
  {
    return e.what();
  }
  return "";
}

} // namespace

TEST(MonitorCurves, SplinesThroughTheDataPointsResampledWithinTheSpacing)
{
  const MeniscusModel m = makeMeniscus();
  const auto data = wrinkleDataCurves(m.monitorCurves);
  const MonitorPointSet set = resampleMonitorCurves(data, 0.2);
  ASSERT_EQ(set.curveCount(), 1u);
  ASSERT_EQ(set.regionPoints.size(), set.size());
  ASSERT_EQ(set.thickness.size(), set.size());
  for (std::size_t k = 1; k < set.size(); ++k)
  {
    EXPECT_LE((set.monitorPoints[k] - set.monitorPoints[k - 1]).norm(), 0.2 + 1e-12);
    EXPECT_GT((set.monitorPoints[k] - set.monitorPoints[k - 1]).norm(), 0.1); // not wasteful
  }
  // Interpolating: the ends are the data's ends, every data point is on the
  // dense curve, and the splines stay close to the model's exact curves.
  const auto& d = data[0];
  EXPECT_LT((set.monitorPoints.front() - d.monitorPoints.front()).norm(), 1e-9);
  EXPECT_LT((set.monitorPoints.back() - d.monitorPoints.back()).norm(), 1e-9);
  EXPECT_LT((set.regionPoints.front() - d.regionPoints.front()).norm(), 1e-9);
  for (const Vector3& x : d.monitorPoints)
  {
    EXPECT_LT(distanceToPolyline(x, set.monitorPoints), 0.01);
  }
  for (const Vector3& x : d.regionPoints)
  {
    EXPECT_LT(distanceToPolyline(x, set.regionPoints), 0.01);
  }
  // The data points are about 5 mm apart along a curve that turns through
  // 290 degrees: the cubic departs from the exact curve by up to 0.3 mm
  // (monitor) and 0.5 mm (region) where it turns fastest.
  const auto exact = sampleMonitorCurves(MeniscusParameters{}, m.monitorCurves, 0.05);
  for (std::size_t k = 0; k < set.size(); ++k)
  {
    EXPECT_LT(distanceToPolyline(set.monitorPoints[k], exact[0].monitorPoints), 0.35) << k;
    EXPECT_LT(distanceToPolyline(set.regionPoints[k], exact[0].regionPoints), 0.55) << k;
    EXPECT_GT(set.thickness[k], 0.0);
  }
}

TEST(MonitorCurves, EveryTearTypeGivesOneSetOfCurves)
{
  for (auto type : { MeniscusTearType::Longitudinal,
         MeniscusTearType::Radial,
         MeniscusTearType::Flap,
         MeniscusTearType::HorizontalCleavage })
  {
    SCOPED_TRACE(meniscusTearTypeName(type));
    MeniscusParameters p;
    p.tear = defaultMeniscusTear(type);
    const MeniscusModel m = makeMeniscus(p);
    const MonitorPointSet set = resampleMonitorCurves(wrinkleDataCurves(m.monitorCurves), 0.25);
    EXPECT_EQ(set.curveCount(), m.monitorCurves.size());
    for (std::size_t c = 0; c < set.curveCount(); ++c)
    {
      EXPECT_GE(set.curveStarts[c + 1] - set.curveStarts[c], 2);
      for (int k = set.curveStarts[c] + 1; k < set.curveStarts[c + 1]; ++k)
      {
        EXPECT_LE((set.monitorPoints[k] - set.monitorPoints[k - 1]).norm(), 0.25 + 1e-12);
        EXPECT_EQ(set.curveOf(k), static_cast<int>(c));
      }
    }
  }
}

TEST(MonitorCurves, BadDataIsRefusedWithItsName)
{
  const WrinkleDataCurve good{ "rim",
    { Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(2, 0.5, 0) },
    { Vector3(0, 1, 0), Vector3(1, 1, 0), Vector3(2, 1.5, 0) },
    { 0.5, 0.6, 0.7 } };
  EXPECT_NO_THROW(resampleMonitorCurves({ good }, 0.1, "knee.json"));
  auto single = good;
  single.monitorPoints.resize(1);
  single.regionPoints.resize(1);
  single.thickness.resize(1);
  auto sizes = good;
  sizes.thickness.pop_back();
  auto nan = good;
  nan.regionPoints[1].x() = std::nan("");
  auto thin = good;
  thin.thickness[2] = 0.0;
  auto repeated = good;
  repeated.monitorPoints[1] = repeated.monitorPoints[0];
  auto onRegion = good;
  onRegion.regionPoints[0] = onRegion.monitorPoints[0];
  for (const auto& bad : { single, sizes, nan, thin, repeated, onRegion })
  {
    const std::string message =
      messageOf([&] { resampleMonitorCurves({ bad }, 0.1, "knee.json"); });
    EXPECT_NE(message.find("knee.json"), std::string::npos) << message;
    EXPECT_NE(message.find("'rim'"), std::string::npos) << message;
  }
  EXPECT_NE(messageOf([&] { resampleMonitorCurves({ good }, 0.0, "knee.json"); }).find("spacing"),
    std::string::npos);
  EXPECT_NE(messageOf([&] { resampleMonitorCurves({}, 0.1, "knee.json"); }).find("no monitor"),
    std::string::npos);
}

/// The search follows each region line through a grid (a tube about the
/// line, where the blend is not negligible): it must find exactly the points
/// a scan of every surface point keeps (4.3's sphere and line tests, the
/// negligible blend), for narrow and wide blends and a sphere that cuts the
/// line short.
TEST(WrinkleInfluence, TheSearchFindsWhatAScanOfEveryPointKeeps)
{
  const MeniscusWrinkleCase c = meniscusWrinkleCase();
  const auto& surface = c.model.visual.positions;
  for (const auto& [blendWidth, sphereRadius] :
    { std::pair{ 0.2, 0.0 }, std::pair{ 1.5, 0.0 }, std::pair{ 0.5, 1.0 } })
  {
    WrinkleInfluenceSettings settings;
    settings.blendWidth = blendWidth;
    settings.sphereRadius = sphereRadius;
    const WrinkleInfluence influence(c.monitors, surface, {}, settings);
    std::size_t entries = 0;
    for (std::size_t i = 0; i < c.monitors.size(); ++i)
    {
      const Vector3& m = c.monitors.monitorPoints[i];
      const Vector3 line = c.monitors.regionPoints[i] - m;
      const double length = line.norm();
      const double sphere = sphereRadius > 0.0 ? sphereRadius : length;
      std::vector<int> scanned;
      for (std::size_t j = 0; j < surface.size(); ++j)
      {
        const Vector3 v = surface[j] - m;
        const double along = v.dot(line) / length;
        const double across2 = std::max(0.0, v.squaredNorm() - along * along);
        if (std::abs(along) < length && v.squaredNorm() <= sphere * sphere &&
            std::exp(-across2 / (2.0 * blendWidth * blendWidth)) >= settings.negligibleBlend)
          scanned.push_back(static_cast<int>(j));
      }
      std::vector<int> found;
      for (int e = influence.affectedBegin(i); e < influence.affectedEnd(i); ++e)
        found.push_back(influence.point(e));
      std::sort(found.begin(), found.end());
      ASSERT_EQ(found, scanned) << "monitor point " << i << ", blend width " << blendWidth
                                << ", sphere " << sphereRadius;
      entries += found.size();
    }
    EXPECT_GT(entries, c.monitors.size()); // not an empty case
  }
}

TEST(WrinkleInfluence, AffectedPointsLieAlongTheRegionLinesNearTheInnerRim)
{
  const MeniscusWrinkleCase c = meniscusWrinkleCase();
  const auto& surface = c.model.visual.positions;
  const WrinkleInfluence influence(c.monitors, surface);
  ASSERT_EQ(influence.monitorCount(), c.monitors.size());
  ASSERT_FALSE(influence.affectedPoints().empty());
  EXPECT_LT(influence.affectedPoints().size(), surface.size() / 2); // local, not everywhere
  std::vector<double> total(surface.size(), 0.0);
  for (std::size_t i = 0; i < influence.monitorCount(); ++i)
  {
    const Vector3& m = c.monitors.monitorPoints[i];
    const Vector3 line = c.monitors.regionPoints[i] - m;
    for (int e = influence.affectedBegin(i); e < influence.affectedEnd(i); ++e)
    {
      const Vector3& x = surface[influence.point(e)];
      // 4.3: the projection onto the region line is nearer than the region
      // point, inside the sphere.
      EXPECT_LT(std::abs((x - m).dot(line)) / line.norm(), line.norm());
      EXPECT_LE((x - m).norm(), line.norm() + 1e-12);
      EXPECT_GT(influence.factor(e), 0.0);
      total[influence.point(e)] += influence.factor(e);
    }
  }
  // A uniform monitor displacement moves each point by at most itself, and
  // the rim (near its monitor points) by nearly itself.
  int nearlyFull = 0;
  for (const int j : influence.affectedPoints())
  {
    EXPECT_LE(total[j], 1.0 + 1e-12);
    nearlyFull += total[j] > 0.9 ? 1 : 0;
  }
  EXPECT_GT(nearlyFull, 50);
}
