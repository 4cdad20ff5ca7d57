#include "TrainingScene.h"

#include "LocalContactModel.h"
#include "ThinTissueError.h"

#include <nlohmann/json.hpp>

#include <algorithm>

namespace thintissue
{

namespace
{

PortalSettings portalOf(const PortalDescription& p)
{
  PortalSettings s;
  s.portal = p.portal;
  s.inward = p.inward;
  return s;
}

} // namespace

TrainingScene::TrainingScene(const ScenarioDescription& scenario,
  HapticDevice& scope,
  HapticDevice& instrument)
  : Scenario(scenario)
  , Tool(instrumentTypeName(scenario.instrument))
{
  KneeSurroundingsParameters knee;
  knee.jointGap = scenario.jointGap;
  Knee = makeKneeSurroundings(knee);
  Instrument = makeSurgicalInstrument(scenario.instrument);
  for (const auto& segment : Instrument.centreLine)
  {
    Tool.addCapsule(segment.end, segment.start, segment.radius);
  }
  buildTissue();
  buildContacts();
  Servo = std::make_unique<HapticServo>(
    std::vector<HapticSlot>{ HapticSlot{ &scope, portalOf(scenario.scopePortal), false },
      HapticSlot{ &instrument, portalOf(scenario.instrumentPortal), true } });
  Servo->tick(0.0);
  Tool.setPose(Servo->latestToolState(1).pose);
  ScopePose = Servo->latestToolState(0).pose;
}

TrainingScene::~TrainingScene() = default;

void TrainingScene::buildTissue()
{
  MeniscusParameters p =
    Scenario.examinationResolution ? examinationMeniscusParameters() : MeniscusParameters{};
  p.tear = defaultMeniscusTear(Scenario.tear);
  Meniscus = makeMeniscus(p);
  CorotationalHexFemSettings settings;
  settings.timeStep = Scenario.timeStep;
  Fem = std::make_unique<CorotationalHexFem>(Meniscus.simulation, Scenario.material, settings);
  Collision = std::make_unique<DeformableCollisionMesh>(Meniscus.collision, Meniscus.simulation);
  VisualEmbedding.embed(Meniscus.simulation, Meniscus.visual.positions);
  if (Scenario.wrinkles)
  {
    // Monitor points every 0.16 mm: about the thesis's 296 (6.4.1).
    Wrinkles = std::make_unique<WrinkleGenerator>(
      resampleMonitorCurves(wrinkleDataCurves(Meniscus.monitorCurves), 0.16, Scenario.source),
      Meniscus.simulation,
      Meniscus.visual);
  }
}

void TrainingScene::buildContacts()
{
  Tibia = std::make_unique<StaticObstacle>(Knee.tibia.collision);
  // The cartilage as its reduced thick mid-surface (100 triangles with radii,
  // thesis 5.4.4): against its 5,080-triangle visual surface the contacts of
  // the meniscus resting on it cost 2.5 ms a step.
  Cartilage = std::make_unique<StaticObstacle>(Knee.tibialCartilage.collision);
  Contacts.addTissue(*Fem, *Collision);
  Contacts.addTool(Tool);
  Contacts.addObstacle(*Tibia);
  CartilageObstacle = Contacts.addObstacle(*Cartilage);
}

bool TrainingScene::step()
{
  const double end = Metrics.time + Scenario.timeStep;
  // The servo at 1 kHz up to the end of the step (lock-step).
  while (ServoTime + 0.001 <= end + 1e-12)
  {
    ServoTime += 0.001;
    Servo->tick(ServoTime);
  }
  const RigidPose previousTool = Tool.pose();
  const RigidPose previousScope = ScopePose;
  Tool.moveTo(Servo->latestToolState(1).pose, Scenario.timeStep);
  ScopePose = Servo->latestToolState(0).pose;
  const SolverResult result = Contacts.step();
  if (!result.ok)
  {
    LastError = result.message;
    return false;
  }
  Metrics.time = end;
  fillLocalContactModel(Contacts, Tool, 0, ServoTime, Servo->contactModelToFill(1));
  Servo->publishContactModel(1);
  if (Wrinkles)
  {
    Wrinkles->update(Fem->positions(), wrinkleContactState(Contacts, 0));
  }
  VisualStale = true;
  updateMetrics(previousTool, previousScope);
  return true;
}

const std::vector<Vector3>& TrainingScene::visualPositions() const
{
  if (VisualStale)
  {
    VisualEmbedding.mapPositions(Fem->positions(), Visual);
    if (Wrinkles)
    {
      Wrinkles->applyTo(Visual);
    }
    VisualStale = false;
  }
  return Visual;
}

bool TrainingScene::runTo(double seconds)
{
  while (Metrics.time + 0.5 * Scenario.timeStep < seconds)
  {
    if (!step())
    {
      return false;
    }
  }
  return true;
}

void TrainingScene::updateMetrics(const RigidPose& previousTool, const RigidPose& previousScope)
{
  ++Metrics.steps;
  Metrics.instrumentPathLength += (Tool.pose().translation - previousTool.translation).norm();
  Metrics.cameraPathLength += (ScopePose.translation - previousScope.translation).norm();
  Metrics.peakForce = std::max(Metrics.peakForce, Tool.force().norm());
  const bool onCartilage = std::any_of(Contacts.contacts().begin(),
    Contacts.contacts().end(),
    [&](const SceneContact& c)
    {
      return c.first.kind == SceneBodyKind::Tool && c.second.kind == SceneBodyKind::Obstacle &&
             c.second.index == CartilageObstacle;
    });
  Metrics.cartilageContactSteps += onCartilage ? 1 : 0;
  Metrics.wrinklingSteps += wrinkling() ? 1 : 0;
}

std::string TrainingScene::metricsJson() const
{
  const nlohmann::ordered_json j = { { "scenario", Scenario.name },
    { "time_s", Metrics.time },
    { "steps", Metrics.steps },
    { "instrument_path_mm", Metrics.instrumentPathLength },
    { "camera_path_mm", Metrics.cameraPathLength },
    { "cartilage_contact_steps", Metrics.cartilageContactSteps },
    { "peak_force_N", Metrics.peakForce },
    { "wrinkling_steps", Metrics.wrinklingSteps } };
  return j.dump(2);
}

} // namespace thintissue
