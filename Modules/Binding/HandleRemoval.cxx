#include "HandleRemoval.h"

#include "MeshPieces.h"
#include "MeshRepair.h"
#include "MeshValidation.h"
#include "TriangleMeshAdjacency.h"
#include "UnionFind.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <tuple>

namespace thintissue
{

namespace
{

constexpr double Infinity = std::numeric_limits<double>::infinity();

/// Geodesic balls (Dijkstra along edges) on one surface, with buffers kept
/// between balls so that a ball costs what it holds.
class BallGrower
{
public:
  BallGrower(const TriangleMesh& mesh, const TriangleMeshAdjacency& adjacency)
    : Mesh(mesh)
    , Adjacency(adjacency)
    , Distance(mesh.vertexCount(), Infinity)
    , TriangleStamp(mesh.triangleCount(), 0)
    , EdgeStamp(adjacency.edgeCount(), 0)
  {
  }

  /// Triangles whose three corners lie within `radius` of `seed`, and the
  /// Euler characteristic V - E + F of that region (1 for a disk).
  int grow(int seed, double radius, std::vector<int>& triangles)
  {
    reset();
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    Distance[seed] = 0.0;
    Reached.push_back(seed);
    queue.emplace(0.0, seed);
    while (!queue.empty())
    {
      const auto [d, v] = queue.top();
      queue.pop();
      if (d > Distance[v])
        continue;
      for (const int* t = Adjacency.vertexTrianglesBegin(v); t != Adjacency.vertexTrianglesEnd(v);
           ++t)
      {
        for (int w : Mesh.triangles[*t])
        {
          const double next = d + (Mesh.positions[w] - Mesh.positions[v]).norm();
          if (next <= radius && next < Distance[w])
          {
            if (Distance[w] == Infinity)
              Reached.push_back(w);
            Distance[w] = next;
            queue.emplace(next, w);
          }
        }
      }
    }
    ++Stamp;
    triangles.clear();
    int vertices = 0;
    int edges = 0;
    for (int v : Reached)
    {
      bool used = false;
      for (const int* t = Adjacency.vertexTrianglesBegin(v); t != Adjacency.vertexTrianglesEnd(v);
           ++t)
      {
        const Triangle& c = Mesh.triangles[*t];
        if (!(Distance[c[0]] <= radius && Distance[c[1]] <= radius && Distance[c[2]] <= radius))
          continue;
        used = true;
        if (TriangleStamp[*t] == Stamp)
          continue;
        TriangleStamp[*t] = Stamp;
        triangles.push_back(*t);
        for (int e : Adjacency.triangleEdges(*t))
        {
          edges += EdgeStamp[e] == Stamp ? 0 : 1;
          EdgeStamp[e] = Stamp;
        }
      }
      vertices += used ? 1 : 0;
    }
    return vertices - edges + static_cast<int>(triangles.size());
  }

  /// Distance from the last ball's seed (infinity beyond its radius).
  double distance(int v) const { return Distance[v]; }

private:
  void reset()
  {
    for (int v : Reached)
      Distance[v] = Infinity;
    Reached.clear();
  }

