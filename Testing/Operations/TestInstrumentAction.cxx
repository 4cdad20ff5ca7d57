// Instrument semantics (thesis 6.4; issue: surgical operations): the punch
// bites a piece out of the meniscus's inner rim when its jaws close, and the
// piece goes; the probe never cuts; scissors cut only while closing; the
// scalpel only while engaged and moving; the shaver bites while its motor
// runs, at its bite rate. Every operation keeps the cutter's invariants.
#include "CuttingInvariants.h"
#include "InstrumentAction.h"
#include "MeniscusModel.h"
#include "OperationTestHelpers.h"
#include "ThinSheetModel.h"
#include "ThinTissueError.h"
#include "VisualCollisionBinding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace thintissue;
using namespace thintissue::cutting_test;
using namespace thintissue::operations_test;

namespace
{

/// The punch over the middle of the inner border: its jaws around the rim
/// (fixed jaw below, opening upward), the shaft toward the meniscus's open
/// centre, the bite outline's centre on the border.
RigidPose punchOverInnerBorder(const SurgicalInstrumentModel& punch, const MeniscusModel& model)
{
  const MonitorCurve& curve = model.monitorCurves.front();
  return punchOverBorder(punch, curve, curve.monitorPoints.size() / 2);
}

} // namespace

TEST(InstrumentAction, ThePunchBitesAPieceOutOfTheInnerRimWhenItsJawsClose)
{
  const BoundMeniscus& m = boundMeniscus();
  TissueCutter cutter(m.binding, m.model.simulation, nullptr, handOverPieces());
  InstrumentAction punch(makeSurgicalInstrument(SurgicalInstrumentType::Punch));
  const RigidPose pose = punchOverInnerBorder(punch.instrument(), m.model);
  const double active = activeArea(cutter);

  // Open, then closing but not yet closed: nothing happens.
  EXPECT_EQ(punch.apply(cutter, command(0.00, pose, 1.0)).kind, OperationKind::None);
  EXPECT_EQ(punch.apply(cutter, command(0.01, pose, 0.5)).kind, OperationKind::None);
  EXPECT_EQ(activeArea(cutter), active);

  // Closed: one bite, one piece removed.
  const InstrumentActionResult bite = punch.apply(cutter, command(0.02, pose, 0.0));
  EXPECT_EQ(bite.kind, OperationKind::Bite);
  ASSERT_TRUE(bite.changed()) << bite.refused;
  EXPECT_EQ(bite.report.removedPieces, 1);
  ASSERT_EQ(bite.report.handedOver.size(), 1u);
  EXPECT_LT(activeArea(cutter), active - 1.0);
  EXPECT_TRUE(cutterIsConsistent(cutter, m.model.simulation));

  // The removed volume is what the jaws enclosed: the outline's area times
  // the rim's thickness there (up to about 3 mm), half the outline reaching
  // past the border (measured: 4.9 mm^3 for 5.5 mm^2).
  const SurgicalInstrumentParameters& p = punch.instrument().parameters;
  const double outlineArea = M_PI / 4.0 * p.biteLength * p.biteWidth; // about (rounded ends)
  EXPECT_GT(bite.removedVolume, 0.25 * outlineArea);
  EXPECT_LT(bite.removedVolume, outlineArea * 3.0);
  EXPECT_EQ(punch.operations(), 1);

  // Staying closed bites no more; opening and closing again bites again,
  // a little further along (the rim is jagged where bites overlap).
  EXPECT_EQ(punch.apply(cutter, command(0.03, pose, 0.0)).kind, OperationKind::None);
  RigidPose further = pose;
  further.translation += pose.rotation * Vector3(0.0, 1.2, 0.0);
  punch.apply(cutter, command(0.04, further, 1.0));
  const InstrumentActionResult second = punch.apply(cutter, command(0.05, further, 0.0));
  EXPECT_EQ(second.kind, OperationKind::Bite);
  EXPECT_TRUE(second.changed());
  EXPECT_TRUE(cutterIsConsistent(cutter, m.model.simulation));
}

TEST(InstrumentAction, TheProbeHookNeverCuts)
{
  const BoundMeniscus& m = boundMeniscus();
  TissueCutter cutter(m.binding, m.model.simulation);
  InstrumentAction hook(makeSurgicalInstrument(SurgicalInstrumentType::ProbeHook));
  const RigidPose pose = punchOverInnerBorder(hook.instrument(), m.model);
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_EQ(hook.apply(cutter, command(0.01 * k, pose, k % 2, true)).kind, OperationKind::None);
  }
  EXPECT_FALSE(instrumentCuts(SurgicalInstrumentType::ProbeHook));
  EXPECT_TRUE(instrumentCuts(SurgicalInstrumentType::Punch));
}

