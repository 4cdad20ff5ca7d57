// Procedural wrinkles of a thin border from embedded monitor points
// (thesis 4.4): each physics step, after the hexahedra moved and before the
// visual surface is drawn,
//  1. the monitor points follow the hexahedra (formula 4-1);
//  2. the reference configuration of the wrinkles (4.4.1): around the
//     monitor point nearest the instrument's contact, the window
//     i_s..i_e; when the lower surface touches more than N_s times, the
//     instrument touches and most window points reverse (V^c . V^l < 0 more
//     than N_c times), the previous monitor points become the reference
//     P^w0; it is cleared when the lower-surface contacts fall below N_e and
//     the instrument has left;
//  3. while there is a reference, the wrinkle points of formula 4-16,
//     P^wc_k = P^w0_k + W(k) (P^mc_k - P^w0_k) / |P^mc_k - P^w0_k|
//     (WrinkleAnchor::Reference; by default the offset is added to P^mc_k
//     instead, see WrinkleAnchor), with
//     W(k) = D(k) M(k), D(k) = sin(theta_k) over the reference's chord
//     length (0 to theta^d), M(k) = delta(k) eta(s m^d), m^d the mean of the
//     largest and smallest |P^mc_k - P^w0_k|, eta clamping to m^up, delta
//     the thickness ratio t_k (0 below the cut-off thickness r^c);
//  4. the monitor displacements P^wc_k - P^mc_k reach the surface points
//     they affect (WrinkleInfluence, Gaussian attenuation).
// Only the affected surface points of the window move; a step costs the
// monitor points and those surface points, not the mesh.
#ifndef WrinkleGenerator_h
#define WrinkleGenerator_h

#include "HexahedralEmbedding.h"
#include "MonitorCurves.h"
#include "ThinTissueWrinklesModule.h"
#include "WrinkleInfluence.h"

#include <cmath>
#include <vector>

namespace thintissue
{

class CollisionScene;
class TissueCutter;
struct TissueCutReport;

/// Where the wrinkle offset W(k) (P^mc - P^w0) / |P^mc - P^w0| is added.
enum class WrinkleAnchor
{
  /// To the current monitor point: the surface keeps the coarse deformation
  /// and gets a wave on top, continuous where the window ends (D = 0 there)
  /// and never moved by more than m^up. The default.
  Current,
  /// To the reference point, as formula 4-16 writes it: the window's border
  /// is drawn around the reference shape, so where the window ends the
  /// surface steps by the motion since the reversal (|P^mc - P^w0|).
  Reference
};

/// The parameters of 4.4 with the thesis's defaults where it gives them.
struct WrinkleParameters
{
  /// theta^d: the window spans theta^d / (2 pi) wrinkle periods.
  double frequency = 5.0 * M_PI;
  /// s: scale of the default magnitude m^d.
  double scale = 1.0;
  /// m^up: upper bound of the wrinkle magnitude (model units); <= 0: none.
  double magnitudeBound = 0.5;
  /// r^c: monitor points thinner than this do not wrinkle.
  double cutOffThickness = 0.0;
  /// e - s: monitor points in the window (the thesis selects 70 of 296).
  int windowSize = 70;
  /// N_c: reversals needed to set the reference; < 0: 0.5 (e - s).
  double reversalThreshold = -1.0;
  /// N_s: lower-surface contacts needed before reversals are counted.
  int startContacts = 0;
  /// N_e: fewer lower-surface contacts than this (and no instrument) end
  /// the wrinkles.
  int endContacts = 1;
  WrinkleAnchor anchor = WrinkleAnchor::Current;
  /// After a cut, the monitor points near it are searched again on the new
  /// surface (WrinkleInfluence::refresh). 0: inside followCut, all at once;
  /// n > 0: n of them per update() from the one after the cut's own step
  /// on (a time-sliced refresh: the step with the cut does not pay the
  /// searches, nor the grid they walk). Until the last one, the monitor
  /// points near the cut move the surface points they moved before it
  /// (the new rim's vertices follow a few updates late); then the
  /// influence is the one the whole refresh makes, bit for bit.
  int refreshMonitorsPerUpdate = 0;
};

/// Throws InvalidInputError naming the parameter on a value out of range.
THINTISSUEWRINKLES_EXPORT void checkWrinkleParameters(const WrinkleParameters& parameters);

/// What the contacts of the step were (4.4.1).
struct WrinkleContactState
{
  /// Contacts on the tissue's lower collision surface with other bodies
  /// than instruments ("numberOfCollideWithLowerSurface").
  int lowerSurfaceContacts = 0;
  bool instrumentTouches = false;
  /// Where the instrument touches the tissue (its deepest contact).
  Vector3 instrumentContact = Vector3::Zero();
};

/// The contact state of tissue `tissue` after CollisionScene::detectContacts
/// or step(): lower-surface contacts with obstacles and other tissues, the
/// deepest tool contact.
THINTISSUEWRINKLES_EXPORT WrinkleContactState wrinkleContactState(const CollisionScene& scene,
  int tissue);

class THINTISSUEWRINKLES_EXPORT WrinkleGenerator
{
public:
  WrinkleGenerator() = default;
  /// Embeds the monitor points in `mesh` (rest node positions; the nearest
  /// hexahedron for points outside) and finds the points of `surfaceRest`
  /// (the visual surface at rest) each affects. Throws InvalidInputError on
  /// bad parameters or an empty set.
  WrinkleGenerator(MonitorPointSet monitors,
    const HexahedralMesh& mesh,
    const TriangleMesh& surfaceRest,
    const WrinkleParameters& parameters = {},
    const WrinkleInfluenceSettings& influence = {});

