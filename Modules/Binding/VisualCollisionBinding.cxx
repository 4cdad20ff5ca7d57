#include "VisualCollisionBinding.h"

#include "EquatorRimPaths.h"
#include "GeodesicPaths.h"
#include "MeshPieces.h"
#include "MeshQueries.h"
#include "MeshValidation.h"
#include "PathRemeshing.h"
#include "SharedPathRuns.h"
#include "TriangleBvh.h"
#include "TriangleMeshAdjacency.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <tuple>
#include <unordered_map>

namespace thintissue
{

namespace
{

constexpr double Infinity = std::numeric_limits<double>::infinity();

void report(const BindingProgress& progress, double fraction, const char* stage)
{
  if (progress && !progress(fraction, stage))
  {
    throw BindingAbortedError("visual-collision binding aborted during " + std::string(stage));
  }
}

std::string nameOf(const TriangleMesh& mesh, const char* role)
{
  return std::string(role) + " mesh '" + mesh.name + "'";
}

/// Nearest intersection of the ray origin + t direction (t > 0) with the
/// surface: t and triangle (infinity, -1 when it misses). Möller-Trumbore
/// on every triangle, or with `bvh` (of the surface) on the triangles near
/// the segment up to `reach` only (a miss then means none within reach).
std::pair<double, int> nearestRayHit(const TriangleMesh& mesh,
  const Vector3& origin,
  const Vector3& direction,
  const TriangleBvh* bvh = nullptr,
  double reach = Infinity)
{
  double best = Infinity;
  int bestTriangle = -1;
  auto test = [&](int t)
  {
    const Triangle& tri = mesh.triangles[t];
    const double distance = rayTriangleHit(origin,
      direction,
      mesh.positions[tri[0]],
      mesh.positions[tri[1]],
      mesh.positions[tri[2]],
      1e-12);
    if (distance > 0.0 && distance < best && distance <= reach)
    {
      best = distance;
      bestTriangle = t;
    }
  };
  if (bvh != nullptr && std::isfinite(reach))
  {
    BoundingBox segment(origin);
    segment.extend(origin + reach * direction);
    bvh->forEachOverlap(segment, test);
  }
  else
  {
    for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    {
      test(t);
    }
  }
  return { best, bestTriangle };
}

/// Visual vertices within `rings` rings of the given seed vertices.
std::vector<int> ringNeighbourhood(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  std::vector<int> seeds,
  int rings)
{
  std::vector<int> found = seeds;
  std::vector<int> frontier = std::move(seeds);
  for (int ring = 0; ring < rings; ++ring)
  {
    std::vector<int> next;
    for (int v : frontier)
    {
      for (const int* t = adjacency.vertexTrianglesBegin(v); t != adjacency.vertexTrianglesEnd(v);
           ++t)
      {
        for (int w : mesh.triangles[*t])
        {
          if (std::find(found.begin(), found.end(), w) == found.end())
          {
            found.push_back(w);
            next.push_back(w);
          }
        }
      }
    }
    frontier = std::move(next);
  }
  return found;
}

double distanceToLine(const Vector3& point, const Vector3& origin, const Vector3& unitDirection)
{
  const Vector3 offset = point - origin;
  return (offset - offset.dot(unitDirection) * unitDirection).norm();
}

std::uint64_t edgeKey(int a, int b)
{
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

/// Path points this close (in edge parameter) to another point on the same
/// edge or to its end are one vertex: exact geodesics often run along a
/// line of vertices a round-off away from them (the meniscus's inner rim),
/// and keeping such points apart would leave sliver triangles of no area.
/// The path moves by at most this fraction of an edge.
constexpr double PathMergeTolerance = 1e-3;
// Where a re-routed shared run crosses the edges around its vertices (as a
// fraction of each edge from the run): wide enough that the region between
// the two paths is laid out without folds, near enough to stay beside the
// geodesic.
constexpr double SharedRunOffsetFraction = 0.25;
constexpr int MaximumSeparationPasses = 6;

/// A border collision vertex may take a point inside a visual edge at least
/// this far (in edge parameter) from both ends; nearer, the end vertex.
constexpr double EdgePointMargin = 0.1;

/// One collision vertex's wish for a visual vertex on one side (slot 0: +,
/// slot 1: -), candidates best first.
/// Paired visual vertices per collision vertex: positive, negative, and
/// the crease's at a junction vertex.
constexpr std::size_t PairedSlots = 3;
constexpr int CreaseSlot = 2;
using PairedPoints = std::array<SurfacePoint, PairedSlots>;

struct PairingClaim
{
  int collisionVertex = -1;
  int slot = 0;
  std::vector<std::pair<double, SurfacePoint>> candidates; // (distance, point), best first
};

} // namespace

//------------------------------------------------------------------------------
Vector3 VisualCollisionBinding::projectedPoint(std::size_t v,
  const std::vector<Vector3>& positions) const
{
  const VisualVertexBinding& b = vertices[v];
  switch (b.kind)
  {
    case BindingKind::CollisionVertex:
      return positions[b.element];
    case BindingKind::CollisionEdge:
    {
      const auto& e = collisionEdges[b.element];
      return b.parameters[0] * positions[e[0]] + b.parameters[1] * positions[e[1]];
    }
    case BindingKind::CollisionTriangle:
    default:
    {
      const Triangle& t = collisionTriangles[b.element];
      return b.parameters[0] * positions[t[0]] + b.parameters[1] * positions[t[1]] +
             b.parameters[2] * positions[t[2]];
    }
  }
}

Vector3 VisualCollisionBinding::parametersInTriangle(std::size_t v, int t) const
{
  const VisualVertexBinding& b = vertices[v];
  const Triangle& tri = collisionTriangles[t];
  Vector3 result = Vector3::Zero();
  switch (b.kind)
  {
    case BindingKind::CollisionVertex:
      for (int k = 0; k < 3; ++k)
      {
        if (tri[k] == b.element)
        {
          result[k] = 1.0;
          return result;
        }
      }
      break;
    case BindingKind::CollisionEdge:
    {
      const auto& e = collisionEdges[b.element];
      int first = -1;
      int second = -1;
      for (int k = 0; k < 3; ++k)
      {
        first = tri[k] == e[0] ? k : first;
        second = tri[k] == e[1] ? k : second;
      }
      if (first >= 0 && second >= 0)
      {
        result[first] = b.parameters[0];
        result[second] = b.parameters[1];
        return result;
      }
      break;
    }
    case BindingKind::CollisionTriangle:
      if (b.element == t)
      {
        return b.parameters;
      }
      break;
  }
  throw InvalidInputError("visual-collision binding: visual vertex " + std::to_string(v) +
                          " is not bound to collision triangle " + std::to_string(t) +
                          " or one of its edges or vertices");
}

int VisualCollisionBinding::collisionEdgeIndex(int a, int b) const
{
  const std::array<int, 2> key{ { std::min(a, b), std::max(a, b) } };
  const auto it = std::lower_bound(collisionEdges.begin(), collisionEdges.end(), key);
  return it != collisionEdges.end() && *it == key ? static_cast<int>(it - collisionEdges.begin())
                                                  : -1;
}

int VisualCollisionBinding::pairedVisualVertex(int v, int t, int side) const
{
  // Without side classes (a binding read from arrays that predate them)
  // every vertex has two sides.
  const int slot =
    collisionSides.junctionVertex.empty() ? sideSlot(side) : collisionSides.pairedSlot(v, t, side);
  return slot == 2 ? creaseVisualVertices[v] : pairedVisualVertices[v][slot];
}

std::vector<std::array<std::array<int, 2>, 3>> VisualCollisionBinding::pathEnds() const
{
  std::vector<int> triangleCount(collisionEdges.size(), 0);
  for (const Triangle& t : collisionTriangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      ++triangleCount[collisionEdgeIndex(t[k], t[(k + 1) % 3])];
    }
  }
  std::vector<std::array<std::array<int, 2>, 3>> ends(
    collisionEdges.size(), { { { { -1, -1 } }, { { -1, -1 } }, { { -1, -1 } } } });
  for (std::size_t t = 0; t < collisionTriangles.size(); ++t)
  {
    const auto triangle = static_cast<int>(t);
    for (int k = 0; k < 3; ++k)
    {
      const int e =
        collisionEdgeIndex(collisionTriangles[t][k], collisionTriangles[t][(k + 1) % 3]);
      for (int side : { 1, -1 })
      {
        const int label = collisionSides.halves.empty()
                            ? (triangleCount[e] == 1 ? 0 : side)
                            : collisionSides.pathSide(triangle, side, triangleCount[e]);
        ends[e][label + 1] = { { pairedVisualVertex(collisionEdges[e][0], triangle, side),
          pairedVisualVertex(collisionEdges[e][1], triangle, side) } };
      }
    }
  }
  return ends;
}

//------------------------------------------------------------------------------
namespace
{

/// What the binding needs of the collision mesh.
struct CollisionTopology
{
  std::vector<std::array<int, 2>> edges; // sorted (lower, higher)
  std::vector<int> edgeTriangleCount;
  std::vector<std::array<int, 3>> edgeTriangles; // -1 beyond the count
  std::vector<char> borderVertex;
  std::vector<Vector3> vertexNormals; // unit, area-weighted
  CollisionSides sides;
};

CollisionTopology analyseCollision(const TriangleMesh& collision)
{
  CollisionTopology topology;
  const TriangleMeshAdjacency adjacency(collision);             // edges sorted (lower, higher)
  topology.sides = analyseCollisionSides(collision, adjacency); // at most three triangles an edge
  topology.borderVertex = topology.sides.borderVertex;
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e)
  {
    const auto edge = static_cast<int>(e);
    std::array<int, 3> triangles{ { -1, -1, -1 } };
    std::copy(
      adjacency.edgeTrianglesBegin(edge), adjacency.edgeTrianglesEnd(edge), triangles.begin());
    topology.edges.push_back(adjacency.edge(edge));
    topology.edgeTriangles.push_back(triangles);
    topology.edgeTriangleCount.push_back(adjacency.edgeTriangleCount(edge));
  }
  topology.vertexNormals.assign(collision.vertexCount(), Vector3::Zero());
  for (const Triangle& t : collision.triangles)
  {
    const Vector3 n = (collision.positions[t[1]] - collision.positions[t[0]])
                        .cross(collision.positions[t[2]] - collision.positions[t[0]]);
    for (int k = 0; k < 3; ++k)
    {
      topology.vertexNormals[t[k]] += n;
    }
  }
  for (std::size_t v = 0; v < collision.vertexCount(); ++v)
  {
    if (topology.vertexNormals[v].norm() == 0.0)
    {
      throw InvalidInputError(nameOf(collision, "collision") + ": vertex " + std::to_string(v) +
                              " belongs to no triangle of non-zero area");
    }
    topology.vertexNormals[v].normalize();
  }
  return topology;
}

/// Crossings of the vertical line through p with the surface above and
/// below p (through the tree: a column of boxes). Both odd means inside;
/// a line through an edge or vertex may count a crossing twice, so any
/// other answer is decided by the winding number.
bool insideByVerticalCrossings(const TriangleMesh& mesh, const TriangleBvh& bvh, const Vector3& p)
{
  const BoundingBox bounds = bvh.bounds();
  BoundingBox column(Vector3(p.x(), p.y(), bounds.min().z() - 1.0));
  column.extend(Vector3(p.x(), p.y(), bounds.max().z() + 1.0));
  int above = 0;
  int below = 0;
  bool ambiguous = false;
  bvh.forEachOverlap(column,
    [&](int t)
    {
      const Triangle& tri = mesh.triangles[t];
      const double s = rayTriangleHit(p,
        Vector3::UnitZ(),
        mesh.positions[tri[0]],
        mesh.positions[tri[1]],
        mesh.positions[tri[2]],
        1e-9);
      if (std::isfinite(s))
      {
        ambiguous = ambiguous || s == 0.0;
        (s > 0.0 ? above : below) += 1;
      }
    });
  return !ambiguous && above % 2 == 1 && below % 2 == 1;
}

void checkInputs(const TriangleMesh& visual,
  const TriangleBvh& visualBvh,
  const TriangleMesh& collision,
  const std::vector<double>& radii,
  const VisualCollisionBindingSettings& settings)
{
  visual.checkConsistency();
  collision.checkConsistency();
  if (visual.triangles.empty())
  {
    throw InvalidInputError(nameOf(visual, "visual") + " has no triangles");
  }
  if (collision.triangles.empty())
  {
    throw InvalidInputError(nameOf(collision, "collision") + " has no triangles");
  }
  const MeshValidationReport report =
    requireClosedOrientedManifold(visual, nameOf(visual, "visual"), true);
  if (report.signedVolume <= 0.0)
  {
    throw InvalidInputError(
      nameOf(visual, "visual") + " faces inward (negative enclosed volume): flip its triangles");
  }
  if (!collision.pointAttributes.has(settings.radiusArrayName))
  {
    throw InvalidInputError(nameOf(collision, "collision") + " has no per-vertex '" +
                            settings.radiusArrayName + "' array (the radii)");
  }
  for (std::size_t v = 0; v < radii.size(); ++v)
  {
    if (!(radii[v] > 0.0) || !std::isfinite(radii[v]))
    {
      throw InvalidInputError(nameOf(collision, "collision") + ": vertex " + std::to_string(v) +
                              " has radius " + std::to_string(radii[v]) +
                              " (radii must be positive)");
    }
  }
  // Inside the visual volume (or on its surface, within the tolerance).
  const double tolerance = settings.insideTolerance * visual.boundingBox().diagonal().norm();
  std::vector<char> outside(collision.vertexCount(), 0);
  tbb::parallel_for(std::size_t(0),
    collision.vertexCount(),
    [&](std::size_t v)
    {
      const Vector3& p = collision.positions[v];
      outside[v] = !insideByVerticalCrossings(visual, visualBvh, p) &&
                   windingNumber(visual, p) < 0.5 && distanceToSurface(visual, p) > tolerance;
    });
  const auto first = std::find(outside.begin(), outside.end(), 1);
  if (first != outside.end())
  {
    const auto v = static_cast<std::size_t>(first - outside.begin());
    throw InvalidInputError(nameOf(collision, "collision") + ": vertex " + std::to_string(v) +
                            " lies outside the visual volume of " + nameOf(visual, "visual") +
                            " (the collision mid-surface must lie inside the visual surface)");
  }
}

/// Candidates inside the visual edges of the triangles around `ring`: the
/// closest point of each edge to `target`, away from the edge's ends (near
/// an end the vertex serves: no sliver triangles).
void addEdgePointCandidates(const TriangleMesh& visual,
  const TriangleMeshAdjacency& visualAdjacency,
  const std::vector<int>& ring,
  const Vector3& target,
  PairingClaim& claim)
{
  for (int w : ring)
  {
    for (const int* t = visualAdjacency.vertexTrianglesBegin(w);
         t != visualAdjacency.vertexTrianglesEnd(w);
         ++t)
    {
      const Triangle& tri = visual.triangles[*t];
      for (int k = 0; k < 3; ++k)
      {
        const int a = std::min(tri[k], tri[(k + 1) % 3]);
        const int b = std::max(tri[k], tri[(k + 1) % 3]);
        const Vector3 d = visual.positions[b] - visual.positions[a];
        const double along = d.dot(target - visual.positions[a]) / d.squaredNorm();
        if (along > EdgePointMargin && along < 1.0 - EdgePointMargin)
        {
          const Vector3 x = visual.positions[a] + along * d;
          claim.candidates.emplace_back((x - target).norm(), SurfacePoint::onEdge(a, b, along));
        }
      }
    }
  }
}

/// The `count` visual vertices nearest to `target` as (distance, vertex),
/// nearest first (ties by index; all of them on a smaller surface). Local:
/// the vertices of the triangles the tree finds in a cube about the target,
/// the cube doubled until `count` of them lie within its half width (any
/// vertex nearer lies in such a triangle), instead of every vertex.
std::vector<std::pair<double, int>> nearestVisualVertices(const TriangleMesh& visual,
  const TriangleBvh& visualBvh,
  const Vector3& target,
  std::size_t count)
{
  count = std::min(count, visual.vertexCount());
  const double diagonal = visualBvh.bounds().diagonal().norm();
  double half =
    diagonal / std::sqrt(static_cast<double>(std::max<std::size_t>(1, visual.vertexCount())));
  std::vector<int> found;
  std::vector<std::pair<double, int>> nearest;
  while (true)
  {
    found.clear();
    const Vector3 corner(half, half, half);
    visualBvh.forEachOverlap(BoundingBox(target - corner, target + corner),
      [&](int t)
      {
        for (int w : visual.triangles[t])
          found.push_back(w);
      });
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    nearest.clear();
    std::size_t within = 0;
    for (int w : found)
    {
      nearest.emplace_back((visual.positions[w] - target).norm(), w);
      within += nearest.back().first <= half ? 1 : 0;
    }
    if (within >= count || half > diagonal + visualBvh.bounds().exteriorDistance(target))
      break;
    half *= 2.0;
  }
  std::partial_sort(nearest.begin(), nearest.begin() + count, nearest.end());
  nearest.resize(count);
  return nearest;
}

/// The claim of border collision vertex v on the visual rim (5.2.1): its
/// candidates, closest first. Returns why it has none within reach, or an
/// empty text. `reach`: `thinnessFactor` radii, or more within half the
/// vertex's mean collision edge (see pairCollisionVertices).
std::string claimRimPoint(const TriangleMesh& visual,
  const TriangleMeshAdjacency& visualAdjacency,
  const TriangleBvh& visualBvh,
  int v,
  const Vector3& origin,
  const Vector3& outwardSum,
  double reach,
  double radius,
  double thinnessFactor,
  PairingClaim& claim)
{
  // The rim point: where the surface is met going outward across
  // the border in the collision surface's plane (on a thick rim,
  // the meniscus's outer wall, the closest point could lie on the
  // upper or lower face instead), else the vertex itself. Around
  // it, the closest visual vertices (a short list for conflicts)
  // and the closest points inside the edges around the closest
  // one: on a rim only a cell thick (the sheets' side walls),
  // every vertex lies on the upper or the lower edge of the wall,
  // but an edge point lies half-way, where the rim paths (the
  // equator between the two sides) belong.
  Vector3 target = origin;
  // At the tip of a slit (a tear's lips meeting), the border turns
  // back on itself: "outward" points along the slit, into the gap
  // between the lips, and the ray meets a lip far from the tip. The
  // tip's own rim point is beside it.
  constexpr double SlitTipOutward = 0.5; // border edges > 150 degrees apart
  if (outwardSum.norm() > SlitTipOutward)
  {
    Vector3 direction = outwardSum.normalized();
    auto [distance, triangle] = nearestRayHit(visual, origin, direction, &visualBvh, reach);
    if (triangle >= 0 && visual.triangleNormal(triangle).dot(direction) < 0.0)
    {
      // The ray enters the surface: the vertex lies outside it (in
      // the gap between a tear's lips, the collision lip short of
      // the visual one), and what it met is the other lip. Its own
      // wall is behind it.
      direction = -direction;
      std::tie(distance, triangle) = nearestRayHit(visual, origin, direction, &visualBvh, reach);
    }
    if (triangle >= 0)
    {
      target = origin + distance * direction;
    }
  }
  const std::vector<std::pair<double, int>> nearest =
    nearestVisualVertices(visual, visualBvh, target, 16);
  for (const auto& [distance, w] : nearest)
  {
    claim.candidates.emplace_back(distance, SurfacePoint::atVertex(w));
  }
  addEdgePointCandidates(visual,
    visualAdjacency,
    ringNeighbourhood(visual, visualAdjacency, { nearest.front().second }, 1),
    target,
    claim);
  std::stable_sort(claim.candidates.begin(),
    claim.candidates.end(),
    [](const auto& x, const auto& y) { return x.first < y.first; });
  const double away = (target - origin).norm() + claim.candidates.front().first;
  if (away > reach)
  {
    return nameOf(visual, "visual") + " is not thin at border collision vertex " +
           std::to_string(v) + ": its rim point is " + std::to_string(away) +
           " away (outward across the border " + std::to_string((target - origin).norm()) +
           ", then " + std::to_string(claim.candidates.front().first) +
           " to the closest visual vertex), more than " + std::to_string(reach) + " (" +
           std::to_string(thinnessFactor) + " radii of " + std::to_string(radius) +
           ", or more within half its mean collision edge)";
  }
  return {};
}

/// Outward direction of each border vertex in the collision surface:
/// across its border edges, away from their triangles (zero inside).
std::vector<Vector3> outwardDirections(const TriangleMesh& collision,
  const CollisionTopology& topology)
{
  const std::size_t n = collision.vertexCount();
  std::vector<Vector3> outward(n, Vector3::Zero());
  for (const Triangle& t : collision.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int a = t[k];
      const int b = t[(k + 1) % 3];
      const int e = static_cast<int>(std::lower_bound(topology.edges.begin(),
                                       topology.edges.end(),
                                       std::array<int, 2>{ { std::min(a, b), std::max(a, b) } }) -
                                     topology.edges.begin());
      if (topology.edgeTriangleCount[e] != 1)
      {
        continue;
      }
      const Vector3 along = collision.positions[b] - collision.positions[a];
      const Vector3 normal =
        along.cross(collision.positions[t[(k + 2) % 3]] - collision.positions[a]);
      Vector3 away = along.cross(normal);
      if (away.dot(collision.positions[t[(k + 2) % 3]] - collision.positions[a]) > 0.0)
      {
        away = -away;
      }
      if (away.norm() > 0.0)
      {
        outward[a] += away.normalized();
        outward[b] += away.normalized();
      }
    }
  }
  return outward;
}

