// The surroundings of the medial meniscus in the thesis's knee scenes:
// proximal tibia and distal femur (rigid bones, table 6-2), the medial
// tibial articular cartilage (5.4.4, fig. 5-27) and the anterior and
// posterior cruciate ligaments (5.4.3, table 5-7), all in the anatomical
// frame of KneeAnatomy.h (mm, +x lateral, +y anterior, +z proximal, origin
// at the centre of the tibial plateau on the subchondral bone).
//
// Bones are smooth implicit solids (smooth unions and subtractions of
// anatomical primitives) meshed at the requested density; their reduced
// collision meshes are coarse rings of points on the same implicit
// surface. Cartilage and ligaments are ParametricSolids, so their visual,
// collision and simulation meshes come from one description.
#ifndef KneeModels_h
#define KneeModels_h

#include "KneeAnatomy.h"
#include "ParametricSolid.h"
#include "ThinTissueModelsModule.h"
#include "TissueModel.h"
#include "TriangleMesh.h"

#include <string>

namespace thintissue
{

/// A rigid bone: fine visual surface and coarse collision surface, both
/// closed, outward, 2-manifold, genus 0. Every collision vertex lies on the
/// bone's smooth surface, which the visual surface samples.
struct THINTISSUEMODELS_EXPORT BoneModel
{
  std::string name;
  TriangleMesh visual;
  TriangleMesh collision;
};

/// Collision settings of the medial tibial cartilage (thesis 5.4.4,
/// fig. 5-27): the visual mesh itself, or mid-surfaces with radii of about
/// 1,000, 500 and 100 triangles.
enum class CartilageCollisionSetting
{
  VisualMesh = 1,
  Triangles1000 = 2,
  Triangles500 = 3,
  Triangles100 = 4
};

/// Collision settings of the cruciate ligaments (thesis table 5-7): the
/// visual mesh, closed surfaces of about 2,000 and 500 triangles, or the
/// reduced mid-surface with radii (ACL 25 v / 32 t, PCL 45 v / 64 t).
enum class LigamentCollisionSetting
{
  VisualMesh = 1,
  Triangles2000 = 2,
  Triangles500 = 3,
  ReducedWithRadii = 4
};

enum class CruciateLigament
{
  Anterior,
  Posterior
};

THINTISSUEMODELS_EXPORT const char* cruciateLigamentName(CruciateLigament ligament);

/// Resolution of one cruciate ligament (anteriorCruciateResolution and
/// posteriorCruciateResolution give the figures of table 5-7). A closed
/// genus-0 surface has V = T/2 + 2: the PCL's thesis figures (5,634 v /
/// 11,264 t) obey it exactly, the ACL's (5,702 v / 12,064 t) do not, so its
/// visual grid is chosen with both counts within 5% (5,890 v / 11,776 t).
/// The closed collision surfaces have 2,000 and 496 triangles (thesis:
/// 2,001 / 1,999 and 500 / 499; an odd count cannot close a surface).
struct LigamentResolution
{
  ParametricResolution visual{ 82, 24, 8 };
  ParametricResolution collision2000{ 39, 8, 4 };
  ParametricResolution collision500{ 14, 6, 2 };
  /// Reduced mid-surface with radii (TissueModel::collision): cells along
  /// and across (thesis: ACL 4 x 4 = 25 v / 32 t, PCL 8 x 4 = 45 v / 64 t).
  int reducedAlong = 4;
  int reducedAcross = 4;
  /// Hexahedra (simulation mesh).
  ParametricResolution hexahedra{ 8, 2, 1 };
};

/// Table 5-7 for the ACL: visual 86 x 24 x 8 cells (5,890 v / 11,776 t),
/// reduced mid-surface 4 x 4 cells (25 v / 32 t).
inline LigamentResolution anteriorCruciateResolution()
{
  LigamentResolution resolution;
  resolution.visual = { 86, 24, 8 };
  resolution.reducedAlong = 4;
  resolution.reducedAcross = 4;
  return resolution;
}

/// Table 5-7 for the PCL: visual 82 x 24 x 8 cells (5,634 v / 11,264 t),
/// reduced mid-surface 8 x 4 cells (45 v / 64 t).
inline LigamentResolution posteriorCruciateResolution()
{
  LigamentResolution resolution;
  resolution.visual = { 82, 24, 8 };
  resolution.reducedAlong = 8;
  resolution.reducedAcross = 4;
  return resolution;
}

struct KneeSurroundingsParameters
{
  /// Distance between tibial and femoral cartilage at the compartment
  /// centres (mm); the femur and the ligaments' femoral ends follow it.
  double jointGap = knee::DefaultJointGap;