namespace
{

ThinSheetParameters smallSheet()
{
  ThinSheetParameters p;
  p.width = 24.0;
  p.depth = 24.0;
  p.visualCellsX = 24;
  p.visualCellsY = 24;
  return p;
}

/// A thin sheet 24 x 24 mm (in x, y; 2 mm thick in z; collision edges
/// about 4 mm) and a cutter on it.
struct SheetCase
{
  TissueModel sheet = makeThinSheet(smallSheet());
  VisualCollisionBinding binding = bindVisualToCollision(sheet.visual, sheet.collision);
  TissueCutter cutter{ binding, sheet.simulation };
  Vector3 centre = sheet.visual.boundingBox().center();
};

} // namespace

TEST(InstrumentAction, ScissorsCutOnlyWhileTheyClose)
{
  SheetCase s;
  InstrumentAction scissors(makeSurgicalInstrument(SurgicalInstrumentType::Scissors));
  const SurgicalInstrumentModel& model = scissors.instrument();
  // Blades opening upward (+z across the sheet), pointing along +x: the
  // sheet's edge between them, the hinge 1 mm outside it.
  const Vector3 edgeStart(s.sheet.visual.boundingBox().min().x(), s.centre.y(), s.centre.z());
  const RigidPose pose = poseAt(
    model.cuttingEdge.back(), edgeStart - Vector3(1.0, 0, 0), Vector3::UnitZ(), -Vector3::UnitX());
  const std::size_t vertices = s.cutter.collision().vertexCount();
  scissors.apply(s.cutter, command(0.0, pose, 1.0));
  // Opening further, or holding: no cut.
  EXPECT_EQ(scissors.apply(s.cutter, command(0.01, pose, 1.0)).kind, OperationKind::None);
  // Closing: a cut that grows from the hinge; then opened, pushed 4 mm
  // further in and closed again, as one cuts with scissors.
  const InstrumentActionResult half = scissors.apply(s.cutter, command(0.02, pose, 0.5));
  EXPECT_EQ(half.kind, OperationKind::Cut);
  const InstrumentActionResult closed = scissors.apply(s.cutter, command(0.03, pose, 0.0));
  EXPECT_EQ(closed.kind, OperationKind::Cut);
  EXPECT_TRUE(half.changed() || closed.changed()) << half.refused << closed.refused;
  RigidPose further = pose;
  further.translation.x() += 4.0;
  EXPECT_EQ(scissors.apply(s.cutter, command(0.04, further, 1.0)).kind, OperationKind::None);
  const InstrumentActionResult second = scissors.apply(s.cutter, command(0.05, further, 0.0));
  EXPECT_TRUE(second.changed()) << second.refused;
  // The sheet opened along the cut (runs along lattice edges here).
  EXPECT_GT(s.cutter.collision().vertexCount(), vertices);
  EXPECT_TRUE(cutterIsConsistent(s.cutter, s.sheet.simulation));
}

TEST(InstrumentAction, TheScalpelCutsWhileEngagedAndMoving)
{
  SheetCase s;
  InstrumentAction scalpel(makeSurgicalInstrument(SurgicalInstrumentType::Scalpel));
  const SurgicalInstrumentModel& model = scalpel.instrument();
  // Blade upright through the sheet (its point below), edge facing +y,
  // drawn along +y through the middle.
  const Vector3 edgeMiddle = 0.5 * (model.cuttingEdge.front() + model.cuttingEdge.back());
  auto at = [&](double y)
  { return poseAt(edgeMiddle, s.centre + Vector3(0, y, 0), Vector3::UnitY(), Vector3::UnitZ()); };
  scalpel.apply(s.cutter, command(0.0, at(-9.0), 1.0, false));
  // Moving, not engaged: no cut.
  EXPECT_EQ(scalpel.apply(s.cutter, command(0.01, at(-7.0), 1.0, false)).kind, OperationKind::None);
  scalpel.apply(s.cutter, command(0.02, at(-7.0), 1.0, true));
  // Engaged, still: no cut.
  EXPECT_EQ(scalpel.apply(s.cutter, command(0.03, at(-7.0), 1.0, true)).kind, OperationKind::None);
  const std::size_t triangles = s.cutter.collision().triangleCount();
  const InstrumentActionResult stroke = scalpel.apply(s.cutter, command(0.04, at(7.0), 1.0, true));
  EXPECT_EQ(stroke.kind, OperationKind::Cut);
  EXPECT_TRUE(stroke.changed()) << stroke.refused;
  EXPECT_GT(s.cutter.collision().triangleCount(), triangles);
  EXPECT_TRUE(cutterIsConsistent(s.cutter, s.sheet.simulation));
}

