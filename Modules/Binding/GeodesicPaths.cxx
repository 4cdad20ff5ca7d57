#include "GeodesicPaths.h"

#include "SleeveGeodesic.h"
#include "SurfaceSteps.h"
#include "ThinTissueError.h"
#include "TriangleMask.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <queue>
#include <string>
#include <utility>
#include <vector>

namespace thintissue
{

namespace
{

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using PatchMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using PatchTraits = CGAL::Surface_mesh_shortest_path_traits<Kernel, PatchMesh>;
using PatchShortestPath = CGAL::Surface_mesh_shortest_path<PatchTraits>;

constexpr double Infinity = std::numeric_limits<double>::infinity();
/// A path point this close (in edge parameter) to an edge end is that vertex.
constexpr double EndpointTolerance = 1e-12;
/// Relative slack of the ellipse bound, so that round-off in the two
/// Dijkstra sums cannot drop a vertex of a shortest search path.
constexpr double EllipseTolerance = 1e-12;

std::string meshLabel(const TriangleMesh& mesh)
{
  return mesh.name.empty() ? std::string("mesh") : "mesh '" + mesh.name + "'";
}

/// What one call knows about one mesh vertex.
struct VertexState
{
  double fromSource = Infinity;
  double fromTarget = Infinity;
  int patchTriangles = 0; ///< triangles of the vertex in the patch
  int patchVertex = -1;   ///< CGAL vertex (vertices whose star is in the patch)
  int rimVertex = -1;     ///< index into Patch::rimVertices (the others)
  bool sourceSettled = false;
  bool targetSettled = false;
};

/// Open-addressing hash map vertex -> VertexState, so that a call costs
/// memory and time in proportion to the vertices it touches, not to the
/// mesh. Deterministic (no iteration is exposed). References returned by
/// `at` are invalidated by the next insertion.
class VertexTable
{
public:
  VertexTable() { rehash(1024); }

  /// The state of `vertex`, inserted (default) if missing.
  VertexState& at(int vertex)
  {
    std::size_t slot = slotOf(vertex);
    if (Keys[slot] == vertex)
    {
      return Values[slot];
    }
    if (2 * (Count + 1) > Keys.size())
    {
      rehash(2 * Keys.size());
      slot = slotOf(vertex);
    }
    while (Keys[slot] >= 0)
    {
      if (Keys[slot] == vertex)
      {
        return Values[slot];
      }
      slot = (slot + 1) & Mask;
    }
    Keys[slot] = vertex;
    Values[slot] = VertexState();
    ++Count;
    return Values[slot];
  }

  /// The state of `vertex`, or nullptr.
  const VertexState* find(int vertex) const
  {
    for (std::size_t slot = slotOf(vertex); Keys[slot] >= 0; slot = (slot + 1) & Mask)
    {
      if (Keys[slot] == vertex)
      {
        return &Values[slot];
      }
    }
    return nullptr;
  }
  VertexState* find(int vertex)
  {
    return const_cast<VertexState*>(static_cast<const VertexTable&>(*this).find(vertex));
  }

  void clear()
  {
    std::fill(Keys.begin(), Keys.end(), -1);
    Count = 0;
  }

private:
  std::size_t slotOf(int vertex) const
  {
    // Fibonacci hashing: the high bits of the product are well mixed.
    const std::uint64_t h =
      static_cast<std::uint64_t>(static_cast<std::uint32_t>(vertex)) * UINT64_C(0x9E3779B97F4A7C15);
    return static_cast<std::size_t>(h >> Shift);
  }

  void rehash(std::size_t capacity)
  {
    std::vector<int> oldKeys(capacity, -1);
    std::vector<VertexState> oldValues(capacity);
    oldKeys.swap(Keys);
    oldValues.swap(Values);
    Mask = capacity - 1;
    Shift = 64;
    for (std::size_t c = capacity; c > 1; c >>= 1)
    {
      --Shift;
    }
    Count = 0;
    for (std::size_t i = 0; i < oldKeys.size(); ++i)
    {
      if (oldKeys[i] >= 0)
      {
        at(oldKeys[i]) = oldValues[i];
      }
    }
  }

