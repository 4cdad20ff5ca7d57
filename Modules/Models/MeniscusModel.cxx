#include "MeniscusModel.h"

#include "ModelParameterChecks.h"
#include "ThinTissueError.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace thintissue
{

namespace
{

constexpr double DegreesToRadians = M_PI / 180.0;
/// Mesh lines crowd toward the thin inner edge, where wrinkles form (ch. 4):
/// the fraction of the width from the inner edge is u^InnerEdgeGrading.
constexpr double InnerEdgeGrading = 1.3;
/// The upper surface rises from the inner edge to the rim as
/// (fraction of width)^WedgeExponent: concave, to seat the femoral condyle.
constexpr double WedgeExponent = 1.5;

const detail::ParameterChecks Checks("meniscus");

void validate(const MeniscusParameters& p)
{
  Checks.requirePositive(p.outerSemiAxisX, "outer semi-axis x");
  Checks.requirePositive(p.outerSemiAxisY, "outer semi-axis y");
  Checks.requirePositive(p.innerSemiAxisX, "inner semi-axis x");
  Checks.requirePositive(p.innerSemiAxisY, "inner semi-axis y");
  Checks.requirePositive(p.rimHeight, "rim height");
  Checks.requirePositive(p.hornHeight, "horn height");
  Checks.requirePositive(p.innerEdgeHeight, "inner edge height");
  Checks.requirePositive(p.textureScale, "texture scale");
  Checks.requirePositive(p.monitorDataPointsPerCentimetre, "monitor data points per centimetre");
  Checks.requirePositive(p.regionDepth, "region depth");
  Checks.requirePositive(p.monitorInset, "monitor inset");
  if (!p.centre.allFinite() || !std::isfinite(p.innerCentreOffsetX) ||
      !std::isfinite(p.innerCentreOffsetY))
  {
    Checks.fail("centre and inner centre offset must be finite");
  }
  if (p.innerEdgeHeight >= p.rimHeight || p.innerEdgeHeight >= p.hornHeight)
  {
    Checks.fail("the inner edge must be thinner than the rim and the horns (wedge cross-section)");
  }
  const double span = p.anteriorHornAngle - p.posteriorHornAngle;
  if (!(span > 0.0 && span < 180.0))
  {
    Checks.fail(
      "the horn angles must leave an opening between 0 and 180 degrees (anterior > posterior)");
  }
  // The inner edge must lie inside the rim with a margin everywhere.
  for (int k = 0; k <= 360; ++k)
  {
    const double theta = k * DegreesToRadians;
    const Vector2 outer(p.outerSemiAxisX * std::cos(theta), p.outerSemiAxisY * std::sin(theta));
    const Vector2 inner(p.innerCentreOffsetX + p.innerSemiAxisX * std::cos(theta),
      p.innerCentreOffsetY + p.innerSemiAxisY * std::sin(theta));
    const double outerRadius = outer.norm();
    if (inner.dot(outer / outerRadius) >= outerRadius - 1.0)
    {
      Checks.fail(
        "the inner edge ellipse must lie inside the outer rim ellipse, at least 1 mm from it");
    }
  }
  Checks.requireAtLeast(p.visualAlong, 8, "visual cells along the C");
  Checks.requireAtLeast(p.visualAcross, 2, "visual cells across");
  Checks.requireAtLeast(p.visualThrough, 1, "visual cells through the thickness");
  Checks.requireAtLeast(p.collisionAlong, 4, "collision cells along the C");
  Checks.requireAtLeast(p.collisionAcross, 1, "collision cells across");
  Checks.requireAtLeast(p.hexahedraAlong, 2, "hexahedra along the C");
  Checks.requireAtLeast(p.hexahedraAcross, 1, "hexahedra across");
  Checks.requireAtLeast(p.hexahedraThrough, 1, "hexahedra through the thickness");
  if (!(p.hornAttachment >= 0.0 && p.hornAttachment < 0.5))
  {
    Checks.fail("horn attachment must be in [0, 0.5)");
  }
  const MeniscusTear& tear = p.tear;
  if (tear.type == MeniscusTearType::None)
  {
    return;
  }
  auto inside = [](double x) { return x > 0.0 && x < 1.0; };
  if (!inside(tear.alongBegin) || !inside(tear.across) ||
      (tear.type != MeniscusTearType::Radial &&
        (!inside(tear.alongEnd) || !(tear.alongEnd > tear.alongBegin))))
  {
    std::ostringstream message;
    message << meniscusTearTypeName(tear.type) << " tear outside the meniscus: along ["
            << tear.alongBegin << ", " << tear.alongEnd << "], across " << tear.across
            << " (need 0 < begin < end < 1 and 0 < across < 1)";
    Checks.fail(message.str());
  }
  if (!(tear.opening >= 0.0))
  {
    Checks.fail("tear opening must not be negative");
  }
}

} // namespace

const char* meniscusTearTypeName(MeniscusTearType type)
{
  switch (type)
  {
    case MeniscusTearType::None:
      return "none";
    case MeniscusTearType::Longitudinal:
      return "longitudinal";
    case MeniscusTearType::Radial:
      return "radial";
    case MeniscusTearType::Flap:
      return "flap";
    case MeniscusTearType::HorizontalCleavage:
      return "horizontal-cleavage";
  }
  return "unknown";
}

MeniscusTearType meniscusTearTypeFromName(const std::string& name)
{
  for (auto type : { MeniscusTearType::None,
         MeniscusTearType::Longitudinal,
         MeniscusTearType::Radial,
         MeniscusTearType::Flap,
         MeniscusTearType::HorizontalCleavage })
  {
    if (name == meniscusTearTypeName(type))
    {
      return type;
    }
  }
  throw InvalidInputError("meniscus: unknown tear type '" + name +
                          "' (valid: none, longitudinal, radial, flap, horizontal-cleavage)");
}

MeniscusTear defaultMeniscusTear(MeniscusTearType type)
{
  MeniscusTear tear;
  tear.type = type;
  switch (type)
  {
    case MeniscusTearType::Longitudinal: // a bucket handle in the body
      tear.alongBegin = 0.25;
      tear.alongEnd = 0.75;
      tear.across = 0.45;
      break;
    case MeniscusTearType::Radial: // posterior body
      tear.alongBegin = 0.35;
      tear.across = 0.6;
      break;
    case MeniscusTearType::Flap: // a tongue in the posterior body
      tear.alongBegin = 0.3;
      tear.alongEnd = 0.45;
      tear.across = 0.5;
      break;
    case MeniscusTearType::HorizontalCleavage:
      tear.alongBegin = 0.2;
      tear.alongEnd = 0.55;
      tear.across = 0.6;
      break;
    case MeniscusTearType::None:
      break;
  }
  return tear;
}

MeniscusParameters examinationMeniscusParameters(MeniscusParameters parameters)
{
  // 4 (151 * 8 + 151 * 2 + 8 * 2) = 6,104 triangles beside the thesis's
  // 6,096 faces (6.4.1).
  parameters.visualAlong = 151;
  parameters.visualAcross = 8;
  parameters.visualThrough = 2;
  return parameters;
}

ParametricSolid makeMeniscusSolid(const MeniscusParameters& p)
{
  validate(p);
  const MeniscusParameters q = p;
  // s = 0 at the posterior horn, running clockwise seen from above (through
  // the medial side) to the anterior horn: with u pointing outward and w up
  // this is right-handed.
  const double sweep = (360.0 - (q.anteriorHornAngle - q.posteriorHornAngle)) * DegreesToRadians;
  auto map = [q, sweep](const ParameterPoint& x)
  {
    const double theta = q.posteriorHornAngle * DegreesToRadians - x[0] * sweep;
    const double c = std::cos(theta);
    const double s = std::sin(theta);
    const Vector2 outer(q.outerSemiAxisX * c, q.outerSemiAxisY * s);
    const Vector2 inner(
      q.innerCentreOffsetX + q.innerSemiAxisX * c, q.innerCentreOffsetY + q.innerSemiAxisY * s);
    const double fraction = std::pow(std::clamp(x[1], 0.0, 1.0), InnerEdgeGrading);
    const Vector2 planar = inner + fraction * (outer - inner);
    // Rim height tapers toward the horns.
    const double body = std::sin(M_PI * std::clamp(x[0], 0.0, 1.0));
    const double rim = q.rimHeight - (q.rimHeight - q.hornHeight) * (1.0 - body) * (1.0 - body);
    const double thickness =
      q.innerEdgeHeight + (rim - q.innerEdgeHeight) * std::pow(fraction, WedgeExponent);
    return Vector3(
      q.centre.x() + planar.x(), q.centre.y() + planar.y(), q.centre.z() + x[2] * thickness);
  };
  ParametricSolid solid("medial meniscus", map);

  const MeniscusTear& tear = p.tear;
  ParametricCrack longitudinal;
  longitudinal.normalAxis = 1;
  longitudinal.position = tear.across;
  longitudinal.ranges = { { { tear.alongBegin, tear.alongEnd }, { 0.0, 1.0 } } };
  longitudinal.opening = tear.opening;
  longitudinal.influence = std::min({ 0.2, 0.5 * tear.across, 0.5 * (1.0 - tear.across) });
  ParametricCrack radial;
  radial.normalAxis = 0;
  radial.position = tear.alongBegin;
  radial.ranges = { { { 0.0, tear.across }, { 0.0, 1.0 } } };
  radial.opening = tear.opening;
  radial.influence = std::min({ 0.03, 0.5 * tear.alongBegin, 0.5 * (1.0 - tear.alongBegin) });
  switch (tear.type)
  {
    case MeniscusTearType::None:
      break;
    case MeniscusTearType::Longitudinal:
      solid.addCrack(longitudinal);
      break;
    case MeniscusTearType::Radial:
      solid.addCrack(radial);
      break;
    case MeniscusTearType::Flap:
      solid.addCrack(radial);
      solid.addCrack(longitudinal);
      break;
    case MeniscusTearType::HorizontalCleavage:
    {
      ParametricCrack cleavage;
      cleavage.normalAxis = 2;
      cleavage.position = 0.5;
      cleavage.ranges = { { { tear.alongBegin, tear.alongEnd }, { 0.0, tear.across } } };
      cleavage.opening = tear.opening;
      // The lower leaf stays on the tibia; the upper leaf lifts as a whole
      // (its thickness, hence its collision radius, is kept).
      cleavage.positiveShare = 1.0;
      cleavage.influence = 1e6; // no fading: the whole leaf moves
      solid.addCrack(cleavage);
      break;
    }
  }
  return solid;
}

namespace
{

/// Parameter u at `distance` mm from the inner edge at s (inverse of the
/// grading; the width is measured on the unopened map).
double acrossAtDistance(const ParametricSolid& solid, double s, double distance)
{
  const double width =
    (solid.point(ParameterPoint(s, 1.0, 0.5)) - solid.point(ParameterPoint(s, 0.0, 0.5)))
      .head<2>()
      .norm();
  return std::pow(std::clamp(distance / width, 0.0, 1.0), 1.0 / InnerEdgeGrading);
}

/// Monitor data points along a free border: from s = `begin` to `end`, at
/// `inset` mm from the border at parameter u = `borderAcross` (toward
/// increasing u when `inward` is +1), region points `depth` mm further in.
MonitorCurve monitorCurve(const ParametricSolid& solid,
  const MeniscusParameters& p,
  const std::string& name,
  double begin,
  double end,
  double borderAcross,
  double w,
  double thicknessFraction,
  const std::vector<int>& sides)
{
  MonitorCurve curve;
  curve.name = name;
  curve.crackSides = sides;
  // Count from the border's length.
  double length = 0.0;
  Vector3 previous = solid.point(ParameterPoint(begin, borderAcross, w));
  for (int k = 1; k <= 64; ++k)
  {
    const Vector3 x =
      solid.point(ParameterPoint(begin + (end - begin) * k / 64.0, borderAcross, w));
    length += (x - previous).norm();
    previous = x;
  }
  const int count =
    std::max(2, static_cast<int>(std::ceil(length / 10.0 * p.monitorDataPointsPerCentimetre)) + 1);
  for (int k = 0; k < count; ++k)
  {
    const double s = begin + (end - begin) * k / (count - 1);
    const double borderDistance = borderAcross <= 0.0
                                    ? 0.0
                                    : (solid.point(ParameterPoint(s, borderAcross, 0.5)) -
                                        solid.point(ParameterPoint(s, 0.0, 0.5)))
                                        .head<2>()
                                        .norm();
    const double monitorU = acrossAtDistance(solid, s, borderDistance + p.monitorInset);
    const double regionU =
      acrossAtDistance(solid, s, borderDistance + p.monitorInset + p.regionDepth);
    const ParameterPoint monitor(s, monitorU, w);
    const ParameterPoint region(s, regionU, w);
    curve.monitorParameters.push_back(monitor);
    curve.regionParameters.push_back(region);
    curve.monitorPoints.push_back(solid.openedPoint(monitor, sides));
    curve.regionPoints.push_back(solid.openedPoint(region, sides));
    curve.thickness.push_back(thicknessFraction * solid.thickness(s, monitorU));
  }
  return curve;
}

} // namespace

MeniscusModel makeMeniscus(const MeniscusParameters& p)
{
  const ParametricSolid solid = makeMeniscusSolid(p);
  const MeniscusTear& tear = p.tear;

  MeniscusModel model;
  model.name = std::string("medial meniscus") +
               (tear.type == MeniscusTearType::None
                   ? ""
                   : std::string(", ") + meniscusTearTypeName(tear.type) + " tear");
  model.tear = tear;
  model.visual =
    solid.boundarySurface({ p.visualAlong, p.visualAcross, p.visualThrough }, p.textureScale);
  model.visual.name = model.name + " visual";
  model.collision = solid.midSurface(p.collisionAlong, p.collisionAcross);
  model.collision.name = model.name + " collision";
  // A horizontal cleavage must lie on hexahedron faces: two layers at least.
  const int through = tear.type == MeniscusTearType::HorizontalCleavage
                        ? std::max(2, p.hexahedraThrough)
                        : p.hexahedraThrough;
  // Margins cover the bulge of the curved rim and of the tapering height
  // between hexahedron nodes.
  const double attachment = p.hornAttachment;
  model.simulation = solid.hexahedra({ p.hexahedraAlong, p.hexahedraAcross, through },
    { 0.0, 0.8, 0.3 },
    [attachment](const ParameterPoint& x)
    { return x[0] <= attachment || x[0] >= 1.0 - attachment; });
  model.simulation.name = model.name + " hexahedra";

  // Monitor and region data points (4.3): along the inner border, broken by
  // the tear, plus the new free lips it creates.
  const std::size_t crackCount = solid.cracks().size();
  const std::vector<int> noSides(crackCount, 0);
  const double first = 0.03;
  const double last = 0.97;
  const double gap = 0.01;
  switch (tear.type)
  {
    case MeniscusTearType::None:
      model.monitorCurves.push_back(
        monitorCurve(solid, p, "inner border", first, last, 0.0, 0.5, 1.0, noSides));
      break;
    case MeniscusTearType::Longitudinal:
      model.monitorCurves.push_back(
        monitorCurve(solid, p, "inner border", first, last, 0.0, 0.5, 1.0, noSides));
      model.monitorCurves.push_back(monitorCurve(solid,
        p,
        "rim-side lip of the tear",
        tear.alongBegin + gap,
        tear.alongEnd - gap,
        tear.across,
        0.5,
        1.0,
        { 1 }));
      break;
    case MeniscusTearType::Radial:
      model.monitorCurves.push_back(monitorCurve(solid,
        p,
        "inner border, posterior part",
        first,
        tear.alongBegin - gap,
        0.0,
        0.5,
        1.0,
        noSides));
      model.monitorCurves.push_back(monitorCurve(solid,
        p,
        "inner border, anterior part",
        tear.alongBegin + gap,
        last,
        0.0,
        0.5,
        1.0,
        noSides));
      break;
    case MeniscusTearType::Flap:
      model.monitorCurves.push_back(monitorCurve(solid,
        p,
        "inner border, posterior part",
        first,
        tear.alongBegin - gap,
        0.0,
        0.5,
        1.0,
        noSides));
      model.monitorCurves.push_back(monitorCurve(solid,
        p,
        "inner border of the flap and beyond",
        tear.alongBegin + gap,
        last,
        0.0,
        0.5,
        1.0,
        noSides));
      model.monitorCurves.push_back(monitorCurve(solid,
        p,
        "rim-side lip of the flap",
        tear.alongBegin + gap,
        tear.alongEnd - gap,
        tear.across,
        0.5,
        1.0,
        { 0, 1 }));
      break;
    case MeniscusTearType::HorizontalCleavage:
      model.monitorCurves.push_back(monitorCurve(solid,
        p,
        "inner border, posterior part",
        first,
        tear.alongBegin - gap,
        0.0,
        0.5,
        1.0,
        noSides));
      model.monitorCurves.push_back(monitorCurve(solid,
        p,
        "inner border of the upper leaf",
        tear.alongBegin + gap,
        tear.alongEnd - gap,
        0.0,
        0.75,
        0.5,
        { 1 }));
      model.monitorCurves.push_back(monitorCurve(solid,
        p,
        "inner border of the lower leaf",
        tear.alongBegin + gap,
        tear.alongEnd - gap,
        0.0,
        0.25,
        0.5,
        { -1 }));
      model.monitorCurves.push_back(monitorCurve(solid,
        p,
        "inner border, anterior part",
        tear.alongEnd + gap,
        last,
        0.0,
        0.5,
        1.0,
        noSides));
      break;
  }
  return model;
}

std::vector<MonitorCurve> sampleMonitorCurves(const MeniscusParameters& parameters,
  const std::vector<MonitorCurve>& dataCurves,
  double maxSpacing)
{
  Checks.requirePositive(maxSpacing, "monitor point spacing");
  const ParametricSolid solid = makeMeniscusSolid(parameters);
  std::vector<MonitorCurve> dense;
  for (const auto& data : dataCurves)
  {
    if (data.monitorParameters.size() < 2 ||
        data.regionParameters.size() != data.monitorParameters.size() ||
        data.thickness.size() != data.monitorParameters.size())
    {
      Checks.fail("monitor curve '" + data.name + "' needs at least two complete data points");
    }
    MonitorCurve curve;
    curve.name = data.name;
    curve.crackSides = data.crackSides;
    // The data points lie on exact parameter lines: sample those lines
    // between consecutive data points, the thickness scaled as at the data.
    for (std::size_t k = 0; k + 1 < data.monitorParameters.size(); ++k)
    {
      const ParameterPoint& a = data.monitorParameters[k];
      const ParameterPoint& b = data.monitorParameters[k + 1];
      // Arc length along the segment, tabulated, so that the samples are
      // equally spaced along the curve (chords never exceed the arcs).
      constexpr int Steps = 256;
      std::vector<double> arc(Steps + 1, 0.0);
      Vector3 previous = solid.openedPoint(a, data.crackSides);
      for (int step = 1; step <= Steps; ++step)
      {
        const Vector3 x =
          solid.openedPoint(a + (b - a) * (static_cast<double>(step) / Steps), data.crackSides);
        arc[step] = arc[step - 1] + (x - previous).norm();
        previous = x;
      }
      const int pieces = std::max(1, static_cast<int>(std::ceil(arc[Steps] / maxSpacing)));
      const double fractionA = data.thickness[k] / solid.thickness(a[0], a[1]);
      const double fractionB = data.thickness[k + 1] / solid.thickness(b[0], b[1]);
      const int firstPiece = k == 0 ? 0 : 1;
      for (int piece = firstPiece; piece <= pieces; ++piece)
      {
        const double target = arc[Steps] * piece / pieces;
        const int step = static_cast<int>(std::min<std::ptrdiff_t>(
          Steps, std::lower_bound(arc.begin(), arc.end(), target) - arc.begin()));
        const double below = step > 0 ? arc[step - 1] : 0.0;
        const double within = arc[step] > below ? (target - below) / (arc[step] - below) : 0.0;
        const double t = step > 0 ? (step - 1 + within) / Steps : 0.0;
        const ParameterPoint monitor = a + t * (b - a);
        const ParameterPoint region =
          data.regionParameters[k] + t * (data.regionParameters[k + 1] - data.regionParameters[k]);
        curve.monitorParameters.push_back(monitor);
        curve.regionParameters.push_back(region);
        curve.monitorPoints.push_back(solid.openedPoint(monitor, data.crackSides));
        curve.regionPoints.push_back(solid.openedPoint(region, data.crackSides));
        curve.thickness.push_back(
          (fractionA + t * (fractionB - fractionA)) * solid.thickness(monitor[0], monitor[1]));
      }
    }
    dense.push_back(std::move(curve));
  }
  return dense;
}

} // namespace thintissue
