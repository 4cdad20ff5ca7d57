// Cutting the visual mesh through the binding (thesis 5.3.2 - 5.3.4): the
// visual surface follows every collision cut, stays closed with its cut
// surfaces, and every visual vertex stays bound.
#include "CollisionMeshCut.h"
#include "CuttingInvariants.h"
#include "MeniscusModel.h"
#include "ThinSheetModel.h"
#include "VisualCollisionBinding.h"
#include "VisualMeshCut.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <string>

using namespace thintissue;
using namespace thintissue::cutting_test;

namespace
{

const TissueModel& sheet()
{
  static const TissueModel model = makeThinSheet(thesisSheetVisualResolution(1));
  return model;
}

const VisualCollisionBinding& sheetBinding()
{
  static const VisualCollisionBinding binding =
    bindVisualToCollision(sheet().visual, sheet().collision);
  return binding;
}

/// The collision and visual meshes of a bound tissue, cut together.
struct CutPair
{
  CuttableCollisionMesh collision;
  CuttableVisualMesh visual;

  explicit CutPair(const VisualCollisionBinding& binding, int rows = 1)
    : collision("collision",
        binding.collisionPositions,
        binding.collisionTriangles,
        binding.collisionRadii)
    , visual(binding, VisualCutSettings{ rows })
  {
  }
  VisualCutResult cut(const Blade& blade)
  {
    const CollisionCutResult c = collision.cut(blade, collision.restPositions());
    return visual.cut(collision, c);
  }
};

/// A vertical scalpel at x = `x` swept along y from y0 to y1 (the sheet
/// lies in z = 0, 100 mm square centred on the origin).
Blade scalpelAlongY(double x, double y0, double y1)
{
  return Blade::sweptSegment(
    Vector3(x, y0, -5), Vector3(x, y0, 5), Vector3(x, y1, -5), Vector3(x, y1, 5));
}

} // namespace

TEST(VisualCut, UncutSheetIsValid)
{
  CutPair pair(sheetBinding());
  EXPECT_TRUE(visualMeshIsValid(pair.visual, pair.collision));
}

TEST(VisualCut, HalfwayCutOpensTheVisualSurfaceAndClosesItWithACutSurface)
{
  CutPair pair(sheetBinding());
  const std::size_t before = pair.visual.mesh().vertexCount();
  const VisualCutResult result = pair.cut(scalpelAlongY(3.0, -80.0, 1.0));
  EXPECT_TRUE(result.changed());
  EXPECT_GT(pair.visual.mesh().vertexCount(), before);
  EXPECT_GT(pair.visual.cutSurfaceTriangleCount(), 0u);
  EXPECT_TRUE(visualMeshIsValid(pair.visual, pair.collision));
}

TEST(VisualCut, CutThroughSeparatesTheVisualSurfaceIntoTwoClosedPieces)
{
  CutPair pair(sheetBinding());
  pair.cut(scalpelAlongY(3.0, -80.0, 80.0));
  int pieces = 0;
  collisionPieces(pair.collision, pieces);
  EXPECT_EQ(pieces, 2);
  EXPECT_TRUE(visualMeshIsValid(pair.visual, pair.collision));
}

TEST(VisualCut, ProgressiveCutsStayClosed)
{
  CutPair pair(sheetBinding());
  for (int step = 0; step < 8; ++step)
  {
    const double y0 = -60.0 + 12.0 * step;
    pair.cut(scalpelAlongY(-7.0 + 0.5 * step, y0, y0 + 12.0));
    ASSERT_TRUE(visualMeshIsValid(pair.visual, pair.collision)) << "after step " << step;
  }
}

TEST(VisualCut, RandomSweepsKeepTheVisualMeshValid)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-60.0, 60.0);
  for (int run = 0; run < 20; ++run)
  {
    CutPair pair(sheetBinding(), run % 3);
    for (int c = 0; c < 4; ++c)
    {
      const Vector3 a(coordinate(random), coordinate(random), 0.0);
      const Vector3 b(coordinate(random), coordinate(random), 0.0);
      pair.cut(Blade::sweptSegment(
        a - Vector3(0, 0, 5), a + Vector3(0, 0, 5), b - Vector3(0, 0, 5), b + Vector3(0, 0, 5)));
      ASSERT_TRUE(visualMeshIsValid(pair.visual, pair.collision)) << "run " << run << ", cut " << c;
    }
  }
}

// The regions of a cut traced and rebound on several threads give the
// same visual mesh and binding, bit for bit, as on one (the simulator
// replays sessions exactly).
TEST(VisualCut, RegionsOnSeveralThreadsCutBitForBitAsOnOne)
{
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coordinate(-60.0, 60.0);
  for (int run = 0; run < 6; ++run)
  {
    VisualCutSettings serial{ run % 3 };
    serial.parallelRegionTriangles = std::numeric_limits<std::size_t>::max();
    VisualCutSettings parallel = serial;
    parallel.parallelRegionTriangles = 0;
    CutPair one(sheetBinding(), run % 3);
    CutPair several(sheetBinding(), run % 3);
    one.visual.setSettings(serial);
    several.visual.setSettings(parallel);
    for (int c = 0; c < 4; ++c)
    {
      const Vector3 a(coordinate(random), coordinate(random), 0.0);
      const Vector3 b(coordinate(random), coordinate(random), 0.0);
      const Blade blade = Blade::sweptSegment(
        a - Vector3(0, 0, 5), a + Vector3(0, 0, 5), b - Vector3(0, 0, 5), b + Vector3(0, 0, 5));
      const VisualCutResult x = one.cut(blade);
      const VisualCutResult y = several.cut(blade);
      const std::string where = "run " + std::to_string(run) + ", cut " + std::to_string(c);
      EXPECT_EQ(x.newVertices, y.newVertices) << where;
      EXPECT_EQ(x.reboundVertices, y.reboundVertices) << where;
      EXPECT_EQ(x.changedTriangles, y.changedTriangles) << where;
      ASSERT_TRUE(sameVisualMesh(one.visual, several.visual)) << where;
      ASSERT_TRUE(visualMeshIsValid(several.visual, several.collision)) << where;
    }
  }
}