  /// Target visual vertex counts of the bones (table 6-2: lower bone 2,206,
  /// upper bone 5,850). The mesher picks the density that comes nearest.
  int tibiaVisualVertices = 2206;
  int femurVisualVertices = 5850;
  /// Reduced collision meshes: `rings` x `sectors` + 2 poles (table 6-2:
  /// 63 and 59 vertices; defaults give 62 and 58).
  int tibiaCollisionRings = 6;
  int tibiaCollisionSectors = 10;
  int femurCollisionRings = 7;
  int femurCollisionSectors = 8;

  /// Medial tibial cartilage: visual cells (5.4.4: 5,062 triangles; the
  /// defaults give 5,080), collision grids of the three reduced settings
  /// (mid-surfaces: `through` is not used; 1,000 / 494 / 100 triangles),
  /// hexahedra, and the setting stored in TissueModel::collision.
  ParametricResolution cartilageVisual{ 40, 30, 1 };
  ParametricResolution cartilageCollision1000{ 25, 20, 1 };
  ParametricResolution cartilageCollision500{ 19, 13, 1 };
  ParametricResolution cartilageCollision100{ 10, 5, 1 };
  ParametricResolution cartilageHexahedra{ 6, 4, 1 };
  CartilageCollisionSetting cartilageCollisionSetting = CartilageCollisionSetting::Triangles100;

  LigamentResolution anteriorCruciate = anteriorCruciateResolution();
  LigamentResolution posteriorCruciate = posteriorCruciateResolution();

