// The reference configuration (thesis 4.4.1) and the wrinkle function
// (4.4.2, formula 4-16) on the examination meniscus, pressed by a smooth
// dent of its hexahedra (no solver: every motion is known), and once with
// the FEM and the collision scene.
#include "CollisionScene.h"
#include "KneeModels.h"
#include "ThinTissueError.h"
#include "WrinkleGenerator.h"
#include "WrinkleTestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace thintissue;
using namespace thintissue::testing;

namespace
{

/// A press and release at the middle of the inner border: `press` steps
/// down by `stride`, then up.
struct PressScript
{
  MeniscusWrinkleCase c = meniscusWrinkleCase();
  Vector3 contact;
  double stride = 0.1;
  double radius = 4.0;

  PressScript()
  {
    contact = c.monitors.monitorPoints[c.monitors.size() / 2] + Vector3(0.0, 0.0, 0.5);
  }
  std::vector<Vector3> nodesAt(double depth) const
  {
    return dentedNodes(c.model.simulation, contact, depth, radius);
  }
  WrinkleGenerator generator(const WrinkleParameters& p = {}) const
  {
    return WrinkleGenerator(c.monitors, c.model.simulation, c.model.visual, p);
  }
  /// Runs `press` steps down then `release` steps up; returns the depth.
  double run(WrinkleGenerator& g, int press, int release, int lower = 5) const
  {
    double depth = 0.0;
    for (int k = 0; k < press + release; ++k)
    {
      depth += k < press ? stride : -stride;
      g.update(nodesAt(depth), pressing(contact, lower));
    }
    return depth;
  }
};

/// Zeros of D in (theta_s, theta_e]: sign changes between consecutive
/// points, plus a zero exactly at the end.
int zerosAfterTheStart(const std::vector<double>& d)
{
  int zeros = 0;
  double last = 0.0;
  for (std::size_t k = 1; k < d.size(); ++k)
  {
    if (std::abs(d[k]) < 1e-9)
    {
      zeros += k + 1 == d.size() ? 1 : 0;
      continue;
    }
    if (last != 0.0 && (d[k] > 0.0) != (last > 0.0))
    {
      ++zeros;
    }
    last = d[k];
  }
  return zeros;
}

} // namespace

TEST(WrinkleGenerator, NoWrinklesWhilePressingOnlyThenTheReversalSetsTheReference)
{
  const PressScript s;
  WrinkleGenerator g = s.generator();
  s.run(g, 10, 0);
  EXPECT_FALSE(g.wrinkling());
  EXPECT_TRUE(g.displacedPoints().empty());
  EXPECT_EQ(g.lastReversals(), 0);
  EXPECT_EQ(g.windowEnd() - g.windowBegin(), 70);
  const std::vector<Vector3> before = g.currentMonitorPoints();
  // The first step back up: the window's monitor points reverse.
  g.update(s.nodesAt(10 * s.stride - s.stride), pressing(s.contact));
  EXPECT_TRUE(g.wrinkling());
  EXPECT_GT(g.lastReversals(), 35);
  ASSERT_EQ(g.referencePoints().size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i)
  {
    EXPECT_EQ(g.referencePoints()[i], before[i]); // P^w0 = P^ml
  }
  EXPECT_FALSE(g.displacedPoints().empty());
  // The window is around the monitor point nearest the contact.
  const int middle = static_cast<int>(s.c.monitors.size() / 2);
  EXPECT_LE(g.windowBegin(), middle);
  EXPECT_GT(g.windowEnd(), middle);
}

TEST(WrinkleGenerator, DirectionChangesSignOncePerHalfPeriod)
{
  const PressScript s;
  for (const double periods : { 5.0, 7.0, 3.0, 4.5 })
  {
    SCOPED_TRACE(periods);
    WrinkleParameters p;
    p.frequency = periods * M_PI;
    WrinkleGenerator g = s.generator(p);
    s.run(g, 10, 3);
    ASSERT_TRUE(g.wrinkling());
    ASSERT_EQ(g.direction().size(), 70u);
    EXPECT_EQ(zerosAfterTheStart(g.direction()), static_cast<int>(std::floor(periods)));
    EXPECT_DOUBLE_EQ(g.direction().front(), 0.0);
  }
}

