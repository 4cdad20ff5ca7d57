// Property test of the surgical operations (thesis 6.4; issue: surgical
// operations, validation): random punch bites, shaver bites and contouring
// passes on the intact and every torn meniscus, with a jagged cut surface,
// and after every operation all the cutting invariants (closed, oriented,
// bound visual mesh; hexahedron copies at rest geometry; pieces that share
// no node; no NaN; the FEM steps), plus:
//  - a bite removes what it cut loose: the tissue's visual volume drops by
//    the removed pieces' volume (within the jaggedness and the zipping of
//    the two lips' cut surfaces), and every removed piece reaches into the
//    bite (its outline grown by the collision mesh's resolution);
//  - a contouring pass removes nothing (collision mesh, active area,
//    visual triangles and volume within the jaggedness unchanged) and does
//    not roughen the rim; over an episode it smooths it.
// 500 operations per tissue, 2,500 in all; THINTISSUE_CUT_SOAK=N runs N
// times as many. On the horizontally cleaved meniscus a bite through the
// body and one leaf past a junction vertex cracks the other leaf there
// (CuttableCollisionMesh::notchedJunctionCut); before, the visual cut
// refused it by name within 200 operations.
#include "RandomOperations.h"

#include <gtest/gtest.h>

using namespace thintissue;
using namespace thintissue::cutting_test;
using namespace thintissue::operations_test;

namespace
{

void operateOn(MeniscusTearType tear, unsigned seed)
{
  MeniscusParameters parameters;
  parameters.tear = defaultMeniscusTear(tear);
  const MeniscusModel meniscus = makeMeniscus(parameters);
  const VisualCollisionBinding binding = bindVisualToCollision(meniscus.visual, meniscus.collision);
  const OperatedTissue tissue{
    meniscus.name, binding, meniscus.simulation, meniscus.monitorCurves
  };
  RandomOperations operations(tissue, seed);
  operations.run(10 * soakScale(), 50);
  EXPECT_EQ(operations.Operations, 500 * soakScale());
  // The random poses reach the tissue: bites that remove, and passes that
  // smooth, in every tissue.
  EXPECT_GT(operations.Removals, 10) << meniscus.name;
  EXPECT_GT(operations.Contours, 10) << meniscus.name;
}

} // namespace

TEST(OperationsProperty, RandomOperationsOnTheIntactMeniscusKeepEveryInvariant)
{
  operateOn(MeniscusTearType::None, 1801u);
}

TEST(OperationsProperty, RandomOperationsOnTheLongitudinallyTornMeniscusKeepEveryInvariant)
{
  operateOn(MeniscusTearType::Longitudinal, 1802u);
}

TEST(OperationsProperty, RandomOperationsOnTheRadiallyTornMeniscusKeepEveryInvariant)
{
  operateOn(MeniscusTearType::Radial, 1803u);
}

TEST(OperationsProperty, RandomOperationsOnTheFlapTornMeniscusKeepEveryInvariant)
{
  operateOn(MeniscusTearType::Flap, 1804u);
}

TEST(OperationsProperty, RandomOperationsOnTheHorizontallyCleavedMeniscusKeepEveryInvariant)
{
  operateOn(MeniscusTearType::HorizontalCleavage, 1805u);
}
