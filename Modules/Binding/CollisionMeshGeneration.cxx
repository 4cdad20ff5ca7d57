#include "CollisionMeshGeneration.h"

#include "BandMidSurface.h"
#include "HandleRemoval.h"

#include "MeshPieces.h"
#include "MeshQueries.h"
#include "MeshRepair.h"
#include "MeshValidation.h"
#include "ProximityQueries.h"
#include "SparseHexahedralGrid.h"
#include "ThinTissueError.h"
#include "TriangleBvh.h"
#include "TriangleMeshAdjacency.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace thintissue
{

namespace
{

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Triangulation =
  CGAL::Constrained_Delaunay_triangulation_2<Kernel, DataStructure, CGAL::Exact_predicates_tag>;

constexpr double Infinity = std::numeric_limits<double>::infinity();
/// Elongation (length over width from the area's principal spreads; the
/// menisci 1.9, the tibial cartilage 1.6, the steak 1.2, the cruciate
/// ligaments 3.6-4.1) below which a tissue is never taken for a band.
constexpr double MinimumBandElongation = 2.0;
/// The least half thickness under a collision vertex, as a share of the
/// largest thickness (tissue a twentieth as thick as its thickest): a
/// vertex whose axis line only grazes the tissue (a strip beside a tear's
/// gap narrower than the lattice, a staircase's edge) would get a radius
/// of almost nothing that cannot reach the faces.
constexpr double ThinnestShare = 0.025;

std::string nameOf(const TriangleMesh& mesh)
{
  return "visual mesh '" + mesh.name + "'";
}

void report(const GenerationProgress& progress, double fraction, const char* stage)
{
  if (progress && !progress(fraction, stage))
  {
    throw GenerationAbortedError(std::string("collision mesh generation aborted during ") + stage);
  }
}

/// The surface seen along its thickness axis: a frame (u, v across, n
/// along), and a bucket grid of the triangles' projections, so that the
/// line through a point of the (u, v) plane meets only the triangles of
/// its bucket.
class ProjectedSurface
{
public:
  ProjectedSurface(const TriangleMesh& mesh,
    const Vector3& centre,
    const Vector3& u,
    const Vector3& v,
    const Vector3& n)
    : Mesh(mesh)
    , Centre(centre)
    , U(u)
    , V(v)
    , N(n)
  {
    Low = Vector2(Infinity, Infinity);
    Vector2 high(-Infinity, -Infinity);
    for (const Vector3& x : mesh.positions)
    {
      const Vector2 q = project(x);
      Low = Low.cwiseMin(q);
      high = high.cwiseMax(q);
      Depth = std::max(Depth, std::abs((x - centre).dot(n)));
    }
    Extent = high - Low;
    const int cells = std::max(1, static_cast<int>(std::sqrt(mesh.triangleCount() / 4.0)));
    const double size = std::max(Extent.x(), Extent.y()) / cells;
    CellSize = size > 0.0 ? size : 1.0;
    Columns = std::max(1, static_cast<int>(std::ceil(Extent.x() / CellSize)) + 1);
    Rows = std::max(1, static_cast<int>(std::ceil(Extent.y() / CellSize)) + 1);
    Buckets.assign(static_cast<std::size_t>(Columns) * Rows, {});
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
      Vector2 a(Infinity, Infinity);
      Vector2 b(-Infinity, -Infinity);
      for (int k : mesh.triangles[t])
      {
        const Vector2 q = project(mesh.positions[k]);
        a = a.cwiseMin(q);
        b = b.cwiseMax(q);
      }
      const auto [i0, j0] = cellOf(a);
      const auto [i1, j1] = cellOf(b);
      for (int j = j0; j <= j1; ++j)
      {
        for (int i = i0; i <= i1; ++i)
        {
          Buckets[static_cast<std::size_t>(j) * Columns + i].push_back(static_cast<int>(t));
        }
      }
    }
  }

  Vector2 project(const Vector3& x) const
  {
    const Vector3 d = x - Centre;
    return Vector2(d.dot(U), d.dot(V));
  }
  Vector3 lift(const Vector2& q, double height) const
  {
    return Centre + q.x() * U + q.y() * V + height * N;
  }
  const Vector2& low() const { return Low; }
  const Vector3& axis() const { return N; }
  const Vector2& extent() const { return Extent; }

  /// Heights (along n) of the first and last crossing of the line through
  /// q; false when the line misses the surface.
  bool crossing(const Vector2& q, double& bottom, double& top) const
  {
    bottom = Infinity;
    top = -Infinity;
    forEachCrossing(q,
      [&](double height)
      {
        bottom = std::min(bottom, height);
        top = std::max(top, height);
      });
    return top > bottom;
  }

  /// Where the line through q runs inside the tissue, when the middle of
  /// its first and last crossing does not: the thickest of its inside
  /// intervals (between crossings 2k and 2k + 1, sorted; crossings closer
  /// than `merge` are one, a ray through an edge meets both triangles).
  /// False when the middle is inside already, or the crossings do not
  /// pair up.
  bool thickestInsideInterval(const Vector2& q, double merge, double& bottom, double& top) const
  {
    std::vector<double> heights;
    forEachCrossing(q, [&](double height) { heights.push_back(height); });
    std::sort(heights.begin(), heights.end());
    std::vector<double> crossings;
    for (double h : heights)
    {
      if (crossings.empty() || h - crossings.back() > merge)
      {
        crossings.push_back(h);
      }
    }
    if (crossings.size() < 4 || crossings.size() % 2 != 0)
    {
      return false;
    }
    const double middle = 0.5 * (crossings.front() + crossings.back());
    int thickest = 0;
    for (std::size_t k = 0; k < crossings.size(); k += 2)
    {
      if (middle >= crossings[k] && middle <= crossings[k + 1])
      {
        return false;
      }
      if (crossings[k + 1] - crossings[k] > crossings[thickest + 1] - crossings[thickest])
      {
        thickest = static_cast<int>(k);
      }
    }
    bottom = crossings[thickest];
    top = crossings[thickest + 1];
    return true;
  }

private:
  /// f(height) for each crossing of the line through q with the surface.
  template <class Function>
  void forEachCrossing(const Vector2& q, Function&& f) const
  {
    const auto [i, j] = cellOf(q);
    const Vector3 origin = lift(q, -2.0 * Depth - 1.0);
    for (int t : Buckets[static_cast<std::size_t>(j) * Columns + i])
    {
      const Triangle& tri = Mesh.triangles[t];
      const double s = rayTriangleHit(
        origin, N, Mesh.positions[tri[0]], Mesh.positions[tri[1]], Mesh.positions[tri[2]], 1e-9);
      if (std::isfinite(s))
      {
        f(s - 2.0 * Depth - 1.0);
      }
    }
  }

  std::pair<int, int> cellOf(const Vector2& q) const
  {
    const int i = static_cast<int>(std::floor((q.x() - Low.x()) / CellSize));
    const int j = static_cast<int>(std::floor((q.y() - Low.y()) / CellSize));
    return { std::clamp(i, 0, Columns - 1), std::clamp(j, 0, Rows - 1) };
  }

  const TriangleMesh& Mesh;
  Vector3 Centre, U, V, N;
  Vector2 Low = Vector2::Zero();
  Vector2 Extent = Vector2::Zero();
  double Depth = 0.0;
  double CellSize = 1.0;
  int Columns = 1;
  int Rows = 1;
  std::vector<std::vector<int>> Buckets;
};

void checkVisual(const TriangleMesh& visual)
{
  visual.checkConsistency();
  if (visual.triangles.empty())
  {
    throw InvalidInputError(nameOf(visual) + " has no triangles");
  }
  requireClosedOrientedManifold(visual, nameOf(visual));
}

using Loop = std::vector<Vector2>;

/// Twice the signed area of a closed polygon (positive counter-clockwise).
double signedArea(const Loop& polygon)
{
  double area = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const Vector2& a = polygon[i];
    const Vector2& b = polygon[(i + 1) % polygon.size()];
    area += a.x() * b.y() - a.y() * b.x();
  }
  return area;
}

/// The polygon of a loop of mesh vertices projected, points that project
/// onto each other (a vertical edge on the silhouette, the two ends of a
/// wall's corner) merged.
Loop projectedLoop(const TriangleMesh& mesh,
  const ProjectedSurface& surface,
  const std::vector<int>& loop)
{
  Loop points;
  double length = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    points.push_back(surface.project(mesh.positions[loop[i]]));
    length += i > 0 ? (points[i] - points[i - 1]).norm() : 0.0;
  }
  Loop merged;
  for (const Vector2& q : points)
  {
    if (merged.empty() || (q - merged.back()).norm() > 1e-6 * length)
    {
      merged.push_back(q);
    }
  }
  while (merged.size() > 1 && (merged.front() - merged.back()).norm() <= 1e-6 * length)
  {
    merged.pop_back();
  }
  return merged;
}

/// Closed loops of silhouette edges (between triangles facing +n and -n),
/// projected along n: the outline of the shadow and of its holes (the gap
/// of a tear through the thickness), and the folds of the surface.
std::vector<Loop> silhouetteLoops(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const ProjectedSurface& surface,
  const Vector3& n)
{
  std::vector<char> facingUp(mesh.triangleCount());
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const Triangle& c = mesh.triangles[t];
    const Vector3 normal = (mesh.positions[c[1]] - mesh.positions[c[0]])
                             .cross(mesh.positions[c[2]] - mesh.positions[c[0]]);
    facingUp[t] = normal.dot(n) > 0.0 ? 1 : 0;
  }
  std::vector<std::vector<int>> edgesOfVertex(mesh.vertexCount());
  std::vector<int> silhouette;
  for (int e = 0; e < static_cast<int>(adjacency.edgeCount()); ++e)
  {
    const int* t = adjacency.edgeTrianglesBegin(e);
    if (adjacency.edgeTriangleCount(e) == 2 && facingUp[t[0]] != facingUp[t[1]])
    {
      silhouette.push_back(e);
      edgesOfVertex[adjacency.edge(e)[0]].push_back(e);
      edgesOfVertex[adjacency.edge(e)[1]].push_back(e);
    }
  }
  std::vector<char> used(adjacency.edgeCount(), 0);
  std::vector<Loop> loops;
  for (int first : silhouette)
  {
    if (used[first])
    {
      continue;
    }
    used[first] = 1;
    const int start = adjacency.edge(first)[0];
    std::vector<int> loop{ start };
    int vertex = adjacency.edge(first)[1];
    while (vertex != start)
    {
      loop.push_back(vertex);
      const auto next = std::find_if(edgesOfVertex[vertex].begin(),
        edgesOfVertex[vertex].end(),
        [&](int e) { return !used[e]; });
      if (next == edgesOfVertex[vertex].end())
      {
        break;
      }
      used[*next] = 1;
      const auto& ends = adjacency.edge(*next);
      vertex = ends[0] == vertex ? ends[1] : ends[0];
    }
    if (vertex == start && loop.size() >= 3)
    {
      loops.push_back(projectedLoop(mesh, surface, loop));
    }
  }
  return loops;
}

/// Whether two segments of the closed polygon that share no end cross.
bool crossesItself(const std::vector<Vector2>& polygon)
{
  const std::size_t n = polygon.size();
  auto side = [](const Vector2& a, const Vector2& b, const Vector2& c)
  { return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x(); };
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vector2& a = polygon[i];
    const Vector2& b = polygon[(i + 1) % n];
    for (std::size_t j = i + 2; j < n; ++j)
    {
      if ((j + 1) % n == i)
        continue;
      const Vector2& c = polygon[j];
      const Vector2& d = polygon[(j + 1) % n];
      if (side(a, b, c) * side(a, b, d) < 0.0 && side(c, d, a) * side(c, d, b) < 0.0)
        return true;
    }
  }
  return false;
}

