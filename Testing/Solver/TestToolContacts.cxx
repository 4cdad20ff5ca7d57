// A rigid capsule tool against a deformable collision mesh with radii
// (collision issue: detection + response through the implicit FEM).
#include "SoftTissueMaterial.h"
#include "ThinSheetModel.h"
#include "ToolContacts.h"

#include <gtest/gtest.h>

using namespace thintissue;
using thintissue::test::softTissue;

namespace
{
/// A vertical probe: a capsule from high above down to `tip`.
std::vector<ToolCapsule> probeAt(const Vector3& tip, double radius)
{
  return { ToolCapsule{ tip + Vector3(0.0, 0.0, 60.0), tip, radius } };
}

struct SheetScene
{
  TissueModel sheet;
  CorotationalHexFem fem;
  DeformableCollisionMesh collision;
  double stiffness = 50.0;

  explicit SheetScene(int collisionModel)
    : sheet(makeThinSheet(thesisSheetCollisionResolution(collisionModel)))
    , fem(sheet.simulation,
        softTissue(),
        []
        {
          CorotationalHexFemSettings s;
          s.timeStep = 0.01;
          return s;
        }())
    , collision(sheet.collision, sheet.simulation)
  {
  }

  std::vector<ToolContact> step(const std::vector<ToolCapsule>& tool)
  {
    collision.update(fem.positions());
    std::vector<EmbeddedContact> springs;
    std::vector<ToolContact> contacts;
    findToolContacts(collision, tool, stiffness, 0.1, springs, contacts);
    fem.setContacts(springs);
    EXPECT_TRUE(fem.step().ok);
    return contacts;
  }

  Vector3 toolReaction() const
  {
    Vector3 total = Vector3::Zero();
    for (const auto& f : fem.contactForces())
    {
      total -= f;
    }
    return total;
  }
};
} // namespace

TEST(ToolContacts, ProbeStopsAtTheRadiusAndReleases)
{
  SheetScene scene(2);
  const double probeRadius = 1.5;
  Vector3 tip(0.0, 0.0, 1.0 + probeRadius + 1.0); // 1 mm above first touch
  std::vector<ToolContact> contacts;
  for (int k = 0; k < 300; ++k)
  {
    if (k < 80)
    {
      tip.z() -= 0.05; // 3 mm past first touch
    }
    contacts = scene.step(probeAt(tip, probeRadius));
  }
  ASSERT_EQ(contacts.size(), 1u);
  const Vector3 reaction = scene.toolReaction();
  EXPECT_GT(reaction.z(), 0.0); // the tissue pushes the tool up
  // Stopped at the radii: what overlap remains is what the penalty needs.
  EXPECT_NEAR(contacts[0].depth, reaction.norm() / scene.stiffness, 0.05);
  EXPECT_LT(contacts[0].depth, 0.1);
  EXPECT_EQ(contacts[0].side, 1); // touching the upper surface
  // Withdraw: no contact, no force.
  tip.z() += 30.0;
  EXPECT_TRUE(scene.step(probeAt(tip, probeRadius)).empty());
  EXPECT_EQ(scene.toolReaction().norm(), 0.0);
}

TEST(ToolContacts, ToolReactionIsMinusTheForceOnTheTissue)
{
  SheetScene scene(1);
  const Vector3 tip(7.0, -4.0, 1.0 + 1.5 - 0.4);
  ASSERT_FALSE(scene.step(probeAt(tip, 1.5)).empty());
  // H^T of the applied spring forces, summed over the nodes.
  Vector3 onTissue = Vector3::Zero();
  for (std::size_t k = 0; k < scene.fem.contacts().size(); ++k)
  {
    const auto weights = trilinearWeights(scene.fem.contacts()[k].local);
    for (int a = 0; a < 8; ++a)
    {
      onTissue += weights[a] * scene.fem.contactForces()[k];
    }
  }
  EXPECT_LT((onTissue + scene.toolReaction()).norm(), 1e-12 * (1.0 + onTissue.norm()));
  EXPECT_GT(onTissue.norm(), 0.0);
}

