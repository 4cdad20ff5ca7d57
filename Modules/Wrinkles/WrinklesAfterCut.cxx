// WrinkleGenerator::followCut: the monitor points after a cut (thesis 5.3
// changes the hexahedra and the visual surface the wrinkles live on).
#include "WrinkleGenerator.h"

#include "MeshQueries.h"
#include "TissueCutter.h"

#include <algorithm>
#include <limits>

namespace thintissue
{

namespace
{

/// The collision triangle nearest `point` (rest positions) among those in
/// the copies of hexahedron h; -1 if they hold none.
int nearestTriangle(const TissueCutter& cutter, int h, const Vector3& point)
{
  const auto& rest = cutter.collision().restPositions();
  const auto& triangles = cutter.collision().triangles();
  int best = -1;
  double nearest = std::numeric_limits<double>::infinity();
  for (const int copy : cutter.branches().copiesOf(h))
  {
    for (const int t : cutter.branches().trianglesOf(copy))
    {
      const Triangle& c = triangles[t];
      // Its bounding box bounds its distance from below: a triangle whose
      // box lies farther (beyond a round-off margin) cannot be nearer.
      BoundingBox box(rest[c[0]], rest[c[0]]);
      box.extend(rest[c[1]]);
      box.extend(rest[c[2]]);
      if (box.squaredExteriorDistance(point) > nearest * (1.0 + 1e-9))
        continue;
      const double d =
        (closestPointOnTriangle(point, rest[c[0]], rest[c[1]], rest[c[2]]) - point).squaredNorm();
      if (d < nearest)
      {
        nearest = d;
        best = t;
      }
    }
  }
  return best;
}

bool shareANode(const Hexahedron& a, const Hexahedron& b)
{
  for (const int n : a)
  {
    if (std::find(b.begin(), b.end(), n) != b.end())
    {
      return true;
    }
  }
  return false;
}

} // namespace

void WrinkleGenerator::followCut(const TissueCutter& cutter, const TissueCutReport& report)
{
  if (!report.changed() && report.removedPieces == 0)
  {
    return;
  }
  const std::vector<char> keep = placeAfterCut(cutter, report);
  const std::vector<int> oldStarts = Monitors.curveStarts;
  std::vector<int> previous = dropAndSplit(keep, cutter.simulation());
  forgetNewCurveEnds(oldStarts, previous);
  if (cutter.hasVisual())
  {
    refreshInfluence(cutter, report, previous);
  }
  Displaced.clear();
  Displacements.clear();
  Displaced.reserve(Influence.affectedPoints().size());
  Displacements.reserve(Influence.affectedPoints().size());
  NeedWrinkles = false;
  RefreshDeferredThisStep = Influence.refreshPending();
  Reference.clear();
  WindowBegin = WindowEnd = 0;
}

/// A point that ends a curve now but did not before has other neighbours
/// (its blend width is their spacing): it is searched again as if new.
void WrinkleGenerator::forgetNewCurveEnds(const std::vector<int>& oldStarts,
  std::vector<int>& previous) const
{
  const auto isOldStart = [&](int old)
  { return std::binary_search(oldStarts.begin(), oldStarts.end(), old); };
  for (std::size_t c = 0; c < Monitors.curveCount(); ++c)
  {
    const int first = Monitors.curveStarts[c];
    const int last = Monitors.curveStarts[c + 1] - 1;
    if (!isOldStart(previous[first]))
      previous[first] = -1;
    if (!isOldStart(previous[last] + 1))
      previous[last] = -1;
  }
}

/// The affected points again where the cut changed the surface: the
/// triangles it rewrote or added and those it took away (removed pieces).
void WrinkleGenerator::refreshInfluence(const TissueCutter& cutter,
  const TissueCutReport& report,
  const std::vector<int>& previous)
{
  // Only the triangles still part of the tissue carry wrinkles.
  const TriangleMesh& visual = cutter.visual().mesh();
  const std::vector<char> active = cutter.activeVisualTriangles();
  BoundingBox changed;
  const auto include = [&](std::size_t t)
  {
    for (const int v : visual.triangles[t])
      changed.extend(visual.positions[v]);
  };
  for (const int t : report.visual.changedTriangles)
  {
    include(static_cast<std::size_t>(t));
  }
  std::vector<Triangle> shown;
  shown.reserve(visual.triangleCount());
  for (std::size_t t = 0; t < visual.triangleCount(); ++t)
  {
    const bool wasShown = t < ShownTriangles.size() && ShownTriangles[t];
    if (active[t])
    {
      shown.push_back(visual.triangles[t]);
    }
    if (wasShown != (active[t] != 0))
    {
      include(t);
    }
  }
  if (Parameters.refreshMonitorsPerUpdate > 0)
    Influence.deferRefresh(Monitors, previous, visual.positions, shown, changed);
  else
    Influence.refresh(Monitors, previous, visual.positions, shown, changed);
  ShownTriangles = active;
  SlotOfPoint.assign(visual.vertexCount(), -1);
}

/// Moves monitor points to the copy of their hexahedron holding their
/// nearest collision triangle; returns which survive.
std::vector<char> WrinkleGenerator::placeAfterCut(const TissueCutter& cutter,
  const TissueCutReport& report)
{
  const HexahedralMesh& mesh = cutter.simulation();
  Embedding.updateHexahedra(mesh, report.simulation.renodedHexahedra);
  std::vector<char> keep(Monitors.size(), 1);
  // The hexahedra this cut looked at: those whose branches it analysed
  // and those that lost a collision triangle, each with every copy of its
  // original (triangles move between copies, and a point's nearest
  // triangle is sought among them all). A point elsewhere keeps its
  // place: its nearest triangle was part of the tissue after the last cut
  // and is still held by its hexahedron (a split keeps its pieces so).
  std::vector<char> lookedAt(mesh.hexahedra.size(), 0);
  const HexahedralBranches& branches = cutter.branches();
  const auto markFamily = [&](int h)
  {
    for (const int copy : branches.copiesOf(h))
      lookedAt[copy] = 1;
  };
  for (const int h : report.simulation.touchedHexahedra)
    markFamily(h);
  for (const auto& [copy, source] : report.simulation.newHexahedra)
    markFamily(source);
  for (const int t : report.removedTriangles)
  {
    for (const int h : branches.hexahedraOf(t))
      markFamily(h); // nearestTriangle looks at the whole family
  }
  for (std::size_t i = 0; i < Monitors.size(); ++i)
  {
    const int h = Embedding.hexahedron(i);
    if (!lookedAt[h])
    {
      continue;
    }
    const int t = nearestTriangle(cutter, h, Monitors.monitorPoints[i]);
    if (t < 0)
    {
      continue;
    }
    if (!cutter.isActive(t))
    {
      keep[i] = 0;
      continue;
    }
    const int copy = cutter.branches().copyHolding(h, t);
    if (copy >= 0 && copy != h)
    {
      Embedding.setPoint(i, copy, Embedding.localCoordinates(i));
    }
  }
  return keep;
}

/// Drops the points not kept and splits curves where points were dropped
/// or consecutive points' hexahedra share no node; returns, per point kept,
/// its index before.
std::vector<int> WrinkleGenerator::dropAndSplit(const std::vector<char>& keep,
  const HexahedralMesh& mesh)
{
  std::vector<int> previous;
  MonitorPointSet survivors;
  std::vector<int> hexahedra;
  std::vector<Vector3> local, current, previousPositions;
  std::vector<Vector3> monitor, region;
  std::vector<double> thickness;
  const auto closeCurve = [&]
  {
    if (monitor.size() >= 2)
    {
      survivors.appendCurve(monitor, region, thickness);
    }
    else if (!monitor.empty()) // a lone point cannot wave: drop it too
    {
      hexahedra.pop_back();
      previous.pop_back();
      local.pop_back();
      current.pop_back();
      previousPositions.pop_back();
    }
    monitor.clear();
    region.clear();
    thickness.clear();
  };
  for (std::size_t c = 0; c < Monitors.curveCount(); ++c)
  {
    for (int i = Monitors.curveStarts[c]; i < Monitors.curveStarts[c + 1]; ++i)
    {
      const bool parted =
        !monitor.empty() && !shareANode(mesh.hexahedra[hexahedra.back()],
                              mesh.hexahedra[Embedding.hexahedron(static_cast<std::size_t>(i))]);
      if (!keep[i] || parted)
      {
        closeCurve();
      }
      if (!keep[i])
      {
        continue;
      }
      monitor.push_back(Monitors.monitorPoints[i]);
      region.push_back(Monitors.regionPoints[i]);
      thickness.push_back(Monitors.thickness[i]);
      hexahedra.push_back(Embedding.hexahedron(static_cast<std::size_t>(i)));
      previous.push_back(i);
      local.push_back(Embedding.localCoordinates(static_cast<std::size_t>(i)));
      current.push_back(Current[i]);
      previousPositions.push_back(Previous[i]);
    }
    closeCurve();
  }
  Monitors = std::move(survivors);
  Embedding.assign(mesh, std::move(hexahedra), std::move(local));
  Current = std::move(current);
  Previous = std::move(previousPositions);
  return previous;
}

} // namespace thintissue
