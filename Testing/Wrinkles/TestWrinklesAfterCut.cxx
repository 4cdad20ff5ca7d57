// Wrinkles after cuts (issue: "monitor points whose region was removed are
// dropped and the rest stay valid"): the examination meniscus bound and
// cut; the monitor points follow the hexahedron copies, the curves split at
// the cut, a punched-out piece takes its monitor points with it, and the
// remaining rim still wrinkles, on its own side of a cut.
#include "TissueCutter.h"
#include "VisualCollisionBinding.h"
#include "WrinkleGenerator.h"
#include "WrinkleTestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace thintissue;
using namespace thintissue::testing;

namespace
{

struct CutMeniscus
{
  MeniscusWrinkleCase c = meniscusWrinkleCase();
  VisualCollisionBinding binding = bindVisualToCollision(c.model.visual, c.model.collision);
};

const CutMeniscus& boundMeniscus()
{
  static const CutMeniscus meniscus;
  return meniscus;
}

/// Inward (toward the region point, horizontal) at monitor point i.
Vector3 inwardAt(const MonitorPointSet& m, std::size_t i)
{
  Vector3 d = m.regionPoints[i] - m.monitorPoints[i];
  d.z() = 0.0;
  return d.normalized();
}

/// Presses 10 steps down by 0.1 mm around `contact` and releases 3 steps.
void pressAndRelease(WrinkleGenerator& g, const HexahedralMesh& mesh, const Vector3& contact)
{
  double depth = 0.0;
  for (int k = 0; k < 13; ++k)
  {
    depth += k < 10 ? 0.1 : -0.1;
    g.update(dentedNodes(mesh, contact, depth, 4.0), pressing(contact));
  }
}

Blade punchAt(const Vector3& centre, double radius)
{
  std::vector<Vector3> low, high;
  for (int i = 0; i < 24; ++i)
  {
    const double a = 2.0 * M_PI * i / 24.0;
    const Vector3 p = centre + radius * Vector3(std::cos(a), std::sin(a), 0.0);
    low.push_back(p - Vector3(0, 0, 10));
    high.push_back(p + Vector3(0, 0, 10));
  }
  return Blade::sweptOutline(low, high);
}

/// The influence followCut refreshed near the cut is the one a search of
/// every monitor point on the cut surface finds (same points, same factors).
::testing::AssertionResult influenceIsAsIfFound(const WrinkleGenerator& g,
  const TissueCutter& cutter)
{
  const TriangleMesh& visual = cutter.visual().mesh();
  const std::vector<char> active = cutter.activeVisualTriangles();
  std::vector<Triangle> shown;
  for (std::size_t t = 0; t < visual.triangleCount(); ++t)
    if (active[t])
      shown.push_back(visual.triangles[t]);
  const WrinkleInfluence found(g.monitors(), visual.positions, shown);
  const WrinkleInfluence& kept = g.influence();
  if (found.monitorCount() != kept.monitorCount() || found.entryCount() != kept.entryCount())
    return ::testing::AssertionFailure()
           << kept.entryCount() << " entries kept, " << found.entryCount() << " found";
  for (std::size_t e = 0; e < found.entryCount(); ++e)
  {
    const int i = static_cast<int>(e);
    if (found.point(i) != kept.point(i) || std::abs(found.factor(i) - kept.factor(i)) > 1e-12)
      return ::testing::AssertionFailure() << "entry " << e << " differs";
  }
  return ::testing::AssertionSuccess();
}

} // namespace