  std::vector<int> Keys;
  std::vector<VertexState> Values;
  std::size_t Mask = 0;
  int Shift = 64;
  std::size_t Count = 0;
};

using QueueEntry = std::pair<double, int>;
using MinQueue = std::priority_queue<QueueEntry, std::vector<QueueEntry>, std::greater<QueueEntry>>;

/// A* search (the straight-line distance to `target` is a consistent
/// heuristic) with the steps of forEachStep; +infinity when the vertices are
/// not connected.
double searchDistance(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  int source,
  int target,
  bool acrossEdges)
{
  if (source == target)
  {
    return 0.0;
  }
  const std::vector<Vector3>& p = mesh.positions;
  VertexTable table;
  MinQueue queue;
  table.at(source).fromSource = 0.0;
  queue.emplace((p[source] - p[target]).norm(), source);
  while (!queue.empty())
  {
    const int v = queue.top().second;
    queue.pop();
    VertexState& state = table.at(v);
    if (state.sourceSettled)
    {
      continue;
    }
    state.sourceSettled = true;
    const double distance = state.fromSource;
    if (v == target)
    {
      return distance;
    }
    forEachStep(mesh,
      adjacency,
      mask,
      v,
      acrossEdges,
      [&](int u, double length, int, int)
      {
        const double d = distance + length;
        VertexState& neighbour = table.at(u);
        if (!neighbour.sourceSettled && d < neighbour.fromSource)
        {
          neighbour.fromSource = d;
          queue.emplace(d + (p[u] - p[target]).norm(), u);
        }
      });
  }
  return Infinity;
}

/// The vertices v with d(s, v) + d(v, t) <= bound (the ellipse), in the
/// order the search from t settles them; `table` receives both distances.
/// Dijkstra from s keeps only vertices with d(s, v) + |v - t| <= bound, the
/// one from t only vertices with d(s, v) + d(t, v) <= bound: every vertex
/// of a shortest search path from s or t to an ellipse vertex passes both
/// tests, so the ellipse's distances are exact.
std::vector<int> ellipseVertices(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  int source,
  int target,
  double bound,
  VertexTable& table)
{
  const std::vector<Vector3>& p = mesh.positions;
  MinQueue queue;
  table.at(source).fromSource = 0.0;
  queue.emplace(0.0, source);
  while (!queue.empty())
  {
    const auto [distance, v] = queue.top();
    queue.pop();
    VertexState& state = table.at(v);
    if (state.sourceSettled)
    {
      continue;
    }
    state.sourceSettled = true;
    forEachStep(mesh,
      adjacency,
      mask,
      v,
      true,
      [&, distance = distance](int u, double length, int, int)
      {
        const double d = distance + length;
        if (d + (p[u] - p[target]).norm() > bound)
        {
          return;
        }
        VertexState& neighbour = table.at(u);
        if (!neighbour.sourceSettled && d < neighbour.fromSource)
        {
          neighbour.fromSource = d;
          queue.emplace(d, u);
        }
      });
  }

  std::vector<int> ellipse;
  table.at(target).fromTarget = 0.0;
  queue.emplace(0.0, target);
  while (!queue.empty())
  {
    const auto [distance, v] = queue.top();
    queue.pop();
    VertexState& state = table.at(v);
    if (state.targetSettled)
    {
      continue;
    }
    state.targetSettled = true;
    ellipse.push_back(v);
    forEachStep(mesh,
      adjacency,
      mask,
      v,
      true,
      [&, distance = distance](int u, double length, int, int)
      {
        const double d = distance + length;
        VertexState* neighbour = table.find(u);
        // Not reached from s: d(s, u) + |u - t| > bound, so u is outside.
        if (neighbour == nullptr || !neighbour->sourceSettled || neighbour->targetSettled ||
            neighbour->fromSource + d > bound || d >= neighbour->fromTarget)
        {
          return;
        }
        neighbour->fromTarget = d;
        queue.emplace(d, u);
      });
  }
  return ellipse;
}

/// A local patch as a CGAL surface: the stars of the ellipse vertices. A
/// vertex whose star is only partly in the patch (on the patch's rim) gets
/// one CGAL vertex per fan of its patch triangles, so that the patch is a
/// manifold with border.
struct Patch
{
  std::vector<int> triangles;    ///< sorted mesh triangle indices
  std::vector<int> meshVertexOf; ///< CGAL vertex -> mesh vertex
  /// Rim vertices: (mesh triangle, CGAL vertex) for each of its patch
  /// triangles.
  std::vector<std::vector<std::pair<int, int>>> rimVertices;
  PatchMesh surface;
  /// Some vertex has triangles outside the patch (else the patch is a
  /// whole connected piece of the mesh).
  bool hasRim = false;

