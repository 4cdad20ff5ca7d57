#include "SleeveGeodesic.h"

#include "SurfaceSteps.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

namespace thintissue
{

namespace
{

constexpr double Infinity = std::numeric_limits<double>::infinity();
constexpr double Pi = 3.14159265358979323846;
/// A path point this close (in edge parameter) to an edge end is that vertex.
constexpr double EndpointTolerance = 1e-12;
/// A bend whose far-side angle falls short of pi by less than this (radians)
/// stays: a path straight through a flat vertex has exactly pi on each side.
constexpr double AngleTolerance = 1e-9;

double cross2(const Vector2& a, const Vector2& b)
{
  return a.x() * b.y() - a.y() * b.x();
}

bool hasCorner(const Triangle& c, int v)
{
  return c[0] == v || c[1] == v || c[2] == v;
}

/// The angle between two plane vectors, in [0, pi].
double angleBetween(const Vector2& a, const Vector2& b)
{
  return std::atan2(std::abs(cross2(a, b)), a.dot(b));
}

/// The angle of triangle c at its corner v, on the surface.
double cornerAngle(const TriangleMesh& mesh, const Triangle& c, int v)
{
  const int k = c[0] == v ? 0 : (c[1] == v ? 1 : 2);
  const Vector3& at = mesh.positions[v];
  const Vector3 a = mesh.positions[c[(k + 1) % 3]] - at;
  const Vector3 b = mesh.positions[c[(k + 2) % 3]] - at;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// The edge of triangle t joining a and b (its index k: corners k, k + 1).
int edgeOf(const Triangle& c, int a, int b)
{
  for (int k = 0; k < 3; ++k)
  {
    const int u = c[k];
    const int w = c[(k + 1) % 3];
    if ((u == a && w == b) || (u == b && w == a))
    {
      return k;
    }
  }
  return -1;
}

struct SearchNode
{
  double distance = Infinity;
  int parent = -1;
  /// A step across an edge from the parent: the parent's triangle and the
  /// one across its far edge (-1 for a step along an edge).
  int near = -1;
  int across = -1;
  bool closed = false;
};

Vector3 centroid(const TriangleMesh& mesh, int t)
{
  const Triangle& c = mesh.triangles[t];
  return (mesh.positions[c[0]] + mesh.positions[c[1]] + mesh.positions[c[2]]) / 3.0;
}

/// A sleeve found by A* over the allowed triangles, from those of `source`
/// to the first holding `target`, stepping between centroids (the
/// straight-line distance to the target is a consistent heuristic), cut to
/// start at the last triangle holding `source`.
bool searchCentroidSleeve(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  int source,
  int target,
  std::vector<int>& sleeve)
{
  const Vector3& goal = mesh.positions[target];
  std::unordered_map<int, SearchNode> nodes;
  nodes.reserve(512);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (const int* t = adjacency.vertexTrianglesBegin(source);
       t != adjacency.vertexTrianglesEnd(source);
       ++t)
  {
    if (mask(*t))
    {
      const Vector3 c = centroid(mesh, *t);
      const double d = (c - mesh.positions[source]).norm();
      nodes[*t].distance = d;
      queue.emplace(d + (c - goal).norm(), *t);
    }
  }
  while (!queue.empty())
  {
    const int t = queue.top().second;
    queue.pop();
    SearchNode& node = nodes[t];
    if (node.closed)
    {
      continue;
    }
    node.closed = true;
    if (hasCorner(mesh.triangles[t], target))
    {
      sleeve.clear();
      for (int u = t; u >= 0; u = nodes[u].parent)
      {
        sleeve.push_back(u);
      }
      std::reverse(sleeve.begin(), sleeve.end());
      std::size_t first = 0;
      for (std::size_t i = 0; i < sleeve.size(); ++i)
      {
        first = hasCorner(mesh.triangles[sleeve[i]], source) ? i : first;
      }
      sleeve.erase(sleeve.begin(), sleeve.begin() + static_cast<std::ptrdiff_t>(first));
      return true;
    }
    const double distance = node.distance;
    const Vector3 from = centroid(mesh, t);
    for (int k = 0; k < 3; ++k)
    {
      const int n = adjacency.neighbourAcross(t, k);
      if (n < 0 || !mask(n))
      {
        continue;
      }
      const Vector3 c = centroid(mesh, n);
      const double d = distance + (c - from).norm();
      SearchNode& next = nodes[n];
      if (next.closed || d >= next.distance)
      {
        continue;
      }
      next.distance = d;
      next.parent = t;
      queue.emplace(d + (c - goal).norm(), n);
    }
  }
  return false;
}

/// The shortest path from `source` to `target` over the allowed triangles
/// whose steps run along an edge or straight across one (through two
/// triangles unfolded): A* over vertices, the straight-line distance as
/// heuristic. Closer to the geodesic than an edge path on a rough surface,
/// whose bumps an edge path passes on whichever side its edges happen to
/// lie; the sleeve around it then holds the geodesic's corridor.
/// `steps[i]`: the node reached at vertices[i + 1] (its near and across
/// triangles).
bool searchStepPath(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  int source,
  int target,
  std::vector<int>& vertices,
  std::vector<SearchNode>& steps,
  std::size_t& searched)
{
  const std::vector<Vector3>& p = mesh.positions;
  std::unordered_map<int, SearchNode> nodes;
  nodes.reserve(512);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  nodes[source].distance = 0.0;
  queue.emplace((p[source] - p[target]).norm(), source);
  auto relax = [&](int from, int to, double d, int near, int across)
  {
    SearchNode& next = nodes[to];
    if (next.closed || d >= next.distance)
    {
      return;
    }
    next.distance = d;
    next.parent = from;
    next.near = near;
    next.across = across;
    queue.emplace(d + (p[to] - p[target]).norm(), to);
  };
  while (!queue.empty())
  {
    const int v = queue.top().second;
    queue.pop();
    SearchNode& node = nodes[v];
    if (node.closed)
    {
      continue;
    }
    node.closed = true;
    if (v == target)
    {
      vertices.clear();
      steps.clear();
      for (int u = v; u >= 0; u = nodes[u].parent)
      {
        vertices.push_back(u);
        steps.push_back(nodes[u]);
      }
      std::reverse(vertices.begin(), vertices.end());
      std::reverse(steps.begin(), steps.end());
      steps.erase(steps.begin()); // the source's
      searched = nodes.size();
      return true;
    }
    const double distance = node.distance;
    forEachStep(mesh,
      adjacency,
      mask,
      v,
      true,
      [&](int u, double length, int near, int across)
      { relax(v, u, distance + length, near, across); });
  }
  searched = nodes.size();
  return false;
}

/// The allowed triangles met turning round vertex v from `from` (which
/// holds v and `edgeEnd`), first across edge (v, edgeEnd), up to the first
/// holding `next` (or up to triangle `goal`, when not -1); false where the
/// turn leaves the allowed surface.
bool turnRound(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  int from,
  int v,
  int edgeEnd,
  int next,
  int goal,
  std::vector<int>& run,
  double& angle)
{
  run.clear();
  angle = 0.0;
  int current = from;
  for (int guard = adjacency.vertexTriangleCount(v); guard >= 0; --guard)
  {
    const int k = edgeOf(mesh.triangles[current], v, edgeEnd);
    const int n = k < 0 ? -1 : adjacency.neighbourAcross(current, k);
    if (n < 0 || !mask(n) || n == from)
    {
      return false;
    }
    const Triangle& c = mesh.triangles[n];
    run.push_back(n);
    angle += cornerAngle(mesh, c, v);
    if (goal >= 0 ? n == goal : hasCorner(c, next))
    {
      return true;
    }
    edgeEnd = c[0] != v && c[0] != edgeEnd ? c[0] : (c[1] != v && c[1] != edgeEnd ? c[1] : c[2]);
    current = n;
  }
  return false;
}

/// The first sleeve: triangles along the path of searchStepPath (a step
/// across an edge takes its two triangles), turning round each of its
/// vertices the way of the smaller angle, so that the path runs inside it
/// (the funnel's path is no longer), cut to start at the last triangle
/// holding `source` and end at the first holding `target`, and loops (a
/// triangle met twice) cut out.
bool sleeveAlongStepPath(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  const std::vector<int>& path,
  const std::vector<SearchNode>& steps,
  std::vector<int>& sleeve)
{
  sleeve.clear();
  if (steps.front().across >= 0)
  {
    sleeve = { steps.front().near, steps.front().across };
  }
  else
  {
    const int e = adjacency.findEdge(path[0], path[1]);
    for (const int* t = adjacency.edgeTrianglesBegin(e); t != adjacency.edgeTrianglesEnd(e); ++t)
    {
      if (mask(*t) && sleeve.empty())
      {
        sleeve.push_back(*t);
      }
    }
  }
  if (sleeve.empty())
  {
    return false;
  }
  std::vector<int> run;
  std::vector<int> best;
  for (std::size_t i = 1; i + 1 < path.size(); ++i)
  {
    const int v = path[i];
    const int next = path[i + 1];
    const int goal = steps[i].across >= 0 ? steps[i].near : -1;
    const Triangle& here = mesh.triangles[sleeve.back()];
    if (goal >= 0 ? sleeve.back() != goal : !hasCorner(here, next))
    {
      double bestAngle = Infinity;
      best.clear();
      for (const int edgeEnd : here)
      {
        double angle = 0.0;
        if (edgeEnd != v &&
            turnRound(mesh, adjacency, mask, sleeve.back(), v, edgeEnd, next, goal, run, angle) &&
            angle < bestAngle)
        {
          bestAngle = angle;
          best.swap(run);
        }
      }
      if (best.empty())
      {
        return false;
      }
      sleeve.insert(sleeve.end(), best.begin(), best.end());
    }
    if (goal >= 0)
    {
      sleeve.push_back(steps[i].across);
    }
  }
  const int source = path.front();
  const int target = path.back();
  std::size_t first = 0;
  std::size_t last = sleeve.size() - 1;
  for (std::size_t i = 0; i < sleeve.size(); ++i)
  {
    first = hasCorner(mesh.triangles[sleeve[i]], source) ? i : first;
  }
  for (std::size_t i = sleeve.size(); i-- > first;)
  {
    last = hasCorner(mesh.triangles[sleeve[i]], target) ? i : last;
  }
  sleeve.erase(sleeve.begin() + static_cast<std::ptrdiff_t>(last) + 1, sleeve.end());
  sleeve.erase(sleeve.begin(), sleeve.begin() + static_cast<std::ptrdiff_t>(first));
  std::unordered_map<int, std::size_t> seen;
  for (std::size_t i = 0; i < sleeve.size(); ++i)
  {
    const auto [at, inserted] = seen.emplace(sleeve[i], i);
    if (!inserted)
    {
      for (std::size_t j = at->second + 1; j <= i; ++j)
      {
        seen.erase(sleeve[j]);
      }
      seen.emplace(sleeve[i], at->second);
      sleeve.erase(sleeve.begin() + static_cast<std::ptrdiff_t>(at->second) + 1,
        sleeve.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      i = at->second;
    }
  }
  return !sleeve.empty() && hasCorner(mesh.triangles[sleeve.front()], source) &&
         hasCorner(mesh.triangles[sleeve.back()], target);
}

/// A corner of a sleeve triangle, unfolded into the plane.
struct Corner
{
  int vertex = -1;
  Vector2 at = Vector2::Zero();
};
using FlatTriangle = std::array<Corner, 3>;

/// The edge between sleeve triangles i and i + 1, its ends as seen going
/// through it.
struct Portal
{
  Corner left;
  Corner right;
};

/// Unfolds the sleeve into one plane, triangle after triangle across the
/// portals (each new corner placed from its two edge lengths, on the far
/// side of the portal). False if consecutive triangles share no edge.
bool unfoldSleeve(const TriangleMesh& mesh,
  const std::vector<int>& sleeve,
  std::vector<FlatTriangle>& flat,
  std::vector<Portal>& portals)
{
  const std::vector<Vector3>& p = mesh.positions;
  flat.resize(sleeve.size());
  portals.clear();
  const Triangle& c0 = mesh.triangles[sleeve[0]];
  const double ab = (p[c0[1]] - p[c0[0]]).norm();
  const double ac = (p[c0[2]] - p[c0[0]]).norm();
  const double bc = (p[c0[2]] - p[c0[1]]).norm();
  if (!(ab > 0.0))
  {
    return false;
  }
  const double x = (ac * ac - bc * bc + ab * ab) / (2.0 * ab);
  flat[0] = { { { c0[0], Vector2(0.0, 0.0) },
    { c0[1], Vector2(ab, 0.0) },
    { c0[2], Vector2(x, std::sqrt(std::max(ac * ac - x * x, 0.0))) } } };
  for (std::size_t i = 0; i + 1 < sleeve.size(); ++i)
  {
    const Triangle& next = mesh.triangles[sleeve[i + 1]];
    std::array<Corner, 2> shared;
    int sharedCount = 0;
    Corner behind;
    for (const Corner& corner : flat[i])
    {
      if (hasCorner(next, corner.vertex) && sharedCount < 2)
      {
        shared[sharedCount++] = corner;
      }
      else
      {
        behind = corner;
      }
    }
    const int ahead =
      next[0] != shared[0].vertex && next[0] != shared[1].vertex
        ? next[0]
        : (next[1] != shared[0].vertex && next[1] != shared[1].vertex ? next[1] : next[2]);
    const Corner& u = shared[0];
    const Corner& w = shared[1];
    const Vector2 base = w.at - u.at;
    const double length = base.norm();
    if (sharedCount != 2 || !(length > 0.0))
    {
      return false;
    }
    const double du = (p[ahead] - p[u.vertex]).norm();
    const double dw = (p[ahead] - p[w.vertex]).norm();
    const Vector2 e = base / length;
    const Vector2 normal(-e.y(), e.x()); // left of u -> w
    const double along = (du * du - dw * dw + length * length) / (2.0 * length);
    const double height = std::sqrt(std::max(du * du - along * along, 0.0));
    const bool behindOnLeft = cross2(base, behind.at - u.at) > 0.0;
    const Vector2 at = u.at + along * e + (behindOnLeft ? -height : height) * normal;
    flat[i + 1] = { { u, w, { ahead, at } } };
    // Going away from `behind`, w is on the left when `behind` is.
    portals.push_back(behindOnLeft ? Portal{ w, u } : Portal{ u, w });
  }
  return true;
}

/// A vertex where the shortest path through the sleeve bends (the source
/// and the target included), and the funnel portal it was reached at.
struct Bend
{
  Corner corner;
  int portal = 0;
};

/// The funnel algorithm over portals 0 (the source), the sleeve's, and the
/// last (the target): the bends of the shortest path through the sleeve.
void funnelPath(const Corner& source,
  const Corner& target,
  const std::vector<Portal>& portals,
  std::vector<Bend>& bends)
{
  const int count = static_cast<int>(portals.size()) + 2;
  auto portal = [&](int i) -> Portal
  {
    if (i == 0)
      return Portal{ source, source };
    if (i == count - 1)
      return Portal{ target, target };
    return portals[static_cast<std::size_t>(i - 1)];
  };
  bends.assign(1, Bend{ source, 0 });
  Corner apex = source;
  Corner left = source;
  Corner right = source;
  int apexIndex = 0;
  int leftIndex = 0;
  int rightIndex = 0;
  auto moveApex = [&](const Corner& to, int index)
  {
    if (to.vertex != apex.vertex)
    {
      bends.push_back(Bend{ to, index });
    }
    apex = left = right = to;
    apexIndex = leftIndex = rightIndex = index;
  };
  for (int i = 1; i < count; ++i)
  {
    const Portal next = portal(i);
    // The right side narrows (or holds) unless it crosses the left one.
    if (cross2(right.at - apex.at, next.right.at - apex.at) >= 0.0)
    {
      // A side still at the apex (after a bend) bounds nothing.
      if (right.vertex == apex.vertex || left.vertex == apex.vertex ||
          cross2(next.right.at - apex.at, left.at - apex.at) > 0.0)
      {
        right = next.right;
        rightIndex = i;
      }
      else
      {
        moveApex(left, leftIndex);
        i = apexIndex;
        continue;
      }
    }
    if (cross2(next.left.at - apex.at, left.at - apex.at) >= 0.0)
    {
      if (left.vertex == apex.vertex || right.vertex == apex.vertex ||
          cross2(right.at - apex.at, next.left.at - apex.at) > 0.0)
      {
        left = next.left;
        leftIndex = i;
      }
      else
      {
        moveApex(right, rightIndex);
        i = apexIndex;
        continue;
      }
    }
  }
  if (bends.back().corner.vertex != target.vertex)
  {
    bends.push_back(Bend{ target, count - 1 });
  }
}

/// The sleeve triangles around an inner bend: [first, last], all holding
/// its vertex.
std::array<int, 2> bendRun(const TriangleMesh& mesh,
  const std::vector<int>& sleeve,
  const Bend& bend)
{
  const int v = bend.corner.vertex;
  int first = bend.portal - 1; // funnel portal i joins sleeve triangles i - 1 and i
  int last = bend.portal;
  while (first > 0 && hasCorner(mesh.triangles[sleeve[first - 1]], v))
  {
    --first;
  }
  while (
    last + 1 < static_cast<int>(sleeve.size()) && hasCorner(mesh.triangles[sleeve[last + 1]], v))
  {
    ++last;
  }
  return { { first, last } };
}

/// The corner of flat triangle `here` that is neither v nor a corner of
/// mesh triangle `neighbour`.
const Corner& farCorner(const FlatTriangle& here, int v, const Triangle& neighbour)
{
  for (const Corner& corner : here)
  {
    if (corner.vertex != v && !hasCorner(neighbour, corner.vertex))
    {
      return corner;
    }
  }
  return here[0];
}

/// If the path bending at inner bend `b` (sleeve triangles `run` around its
/// vertex) would be shorter round the vertex's other side (the angle there
/// below pi), the triangles of that side from the run's first to its last,
/// exclusive; empty if the bend may stay (also where that side leaves the
/// allowed surface: a border vertex holds a bend).
std::vector<int> otherSide(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  const std::vector<int>& sleeve,
  const std::vector<FlatTriangle>& flat,
  const std::vector<Bend>& bends,
  std::size_t b,
  const std::array<int, 2>& run,
  double limit = Pi - AngleTolerance)
{
  const Corner& at = bends[b].corner;
  const int v = at.vertex;
  const auto [first, last] = run;
  const Corner& in = farCorner(flat[first], v, mesh.triangles[sleeve[first + 1]]);
  const Corner& out = farCorner(flat[last], v, mesh.triangles[sleeve[last - 1]]);
  double angle = angleBetween(in.at - at.at, bends[b - 1].corner.at - at.at) +
                 angleBetween(out.at - at.at, bends[b + 1].corner.at - at.at);
  if (angle >= limit)
  {
    return {};
  }
  std::vector<int> around;
  int current = sleeve[first];
  int edgeEnd = in.vertex;
  for (int guard = adjacency.vertexTriangleCount(v); guard >= 0; --guard)
  {
    const int k = edgeOf(mesh.triangles[current], v, edgeEnd);
    const int n = k < 0 ? -1 : adjacency.neighbourAcross(current, k);
    if (n < 0 || !mask(n))
    {
      return {};
    }
    if (n == sleeve[last])
    {
      return angle < limit ? around : std::vector<int>{};
    }
    if (std::find(sleeve.begin() + first, sleeve.begin() + last + 1, n) !=
        sleeve.begin() + last + 1)
    {
      return {};
    }
    const Triangle& nc = mesh.triangles[n];
    angle += cornerAngle(mesh, nc, v);
    if (angle >= limit)
    {
      return {};
    }
    around.push_back(n);
    edgeEnd =
      nc[0] != v && nc[0] != edgeEnd ? nc[0] : (nc[1] != v && nc[1] != edgeEnd ? nc[1] : nc[2]);
    current = n;
  }
  return {};
}

/// Moves every bend that a vertex's other side would shorten (runs not
/// sharing inner triangles, from the last); false if none moved.
/// `degenerate` is set when a move would make the sleeve visit a triangle
/// twice.
bool rerouteBends(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  std::vector<int>& sleeve,
  const std::vector<FlatTriangle>& flat,
  const std::vector<Bend>& bends,
  int& reroutes,
  bool& degenerate)
{
  bool moved = false;
  int lowestFirst = static_cast<int>(sleeve.size());
  for (std::size_t b = bends.size() - 2; b >= 1; --b)
  {
    const std::array<int, 2> run = bendRun(mesh, sleeve, bends[b]);
    if (run[1] > lowestFirst)
    {
      continue;
    }
    const std::vector<int> around = otherSide(mesh, adjacency, mask, sleeve, flat, bends, b, run);
    if (around.empty())
    {
      continue;
    }
    for (int t : around)
    {
      if (std::find(sleeve.begin(), sleeve.end(), t) != sleeve.end())
      {
        degenerate = true;
        return false;
      }
    }
    sleeve.erase(sleeve.begin() + run[0] + 1, sleeve.begin() + run[1]);
    sleeve.insert(sleeve.begin() + run[0] + 1, around.begin(), around.end());
    lowestFirst = run[0];
    moved = true;
    ++reroutes;
  }
  return moved;
}

/// The path's points: the bends, and where each straight piece between
/// them crosses a portal (a portal in a bend's run meets the path at the
/// bend's vertex).
std::optional<SurfacePath> pathThroughSleeve(const TriangleMesh& mesh,
  const std::vector<int>& sleeve,
  const std::vector<Portal>& portals,
  const std::vector<Bend>& bends)
{
  SurfacePath path;
  auto add = [&path](const SurfacePoint& point) { path.appendMerged(point, EndpointTolerance); };
  const std::size_t target = bends.size() - 1;
  std::vector<std::array<int, 2>> runs(bends.size(), std::array<int, 2>{ { -1, -1 } });
  for (std::size_t b = 1; b < target; ++b)
  {
    runs[b] = bendRun(mesh, sleeve, bends[b]);
  }
  add(SurfacePoint::atVertex(bends.front().corner.vertex));
  std::size_t q = 0; // the piece from bend q to bend q + 1
  for (int j = 0; j < static_cast<int>(portals.size()); ++j)
  {
    while (q + 1 < target && j >= runs[q + 1][1])
    {
      add(SurfacePoint::atVertex(bends[q + 1].corner.vertex));
      ++q;
    }
    if (q + 1 < target && j >= runs[q + 1][0])
    {
      add(SurfacePoint::atVertex(bends[q + 1].corner.vertex));
      continue;
    }
    const Vector2& from = bends[q].corner.at;
    const Vector2 along = bends[q + 1].corner.at - from;
    const Portal& portal = portals[static_cast<std::size_t>(j)];
    const Vector2 edge = portal.right.at - portal.left.at;
    const double denominator = cross2(edge, along);
    const double u = std::clamp(
      denominator != 0.0 ? cross2(from - portal.left.at, along) / denominator : 0.5, 0.0, 1.0);
    if (!std::isfinite(u))
    {
      return std::nullopt;
    }
    if (u <= EndpointTolerance)
      add(SurfacePoint::atVertex(portal.left.vertex));
    else if (u >= 1.0 - EndpointTolerance)
      add(SurfacePoint::atVertex(portal.right.vertex));
    else
      add(SurfacePoint::onEdge(portal.left.vertex, portal.right.vertex, u));
  }
  for (std::size_t b = q + 1; b <= target; ++b)
  {
    add(SurfacePoint::atVertex(bends[b].corner.vertex));
  }
  path.measure(mesh.positions);
  return path;
}

/// The corner of flat triangle `flat` at vertex v.
Corner cornerAt(const FlatTriangle& flat, int v)
{
  for (const Corner& corner : flat)
  {
    if (corner.vertex == v)
    {
      return corner;
    }
  }
  return flat[0];
}

/// The locally shortest path through a first sleeve, its bends rerouted
/// until none may go round its vertex's other side.
std::optional<SurfacePath> tightenSleeve(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  int source,
  int target,
  std::vector<int>& sleeve,
  SleeveStatistics& stats)
{
  std::vector<FlatTriangle> flat;
  std::vector<Portal> portals;
  std::vector<Bend> bends;
  // Each reroute shortens the path; the cap only guards against round-off
  // trading two bends back and forth.
  const int rerouteCap = 4 * static_cast<int>(sleeve.size()) + 64;
  for (;;)
  {
    if (!unfoldSleeve(mesh, sleeve, flat, portals))
    {
      return std::nullopt;
    }
    funnelPath(cornerAt(flat.front(), source), cornerAt(flat.back(), target), portals, bends);
    bool degenerate = false;
    if (bends.size() < 3 ||
        !rerouteBends(mesh, adjacency, mask, sleeve, flat, bends, stats.reroutes, degenerate))
    {
      if (degenerate)
      {
        return std::nullopt;
      }
      break;
    }
    if (stats.reroutes > rerouteCap)
    {
      return std::nullopt;
    }
  }
  stats.sleeveTriangles = sleeve.size();
  return pathThroughSleeve(mesh, sleeve, portals, bends);
}

/// A locally shortest path can hang on a saddle vertex (at least pi on both
/// sides), and rough surfaces have many: each bend is tried on its vertex's
/// other side, tightened again, and the shorter path kept, until no bend
/// moves (at most `trials` tries).
std::optional<SurfacePath> escapeSaddles(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  int source,
  int target,
  std::vector<int>& sleeve,
  SurfacePath path,
  SleeveStatistics& stats)
{
  std::vector<FlatTriangle> flat;
  std::vector<Portal> portals;
  std::vector<Bend> bends;
  int trials = 4 * static_cast<int>(sleeve.size()) + 64;
  for (bool improved = true; improved && trials > 0;)
  {
    improved = false;
    if (!unfoldSleeve(mesh, sleeve, flat, portals))
    {
      break;
    }
    funnelPath(cornerAt(flat.front(), source), cornerAt(flat.back(), target), portals, bends);
    for (std::size_t b = 1; b + 1 < bends.size() && trials > 0 && !improved; ++b, --trials)
    {
      const std::array<int, 2> run = bendRun(mesh, sleeve, bends[b]);
      const std::vector<int> around =
        otherSide(mesh, adjacency, mask, sleeve, flat, bends, b, run, Infinity);
      if (around.empty() ||
          std::any_of(around.begin(),
            around.end(),
            [&](int t) { return std::find(sleeve.begin(), sleeve.end(), t) != sleeve.end(); }))
      {
        continue;
      }
      std::vector<int> candidate(sleeve.begin(), sleeve.begin() + run[0] + 1);
      candidate.insert(candidate.end(), around.begin(), around.end());
      candidate.insert(candidate.end(), sleeve.begin() + run[1], sleeve.end());
      SleeveStatistics candidateStats;
      std::optional<SurfacePath> shorter =
        tightenSleeve(mesh, adjacency, mask, source, target, candidate, candidateStats);
      if (shorter && shorter->length < path.length * (1.0 - 1e-12))
      {
        path = std::move(*shorter);
        sleeve.swap(candidate);
        stats.reroutes += candidateStats.reroutes + 1;
        stats.sleeveTriangles = sleeve.size();
        improved = true;
      }
    }
  }
  return path;
}

} // namespace

std::optional<SurfacePath> sleeveGeodesic(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  int source,
  int target,
  SleeveStatistics* statistics)
{
  if (source == target)
  {
    return std::nullopt;
  }
  // Two first sleeves: along the shortest path of steps along and across
  // edges (its path is no longer than that path, nor than the edge path)
  // and A*'s over triangle centroids. Each settles in a local geodesic; on
  // curved or rough surfaces they can differ (a bump passed on the other
  // side), and the shorter is kept.
  SleeveStatistics stats;
  std::optional<SurfacePath> best;
  std::vector<int> stepPath;
  std::vector<SearchNode> steps;
  std::vector<int> sleeve;
  if (searchStepPath(
        mesh, adjacency, mask, source, target, stepPath, steps, stats.searchedVertices) &&
      sleeveAlongStepPath(mesh, adjacency, mask, stepPath, steps, sleeve))
  {
    best = tightenSleeve(mesh, adjacency, mask, source, target, sleeve, stats);
    if (best)
    {
      best = escapeSaddles(mesh, adjacency, mask, source, target, sleeve, *best, stats);
    }
  }
  SleeveStatistics centroidStats;
  if (searchCentroidSleeve(mesh, adjacency, mask, source, target, sleeve))
  {
    std::optional<SurfacePath> other =
      tightenSleeve(mesh, adjacency, mask, source, target, sleeve, centroidStats);
    if (other)
    {
      other = escapeSaddles(mesh, adjacency, mask, source, target, sleeve, *other, centroidStats);
    }
    if (other && (!best || other->length < best->length * (1.0 - 1e-12)))
    {
      best = std::move(other);
      centroidStats.searchedVertices = stats.searchedVertices;
      stats = centroidStats;
    }
  }
  if (statistics)
  {
    *statistics = stats;
  }
  return best;
}

} // namespace thintissue
