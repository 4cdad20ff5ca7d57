// Checks every procedural tissue model must pass (issue "Procedural tissue,
// bone and tool models"): closed outward visual surface, thinness, counts
// near the thesis figures, collision mid-surface inside the visual volume
// with radii near half the local thickness, hexahedra covering it.
// Header-only, for GoogleTest executables.
#ifndef TissueModelChecks_h
#define TissueModelChecks_h

#include "MeshQueries.h"
#include "MeshValidation.h"
#include "TriangleMesh.h"
#include "TrilinearCoordinates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <vector>

namespace thintissue::testing
{

/// |actual - thesis| <= tolerance * thesis.
inline ::testing::AssertionResult isWithinFraction(double actual, double thesis, double tolerance)
{
  const double deviation = std::abs(actual - thesis) / thesis;
  if (deviation <= tolerance)
  {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure()
         << actual << " differs from the thesis figure " << thesis << " by " << 100.0 * deviation
         << "% (allowed " << 100.0 * tolerance << "%)";
}

/// One closed, 2-manifold, consistently outward surface.
inline ::testing::AssertionResult isClosedOutwardSurface(const TriangleMesh& mesh)
{
  const auto report = validateTriangleMesh(mesh);
  if (report.isClosedOutwardSingleSurface())
  {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << report.toString();
}

/// Smallest bounding-box side over largest: how thin the solid is.
inline double thicknessToExtentRatio(const TriangleMesh& mesh)
{
  const Vector3 size = mesh.boundingBox().sizes();
  return size.minCoeff() / size.maxCoeff();
}

/// Every collision vertex lies inside the visual volume (winding number
/// >= 1/2) or on its surface: within `surfaceTolerance` times the bounding-
/// box diagonal of it (default 1e-3: a vertex on a curved border lies
/// outside the facets of the visual surface by their sagitta).
inline ::testing::AssertionResult isInsideVolume(const TriangleMesh& inner,
  const TriangleMesh& outer,
  double surfaceTolerance = 1e-3)
{
  const double onSurface = surfaceTolerance * outer.boundingBox().diagonal().norm();
  for (std::size_t v = 0; v < inner.vertexCount(); ++v)
  {
    const double winding = windingNumber(outer, inner.positions[v]);
    if (winding < 0.5 - 1e-6 && distanceToSurface(outer, inner.positions[v]) > onSurface)
    {
      return ::testing::AssertionFailure()
             << "vertex " << v << " at (" << inner.positions[v].transpose() << ") is outside '"
             << outer.name << "' (winding number " << winding << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

/// Local thickness of the closed surface `visual` through `point` along
/// `normal`: nearest hit ahead plus nearest hit behind.
inline double thicknessAlong(const TriangleMesh& visual,
  const Vector3& point,
  const Vector3& normal)
{
  const auto ahead = rayHits(visual, point, normal);
  const auto behind = rayHits(visual, point, -normal);
  if (ahead.empty() || behind.empty())
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return ahead.front() + behind.front();
}

/// For every collision vertex v accepted by `include` (all when empty):
/// |radius(v) - thickness(v)/2| <= tolerance * thickness(v)/2, thickness
/// measured along the collision mesh's vertex normal.
/// `thicknessDirection` (default: the collision vertex normal) is the
/// direction the thickness is measured along, e.g. vertical for a wedge
/// lying on a plateau, whose mid-surface normal tilts toward the rim.
inline ::testing::AssertionResult radiiMatchHalfThickness(const TriangleMesh& collision,
  const std::vector<double>& radii,
  const TriangleMesh& visual,
  double tolerance,
  const std::function<bool(std::size_t)>& include = {},
  const std::function<Vector3(std::size_t)>& thicknessDirection = {})
{
  TriangleMesh withNormals = collision;
  withNormals.computeVertexNormals();
  // Border vertices of the mid-surface lie on the visual surface, where a
  // ray is ambiguous: measure a hair inside, toward the one-ring's centre.
  std::vector<Vector3> ringSum(collision.vertexCount(), Vector3::Zero());
  std::vector<int> ringCount(collision.vertexCount(), 0);
  for (const auto& t : collision.triangles)
  {
    const Vector3 centre =
      (collision.positions[t[0]] + collision.positions[t[1]] + collision.positions[t[2]]) / 3.0;
    for (int k = 0; k < 3; ++k)
    {
      ringSum[t[k]] += centre;
      ++ringCount[t[k]];
    }
  }
  std::size_t checked = 0;
  for (std::size_t v = 0; v < collision.vertexCount(); ++v)
  {
    if (include && !include(v))
    {
      continue;
    }
    Vector3 sample = collision.positions[v];
    if (ringCount[v] > 0)
    {
      sample += 0.05 * (ringSum[v] / ringCount[v] - sample);
    }
    const Vector3 direction =
      thicknessDirection ? thicknessDirection(v) : Vector3(withNormals.normals[v].normalized());
    const double thickness = thicknessAlong(visual, sample, direction);
    const double expected = 0.5 * thickness;
    if (!(std::abs(radii[v] - expected) <= tolerance * expected))
    {
      return ::testing::AssertionFailure()
             << "collision vertex " << v << " at (" << collision.positions[v].transpose()
             << "): radius " << radii[v] << ", half the local thickness " << expected;
    }
    ++checked;
  }
  if (checked == 0)
  {
    return ::testing::AssertionFailure() << "no collision vertex checked";
  }
  return ::testing::AssertionSuccess();
}

/// Every point lies in some hexahedron of `mesh` (local coordinates within
/// [-tolerance, 1 + tolerance]).
inline ::testing::AssertionResult isCoveredByHexahedra(const std::vector<Vector3>& points,
  const HexahedralMesh& mesh,
  double tolerance = 1e-6)
{
  for (std::size_t p = 0; p < points.size(); ++p)
  {
    if (findContainingHexahedron(mesh, points[p], tolerance) < 0)
    {
      return ::testing::AssertionFailure()
             << "point " << p << " at (" << points[p].transpose() << ") is in no hexahedron";
    }
  }
  return ::testing::AssertionSuccess();
}

/// Distance from `point` to the nearest hexahedron (0 inside), from the
/// clamped local coordinates: what the nearest-hexahedron embedding of
/// thesis 4.3 would use.
inline double distanceToHexahedra(const HexahedralMesh& mesh, const Vector3& point)
{
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t h = 0; h < mesh.hexahedronCount(); ++h)
  {
    const auto corners = hexahedronCorners(mesh, h);
    Vector3 local;
    if (!trilinearCoordinates(corners, point, local))
    {
      continue;
    }
    const Vector3 clamped = local.cwiseMax(0.0).cwiseMin(1.0);
    best = std::min(best, (trilinearPoint(corners, clamped) - point).norm());
  }
  return best;
}

/// Every point is in a hexahedron or at most `distance` from one.
inline ::testing::AssertionResult isNearHexahedra(const std::vector<Vector3>& points,
  const HexahedralMesh& mesh,
  double distance)
{
  for (std::size_t p = 0; p < points.size(); ++p)
  {
    if (findContainingHexahedron(mesh, points[p], 1e-6) < 0)
    {
      const double d = distanceToHexahedra(mesh, points[p]);
      if (!(d <= distance))
      {
        return ::testing::AssertionFailure() << "point " << p << " at (" << points[p].transpose()
                                             << ") is " << d << " from the nearest hexahedron";
      }
    }
  }
  return ::testing::AssertionSuccess();
}

/// Shortest path length along mesh edges (Dijkstra) from every vertex to
/// `source`; infinity where unreachable. Used to show that a tear separates
/// material: two points facing each other across it are far apart along the
/// mesh although close in space.
inline std::vector<double> edgePathDistances(const std::vector<Vector3>& points,
  const std::vector<std::vector<int>>& neighbours,
  int source)
{
  std::vector<double> distance(points.size(), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  distance[source] = 0.0;
  queue.push({ 0.0, source });
  while (!queue.empty())
  {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v])
    {
      continue;
    }
    for (int w : neighbours[v])
    {
      const double candidate = d + (points[w] - points[v]).norm();
      if (candidate < distance[w])
      {
        distance[w] = candidate;
        queue.push({ candidate, w });
      }
    }
  }
  return distance;
}

/// Vertex neighbours through triangle edges.
inline std::vector<std::vector<int>> triangleMeshNeighbours(const TriangleMesh& mesh)
{
  std::vector<std::vector<int>> neighbours(mesh.vertexCount());
  for (const auto& t : mesh.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      neighbours[t[k]].push_back(t[(k + 1) % 3]);
      neighbours[t[(k + 1) % 3]].push_back(t[k]);
    }
  }
  return neighbours;
}

/// Node neighbours through hexahedron edges.
inline std::vector<std::vector<int>> hexahedralMeshNeighbours(const HexahedralMesh& mesh)
{
  static const int edges[12][2] = { { 0, 1 },
    { 1, 2 },
    { 2, 3 },
    { 3, 0 },
    { 4, 5 },
    { 5, 6 },
    { 6, 7 },
    { 7, 4 },
    { 0, 4 },
    { 1, 5 },
    { 2, 6 },
    { 3, 7 } };
  std::vector<std::vector<int>> neighbours(mesh.nodeCount());
  for (const auto& h : mesh.hexahedra)
  {
    for (const auto& e : edges)
    {
      neighbours[h[e[0]]].push_back(h[e[1]]);
      neighbours[h[e[1]]].push_back(h[e[0]]);
    }
  }
  return neighbours;
}

/// Index of the point nearest to `target`.
inline int nearestPoint(const std::vector<Vector3>& points, const Vector3& target)
{
  int best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < points.size(); ++p)
  {
    const double d = (points[p] - target).squaredNorm();
    if (d < bestDistance)
    {
      bestDistance = d;
      best = static_cast<int>(p);
    }
  }
  return best;
}

/// Path length along the mesh between the points nearest to `a` and `b`.
inline double pathLengthBetween(const std::vector<Vector3>& points,
  const std::vector<std::vector<int>>& neighbours,
  const Vector3& a,
  const Vector3& b)
{
  const auto distances = edgePathDistances(points, neighbours, nearestPoint(points, a));
  return distances[nearestPoint(points, b)];
}

} // namespace thintissue::testing

#endif