  bool contains(int triangle) const
  {
    return std::binary_search(triangles.begin(), triangles.end(), triangle);
  }
};

void buildPatch(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  const std::vector<char>& flipped,
  const std::vector<int>& ellipse,
  VertexTable& table,
  Patch& patch)
{
  for (int v : ellipse)
  {
    for (const int* t = adjacency.vertexTrianglesBegin(v); t != adjacency.vertexTrianglesEnd(v);
         ++t)
    {
      if (mask(*t))
      {
        patch.triangles.push_back(*t);
      }
    }
  }
  std::sort(patch.triangles.begin(), patch.triangles.end());
  patch.triangles.erase(
    std::unique(patch.triangles.begin(), patch.triangles.end()), patch.triangles.end());
  for (int t : patch.triangles)
  {
    for (int v : mesh.triangles[t])
    {
      ++table.at(v).patchTriangles;
    }
  }

  auto addVertex = [&](int v)
  {
    patch.meshVertexOf.push_back(v);
    const Vector3& x = mesh.positions[v];
    return static_cast<int>(patch.surface.add_vertex(Kernel::Point_3(x.x(), x.y(), x.z())));
  };

  // Fans of a rim vertex: its patch triangles joined across the edges
  // through it (union-find on a handful of triangles).
  auto splitRimVertex = [&](int v)
  {
    std::vector<int> fan;
    for (const int* t = adjacency.vertexTrianglesBegin(v); t != adjacency.vertexTrianglesEnd(v);
         ++t)
    {
      if (patch.contains(*t))
      {
        fan.push_back(*t);
      }
    }
    std::vector<int> parent(fan.size());
    for (std::size_t i = 0; i < fan.size(); ++i)
    {
      parent[i] = static_cast<int>(i);
    }
    auto root = [&](int i)
    {
      while (parent[i] != i)
      {
        i = parent[i] = parent[parent[i]];
      }
      return i;
    };
    for (std::size_t i = 0; i < fan.size(); ++i)
    {
      const Triangle& corners = mesh.triangles[fan[i]];
      for (int k = 0; k < 3; ++k)
      {
        if (corners[k] != v && corners[(k + 1) % 3] != v)
        {
          continue;
        }
        const int across = adjacency.neighbourAcross(fan[i], k);
        const auto j = std::lower_bound(fan.begin(), fan.end(), across);
        if (across >= 0 && j != fan.end() && *j == across)
        {
          const int a = root(static_cast<int>(i));
          const int b = root(static_cast<int>(j - fan.begin()));
          parent[std::max(a, b)] = std::min(a, b);
        }
      }
    }
    std::vector<int> vertexOfRoot(fan.size(), -1);
    std::vector<std::pair<int, int>> assignment;
    for (std::size_t i = 0; i < fan.size(); ++i)
    {
      const int r = root(static_cast<int>(i));
      if (vertexOfRoot[r] < 0)
      {
        vertexOfRoot[r] = addVertex(v);
      }
      assignment.emplace_back(fan[i], vertexOfRoot[r]);
    }
    patch.rimVertices.push_back(std::move(assignment));
    return static_cast<int>(patch.rimVertices.size()) - 1;
  };

  const std::size_t faces = patch.triangles.size();
  patch.surface.reserve(faces / 2 + 16, 3 * faces / 2 + 16, faces);
  for (int t : patch.triangles)
  {
    std::array<int, 3> corners{};
    for (int k = 0; k < 3; ++k)
    {
      const int v = mesh.triangles[t][k];
      VertexState& state = table.at(v);
      if (state.patchTriangles == mask.vertexTriangleCount(adjacency, v))
      {
        if (state.patchVertex < 0)
        {
          const int created = addVertex(v);
          table.at(v).patchVertex = created;
        }
        corners[k] = table.at(v).patchVertex;
        continue;
      }
      patch.hasRim = true;
      if (state.rimVertex < 0)
      {
        const int created = splitRimVertex(v);
        table.at(v).rimVertex = created;
      }
      for (const auto& [triangle, vertex] : patch.rimVertices[table.at(v).rimVertex])
      {
        if (triangle == t)
        {
          corners[k] = vertex;
        }
      }
    }
    if (flipped[t])
    {
      std::swap(corners[1], corners[2]);
    }
    const auto face = patch.surface.add_face(PatchMesh::Vertex_index(corners[0]),
      PatchMesh::Vertex_index(corners[1]),
      PatchMesh::Vertex_index(corners[2]));
    if (face == PatchMesh::null_face())
    {
      throw Error("geodesic path on " + meshLabel(mesh) + ": could not build the local patch (" +
                  "triangle " + std::to_string(t) + " rejected)");
    }
  }
}

/// The straight segment from vertex `source` to vertex `target` walked
/// across the surface, triangle by triangle, if it lies on the surface:
/// every triangle it crosses (all allowed by `mask`) contains it. A straight
/// segment is the shortest of all curves between its ends, so such a path
/// is the exact geodesic whatever the rest of the surface is: flat regions
/// (most of a sheet's paths) need no CGAL patch. Nothing when the segment
/// leaves the surface, meets a masked triangle, or the walk stalls.
std::optional<SurfacePath> straightPathOnSurface(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  int source,
  int target)
{
  const std::vector<Vector3>& p = mesh.positions;
  const Vector3 start = p[source];
  const Vector3 direction = p[target] - start;
  const double length = direction.norm();
  if (!(length > 0.0))
  {
    return std::nullopt;
  }
  // Relative tolerances: in the plane (sines) and along edges.
  constexpr double PlaneTolerance = 1e-10;
  constexpr double EdgeTolerance = 1e-10;
  auto inPlane = [&](int t)
  {
    const Triangle& c = mesh.triangles[t];
    const Vector3 n = (p[c[1]] - p[c[0]]).cross(p[c[2]] - p[c[0]]);
    const double scale = n.norm();
    return scale > 0.0 && std::abs(n.dot(direction)) <= PlaneTolerance * scale * length &&
           std::abs(n.dot(start - p[c[0]])) <= PlaneTolerance * scale * length;
  };
  SurfacePath path;
  path.points.push_back(SurfacePoint::atVertex(source));
  // The walk's state: at a vertex (vertex >= 0) or inside edge (a, b) of
  // triangle `from`, heading into the triangle across it.
  int vertex = source;
  int edgeA = -1;
  int edgeB = -1;
  int from = -1;
  double travelled = 0.0; // parameter s of the present point
  const std::size_t limit = 4 * mesh.triangleCount() + 16;
  for (std::size_t step = 0; step < limit; ++step)
  {
    int triangle = -1;
    if (vertex >= 0)
    {
      // The triangle of the vertex's fan whose angle holds the direction.
      for (const int* t = adjacency.vertexTrianglesBegin(vertex);
           t != adjacency.vertexTrianglesEnd(vertex);
           ++t)
      {
        if (!mask(*t) || !inPlane(*t))
        {
          continue;
        }
        const Triangle& c = mesh.triangles[*t];
        const int k = c[0] == vertex ? 0 : (c[1] == vertex ? 1 : 2);
        const Vector3 toP = p[c[(k + 1) % 3]] - p[vertex];
        const Vector3 toQ = p[c[(k + 2) % 3]] - p[vertex];
        const Vector3 n = toP.cross(toQ);
        const double slack = -EdgeTolerance * n.norm() * length;
        if (toP.cross(direction).dot(n) >= slack * toP.norm() &&
            direction.cross(toQ).dot(n) >= slack * toQ.norm())
        {
          triangle = *t;
          break;
        }
      }
    }
    else
    {
      const int e = adjacency.findEdge(edgeA, edgeB);
      for (const int* t = adjacency.edgeTrianglesBegin(e); t != adjacency.edgeTrianglesEnd(e); ++t)
      {
        if (*t != from && mask(*t) && inPlane(*t))
        {
          triangle = *t;
        }
      }
    }
    if (triangle < 0)
    {
      return std::nullopt;
    }
    const Triangle& c = mesh.triangles[triangle];
    if (c[0] == target || c[1] == target || c[2] == target)
    {
      // The triangle is convex and holds the present point and the target.
      path.points.push_back(SurfacePoint::atVertex(target));
      path.length = length;
      return path;
    }
    // Leave across the edge (not through the present point) that the line
    // meets farthest along: with the line x(s) = start + s d and edge
    // u + t (v - u), solved in the triangle's plane.
    const Vector3 n = (p[c[1]] - p[c[0]]).cross(p[c[2]] - p[c[0]]);
    double bestS = -Infinity;
    int bestK = -1;
    double bestT = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      const int u = c[k];
      const int v = c[(k + 1) % 3];
      if (u == vertex || v == vertex ||
          (std::min(u, v) == std::min(edgeA, edgeB) && std::max(u, v) == std::max(edgeA, edgeB)))
      {
        continue;
      }
      const Vector3 edge = p[v] - p[u];
      const double denominator = direction.cross(edge).dot(n);
      if (denominator == 0.0)
      {
        continue;
      }
      const Vector3 offset = p[u] - start;
      const double along = offset.cross(edge).dot(n) / denominator;
      const double t = offset.cross(direction).dot(n) / denominator;
      if (t >= -EdgeTolerance && t <= 1.0 + EdgeTolerance && along > bestS)
      {
        bestS = along;
        bestK = k;
        bestT = std::clamp(t, 0.0, 1.0);
      }
    }
    if (bestK < 0 || bestS >= 1.0 || !(bestS > travelled))
    {
      return std::nullopt; // stalled, or the target is not where the line goes
    }
    travelled = bestS;
    const int u = c[bestK];
    const int v = c[(bestK + 1) % 3];
    from = triangle;
    if (bestT <= EdgeTolerance || bestT >= 1.0 - EdgeTolerance)
    {
      vertex = bestT <= EdgeTolerance ? u : v;
      edgeA = edgeB = -1;
      if (vertex == path.points.back().vertex)
      {
        return std::nullopt; // no progress
      }
      path.points.push_back(SurfacePoint::atVertex(vertex));
      if (vertex == target)
      {
        path.length = length;
        return path;
      }
    }
    else
    {
      vertex = -1;
      edgeA = u;
      edgeB = v;
      path.points.push_back(SurfacePoint::onEdge(u, v, bestT));
    }
  }
  return std::nullopt;
}

DisconnectedPathError notConnected(const TriangleMesh& mesh, int source, int target)
{
  return DisconnectedPathError("geodesic path on " + meshLabel(mesh) + ": vertices " +
                               std::to_string(source) + " and " + std::to_string(target) +
                               " are not connected");
}

/// A point of CGAL's path as it is reported, before snapping.
struct RawPathPoint
{
  int vertex = -1; ///< mesh vertex, or
  int edgeStart = -1;
  int edgeEnd = -1;
  double edgeParameter = 0.0; ///< toward edgeEnd
  bool onPatchBorderEdge = false;
};

/// Receives CGAL's path from the query vertex back to the source point.
struct PathCollector
{
  const Patch& patch;
  std::vector<RawPathPoint> points;