/// Direction from each junction vertex into the cleft between its leaves:
/// across its junction edges, toward the two leaves (whose triangles leave
/// the edge above and below the cleft: between them lies its crease), in
/// their planes.
std::vector<Vector3> creaseDirections(const TriangleMesh& collision,
  const CollisionTopology& topology)
{
  std::vector<Vector3> intoCleft(collision.vertexCount(), Vector3::Zero());
  for (std::size_t e = 0; e < topology.edges.size(); ++e)
  {
    if (topology.edgeTriangleCount[e] != 3)
    {
      continue;
    }
    for (int t : topology.edgeTriangles[e])
    {
      const auto& halves = topology.sides.halves[t];
      if (halves[0] != SurfaceHalf::Cleft && halves[1] != SurfaceHalf::Cleft)
      {
        continue; // the body
      }
      const auto& edge = topology.edges[e];
      const Vector3& a = collision.positions[edge[0]];
      const Vector3 along = (collision.positions[edge[1]] - a).normalized();
      int apex = -1;
      for (int c : collision.triangles[t])
      {
        apex = c != edge[0] && c != edge[1] ? c : apex;
      }
      Vector3 towardLeaf = collision.positions[apex] - a;
      towardLeaf -= towardLeaf.dot(along) * along;
      for (int v : edge)
      {
        intoCleft[v] += towardLeaf.normalized();
      }
    }
  }
  return intoCleft;
}

/// Per collision vertex: how far from where its normal meets the surface
/// a paired visual vertex may lie (beyond, a point inside a visual edge
/// there is a candidate too).
std::vector<double> snapDistances(const TriangleMesh& collision, const CollisionTopology& topology)
{
  const std::size_t n = collision.vertexCount();
  // A paired vertex this close to where the normal meets the surface
  // keeps the pairing on visual vertices: a quarter of the shortest
  // collision edge at the vertex.
  constexpr double SnapFraction = 0.25;
  std::vector<double> snapDistance(n, std::numeric_limits<double>::infinity());
  for (const auto& edge : topology.edges)
  {
    const double length =
      SnapFraction * (collision.positions[edge[0]] - collision.positions[edge[1]]).norm();
    snapDistance[edge[0]] = std::min(snapDistance[edge[0]], length);
    snapDistance[edge[1]] = std::min(snapDistance[edge[1]], length);
  }
  return snapDistance;
}

/// Half the mean length of the collision edges at each vertex.
std::vector<double> halfMeanEdgeLengths(const TriangleMesh& collision,
  const CollisionTopology& topology)
{
  const std::size_t n = collision.vertexCount();
  std::vector<double> sum(n, 0.0);
  std::vector<int> count(n, 0);
  for (const auto& edge : topology.edges)
  {
    const double length = (collision.positions[edge[0]] - collision.positions[edge[1]]).norm();
    for (const int v : edge)
    {
      sum[v] += length;
      ++count[v];
    }
  }
  for (std::size_t v = 0; v < n; ++v)
  {
    sum[v] = count[v] > 0 ? 0.5 * sum[v] / count[v] : 0.0;
  }
  return sum;
}

