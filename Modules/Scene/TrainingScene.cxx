#include "TrainingScene.h"

#include "LocalContactModel.h"
#include "ThinTissueError.h"
#include "VisualCollisionBinding.h"

#include <nlohmann/json.hpp>
#include <tbb/task_group.h>

#include <algorithm>
#include <chrono>

namespace thintissue
{

namespace
{

double millisecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

PortalSettings portalOf(const PortalDescription& p)
{
  PortalSettings s;
  s.portal = p.portal;
  s.inward = p.inward;
  return s;
}

/// Seconds the punch's or the scissors' jaws take to close fully (and to
/// open again) while the stylus's first button is held (released).
constexpr double JawTravelTime = 0.1;

} // namespace

/// A cut whose visual half is due in this step, and the task group that
/// runs the physics beside it.
struct TrainingScene::VisualHalf
{
  InstrumentActionResult done;
  bool due = false;
  tbb::task_group task;
};

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
    // A cutting instrument's jaws and blades close around the tissue they
    // cut: only its shaft pushes tissue (the capsules containing the jaws
    // would squeeze the tissue held between them).
    if (instrumentCuts(scenario.instrument) && segment.part != "shaft")
    {
      continue;
    }
    Tool.addCapsule(segment.end, segment.start, segment.radius);
  }
  buildTissue();
  if (Scenario.portalsFromTissueCentre)
  {
    const Vector3 centre = Tissue.model.visual.boundingBox().center();
    Scenario.instrumentPortal.portal += centre;
    Scenario.scopePortal.portal += centre;
  }
  buildContacts();
  Servo = std::make_unique<HapticServo>(
    std::vector<HapticSlot>{ HapticSlot{ &scope, portalOf(Scenario.scopePortal), false },
      HapticSlot{ &instrument, portalOf(Scenario.instrumentPortal), true } });
  Servo->tick(0.0);
  InstrumentState = Servo->latestToolState(1);
  ScopeState = Servo->latestToolState(0);
  Tool.setPose(InstrumentState.pose);
  ScopePose = ScopeState.pose;
}

TrainingScene::~TrainingScene() = default;

void TrainingScene::buildTissue()
{
  Tissue = makeScenarioTissue(Scenario, Knee);
  const TissueModel& model = Tissue.model;
  CorotationalHexFemSettings settings;
  settings.timeStep = Scenario.timeStep;
  Fem = std::make_unique<CorotationalHexFem>(model.simulation, Scenario.material, settings);
  if (instrumentCuts(Scenario.instrument))
  {
    buildCutting();
    return;
  }
  Collision = std::make_unique<DeformableCollisionMesh>(model.collision, model.simulation);
  VisualEmbedding.embed(model.simulation, model.visual.positions);
  buildWrinkles(model.simulation, model.visual);
}

void TrainingScene::buildWrinkles(const HexahedralMesh& hexahedra, const TriangleMesh& surface)
{
  if (Scenario.wrinkles && !Tissue.monitorCurves.empty())
  {
    // Monitor points every 0.16 mm: about the thesis's 296 (6.4.1).
    Wrinkles = std::make_unique<WrinkleGenerator>(
      resampleMonitorCurves(wrinkleDataCurves(Tissue.monitorCurves), 0.16, Scenario.source),
      hexahedra,
      surface,
      Scenario.wrinkle);
  }
}

namespace
{

/// The cutter's settings from the scenario's cutting keys; removed pieces
/// are handed over so that the scene can measure them.
TissueCutterSettings cutterSettings(const ScenarioDescription& scenario)
{
  TissueCutterSettings settings;
  settings.freePieces = FreePieceHandling::HandOver;
  settings.visual.cutSurfaceRows = scenario.cutSurfaceRows;
  settings.fragmentAreaFraction = scenario.fragmentAreaFraction;
  settings.visual.jaggedAmplitude = scenario.jaggedAmplitude;
  settings.visual.jaggedWavelength = scenario.jaggedWavelength;
  settings.visual.jaggedSeed = scenario.jaggedSeed;
  return settings;
}

} // namespace

