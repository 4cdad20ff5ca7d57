// Re-meshing of a surface along paths (thesis 5.2.3, fig. 5-4): straight
// paths built by intersecting segments with the mesh edges (no geodesics)
// on flat grids and on the faces of the closed thin sheet; geometry,
// topology, texture seams, normals and attributes, shared points, invalid
// input, determinism, and a thesis-sized sheet.
#include "MeshValidation.h"
#include "PathRemeshing.h"
#include "ThinSheetModel.h"
#include "ThinTissueError.h"
#include "TriangleMeshAdjacency.h"

#include "BindingTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

using namespace thintissue;

namespace
{

using thintissue::testing::Random;
using thintissue::testing::vertexAt;

int gridIndex(int cellsX, int i, int j)
{
  return j * (cellsX + 1) + i;
}

/// A flat (z = 0) grid of cellsX x cellsY unit cells, counter-clockwise from
/// +z. `seed` 0: every cell split along its diagonal from (i, j) to
/// (i + 1, j + 1); otherwise random diagonals and inner vertices moved by up
/// to `jitter` in x and y. Texture coordinates (per corner, one per vertex),
/// unit normals leaning with the position, and the point attributes
/// "Linear" (x + 2 y) and "Vector" (3 components).
TriangleMesh gridPlane(int cellsX, int cellsY, double jitter, std::uint64_t seed)
{
  TriangleMesh mesh;
  mesh.name = "grid plane";
  Random random(seed);
  for (int j = 0; j <= cellsY; ++j)
  {
    for (int i = 0; i <= cellsX; ++i)
    {
      Vector3 p(i, j, 0.0);
      if (seed != 0 && jitter > 0.0 && i > 0 && j > 0 && i < cellsX && j < cellsY)
      {
        p.x() += jitter * (2.0 * random.unit() - 1.0);
        p.y() += jitter * (2.0 * random.unit() - 1.0);
      }
      mesh.positions.push_back(p);
      mesh.textureCoordinates.emplace_back(p.x() / cellsX, p.y() / cellsY);
      mesh.normals.push_back(Vector3(0.1 * p.x(), -0.05 * p.y(), 1.0).normalized());
    }
  }
  for (int j = 0; j < cellsY; ++j)
  {
    for (int i = 0; i < cellsX; ++i)
    {
      const int a = gridIndex(cellsX, i, j);
      const int b = gridIndex(cellsX, i + 1, j);
      const int c = gridIndex(cellsX, i + 1, j + 1);
      const int d = gridIndex(cellsX, i, j + 1);
      if (seed == 0 || random.below(2) == 0)
      {
        mesh.triangles.push_back({ a, b, c });
        mesh.triangles.push_back({ a, c, d });
      }
      else
      {
        mesh.triangles.push_back({ a, b, d });
        mesh.triangles.push_back({ b, c, d });
      }
    }
  }
  mesh.textureCorners = mesh.triangles;
  std::vector<double> linear;
  std::vector<double> vector;
  for (const Vector3& p : mesh.positions)
  {
    linear.push_back(p.x() + 2.0 * p.y());
    vector.insert(vector.end(), { p.x(), p.y() * p.y(), 3.0 });
  }
  mesh.pointAttributes.set("Linear", 1, linear);
  mesh.pointAttributes.set("Vector", 3, vector);
  return mesh;
}

double cross2(const Vector2& a, const Vector2& b)
{
  return a.x() * b.y() - a.y() * b.x();
}

/// The points where the straight segment from `from` to `to` meets the
/// vertices and edges of the triangles `subset` of a planar piece of `mesh`
/// (projected on the coordinate axes `u` and `v`), strictly between its
/// ends, ordered from `from`: vertices on the segment, and crossings of the
/// other edges.
std::vector<SurfacePoint> crossings(const TriangleMesh& mesh,
  const std::vector<int>& subset,
  const Vector3& from,
  const Vector3& to,
  int u,
  int v)
{
  auto flat = [&](const Vector3& p) { return Vector2(p[u], p[v]); };
  const Vector2 start = flat(from);
  const Vector2 direction = flat(to) - start;
  const double length = direction.norm();
  std::set<int> vertices;
  std::set<std::pair<int, int>> edges;
  for (int t : subset)
  {
    const Triangle& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      vertices.insert(tri[k]);
      const int a = tri[k];
      const int b = tri[(k + 1) % 3];
      edges.insert({ std::min(a, b), std::max(a, b) });
    }
  }
  constexpr double ends = 1e-9;
  std::vector<std::pair<double, SurfacePoint>> events;
  std::set<int> onLine;
  for (int vertex : vertices)
  {
    const Vector2 w = flat(mesh.positions[vertex]) - start;
    if (std::abs(cross2(direction, w)) <= 1e-10 * length * length)
    {
      onLine.insert(vertex);
      const double s = direction.dot(w) / (length * length);
      if (s > ends && s < 1.0 - ends)
      {
        events.emplace_back(s, SurfacePoint::atVertex(vertex));
      }
    }
  }
  for (const auto& [a, b] : edges)
  {
    if (onLine.count(a) != 0 || onLine.count(b) != 0)
    {
      continue;
    }
    const Vector2 e = flat(mesh.positions[b]) - flat(mesh.positions[a]);
    const double denominator = cross2(direction, e);
    if (std::abs(denominator) < 1e-14 * length * e.norm())
    {
      continue;
    }
    const Vector2 w = flat(mesh.positions[a]) - start;
    const double s = cross2(w, e) / denominator;
    const double t = cross2(w, direction) / denominator;
    if (t > 0.0 && t < 1.0 && s > ends && s < 1.0 - ends)
    {
      events.emplace_back(s, SurfacePoint::onEdge(a, b, t));
    }
  }
  std::sort(
    events.begin(), events.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<SurfacePoint> points;
  for (const auto& event : events)
  {
    points.push_back(event.second);
  }
  return points;
}

/// The straight path between two surface points (vertices or points on
/// edges) over the planar triangles `subset` (projected on axes u, v).
SurfacePath segmentPath(const TriangleMesh& mesh,
  const std::vector<int>& subset,
  const SurfacePoint& from,
  const SurfacePoint& to,
  int u = 0,
  int v = 1)
{
  const Vector3 start = from.position(mesh.positions);
  const Vector3 end = to.position(mesh.positions);
  SurfacePath path;
  path.points.push_back(from);
  for (const SurfacePoint& point : crossings(mesh, subset, start, end, u, v))
  {
    path.points.push_back(point);
  }
  path.points.push_back(to);
  path.length = (end - start).norm();
  return path;
}

/// The straight path from vertex a to vertex b.
SurfacePath straightPath(const TriangleMesh& mesh,
  const std::vector<int>& subset,
  int a,
  int b,
  int u = 0,
  int v = 1)
{
  return segmentPath(mesh, subset, SurfacePoint::atVertex(a), SurfacePoint::atVertex(b), u, v);
}

std::vector<int> allTriangles(const TriangleMesh& mesh)
{
  std::vector<int> all(mesh.triangleCount());
  for (std::size_t t = 0; t < all.size(); ++t)
  {
    all[t] = static_cast<int>(t);
  }
  return all;
}

/// Triangles whose three vertices satisfy `inside`.
template <typename Predicate>
std::vector<int> trianglesWhere(const TriangleMesh& mesh, Predicate inside)
{
  std::vector<int> subset;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const Triangle& tri = mesh.triangles[t];
    if (inside(mesh.positions[tri[0]]) && inside(mesh.positions[tri[1]]) &&
        inside(mesh.positions[tri[2]]))
    {
      subset.push_back(static_cast<int>(t));
    }
  }
  return subset;
}