/// The claims resolved: no visual vertex serves two collision vertices, the
/// closest claims choose first and the others take their next candidate.
std::vector<PairedPoints> resolveClaims(const TriangleMesh& visual,
  const TriangleMesh& collision,
  const CollisionTopology& topology,
  const std::vector<PairingClaim>& claims)
{
  const std::size_t n = collision.vertexCount();
  std::vector<std::size_t> order;
  for (std::size_t c = 0; c < claims.size(); ++c)
  {
    if (!claims[c].candidates.empty())
    {
      order.push_back(c);
    }
  }
  std::sort(order.begin(),
    order.end(),
    [&](std::size_t x, std::size_t y)
    {
      const auto& cx = claims[x].candidates.front();
      const auto& cy = claims[y].candidates.front();
      return cx.first != cy.first ? cx.first < cy.first : x < y;
    });
  std::vector<char> taken(visual.vertexCount(), 0);
  // Edge points taken, per edge: parameters (another point on the edge
  // must keep EdgePointMargin away, or the two would merge).
  std::unordered_map<std::uint64_t, std::vector<double>> takenOnEdge;
  std::vector<PairedPoints> paired(n);
  std::vector<std::array<char, PairedSlots>> found(n, { { 0, 0, 0 } });
  for (std::size_t c : order)
  {
    const PairingClaim& claim = claims[c];
    for (const auto& [distance, point] : claim.candidates)
    {
      if (point.isVertex())
      {
        if (taken[point.vertex])
        {
          continue;
        }
        taken[point.vertex] = 1;
      }
      else
      {
        auto& onEdge = takenOnEdge[edgeKey(point.edgeStart, point.edgeEnd)];
        const bool crowded = std::any_of(onEdge.begin(),
          onEdge.end(),
          [&](double t) { return std::abs(t - point.edgeParameter) < EdgePointMargin; });
        if (crowded)
        {
          continue;
        }
        onEdge.push_back(point.edgeParameter);
      }
      paired[claim.collisionVertex][claim.slot] = point;
      found[claim.collisionVertex][claim.slot] = 1;
      break;
    }
    if (!found[claim.collisionVertex][claim.slot])
    {
      throw InvalidInputError(
        "collision vertex " + std::to_string(claim.collisionVertex) + " of " +
        nameOf(collision, "collision") + " finds no free visual vertex on its " +
        (claim.slot == CreaseSlot ? "cleft's crease"
                                  : (topology.borderVertex[claim.collisionVertex]
                                        ? "rim"
                                        : (claim.slot == 0 ? "positive side" : "negative side"))) +
        ": its neighbours took them all (the visual mesh is too coarse there)");
    }
  }
  for (std::size_t v = 0; v < n; ++v)
  {
    if (topology.borderVertex[v])
    {
      paired[v][1] = paired[v][0];
    }
    if (!topology.sides.junctionVertex[v])
    {
      paired[v][CreaseSlot] = paired[v][0];
    }
  }
  return paired;
}

/// 5.2.1: the visual point of every collision vertex and side: a visual
/// vertex, or for a border collision vertex possibly a point inside a
/// visual edge (inserted as a vertex before the paths are computed).
std::vector<PairedPoints> pairCollisionVertices(const TriangleMesh& visual,
  const TriangleMeshAdjacency& visualAdjacency,
  const TriangleBvh& visualBvh,
  const TriangleMesh& collision,
  const std::vector<double>& radii,
  const CollisionTopology& topology,
  const VisualCollisionBindingSettings& settings)
{
  const std::size_t n = collision.vertexCount();
  const std::vector<Vector3> outward = outwardDirections(collision, topology);
  const std::vector<Vector3> intoCleft = creaseDirections(collision, topology);
  const std::vector<double> snapDistance = snapDistances(collision, topology);
  const std::vector<double> halfMeanEdge = halfMeanEdgeLengths(collision, topology);
  std::vector<PairingClaim> claims(PairedSlots * n);
  std::vector<std::string> errors(PairedSlots * n);
  tbb::parallel_for(std::size_t(0),
    PairedSlots * n,
    [&](std::size_t c)
    {
      const auto v = static_cast<int>(c / PairedSlots);
      const int slot = static_cast<int>(c % PairedSlots);
      PairingClaim& claim = claims[c];
      claim.collisionVertex = v;
      claim.slot = slot;
      const Vector3& origin = collision.positions[v];
      // A wedge-shaped rim (a meniscus's inner rim or a tear's lip,
      // sharpened by a segmentation) thins slower than a quarter of a
      // radius per unit outward: a border vertex sits where the tissue
      // still has a radius and its rim lies more than 4 radii beyond it,
      // and the normal of a vertex beside it crosses the wedge obliquely.
      // Both still belong to the vertex while nearer than half way to its
      // neighbours (half its mean collision edge), up to twice the
      // thinness factor: radii far too small are still refused.
      const double thinReach = settings.thinnessFactor * radii[v];
      const double reach = std::max(thinReach, std::min(halfMeanEdge[v], 2.0 * thinReach));
      if (slot == CreaseSlot)
      {
        if (topology.sides.junctionVertex[v])
        {
          // The cleft ends at the junction vertex: the visual vertices
          // nearest to it lie on the cleft's walls (the top and the
          // bottom are a radius away). No ray: one along the leaves can
          // run along the cleft's gap and out of its mouth.
          errors[c] = claimRimPoint(visual,
            visualAdjacency,
            visualBvh,
            v,
            origin,
            Vector3::Zero(),
            reach,
            radii[v],
            settings.thinnessFactor,
            claim);
        }
        return;
      }
      if (topology.borderVertex[v])
      {
        if (slot == 1)
        {
          return; // one visual vertex for both sides
        }
        // The ray outward across the border leaves the surface at the
        // tissue's own rim, however thin the tissue is where the vertex
        // stands: a segmented rim thinning to an edge puts it tens of radii
        // out (a sheet's or a cartilage's rim). It still belongs to the
        // vertex while nearer than half way to its neighbours.
        errors[c] = claimRimPoint(visual,
          visualAdjacency,
          visualBvh,
          v,
          origin,
          outward[v],
          std::max(reach, halfMeanEdge[v]),
          radii[v],
          settings.thinnessFactor,
          claim);
        return;
      }
      // A junction vertex sits on the cleft's end: its normal runs along
      // the end's wall and could meet the cleft instead of the top or the
      // bottom. Its rays start a quarter radius back into the body.
      const Vector3 rayOrigin = topology.sides.junctionVertex[v]
                                  ? Vector3(origin - 0.25 * radii[v] * intoCleft[v].normalized())
                                  : origin;
      const Vector3 direction = (slot == 0 ? 1.0 : -1.0) * topology.vertexNormals[v];
      // Within reach through the tree; the whole surface only to word the
      // error when nothing is.
      auto [distance, triangle] = nearestRayHit(visual, rayOrigin, direction, &visualBvh, reach);
      if (triangle < 0)
      {
        std::tie(distance, triangle) = nearestRayHit(visual, rayOrigin, direction);
      }
      if (triangle < 0)
      {
        errors[c] = "collision vertex " + std::to_string(v) + " has no visual vertex on its " +
                    (slot == 0 ? "positive" : "negative") + " side: its normal ray does not meet " +
                    nameOf(visual, "visual");
        return;
      }
      if (distance > reach)
      {
        errors[c] = nameOf(visual, "visual") + " is not thin at collision vertex " +
                    std::to_string(v) + ": along its " + (slot == 0 ? "positive" : "negative") +
                    " normal the surface is " + std::to_string(distance) + " away, more than " +
                    std::to_string(reach) + " (" + std::to_string(settings.thinnessFactor) +
                    " radii, or up to twice that within half its mean collision edge)";
        return;
      }
      const Triangle& hit = visual.triangles[triangle];
      const std::vector<int> nearby =
        ringNeighbourhood(visual, visualAdjacency, { hit[0], hit[1], hit[2] }, 2);
      std::vector<std::pair<double, int>> onSide;
      for (int w : nearby)
      {
        // Only vertices on this side of the collision vertex.
        if ((visual.positions[w] - rayOrigin).dot(direction) > 0.0)
        {
          onSide.emplace_back(distanceToLine(visual.positions[w], rayOrigin, direction), w);
        }
      }
      std::sort(onSide.begin(), onSide.end());
      for (const auto& [distance, w] : onSide)
      {
        claim.candidates.emplace_back(distance, SurfacePoint::atVertex(w));
      }
      // Where the visual mesh is coarse beside short collision edges
      // (segmented anatomy, dense collision meshes), the nearest vertex
      // can lie beyond a neighbour's path: the paired point then goes
      // inside a visual edge next to where the normal meets the surface.
      if (claim.candidates.empty() || claim.candidates.front().first > snapDistance[v])
      {
        addEdgePointCandidates(visual,
          visualAdjacency,
          { hit[0], hit[1], hit[2] },
          rayOrigin + distance * direction,
          claim);
        std::stable_sort(claim.candidates.begin(),
          claim.candidates.end(),
          [](const auto& x, const auto& y) { return x.first < y.first; });
      }
    });
  for (const std::string& error : errors)
  {
    if (!error.empty())
    {
      throw InvalidInputError(error);
    }
  }
  return resolveClaims(visual, collision, topology, claims);
}

/// Binding of one region's vertices (5.2.4): boundary on the collision
/// triangle by accumulated path length, inside by mean value coordinates.
class RegionParameterisation
{
public:
  explicit RegionParameterisation(std::size_t visualVertexCount)
    : Local(visualVertexCount, -1)
    , Boundary(visualVertexCount, 0)
  {
  }

  /// `triangles`: the region's visual triangles; `boundary`: its boundary
  /// vertices with their positions in the collision triangle's 2D frame.
  /// Writes the barycentric parameters of every other vertex of the region
  /// whose binding is CollisionTriangle.
  void solve(const TriangleMesh& mesh,
    const std::vector<int>& triangles,
    const std::vector<std::pair<int, Vector2>>& boundary,
    const std::array<Vector2, 3>& corners,
    std::vector<VisualVertexBinding>& bindings)
  {
    std::vector<int> interior;
    for (const auto& [v, p] : boundary)
    {
      Boundary[v] = 1;
      BoundaryPosition[v] = p;
    }
    for (int t : triangles)
    {
      for (int v : mesh.triangles[t])
      {
        if (!Boundary[v] && Local[v] < 0)
        {
          Local[v] = static_cast<int>(interior.size());
          interior.push_back(v);
        }
      }
    }
    const auto size = static_cast<Eigen::Index>(interior.size());
    if (size > 0)
    {
      // Floater's mean value weights from the rest angles: for triangle
      // (i, j, k) the angle at i adds tan(angle/2)/|x_j - x_i| to w_ij and
      // tan(angle/2)/|x_k - x_i| to w_ik.
      std::vector<Eigen::Triplet<double>> entries;
      Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(size, 2);
      Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(size);
      for (int t : triangles)
      {
        const Triangle& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k)
        {
          const int i = tri[k];
          if (Local[i] < 0)
          {
            continue;
          }
          const int j = tri[(k + 1) % 3];
          const int l = tri[(k + 2) % 3];
          const Vector3 toJ = mesh.positions[j] - mesh.positions[i];
          const Vector3 toL = mesh.positions[l] - mesh.positions[i];
          const double angle = std::atan2(toJ.cross(toL).norm(), toJ.dot(toL));
          const double halfTangent = std::tan(0.5 * angle);
          for (const auto& [other, length] :
            { std::pair<int, double>(j, toJ.norm()), std::pair<int, double>(l, toL.norm()) })
          {
            const double w = halfTangent / length;
            diagonal[Local[i]] += w;
            if (Local[other] >= 0)
            {
              entries.emplace_back(Local[i], Local[other], -w);
            }
            else
            {
              rhs.row(Local[i]) += w * BoundaryPosition[other].transpose();
            }
          }
        }
      }
      for (Eigen::Index i = 0; i < size; ++i)
      {
        entries.emplace_back(i, i, diagonal[i]);
      }
      Eigen::SparseMatrix<double> matrix(size, size);
      matrix.setFromTriplets(entries.begin(), entries.end());
      Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
      lu.compute(matrix);
      if (lu.info() != Eigen::Success)
      {
        throw InvalidInputError("visual-collision binding: the mean value parameterisation of a "
                                "region is singular (a region without boundary?)");
      }
      const Eigen::MatrixX2d solution = lu.solve(rhs);
      // Barycentric coordinates in the collision triangle's 2D frame.
      const Vector2 e1 = corners[1] - corners[0];
      const Vector2 e2 = corners[2] - corners[0];
      const double area = e1.x() * e2.y() - e1.y() * e2.x();
      for (Eigen::Index i = 0; i < size; ++i)
      {
        VisualVertexBinding& b = bindings[interior[i]];
        if (b.kind != BindingKind::CollisionTriangle)
        {
          continue;
        }
        const Vector2 d = solution.row(i).transpose() - corners[0];
        double beta = (d.x() * e2.y() - d.y() * e2.x()) / area;
        double gamma = (e1.x() * d.y() - e1.y() * d.x()) / area;
        double alpha = 1.0 - beta - gamma;
        // Round-off below zero only: the mapping of a disk onto a convex
        // boundary by convex combinations stays inside (Floater).
        alpha = std::max(alpha, 0.0);
        beta = std::max(beta, 0.0);
        gamma = std::max(gamma, 0.0);
        const double sum = alpha + beta + gamma;
        b.parameters = Vector3(alpha, beta, gamma) / sum;
      }
    }
    for (int v : interior)
    {
      Local[v] = -1;
    }
    for (const auto& entry : boundary)
    {
      Boundary[entry.first] = 0;
    }
    BoundaryPosition.clear();
  }