void TrainingScene::buildCutting()
{
  // A cutting instrument: the visual mesh bound to the collision mesh (5.2)
  // so that cuts reach it (5.3), removed pieces handed over to measure them.
  // (A file or a bundle came with its binding.)
  if (!Tissue.binding)
  {
    Tissue.binding = std::make_unique<VisualCollisionBinding>(
      bindVisualToCollision(Tissue.model.visual, Tissue.model.collision));
  }
  Cutter = std::make_unique<TissueCutter>(
    *Tissue.binding, Tissue.model.simulation, Fem.get(), cutterSettings(Scenario));
  InstrumentActionSettings action;
  action.shaverMode = Scenario.shaverMode;
  action.contourStrength = Scenario.contourStrength;
  Action = std::make_unique<InstrumentAction>(Instrument, action);
  // The monitor points in the cutter's hexahedra (a torn tissue's copies).
  buildWrinkles(Cutter->simulation(), Cutter->visual().mesh());
  biteAtLoad();
  rebuildCollisionMesh();
  measureRim();
  Metrics.rimRoughnessAtStart = Metrics.rimRoughness;
}

void TrainingScene::biteAtLoad()
{
  // The scenario's preparation: punch bites along the inner border (the
  // first monitor curve), the punch's jaws around it opening upward, its
  // shaft toward the open side, as a surgeon bites (6.4.2) -- the rim a
  // contouring task starts from. The bitten pieces go uncounted.
  if (Scenario.preBites == 0 || Tissue.monitorCurves.empty())
    return;
  const MonitorCurve& border = Tissue.monitorCurves.front();
  const SurgicalInstrumentModel punch = makeSurgicalInstrument(SurgicalInstrumentType::Punch);
  Vector3 biteCentre = Vector3::Zero();
  for (const Vector3& p : punch.biteOutline)
    biteCentre += p;
  biteCentre /= static_cast<double>(punch.biteOutline.size());
  for (int k = 0; k < Scenario.preBites; ++k)
  {
    const double along = Scenario.preBitesFrom + (Scenario.preBitesTo - Scenario.preBitesFrom) * k /
                                                   std::max(1, Scenario.preBites - 1);
    // Between the border's data points (a few mm apart), so that the bites
    // are evenly spaced.
    const double x = along * static_cast<double>(border.monitorPoints.size() - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(x), border.monitorPoints.size() - 2);
    const double w = x - static_cast<double>(i);
    const Vector3 rim = (1 - w) * border.monitorPoints[i] + w * border.monitorPoints[i + 1];
    Vector3 into = (1 - w) * border.regionPoints[i] + w * border.regionPoints[i + 1] - rim;
    into.z() = 0.0;
    into.normalize();
    ToolFrame frame;
    frame.handleAxis = -into;
    frame.up = Vector3::UnitZ();
    InstrumentCommand command;
    command.pose.rotation = frame.rotation();
    // The fixed jaw 0.6 mm below the border: the tissue rests on it.
    command.pose.translation = rim + Scenario.preBitesInward * into - Vector3(0.0, 0.0, 0.6) -
                               command.pose.rotation * biteCentre;
    InstrumentAction bite(punch);
    bite.apply(*Cutter, command);
    command.time = JawTravelTime;
    command.jawOpening = 0.0;
    const InstrumentActionResult done = bite.apply(*Cutter, command);
    if (done.changed() && Wrinkles)
      Wrinkles->followCut(*Cutter, done.report);
  }
}

void TrainingScene::measureRim()
{
  // Only where a rim can be rough (a jagged cut surface, or a shaver that
  // contours): the measure walks every cut-surface strip.
  if (Scenario.jaggedAmplitude > 0.0 || Scenario.shaverMode == ShaverMode::Contour)
  {
    const CutSurfaceRoughness rim = Cutter->cutRimRoughness();
    Metrics.rimRoughness = rim.rootMeanSquare;
    Metrics.rimRoughnessMaximum = rim.maximum;
  }
}