/// Barycentric coordinates of p in triangle (a, b, c) after projection on
/// its plane, and p's distance to that plane.
std::pair<Vector3, double> barycentric(const Vector3& a,
  const Vector3& b,
  const Vector3& c,
  const Vector3& p)
{
  const Vector3 e1 = b - a;
  const Vector3 e2 = c - a;
  const Vector3 w = p - a;
  const Vector3 n = e1.cross(e2);
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double w1 = w.dot(e1), w2 = w.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  const double l1 = (d22 * w1 - d12 * w2) / det;
  const double l2 = (d11 * w2 - d12 * w1) / det;
  return { Vector3(1.0 - l1 - l2, l1, l2), std::abs(w.dot(n)) / n.norm() };
}

double scaleOf(const TriangleMesh& mesh)
{
  return mesh.boundingBox().diagonal().norm();
}

/// An inserted vertex x at barycentric `lambda` in input triangle `parent`:
/// its normal and point attributes interpolated from the parent's corners.
::testing::AssertionResult insertedVertexIsInterpolated(const TriangleMesh& input,
  const TriangleMesh& mesh,
  int parent,
  int x,
  const Vector3& lambda)
{
  const Triangle& p = input.triangles[parent];
  // Inserted vertices lie on an edge of the parent: interpolation.
  if (input.hasNormals())
  {
    const Vector3 expected = (lambda[0] * input.normals[p[0]] + lambda[1] * input.normals[p[1]] +
                              lambda[2] * input.normals[p[2]])
                               .normalized();
    if ((mesh.normals[x] - expected).norm() > 1e-9 ||
        std::abs(mesh.normals[x].norm() - 1.0) > 1e-14)
    {
      return ::testing::AssertionFailure() << "normal of vertex " << x << " not interpolated";
    }
  }
  for (const std::string& name : input.pointAttributes.names())
  {
    const AttributeArray& in = input.pointAttributes.get(name);
    const AttributeArray& out = mesh.pointAttributes.get(name);
    for (int component = 0; component < in.components; ++component)
    {
      double expected = 0.0;
      double size = 0.0;
      for (int corner = 0; corner < 3; ++corner)
      {
        expected += lambda[corner] * in.element(p[corner])[component];
        size = std::max(size, std::abs(in.element(p[corner])[component]));
      }
      if (std::abs(out.element(x)[component] - expected) > 1e-12 * std::max(1.0, size))
      {
        return ::testing::AssertionFailure()
               << "attribute " << name << " of vertex " << x << " not interpolated";
      }
    }
  }
  return ::testing::AssertionSuccess();
}

/// insertPaths' result keeps the input: consistent, sizes and kept data
/// alike, old vertices and texture coordinates unchanged, vertex origins.
::testing::AssertionResult keepsTheInput(const TriangleMesh& input, const RemeshedSurface& result)
{
  const TriangleMesh& mesh = result.mesh;
  try
  {
    mesh.checkConsistency();
  }
  catch (const Error& error)
  {
    return ::testing::AssertionFailure() << error.what();
  }
  const std::size_t oldVertices = input.vertexCount();
  if (mesh.vertexCount() < oldVertices || result.inputVertex.size() != mesh.vertexCount() ||
      result.inputTriangle.size() != mesh.triangleCount() ||
      mesh.triangleCount() < input.triangleCount() ||
      mesh.hasTextureCoordinates() != input.hasTextureCoordinates() ||
      mesh.hasNormals() != input.hasNormals() || mesh.name != input.name)
  {
    return ::testing::AssertionFailure() << "sizes or kept data differ";
  }
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
  {
    const int expected = v < oldVertices ? static_cast<int>(v) : -1;
    if (result.inputVertex[v] != expected)
    {
      return ::testing::AssertionFailure() << "inputVertex[" << v << "] is wrong";
    }
    if (v < oldVertices &&
        (std::memcmp(mesh.positions[v].data(), input.positions[v].data(), sizeof(Vector3)) != 0 ||
          (input.hasNormals() &&
            std::memcmp(mesh.normals[v].data(), input.normals[v].data(), sizeof(Vector3)) != 0)))
    {
      return ::testing::AssertionFailure() << "old vertex " << v << " changed";
    }
  }
  for (std::size_t i = 0; i < input.textureCoordinates.size(); ++i)
  {
    if (mesh.textureCoordinates[i] != input.textureCoordinates[i])
    {
      return ::testing::AssertionFailure() << "old texture coordinate " << i << " changed";
    }
  }
  return ::testing::AssertionSuccess();
}

/// Every triangle non-degenerate, inside its parent in the documented order
/// and facing the same way, texture coordinates and inserted vertices
/// interpolated, untouched triangles in place, parents' areas covered.
::testing::AssertionResult childrenAreFaithful(const TriangleMesh& input,
  const RemeshedSurface& result)
{
  const TriangleMesh& mesh = result.mesh;
  const double scale = scaleOf(input);
  const double tolerance = 1e-12 * scale;
  const std::size_t oldVertices = input.vertexCount();
  // Documented order: triangle t < input count comes from input triangle t,
  // the others from increasing input triangles.
  std::vector<int> children(input.triangleCount(), 0);
  std::vector<double> childArea(input.triangleCount(), 0.0);
  std::vector<bool> used(mesh.vertexCount(), false);
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const int parent = result.inputTriangle[t];
    if (t < input.triangleCount()
          ? parent != static_cast<int>(t)
          : (parent < 0 || parent >= static_cast<int>(input.triangleCount()) ||
              (t > input.triangleCount() && parent < result.inputTriangle[t - 1])))
    {
      return ::testing::AssertionFailure()
             << "triangle " << t << " has parent " << parent << " against the documented order";
    }
    ++children[parent];
    const double area = mesh.triangleArea(t);
    childArea[parent] += area;
    if (!(area > 1e-12 * scale * scale))
    {
      return ::testing::AssertionFailure()
             << "triangle " << t << " is degenerate (area " << area << ")";
    }
    if (mesh.triangleNormal(t).dot(input.triangleNormal(parent)) < 1.0 - 1e-9)
    {
      return ::testing::AssertionFailure() << "triangle " << t << " does not face like its parent";
    }
    const Triangle& p = input.triangles[parent];
    const Vector3& a = input.positions[p[0]];
    const Vector3& b = input.positions[p[1]];
    const Vector3& c = input.positions[p[2]];
    for (int k = 0; k < 3; ++k)
    {
      const int x = mesh.triangles[t][k];
      used[x] = true;
      const auto [lambda, distance] = barycentric(a, b, c, mesh.positions[x]);
      if (distance > tolerance || lambda.minCoeff() < -1e-12)
      {
        return ::testing::AssertionFailure()
               << "vertex " << x << " of triangle " << t << " is not inside its parent " << parent;
      }
      if (input.hasTextureCoordinates())
      {
        const Triangle& uv = input.textureCorners[parent];
        const Vector2 expected = lambda[0] * input.textureCoordinates[uv[0]] +
                                 lambda[1] * input.textureCoordinates[uv[1]] +
                                 lambda[2] * input.textureCoordinates[uv[2]];
        if ((mesh.textureCoordinates[mesh.textureCorners[t][k]] - expected).norm() > 1e-12)
        {
          return ::testing::AssertionFailure() << "corner " << k << " of triangle " << t
                                               << ": texture coordinates not interpolated";
        }
      }
      if (x < static_cast<int>(oldVertices))
      {
        continue;
      }
      const auto interpolated = insertedVertexIsInterpolated(input, mesh, parent, x, lambda);
      if (!interpolated)
      {
        return interpolated;
      }
    }
  }
  for (std::size_t t = 0; t < input.triangleCount(); ++t)
  {
    if (children[t] == 1 && mesh.triangles[t] != input.triangles[t])
    {
      return ::testing::AssertionFailure() << "untouched triangle " << t << " changed";
    }
    if (std::abs(childArea[t] - input.triangleArea(t)) > 1e-12 * input.triangleArea(t))
    {
      return ::testing::AssertionFailure()
             << "the pieces of triangle " << t << " do not cover its area";
    }
  }
  for (std::size_t v = oldVertices; v < mesh.vertexCount(); ++v)
  {
    if (!used[v])
    {
      return ::testing::AssertionFailure() << "inserted vertex " << v << " is in no triangle";
    }
  }
  if (std::abs(mesh.surfaceArea() - input.surfaceArea()) > 1e-12 * input.surfaceArea())
  {
    return ::testing::AssertionFailure() << "the area changed";
  }
  return ::testing::AssertionSuccess();
}

