// Procedural arthroscopic instruments and the arthroscope camera (thesis
// ch. 6: probe hook for palpation, basket punch for torn meniscus tissue,
// small shaver for contouring, large shaver for removing pieces, scissors
// and knife for cutting).
//
// Each instrument has three descriptions that agree by construction:
// - a visual mesh: closed, outward, 2-manifold triangle pieces with normals;
// - collision primitives: the centre line as capsules (segment + radius).
//   The thesis replaces the tool's collision mesh by its centre line with a
//   collision distance (section 6.3, table 6-2 "Tool 7 DOFs"); the radius of
//   each segment is chosen so that the capsules contain the visual mesh
//   between the tip and the handle;
// - working features: the tip point, the cutting edge of a blade, the bite
//   outline of a punch jaw or shaver window.
//
// Tool frame (millimetres): the tip is at the origin, the shaft runs along +z
// toward the handle (handle axis = +z), and the working part faces +x (the
// "up" direction: where the hook points, the punch and scissors open, the
// knife's edge and the shaver's window face). +y = handle axis x up.
#ifndef SurgicalInstruments_h
#define SurgicalInstruments_h

#include "ThinTissueModelsModule.h"
#include "TriangleMesh.h"

#include <array>
#include <string>
#include <vector>

namespace thintissue
{

enum class SurgicalInstrumentType
{
  ProbeHook,
  Punch, ///< basket forceps
  SmallShaver,
  LargeShaver,
  Scissors,
  Scalpel ///< arthroscopic knife
};

/// The six types, in declaration order.
THINTISSUEMODELS_EXPORT const std::array<SurgicalInstrumentType, 6>& allSurgicalInstrumentTypes();

/// "probe_hook", "punch", "small_shaver", "large_shaver", "scissors", "scalpel".
THINTISSUEMODELS_EXPORT std::string instrumentTypeName(SurgicalInstrumentType type);

/// Inverse of instrumentTypeName. Case, '_', '-' and spaces are ignored, so
/// "ProbeHook", "probe hook" and "PROBE_HOOK" all parse. Throws
/// InvalidInputError listing the valid names on anything else.
THINTISSUEMODELS_EXPORT SurgicalInstrumentType parseSurgicalInstrumentType(const std::string& name);

/// Dimensions in millimetres. Only the fields of the instrument's type are
/// used (and checked); the others are ignored.
struct SurgicalInstrumentParameters
{
  SurgicalInstrumentType type = SurgicalInstrumentType::ProbeHook;

  // Every instrument.
  double shaftDiameter = 3.0;
  /// From the tip plane (z = 0) to the start of the handle.
  double shaftLength = 120.0;
  /// Pen handle (probe, knife), grip body (punch, scissors; finger rings
  /// added), or hub and motor handpiece (shavers).
  double handleDiameter = 10.0;
  double handleLength = 100.0;
  /// Vertices around every round cross-section; 8 to 256.
  int segmentsAround = 24;

  // Probe hook: a thinner rod bent 90 degrees at the end of the tapered shaft.
  /// From the shaft axis to the far end of the hook (the measuring length).
  double hookLength = 3.0;
  double hookDiameter = 1.5;

  // Punch: a fixed lower jaw with a through hole (the basket) and a moving
  // upper jaw hinged at the shaft end.
  /// Size of the hole the punched piece goes through (along z, along y).
  double biteLength = 3.5;
  double biteWidth = 2.0;
  /// Thickness of each jaw (along x).
  double jawThickness = 0.8;
  /// Opening of the moving jaw or blade (punch, scissors); 0 = closed, at most 60.
  double jawOpeningDegrees = 30.0;

  // Shavers: a window on the +x side of the rounded tube end, cut by a plane
  // parallel to the axis, showing the inner cutter.
  /// From the distal end of the window to its proximal end, along z.
  double windowLength = 4.0;
  /// Width of the window across the tube (along y).
  double windowWidth = 2.6;