void TrainingScene::rebuildCollisionMesh()
{
  // The collision mesh of the triangles still in the tissue, each vertex
  // embedded where the cutter keeps it (the copy holding its branch).
  const CuttableCollisionMesh& cut = Cutter->collision();
  const HexahedralEmbedding& embedding = Cutter->collisionEmbedding();
  std::vector<int> newIndex(cut.vertexCount(), -1);
  TriangleMesh active;
  active.name = Tissue.model.collision.name;
  std::vector<double> radii;
  std::vector<int> hexahedra;
  std::vector<Vector3> local;
  for (std::size_t t = 0; t < cut.triangleCount(); ++t)
  {
    if (!Cutter->isActive(static_cast<int>(t)))
      continue;
    Triangle triangle = cut.triangles()[t];
    for (int& v : triangle)
    {
      if (newIndex[v] < 0)
      {
        newIndex[v] = static_cast<int>(active.positions.size());
        active.positions.push_back(cut.restPositions()[v]);
        radii.push_back(cut.radii()[v]);
        hexahedra.push_back(embedding.hexahedron(v));
        local.push_back(embedding.localCoordinates(v));
      }
      v = newIndex[v];
    }
    active.triangles.push_back(triangle);
  }
  active.pointAttributes.set("Radius", 1, radii);
  HexahedralEmbedding activeEmbedding;
  activeEmbedding.assign(Cutter->simulation(), std::move(hexahedra), std::move(local));
  if (Collision)
  {
    *Collision = DeformableCollisionMesh(active, std::move(activeEmbedding));
  }
  else
  {
    Collision = std::make_unique<DeformableCollisionMesh>(active, std::move(activeEmbedding));
  }
}

void TrainingScene::buildContacts()
{
  Contacts.addTissue(*Fem, *Collision);
  Contacts.addTool(Tool);
  // The bones and the cartilage are obstacles for the meniscus and for
  // tissues brought in; the knee's own ligaments and cartilage are held by
  // their attachments instead (they lie on the bone).
  const bool kneePart = Scenario.tissueModel == "anterior_cruciate_ligament" ||
                        Scenario.tissueModel == "posterior_cruciate_ligament" ||
                        Scenario.tissueModel == "tibial_cartilage";
  if (!Scenario.knee || kneePart)
  {
    return;
  }
  Tibia = std::make_unique<StaticObstacle>(Knee.tibia.collision);
  // The cartilage as its reduced thick mid-surface (100 triangles with radii,
  // thesis 5.4.4): against its 5,080-triangle visual surface the contacts of
  // the meniscus resting on it cost 2.5 ms a step.
  Cartilage = std::make_unique<StaticObstacle>(Knee.tibialCartilage.collision);
  Contacts.addObstacle(*Tibia);
  CartilageObstacle = Contacts.addObstacle(*Cartilage);
}