/// Paths: one vertex list each, consecutive vertices distinct and joined by
/// an edge, on the input path, with its ends.
::testing::AssertionResult pathsAreFaithful(const TriangleMesh& input,
  const std::vector<SurfacePath>& paths,
  const RemeshedSurface& result)
{
  const TriangleMesh& mesh = result.mesh;
  const double scale = scaleOf(input);
  // Paths: consecutive vertices distinct and joined by an edge, on the path.
  const TriangleMeshAdjacency adjacency(mesh);
  if (result.pathVertices.size() != paths.size())
  {
    return ::testing::AssertionFailure() << "one vertex list per path expected";
  }
  for (std::size_t p = 0; p < paths.size(); ++p)
  {
    const auto& vertices = result.pathVertices[p];
    const auto& points = paths[p].points;
    if (points.empty() != vertices.empty())
    {
      return ::testing::AssertionFailure() << "path " << p << ": empty or not";
    }
    if (points.empty())
    {
      continue;
    }
    if ((mesh.positions[vertices.front()] - points.front().position(input.positions)).norm() >
          1e-9 * scale ||
        (mesh.positions[vertices.back()] - points.back().position(input.positions)).norm() >
          1e-9 * scale)
    {
      return ::testing::AssertionFailure() << "path " << p << " has the wrong ends";
    }
    for (std::size_t i = 0; i < vertices.size(); ++i)
    {
      if (i > 0 &&
          (vertices[i] == vertices[i - 1] || adjacency.findEdge(vertices[i - 1], vertices[i]) < 0))
      {
        return ::testing::AssertionFailure()
               << "path " << p << ": vertices " << vertices[i - 1] << " and " << vertices[i]
               << " are not joined by an edge";
      }
      // On the polyline of the input points (merging moves by <= 1e-9).
      double nearest = std::numeric_limits<double>::infinity();
      const Vector3& x = mesh.positions[vertices[i]];
      for (std::size_t k = 0; k < points.size(); ++k)
      {
        const Vector3 q = points[k].position(input.positions);
        nearest = std::min(nearest, (x - q).norm());
        if (k > 0)
        {
          const Vector3 r = points[k - 1].position(input.positions);
          const double s = std::clamp((x - r).dot(q - r) / (q - r).squaredNorm(), 0.0, 1.0);
          nearest = std::min(nearest, (x - (r + s * (q - r))).norm());
        }
      }
      if (nearest > 1e-9 * scale)
      {
        return ::testing::AssertionFailure()
               << "path " << p << ": vertex " << vertices[i] << " is off the path";
      }
    }
  }
  return ::testing::AssertionSuccess();
}

/// Everything insertPaths promises about its result, for any input:
/// indices, untouched triangles in place, every triangle non-degenerate,
/// inside its parent and facing the same way, parents' areas kept, old
/// vertices unchanged, texture coordinates / normals / attributes
/// interpolated from the parent, consecutive path vertices joined by edges
/// and lying on the input paths.
::testing::AssertionResult isFaithfulRemeshing(const TriangleMesh& input,
  const std::vector<SurfacePath>& paths,
  const RemeshedSurface& result)
{
  auto faithful = keepsTheInput(input, result);
  if (faithful)
    faithful = childrenAreFaithful(input, result);
  if (faithful)
    faithful = pathsAreFaithful(input, paths, result);
  return faithful;
}

::testing::AssertionResult isClosedOriented(const TriangleMesh& mesh)
{
  const MeshValidationReport report = validateTriangleMesh(mesh);
  if (!report.isClosedManifold() || report.inconsistentlyOrientedEdges.count != 0 ||
      report.borderEdges.count != 0 || report.nonManifoldEdges.count != 0 ||
      report.nonManifoldVertices.count != 0 || report.degenerateTriangles.count != 0)
  {
    return ::testing::AssertionFailure() << report.toString();
  }
  return ::testing::AssertionSuccess();
}

std::size_t countThrough(const RemeshedSurface& result, int vertex)
{
  std::size_t count = 0;
  for (const auto& path : result.pathVertices)
  {
    count += std::count(path.begin(), path.end(), vertex);
  }
  return count;
}

/// A small closed thin sheet with texture coordinates and normals.
TriangleMesh smallSheet()
{
  ThinSheetParameters parameters;
  parameters.visualCellsX = 12;
  parameters.visualCellsY = 10;
  return makeThinSheet(parameters).visual;
}

// ---------------------------------------------------------------------------