/// A raster of the surface's shadow along the axis: cells of a 256th of
/// the extent, 1 where a projected triangle covers the cell's centre.
struct ShadowRaster
{
  double cell = 1.0;
  Vector2 origin = Vector2::Zero();
  int width = 0;
  int height = 0;
  std::vector<char> inside;

  std::size_t at(int i, int j) const { return static_cast<std::size_t>(j) * width + i; }
};

/// Marks the cells of `r` (its frame set) whose centre a projected
/// triangle covers; cells beyond the frame are left out.
void coverTriangles(const TriangleMesh& mesh, const ProjectedSurface& surface, ShadowRaster& r)
{
  r.inside.assign(static_cast<std::size_t>(r.width) * r.height, 0);
  for (const Triangle& t : mesh.triangles)
  {
    const Vector2 a = (surface.project(mesh.positions[t[0]]) - r.origin) / r.cell;
    const Vector2 b = (surface.project(mesh.positions[t[1]]) - r.origin) / r.cell;
    const Vector2 c = (surface.project(mesh.positions[t[2]]) - r.origin) / r.cell;
    const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    const Vector2 low = a.cwiseMin(b).cwiseMin(c), high = a.cwiseMax(b).cwiseMax(c);
    if (std::abs(area) < 1e-12 || high.x() < 0.0 || high.y() < 0.0 || low.x() > r.width ||
        low.y() > r.height)
      continue;
    const int jEnd = std::min(static_cast<int>(high.y()), r.height - 1);
    const int iEnd = std::min(static_cast<int>(high.x()), r.width - 1);
    for (int j = std::max(0, static_cast<int>(std::floor(low.y()))); j <= jEnd; ++j)
      for (int i = std::max(0, static_cast<int>(std::floor(low.x()))); i <= iEnd; ++i)
      {
        const Vector2 q(i + 0.5, j + 0.5);
        const double u = ((b - q).x() * (c - q).y() - (b - q).y() * (c - q).x()) / area;
        const double v = ((c - q).x() * (a - q).y() - (c - q).y() * (a - q).x()) / area;
        if (u >= 0.0 && v >= 0.0 && u + v <= 1.0)
          r.inside[r.at(i, j)] = 1;
      }
  }
}

ShadowRaster rasterizeShadow(const TriangleMesh& mesh,
  const ProjectedSurface& surface,
  double cellsAcross = 256.0)
{
  ShadowRaster r;
  r.cell = std::max(surface.extent().x(), surface.extent().y()) / cellsAcross;
  r.origin = surface.low() - Vector2(3.0 * r.cell, 3.0 * r.cell);
  r.width = static_cast<int>(std::ceil(surface.extent().x() / r.cell)) + 7;
  r.height = static_cast<int>(std::ceil(surface.extent().y() / r.cell)) + 7;
  coverTriangles(mesh, surface, r);
  return r;
}

/// The raster closed by one cell: dilated, then eroded.
std::vector<char> closeByOneCell(const ShadowRaster& r)
{
  auto dilate = [&r](const std::vector<char>& from, char value)
  {
    std::vector<char> to(from);
    for (int j = 1; j + 1 < r.height; ++j)
      for (int i = 1; i + 1 < r.width; ++i)
        if (from[r.at(i, j)] != value)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di)
              if (from[r.at(i + di, j + dj)] == value)
                to[r.at(i, j)] = value;
    return to;
  };
  return dilate(dilate(r.inside, 1), 0);
}

/// Connected pieces (4-neighbours) of the empty cells: 0 is the outside
/// (reached from the raster's border), 1, 2, ... the holes; -1 on tissue.
std::vector<int> emptyPieces(const ShadowRaster& r, std::vector<int>& cellCounts)
{
  std::vector<int> piece(r.inside.size(), -1);
  cellCounts.clear();
  std::vector<std::pair<int, int>> stack;
  for (int j0 = 0; j0 < r.height; ++j0)
    for (int i0 = 0; i0 < r.width; ++i0)
    {
      if (r.inside[r.at(i0, j0)] || piece[r.at(i0, j0)] >= 0)
        continue;
      const int label = static_cast<int>(cellCounts.size());
      cellCounts.push_back(1);
      piece[r.at(i0, j0)] = label;
      stack.assign(1, { i0, j0 });
      while (!stack.empty())
      {
        const auto [i, j] = stack.back();
        stack.pop_back();
        const int next[4][2] = { { i + 1, j }, { i - 1, j }, { i, j + 1 }, { i, j - 1 } };
        for (const auto& [x, y] : next)
          if (x >= 0 && y >= 0 && x < r.width && y < r.height && !r.inside[r.at(x, y)] &&
              piece[r.at(x, y)] < 0)
          {
            piece[r.at(x, y)] = label;
            ++cellCounts[label];
            stack.emplace_back(x, y);
          }
      }
    }
  return piece;
}

