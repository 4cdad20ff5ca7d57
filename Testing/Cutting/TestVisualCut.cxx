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

#include <random>

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
      pair.cut(Blade::sweptSegment(a - Vector3(0, 0, 5),
        a + Vector3(0, 0, 5),
        b - Vector3(0, 0, 5),
        b + Vector3(0, 0, 5)));
      ASSERT_TRUE(visualMeshIsValid(pair.visual, pair.collision))
        << "run " << run << ", cut " << c;
    }
  }
}