  /// The point (1 - t) source(h) + t target(h): CGAL's edge parameter
  /// weights the halfedge's target (Surface_mesh_shortest_path::point).
  void operator()(PatchMesh::Halfedge_index h, double t)
  {
    RawPathPoint point;
    point.edgeStart = patch.meshVertexOf[patch.surface.source(h)];
    point.edgeEnd = patch.meshVertexOf[patch.surface.target(h)];
    point.edgeParameter = t;
    point.onPatchBorderEdge = patch.surface.is_border(patch.surface.edge(h));
    points.push_back(point);
  }
  void operator()(PatchMesh::Vertex_index v)
  {
    RawPathPoint point;
    point.vertex = patch.meshVertexOf[v];
    points.push_back(point);
  }
  /// Only a face or edge source point ends a path this way; the source is
  /// a vertex here, so it gives the corner its coordinates select.
  template <class Coordinates>
  void operator()(PatchMesh::Face_index f, const Coordinates& coordinates)
  {
    auto h = patch.surface.halfedge(f);
    int best = 0;
    for (int k = 1; k < 3; ++k)
    {
      if (coordinates[k] > coordinates[best])
      {
        best = k;
      }
    }
    for (int k = 0; k < best; ++k)
    {
      h = patch.surface.next(h);
    }
    (*this)(patch.surface.source(h));
  }
};

struct PatchPath
{
  SurfacePath path;
  bool touchesRim = false;
  bool found = false;
};

/// CGAL's exact shortest path from `source` to `target` on the patch, in
/// mesh vertex indices, snapped, merged, and whether it touches the rim.
PatchPath shortestPathOnPatch(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  const Patch& patch,
  const VertexTable& table,
  int source,
  int target)
{
  PatchPath result;
  PatchShortestPath shortestPaths(patch.surface);
  shortestPaths.add_source_point(PatchMesh::Vertex_index(table.find(target)->patchVertex));
  PathCollector collector{ patch, {} };
  const auto reached = shortestPaths.shortest_path_sequence_to_source_points(
    PatchMesh::Vertex_index(table.find(source)->patchVertex), collector);
  if (reached.first < 0.0 || collector.points.empty())
  {
    return result;
  }
  result.found = true;

  auto isRimVertex = [&](int v)
  { return table.find(v)->patchTriangles != mask.vertexTriangleCount(adjacency, v); };
  std::vector<SurfacePoint>& points = result.path.points;
  for (const RawPathPoint& raw : collector.points)
  {
    SurfacePoint point;
    bool onRim = false;
    if (raw.vertex >= 0)
    {
      point = SurfacePoint::atVertex(raw.vertex);
      onRim = isRimVertex(raw.vertex);
    }
    else
    {
      const double t = raw.edgeParameter;
      if (!std::isfinite(t))
      {
        throw Error("geodesic path on " + meshLabel(mesh) +
                    ": non-finite edge parameter on edge (" + std::to_string(raw.edgeStart) + ", " +
                    std::to_string(raw.edgeEnd) + ")");
      }
      if (t <= EndpointTolerance)
      {
        point = SurfacePoint::atVertex(raw.edgeStart);
        onRim = isRimVertex(raw.edgeStart);
      }
      else if (t >= 1.0 - EndpointTolerance)
      {
        point = SurfacePoint::atVertex(raw.edgeEnd);
        onRim = isRimVertex(raw.edgeEnd);
      }
      else
      {
        point = SurfacePoint::onEdge(raw.edgeStart, raw.edgeEnd, t);
        onRim = raw.onPatchBorderEdge && mask.edgeTriangleCount(adjacency,
                                           adjacency.findEdge(raw.edgeStart, raw.edgeEnd)) == 2;
      }
    }
    result.touchesRim = result.touchesRim || onRim;
    result.path.appendMerged(point, EndpointTolerance);
  }
  if (points.front().vertex != source || points.back().vertex != target)
  {
    throw Error("geodesic path on " + meshLabel(mesh) + ": CGAL's path from vertex " +
                std::to_string(source) + " does not run to vertex " + std::to_string(target));
  }
  result.path.measure(mesh.positions);
  return result;
}

} // namespace

