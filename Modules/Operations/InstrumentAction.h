// What each arthroscopic instrument does to a tissue being cut (thesis 6.4),
// behind one entry point the simulator calls once per physics step with the
// instrument's pose, its jaw opening and whether it is working:
//
//  - probe hook: palpates only (its contacts are the collision scene's);
//  - basket punch (6.4.2): when its jaws close, the bite outline of the
//    fixed jaw, extruded across the jaws' gap, cuts a loop through the
//    tissue, and the bitten piece, attached to nothing, is removed at once
//    (one bite = one cut + removal, by the cutter's free-piece handling);
//  - scissors: where the blades close on each other the tissue is cut
//    (scissorsBlade, from the pose before to the pose now);
//  - scalpel: while engaged, its straight cutting edge cuts along the
//    surface it sweeps from one step to the next;
//  - shavers (6.4.3, piecewise removal): while the motor runs and tissue
//    lies in front of the window, the window outline extruded across the
//    tissue cuts the tissue in reach loose, and it is removed -- one bite
//    per `shaverBitePeriod`, as the inner cutter does;
//  - shavers in contouring mode (6.4.4): nothing is cut; each bite period
//    the running shaver smooths the jagged cut surface where its window
//    touches the cut rim (TissueCutter::contour), so the trainee evens the
//    rim out (fig. 6-15); no material goes.
//
// The blades are built from the instrument model's working features
// (SurgicalInstruments.h: biteOutline, cuttingEdge), moved by the pose; the
// cut itself is TissueCutter::cut (5.3), so every operation keeps the
// cutter's invariants (closed visual mesh with cut surfaces, pieces that
// share no node).
#ifndef InstrumentAction_h
#define InstrumentAction_h

#include "RigidTool.h"
#include "SurgicalInstruments.h"
#include "ThinTissueOperationsModule.h"
#include "TissueCutter.h"

#include <string>
#include <utility>
#include <vector>

namespace thintissue
{

/// The instrument's state at one physics step.
struct InstrumentCommand
{
  double time = 0.0; ///< seconds
  /// Tool frame (SurgicalInstruments.h) to world.
  RigidPose pose;
  /// Punch and scissors: 1 = open as built (the model's jawOpeningDegrees),
  /// 0 = closed.
  double jawOpening = 1.0;
  /// Scalpel: the edge is engaged; shavers: the motor runs.
  bool working = false;
};

enum class OperationKind
{
  None,    ///< nothing this step
  Cut,     ///< scissors or scalpel stroke
  Bite,    ///< punch bite
  Shave,   ///< shaver bite
  Contour, ///< contouring pass of a shaver in contouring mode
};

/// What a running shaver does (6.4.3 / 6.4.4).
enum class ShaverMode
{
  Remove, ///< bites the tissue in front of its window away
  Contour ///< smooths the cut rim its window touches, removes nothing
};

/// "remove", "contour".
THINTISSUEOPERATIONS_EXPORT const char* shaverModeName(ShaverMode mode);
/// Throws InvalidInputError naming `name` and the valid names.
THINTISSUEOPERATIONS_EXPORT ShaverMode shaverModeFromName(const std::string& name);

/// What one step of an instrument did.
struct InstrumentActionResult
{
  OperationKind kind = OperationKind::None;
  /// The cut, when one was made (kind Cut, Bite or Shave).
  TissueCutReport report;
  /// The contouring pass (kind Contour).
  CutRimContourReport contour;
  /// Rest volume (mm^3) of the pieces this step removed, from their closed
  /// visual surfaces (0 when the cutter has no visual mesh or keeps its
  /// free pieces).
  double removedVolume = 0.0;
  /// Per piece of report.handedOver, its rest volume (mm^3).
  std::vector<double> pieceVolumes;
  /// Set when the cutter refused the blade (a tool that did not move, say):
  /// the tissue is untouched.
  std::string refused;
  /// Whether the meshes were cut (their topology changed).
  bool changed() const { return kind != OperationKind::None && report.changed(); }
  /// Whether a contouring pass moved cut-surface vertices (rest positions
  /// and embedding; the topology is as it was).
  bool contoured() const
  {
    return kind == OperationKind::Contour && !contour.movedVertices.empty();
  }
};

struct InstrumentActionSettings
{
  /// Jaws at or below this opening count as closed (punch, scissors).
  double closedJawOpening = 0.05;
  /// How far the punch's cut reaches below the fixed jaw's face (mm): the
  /// tissue resting on the jaw is cut through.
  double biteDepthBelowJaw = 1.0;
  /// How far the scissors' cut reaches either side of the blades' middle
  /// line, across the tissue between them (mm).
  double scissorsHalfHeight = 3.0;
  /// Shavers: how far in front of and behind the window the inner cutter
  /// reaches (mm), and seconds between two bites.
  double shaverReach = 1.0;
  double shaverBitePeriod = 0.05;
  /// Shavers: remove tissue or contour the cut rim; a contouring pass each
  /// bite period reaches `shaverReach` beyond the window's outline around
  /// its centre and takes this fraction of the jaggedness away where the
  /// window's centre is (less toward the reach), in [0, 1].
  ShaverMode shaverMode = ShaverMode::Remove;
  double contourStrength = 0.3;
};

/// Whether an instrument of this type can change a tissue (all but the
/// probe hook).
THINTISSUEOPERATIONS_EXPORT bool instrumentCuts(SurgicalInstrumentType type);

class THINTISSUEOPERATIONS_EXPORT InstrumentAction
{
public:
  /// `model`: the instrument as built, in its tool frame. Throws
  /// InvalidInputError naming the instrument when it lacks the working
  /// feature its type needs, or on bad settings.
  explicit InstrumentAction(const SurgicalInstrumentModel& model,
    const InstrumentActionSettings& settings = {});