/// The loops between tissue cells and `empty` cells, tissue on the left
/// (the outline counter-clockwise, holes clockwise), corner to corner,
/// smoothed a little (the staircase of the cells).
std::vector<Loop> traceCellBorders(const ShadowRaster& r, const std::vector<char>& empty)
{
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> next;
  for (int j = 1; j + 1 < r.height; ++j)
    for (int i = 1; i + 1 < r.width; ++i)
    {
      if (empty[r.at(i, j)])
        continue;
      if (empty[r.at(i, j - 1)])
        next[{ i, j }].push_back({ i + 1, j });
      if (empty[r.at(i + 1, j)])
        next[{ i + 1, j }].push_back({ i + 1, j + 1 });
      if (empty[r.at(i, j + 1)])
        next[{ i + 1, j + 1 }].push_back({ i, j + 1 });
      if (empty[r.at(i - 1, j)])
        next[{ i, j + 1 }].push_back({ i, j });
    }
  std::vector<Loop> loops;
  while (!next.empty())
  {
    std::vector<std::pair<int, int>> corners{ next.begin()->first };
    while (true)
    {
      auto found = next.find(corners.back());
      if (found == next.end() || found->second.empty())
        break;
      const std::pair<int, int> to = found->second.back();
      found->second.pop_back();
      if (found->second.empty())
        next.erase(found);
      if (to == corners.front())
        break;
      corners.push_back(to);
    }
    Loop loop;
    for (const auto& [i, j] : corners)
      loop.push_back(r.origin + r.cell * Vector2(i, j));
    for (int pass = 0; pass < 3; ++pass)
    {
      Loop smooth(loop.size());
      for (std::size_t k = 0; k < loop.size(); ++k)
        smooth[k] = 0.25 * loop[(k + loop.size() - 1) % loop.size()] + 0.5 * loop[k] +
                    0.25 * loop[(k + 1) % loop.size()];
      loop = std::move(smooth);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

/// Holes of the raster of fewer cells are filled (gaps between the steps of
/// a staircase, not tears).
constexpr int SmallestHole = 16;

/// Holes of the raster within this many cells of each other are looked at
/// finer (ChannelRefinement times) for a see-through channel between them.
constexpr int ChannelReach = 4;
constexpr int ChannelRefinement = 8;

/// The shortest channel of 4-neighbour cells of `r` that `passable`
/// admits, breadth first from `seeds` (in order) to the first cell that
/// `reached` accepts: its cells from that one back to a seed, or none.
template <class Passable, class Reached>
std::vector<int> shortestCellChannel(const ShadowRaster& r,
  const std::vector<int>& seeds,
  Passable passable,
  Reached reached)
{
  std::vector<int> from(static_cast<std::size_t>(r.width) * r.height, -2);
  std::vector<int> queue = seeds;
  for (int c : seeds)
    from[c] = -1;
  for (std::size_t k = 0; k < queue.size(); ++k)
  {
    const int c = queue[k];
    if (reached(c))
    {
      std::vector<int> channel;
      for (int g = c; g >= 0; g = from[g])
        channel.push_back(g);
      return channel;
    }
    const int i = c % r.width;
    const int j = c / r.width;
    const int next[4][2] = { { i + 1, j }, { i - 1, j }, { i, j + 1 }, { i, j - 1 } };
    for (const auto& [x, y] : next)
    {
      if (x < 0 || y < 0 || x >= r.width || y >= r.height)
        continue;
      const int n = static_cast<int>(r.at(x, y));
      if (from[n] == -2 && passable(n))
      {
        from[n] = c;
        queue.push_back(n);
      }
    }
  }
  return {};
}

/// Opens the cells of `r` along a see-through channel from hole a to hole
/// b (pieces of `piece`) near cells ca and cb, if the finer raster of the
/// cells around them has one; whether it had.
bool openChannel(const TriangleMesh& mesh,
  const ProjectedSurface& surface,
  ShadowRaster& r,
  const std::vector<int>& piece,
  std::array<int, 4> pair)
{
  const auto [a, b, ca, cb] = pair;
  const int i0 = std::max(1, std::min(ca % r.width, cb % r.width) - ChannelReach);
  const int i1 = std::min(r.width - 2, std::max(ca % r.width, cb % r.width) + ChannelReach);
  const int j0 = std::max(1, std::min(ca / r.width, cb / r.width) - ChannelReach);
  const int j1 = std::min(r.height - 2, std::max(ca / r.width, cb / r.width) + ChannelReach);
  ShadowRaster fine;
  fine.cell = r.cell / ChannelRefinement;
  fine.origin = r.origin + r.cell * Vector2(i0, j0);
  fine.width = (i1 - i0 + 1) * ChannelRefinement;
  fine.height = (j1 - j0 + 1) * ChannelRefinement;
  coverTriangles(mesh, surface, fine);
  auto coarse = [&](int f) {
    return r.at(i0 + f % fine.width / ChannelRefinement, j0 + f / fine.width / ChannelRefinement);
  };
  // Breadth first over the fine empty cells, from those in hole a.
  std::vector<int> seeds;
  for (int f = 0; f < static_cast<int>(fine.inside.size()); ++f)
    if (!fine.inside[f] && piece[coarse(f)] == a)
      seeds.push_back(f);
  const std::vector<int> channel = shortestCellChannel(
    fine,
    seeds,
    [&](int f) { return !fine.inside[f]; },
    [&](int f) { return piece[coarse(f)] == b; });
  for (int f : channel)
    r.inside[coarse(f)] = 0;
  return !channel.empty();
}

/// A tear's slit narrower than a cell somewhere along it leaves the raster
/// several holes where the surface has one opening, and the collision mesh
/// spanned the lips between them (issue 14: fine longitudinal tear, seed
/// 1004, two holes 0.26 mm apart joined by a channel 0.05 mm wide). Holes
/// the outline keeps within ChannelReach cells of each other are joined
/// where a finer raster of the cells between sees through along a
/// channel: the cells along it are opened. (Joining every hole piece, the
/// small ones at a slit's narrow ends too, reshuffled which sweep cases
/// bind.)
void openChannelsBetweenHoles(const TriangleMesh& mesh,
  const ProjectedSurface& surface,
  ShadowRaster& r)
{
  std::vector<int> counts;
  const std::vector<int> piece = emptyPieces(r, counts);
  // Holes that outlineAndHoles keeps: SmallestHole cells at least, and a
  // 50th of the outline's length (cell sides along tissue, both).
  std::vector<int> sides(counts.size(), 0);
  for (int j = 1; j + 1 < r.height; ++j)
    for (int i = 1; i + 1 < r.width; ++i)
      if (r.inside[r.at(i, j)])
        for (const std::size_t c :
          { r.at(i + 1, j), r.at(i - 1, j), r.at(i, j + 1), r.at(i, j - 1) })
          if (piece[c] >= 0)
            ++sides[piece[c]];
  auto kept = [&](int hole)
  { return counts[hole] >= SmallestHole && 50 * sides[hole] >= sides.front(); };
  // The closest cells of each pair of kept holes (a < b) within reach.
  std::map<std::pair<int, int>, std::pair<int, std::array<int, 2>>> closest;
  for (int j = 1; j + 1 < r.height; ++j)
    for (int i = 1; i + 1 < r.width; ++i)
    {
      const int a = piece[r.at(i, j)];
      if (a <= 0 || !kept(a))
        continue;
      for (int y = std::max(0, j - ChannelReach); y <= std::min(r.height - 1, j + ChannelReach);
           ++y)
        for (int x = std::max(0, i - ChannelReach); x <= std::min(r.width - 1, i + ChannelReach);
             ++x)
        {
          const int b = piece[r.at(x, y)];
          const int distance = (x - i) * (x - i) + (y - j) * (y - j);
          auto found = closest.find({ a, b });
          if (b > a && kept(b) && (found == closest.end() || distance < found->second.first))
            closest[{ a, b }] = { distance,
              { { static_cast<int>(r.at(i, j)), static_cast<int>(r.at(x, y)) } } };
        }
    }
  for (const auto& [holes, nearest] : closest)
    openChannel(mesh,
      surface,
      r,
      piece,
      { { holes.first, holes.second, nearest.second[0], nearest.second[1] } });
}

/// Reopens the bays the closing cut off from the outside (`empty` as
/// shadowLoops made it): a gap reaching in from the rim through a mouth
/// narrower than the closing, such as a longitudinal tear's slit whose
/// inner lip broke off in the segmentation, its free tip against the
/// other lip (issue 14: fine longitudinal tear, seed 1023; the filled slit
/// left the collision mesh spanning it). A piece of the closed raster's
/// empty cells, of SmallestHole cells at least, all outside before the
/// closing, gets its empty cells back, joined to the outside along the
/// shortest channel of the raster's empty cells, so the outline follows
/// the bay in. (Every strip the closing filled was tried too: a ragged,
/// perforated rim's slits then drew the border into the tissue, and
/// fewer tears prepared.)
void reopenBays(const ShadowRaster& raster,
  const std::vector<int>& piece,
  const std::vector<int>& closedPiece,
  const std::vector<int>& closedCounts,
  std::vector<char>& empty)
{
  // Each closed piece's cells that were outside before the closing.
  std::vector<std::vector<int>> outsideBefore(closedCounts.size());
  for (int c = 0; c < static_cast<int>(piece.size()); ++c)
    if (closedPiece[c] > 0 && piece[c] == 0 && closedCounts[closedPiece[c]] >= SmallestHole)
      outsideBefore[closedPiece[c]].push_back(c);
  for (std::size_t bay = 1; bay < closedCounts.size(); ++bay)
  {
    // Some cells a hole before the closing too: kept or filled as a hole.
    if (outsideBefore[bay].empty() ||
        static_cast<int>(outsideBefore[bay].size()) < closedCounts[bay])
      continue;
    for (int c : outsideBefore[bay])
      empty[c] = 1;
    for (int c : shortestCellChannel(
           raster,
           outsideBefore[bay],
           [&](int n) { return piece[n] == 0; },
           [&](int n) { return closedPiece[n] == 0; }))
      empty[c] = 1;
  }
}

/// The loops of the surface's shadow along the axis, from its raster: for
/// a rough surface (a segmentation's staircase), whose silhouette edges
/// wander over the step walls and may cross themselves. Holes of fewer
/// than 16 cells are filled (gaps between the steps, not tears).
std::vector<Loop> shadowLoops(const TriangleMesh& mesh, const ProjectedSurface& surface)
{
  ShadowRaster raster = rasterizeShadow(mesh, surface);
  openChannelsBetweenHoles(mesh, surface, raster);
  std::vector<int> cellCounts;
  const std::vector<int> piece = emptyPieces(raster, cellCounts);
  // The outside closed by one cell (pinholes between projected triangles,
  // the staircase's notches); the holes not (a tear's gap narrows to
  // nothing at its ends, and its hole must reach them).
  ShadowRaster closed = raster;
  closed.inside = closeByOneCell(raster);
  std::vector<int> closedCounts;
  const std::vector<int> closedPiece = emptyPieces(closed, closedCounts);
  std::vector<char> empty(piece.size(), 0);
  for (std::size_t c = 0; c < piece.size(); ++c)
    empty[c] = closedPiece[c] == 0 || (piece[c] > 0 && cellCounts[piece[c]] >= SmallestHole);
  reopenBays(raster, piece, closedPiece, closedCounts, empty);
  return traceCellBorders(raster, empty);
}

std::vector<Vector2> resampleEvenly(const std::vector<Vector2>& polygon, int count);

/// `count` points along the closed polygon: its corners (turning by more
/// than 40 degrees over a sample spacing each way, two sample spacings
/// apart at least, at most count / 2, sharpest first) and the rest at equal arc
/// lengths between them.
std::vector<Vector2> resample(const std::vector<Vector2>& polygon, int count)
{
  const std::size_t n = polygon.size();
  std::vector<double> at(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    at[i + 1] = at[i] + (polygon[(i + 1) % n] - polygon[i]).norm();
  }
  const double total = at.back();
  // The turn at each point seen over a sample spacing each way (a
  // chamfered corner is one corner; a jagged outline has none).
  const double window = total / count;
  auto pointAt = [&](double s)
  {
    s = std::fmod(std::fmod(s, total) + total, total);
    const std::size_t i = std::min(
      static_cast<std::size_t>(std::upper_bound(at.begin(), at.end(), s) - at.begin()) - 1, n - 1);
    const double span = at[i + 1] - at[i];
    const double f = span > 0.0 ? (s - at[i]) / span : 0.0;
    return Vector2((1.0 - f) * polygon[i] + f * polygon[(i + 1) % n]);
  };
  std::vector<std::pair<double, std::size_t>> turns;
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vector2 a = (polygon[i] - pointAt(at[i] - window)).normalized();
    const Vector2 b = (pointAt(at[i] + window) - polygon[i]).normalized();
    const double turn = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    if (std::abs(turn) > 40.0 * 3.14159265358979 / 180.0)
    {
      turns.emplace_back(-std::abs(turn), i);
    }
  }
  std::sort(turns.begin(), turns.end());
  std::vector<std::size_t> corners;
  for (const auto& turn : turns)
  {
    const bool apart = std::all_of(corners.begin(),
      corners.end(),
      [&](std::size_t c)
      {
        const double d = std::abs(at[c] - at[turn.second]);
        return std::min(d, total - d) > 2.0 * window;
      });
    if (apart && static_cast<int>(corners.size()) < count / 2)
    {
      corners.push_back(turn.second);
    }
  }
  std::sort(corners.begin(), corners.end());
  if (corners.empty())
  {
    return resampleEvenly(polygon, count);
  }
  // The free points shared out between the corners by arc length.
  const int pieces = static_cast<int>(corners.size());
  const int free = count - pieces;
  std::vector<Vector2> result;
  double carried = 0.0;
  int placed = 0;
  for (int k = 0; k < pieces; ++k)
  {
    const std::size_t from = corners[k];
    const std::size_t to = corners[(k + 1) % pieces];
    double length = at[to] - at[from];
    if (length <= 0.0)
    {
      length += total;
    }
    const double share = free * length / total + carried;
    // The last piece takes what is left (round-off must not lose a point).
    const int inside = k + 1 == pieces ? free - placed : static_cast<int>(std::floor(share + 1e-9));
    carried = share - inside;
    placed += inside;
    for (int m = 0; m <= inside; ++m)
    {
      double s = at[from] + length * m / (inside + 1);
      s = s >= total ? s - total : s;
      const std::size_t segment =
        static_cast<std::size_t>(std::upper_bound(at.begin(), at.end(), s) - at.begin()) - 1;
      const std::size_t i = std::min(segment, n - 1);
      const double span = at[i + 1] - at[i];
      const double f = span > 0.0 ? (s - at[i]) / span : 0.0;
      result.push_back((1.0 - f) * polygon[i] + f * polygon[(i + 1) % n]);
    }
  }
  return result;
}

/// `count` points along the closed polygon at equal arc lengths.
std::vector<Vector2> resampleEvenly(const std::vector<Vector2>& polygon, int count)
{
  std::vector<double> at(polygon.size() + 1, 0.0);
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    at[i + 1] = at[i] + (polygon[(i + 1) % polygon.size()] - polygon[i]).norm();
  }
  std::vector<Vector2> result;
  std::size_t segment = 0;
  for (int k = 0; k < count; ++k)
  {
    const double s = at.back() * k / count;
    while (segment + 1 < polygon.size() && at[segment + 1] < s)
    {
      ++segment;
    }
    const double span = at[segment + 1] - at[segment];
    const double f = span > 0.0 ? (s - at[segment]) / span : 0.0;
    result.push_back((1.0 - f) * polygon[segment] + f * polygon[(segment + 1) % polygon.size()]);
  }
  return result;
}

/// The point of segment ab nearest q.
Vector2 nearestOnSegment(const Vector2& a, const Vector2& b, const Vector2& q)
{
  const Vector2 d = b - a;
  const double t = std::clamp((q - a).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
  return a + t * d;
}

/// The point of the closed polygon nearest to q (q itself for none).
Vector2 nearestOnLoop(const std::vector<Vector2>& loop, const Vector2& q)
{
  Vector2 nearest = q;
  double best = Infinity;
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    const Vector2 p = nearestOnSegment(loop[i], loop[(i + 1) % loop.size()], q);
    if ((p - q).squaredNorm() < best)
    {
      best = (p - q).squaredNorm();
      nearest = p;
    }
  }
  return nearest;
}

/// How far q is from the closed polygon (infinitely for none).
double distanceToPolygon(const std::vector<Vector2>& polygon, const Vector2& q)
{
  return polygon.empty() ? Infinity : (q - nearestOnLoop(polygon, q)).norm();
}

/// Points of a triangular lattice of spacing h inside the outline and out
/// of its holes (loops[0] and the rest), at least `margin` from their
/// edges, nearest the edges last; with `tissue`, only where the line along
/// the axis meets the surface (not in the closed ends of a tear's gap) and
/// the tissue is at least 2 `thinnest` thick there.
/// Inside the region of an outline and its holes (inside an odd number of
/// its loops).
bool insideLoops(const std::vector<Loop>& loops, const Vector2& q)
{
  bool inside = false;
  for (const Loop& loop : loops)
  {
    inside = insidePolygon(loop, q) ? !inside : inside;
  }
  return inside;
}

double distanceToLoops(const std::vector<Loop>& loops, const Vector2& q)
{
  double best = Infinity;
  for (const Loop& loop : loops)
  {
    best = std::min(best, distanceToPolygon(loop, q));
  }
  return best;
}

/// The distance from q to the nearest point of `loops` ahead of it, within
/// 60 degrees of `ahead` (unit): what a move of q along `ahead` can reach.
/// Each loop edge counts by its ends and its point nearest q.
double distanceAheadToLoops(const std::vector<Loop>& loops, const Vector2& q, const Vector2& ahead)
{
  double best = Infinity;
  const auto consider = [&](const Vector2& p)
  {
    const Vector2 offset = p - q;
    const double distance = offset.norm();
    if (offset.dot(ahead) >= 0.5 * distance)
      best = std::min(best, distance);
  };
  for (const Loop& loop : loops)
  {
    for (std::size_t i = 0; i < loop.size(); ++i)
    {
      consider(loop[i]);
      consider(nearestOnSegment(loop[i], loop[(i + 1) % loop.size()], q));
    }
  }
  return best;
}

std::vector<Vector2> latticeInside(const std::vector<Loop>& loops,
  double h,
  double margin,
  const ProjectedSurface* tissue = nullptr,
  double thinnest = 0.0,
  double phase = 0.0)
{
  Vector2 low(Infinity, Infinity);
  Vector2 high(-Infinity, -Infinity);
  for (const Vector2& p : loops.front())
  {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const double rowHeight = h * std::sqrt(3.0) / 2.0;
  // The phase moves the lattice by its share of the lattice vector one and
  // a half spacings along the rows and one row across: 0 and 1 give the
  // same points, 1/3 and 2/3 the centres of its triangles.
  low -= Vector2(1.5 * h, rowHeight) * phase;
  std::vector<std::pair<double, Vector2>> points;
  const int rows = static_cast<int>((high.y() - low.y()) / rowHeight) + 1;
  const int columns = static_cast<int>((high.x() - low.x()) / h) + 1;
  if (static_cast<double>(rows) * columns > 4e6)
  {
    return {};
  }
  for (int j = 0; j <= rows; ++j)
  {
    for (int i = 0; i <= columns; ++i)
    {
      const Vector2 q(low.x() + (i + (j % 2 ? 0.5 : 0.0)) * h, low.y() + j * rowHeight);
      if (!insideLoops(loops, q))
      {
        continue;
      }
      const double d = distanceToLoops(loops, q);
      double bottom = 0.0;
      double top = 0.0;
      if (d >= margin && (tissue == nullptr ||
                           (tissue->crossing(q, bottom, top) && top - bottom >= 2.0 * thinnest)))
      {
        points.emplace_back(d, q);
      }
    }
  }
  std::stable_sort(
    points.begin(), points.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<Vector2> result;
  for (const auto& p : points)
  {
    result.push_back(p.second);
  }
  return result;
}

/// Flips inner edges that join two border vertices (a border vertex with
/// one triangle: an "ear") where the quadrilateral of its two triangles is
/// convex and the new edge reaches an inner vertex: every border vertex
/// then has an inner neighbour, and the binding's positive and negative
/// paths of such an edge cannot both run along the rim.
void flipBorderChords(std::vector<Triangle>& triangles,
  const std::vector<Vector2>& points,
  int borderCount)
{
  auto isBorder = [&](int v) { return v < borderCount; };
  auto cross = [&](int a, int b, int c)
  {
    const Vector2 ab = points[b] - points[a];
    const Vector2 ac = points[c] - points[a];
    return ab.x() * ac.y() - ab.y() * ac.x();
  };
  for (int pass = 0; pass < 4; ++pass)
  {
    bool flipped = false;
    std::map<std::pair<int, int>, std::vector<int>> edgeTriangles;
    for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        edgeTriangles[std::minmax(triangles[t][k], triangles[t][(k + 1) % 3])].push_back(t);
      }
    }
    std::vector<char> changed(triangles.size(), 0);
    for (const auto& [edge, owners] : edgeTriangles)
    {
      if (owners.size() != 2 || !isBorder(edge.first) || !isBorder(edge.second) ||
          changed[owners[0]] || changed[owners[1]])
      {
        continue;
      }
      // The two opposite vertices; flip to an inner one.
      int opposite[2];
      for (int s = 0; s < 2; ++s)
      {
        const Triangle& t = triangles[owners[s]];
        opposite[s] = t[0] != edge.first && t[0] != edge.second
                        ? t[0]
                        : (t[1] != edge.first && t[1] != edge.second ? t[1] : t[2]);
      }
      if (isBorder(opposite[0]) && isBorder(opposite[1]))
      {
        continue;
      }
      const int a = edge.first;
      const int b = edge.second;
      const int c = opposite[0];
      const int d = opposite[1];
      // Convex: c and d on opposite sides of ab, a and b on opposite sides of cd.
      if (!(cross(a, b, c) * cross(a, b, d) < 0.0 && cross(c, d, a) * cross(c, d, b) < 0.0))
      {
        continue;
      }
      // Counter-clockwise: (c, d, a) and (d, c, b) or the other way round.
      const bool left = cross(c, d, a) > 0.0;
      triangles[owners[0]] = left ? Triangle{ { c, d, a } } : Triangle{ { d, c, a } };
      triangles[owners[1]] = left ? Triangle{ { d, c, b } } : Triangle{ { c, d, b } };
      changed[owners[0]] = changed[owners[1]] = 1;
      flipped = true;
    }
    if (!flipped)
    {
      break;
    }
  }
}

/// Border vertices of a mesh of `vertices`: about 3.8 sqrt(V), which gives
/// the triangle counts of the thesis's hand-made steak meshes within 6%.
int borderVertexCountFor(int vertices)
{
  return std::clamp(static_cast<int>(std::lround(3.8 * std::sqrt(vertices))), 4, vertices - 3);
}

/// Half the thickness along the axis at q (and the middle there), or -1
/// where the line misses the surface.
double halfThicknessAt(const ProjectedSurface& surface, const Vector2& q, double& middle)
{
  double bottom = 0.0;
  double top = 0.0;
  if (!surface.crossing(q, bottom, top))
  {
    return -1.0;
  }
  middle = 0.5 * (bottom + top);
  return 0.5 * (top - bottom);
}

/// A point of the outline moved `inward` (unit, toward the tissue) until
/// the local half thickness reaches it.
Vector2 movedIn(const ProjectedSurface& surface,
  const Vector2& q,
  const Vector2& inward,
  double extent,
  double maximumDepth = Infinity)
{
  double depth = std::min(1e-3 * extent, maximumDepth);
  double middle = 0.0;
  for (int iteration = 0; iteration < 12; ++iteration)
  {
    const double half = halfThicknessAt(surface, q + depth * inward, middle);
    depth = std::min(half > 0.0 ? std::min(half, 0.25 * extent) : 1.5 * depth, maximumDepth);
  }
  return q + depth * inward;
}

/// q, or the nearest point (rings of growing radius around it) where the
/// tissue is at least `thinnest` thick.
Vector2 ontoTissue(const ProjectedSurface& surface, Vector2 q, double thinnest, double extent)
{
  double middle = 0.0;
  for (double radius = 1e-3 * extent;
       halfThicknessAt(surface, q, middle) < thinnest && radius < 0.1 * extent;
       radius *= 1.5)
  {
    for (int k = 0; k < 16; ++k)
    {
      const double angle = 2.0 * M_PI * k / 16.0;
      const Vector2 candidate = q + radius * Vector2(std::cos(angle), std::sin(angle));
      if (halfThicknessAt(surface, candidate, middle) >= thinnest)
      {
        q = candidate;
        break;
      }
    }
  }
  return q;
}

/// The border of the collision mid-surface: the outline resampled to
/// `borderCount` points and moved in until the local half thickness
/// reaches it, so that the border spheres reach the rim.
std::vector<Vector2> placeBorder(const ProjectedSurface& surface,
  const std::vector<Vector2>& silhouette,
  const std::vector<Loop>& otherLoops,
  int borderCount,
  double extent,
  double largestThickness)
{
  std::vector<Vector2> border = resample(silhouette, borderCount);
  if (static_cast<int>(border.size()) != borderCount)
  {
    border = resampleEvenly(silhouette, borderCount);
  }
  {
    std::vector<Vector2> moved(border.size());
    for (std::size_t i = 0; i < border.size(); ++i)
    {
      const Vector2& previous = border[(i + border.size() - 1) % border.size()];
      const Vector2& next = border[(i + 1) % border.size()];
      const Vector2 along = (next - previous).normalized();
      // Less than half the way to another loop of the outline ahead (a
      // hole about a thickness from the rim): moved in from both sides, the
      // two borders would cross. A loop beside or behind (a tear's other
      // lip) does not limit the move.
      const Vector2 inward(-along.y(), along.x());
      const double room = 0.45 * distanceAheadToLoops(otherLoops, border[i], inward);
      moved[i] = movedIn(surface, border[i], inward, extent, room);
    }
    // Moving in gathers points on concave stretches: spread them evenly
    // again along the moved outline (its corners kept).
    border = resample(moved, borderCount);
    if (static_cast<int>(border.size()) != borderCount)
    {
      border = resampleEvenly(moved, borderCount);
    }
    // On a rough outline (a segmentation's staircase) a point moved in by
    // its neighbours' inward direction, or resampled across a concave jag,
    // can land beside the tissue or on a sliver of it: it goes to the
    // nearest point where the tissue is at least a twentieth of its largest
    // thickness (rings of growing radius around it), so that its sphere
    // has a radius to reach the rim with.
    for (Vector2& q : border)
      q = ontoTissue(surface, q, ThinnestShare * largestThickness, extent);
  }
  return border;
}

/// Arc length of the point of closed polyline `loop` nearest q (`at`:
/// the arc length at each loop vertex, loop.size() + 1 entries).
double arcLengthNearest(const Loop& loop, const std::vector<double>& at, const Vector2& q)
{
  double best = Infinity, where = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    const Vector2& a = loop[i];
    const Vector2 ab = loop[(i + 1) % loop.size()] - a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((q - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    const double d = (a + t * ab - q).squaredNorm();
    if (d < best)
    {
      best = d;
      where = at[i] + t * (at[i + 1] - at[i]);
    }
  }
  return where;
}

/// Whether segment [a, b] passes over a place where the tissue is thinner
/// than `thinnest` (32 samples inside it).
bool spansNoTissue(const ProjectedSurface& surface,
  const Vector2& a,
  const Vector2& b,
  double thinnest)
{
  double middle = 0.0;
  for (int k = 1; k < 32; ++k)
    if (halfThicknessAt(surface, a + (b - a) * (k / 32.0), middle) < thinnest)
      return true;
  return false;
}

/// Whether segments [a, b] and [c, d] cross (touching ends excluded).
bool segmentsCross(const Vector2& a, const Vector2& b, const Vector2& c, const Vector2& d)
{
  const auto side = [](const Vector2& p, const Vector2& q, const Vector2& r)
  { return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x()); };
  const double abc = side(a, b, c), abd = side(a, b, d), cda = side(c, d, a), cdb = side(c, d, b);
  return ((abc > 0.0 && abd < 0.0) || (abc < 0.0 && abd > 0.0)) &&
         ((cda > 0.0 && cdb < 0.0) || (cda < 0.0 && cdb > 0.0));
}

/// Whether `added` between border[i] and border[i + 1] keeps the loop
/// simple: its two chords cross no other chord of the loop.
bool keepsLoopSimple(const Loop& border, std::size_t i, const Vector2& added)
{
  const std::size_t m = border.size();
  const Vector2& a = border[i];
  const Vector2& b = border[(i + 1) % m];
  for (std::size_t j = 0; j < m; ++j)
  {
    if (j == i)
      continue; // the chord being replaced
    const Vector2& c = border[j];
    const Vector2& d = border[(j + 1) % m];
    if (segmentsCross(a, added, c, d) || segmentsCross(added, b, c, d))
      return false;
  }
  return true;
}

/// The border made to follow the bays of its outline (issue 14: a border
/// chord that spans a bay or a bend of a slit leaves collision triangles
/// over no tissue, round which the binding's paths must detour and cross).
/// Where the outline between two consecutive border points runs on the
/// tissue's side of their chord (the tissue lies left of every loop) by
/// more than the larger half thickness at the two points, a border point
/// is added at the outline's deepest point there, moved in like the
/// others; again on the two new chords, `budget` points at most. Returns
/// the border, its points in the outline's order.
Loop followBays(const ProjectedSurface& surface,
  const Loop& outline,
  Loop border,
  double extent,
  double thinnest,
  int budget)
{
  const std::size_t n = outline.size();
  std::vector<double> at(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    at[i + 1] = at[i] + (outline[(i + 1) % n] - outline[i]).norm();
  const double total = at.back();
  std::vector<double> arc(border.size());
  for (std::size_t i = 0; i < border.size(); ++i)
    arc[i] = arcLengthNearest(outline, at, border[i]);
  double middle = 0.0;
  for (std::size_t i = 0; i < border.size() && budget > 0;)
  {
    const std::size_t next = (i + 1) % border.size();
    const Vector2 a = border[i], b = border[next];
    const Vector2 chord = b - a;
    const double length = chord.norm();
    const double from = arc[i];
    double to = arc[next];
    if (to <= from)
      to += total;
    if (to - from > 0.5 * total) // not in the outline's order: left alone
    {
      ++i;
      continue;
    }
    // A bay is followed when deeper than the border's half thickness; a
    // chord over no tissue (across a slit's bend) when the outline's detour
    // is a quarter of that, and a twentieth of the chord (not for a jag of
    // a rough rim).
    const double half =
      std::max(halfThicknessAt(surface, a, middle), halfThicknessAt(surface, b, middle));
    const double tolerance =
      spansNoTissue(surface, a, b, thinnest) ? std::max(0.25 * half, 0.05 * length) : half;
    double deepest = tolerance;
    std::size_t deepestVertex = n;
    for (std::size_t k = 0; k < n && length > 0.0; ++k)
    {
      double s = at[k];
      if (s < from)
        s += total;
      // Off the chord's ends by a tenth of the arc at least: no sliver.
      if (s <= from + 0.1 * (to - from) || s >= to - 0.1 * (to - from))
        continue;
      const Vector2 p = outline[k] - a;
      const double left = (chord.x() * p.y() - chord.y() * p.x()) / length;
      if (left > deepest)
      {
        deepest = left;
        deepestVertex = k;
      }
    }
    if (deepestVertex == n)
    {
      ++i;
      continue;
    }
    const Vector2& before = outline[(deepestVertex + n - 1) % n];
    const Vector2& after = outline[(deepestVertex + 1) % n];
    const Vector2 along = (after - before).normalized();
    const Vector2 added = ontoTissue(surface,
      movedIn(surface, outline[deepestVertex], Vector2(-along.y(), along.x()), extent),
      thinnest,
      extent);
    // Not beside a chord's end (its paths would run side by side with the
    // end's and cross them), nor making the loop cross itself (a bay
    // narrower than the tissue beside it is thick).
    const double apart = 0.25 * length;
    if ((added - a).norm() < apart || (added - b).norm() < apart ||
        !keepsLoopSimple(border, i, added))
    {
      ++i;
      continue;
    }
    border.insert(border.begin() + static_cast<std::ptrdiff_t>(i + 1), added);
    arc.insert(arc.begin() + static_cast<std::ptrdiff_t>(i + 1), at[deepestVertex]);
    --budget; // the chord from i is looked at again, now shorter
  }
  return border;
}

/// A border segment: its loop among the borders and its first point.
struct BorderSegment
{
  std::size_t loop = 0;
  std::size_t index = 0;
};

/// Two segments of the border loops that cross (of one loop or of two),
/// the first found; false when the borders are simple and apart.
bool crossingBorderSegments(const std::vector<Loop>& borders, std::array<BorderSegment, 2>& found)
{
  for (std::size_t a = 0; a < borders.size(); ++a)
    for (std::size_t i = 0; i < borders[a].size(); ++i)
    {
      const Vector2& p = borders[a][i];
      const Vector2& q = borders[a][(i + 1) % borders[a].size()];
      for (std::size_t b = a; b < borders.size(); ++b)
        for (std::size_t j = b == a ? i + 1 : 0; j < borders[b].size(); ++j)
        {
          if (segmentsCross(p, q, borders[b][j], borders[b][(j + 1) % borders[b].size()]))
          {
            found = { { { a, i }, { b, j } } };
            return true;
          }
        }
    }
  return false;
}

/// Borders that cross, untangled (issue 14: "its outline crosses itself"
/// on eight sweep cases, coarse cartilages and torn menisci, a sheet).
/// Each loop is moved in by its own local half thickness, spread again and
/// put onto tissue, so on a ragged, thin rim two borders a notch apart, or
/// the stretches of one border either side of a notch, can cross. The four
/// points of two crossing segments move halfway back to their own outline
/// loop (where the rim is), at most `BackSteps` times for a crossing, a
/// point only where the tissue is `thinnest` thick at least (so its sphere
/// still has a radius); one
/// that remains drops the point of the two segments that moved in
/// farthest (the inner lattice takes its place in the count). A loop
/// keeps three points at least, and at most three points are dropped in
/// all: past that the borders are left as placed and the triangulation
/// reports the crossing. A ragged rim's tangles took one drop at most; a
/// band twisted through 90 degrees (the PCL) overlaps itself seen along
/// any axis, and untangled at the cost of 25 points its one-axis
/// mid-surface came 24 mm from the tissue: it must fail, so that the
/// automatic method takes the band.
void untangleBorders(const ProjectedSurface& surface,
  std::vector<Loop>& borders,
  const std::vector<Loop>& outline,
  double thinnest)
{
  constexpr int BackSteps = 6;
  constexpr int MostDropped = 3;
  const std::vector<Loop> placed = borders;
  int droppedCount = 0;
  using BorderPoint = std::pair<std::size_t, std::size_t>; // loop, index
  // Steps back taken per crossing (its two segments' first points); the
  // indices shift when a point is dropped, so the counts start anew then.
  std::map<std::array<BorderPoint, 2>, int> stepsBack;
  std::array<BorderSegment, 2> crossing;
  for (int round = 0; round < 200 && crossingBorderSegments(borders, crossing); ++round)
  {
    std::vector<BorderPoint> ends;
    for (const BorderSegment& segment : crossing)
    {
      ends.emplace_back(segment.loop, segment.index);
      ends.emplace_back(segment.loop, (segment.index + 1) % borders[segment.loop].size());
    }
    if (stepsBack[{ { ends[0], ends[2] } }]++ < BackSteps)
    {
      for (const auto& [loop, i] : ends)
      {
        Vector2& q = borders[loop][i];
        const Vector2 back = 0.5 * (q + nearestOnLoop(outline[loop], q));
        double middle = 0.0;
        if (halfThicknessAt(surface, back, middle) >= thinnest)
          q = back;
      }
      continue;
    }
    auto depth = [&](const BorderPoint& end)
    {
      const Vector2& q = borders[end.first][end.second];
      return borders[end.first].size() > 3 ? (nearestOnLoop(outline[end.first], q) - q).norm()
                                           : -1.0;
    };
    const BorderPoint dropped = *std::max_element(ends.begin(),
      ends.end(),
      [&](const BorderPoint& x, const BorderPoint& y) { return depth(x) < depth(y); });
    if (depth(dropped) < 0.0)
      return;
    if (++droppedCount > MostDropped)
    {
      borders = placed; // not a ragged rim: an outline that overlaps itself
      return;
    }
    borders[dropped.first].erase(
      borders[dropped.first].begin() + static_cast<std::ptrdiff_t>(dropped.second));
    stepsBack.clear();
  }
}

/// At least `interiorCount` lattice points inside the borders (the largest
/// spacing that gives them, by bisection), kept off the border; fewer if
/// none fits.
std::vector<Vector2> interiorLattice(const ProjectedSurface& surface,
  const std::vector<Loop>& borders,
  int interiorCount,
  double extent,
  double largestThickness,
  double phase)
{
  double perimeter = 0.0;
  std::size_t count = 0;
  for (const Loop& border : borders)
  {
    for (std::size_t i = 0; i < border.size(); ++i)
    {
      perimeter += (border[(i + 1) % border.size()] - border[i]).norm();
    }
    count += border.size();
  }
  const double borderSpacing = perimeter / static_cast<double>(count);
  double small = 1e-3 * extent;
  double large = extent;
  std::vector<Vector2> interior;
  for (int iteration = 0; iteration < 60; ++iteration)
  {
    const double h = std::sqrt(small * large);
    std::vector<Vector2> points = latticeInside(borders,
      h,
      0.45 * std::min(h, borderSpacing),
      &surface,
      ThinnestShare * largestThickness,
      phase);
    if (static_cast<int>(points.size()) >= interiorCount)
    {
      small = h;
      interior = std::move(points);
    }
    else
    {
      large = h;
    }
    if (large / small < 1.0 + 1e-6)
    {
      break;
    }
  }
  return interior;
}

/// Constrained Delaunay triangulation (CGAL) of `points`, whose first ones
/// are the border loops in order (`borders`: the outline, then the
/// holes), keeping the triangles inside the outline and out of the holes,
/// with chords between border vertices flipped to inner ones.
std::vector<Triangle> triangulateInside(const std::vector<Vector2>& points,
  const std::vector<Loop>& borders,
  const std::string& name)
{
  Triangulation triangulation;
  std::vector<Triangulation::Vertex_handle> handles;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    auto handle = triangulation.insert(Kernel::Point_2(points[i].x(), points[i].y()));
    handle->info() = static_cast<int>(i);
    handles.push_back(handle);
  }
  std::size_t first = 0;
  for (const Loop& border : borders)
  {
    for (std::size_t i = 0; i < border.size(); ++i)
    {
      const auto from = handles[first + i];
      const auto to = handles[first + (i + 1) % border.size()];
      if (from == to) // a constraint from a vertex to itself crashes CGAL
      {
        throw InvalidInputError(name + ": collision vertices coincide (outline too tight)");
      }
      triangulation.insert_constraint(from, to);
    }
    first += border.size();
  }
  std::vector<Triangle> triangles;
  for (auto face = triangulation.finite_faces_begin(); face != triangulation.finite_faces_end();
       ++face)
  {
    Triangle t{};
    Vector2 centroid = Vector2::Zero();
    for (int k = 0; k < 3; ++k)
    {
      t[k] = face->vertex(k)->info();
      if (t[k] < 0 || t[k] >= static_cast<int>(points.size()))
      {
        throw InvalidInputError(name + ": its outline crosses itself");
      }
      centroid += points[t[k]] / 3.0;
    }
    if (insideLoops(borders, centroid))
    {
      triangles.push_back(t);
    }
  }
  flipBorderChords(triangles, points, static_cast<int>(first));
  if (triangulation.number_of_vertices() != points.size())
  {
    throw InvalidInputError(name + ": collision vertices coincide (outline too tight)");
  }
  return triangles;
}

/// Whether the surface is missing just inside the loop (a hole of the
/// shadow: the gap of a tear through the thickness, not a fold of the
/// surface), seen `step` beside the middle of each of its edges.
bool enclosesNoTissue(const ProjectedSurface& surface, const Loop& loop, double step)
{
  const double turn = signedArea(loop) > 0.0 ? 1.0 : -1.0;
  int empty = 0;
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    const Vector2 along = loop[(i + 1) % loop.size()] - loop[i];
    if (along.norm() <= 0.0)
    {
      continue;
    }
    const Vector2 left = turn * Vector2(-along.y(), along.x()).normalized();
    double middle = 0.0;
    empty += halfThicknessAt(surface, loop[i] + 0.5 * along + step * left, middle) < 0.0 ? 1 : 0;
  }
  return 2 * empty > static_cast<int>(loop.size());
}