  const TriangleMesh& Mesh;
  const TriangleMeshAdjacency& Adjacency;
  std::vector<double> Distance;
  std::vector<int> Reached;
  std::vector<int> TriangleStamp;
  std::vector<int> EdgeStamp;
  int Stamp = 0;
};

/// Whether the region holds a loop that does not separate the surface:
/// two of its border loops open onto the same piece of the rest.
bool holdsHandle(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<int>& region)
{
  const std::size_t n = mesh.triangleCount();
  std::vector<char> inRegion(n, 0);
  for (int t : region)
    inRegion[t] = 1;
  // Pieces of the rest (triangles across edges), by union-find.
  UnionFind piece(n);
  for (std::size_t t = 0; t < n; ++t)
  {
    if (inRegion[t])
      continue;
    for (int k = 0; k < 3; ++k)
    {
      const int u = adjacency.neighbourAcross(static_cast<int>(t), k);
      if (u >= 0 && !inRegion[u])
        piece.unite(static_cast<int>(t), u);
    }
  }
  // Border loops of the region: its border vertices joined along its
  // border edges; each loop opens onto the piece beyond its edges.
  UnionFind loop(mesh.vertexCount());
  std::vector<std::pair<int, int>> borderEdges; // (vertex, piece beyond)
  for (int t : region)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int u = adjacency.neighbourAcross(t, k);
      if (u < 0 || inRegion[u])
        continue;
      const int a = mesh.triangles[t][k];
      const int b = mesh.triangles[t][(k + 1) % 3];
      loop.unite(a, b);
      borderEdges.emplace_back(a, piece.find(u));
    }
  }
  std::vector<std::pair<int, int>> loopPiece;
  for (const auto& [vertex, beyond] : borderEdges)
    loopPiece.emplace_back(loop.find(vertex), beyond);
  std::sort(loopPiece.begin(), loopPiece.end());
  loopPiece.erase(std::unique(loopPiece.begin(), loopPiece.end()), loopPiece.end());
  std::vector<int> pieces;
  std::vector<int> loops;
  for (const auto& [l, p] : loopPiece)
  {
    loops.push_back(l);
    pieces.push_back(p);
  }
  std::sort(loops.begin(), loops.end());
  std::sort(pieces.begin(), pieces.end());
  const auto distinct = [](std::vector<int>& v)
  { return static_cast<std::size_t>(std::unique(v.begin(), v.end()) - v.begin()); };
  return distinct(pieces) < distinct(loops);
}

/// Triangles of balls of `radius` that hold a handle (seeds beyond every
/// earlier ball's inner half), and their centres.
std::vector<char> handleBalls(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  double radius,
  std::vector<Vector3>& centres)
{
  BallGrower balls(mesh, adjacency);
  std::vector<char> cut(mesh.triangleCount(), 0);
  std::vector<char> seen(mesh.vertexCount(), 0);
  std::vector<int> region;
  for (std::size_t seed = 0; seed < mesh.vertexCount(); ++seed)
  {
    if (seen[seed])
      continue;
    const int euler = balls.grow(static_cast<int>(seed), radius, region);
    if (euler >= 1)
    {
      seen[seed] = 1;
      continue;
    }
    const bool handle = holdsHandle(mesh, adjacency, region);
    for (int t : region)
    {
      for (int v : mesh.triangles[t])
        seen[v] = seen[v] || balls.distance(v) <= 0.5 * radius || handle;
      cut[t] = cut[t] || handle;
    }
    if (handle)
      centres.push_back(mesh.positions[seed]);
  }
  return cut;
}

/// Vertices at the position of another (a segmentation's pinch points,
/// or the split of a non-manifold vertex by an earlier repair) moved a
/// billionth of the diagonal towards their own triangles' centres: the
/// repair merges coincident vertices, which would pinch the surface again.
void separateCoincidentVertices(TriangleMesh& mesh, const TriangleMeshAdjacency& adjacency)
{
  std::vector<int> order(mesh.vertexCount());
  std::iota(order.begin(), order.end(), 0);
  const auto less = [&](int a, int b)
  {
    const Vector3& p = mesh.positions[a];
    const Vector3& q = mesh.positions[b];
    return std::tie(p.x(), p.y(), p.z()) < std::tie(q.x(), q.y(), q.z());
  };
  std::sort(order.begin(), order.end(), less);
  const double step = 1e-9 * mesh.boundingBox().diagonal().norm();
  for (std::size_t i = 1; i < order.size(); ++i)
  {
    const int v = order[i];
    if (mesh.positions[v] != mesh.positions[order[i - 1]])
      continue;
    Vector3 centre = Vector3::Zero();
    int count = 0;
    for (const int* t = adjacency.vertexTrianglesBegin(v); t != adjacency.vertexTrianglesEnd(v);
         ++t, ++count)
    {
      const Triangle& c = mesh.triangles[*t];
      centre += (mesh.positions[c[0]] + mesh.positions[c[1]] + mesh.positions[c[2]]) / 3.0;
    }
    const Vector3 towards =
      count > 0 ? Vector3(centre / count - mesh.positions[v]) : Vector3::Zero();
    if (towards.norm() > 0.0)
      mesh.positions[v] += step * towards.normalized();
  }
}

