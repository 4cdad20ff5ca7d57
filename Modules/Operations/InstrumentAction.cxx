#include "InstrumentAction.h"

#include "MeshQueries.h"
#include "ThinTissueError.h"

#include <algorithm>
#include <cmath>

namespace thintissue
{

namespace
{

constexpr double DegreesToRadians = M_PI / 180.0;

void requireFeature(const SurgicalInstrumentModel& model, bool present, const char* feature)
{
  if (!present)
  {
    throw InvalidInputError(
      "instrument '" + model.name + "': its model has no " + feature + ", which it needs to cut");
  }
}

void checkSettings(const SurgicalInstrumentModel& model, const InstrumentActionSettings& s)
{
  const bool good =
    s.closedJawOpening >= 0.0 && s.closedJawOpening < 1.0 && s.biteDepthBelowJaw >= 0.0 &&
    s.scissorsHalfHeight > 0.0 && s.shaverReach > 0.0 && s.shaverBitePeriod >= 0.0 &&
    s.contourStrength >= 0.0 && s.contourStrength <= 1.0 &&
    std::isfinite(s.biteDepthBelowJaw + s.scissorsHalfHeight + s.shaverReach + s.shaverBitePeriod);
  if (!good)
  {
    throw InvalidInputError("instrument '" + model.name +
                            "': action settings out of range (closed jaw opening in [0, 1), "
                            "depths and reach positive and finite, contour strength in [0, 1])");
  }
}

/// The outline moved by `pose` and offset by `offset` (tool frame) first.
std::vector<Vector3> placedOutline(const std::vector<Vector3>& outline,
  const RigidPose& pose,
  const Vector3& offset)
{
  std::vector<Vector3> placed;
  placed.reserve(outline.size());
  for (const Vector3& p : outline)
  {
    placed.push_back(pose * (p + offset));
  }
  return placed;
}

/// Twice the area of the quad swept by the segment (a, b) from `before` to
/// `now`, roughly: zero when the edge did not move across itself.
double sweptArea(const Vector3& a0, const Vector3& b0, const Vector3& a1, const Vector3& b1)
{
  return (b0 - a0).cross(a1 - a0).norm() + (b1 - a1).cross(b0 - a1).norm();
}

double signedVolume(const std::vector<Vector3>& positions, const std::vector<Triangle>& triangles)
{
  double volume = 0.0;
  for (const Triangle& t : triangles)
  {
    volume += positions[t[0]].dot(positions[t[1]].cross(positions[t[2]]));
  }
  return volume / 6.0;
}

} // namespace

const char* shaverModeName(ShaverMode mode)
{
  return mode == ShaverMode::Contour ? "contour" : "remove";
}

ShaverMode shaverModeFromName(const std::string& name)
{
  for (const ShaverMode mode : { ShaverMode::Remove, ShaverMode::Contour })
    if (name == shaverModeName(mode))
      return mode;
  throw InvalidInputError("shaver mode '" + name + "': unknown (valid: remove, contour)");
}

bool instrumentCuts(SurgicalInstrumentType type)
{
  return type != SurgicalInstrumentType::ProbeHook;
}

InstrumentAction::InstrumentAction(const SurgicalInstrumentModel& model,
  const InstrumentActionSettings& settings)
  : Model(model)
  , Settings(settings)
{
  checkSettings(model, settings);
  switch (model.type)
  {
    case SurgicalInstrumentType::Punch:
    case SurgicalInstrumentType::SmallShaver:
    case SurgicalInstrumentType::LargeShaver:
      requireFeature(model, model.biteOutline.size() >= 3, "bite outline");
      break;
    case SurgicalInstrumentType::Scissors:
    case SurgicalInstrumentType::Scalpel:
      requireFeature(model, model.cuttingEdge.size() >= 2, "cutting edge");
      break;
    case SurgicalInstrumentType::ProbeHook:
      break;
  }
}

Blade InstrumentAction::punchBite(const RigidPose& pose) const
{
  // The tissue between the jaws: from just below the fixed jaw's face (the
  // outline's plane, x = 0) up to the open moving jaw.
  const SurgicalInstrumentParameters& p = Model.parameters;
  const double open = p.biteLength * std::sin(p.jawOpeningDegrees * DegreesToRadians);
  const Vector3 up = Vector3::UnitX();
  return Blade::sweptOutline(
    placedOutline(Model.biteOutline, pose, -Settings.biteDepthBelowJaw * up),
    placedOutline(Model.biteOutline, pose, (open + p.jawThickness) * up));
}

Blade InstrumentAction::shaverBite(const RigidPose& pose) const
{
  const Vector3 reach = Settings.shaverReach * Vector3::UnitX();
  return Blade::sweptOutline(
    placedOutline(Model.biteOutline, pose, -reach), placedOutline(Model.biteOutline, pose, reach));
}

std::vector<int> InstrumentAction::shavedTriangles(const TissueCutter& cutter,
  const RigidPose& pose) const
{
  // The window outline across the tool's x axis (its y, z), and its extent
  // along it.
  std::vector<Vector2> window;
  double low = 1e300, high = -1e300;
  for (const Vector3& p : Model.biteOutline)
  {
    window.emplace_back(p.y(), p.z());
    low = std::min(low, p.x() - Settings.shaverReach);
    high = std::max(high, p.x() + Settings.shaverReach);
  }
  auto inside = [&](const Vector3& world)
  {
    const Vector3 q = pose.rotation.transpose() * (world - pose.translation);
    return q.x() >= low && q.x() <= high && insidePolygon(window, Vector2(q.y(), q.z()));
  };
  const std::vector<Vector3> x = cutter.currentCollisionPositions();
  const auto& triangles = cutter.collision().triangles();
  std::vector<int> shaved;
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    if (!cutter.isActive(static_cast<int>(t)))
      continue;
    const Triangle& c = triangles[t];
    if (inside(x[c[0]]) || inside(x[c[1]]) || inside(x[c[2]]) ||
        inside((x[c[0]] + x[c[1]] + x[c[2]]) / 3.0))
      shaved.push_back(static_cast<int>(t));
  }
  return shaved;
}