TEST(WrinkleGenerator, MagnitudeIsBoundedAndThinPointsBelowTheCutOffStayStill)
{
  const PressScript s;
  WrinkleParameters p;
  p.magnitudeBound = 0.02;
  WrinkleGenerator g = s.generator(p);
  s.run(g, 10, 4);
  ASSERT_TRUE(g.wrinkling());
  double largest = 0.0;
  for (std::size_t k = 0; k < g.wrinkleFunction().size(); ++k)
  {
    const int i = g.windowBegin() + static_cast<int>(k);
    // |W(k)| <= m^up, the offset from the current monitor point.
    EXPECT_LE(std::abs(g.wrinkleFunction()[k]), p.magnitudeBound + 1e-12);
    EXPECT_NEAR((g.wrinklePoints()[k] - g.currentMonitorPoints()[i]).norm(),
      std::abs(g.wrinkleFunction()[k]),
      1e-12);
    largest = std::max(largest, std::abs(g.wrinkleFunction()[k]));
  }
  EXPECT_GT(largest, 0.5 * p.magnitudeBound); // the bound is reached, not just respected
  // No surface point moves by more than m^up.
  for (const Vector3& d : g.displacements())
  {
    EXPECT_LE(d.norm(), p.magnitudeBound + 1e-12);
  }
  // Formula 4-16 as written: around the reference, |P^wc - P^w0| = |W(k)|.
  WrinkleParameters literal = p;
  literal.anchor = WrinkleAnchor::Reference;
  WrinkleGenerator thesis = s.generator(literal);
  s.run(thesis, 10, 4);
  ASSERT_TRUE(thesis.wrinkling());
  for (std::size_t k = 0; k < thesis.wrinkleFunction().size(); ++k)
  {
    const int i = thesis.windowBegin() + static_cast<int>(k);
    EXPECT_NEAR((thesis.wrinklePoints()[k] - thesis.referencePoints()[i]).norm(),
      std::abs(thesis.wrinkleFunction()[k]),
      1e-12);
    EXPECT_DOUBLE_EQ(thesis.wrinkleFunction()[k], g.wrinkleFunction()[k]);
  }
  // r^c between the thinnest and thickest window points.
  double thin = 1e9, thick = 0.0;
  for (int i = g.windowBegin(); i < g.windowEnd(); ++i)
  {
    thin = std::min(thin, s.c.monitors.thickness[i]);
    thick = std::max(thick, s.c.monitors.thickness[i]);
  }
  ASSERT_GT(thick, thin);
  p.cutOffThickness = 0.5 * (thin + thick);
  WrinkleGenerator cut = s.generator(p);
  s.run(cut, 10, 4);
  int still = 0, moving = 0;
  for (std::size_t k = 0; k < cut.wrinkleFunction().size(); ++k)
  {
    const int i = cut.windowBegin() + static_cast<int>(k);
    if (s.c.monitors.thickness[i] < p.cutOffThickness)
    {
      EXPECT_EQ(cut.wrinkleFunction()[k], 0.0);
      EXPECT_EQ(cut.wrinklePoints()[k], cut.currentMonitorPoints()[i]);
      ++still;
    }
    else
    {
      moving += cut.wrinkleFunction()[k] != 0.0 ? 1 : 0;
    }
  }
  EXPECT_GT(still, 0);
  EXPECT_GT(moving, 0);
}

TEST(WrinkleGenerator, OnlyAffectedSurfacePointsMoveAndStepsAreDeterministic)
{
  const PressScript s;
  WrinkleGenerator a = s.generator();
  WrinkleGenerator b = s.generator();
  const double depth = s.run(a, 10, 5);
  s.run(b, 10, 5);
  ASSERT_TRUE(a.wrinkling());
  EXPECT_EQ(a.displacedPoints(), b.displacedPoints());
  EXPECT_EQ(a.displacements(), b.displacements());

  std::vector<Vector3> surface;
  HexahedralEmbedding embedding(s.c.model.simulation, s.c.model.visual.positions);
  embedding.mapPositions(s.nodesAt(depth), surface);
  std::vector<Vector3> wrinkled = surface;
  a.applyTo(wrinkled);
  const auto& affected = a.influence().affectedPoints();
  int moved = 0;
  for (std::size_t j = 0; j < surface.size(); ++j)
  {
    if (wrinkled[j] != surface[j])
    {
      ++moved;
      EXPECT_TRUE(std::binary_search(affected.begin(), affected.end(), static_cast<int>(j))) << j;
    }
  }
  EXPECT_GT(moved, 20);
  // Every displacement is a blend of the window's monitor displacements.
  double largestMonitor = 0.0;
  for (std::size_t k = 0; k < a.wrinklePoints().size(); ++k)
  {
    largestMonitor = std::max(largestMonitor,
      (a.wrinklePoints()[k] - a.currentMonitorPoints()[a.windowBegin() + k]).norm());
  }
  for (const Vector3& d : a.displacements())
  {
    EXPECT_LE(d.norm(), largestMonitor + 1e-12);
  }
}