//------------------------------------------------------------------------------
GeodesicPathFinder::GeodesicPathFinder(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency)
  : Mesh(mesh)
  , Adjacency(adjacency)
{
  mesh.checkConsistency();
  const std::string label = meshLabel(mesh);
  const int triangleCount = static_cast<int>(mesh.triangleCount());
  for (int t = 0; t < triangleCount; ++t)
  {
    const Triangle& c = mesh.triangles[t];
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0])
    {
      throw InvalidInputError(
        "geodesic paths: " + label + ": triangle " + std::to_string(t) + " repeats a vertex");
    }
    const Vector3& a = mesh.positions[c[0]];
    if ((mesh.positions[c[1]] - a).cross(mesh.positions[c[2]] - a).squaredNorm() == 0.0)
    {
      throw InvalidInputError("geodesic paths: " + label + ": triangle " + std::to_string(t) +
                              " is degenerate (zero area)");
    }
  }
  for (int e = 0; e < static_cast<int>(adjacency.edgeCount()); ++e)
  {
    if (adjacency.edgeTriangleCount(e) > 2)
    {
      throw InvalidInputError("geodesic paths: " + label + " is not edge-manifold: edge (" +
                              std::to_string(adjacency.edge(e)[0]) + ", " +
                              std::to_string(adjacency.edge(e)[1]) + ") has " +
                              std::to_string(adjacency.edgeTriangleCount(e)) + " triangles");
    }
  }
  // Vertex-manifold: the triangles around each vertex form one fan.
  for (int v = 0; v < static_cast<int>(mesh.vertexCount()); ++v)
  {
    const int fans = adjacency.vertexFanCount(v);
    if (fans > 1)
    {
      throw InvalidInputError("geodesic paths: " + label + " is not vertex-manifold: vertex " +
                              std::to_string(v) + " joins " + std::to_string(fans) +
                              " separate fans of triangles");
    }
  }
  // Orientation: each piece made consistent with its first triangle (the
  // patch surfaces need it); a non-orientable piece is rejected.
  Flipped.assign(mesh.triangleCount(), 0);
  std::vector<char> visited(mesh.triangleCount(), 0);
  std::vector<int> stack;
  for (int seed = 0; seed < triangleCount; ++seed)
  {
    if (visited[seed])
    {
      continue;
    }
    visited[seed] = 1;
    stack.push_back(seed);
    while (!stack.empty())
    {
      const int t = stack.back();
      stack.pop_back();
      const Triangle& c = mesh.triangles[t];
      for (int k = 0; k < 3; ++k)
      {
        const int n = adjacency.neighbourAcross(t, k);
        if (n < 0)
        {
          continue;
        }
        // Does n traverse the shared edge in the same direction as t?
        const int a = c[k];
        const int b = c[(k + 1) % 3];
        const Triangle& d = mesh.triangles[n];
        bool sameDirection = false;
        for (int m = 0; m < 3; ++m)
        {
          sameDirection = sameDirection || (d[m] == a && d[(m + 1) % 3] == b);
        }
        const char flip = static_cast<char>(Flipped[t] ^ (sameDirection ? 1 : 0));
        if (!visited[n])
        {
          visited[n] = 1;
          Flipped[n] = flip;
          stack.push_back(n);
        }
        else if (Flipped[n] != flip)
        {
          throw InvalidInputError("geodesic paths: " + label +
                                  " is not orientable: the piece of triangle " +
                                  std::to_string(seed) + " cannot be oriented consistently");
        }
      }
    }
  }
}