TEST(PathRemeshing, StraightPathsAcrossAJitteredGrid)
{
  const TriangleMesh grid = gridPlane(12, 10, 0.25, 7);
  const auto all = allTriangles(grid);
  std::vector<SurfacePath> paths{
    straightPath(grid, all, gridIndex(12, 0, 1), gridIndex(12, 12, 7)),
    straightPath(grid, all, gridIndex(12, 0, 3), gridIndex(12, 12, 9)),
    straightPath(grid, all, gridIndex(12, 2, 0), gridIndex(12, 7, 2)),
  };
  std::size_t edgePoints = 0;
  for (const auto& path : paths)
  {
    ASSERT_GT(path.points.size(), 4u);
    for (const auto& point : path.points)
    {
      edgePoints += point.isVertex() ? 0 : 1;
    }
  }
  const RemeshedSurface result = insertPaths(grid, paths);
  EXPECT_TRUE(isFaithfulRemeshing(grid, paths, result));
  // Distinct crossings (the paths do not meet): one vertex each.
  EXPECT_EQ(result.mesh.vertexCount(), grid.vertexCount() + edgePoints);
  for (std::size_t p = 0; p < paths.size(); ++p)
  {
    EXPECT_EQ(result.pathVertices[p].size(), paths[p].points.size());
  }
  // Each path point is its vertex: old ones by index, new ones in place.
  for (std::size_t p = 0; p < paths.size(); ++p)
  {
    for (std::size_t i = 0; i < paths[p].points.size(); ++i)
    {
      const SurfacePoint& point = paths[p].points[i];
      const int v = result.pathVertices[p][i];
      if (point.isVertex())
      {
        EXPECT_EQ(v, point.vertex);
      }
      else
      {
        EXPECT_GE(v, static_cast<int>(grid.vertexCount()));
        EXPECT_LE((result.mesh.positions[v] - point.position(grid.positions)).norm(), 1e-14);
      }
    }
  }
  const MeshValidationReport report = validateTriangleMesh(result.mesh);
  EXPECT_EQ(report.degenerateTriangles.count, 0u);
  EXPECT_EQ(report.inconsistentlyOrientedEdges.count, 0u);
  EXPECT_EQ(report.nonManifoldEdges.count, 0u);
  EXPECT_EQ(report.connectedComponents, 1u);
}

TEST(PathRemeshing, ClosedSheetStaysAnOrientedManifold)
{
  const TriangleMesh sheet = smallSheet();
  ASSERT_TRUE(isClosedOriented(sheet));
  const double top = 1.0;
  const double right = 50.0;
  auto near = [](double a, double b) { return std::abs(a - b) < 1e-9; };
  const auto topFace = trianglesWhere(sheet, [&](const Vector3& p) { return near(p.z(), top); });
  const auto rightFace =
    trianglesWhere(sheet, [&](const Vector3& p) { return near(p.x(), right); });
  ASSERT_FALSE(topFace.empty());
  ASSERT_FALSE(rightFace.empty());

  // Across the top face.
  std::vector<SurfacePath> paths{ straightPath(sheet,
    topFace,
    vertexAt(sheet, Vector3(-40.0, -30.0, top)),
    vertexAt(sheet, Vector3(30.0, 40.0, top))) };
  // Over the rim: top face to a point on the top-right border edge, then
  // down the right face to a bottom vertex.
  const int a = vertexAt(sheet, Vector3(right, 0.0, top));
  const int b = vertexAt(sheet, Vector3(right, 10.0, top));
  ASSERT_NEAR(sheet.positions[b].y() - sheet.positions[a].y(), 10.0, 1e-9);
  const SurfacePoint rim = SurfacePoint::onEdge(a, b, 0.37);
  const Vector3 rimPoint = rim.position(sheet.positions);
  const int start = vertexAt(sheet, Vector3(10.0, -20.0, top));
  const int end = vertexAt(sheet, Vector3(right, 30.0, -top));
  SurfacePath overRim;
  overRim.points.push_back(SurfacePoint::atVertex(start));
  for (const auto& point : crossings(sheet, topFace, sheet.positions[start], rimPoint, 0, 1))
  {
    overRim.points.push_back(point);
  }
  overRim.points.push_back(rim);
  for (const auto& point : crossings(sheet, rightFace, rimPoint, sheet.positions[end], 1, 2))
  {
    overRim.points.push_back(point);
  }
  overRim.points.push_back(SurfacePoint::atVertex(end));
  paths.push_back(overRim);

  const RemeshedSurface result = insertPaths(sheet, paths);
  EXPECT_GT(result.mesh.vertexCount(), sheet.vertexCount() + 10);
  EXPECT_TRUE(isFaithfulRemeshing(sheet, paths, result));
  EXPECT_TRUE(isClosedOriented(result.mesh));
  EXPECT_NEAR(result.mesh.signedVolume(), sheet.signedVolume(), 1e-12 * sheet.signedVolume());
  // The rim point split the edge for both triangles beside it (closedness
  // checks that too): its vertex is in a top and in a side triangle.
  const int rimVertex = vertexAt(result.mesh, rimPoint);
  EXPECT_GE(rimVertex, static_cast<int>(sheet.vertexCount()));
  EXPECT_EQ(countThrough(result, rimVertex), 1u);
  EXPECT_LE((result.mesh.positions[rimVertex] - rimPoint).norm(), 1e-13);
  std::set<int> parents;
  for (std::size_t t = 0; t < result.mesh.triangleCount(); ++t)
  {
    const Triangle& tri = result.mesh.triangles[t];
    if (std::find(tri.begin(), tri.end(), rimVertex) != tri.end())
    {
      parents.insert(result.inputTriangle[t]);
    }
  }
  EXPECT_EQ(parents.size(), 2u);
}

// ---------------------------------------------------------------------------

TEST(PathRemeshing, PathsCrossingAnEdgeAtTheSamePointShareOneVertex)
{
  const TriangleMesh grid = gridPlane(6, 4, 0.0, 0);
  const auto all = allTriangles(grid);
  // y = x / 4 and y = 1 - x / 4 meet at (2, 0.5) on the edge x = 2.
  std::vector<SurfacePath> paths{
    straightPath(grid, all, gridIndex(6, 0, 0), gridIndex(6, 4, 1)),
    straightPath(grid, all, gridIndex(6, 0, 1), gridIndex(6, 4, 0)),
  };
  const RemeshedSurface exact = insertPaths(grid, paths);
  EXPECT_TRUE(isFaithfulRemeshing(grid, paths, exact));
  const int meeting = vertexAt(exact.mesh, Vector3(2.0, 0.5, 0.0));
  ASSERT_EQ(exact.mesh.positions[meeting], Vector3(2.0, 0.5, 0.0));
  EXPECT_EQ(countThrough(exact, meeting), 2u);
  std::size_t edgePoints = 0;
  for (const auto& path : paths)
  {
    for (const auto& point : path.points)
    {
      edgePoints += point.isVertex() ? 0 : 1;
    }
  }
  EXPECT_EQ(exact.mesh.vertexCount(), grid.vertexCount() + edgePoints - 1);

  // Parameters a hair apart (below the tolerance) still make one vertex; a
  // larger gap makes two, and the paths then cross inside a triangle.
  for (const double shift : { 3e-10, -3e-10, 5e-9 })
  {
    std::vector<SurfacePath> moved = paths;
    for (SurfacePoint& point : moved[1].points)
    {
      if (!point.isVertex() && point.position(grid.positions).x() == 2.0)
      {
        point.edgeParameter += shift;
      }
    }
    if (std::abs(shift) < 1e-9)
    {
      const RemeshedSurface result = insertPaths(grid, moved);
      EXPECT_TRUE(isFaithfulRemeshing(grid, moved, result));
      EXPECT_EQ(result.mesh.vertexCount(), exact.mesh.vertexCount());
      EXPECT_EQ(countThrough(result, vertexAt(result.mesh, Vector3(2.0, 0.5, 0.0))), 2u);
    }
    else
    {
      EXPECT_THROW(insertPaths(grid, moved), InvalidInputError);
    }
  }
}