  // Scissors (two blades, each of this size) and scalpel (one spear-point blade).
  /// From the blade point to the shaft end.
  double bladeLength = 7.0;
  /// Scissors: each blade from edge to back; scalpel: the whole blade.
  double bladeWidth = 2.4;
  double bladeThickness = 0.4;
};

/// Typical arthroscopic dimensions for `type`:
/// - probe hook: 3 mm shaft, 120 mm long, 3 mm hook of 1.5 mm rod, pen handle 10 x 100;
/// - punch: 3.4 mm shaft, 130 mm, bite 3.5 x 2 mm, jaws 0.8 mm thick, open 30 degrees;
/// - small shaver: 3.5 mm tube, 120 mm, window 4 x 2.6 mm, handpiece 24 x 150;
/// - large shaver: 5.5 mm tube, 120 mm, window 6 x 4.2 mm, handpiece 24 x 150;
/// - scissors: 3.4 mm shaft, 130 mm, blades 5 x 1.3 x 0.5 mm, open 25 degrees;
/// - scalpel: 3 mm shaft, 120 mm, blade 7 x 2.4 x 0.4 mm, pen handle 10 x 100.
THINTISSUEMODELS_EXPORT SurgicalInstrumentParameters defaultInstrumentParameters(
  SurgicalInstrumentType type);

/// Throws InvalidInputError naming the instrument and the parameter, e.g.
/// "surgical instrument 'punch': biteWidth must be positive (got -1)".
THINTISSUEMODELS_EXPORT void checkInstrumentParameters(const SurgicalInstrumentParameters& p);

/// One capsule of the centre line: every point within `radius` of the
/// segment [start, end].
struct THINTISSUEMODELS_EXPORT CollisionSegment
{
  Vector3 start = Vector3::Zero();
  Vector3 end = Vector3::Zero();
  double radius = 0.0;
  /// "shaft", "hook", "bend", "fixed jaw", "moving jaw", "fixed blade",
  /// "moving blade" or "blade".
  std::string part;

  /// Distance from `point` to the segment (not to the capsule surface).
  double distanceToCentreLine(const Vector3& point) const;
};

/// Orthonormal, right-handed tool frame: (up, side(), handleAxis).
struct ToolFrame
{
  Vector3 origin = Vector3::Zero();
  /// Unit, from the tip toward the handle.
  Vector3 handleAxis = Vector3::UnitZ();
  /// Unit, perpendicular to handleAxis: the side the working part faces.
  Vector3 up = Vector3::UnitX();

  Vector3 side() const { return handleAxis.cross(up); }
  /// Columns up, side, handleAxis: maps tool coordinates to this frame.
  Eigen::Matrix3d rotation() const
  {
    Eigen::Matrix3d r;
    r.col(0) = up;
    r.col(1) = side();
    r.col(2) = handleAxis;
    return r;
  }
};

/// Per-vertex array of the visual mesh saying which part a vertex belongs
/// to (for materials: metal shaft and tip, plastic handle).
constexpr const char* InstrumentPartArrayName = "InstrumentPart";
enum class InstrumentPart
{
  Handle = 0,
  Shaft = 1,
  WorkingTip = 2
};

struct THINTISSUEMODELS_EXPORT SurgicalInstrumentModel
{
  std::string name;
  SurgicalInstrumentType type = SurgicalInstrumentType::ProbeHook;
  SurgicalInstrumentParameters parameters;