TEST(WrinklesAfterCut, ARadialCutSplitsTheCurveAndTheLipsDoNotMoveEachOther)
{
  const CutMeniscus& m = boundMeniscus();
  TissueCutter cutter(m.binding, m.c.model.simulation);
  WrinkleGenerator g(m.c.monitors, cutter.simulation(), cutter.visual().mesh());
  const std::size_t before = g.monitors().size();
  // A radial cut through the whole meniscus at the middle of its inner
  // border: two pieces, each held by its horn. (A cut that stops inside a
  // hexahedron leaves its collision surface in one branch: no copy, and the
  // monitor points stay as they were.)
  const std::size_t middle = before / 2;
  const Vector3 p = m.c.monitors.monitorPoints[middle];
  const Vector3 inward = inwardAt(m.c.monitors, middle);
  const Vector3 up(0.0, 0.0, 10.0);
  const TissueCutReport report = cutter.cut(Blade::sweptSegment(
    p - 2.0 * inward - up, p - 2.0 * inward + up, p + 15.0 * inward - up, p + 15.0 * inward + up));
  ASSERT_TRUE(report.changed());
  ASSERT_FALSE(report.simulation.newHexahedra.empty());
  g.followCut(cutter, report);
  EXPECT_TRUE(influenceIsAsIfFound(g, cutter));
  EXPECT_EQ(g.monitors().curveCount(), 2u);
  EXPECT_GE(g.monitors().size(), before - 2); // at most a lone point at the cut
  EXPECT_EQ(g.monitorEmbedding().nodeCount(), cutter.simulation().nodeCount());

  // Pressed 1.6 mm before the cut, on the side of the lower indices.
  const Vector3 across = inward.cross(Vector3::UnitZ());
  const Vector3 contact = m.c.monitors.monitorPoints[middle - 10];
  const double contactSide = (contact - p).dot(across);
  pressAndRelease(g, cutter.simulation(), contact);
  ASSERT_TRUE(g.wrinkling());
  EXPECT_EQ(g.monitors().curveOf(g.windowBegin()), g.monitors().curveOf(g.windowEnd() - 1));
  const auto& rest = cutter.visual().mesh().positions;
  int near = 0;
  for (const int j : g.displacedPoints())
  {
    const Vector3 x = rest[j] - p;
    EXPECT_GT(x.dot(across) * contactSide, 0.0) << "visual vertex " << j << " across the cut";
    near += std::abs(x.dot(across)) < 1.0 ? 1 : 0;
  }
  EXPECT_GT(near, 0); // the lip on the pressed side does wrinkle
}

TEST(WrinklesAfterCut, APunchedOutPieceTakesItsMonitorPointsAndTheRestStillWrinkles)
{
  const CutMeniscus& m = boundMeniscus();
  TissueCutterSettings settings;
  settings.freePieces = FreePieceHandling::Drop;
  TissueCutter cutter(m.binding, m.c.model.simulation, nullptr, settings);
  WrinkleGenerator g(m.c.monitors, cutter.simulation(), cutter.visual().mesh());
  const std::size_t before = g.monitors().size();
  // A 2.5 mm bite centred on the inner edge, a quarter along the border.
  const std::size_t quarter = before / 4;
  const Vector3 centre =
    m.c.monitors.monitorPoints[quarter] - 0.5 * inwardAt(m.c.monitors, quarter);
  const TissueCutReport report = cutter.cut(punchAt(centre, 2.5));
  ASSERT_TRUE(report.changed());
  ASSERT_GE(report.removedPieces, 1);
  g.followCut(cutter, report);
  EXPECT_TRUE(influenceIsAsIfFound(g, cutter));
  const std::size_t dropped = before - g.monitors().size();
  EXPECT_GT(dropped, 15u); // about 2 x 2.5 mm of border at 0.16 mm
  EXPECT_LT(dropped, 45u);
  EXPECT_EQ(g.monitors().curveCount(), 2u);
  for (const Vector3& x : g.monitors().monitorPoints)
  {
    EXPECT_GT((x - centre).head<2>().norm(), 2.0); // none left inside the bite
  }
  // The remaining rim wrinkles, beside the hole and far from it.
  for (const std::size_t at : { quarter + 25, 3 * before / 4 })
  {
    WrinkleGenerator fresh = g;
    const Vector3 contact = m.c.monitors.monitorPoints[at];
    pressAndRelease(fresh, cutter.simulation(), contact);
    EXPECT_TRUE(fresh.wrinkling()) << "pressed at monitor point " << at;
    EXPECT_FALSE(fresh.displacedPoints().empty());
    const auto active = cutter.activeVisualTriangles();
    std::vector<char> shown(cutter.visual().mesh().vertexCount(), 0);
    for (std::size_t t = 0; t < active.size(); ++t)
    {
      for (const int v : cutter.visual().mesh().triangles[t])
      {
        shown[v] = shown[v] || active[t];
      }
    }
    for (const int j : fresh.displacedPoints())
    {
      EXPECT_TRUE(shown[j]) << "a removed visual vertex moves: " << j;
    }
  }
}

namespace
{

/// Same monitor points, entries and factors, bit for bit.
::testing::AssertionResult sameInfluence(const WrinkleInfluence& a, const WrinkleInfluence& b)
{
  if (a.monitorCount() != b.monitorCount() || a.entryCount() != b.entryCount())
    return ::testing::AssertionFailure()
           << a.monitorCount() << " monitor points and " << a.entryCount() << " entries against "
           << b.monitorCount() << " and " << b.entryCount();
  for (std::size_t i = 0; i < a.monitorCount(); ++i)
    if (a.affectedBegin(i) != b.affectedBegin(i) || a.affectedEnd(i) != b.affectedEnd(i))
      return ::testing::AssertionFailure() << "monitor point " << i << "'s entries differ";
  for (int e = 0; e < static_cast<int>(a.entryCount()); ++e)
    if (a.point(e) != b.point(e) || a.factor(e) != b.factor(e))
      return ::testing::AssertionFailure() << "entry " << e << " differs";
  if (a.affectedPoints() != b.affectedPoints())
    return ::testing::AssertionFailure() << "the affected points differ";
  return ::testing::AssertionSuccess();
}

} // namespace

