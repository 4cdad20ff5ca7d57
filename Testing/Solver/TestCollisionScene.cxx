// Collision scene: rigid tools (spheres, capsules, triangle meshes) moved by
// a pose, static obstacles, tissue-tissue contacts, broad phase, friction,
// tool force and torque, and the meniscus pressed onto the tibia (table 6-2).
#include "BoxSurface.h"
#include "CollisionScene.h"
#include "KneeModels.h"
#include "MeniscusModel.h"
#include "SoftTissueMaterial.h"
#include "SurgicalInstruments.h"
#include "ThinSheetModel.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace thintissue;
using thintissue::test::softTissue;
using thintissue::testing::boxSurface;

namespace
{
CorotationalHexFemSettings stepOf(double timeStep)
{
  CorotationalHexFemSettings s;
  s.timeStep = timeStep;
  return s;
}

RigidPose translation(const Vector3& t)
{
  RigidPose pose;
  pose.translation = t;
  return pose;
}

void translateModel(TissueModel& model, const Vector3& offset)
{
  for (auto& p : model.visual.positions)
  {
    p += offset;
  }
  for (auto& p : model.collision.positions)
  {
    p += offset;
  }
  for (auto& p : model.simulation.nodes)
  {
    p += offset;
  }
}

/// A flat square in the plane z = 0 made of 2 n^2 triangles (an obstacle).
TriangleMesh floorSurface(double halfSize, int n)
{
  TriangleMesh floor;
  floor.name = "floor";
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      floor.positions.emplace_back(
        -halfSize + 2.0 * halfSize * i / n, -halfSize + 2.0 * halfSize * j / n, 0.0);
    }
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const int a = j * (n + 1) + i;
      floor.triangles.push_back({ a, a + 1, a + n + 2 });
      floor.triangles.push_back({ a, a + n + 2, a + n + 1 });
    }
  }
  return floor;
}

struct SheetWithTool
{
  TissueModel sheet;
  CorotationalHexFem fem;
  DeformableCollisionMesh collision;
  RigidTool tool{ "probe" };
  CollisionScene scene;

  explicit SheetWithTool(int collisionModel, double timeStep = 0.01)
    : sheet(makeThinSheet(thesisSheetCollisionResolution(collisionModel)))
    , fem(sheet.simulation, softTissue(), stepOf(timeStep))
    , collision(sheet.collision, sheet.simulation)
  {
    scene.addTissue(fem, collision);
    scene.addTool(tool);
  }

  Vector3 nodeDisplacementNear(const Vector3& point) const
  {
    std::size_t best = 0;
    for (std::size_t n = 0; n < fem.positions().size(); ++n)
    {
      if ((fem.restPositions()[n] - point).squaredNorm() <
          (fem.restPositions()[best] - point).squaredNorm())
      {
        best = n;
      }
    }
    return fem.positions()[best] - fem.restPositions()[best];
  }
};
} // namespace

TEST(RigidTool, PoseMovesPrimitivesAndGivesVelocities)
{
  RigidTool tool("hook");
  tool.addSphere(Vector3(0.0, 0.0, 0.0), 0.5);
  tool.addCapsule(Vector3(0.0, 0.0, 0.0), Vector3(0.0, 0.0, 10.0), 1.0);
  tool.setMesh(boxSurface(Vector3(-1, -1, 0), Vector3(1, 1, 2)));
  RigidPose pose;
  pose.rotation = Eigen::AngleAxisd(0.5 * M_PI, Vector3::UnitX()).toRotationMatrix();
  pose.translation = Vector3(1.0, 2.0, 3.0);
  tool.moveTo(pose, 0.01);
  EXPECT_TRUE(tool.linearVelocity().isZero()); // first pose: at rest
  EXPECT_TRUE(tool.capsules()[0].end.isApprox(Vector3(1.0, -8.0, 3.0), 1e-12));
  EXPECT_TRUE(tool.meshPositions()[7].isApprox(pose * Vector3(1, 1, 2), 1e-12));
  EXPECT_TRUE(tool.bounds().contains(Vector3(1.0, -8.0, 3.0)));

  RigidPose next = pose;
  next.translation += Vector3(0.02, 0.0, 0.0);
  next.rotation = Eigen::AngleAxisd(0.01, Vector3::UnitZ()).toRotationMatrix() * pose.rotation;
  tool.moveTo(next, 0.01);
  EXPECT_TRUE(tool.linearVelocity().isApprox(Vector3(2.0, 0.0, 0.0), 1e-9));
  EXPECT_TRUE(tool.angularVelocity().isApprox(Vector3(0.0, 0.0, 1.0), 1e-9));
  // A point 1 mm along +x from the origin moves at v + w x r.
  EXPECT_TRUE(
    tool.velocityAt(next.translation + Vector3(1, 0, 0)).isApprox(Vector3(2, 1, 0), 1e-9));

  EXPECT_THROW(tool.addSphere(Vector3::Zero(), -1.0), InvalidInputError);
  EXPECT_THROW(tool.addCapsule(Vector3::Zero(), Vector3::Constant(NAN), 1.0), InvalidInputError);
  RigidPose sheared = pose;
  sheared.rotation(0, 1) = 0.3;
  EXPECT_THROW(tool.setPose(sheared), InvalidInputError);
  TriangleMesh bad = boxSurface(Vector3::Zero(), Vector3::Ones());
  bad.pointAttributes.set("Radius", 1, std::vector<double>(8, -0.1));
  EXPECT_THROW(tool.setMesh(bad), InvalidInputError);
}