namespace
{

/// Pieces of the collision triangles still in the tissue (through edges).
int collisionPieceCount(const TissueCutter& cutter)
{
  int count = 0;
  const std::vector<int> piece = collisionPieces(cutter.collision(), count);
  std::set<int> active;
  for (std::size_t t = 0; t < piece.size(); ++t)
    if (cutter.isActive(static_cast<int>(t)))
      active.insert(piece[t]);
  return static_cast<int>(active.size());
}

} // namespace

// The simulator draws the knife a little each physics step (0.07 mm at
// 36 mm/s and 2 ms): the cut must go on from where the last step left it,
// also when a step reaches only its tip again or a vertex beside it (before
// the fix, the tip was dropped and the sheet stayed one piece).
TEST(InstrumentAction, TheScalpelDrawnAcrossInSmallStepsCutsTheSheetInTwo)
{
  ThinSheetParameters p;
  p.width = 60.0;
  p.depth = 60.0;
  const TissueModel sheet = makeThinSheet(p);
  for (const double x : { 0.0, 1.3 }) // through lattice vertices, and between
  {
    TissueCutter cutter(sheet.collision, sheet.simulation);
    InstrumentAction scalpel(makeSurgicalInstrument(SurgicalInstrumentType::Scalpel));
    const SurgicalInstrumentModel& model = scalpel.instrument();
    const Vector3 edgeMiddle = 0.5 * (model.cuttingEdge.front() + model.cuttingEdge.back());
    for (double y = -36.0; y <= 36.0; y += 0.072)
    {
      const RigidPose pose =
        poseAt(edgeMiddle, Vector3(x, y, 0.0), Vector3::UnitY(), Vector3(0.0, -1.0, 1.0));
      scalpel.apply(cutter, command(y, pose, 1.0, true));
    }
    EXPECT_EQ(collisionPieceCount(cutter), 2) << "cut at x = " << x;
    EXPECT_TRUE(cutterIsConsistent(cutter, sheet.simulation)) << "cut at x = " << x;
  }
}

TEST(InstrumentAction, TheShaverBitesWhileItsMotorRunsAtItsBiteRate)
{
  const BoundMeniscus& m = boundMeniscus();
  TissueCutter cutter(m.binding, m.model.simulation, nullptr, handOverPieces());
  InstrumentActionSettings settings;
  settings.shaverBitePeriod = 0.05;
  InstrumentAction shaver(makeSurgicalInstrument(SurgicalInstrumentType::SmallShaver), settings);
  const SurgicalInstrumentModel& model = shaver.instrument();
  // The window facing down onto the inner part of the meniscus, at its
  // mid-surface.
  const MonitorCurve& curve = m.model.monitorCurves.front();
  const std::size_t middle = curve.monitorPoints.size() / 2;
  const Vector3 rim = curve.monitorPoints[middle];
  Vector3 inward = curve.regionPoints[middle] - rim;
  inward.z() = 0.0;
  const RigidPose pose =
    poseAt(centroid(model.biteOutline), rim, -Vector3::UnitZ(), -inward.normalized());
  shaver.apply(cutter, command(0.0, pose, 1.0, false));
  EXPECT_EQ(shaver.apply(cutter, command(0.01, pose, 1.0, false)).kind, OperationKind::None);
  const InstrumentActionResult first = shaver.apply(cutter, command(0.02, pose, 1.0, true));
  EXPECT_EQ(first.kind, OperationKind::Shave);
  EXPECT_TRUE(first.changed()) << first.refused;
  EXPECT_GT(first.removedVolume, 0.0);
  // Within the bite period: nothing.
  EXPECT_EQ(shaver.apply(cutter, command(0.05, pose, 1.0, true)).kind, OperationKind::None);
  EXPECT_EQ(shaver.apply(cutter, command(0.08, pose, 1.0, true)).kind, OperationKind::Shave);
  EXPECT_TRUE(cutterIsConsistent(cutter, m.model.simulation));
}

