// 5.3.4: the cut surface. Each opened collision edge carries a strip that
// joins its + and - visual paths (fig. 5-12); rows of vertices in between
// sit at the union of both paths' edge parameters (up-sampling), and the
// rows at the edge's ends belong to the collision vertex, so strips meeting
// there share them and the surface stays closed. A strip whose edge is cut
// again is split by comparing parameters (fig. 5-13).
#include "VisualMeshCut.h"
#include "VisualMeshCutPrivate.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace thintissue
{

namespace
{

constexpr double ColumnMerge = 1e-9; ///< of the edge's parameter

/// A point at edge parameter u on a path whose vertices have parameters
/// `at` (increasing).
Vector3 pointAt(const std::vector<Vector3>& positions,
  const std::vector<int>& path,
  const std::vector<double>& at,
  double u)
{
  std::size_t i = 0;
  while (i + 2 < path.size() && at[i + 1] <= u)
    ++i;
  const double span = at[i + 1] - at[i];
  const double s = span > 0.0 ? std::clamp((u - at[i]) / span, 0.0, 1.0) : 0.0;
  return (1.0 - s) * positions[path[i]] + s * positions[path[i + 1]];
}

/// Joins two rows running the same way along the edge (parameters
/// increasing): (a_i, a_i+1, b_j) or (a_i, b_j+1, b_j), whichever row's
/// next point comes first; triangles that repeat a vertex are left out.
void zipRows(const std::vector<int>& upper,
  const std::vector<double>& upperAt,
  const std::vector<int>& lower,
  const std::vector<double>& lowerAt,
  std::vector<Triangle>& out)
{
  std::size_t i = 0, j = 0;
  while (i + 1 < upper.size() || j + 1 < lower.size())
  {
    const bool advanceUpper =
      j + 1 >= lower.size() || (i + 1 < upper.size() && upperAt[i + 1] <= lowerAt[j + 1]);
    Triangle t = advanceUpper ? Triangle{ { upper[i], upper[i + 1], lower[j] } }
                              : Triangle{ { upper[i], lower[j + 1], lower[j] } };
    advanceUpper ? ++i : ++j;
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
      out.push_back(t);
  }
}

/// The cut surface's outward direction on collision edge (a, b): across
/// the edge in the plane of its triangle, away from the triangle's third
/// corner (rest configuration).
Vector3 outwardAcross(const CuttableCollisionMesh& collision, int a, int b)
{
  const int region = collision.trianglesOfEdge(a, b)[0];
  const Triangle& corners = collision.triangles()[region];
  const auto& rest = collision.restPositions();
  int third = corners[0];
  for (int c : corners)
    third = (c != a && c != b) ? c : third;
  const Vector3 along = rest[b] - rest[a];
  Vector3 outward = along.cross(along.cross(rest[third] - rest[a]));
  if (outward.dot(rest[third] - rest[a]) > 0.0)
    outward = -outward;
  return outward.normalized();
}

/// Where a smooth cut puts the vertex of row fraction s (0 at the + path,
/// 1 at the - path) at edge parameter u: between the two paths (5.3.4).
Vector3 betweenPaths(const std::vector<Vector3>& positions,
  const std::array<std::vector<int>, 2>& sides,
  const std::array<std::vector<double>, 2>& at,
  double u,
  double s)
{
  return (1.0 - s) * pointAt(positions, sides[1], at[1], u) +
         s * pointAt(positions, sides[0], at[0], u);
}

} // namespace

void CuttableVisualMesh::splitStrip(std::uint64_t key,
  int a,
  int b,
  int middle,
  double at,
  CutContext& context)
{
  CutStrip strip = std::move(Strips.at(key));
  Strips.erase(key);
  for (int t : strip.triangles)
    freeTriangle(t);
  CutStrip first, second;
  for (const auto& row : strip.rows)
  {
    std::vector<int> before, after;
    for (int w : row)
    {
      const double u = edgeParameter(w, a, b);
      if (u < at)
      {
        bindToEdge(w, a, middle, u / at, 0);
        before.push_back(w);
      }
      else
      {
        bindToEdge(w, middle, b, (u - at) / (1.0 - at), 0);
        after.push_back(w);
      }
      context.rebound.push_back(w);
    }
    std::reverse(after.begin(), after.end()); // (b, middle): from b, the lower
    first.rows.push_back(std::move(before));
    second.rows.push_back(std::move(after));
  }
  Strips[edgeKey(a, middle)] = std::move(first);
  Strips[edgeKey(b, middle)] = std::move(second);
}

const std::vector<int>& CuttableVisualMesh::endColumn(int collisionVertex, const Vector3& outward)
{
  auto [it, added] = EndColumns.emplace(collisionVertex, EndColumn{});
  std::vector<int>& column = it->second.vertices;
  if (!added)
    return column;
  const int minus = Paired[collisionVertex][0], plus = Paired[collisionVertex][1];
  const int rows = Settings.cutSurfaceRows;
  it->second.rim = minus == plus;
  for (int r = 0; r < rows; ++r)
  {
    if (minus == plus)
    {
      column.push_back(plus); // on the rim both sides meet
      continue;
    }
    const double s = static_cast<double>(r + 1) / (rows + 1);
    const int w = addVertexCopy(plus);
    Mesh.positions[w] = (1.0 - s) * Mesh.positions[plus] + s * Mesh.positions[minus];
    Mesh.positions[w] += jaggedOffset(Mesh.positions[w], outward);
    if (Mesh.hasNormals())
      Mesh.normals[w] = outward;
    Bindings[w].kind = BindingKind::CollisionVertex;
    Bindings[w].element = collisionVertex;
    Bindings[w].side = 0;
    Bindings[w].parameters = Vector3(1.0, 0.0, 0.0);
    column.push_back(w);
  }
  return column;
}

/// The part of an opened edge's path the cut surface joins: where two cuts
/// from one collision vertex share their first visual vertices (bound to
/// that vertex), the opening starts at the last of them.
std::vector<int> CuttableVisualMesh::openPart(const std::vector<int>& path, int a, int b) const
{
  auto boundTo = [&](int w, int c)
  { return Bindings[w].kind == BindingKind::CollisionVertex && Bindings[w].element == c; };
  std::size_t first = 0, last = path.size() - 1;
  while (first + 1 < last && boundTo(path[first + 1], a))
    ++first;
  while (last > first + 1 && boundTo(path[last - 1], b))
    --last;
  return std::vector<int>(path.begin() + static_cast<std::ptrdiff_t>(first),
    path.begin() + static_cast<std::ptrdiff_t>(last) + 1);
}

void CuttableVisualMesh::buildStrip(const CuttableCollisionMesh& collision,
  int a,
  int b,
  CutStrip& strip)
{
  for (int t : strip.triangles)
    freeTriangle(t);
  strip.triangles.clear();
  const int region = collision.trianglesOfEdge(a, b)[0];
  const Vector3 outward = outwardAcross(collision, a, b);
  const EdgePaths& paths = Paths.at(edgeKey(a, b));
  std::vector<std::vector<int>> rows;
  rows.push_back(openPart(paths.sides[1], a, b));
  for (std::size_t r = 0; r < strip.rows.size(); ++r)
  {
    std::vector<int> row{ endColumn(a, outward)[r] };
    row.insert(row.end(), strip.rows[r].begin(), strip.rows[r].end());
    for (int w : strip.rows[r])
      if (Mesh.hasNormals())
        Mesh.normals[w] = outward;
    row.push_back(endColumn(b, outward)[r]);
    rows.push_back(std::move(row));
  }
  rows.push_back(openPart(paths.sides[0], a, b));
  std::vector<std::vector<double>> at(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    at[r] = pathParameters(rows[r], a, b);
  std::vector<Triangle> triangles;
  for (std::size_t r = 0; r + 1 < rows.size(); ++r)
    zipRows(rows[r], at[r], rows[r + 1], at[r + 1], triangles);

  // Opposite to the + side's triangles along the path (the zip runs along
  // every row edge from lower to higher parameter).
  std::unordered_map<std::uint64_t, int> alongPath;
  for (std::size_t i = 0; i + 1 < rows[0].size(); ++i)
    alongPath.emplace(edgeKey(rows[0][i], rows[0][i + 1]), rows[0][i]);
  int forward = 0, backward = 0;
  for (int t : Regions[region][1])
  {
    const Triangle& face = Mesh.triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      const auto found = alongPath.find(edgeKey(face[k], face[(k + 1) % 3]));
      if (found != alongPath.end())
        (found->second == face[k] ? forward : backward) += 1;
    }
  }
  const bool flip = forward > backward;
  for (Triangle t : triangles)
  {
    if (flip)
      std::swap(t[1], t[2]);
    const int index = addTriangle(t, region, 0, VisualMaterial::CutSurface);
    if (Mesh.hasTextureCoordinates())
    {
      if (CutSurfaceTexture < 0)
      {
        CutSurfaceTexture = static_cast<int>(Mesh.textureCoordinates.size());
        Mesh.textureCoordinates.push_back(Vector2::Zero());
      }
      Mesh.textureCorners[index] = { { CutSurfaceTexture, CutSurfaceTexture, CutSurfaceTexture } };
    }
    strip.triangles.push_back(index);
  }
}

void CuttableVisualMesh::updateCutSurface(const CuttableCollisionMesh& collision,
  CutContext& context)
{
  std::vector<std::array<int, 2>> edges;
  for (int T : context.cut->changedTriangles)
  {
    const Triangle& tri = collision.triangles()[T];
    for (int k = 0; k < 3; ++k)
    {
      // The edge, and the edge it was copied from: the other lip of an
      // opened cut may lie in a triangle the cut did not change.
      const int x = tri[k], y = tri[(k + 1) % 3];
      for (const auto& [a, b] : { std::array<int, 2>{ { std::min(x, y), std::max(x, y) } },
             std::array<int, 2>{ { std::min(context.root(x), context.root(y)),
               std::max(context.root(x), context.root(y)) } } })
      {
        const auto lips = collision.trianglesOfEdge(a, b);
        if (lips[0] >= 0 && lips[1] < 0 && !Paths.at(edgeKey(a, b)).rim)
          edges.push_back({ { a, b } });
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const int rows = Settings.cutSurfaceRows;
  for (const auto& [a, b] : edges)
  {
    auto [it, added] = Strips.emplace(edgeKey(a, b), CutStrip{});
    CutStrip& strip = it->second;
    if (added)
    {
      // Up-sampling: the rows take the parameters of both sides.
      const EdgePaths& paths = Paths.at(edgeKey(a, b));
      std::array<std::vector<double>, 2> at;
      std::vector<double> all;
      for (int side = 0; side < 2; ++side)
      {
        at[side] = pathParameters(paths.sides[side], a, b);
        for (double t : at[side])
          if (t > ColumnMerge && t < 1.0 - ColumnMerge)
            all.push_back(t);
      }
      std::sort(all.begin(), all.end());
      // Both sides often share a parameter (up to round-off): one column.
      all.erase(
        std::unique(
          all.begin(), all.end(), [](double x, double y) { return std::abs(x - y) < ColumnMerge; }),
        all.end());
      strip.rows.resize(static_cast<std::size_t>(rows));
      const Vector3 outward = outwardAcross(collision, a, b);
      for (int r = 0; r < rows; ++r)
      {
        const double s = static_cast<double>(r + 1) / (rows + 1);
        for (double u : all)
        {
          const Vector3 smooth = betweenPaths(Mesh.positions, paths.sides, at, u, s);
          const int w = addVertexCopy(paths.sides[1][1]);
          Mesh.positions[w] = smooth + jaggedOffset(smooth, outward);
          bindToEdge(w, a, b, u, 0);
          strip.rows[r].push_back(w);
          context.newVertices.push_back(w);
        }
      }
    }
    const std::size_t before = Mesh.vertexCount();
    buildStrip(collision, a, b, strip);
    for (std::size_t w = before; w < Mesh.vertexCount(); ++w)
      context.newVertices.push_back(static_cast<int>(w));
    context.changedTriangles.insert(
      context.changedTriangles.end(), strip.triangles.begin(), strip.triangles.end());
  }
}

void CuttableVisualMesh::smoothPlaces(std::uint64_t key,
  const CutStrip& strip,
  std::vector<SmoothPlace>& places) const
{
  const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
  const EdgePaths& paths = Paths.at(key);
  const std::array<std::vector<double>, 2> at{ { pathParameters(paths.sides[0], a, b),
    pathParameters(paths.sides[1], a, b) } };
  const auto rows = static_cast<int>(strip.rows.size());
  for (int r = 0; r < rows; ++r)
  {
    const double s = static_cast<double>(r + 1) / (rows + 1);
    for (int w : strip.rows[r])
    {
      const double u = edgeParameter(w, a, b);
      places.push_back({ w, u, betweenPaths(Mesh.positions, paths.sides, at, u, s) });
    }
  }
  // The columns at the edge's ends (shared with the strips meeting there).
  for (const int end : { a, b })
  {
    const auto column = EndColumns.find(end);
    if (column == EndColumns.end() || column->second.rim)
      continue;
    const Vector3& plus = Mesh.positions[Paired[end][1]];
    const Vector3& minus = Mesh.positions[Paired[end][0]];
    const std::vector<int>& vertices = column->second.vertices;
    const auto count = static_cast<int>(vertices.size());
    for (int r = 0; r < count; ++r)
    {
      const double s = static_cast<double>(r + 1) / (count + 1);
      places.push_back({ vertices[r], end == a ? 0.0 : 1.0, (1.0 - s) * plus + s * minus });
    }
  }
}

} // namespace thintissue