//------------------------------------------------------------------------------
void GeodesicPathFinder::setInitialPatchScale(double scale)
{
  if (!(scale >= 1.0) || !std::isfinite(scale))
  {
    throw InvalidInputError(
      "geodesic paths: the initial patch scale must be finite and at least 1, not " +
      std::to_string(scale));
  }
  InitialPatchScale = scale;
}

//------------------------------------------------------------------------------
void GeodesicPathFinder::checkVertices(int source, int target) const
{
  const int count = static_cast<int>(Mesh.vertexCount());
  for (int v : { source, target })
  {
    if (v < 0 || v >= count)
    {
      throw InvalidInputError("geodesic path on " + meshLabel(Mesh) + ": vertex " +
                              std::to_string(v) + " out of range (the mesh has " +
                              std::to_string(count) + " vertices)");
    }
  }
}

//------------------------------------------------------------------------------
double GeodesicPathFinder::edgePathLength(int source, int target) const
{
  checkVertices(source, target);
  const double distance = searchDistance(Mesh, Adjacency, TriangleMask{}, source, target, false);
  if (!std::isfinite(distance))
  {
    throw notConnected(Mesh, source, target);
  }
  return distance;
}

//------------------------------------------------------------------------------
SurfacePath GeodesicPathFinder::shortestPath(int source,
  int target,
  GeodesicPathStatistics* statistics) const
{
  return shortestPathOn(source, target, nullptr, nullptr, statistics);
}

