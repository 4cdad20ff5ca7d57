// The training scene (thesis 6.2, without SOFA's scene graph): one tissue
// (its three meshes, the FEM, the collision mesh, the wrinkles and, with a
// cutting instrument, its cutter), the static bones, the instrument (a
// rigid tool moved by its device through its portal) and the arthroscope,
// and the one place that orders a physics step:
//   device poses -> cutting / removal (InstrumentAction, 6.4) -> collision
//   -> contact forces -> FEM step -> local contact model published to the
//   servo -> wrinkles -> visual surface -> metrics.
//
// By default the scene runs in lock-step (no threads): step() ticks the
// servo at 1 ms up to the step's end, then does the rest. With scripted
// devices a run is deterministic: tests, benchmarks, replays and image
// baselines use it. RealTimeLoop runs it on a physics thread instead, the
// servo ticked on its own (ServoTicking::Elsewhere), and hands the GUI
// SceneSnapshots.
#ifndef TrainingScene_h
#define TrainingScene_h

#include "CollisionScene.h"
#include "HapticServo.h"
#include "InstrumentAction.h"
#include "KneeModels.h"
#include "Scenario.h"
#include "ScenarioTissue.h"
#include "SceneSnapshot.h"
#include "ThinTissueSceneModule.h"
#include "WrinkleGenerator.h"

#include <memory>
#include <string>
#include <vector>

namespace thintissue
{

/// Who ticks the servo: the scene's step itself at 1 ms up to the step's
/// end (lock-step: deterministic), or another thread (ServoThread, the
/// OpenHaptics scheduler; the step then takes the servo's latest poses).
enum class ServoTicking
{
  LockStep,
  Elsewhere
};

/// Where the last step with a cut spent its time (ms): the cutter's stages
/// (TissueCutReport), the operation around it (InstrumentAction: the blade,
/// the removed pieces' volumes), and the scene's part (wrinkles following
/// the cut, the collision mesh rebuilt, the rim measured). For benchmarks.
struct CutStepTimes
{
  TissueCutReport cutter; ///< timings only (its meshes' lists cleared)
  /// The cutter's work on the stepping thread (a blade cut's collision
  /// half; a shaving pass whole).
  double cutterOnStep = 0.0;
  double operation = 0.0;
  double scene = 0.0;
  /// The contacts and FEM step that follows the cut in the same physics
  /// step (the solver takes the changed hexahedra in it).
  double physics = 0.0;
  /// The rest of the cut (a blade cut's visual half: visual cut,
  /// re-embedding, the pieces' visual parts and volumes; the wrinkles
  /// following the cut) on the stepping thread while a worker runs the
  /// contacts and FEM step (`physics`), and how long the step then waited
  /// for that.
  double visualAside = 0.0;
  double visualWait = 0.0;
};

class THINTISSUESCENE_EXPORT TrainingScene
{
public:
  /// Builds the scenario's tissue, bones, instrument and arthroscope; the
  /// devices (not owned) drive the arthroscope and the instrument. Throws
  /// InvalidInputError naming the scenario on what it cannot build.
  TrainingScene(const ScenarioDescription& scenario, HapticDevice& scope, HapticDevice& instrument);
  ~TrainingScene();
  TrainingScene(const TrainingScene&) = delete;
  TrainingScene& operator=(const TrainingScene&) = delete;

  /// One physics step of scenario().timeStep seconds. Returns false if the
  /// solver failed (the scene keeps its last good state; see lastError()).
  bool step();
  /// Steps until time() reaches `seconds`.
  bool runTo(double seconds);
  /// Before the first step on another thread: who ticks the servo.
  void setServoTicking(ServoTicking ticking) { Ticking = ticking; }
  ServoTicking servoTicking() const { return Ticking; }
  /// The servo clock's time of the last tool state the scene took (s).
  double servoTime() const { return ServoTime; }
  /// Copies what the GUI draws into `out` (reusing its buffers; the
  /// topology is shared and made again only after a cut). Call on the
  /// thread that steps the scene.
  void snapshot(SceneSnapshot& out) const;

  /// Applies changed settings (the window's panel: applyScenarioSettings)
  /// to the running scene between two steps, without building it again:
  /// the material (every hexahedron's, the masses following) and the
  /// wrinkle parameters, and the cut-surface settings (fragments, jagged
  /// cut surface, rows until the first cut) for the cuts to come. A new row
  /// count once the tissue has a cut surface returns false, changing
  /// nothing (build the scene again). Only
  /// the settings' keys may differ from scenario(). Not while another
  /// thread steps the scene.
  bool applySettings(const ScenarioDescription& changed);

