#include "SurgicalInstruments.h"

#include "ThinTissueError.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace thintissue
{
namespace
{

constexpr double Pi = 3.14159265358979323846;

double radians(double degrees)
{
  return degrees * Pi / 180.0;
}

// ---------------------------------------------------------------------------
// Names
// ---------------------------------------------------------------------------

std::string normalizedName(const std::string& name)
{
  std::string result;
  for (const char c : name)
  {
    if (c == '_' || c == '-' || std::isspace(static_cast<unsigned char>(c)))
    {
      continue;
    }
    result.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  return result;
}

// ---------------------------------------------------------------------------
// Parameter checks
// ---------------------------------------------------------------------------

std::string formatNumber(double value)
{
  std::ostringstream stream;
  stream << value;
  return stream.str();
}

/// Builds the messages "surgical instrument 'x': <parameter> <problem>".
class ParameterChecker
{
public:
  explicit ParameterChecker(std::string instrument)
    : Instrument(std::move(instrument))
  {
  }

  [[noreturn]] void fail(const std::string& parameter, const std::string& problem) const
  {
    throw InvalidInputError(
      "surgical instrument '" + Instrument + "': " + parameter + " " + problem);
  }

  void positive(const char* parameter, double value) const
  {
    if (!(value > 0.0) || !std::isfinite(value))
    {
      fail(parameter, "must be positive and finite (got " + formatNumber(value) + ")");
    }
  }

  void inRange(const char* parameter, double value, double low, double high) const
  {
    if (!(value >= low && value <= high))
    {
      fail(parameter,
        "must lie in [" + formatNumber(low) + ", " + formatNumber(high) + "] (got " +
          formatNumber(value) + ")");
    }
  }

private:
  std::string Instrument;
};

// ---------------------------------------------------------------------------
// Geometry helpers
// ---------------------------------------------------------------------------

/// One cross-section of a swept piece. A ring of one point is a pole (only
/// at either end of a non-periodic sweep).
struct Ring
{
  std::vector<Vector3> points;
  InstrumentPart part = InstrumentPart::Shaft;
};

Ring poleRing(const Vector3& point, InstrumentPart part)
{
  return Ring{ { point }, part };
}

Vector3 centroidOf(const std::vector<Vector3>& points)
{
  Vector3 sum = Vector3::Zero();
  for (const Vector3& p : points)
  {
    sum += p;
  }
  return sum / static_cast<double>(points.size());
}

/// Closes a ring with a flat fan: the pole at its centroid (rings here are
/// star-shaped about their centroid).
Ring centroidPole(const Ring& ring)
{
  return poleRing(centroidOf(ring.points), ring.part);
}

/// Closed piece: consecutive rings (of equal size, poles excepted) joined by
/// quads; a periodic sweep also joins the last ring to the first. Faces
/// outward (fixed by the sign of the enclosed volume), with vertex normals
/// and the InstrumentPart array.
TriangleMesh sweepPiece(const std::vector<Ring>& rings, bool periodic = false)
{
  TriangleMesh piece;
  std::vector<int> base;
  std::vector<double> parts;
  for (const Ring& ring : rings)
  {
    base.push_back(static_cast<int>(piece.positions.size()));
    for (const Vector3& p : ring.points)
    {
      piece.positions.push_back(p);
      parts.push_back(static_cast<double>(static_cast<int>(ring.part)));
    }
  }
  const std::size_t ringCount = rings.size();
  const std::size_t joints = periodic ? ringCount : ringCount - 1;
  for (std::size_t i = 0; i < joints; ++i)
  {
    const std::size_t k = (i + 1) % ringCount;
    const int sizeA = static_cast<int>(rings[i].points.size());
    const int sizeB = static_cast<int>(rings[k].points.size());
    const int n = std::max(sizeA, sizeB);
    for (int j = 0; j < n; ++j)
    {
      const int jn = (j + 1) % n;
      const int a = base[i] + (sizeA == 1 ? 0 : j);
      const int b = base[i] + (sizeA == 1 ? 0 : jn);
      const int c = base[k] + (sizeB == 1 ? 0 : jn);
      const int d = base[k] + (sizeB == 1 ? 0 : j);
      if (sizeA != 1)
      {
        piece.triangles.push_back({ a, b, c });
      }
      if (sizeB != 1)
      {
        piece.triangles.push_back({ a, c, d });
      }
    }
  }
  if (piece.signedVolume() < 0.0)
  {
    piece.reverseOrientation();
  }
  piece.computeVertexNormals();
  piece.pointAttributes.set(InstrumentPartArrayName, 1, std::move(parts));
  return piece;
}

/// Unit vector perpendicular to `direction`.
Vector3 anyPerpendicular(const Vector3& direction)
{
  const Vector3 helper = std::abs(direction.x()) < 0.9 ? Vector3::UnitX() : Vector3::UnitY();
  return direction.cross(helper).normalized();
}

std::vector<double> uniformAngles(int count)
{
  std::vector<double> angles(count);
  for (int j = 0; j < count; ++j)
  {
    angles[j] = 2.0 * Pi * j / count;
  }
  return angles;
}

/// Circle of `radius` about `centre` in the plane spanned by u and v.
Ring circleRing(const Vector3& centre,
  const Vector3& u,
  const Vector3& v,
  double radius,
  const std::vector<double>& angles,
  InstrumentPart part)
{
  Ring ring;
  ring.part = part;
  for (const double angle : angles)
  {
    ring.points.push_back(centre + radius * (std::cos(angle) * u + std::sin(angle) * v));
  }
  return ring;
}

/// Closed cylinder between two points (flat ends).
TriangleMesh cylinderPiece(const Vector3& from,
  const Vector3& to,
  double radius,
  int segments,
  InstrumentPart part)
{
  const Vector3 axis = (to - from).normalized();
  const Vector3 u = anyPerpendicular(axis);
  const Vector3 v = axis.cross(u);
  const std::vector<double> angles = uniformAngles(segments);
  return sweepPiece({ poleRing(from, part),
    circleRing(from, u, v, radius, angles, part),
    circleRing(to, u, v, radius, angles, part),
    poleRing(to, part) });
}

/// Torus about `centre` whose tube centre circle (radius `major`) lies in
/// the plane spanned by u and v.
TriangleMesh torusPiece(const Vector3& centre,
  const Vector3& u,
  const Vector3& v,
  double major,
  double minor,
  int segmentsAlong,
  int segmentsAround,
  InstrumentPart part)
{
  const Vector3 normal = u.cross(v);
  const std::vector<double> around = uniformAngles(segmentsAround);
  std::vector<Ring> rings;
  for (int i = 0; i < segmentsAlong; ++i)
  {
    const double angle = 2.0 * Pi * i / segmentsAlong;
    const Vector3 radial = std::cos(angle) * u + std::sin(angle) * v;
    rings.push_back(circleRing(centre + major * radial, radial, normal, minor, around, part));
  }
  return sweepPiece(rings, true);
}

/// Radius profile of a body of revolution about the z axis.
struct ProfilePoint
{
  double z;
  double radius;
  InstrumentPart part;
};

/// Rings about the z axis; a zero radius gives a pole.
std::vector<Ring> latheRings(const std::vector<ProfilePoint>& profile,
  const std::vector<double>& angles)
{
  std::vector<Ring> rings;
  for (const ProfilePoint& p : profile)
  {
    const Vector3 centre(0.0, 0.0, p.z);
    if (p.radius <= 0.0)
    {
      rings.push_back(poleRing(centre, p.part));
    }
    else
    {
      rings.push_back(
        circleRing(centre, Vector3::UnitX(), Vector3::UnitY(), p.radius, angles, p.part));
    }
  }
  return rings;
}

/// Shaft points from `zFrom` (exclusive) to `zTo` (inclusive), at most
/// `spacing` apart, so that long shafts keep moderate triangle shapes.
void appendShaftProfile(std::vector<ProfilePoint>& profile,
  double zFrom,
  double zTo,
  double radius,
  double spacing,
  InstrumentPart part = InstrumentPart::Shaft)
{
  const int steps = std::max(1, static_cast<int>(std::ceil((zTo - zFrom) / spacing)));
  for (int k = 1; k <= steps; ++k)
  {
    profile.push_back({ zFrom + (zTo - zFrom) * k / steps, radius, part });
  }
}

/// Rounded end of a handle: quarter ellipse from (zStart, radius) to the
/// pole at zStart + length.
void appendRoundedEnd(std::vector<ProfilePoint>& profile,
  double zStart,
  double length,
  double radius,
  int steps)
{
  for (int k = 1; k <= steps; ++k)
  {
    const double psi = 0.5 * Pi * k / steps;
    profile.push_back({ zStart + length * std::sin(psi),
      k == steps ? 0.0 : radius * std::cos(psi),
      InstrumentPart::Handle });
  }
}

enum class HandleStyle
{
  Pen,       ///< probe, knife: collar, grooved grip, rounded end
  Handpiece, ///< shavers: blade hub, then the motor handpiece
  GripBody   ///< punch, scissors: short body carrying the finger rings
};

/// Handle profile from the end of the shaft (z = zStart, radius
/// shaftRadius) to the pole at zStart + length. Every z increases strictly.
std::vector<ProfilePoint> handleProfile(HandleStyle style,
  double zStart,
  double shaftRadius,
  double handleRadius,
  double length)
{
  const double R = shaftRadius;
  const double H = handleRadius;
  const double L = length;
  const auto handle = InstrumentPart::Handle;
  std::vector<ProfilePoint> profile;
  switch (style)
  {
    case HandleStyle::Pen:
    {
      const double collar = std::min(0.15 * L, 12.0);
      profile.push_back({ zStart + 0.4 * collar, R + 0.35 * (H - R), handle });
      profile.push_back({ zStart + collar, 0.92 * H, handle });
      profile.push_back({ zStart + collar + 0.03 * L, H, handle });
      for (int groove = 0; groove < 4; ++groove)
      {
        const double zGroove = zStart + collar + 0.2 * L + 0.08 * L * groove;
        profile.push_back({ zGroove - 0.015 * L, H, handle });
        profile.push_back({ zGroove, 0.9 * H, handle });
        profile.push_back({ zGroove + 0.015 * L, H, handle });
      }
      const double endLength = std::min(0.6 * H, 0.1 * L);
      profile.push_back({ zStart + L - endLength, H, handle });
      appendRoundedEnd(profile, zStart + L - endLength, endLength, H, 5);
      break;
    }
    case HandleStyle::Handpiece:
    {
      const double hub = std::min(25.0, 0.2 * L);
      const double hubRadius = std::min(H, std::max(R + 1.5, 0.3 * H));
      profile.push_back({ zStart + 0.12 * hub, hubRadius, handle });
      profile.push_back({ zStart + hub, hubRadius, handle });
      profile.push_back({ zStart + hub + 0.02 * L, 0.85 * H, handle });
      profile.push_back({ zStart + hub + 0.04 * L, H, handle });
      const double endLength = std::min(0.5 * H, 0.1 * L);
      const double zEnd = zStart + L - endLength;
      const double zFront = zStart + hub + 0.04 * L;
      appendShaftProfile(profile, zFront, zEnd, H, 20.0, handle);
      appendRoundedEnd(profile, zEnd, endLength, H, 5);
      break;
    }
    case HandleStyle::GripBody:
    {
      profile.push_back({ zStart + 0.15 * L, 0.7 * H, handle });
      profile.push_back({ zStart + 0.25 * L, H, handle });
      const double endLength = std::min(0.5 * H, 0.15 * L);
      profile.push_back({ zStart + L - endLength, H, handle });
      appendRoundedEnd(profile, zStart + L - endLength, endLength, H, 4);
      break;
    }
  }
  return profile;
}

/// Flat distal end of a shaft at zDistal with a small chamfer, then the
/// shaft to zHandle.
std::vector<ProfilePoint> chamferedShaftProfile(double zDistal, double zHandle, double R)
{
  std::vector<ProfilePoint> profile;
  profile.push_back({ zDistal, 0.0, InstrumentPart::Shaft });
  profile.push_back({ zDistal, 0.8 * R, InstrumentPart::Shaft });
  profile.push_back({ zDistal + 0.2 * R, R, InstrumentPart::Shaft });
  appendShaftProfile(profile, zDistal + 0.2 * R, zHandle, R, 10.0);
  return profile;
}

/// Point of a moving jaw or blade turned about the hinge line through
/// `hinge` parallel to y, so that the distal end (toward -z) opens to +x.
Vector3 openedAboutHinge(const Vector3& point, const Vector3& hinge, double openingRadians)
{
  const Eigen::AngleAxisd rotation(-openingRadians, Vector3::UnitY());
  return hinge + rotation * (point - hinge);
}

void openPiece(TriangleMesh& piece, const Vector3& hinge, double openingRadians)
{
  const Eigen::AngleAxisd rotation(-openingRadians, Vector3::UnitY());
  for (Vector3& p : piece.positions)
  {
    p = hinge + rotation * (p - hinge);
  }
  for (Vector3& n : piece.normals)
  {
    n = rotation * n;
  }
}

/// Two finger rings on shanks below (-x) and behind the grip body of a punch
/// or scissors. The body spans z in [zBody, zBody + bodyLength].
void appendFingerRings(TriangleMesh& visual,
  double zBody,
  double bodyRadius,
  double bodyLength,
  int segments)
{
  const double major = 10.0;
  const double minor = 2.5;
  const double shank = std::min(2.2, 0.6 * bodyRadius);
  const int around = std::max(8, segments / 2);
  const auto handle = InstrumentPart::Handle;
  // Shanks start inside the body; the rings stay behind the start of the
  // handle (zBody) however short the body is.
  const auto addRing = [&](const Vector3& start, const Vector3& centre)
  {
    visual.append(cylinderPiece(
      start, centre + major * (start - centre).normalized(), shank, segments, handle));
    visual.append(torusPiece(
      centre, Vector3::UnitX(), Vector3::UnitZ(), major, minor, segments, around, handle));
  };
  // Finger ring below the middle of the body.
  const double zFixed = zBody + std::max(0.45 * bodyLength, shank + 0.5);
  addRing(Vector3(-0.5 * bodyRadius, 0.0, zFixed),
    Vector3(
      -(bodyRadius + major + 18.0), 0.0, zBody + std::max(0.45 * bodyLength, major + minor + 1.0)));
  // Thumb ring behind the body.
  addRing(Vector3(-0.5 * bodyRadius, 0.0, zBody + std::max(0.8 * bodyLength, shank + 0.5)),
    Vector3(-(bodyRadius + major + 8.0), 0.0, zBody + bodyLength + 22.0));
}

// ---------------------------------------------------------------------------
// Instruments
// ---------------------------------------------------------------------------

/// Tube along a planar path (in the x-z plane); radius 0 at either end is a
/// pole. The ring's angle 0 is at binormal(+y) x tangent.
struct PathStation
{
  Vector3 point;
  Vector3 tangent;
  double radius;
  InstrumentPart part;
};

void buildProbeHook(const SurgicalInstrumentParameters& p, SurgicalInstrumentModel& model)
{
  const double R = 0.5 * p.shaftDiameter;
  const double r = 0.5 * p.hookDiameter;
  const double bend = 2.0 * r;          // centre-line radius of the 90-degree bend
  const double taper = 4.0 * R;         // shaft narrows from R to r above the bend
  const double xEnd = p.hookLength - r; // centre of the hook's rounded end
  const double zBendTop = r + bend;     // the hook's underside lies on z = 0
  const Vector3 down = -Vector3::UnitZ();
  const auto working = InstrumentPart::WorkingTip;

  // Stations from the handle's end down the shaft, round the bend, out the hook.
  std::vector<PathStation> stations;
  const std::vector<ProfilePoint> handle =
    handleProfile(HandleStyle::Pen, p.shaftLength, R, 0.5 * p.handleDiameter, p.handleLength);
  for (auto it = handle.rbegin(); it != handle.rend(); ++it)
  {
    stations.push_back({ Vector3(0.0, 0.0, it->z), down, it->radius, it->part });
  }
  std::vector<ProfilePoint> shaft;
  shaft.push_back({ zBendTop + taper, R, InstrumentPart::Shaft });
  appendShaftProfile(shaft, zBendTop + taper, p.shaftLength, R, 10.0);
  for (auto it = shaft.rbegin(); it != shaft.rend(); ++it)
  {
    stations.push_back({ Vector3(0.0, 0.0, it->z), down, it->radius, it->part });
  }
  const int taperSteps = 6;
  for (int k = 1; k < taperSteps; ++k)
  {
    const double t = static_cast<double>(k) / taperSteps; // 0 at the shaft, 1 at the bend
    const double smooth = t * t * (3.0 - 2.0 * t);
    stations.push_back(
      { Vector3(0.0, 0.0, zBendTop + taper * (1.0 - t)), down, R + (r - R) * smooth, working });
  }
  const int bendSteps = 8;
  for (int k = 0; k <= bendSteps; ++k)
  {
    const double alpha = 0.5 * Pi * k / bendSteps;
    stations.push_back(
      { Vector3(bend - bend * std::cos(alpha), 0.0, zBendTop - bend * std::sin(alpha)),
        Vector3(std::sin(alpha), 0.0, -std::cos(alpha)),
        r,
        working });
  }
  if (xEnd > bend + 1e-9)
  {
    stations.push_back({ Vector3(xEnd, 0.0, r), Vector3::UnitX(), r, working });
  }
  const int capSteps = 4;
  for (int k = 1; k <= capSteps; ++k)
  {
    const double phi = 0.5 * Pi * k / capSteps;
    stations.push_back({ Vector3(xEnd + r * std::sin(phi), 0.0, r),
      Vector3::UnitX(),
      k == capSteps ? 0.0 : r * std::cos(phi),
      working });
  }

  // The tip (the underside of the hook's end) goes to the origin.
  const Vector3 shift(-xEnd, 0.0, 0.0);
  const std::vector<double> angles = uniformAngles(p.segmentsAround);
  std::vector<Ring> rings;
  for (const PathStation& s : stations)
  {
    if (s.radius <= 0.0)
    {
      rings.push_back(poleRing(s.point + shift, s.part));
      continue;
    }
    const Vector3 normal = Vector3::UnitY().cross(s.tangent).normalized();
    rings.push_back(
      circleRing(s.point + shift, normal, Vector3::UnitY(), s.radius, angles, s.part));
  }
  model.visual = sweepPiece(rings);

  // Centre line: hook, the bend as two chords (radius grown by the sagitta),
  // then the shaft (its taper lies inside radius R).
  const auto bendPoint = [&](double alpha) -> Vector3 {
    return Vector3(bend - bend * std::cos(alpha), 0.0, zBendTop - bend * std::sin(alpha)) + shift;
  };
  const double sagitta = bend * (1.0 - std::cos(Pi / 8.0));
  model.centreLine.push_back({ Vector3(xEnd, 0.0, r) + shift, bendPoint(0.5 * Pi), r, "hook" });
  model.centreLine.push_back({ bendPoint(0.5 * Pi), bendPoint(0.25 * Pi), r + sagitta, "bend" });
  model.centreLine.push_back({ bendPoint(0.25 * Pi), bendPoint(0.0), r + sagitta, "bend" });
  model.centreLine.push_back(
    { bendPoint(0.0), Vector3(0.0, 0.0, p.shaftLength) + shift, R, "shaft" });
}

/// Outline of a jaw: distal semicircle (centre z = zDistalCentre, radius
/// width), straight sides, and a proximal end that is straight at zTop
/// (squareEnd) or a semicircle centred at zTop. Sampled at u = k / count in
/// four quarters: distal arc, +y side, proximal end, -y side; `count` is a
/// multiple of 8 so that the distal apex (u = 1/8) is a sample.
std::vector<Vector2> jawOutline(double width,
  double zDistalCentre,
  double zTop,
  bool squareEnd,
  int count)
{
  std::vector<Vector2> outline; // (y, z)
  const int quarter = count / 4;
  for (int k = 0; k < count; ++k)
  {
    const int piece = k / quarter;
    const double t = static_cast<double>(k % quarter) / quarter;
    switch (piece)
    {
      case 0:
      {
        const double beta = -0.5 * Pi + Pi * t;
        outline.emplace_back(width * std::sin(beta), zDistalCentre - width * std::cos(beta));
        break;
      }
      case 1:
        outline.emplace_back(width, zDistalCentre + (zTop - zDistalCentre) * t);
        break;
      case 2:
        if (squareEnd)
        {
          outline.emplace_back(width * (1.0 - 2.0 * t), zTop);
        }
        else
        {
          const double gamma = 0.5 * Pi + Pi * t;
          outline.emplace_back(width * std::sin(gamma), zTop - width * std::cos(gamma));
        }
        break;
      default:
        outline.emplace_back(-width, zTop - (zTop - zDistalCentre) * t);
        break;
    }
  }
  return outline;
}

int outlineSampleCount(int segmentsAround)
{
  return 8 * std::max(1, (segmentsAround + 7) / 8);
}

void buildPunch(const SurgicalInstrumentParameters& p, SurgicalInstrumentModel& model)
{
  const double R = 0.5 * p.shaftDiameter;
  const double a = p.jawThickness;
  const double biteHalfWidth = 0.5 * p.biteWidth;
  const double wall = 0.2 * p.biteWidth;
  const double outerHalfWidth = biteHalfWidth + wall;
  const double zShaft = p.biteLength + 2.0 * wall; // distal end of the shaft, the hinge
  const double overlap = std::min(1.0, 0.5 * zShaft);
  const double zInside = zShaft + overlap; // the jaws reach into the shaft
  const double opening = radians(p.jawOpeningDegrees);
  const Vector3 hinge(0.0, 0.0, zShaft);
  const auto working = InstrumentPart::WorkingTip;

  // Shaft with the grip body, finger rings.
  std::vector<ProfilePoint> profile = chamferedShaftProfile(zShaft, p.shaftLength, R);
  const std::vector<ProfilePoint> handle =
    handleProfile(HandleStyle::GripBody, p.shaftLength, R, 0.5 * p.handleDiameter, p.handleLength);
  profile.insert(profile.end(), handle.begin(), handle.end());
  model.visual = sweepPiece(latheRings(profile, uniformAngles(p.segmentsAround)));
  appendFingerRings(
    model.visual, p.shaftLength, 0.5 * p.handleDiameter, p.handleLength, p.segmentsAround);

  // Fixed (lower) jaw: a frame around the bite hole, x in [-a, 0]; its top
  // face x = 0 is the cutting face the moving jaw closes on.
  const int count = outlineSampleCount(p.segmentsAround);
  const std::vector<Vector2> outer =
    jawOutline(outerHalfWidth, outerHalfWidth, zInside, true, count);
  const std::vector<Vector2> bite =
    jawOutline(biteHalfWidth, outerHalfWidth, wall + p.biteLength - biteHalfWidth, false, count);
  std::vector<Ring> frameRings;
  for (int k = 0; k < count; ++k)
  {
    const Vector2& o = outer[k];
    const Vector2& i = bite[k];
    frameRings.push_back(Ring{ { Vector3(-a, o.x(), o.y()),
                                 Vector3(0.0, o.x(), o.y()),
                                 Vector3(0.0, i.x(), i.y()),
                                 Vector3(-a, i.x(), i.y()) },
      working });
  }
  model.visual.append(sweepPiece(frameRings, true));

  // Moving (upper) jaw: a solid plate x in [0, a] over the same outline,
  // opened about the hinge.
  Ring lower{ {}, working };
  Ring upper{ {}, working };
  for (const Vector2& o : outer)
  {
    lower.points.emplace_back(0.0, o.x(), o.y());
    upper.points.emplace_back(a, o.x(), o.y());
  }
  TriangleMesh movingJaw = sweepPiece({ centroidPole(lower), lower, upper, centroidPole(upper) });
  openPiece(movingJaw, hinge, opening);
  model.visual.append(movingJaw);

  for (const Vector2& i : bite)
  {
    model.biteOutline.emplace_back(0.0, i.x(), i.y());
  }

  const double jawRadius = std::hypot(outerHalfWidth, 0.5 * a);
  model.centreLine.push_back({ Vector3(-0.5 * a, 0.0, outerHalfWidth),
    Vector3(-0.5 * a, 0.0, zInside),
    jawRadius,
    "fixed jaw" });
  model.centreLine.push_back(
    { openedAboutHinge(Vector3(0.5 * a, 0.0, outerHalfWidth), hinge, opening),
      openedAboutHinge(Vector3(0.5 * a, 0.0, zInside), hinge, opening),
      jawRadius,
      "moving jaw" });
  model.centreLine.push_back(
    { Vector3(0.0, 0.0, zShaft), Vector3(0.0, 0.0, p.shaftLength), R, "shaft" });
}

void buildShaver(const SurgicalInstrumentParameters& p, SurgicalInstrumentModel& model)
{
  const double R = 0.5 * p.shaftDiameter;
  const double innerRadius = 0.75 * R; // the inner cutter seen through the window
  const double halfWindow = 0.5 * p.windowWidth;
  const double cutPlane = std::sqrt(R * R - halfWindow * halfWindow); // window plane x = cutPlane
  const double zWindowDistal = R - halfWindow;
  const double zWindowEnd = zWindowDistal + p.windowLength;
  const double wallStep = std::min(0.05 * R, 0.2 * halfWindow);
  const int n = p.segmentsAround;
  const int windowSamples = std::max(4, n / 3);
  const int otherSamples = n - windowSamples;
  const double minimumHalfAngle = 0.12;
  const double inset = 0.04; // rim to the first recessed sample, fraction of the window arc

  std::vector<Ring> rings;
  const auto addRing = [&](double ringRadius,
                         const Vector3& ringCentre,
                         const Vector3& scaleCentre,
                         bool windowAllowed,
                         InstrumentPart ringPart)
  {
    const double layoutRadius = std::min(ringRadius, R);
    const double halfAngle =
      std::max(std::acos(std::min(1.0, cutPlane / layoutRadius)), minimumHalfAngle);
    const bool windowRing = windowAllowed && ringRadius > cutPlane;
    Ring ring;
    ring.part = ringPart;
    for (int k = 0; k < n; ++k)
    {
      double angle;
      bool recessed = false;
      if (k < windowSamples)
      {
        double f;
        if (k == 0 || k == windowSamples - 1)
        {
          f = k == 0 ? 0.0 : 1.0;
        }
        else
        {
          f = inset + (1.0 - 2.0 * inset) * (k - 1) / (windowSamples - 3);
          recessed = windowRing;
        }
        angle = -halfAngle + 2.0 * halfAngle * f;
        recessed = recessed && ringRadius * std::cos(angle) > cutPlane;
      }
      else
      {
        angle =
          halfAngle + (2.0 * Pi - 2.0 * halfAngle) * (k - windowSamples + 1) / (otherSamples + 1);
      }
      Vector3 point = ringCentre + ringRadius * Vector3(std::cos(angle), std::sin(angle), 0.0);
      if (recessed)
      {
        point = scaleCentre + (innerRadius / R) * (point - scaleCentre);
      }
      ring.points.push_back(point);
    }
    rings.push_back(ring);
  };

  // Distal hemisphere (centre (0, 0, R)), pole at the origin.
  const Vector3 sphereCentre(0.0, 0.0, R);
  rings.push_back(poleRing(Vector3::Zero(), InstrumentPart::WorkingTip));
  const int hemisphereSteps = std::max(6, n / 3);
  std::vector<Vector3> rimRight; // window rim on the +y side, distal to proximal
  for (int j = 1; j <= hemisphereSteps; ++j)
  {
    const double phi = 0.5 * Pi * j / hemisphereSteps;
    const double ringRadius = R * std::sin(phi);
    const double z = R - R * std::cos(phi);
    addRing(ringRadius, Vector3(0.0, 0.0, z), sphereCentre, true, InstrumentPart::WorkingTip);
    if (ringRadius > cutPlane)
    {
      rimRight.emplace_back(cutPlane, std::sqrt(ringRadius * ringRadius - cutPlane * cutPlane), z);
    }
  }
  // Cylinder part of the window, then its proximal wall.
  const double zRecessEnd = zWindowEnd - wallStep;
  const int windowSteps =
    std::max(1, static_cast<int>(std::ceil((zRecessEnd - R) / (0.5 * halfWindow))));
  for (int k = 1; k <= windowSteps; ++k)
  {
    const double z = R + (zRecessEnd - R) * k / windowSteps;
    addRing(R, Vector3(0.0, 0.0, z), Vector3(0.0, 0.0, z), true, InstrumentPart::WorkingTip);
    rimRight.emplace_back(cutPlane, halfWindow, z);
  }
  addRing(R, Vector3(0.0, 0.0, zWindowEnd), Vector3::Zero(), false, InstrumentPart::WorkingTip);
  rimRight.emplace_back(cutPlane, halfWindow, zWindowEnd);
  // Shaft, hub and handpiece.
  std::vector<ProfilePoint> rest;
  appendShaftProfile(rest, zWindowEnd, p.shaftLength, R, 10.0);
  const std::vector<ProfilePoint> handle =
    handleProfile(HandleStyle::Handpiece, p.shaftLength, R, 0.5 * p.handleDiameter, p.handleLength);
  rest.insert(rest.end(), handle.begin(), handle.end());
  for (const ProfilePoint& q : rest)
  {
    if (q.radius <= 0.0)
    {
      rings.push_back(poleRing(Vector3(0.0, 0.0, q.z), q.part));
    }
    else
    {
      addRing(q.radius, Vector3(0.0, 0.0, q.z), Vector3::Zero(), false, q.part);
    }
  }
  model.visual = sweepPiece(rings);

  // Window outline in its plane x = cutPlane: distal point, +y rim, -y rim back.
  model.biteOutline.emplace_back(cutPlane, 0.0, zWindowDistal);
  for (const Vector3& q : rimRight)
  {
    model.biteOutline.push_back(q);
  }
  for (auto it = rimRight.rbegin(); it != rimRight.rend(); ++it)
  {
    model.biteOutline.emplace_back(it->x(), -it->y(), it->z());
  }

  model.centreLine.push_back({ sphereCentre, Vector3(0.0, 0.0, p.shaftLength), R, "shaft" });
}

/// A blade swept from its point (a pole at `point`) to the shaft, then
/// `overlap` into the shaft. `section(s)` gives the cross-section at the
/// fraction s of the blade length (x, y offsets); `edge` returns the index
/// of the section point on the cutting edge.
template <typename Section>
TriangleMesh bladePiece(double length,
  double overlap,
  int steps,
  Section section,
  std::vector<Vector3>* edgePoints,
  int edgeIndex)
{
  const auto working = InstrumentPart::WorkingTip;
  std::vector<Ring> rings;
  rings.push_back(poleRing(Vector3::Zero(), working));
  if (edgePoints)
  {
    edgePoints->push_back(Vector3::Zero());
  }
  for (int k = 1; k <= steps + 1; ++k)
  {
    const double s = k <= steps ? std::pow(static_cast<double>(k) / steps, 1.5) : 1.0;
    const double z = k <= steps ? s * length : length + overlap;
    Ring ring{ {}, working };
    for (const Vector2& q : section(s))
    {
      ring.points.emplace_back(q.x(), q.y(), z);
    }
    if (edgePoints && k <= steps)
    {
      edgePoints->push_back(ring.points[edgeIndex]);
    }
    rings.push_back(ring);
  }
  rings.push_back(centroidPole(rings.back()));
  return sweepPiece(rings);
}

void buildScissors(const SurgicalInstrumentParameters& p, SurgicalInstrumentModel& model)
{
  const double R = 0.5 * p.shaftDiameter;
  const double h0 = p.bladeWidth;
  const double t0 = p.bladeThickness;
  const double zShaft = p.bladeLength;
  const double overlap = std::min(1.0, 0.5 * zShaft);
  const double opening = radians(p.jawOpeningDegrees);
  const Vector3 hinge(0.0, 0.0, zShaft);

  std::vector<ProfilePoint> profile = chamferedShaftProfile(zShaft, p.shaftLength, R);
  const std::vector<ProfilePoint> handle =
    handleProfile(HandleStyle::GripBody, p.shaftLength, R, 0.5 * p.handleDiameter, p.handleLength);
  profile.insert(profile.end(), handle.begin(), handle.end());
  model.visual = sweepPiece(latheRings(profile, uniformAngles(p.segmentsAround)));
  appendFingerRings(
    model.visual, p.shaftLength, 0.5 * p.handleDiameter, p.handleLength, p.segmentsAround);

  // Fixed blade below the axis (x in [-h, 0]) on the -y side of the shear
  // plane y = 0; its edge is the line x = y = 0, bevelled on the outer face.
  // A blunt rounded point, as on arthroscopic scissors.
  const auto fixedSection = [&](double s)
  {
    const double u = std::min(1.0, s / 0.35);
    const double g = std::sqrt(u * (2.0 - u));
    const double h = h0 * g;
    const double t = t0 * g;
    return std::vector<Vector2>{
      Vector2(0.0, 0.0), Vector2(-h, 0.0), Vector2(-h, -t), Vector2(-0.35 * h, -t)
    };
  };
  const auto movingSection = [&](double s)
  {
    std::vector<Vector2> section = fixedSection(s);
    for (Vector2& q : section)
    {
      q = -q; // half-turn about z: above the axis, on the +y side
    }
    return section;
  };
  const int steps = 12;
  model.visual.append(bladePiece(zShaft, overlap, steps, fixedSection, &model.cuttingEdge, 0));
  std::vector<Vector3> movingEdge;
  TriangleMesh movingBlade = bladePiece(zShaft, overlap, steps, movingSection, &movingEdge, 0);
  openPiece(movingBlade, hinge, opening);
  model.visual.append(movingBlade);
  for (const Vector3& q : movingEdge)
  {
    model.opposingCuttingEdge.push_back(openedAboutHinge(q, hinge, opening));
  }

  const double bladeRadius = 0.5 * std::hypot(h0, t0);
  model.centreLine.push_back({ Vector3(-0.5 * h0, -0.5 * t0, 0.0),
    Vector3(-0.5 * h0, -0.5 * t0, zShaft + overlap),
    bladeRadius,
    "fixed blade" });
  model.centreLine.push_back({ openedAboutHinge(Vector3(0.5 * h0, 0.5 * t0, 0.0), hinge, opening),
    openedAboutHinge(Vector3(0.5 * h0, 0.5 * t0, zShaft + overlap), hinge, opening),
    bladeRadius,
    "moving blade" });
  model.centreLine.push_back(
    { Vector3(0.0, 0.0, zShaft), Vector3(0.0, 0.0, p.shaftLength), R, "shaft" });
}

void buildScalpel(const SurgicalInstrumentParameters& p, SurgicalInstrumentModel& model)
{
  const double R = 0.5 * p.shaftDiameter;
  const double zShaft = p.bladeLength;
  const double overlap = std::min(1.5, 0.5 * zShaft);
  const double halfWidth = 0.5 * p.bladeWidth;
  const double halfThickness = 0.5 * p.bladeThickness;

  std::vector<ProfilePoint> profile = chamferedShaftProfile(zShaft, p.shaftLength, R);
  const std::vector<ProfilePoint> handle =
    handleProfile(HandleStyle::Pen, p.shaftLength, R, 0.5 * p.handleDiameter, p.handleLength);
  profile.insert(profile.end(), handle.begin(), handle.end());
  model.visual = sweepPiece(latheRings(profile, uniformAngles(p.segmentsAround)));

  // Spear point: both sides curve to the point on the axis; the +x side is
  // ground to an edge, the -x side is the flat back.
  const auto section = [&](double s)
  {
    const double g = std::sin(0.5 * Pi * std::min(1.0, s / 0.45));
    const double w = halfWidth * g;
    const double t = halfThickness * g;
    const double bevel = 0.1 * w;
    return std::vector<Vector2>{
      Vector2(-w, -t), Vector2(bevel, -t), Vector2(w, 0.0), Vector2(bevel, t), Vector2(-w, t)
    };
  };
  model.visual.append(bladePiece(zShaft, overlap, 14, section, &model.cuttingEdge, 2));

  model.centreLine.push_back({ Vector3::Zero(),
    Vector3(0.0, 0.0, zShaft + overlap),
    std::hypot(halfWidth, halfThickness),
    "blade" });
  model.centreLine.push_back(
    { Vector3(0.0, 0.0, zShaft), Vector3(0.0, 0.0, p.shaftLength), R, "shaft" });
}

/// Length of the working part along the axis, which the shaft must exceed.
double workingLength(const SurgicalInstrumentParameters& p)
{
  switch (p.type)
  {
    case SurgicalInstrumentType::ProbeHook:
      return 1.5 * p.hookDiameter + 2.0 * p.shaftDiameter;
    case SurgicalInstrumentType::Punch:
      return p.biteLength + 0.4 * p.biteWidth + 1.0;
    case SurgicalInstrumentType::SmallShaver:
    case SurgicalInstrumentType::LargeShaver:
      return 0.5 * (p.shaftDiameter - p.windowWidth) + p.windowLength;
    case SurgicalInstrumentType::Scissors:
    case SurgicalInstrumentType::Scalpel:
      return p.bladeLength + 1.5;
  }
  return 0.0;
}

} // namespace

// ---------------------------------------------------------------------------
// Public functions
// ---------------------------------------------------------------------------

const std::array<SurgicalInstrumentType, 6>& allSurgicalInstrumentTypes()
{
  static const std::array<SurgicalInstrumentType, 6> types{ SurgicalInstrumentType::ProbeHook,
    SurgicalInstrumentType::Punch,
    SurgicalInstrumentType::SmallShaver,
    SurgicalInstrumentType::LargeShaver,
    SurgicalInstrumentType::Scissors,
    SurgicalInstrumentType::Scalpel };
  return types;
}

std::string instrumentTypeName(SurgicalInstrumentType type)
{
  switch (type)
  {
    case SurgicalInstrumentType::ProbeHook:
      return "probe_hook";
    case SurgicalInstrumentType::Punch:
      return "punch";
    case SurgicalInstrumentType::SmallShaver:
      return "small_shaver";
    case SurgicalInstrumentType::LargeShaver:
      return "large_shaver";
    case SurgicalInstrumentType::Scissors:
      return "scissors";
    case SurgicalInstrumentType::Scalpel:
      return "scalpel";
  }
  throw InvalidInputError(
    "surgical instrument type " + std::to_string(static_cast<int>(type)) + " is not defined");
}

SurgicalInstrumentType parseSurgicalInstrumentType(const std::string& name)
{
  const std::string wanted = normalizedName(name);
  std::string valid;
  for (const SurgicalInstrumentType type : allSurgicalInstrumentTypes())
  {
    const std::string candidate = instrumentTypeName(type);
    if (normalizedName(candidate) == wanted)
    {
      return type;
    }
    valid += (valid.empty() ? "" : ", ") + candidate;
  }
  throw InvalidInputError(
    "unknown surgical instrument '" + name + "'; valid instruments are " + valid);
}

SurgicalInstrumentParameters defaultInstrumentParameters(SurgicalInstrumentType type)
{
  SurgicalInstrumentParameters p;
  p.type = type;
  switch (type)
  {
    case SurgicalInstrumentType::ProbeHook:
      p.shaftDiameter = 3.0;
      p.shaftLength = 120.0;
      p.handleDiameter = 10.0;
      p.handleLength = 100.0;
      p.hookLength = 3.0;
      p.hookDiameter = 1.5;
      break;
    case SurgicalInstrumentType::Punch:
      p.shaftDiameter = 3.4;
      p.shaftLength = 130.0;
      p.handleDiameter = 10.0;
      p.handleLength = 35.0;
      p.biteLength = 3.5;
      p.biteWidth = 2.0;
      p.jawThickness = 0.8;
      p.jawOpeningDegrees = 30.0;
      break;
    case SurgicalInstrumentType::SmallShaver:
      p.shaftDiameter = 3.5;
      p.shaftLength = 120.0;
      p.handleDiameter = 24.0;
      p.handleLength = 150.0;
      p.windowLength = 4.0;
      p.windowWidth = 2.6;
      break;
    case SurgicalInstrumentType::LargeShaver:
      p.shaftDiameter = 5.5;
      p.shaftLength = 120.0;
      p.handleDiameter = 24.0;
      p.handleLength = 150.0;
      p.windowLength = 6.0;
      p.windowWidth = 4.2;
      break;
    case SurgicalInstrumentType::Scissors:
      p.shaftDiameter = 3.4;
      p.shaftLength = 130.0;
      p.handleDiameter = 10.0;
      p.handleLength = 35.0;
      p.bladeLength = 5.0;
      p.bladeWidth = 1.3;
      p.bladeThickness = 0.5;
      p.jawOpeningDegrees = 25.0;
      break;
    case SurgicalInstrumentType::Scalpel:
      p.shaftDiameter = 3.0;
      p.shaftLength = 120.0;
      p.handleDiameter = 10.0;
      p.handleLength = 100.0;
      p.bladeLength = 7.0;
      p.bladeWidth = 2.4;
      p.bladeThickness = 0.4;
      break;
  }
  return p;
}

void checkInstrumentParameters(const SurgicalInstrumentParameters& p)
{
  const auto& types = allSurgicalInstrumentTypes();
  if (std::find(types.begin(), types.end(), p.type) == types.end())
  {
    throw InvalidInputError(
      "surgical instrument: type " + std::to_string(static_cast<int>(p.type)) + " is not defined");
  }
  const ParameterChecker check(instrumentTypeName(p.type));
  check.positive("shaftDiameter", p.shaftDiameter);
  check.positive("shaftLength", p.shaftLength);
  check.positive("handleDiameter", p.handleDiameter);
  check.positive("handleLength", p.handleLength);
  if (p.segmentsAround < 8 || p.segmentsAround > 256)
  {
    check.fail(
      "segmentsAround", "must lie in [8, 256] (got " + std::to_string(p.segmentsAround) + ")");
  }
  if (p.handleDiameter < p.shaftDiameter)
  {
    check.fail("handleDiameter",
      "(" + formatNumber(p.handleDiameter) + ") must be at least shaftDiameter (" +
        formatNumber(p.shaftDiameter) + ")");
  }
  const double R = 0.5 * p.shaftDiameter;
  switch (p.type)
  {
    case SurgicalInstrumentType::ProbeHook:
      check.positive("hookDiameter", p.hookDiameter);
      check.positive("hookLength", p.hookLength);
      if (p.hookDiameter > p.shaftDiameter)
      {
        check.fail("hookDiameter",
          "(" + formatNumber(p.hookDiameter) + ") must not exceed shaftDiameter (" +
            formatNumber(p.shaftDiameter) + ")");
      }
      if (p.hookLength < 1.5 * p.hookDiameter)
      {
        check.fail("hookLength",
          "(" + formatNumber(p.hookLength) + ") must be at least 1.5 x hookDiameter (" +
            formatNumber(1.5 * p.hookDiameter) + ") to leave room for the bend");
      }
      break;
    case SurgicalInstrumentType::Punch:
      check.positive("biteLength", p.biteLength);
      check.positive("biteWidth", p.biteWidth);
      check.positive("jawThickness", p.jawThickness);
      check.inRange("jawOpeningDegrees", p.jawOpeningDegrees, 0.0, 60.0);
      if (p.biteLength < p.biteWidth)
      {
        check.fail("biteLength",
          "(" + formatNumber(p.biteLength) + ") must be at least biteWidth (" +
            formatNumber(p.biteWidth) + ")");
      }
      if (std::hypot(0.7 * p.biteWidth, p.jawThickness) > R)
      {
        check.fail("biteWidth",
          "(" + formatNumber(p.biteWidth) + ") and jawThickness (" + formatNumber(p.jawThickness) +
            ") give jaws wider than the shaft (diameter " + formatNumber(p.shaftDiameter) +
            "; the jaw frame is 1.4 x biteWidth wide)");
      }
      break;
    case SurgicalInstrumentType::SmallShaver:
    case SurgicalInstrumentType::LargeShaver:
      check.positive("windowLength", p.windowLength);
      check.positive("windowWidth", p.windowWidth);
      if (p.windowWidth > 0.95 * p.shaftDiameter)
      {
        check.fail("windowWidth",
          "(" + formatNumber(p.windowWidth) + ") must not exceed 0.95 x shaftDiameter (" +
            formatNumber(0.95 * p.shaftDiameter) + ")");
      }
      if (p.windowLength < p.windowWidth)
      {
        check.fail("windowLength",
          "(" + formatNumber(p.windowLength) + ") must be at least windowWidth (" +
            formatNumber(p.windowWidth) + ")");
      }
      break;
    case SurgicalInstrumentType::Scissors:
      check.positive("bladeLength", p.bladeLength);
      check.positive("bladeWidth", p.bladeWidth);
      check.positive("bladeThickness", p.bladeThickness);
      check.inRange("jawOpeningDegrees", p.jawOpeningDegrees, 0.0, 60.0);
      if (std::hypot(p.bladeWidth, p.bladeThickness) > R)
      {
        check.fail("bladeWidth",
          "(" + formatNumber(p.bladeWidth) + ") and bladeThickness (" +
            formatNumber(p.bladeThickness) +
            ") give closed blades wider than the shaft (diameter " + formatNumber(p.shaftDiameter) +
            ")");
      }
      break;
    case SurgicalInstrumentType::Scalpel:
      check.positive("bladeLength", p.bladeLength);
      check.positive("bladeWidth", p.bladeWidth);
      check.positive("bladeThickness", p.bladeThickness);
      if (p.bladeWidth > p.shaftDiameter)
      {
        check.fail("bladeWidth",
          "(" + formatNumber(p.bladeWidth) + ") must not exceed shaftDiameter (" +
            formatNumber(p.shaftDiameter) + ")");
      }
      if (p.bladeThickness > 0.5 * p.bladeWidth)
      {
        check.fail("bladeThickness",
          "(" + formatNumber(p.bladeThickness) + ") must not exceed half the bladeWidth (" +
            formatNumber(0.5 * p.bladeWidth) + ")");
      }
      break;
  }
  const double working = workingLength(p);
  if (p.shaftLength < working + 5.0)
  {
    check.fail("shaftLength",
      "(" + formatNumber(p.shaftLength) + ") must exceed the working tip length (" +
        formatNumber(working) + ") by at least 5 mm");
  }
}

double CollisionSegment::distanceToCentreLine(const Vector3& point) const
{
  const Vector3 direction = end - start;
  const double lengthSquared = direction.squaredNorm();
  double t = 0.0;
  if (lengthSquared > 0.0)
  {
    t = std::clamp((point - start).dot(direction) / lengthSquared, 0.0, 1.0);
  }
  return (point - (start + t * direction)).norm();
}

SurgicalInstrumentModel makeSurgicalInstrument(const SurgicalInstrumentParameters& parameters)
{
  checkInstrumentParameters(parameters);
  SurgicalInstrumentModel model;
  model.name = instrumentTypeName(parameters.type);
  model.type = parameters.type;
  model.parameters = parameters;
  model.shaftRadius = 0.5 * parameters.shaftDiameter;
  switch (parameters.type)
  {
    case SurgicalInstrumentType::ProbeHook:
      buildProbeHook(parameters, model);
      break;
    case SurgicalInstrumentType::Punch:
      buildPunch(parameters, model);
      break;
    case SurgicalInstrumentType::SmallShaver:
    case SurgicalInstrumentType::LargeShaver:
      buildShaver(parameters, model);
      break;
    case SurgicalInstrumentType::Scissors:
      buildScissors(parameters, model);
      break;
    case SurgicalInstrumentType::Scalpel:
      buildScalpel(parameters, model);
      break;
  }
  model.visual.name = model.name;
  model.tip = Vector3::Zero();
  model.frame = ToolFrame{};
  return model;
}

SurgicalInstrumentModel makeSurgicalInstrument(SurgicalInstrumentType type)
{
  return makeSurgicalInstrument(defaultInstrumentParameters(type));
}

SurgicalInstrumentModel transformedInstrument(const SurgicalInstrumentModel& model,
  const Eigen::Isometry3d& pose)
{
  SurgicalInstrumentModel result = model;
  const Eigen::Matrix3d rotation = pose.linear();
  for (Vector3& p : result.visual.positions)
  {
    p = pose * p;
  }
  for (Vector3& n : result.visual.normals)
  {
    n = rotation * n;
  }
  for (CollisionSegment& segment : result.centreLine)
  {
    segment.start = pose * segment.start;
    segment.end = pose * segment.end;
  }
  for (auto* polyline : { &result.cuttingEdge, &result.opposingCuttingEdge, &result.biteOutline })
  {
    for (Vector3& p : *polyline)
    {
      p = pose * p;
    }
  }
  result.tip = pose * model.tip;
  result.frame.origin = pose * model.frame.origin;
  result.frame.handleAxis = rotation * model.frame.handleAxis;
  result.frame.up = rotation * model.frame.up;
  return result;
}

// ---------------------------------------------------------------------------
// Arthroscope
// ---------------------------------------------------------------------------

Vector3 ArthroscopeCamera::scopeAxis() const
{
  return -handleAxis.normalized();
}

Vector3 ArthroscopeCamera::tiltDirection() const
{
  const Vector3 axis = scopeAxis();
  const Vector3 up = (imageUp - imageUp.dot(axis) * axis).normalized();
  return Eigen::AngleAxisd(radians(opticsRotationDegrees), axis) * up;
}

Vector3 ArthroscopeCamera::lightPostDirection() const
{
  return -tiltDirection();
}

Vector3 ArthroscopeCamera::viewDirection() const
{
  const double angle = radians(opticsAngleDegrees);
  return (std::cos(angle) * scopeAxis() + std::sin(angle) * tiltDirection()).normalized();
}

Vector3 ArthroscopeCamera::viewUp() const
{
  const Vector3 axis = scopeAxis();
  const Vector3 up = (imageUp - imageUp.dot(axis) * axis).normalized();
  const Vector3 view = viewDirection();
  return (up - up.dot(view) * view).normalized();
}

Vector3 ArthroscopeCamera::focalPoint(double distance) const
{
  return tip + distance * viewDirection();
}

void ArthroscopeCamera::rotateOptics(double degrees)
{
  double angle = std::fmod(opticsRotationDegrees + degrees + 180.0, 360.0);
  if (angle <= 0.0)
  {
    angle += 360.0;
  }
  opticsRotationDegrees = angle - 180.0;
}

void ArthroscopeCamera::check() const
{
  const auto fail = [](const std::string& field, const std::string& problem)
  { throw InvalidInputError("arthroscope camera: " + field + " " + problem); };
  if (!tip.allFinite())
  {
    fail("tip", "must be finite");
  }
  if (!handleAxis.allFinite() || handleAxis.norm() < 1e-12)
  {
    fail("handleAxis", "must be a finite non-zero direction");
  }
  if (!imageUp.allFinite() || imageUp.norm() < 1e-12)
  {
    fail("imageUp", "must be a finite non-zero direction");
  }
  if (handleAxis.normalized().cross(imageUp.normalized()).norm() < 1e-6)
  {
    fail("imageUp", "must not be parallel to handleAxis");
  }
  if (!(opticsAngleDegrees >= 0.0 && opticsAngleDegrees < 90.0))
  {
    fail(
      "opticsAngleDegrees", "must lie in [0, 90) (got " + formatNumber(opticsAngleDegrees) + ")");
  }
  if (!std::isfinite(opticsRotationDegrees))
  {
    fail("opticsRotationDegrees", "must be finite");
  }
  if (!(fieldOfViewDegrees > 0.0 && fieldOfViewDegrees < 180.0))
  {
    fail(
      "fieldOfViewDegrees", "must lie in (0, 180) (got " + formatNumber(fieldOfViewDegrees) + ")");
  }
  if (!(nearClipDistance > 0.0 && std::isfinite(nearClipDistance)))
  {
    fail("nearClipDistance", "must be positive (got " + formatNumber(nearClipDistance) + ")");
  }
  if (!(farClipDistance > nearClipDistance && std::isfinite(farClipDistance)))
  {
    fail("farClipDistance",
      "(" + formatNumber(farClipDistance) + ") must exceed nearClipDistance (" +
        formatNumber(nearClipDistance) + ")");
  }
  if (!(scopeDiameter > 0.0 && std::isfinite(scopeDiameter)))
  {
    fail("scopeDiameter", "must be positive (got " + formatNumber(scopeDiameter) + ")");
  }
  if (!(sheathDiameter >= scopeDiameter && std::isfinite(sheathDiameter)))
  {
    fail("sheathDiameter",
      "(" + formatNumber(sheathDiameter) + ") must be at least scopeDiameter (" +
        formatNumber(scopeDiameter) + ")");
  }
  if (!(scopeLength > 0.0 && std::isfinite(scopeLength)))
  {
    fail("scopeLength", "must be positive (got " + formatNumber(scopeLength) + ")");
  }
}

ArthroscopeCamera defaultArthroscopeCamera()
{
  return ArthroscopeCamera{};
}

} // namespace thintissue