TEST(CollisionScene, BroadPhaseSkipsDistantBodies)
{
  SheetWithTool s(1);
  const StaticObstacle floor(floorSurface(80.0, 4));
  // Floor far below the sheet: never a candidate.
  TriangleMesh lowFloor = floorSurface(80.0, 4);
  for (auto& p : lowFloor.positions)
  {
    p.z() -= 50.0;
  }
  const StaticObstacle farFloor(lowFloor);
  s.scene.addObstacle(farFloor);
  s.tool.addSphere(Vector3::Zero(), 1.0);
  s.tool.setPose(translation(Vector3(0.0, 0.0, 30.0)));
  s.scene.detectContacts();
  // tissue-tool, tissue-obstacle, tool-obstacle
  EXPECT_EQ(s.scene.statistics().bodyPairs, 3);
  EXPECT_EQ(s.scene.statistics().overlappingBodyPairs, 0);
  EXPECT_TRUE(s.scene.contacts().empty());
  // The sphere dipped 0.5 mm into the upper surface: one pair, one contact.
  s.tool.setPose(translation(Vector3(3.0, 2.0, 1.0 + 1.0 - 0.5)));
  s.scene.detectContacts();
  EXPECT_EQ(s.scene.statistics().overlappingBodyPairs, 1);
  ASSERT_EQ(s.scene.contacts().size(), 1u);
  const SceneContact& c = s.scene.contacts()[0];
  EXPECT_EQ(c.first.kind, SceneBodyKind::Tissue);
  EXPECT_EQ(c.second.kind, SceneBodyKind::Tool);
  EXPECT_NEAR(c.depth, 0.5, 1e-9);
  EXPECT_TRUE(c.normal.isApprox(Vector3(0, 0, -1), 1e-9)); // tissue pushed down
  EXPECT_EQ(c.sideOnFirst, 1);
  EXPECT_EQ(s.scene.contactCountOnSide(0, 1), 1);
  EXPECT_EQ(s.scene.contactCountOnSide(0, -1), 0);
}

TEST(CollisionScene, ContactDistanceThickensTheSurfaces)
{
  // Tissue contact distance 0.5 and floor contact distance 0.25: a sphere
  // 0.3 above the thick sheet is in contact (depth 0.2), a tissue vertex
  // 0.6 above the floor's surface too (depth 0.15).
  TissueModel sheet = makeThinSheet(thesisSheetCollisionResolution(1));
  CorotationalHexFem fem(sheet.simulation, softTissue(), stepOf(0.01));
  DeformableCollisionMesh collision(sheet.collision, sheet.simulation, 0.5);
  TriangleMesh low = floorSurface(80.0, 2);
  for (auto& p : low.positions)
  {
    p.z() -= 1.0 + 0.6;
  }
  const StaticObstacle floor(low, 0.25);
  RigidTool tool;
  tool.addSphere(Vector3::Zero(), 1.0);
  tool.setPose(translation(Vector3(3.0, 2.0, 1.0 + 1.0 + 0.3)));
  CollisionScene scene;
  scene.addTissue(fem, collision);
  scene.addTool(tool);
  scene.addObstacle(floor);
  scene.detectContacts();
  int toolContacts = 0;
  int floorContacts = 0;
  for (const SceneContact& c : scene.contacts())
  {
    if (c.second.kind == SceneBodyKind::Tool)
    {
      ++toolContacts;
      EXPECT_NEAR(c.depth, 0.2, 1e-9);
    }
    else
    {
      ++floorContacts;
      EXPECT_NEAR(c.depth, 0.5 + 0.25 - 0.6, 1e-9);
      EXPECT_EQ(c.sideOnFirst, -1);
    }
  }
  EXPECT_EQ(toolContacts, 1);
  // Every tissue vertex on the floor, and the floor's one vertex under the
  // sheet (its centre) on a tissue triangle; no edge-edge contact where
  // the vertices hold the surfaces face to face.
  EXPECT_EQ(floorContacts, static_cast<int>(collision.positions().size()) + 1);
}