  /// Texture coordinates are model units divided by this (mm).
  double textureScale = 10.0;
};

/// Throws InvalidInputError naming the first bad parameter: joint gap outside
/// [0.5, 12] mm (closed joint or torn ligaments), vertex targets below 200,
/// collision rings below 3 or sectors below 4, cells below 1 (ligament
/// visual grids need across >= 2 and through >= 2), non-positive texture
/// scale, or an unknown collision setting.
THINTISSUEMODELS_EXPORT void validateKneeSurroundingsParameters(
  const KneeSurroundingsParameters& parameters);

/// Height of the subchondral tibial plateau surface at (x, y) (the bone top
/// of the tibia where it is not a side wall): 0 at the compartment centres,
/// concave medially, convex laterally, two tibial spines near x = 0.
THINTISSUEMODELS_EXPORT double tibialPlateauHeight(double x, double y);

/// Height over the compartment centres of the femur's lowest points. The
/// femur's visual surface includes the femoral articular cartilage (it is
/// not a separate tissue), so this is TibialCartilageThickness + jointGap;
/// the subchondral bone lies FemoralCartilageThickness higher.
THINTISSUEMODELS_EXPORT double femoralArticularHeight(double jointGap);

/// Proximal tibia: plateau about 76 mm (medial-lateral) by 50 mm
/// (anterior-posterior), concave medial and convex lateral compartment
/// around the compartment centres, intercondylar eminence with two spines,
/// posterior intercondylar area sloping down to the PCL facet, metaphysis
/// narrowing into the shaft, tibial tuberosity, cut 60 mm below the plateau.
THINTISSUEMODELS_EXPORT BoneModel makeTibia(const KneeSurroundingsParameters& parameters);

/// Distal femur: medial and lateral condyles (sagittal radius 22 mm,
/// 25 mm wide) over the compartments, the intercondylar notch between them
/// (19.6 mm wide, its roof rising posteriorly), the trochlear groove in
/// front, epicondyles, metaphysis and the shaft up to 85 mm above the
/// condyles. Lowest points at femoralArticularHeight(jointGap).
THINTISSUEMODELS_EXPORT BoneModel makeFemur(const KneeSurroundingsParameters& parameters);

/// Medial tibial articular cartilage on the plateau, under and inside the
/// medial meniscus. Parameter axes: s posterior to anterior, u from the
/// intercondylar side to the medial side, w from the bone (w = 0, lying on
/// the tibia) to the joint surface. About 2 mm thick at the centre,
/// thinner under the meniscus so that its top stays below the meniscus's
/// base (MeniscusBaseHeight).
THINTISSUEMODELS_EXPORT ParametricSolid makeTibialCartilageSolid(
  const KneeSurroundingsParameters& parameters);

/// The cartilage as a tissue: the visual surface, the collision mid-surface
/// of `parameters.cartilageCollisionSetting` (the visual mesh itself for
/// VisualMesh), hexahedra with the nodes on the bone side fixed.
THINTISSUEMODELS_EXPORT TissueModel makeTibialCartilage(
  const KneeSurroundingsParameters& parameters);

/// The cartilage collision mesh of one setting: the closed visual surface
/// for VisualMesh (with "Radius" 0: contact on the surface itself),
/// otherwise a mid-surface with "Radius" = half the local thickness.
THINTISSUEMODELS_EXPORT TriangleMesh tibialCartilageCollisionMesh(
  const KneeSurroundingsParameters& parameters,
  CartilageCollisionSetting setting);

/// Centre of a ligament's attachment: s = 0 on the tibia, s = 1 on the
/// femur (both inside the bone: the insertions).
THINTISSUEMODELS_EXPORT Vector3 cruciateLigamentAttachment(CruciateLigament ligament,
  double s,
  const KneeSurroundingsParameters& parameters);

/// A cruciate ligament as a flattened elliptic band along a curved,
/// slightly twisted course. s runs from the tibial insertion (s = 0) to the
/// femoral insertion (s = 1), u across the band's width, w through its
/// thickness. ACL: from the anterior intercondylar area up and back to the
/// medial wall of the lateral condyle, posteriorly. PCL: from the posterior
/// intercondylar area below the plateau up and forward to the lateral wall
/// of the medial condyle, anteriorly. They cross in the notch without
/// touching.
THINTISSUEMODELS_EXPORT ParametricSolid makeCruciateLigamentSolid(CruciateLigament ligament,
  const KneeSurroundingsParameters& parameters);

/// The ligament as a tissue: visual surface, reduced collision mid-surface
/// with radii (setting 4), hexahedra fixed at both insertions (s = 0, 1).
THINTISSUEMODELS_EXPORT TissueModel makeCruciateLigament(CruciateLigament ligament,
  const KneeSurroundingsParameters& parameters);

/// The ligament's collision mesh of one setting of table 5-7: closed
/// surfaces for settings 1 to 3 (setting 1 is the visual surface; "Radius"
/// 0 on every vertex), the reduced mid-surface with "Radius" = half the
/// local thickness for setting 4. Throws InvalidInputError on an unknown
/// setting.
THINTISSUEMODELS_EXPORT TriangleMesh cruciateLigamentCollisionMesh(CruciateLigament ligament,
  LigamentCollisionSetting setting,
  const KneeSurroundingsParameters& parameters);

/// Everything around the medial meniscus (the meniscus itself comes from
/// makeMeniscus()).
struct THINTISSUEMODELS_EXPORT KneeSurroundings
{
  BoneModel tibia;
  BoneModel femur;
  TissueModel tibialCartilage;
  TissueModel anteriorCruciateLigament;
  TissueModel posteriorCruciateLigament;
};

/// Validates the parameters (see validateKneeSurroundingsParameters) and
/// builds the scene. Deterministic.
THINTISSUEMODELS_EXPORT KneeSurroundings makeKneeSurroundings(
  const KneeSurroundingsParameters& parameters = KneeSurroundingsParameters());

} // namespace thintissue

#endif
