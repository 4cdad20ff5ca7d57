// The training scene (thesis 6.2, without SOFA's scene graph): one tissue
// (its three meshes, the FEM, the collision mesh, the wrinkles and, with a
// cutting instrument, its cutter), the static bones, the instrument (a
// rigid tool moved by its device through its portal) and the arthroscope,
// and the one place that orders a physics step:
//   device poses -> cutting / removal (InstrumentAction, 6.4) -> collision
//   -> contact forces -> FEM step -> local contact model published to the
//   servo -> wrinkles -> visual surface -> metrics.
//
// This class runs in lock-step (no threads): step() ticks the servo at 1 ms
// up to the step's end, then does the rest. With scripted devices a run is
// deterministic: tests, benchmarks, replays and image baselines use it.
#ifndef TrainingScene_h
#define TrainingScene_h

#include "CollisionScene.h"
#include "HapticServo.h"
#include "InstrumentAction.h"
#include "KneeModels.h"
#include "Scenario.h"
#include "ScenarioTissue.h"
#include "ThinTissueSceneModule.h"
#include "WrinkleGenerator.h"

#include <memory>
#include <string>
#include <vector>

namespace thintissue
{

/// What a run measured (issue: metrics and assessment).
struct SceneMetrics
{
  double time = 0.0;                 ///< s
  double instrumentPathLength = 0.0; ///< mm, of the instrument tip
  double cameraPathLength = 0.0;     ///< mm, of the arthroscope tip
  int cartilageContactSteps = 0;     ///< steps the instrument touched cartilage
  double peakForce = 0.0;            ///< N, on the instrument
  int wrinklingSteps = 0;
  int steps = 0;
  /// Bites, strokes and shaver bites that changed the tissue, and the rest
  /// volume they removed (mm^3).
  int operations = 0;
  double removedVolume = 0.0;
  /// Of it, the pieces whose centre lies in the task's target region (and
  /// the rest: tissue that should have stayed).
  double removedInTarget = 0.0;
  double removedOutsideTarget = 0.0;
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
  /// The collision scene of the last step (contacts, statistics).
  const CollisionScene& contacts() const { return Contacts; }

private:
  void buildTissue();
  void buildCutting();
  void buildWrinkles(const HexahedralMesh& hexahedra, const TriangleMesh& surface);
  void buildContacts();
  void rebuildCollisionMesh();
  void operate(const HapticToolState& instrument);
  void updateMetrics(const RigidPose& previousTool, const RigidPose& previousScope);

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
  int CartilageObstacle = -1;
  SceneMetrics Metrics;
  std::string LastError;
};

} // namespace thintissue

#endif