TEST(CollisionScene, SpherePressedIntoTheSheetStopsAtTheRadii)
{
  SheetWithTool s(2);
  s.tool.addSphere(Vector3::Zero(), 1.0);
  Vector3 centre(0.0, 0.0, 3.0);
  for (int k = 0; k < 300; ++k)
  {
    if (k < 60)
    {
      centre.z() -= 0.05; // 2 mm past first touch
    }
    s.tool.moveTo(translation(centre), 0.01);
    ASSERT_TRUE(s.scene.step().ok);
  }
  ASSERT_EQ(s.scene.contacts().size(), 1u);
  const double k = s.scene.parameters().toolTissue.stiffness;
  EXPECT_GT(s.tool.force().z(), 0.0);
  EXPECT_NEAR(s.scene.contacts()[0].depth, s.tool.force().norm() / k, 0.02);
  EXPECT_LT(s.scene.contacts()[0].depth, 0.1);
  // Newton's third law: force on the tool = - force on the tissue (H^T).
  Vector3 onTissue = Vector3::Zero();
  for (const Vector3& f : s.fem.contactForces())
  {
    onTissue += f;
  }
  EXPECT_LT((onTissue + s.tool.force()).norm(), 1e-12 * onTissue.norm());
  // Withdrawn: no contact, no force.
  s.tool.moveTo(translation(Vector3(0.0, 0.0, 20.0)), 0.01);
  ASSERT_TRUE(s.scene.step().ok);
  EXPECT_TRUE(s.scene.contacts().empty());
  EXPECT_EQ(s.tool.force().norm(), 0.0);
}

TEST(CollisionScene, TriangleMeshToolSharesItsStiffnessAndGetsTheReaction)
{
  // A 6 x 6 x 4 mm block with a flat bottom pressed into the sheet: many
  // feature contacts, total stiffness that of one contact.
  SheetWithTool s(3);
  s.tool.setMesh(boxSurface(Vector3(-3, -3, 0), Vector3(3, 3, 4)));
  Vector3 origin(0.5, 0.3, 1.5);
  for (int k = 0; k < 300; ++k)
  {
    if (k < 30)
    {
      origin.z() -= 0.05; // 1 mm past first touch
    }
    s.tool.moveTo(translation(origin), 0.01);
    ASSERT_TRUE(s.scene.step().ok);
  }
  const auto& contacts = s.scene.contacts();
  ASSERT_GT(contacts.size(), 3u);
  double stiffness = 0.0;
  double deepest = 0.0;
  for (const SceneContact& c : contacts)
  {
    EXPECT_EQ(c.second.kind, SceneBodyKind::Tool);
    EXPECT_EQ(c.sideOnFirst, 1);
    stiffness += c.stiffness;
    deepest = std::max(deepest, c.depth);
  }
  const double k = s.scene.parameters().toolTissue.stiffness;
  EXPECT_LE(stiffness, k * (1.0 + 1e-12));
  EXPECT_GT(s.tool.force().z(), 0.0);
  EXPECT_LT(deepest, 0.1);                                        // held at the radius
  EXPECT_LT(s.nodeDisplacementNear(Vector3(0, 0, -1)).z(), -0.5); // the sheet was pushed down
  Vector3 onTissue = Vector3::Zero();
  for (const Vector3& f : s.fem.contactForces())
  {
    onTissue += f;
  }
  EXPECT_LT((onTissue + s.tool.force()).norm(), 1e-12 * onTissue.norm());
  // The torque is the moment of the contact forces about the tool origin,
  // with a lever inside the 3 mm half-width footprint.
  Vector3 moment = Vector3::Zero();
  for (const SceneContact& c : contacts)
  {
    moment -= (c.pointOnSecond - origin).cross(c.force);
  }
  EXPECT_TRUE(s.tool.torque().isApprox(moment, 1e-12));
  EXPECT_LT(s.tool.torque().norm(), 3.0 * std::sqrt(2.0) * s.tool.force().norm());
}