namespace
{

/// Formula 5-1: where a visual vertex projects on the collision mesh.
Vector3 projected(const CuttableVisualMesh& visual, const CuttableCollisionMesh& collision, int v)
{
  const VisualVertexBinding b = visual.binding(static_cast<int>(v));
  const auto& x = collision.restPositions();
  switch (b.kind)
  {
    case BindingKind::CollisionVertex:
      return x[b.element];
    case BindingKind::CollisionEdge:
    {
      const auto& e = visual.collisionEdges()[b.element];
      return b.parameters[0] * x[e[0]] + b.parameters[1] * x[e[1]];
    }
    default:
    {
      const Triangle& t = collision.triangles()[b.element];
      return b.parameters[0] * x[t[0]] + b.parameters[1] * x[t[1]] + b.parameters[2] * x[t[2]];
    }
  }
}

} // namespace

TEST(VisualCut, RebindingKeepsEveryVisualVertexWhereItProjected)
{
  // Formula 5-2 for vertices inside split triangles, rescaled accumulated
  // length for vertices on split edges: the point each projects to on the
  // collision mesh (formula 5-1) does not move (the second cut crosses the
  // first).
  CutPair pair(sheetBinding());
  const std::size_t before = pair.visual.mesh().vertexCount();
  std::vector<Vector3> was;
  for (std::size_t v = 0; v < before; ++v)
    was.push_back(projected(pair.visual, pair.collision, static_cast<int>(v)));
  const std::vector<VisualVertexBinding> old = pair.visual.bindings();
  pair.cut(scalpelAlongY(3.3, -80.0, 80.0));
  pair.cut(Blade::sweptSegment(
    Vector3(-80, 7.1, -5), Vector3(-80, 7.1, 5), Vector3(80, 4.2, -5), Vector3(80, 4.2, 5)));
  int checked = 0, rebound = 0;
  for (std::size_t v = 0; v < before; ++v)
  {
    const VisualVertexBinding b = pair.visual.binding(static_cast<int>(v));
    if (b.kind != old[v].kind)
      continue; // an inner vertex the cut passed through: now on the cut
    rebound += b.element != old[v].element ? 1 : 0;
    // Exact but where a cut snapped onto a visual vertex within a thousandth
    // of a visual edge (the sheet's are 2.5 mm).
    EXPECT_LT((projected(pair.visual, pair.collision, static_cast<int>(v)) - was[v]).norm(), 3e-3)
      << "visual vertex " << v << " was kind " << int(old[v].kind) << " element " << old[v].element
      << " t " << old[v].parameters.transpose() << ", is element " << b.element << " t "
      << b.parameters.transpose() << " edge "
      << (b.kind == BindingKind::CollisionEdge ? pair.visual.collisionEdges()[b.element][0] : -1)
      << "-"
      << (b.kind == BindingKind::CollisionEdge ? pair.visual.collisionEdges()[b.element][1] : -1);
    ++checked;
  }
  EXPECT_GT(rebound, 100);
  EXPECT_GT(checked, static_cast<int>(before) - 20);
  EXPECT_TRUE(visualMeshIsValid(pair.visual, pair.collision));
}

TEST(VisualCut, CutSurfaceResolutionFollowsTheRowCount)
{
  // Fig. 5-12(c): more in-between rows, a finer cut surface.
  std::vector<std::size_t> triangles, vertices;
  for (int rows : { 0, 1, 3 })
  {
    CutPair pair(sheetBinding(), rows);
    const std::size_t start = pair.visual.mesh().vertexCount();
    pair.cut(scalpelAlongY(3.0, -80.0, 80.0));
    ASSERT_TRUE(visualMeshIsValid(pair.visual, pair.collision)) << rows << " rows";
    triangles.push_back(pair.visual.cutSurfaceTriangleCount());
    vertices.push_back(pair.visual.mesh().vertexCount() - start);
  }
  EXPECT_LT(triangles[0], triangles[1]);
  EXPECT_LT(triangles[1], triangles[2]);
  EXPECT_LT(vertices[0], vertices[1]);
  EXPECT_LT(vertices[1], vertices[2]);
}

TEST(VisualCut, ACutAcrossACutSplitsItsCutSurface)
{
  // Fig. 5-13: the second cut crosses the first one's opened edges; their
  // cut surfaces are split by parameter and the sheet falls into four.
  CutPair pair(sheetBinding(), 2);
  pair.cut(scalpelAlongY(3.0, -80.0, 80.0));
  const std::size_t surface = pair.visual.cutSurfaceTriangleCount();
  pair.cut(Blade::sweptSegment(
    Vector3(-80, 6.0, -5), Vector3(-80, 6.0, 5), Vector3(80, 6.0, -5), Vector3(80, 6.0, 5)));
  int pieces = 0;
  collisionPieces(pair.collision, pieces);
  EXPECT_EQ(pieces, 4);
  EXPECT_GT(pair.visual.cutSurfaceTriangleCount(), surface);
  EXPECT_TRUE(visualMeshIsValid(pair.visual, pair.collision));
}

TEST(VisualCut, ABadSettingIsRefused)
{
  EXPECT_THROW(CuttableVisualMesh(sheetBinding(), VisualCutSettings{ -1 }), InvalidInputError);
}
