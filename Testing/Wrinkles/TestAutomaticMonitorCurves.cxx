// Monitor and region data points derived from the collision mid-surface:
// on the meniscus models they land on the inner rim where the models put
// theirs; on a sheet thinning toward one side, on that side; on a prepared
// meniscus and the prepared steak (../shared/data), on the thinnest border.
#include "AutomaticMonitorCurves.h"
#include "CollisionMeshGeneration.h"
#include "MeshImport.h"
#include "MeshQueries.h"
#include "ThinSheetModel.h"
#include "ThinTissueError.h"
#include "ThinTissueTestSupport.h"
#include "TissueBundle.h"
#include "TriangleMeshAdjacency.h"
#include "WrinkleGenerator.h"
#include "WrinkleTestHelpers.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <limits>

using namespace thintissue;
using namespace thintissue::testing;

namespace
{

double distanceToCurves(const Vector3& x, const std::vector<WrinkleDataCurve>& curves)
{
  double best = std::numeric_limits<double>::infinity();
  for (const auto& c : curves)
  {
    for (std::size_t k = 1; k < c.monitorPoints.size(); ++k)
    {
      const Vector3 d = c.monitorPoints[k] - c.monitorPoints[k - 1];
      const double t = std::clamp((x - c.monitorPoints[k - 1]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (c.monitorPoints[k - 1] + t * d - x).norm());
    }
  }
  return best;
}

/// Fraction of `reference`'s monitor data points within `tolerance` of the
/// curves `found`.
double coverage(const std::vector<WrinkleDataCurve>& reference,
  const std::vector<WrinkleDataCurve>& found,
  double tolerance)
{
  int near = 0, total = 0;
  for (const auto& c : reference)
  {
    for (const Vector3& x : c.monitorPoints)
    {
      near += distanceToCurves(x, found) < tolerance ? 1 : 0;
      ++total;
    }
  }
  return static_cast<double>(near) / total;
}

} // namespace

TEST(AutomaticMonitorCurves, LandOnTheInnerRimOfTheIntactMeniscus)
{
  const MeniscusModel m = makeMeniscus();
  const auto automatic = deriveWrinkleDataCurves(m.collision, m.collisionRadii());
  ASSERT_EQ(automatic.size(), 1u);
  const auto model = wrinkleDataCurves(m.monitorCurves);
  // Every automatic monitor data point is near the model's inner border
  // curve, and the model's curve is covered (the horn tips aside).
  for (const Vector3& x : automatic[0].monitorPoints)
  {
    EXPECT_LT(distanceToCurves(x, model), 1.5);
  }
  EXPECT_GT(coverage(model, automatic, 1.5), 0.8);
  for (std::size_t k = 0; k < automatic[0].monitorPoints.size(); ++k)
  {
    const Vector3 line = automatic[0].regionPoints[k] - automatic[0].monitorPoints[k];
    EXPECT_GT(line.norm(), 1.0);
    // Inward: the region point is thicker (further from the inner edge).
    EXPECT_GT(windingNumber(m.visual, automatic[0].regionPoints[k]), 0.5);
  }
  // And it makes a working monitor point set.
  EXPECT_NO_THROW(resampleMonitorCurves(automatic, 0.2));
}

TEST(AutomaticMonitorCurves, FollowTheRemainingRimOfEveryTornMeniscus)
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
    const auto automatic = deriveWrinkleDataCurves(m.collision, m.collisionRadii());
    ASSERT_FALSE(automatic.empty());
    // The model's inner border curves (not the lips) are covered.
    std::vector<WrinkleDataCurve> innerBorder;
    for (const auto& c : wrinkleDataCurves(m.monitorCurves))
    {
      if (c.name.rfind("inner border", 0) == 0)
      {
        innerBorder.push_back(c);
      }
    }
    ASSERT_FALSE(innerBorder.empty());
    EXPECT_GT(coverage(innerBorder, automatic, 1.5), 0.7);
    EXPECT_NO_THROW(resampleMonitorCurves(automatic, 0.2));
  }
}

TEST(AutomaticMonitorCurves, OnASheetThinningTowardOneSideTheThinSide)
{
  const TissueModel sheet = makeThinSheet(ThinSheetParameters{});
  // Radii from 0.3 at x = -50 to 1.5 at x = +50.
  std::vector<double> radii;
  for (const Vector3& x : sheet.collision.positions)
  {
    radii.push_back(0.3 + 1.2 * (x.x() + 50.0) / 100.0);
  }
  const auto automatic = deriveWrinkleDataCurves(sheet.collision, radii);
  ASSERT_EQ(automatic.size(), 1u);
  ASSERT_GE(automatic[0].monitorPoints.size(), 2u);
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < automatic[0].monitorPoints.size(); ++k)
  {
    EXPECT_LT(automatic[0].monitorPoints[k].x(), -50.0 + 35.0 + 1e-9);
    EXPECT_NEAR(automatic[0].thickness[k],
      2.0 * (0.3 + 1.2 * (automatic[0].monitorPoints[k].x() + 50.0) / 100.0),
      1e-12);
    lowest = std::min(lowest, automatic[0].monitorPoints[k].x());
  }
  EXPECT_NEAR(lowest, -50.0, 1e-9);
  // Uniform radii: the whole border, split at the four corners (which
  // belong to no side): 2 (5 + 7) vertices.
  const auto whole = deriveWrinkleDataCurves(
    sheet.collision, std::vector<double>(sheet.collision.vertexCount(), 1.0));
  ASSERT_EQ(whole.size(), 4u);
  std::size_t sides = 0;
  for (const auto& c : whole)
  {
    sides += c.monitorPoints.size();
  }
  EXPECT_EQ(sides, 2u * (5 + 7));
  // Near a point: the run nearest it.
  AutomaticMonitorSettings near;
  near.useNearPoint = true;
  near.nearPoint = Vector3(-60.0, 0.0, 0.0);
  EXPECT_EQ(deriveWrinkleDataCurves(sheet.collision, radii, near).size(), 1u);
}