double perimeterOf(const Loop& loop)
{
  double length = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    length += (loop[(i + 1) % loop.size()] - loop[i]).norm();
  }
  return length;
}

/// The outline among the loops (the longest, made counter-clockwise) and
/// its holes (loops inside it, at least a 50th of its length, around no
/// tissue; made clockwise): tissue lies on the left of every loop. Empty
/// when no loop has three points; `tangled` when a hole crosses itself.
std::vector<Loop> outlineAndHoles(std::vector<Loop> loops,
  const ProjectedSurface& surface,
  double extent,
  bool& tangled)
{
  tangled = false;
  std::stable_sort(loops.begin(),
    loops.end(),
    [](const Loop& a, const Loop& b) { return perimeterOf(a) > perimeterOf(b); });
  if (loops.empty() || loops.front().size() < 3)
  {
    return {};
  }
  std::vector<Loop> result{ loops.front() };
  if (signedArea(result.front()) < 0.0)
  {
    std::reverse(result.front().begin(), result.front().end());
  }
  const double outline = perimeterOf(result.front());
  for (std::size_t k = 1; k < loops.size(); ++k)
  {
    Loop& hole = loops[k];
    const bool inside = std::all_of(
      hole.begin(), hole.end(), [&](const Vector2& q) { return insidePolygon(result.front(), q); });
    if (hole.size() < 3 || perimeterOf(hole) < outline / 50.0 || !inside ||
        !enclosesNoTissue(surface, hole, 1e-3 * extent))
    {
      continue;
    }
    if (crossesItself(hole))
    {
      tangled = true;
      continue;
    }
    if (signedArea(hole) > 0.0)
    {
      std::reverse(hole.begin(), hole.end());
    }
    result.push_back(std::move(hole));
  }
  return result;
}