  /// After `cutter` cut the tissue (thesis 5.3; `report` is what cut()
  /// returned): monitor points in duplicated hexahedra move to the copy
  /// holding their nearest collision triangle; those whose nearest triangle
  /// was removed (a piece dropped or handed over) are dropped; a curve is
  /// split where a point was dropped or where the cut parted two
  /// consecutive points (their hexahedra share no node); the affected
  /// surface points are found again on the cut visual surface. The
  /// wrinkles stop (a cut is no reversal); the rest stays valid.
  void followCut(const TissueCutter& cutter, const TissueCutReport& report);

  void setParameters(const WrinkleParameters& parameters);
  const WrinkleParameters& parameters() const { return Parameters; }

  /// One step (items 1-4 of the file comment) from the hexahedra's current
  /// node positions. No allocation after the first step, but in the steps
  /// of a time-sliced refresh after a cut.
  void update(const std::vector<Vector3>& nodePositions, const WrinkleContactState& contacts);

  /// Adds the wrinkle displacement to the displaced points of `positions`
  /// (the surface as the embedding placed it this step).
  void applyTo(std::vector<Vector3>& positions) const;

  bool wrinkling() const { return NeedWrinkles; }
  /// Window of the last step: first and one-past-last monitor point.
  int windowBegin() const { return WindowBegin; }
  int windowEnd() const { return WindowEnd; }
  /// Reversals counted at the last step that counted them.
  int lastReversals() const { return LastReversals; }

  const MonitorPointSet& monitors() const { return Monitors; }
  const HexahedralEmbedding& monitorEmbedding() const { return Embedding; }
  const WrinkleInfluence& influence() const { return Influence; }
  /// P^mc (all monitor points) and P^w0 (empty without reference).
  const std::vector<Vector3>& currentMonitorPoints() const { return Current; }
  const std::vector<Vector3>& referencePoints() const { return Reference; }
  /// Per window point k (index k - windowBegin()): D(k), W(k), P^wc_k.
  const std::vector<double>& direction() const { return Direction; }
  const std::vector<double>& wrinkleFunction() const { return Wrinkle; }
  const std::vector<Vector3>& wrinklePoints() const { return WrinklePoints; }
  /// The surface points moved this step and their displacements.
  const std::vector<int>& displacedPoints() const { return Displaced; }
  const std::vector<Vector3>& displacements() const { return Displacements; }

private:
  void selectWindow(const Vector3& contact);
  int countReversals() const;
  void updateReference(const WrinkleContactState& contacts);
  void computeWrinklePoints();
  void propagate();
  std::vector<char> placeAfterCut(const TissueCutter& cutter, const TissueCutReport& report);
  std::vector<int> dropAndSplit(const std::vector<char>& keep, const HexahedralMesh& mesh);
  void forgetNewCurveEnds(const std::vector<int>& oldStarts, std::vector<int>& previous) const;
  void refreshInfluence(const TissueCutter& cutter,
    const TissueCutReport& report,
    const std::vector<int>& previous);

  MonitorPointSet Monitors;
  HexahedralEmbedding Embedding;
  WrinkleInfluence Influence;
  WrinkleParameters Parameters;
  WrinkleInfluenceSettings InfluenceSettings;
  /// Per visual triangle: whether the influence was found on it (the
  /// surface's triangles still in the tissue).
  std::vector<char> ShownTriangles;
  std::vector<Vector3> Current;
  std::vector<Vector3> Previous;
  std::vector<Vector3> Reference;
  bool HasPrevious = false;
  bool NeedWrinkles = false;
  /// followCut deferred the refresh in this step: the searches start with
  /// the next update (not in the step that already paid for the cut).
  bool RefreshDeferredThisStep = false;
  int WindowBegin = 0;
  int WindowEnd = 0;
  int LastReversals = 0;
  std::vector<double> Direction;
  std::vector<double> Wrinkle;
  std::vector<Vector3> WrinklePoints;
  std::vector<int> Displaced;
  std::vector<Vector3> Displacements;
  std::vector<int> SlotOfPoint; ///< index in Displaced, -1 if none (per surface point)
};

} // namespace thintissue

#endif