TEST(WrinkleGenerator, ContactThresholdsStartAndEndTheWrinkles)
{
  const PressScript s;
  // No lower-surface contact (N_s = 0): reversals are not even counted.
  WrinkleGenerator free = s.generator();
  s.run(free, 10, 3, 0);
  EXPECT_FALSE(free.wrinkling());
  // N_s = 8 needs more than eight.
  WrinkleParameters p;
  p.startContacts = 8;
  WrinkleGenerator strict = s.generator(p);
  s.run(strict, 10, 3, 8);
  EXPECT_FALSE(strict.wrinkling());
  s.run(strict, 3, 3, 9);
  EXPECT_TRUE(strict.wrinkling());

  WrinkleGenerator g = s.generator();
  s.run(g, 10, 3);
  ASSERT_TRUE(g.wrinkling());
  // The instrument still touches: the wrinkles stay, whatever the contacts.
  g.update(s.nodesAt(0.6), pressing(s.contact, 0));
  EXPECT_TRUE(g.wrinkling());
  // Contacts below N_e = 1 but the instrument touches... and then leaves.
  WrinkleContactState gone;
  gone.lowerSurfaceContacts = 3;
  g.update(s.nodesAt(0.5), gone);
  EXPECT_TRUE(g.wrinkling()); // lower contacts still >= N_e
  gone.lowerSurfaceContacts = 0;
  g.update(s.nodesAt(0.4), gone);
  EXPECT_FALSE(g.wrinkling());
  EXPECT_TRUE(g.referencePoints().empty());
  EXPECT_TRUE(g.displacedPoints().empty());
}

TEST(WrinkleGenerator, BadParametersAreRefused)
{
  const PressScript s;
  WrinkleParameters p;
  p.frequency = 0.0;
  EXPECT_THROW(s.generator(p), InvalidInputError);
  p = {};
  p.windowSize = 1;
  EXPECT_THROW(s.generator(p), InvalidInputError);
  p = {};
  p.cutOffThickness = -1.0;
  EXPECT_THROW(s.generator(p), InvalidInputError);
  p = {};
  p.magnitudeBound = std::nan("");
  EXPECT_THROW(s.generator(p), InvalidInputError);
  WrinkleGenerator g = s.generator();
  p = {};
  p.startContacts = -2;
  EXPECT_THROW(g.setParameters(p), InvalidInputError);
  EXPECT_EQ(g.parameters().startContacts, 0); // kept
  EXPECT_THROW(
    WrinkleGenerator(MonitorPointSet{}, s.c.model.simulation, TriangleMesh{}), InvalidInputError);
}

TEST(WrinkleGenerator, ProbePressingTheInnerBorderOntoThePlateauThenLiftingWrinklesIt)
{
  // The scenario of 4.5 with the solver: a probe presses the inner border
  // down onto the tibial plateau and lifts; the contact state comes from the
  // collision scene. No wrinkles while it presses, wrinkles from its first
  // step back, none once it has left.
  const MeniscusWrinkleCase c = meniscusWrinkleCase();
  const KneeSurroundings knee = makeKneeSurroundings();
  LinearMaterial material; // thesis 4.5
  material.youngModulus = 150.0;
  material.poissonRatio = 0.49;
  material.density = 1.1e-9;
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.001;
  CorotationalHexFem fem(c.model.simulation, material, settings);
  DeformableCollisionMesh collision(c.model.collision, c.model.simulation);
  const StaticObstacle tibia(knee.tibia.collision);
  const StaticObstacle cartilage(knee.tibialCartilage.visual);
  RigidTool probe("probe");
  probe.addSphere(Vector3::Zero(), 1.0);
  CollisionScene scene;
  scene.addTissue(fem, collision);
  scene.addTool(probe);
  scene.addObstacle(tibia);
  scene.addObstacle(cartilage);
  WrinkleGenerator wrinkles(c.monitors, c.model.simulation, c.model.visual);

  // 1.5 mm in from the middle monitor point, 3 mm above it.
  const std::size_t middle = c.monitors.size() / 2;
  const Vector3 inward =
    (c.monitors.regionPoints[middle] - c.monitors.monitorPoints[middle]).normalized();
  RigidPose pose;
  pose.translation = c.monitors.monitorPoints[middle] + 1.5 * inward + Vector3(0.0, 0.0, 3.0);
  probe.setPose(pose);
  constexpr int Press = 250, Lift = 150;
  int pressedOntoThePlateau = 0, wrinklingWhilePressing = 0, wrinklingWhileLifting = 0;
  for (int k = 0; k < Press + Lift; ++k)
  {
    pose.translation.z() += k < Press ? -0.01 : 0.01;
    probe.moveTo(pose, 0.001);
    ASSERT_TRUE(scene.step().ok);
    const WrinkleContactState contacts = wrinkleContactState(scene, 0);
    pressedOntoThePlateau += contacts.instrumentTouches && contacts.lowerSurfaceContacts > 0;
    wrinkles.update(fem.positions(), contacts);
    (k < Press ? wrinklingWhilePressing : wrinklingWhileLifting) += wrinkles.wrinkling() ? 1 : 0;
  }
  EXPECT_GT(pressedOntoThePlateau, 100);
  EXPECT_EQ(wrinklingWhilePressing, 0);
  EXPECT_GT(wrinklingWhileLifting, 100);
  EXPECT_FALSE(wrinkles.wrinkling()); // the probe has left the meniscus
  EXPECT_EQ(wrinkleContactState(scene, 0).instrumentTouches, false);
}