private:
  std::vector<int> Local;
  std::vector<char> Boundary;
  std::unordered_map<int, Vector2> BoundaryPosition;
};

/// A geodesic path wanted for collision edge `edge` on side `side` (0: the
/// rim path of a border edge, or a junction's crease path) between two
/// visual vertices.
struct PathRequest
{
  int edge;
  int side;
  /// The collision edge's vertices (lower, higher), for messages.
  std::array<int, 2> collisionEnds{ -1, -1 };
  int source = -1;
  int target = -1;
  /// An inner edge joining two border vertices: both ends on the rim.
  bool chord = false;
  /// The half of the visual surface an inner path stays on.
  SurfaceHalf half = SurfaceHalf::Positive;
};

/// Index of a half in SideRegions (positive, negative, a cleft's).
int halfIndex(SurfaceHalf half)
{
  return half == SurfaceHalf::Positive ? 0 : (half == SurfaceHalf::Negative ? 1 : 2);
}

/// The ends of request r and the half it stays on: the visual vertices
/// that a triangle side of its wedge sees at the edge's two vertices.
void setRequestEnds(const VisualCollisionBinding& binding,
  const CollisionTopology& topology,
  PathRequest& r)
{
  const auto& edge = topology.edges[r.edge];
  const int count = topology.edgeTriangleCount[r.edge];
  for (int t : topology.edgeTriangles[r.edge])
  {
    for (int side : { 1, -1 })
    {
      if (t >= 0 && topology.sides.pathSide(t, side, count) == r.side)
      {
        r.source = binding.pairedVisualVertex(edge[0], t, side);
        r.target = binding.pairedVisualVertex(edge[1], t, side);
        r.half = topology.sides.halves[t][sideSlot(side)];
        return;
      }
    }
  }
}

/// The paired visual vertices into the binding: the positive and negative
/// ones of every vertex, the crease's of the junction vertices.
void setPairedVisualVertices(VisualCollisionBinding& binding,
  const std::vector<std::array<int, PairedSlots>>& indices)
{
  binding.pairedVisualVertices.resize(indices.size());
  binding.creaseVisualVertices.assign(indices.size(), -1);
  for (std::size_t v = 0; v < indices.size(); ++v)
  {
    binding.pairedVisualVertices[v] = { { indices[v][0], indices[v][1] } };
    if (binding.collisionSides.junctionVertex[v])
    {
      binding.creaseVisualVertices[v] = indices[v][CreaseSlot];
    }
  }
}

/// Where the side paths may run: each half of the visual surface (split by
/// the rim paths: positive, negative, and the clefts'), and each half
/// without the triangles touching the rim paths (its core).
struct SideRegions
{
  const TriangleMeshAdjacency* adjacency = nullptr;
  std::vector<char> onRim; ///< per vertex: on a rim path
  std::array<std::vector<char>, 3> halves;
  std::array<std::vector<char>, 3> cores;
};

/// The + and - halves of the rim-meshed surface for the inner paths, and
/// their cores (the triangles that touch no rim vertex).
SideRegions sideRegions(const RemeshedSurface& rimmed,
  const TriangleMeshAdjacency& rimmedAdjacency,
  const std::vector<std::int8_t>& half)
{
  SideRegions regions;
  regions.adjacency = &rimmedAdjacency;
  std::vector<char>& onRim = regions.onRim;
  onRim.assign(rimmed.mesh.vertexCount(), 0);
  for (const std::vector<int>& path : rimmed.pathVertices)
  {
    for (int v : path)
    {
      onRim[v] = 1;
    }
  }
  for (SurfaceHalf which : { SurfaceHalf::Positive, SurfaceHalf::Negative, SurfaceHalf::Cleft })
  {
    const int slot = halfIndex(which);
    regions.halves[slot].resize(half.size());
    regions.cores[slot].resize(half.size());
    for (std::size_t t = 0; t < half.size(); ++t)
    {
      const Triangle& tri = rimmed.mesh.triangles[t];
      regions.halves[slot][t] = half[t] == static_cast<std::int8_t>(which) ? 1 : 0;
      regions.cores[slot][t] =
        regions.halves[slot][t] && !onRim[tri[0]] && !onRim[tri[1]] && !onRim[tri[2]] ? 1 : 0;
    }
  }
  return regions;
}

/// Where a path request is, for an error about it: its collision edge and
/// side and, when no path joins its ends (`disconnected`), what usually
/// parts the surface there.
std::string pathContext(const PathRequest& r, bool onHalf, bool disconnected)
{
  const std::string edge =
    "(" + std::to_string(r.collisionEnds[0]) + ", " + std::to_string(r.collisionEnds[1]) + ")";
  if (!onHalf)
  {
    return " (the rim path of collision edge " + edge +
           (disconnected ? "; the visual surface is in pieces there: prepare each piece as its "
                           "own tissue)"
                         : ")");
  }
  const char* half = r.half == SurfaceHalf::Positive
                       ? "positive"
                       : (r.half == SurfaceHalf::Negative ? "negative" : "cleft's");
  return std::string(" (the ") + half + " path of collision edge " + edge +
         ", which stays on the " + half + " half of the visual surface between the rim paths" +
         (disconnected ? "; that half is in pieces there: tunnels through the tissue, or a rim "
                         "path cutting part of it off; a finer collision mesh or segmentation may "
                         "help)"
                       : ")");
}

/// One requested path: on the whole surface, or with `regions` on its half
/// (a chord along the rim paths moved off them, `detour` counting the rim
/// vertices it was moved round).
void computeOnePath(const GeodesicPathFinder& finder,
  const PathRequest& r,
  const SideRegions* regions,
  SurfacePath& path,
  int& detour)
{
  if (regions == nullptr)
  {
    path = finder.shortestPath(r.source, r.target);
    return;
  }
  const int slot = halfIndex(r.half);
  path = finder.shortestPathWithin(r.source, r.target, regions->halves[slot]);
  // Between two rim points the shortest path on the half may run all
  // along the rim paths (a thin corner triangle: around the corner is
  // barely longer than over it), leaving the triangle's region no width.
  // Such a chord is recomputed off the rim paths: on the core of its
  // half and the triangles around its own two ends, if they connect.
  const bool alongTheRim = r.chord && std::all_of(path.points.begin(),
                                        path.points.end(),
                                        [&](const SurfacePoint& point) {
                                          return point.isVertex() && regions->onRim[point.vertex];
                                        });
  if (!alongTheRim)
  {
    return;
  }
  std::vector<int> ends;
  for (int v : { r.source, r.target })
  {
    for (const int* t = regions->adjacency->vertexTrianglesBegin(v);
         t != regions->adjacency->vertexTrianglesEnd(v);
         ++t)
    {
      if (regions->halves[slot][*t])
      {
        ends.push_back(*t);
      }
    }
  }
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  try
  {
    const auto alongRim = static_cast<int>(path.points.size());
    path = finder.shortestPathWithin(r.source, r.target, regions->cores[slot], ends);
    detour = std::max(1, alongRim - 2);
  }
  catch (const DisconnectedPathError&)
  {
    // The core does not connect the ends: the path along the rim stays
    // (the flood fill reports the region without width).
  }
}

/// The requested paths, in parallel or not (same result), in blocks so that
/// progress (and abort) is reported from this thread between `from` and
/// `to`. With `regions`, an inner path stays on its half. `detours`: per path, the vertices of the
/// geodesic it was re-routed around (a chord moved off the rim paths), else 0.
std::vector<SurfacePath> computePaths(const GeodesicPathFinder& finder,
  const std::vector<PathRequest>& requests,
  const SideRegions* regions,
  bool parallel,
  const BindingProgress& progress,
  double from,
  double to,
  std::vector<int>& detours)
{
  std::vector<SurfacePath> paths(requests.size());
  detours.assign(requests.size(), 0);
  auto computePath = [&](std::size_t k)
  {
    const PathRequest& r = requests[k];
    try
    {
      computeOnePath(finder, r, regions, paths[k], detours[k]);
    }
    catch (const DisconnectedPathError& error)
    {
      throw DisconnectedPathError(
        std::string(error.what()) + pathContext(r, regions != nullptr, true));
    }
    catch (const InvalidInputError& error)
    {
      throw InvalidInputError(
        std::string(error.what()) + pathContext(r, regions != nullptr, false));
    }
  };
  // At most 20 blocks, at least 32 paths each: every block wakes the
  // thread pool, which costs more than a short path.
  const std::size_t block = std::max<std::size_t>(32, requests.size() / 20);
  for (std::size_t begin = 0; begin < requests.size(); begin += block)
  {
    const std::size_t end = std::min(requests.size(), begin + block);
    if (parallel)
    {
      tbb::parallel_for(begin, end, computePath);
    }
    else
    {
      for (std::size_t k = begin; k < end; ++k)
      {
        computePath(k);
      }
    }
    report(progress,
      from + (to - from) * static_cast<double>(end) / static_cast<double>(requests.size()),
      "computing geodesic paths");
  }
  return paths;
}

/// The pieces of the visual surface that the rim paths bound (flood fill):
/// per triangle its piece; `onRim` marks the rim paths' vertices.
std::vector<int> piecesBetweenRimPaths(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<std::vector<int>>& rimPaths,
  std::vector<char>& onRim,
  int& pieces)
{
  std::vector<char> barrier(adjacency.edgeCount(), 0);
  onRim.assign(mesh.vertexCount(), 0);
  for (const std::vector<int>& path : rimPaths)
  {
    for (std::size_t i = 0; i < path.size(); ++i)
    {
      onRim[path[i]] = 1;
      if (i > 0)
      {
        barrier[adjacency.findEdge(path[i - 1], path[i])] = 1;
      }
    }
  }
  std::vector<int> piece;
  pieces = floodTrianglePieces(
    adjacency,
    mesh.triangleCount(),
    [&](int t, int k) { return !barrier[adjacency.triangleEdges(t)[k]]; },
    piece);
  return piece;
}

/// Per collision vertex and paired slot: the half its visual vertex lies on
/// (a leaf's negative side faces its cleft, not the negative half).
std::vector<std::array<SurfaceHalf, PairedSlots>> pairedHalves(const TriangleMesh& collision,
  const CollisionTopology& topology)
{
  std::vector<std::array<SurfaceHalf, PairedSlots>> halves(collision.vertexCount(),
    { { SurfaceHalf::Positive, SurfaceHalf::Negative, SurfaceHalf::Cleft } });
  for (std::size_t t = 0; t < collision.triangleCount(); ++t)
  {
    for (int v : collision.triangles[t])
    {
      for (int side : { 1, -1 })
      {
        halves[v][topology.sides.pairedSlot(v, static_cast<int>(t), side)] =
          topology.sides.halves[t][sideSlot(side)];
      }
    }
  }
  return halves;
}

/// Votes per piece of the paired visual vertices of inner collision
/// vertices for the half they lie on (positive, negative, a cleft's), and
/// the first voter of each.
struct HalfVotes
{
  std::vector<std::array<int, 3>> votes;
  std::vector<std::array<int, 3>> firstVoter;
};

HalfVotes votesForHalves(const VisualCollisionBinding& binding,
  const TriangleMesh& collision,
  const CollisionTopology& topology,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<int>& piece,
  const std::vector<char>& onRim,
  int pieces)
{
  const std::vector<std::array<SurfaceHalf, PairedSlots>> halves =
    pairedHalves(collision, topology);
  HalfVotes result;
  result.votes.assign(static_cast<std::size_t>(pieces), { { 0, 0, 0 } });
  result.firstVoter.assign(static_cast<std::size_t>(pieces), { { -1, -1, -1 } });
  for (std::size_t c = 0; c < collision.vertexCount(); ++c)
  {
    if (topology.borderVertex[c])
    {
      continue;
    }
    for (int slot = 0; slot < static_cast<int>(PairedSlots); ++slot)
    {
      const int v = slot == CreaseSlot ? binding.creaseVisualVertices[c]
                                       : binding.pairedVisualVertices[c][slot];
      if (v < 0 || onRim[v])
      {
        continue;
      }
      const int p = piece[*adjacency.vertexTrianglesBegin(v)];
      const int h = halfIndex(halves[c][slot]);
      ++result.votes[p][h];
      int& first = result.firstVoter[p][h];
      first = first < 0 ? static_cast<int>(c) : first;
    }
  }
  return result;
}

