#include "WrinkleInfluence.h"

#include "ThinTissueError.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace thintissue
{

namespace
{

/// What decides whether and how much one monitor point moves a surface
/// point (see the header).
struct MonitorReach
{
  Vector3 origin;
  Vector3 direction; ///< unit, toward the region point
  double length = 0.0;
  double sphereRadius = 0.0;
  double sigma = 0.0;
  double rho = 0.0;
  /// Distance from the region line beyond which the blend is negligible
  /// (infinite when nothing is negligible): only the tube around the line
  /// is searched, not the whole sphere.
  double tubeRadius = std::numeric_limits<double>::infinity();
  /// Half the length of the line segment searched (inside the sphere).
  double reach() const { return std::min(sphereRadius, length); }
};

double spacingOf(const MonitorPointSet& monitors, std::size_t i)
{
  const int curve = monitors.curveOf(i);
  const int begin = monitors.curveStarts[curve];
  const int end = monitors.curveStarts[curve + 1];
  double sum = 0.0;
  int count = 0;
  const int k = static_cast<int>(i);
  if (k > begin)
  {
    sum += (monitors.monitorPoints[k] - monitors.monitorPoints[k - 1]).norm();
    ++count;
  }
  if (k + 1 < end)
  {
    sum += (monitors.monitorPoints[k + 1] - monitors.monitorPoints[k]).norm();
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

std::vector<MonitorReach> reachesOf(const MonitorPointSet& monitors,
  const WrinkleInfluenceSettings& settings)
{
  std::vector<MonitorReach> reaches(monitors.size());
  for (std::size_t i = 0; i < monitors.size(); ++i)
  {
    MonitorReach& r = reaches[i];
    const Vector3 line = monitors.regionPoints[i] - monitors.monitorPoints[i];
    r.origin = monitors.monitorPoints[i];
    r.length = line.norm();
    if (!(r.length > 0.0))
    {
      throw InvalidInputError(
        "wrinkle influence: monitor point " + std::to_string(i) + " lies on its region point");
    }
    r.direction = line / r.length;
    r.sphereRadius = settings.sphereRadius > 0.0 ? settings.sphereRadius : r.length;
    r.sigma = settings.gaussianWidth > 0.0 ? settings.gaussianWidth : 0.5 * r.length;
    const double spacing = spacingOf(monitors, i);
    r.rho =
      settings.blendWidth > 0.0 ? settings.blendWidth : (spacing > 0.0 ? spacing : 0.25 * r.length);
    if (settings.negligibleBlend > 0.0 && settings.negligibleBlend < 1.0)
    {
      // exp(-d^2 / (2 rho^2)) >= negligible  <=>  d <= rho sqrt(-2 ln negligible);
      // a hair wider so that rounding never drops a point the test keeps.
      r.tubeRadius = r.rho * std::sqrt(-2.0 * std::log(settings.negligibleBlend)) * (1.0 + 1e-9);
    }
  }
  return reaches;
}

/// Uniform grid of surface points (only those inside `box`), cells of size
/// `cell`: CSR per cell.
class PointGrid
{
public:
  PointGrid(const std::vector<Vector3>& points, const BoundingBox& box, double cell)
    : Origin(box.min())
    , Cell(cell)
  {
    const Vector3 extent = box.sizes() / cell;
    for (int a = 0; a < 3; ++a)
    {
      Dimensions[a] = std::clamp(static_cast<int>(std::ceil(extent[a])), 1, 256);
    }
    Start.assign(cellCount() + 1, 0);
    for (const Vector3& p : points)
    {
      const int c = cellOf(p);
      if (c >= 0)
      {
        ++Start[c + 1];
      }
    }
    for (std::size_t c = 0; c < cellCount(); ++c)
    {
      Start[c + 1] += Start[c];
    }
    Entries.resize(Start.back());
    std::vector<int> fill(Start.begin(), Start.end() - 1);
    for (std::size_t j = 0; j < points.size(); ++j)
    {
      const int c = cellOf(points[j]);
      if (c >= 0)
      {
        Entries[fill[c]++] = static_cast<int>(j);
      }
    }
  }

  /// Calls f(point) for every point in the cells that meet the ball.
  template <typename F>
  void forEachNear(const Vector3& centre, double radius, F&& f) const
  {
    std::array<int, 3> low{}, high{};
    for (int a = 0; a < 3; ++a)
    {
      low[a] = std::max(0, static_cast<int>(std::floor((centre[a] - radius - Origin[a]) / Cell)));
      high[a] = std::min(
        Dimensions[a] - 1, static_cast<int>(std::floor((centre[a] + radius - Origin[a]) / Cell)));
    }
    for (int z = low[2]; z <= high[2]; ++z)
      for (int y = low[1]; y <= high[1]; ++y)
        for (int x = low[0]; x <= high[0]; ++x)
        {
          const int c = (z * Dimensions[1] + y) * Dimensions[0] + x;
          for (int e = Start[c]; e < Start[c + 1]; ++e)
          {
            f(Entries[e]);
          }
        }
  }

  /// Calls f(point) once for every point in the cells that meet the tube
  /// of `radius` about segment [a, b]: balls at steps of one cell along the
  /// segment, each cell tested by its centre's distance to the segment
  /// against radius plus half its diagonal, and marked in `stamps` (one
  /// entry per cell, this query's mark `mark`) so that it is seen once.
  template <typename F>
  void forEachNearSegment(const Vector3& a,
    const Vector3& b,
    double radius,
    std::vector<unsigned>& stamps,
    unsigned mark,
    F&& f) const
  {
    const Vector3 axis = b - a;
    const double axisSquared = axis.squaredNorm();
    const double within = radius + 0.5 * std::sqrt(3.0) * Cell;
    const int samples = std::max(1, static_cast<int>(std::ceil(std::sqrt(axisSquared) / Cell)));
    for (int s = 0; s <= samples; ++s)
    {
      const Vector3 centre = a + axis * (static_cast<double>(s) / samples);
      std::array<int, 3> low{}, high{};
      for (int k = 0; k < 3; ++k)
      {
        // A point within `radius` of the segment is within radius + Cell/2
        // of a sample.
        const double reach = radius + 0.5 * Cell;
        low[k] = std::max(0, static_cast<int>(std::floor((centre[k] - reach - Origin[k]) / Cell)));
        high[k] = std::min(
          Dimensions[k] - 1, static_cast<int>(std::floor((centre[k] + reach - Origin[k]) / Cell)));
      }
      for (int z = low[2]; z <= high[2]; ++z)
        for (int y = low[1]; y <= high[1]; ++y)
          for (int x = low[0]; x <= high[0]; ++x)
          {
            const int c = (z * Dimensions[1] + y) * Dimensions[0] + x;
            if (stamps[c] == mark)
              continue;
            stamps[c] = mark;
            const Vector3 middle = Origin + Cell * Vector3(x + 0.5, y + 0.5, z + 0.5);
            const double t =
              axisSquared > 0.0 ? std::clamp((middle - a).dot(axis) / axisSquared, 0.0, 1.0) : 0.0;
            if ((a + t * axis - middle).squaredNorm() > within * within)
              continue;
            for (int e = Start[c]; e < Start[c + 1]; ++e)
              f(Entries[e]);
          }
    }
  }

  std::size_t cellCount() const
  {
    return static_cast<std::size_t>(Dimensions[0]) * Dimensions[1] * Dimensions[2];
  }

private:
  int cellOf(const Vector3& p) const
  {
    std::array<int, 3> index{};
    for (int a = 0; a < 3; ++a)
    {
      const double x = (p[a] - Origin[a]) / Cell;
      if (!(x >= 0.0) || x > Dimensions[a])
      {
        return -1;
      }
      index[a] = std::min(Dimensions[a] - 1, static_cast<int>(x));
    }
    return (index[2] * Dimensions[1] + index[1]) * Dimensions[0] + index[0];
  }

  Vector3 Origin;
  double Cell;
  std::array<int, 3> Dimensions{ { 1, 1, 1 } };
  std::vector<int> Start;
  std::vector<int> Entries;
};

struct RawEntry
{
  int monitor;
  int point;
  double blend;
  double attenuation;
};

/// Vertex neighbours through triangle edges (CSR); `used` marks the
/// vertices of at least one triangle.
struct SurfaceNeighbours
{
  std::vector<int> start;
  std::vector<int> next;
  std::vector<char> used;

  SurfaceNeighbours(std::size_t vertexCount, const std::vector<Triangle>& triangles)
    : start(vertexCount + 1, 0)
    , used(vertexCount, 0)
  {
    for (const Triangle& t : triangles)
    {
      for (const int v : t)
      {
        start[v + 1] += 2;
        used[v] = 1;
      }
    }
    for (std::size_t v = 0; v < vertexCount; ++v)
    {
      start[v + 1] += start[v];
    }
    next.resize(start.back());
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (const Triangle& t : triangles)
    {
      for (int k = 0; k < 3; ++k)
      {
        next[fill[t[k]]++] = t[(k + 1) % 3];
        next[fill[t[k]]++] = t[(k + 2) % 3];
      }
    }
  }
};

/// The surface points one monitor point affects, before normalising the
/// blend (see the header): appended to `raw`.
class AffectedPointSearch
{
public:
  /// `neighbours` empty (no triangles): every point counts, connected or not.
  AffectedPointSearch(const std::vector<Vector3>& surface,
    const SurfaceNeighbours& neighbours,
    const PointGrid& grid,
    double negligibleBlend)
    : Surface(surface)
    , Grid(grid)
    , NegligibleBlend(negligibleBlend)
    , Connected(!neighbours.used.empty())
    , Neighbours(neighbours)
    , Mark(Connected ? surface.size() : 0, 0)
    , CellStamps(grid.cellCount(), 0u)
  {
  }

  void find(int monitor, const MonitorReach& r, std::vector<RawEntry>& raw)
  {
    const std::size_t first = raw.size();
    Distance.clear();
    const auto visit = [&](int j) { consider(monitor, r, j, raw); };
    if (std::isfinite(r.tubeRadius))
    {
      if (++CellMark == 0) // wrapped: no cell may keep an old mark
      {
        std::fill(CellStamps.begin(), CellStamps.end(), 0u);
        CellMark = 1;
      }
      Grid.forEachNearSegment(r.origin - r.reach() * r.direction,
        r.origin + r.reach() * r.direction,
        r.tubeRadius,
        CellStamps,
        CellMark,
        visit);
    }
    else
    {
      Grid.forEachNear(r.origin, r.reach(), visit);
    }
    if (Connected)
    {
      keepConnected(raw, first);
    }
    // In point order, whatever the grid's cells: the entries do not depend
    // on how the search was laid out (after keepConnected, whose distances
    // follow the visiting order).
    std::sort(raw.begin() + static_cast<std::ptrdiff_t>(first),
      raw.end(),
      [](const RawEntry& a, const RawEntry& b) { return a.point < b.point; });
  }

private:
  void consider(int monitor, const MonitorReach& r, int j, std::vector<RawEntry>& raw)
  {
    if (Connected && !Neighbours.used[j])
    {
      return;
    }
    const Vector3 v = Surface[j] - r.origin;
    const double along = v.dot(r.direction);
    const double squared = v.squaredNorm();
    if (std::abs(along) >= r.length || squared > r.sphereRadius * r.sphereRadius)
    {
      return;
    }
    const double across2 = std::max(0.0, squared - along * along);
    const double blend = std::exp(-across2 / (2.0 * r.rho * r.rho));
    if (blend < NegligibleBlend)
    {
      return;
    }
    raw.push_back(
      RawEntry{ monitor, j, blend, std::exp(-along * along / (2.0 * r.sigma * r.sigma)) });
    Distance.push_back(squared);
  }

  /// Keeps the candidates [first, raw.end()) connected through candidates
  /// to the one nearest the monitor point.
  void keepConnected(std::vector<RawEntry>& raw, std::size_t first)
  {
    if (raw.size() == first)
    {
      return;
    }
    std::size_t seed = first;
    for (std::size_t e = first; e < raw.size(); ++e)
    {
      Mark[raw[e].point] = 1; // candidate
      seed = Distance[e - first] < Distance[seed - first] ? e : seed;
    }
    Queue.assign(1, raw[seed].point);
    Mark[raw[seed].point] = 2; // reached
    for (std::size_t q = 0; q < Queue.size(); ++q)
    {
      const int v = Queue[q];
      for (int n = Neighbours.start[v]; n < Neighbours.start[v + 1]; ++n)
      {
        const int w = Neighbours.next[n];
        if (Mark[w] == 1)
        {
          Mark[w] = 2;
          Queue.push_back(w);
        }
      }
    }
    std::size_t kept = first;
    for (std::size_t e = first; e < raw.size(); ++e)
    {
      const bool reached = Mark[raw[e].point] == 2;
      Mark[raw[e].point] = 0;
      if (reached)
      {
        raw[kept++] = raw[e];
      }
    }
    raw.resize(kept);
  }

  const std::vector<Vector3>& Surface;
  const PointGrid& Grid;
  double NegligibleBlend;
  bool Connected;
  const SurfaceNeighbours& Neighbours;
  std::vector<int> Mark;
  std::vector<int> Queue;
  std::vector<double> Distance;
  std::vector<unsigned> CellStamps; ///< per grid cell: the last query that saw it
  unsigned CellMark = 0;
};

} // namespace

namespace
{

/// The grid over the surface points any of `reaches` can affect. Its cells
/// are as wide as the widest tube (the searches follow the region lines),
/// or as the largest reach when a tube is unbounded.
PointGrid gridFor(const std::vector<MonitorReach>& reaches, const std::vector<Vector3>& surface)
{
  BoundingBox box;
  double largest = 0.0;
  double widestTube = 0.0;
  for (const MonitorReach& r : reaches)
  {
    box.extend(r.origin);
    largest = std::max(largest, r.reach());
    widestTube = std::max(widestTube, r.tubeRadius);
  }
  box.min().array() -= largest;
  box.max().array() += largest;
  double cell = largest > 0.0 ? largest : 1.0;
  if (std::isfinite(widestTube) && widestTube > 0.0)
  {
    // At most about 2^16 cells: the grid and the searches' cell marks are
    // made for every refresh after a cut.
    const Vector3 sizes = box.sizes();
    const double coarsest = std::cbrt(sizes.prod() / 65536.0);
    cell = std::min(cell, std::max({ widestTube, coarsest, sizes.maxCoeff() / 256.0 }));
  }
  return PointGrid(surface, box, cell);
}

/// Whether a change inside `box` can change what monitor r affects: the box
/// meets its sphere and, when bounded, the tube about its line (the segment
/// tested against the box grown by the tube's radius: conservative).
bool reachMeets(const MonitorReach& r, const BoundingBox& box)
{
  if (box.isEmpty())
    return false;
  const double radius = r.reach();
  const Vector3 nearest = r.origin.cwiseMax(box.min()).cwiseMin(box.max());
  if ((nearest - r.origin).squaredNorm() > radius * radius)
    return false;
  if (!std::isfinite(r.tubeRadius))
    return true;
  // Slab test of segment origin + t direction, |t| <= reach.
  double low = -radius, high = radius;
  for (int k = 0; k < 3; ++k)
  {
    const double lo = box.min()[k] - r.tubeRadius, hi = box.max()[k] + r.tubeRadius;
    const double d = r.direction[k];
    if (std::abs(d) < 1e-300)
    {
      if (r.origin[k] < lo || r.origin[k] > hi)
        return false;
      continue;
    }
    double t0 = (lo - r.origin[k]) / d, t1 = (hi - r.origin[k]) / d;
    if (t0 > t1)
      std::swap(t0, t1);
    low = std::max(low, t0);
    high = std::min(high, t1);
    if (low > high)
      return false;
  }
  return true;
}

} // namespace

namespace
{

/// find() for each of `count` monitors listed from `monitors`, in parallel
/// (a search, with its scratch, per thread; each monitor's entries depend
/// on it alone).
std::vector<std::vector<RawEntry>> searchAffected(const std::vector<MonitorReach>& reaches,
  const int* monitors,
  std::size_t count,
  const std::vector<Vector3>& surfaceRest,
  const SurfaceNeighbours& neighbours,
  const PointGrid& grid,
  double negligibleBlend)
{
  std::vector<std::vector<RawEntry>> found(count);
  if (count == 0)
    return found;
  tbb::enumerable_thread_specific<AffectedPointSearch> searches(
    [&] { return AffectedPointSearch(surfaceRest, neighbours, grid, negligibleBlend); });
  // Grains of 8: a search costs some microseconds.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 8),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      AffectedPointSearch& search = searches.local();
      for (std::size_t k = range.begin(); k != range.end(); ++k)
        search.find(monitors[k], reaches[monitors[k]], found[k]);
    });
  return found;
}

/// The same over a grid and neighbours made for this search only.
std::vector<std::vector<RawEntry>> findAffected(const std::vector<MonitorReach>& reaches,
  const std::vector<int>& monitors,
  const std::vector<Vector3>& surfaceRest,
  const std::vector<Triangle>& triangles,
  double negligibleBlend)
{
  if (monitors.empty())
    return {};
  const PointGrid grid = gridFor(reaches, surfaceRest);
  // The neighbours once, shared by the threads' searches.
  const SurfaceNeighbours neighbours(triangles.empty() ? 0 : surfaceRest.size(), triangles);
  return searchAffected(
    reaches, monitors.data(), monitors.size(), surfaceRest, neighbours, grid, negligibleBlend);
}

/// Monitor points to search again: new ones, those whose reach meets
/// `changed`, and those a pending refresh had (`wasPending`, by old index).
std::vector<int> staleMonitors(const std::vector<MonitorReach>& reaches,
  const std::vector<int>& previous,
  const BoundingBox& changed,
  const std::vector<char>& wasPending)
{
  std::vector<int> stale;
  for (std::size_t i = 0; i < reaches.size(); ++i)
  {
    const int old = previous[i];
    if (old < 0 || (old < static_cast<int>(wasPending.size()) && wasPending[old]) ||
        reachMeets(reaches[i], changed))
      stale.push_back(static_cast<int>(i));
  }
  return stale;
}

/// Entries being gathered: points, blends and attenuations side by side.
struct EntryArrays
{
  std::vector<int> points;
  std::vector<double> blends;
  std::vector<double> attenuations;

  /// Appends entries [begin, end) of the given arrays.
  void append(const std::vector<int>& p,
    const std::vector<double>& b,
    const std::vector<double>& a,
    int begin,
    int end)
  {
    points.insert(points.end(), p.begin() + begin, p.begin() + end);
    blends.insert(blends.end(), b.begin() + begin, b.begin() + end);
    attenuations.insert(attenuations.end(), a.begin() + begin, a.begin() + end);
  }
};

/// The raw arrays (grouped per monitor point by `offsets`) with the entries
/// of the `searched` monitor points replaced by those `found`; `counts`
/// receives each one's entry count.
void mergeEntries(const std::vector<int>& searched,
  const std::vector<std::vector<RawEntry>>& found,
  const std::vector<int>& offsets,
  std::vector<int>& points,
  std::vector<double>& blends,
  std::vector<double>& attenuations,
  std::vector<int>& counts)
{
  EntryArrays merged;
  counts.assign(offsets.size() - 1, 0);
  std::size_t next = 0; // in `searched` and `found`
  for (std::size_t i = 0; i < counts.size(); ++i)
  {
    if (next < searched.size() && searched[next] == static_cast<int>(i))
    {
      const std::vector<RawEntry>& raw = found[next++];
      counts[i] = static_cast<int>(raw.size());
      for (const RawEntry& e : raw)
      {
        merged.points.push_back(e.point);
        merged.blends.push_back(e.blend);
        merged.attenuations.push_back(e.attenuation);
      }
      continue;
    }
    // Far from the cut: the same points, blends and attenuations.
    counts[i] = offsets[i + 1] - offsets[i];
    merged.append(points, blends, attenuations, offsets[i], offsets[i + 1]);
  }
  points = std::move(merged.points);
  blends = std::move(merged.blends);
  attenuations = std::move(merged.attenuations);
}

} // namespace

/// What a deferred refresh searches in (a copy of the surface it was given,
/// its neighbours and grid) and what it has found so far, in the order of
/// `monitors`.
struct WrinkleInfluence::PendingRefresh
{
  PendingRefresh(std::vector<MonitorReach> monitorReaches,
    std::vector<int> stale,
    const std::vector<Vector3>& surfaceRest,
    const std::vector<Triangle>& surfaceTriangles)
    : reaches(std::move(monitorReaches))
    , monitors(std::move(stale))
    , surface(surfaceRest)
    , triangles(surfaceTriangles)
  {
  }

  /// The neighbours and the grid, made by the first search (not in the
  /// step with the cut).
  void prepare()
  {
    if (!neighbours)
    {
      neighbours.emplace(triangles.empty() ? 0 : surface.size(), triangles);
      grid.emplace(gridFor(reaches, surface));
    }
  }

  std::vector<MonitorReach> reaches;
  /// Monitor points to search (ascending); the first found.size() are done.
  std::vector<int> monitors;
  std::vector<Vector3> surface;
  std::vector<Triangle> triangles;
  std::optional<SurfaceNeighbours> neighbours;
  std::optional<PointGrid> grid;
  std::vector<std::vector<RawEntry>> found;
};

WrinkleInfluence::WrinkleInfluence() = default;
WrinkleInfluence::~WrinkleInfluence() = default;
WrinkleInfluence::WrinkleInfluence(WrinkleInfluence&& other) noexcept = default;
WrinkleInfluence& WrinkleInfluence::operator=(WrinkleInfluence&& other) noexcept = default;

WrinkleInfluence::WrinkleInfluence(const WrinkleInfluence& other)
  : Settings(other.Settings)
  , Offsets(other.Offsets)
  , Points(other.Points)
  , Factors(other.Factors)
  , Blends(other.Blends)
  , Attenuations(other.Attenuations)
  , Affected(other.Affected)
  , Pending(other.Pending ? std::make_unique<PendingRefresh>(*other.Pending) : nullptr)
{
}

WrinkleInfluence& WrinkleInfluence::operator=(const WrinkleInfluence& other)
{
  if (this != &other)
  {
    WrinkleInfluence copy(other);
    *this = std::move(copy);
  }
  return *this;
}

WrinkleInfluence::WrinkleInfluence(const MonitorPointSet& monitors,
  const std::vector<Vector3>& surfaceRest,
  const std::vector<Triangle>& triangles,
  const WrinkleInfluenceSettings& settings)
  : Settings(settings)
{
  // Every monitor point searched: a refresh with nothing to keep.
  refresh(monitors, std::vector<int>(monitors.size(), -1), surfaceRest, triangles, BoundingBox());
}

std::vector<char> WrinkleInfluence::pendingFlags() const
{
  std::vector<char> flags(Pending ? monitorCount() : 0, 0);
  if (Pending)
    for (const int i : Pending->monitors)
      flags[i] = 1;
  return flags;
}

void WrinkleInfluence::keepPreviousEntries(const std::vector<int>& previous)
{
  EntryArrays kept;
  std::vector<int> offsets(previous.size() + 1, 0);
  for (std::size_t i = 0; i < previous.size(); ++i)
  {
    const int old = previous[i];
    offsets[i + 1] = offsets[i];
    if (old < 0)
      continue; // new: searched
    if (old + 1 >= static_cast<int>(Offsets.size()))
      throw InvalidInputError("wrinkle influence refresh: monitor point " + std::to_string(i) +
                              " was monitor point " + std::to_string(old) + " of " +
                              std::to_string(monitorCount()) + " before");
    offsets[i + 1] += Offsets[old + 1] - Offsets[old];
    kept.append(Points, Blends, Attenuations, Offsets[old], Offsets[old + 1]);
  }
  Offsets = std::move(offsets);
  Points = std::move(kept.points);
  Blends = std::move(kept.blends);
  Attenuations = std::move(kept.attenuations);
}

void WrinkleInfluence::refresh(const MonitorPointSet& monitors,
  const std::vector<int>& previous,
  const std::vector<Vector3>& surfaceRest,
  const std::vector<Triangle>& triangles,
  const BoundingBox& changed)
{
  startRefresh(monitors, previous, surfaceRest, triangles, changed, false);
}

void WrinkleInfluence::deferRefresh(const MonitorPointSet& monitors,
  const std::vector<int>& previous,
  const std::vector<Vector3>& surfaceRest,
  const std::vector<Triangle>& triangles,
  const BoundingBox& changed)
{
  startRefresh(monitors, previous, surfaceRest, triangles, changed, true);
}

void WrinkleInfluence::startRefresh(const MonitorPointSet& monitors,
  const std::vector<int>& previous,
  const std::vector<Vector3>& surfaceRest,
  const std::vector<Triangle>& triangles,
  const BoundingBox& changed,
  bool defer)
{
  checkPrevious(monitors, previous);
  std::vector<MonitorReach> reaches = reachesOf(monitors, Settings);
  std::vector<int> stale = staleMonitors(reaches, previous, changed, pendingFlags());
  Pending.reset(); // superseded: what it had left is stale here
  keepPreviousEntries(previous);
  std::vector<int> counts;
  if (defer)
  {
    // Until the searches are done, every monitor point keeps its entries.
    counts.resize(previous.size());
    for (std::size_t i = 0; i < counts.size(); ++i)
      counts[i] = Offsets[i + 1] - Offsets[i];
    if (!stale.empty())
      Pending = std::make_unique<PendingRefresh>(
        std::move(reaches), std::move(stale), surfaceRest, triangles);
  }
  else
  {
    const std::vector<std::vector<RawEntry>> found =
      findAffected(reaches, stale, surfaceRest, triangles, Settings.negligibleBlend);
    mergeEntries(stale, found, Offsets, Points, Blends, Attenuations, counts);
  }
  normalise(counts, surfaceRest.size());
}

void WrinkleInfluence::checkPrevious(const MonitorPointSet& monitors,
  const std::vector<int>& previous) const
{
  if (previous.size() != monitors.size())
    throw InvalidInputError("wrinkle influence refresh: " + std::to_string(previous.size()) +
                            " previous indices for " + std::to_string(monitors.size()) +
                            " monitor points");
}

std::size_t WrinkleInfluence::pendingMonitorCount() const
{
  return Pending ? Pending->monitors.size() - Pending->found.size() : 0;
}

void WrinkleInfluence::continueRefresh(std::size_t monitorBudget)
{
  if (!Pending)
    return;
  PendingRefresh& p = *Pending;
  p.prepare();
  const std::size_t done = p.found.size();
  const std::size_t left = p.monitors.size() - done;
  const std::size_t count = monitorBudget == 0 ? left : std::min(left, monitorBudget);
  std::vector<std::vector<RawEntry>> found = searchAffected(p.reaches,
    p.monitors.data() + done,
    count,
    p.surface,
    *p.neighbours,
    *p.grid,
    Settings.negligibleBlend);
  std::move(found.begin(), found.end(), std::back_inserter(p.found));
  if (p.found.size() < p.monitors.size())
    return;
  // The searched monitor points' new entries, the others' kept ones.
  std::vector<int> counts;
  mergeEntries(p.monitors, p.found, Offsets, Points, Blends, Attenuations, counts);
  const std::size_t surfaceCount = p.surface.size();
  Pending.reset();
  normalise(counts, surfaceCount);
}

void WrinkleInfluence::normalise(const std::vector<int>& counts, std::size_t surfaceCount)
{
  std::vector<double> blendSum(surfaceCount, 0.0);
  for (std::size_t e = 0; e < Points.size(); ++e)
  {
    blendSum[Points[e]] += Blends[e];
  }
  Offsets.assign(counts.size() + 1, 0);
  for (std::size_t i = 0; i < counts.size(); ++i)
  {
    Offsets[i + 1] = Offsets[i] + counts[i];
  }
  Factors.resize(Points.size());
  Affected.clear();
  std::vector<char> seen(surfaceCount, 0);
  for (std::size_t e = 0; e < Points.size(); ++e)
  {
    Factors[e] = Blends[e] / blendSum[Points[e]] * Attenuations[e];
    if (!seen[Points[e]])
    {
      seen[Points[e]] = 1;
      Affected.push_back(Points[e]);
    }
  }
  std::sort(Affected.begin(), Affected.end());
}

std::size_t WrinkleInfluence::memoryBytes() const
{
  return (Offsets.size() + Points.size() + Affected.size()) * sizeof(int) +
         (Factors.size() + Blends.size() + Attenuations.size()) * sizeof(double);
}

} // namespace thintissue