TEST(PathRemeshing, PathsMeetingAtAVertex)
{
  const TriangleMesh grid = gridPlane(4, 4, 0.0, 0);
  const auto all = allTriangles(grid);
  // Along the diagonals (edges only), and across them through (2, 2).
  std::vector<SurfacePath> paths{
    straightPath(grid, all, gridIndex(4, 0, 0), gridIndex(4, 4, 4)),
    straightPath(grid, all, gridIndex(4, 0, 4), gridIndex(4, 4, 0)),
    // Two more from the ends of those to one vertex between them.
    straightPath(grid, all, gridIndex(4, 4, 4), gridIndex(4, 3, 2)),
    straightPath(grid, all, gridIndex(4, 4, 0), gridIndex(4, 3, 2)),
  };
  for (const auto& point : paths[0].points)
  {
    ASSERT_TRUE(point.isVertex());
  }
  const RemeshedSurface result = insertPaths(grid, paths);
  EXPECT_TRUE(isFaithfulRemeshing(grid, paths, result));
  EXPECT_EQ(result.pathVertices[0],
    (std::vector<int>{ gridIndex(4, 0, 0),
      gridIndex(4, 1, 1),
      gridIndex(4, 2, 2),
      gridIndex(4, 3, 3),
      gridIndex(4, 4, 4) }));
  EXPECT_EQ(countThrough(result, gridIndex(4, 2, 2)), 2u);
  EXPECT_EQ(countThrough(result, gridIndex(4, 3, 2)), 2u);
  EXPECT_EQ(countThrough(result, gridIndex(4, 4, 4)), 2u);
  EXPECT_EQ(countThrough(result, gridIndex(4, 4, 0)), 2u);
}

TEST(PathRemeshing, PathsRunningAlongTheSameEdge)
{
  const TriangleMesh grid = gridPlane(4, 3, 0.0, 0);
  const auto all = allTriangles(grid);
  const int p11 = gridIndex(4, 1, 1);
  const int p21 = gridIndex(4, 2, 1);
  const int p22 = gridIndex(4, 2, 2);
  std::vector<SurfacePath> paths{
    // Along the grid line y = 1 (vertices only).
    straightPath(grid, all, gridIndex(4, 0, 1), gridIndex(4, 4, 1)),
    // y = 2 x / 3 crosses it inside edge (1, 1)-(2, 1) at 0.5.
    straightPath(grid, all, gridIndex(4, 0, 0), gridIndex(4, 3, 2)),
  };
  // Along the edge from (1, 1) to the crossing, then across to (2, 2).
  SurfacePath along;
  along.points = {
    SurfacePoint::atVertex(p11), SurfacePoint::onEdge(p11, p21, 0.5), SurfacePoint::atVertex(p22)
  };
  paths.push_back(along);
  // Along the whole edge from (2, 1) to (1, 1), given by its end points.
  SurfacePath whole;
  whole.points = { SurfacePoint::atVertex(p21), SurfacePoint::atVertex(p11) };
  paths.push_back(whole);
  ASSERT_EQ(paths[0].points.size(), 5u);

  const RemeshedSurface result = insertPaths(grid, paths);
  EXPECT_TRUE(isFaithfulRemeshing(grid, paths, result));
  const int middle = vertexAt(result.mesh, Vector3(1.5, 1.0, 0.0));
  ASSERT_EQ(result.mesh.positions[middle], Vector3(1.5, 1.0, 0.0));
  ASSERT_GE(middle, static_cast<int>(grid.vertexCount()));
  // The path along y = 1 now visits the inserted vertex.
  EXPECT_EQ(result.pathVertices[0],
    (std::vector<int>{
      gridIndex(4, 0, 1), p11, middle, p21, gridIndex(4, 3, 1), gridIndex(4, 4, 1) }));
  EXPECT_EQ(result.pathVertices[2], (std::vector<int>{ p11, middle, p22 }));
  EXPECT_EQ(result.pathVertices[3], (std::vector<int>{ p21, middle, p11 }));
  EXPECT_EQ(countThrough(result, middle), 4u);
}

TEST(PathRemeshing, PathsAlongExistingEdgesChangeNothing)
{
  const TriangleMesh grid = gridPlane(4, 4, 0.25, 11);
  SurfacePath path;
  const std::vector<int> vertices{
    gridIndex(4, 0, 0), gridIndex(4, 1, 0), gridIndex(4, 2, 0), gridIndex(4, 2, 1)
  };
  for (int v : vertices)
  {
    path.points.push_back(SurfacePoint::atVertex(v));
  }
  // A repeated point and points within the tolerance of an edge end.
  path.points.insert(path.points.begin() + 1, SurfacePoint::atVertex(vertices[0]));
  path.points.insert(
    path.points.begin() + 3, SurfacePoint::onEdge(gridIndex(4, 1, 0), gridIndex(4, 2, 0), 1e-12));
  path.points.insert(path.points.begin() + 5,
    SurfacePoint::onEdge(gridIndex(4, 2, 0), gridIndex(4, 2, 1), 1.0 - 1e-12));
  const std::vector<SurfacePath> paths{ path, SurfacePath{} };
  const RemeshedSurface result = insertPaths(grid, paths);
  EXPECT_TRUE(isFaithfulRemeshing(grid, paths, result));
  EXPECT_EQ(result.pathVertices[0], vertices);
  EXPECT_TRUE(result.pathVertices[1].empty());
  EXPECT_EQ(result.mesh.vertexCount(), grid.vertexCount());
  EXPECT_EQ(result.mesh.triangles, grid.triangles);
  EXPECT_EQ(result.mesh.textureCorners, grid.textureCorners);
  EXPECT_EQ(result.mesh.textureCoordinates.size(), grid.textureCoordinates.size());
}