/// The surface without the cut triangles, its openings filled (islands
/// left between cuts dropped); empty when not closed or not one piece.
TriangleMesh cutAndFill(const TriangleMesh& mesh, const std::vector<char>& cut)
{
  TriangleMesh kept = mesh;
  separateCoincidentVertices(kept, TriangleMeshAdjacency(mesh));
  kept.triangles.clear();
  kept.textureCorners.clear();
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    if (cut[t])
      continue;
    kept.triangles.push_back(mesh.triangles[t]);
    if (mesh.hasTextureCoordinates())
      kept.textureCorners.push_back(mesh.textureCorners[t]);
  }
  kept.name = mesh.name;
  TriangleMesh closed = closeOpeningsKeepLargest(kept);
  if (!validateTriangleMesh(closed).isClosedOutwardSingleSurface())
    return {};
  return closed;
}

/// The triangles sharing a vertex with a marked one, marked too.
std::vector<char> grownByARing(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<char>& marked)
{
  std::vector<char> grown = marked;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    if (!marked[t])
      continue;
    for (int v : mesh.triangles[t])
      for (const int* u = adjacency.vertexTrianglesBegin(v); u != adjacency.vertexTrianglesEnd(v);
           ++u)
        grown[*u] = 1;
  }
  return grown;
}

double meanEdgeLength(const TriangleMesh& mesh, const TriangleMeshAdjacency& adjacency)
{
  double sum = 0.0;
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e)
  {
    const auto& edge = adjacency.edge(static_cast<int>(e));
    sum += (mesh.positions[edge[0]] - mesh.positions[edge[1]]).norm();
  }
  return adjacency.edgeCount() > 0 ? sum / adjacency.edgeCount() : 0.0;
}

} // namespace

TriangleMesh removeSmallHandles(const TriangleMesh& mesh,
  double largestRadius,
  std::vector<std::string>& places)
{
  TriangleMesh current = mesh;
  TriangleMeshAdjacency adjacency(current);
  int genus = adjacency.closedSurfaceGenus();
  const double edge = meanEdgeLength(current, adjacency);
  for (double radius = 2.0 * edge; genus > 0 && radius <= largestRadius; radius *= 1.6)
  {
    std::vector<Vector3> centres;
    const std::vector<char> cut = handleBalls(current, adjacency, radius, centres);
    if (centres.empty())
      continue;
    // An opening the filling cannot close (a cut's border pinched at a
    // vertex) is tried again a ring of triangles wider.
    std::vector<char> wider = cut;
    TriangleMesh closed = cutAndFill(current, wider);
    for (int ring = 0; ring < 2 && closed.triangles.empty(); ++ring)
    {
      wider = grownByARing(current, adjacency, wider);
      closed = cutAndFill(current, wider);
    }
    if (closed.triangles.empty())
      continue;
    const TriangleMeshAdjacency closedAdjacency(closed);
    const int closedGenus = closedAdjacency.closedSurfaceGenus();
    if (closedGenus >= genus)
      continue;
    for (const Vector3& x : centres)
    {
      places.push_back("handle through the tissue at (" + std::to_string(x.x()) + ", " +
                       std::to_string(x.y()) + ", " + std::to_string(x.z()) + ")");
    }
    current = std::move(closed);
    adjacency = TriangleMeshAdjacency(current);
    genus = closedGenus;
    radius /= 1.6; // the same size again: a cut can leave its neighbour's handle
  }
  return current;
}

} // namespace thintissue