SurfacePath GeodesicPathFinder::shortestPathWithin(int source,
  int target,
  const std::vector<char>& allowedTriangles,
  GeodesicPathStatistics* statistics) const
{
  if (allowedTriangles.size() != Mesh.triangleCount())
  {
    throw InvalidInputError("geodesic path on " + meshLabel(Mesh) + ": the triangle mask has " +
                            std::to_string(allowedTriangles.size()) + " entries, the mesh " +
                            std::to_string(Mesh.triangleCount()) + " triangles");
  }
  return shortestPathOn(source, target, &allowedTriangles, nullptr, statistics);
}

SurfacePath GeodesicPathFinder::shortestPathWithin(int source,
  int target,
  const std::vector<char>& allowedTriangles,
  const std::vector<int>& alsoAllowedTriangles,
  GeodesicPathStatistics* statistics) const
{
  if (allowedTriangles.size() != Mesh.triangleCount() ||
      !std::is_sorted(alsoAllowedTriangles.begin(), alsoAllowedTriangles.end()) ||
      (!alsoAllowedTriangles.empty() &&
        (alsoAllowedTriangles.front() < 0 ||
          alsoAllowedTriangles.back() >= static_cast<int>(Mesh.triangleCount()))))
  {
    throw InvalidInputError("geodesic path on " + meshLabel(Mesh) +
                            ": the triangle mask must have one entry per triangle (" +
                            std::to_string(Mesh.triangleCount()) +
                            ") and the extra triangles must be sorted and in range");
  }
  return shortestPathOn(source, target, &allowedTriangles, &alsoAllowedTriangles, statistics);
}

