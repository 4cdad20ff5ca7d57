// Penalty contact on embedded points, linearised into the implicit step
// (the response part of the collision issue, thesis 5.1).
#include "CorotationalHexFem.h"
#include "HexahedralEmbedding.h"
#include "ThinSheetModel.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

using namespace thintissue;

namespace
{

/// A spherical probe against the sheet's collision vertices (thick points):
/// one contact per vertex whose sphere of radius `Radius` overlaps the probe.
struct ProbeScene
{
  TissueModel sheet = makeThinSheet(thesisSheetCollisionResolution(2));
  HexahedralEmbedding embedding{ sheet.simulation, sheet.collision.positions };
  CorotationalHexFem fem;
  std::vector<Vector3> collisionPositions;
  double stiffness = 50.0;

  static CorotationalHexFem makeFem(const TissueModel& sheet)
  {
    LinearMaterial material; // soft tissue in mm, N, s
    material.youngModulus = 0.5;
    material.poissonRatio = 0.45;
    material.density = 1.0e-9;
    CorotationalHexFemSettings settings;
    settings.timeStep = 0.01;
    return CorotationalHexFem(sheet.simulation, material, settings);
  }

  ProbeScene()
    : fem(makeFem(sheet))
  {
    collisionPositions.resize(embedding.pointCount());
  }

  /// Contacts with a probe of radius `probeRadius` at `centre`; returns them.
  std::vector<EmbeddedContact> detect(const Vector3& centre, double probeRadius)
  {
    embedding.mapPositions(fem.positions(), collisionPositions);
    const auto& radii = sheet.collisionRadii();
    std::vector<EmbeddedContact> contacts;
    for (std::size_t v = 0; v < collisionPositions.size(); ++v)
    {
      const Vector3 offset = collisionPositions[v] - centre;
      const double distance = offset.norm();
      const double depth = probeRadius + radii[v] - distance;
      if (depth > 0.0 && distance > 1e-12)
      {
        EmbeddedContact contact;
        contact.hexahedron = static_cast<std::size_t>(embedding.hexahedron(v));
        contact.local = embedding.localCoordinates(v);
        contact.normal = offset / distance;
        contact.depth = depth;
        contact.stiffness = stiffness;
        contact.damping = 0.1;
        contacts.push_back(contact);
      }
    }
    fem.setContacts(contacts);
    return contacts;
  }
};

Vector3 sum(const std::vector<Vector3>& vectors)
{
  Vector3 total = Vector3::Zero();
  for (const auto& v : vectors)
  {
    total += v;
  }
  return total;
}

} // namespace

TEST(EmbeddedContact, ProbeStopsAtTheRadiusAndReleases)
{
  ProbeScene scene;
  const double probeRadius = 3.0;
  const double halfThickness = 1.0;
  // Lower the probe onto the centre of the sheet, 2 mm below first touch,
  // then hold it there until the sheet settles.
  Vector3 centre(0.0, 0.0, halfThickness + probeRadius + 1.0);
  Vector3 lastReaction = Vector3::Zero();
  for (int k = 0; k < 400; ++k)
  {
    if (k < 60)
    {
      centre.z() -= 0.05;
    }
    scene.detect(centre, probeRadius);
    ASSERT_TRUE(scene.fem.step().ok);
    lastReaction = -sum(scene.fem.contactForces());
  }
  // The tissue pushes the tool up; the sheet is pressed down.
  EXPECT_GT(lastReaction.z(), 0.0);
  // The sheet gives way: the nearest collision vertex ends at the radius,
  // within the penetration the penalty allows (force / stiffness).
  scene.embedding.mapPositions(scene.fem.positions(), scene.collisionPositions);
  double nearest = 1e300;
  for (const auto& p : scene.collisionPositions)
  {
    nearest = std::min(nearest, (p - centre).norm());
  }
  const double tolerance = lastReaction.norm() / scene.stiffness;
  EXPECT_NEAR(nearest, probeRadius + halfThickness, tolerance + 1e-3);
  EXPECT_LT(scene.fem.positions()[0].z(), 10.0); // sanity: finite, moved little at edges

  // Withdraw: no contact, no force.
  centre.z() += 20.0;
  EXPECT_TRUE(scene.detect(centre, probeRadius).empty());
  ASSERT_TRUE(scene.fem.step().ok);
  EXPECT_EQ(sum(scene.fem.contactForces()).norm(), 0.0);
}

TEST(EmbeddedContact, TissueReceivesExactlyWhatTheToolGives)
{
  ProbeScene scene;
  // Over a collision vertex, 0.5 mm into its radius.
  const Vector3 centre = scene.sheet.collision.positions[100] + Vector3(0.2, -0.1, 1.0 + 3.0 - 0.5);
  const auto contacts = scene.detect(centre, 3.0);
  ASSERT_FALSE(contacts.empty());
  ASSERT_TRUE(scene.fem.step().ok);
  // Forces up to the nodes (H^T f) sum to the tool's reaction, reversed.
  std::vector<Vector3> nodeForces(scene.fem.nodeCount(), Vector3::Zero());
  for (std::size_t k = 0; k < contacts.size(); ++k)
  {
    const auto weights = trilinearWeights(contacts[k].local);
    for (int a = 0; a < 8; ++a)
    {
      nodeForces[scene.fem.hexahedronNodes(contacts[k].hexahedron)[a]] +=
        weights[a] * scene.fem.contactForces()[k];
    }
  }
  const Vector3 toolReaction = -sum(scene.fem.contactForces());
  EXPECT_LT((sum(nodeForces) + toolReaction).norm(), 1e-12 * (1.0 + toolReaction.norm()));
}

TEST(EmbeddedContact, StiffContactIsStableAtLargeTimeSteps)
{
  ProbeScene scene;
  scene.stiffness = 1.0e5; // 2e5 times the tissue's modulus
  CorotationalHexFemSettings settings = scene.fem.settings();
  settings.timeStep = 0.02;
  scene.fem.setSettings(settings);
  const Vector3 centre(0.0, 0.0, 1.0 + 3.0 - 1.5);
  for (int k = 0; k < 200; ++k)
  {
    scene.detect(centre, 3.0);
    ASSERT_TRUE(scene.fem.step().ok) << "step " << k;
  }
  for (const auto& p : scene.fem.positions())
  {
    ASSERT_TRUE(p.allFinite());
    EXPECT_LT(std::abs(p.z()), 10.0);
  }
}

TEST(EmbeddedContact, InvalidContactsAreRejected)
{
  ProbeScene scene;
  EmbeddedContact contact;
  contact.hexahedron = 1000;
  EXPECT_THROW(scene.fem.setContacts({ contact }), InvalidInputError);
  contact.hexahedron = 0;
  contact.normal = Vector3(0.0, 0.0, 2.0);
  EXPECT_THROW(scene.fem.setContacts({ contact }), InvalidInputError);
  contact.normal = Vector3::UnitZ();
  contact.stiffness = -1.0;
  EXPECT_THROW(scene.fem.setContacts({ contact }), InvalidInputError);
  contact.stiffness = 1.0;
  scene.fem.setContacts({ contact });
  scene.fem.removeHexahedron(0);
  EXPECT_TRUE(scene.fem.contacts().empty());
}