TEST(PathRemeshing, DenseParallelPathsAndAFan)
{
  const TriangleMesh grid = gridPlane(12, 16, 0.25, 13);
  const auto all = allTriangles(grid);
  // 40 parallel lines 0.25 apart (several per triangle), from the left
  // border to the right border (points inside border edges).
  std::vector<SurfacePath> parallel;
  for (int k = 0; k < 40; ++k)
  {
    const double y = 0.3 + 0.25 * k;
    const double yEnd = y + 0.37 * 12;
    const int j = static_cast<int>(y);
    const int jEnd = static_cast<int>(yEnd);
    parallel.push_back(segmentPath(grid,
      all,
      SurfacePoint::onEdge(gridIndex(12, 0, j), gridIndex(12, 0, j + 1), y - j),
      SurfacePoint::onEdge(gridIndex(12, 12, jEnd), gridIndex(12, 12, jEnd + 1), yEnd - jEnd)));
  }
  const RemeshedSurface lines = insertPaths(grid, parallel);
  EXPECT_TRUE(isFaithfulRemeshing(grid, parallel, lines));
  std::vector<int> piecesPerTriangle(grid.triangleCount(), 0);
  for (int parent : lines.inputTriangle)
  {
    ++piecesPerTriangle[parent];
  }
  EXPECT_GE(*std::max_element(piecesPerTriangle.begin(), piecesPerTriangle.end()), 8);

  // A fan from one inner vertex to every border vertex: the paths touch at
  // the centre only.
  std::vector<SurfacePath> fan;
  const int centre = gridIndex(12, 6, 8);
  for (int v = 0; v < static_cast<int>(grid.vertexCount()); ++v)
  {
    const int i = v % 13;
    const int j = v / 13;
    if (i == 0 || j == 0 || i == 12 || j == 16)
    {
      fan.push_back(straightPath(grid, all, centre, v));
    }
  }
  ASSERT_EQ(fan.size(), 56u);
  const RemeshedSurface rays = insertPaths(grid, fan);
  EXPECT_TRUE(isFaithfulRemeshing(grid, fan, rays));
  EXPECT_EQ(countThrough(rays, centre), 56u);
  const MeshValidationReport report = validateTriangleMesh(rays.mesh);
  EXPECT_EQ(report.degenerateTriangles.count, 0u);
  EXPECT_EQ(report.nonManifoldEdges.count, 0u);
  EXPECT_EQ(report.inconsistentlyOrientedEdges.count, 0u);
}

// ---------------------------------------------------------------------------

/// Two triangles (a, b, c) and (b, a, d) beside edge (a, b) with their own
/// texture coordinates for a and b when `seam`, shared ones otherwise.
TriangleMesh twoTriangles(bool seam)
{
  TriangleMesh mesh;
  mesh.name = "two triangles";
  mesh.positions = {
    Vector3(0.0, 0.0, 0.0), Vector3(2.0, 0.0, 0.0), Vector3(1.0, 1.5, 0.2), Vector3(1.0, -1.5, -0.3)
  };
  mesh.triangles = { { 0, 1, 2 }, { 1, 0, 3 } };
  mesh.textureCoordinates = { Vector2(0.0, 0.0),
    Vector2(1.0, 0.0),
    Vector2(0.5, 1.0),
    Vector2(0.2, 0.9),
    Vector2(0.8, 0.9),
    Vector2(0.5, 0.1) };
  mesh.textureCorners = { { 0, 1, 2 }, { 3, 4, 5 } };
  if (!seam)
  {
    mesh.textureCorners[1] = { 1, 0, 5 };
  }
  mesh.normals = { Vector3(1.0, 0.0, 1.0).normalized(),
    Vector3(-1.0, 0.5, 1.0).normalized(),
    Vector3(0.0, 0.0, 1.0),
    Vector3(0.0, 0.0, 1.0) };
  mesh.pointAttributes.set("Scalar", 1, { 1.0, 5.0, 2.0, 3.0 });
  return mesh;
}

TEST(PathRemeshing, SideSplitWithoutChordsIsFannedFromTheOppositeCorner)
{
  // Three paths from d end inside edge (a, b): triangle (a, b, c) gets three
  // points on one side and no chord. Its only non-degenerate triangulation
  // is the fan from c (a fan from a, or cutting the ear at c first, would
  // leave triangles of three collinear points).
  TriangleMesh mesh = twoTriangles(true);
  mesh.positions[2] = Vector3(1.0, 1.7, 0.0);
  mesh.positions[3] = Vector3(1.0, -1.7, 0.0);
  std::vector<SurfacePath> paths;
  for (const double t : { 0.25, 0.5, 0.75 })
  {
    SurfacePath path;
    path.points = { SurfacePoint::atVertex(3), SurfacePoint::onEdge(0, 1, t) };
    paths.push_back(path);
  }
  const RemeshedSurface result = insertPaths(mesh, paths);
  EXPECT_TRUE(isFaithfulRemeshing(mesh, paths, result));
  ASSERT_EQ(result.mesh.triangleCount(), 8u);
  for (std::size_t t = 0; t < result.mesh.triangleCount(); ++t)
  {
    const Triangle& tri = result.mesh.triangles[t];
    const int apex = result.inputTriangle[t] == 0 ? 2 : 3;
    EXPECT_NE(std::find(tri.begin(), tri.end(), apex), tri.end()) << "triangle " << t;
  }
}

TEST(PathRemeshing, TextureSeamNormalsAndAttributes)
{
  for (const bool seam : { true, false })
  {
    SCOPED_TRACE(seam ? "seam" : "no seam");
    const TriangleMesh mesh = twoTriangles(seam);
    SurfacePath path;
    path.points = {
      SurfacePoint::atVertex(2), SurfacePoint::onEdge(0, 1, 0.3), SurfacePoint::atVertex(3)
    };
    const std::vector<SurfacePath> paths{ path };
    const RemeshedSurface result = insertPaths(mesh, paths);
    EXPECT_TRUE(isFaithfulRemeshing(mesh, paths, result));
    ASSERT_EQ(result.mesh.vertexCount(), 5u);
    ASSERT_EQ(result.mesh.triangleCount(), 4u);
    EXPECT_EQ(result.pathVertices[0], (std::vector<int>{ 2, 4, 3 }));
    EXPECT_EQ(result.mesh.positions[4], Vector3(0.6, 0.0, 0.0));
    // Each side interpolates its own corners' coordinates.
    std::map<int, std::set<int>> textureOfParent;
    for (std::size_t t = 0; t < 4; ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (result.mesh.triangles[t][k] == 4)
        {
          textureOfParent[result.inputTriangle[t]].insert(result.mesh.textureCorners[t][k]);
        }
      }
    }
    ASSERT_EQ(textureOfParent.size(), 2u);
    ASSERT_EQ(textureOfParent[0].size(), 1u);
    ASSERT_EQ(textureOfParent[1].size(), 1u);
    const Vector2 first = result.mesh.textureCoordinates[*textureOfParent[0].begin()];
    const Vector2 second = result.mesh.textureCoordinates[*textureOfParent[1].begin()];
    EXPECT_LE((first - Vector2(0.3, 0.0)).norm(), 1e-15);
    if (seam)
    {
      EXPECT_LE((second - Vector2(0.62, 0.9)).norm(), 1e-15);
      EXPECT_EQ(result.mesh.textureCoordinates.size(), 8u);
    }
    else
    {
      // Same value for the same vertex: one shared entry.
      EXPECT_EQ(*textureOfParent[0].begin(), *textureOfParent[1].begin());
      EXPECT_EQ(result.mesh.textureCoordinates.size(), 7u);
    }
    const Vector3 normal = (0.7 * mesh.normals[0] + 0.3 * mesh.normals[1]).normalized();
    EXPECT_NEAR(result.mesh.normals[4].norm(), 1.0, 1e-15);
    EXPECT_LE((result.mesh.normals[4] - normal).norm(), 1e-15);
    EXPECT_NEAR(result.mesh.pointAttributes.get("Scalar").values[4], 0.7 * 1.0 + 0.3 * 5.0, 1e-15);
  }
}