  /// One physics step: compares `command` with the previous one and cuts
  /// `cutter`'s tissue as the instrument does. The first call only records
  /// the state (nothing sweeps from nowhere).
  InstrumentActionResult apply(TissueCutter& cutter, const InstrumentCommand& command);
  /// apply() for a caller that overlaps a cut's visual half with other
  /// work: a blade cut or a shaving pass stops after its collision half
  /// (TissueCutter::cutCollision, removeTrianglesCollision), and finishCut
  /// (before anything else reads the visual mesh or the result's volumes)
  /// completes it. Contouring is done whole.
  InstrumentActionResult applyVisualLater(TissueCutter& cutter, const InstrumentCommand& command);
  /// The visual half of a cut applyVisualLater left, and its pieces'
  /// volumes and operation count; nothing when none is pending.
  void finishCut(TissueCutter& cutter, InstrumentActionResult& result);

  const SurgicalInstrumentModel& instrument() const { return Model; }
  /// Bites and strokes that changed the tissue so far.
  int operations() const { return Operations; }

  /// The punch's bite at `pose`: its outline on the fixed jaw's face swept
  /// from below the jaw to the open moving jaw (for tests and drawing).
  Blade punchBite(const RigidPose& pose) const;
  /// The shaver's bite at `pose`: its window outline swept through the
  /// window's plane, `shaverReach` either side (the prism whose triangles
  /// the running shaver removes, as a blade for drawing).
  Blade shaverBite(const RigidPose& pose) const;
  /// The collision triangles of `cutter`'s tissue a removing shaver at
  /// `pose` takes (6.4.3): those with a corner or their centre (current
  /// positions) in the prism its window outline sweeps, `shaverReach`
  /// either side of the window's plane.
  std::vector<int> shavedTriangles(const TissueCutter& cutter, const RigidPose& pose) const;
  /// The sphere a contouring shaver at `pose` smooths the cut rim in: its
  /// window's centre, and the window's half diagonal plus `shaverReach`.
  std::pair<Vector3, double> contourReach(const RigidPose& pose) const;
  /// The blade of the instrument going from `before` to `now`, whatever its
  /// jaws or buttons say (for VTK and tests): punch and shavers their bite
  /// at `now`, scissors what their blades closed over, the scalpel the
  /// surface its edge swept; empty for the probe or no motion.
  Blade bladeBetween(const InstrumentCommand& before, const InstrumentCommand& now) const;

private:
  /// Whether the instrument acts this step, and how (the shaver's bite
  /// period counted from here).
  OperationKind actsNow(const InstrumentCommand& command);
  Blade scissorsStroke(const InstrumentCommand& before, const InstrumentCommand& now) const;
  Blade scalpelStroke(const InstrumentCommand& before, const InstrumentCommand& now) const;
  bool jawsJustClosed(const InstrumentCommand& command) const;
  /// The removed pieces' volumes into `result`, and the operation counted.
  InstrumentActionResult& takeRemoved(InstrumentActionResult& result);
  InstrumentActionResult applyWith(TissueCutter& cutter,
    const InstrumentCommand& command,
    bool visualLater);

  SurgicalInstrumentModel Model;
  InstrumentActionSettings Settings;
  InstrumentCommand Previous;
  bool HasPrevious = false;
  double LastShave = -1.0e300;
  int Operations = 0;
};

/// Rest volume enclosed by a removed piece's closed visual surface (mm^3).
THINTISSUEOPERATIONS_EXPORT double restVolume(const TissuePiece& piece);

} // namespace thintissue

#endif