/// The side a piece with no paired vertex lies on (a collision mesh with no
/// inner vertex), measured from the nearest collision vertex along its
/// normal, sampled (every piece at least once; about 8192 triangles in all).
std::vector<double> pieceOffsets(const TriangleMesh& mesh,
  const TriangleMesh& collision,
  const CollisionTopology& topology,
  const std::vector<int>& piece,
  const std::vector<char>& decided,
  int pieces)
{
  std::vector<double> offset(static_cast<std::size_t>(pieces), 0.0);
  const std::size_t stride = std::max<std::size_t>(1, mesh.triangleCount() / 8192);
  std::vector<char> sampled(static_cast<std::size_t>(pieces), 0);
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const int p = piece[t];
    if (decided[p] || (t % stride != 0 && sampled[p]))
    {
      continue;
    }
    sampled[p] = 1;
    const Triangle& tri = mesh.triangles[t];
    const Vector3 centre =
      (mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]) / 3.0;
    double best = Infinity;
    int nearest = 0;
    for (std::size_t c = 0; c < collision.vertexCount(); ++c)
    {
      const double d = (collision.positions[c] - centre).squaredNorm();
      if (d < best)
      {
        best = d;
        nearest = static_cast<int>(c);
      }
    }
    offset[p] += mesh.triangleArea(t) *
                 (centre - collision.positions[nearest]).dot(topology.vertexNormals[nearest]);
  }
  return offset;
}

/// A paired visual vertex off the main piece of its slot's half (a stray
/// vote, outvoted; see outvotedPairings).
struct MisplacedPairing
{
  int collisionVertex = -1;
  int slot = 0;
  /// The main piece of the slot's half (most votes), where it goes.
  int piece = -1;
};

/// A piece's votes decide its half when one half has all of them, or at
/// least this many times the votes of every other (a stray vote: see
/// repairMisplacedPairings).
constexpr int StrayVoteMajority = 8;

/// The half of a piece with votes from several halves: the one with at
/// least StrayVoteMajority times the votes of every other (and a voter of
/// a positive or negative slot), or -1.
int outvotingHalf(const std::array<int, 3>& votes)
{
  for (int h = 0; h < 2; ++h)
  {
    bool outvotes = true;
    for (int other = 0; other < 3; ++other)
    {
      outvotes = outvotes && (other == h || votes[h] >= StrayVoteMajority * votes[other]);
    }
    if (outvotes && votes[h] > 0)
    {
      return h;
    }
  }
  return -1;
}

/// The positive and negative paired visual vertices of inner collision
/// vertices that lie off the main piece of their slot's half (the piece
/// with the most votes for it): on a piece the other half outvoted, or on
/// a stray piece of their own half, which no path from the main piece
/// reaches. Each with the main piece, where it goes.
std::vector<MisplacedPairing> outvotedPairings(const VisualCollisionBinding& binding,
  const TriangleMesh& collision,
  const CollisionTopology& topology,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<char>& onRim,
  const std::vector<int>& piece,
  const HalfVotes& votes)
{
  const std::vector<std::array<SurfaceHalf, PairedSlots>> halves =
    pairedHalves(collision, topology);
  std::array<int, 2> mainPiece{ { -1, -1 } };
  for (int h = 0; h < 2; ++h)
  {
    for (std::size_t p = 0; p < votes.votes.size(); ++p)
    {
      if (votes.votes[p][h] > 0 &&
          (mainPiece[h] < 0 || votes.votes[p][h] > votes.votes[mainPiece[h]][h]))
      {
        mainPiece[h] = static_cast<int>(p);
      }
    }
  }
  std::vector<MisplacedPairing> misplaced;
  for (std::size_t c = 0; c < collision.vertexCount(); ++c)
  {
    for (int slot = 0; slot < 2 && !topology.borderVertex[c]; ++slot)
    {
      const int v = binding.pairedVisualVertices[c][slot];
      const int h = halfIndex(halves[c][slot]);
      const int main = h < 2 ? mainPiece[h] : -1;
      if (v >= 0 && !onRim[v] && main >= 0 && piece[*adjacency.vertexTrianglesBegin(v)] != main)
      {
        misplaced.push_back({ static_cast<int>(c), slot, main });
      }
    }
  }
  return misplaced;
}

/// The visual surface cut along the rim paths, by triangle.
struct SurfaceHalves
{
  std::vector<std::int8_t> half;           ///< per triangle
  std::vector<int> piece;                  ///< per triangle, between the rim paths
  std::vector<MisplacedPairing> misplaced; ///< pairings off their half's main piece
};

/// The half (SurfaceHalf: +1, -1, 0 for a cleft) of every triangle of the
/// visual surface cut along the rim paths: each piece the rim paths bound
/// takes the half of the collision vertices' paired visual vertices in it;
/// a piece without any the side its surface lies on (pieceOffsets). A
/// piece holding vertices of two halves means the rim paths do not
/// separate them: InvalidInputError, unless one half outvotes the others
/// (outvotingHalf); the pairings off their half's main piece are listed
/// (outvotedPairings) for repairMisplacedPairings.
SurfaceHalves surfaceHalves(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<std::vector<int>>& rimPaths,
  const TriangleMesh& collision,
  const VisualCollisionBinding& binding,
  const CollisionTopology& topology)
{
  std::vector<char> onRim;
  int pieces = 0;
  SurfaceHalves result;
  result.piece = piecesBetweenRimPaths(mesh, adjacency, rimPaths, onRim, pieces);
  const std::vector<int>& piece = result.piece;
  const HalfVotes votes =
    votesForHalves(binding, collision, topology, adjacency, piece, onRim, pieces);
  constexpr std::array<SurfaceHalf, 3> HalfOfIndex{
    { SurfaceHalf::Positive, SurfaceHalf::Negative, SurfaceHalf::Cleft }
  };
  constexpr std::array<const char*, 3> HalfName{ { "positive", "negative", "cleft's" } };
  std::vector<std::int8_t> halfOfPiece(static_cast<std::size_t>(pieces), 0);
  std::vector<char> decided(static_cast<std::size_t>(pieces), 0);
  bool needOffsets = false;
  for (int p = 0; p < pieces; ++p)
  {
    int chosen = outvotingHalf(votes.votes[p]);
    const bool outvoted = chosen >= 0;
    for (int h = 0; h < 3 && !outvoted; ++h)
    {
      if (votes.votes[p][h] == 0)
      {
        continue;
      }
      if (chosen >= 0)
      {
        throw InvalidInputError("collision mesh '" + collision.name + "': collision vertex " +
                                std::to_string(votes.firstVoter[p][chosen]) + " finds its " +
                                HalfName[chosen] + " visual vertex, and collision vertex " +
                                std::to_string(votes.firstVoter[p][h]) + " its " + HalfName[h] +
                                " one, on one piece of the visual surface between the rim paths (" +
                                std::to_string(votes.votes[p][chosen]) + " " + HalfName[chosen] +
                                " and " + std::to_string(votes.votes[p][h]) + " " + HalfName[h] +
                                " ones there; the collision normals are not consistent, the "
                                "border does not run around the visual rim, or tunnels through "
                                "the tissue join its sides: the visual surface has genus " +
                                std::to_string(adjacency.closedSurfaceGenus()) + ")");
      }
      chosen = h;
    }
    decided[p] = chosen >= 0 ? 1 : 0;
    halfOfPiece[p] = chosen >= 0 ? static_cast<std::int8_t>(HalfOfIndex[chosen]) : 0;
    needOffsets = needOffsets || chosen < 0;
  }
  if (needOffsets)
  {
    const std::vector<double> offset =
      pieceOffsets(mesh, collision, topology, piece, decided, pieces);
    for (int p = 0; p < pieces; ++p)
    {
      if (!decided[p])
      {
        halfOfPiece[p] = offset[p] >= 0.0 ? 1 : -1;
      }
    }
  }
  result.half.resize(mesh.triangleCount());
  for (std::size_t t = 0; t < result.half.size(); ++t)
  {
    result.half[t] = halfOfPiece[piece[t]];
  }
  result.misplaced = outvotedPairings(binding, collision, topology, adjacency, onRim, piece, votes);
  return result;
}

/// Stray votes: an inner collision vertex beside an opening of the visual
/// outline that its border spans (a bay of a rough rim, a tear's gap) can
/// see, along its normal, the opening's rounded shoulder beyond the rim
/// paths, which lies on the other half. When the piece's other voters
/// outvote it (outvotingHalf), that pairing moves to the vertex of the
/// main piece of its own half (not on a rim path, not paired already)
/// nearest to where the thickness puts it: the collision vertex plus its
/// radius along its normal, on the slot's side. Returns whether any moved;
/// InvalidInputError when the piece has no such vertex. A linear scan per
/// moved pairing: they are a handful, and only on such surfaces.
bool repairMisplacedPairings(VisualCollisionBinding& binding,
  const RemeshedSurface& rimmed,
  const TriangleMeshAdjacency& adjacency,
  const SurfaceHalves& halves,
  const TriangleMesh& collision,
  const CollisionTopology& topology)
{
  const TriangleMesh& mesh = rimmed.mesh;
  const std::vector<int>& piece = halves.piece;
  std::vector<char> taken(mesh.vertexCount(), 0);
  for (const std::vector<int>& path : rimmed.pathVertices)
  {
    for (int v : path)
    {
      taken[v] = 1;
    }
  }
  for (std::size_t c = 0; c < binding.pairedVisualVertices.size(); ++c)
  {
    for (int v : binding.pairedVisualVertices[c])
    {
      if (v >= 0)
      {
        taken[v] = 1;
      }
    }
  }
  for (const MisplacedPairing& m : halves.misplaced)
  {
    const int c = m.collisionVertex;
    const double sign = m.slot == 0 ? 1.0 : -1.0;
    const Vector3 expected =
      collision.positions[c] + sign * binding.collisionRadii[c] * topology.vertexNormals[c];
    int best = -1;
    double bestDistance = Infinity;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    {
      const int* first = adjacency.vertexTrianglesBegin(static_cast<int>(v));
      if (taken[v] || first == adjacency.vertexTrianglesEnd(static_cast<int>(v)) ||
          piece[*first] != m.piece)
      {
        continue;
      }
      const double d = (mesh.positions[v] - expected).squaredNorm();
      if (d < bestDistance)
      {
        bestDistance = d;
        best = static_cast<int>(v);
      }
    }
    if (best < 0)
    {
      throw InvalidInputError("collision mesh '" + collision.name + "': collision vertex " +
                              std::to_string(c) + " finds no visual vertex on its side of the " +
                              "rim paths");
    }
    taken[best] = 1;
    binding.pairedVisualVertices[c][m.slot] = best;
  }
  return !halves.misplaced.empty();
}

/// The path of each collision edge and side label (a border edge's one
/// path, side 0, serves both sides; a junction's crease path the two
/// leaves' sides facing the cleft).
struct PathsOfEdges
{
  const CollisionTopology* topology = nullptr;
  std::vector<std::array<int, 3>> byEdge; ///< path index per side label + 1
  /// The path bounding side `side` of collision triangle t along `edge`.
  int operator()(int edge, int t, int side) const
  {
    const int label = topology->sides.pathSide(t, side, topology->edgeTriangleCount[edge]);
    return byEdge[edge][label + 1];
  }
};

