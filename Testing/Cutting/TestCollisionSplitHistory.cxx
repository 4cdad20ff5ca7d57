// The split history of the collision triangles (the lazy binding's first
// stage, issue 13): a binding taken before any number of cuts resolves to
// the binding the eager cut made, bit for bit.
#include "CollisionMeshCut.h"
#include "CollisionSplitHistory.h"
#include "MeniscusModel.h"
#include "ThinSheetModel.h"
#include "ThinTissueError.h"
#include "VisualCollisionBinding.h"
#include "VisualMeshCut.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

using namespace thintissue;

namespace
{

/// What the comparison saw over one run of cuts.
struct Comparison
{
  std::size_t compared = 0;   ///< inner vertices, resolved and eager
  std::size_t moved = 0;      ///< of those, now bound to another node
  std::size_t mismatched = 0; ///< node or parameters not the eager ones
  std::string firstMismatch;
};

bool inner(const VisualVertexBinding& b)
{
  return b.kind == BindingKind::CollisionTriangle && b.parameters.minCoeff() > 0.0;
}

/// Every visual vertex bound inside a collision triangle at the start and
/// still bound inside one now, resolved from its first binding.
void compare(const std::vector<VisualVertexBinding>& first,
  const CuttableVisualMesh& visual,
  Comparison& seen)
{
  const CollisionSplitHistory& history = visual.splitHistory();
  for (std::size_t v = 0; v < first.size(); ++v)
  {
    const VisualVertexBinding now = visual.binding(static_cast<int>(v));
    if (!inner(first[v]) || !inner(now))
      continue;
    // Before any cut, node t is triangle t.
    const CollisionSplitHistory::Resolved resolved =
      history.resolve(first[v].element, first[v].parameters);
    ++seen.compared;
    seen.moved += resolved.node != first[v].element ? 1 : 0;
    const bool same = history.isCurrent(resolved.node) &&
                      history.triangleOf(resolved.node) == now.element &&
                      resolved.parameters == now.parameters;
    if (!same && seen.mismatched++ == 0)
      seen.firstMismatch = "vertex " + std::to_string(v) + ": resolved to triangle " +
                           std::to_string(history.triangleOf(resolved.node)) + ", eager " +
                           std::to_string(now.element);
  }
}

/// Random straight cuts across a tissue's box (vertical blades through its
/// whole thickness), each compared with the history after it.
Comparison cutAndCompare(const TissueModel& model, unsigned seed, int cuts)
{
  const VisualCollisionBinding binding = bindVisualToCollision(model.visual, model.collision);
  CuttableCollisionMesh collision(
    model.name, binding.collisionPositions, binding.collisionTriangles, binding.collisionRadii);
  VisualCutSettings settings;
  settings.separatedRegionTriangles = 0; // the far path too
  settings.lazyBinding = false;          // the eager binding, compared
  CuttableVisualMesh visual(binding, settings);
  const std::vector<VisualVertexBinding> first = visual.bindings();
  const BoundingBox box = model.collision.boundingBox();
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.1, 0.9);
  const Vector3 up = Vector3::UnitZ() * box.sizes().norm();
  Comparison seen;
  for (int c = 0; c < cuts; ++c)
  {
    auto point = [&]
    {
      return Vector3(box.min().x() + unit(random) * box.sizes().x(),
        box.min().y() + unit(random) * box.sizes().y(),
        box.center().z());
    };
    const Vector3 a = point(), b = point();
    const CollisionCutResult cut =
      collision.cut(Blade::sweptSegment(a - up, a + up, b - up, b + up), collision.restPositions());
    visual.cut(collision, cut);
    compare(first, visual, seen);
  }
  EXPECT_GT(visual.splitHistory().splitCount(), 0u) << model.name;
  return seen;
}

/// Rest corners of triangle 0: (0,0,0) (1,0,0) (0,1,0).
const std::vector<Vector3> unitTriangle{ Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0) };

