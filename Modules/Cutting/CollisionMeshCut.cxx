#include "CollisionMeshCut.h"

#include "ThinTissueError.h"
#include "UnionFind.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace thintissue
{

struct CuttableCollisionMesh::Crossing
{
  int a = -1; ///< lower vertex of the edge
  int b = -1;
  double t = 0.0; ///< from a to b
};

/// A triangle the cut reaches: its corners and the cut points on its
/// edges as one counter-clockwise polygon, and which of them the cut joins.
struct CuttableCollisionMesh::TriangleFeatures
{
  int triangle = -1;
  std::vector<int> polygon;         ///< vertex ids
  std::vector<Vector3> barycentric; ///< of each polygon vertex in the triangle
  std::vector<int> edgeOf;          ///< triangle edge k of an edge point, -1 for a corner
  std::vector<int> cornerOf;        ///< corner k of a corner, -1 for an edge point
  std::vector<int> features;        ///< polygon positions on the cut
  std::vector<int> tipFeatures;     ///< those that are only a tip left earlier
};

namespace
{

/// Where segment p-q crosses triangle (a, b, c): parameter t in [0, 1] from
/// p, or a negative value. Segments in the triangle's plane do not cross.
double segmentCrossing(const Vector3& p,
  const Vector3& q,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c)
{
  const Vector3 normal = (b - a).cross(c - a);
  const double area2 = normal.norm();
  if (area2 <= 0.0)
  {
    return -1.0;
  }
  const Vector3 n = normal / area2;
  const double sp = (p - a).dot(n);
  const double sq = (q - a).dot(n);
  const double eps = 1e-10 * ((q - p).norm() + std::sqrt(area2));
  const bool pOn = std::abs(sp) <= eps;
  const bool qOn = std::abs(sq) <= eps;
  if ((pOn && qOn) || (!pOn && !qOn && (sp > 0.0) == (sq > 0.0)))
  {
    return -1.0;
  }
  const double t = pOn ? 0.0 : (qOn ? 1.0 : sp / (sp - sq));
  const Vector3 x = p + t * (q - p);
  // Barycentric test with a small tolerance: crossings on a blade edge
  // shared by two blade triangles count.
  const double tolerance = -1e-9;
  const double u = (c - b).cross(x - b).dot(n) / area2;
  const double v = (a - c).cross(x - c).dot(n) / area2;
  const double w = 1.0 - u - v;
  return (u >= tolerance && v >= tolerance && w >= tolerance) ? t : -1.0;
}

/// Triangulates a counter-clockwise polygon (convex, possibly with
/// collinear points) by clipping the best-shaped ear each time; appends
/// triangles of polygon positions.
void clipEars(const std::vector<Vector2>& points,
  std::vector<int> polygon,
  std::vector<std::array<int, 3>>& out)
{
  auto cross = [&points](int i, int j, int k)
  {
    const Vector2 u = points[j] - points[i];
    const Vector2 v = points[k] - points[i];
    return u.x() * v.y() - u.y() * v.x();
  };
  double scale = 0.0;
  for (int i : polygon)
  {
    scale = std::max(scale, (points[i] - points[polygon[0]]).squaredNorm());
  }
  const double minimumArea = 1e-12 * scale;
  while (polygon.size() > 3)
  {
    const int n = static_cast<int>(polygon.size());
    int best = -1;
    double bestQuality = -1.0;
    for (int e = 0; e < n; ++e)
    {
      const int i = polygon[(e + n - 1) % n], j = polygon[e], k = polygon[(e + 1) % n];
      const double area = cross(i, j, k);
      if (area <= minimumArea)
      {
        continue;
      }
      bool empty = true;
      for (int m : polygon)
      {
        if (m != i && m != j && m != k && cross(i, j, m) >= -minimumArea &&
            cross(j, k, m) >= -minimumArea && cross(k, i, m) >= -minimumArea)
        {
          empty = false;
          break;
        }
      }
      if (!empty)
      {
        continue;
      }
      const double longest = std::max({ (points[j] - points[i]).squaredNorm(),
        (points[k] - points[j]).squaredNorm(),
        (points[i] - points[k]).squaredNorm() });
      const double quality = area / longest;
      if (quality > bestQuality)
      {
        bestQuality = quality;
        best = e;
      }
    }
    if (best < 0)
    {
      best = 0; // cannot happen for a convex polygon; keep going
    }
    out.push_back({ polygon[(best + n - 1) % n], polygon[best], polygon[(best + 1) % n] });
    polygon.erase(polygon.begin() + best);
  }
  out.push_back({ polygon[0], polygon[1], polygon[2] });
}

} // namespace

std::uint64_t CuttableCollisionMesh::edgeKey(int a, int b)
{
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

CuttableCollisionMesh::CuttableCollisionMesh(std::string name,
  std::vector<Vector3> restPositions,
  std::vector<Triangle> triangles,
  std::vector<double> radii)
  : Name(std::move(name))
  , RestPositions(std::move(restPositions))
  , Triangles(std::move(triangles))
  , Radii(std::move(radii))
{
  const int n = static_cast<int>(RestPositions.size());
  if (Radii.size() != RestPositions.size())
  {
    throw InvalidInputError("collision mesh '" + Name + "': " + std::to_string(Radii.size()) +
                            " radii for " + std::to_string(n) + " vertices");
  }
  for (int v = 0; v < n; ++v)
  {
    if (!RestPositions[v].allFinite() || !std::isfinite(Radii[v]))
    {
      throw InvalidInputError(
        "collision mesh '" + Name + "': vertex " + std::to_string(v) + " is not finite");
    }
  }
  checkTriangles();
  TriangleMesh surface;
  surface.name = Name;
  surface.positions = RestPositions;
  surface.triangles = Triangles;
  Halves = analyseCollisionSides(surface).halves;
  VertexTriangles.assign(RestPositions.size(), {});
  for (std::size_t t = 0; t < Triangles.size(); ++t)
  {
    addToAdjacency(static_cast<int>(t));
  }
}

void CuttableCollisionMesh::checkTriangles() const
{
  const int n = static_cast<int>(RestPositions.size());
  for (std::size_t t = 0; t < Triangles.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int a = Triangles[t][k], b = Triangles[t][(k + 1) % 3];
      if (a < 0 || a >= n || a == b)
      {
        throw InvalidInputError("collision mesh '" + Name + "': triangle " + std::to_string(t) +
                                " has a bad corner " + std::to_string(a));
      }
    }
  }
}

std::array<int, 3> CuttableCollisionMesh::trianglesOfEdge(int a, int b) const
{
  const auto it = EdgeTriangles.find(edgeKey(a, b));
  return it == EdgeTriangles.end() ? std::array<int, 3>{ { -1, -1, -1 } } : it->second;
}

std::vector<std::array<int, 2>> CuttableCollisionMesh::closedCutEdges() const
{
  std::vector<std::array<int, 2>> edges;
  edges.reserve(CutEdges.size());
  for (std::uint64_t key : CutEdges)
  {
    edges.push_back({ { static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu) } });
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

bool CuttableCollisionMesh::isLeavesFold(int a, int b) const
{
  if (!CutEdges.count(edgeKey(a, b)))
  {
    return false;
  }
  const auto onEdge = trianglesOfEdge(a, b);
  if (onEdge[1] < 0 || onEdge[2] >= 0)
  {
    return false;
  }
  // Alike: both run a -> b, or both b -> a.
  auto runs = [this, a, b](int t)
  {
    const Triangle& corners = Triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      if (corners[k] == a && corners[(k + 1) % 3] == b)
      {
        return true;
      }
    }
    return false;
  };
  return runs(onEdge[0]) == runs(onEdge[1]);
}

void CuttableCollisionMesh::addToAdjacency(int t)
{
  for (int k = 0; k < 3; ++k)
  {
    const int a = Triangles[t][k], b = Triangles[t][(k + 1) % 3];
    VertexTriangles[a].push_back(t);
    auto [it, inserted] = EdgeTriangles.emplace(edgeKey(a, b), std::array<int, 3>{ { t, -1, -1 } });
    if (!inserted)
    {
      // The sides analysis (constructor) and the cut's splits and copies
      // (which never add a triangle at an edge) keep three at most.
      auto& list = it->second;
      *std::find(list.begin(), list.end(), -1) = t;
    }
  }
}

void CuttableCollisionMesh::removeFromAdjacency(int t)
{
  for (int k = 0; k < 3; ++k)
  {
    const int a = Triangles[t][k], b = Triangles[t][(k + 1) % 3];
    auto& fan = VertexTriangles[a];
    fan.erase(std::find(fan.begin(), fan.end(), t));
    auto it = EdgeTriangles.find(edgeKey(a, b));
    auto& onEdge = it->second;
    // Kept packed: the triangles first, then -1.
    std::remove(onEdge.begin(), onEdge.end(), t);
    onEdge[2] = -1;
    if (onEdge[0] < 0)
    {
      EdgeTriangles.erase(it);
    }
  }
}

int CuttableCollisionMesh::addVertex(const Vector3& rest, double radius)
{
  RestPositions.push_back(rest);
  Radii.push_back(radius);
  VertexTriangles.emplace_back();
  return static_cast<int>(RestPositions.size()) - 1;
}

std::unordered_map<std::uint64_t, CuttableCollisionMesh::Crossing>
CuttableCollisionMesh::findCrossings(const Blade& blade, const std::vector<Vector3>& current) const
{
  std::unordered_map<std::uint64_t, Crossing> crossings;
  BoundingBox box = blade.boundingBox();
  const double margin = 1e-9 * box.diagonal().norm();
  box.min().array() -= margin;
  box.max().array() += margin;
  for (const auto& [key, pair] : EdgeTriangles)
  {
    const int a = static_cast<int>(key >> 32);
    const int b = static_cast<int>(key & 0xffffffffu);
    BoundingBox edgeBox(current[a].cwiseMin(current[b]), current[a].cwiseMax(current[b]));
    if (!box.intersects(edgeBox))
    {
      continue;
    }
    for (const Triangle& bt : blade.triangles)
    {
      const double t = segmentCrossing(
        current[a], current[b], blade.points[bt[0]], blade.points[bt[1]], blade.points[bt[2]]);
      if (t >= 0.0)
      {
        crossings.emplace(key, Crossing{ a, b, t });
        break;
      }
    }
  }
  return crossings;
}

std::vector<CuttableCollisionMesh::TriangleFeatures> CuttableCollisionMesh::collectFeatures(
  const std::unordered_map<std::uint64_t, Crossing>& crossings,
  double snapFraction,
  CollisionCutResult& result)
{
  // Crossings become snapped vertices or new edge points (sorted by edge
  // for determinism: the map's order is not).
  std::vector<Crossing> sorted;
  sorted.reserve(crossings.size());
  for (const auto& entry : crossings)
  {
    sorted.push_back(entry.second);
  }
  std::sort(sorted.begin(),
    sorted.end(),
    [](const Crossing& x, const Crossing& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
  std::unordered_set<int> cutVertices;
  std::unordered_map<std::uint64_t, int> edgePoints;
  std::vector<int> candidates;
  for (const Crossing& c : sorted)
  {
    const auto onEdge = trianglesOfEdge(c.a, c.b);
    candidates.insert(candidates.end(), onEdge.begin(), onEdge.end());
    if (c.t < snapFraction || c.t > 1.0 - snapFraction)
    {
      const int v = c.t < snapFraction ? c.a : c.b;
      if (cutVertices.insert(v).second)
      {
        candidates.insert(candidates.end(), VertexTriangles[v].begin(), VertexTriangles[v].end());
      }
      continue;
    }
    const Vector3 rest = (1.0 - c.t) * RestPositions[c.a] + c.t * RestPositions[c.b];
    const int v = addVertex(rest, (1.0 - c.t) * Radii[c.a] + c.t * Radii[c.b]);
    edgePoints.emplace(edgeKey(c.a, c.b), v);
    if (isLeavesFold(c.a, c.b))
    {
      // Two leaves whose body was cut off along their junction edge stay
      // apart on both sides of a crossing. (A closed slit of one sheet
      // crossed again closes there, as it always did: keeping it open
      // would open its ends, which this cut does not reach.)
      CutEdges.insert(edgeKey(c.a, v));
      CutEdges.insert(edgeKey(v, c.b));
    }
    NewCollisionVertex made;
    made.vertex = v;
    made.edge = { c.a, c.b };
    made.t = c.t;
    result.newVertices.push_back(made);
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  if (!candidates.empty() && candidates.front() < 0)
  {
    candidates.erase(candidates.begin());
  }

  std::vector<TriangleFeatures> reached;
  for (int t : candidates)
  {
    TriangleFeatures f;
    f.triangle = t;
    const Triangle& tri = Triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      Vector3 corner = Vector3::Zero();
      corner[k] = 1.0;
      f.polygon.push_back(tri[k]);
      f.barycentric.push_back(corner);
      f.edgeOf.push_back(-1);
      f.cornerOf.push_back(k);
      if (cutVertices.count(tri[k]))
      {
        f.features.push_back(static_cast<int>(f.polygon.size()) - 1);
      }
      const int next = tri[(k + 1) % 3];
      const auto found = edgePoints.find(edgeKey(tri[k], next));
      if (found == edgePoints.end())
      {
        continue;
      }
      const Crossing& c = crossings.at(edgeKey(tri[k], next));
      // t runs from the lower vertex; here from tri[k] to next.
      const double s = (c.a == tri[k]) ? c.t : 1.0 - c.t;
      Vector3 along = Vector3::Zero();
      along[k] = 1.0 - s;
      along[(k + 1) % 3] = s;
      f.polygon.push_back(found->second);
      f.barycentric.push_back(along);
      f.edgeOf.push_back(k);
      f.cornerOf.push_back(-1);
      f.features.push_back(static_cast<int>(f.polygon.size()) - 1);
    }
    if (f.features.empty())
    {
      continue;
    }
    // A progressive cut continues from a tip left by an earlier blade.
    for (std::size_t i = 0; i < f.polygon.size(); ++i)
    {
      const bool isFeature =
        std::find(f.features.begin(), f.features.end(), static_cast<int>(i)) != f.features.end();
      if (f.cornerOf[i] >= 0 && !isFeature && Tips.count(f.polygon[i]))
      {
        f.features.push_back(static_cast<int>(i));
        f.tipFeatures.push_back(static_cast<int>(i));
      }
    }
    reached.push_back(std::move(f));
  }
  keepNearestTipLinks(reached);
  return reached;
}

void CuttableCollisionMesh::keepNearestTipLinks(std::vector<TriangleFeatures>& reached) const
{
  // A tip is a feature of every reached triangle around it, but the blade
  // went on from it through one: the triangle where the next feature is
  // nearest (ties: each, as along an edge both sides list it). Joining it
  // in the others too cut a triangle out between two of them.
  auto at = [this](const TriangleFeatures& f, int i)
  {
    const Triangle& corners = Triangles[f.triangle];
    return Vector3(f.barycentric[i][0] * RestPositions[corners[0]] +
                   f.barycentric[i][1] * RestPositions[corners[1]] +
                   f.barycentric[i][2] * RestPositions[corners[2]]);
  };
  auto link = [&](const TriangleFeatures& f, int tip)
  {
    double nearest = std::numeric_limits<double>::infinity();
    for (int i : f.features)
      if (i != tip &&
          std::find(f.tipFeatures.begin(), f.tipFeatures.end(), i) == f.tipFeatures.end())
        nearest = std::min(nearest, (at(f, i) - at(f, tip)).norm());
    return nearest;
  };
  std::unordered_map<int, double> shortest;
  for (const TriangleFeatures& f : reached)
    for (int tip : f.tipFeatures)
    {
      const auto [it, added] = shortest.emplace(f.polygon[tip], link(f, tip));
      it->second = added ? it->second : std::min(it->second, link(f, tip));
    }
  for (TriangleFeatures& f : reached)
    for (int tip : f.tipFeatures)
    {
      const double best = shortest.at(f.polygon[tip]);
      if (link(f, tip) > best * (1.0 + 1e-9))
        f.features.erase(std::find(f.features.begin(), f.features.end(), tip));
    }
}

namespace
{

bool onTriangleEdge(const std::vector<int>& edgeOf,
  const std::vector<int>& cornerOf,
  int position,
  int k)
{
  return edgeOf[position] == k || cornerOf[position] == k || cornerOf[position] == (k + 1) % 3;
}

/// The edge of the triangle holding polygon positions i and j of its cut
/// polygon (a cut between them runs along it), or -1.
int sharedEdge(const std::vector<int>& edgeOf, const std::vector<int>& cornerOf, int i, int j)
{
  for (int k = 0; k < 3; ++k)
    if (onTriangleEdge(edgeOf, cornerOf, i, k) && onTriangleEdge(edgeOf, cornerOf, j, k))
      return k;
  return -1;
}

/// The features in the order the cut passes them: the shortest path
/// through all of them. A blade that crossed the whole triangle in one step
/// and also reached a tip, or snapped to a corner, passes three or more;
/// joining only two of them (as before) cut the third off as a fragment.
std::vector<int> featureChain(const std::vector<Vector3>& barycentric, std::vector<int> features)
{
  std::sort(features.begin(), features.end());
  std::vector<int> best = features;
  double shortest = std::numeric_limits<double>::infinity();
  do
  {
    double length = 0.0;
    for (std::size_t i = 0; i + 1 < features.size(); ++i)
      length += (barycentric[features[i]] - barycentric[features[i + 1]]).norm();
    if (length < shortest - 1e-12)
    {
      shortest = length;
      best = features;
    }
  } while (std::next_permutation(features.begin(), features.end()));
  return best;
}

/// Splits the polygon (of polygon positions) holding chord (i, j) in two.
void splitAlongChord(std::vector<std::vector<int>>& polygons, int i, int j)
{
  for (std::size_t p = 0; p < polygons.size(); ++p)
  {
    const std::vector<int> polygon = polygons[p];
    const auto at = std::find(polygon.begin(), polygon.end(), i);
    const auto to = std::find(polygon.begin(), polygon.end(), j);
    if (at == polygon.end() || to == polygon.end())
      continue;
    const int n = static_cast<int>(polygon.size());
    const int from = static_cast<int>(at - polygon.begin());
    const int until = static_cast<int>(to - polygon.begin());
    if ((from + 1) % n == until || (until + 1) % n == from)
      return; // already a side of a piece
    std::vector<int> first, second;
    for (int k = from;; k = (k + 1) % n)
    {
      first.push_back(polygon[k]);
      if (k == until)
        break;
    }
    for (int k = until;; k = (k + 1) % n)
    {
      second.push_back(polygon[k]);
      if (k == from)
        break;
    }
    polygons[p] = std::move(first);
    polygons.push_back(std::move(second));
    return;
  }
}

} // namespace

void CuttableCollisionMesh::recordCutAlongEdge(const TriangleFeatures& f,
  int i,
  int j,
  CollisionCutResult& result) const
{
  // The sides of the polygon between i and j along their edge (an edge
  // point inserted between them splits the edge in two).
  const int n = static_cast<int>(f.polygon.size());
  const int edge = sharedEdge(f.edgeOf, f.cornerOf, i, j);
  for (const int direction : { 1, n - 1 })
  {
    std::vector<std::array<int, 2>> sides;
    bool along = true;
    for (int k = i; k != j && along; k = (k + direction) % n)
    {
      const int next = (k + direction) % n;
      along = onTriangleEdge(f.edgeOf, f.cornerOf, next, edge);
      sides.push_back({ f.polygon[k], f.polygon[next] });
    }
    if (along)
    {
      result.cutEdges.insert(result.cutEdges.end(), sides.begin(), sides.end());
      return;
    }
  }
}

void CuttableCollisionMesh::splitTriangle(const TriangleFeatures& f, CollisionCutResult& result)
{
  const int n = static_cast<int>(f.polygon.size());
  // The cut joins the features in the order it passes them: chords across
  // the triangle split it, stretches along an edge only open it there.
  std::vector<std::vector<int>> polygons(1);
  for (int i = 0; i < n; ++i)
    polygons[0].push_back(i);
  const std::vector<int> chain = featureChain(f.barycentric, f.features);
  bool inner = false;
  for (std::size_t c = 0; c + 1 < chain.size(); ++c)
  {
    const int i = chain[c], j = chain[c + 1];
    if (sharedEdge(f.edgeOf, f.cornerOf, i, j) >= 0)
    {
      recordCutAlongEdge(f, i, j, result);
      continue;
    }
    result.cutEdges.push_back({ f.polygon[i], f.polygon[j] });
    splitAlongChord(polygons, i, j);
    inner = true;
  }
  if (n == 3 && !inner)
  {
    return; // a cut along an edge, or through a corner only
  }

  // Polygon in the triangle's plane (rest), counter-clockwise.
  const Triangle corners = Triangles[f.triangle];
  const Vector3 p0 = RestPositions[corners[0]];
  const Vector3 e1 = RestPositions[corners[1]] - p0;
  const Vector3 e2 = RestPositions[corners[2]] - p0;
  const Vector3 xAxis = e1.normalized();
  const Vector3 yAxis = e1.cross(e2).cross(e1).normalized();
  const std::array<Vector2, 3> planar = {
    Vector2::Zero(), Vector2(e1.norm(), 0.0), Vector2(e2.dot(xAxis), e2.dot(yAxis))
  };
  std::vector<Vector2> points(n);
  for (int i = 0; i < n; ++i)
  {
    points[i] = f.barycentric[i][0] * planar[0] + f.barycentric[i][1] * planar[1] +
                f.barycentric[i][2] * planar[2];
  }
  std::vector<std::array<int, 3>> pieces;
  for (const std::vector<int>& polygon : polygons)
    clipEars(points, polygon, pieces);

  CollisionTriangleSplit split;
  split.parent = f.triangle;
  split.parentCorners = corners;
  removeFromAdjacency(f.triangle);
  for (std::size_t p = 0; p < pieces.size(); ++p)
  {
    const Triangle piece{
      { f.polygon[pieces[p][0]], f.polygon[pieces[p][1]], f.polygon[pieces[p][2]] }
    };
    int index = f.triangle;
    if (p == 0)
    {
      Triangles[index] = piece;
    }
    else
    {
      index = static_cast<int>(Triangles.size());
      Triangles.push_back(piece);
      Halves.push_back(Halves[f.triangle]);
    }
    addToAdjacency(index);
    split.children.push_back(index);
    split.childCorners.push_back(
      { f.barycentric[pieces[p][0]], f.barycentric[pieces[p][1]], f.barycentric[pieces[p][2]] });
    result.changedTriangles.push_back(index);
  }
  result.splits.push_back(std::move(split));
}

template <typename Member>
UnionFind CuttableCollisionMesh::joinAcrossUncutEdges(int v,
  const std::vector<int>& fan,
  Member member) const
{
  UnionFind groups(fan.size());
  for (std::size_t i = 0; i < fan.size(); ++i)
  {
    for (int k = 0; k < 3 && member(fan[i]); ++k)
    {
      const int a = Triangles[fan[i]][k], b = Triangles[fan[i]][(k + 1) % 3];
      if ((a != v && b != v) || CutEdges.count(edgeKey(a, b)))
      {
        continue;
      }
      for (int other : trianglesOfEdge(a, b))
      {
        const auto found = std::find(fan.begin(), fan.end(), other);
        if (other >= 0 && other != fan[i] && found != fan.end() && member(other))
        {
          groups.unite(static_cast<int>(i), static_cast<int>(found - fan.begin()));
        }
      }
    }
  }
  return groups;
}

std::vector<int> CuttableCollisionMesh::fanBranches(int v, const std::vector<int>& fan) const
{
  // Through every other triangle of an uncut edge: a junction's three stay
  // one fan while their edge is uncut.
  UnionFind groups = joinAcrossUncutEdges(v, fan, [](int) { return true; });
  std::vector<int> branch(fan.size());
  for (std::size_t i = 0; i < fan.size(); ++i)
  {
    branch[i] = groups.find(static_cast<int>(i));
  }
  return branch;
}

// A junction vertex of a horizontal cleavage where the body and one leaf
// are notched (a bite's outline through the vertex) and the other leaf is
// whole: the whole leaf alone holds the notch's two sides together there,
// so the surface half the notched leaf shares with the body falls into two
// fans that touch at one point. No sheet mesh carries that (the visual cut
// would need two columns at one collision vertex), so the whole leaf is
// cut along one of its edges at the vertex: the shortest whose far end is
// inside the tissue (a crack, not a cut through). Returns that edge, or
// (-1, -1) where none is needed or none can serve.
std::array<int, 2> CuttableCollisionMesh::notchedJunctionCut(int v,
  const std::vector<int>& fan,
  const std::vector<int>& branch,
  SurfaceHalf half) const
{
  const std::array<int, 2> none{ { -1, -1 } };
  auto faces = [&](int t) { return Halves[t][0] == half || Halves[t][1] == half; };
  auto cleft = [&](int t)
  { return Halves[t][0] == SurfaceHalf::Cleft || Halves[t][1] == SurfaceHalf::Cleft; };
  if (!std::any_of(fan.begin(), fan.end(), cleft))
  {
    return none;
  }
  // Per branch, the first fan of this half met (branch labels are fan
  // indices): a second one in the same branch calls for the crack.
  UnionFind sides = joinAcrossUncutEdges(v, fan, faces);
  std::vector<int> firstSide(fan.size(), -1);
  for (std::size_t i = 0; i < fan.size(); ++i)
  {
    if (!faces(fan[i]))
    {
      continue;
    }
    const int side = sides.find(static_cast<int>(i));
    int& first = firstSide[static_cast<std::size_t>(branch[i])];
    if (first >= 0 && first != side)
    {
      return wholeLeafEdge(v, fan, branch, branch[i], faces);
    }
    first = side;
  }
  return none;
}

template <typename Faces>
std::array<int, 2> CuttableCollisionMesh::wholeLeafEdge(int v,
  const std::vector<int>& fan,
  const std::vector<int>& branch,
  int component,
  Faces faces) const
{
  std::array<int, 2> best{ { -1, -1 } };
  double bestLength = 0.0;
  bool bestInside = false;
  for (std::size_t i = 0; i < fan.size(); ++i)
  {
    if (branch[i] != component || faces(fan[i]))
    {
      continue;
    }
    for (int w : Triangles[fan[i]])
    {
      const auto onEdge = trianglesOfEdge(v, w);
      if (w == v || onEdge[1] < 0 || onEdge[2] >= 0 || faces(onEdge[0]) || faces(onEdge[1]) ||
          CutEdges.count(edgeKey(v, w)))
      {
        continue; // not an inner edge of the whole leaf
      }
      const bool inside = !onBorder(w);
      const double length = (RestPositions[w] - RestPositions[v]).norm();
      if (best[0] < 0 || (inside && !bestInside) || (inside == bestInside && length < bestLength))
      {
        best = { { std::min(v, w), std::max(v, w) } };
        bestLength = length;
        bestInside = inside;
      }
    }
  }
  return best;
}

bool CuttableCollisionMesh::onBorder(int w) const
{
  for (int t : VertexTriangles[w])
  {
    for (int k = 0; k < 3; ++k)
    {
      const int a = Triangles[t][k], b = Triangles[t][(k + 1) % 3];
      if ((a == w || b == w) && trianglesOfEdge(a, b)[1] < 0)
      {
        return true;
      }
    }
  }
  return false;
}

void CuttableCollisionMesh::openAlongCut(CollisionCutResult& result)
{
  std::vector<int> vertices;
  for (const auto& edge : result.cutEdges)
  {
    vertices.push_back(edge[0]);
    vertices.push_back(edge[1]);
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  // (Indices: the crack a notched junction needs appends its far end.)
  for (std::size_t next = 0; next < vertices.size(); ++next)
  {
    const int v = vertices[next];
    const std::vector<int> fan = VertexTriangles[v];
    if (fan.empty())
    {
      continue;
    }
    std::vector<int> branch = fanBranches(v, fan);
    for (const SurfaceHalf half : { SurfaceHalf::Negative, SurfaceHalf::Positive })
    {
      const std::array<int, 2> crack = notchedJunctionCut(v, fan, branch, half);
      if (crack[0] >= 0)
      {
        CutEdges.insert(edgeKey(crack[0], crack[1]));
        result.cutEdges.push_back(crack);
        vertices.push_back(crack[0] == v ? crack[1] : crack[0]);
        branch = fanBranches(v, fan);
      }
    }
    const int components = *std::max_element(branch.begin(), branch.end()) + 1;
    std::vector<int> copyOfRoot(static_cast<std::size_t>(components), -1);
    for (std::size_t i = 0; i < fan.size(); ++i)
    {
      const int root = branch[i];
      if (root == branch[0])
      {
        continue; // the first fan keeps the vertex
      }
      if (copyOfRoot[root] < 0)
      {
        copyOfRoot[root] = addVertex(RestPositions[v], Radii[v]);
        NewCollisionVertex made;
        made.vertex = copyOfRoot[root];
        made.duplicateOf = v;
        result.newVertices.push_back(made);
      }
      const int t = fan[i];
      removeFromAdjacency(t);
      std::replace(Triangles[t].begin(), Triangles[t].end(), v, copyOfRoot[root]);
      addToAdjacency(t);
      keepCutEdgesOfCopy(t, v, copyOfRoot[root]);
      result.changedTriangles.push_back(t);
    }
    if (std::any_of(copyOfRoot.begin(), copyOfRoot.end(), [](int c) { return c >= 0; }))
    {
      result.openedVertices.push_back(v);
    }
  }
  // Cut edges that opened are border edges now.
  for (auto it = CutEdges.begin(); it != CutEdges.end();)
  {
    const auto onEdge =
      trianglesOfEdge(static_cast<int>(*it >> 32), static_cast<int>(*it & 0xffffffffu));
    it = (onEdge[1] < 0) ? CutEdges.erase(it) : std::next(it);
  }
  // Each changed triangle once, ascending (splitting and opening both list them).
  auto& changed = result.changedTriangles;
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
}

void CuttableCollisionMesh::keepCutEdgesOfCopy(int t, int v, int copy)
{
  // A cut edge at v moved to the copy is cut still: the triangles left on
  // it (two leaves whose body was cut off along their junction edge, or
  // two sides a closed slit joins) must not be joined through it by the
  // fans of the vertices opened next, nor by a later cut's.
  for (int w : Triangles[t])
  {
    if (w != copy && CutEdges.count(edgeKey(v, w)))
    {
      CutEdges.insert(edgeKey(copy, w));
    }
  }
}

void CuttableCollisionMesh::updateTips(const std::vector<int>& sweepFeatures,
  const std::vector<int>& reachedTips,
  const std::vector<std::array<int, 2>>& sweepCutEdges)
{
  // The blade moves on: what it reached this time and left with at most
  // one cut edge is where the next blade continues (the tips it continued
  // from are behind it).
  Tips.clear();
  // Each cut edge once: the triangles on both of its sides list it.
  std::vector<std::array<int, 2>> edges = sweepCutEdges;
  for (auto& edge : edges)
  {
    if (edge[0] > edge[1])
      std::swap(edge[0], edge[1]);
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (int v : sweepFeatures)
  {
    int cutEdges = 0;
    for (const auto& edge : edges)
    {
      cutEdges += (edge[0] == v || edge[1] == v) ? 1 : 0;
    }
    if (cutEdges <= 1 && !VertexTriangles[v].empty())
    {
      Tips.insert(v);
    }
  }
  // A tip the blade reached again without cutting on from it (a blade
  // that moved less than to the next edge, or back) is still the tip.
  for (int v : reachedTips)
  {
    const bool left = std::any_of(
      edges.begin(), edges.end(), [v](const auto& edge) { return edge[0] == v || edge[1] == v; });
    if (!left && !VertexTriangles[v].empty())
    {
      Tips.insert(v);
    }
  }
}

CollisionCutResult CuttableCollisionMesh::cutAlongEdges(std::vector<std::array<int, 2>> edges)
{
  for (auto& edge : edges)
  {
    if (edge[0] > edge[1])
      std::swap(edge[0], edge[1]);
    if (edge[0] < 0 || edge[1] >= static_cast<int>(vertexCount()) ||
        trianglesOfEdge(edge[0], edge[1])[1] < 0)
    {
      throw InvalidInputError("cut of collision mesh '" + Name + "' along its edges: (" +
                              std::to_string(edge[0]) + ", " + std::to_string(edge[1]) +
                              ") is no edge between two of its triangles");
    }
  }
  CollisionCutResult result;
  for (const auto& edge : edges)
  {
    if (CutEdges.insert(edgeKey(edge[0], edge[1])).second)
      result.cutEdges.push_back(edge);
  }
  openAlongCut(result);
  return result;
}

CollisionCutResult CuttableCollisionMesh::cut(const Blade& blade,
  const std::vector<Vector3>& current,
  const CollisionCutSettings& settings)
{
  blade.validate("cut of collision mesh '" + Name + "'");
  if (current.size() != RestPositions.size())
  {
    throw InvalidInputError("cut of collision mesh '" + Name +
                            "': " + std::to_string(current.size()) + " current positions for " +
                            std::to_string(RestPositions.size()) + " vertices");
  }
  if (!(settings.snapFraction >= 0.0 && settings.snapFraction < 0.5))
  {
    throw InvalidInputError("cut of collision mesh '" + Name + "': snap fraction " +
                            std::to_string(settings.snapFraction) + " is not in [0, 0.5)");
  }
  CollisionCutResult result;
  const auto crossings = findCrossings(blade, current);
  if (crossings.empty())
  {
    return result;
  }
  const auto reached = collectFeatures(crossings, settings.snapFraction, result);
  std::vector<int> sweepFeatures, reachedTips;
  for (const auto& f : reached)
  {
    for (int i : f.features)
    {
      (Tips.count(f.polygon[i]) ? reachedTips : sweepFeatures).push_back(f.polygon[i]);
    }
    splitTriangle(f, result);
  }
  std::sort(sweepFeatures.begin(), sweepFeatures.end());
  sweepFeatures.erase(std::unique(sweepFeatures.begin(), sweepFeatures.end()), sweepFeatures.end());
  const std::vector<std::array<int, 2>> sweepCutEdges = result.cutEdges;
  // Keep the cut edges that lie inside the mesh (two triangles), once.
  std::vector<std::array<int, 2>> inside;
  for (auto edge : result.cutEdges)
  {
    if (edge[0] > edge[1])
      std::swap(edge[0], edge[1]);
    if (trianglesOfEdge(edge[0], edge[1])[1] >= 0 &&
        CutEdges.insert(edgeKey(edge[0], edge[1])).second)
    {
      inside.push_back(edge);
    }
  }
  result.cutEdges = inside;
  // Tips are found before opening: a copy made by opening is not a tip.
  updateTips(sweepFeatures, reachedTips, sweepCutEdges);
  openAlongCut(result);
  return result;
}

} // namespace thintissue