TEST(InstrumentAction, BadSettingsAreRefusedByName)
{
  InstrumentActionSettings bad;
  bad.shaverReach = -1.0;
  try
  {
    InstrumentAction action(makeSurgicalInstrument(SurgicalInstrumentType::Punch), bad);
    FAIL() << "accepted a negative shaver reach";
  }
  catch (const InvalidInputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("punch"), std::string::npos) << e.what();
  }
  SurgicalInstrumentModel noOutline = makeSurgicalInstrument(SurgicalInstrumentType::Punch);
  noOutline.biteOutline.clear();
  EXPECT_THROW(InstrumentAction{ noOutline }, InvalidInputError);
}

// 6.4.4: after a bite with a jagged cut surface, the small shaver in
// contouring mode held on the bitten rim smooths it pass by pass (one pass
// per bite period while the motor runs) and removes nothing.
TEST(InstrumentAction, TheShaverInContouringModeSmoothsTheBittenRimAndRemovesNothing)
{
  const BoundMeniscus& m = boundMeniscus();
  TissueCutterSettings settings = handOverPieces();
  settings.visual.jaggedAmplitude = 0.3;
  settings.visual.jaggedSeed = 5u;
  TissueCutter cutter(m.binding, m.model.simulation, nullptr, settings);
  InstrumentAction punch(makeSurgicalInstrument(SurgicalInstrumentType::Punch));
  const RigidPose bite = punchOverInnerBorder(punch.instrument(), m.model);
  punch.apply(cutter, command(0.0, bite, 1.0));
  ASSERT_TRUE(punch.apply(cutter, command(0.1, bite, 0.0)).changed());
  const double jagged = cutter.cutRimRoughness().rootMeanSquare;
  EXPECT_GT(jagged, 0.03);

  InstrumentActionSettings contouring;
  contouring.shaverMode = ShaverMode::Contour;
  InstrumentAction shaver(makeSurgicalInstrument(SurgicalInstrumentType::SmallShaver), contouring);
  // The window's centre where the punch bit, 0.6 mm up (the rim's middle).
  const Vector3 bitten = bite * centroid(punch.instrument().biteOutline) + Vector3(0, 0, 0.6);
  const RigidPose pose = poseAt(
    centroid(shaver.instrument().biteOutline), bitten, -Vector3::UnitZ(), Vector3(1.0, 0.2, 0.0));
  const double area = activeArea(cutter);
  const std::size_t triangles = cutter.visual().mesh().triangleCount();
  // Motor off: nothing.
  shaver.apply(cutter, command(0.0, pose, 1.0, false));
  EXPECT_EQ(shaver.apply(cutter, command(0.1, pose, 1.0, false)).kind, OperationKind::None);
  EXPECT_EQ(cutter.cutRimRoughness().rootMeanSquare, jagged);
  int passes = 0;
  for (double t = 0.2; t < 1.2; t += 0.01)
  {
    const InstrumentActionResult pass = shaver.apply(cutter, command(t, pose, 1.0, true));
    EXPECT_FALSE(pass.changed());
    EXPECT_EQ(pass.removedVolume, 0.0);
    passes += pass.contoured();
  }
  EXPECT_GE(passes, 15); // one per 50 ms
  EXPECT_LE(passes, 21);
  EXPECT_LT(cutter.cutRimRoughness().rootMeanSquare, 0.7 * jagged);
  EXPECT_EQ(activeArea(cutter), area);
  EXPECT_EQ(cutter.visual().mesh().triangleCount(), triangles);
  EXPECT_TRUE(cutterIsConsistent(cutter, m.model.simulation));
}

TEST(InstrumentAction, ShaverModesHaveNames)
{
  EXPECT_EQ(shaverModeFromName("contour"), ShaverMode::Contour);
  EXPECT_EQ(shaverModeFromName(shaverModeName(ShaverMode::Remove)), ShaverMode::Remove);
  try
  {
    shaverModeFromName("polish");
    FAIL() << "accepted an unknown shaver mode";
  }
  catch (const InvalidInputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("polish"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("contour"), std::string::npos) << e.what();
  }
  InstrumentActionSettings bad;
  bad.contourStrength = 1.5;
  EXPECT_THROW(InstrumentAction(makeSurgicalInstrument(SurgicalInstrumentType::SmallShaver), bad),
    InvalidInputError);
}