TEST(PathRemeshing, LinearAttributesStayLinearOnAGrid)
{
  const TriangleMesh grid = gridPlane(8, 8, 0.25, 3);
  const auto all = allTriangles(grid);
  const std::vector<SurfacePath> paths{ straightPath(
    grid, all, gridIndex(8, 0, 2), gridIndex(8, 8, 5)) };
  const RemeshedSurface result = insertPaths(grid, paths);
  ASSERT_GT(result.mesh.vertexCount(), grid.vertexCount());
  const AttributeArray& linear = result.mesh.pointAttributes.get("Linear");
  ASSERT_EQ(linear.elementCount(), result.mesh.vertexCount());
  ASSERT_EQ(result.mesh.pointAttributes.get("Vector").elementCount(), result.mesh.vertexCount());
  for (std::size_t v = grid.vertexCount(); v < result.mesh.vertexCount(); ++v)
  {
    const Vector3& p = result.mesh.positions[v];
    EXPECT_NEAR(linear.values[v], p.x() + 2.0 * p.y(), 1e-13);
    EXPECT_NEAR(result.mesh.normals[v].norm(), 1.0, 1e-15);
  }
}

// ---------------------------------------------------------------------------

TEST(PathRemeshing, CrossingPathsAreRejected)
{
  const TriangleMesh grid = gridPlane(6, 4, 0.0, 0);
  const auto all = allTriangles(grid);
  // y = x / 5 and y = 2 - 2 x / 5 cross at (10/3, 2/3), inside a triangle.
  const std::vector<SurfacePath> paths{
    straightPath(grid, all, gridIndex(6, 0, 0), gridIndex(6, 5, 1)),
    straightPath(grid, all, gridIndex(6, 0, 2), gridIndex(6, 5, 0)),
  };
  const Vector3 crossing(10.0 / 3.0, 2.0 / 3.0, 0.0);
  int inside = -1;
  for (std::size_t t = 0; t < grid.triangleCount(); ++t)
  {
    const Triangle& tri = grid.triangles[t];
    const auto lambda =
      barycentric(grid.positions[tri[0]], grid.positions[tri[1]], grid.positions[tri[2]], crossing)
        .first;
    if (lambda.minCoeff() > 1e-6)
    {
      inside = static_cast<int>(t);
    }
  }
  ASSERT_GE(inside, 0);
  try
  {
    insertPaths(grid, paths);
    FAIL() << "crossing paths accepted";
  }
  catch (const PathsCrossError& error)
  {
    // The paths and the triangle by number too, for a caller that finds
    // one of them again (the binding).
    EXPECT_EQ(error.firstPath(), 0);
    EXPECT_EQ(error.secondPath(), 1);
    EXPECT_EQ(error.triangle(), inside);
    const std::string message = error.what();
    EXPECT_NE(message.find("grid plane"), std::string::npos) << message;
    EXPECT_NE(message.find("triangle " + std::to_string(inside) + " "), std::string::npos)
      << message;
    EXPECT_NE(message.find("paths 0 and 1"), std::string::npos) << message;
  }
  // Each path alone is fine; the same path twice touches itself everywhere.
  EXPECT_NO_THROW(insertPaths(grid, { paths[0] }));
  EXPECT_NO_THROW(insertPaths(grid, { paths[1] }));
  const std::vector<SurfacePath> twice{ paths[0], paths[0] };
  const RemeshedSurface result = insertPaths(grid, twice);
  EXPECT_TRUE(isFaithfulRemeshing(grid, twice, result));
  EXPECT_EQ(result.pathVertices[0], result.pathVertices[1]);
}

TEST(PathRemeshing, TouchingPathsAreAccepted)
{
  const TriangleMesh grid = gridPlane(6, 4, 0.0, 0);
  const auto all = allTriangles(grid);
  // y = x / 5 crosses edge x = 2 at y = 0.4; a second path comes to that
  // point from (3, 1) and ends there; a third leaves it for (1, 0). Each
  // shares a chord end with the first inside a triangle.
  std::vector<SurfacePath> paths{ straightPath(grid, all, gridIndex(6, 0, 0), gridIndex(6, 5, 1)) };
  const auto onX2 = std::find_if(paths[0].points.begin(),
    paths[0].points.end(),
    [&](const SurfacePoint& p)
    { return !p.isVertex() && std::abs(p.position(grid.positions).x() - 2.0) < 1e-12; });
  ASSERT_NE(onX2, paths[0].points.end());
  SurfacePath ending;
  ending.points = { SurfacePoint::atVertex(gridIndex(6, 3, 1)), *onX2 };
  SurfacePath leaving;
  leaving.points = { *onX2, SurfacePoint::atVertex(gridIndex(6, 1, 0)) };
  paths.push_back(ending);
  paths.push_back(leaving);
  const RemeshedSurface result = insertPaths(grid, paths);
  EXPECT_TRUE(isFaithfulRemeshing(grid, paths, result));
  EXPECT_EQ(result.pathVertices[1].back(), result.pathVertices[2].front());
  EXPECT_EQ(countThrough(result, result.pathVertices[1].back()), 3u);
}

TEST(PathRemeshing, BadReferencesAreRejected)
{
  const TriangleMesh grid = gridPlane(4, 4, 0.0, 0);
  const int a = gridIndex(4, 1, 1);
  const int b = gridIndex(4, 2, 1);
  auto pathOf = [](std::vector<SurfacePoint> points)
  {
    SurfacePath path;
    path.points = std::move(points);
    return path;
  };
  SurfacePoint reversed;
  reversed.edgeStart = b;
  reversed.edgeEnd = a;
  reversed.edgeParameter = 0.5;
  SurfacePoint nothing;
  const std::vector<std::pair<const char*, SurfacePath>> bad{
    { "vertex out of range", pathOf({ SurfacePoint::atVertex(a), SurfacePoint::atVertex(25) }) },
    { "neither vertex nor edge", pathOf({ SurfacePoint::atVertex(a), nothing }) },
    { "edge end out of range", pathOf({ SurfacePoint::onEdge(a, 1000, 0.5) }) },
    { "edge given end first", pathOf({ SurfacePoint::atVertex(a), reversed }) },
    { "not an edge", pathOf({ SurfacePoint::onEdge(a, gridIndex(4, 3, 3), 0.5) }) },
    { "not an edge (anti-diagonal)", pathOf({ SurfacePoint::onEdge(b, gridIndex(4, 1, 2), 0.5) }) },
    { "parameter outside", pathOf({ SurfacePoint::onEdge(a, b, 1.5) }) },
    { "parameter not a number",
      pathOf({ SurfacePoint::onEdge(a, b, std::numeric_limits<double>::quiet_NaN()) }) },
    { "vertices on no common triangle",
      pathOf({ SurfacePoint::atVertex(a), SurfacePoint::atVertex(gridIndex(4, 3, 3)) }) },
    { "edge points on no common triangle",
      pathOf({ SurfacePoint::onEdge(gridIndex(4, 0, 0), gridIndex(4, 1, 0), 0.5),
        SurfacePoint::onEdge(gridIndex(4, 2, 0), gridIndex(4, 3, 0), 0.5) }) },
    { "vertex and edge on no common triangle",
      pathOf({ SurfacePoint::atVertex(gridIndex(4, 0, 2)),
        SurfacePoint::onEdge(gridIndex(4, 2, 0), gridIndex(4, 3, 0), 0.5) }) },
  };
  for (const auto& [what, path] : bad)
  {
    SCOPED_TRACE(what);
    try
    {
      insertPaths(grid, { SurfacePath{}, path });
      ADD_FAILURE() << "accepted";
    }
    catch (const InvalidInputError& error)
    {
      const std::string message = error.what();
      EXPECT_NE(message.find("grid plane"), std::string::npos) << message;
      EXPECT_NE(message.find("path 1"), std::string::npos) << message;
    }
  }
  const std::vector<SurfacePath> good{ pathOf({ SurfacePoint::atVertex(a),
    SurfacePoint::onEdge(a, b, 0.5),
    SurfacePoint::atVertex(gridIndex(4, 2, 2)) }) };
  EXPECT_NO_THROW(insertPaths(grid, good));
  EXPECT_THROW(insertPaths(grid, good, -1.0), InvalidInputError);
  EXPECT_THROW(
    insertPaths(grid, good, std::numeric_limits<double>::quiet_NaN()), InvalidInputError);
  TriangleMesh broken = grid;
  broken.triangles[3][1] = 999;
  EXPECT_THROW(insertPaths(broken, good), InvalidInputError);
}

