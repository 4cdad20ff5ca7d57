// Scenario files (JSON, versioned): what a training run contains -- the
// tissue (a procedural model by name), its material and wrinkles, the
// bones, the instrument and its portal, the arthroscope and its portal,
// the physics step, the task. Validated when read; every message names the
// file, the key and the problem.
#ifndef Scenario_h
#define Scenario_h

#include "HexahedronElement.h"
#include "InstrumentAction.h"
#include "MeniscusModel.h"
#include "ScriptedHapticDevice.h"
#include "SurgicalInstruments.h"
#include "ThinTissueSceneModule.h"
#include "WrinkleGenerator.h"

#include <string>

namespace thintissue
{

constexpr int ScenarioVersion = 1;

struct PortalDescription
{
  Vector3 portal = Vector3::Zero();
  Vector3 inward = -Vector3::UnitZ();
};

struct ScenarioDescription
{
  std::string source; ///< the file it came from (for messages)
  std::string name;
  std::string description;
  /// The tissue: "meniscus" (with `tear`, `examinationResolution`),
  /// "anterior_cruciate_ligament", "posterior_cruciate_ligament",
  /// "tibial_cartilage" (the knee's own, made deformable), "sheet" (the
  /// thesis's thin sheet, `sheetSize`), "file" (a mesh file prepared when the
  /// scenario loads) or "bundle" (a tissue prepared by ThinTissuePrepare).
  std::string tissueModel = "meniscus";
  /// "file" and "bundle": the path (relative paths are relative to the
  /// scenario file).
  std::string tissueFile;
  /// "file": the mesh's length unit ("mm", "cm", "m", "um"); empty:
  /// detected from its size (LengthUnits.h). The scene works in mm.
  std::string tissueUnits;
  /// "file": the thickness (mm) given to an open sheet (a tissue segmented
  /// as one surface, SheetThickening.h); 0: the mesh must be closed.
  double tissueThickness = 0.0;
  /// Nodes held still: "model" (the procedural model's own attachments;
  /// none for files and bundles), "none", "ends" (both ends of the longest
  /// side, 5 % of it each) or "bottom" (the lowest 10 % of the height).
  std::string fixedNodes = "model";
  /// "sheet": width, depth and thickness (mm).
  Vector3 sheetSize = Vector3(100.0, 100.0, 2.0);
  /// Whether the knee (bones, cartilage, ligaments) is there: off for a
  /// tissue on the bench (sheet, steak).
  bool knee = true;
  /// Portals given from the tissue's centre (its bounding box's) rather than
  /// the world origin: a scenario for any tissue brought in ("your own
  /// tissue"), its recording replaying around wherever the tissue lies.
  bool portalsFromTissueCentre = false;
  MeniscusTearType tear = MeniscusTearType::None;
  bool examinationResolution = true;
  bool wrinkles = true;
  LinearMaterial material;
  /// Wrinkle parameters (4.4; key tissue.wrinkle: frequency, scale,
  /// magnitudeBound, windowSize, refreshMonitorsPerStep). A scene
  /// time-slices the refresh of the influence after a cut, 16 monitor
  /// points a step (0: all in the step with the cut), so that a bite's
  /// step does not pay it.
  WrinkleParameters wrinkle = []
  {
    WrinkleParameters w;
    w.refreshMonitorsPerUpdate = 16;
    return w;
  }();
  /// Cut surface (5.3.4; key cutting): rows of vertices between the two
  /// sides, and the free pieces below this fraction of the tissue's
  /// collision area removed whole.
  int cutSurfaceRows = 1;
  double fragmentAreaFraction = 0.0;
  /// Jagged cut surface (6.4.4; keys cutting.jagged.amplitude, .wavelength,
  /// .seed): the rim a bite leaves, for contouring to even out.
  double jaggedAmplitude = 0.0;
  double jaggedWavelength = 0.5;
  unsigned jaggedSeed = 0;
  /// Shavers (keys instrument.shaverMode, instrument.contourStrength):
  /// remove tissue (6.4.3) or contour the cut rim (6.4.4).
  ShaverMode shaverMode = ShaverMode::Remove;
  double contourStrength = 0.3;
  /// Punch bites made as the scenario loads (key preparation.punchBites;
  /// meniscus only): `count` bites along the inner border from fraction
  /// `from` to `to` of it, the bite outline's centre `inward` mm into the
  /// tissue -- the jagged rim a contouring task starts from. Not counted in
  /// the metrics.
  int preBites = 0;
  double preBitesFrom = 0.4;
  double preBitesTo = 0.6;
  double preBitesInward = 1.0;
  /// Millimetres between the tibial and femoral cartilage.
  double jointGap = 10.0;
  SurgicalInstrumentType instrument = SurgicalInstrumentType::ProbeHook;
  PortalDescription instrumentPortal;
  PortalDescription scopePortal;
  double viewingAngle = 30.0;
  /// Seconds per physics step.
  double timeStep = 0.002;
  /// "examination", ...; the run's length in seconds.
  std::string task = "examination";
  double duration = 5.0;
  /// The region the task should remove (a ball; radius 0: none): the
  /// metrics split the removed volume into inside and outside it.
  Vector3 targetCentre = Vector3::Zero();
  double targetRadius = 0.0;
};

/// Throws InvalidInputError "scenario '<source>': key '<key>': <problem>"
/// (or FileError for an unreadable file).
THINTISSUESCENE_EXPORT ScenarioDescription readScenario(const std::string& path);
THINTISSUESCENE_EXPORT ScenarioDescription parseScenario(const std::string& json,
  const std::string& source);

/// The settings a user may change while training (the window's settings
/// panel): `json` holds any of the keys tissue.material.*, tissue.wrinkle.*
/// and cutting.*, as in a scenario file; the rest comes from `base`.
/// Validated as a scenario file is; messages name `source` and the key.
THINTISSUESCENE_EXPORT ScenarioDescription applyScenarioSettings(const ScenarioDescription& base,
  const std::string& json,
  const std::string& source);

/// A recorded run (issue: record and replay): the scenario file (relative
/// paths are relative to the recording), the seed, and the two styluses'
/// trajectories. Replayed in lock-step it gives the same meshes bit for bit.
struct SceneRecording
{
  std::string scenario;
  unsigned seed = 0;
  HapticTrajectory scope;
  HapticTrajectory instrument;
};

/// Throws FileError / InvalidInputError naming the file and the key.
THINTISSUESCENE_EXPORT SceneRecording readSceneRecording(const std::string& path);
THINTISSUESCENE_EXPORT void writeSceneRecording(const std::string& path,
  const SceneRecording& recording);

} // namespace thintissue

#endif