/// Border points per loop: `total` shared out by length, at least 4 on a
/// hole (the outline keeps the rest).
std::vector<int> borderCountsOf(const std::vector<Loop>& loops, int total)
{
  double perimeter = 0.0;
  for (const Loop& loop : loops)
  {
    perimeter += perimeterOf(loop);
  }
  std::vector<int> counts(loops.size(), 0);
  int holes = 0;
  for (std::size_t k = 1; k < loops.size(); ++k)
  {
    counts[k] =
      std::max(4, static_cast<int>(std::lround(total * perimeterOf(loops[k]) / perimeter)));
    holes += counts[k];
  }
  counts[0] = total - holes;
  return counts;
}

/// The thickness axis (least spread of the area: triangle centres, area
/// weighted) and two axes across it, about the area's centre.
ProjectedSurface projectionAlongThickness(const TriangleMesh& visual)
{
  double area = 0.0;
  Vector3 centre = Vector3::Zero();
  for (std::size_t t = 0; t < visual.triangleCount(); ++t)
  {
    const Triangle& c = visual.triangles[t];
    const double a = visual.triangleArea(t);
    area += a;
    centre += a * (visual.positions[c[0]] + visual.positions[c[1]] + visual.positions[c[2]]) / 3.0;
  }
  centre /= area;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t t = 0; t < visual.triangleCount(); ++t)
  {
    const Triangle& c = visual.triangles[t];
    const Vector3 d =
      (visual.positions[c[0]] + visual.positions[c[1]] + visual.positions[c[2]]) / 3.0 - centre;
    covariance += visual.triangleArea(t) * d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> axes(covariance);
  const Vector3 n = axes.eigenvectors().col(0).normalized();
  const Vector3 u = axes.eigenvectors().col(2).normalized();
  return ProjectedSurface(visual, centre, u, n.cross(u), n);
}