TEST(CollisionScene, TorqueIsTheMomentOfTheContactForcesAboutTheToolOrigin)
{
  // A horizontal lever 20 mm long whose far end presses on the sheet: the
  // torque about the origin is r x F with r the lever.
  SheetWithTool s(2);
  s.tool.addCapsule(Vector3::Zero(), Vector3(20.0, 0.0, 0.0), 0.5);
  s.tool.moveTo(translation(Vector3(-35.0, 0.0, 30.0)), 0.01); // origin far from the sheet
  RigidPose pose;
  pose.rotation = Eigen::AngleAxisd(0.5 * M_PI, Vector3::UnitY()).toRotationMatrix(); // +x -> -z
  pose.translation = Vector3(10.0, 5.0, 20.0 + 1.0 + 0.5 - 0.3); // tip 0.3 mm into the sheet
  s.tool.setPose(pose);
  ASSERT_TRUE(s.scene.step().ok);
  ASSERT_EQ(s.scene.contacts().size(), 1u);
  const SceneContact& c = s.scene.contacts()[0];
  const Vector3 expected = (c.pointOnSecond - pose.translation).cross(s.tool.force());
  EXPECT_TRUE(s.tool.torque().isApprox(expected, 1e-12));
  EXPECT_NEAR(c.pointOnSecond.z(), pose.translation.z() - 20.0, 1e-9);
  // The lever points down, the force up: the moment is about the lever, zero.
  EXPECT_LT(s.tool.torque().norm(), 1e-9 * s.tool.force().norm() * 20.0);

  // Lying flat: the lever's tip presses at 20 mm from the origin.
  SheetWithTool flat(2);
  flat.tool.addSphere(Vector3(20.0, 0.0, 0.0), 1.0);
  flat.tool.setPose(translation(Vector3(-10.0, 5.0, 2.0 - 0.3)));
  ASSERT_TRUE(flat.scene.step().ok);
  const Vector3 f = flat.tool.force();
  ASSERT_GT(f.z(), 0.0);
  EXPECT_NEAR(flat.tool.torque().y(), -20.0 * f.z(), 1e-9 * f.norm() * 20.0);
  EXPECT_NEAR(flat.tool.torque().x(), 0.0, 0.05 * f.norm() * 20.0);
}

TEST(CollisionScene, FrictionDragsTheSheetAndIsBoundedByTheCone)
{
  // Press, then slide 5 mm along +y: frictionless the sheet barely follows;
  // with mu = 0.8 it is dragged, and while sliding the tangential force
  // stays within the cone (mu times the normal force). The cone holds on
  // the start-of-step slip; a step where the contact moves onto other
  // vertices may exceed it briefly (the friction damper is lagged).
  struct Drag
  {
    double displacement = 0.0; ///< of the sheet near the tool, end of the slide
    double meanTangential = 0.0;
    double maxConeRatio = 0.0;
    double insideConeShare = 0.0;
  };
  auto drag = [](double friction)
  {
    SheetWithTool s(2);
    CollisionSceneParameters p;
    p.toolTissue.friction = friction;
    p.toolTissue.slipVelocity = 0.5;
    s.scene.setParameters(p);
    s.tool.addSphere(Vector3::Zero(), 1.0);
    Vector3 centre(20.0, 0.0, 2.0);
    Drag result;
    int sliding = 0;
    int inside = 0;
    for (int k = 0; k < 150; ++k)
    {
      if (k < 20)
      {
        centre.z() -= 0.05;
      }
      else if (k >= 100)
      {
        centre.y() += 0.1;
      }
      s.tool.moveTo(translation(centre), 0.01);
      EXPECT_TRUE(s.scene.step().ok);
      if (k >= 100 && !s.scene.contacts().empty())
      {
        const Vector3& n = s.scene.contacts()[0].normal;
        const Vector3 f = s.scene.contacts()[0].force;
        const double normal = f.dot(n);
        const double tangential = (f - normal * n).norm();
        EXPECT_GT(normal, 0.0);
        const double ratio = tangential / normal;
        result.maxConeRatio = std::max(result.maxConeRatio, ratio);
        result.meanTangential += tangential;
        inside += ratio <= 1.05 * friction + 1e-3 ? 1 : 0;
        ++sliding;
      }
    }
    EXPECT_EQ(sliding, 50);
    result.meanTangential /= sliding;
    result.insideConeShare = static_cast<double>(inside) / sliding;
    result.displacement = s.nodeDisplacementNear(Vector3(20.0, 5.0, -1.0)).y();
    return result;
  };
  const Drag frictionless = drag(0.0);
  const Drag rough = drag(0.8);
  EXPECT_LT(frictionless.maxConeRatio, 0.05);
  EXPECT_GT(rough.displacement, 0.04); // the sheet's in-plane stiffness allows little
  EXPECT_GT(rough.displacement, 3.0 * std::abs(frictionless.displacement));
  EXPECT_GT(rough.meanTangential, 10.0 * frictionless.meanTangential);
  EXPECT_GT(rough.maxConeRatio, 0.5); // sliding, near the cone
  EXPECT_GE(rough.insideConeShare, 0.9);
  EXPECT_LT(rough.maxConeRatio, 2.0 * 0.8);
}