/// The regions (5.2.3): flood fill over the re-meshed visual surface with
/// path edges as barriers, each collision triangle and side seeded beside
/// its own paths. Sets binding.triangleRegion and triangleSide; returns
/// the triangles of each region (index 2 t + (side < 0)).
std::vector<std::vector<int>> floodRegions(VisualCollisionBinding& binding,
  const TriangleMesh& collision,
  const CollisionTopology& topology,
  const PathsOfEdges& pathFor)
{
  const TriangleMesh& mesh = binding.visual;
  const TriangleMeshAdjacency adjacency(mesh);
  std::vector<int> pathUses(adjacency.edgeCount(), 0);
  for (const BindingPath& path : binding.paths)
  {
    for (std::size_t i = 1; i < path.visualVertices.size(); ++i)
    {
      const int e = adjacency.findEdge(path.visualVertices[i - 1], path.visualVertices[i]);
      if (e < 0)
      {
        throw InvalidInputError("visual-collision binding: re-meshing lost a path edge");
      }
      ++pathUses[e];
    }
  }
  const std::size_t triangleCount = mesh.triangles.size();
  binding.triangleRegion.assign(triangleCount, -1);
  binding.triangleSide.assign(triangleCount, 0);
  std::vector<int> regionLabel(triangleCount, -1); // 2 t + (side < 0)
  std::vector<std::vector<int>> regionTriangles(2 * collision.triangles.size());
  auto triangleLeftOf = [&](int u, int w) -> int
  {
    // The triangle in which u -> w runs counter-clockwise.
    const int e = adjacency.findEdge(u, w);
    for (const int* t = adjacency.edgeTrianglesBegin(e); t != adjacency.edgeTrianglesEnd(e); ++t)
    {
      const Triangle& tri = mesh.triangles[*t];
      for (int k = 0; k < 3; ++k)
      {
        if (tri[k] == u && tri[(k + 1) % 3] == w)
        {
          return *t;
        }
      }
    }
    return -1;
  };
  std::vector<int> stack;
  for (std::size_t t = 0; t < collision.triangles.size(); ++t)
  {
    const Triangle& ct = collision.triangles[t];
    for (int side : { 1, -1 })
    {
      const int label = 2 * static_cast<int>(t) + (side < 0 ? 1 : 0);
      for (int k = 0; k < 3; ++k)
      {
        const int a = ct[k];
        const int b = ct[(k + 1) % 3];
        const int edge = binding.collisionEdgeIndex(a, b);
        const BindingPath& path = binding.paths[pathFor(edge, static_cast<int>(t), side)];
        const bool forward = topology.edges[edge][0] == a;
        // A segment of this path that no other path uses.
        int seed = -1;
        const auto& pv = path.visualVertices;
        for (std::size_t i = 1; i < pv.size() && seed < 0; ++i)
        {
          int u = pv[i - 1];
          int w = pv[i];
          if (!forward)
          {
            std::swap(u, w);
          }
          if (pathUses[adjacency.findEdge(u, w)] == 1)
          {
            seed = side > 0 ? triangleLeftOf(u, w) : triangleLeftOf(w, u);
          }
        }
        if (seed < 0)
        {
          throw InvalidInputError("visual-collision binding: every segment of the " +
                                  std::string(side > 0 ? "positive" : "negative") +
                                  " path of collision edge (" + std::to_string(a) + ", " +
                                  std::to_string(b) +
                                  ") is shared with another path; the region of collision "
                                  "triangle " +
                                  std::to_string(t) + " has no width there");
        }
        if (regionLabel[seed] == label)
        {
          continue;
        }
        if (regionLabel[seed] >= 0)
        {
          throw InvalidInputError(
            "visual-collision binding: the regions of collision triangles " + std::to_string(t) +
            " and " + std::to_string(regionLabel[seed] / 2) +
            " are not separated by their paths (paths cross or the collision mesh folds)");
        }
        if (!regionTriangles[label].empty())
        {
          throw InvalidInputError("visual-collision binding: the " +
                                  std::string(side > 0 ? "positive" : "negative") +
                                  " region of collision triangle " + std::to_string(t) +
                                  " falls apart into several pieces (its paths cross others)");
        }
        regionLabel[seed] = label;
        stack.assign(1, seed);
        while (!stack.empty())
        {
          const int current = stack.back();
          stack.pop_back();
          regionTriangles[label].push_back(current);
          const auto& edges = adjacency.triangleEdges(current);
          for (int j = 0; j < 3; ++j)
          {
            if (pathUses[edges[j]] > 0)
            {
              continue;
            }
            const int next = adjacency.neighbourAcross(current, j);
            if (next >= 0 && regionLabel[next] < 0)
            {
              regionLabel[next] = label;
              stack.push_back(next);
            }
            else if (next >= 0 && regionLabel[next] != label)
            {
              throw InvalidInputError("visual-collision binding: the regions of collision "
                                      "triangles " +
                                      std::to_string(t) + " and " +
                                      std::to_string(regionLabel[next] / 2) + " touch");
            }
          }
        }
      }
    }
  }
  for (std::size_t t = 0; t < triangleCount; ++t)
  {
    if (regionLabel[t] < 0)
    {
      throw InvalidInputError("visual-collision binding: visual triangle " + std::to_string(t) +
                              " (at vertex " + std::to_string(mesh.triangles[t][0]) +
                              ") is enclosed by no collision triangle's paths");
    }
    binding.triangleRegion[t] = regionLabel[t] / 2;
    binding.triangleSide[t] = static_cast<std::int8_t>(regionLabel[t] % 2 == 0 ? 1 : -1);
  }
  return regionTriangles;
}

/// Vertex bindings (5.2.4): paired vertices bound to their collision
/// vertex, path vertices to their edge by accumulated length, the rest to
/// their region's triangle (parameters still to solve). Returns each
/// path's accumulated-length fractions from its edge's first vertex.
std::vector<std::vector<double>> bindVisualVertices(VisualCollisionBinding& binding)
{
  const TriangleMesh& mesh = binding.visual;
  const std::size_t triangleCount = mesh.triangles.size();
  binding.vertices.assign(mesh.positions.size(), VisualVertexBinding());
  std::vector<char> assigned(mesh.positions.size(), 0);
  for (std::size_t v = 0; v < binding.pairedVisualVertices.size(); ++v)
  {
    const auto& pair = binding.pairedVisualVertices[v];
    // The crease's vertex lies between two sides, like a rim vertex.
    const std::array<std::pair<int, int>, 3> sides{ { { pair[0], pair[0] == pair[1] ? 0 : 1 },
      { pair[1], pair[0] == pair[1] ? 0 : -1 },
      { binding.creaseVisualVertices[v], 0 } } };
    for (const auto& [visualVertex, side] : sides)
    {
      if (visualVertex < 0)
      {
        continue;
      }
      VisualVertexBinding& b = binding.vertices[visualVertex];
      b.kind = BindingKind::CollisionVertex;
      b.element = static_cast<int>(v);
      b.side = side;
      b.parameters = Vector3(1.0, 0.0, 0.0);
      assigned[visualVertex] = 1;
    }
  }
  // Accumulated length along each path (fraction from the edge's first vertex).
  std::vector<std::vector<double>> pathFractions(binding.paths.size());
  for (std::size_t k = 0; k < binding.paths.size(); ++k)
  {
    const BindingPath& path = binding.paths[k];
    auto& fractions = pathFractions[k];
    fractions.assign(path.visualVertices.size(), 0.0);
    double accumulated = 0.0;
    for (std::size_t i = 1; i < path.visualVertices.size(); ++i)
    {
      accumulated +=
        (mesh.positions[path.visualVertices[i]] - mesh.positions[path.visualVertices[i - 1]])
          .norm();
      fractions[i] = path.length > 0.0 ? accumulated / path.length : 0.0;
    }
    for (std::size_t i = 1; i + 1 < path.visualVertices.size(); ++i)
    {
      const int v = path.visualVertices[i];
      if (assigned[v])
      {
        continue; // shared with an earlier path: keeps that binding
      }
      assigned[v] = 1;
      VisualVertexBinding& b = binding.vertices[v];
      b.kind = BindingKind::CollisionEdge;
      b.element = path.collisionEdge;
      b.side = path.side;
      b.parameters = Vector3(1.0 - fractions[i], fractions[i], 0.0);
    }
  }
  for (std::size_t t = 0; t < triangleCount; ++t)
  {
    for (int v : mesh.triangles[t])
    {
      if (!assigned[v])
      {
        assigned[v] = 1;
        VisualVertexBinding& b = binding.vertices[v];
        b.kind = BindingKind::CollisionTriangle;
        b.element = binding.triangleRegion[t];
        b.side = binding.triangleSide[t];
      }
    }
  }
  return pathFractions;
}

bool samePoint(const SurfacePoint& x, const SurfacePoint& y)
{
  return x.isVertex() ? y.isVertex() && x.vertex == y.vertex
                      : !y.isVertex() && x.edgeStart == y.edgeStart && x.edgeEnd == y.edgeEnd &&
                          x.edgeParameter == y.edgeParameter;
}

/// The first slot of `points` before `slot` holding the same point, or -1
/// (a rim vertex's slots all hold one point).
int earlierSlotOf(const PairedPoints& points, int slot)
{
  for (int earlier = 0; earlier < slot; ++earlier)
  {
    if (samePoint(points[earlier], points[slot]))
    {
      return earlier;
    }
  }
  return -1;
}

/// The paired points inside visual edges, each as a one-point path (to
/// become vertices first; the sides of a rim vertex share one).
std::vector<SurfacePath> pairedEdgePointPaths(const std::vector<PairedPoints>& pairedPoints)
{
  std::vector<SurfacePath> pairedEdgePoints;
  for (const PairedPoints& points : pairedPoints)
  {
    for (int slot = 0; slot < static_cast<int>(PairedSlots); ++slot)
    {
      if (!points[slot].isVertex() && earlierSlotOf(points, slot) < 0)
      {
        SurfacePath single;
        single.points.push_back(points[slot]);
        pairedEdgePoints.push_back(std::move(single));
      }
    }
  }
  return pairedEdgePoints;
}

/// The visual vertex of each paired point: its own vertex, or the one its
/// edge point became (`paired`: the one-point paths inserted, in order).
std::vector<std::array<int, PairedSlots>> pairedVertexIndices(
  const std::vector<PairedPoints>& pairedPoints,
  const RemeshedSurface& paired)
{
  std::vector<std::array<int, PairedSlots>> indices(pairedPoints.size(), { { -1, -1, -1 } });
  std::size_t next = 0;
  for (std::size_t v = 0; v < pairedPoints.size(); ++v)
  {
    for (int slot = 0; slot < static_cast<int>(PairedSlots); ++slot)
    {
      const SurfacePoint& point = pairedPoints[v][slot];
      const int earlier = earlierSlotOf(pairedPoints[v], slot);
      if (point.isVertex())
      {
        indices[v][slot] = point.vertex;
      }
      else if (earlier >= 0)
      {
        indices[v][slot] = indices[v][earlier];
      }
      else
      {
        indices[v][slot] = paired.pathVertices[next++].front();
      }
    }
  }
  return indices;
}

/// A rim path re-routed around vertices an inner path passes widens that
/// path's half there, so the inner path is the shortest up to those
/// vertices: they count as its detours too (longitudinal tear, sweep seed
/// 1006: a side path kept at a vertex with no free side, the rim path moved
/// around it, the half then held a path 1.5 % shorter).
void creditRimDetours(const SharedRunSeparation& separated,
  const std::vector<std::vector<int>>& ordered,
  std::size_t innerCount,
  std::size_t vertexCount,
  std::vector<int>& detours)
{
  const bool rimMoved = std::any_of(separated.aroundVertices.begin() + innerCount,
    separated.aroundVertices.end(),
    [](const std::vector<int>& vertices) { return !vertices.empty(); });
  if (!rimMoved)
  {
    return;
  }
  std::vector<char> around(vertexCount, 0);
  for (std::size_t i = innerCount; i < ordered.size(); ++i)
  {
    for (int v : separated.aroundVertices[i])
    {
      around[v] = 1;
    }
  }
  for (std::size_t i = 0; i < innerCount; ++i)
  {
    for (std::size_t j = 1; j + 1 < ordered[i].size(); ++j)
    {
      detours[i] += around[ordered[i][j]];
    }
  }
}

/// Paths that touch are moved apart (SharedPathRuns.h) and inserted again
/// into `remeshed`, pass by pass (a path re-routed around a vertex frees
/// the vertices inside it for the next pass: a hub where several paths
/// touch takes one pass per path around it). Returns each path's detours
/// (creditRimDetours included).
std::vector<int> separateTouchingPaths(RemeshedSurface& remeshed, std::size_t rimPathCount)
{
  // The side paths are moved before the rim paths (separateSharedRuns
  // moves the first of two paths that touch): a rim path is the equator
  // between the halves, and when a side path runs along it (through
  // another vertex's rim point, on a rough rim) moving the rim path
  // instead put the two detours across each other (longitudinal tear,
  // sweep seed 1010: "paths 30 and 210 cross").
  const std::size_t count = remeshed.pathVertices.size();
  auto pathAt = [&](std::size_t position) { return (position + rimPathCount) % count; };
  std::vector<int> detours(count, 0);
  std::vector<std::vector<int>> ordered(count);
  for (int pass = 0; pass < MaximumSeparationPasses; ++pass)
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      ordered[i] = remeshed.pathVertices[pathAt(i)];
    }
    const TriangleMeshAdjacency remeshedAdjacency(remeshed.mesh);
    SharedRunSeparation separated =
      separateSharedRuns(remeshed.mesh, remeshedAdjacency, ordered, SharedRunOffsetFraction);
    if (separated.runsSeparated == 0)
    {
      break;
    }
    std::vector<int> credited(count, 0);
    creditRimDetours(
      separated, ordered, count - rimPathCount, remeshed.mesh.vertexCount(), credited);
    std::vector<SurfacePath> paths(count);
    for (std::size_t i = 0; i < count; ++i)
    {
      paths[pathAt(i)] = std::move(separated.paths[i]);
      detours[pathAt(i)] += separated.detours[i] + credited[i];
    }
    remeshed = insertPaths(remeshed.mesh, paths, PathMergeTolerance);
  }
  return detours;
}