std::pair<Vector3, double> InstrumentAction::contourReach(const RigidPose& pose) const
{
  Vector3 centre = Vector3::Zero();
  for (const Vector3& p : Model.biteOutline)
    centre += p;
  centre /= static_cast<double>(Model.biteOutline.size());
  double halfDiagonal = 0.0;
  for (const Vector3& p : Model.biteOutline)
    halfDiagonal = std::max(halfDiagonal, (p - centre).norm());
  return { pose * centre, halfDiagonal + Settings.shaverReach };
}

Blade InstrumentAction::scissorsStroke(const InstrumentCommand& before,
  const InstrumentCommand& now) const
{
  // The fixed blade's edge runs from its point to the hinge. The blades
  // turn about the hinge's pin (the tool's side axis): passing the pin axis
  // as ScissorsPose::opening extrudes the closed middle line across the
  // blades' own plane, through the tissue held between them.
  const double maximum = Model.parameters.jawOpeningDegrees * DegreesToRadians;
  auto poseAt = [&](const InstrumentCommand& c)
  {
    ScissorsPose s;
    s.pivot = c.pose * Model.cuttingEdge.back();
    const Vector3 tip = c.pose * Model.cuttingEdge.front();
    s.direction = (tip - s.pivot).normalized();
    s.length = (tip - s.pivot).norm();
    s.opening = c.pose.rotation * Vector3::UnitY();
    s.maximumOpeningAngle = maximum;
    s.openingAngle = std::clamp(c.jawOpening, 0.0, 1.0) * maximum;
    s.halfHeight = Settings.scissorsHalfHeight;
    return s;
  };
  return scissorsBlade(poseAt(before), poseAt(now));
}

Blade InstrumentAction::scalpelStroke(const InstrumentCommand& before,
  const InstrumentCommand& now) const
{
  const Vector3& point = Model.cuttingEdge.front();
  const Vector3& heel = Model.cuttingEdge.back();
  const Vector3 a0 = before.pose * point, b0 = before.pose * heel;
  const Vector3 a1 = now.pose * point, b1 = now.pose * heel;
  // An edge that did not sweep any area this step cuts nothing.
  if (sweptArea(a0, b0, a1, b1) <= 1e-9 * (b0 - a0).squaredNorm())
  {
    return {};
  }
  return Blade::sweptSegment(a0, b0, a1, b1);
}