TEST(CollisionScene, ToolAgainstAnObstacleFeelsTheObstacleOnly)
{
  SheetWithTool s(1);
  const StaticObstacle floor(
    [&]
    {
      TriangleMesh f = floorSurface(10.0, 2);
      for (auto& p : f.positions)
      {
        p += Vector3(80.0, 0.0, 0.0); // beside the sheet
      }
      return f;
    }());
  s.scene.addObstacle(floor);
  s.tool.addSphere(Vector3::Zero(), 1.0);
  s.tool.setPose(translation(Vector3(80.0, 0.0, 0.6)));
  ASSERT_TRUE(s.scene.step().ok);
  ASSERT_EQ(s.scene.contacts().size(), 1u);
  EXPECT_EQ(s.scene.contacts()[0].first.kind, SceneBodyKind::Tool);
  const double k = s.scene.parameters().toolObstacle.stiffness;
  EXPECT_TRUE(s.tool.force().isApprox(Vector3(0, 0, k * 0.4), 1e-9));
  EXPECT_TRUE(s.fem.contacts().empty());
}

TEST(CollisionScene, StackedSheetsDoNotInterpenetrate)
{
  // An upper sheet pressed by a probe onto a lower one (tissue-tissue, two
  // solvers solved jointly): they touch with the upper's lower surface and
  // the lower's upper surface, hold at the radii, the lower is pushed too,
  // and the probe's force settles.
  TissueModel lowerModel = makeThinSheet(thesisSheetCollisionResolution(1));
  TissueModel upperModel = makeThinSheet(thesisSheetCollisionResolution(2));
  translateModel(upperModel, Vector3(0.0, 0.0, 2.5)); // 0.5 mm gap
  CorotationalHexFem lower(lowerModel.simulation, softTissue(), stepOf(0.01));
  CorotationalHexFem upper(upperModel.simulation, softTissue(), stepOf(0.01));
  DeformableCollisionMesh lowerCollision(lowerModel.collision, lowerModel.simulation);
  DeformableCollisionMesh upperCollision(upperModel.collision, upperModel.simulation);
  RigidTool probe("probe");
  probe.addCapsule(Vector3(0.0, 0.0, 40.0), Vector3::Zero(), 2.0);
  CollisionScene scene;
  scene.addTissue(lower, lowerCollision);
  scene.addTissue(upper, upperCollision);
  scene.addTool(probe);
  Vector3 tip(0.0, 0.0, 2.5 + 1.0 + 2.0);
  int tissueContacts = 0;
  double previousForce = 0.0;
  for (int k = 0; k < 250; ++k)
  {
    if (k < 60)
    {
      tip.z() -= 0.05; // 3 mm: through the gap and 2.5 mm into the pair
    }
    probe.moveTo(translation(tip), 0.01);
    ASSERT_TRUE(scene.step().ok);
    if (k >= 200)
    {
      // Settled: the sheets are solved jointly and do not chatter (solving
      // each against the other's extrapolated motion gave a two-step
      // cycle between 46 N and 0.3 N here).
      EXPECT_GT(scene.statistics().jointIterations, 0);
      EXPECT_NEAR(probe.force().z(), previousForce, 0.01 * previousForce) << "step " << k;
    }
    previousForce = probe.force().z();
  }
  EXPECT_GT(previousForce, 0.0);
  double deepest = 0.0;
  for (const SceneContact& c : scene.contacts())
  {
    if (c.second.kind == SceneBodyKind::Tissue)
    {
      ++tissueContacts;
      EXPECT_EQ(c.first.index, 0);
      EXPECT_EQ(c.sideOnFirst, 1);   // the lower sheet's upper surface
      EXPECT_EQ(c.sideOnSecond, -1); // the upper sheet's lower surface
      deepest = std::max(deepest, c.depth);
    }
  }
  EXPECT_GT(tissueContacts, 0);
  EXPECT_GT(scene.contactCountOnSide(1, -1), 0);
  EXPECT_LT(deepest, 0.5); // held at the radii (2 mm between mid-surfaces)
  // Both were pushed down near the probe; mid-surfaces never crossed.
  const std::size_t centreNode = [&]
  {
    std::size_t best = 0;
    for (std::size_t n = 0; n < lower.positions().size(); ++n)
    {
      if (lower.restPositions()[n].head<2>().norm() < lower.restPositions()[best].head<2>().norm())
      {
        best = n;
      }
    }
    return best;
  }();
  EXPECT_LT(lower.positions()[centreNode].z() - lower.restPositions()[centreNode].z(), -0.5);
  lowerCollision.update(lower.positions());
  upperCollision.update(upper.positions());
  for (std::size_t v = 0; v < upperCollision.positions().size(); ++v)
  {
    const Vector3& p = upperCollision.positions()[v];
    if (p.head<2>().norm() < 10.0)
    {
      // The lower mid-surface under it is flat near the centre to first order.
      double below = -1e9;
      for (const Vector3& q : lowerCollision.positions())
      {
        if ((q.head<2>() - p.head<2>()).norm() < 8.0)
        {
          below = std::max(below, q.z());
        }
      }
      EXPECT_GT(p.z() - below, 1.0) << "upper vertex " << v;
    }
  }
}