/// 5.2.4 inside each region: mean value coordinates, the boundary fixed on
/// the collision triangle laid out in its own plane (accumulated path
/// length along each side).
void parameteriseRegions(VisualCollisionBinding& binding,
  const TriangleMesh& collision,
  const CollisionTopology& topology,
  const PathsOfEdges& pathFor,
  const std::vector<std::vector<int>>& regionTriangles,
  const std::vector<std::vector<double>>& pathFractions,
  const BindingProgress& progress)
{
  const TriangleMesh& mesh = binding.visual;
  RegionParameterisation parameterisation(mesh.positions.size());
  std::vector<std::pair<int, Vector2>> boundary;
  for (std::size_t t = 0; t < collision.triangles.size(); ++t)
  {
    const Triangle& ct = collision.triangles[t];
    const Vector3& p0 = collision.positions[ct[0]];
    const Vector3& p1 = collision.positions[ct[1]];
    const Vector3& p2 = collision.positions[ct[2]];
    const double l01 = (p1 - p0).norm();
    const Vector3 x = (p1 - p0) / l01;
    const Vector3 y = (p2 - p0 - (p2 - p0).dot(x) * x).normalized();
    const std::array<Vector2, 3> corners{
      { Vector2(0.0, 0.0), Vector2(l01, 0.0), Vector2((p2 - p0).dot(x), (p2 - p0).dot(y)) }
    };
    for (int side : { 1, -1 })
    {
      boundary.clear();
      for (int k = 0; k < 3; ++k)
      {
        const int a = ct[k];
        const int b = ct[(k + 1) % 3];
        const int edge = binding.collisionEdgeIndex(a, b);
        const int p = pathFor(edge, static_cast<int>(t), side);
        const bool forward = topology.edges[edge][0] == a;
        const auto& pv = binding.paths[p].visualVertices;
        for (std::size_t i = 0; i < pv.size(); ++i)
        {
          const double fromA = forward ? pathFractions[p][i] : 1.0 - pathFractions[p][i];
          const Vector2 position = (1.0 - fromA) * corners[k] + fromA * corners[(k + 1) % 3];
          boundary.emplace_back(pv[i], position);
        }
      }
      parameterisation.solve(
        mesh, regionTriangles[2 * t + (side < 0 ? 1 : 0)], boundary, corners, binding.vertices);
    }
    if (t % 16 == 0)
    {
      report(progress,
        0.85 + 0.15 * static_cast<double>(t) / collision.triangles.size(),
        "assigning local parameters");
    }
  }
}

/// The geodesic paths to find (5.2.2): one per border edge (the rim path),
/// two per inner edge (a positive and a negative one), three per junction
/// edge (and the crease's).
void collectPathRequests(const VisualCollisionBinding& binding,
  const CollisionTopology& topology,
  std::vector<PathRequest>& rimRequests,
  std::vector<PathRequest>& innerRequests)
{
  for (std::size_t e = 0; e < topology.edges.size(); ++e)
  {
    const auto& edge = topology.edges[e];
    const int count = topology.edgeTriangleCount[e];
    const bool chord = topology.borderVertex[edge[0]] && topology.borderVertex[edge[1]];
    for (int side : { 1, -1, 0 })
    {
      const bool wanted = count == 1 ? side == 0 : (side != 0 || count == 3);
      if (!wanted)
      {
        continue; // a border edge has its rim path only, a junction all three
      }
      PathRequest r{ static_cast<int>(e), side };
      r.collisionEnds = { std::min(edge[0], edge[1]), std::max(edge[0], edge[1]) };
      r.chord = count > 1 && chord;
      setRequestEnds(binding, topology, r);
      (count == 1 ? rimRequests : innerRequests).push_back(r);
    }
  }
}

/// The triangles a surface path runs through: those around its vertices
/// and on either side of its edge points.
std::vector<int> trianglesAlong(const SurfacePath& path, const TriangleMeshAdjacency& adjacency)
{
  std::vector<int> triangles;
  for (const SurfacePoint& point : path.points)
  {
    if (point.isVertex())
    {
      triangles.insert(triangles.end(),
        adjacency.vertexTrianglesBegin(point.vertex),
        adjacency.vertexTrianglesEnd(point.vertex));
      continue;
    }
    const int e = adjacency.findEdge(point.edgeStart, point.edgeEnd);
    triangles.insert(
      triangles.end(), adjacency.edgeTrianglesBegin(e), adjacency.edgeTrianglesEnd(e));
  }
  return triangles;
}

/// How far a path strays from the straight line between its ends.
double straightness(const SurfacePath& path, const std::vector<Vector3>& positions)
{
  const double ends =
    (path.points.back().position(positions) - path.points.front().position(positions)).norm();
  return path.length / std::max(ends, 1e-300);
}

/// The crossing, rethrown with how far the straying path runs between its
/// ends when that is well over their distance: it goes round an opening of
/// the visual surface that the collision mesh spans (a tear's gap the
/// outline split in two, a perforated sheet), which no re-routing mends.
[[noreturn]] void throwCrossing(const PathsCrossError& crossing,
  const SurfacePath& path,
  int index,
  const std::vector<Vector3>& positions)
{
  const double ends =
    (path.points.back().position(positions) - path.points.front().position(positions)).norm();
  if (!(path.length > 1.5 * ends))
  {
    throw crossing;
  }
  std::ostringstream text;
  text.precision(3);
  text << crossing.what() << "; path " << index << " runs " << path.length << " between ends "
       << ends
       << " apart: the collision mesh may span an opening of the visual surface (a tear's gap "
          "or a perforation its outline does not follow)";
  throw PathsCrossError(
    text.str(), crossing.firstPath(), crossing.secondPath(), crossing.triangle());
}

/// insertPaths, with paths that cross found again (paths may touch, never
/// cross: 5.2.3). Shortest paths cross where the rim is rough: a rim path
/// whose ends sit on either side of a notch runs over the face and across
/// its neighbour's, and two side paths from points a rough rim put out of
/// order cross each other. Of two crossing paths, the one that strays more
/// from a straight line (and has a region: regionOf) is found again as the
/// shortest path on its region off the other's triangles (around its own
/// ends allowed); each such path counts the other's points as detours.
/// The crossing is reported when that finds no path, or after 16 tries.
RemeshedSurface insertUncrossedPaths(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  std::vector<SurfacePath>& paths,
  const std::function<const std::vector<char>*(int path)>& regionOf,
  std::vector<int>& detours)
{
  detours.assign(paths.size(), 0);
  std::vector<std::vector<int>> avoided(paths.size());
  const GeodesicPathFinder finder(mesh, adjacency);
  for (int attempt = 0;; ++attempt)
  {
    try
    {
      return insertPaths(mesh, paths, PathMergeTolerance);
    }
    catch (const PathsCrossError& crossing)
    {
      int again = crossing.firstPath();
      int other = crossing.secondPath();
      if (regionOf(other) != nullptr &&
          (regionOf(again) == nullptr || straightness(paths[other], mesh.positions) >
                                           straightness(paths[again], mesh.positions)))
      {
        std::swap(again, other);
      }
      const std::vector<char>* region = regionOf(again);
      if (region == nullptr || attempt == 16)
      {
        throwCrossing(crossing, paths[again], again, mesh.positions);
      }
      // Off every path it was found again around so far (else two
      // neighbours can send it back and forth).
      avoided[again].push_back(other);
      std::vector<char> allowed = *region;
      for (int k : avoided[again])
      {
        for (int t : trianglesAlong(paths[k], adjacency))
        {
          allowed[t] = 0;
        }
      }
      const SurfacePath& before = paths[again];
      std::vector<int> ends;
      for (const SurfacePoint* end : { &before.points.front(), &before.points.back() })
      {
        for (int t : trianglesAlong(SurfacePath{ { *end }, 0.0 }, adjacency))
        {
          if ((*region)[t])
          {
            ends.push_back(t);
          }
        }
      }
      std::sort(ends.begin(), ends.end());
      ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
      try
      {
        paths[again] = finder.shortestPathWithin(
          before.points.front().vertex, before.points.back().vertex, allowed, ends);
      }
      catch (const InvalidInputError&)
      {
        throwCrossing(crossing, paths[again], again, mesh.positions);
      }
      detours[again] += static_cast<int>(paths[other].points.size());
    }
  }
}

/// Two rim paths that leave a border collision vertex's rim point along
/// the same visual edges (a rough rim: the point sits at the end of a
/// spur, and both neighbours' shortest paths come in along it) make a
/// dead end of the equator: the point's triangles all lie on one half, and
/// the other half's paths from it found it "not connected". The rim point
/// moves to where the two paths part and the shared run leaves both (a
/// rim point is where the rim paths meet, 5.2.2). Returns the count moved.
int trimRimDeadEnds(std::vector<std::vector<int>>& rimPathVertices,
  const std::vector<PathRequest>& rimRequests,
  const CollisionTopology& topology,
  std::vector<std::array<int, 2>>& pairedVisualVertices)
{
  // The (at most two) rim paths at each border collision vertex, and
  // whether they start there.
  std::vector<std::vector<std::pair<int, bool>>> pathsAt(pairedVisualVertices.size());
  for (std::size_t k = 0; k < rimRequests.size(); ++k)
  {
    const auto& edge = topology.edges[rimRequests[k].edge];
    pathsAt[edge[0]].emplace_back(static_cast<int>(k), true);
    pathsAt[edge[1]].emplace_back(static_cast<int>(k), false);
  }
  int moved = 0;
  for (std::size_t c = 0; c < pathsAt.size(); ++c)
  {
    auto& pair = pairedVisualVertices[c];
    if (pathsAt[c].size() != 2 || pair[0] != pair[1])
    {
      continue;
    }
    std::vector<int>& a = rimPathVertices[pathsAt[c][0].first];
    std::vector<int>& b = rimPathVertices[pathsAt[c][1].first];
    const bool aStarts = pathsAt[c][0].second;
    const bool bStarts = pathsAt[c][1].second;
    // The i-th vertex from c's end of a path.
    auto from = [](const std::vector<int>& path, bool starts, std::size_t i)
    { return starts ? path[i] : path[path.size() - 1 - i]; };
    std::size_t shared = 0;
    while (shared + 2 < a.size() && shared + 2 < b.size() &&
           from(a, aStarts, shared + 1) == from(b, bStarts, shared + 1))
    {
      ++shared;
    }
    if (shared == 0 || from(a, aStarts, 0) != pair[0] || from(b, bStarts, 0) != pair[0])
    {
      continue;
    }
    auto trim = [shared](std::vector<int>& path, bool starts)
    {
      const auto count = static_cast<std::ptrdiff_t>(shared);
      starts ? path.erase(path.begin(), path.begin() + count)
             : path.erase(path.end() - count, path.end());
    };
    trim(a, aStarts);
    trim(b, bStarts);
    pair[0] = pair[1] = from(a, aStarts, 0);
    ++moved;
  }
  return moved;
}

/// 5.2.3 Re-meshing along the inner paths (crossings found again); the
/// rim paths, given again by their vertices, pick up the vertices inserted
/// on their edges; paths that touch are moved apart. Sets binding.visual
/// and binding.paths (rim paths first), each path's detours summed.
void remeshAlongAllPaths(VisualCollisionBinding& binding,
  const RemeshedSurface& rimmed,
  const TriangleMeshAdjacency& rimmedAdjacency,
  const SideRegions& regions,
  const std::vector<PathRequest>& rimRequests,
  const std::vector<PathRequest>& innerRequests,
  std::vector<SurfacePath> innerPaths,
  const std::vector<int>& rimDetours,
  const std::vector<int>& innerDetours)
{
  std::vector<PathRequest> requests = rimRequests;
  requests.insert(requests.end(), innerRequests.begin(), innerRequests.end());
  std::vector<SurfacePath> allPaths;
  for (const std::vector<int>& vertices : rimmed.pathVertices)
  {
    SurfacePath path;
    for (int v : vertices)
    {
      path.points.push_back(SurfacePoint::atVertex(v));
    }
    allPaths.push_back(std::move(path));
  }
  allPaths.insert(allPaths.end(),
    std::make_move_iterator(innerPaths.begin()),
    std::make_move_iterator(innerPaths.end()));
  std::vector<int> detours;
  RemeshedSurface remeshed = insertUncrossedPaths(
    rimmed.mesh,
    rimmedAdjacency,
    allPaths,
    [&](int k) -> const std::vector<char>*
    {
      const int inner = k - static_cast<int>(rimRequests.size());
      return inner < 0 ? nullptr : &regions.halves[halfIndex(innerRequests[inner].half)];
    },
    detours);
  const std::vector<int> separated = separateTouchingPaths(remeshed, rimRequests.size());
  for (std::size_t k = 0; k < detours.size(); ++k)
  {
    const int computed =
      k < rimDetours.size() ? rimDetours[k] : innerDetours[k - rimDetours.size()];
    detours[k] = std::min(
      detours[k] + separated[k] + computed, static_cast<int>(remeshed.pathVertices[k].size()));
  }
  binding.visual = std::move(remeshed.mesh);
  const TriangleMesh& mesh = binding.visual;
  for (std::size_t k = 0; k < requests.size(); ++k)
  {
    BindingPath path;
    path.collisionEdge = requests[k].edge;
    path.side = requests[k].side;
    path.visualVertices = std::move(remeshed.pathVertices[k]);
    path.detours = detours[k];
    for (std::size_t i = 1; i < path.visualVertices.size(); ++i)
    {
      path.length +=
        (mesh.positions[path.visualVertices[i]] - mesh.positions[path.visualVertices[i - 1]])
          .norm();
    }
    binding.paths.push_back(std::move(path));
  }
}