/// The share of a hole's inside (a lattice of about 400 points, or the
/// points beside its edges when none fits) where the axis line meets no
/// tissue.
double seeThroughFraction(const ProjectedSurface& surface, const Loop& hole, double extent)
{
  Loop counterClockwise = hole;
  if (signedArea(counterClockwise) < 0.0)
  {
    std::reverse(counterClockwise.begin(), counterClockwise.end());
  }
  const double spacing = std::sqrt(std::abs(signedArea(hole)) / 400.0);
  const std::vector<Vector2> lattice =
    spacing > 0.0 ? latticeInside({ counterClockwise }, spacing, 0.0) : std::vector<Vector2>();
  if (lattice.empty())
  {
    return enclosesNoTissue(surface, hole, 1e-3 * extent) ? 1.0 : 0.0;
  }
  double middle = 0.0;
  const auto empty = std::count_if(lattice.begin(),
    lattice.end(),
    [&](const Vector2& q) { return halfThicknessAt(surface, q, middle) < 0.0; });
  return static_cast<double>(empty) / static_cast<double>(lattice.size());
}

/// The nearest vertices of two loops (indices) and their distance.
struct NearestVertices
{
  std::size_t a = 0;
  std::size_t b = 0;
  double distance = std::numeric_limits<double>::infinity();
};

NearestVertices nearestVertices(const Loop& a, const Loop& b)
{
  NearestVertices nearest;
  double squared = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t k = 0; k < b.size(); ++k)
      if ((a[i] - b[k]).squaredNorm() < squared)
      {
        squared = (a[i] - b[k]).squaredNorm();
        nearest.a = i;
        nearest.b = k;
      }
  nearest.distance = std::sqrt(squared);
  return nearest;
}

/// Loop `b` joined to loop `a` across their nearest vertices (both with the
/// tissue on their left: the outline counter-clockwise, holes clockwise,
/// so that where they face each other they run opposite ways): `a` from
/// the vertex after the bridge round to its start, over to `b`, round `b`,
/// and back. The bridge replaces an edge of each, and the quadrilateral
/// between those joins the two (the outline takes the hole in as a notch;
/// two holes become one). Empty if no such loop keeps from crossing itself
/// or keeps `a`'s orientation.
Loop joinedLoops(const Loop& a, const Loop& b, const NearestVertices& nearest)
{
  const bool counterClockwise = signedArea(a) > 0.0;
  Loop best;
  double bestBridge = std::numeric_limits<double>::infinity();
  // The bridge runs from a[i] to b[k] and from b[k - 1] to a[i + 1]: the
  // nearest vertices at one end or the other of it.
  for (const std::size_t i : { nearest.a, nearest.a + a.size() - 1 })
    for (const std::size_t k : { nearest.b, nearest.b + 1 })
    {
      Loop joined;
      joined.reserve(a.size() + b.size());
      for (std::size_t j = 1; j <= a.size(); ++j)
        joined.push_back(a[(i + j) % a.size()]);
      for (std::size_t j = 0; j < b.size(); ++j)
        joined.push_back(b[(k + j) % b.size()]);
      const double bridge = (a[i % a.size()] - b[k % b.size()]).norm() +
                            (b[(k + b.size() - 1) % b.size()] - a[(i + 1) % a.size()]).norm();
      if (bridge < bestBridge && (signedArea(joined) > 0.0) == counterClockwise &&
          !crossesItself(joined))
      {
        bestBridge = bridge;
        best = std::move(joined);
      }
    }
  return best;
}

constexpr double JoinedHoleSeeThrough = 0.5; ///< share of a hole seen through
constexpr double JoinedHoleGap = 0.08;       ///< of the extent across the axis
/// A hole of less area than the square of this share of the extent is a
/// pit of the segmentation, not a slit or a notch: filled.
constexpr double JoinedHoleSide = 0.02;