TEST(AutomaticMonitorCurves, MeshesWithoutBorderOrWithWrongRadiiAreRefused)
{
  const MeniscusModel m = makeMeniscus();
  try
  {
    deriveWrinkleDataCurves(m.visual, std::vector<double>(m.visual.vertexCount(), 1.0));
    FAIL() << "a closed surface has no free border";
  }
  catch (const InvalidInputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("no free border"), std::string::npos) << e.what();
  }
  EXPECT_THROW(deriveWrinkleDataCurves(m.collision, { 1.0, 2.0 }), InvalidInputError);
}

namespace
{

/// The border vertices' radii of `mesh`: all, and those the automatic
/// curves chose (monitor data points are border vertices).
std::pair<double, double> meanBorderAndChosenRadius(const TriangleMesh& mesh,
  const std::vector<double>& radii,
  const std::vector<WrinkleDataCurve>& curves)
{
  const TriangleMeshAdjacency adjacency(mesh);
  double border = 0.0, chosen = 0.0;
  int borderCount = 0, chosenCount = 0;
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e)
  {
    if (adjacency.isBorderEdge(static_cast<int>(e)))
    {
      border += radii[adjacency.edge(static_cast<int>(e))[0]];
      ++borderCount;
    }
  }
  for (const auto& c : curves)
  {
    for (const double t : c.thickness)
    {
      chosen += 0.5 * t;
      ++chosenCount;
    }
  }
  return { border / borderCount, chosen / chosenCount };
}

} // namespace

TEST(AutomaticMonitorCurves, OnAPreparedMeniscusTheInnerRimAndOnTheSteakItsThinnestBorder)
{
  // The meniscus prepared from its visual surface alone (no model data).
  const MeniscusModel m = makeMeniscus();
  const GeneratedCollisionMesh prepared = makeCollisionMidSurface(m.visual);
  const std::vector<double>& radii = prepared.mesh.pointAttributes.get("Radius").values;
  const auto automatic = deriveWrinkleDataCurves(prepared.mesh, radii);
  ASSERT_FALSE(automatic.empty());
  const auto model = wrinkleDataCurves(m.monitorCurves);
  EXPECT_GT(coverage(model, automatic, 2.0), 0.7);
  const auto [border, chosen] = meanBorderAndChosenRadius(prepared.mesh, radii, automatic);
  EXPECT_LT(chosen, 0.5 * border);
  EXPECT_NO_THROW(resampleMonitorCurves(automatic, 0.2));

  const std::string data = thintissue::testing::sharedDataDirectory();
  const std::string steakPath = data + "/steak/steak.obj";
  if (data.empty() || !std::filesystem::exists(steakPath))
  {
    GTEST_SKIP() << "../shared/data/steak not present";
  }
  const GeneratedCollisionMesh steak = makeCollisionMidSurface(readTriangleMesh(steakPath));
  const std::vector<double>& steakRadii = steak.mesh.pointAttributes.get("Radius").values;
  const auto steakCurves = deriveWrinkleDataCurves(steak.mesh, steakRadii);
  ASSERT_FALSE(steakCurves.empty());
  const auto [steakBorder, steakChosen] =
    meanBorderAndChosenRadius(steak.mesh, steakRadii, steakCurves);
  // The steak is a slab: its border is about equally thin all round.
  EXPECT_LE(steakChosen, steakBorder * (1.0 + 1e-9));
  std::size_t chosenCount = 0;
  for (const auto& c : steakCurves)
  {
    chosenCount += c.monitorPoints.size();
  }
  EXPECT_GE(chosenCount, 20u);
  std::cout << "steak: mean border radius " << steakBorder << ", chosen " << steakChosen << " in "
            << steakCurves.size() << " curves\n";
}

TEST(AutomaticMonitorCurves, OnTheRealMriMenisciTheirThinBorder)
{
  // ../shared/data/knee-smith2019 (segmented from MRI, in metres): prepared
  // as a user would, the monitor points come from the thin border alone and
  // a wrinkle generator is built on them.
  const std::string data = thintissue::testing::sharedDataDirectory() + "/knee-smith2019/";
  if (!std::filesystem::exists(data + "smith2019-R-medial-meniscus.stl"))
  {
    GTEST_SKIP() << "../shared/data/knee-smith2019 not present";
  }
  for (const char* file : { "smith2019-R-medial-meniscus.stl", "smith2019-R-lateral-meniscus.stl" })
  {
    SCOPED_TRACE(file);
    const TissueBundle bundle = prepareTissue(readTriangleMesh(data + file));
    const std::vector<double>& radii = bundle.collision.pointAttributes.get("Radius").values;
    const auto curves = deriveWrinkleDataCurves(bundle.collision, radii);
    ASSERT_FALSE(curves.empty());
    const auto [border, chosen] = meanBorderAndChosenRadius(bundle.collision, radii, curves);
    EXPECT_LT(chosen, 0.5 * border);
    const double extent = bundle.collision.boundingBox().sizes().maxCoeff();
    const MonitorPointSet monitors = resampleMonitorCurves(curves, extent / 300.0, file);
    EXPECT_GT(monitors.size(), 100u);
    const WrinkleGenerator generator(monitors, bundle.simulation, bundle.visual);
    EXPECT_GT(generator.influence().affectedPoints().size(), 50u);
    EXPECT_LT(generator.influence().affectedPoints().size(), bundle.visual.vertexCount() / 2);
  }
}
