// Suite "collision": a full physics step with CollisionScene -- collision
// meshes mapped from the hexahedra, broad and narrow phase, the implicit FEM
// step(s) with the contact springs, the tools' reactions -- plus the
// tissues' visual meshes mapped from the hexahedra (the thesis's simulation
// times include updating the visual mesh), for three thesis tables:
// - table 6-2: the meniscus pressed onto the tibia by the probe hook, at the
//   three multi-resolution settings (setting 1: every body, the hook too,
//   collides with its full-resolution visual mesh);
// - table 5-6: the thin sheet pressed onto a floor by a probe, with the
//   collision meshes of models 1 to 3 and its visual mesh as model 4;
// - table 5-7: the hook pushing the anterior cruciate ligament into the
//   posterior one (tissue-tissue contacts, solved jointly), at the four
//   ligament collision settings.
// Each case first presses (warm-up steps with the tool moving, stopped by
// the force the tissues push back with), then times blocks of steps with
// the tool held where the press ended.
#include "BenchmarkRegistry.h"

#include "CollisionScene.h"
#include "CorotationalHexFem.h"
#include "HexahedralEmbedding.h"
#include "KneeModels.h"
#include "MeniscusModel.h"
#include "SurgicalInstruments.h"
#include "ThinSheetModel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace
{
using namespace thintissue;
using namespace thintissue::bench;

/// A collision scene stepped as the simulation loop steps it: the tools are
/// placed (a device sampled once per physics step), CollisionScene::step,
/// then each tissue's visual mesh is mapped from its hexahedra (embedded
/// once). Solver failures are counted and the first message kept.
class PhysicsLoop
{
public:
  PhysicsLoop(CollisionScene& scene, double timeStep)
    : Scene(scene)
    , TimeStep(timeStep)
  {
  }

  void addVisual(const CorotationalHexFem& fem,
    const HexahedralMesh& hexahedra,
    const TriangleMesh& visual)
  {
    Visuals.push_back({ &fem, HexahedralEmbedding(hexahedra, visual.positions), {} });
    Visuals.back().positions.resize(visual.positions.size());
  }

  /// The scene's tool `toolIndex`, placed at `start`, then pushed along
  /// `direction` at `speed` (mm/s) while the tissues push back along it
  /// with less than `force` -- a hand pressing with a given force -- and at
  /// most `travel` far; held still from then on.
  void addPressingTool(RigidTool& tool,
    int toolIndex,
    const RigidPose& start,
    const Vector3& direction,
    double speed,
    double force,
    double travel)
  {
    Tools.push_back({ &tool, toolIndex, start, direction.normalized(), speed, force, travel, 0.0 });
    tool.moveTo(start, TimeStep);
  }

  void step()
  {
    for (PressingTool& t : Tools)
    {
      const double advance = std::min(t.speed * TimeStep, t.travel - t.moved);
      if (advance > 0.0 && -t.direction.dot(tissueReaction(t.index)) < t.force)
      {
        t.pose.translation += advance * t.direction;
        t.moved += advance;
      }
      t.tool->moveTo(t.pose, TimeStep);
    }
    const SolverResult result = Scene.step();
    if (!result.ok)
    {
      ++Failures;
      if (FirstFailure.empty())
      {
        FirstFailure = result.message;
      }
    }
    for (Visual& v : Visuals)
    {
      v.embedding.mapPositions(v.fem->positions(), v.positions);
    }
  }

  void run(int steps)
  {
    for (int k = 0; k < steps; ++k)
    {
      step();
    }
  }

  /// Milliseconds per step: median over repetitions of blocks of steps.
  double millisecondsPerStep(const BenchmarkContext& context, int steps)
  {
    return 1e3 * medianSeconds([&] { run(steps); }, context.quick ? 1 : 5, false) / steps;
  }

  /// ", N solver failures (first: ...)" or nothing.
  std::string failureNote() const
  {
    if (Failures == 0)
    {
      return {};
    }
    return ", " + std::to_string(Failures) + " solver failures (first: " + FirstFailure + ")";
  }

  /// Force of the tissues (not of the obstacles) on a tool in the last step.
  Vector3 tissueReaction(int toolIndex) const
  {
    Vector3 force = Vector3::Zero();
    for (const SceneContact& c : Scene.contacts())
    {
      if (c.second.kind == SceneBodyKind::Tool && c.second.index == toolIndex)
      {
        force -= c.force;
      }
    }
    return force;
  }

private:
  struct Visual
  {
    const CorotationalHexFem* fem;
    HexahedralEmbedding embedding;
    std::vector<Vector3> positions;
  };
  struct PressingTool
  {
    RigidTool* tool;
    int index;
    RigidPose pose;
    Vector3 direction;
    double speed;
    double force;
    double travel;
    double moved;
  };
  CollisionScene& Scene;
  double TimeStep;
  std::vector<Visual> Visuals;
  std::vector<PressingTool> Tools;
  int Failures = 0;
  std::string FirstFailure;
};

/// The scene's tissue contacts by the kind of the other body (a tool
/// against an obstacle acts on the tool alone and is not counted).
struct ContactCounts
{
  int tool = 0;
  int obstacle = 0;
  int tissue = 0;
  /// Obstacle contacts pushing the tissue up: its lower surface resting on
  /// the obstacle. (contactCountOnSide tells the side from the collision
  /// mesh's normals: right for a mid-surface, but a closed surface touched
  /// from below on its lower face is touched on its outer side, +1.)
  int obstacleFromBelow = 0;
};

ContactCounts countContacts(const CollisionScene& scene)
{
  ContactCounts counts;
  for (const SceneContact& c : scene.contacts())
  {
    if (c.first.kind != SceneBodyKind::Tissue)
    {
      continue;
    }
    switch (c.second.kind)
    {
      case SceneBodyKind::Tool:
        ++counts.tool;
        break;
      case SceneBodyKind::Obstacle:
        ++counts.obstacle;
        counts.obstacleFromBelow += c.normal.z() > 0.0 ? 1 : 0;
        break;
      case SceneBodyKind::Tissue:
        ++counts.tissue;
        break;
    }
  }
  return counts;
}

/// The instrument's pose with its tip at `tip`, its handle along
/// `handleAxis` and its working part (the hook) facing `up` made normal to
/// the handle axis (SurgicalInstruments.h: tool x = up, z = handle axis).
RigidPose poseOf(const Vector3& handleAxis, const Vector3& up, const Vector3& tip)
{
  const Vector3 z = handleAxis.normalized();
  const Vector3 x = (up - up.dot(z) * z).normalized();
  RigidPose pose;
  pose.rotation.col(0) = x;
  pose.rotation.col(1) = z.cross(x);
  pose.rotation.col(2) = z;
  pose.translation = tip;
  return pose;
}

/// The instrument's centre line as capsules (its segments run tip -> handle).
void addCentreLine(RigidTool& tool, const SurgicalInstrumentModel& instrument)
{
  for (const CollisionSegment& segment : instrument.centreLine)
  {
    tool.addCapsule(segment.end, segment.start, segment.radius);
  }
}

/// A flat square in the plane z = height made of 2 n^2 triangles.
TriangleMesh floorSurface(double halfSize, int n, double height)
{
  TriangleMesh floor;
  floor.name = "floor";
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      floor.positions.emplace_back(
        -halfSize + 2.0 * halfSize * i / n, -halfSize + 2.0 * halfSize * j / n, height);
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

// Contact distance of the collision meshes without radii (visual meshes
// used for collision): contacts start this close to the surface (thesis
// 6.3: the distance tuned so that the visual models do not interpenetrate).
// Without it two radius-0 surfaces only meet where they already cross.
constexpr double VisualContactDistance = 0.1;
// The hook's visual mesh as a collision mesh: thickened so that the
// pressing hook (its stiffness shared by all its contacts) stays outside
// the meniscus's surface.
constexpr double ToolMeshContactDistance = 0.5;

// --- Table 6-2 ---------------------------------------------------------------

struct KneeSetting
{
  std::string name;
  bool visualMeniscus;
  bool visualBones;
  bool toolMesh;
  double thesisMilliseconds;
};

void kneeCases(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const MeniscusModel meniscus = makeMeniscus();
  const KneeSurroundings knee = makeKneeSurroundings();
  LinearMaterial material; // thesis 4.5, in mm, N, s
  material.youngModulus = 150.0;
  material.poissonRatio = 0.49;
  material.density = 1.1e-9;
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.001;

  // The hook 2 mm above the upper surface of the meniscus's anterior body
  // (where the femoral condyle leaves room), the shaft coming in from the
  // front at 56 degrees from vertical, the hook pointing down so that its
  // tip touches first. It is lowered at 10 mm/s until the meniscus pushes
  // back with 10 N: the meniscus is pressed onto the tibial cartilage.
  SurgicalInstrumentParameters hookParameters =
    defaultInstrumentParameters(SurgicalInstrumentType::ProbeHook);
  hookParameters.segmentsAround = 50; // visual mesh of 2,552 vertices (thesis: 2,562)
  const SurgicalInstrumentModel hook = makeSurgicalInstrument(hookParameters);
  const ParametricSolid solid = makeMeniscusSolid(MeniscusParameters{});
  const Vector3 top = solid.point(ParameterPoint(0.7, 0.4, 1.0));
  const RigidPose above =
    poseOf(Vector3(0.2, 0.8, 0.55), -Vector3::UnitZ(), top + Vector3(0.0, 0.0, 2.0));
  const double pressForce = 10.0;
  const double pressSpeed = context.quick ? 40.0 : 10.0;
  const int restSteps = context.quick ? 10 : 50;
  const int pressSteps = context.quick ? 100 : 400;

  const std::vector<KneeSetting> knees = {
    { "setting 1 (meniscus, bones and hook at full resolution)", true, true, true, 29.5 },
    { "setting 2 (bones reduced, hook as its centre line)", true, false, false, 8.95 },
    { "setting 3 (meniscus reduced to its collision mesh with radii, bones reduced, hook as its "
      "centre line)",
      false,
      false,
      false,
      6.5 },
  };
  for (const KneeSetting& setting : knees)
  {
    CorotationalHexFem fem(meniscus.simulation, material, settings);
    DeformableCollisionMesh collision(setting.visualMeniscus ? meniscus.visual : meniscus.collision,
      meniscus.simulation,
      setting.visualMeniscus ? VisualContactDistance : 0.0);
    const StaticObstacle tibia(setting.visualBones ? knee.tibia.visual : knee.tibia.collision);
    const StaticObstacle femur(setting.visualBones ? knee.femur.visual : knee.femur.collision);
    // Table 6-2 lists no cartilage: its lower bone is the plateau the
    // meniscus rests on. Ours has the medial tibial cartilage on it, so it
    // follows the bones: its visual surface in setting 1, its reduced
    // mid-surface with radii (100 triangles, 5.4.4) in settings 2 and 3.
    const StaticObstacle cartilage(
      setting.visualBones ? knee.tibialCartilage.visual : knee.tibialCartilage.collision);
    RigidTool tool("probe hook");
    std::string toolName;
    if (setting.toolMesh)
    {
      tool.setMesh(hook.visual, ToolMeshContactDistance);
      toolName = "hook mesh of " + std::to_string(hook.visual.vertexCount()) + " vertices";
    }
    else
    {
      addCentreLine(tool, hook);
      toolName = "hook centre line of " + std::to_string(hook.centreLine.size()) + " capsules";
    }
    CollisionScene scene;
    scene.addTissue(fem, collision);
    const int toolIndex = scene.addTool(tool);
    scene.addObstacle(tibia);
    scene.addObstacle(femur);
    scene.addObstacle(cartilage);
    PhysicsLoop loop(scene, settings.timeStep);
    loop.addVisual(fem, meniscus.simulation, meniscus.visual);
    tool.moveTo(above, settings.timeStep);
    loop.run(restSteps); // the meniscus settles on the plateau, the hook above it
    const ContactCounts before = countContacts(scene);
    loop.addPressingTool(tool, toolIndex, above, -Vector3::UnitZ(), pressSpeed, pressForce, 5.0);
    loop.run(pressSteps);
    const ContactCounts counts = countContacts(scene);
    const int lowerSide = scene.contactCountOnSide(0, -1);
    const double hookForce = loop.tissueReaction(toolIndex).z();
    const double milliseconds = loop.millisecondsPerStep(context, context.quick ? 2 : 100);
    char force[32];
    std::snprintf(force, sizeof(force), "%.1f", hookForce);
    reporter.report("knee " + setting.name + ", " + std::to_string(collision.positions().size()) +
                      " meniscus collision vertices, " + toolName + " pressing with " + force +
                      " N, " + std::to_string(counts.tool + counts.obstacle) + " contacts (" +
                      std::to_string(counts.tool) + " hook, " + std::to_string(counts.obstacle) +
                      " bone and cartilage; " + std::to_string(counts.obstacleFromBelow) +
                      " on the lower surface, " + std::to_string(before.obstacleFromBelow) +
                      " before the press; contactCountOnSide(0, -1) = " +
                      std::to_string(lowerSide) + ")" + loop.failureNote(),
      "physics step",
      milliseconds,
      "ms",
      setting.thesisMilliseconds);
  }
}

// --- Table 5-6 ---------------------------------------------------------------

void sheetCases(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  LinearMaterial material; // soft tissue, 0.5 MPa, 1000 kg/m^3 in mm, N, s
  material.youngModulus = 0.5;
  material.poissonRatio = 0.45;
  material.density = 1.0e-9;
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.01;
  const double halfThickness = 0.5 * ThinSheetParameters{}.thickness;
  const double gap = 2.0; // from the sheet's lower surface to the floor
  const double probeRadius = 1.5;
  const std::vector<double> thesis = { 13.55, 22.85, 45.7, 132.4 };
  for (int model = 1; model <= 4; ++model)
  {
    // The sheet (100 x 100 x 2 mm, centred on z = 0, fixed along x = +-50
    // mm) with the visual mesh of table 5-3's model 2 and the collision
    // mesh of table 5-5's model 1 to 3, or its visual mesh (model 4).
    const TissueModel sheet = makeThinSheet(
      thesisSheetVisualResolution(2, thesisSheetCollisionResolution(std::min(model, 3))));
    CorotationalHexFem fem(sheet.simulation, material, settings);
    const bool visual = model == 4;
    DeformableCollisionMesh collision(visual ? sheet.visual : sheet.collision,
      sheet.simulation,
      visual ? VisualContactDistance : 0.0);
    const StaticObstacle floor(floorSurface(25.0, 10, -halfThickness - gap));
    RigidTool probe("probe");
    probe.addCapsule(Vector3(0.0, 0.0, 60.0), Vector3::Zero(), probeRadius);
    CollisionScene scene;
    scene.addTissue(fem, collision);
    const int probeIndex = scene.addTool(probe);
    scene.addObstacle(floor);
    // The probe, vertical, from 0.5 mm above the sheet's centre down
    // through the gap and 0.5 mm further: the sheet is pressed onto the
    // floor, then held.
    const int pressSteps = context.quick ? 30 : 60;
    const double travel = 0.5 + gap + 0.5;
    PhysicsLoop loop(scene, settings.timeStep);
    loop.addVisual(fem, sheet.simulation, sheet.visual);
    loop.addPressingTool(probe,
      probeIndex,
      poseOf(
        Vector3::UnitZ(), Vector3::UnitX(), Vector3(0.0, 0.0, halfThickness + probeRadius + 0.5)),
      -Vector3::UnitZ(),
      travel / (pressSteps * settings.timeStep),
      std::numeric_limits<double>::infinity(),
      travel);
    loop.run(pressSteps + (context.quick ? 10 : 40));
    const ContactCounts counts = countContacts(scene);
    const double milliseconds = loop.millisecondsPerStep(context, context.quick ? 2 : 20);
    const std::string name =
      visual ? "model 4 (visual mesh as collision mesh, " +
                 std::to_string(collision.positions().size()) + " vertices, no radii)"
             : "model " + std::to_string(model) + " (" +
                 std::to_string(collision.positions().size()) + " collision vertices with radii)";
    reporter.report("sheet pressed onto a floor by a probe, " + name + ", " +
                      std::to_string(sheet.visual.vertexCount()) + " visual vertices, " +
                      std::to_string(counts.tool) + " probe and " +
                      std::to_string(counts.obstacle) + " floor contacts" + loop.failureNote(),
      "physics step",
      milliseconds,
      "ms",
      thesis[static_cast<std::size_t>(model - 1)]);
  }
}

// --- Table 5-7 ---------------------------------------------------------------

void ligamentCases(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const KneeSurroundingsParameters parameters;
  const TissueModel acl = makeCruciateLigament(CruciateLigament::Anterior, parameters);
  const TissueModel pcl = makeCruciateLigament(CruciateLigament::Posterior, parameters);
  // An isotropic stand-in for a ligament pushed sideways: its 100+ MPa act
  // along the fibres, across them it gives way easily. With E = 100 MPa the
  // single layer of hexahedra needs over 100 N to bring the ACL to the PCL.
  LinearMaterial material; // in mm, N, s
  material.youngModulus = 5.0;
  material.poissonRatio = 0.45;
  material.density = 1.1e-9;
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.001;

  // The ligaments cross in the notch without touching. The push goes from
  // the ACL's centre line toward the PCL's where they come closest away
  // from the fixed insertions: the ACL's middle toward the PCL's middle.
  Vector3 aclCentre = Vector3::Zero();
  Vector3 pclCentre = Vector3::Zero();
  double closest = std::numeric_limits<double>::max();
  for (int i = 20; i <= 80; ++i)
  {
    const Vector3 a = cruciateLigamentAttachment(CruciateLigament::Anterior, 0.01 * i, parameters);
    for (int j = 20; j <= 80; ++j)
    {
      const Vector3 p =
        cruciateLigamentAttachment(CruciateLigament::Posterior, 0.01 * j, parameters);
      if ((a - p).norm() < closest)
      {
        closest = (a - p).norm();
        aclCentre = a;
        pclCentre = p;
      }
    }
  }
  const Vector3 push = (pclCentre - aclCentre).normalized();
  // The ACL's back: its surface on the line through its centre, away from
  // the PCL.
  double back = 0.0;
  for (const Vector3& x : acl.visual.positions)
  {
    const Vector3 offset = x - aclCentre;
    const double along = offset.dot(push);
    if ((offset - along * push).norm() < 1.0)
    {
      back = std::min(back, along);
    }
  }
  // The hook 0.5 mm behind the ACL, handle away from the PCL (turned onto
  // the push by the shortest rotation of its axis), pokes it at 20 mm/s,
  // its tip leading, until the ligament pushes back with 30 N or the hook
  // has gone 8 mm: the ACL's middle is pressed onto the PCL. (Rolled with
  // the hook pointing up, +z, its centre line went across the ACL's
  // surface and the ACL was not pushed.)
  const SurgicalInstrumentModel hook = makeSurgicalInstrument(SurgicalInstrumentType::ProbeHook);
  RigidPose start;
  start.rotation = Eigen::Quaterniond::FromTwoVectors(Vector3::UnitZ(), -push).toRotationMatrix();
  start.translation = aclCentre + (back - 0.5) * push;
  const double pushSpeed = context.quick ? 60.0 : 20.0;
  const int pushSteps = context.quick ? 150 : 450;
  const std::vector<double> thesis = { 241.0, 50.0, 22.0, 11.0 };
  const std::vector<std::string> names = { "visual meshes",
    "closed surfaces of about 2,000 triangles",
    "closed surfaces of about 500 triangles",
    "reduced mid-surfaces with radii" };
  for (int s = 1; s <= 4; ++s)
  {
    const auto setting = static_cast<LigamentCollisionSetting>(s);
    const double distance =
      setting == LigamentCollisionSetting::ReducedWithRadii ? 0.0 : VisualContactDistance;
    CorotationalHexFem aclFem(acl.simulation, material, settings);
    CorotationalHexFem pclFem(pcl.simulation, material, settings);
    DeformableCollisionMesh aclCollision(
      cruciateLigamentCollisionMesh(CruciateLigament::Anterior, setting, parameters),
      acl.simulation,
      distance);
    DeformableCollisionMesh pclCollision(
      cruciateLigamentCollisionMesh(CruciateLigament::Posterior, setting, parameters),
      pcl.simulation,
      distance);
    RigidTool tool("probe hook");
    addCentreLine(tool, hook);
    CollisionScene scene;
    scene.addTissue(aclFem, aclCollision);
    scene.addTissue(pclFem, pclCollision);
    const int toolIndex = scene.addTool(tool);
    PhysicsLoop loop(scene, settings.timeStep);
    loop.addVisual(aclFem, acl.simulation, acl.visual);
    loop.addVisual(pclFem, pcl.simulation, pcl.visual);
    loop.addPressingTool(tool, toolIndex, start, push, pushSpeed, 30.0, 8.0);
    loop.run(pushSteps);
    const ContactCounts counts = countContacts(scene);
    const int jointIterations = scene.statistics().jointIterations;
    const double hookForce = -push.dot(loop.tissueReaction(toolIndex));
    const double milliseconds = loop.millisecondsPerStep(context, context.quick ? 2 : 20);
    char force[32];
    std::snprintf(force, sizeof(force), "%.1f", hookForce);
    reporter.report("cruciate ligaments, setting " + std::to_string(s) + " (" + names[s - 1] +
                      ", ACL " + std::to_string(aclCollision.positions().size()) + " and PCL " +
                      std::to_string(pclCollision.positions().size()) +
                      " collision vertices), ACL pushed into the PCL by the hook with " + force +
                      " N, " + std::to_string(counts.tissue) + " tissue-tissue and " +
                      std::to_string(counts.tool) + " hook contacts, " +
                      std::to_string(jointIterations) + " joint CG iterations" + loop.failureNote(),
      "physics step",
      milliseconds,
      "ms",
      thesis[static_cast<std::size_t>(s - 1)]);
  }
}

} // namespace

THINTISSUE_BENCHMARK_SUITE(collisionSuite,
  "collision",
  "full physics step with CollisionScene and the visual mesh update: meniscus pressed onto the "
  "tibia (table 6-2), sheet pressed onto a floor (table 5-6), ACL pushed into the PCL (table 5-7)")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  kneeCases(context, reporter);
  sheetCases(context, reporter);
  ligamentCases(context, reporter);
}
