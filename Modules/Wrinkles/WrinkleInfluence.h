// The surface points each monitor point moves (thesis 4.3, fig. 4-9) and
// how much (4.4.2, Gaussian attenuation).
//
// Surface point P^s is affected by monitor point P^m0 when its projection
// P^p onto the region line L^r = P^r0 - P^m0 is nearer to P^m0 than the
// region point (|P^p - P^m0| < |L^r|, on either side of P^m0, so that the
// rim beyond an inset monitor point moves too), it lies inside a sphere
// around P^m0, and (given the surface's triangles) it is connected to the
// surface point nearest P^m0 through such points. A point may be affected
// by several monitor points.
//
// Weights: the monitor point's displacement reaches the surface point
// attenuated by a Gaussian of the distance along the region line,
// w = exp(-|P^p - P^m0|^2 / (2 sigma^2)), so that wrinkles fade into the
// tissue; the monitor points that affect one surface point are blended by a
// Gaussian of its distance across their region lines, b = exp(-h^2 /
// (2 rho^2)), normalised over all of them (sum b = 1), so that the surface
// follows the nearest monitor points and a wave along the border is not
// averaged away. The surface point moves by u = sum_i (b_i / sum b) w_i d_i
// over the monitor points i with displacement d_i: never more than the
// largest d_i, nothing where no monitor point moves.
#ifndef WrinkleInfluence_h
#define WrinkleInfluence_h

#include "MonitorCurves.h"
#include "ThinTissueWrinklesModule.h"

#include <memory>
#include <vector>

namespace thintissue
{

struct WrinkleInfluenceSettings
{
  /// Sphere filter radius around each monitor point; 0 (default): the length
  /// of its region line.
  double sphereRadius = 0.0;
  /// Gaussian width sigma of the attenuation along the region line; 0
  /// (default): half the region line's length.
  double gaussianWidth = 0.0;
  /// Gaussian width rho of the blend across region lines; 0 (default): the
  /// monitor point's spacing on its curve.
  double blendWidth = 0.0;
  /// Entries whose blend weight falls below this (relative) are dropped.
  double negligibleBlend = 1e-3;
};

/// Per monitor point (CSR), the surface points it affects and the factor
/// (b / sum b) w by which its displacement moves each.
class THINTISSUEWRINKLES_EXPORT WrinkleInfluence
{
public:
  WrinkleInfluence();
  ~WrinkleInfluence();
  WrinkleInfluence(const WrinkleInfluence& other);
  WrinkleInfluence& operator=(const WrinkleInfluence& other);
  WrinkleInfluence(WrinkleInfluence&& other) noexcept;
  WrinkleInfluence& operator=(WrinkleInfluence&& other) noexcept;
  /// Finds the affected points of `surfaceRest` (the visual vertices at
  /// rest). With the surface's `triangles`, only the points connected
  /// through them to the monitor point's nearest one count (and only points
  /// of a triangle): the lips of a cut do not move each other. Cost: the
  /// surface points near each monitor point (a grid), and one pass over the
  /// triangles.
  WrinkleInfluence(const MonitorPointSet& monitors,
    const std::vector<Vector3>& surfaceRest,
    const std::vector<Triangle>& triangles = {},
    const WrinkleInfluenceSettings& settings = {});

  /// After a cut changed the surface within `changed` (rest positions; the
  /// triangles the cut rewrote, added or took away): monitor point i of
  /// `monitors` was monitor point previous[i] before (-1: new). Those whose
  /// reach meets `changed`, and new ones, are searched again on the new
  /// surface; the others keep their entries; the blends are normalised
  /// again. Costs the monitor points near the cut and the entries, not a
  /// search of every monitor point.
  void refresh(const MonitorPointSet& monitors,
    const std::vector<int>& previous,
    const std::vector<Vector3>& surfaceRest,
    const std::vector<Triangle>& triangles,
    const BoundingBox& changed);
  /// The same refresh, deferred (a time-sliced update after a cut): nothing
  /// is searched now; until continueRefresh has searched every monitor
  /// point concerned, each keeps its entries from before the cut (a new
  /// one has none). The surface and its triangles are kept as given here,
  /// so that the finished refresh is the one refresh() makes, bit for bit.
  /// A refresh while one is pending searches again what that one had left
  /// and what it had searched.
  void deferRefresh(const MonitorPointSet& monitors,
    const std::vector<int>& previous,
    const std::vector<Vector3>& surfaceRest,
    const std::vector<Triangle>& triangles,
    const BoundingBox& changed);
  /// Searches up to `monitorBudget` more monitor points of a deferred
  /// refresh (0: all that are left); the last one normalises the blends.
  void continueRefresh(std::size_t monitorBudget);
  bool refreshPending() const { return Pending != nullptr; }
  /// Monitor points a deferred refresh has still to search.
  std::size_t pendingMonitorCount() const;
  std::size_t monitorCount() const { return Offsets.size() - 1; }
  int affectedBegin(std::size_t monitor) const { return Offsets[monitor]; }
  int affectedEnd(std::size_t monitor) const { return Offsets[monitor + 1]; }
  int point(int entry) const { return Points[entry]; }
  double factor(int entry) const { return Factors[entry]; }
  std::size_t entryCount() const { return Points.size(); }
  /// Surface points affected by at least one monitor point.
  const std::vector<int>& affectedPoints() const { return Affected; }
  /// Bytes held (the runtime cost beside MonitorPointSet::storedBytes).
  std::size_t memoryBytes() const;

private:
  /// Offsets, Points, Factors and Affected from Points, Blends and
  /// Attenuations (grouped by monitor, `counts` entries each).
  void normalise(const std::vector<int>& counts, std::size_t surfaceCount);
  /// Per monitor point: whether a pending refresh searches it.
  std::vector<char> pendingFlags() const;
  /// The raw arrays (Offsets, Points, Blends, Attenuations) regrouped as
  /// the new monitor points: each keeps the entries of previous[i] (none
  /// for a new one). Throws InvalidInputError on an index out of range.
  void keepPreviousEntries(const std::vector<int>& previous);
  void checkPrevious(const MonitorPointSet& monitors, const std::vector<int>& previous) const;
  /// refresh (searches now) or deferRefresh (`defer`: searches listed).
  void startRefresh(const MonitorPointSet& monitors,
    const std::vector<int>& previous,
    const std::vector<Vector3>& surfaceRest,
    const std::vector<Triangle>& triangles,
    const BoundingBox& changed,
    bool defer);

  WrinkleInfluenceSettings Settings;
  std::vector<int> Offsets{ 0 };
  std::vector<int> Points;
  std::vector<double> Factors;
  /// Per entry: its blend b and attenuation w before normalising (kept so
  /// that a cut re-searches only the monitor points near it).
  std::vector<double> Blends;
  std::vector<double> Attenuations;
  std::vector<int> Affected;
  /// A deferred refresh: the surface, its neighbours and grid, the monitor
  /// points to search and what was found so far (WrinkleInfluence.cxx).
  /// Last: the members before it never need its destructor.
  struct PendingRefresh;
  std::unique_ptr<PendingRefresh> Pending;
};

} // namespace thintissue

#endif