/// A split of `parent` (corners 0, 1, 2 of unitTriangle) into two pieces,
/// the second `second`, at the midpoint m of its second side: (v0, v1, m)
/// and (v0, m, v2).
CollisionTriangleSplit midpointSplit(int parent, int second)
{
  CollisionTriangleSplit split;
  split.parent = parent;
  split.parentCorners = { { 0, 1, 2 } };
  split.children = { parent, second };
  split.childCorners = { { { Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0.5, 0.5) } },
    { { Vector3(1, 0, 0), Vector3(0, 0.5, 0.5), Vector3(0, 0, 1) } } };
  return split;
}

} // namespace

TEST(CollisionSplitHistory, AnUnsplitTriangleResolvesToItself)
{
  CollisionSplitHistory history(3);
  const Vector3 p(0.2, 0.3, 0.5);
  const auto resolved = history.resolve(2, p);
  EXPECT_EQ(resolved.node, 2);
  EXPECT_EQ(resolved.parameters, p);
  EXPECT_TRUE(history.isCurrent(2));
}

TEST(CollisionSplitHistory, APointGoesToThePieceItLiesInWithFormula52)
{
  CollisionSplitHistory history(1);
  history.recordSplit(midpointSplit(0, 1), unitTriangle);
  EXPECT_FALSE(history.isCurrent(0));
  ASSERT_EQ(history.nodeCount(), 3u);
  // (0.6, 0.3, 0.1) lies below the median from v0 (b > c): the first piece.
  const auto below = history.resolve(0, Vector3(0.6, 0.3, 0.1));
  EXPECT_EQ(history.triangleOf(below.node), 0);
  EXPECT_TRUE(history.isCurrent(below.node));
  // In (v0, v1, m): x = a v0 + b v1 + c m, so b = 0.3 - 0.1, c = 0.2.
  EXPECT_NEAR(below.parameters[0], 0.6, 1e-15);
  EXPECT_NEAR(below.parameters[1], 0.2, 1e-15);
  EXPECT_NEAR(below.parameters[2], 0.2, 1e-15);
  const auto above = history.resolve(0, Vector3(0.6, 0.1, 0.3));
  EXPECT_EQ(history.triangleOf(above.node), 1);
  EXPECT_NEAR(above.parameters[1], 0.2, 1e-15);
  EXPECT_NEAR(above.parameters[2], 0.2, 1e-15);
}

TEST(CollisionSplitHistory, ABadSplitIsRefusedAndChangesNothing)
{
  CollisionSplitHistory history(2);
  EXPECT_THROW(history.recordSplit(midpointSplit(4, 9), unitTriangle), InvalidInputError);
  const CollisionTriangleSplit split = midpointSplit(1, 9);
  CollisionCutResult cut;
  cut.splits = { split };
  try
  {
    history.recordCut(cut, unitTriangle);
    ADD_FAILURE() << "a piece past the triangles known was accepted";
  }
  catch (const InvalidInputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("skips past"), std::string::npos) << e.what();
  }
  EXPECT_EQ(history.nodeCount(), 2u);
  EXPECT_EQ(history.splitCount(), 0u);
}

TEST(CollisionSplitHistory, BindingsBeforeTheCutsResolveToTheEagerBindingsOnTheSheet)
{
  for (unsigned seed : { 3u, 17u })
  {
    const Comparison seen = cutAndCompare(makeThinSheet(thesisSheetVisualResolution(1)), seed, 5);
    EXPECT_GT(seen.moved, 100u) << "seed " << seed;
    EXPECT_EQ(seen.mismatched, 0u)
      << "seed " << seed << ", of " << seen.compared << "; first " << seen.firstMismatch;
  }
}

TEST(CollisionSplitHistory, BindingsBeforeTheCutsResolveToTheEagerBindingsOnTheMeniscus)
{
  const Comparison seen = cutAndCompare(makeMeniscus(), 5u, 4);
  EXPECT_GT(seen.moved, 50u);
  EXPECT_EQ(seen.mismatched, 0u) << "of " << seen.compared << "; first " << seen.firstMismatch;
}