bool TrainingScene::step()
{
  const double end = Metrics.time + Scenario.timeStep;
  if (Ticking == ServoTicking::LockStep)
  {
    // The servo at 1 kHz up to the end of the step.
    while (ServoTime + 0.001 <= end + 1e-12)
    {
      ServoTime += 0.001;
      Servo->tick(ServoTime);
    }
  }
  // Each slot's latest state taken once (copied: the servo may publish
  // another while the step runs).
  InstrumentState = Servo->latestToolState(1);
  ScopeState = Servo->latestToolState(0);
  if (Ticking == ServoTicking::Elsewhere)
  {
    ServoTime = InstrumentState.time; // the contact model's time, on the servo's clock
  }
  const RigidPose previousTool = Tool.pose();
  const RigidPose previousScope = ScopePose;
  Tool.moveTo(InstrumentState.pose, Scenario.timeStep);
  ScopePose = ScopeState.pose;
  if (Action)
  {
    operate(InstrumentState);
  }
  const SolverResult result =
    PendingVisual && PendingVisual->due ? stepBesideVisualHalf() : Contacts.step();
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

void TrainingScene::operate(const HapticToolState& instrument)
{
  // The first button closes the jaws (punch, scissors) and runs the
  // scalpel's edge or the shaver's motor.
  const bool pressed = (instrument.stylus.buttons & 1u) != 0;
  const double travel = Scenario.timeStep / JawTravelTime;
  JawOpening = std::clamp(JawOpening + (pressed ? -travel : travel), 0.0, 1.0);
  InstrumentCommand command;
  command.time = Metrics.time + Scenario.timeStep;
  command.pose = Tool.pose();
  command.jawOpening = JawOpening;
  command.working = pressed;
  const auto start = std::chrono::steady_clock::now();
  InstrumentActionResult done = Action->applyVisualLater(*Cutter, command);
  const double operation = millisecondsSince(start);
  if (done.contoured())
  {
    // The cut surface's rest positions moved (not the collision mesh): the
    // view draws the rest mesh again.
    ++TopologyVersion;
    ++Metrics.contourPasses;
    measureRim();
  }
  // A removal may take a piece that was apart already without cutting
  // anything: it changes the tissue too.
  if (done.changed() || done.report.removedPieces > 0)
  {
    const auto scene = std::chrono::steady_clock::now();
    // The collision side first: the physics step reads nothing else.
    ++TopologyVersion;
    ++Metrics.operations;
    rebuildCollisionMesh();
    LastCutTimes = CutStepTimes();
    LastCutTimes.scene = millisecondsSince(scene);
    LastCutTimes.cutterOnStep = done.report.totalMilliseconds;
    LastCutTimes.operation = operation - done.report.totalMilliseconds;
    if (!PendingVisual)
      PendingVisual = std::make_unique<VisualHalf>();
    PendingVisual->done = std::move(done);
    PendingVisual->due = true;
  }
}

// The rest of a cut or a shaving pass (its visual half), the
// pieces' volumes and the wrinkles following the cut, on this thread, while
// a worker runs the contacts and the FEM step: those read only the
// collision side and the solver, the visual half only the cutter's visual
// side and the wrinkles. (The other way round measured slower: the visual
// half allocates, and a worker's malloc arena gives its memory back after
// each cut.)
SolverResult TrainingScene::stepBesideVisualHalf()
{
  VisualHalf& half = *PendingVisual;
  half.due = false;
  SolverResult result;
  double physics = 0.0;
  half.task.run(
    [&]
    {
      const auto start = std::chrono::steady_clock::now();
      result = Contacts.step();
      physics = millisecondsSince(start);
    });
  const auto start = std::chrono::steady_clock::now();
  try
  {
    Action->finishCut(*Cutter, half.done);
    if (Wrinkles)
      Wrinkles->followCut(*Cutter, half.done.report);
  }
  catch (...)
  {
    try
    {
      half.task.wait();
    }
    catch (...)
    {
      // The visual half's error is the one reported.
    }
    throw;
  }
  LastCutTimes.visualAside = millisecondsSince(start);
  const auto wait = std::chrono::steady_clock::now();
  half.task.wait();
  LastCutTimes.visualWait = millisecondsSince(wait);
  LastCutTimes.physics = physics;
  const auto scene = std::chrono::steady_clock::now();
  takeRemovedPieces(half.done);
  LastCutTimes.scene += millisecondsSince(scene);
  const TissueCutReport& report = half.done.report;
  LastCutTimes.cutter.collisionMilliseconds = report.collisionMilliseconds;
  LastCutTimes.cutter.simulationMilliseconds = report.simulationMilliseconds;
  LastCutTimes.cutter.embeddingMilliseconds = report.embeddingMilliseconds;
  LastCutTimes.cutter.visualMilliseconds = report.visualMilliseconds;
  LastCutTimes.cutter.visualEmbeddingMilliseconds = report.visualEmbeddingMilliseconds;
  LastCutTimes.cutter.removalMilliseconds = report.removalMilliseconds;
  LastCutTimes.cutter.totalMilliseconds = report.totalMilliseconds;
  half.done = InstrumentActionResult();
  return result;
}

// The pieces a cut took into the metrics (in or outside the task's target
// region), and the rim measured again.
void TrainingScene::takeRemovedPieces(const InstrumentActionResult& done)
{
  Metrics.removedVolume += done.removedVolume;
  for (std::size_t p = 0; p < done.report.handedOver.size(); ++p)
  {
    const std::vector<Vector3>& rest = done.report.handedOver[p].visualRest;
    Vector3 centre = Vector3::Zero();
    for (const Vector3& x : rest)
      centre += x;
    centre /= static_cast<double>(std::max<std::size_t>(1, rest.size()));
    const bool inTarget = Scenario.targetRadius > 0.0 &&
                          (centre - Scenario.targetCentre).norm() <= Scenario.targetRadius;
    (inTarget ? Metrics.removedInTarget : Metrics.removedOutsideTarget) += done.pieceVolumes[p];
  }
  measureRim();
}

bool TrainingScene::applySettings(const ScenarioDescription& changed)
{
  const bool cutSurfaceChanged = changed.cutSurfaceRows != Scenario.cutSurfaceRows ||
                                 changed.fragmentAreaFraction != Scenario.fragmentAreaFraction ||
                                 changed.jaggedAmplitude != Scenario.jaggedAmplitude ||
                                 changed.jaggedWavelength != Scenario.jaggedWavelength ||
                                 changed.jaggedSeed != Scenario.jaggedSeed;
  if (Cutter && cutSurfaceChanged)
  {
    // For the cuts to come; a new row count once the tissue has a cut
    // surface is refused (the scene must be built again).
    try
    {
      Cutter->setSettings(cutterSettings(changed));
    }
    catch (const InvalidInputError&)
    {
      return false;
    }
  }
  const LinearMaterial& m = changed.material;
  if (m.youngModulus != Scenario.material.youngModulus ||
      m.poissonRatio != Scenario.material.poissonRatio || m.density != Scenario.material.density)
  {
    // Each element's stiffness and mass made again from its rest shape
    // (the solver keeps positions and velocities: the tissue goes on from
    // where it is, softer or stiffer).
    for (std::size_t h = 0; h < Fem->hexahedronCount(); ++h)
      Fem->setMaterial(h, m);
  }
  if (Wrinkles)
  {
    Wrinkles->setParameters(changed.wrinkle);
  }
  Scenario.material = changed.material;
  Scenario.wrinkle = changed.wrinkle;
  Scenario.cutSurfaceRows = changed.cutSurfaceRows;
  Scenario.fragmentAreaFraction = changed.fragmentAreaFraction;
  Scenario.jaggedAmplitude = changed.jaggedAmplitude;
  Scenario.jaggedWavelength = changed.jaggedWavelength;
  Scenario.jaggedSeed = changed.jaggedSeed;
  return true;
}

const TriangleMesh& TrainingScene::visualMesh() const
{
  return Cutter ? Cutter->visual().mesh() : Tissue.model.visual;
}

std::vector<char> TrainingScene::activeVisualTriangles() const
{
  return Cutter ? Cutter->activeVisualTriangles()
                : std::vector<char>(Tissue.model.visual.triangleCount(), 1);
}

const std::vector<Vector3>& TrainingScene::visualPositions() const
{
  if (VisualStale)
  {
    const HexahedralEmbedding& embedding = Cutter ? Cutter->visualEmbedding() : VisualEmbedding;
    embedding.mapPositions(Fem->positions(), Visual);
    if (Wrinkles)
    {
      Wrinkles->applyTo(Visual);
    }
    VisualStale = false;
  }
  return Visual;
}

std::shared_ptr<const SceneTopology> TrainingScene::currentTopology() const
{
  if (Topology && Topology->version == TopologyVersion)
  {
    return Topology;
  }
  // Made again only after a cut: the mesh's rest state, without texture.
  auto topology = std::make_shared<SceneTopology>();
  const TriangleMesh& mesh = visualMesh();
  topology->version = TopologyVersion;
  topology->mesh.name = mesh.name;
  topology->mesh.positions = mesh.positions;
  topology->mesh.triangles = mesh.triangles;
  topology->mesh.normals = mesh.normals;
  topology->active = activeVisualTriangles();
  if (Cutter)
  {
    topology->materials = Cutter->visual().triangleMaterials();
  }
  Topology = std::move(topology);
  return Topology;
}

void TrainingScene::snapshot(SceneSnapshot& out) const
{
  out.time = Metrics.time;
  out.topology = currentTopology();
  const std::vector<Vector3>& positions = visualPositions();
  out.visualPositions.assign(positions.begin(), positions.end()); // no allocation once sized
  out.instrument = Tool.pose();
  out.scope = ScopePose;
  out.jawOpening = JawOpening;
  out.wrinkling = wrinkling();
  out.metrics = Metrics;
  const HapticToolState* states[2] = { &ScopeState, &InstrumentState };
  for (int slot = 0; slot < 2; ++slot)
  {
    out.devices[slot].calibrated = states[slot]->stylus.calibrated;
    out.devices[slot].buttons = states[slot]->stylus.buttons;
    out.devices[slot].force = states[slot]->force;
  }
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
    { "wrinkling_steps", Metrics.wrinklingSteps },
    { "operations", Metrics.operations },
    { "removed_volume_mm3", Metrics.removedVolume },
    { "removed_in_target_mm3", Metrics.removedInTarget },
    { "removed_outside_target_mm3", Metrics.removedOutsideTarget },
    { "contour_passes", Metrics.contourPasses },
    { "rim_roughness_start_mm", Metrics.rimRoughnessAtStart },
    { "rim_roughness_mm", Metrics.rimRoughness },
    { "rim_roughness_max_mm", Metrics.rimRoughnessMaximum } };
  return j.dump(2);
}

} // namespace thintissue