/// A hole of the outline is a tunnel through the tissue, so the visual
/// surface has at least as many tunnels (its genus) as the outline has
/// holes, or the collision mesh's two sides could not be told apart on it
/// (a hole whose rim closes on itself, a cap where a segmentation's
/// tunnel was closed: the rim paths around it would leave a side in two
/// pieces). Beyond the genus, the holes seen through least are joined to
/// a kept hole or the outline near them, or else filled. Returns how many
/// were joined.
int keepHolesTheSurfaceHas(const TriangleMeshAdjacency& adjacency,
  const ProjectedSurface& surface,
  double extent,
  bool joinSeenThrough,
  std::vector<Loop>& loops)
{
  if (loops.size() <= 1)
  {
    return 0;
  }
  const int genus = adjacency.closedSurfaceGenus();
  if (static_cast<int>(loops.size()) - 1 <= genus)
  {
    return 0;
  }
  std::vector<std::pair<double, std::size_t>> seen;
  for (std::size_t k = 1; k < loops.size(); ++k)
  {
    seen.emplace_back(seeThroughFraction(surface, loops[k], extent), k);
  }
  std::stable_sort(
    seen.begin(), seen.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<Loop> kept{ std::move(loops.front()) };
  const std::size_t keep = static_cast<std::size_t>(std::max(genus, 0));
  for (std::size_t i = 0; i < keep; ++i)
  {
    kept.push_back(std::move(loops[seen[i].second]));
  }
  // A hole seen through that is no tunnel of its own is a part of a kept
  // hole's tunnel (a tear's slit whose lips overlap in projection for a
  // stretch shows as two holes) or a notch whose mouth an overlapping part
  // closes in projection (a flap tear's flap lying on the body at its
  // tip): joined to the nearest of the kept holes and the outline, so that
  // the collision mesh spans no opening of the surface (its paths across
  // would run round it and cross others). Holes seen through little, or
  // far from all, or small, are caps (tunnels the segmentation closed) or
  // pits: filled.
  int joinedHoles = 0;
  for (std::size_t i = keep; i < seen.size() && joinSeenThrough; ++i)
  {
    const Loop& hole = loops[seen[i].second];
    if (seen[i].first < JoinedHoleSeeThrough ||
        0.5 * std::abs(signedArea(hole)) < JoinedHoleSide * JoinedHoleSide * extent * extent)
      continue;
    std::size_t to = 0;
    NearestVertices nearest = nearestVertices(kept[0], hole);
    for (std::size_t k = 1; k < kept.size(); ++k)
    {
      const NearestVertices other = nearestVertices(kept[k], hole);
      if (other.distance < nearest.distance)
      {
        to = k;
        nearest = other;
      }
    }
    if (nearest.distance > JoinedHoleGap * extent)
      continue;
    Loop joined = joinedLoops(kept[to], hole, nearest);
    if (!joined.empty())
    {
      kept[to] = std::move(joined);
      ++joinedHoles;
    }
  }
  loops = std::move(kept);
  return joinedHoles;
}

/// The outline and holes seen along the axis: from the silhouette edges,
/// or from the shadow's raster where the silhouette's outline or a hole
/// crosses itself (a rough surface; a tear's lips overlapping).
std::vector<Loop> outlineAlongAxis(const TriangleMesh& visual,
  const ProjectedSurface& surface,
  double extent,
  bool joinSeenThroughHoles,
  int& joinedHoles)
{
  bool tangled = false;
  const TriangleMeshAdjacency adjacency(visual);
  std::vector<Loop> loops = outlineAndHoles(
    silhouetteLoops(visual, adjacency, surface, surface.axis()), surface, extent, tangled);
  if (loops.empty() || tangled || crossesItself(loops.front()))
  {
    loops = outlineAndHoles(shadowLoops(visual, surface), surface, extent, tangled);
  }
  if (loops.empty())
  {
    throw InvalidInputError(nameOf(visual) + ": no outline seen along the thickness axis");
  }
  joinedHoles = keepHolesTheSurfaceHas(adjacency, surface, extent, joinSeenThroughHoles, loops);
  return loops;
}

/// Largest thickness over a lattice inside the outline; InvalidInputError
/// when it is too large for the extent (not a thin object).
void measureThickness(const TriangleMesh& visual,
  const ProjectedSurface& surface,
  const std::vector<Loop>& loops,
  double maximumRatio,
  GeneratedCollisionMesh& result)
{
  const double extent = std::max(surface.extent().x(), surface.extent().y());
  double largest = 0.0;
  double middle = 0.0;
  for (const Vector2& q : latticeInside(loops, extent / 40.0, 0.0))
  {
    largest = std::max(largest, 2.0 * halfThicknessAt(surface, q, middle));
  }
  result.largestThickness = largest;
  result.thicknessRatio = extent > 0.0 ? largest / extent : Infinity;
  if (!(result.thicknessRatio <= maximumRatio))
  {
    throw InvalidInputError(nameOf(visual) + " is not a thin object: thickness-to-extent ratio " +
                            std::to_string(result.thicknessRatio) + " (largest thickness " +
                            std::to_string(largest) + " over extent " + std::to_string(extent) +
                            "), at most " + std::to_string(maximumRatio));
  }
}

/// Signed distance to the thick surface (the collision mesh's triangles
/// swept by their interpolated radii), exact: a triangle is skipped when its
/// bounding sphere, grown by its largest radius, cannot beat the best so
/// far; the previous query's best triangle goes first (neighbouring queries
/// are near each other).
class ThickSurfaceDistance
{
public:
  ThickSurfaceDistance(const TriangleMesh& mesh, const std::vector<double>& radii)
    : Mesh(mesh)
    , Radii(radii)
    , Centres(mesh.triangleCount())
    , Reach(mesh.triangleCount(), 0.0)
    , LargestRadius(mesh.triangleCount(), 0.0)
  {
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
      const Triangle& c = mesh.triangles[t];
      Centres[t] = (mesh.positions[c[0]] + mesh.positions[c[1]] + mesh.positions[c[2]]) / 3.0;
      for (int k : c)
      {
        Reach[t] = std::max(Reach[t], (mesh.positions[k] - Centres[t]).norm());
        LargestRadius[t] = std::max(LargestRadius[t], radii[k]);
      }
    }
  }

  double operator()(const Vector3& x)
  {
    double best = Infinity;
    visit(x, Hint, best);
    for (std::size_t t = 0; t < Mesh.triangleCount(); ++t)
    {
      visit(x, t, best);
    }
    return best;
  }

private:
  void visit(const Vector3& x, std::size_t index, double& best)
  {
    if ((x - Centres[index]).norm() - Reach[index] - LargestRadius[index] >= best)
    {
      return;
    }
    const Triangle& t = Mesh.triangles[index];
    const TriangleClosestPoint closest = closestPointOnTriangleWithBarycentric(
      x, Mesh.positions[t[0]], Mesh.positions[t[1]], Mesh.positions[t[2]]);
    const double r = closest.barycentric[0] * Radii[t[0]] + closest.barycentric[1] * Radii[t[1]] +
                     closest.barycentric[2] * Radii[t[2]];
    const double distance = (x - closest.point).norm() - r;
    if (distance < best)
    {
      best = distance;
      Hint = index;
    }
  }

  const TriangleMesh& Mesh;
  const std::vector<double>& Radii;
  std::vector<Vector3> Centres;
  std::vector<double> Reach;
  std::vector<double> LargestRadius;
  std::size_t Hint = 0;
};

/// Points of the thick surface: each vertex's sphere along its normal both
/// ways, and each triangle's centre likewise.
std::vector<Vector3> thickSurfaceSamples(const TriangleMesh& mesh, const std::vector<double>& radii)
{
  std::vector<Vector3> vertexNormals(mesh.vertexCount(), Vector3::Zero());
  for (const Triangle& t : mesh.triangles)
  {
    const Vector3 normal = (mesh.positions[t[1]] - mesh.positions[t[0]])
                             .cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
    for (int k : t)
    {
      vertexNormals[k] += normal;
    }
  }
  std::vector<Vector3> samples;
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i)
  {
    const Vector3 normal = vertexNormals[i].normalized();
    samples.push_back(mesh.positions[i] + radii[i] * normal);
    samples.push_back(mesh.positions[i] - radii[i] * normal);
  }
  for (const Triangle& t : mesh.triangles)
  {
    const Vector3 c = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
    const double r = (radii[t[0]] + radii[t[1]] + radii[t[2]]) / 3.0;
    const Vector3 normal = (mesh.positions[t[1]] - mesh.positions[t[0]])
                             .cross(mesh.positions[t[2]] - mesh.positions[t[0]])
                             .normalized();
    samples.push_back(c + r * normal);
    samples.push_back(c - r * normal);
  }
  return samples;
}

/// The two one-sided distances between the visual surface and the thick
/// collision surface, and the Hausdorff distance, the larger.
void measureHausdorff(const TriangleMesh& visual,
  const std::vector<double>& radii,
  double extent,
  GeneratedCollisionMesh& result)
{
  ThickSurfaceDistance thickDistance(result.mesh, radii);
  for (const Vector3& x : visual.positions)
  {
    result.visualToThick = std::max(result.visualToThick, std::abs(thickDistance(x)));
  }
  TriangleBvh visualTree;
  visualTree.build(visual.positions, visual.triangles, {}, 0.0);
  for (const Vector3& x : thickSurfaceSamples(result.mesh, radii))
  {
    // Only points on the thick surface's outside count (a sample inside
    // another part of the thick surface is not on its boundary).
    if (thickDistance(x) >= -1e-9 * extent)
    {
      result.thickToVisual =
        std::max(result.thickToVisual, distanceToSurface(visual, visualTree, x));
    }
  }
  result.hausdorffDistance = std::max(result.visualToThick, result.thickToVisual);
}

/// The mid-surface of a band along its centre curve (BandMidSurface.h),
/// checked for thinness, with its Hausdorff distance.
GeneratedCollisionMesh bandMidSurface(const TriangleMesh& visual,
  const CollisionMeshSettings& settings,
  int vertexCount,
  const GenerationProgress& progress)
{
  report(progress, 0.3, "following the band");
  BandMidSurface band = makeBandMidSurface(
    visual, vertexCount, settings.triangleCount > 0 ? settings.triangleCount : 0, nameOf(visual));
  GeneratedCollisionMesh result;
  result.method = MidSurfaceMethod::Band;
  result.thicknessTurn = band.thicknessTurn;
  result.thicknessAxis = band.meanThicknessDirection;
  result.largestThickness = band.largestThickness;
  result.thicknessRatio = band.length > 0.0 ? band.largestThickness / band.length : Infinity;
  if (!(result.thicknessRatio <= settings.maximumThicknessRatio))
  {
    throw InvalidInputError(nameOf(visual) + " is not a thin band: thickness-to-length ratio " +
                            std::to_string(result.thicknessRatio) + ", at most " +
                            std::to_string(settings.maximumThicknessRatio));
  }
  result.mesh = std::move(band.mesh);
  result.mesh.name = visual.name + " collision";
  result.mesh.pointAttributes.set(settings.radiusArrayName, 1, band.radii);
  result.borderVertexCount = band.borderVertexCount;
  report(progress, 0.7, "measuring the Hausdorff distance");
  measureHausdorff(visual, band.radii, band.length, result);
  report(progress, 1.0, "done");
  return result;
}

/// The mid-surface seen along one thickness axis (steps 1-4 above).
GeneratedCollisionMesh oneAxisMidSurface(const TriangleMesh& visual,
  const CollisionMeshSettings& settings,
  const ProjectedSurface& surface,
  int vertexCount,
  const GenerationProgress& progress)
{
  const Vector3 n = surface.axis();
  const double extent = std::max(surface.extent().x(), surface.extent().y());
  report(progress, 0.2, "tracing the outline");
  GeneratedCollisionMesh result;
  const std::vector<Loop> outline =
    outlineAlongAxis(visual, surface, extent, settings.joinSeenThroughHoles, result.joinedHoles);
  result.thicknessAxis = n;
  result.latticePhase = settings.latticePhase;
  measureThickness(visual, surface, outline, settings.maximumThicknessRatio, result);
  auto halfThickness = [&](const Vector2& q, double& middle)
  { return halfThicknessAt(surface, q, middle); };

  // Borders: resampled, moved in until the local half thickness reaches
  // them; the outline's first, then each hole's.
  report(progress, 0.3, "placing the border");
  const int borderCount = borderVertexCountFor(vertexCount);
  const std::vector<int> counts = borderCountsOf(outline, borderCount);
  std::vector<Loop> borders;
  for (std::size_t k = 0; k < outline.size(); ++k)
  {
    std::vector<Loop> others = outline;
    others.erase(others.begin() + static_cast<std::ptrdiff_t>(k));
    const Loop border =
      placeBorder(surface, outline[k], others, counts[k], extent, result.largestThickness);
    borders.push_back(followBays(surface,
      outline[k],
      border,
      extent,
      ThinnestShare * result.largestThickness,
      std::max(2, counts[k] / 3)));
  }
  untangleBorders(surface, borders, outline, ThinnestShare * result.largestThickness);
  std::vector<Vector2> points;
  int placed = 0;
  for (const Loop& border : borders)
  {
    points.insert(points.end(), border.begin(), border.end());
    placed += static_cast<int>(border.size());
  }

  // 3. Interior lattice with the count that makes vertexCount in all (the
  // points added in bays taken from it).
  report(progress, 0.4, "filling the inside");
  const int interiorCount = vertexCount - placed;
  std::vector<Vector2> interior = interiorLattice(
    surface, borders, interiorCount, extent, result.largestThickness, settings.latticePhase);
  if (static_cast<int>(interior.size()) < interiorCount)
  {
    throw InvalidInputError(nameOf(visual) + ": the outline leaves no room for " +
                            std::to_string(interiorCount) + " inner collision vertices");
  }
  interior.resize(static_cast<std::size_t>(interiorCount)); // the nearest the border go

  // Constrained Delaunay triangulation of borders and inside.
  report(progress, 0.5, "triangulating");
  points.insert(points.end(), interior.begin(), interior.end());
  TriangleMesh& mesh = result.mesh;
  mesh.name = visual.name + " collision";
  mesh.triangles = triangulateInside(points, borders, nameOf(visual));

  // 4. Lift to the middle, radius half the thickness.
  report(progress, 0.6, "lifting to the mid-surface");
  std::vector<double> radii(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    double middle = 0.0;
    double half = halfThickness(points[i], middle);
    if (!(half > 0.0))
    {
      throw InvalidInputError(nameOf(visual) + ": collision vertex " + std::to_string(i) +
                              " finds no surface above and below it (outline too tight?)");
    }
    // A line through two layers (a tear's lips overlapping in projection,
    // a staircase's overhang) can have its middle in the gap between them,
    // outside the tissue: the vertex goes to the thickest layer instead.
    double bottom = 0.0;
    double top = 0.0;
    if (surface.thickestInsideInterval(points[i], 1e-9 * extent, bottom, top))
    {
      middle = 0.5 * (bottom + top);
      half = 0.5 * (top - bottom);
    }
    mesh.positions.push_back(surface.lift(points[i], middle));
    radii[i] = half;
  }
  mesh.pointAttributes.set(settings.radiusArrayName, 1, radii);
  result.borderVertexCount = placed;

  // Two-sided Hausdorff distance to the thick surface.
  report(progress, 0.7, "measuring the Hausdorff distance");
  measureHausdorff(visual, radii, extent, result);
  report(progress, 1.0, "done");
  return result;
}

} // namespace