// Issue 17's bite step: the influence refresh after a cut spread over the
// following updates ends where the refresh inside followCut ends, also
// across a second cut while one is pending; wrinkles made in the meantime
// use a valid influence (the entries from before the cut), and the same
// wrinkles once it has ended.
TEST(WrinklesAfterCut, ATimeSlicedRefreshEndsAsTheWholeOneBitForBit)
{
  const CutMeniscus& m = boundMeniscus();
  TissueCutterSettings settings;
  settings.freePieces = FreePieceHandling::Drop;
  TissueCutter cutter(m.binding, m.c.model.simulation, nullptr, settings);
  WrinkleParameters sliced;
  sliced.refreshMonitorsPerUpdate = 4;
  WrinkleGenerator whole(m.c.monitors, cutter.simulation(), cutter.visual().mesh());
  WrinkleGenerator spread(m.c.monitors, cutter.simulation(), cutter.visual().mesh(), sliced);
  ASSERT_TRUE(sameInfluence(whole.influence(), spread.influence()));
  const std::size_t count = m.c.monitors.size();
  const auto biteAt = [&](std::size_t i)
  { return punchAt(m.c.monitors.monitorPoints[i] - 0.5 * inwardAt(m.c.monitors, i), 2.0); };

  TissueCutReport report = cutter.cut(biteAt(count / 4));
  ASSERT_GE(report.removedPieces, 1);
  whole.followCut(cutter, report);
  spread.followCut(cutter, report);
  ASSERT_TRUE(spread.influence().refreshPending());
  const std::size_t pending = spread.influence().pendingMonitorCount();
  EXPECT_GT(pending, 8u); // the monitor points around the bite
  EXPECT_FALSE(whole.influence().refreshPending());
  // Meanwhile: one entry range per monitor point, points of the surface.
  const WrinkleInfluence& interim = spread.influence();
  ASSERT_EQ(interim.monitorCount(), spread.monitors().size());
  for (int e = 0; e < static_cast<int>(interim.entryCount()); ++e)
  {
    ASSERT_LT(static_cast<std::size_t>(interim.point(e)), cutter.visual().mesh().vertexCount());
    ASSERT_TRUE(std::isfinite(interim.factor(e)) && interim.factor(e) >= 0.0);
  }

  // Pressed right after the cut: the same wrinkles once the refresh ended.
  {
    WrinkleGenerator a = whole, b = spread;
    const Vector3 contact = a.monitors().monitorPoints[a.monitors().size() / 2];
    pressAndRelease(a, cutter.simulation(), contact);
    pressAndRelease(b, cutter.simulation(), contact);
    ASSERT_FALSE(b.influence().refreshPending());
    EXPECT_TRUE(sameInfluence(a.influence(), b.influence()));
    std::vector<Vector3> movedA = cutter.visual().mesh().positions, movedB = movedA;
    a.applyTo(movedA);
    b.applyTo(movedB);
    EXPECT_EQ(movedA, movedB);
  }

  // Left alone: none in the update of the cut's own step, then 4 an update.
  const WrinkleContactState none;
  spread.update(cutter.simulation().nodes, none);
  EXPECT_EQ(spread.influence().pendingMonitorCount(), pending);
  spread.update(cutter.simulation().nodes, none);
  EXPECT_EQ(spread.influence().pendingMonitorCount(), pending - 4);
  // A second bite while that one is pending.
  report = cutter.cut(biteAt(3 * count / 4));
  ASSERT_GE(report.removedPieces, 1);
  whole.followCut(cutter, report);
  spread.followCut(cutter, report);
  int updates = 0;
  while (spread.influence().refreshPending() && updates < 1000)
  {
    spread.update(cutter.simulation().nodes, none);
    ++updates;
  }
  EXPECT_GT(updates, 1);
  EXPECT_TRUE(sameInfluence(whole.influence(), spread.influence()));
  EXPECT_TRUE(influenceIsAsIfFound(spread, cutter));
}

TEST(WrinklesAfterCut, ANegativeRefreshBudgetIsRefused)
{
  WrinkleParameters p;
  p.refreshMonitorsPerUpdate = -1;
  EXPECT_THROW(checkWrinkleParameters(p), InvalidInputError);
}