/// Flood fill: path edges are barriers; each collision triangle and side
/// is seeded beside its own paths. Then the visual vertices' parameters,
/// mean value coordinates per region (the boundary fixed on the collision
/// triangle, laid out in its own plane).
void regionsAndParameters(VisualCollisionBinding& binding,
  const TriangleMesh& collision,
  const CollisionTopology& topology,
  const BindingProgress& progress)
{
  report(progress, 0.8, "finding the regions of the collision triangles");
  PathsOfEdges pathFor;
  pathFor.topology = &topology;
  pathFor.byEdge.assign(topology.edges.size(), { { -1, -1, -1 } });
  for (std::size_t k = 0; k < binding.paths.size(); ++k)
  {
    pathFor.byEdge[binding.paths[k].collisionEdge][binding.paths[k].side + 1] = static_cast<int>(k);
  }
  const std::vector<std::vector<int>> regionTriangles =
    floodRegions(binding, collision, topology, pathFor);
  report(progress, 0.85, "assigning local parameters");
  const std::vector<std::vector<double>> pathFractions = bindVisualVertices(binding);
  parameteriseRegions(
    binding, collision, topology, pathFor, regionTriangles, pathFractions, progress);
}

/// What the stages after the pairing share.
struct BindingStages
{
  const TriangleMesh& collision;
  const CollisionTopology& topology;
  const VisualCollisionBindingSettings& settings;
  const BindingProgress& progress;
  std::vector<PathRequest> rimRequests;
  std::vector<PathRequest> innerRequests;

  /// Progress when the rim paths are done (paths 0.1-0.7, shared by count).
  double rimPathsDone() const
  {
    const auto all = static_cast<double>(rimRequests.size() + innerRequests.size());
    return 0.1 + 0.6 * static_cast<double>(rimRequests.size()) / all;
  }
};

/// The equator (5.2.2): the rim paths inserted into the visual mesh, their
/// detours, and whether rim points moved (the inner paths' ends follow).
struct RimPaths
{
  RemeshedSurface rimmed;
  std::vector<int> detours;
  bool rimPointsMoved = false;
};

/// The rim paths as geodesics between the rim points (the thesis's), crossings
/// found again, dead ends where two of them share a run trimmed.
RimPaths geodesicRimPaths(VisualCollisionBinding& binding,
  const TriangleMesh& start,
  const TriangleMeshAdjacency& startAdjacency,
  const BindingStages& stages)
{
  RimPaths rim;
  const double rimDone = stages.rimPathsDone();
  const GeodesicPathFinder finder(start, startAdjacency);
  std::vector<SurfacePath> rimPaths = computePaths(finder,
    stages.rimRequests,
    nullptr,
    stages.settings.parallel,
    stages.progress,
    0.1,
    rimDone,
    rim.detours);
  report(stages.progress, rimDone, "re-meshing along the rim paths");
  const std::vector<char> everywhere(start.triangleCount(), 1);
  std::vector<int> uncrossingDetours;
  rim.rimmed = insertUncrossedPaths(
    start, startAdjacency, rimPaths, [&](int) { return &everywhere; }, uncrossingDetours);
  for (std::size_t k = 0; k < rim.detours.size(); ++k)
  {
    rim.detours[k] += uncrossingDetours[k];
  }
  rim.rimPointsMoved =
    trimRimDeadEnds(
      rim.rimmed.pathVertices, stages.rimRequests, stages.topology, binding.pairedVisualVertices) >
    0;
  return rim;
}

/// Whether the labelled equator can stand in: a collision mesh with a
/// border and no junction (its halves are the positive and negative ones).
bool equatorMayServe(const CollisionTopology& topology, const std::vector<PathRequest>& rimRequests)
{
  return !rimRequests.empty() && std::none_of(topology.sides.junctionVertex.begin(),
                                   topology.sides.junctionVertex.end(),
                                   [](char junction) { return junction != 0; });
}

/// The rim paths along the border between the visual triangles labelled by
/// the side of the collision mid-surface they lie on (EquatorRimPaths.h):
/// the rim points move onto it. The arcs are no shortest paths: each
/// counts its inner vertices as detours.
RimPaths labelledRimPaths(VisualCollisionBinding& binding,
  const TriangleMesh& start,
  const TriangleMeshAdjacency& startAdjacency,
  const BindingStages& stages)
{
  EquatorInput input;
  input.visual = &start;
  input.adjacency = &startAdjacency;
  input.collision = &stages.collision;
  input.collisionNormals = &stages.topology.vertexNormals;
  input.rimPoints.assign(stages.collision.vertexCount(), -1);
  for (const PathRequest& r : stages.rimRequests)
  {
    const auto& edge = stages.topology.edges[r.edge];
    input.rimEdges.push_back(edge);
    input.rimPoints[edge[0]] = r.source;
    input.rimPoints[edge[1]] = r.target;
  }
  for (std::size_t c = 0; c < stages.collision.vertexCount(); ++c)
  {
    for (int slot = 0; slot < 2 && !stages.topology.borderVertex[c]; ++slot)
    {
      const int v = binding.pairedVisualVertices[c][slot];
      if (v >= 0)
      {
        input.halfVotes.emplace_back(v, slot == 0 ? 1 : -1);
      }
    }
  }
  const EquatorRimPaths equator = equatorRimPaths(input);
  for (std::size_t c = 0; c < equator.rimPoints.size(); ++c)
  {
    if (equator.rimPoints[c] >= 0)
    {
      binding.pairedVisualVertices[c] = { { equator.rimPoints[c], equator.rimPoints[c] } };
    }
  }
  std::vector<SurfacePath> paths;
  RimPaths rim;
  for (const std::vector<int>& arc : equator.paths)
  {
    SurfacePath& path = paths.emplace_back();
    for (int v : arc)
    {
      path.points.push_back(SurfacePoint::atVertex(v));
    }
    rim.detours.push_back(static_cast<int>(arc.size()) - 2);
  }
  rim.rimmed = insertPaths(start, paths);
  rim.rimPointsMoved = true;
  return rim;
}

/// 5.2.2-5.2.3 after the rim paths: the halves they bound, the inner paths
/// on them, the re-meshing along all paths, the regions and their
/// parameters.
void bindAlongRimPaths(VisualCollisionBinding& binding,
  const RimPaths& rim,
  const BindingStages& stages)
{
  const TriangleMesh& collision = stages.collision;
  const CollisionTopology& topology = stages.topology;
  const RemeshedSurface& rimmed = rim.rimmed;
  const TriangleMeshAdjacency rimmedAdjacency(rimmed.mesh);
  const SurfaceHalves halves =
    surfaceHalves(rimmed.mesh, rimmedAdjacency, rimmed.pathVertices, collision, binding, topology);
  const bool repaired =
    repairMisplacedPairings(binding, rimmed, rimmedAdjacency, halves, collision, topology);
  std::vector<PathRequest> innerRequests = stages.innerRequests;
  if (rim.rimPointsMoved || repaired)
  {
    for (PathRequest& r : innerRequests)
    {
      setRequestEnds(binding, topology, r);
    }
  }
  const SideRegions regions = sideRegions(rimmed, rimmedAdjacency, halves.half);
  std::vector<SurfacePath> innerPaths;
  std::vector<int> innerDetours;
  {
    const GeodesicPathFinder finder(rimmed.mesh, rimmedAdjacency);
    innerPaths = computePaths(finder,
      innerRequests,
      &regions,
      stages.settings.parallel,
      stages.progress,
      stages.rimPathsDone(),
      0.7,
      innerDetours);
  }

  // 5.2.3 Re-meshing along the inner paths.
  report(stages.progress, 0.7, "re-meshing the visual mesh along the paths");
  remeshAlongAllPaths(binding,
    rimmed,
    rimmedAdjacency,
    regions,
    stages.rimRequests,
    innerRequests,
    std::move(innerPaths),
    rim.detours,
    innerDetours);
  regionsAndParameters(binding, collision, topology, stages.progress);
}

} // namespace

//------------------------------------------------------------------------------
VisualCollisionBinding bindVisualToCollision(const TriangleMesh& visual,
  const TriangleMesh& collision,
  const VisualCollisionBindingSettings& settings,
  const BindingProgress& progress)
{
  report(progress, 0.0, "checking the meshes");
  const std::vector<double> radii =
    collision.pointAttributes.has(settings.radiusArrayName)
      ? collision.pointAttributes.get(settings.radiusArrayName).values
      : std::vector<double>();
  visual.checkConsistency(); // before the tree, which needs indices in range
  TriangleBvh visualBvh;
  visualBvh.build(visual.positions, visual.triangles, {}, 0.0);
  checkInputs(visual, visualBvh, collision, radii, settings);
  const CollisionTopology topology = analyseCollision(collision);
  const TriangleMeshAdjacency visualAdjacency(visual);

  // 5.2.1 Pairing.
  report(progress, 0.05, "pairing collision and visual vertices");
  VisualCollisionBinding binding;
  binding.collisionPositions = collision.positions;
  binding.collisionTriangles = collision.triangles;
  binding.collisionRadii = radii;
  binding.collisionEdges = topology.edges;
  binding.collisionSides = topology.sides;
  const std::vector<PairedPoints> pairedPoints =
    pairCollisionVertices(visual, visualAdjacency, visualBvh, collision, radii, topology, settings);
  // Paired points inside visual edges become vertices first (one-point
  // paths); the visual vertices keep their indices.
  const std::vector<SurfacePath> pairedEdgePoints = pairedEdgePointPaths(pairedPoints);
  RemeshedSurface paired;
  if (!pairedEdgePoints.empty())
  {
    paired = insertPaths(visual, pairedEdgePoints);
  }
  const TriangleMesh* startMesh = &visual;
  const TriangleMeshAdjacency* startAdjacencyPointer = &visualAdjacency;
  TriangleMeshAdjacency pairedAdjacency;
  if (!pairedEdgePoints.empty())
  {
    pairedAdjacency = TriangleMeshAdjacency(paired.mesh);
    startMesh = &paired.mesh;
    startAdjacencyPointer = &pairedAdjacency;
  }
  const TriangleMesh& start = *startMesh;
  const TriangleMeshAdjacency& startAdjacency = *startAdjacencyPointer;
  setPairedVisualVertices(binding, pairedVertexIndices(pairedPoints, paired));

  // 5.2.2 Geodesic paths: one per border edge (the rim path), two per inner
  // edge. First the rim paths, inserted into the mesh (5.2.3): together
  // they are the "equator" that splits the closed visual surface into its
  // positive and negative halves. Then each inner edge's positive and
  // negative paths, each kept on its own half: they cannot wrap around the
  // rim, and an inner edge joining two border vertices (a corner of a grid)
  // gets two distinct paths between the same two rim vertices.
  report(progress, 0.1, "computing geodesic paths");
  BindingStages stages{ collision, topology, settings, progress, {}, {} };
  collectPathRequests(binding, topology, stages.rimRequests, stages.innerRequests);
  const bool labelledOnly = settings.rimPaths == RimPathMethod::Labelled;
  if (labelledOnly && !equatorMayServe(topology, stages.rimRequests))
  {
    throw InvalidInputError("collision mesh '" + collision.name +
                            "': the labelled equator needs a border and no junction");
  }
  const VisualCollisionBinding afterPairing = binding;
  try
  {
    RimPaths rim = labelledOnly ? labelledRimPaths(binding, start, startAdjacency, stages)
                                : geodesicRimPaths(binding, start, startAdjacency, stages);
    bindAlongRimPaths(binding, rim, stages);
  }
  catch (const InvalidInputError&)
  {
    // A rough rim can defeat the geodesic equator: the labelled one is
    // tried before the first error is reported.
    if (settings.rimPaths != RimPathMethod::Automatic ||
        !equatorMayServe(topology, stages.rimRequests))
    {
      throw;
    }
    const std::exception_ptr first = std::current_exception();
    try
    {
      binding = afterPairing;
      RimPaths rim = labelledRimPaths(binding, start, startAdjacency, stages);
      bindAlongRimPaths(binding, rim, stages);
    }
    catch (const InvalidInputError&)
    {
      std::rethrow_exception(first);
    }
  }
  report(progress, 1.0, "done");
  return binding;
}

} // namespace thintissue