//------------------------------------------------------------------------------
GeneratedCollisionMesh makeCollisionMidSurface(const TriangleMesh& visual,
  const CollisionMeshSettings& settings,
  const GenerationProgress& progress)
{
  report(progress, 0.0, "checking the visual mesh");
  int vertexCount = settings.vertexCount;
  if (settings.triangleCount > 0)
  {
    vertexCount = 8;
    while (2 * vertexCount - borderVertexCountFor(vertexCount) - 2 < settings.triangleCount)
    {
      ++vertexCount;
    }
  }
  if (vertexCount < 8)
  {
    throw InvalidInputError(
      "collision mesh generation: at least 8 vertices, not " + std::to_string(vertexCount));
  }
  if (!(settings.maximumThicknessRatio > 0.0))
  {
    throw InvalidInputError("collision mesh generation: the thickness ratio must be positive");
  }
  if (!(settings.latticePhase >= 0.0 && settings.latticePhase <= 1.0))
  {
    throw InvalidInputError("collision mesh generation: the lattice phase must lie in [0, 1]");
  }
  checkVisual(visual);

  report(progress, 0.1, "finding the thickness axis");
  const ProjectedSurface surface = projectionAlongThickness(visual);
  // Automatic: one axis (the thesis's shapes keep their meshes); a band
  // when that fails on an elongated tissue (an outline crossing itself
  // where a band turns), the one axis's error when both fail.
  const bool bandFirst = settings.method == MidSurfaceMethod::Band;
  auto generate = [&](bool band)
  {
    return band ? bandMidSurface(visual, settings, vertexCount, progress)
                : oneAxisMidSurface(visual, settings, surface, vertexCount, progress);
  };
  try
  {
    return generate(bandFirst);
  }
  catch (const InvalidInputError&)
  {
    if (settings.method != MidSurfaceMethod::Automatic ||
        elongationOf(visual) < MinimumBandElongation)
    {
      throw;
    }
    try
    {
      return generate(!bandFirst);
    }
    catch (const InvalidInputError&)
    {
    }
    throw; // the first one's error
  }
}

//------------------------------------------------------------------------------
namespace
{

/// The raster cells of the shadow's small holes (fewer than `largest`
/// cells, or at most span x span cells and no longer than 2 span cells),
/// grown by `margin` cells, and how many such holes there are.
std::vector<char> tunnelFootprints(const ShadowRaster& raster,
  int largest,
  int span,
  int margin,
  std::vector<Vector2>& centres)
{
  std::vector<int> cellCounts;
  const std::vector<int> piece = emptyPieces(raster, cellCounts);
  std::vector<char> small(cellCounts.size(), 0);
  for (std::size_t label = 1; label < cellCounts.size(); ++label)
    small[label] = cellCounts[label] < largest;
  if (span > 0)
  {
    // Each hole's cell box: a hole no larger than a lattice cell is small
    // however many raster cells it has; a tear's slit is long and stays.
    std::vector<std::array<int, 4>> boxes(
      cellCounts.size(), { raster.width, raster.height, -1, -1 });
    for (int j = 0; j < raster.height; ++j)
      for (int i = 0; i < raster.width; ++i)
      {
        const int label = piece[raster.at(i, j)];
        if (label <= 0)
          continue;
        auto& box = boxes[label];
        box = {
          std::min(box[0], i), std::min(box[1], j), std::max(box[2], i), std::max(box[3], j)
        };
      }
    for (std::size_t label = 1; label < cellCounts.size(); ++label)
    {
      const auto& box = boxes[label];
      const int length = std::max(box[2] - box[0], box[3] - box[1]) + 1;
      small[label] |= cellCounts[label] <= span * span && length <= 2 * span;
    }
  }
  std::vector<Vector2> sums(cellCounts.size(), Vector2::Zero());
  std::vector<char> footprint(piece.size(), 0);
  for (int j = 0; j < raster.height; ++j)
    for (int i = 0; i < raster.width; ++i)
    {
      const int label = piece[raster.at(i, j)];
      if (label <= 0 || !small[label])
        continue;
      sums[label] += raster.origin + raster.cell * Vector2(i + 0.5, j + 0.5);
      for (int dj = -margin; dj <= margin; ++dj)
        for (int di = -margin; di <= margin; ++di)
          if (i + di >= 0 && j + dj >= 0 && i + di < raster.width && j + dj < raster.height)
            footprint[raster.at(i + di, j + dj)] = 1;
    }
  for (std::size_t label = 1; label < cellCounts.size(); ++label)
    if (small[label])
      centres.push_back(sums[label] / static_cast<double>(cellCounts[label]));
  return footprint;
}

/// The width, in raster cells, of the holes a collision mesh of
/// `collisionVertexCount` vertices cannot hold: its spacing, about the
/// square root of the shadow's area per vertex (0: none).
int unrepresentableHoleSpan(const ShadowRaster& raster, int collisionVertexCount)
{
  if (collisionVertexCount <= 0)
    return 0;
  const auto covered = std::count(raster.inside.begin(), raster.inside.end(), char(1));
  return static_cast<int>(std::sqrt(static_cast<double>(covered) / collisionVertexCount));
}

/// The tunnels seen along the thickness axis closed (r's genus set).
TriangleMesh closeShadowTunnels(const TriangleMesh& visual,
  int collisionVertexCount,
  TunnelClosingReport& r)
{
  const ProjectedSurface surface = projectionAlongThickness(visual);
  // A 1024th of the extent: a perforation of a thin rim can be a few tenths
  // of a millimetre across.
  const ShadowRaster raster = rasterizeShadow(visual, surface, 1024.0);
  constexpr int LargestTunnelCells = 1024; // 32 x 32 cells
  constexpr int MarginCells = 8;           // the walls' slant, the mouths' rims
  std::vector<Vector2> centres;
  const std::vector<char> footprint = tunnelFootprints(raster,
    LargestTunnelCells,
    unrepresentableHoleSpan(raster, collisionVertexCount),
    MarginCells,
    centres);
  r.tunnels = static_cast<int>(centres.size());
  if (centres.empty())
    return visual;
  TriangleMesh cut = visual;
  cut.triangles.clear();
  cut.textureCorners.clear();
  for (std::size_t t = 0; t < visual.triangleCount(); ++t)
  {
    const Triangle& c = visual.triangles[t];
    const Vector2 q = surface.project(
      (visual.positions[c[0]] + visual.positions[c[1]] + visual.positions[c[2]]) / 3.0);
    const int i = static_cast<int>(std::floor((q.x() - raster.origin.x()) / raster.cell));
    const int j = static_cast<int>(std::floor((q.y() - raster.origin.y()) / raster.cell));
    const bool inside = i >= 0 && j >= 0 && i < raster.width && j < raster.height;
    if (!(inside && footprint[raster.at(i, j)]))
    {
      cut.triangles.push_back(c);
      if (visual.hasTextureCoordinates())
        cut.textureCorners.push_back(visual.textureCorners[t]);
    }
  }
  // The openings run over the rim where a tunnel perforates it: any length
  // is filled; islands left between neighbouring tunnels go.
  const TriangleMesh closed = closeOpeningsKeepLargest(cut);
  const MeshValidationReport validation = validateTriangleMesh(closed);
  const int genus = validation.isClosedOutwardSingleSurface()
                      ? TriangleMeshAdjacency(closed).closedSurfaceGenus()
                      : r.genusBefore;
  if (genus >= r.genusBefore)
    return visual;
  r.genusAfter = genus;
  r.closed = r.genusBefore - genus;
  for (const Vector2& q : centres)
  {
    double middle = 0.0;
    halfThicknessAt(surface, q, middle);
    const Vector3 x = surface.lift(q, middle);
    r.changes.push_back("tunnel through the tissue at (" + std::to_string(x.x()) + ", " +
                        std::to_string(x.y()) + ", " + std::to_string(x.z()) + ")");
  }
  return closed;
}

} // namespace

TriangleMesh closeSmallTunnels(const TriangleMesh& visual,
  TunnelClosingReport* report,
  int collisionVertexCount)
{
  TunnelClosingReport local;
  TunnelClosingReport& r = report ? *report : local;
  r = TunnelClosingReport{};
  checkVisual(visual);
  r.genusBefore = r.genusAfter = TriangleMeshAdjacency(visual).closedSurfaceGenus();
  if (r.genusBefore <= 0)
    return visual;
  TriangleMesh closed = closeShadowTunnels(visual, collisionVertexCount, r);
  if (r.genusAfter == 0)
    return closed;
  // Tunnels hidden from the axis (slanted through a staircase's riser,
  // under an overhang): small handles found by geodesic balls of up to a
  // 40th of the diagonal (a tear's gap is larger and stays).
  const std::size_t before = r.changes.size();
  closed = removeSmallHandles(closed, visual.boundingBox().diagonal().norm() / 15.0, r.changes);
  const int found = static_cast<int>(r.changes.size() - before);
  if (found > 0)
  {
    r.tunnels += found;
    r.genusAfter = TriangleMeshAdjacency(closed).closedSurfaceGenus();
    r.closed = r.genusBefore - r.genusAfter;
  }
  return closed;
}

//------------------------------------------------------------------------------
HexahedralMesh makeSimulationHexahedra(const TriangleMesh& visual, int hexahedronCount)
{
  if (hexahedronCount < 1)
  {
    throw InvalidInputError(
      "simulation hexahedra: the count must be positive, not " + std::to_string(hexahedronCount));
  }
  const double diagonal = visual.boundingBox().diagonal().norm();
  auto countFor = [&](double size)
  {
    SparseHexahedralGridSettings settings;
    settings.cellSize = size;
    return SparseHexahedralGrid::fromSurface(visual, settings);
  };
  // The count falls as the cubes grow: bisection on the size, keeping the
  // size whose count came nearest.
  double small = diagonal / 400.0;
  double large = diagonal;
  double bestSize = large;
  long bestError = -1;
  for (int iteration = 0; iteration < 40 && large / small > 1.0 + 1e-4; ++iteration)
  {
    const double size = std::sqrt(small * large);
    const auto count = static_cast<long>(countFor(size).mesh.hexahedronCount());
    const long error = std::labs(count - hexahedronCount);
    if (bestError < 0 || error < bestError)
    {
      bestError = error;
      bestSize = size;
    }
    if (count == hexahedronCount)
    {
      break;
    }
    (count > hexahedronCount ? small : large) = size;
  }
  HexahedralMesh mesh = countFor(bestSize).mesh;
  mesh.name = visual.name + " hexahedra";
  return mesh;
}

} // namespace thintissue