// ---------------------------------------------------------------------------

bool sameBits(const void* a, const void* b, std::size_t bytes)
{
  return bytes == 0 || std::memcmp(a, b, bytes) == 0;
}

template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && sameBits(a.data(), b.data(), a.size() * sizeof(T));
}

TEST(PathRemeshing, DeterministicBitForBit)
{
  const TriangleMesh grid = gridPlane(20, 16, 0.25, 5);
  const auto all = allTriangles(grid);
  std::vector<SurfacePath> paths;
  for (int j = 0; j + 4 <= 16; j += 2)
  {
    paths.push_back(straightPath(grid, all, gridIndex(20, 0, j), gridIndex(20, 20, j + 4)));
  }
  paths.push_back(straightPath(grid, all, gridIndex(20, 3, 0), gridIndex(20, 5, 16)));
  EXPECT_THROW(insertPaths(grid, paths), InvalidInputError); // the last one crosses
  paths.pop_back();
  const RemeshedSurface first = insertPaths(grid, paths);
  const TriangleMesh copy = grid;
  const RemeshedSurface second = insertPaths(copy, paths);
  EXPECT_TRUE(isFaithfulRemeshing(grid, paths, first));
  EXPECT_GT(first.mesh.vertexCount(), grid.vertexCount() + 100);
  EXPECT_TRUE(sameBits(first.mesh.positions, second.mesh.positions));
  EXPECT_TRUE(sameBits(first.mesh.normals, second.mesh.normals));
  EXPECT_TRUE(sameBits(first.mesh.textureCoordinates, second.mesh.textureCoordinates));
  EXPECT_TRUE(sameBits(first.mesh.triangles, second.mesh.triangles));
  EXPECT_TRUE(sameBits(first.mesh.textureCorners, second.mesh.textureCorners));
  for (const std::string& name : first.mesh.pointAttributes.names())
  {
    EXPECT_TRUE(sameBits(
      first.mesh.pointAttributes.get(name).values, second.mesh.pointAttributes.get(name).values));
  }
  EXPECT_EQ(first.pathVertices, second.pathVertices);
  EXPECT_EQ(first.inputTriangle, second.inputTriangle);
  EXPECT_EQ(first.inputVertex, second.inputVertex);
}

// ---------------------------------------------------------------------------

TEST(PathRemeshing, ThesisSheetWithManyPaths)
{
  const TriangleMesh sheet = makeThinSheet(thesisSheetVisualResolution(3)).visual;
  ASSERT_GT(sheet.vertexCount(), 13000u);
  const double top = 1.0;
  auto near = [](double a, double b) { return std::abs(a - b) < 1e-9; };
  // Paths of a sheared triangulated lattice of face vertices (an affine
  // image of a planar triangulation: paths meet only at lattice points), on
  // the top and on the bottom face, like the binding's paths of collision
  // edges.
  std::vector<SurfacePath> paths;
  for (const double z : { top, -top })
  {
    const auto face = trianglesWhere(sheet, [&](const Vector3& p) { return near(p.z(), z); });
    std::map<std::pair<int, int>, int> lattice;
    for (int a = -12; a <= 12; ++a)
    {
      for (int b = -12; b <= 12; ++b)
      {
        const double x = -46.0 + 8.3 * a + 2.1 * b;
        const double y = -46.0 + 1.3 * a + 9.7 * b;
        if (x > -47.0 && x < 47.0 && y > -47.0 && y < 47.0)
        {
          lattice[{ a, b }] = vertexAt(sheet, Vector3(x, y, z));
        }
      }
    }
    for (const auto& [key, v] : lattice)
    {
      for (const auto& step : { std::pair<int, int>(1, 0), { 0, 1 }, { 1, 1 } })
      {
        const auto other = lattice.find({ key.first + step.first, key.second + step.second });
        if (other != lattice.end())
        {
          paths.push_back(straightPath(sheet, face, v, other->second));
        }
      }
    }
  }
  ASSERT_GT(paths.size(), 300u);
  std::size_t points = 0;
  for (const auto& path : paths)
  {
    points += path.points.size();
  }

  using Clock = std::chrono::steady_clock;
  const auto copyStart = Clock::now();
  const TriangleMesh copy = sheet;
  const double copySeconds = std::chrono::duration<double>(Clock::now() - copyStart).count();
  const auto adjacencyStart = Clock::now();
  const TriangleMeshAdjacency adjacency(sheet);
  const double adjacencySeconds =
    std::chrono::duration<double>(Clock::now() - adjacencyStart).count();
  double best = std::numeric_limits<double>::infinity();
  RemeshedSurface result;
  for (int run = 0; run < 3; ++run)
  {
    const auto start = Clock::now();
    result = insertPaths(copy, paths);
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
  }
  std::cout << "[ timing   ] insertPaths on " << sheet.vertexCount() << " vertices / "
            << sheet.triangleCount() << " triangles, " << paths.size() << " paths, " << points
            << " path points: " << best * 1e3 << " ms (" << result.mesh.vertexCount()
            << " vertices / " << result.mesh.triangleCount() << " triangles after); mesh copy "
            << copySeconds * 1e3 << " ms, adjacency " << adjacencySeconds * 1e3 << " ms ("
            << adjacency.edgeCount() << " edges)\n";
  RecordProperty("insertPathsMilliseconds", std::to_string(best * 1e3));

  EXPECT_GT(result.mesh.vertexCount(), sheet.vertexCount() + 1000);
  EXPECT_TRUE(isClosedOriented(result.mesh));
  EXPECT_TRUE(isFaithfulRemeshing(sheet, paths, result));
  EXPECT_NEAR(result.mesh.surfaceArea(), sheet.surfaceArea(), 1e-12 * sheet.surfaceArea());
  EXPECT_NEAR(result.mesh.signedVolume(), sheet.signedVolume(), 1e-11 * sheet.signedVolume());
}

} // namespace
