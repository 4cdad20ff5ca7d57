// The medial meniscus of the thesis's knee scenes (chapter 4, section 6.4):
// a C-shaped wedge on the medial tibial plateau, horns attached to the bone,
// intact or with one of the four common tears, and the monitor and region
// data points along its inner border that drive the wrinkles (4.3,
// fig. 4-5 to 4-7).
//
// Parameter axes (see ParametricSolid): s runs along the C from the
// posterior horn (s = 0) to the anterior horn (s = 1), u across it from the
// thin inner edge (u = 0) to the thick outer rim (u = 1), w from the tibial
// (lower) surface to the femoral (upper) surface.
#ifndef MeniscusModel_h
#define MeniscusModel_h

#include "ParametricSolid.h"
#include "ThinTissueModelsModule.h"
#include "TissueModel.h"

#include <string>
#include <vector>

namespace thintissue
{

enum class MeniscusTearType
{
  None,
  /// Longitudinal (vertical, circumferential) tear through the whole
  /// thickness; long enough, its inner fragment is a bucket handle.
  Longitudinal,
  /// Radial tear from the inner edge toward the rim.
  Radial,
  /// Flap: a radial tear turning longitudinal, freeing a tongue of tissue
  /// attached at one end.
  Flap,
  /// Horizontal cleavage splitting upper and lower leaves from the inner edge.
  HorizontalCleavage
};

THINTISSUEMODELS_EXPORT const char* meniscusTearTypeName(MeniscusTearType type);
/// Throws InvalidInputError listing the valid names.
THINTISSUEMODELS_EXPORT MeniscusTearType meniscusTearTypeFromName(const std::string& name);

/// Where a tear lies, in parameter coordinates (see the file comment).
struct MeniscusTear
{
  MeniscusTearType type = MeniscusTearType::None;
  /// Along the C: where the tear starts and ends (Longitudinal, Flap,
  /// HorizontalCleavage) or where it is (Radial: `alongBegin`).
  double alongBegin = 0.3;
  double alongEnd = 0.75;
  /// Across: the longitudinal line (Longitudinal, Flap) or how far the tear
  /// reaches from the inner edge (Radial, HorizontalCleavage).
  double across = 0.4;
  /// Widest gap between the lips, millimetres.
  double opening = 0.8;
};

/// A typical tear of each type: a bucket handle through the body, a radial
/// tear in the posterior body, a flap, a posterior horizontal cleavage.
THINTISSUEMODELS_EXPORT MeniscusTear defaultMeniscusTear(MeniscusTearType type);

struct MeniscusParameters
{
  /// Outer rim: ellipse semi-axes (medial-lateral, anterior-posterior), mm.
  double outerSemiAxisX = 13.5;
  double outerSemiAxisY = 21.0;
  /// Inner edge: ellipse semi-axes and offset of its centre from the rim's.
  double innerSemiAxisX = 6.0;
  double innerSemiAxisY = 12.0;
  double innerCentreOffsetX = 1.5;
  double innerCentreOffsetY = 2.5;
  /// Angles (degrees, from +x = lateral, counter-clockwise seen from above)
  /// of the horn ends; the C opens toward the intercondylar eminence.
  double posteriorHornAngle = -35.0;
  double anteriorHornAngle = 35.0;
  /// Heights: outer rim in the body, at the horn ends, and the inner edge.
  double rimHeight = 7.0;
  double hornHeight = 4.0;
  double innerEdgeHeight = 1.0;
  /// Where the compartment is: rim centre on the plateau and base height.
  Vector3 centre = Vector3(-22.0, 0.0, 2.0);

  /// Visual cells (thesis 6.4.2: 2,882 v / 5,760 t).
  int visualAlong = 142;
  int visualAcross = 8;
  int visualThrough = 2;
  /// Collision grid (thesis: 105 v / 160 t).
  int collisionAlong = 20;
  int collisionAcross = 4;
  /// Hexahedra (thesis: 42 hexahedra, 120 nodes).
  int hexahedraAlong = 14;
  int hexahedraAcross = 3;
  int hexahedraThrough = 1;
  /// Hexahedron nodes within this fraction of s from either end are fixed
  /// (the horns' bony attachments, "roots").
  double hornAttachment = 0.04;

  MeniscusTear tear;

  /// Monitor/region data point pairs per 10 mm of inner border.
  double monitorDataPointsPerCentimetre = 2.0;
  /// Depth of the region data points from the inner edge, mm.
  double regionDepth = 4.0;
  /// Monitor data points lie this far inside the inner edge, mm.
  double monitorInset = 0.5;

  double textureScale = 10.0;
};

/// The 6,096-face variant of section 6.4.1 (meniscus examination).
THINTISSUEMODELS_EXPORT MeniscusParameters examinationMeniscusParameters(
  MeniscusParameters parameters = {});

/// Monitor data points along a free border, each with its region data point
/// (inside the meniscus, mid-way between upper and lower surface) and the
/// thickness sampled at the monitor point (thesis 4.3, step one).
struct MonitorCurve
{
  std::string name;
  std::vector<Vector3> monitorPoints;
  std::vector<Vector3> regionPoints;
  std::vector<double> thickness;
  /// Parameter points of the monitor points (for dense re-sampling).
  std::vector<ParameterPoint> monitorParameters;
  std::vector<ParameterPoint> regionParameters;
  /// Sides of the cracks the curve's tissue lies on (see openedPoint).
  std::vector<int> crackSides;
};

struct THINTISSUEMODELS_EXPORT MeniscusModel : TissueModel
{
  MeniscusTear tear;
  /// Intact: one curve along the inner edge. Torn: the inner border broken
  /// at the tear, plus the new free lips the tear creates.
  std::vector<MonitorCurve> monitorCurves;
};

/// The meniscus as a parametric solid (with the tear as cracks).
THINTISSUEMODELS_EXPORT ParametricSolid makeMeniscusSolid(const MeniscusParameters& parameters);

/// Throws InvalidInputError on non-positive sizes, inner edge outside the
/// rim, heights inconsistent (inner edge not thinner than the rim),
/// resolutions below the minimum or a tear outside the meniscus.
THINTISSUEMODELS_EXPORT MeniscusModel makeMeniscus(const MeniscusParameters& parameters = {});

/// Monitor and region points re-sampled densely on the exact curves so that
/// consecutive monitor points are at most `maxSpacing` apart (thesis 4.3,
/// steps two and three; fig. 4-7).
THINTISSUEMODELS_EXPORT std::vector<MonitorCurve> sampleMonitorCurves(
  const MeniscusParameters& parameters,
  const std::vector<MonitorCurve>& dataCurves,
  double maxSpacing);

} // namespace thintissue

#endif