SurfacePath GeodesicPathFinder::shortestPathOn(int source,
  int target,
  const std::vector<char>* allowedTriangles,
  const std::vector<int>* alsoAllowedTriangles,
  GeodesicPathStatistics* statistics) const
{
  checkVertices(source, target);
  const TriangleMask mask{ allowedTriangles, alsoAllowedTriangles };
  GeodesicPathStatistics stats;
  if (source == target)
  {
    if (statistics)
    {
      *statistics = stats;
    }
    SurfacePath path;
    path.points.push_back(SurfacePoint::atVertex(source));
    return path;
  }
  if (StraightSegmentShortcut)
  {
    if (auto straight = straightPathOnSurface(Mesh, Adjacency, mask, source, target))
    {
      stats.straight = true;
      if (statistics)
      {
        *statistics = stats;
      }
      return std::move(*straight);
    }
  }
  if (Algorithm == GeodesicAlgorithm::Sleeve)
  {
    SleeveStatistics sleeveStatistics;
    if (auto found = sleeveGeodesic(Mesh, Adjacency, mask, source, target, &sleeveStatistics))
    {
      stats.sleeve = true;
      stats.sleeveTriangles = sleeveStatistics.sleeveTriangles;
      stats.sleeveReroutes = sleeveStatistics.reroutes;
      if (statistics)
      {
        *statistics = stats;
      }
      return std::move(*found);
    }
  }
  // The bound of the patch: the search distance with steps across edges
  // (an upper bound of the geodesic length, tighter than the edge path's).
  const double searchLength = searchDistance(Mesh, Adjacency, mask, source, target, true);
  if (!std::isfinite(searchLength))
  {
    throw notConnected(Mesh, source, target);
  }

  VertexTable table;
  // Growth doubles lambda's excess over 1 (at least +0.1): the ellipse's
  // width grows with sqrt(lambda - 1), CGAL's cost about with its square.
  for (double scale = InitialPatchScale;; scale = std::max(2.0 * scale - 1.0, scale + 0.1))
  {
    table.clear();
    const double bound = scale * searchLength * (1.0 + EllipseTolerance);
    const std::vector<int> ellipse =
      ellipseVertices(Mesh, Adjacency, mask, source, target, bound, table);
    Patch patch;
    buildPatch(Mesh, Adjacency, mask, Flipped, ellipse, table, patch);
    PatchPath found = shortestPathOnPatch(Mesh, Adjacency, mask, patch, table, source, target);
    if (!patch.hasRim && !found.found)
    {
      throw DisconnectedPathError("geodesic path on " + meshLabel(Mesh) +
                                  ": no path on the surface " + "from vertex " +
                                  std::to_string(source) + " to vertex " + std::to_string(target));
    }
    if (!patch.hasRim || (found.found && !found.touchesRim))
    {
      stats.patchTriangles = patch.triangles.size();
      if (statistics)
      {
        *statistics = stats;
      }
      return std::move(found.path);
    }
    ++stats.patchGrowths;
  }
}

} // namespace thintissue