TEST(CollisionScene, InvalidInputIsRejected)
{
  SheetWithTool s(1);
  CollisionSceneParameters p;
  p.toolTissue.slipVelocity = 0.0;
  EXPECT_THROW(s.scene.setParameters(p), InvalidInputError);
  p = CollisionSceneParameters();
  p.tissueTissue.stiffness = -1.0;
  EXPECT_THROW(s.scene.setParameters(p), InvalidInputError);
  // A collision mesh embedded in another solver's hexahedra.
  const TissueModel other = makeThinSheet(
    []
    {
      ThinSheetParameters q;
      q.hexahedraX = 3;
      q.hexahedraY = 3;
      return q;
    }());
  DeformableCollisionMesh foreign(other.collision, other.simulation);
  EXPECT_THROW(s.scene.addTissue(s.fem, foreign), InvalidInputError);
}

namespace
{
/// Table 6-2's scenario with the knee models: the meniscus on the tibia
/// and its cartilage (obstacles), the probe hook above its body.
struct MeniscusOnTheKnee
{
  MeniscusModel meniscus = makeMeniscus();
  KneeSurroundings knee = makeKneeSurroundings();
  CorotationalHexFem fem;
  DeformableCollisionMesh collision;
  StaticObstacle tibia;
  StaticObstacle cartilage;
  RigidTool hook{ "probe hook" };
  CollisionScene scene;
  RigidPose pose;

  explicit MeniscusOnTheKnee(
    double candidateMarginPerRadius = CollisionSceneParameters{}.candidateMarginPerRadius)
    : fem(meniscus.simulation, material(), stepOf(0.001))
    , collision(meniscus.collision, meniscus.simulation)
    , tibia(knee.tibia.collision)
    , cartilage(knee.tibialCartilage.visual)
  {
    const SurgicalInstrumentModel model = makeSurgicalInstrument(SurgicalInstrumentType::ProbeHook);
    for (const auto& segment : model.centreLine)
    {
      hook.addCapsule(segment.end, segment.start, segment.radius); // tip -> handle
    }
    CollisionSceneParameters parameters;
    parameters.candidateMarginPerRadius = candidateMarginPerRadius;
    scene.setParameters(parameters);
    scene.addTissue(fem, collision);
    scene.addTool(hook);
    scene.addObstacle(tibia);
    scene.addObstacle(cartilage);
    const ParametricSolid solid = makeMeniscusSolid(MeniscusParameters{});
    const Vector3 top = solid.point(ParameterPoint(0.5, 0.5, 1.0));
    pose.rotation = Eigen::Quaterniond::FromTwoVectors(Vector3::UnitZ(), Vector3(-0.3, 0.6, 0.75))
                      .toRotationMatrix();
    pose.translation = top + Vector3(0.0, 0.0, 1.0); // above the upper surface
    hook.moveTo(pose, 0.001);
  }