  double time() const { return Metrics.time; }
  const ScenarioDescription& scenario() const { return Scenario; }
  const SceneMetrics& metrics() const { return Metrics; }
  /// The metrics as a JSON object (text).
  std::string metricsJson() const;
  const std::string& lastError() const { return LastError; }

  /// The tissue: its model (rest meshes, as built), the visual surface now
  /// (wrinkles included), whether it wrinkles.
  const TissueModel& tissue() const { return Tissue.model; }
  /// The visual surface's rest mesh as cut so far (with its cut surfaces;
  /// the model's before any cut); its topology changes when
  /// topologyVersion() does.
  const TriangleMesh& visualMesh() const;
  int topologyVersion() const { return TopologyVersion; }
  /// Mapped from the hexahedra when asked for (a replay without pictures
  /// never pays for it), wrinkles added; one per visualMesh() vertex.
  const std::vector<Vector3>& visualPositions() const;
  /// Per visualMesh() triangle: whether it is still part of the tissue
  /// (removed pieces are not drawn).
  std::vector<char> activeVisualTriangles() const;
  /// The cutter, with a cutting instrument (null otherwise).
  const TissueCutter* cutter() const { return Cutter.get(); }
  /// Punch and scissors: 1 open, 0 closed (the stylus's first button
  /// closes them); other instruments 1.
  double jawOpening() const { return JawOpening; }
  bool wrinkling() const { return Wrinkles && Wrinkles->wrinkling(); }
  const KneeSurroundings& knee() const { return Knee; }
  const SurgicalInstrumentModel& instrumentModel() const { return Instrument; }
  const RigidPose& instrumentPose() const { return Tool.pose(); }
  const RigidPose& scopePose() const { return ScopePose; }
  HapticServo& servo() { return *Servo; }
  /// The times of the last step that cut (zero before the first).
  const CutStepTimes& lastCutTimes() const { return LastCutTimes; }
  /// The collision scene of the last step (contacts, statistics).
  const CollisionScene& contacts() const { return Contacts; }
  /// The tissue's FEM (read only: counts, positions, settings).
  const CorotationalHexFem& solver() const { return *Fem; }

private:
  void buildTissue();
  void buildCutting();
  void biteAtLoad();
  void measureRim();
  void takeRemovedPieces(const InstrumentActionResult& done);
  SolverResult stepBesideVisualHalf();
  void buildWrinkles(const HexahedralMesh& hexahedra, const TriangleMesh& surface);
  void buildContacts();
  void rebuildCollisionMesh();
  void operate(const HapticToolState& instrument);
  void updateMetrics(const RigidPose& previousTool, const RigidPose& previousScope);
  std::shared_ptr<const SceneTopology> currentTopology() const;

  ScenarioDescription Scenario;
  ScenarioTissue Tissue;
  KneeSurroundings Knee;
  SurgicalInstrumentModel Instrument;
  std::unique_ptr<CorotationalHexFem> Fem;
  std::unique_ptr<DeformableCollisionMesh> Collision;
  std::unique_ptr<StaticObstacle> Tibia;
  std::unique_ptr<StaticObstacle> Cartilage;
  RigidTool Tool;
  CollisionScene Contacts;
  std::unique_ptr<HapticServo> Servo;
  std::unique_ptr<WrinkleGenerator> Wrinkles;
  std::unique_ptr<TissueCutter> Cutter;
  std::unique_ptr<InstrumentAction> Action;
  double JawOpening = 1.0;
  int TopologyVersion = 0;
  HexahedralEmbedding VisualEmbedding;
  mutable std::vector<Vector3> Visual;
  mutable bool VisualStale = true;
  RigidPose ScopePose;
  double ServoTime = 0.0;
  ServoTicking Ticking = ServoTicking::LockStep;
  /// The tool states the last step took from the servo (slot 0: scope).
  HapticToolState ScopeState;
  HapticToolState InstrumentState;
  mutable std::shared_ptr<const SceneTopology> Topology;
  int CartilageObstacle = -1;
  SceneMetrics Metrics;
  CutStepTimes LastCutTimes;
  std::string LastError;
  /// A cut whose visual half runs beside the physics step of the same step
  /// (the contacts and the FEM read only the collision side): the same
  /// results as in a row, whatever the timing.
  struct VisualHalf;
  std::unique_ptr<VisualHalf> PendingVisual;
};

} // namespace thintissue

#endif