TEST(ToolContacts, NoTunnellingAtOneRadiusPerStep)
{
  SheetScene scene(2);
  scene.stiffness = 200.0;
  const double probeRadius = 1.0;
  Vector3 tip(0.0, 0.0, 1.0 + probeRadius + 0.5);
  for (int k = 0; k < 15; ++k)
  {
    tip.z() -= probeRadius; // speed = radius / time step
    const auto contacts = scene.step(probeAt(tip, probeRadius));
    for (const auto& c : contacts)
    {
      EXPECT_EQ(c.side, 1) << "step " << k; // always from above
      EXPECT_GT(c.normal.z(), 0.0) << "step " << k;
    }
  }
  // The sheet went down with the probe instead of letting it through: the
  // collision vertex nearest the tip's axis is still below the tip.
  const auto& positions = scene.collision.positions();
  std::size_t nearest = 0;
  for (std::size_t v = 0; v < positions.size(); ++v)
  {
    if (positions[v].head<2>().norm() < positions[nearest].head<2>().norm())
    {
      nearest = v;
    }
  }
  EXPECT_LT(positions[nearest].z(), tip.z());
  EXPECT_LT(positions[nearest].z(), -3.0); // and it was pushed a long way
}

TEST(ToolContacts, ReducedAndFullMeshesAgreeOnAFlatSheet)
{
  // Same flat geometry at 65 and 796 collision vertices: same contact.
  const TissueModel coarse = makeThinSheet(thesisSheetCollisionResolution(1));
  const TissueModel fine = makeThinSheet(thesisSheetCollisionResolution(3));
  const DeformableCollisionMesh a(coarse.collision, coarse.simulation);
  const DeformableCollisionMesh b(fine.collision, fine.simulation);
  const auto tool = probeAt(Vector3(3.3, -7.1, 1.0 + 2.0 - 0.25), 2.0);
  std::vector<EmbeddedContact> springsA, springsB;
  std::vector<ToolContact> contactsA, contactsB;
  findToolContacts(a, tool, 10.0, 0.0, springsA, contactsA);
  findToolContacts(b, tool, 10.0, 0.0, springsB, contactsB);
  ASSERT_EQ(contactsA.size(), 1u);
  ASSERT_EQ(contactsB.size(), 1u);
  EXPECT_NEAR(contactsA[0].depth, 0.25, 1e-9);
  EXPECT_NEAR(contactsB[0].depth, contactsA[0].depth, 1e-9);
  EXPECT_LT((contactsB[0].point - contactsA[0].point).norm(), 1e-9);
  EXPECT_LT((contactsB[0].normal - contactsA[0].normal).norm(), 1e-9);
  double stiffnessA = 0.0;
  double stiffnessB = 0.0;
  for (const auto& s : springsA)
    stiffnessA += s.stiffness;
  for (const auto& s : springsB)
    stiffnessB += s.stiffness;
  EXPECT_NEAR(stiffnessA, 10.0, 1e-9);
  EXPECT_NEAR(stiffnessB, 10.0, 1e-9);
}

TEST(ToolContacts, PressedOntoAnObstacleTheLowerSurfaceTouches)
{
  // The table 6-2 situation in miniature: the probe presses the tissue down
  // onto a rigid floor 2 mm below it; contacts with the floor appear and all
  // are on the tissue's lower surface.
  SheetScene scene(2);
  TriangleMesh floor;
  floor.name = "floor";
  floor.positions = {
    Vector3(-80, -80, -3), Vector3(80, -80, -3), Vector3(80, 80, -3), Vector3(-80, 80, -3)
  };
  floor.triangles = { { 0, 1, 2 }, { 0, 2, 3 } };
  const StaticObstacle obstacle(floor);
  Vector3 tip(0.0, 0.0, 1.0 + 1.5 + 0.5);
  std::size_t before = 0;
  std::size_t after = 0;
  for (int k = 0; k < 200; ++k)
  {
    if (k < 100)
    {
      tip.z() -= 0.028; // 2.8 mm down: across the 2 mm gap, squeezing 0.3 mm
    }
    scene.collision.update(scene.fem.positions());
    std::vector<EmbeddedContact> springs;
    std::vector<ToolContact> toolContacts;
    std::vector<ObstacleContact> floorContacts;
    findToolContacts(scene.collision, probeAt(tip, 1.5), 200.0, 0.1, springs, toolContacts);
    findObstacleContacts(scene.collision, obstacle, 200.0, 0.1, springs, floorContacts);
    scene.fem.setContacts(springs);
    ASSERT_TRUE(scene.fem.step().ok);
    for (const auto& c : floorContacts)
    {
      EXPECT_EQ(c.tissueSide, -1);
      EXPECT_GT(c.normal.z(), 0.99);
    }
    if (k == 0)
    {
      before = floorContacts.size();
    }
    after = floorContacts.size();
  }
  EXPECT_EQ(before, 0u);
  EXPECT_GT(after, 0u);
  // The floor holds the tissue: nothing sinks much below it.
  for (const auto& p : scene.collision.positions())
  {
    EXPECT_GT(p.z(), -3.0 - 0.2);
  }
}