  static LinearMaterial material()
  {
    LinearMaterial m; // thesis 4.5
    m.youngModulus = 150.0;
    m.poissonRatio = 0.49;
    m.density = 1.1e-9;
    return m;
  }

  /// Step k of the press: 20 steps resting, 200 steps 2 mm down (1 mm into
  /// the meniscus), then held.
  bool step(int k)
  {
    if (k >= 20 && k < 220)
    {
      pose.translation.z() -= 0.01;
    }
    hook.moveTo(pose, 0.001);
    return scene.step().ok;
  }
};
} // namespace

TEST(CollisionScene, MeniscusPressedOntoTheTibiaTouchesWithItsLowerSurface)
{
  // The hook presses the meniscus's body down onto the tibial plateau; the
  // contacts on its lower surface rise.
  MeniscusOnTheKnee knee;
  for (int k = 0; k < 20; ++k)
  {
    ASSERT_TRUE(knee.step(k));
  }
  const int lowerBefore = knee.scene.contactCountOnSide(0, -1);
  for (int k = 20; k < 420; ++k)
  {
    ASSERT_TRUE(knee.step(k));
  }
  const int lowerAfter = knee.scene.contactCountOnSide(0, -1);
  EXPECT_GT(lowerAfter, lowerBefore);
  EXPECT_GT(knee.hook.force().z(), 0.0); // the meniscus pushes the hook up
  int upperHook = 0;
  for (const SceneContact& c : knee.scene.contacts())
  {
    if (c.second.kind == SceneBodyKind::Tool)
    {
      EXPECT_EQ(c.sideOnFirst, 1); // the hook is on the upper surface
      ++upperHook;
    }
    else
    {
      EXPECT_EQ(c.second.kind, SceneBodyKind::Obstacle);
      EXPECT_LT(c.depth, 0.5); // held by the plateau
    }
  }
  EXPECT_GE(upperHook, 1);
  std::cout << "lower-surface contacts before " << lowerBefore << ", after " << lowerAfter
            << ", hook force " << knee.hook.force().transpose() << "\n";
}

TEST(CollisionScene, ObstacleCandidatesKeptBetweenStepsChangeNoBit)
{
  // The press with the obstacles' candidates searched every step (margin
  // 0) and kept between steps (the default): the same contacts and node
  // positions, bit for bit, at every step, with far fewer searches.
  MeniscusOnTheKnee everyStep(0.0), kept;
  int searches = 0, contacts = 0;
  const int steps = 320;
  for (int k = 0; k < steps; ++k)
  {
    ASSERT_TRUE(everyStep.step(k));
    ASSERT_TRUE(kept.step(k));
    EXPECT_EQ(everyStep.scene.statistics().candidateSearches, 0);
    searches += kept.scene.statistics().candidateSearches;
    ASSERT_EQ(everyStep.scene.contacts().size(), kept.scene.contacts().size()) << "step " << k;
    for (std::size_t c = 0; c < kept.scene.contacts().size(); ++c)
    {
      const SceneContact& e = everyStep.scene.contacts()[c];
      const SceneContact& f = kept.scene.contacts()[c];
      ASSERT_TRUE(e.first == f.first && e.second == f.second && e.depth == f.depth &&
                  e.normal == f.normal && e.pointOnFirst == f.pointOnFirst && e.force == f.force)
        << "step " << k << ", contact " << c;
    }
    ASSERT_EQ(everyStep.fem.positions(), kept.fem.positions()) << "step " << k;
    contacts += static_cast<int>(kept.scene.contacts().size());
  }
  EXPECT_EQ(everyStep.hook.force(), kept.hook.force());
  EXPECT_GT(contacts, steps); // it touched the plateau (and the hook)
  EXPECT_GE(searches, 2);     // one per obstacle at the start, more as it moved
  EXPECT_LT(searches, steps / 4);
  std::cout << searches << " candidate searches in " << steps << " steps, " << contacts
            << " contacts\n";
}