Blade InstrumentAction::bladeBetween(const InstrumentCommand& before,
  const InstrumentCommand& now) const
{
  switch (Model.type)
  {
    case SurgicalInstrumentType::Punch:
      return punchBite(now.pose);
    case SurgicalInstrumentType::SmallShaver:
    case SurgicalInstrumentType::LargeShaver:
      return shaverBite(now.pose);
    case SurgicalInstrumentType::Scissors:
      return scissorsStroke(before, now);
    case SurgicalInstrumentType::Scalpel:
      return scalpelStroke(before, now);
    case SurgicalInstrumentType::ProbeHook:
      break;
  }
  return {};
}

bool InstrumentAction::jawsJustClosed(const InstrumentCommand& command) const
{
  return Previous.jawOpening > Settings.closedJawOpening &&
         command.jawOpening <= Settings.closedJawOpening;
}

OperationKind InstrumentAction::actsNow(const InstrumentCommand& command)
{
  switch (Model.type)
  {
    case SurgicalInstrumentType::Punch:
      return jawsJustClosed(command) ? OperationKind::Bite : OperationKind::None;
    case SurgicalInstrumentType::Scissors:
      return command.jawOpening < Previous.jawOpening ? OperationKind::Cut : OperationKind::None;
    case SurgicalInstrumentType::Scalpel:
      return command.working && Previous.working ? OperationKind::Cut : OperationKind::None;
    case SurgicalInstrumentType::SmallShaver:
    case SurgicalInstrumentType::LargeShaver:
      if (!command.working || command.time - LastShave < Settings.shaverBitePeriod)
        return OperationKind::None;
      LastShave = command.time;
      return Settings.shaverMode == ShaverMode::Contour ? OperationKind::Contour
                                                        : OperationKind::Shave;
    case SurgicalInstrumentType::ProbeHook:
      break;
  }
  return OperationKind::None;
}

InstrumentActionResult InstrumentAction::apply(TissueCutter& cutter,
  const InstrumentCommand& command)
{
  return applyWith(cutter, command, false);
}

InstrumentActionResult InstrumentAction::applyVisualLater(TissueCutter& cutter,
  const InstrumentCommand& command)
{
  return applyWith(cutter, command, true);
}

void InstrumentAction::finishCut(TissueCutter& cutter, InstrumentActionResult& result)
{
  if (!cutter.visualCutPending())
    return;
  cutter.finishVisualCut(result.report);
  takeRemoved(result);
}

InstrumentActionResult InstrumentAction::applyWith(TissueCutter& cutter,
  const InstrumentCommand& command,
  bool visualLater)
{
  InstrumentActionResult result;
  if (!HasPrevious)
  {
    Previous = command;
    HasPrevious = true;
    return result;
  }
  result.kind = actsNow(command);
  if (result.kind == OperationKind::Contour)
  {
    Previous = command;
    const auto [centre, radius] = contourReach(command.pose);
    result.contour = cutter.contour(centre, radius, Settings.contourStrength);
    Operations += result.contoured() ? 1 : 0;
    return result;
  }
  if (result.kind == OperationKind::Shave)
  {
    Previous = command;
    const std::vector<int> shaved = shavedTriangles(cutter, command.pose);
    result.report =
      visualLater ? cutter.removeTrianglesCollision(shaved) : cutter.removeTriangles(shaved);
    return cutter.visualCutPending() ? result : takeRemoved(result);
  }
  const Blade blade =
    result.kind == OperationKind::None ? Blade{} : bladeBetween(Previous, command);
  Previous = command;
  if (blade.empty())
  {
    result.kind = OperationKind::None;
    return result;
  }
  try
  {
    result.report = visualLater ? cutter.cutCollision(blade) : cutter.cut(blade);
  }
  catch (const InvalidInputError& error)
  {
    // A blade the cutter refuses leaves the tissue as it was.
    result.refused = error.what();
    result.kind = OperationKind::None;
    return result;
  }
  return cutter.visualCutPending() ? result : takeRemoved(result);
}

InstrumentActionResult& InstrumentAction::takeRemoved(InstrumentActionResult& result)
{
  for (const TissuePiece& piece : result.report.handedOver)
  {
    result.pieceVolumes.push_back(restVolume(piece));
    result.removedVolume += result.pieceVolumes.back();
  }
  Operations += result.report.changed() || result.report.removedPieces > 0 ? 1 : 0;
  return result;
}

double restVolume(const TissuePiece& piece)
{
  return std::abs(signedVolume(piece.visualRest, piece.visual.triangles));
}

} // namespace thintissue