  /// Closed, outward, 2-manifold pieces (one per rigid part: shaft with
  /// handle, each jaw or blade, each finger ring and its shank), with vertex
  /// normals and the InstrumentPart array.
  TriangleMesh visual;
  /// Centre line from the working tip to the start of the handle; the
  /// capsules contain every visual vertex between the tip plane and the
  /// handle. The handle, outside the joint, has no collision primitive.
  std::vector<CollisionSegment> centreLine;
  /// The point that touches tissue first: probe, the underside of the hook
  /// end; punch, the distal end of the fixed jaw's cutting face; shaver, the
  /// distal pole of the tube; scissors, the point of the fixed blade;
  /// scalpel, the blade point. Equal to frame.origin; the whole visual mesh
  /// lies on the handle side of the plane through it normal to handleAxis.
  Vector3 tip = Vector3::Zero();
  /// Scissors: the fixed blade's edge, from its point to the hinge. Scalpel:
  /// the sharpened edge from the point to the shaft. Empty otherwise.
  std::vector<Vector3> cuttingEdge;
  /// Scissors: the moving blade's edge, which closes onto cuttingEdge (the
  /// surface swept between them is the cut of one stroke). Empty otherwise.
  std::vector<Vector3> opposingCuttingEdge;
  /// Closed planar polygon (last point joins the first, not repeated).
  /// Punch: the basket hole on the fixed jaw's cutting face: the piece it
  /// punches out. Shavers: the window in its cutting plane: what the inner
  /// cutter removes. Empty otherwise.
  std::vector<Vector3> biteOutline;
  ToolFrame frame;
  double shaftRadius = 0.0;
};

/// Builds the instrument in its tool frame (see the top of this file).
/// Throws InvalidInputError on bad parameters (checkInstrumentParameters).
THINTISSUEMODELS_EXPORT SurgicalInstrumentModel makeSurgicalInstrument(
  const SurgicalInstrumentParameters& parameters);

/// Shorthand for makeSurgicalInstrument(defaultInstrumentParameters(type)).
THINTISSUEMODELS_EXPORT SurgicalInstrumentModel makeSurgicalInstrument(SurgicalInstrumentType type);

/// The model moved rigidly by `pose` (tool frame -> world): visual positions
/// and normals, centre line, tip, edges, outline and frame.
THINTISSUEMODELS_EXPORT SurgicalInstrumentModel transformedInstrument(
  const SurgicalInstrumentModel& model,
  const Eigen::Isometry3d& pose);

/// A 4 mm arthroscope with angled (forward-oblique) optics. The image is
/// fixed to the camera head: `imageUp` is shown at the top of the monitor.
/// The surgeon turns the light post, which turns the optics about the scope
/// axis and sweeps the view direction around a cone of half-angle
/// opticsAngleDegrees, while the horizon stays. As on real scopes, the
/// optics look away from the light post.
struct THINTISSUEMODELS_EXPORT ArthroscopeCamera
{
  /// Centre of the lens at the distal end of the scope.
  Vector3 tip = Vector3::Zero();
  /// Unit, from the tip toward the camera head (the scope looks along -handleAxis).
  Vector3 handleAxis = Vector3::UnitZ();
  /// Unit direction perpendicular to handleAxis shown at the top of the image.
  Vector3 imageUp = Vector3::UnitX();
  /// Angle between view direction and scope axis: 30 degrees (0, 30, 45, 70 exist).
  double opticsAngleDegrees = 30.0;
  /// Rotation of the optics about the scope axis, right-handed about the
  /// viewing axis -handleAxis. At 0 the view tilts toward imageUp (light
  /// post pointing down, the usual starting position).
  double opticsRotationDegrees = 0.0;
  /// Apex angle of the circular image: 105 degrees, within the 90-115
  /// degrees that makers list for 4 mm wide-angle arthroscopes. Rendered as
  /// a vertical view angle with the image circle inscribed in the viewport.
  double fieldOfViewDegrees = 105.0;
  /// Clipping distances along the view direction (the joint is ~100 mm wide).
  double nearClipDistance = 0.5;
  double farClipDistance = 200.0;
  /// Optical tube and the sheath (cannula) around it that touches tissue.
  double scopeDiameter = 4.0;
  double sheathDiameter = 5.5;
  /// Length of the scope from tip to camera head.
  double scopeLength = 160.0;

  /// Unit axis the scope points along (-handleAxis).
  Vector3 scopeAxis() const;
  /// Unit direction perpendicular to the axis toward which the optics look
  /// (imageUp turned by opticsRotationDegrees about scopeAxis()).
  Vector3 tiltDirection() const;
  /// Unit direction of the light post: -tiltDirection().
  Vector3 lightPostDirection() const;
  /// Unit view direction, opticsAngleDegrees from scopeAxis().
  Vector3 viewDirection() const;
  /// Unit, perpendicular to viewDirection(): imageUp made orthogonal.
  Vector3 viewUp() const;
  /// tip + distance * viewDirection().
  Vector3 focalPoint(double distance) const;
  /// Turns the light post (and optics) by `degrees`; kept in (-180, 180].
  void rotateOptics(double degrees);
  /// Throws InvalidInputError naming the field: axes zero or not finite,
  /// imageUp parallel to handleAxis, angles out of range, clip distances
  /// not 0 < near < far, diameters not 0 < scope <= sheath.
  void check() const;
};

/// The 4 mm 30-degree arthroscope above, tip at the origin, looking along -z.
THINTISSUEMODELS_EXPORT ArthroscopeCamera defaultArthroscopeCamera();

} // namespace thintissue

#endif
