#include "AutomaticMonitorCurves.h"

#include "MeshQueries.h"
#include "ThinTissueError.h"
#include "TriangleMeshAdjacency.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thintissue
{

namespace
{

using Run = std::vector<int>; // border vertices in order

/// Border loops, each in the direction of its triangles' orientation.
std::vector<Run> borderLoops(const TriangleMesh& mesh, const TriangleMeshAdjacency& adjacency)
{
  std::vector<int> next(mesh.vertexCount(), -1);
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int e = adjacency.triangleEdges(static_cast<int>(t))[k];
      if (adjacency.isBorderEdge(e) && next[mesh.triangles[t][k]] < 0)
      {
        next[mesh.triangles[t][k]] = mesh.triangles[t][(k + 1) % 3];
      }
    }
  }
  std::vector<Run> loops;
  std::vector<char> visited(mesh.vertexCount(), 0);
  for (std::size_t start = 0; start < mesh.vertexCount(); ++start)
  {
    if (next[start] < 0 || visited[start])
    {
      continue;
    }
    Run loop;
    for (int v = static_cast<int>(start); v >= 0 && !visited[v]; v = next[v])
    {
      visited[v] = 1;
      loop.push_back(v);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

double runLength(const TriangleMesh& mesh, const Run& run)
{
  double length = 0.0;
  for (std::size_t k = 1; k < run.size(); ++k)
  {
    length += (mesh.positions[run[k]] - mesh.positions[run[k - 1]]).norm();
  }
  return length;
}

/// The maximal runs of thin vertices of a loop; a loop thin all round is
/// one run opened at its first vertex.
std::vector<Run> thinRuns(const Run& loop, const std::vector<char>& thin)
{
  const std::size_t n = loop.size();
  std::size_t thick = n;
  for (std::size_t k = 0; k < n; ++k)
  {
    if (!thin[loop[k]])
    {
      thick = k;
      break;
    }
  }
  if (thick == n)
  {
    return { loop };
  }
  std::vector<Run> runs;
  Run current;
  for (std::size_t step = 1; step <= n; ++step)
  {
    const int v = loop[(thick + step) % n];
    if (thin[v])
    {
      current.push_back(v);
    }
    else if (!current.empty())
    {
      runs.push_back(std::move(current));
      current.clear();
    }
  }
  return runs;
}

bool isCorner(const TriangleMesh& mesh, int before, int at, int after, double cosine)
{
  const Vector3 in = (mesh.positions[at] - mesh.positions[before]).normalized();
  const Vector3 out = (mesh.positions[after] - mesh.positions[at]).normalized();
  return in.dot(out) < cosine;
}

/// Splits a run where the border turns by more than `cornerAngle` (radians)
/// at a vertex: a wrinkle window does not wrap round a corner (the inner
/// rim of a meniscus meets its horn ends at right angles). The corner
/// vertex itself joins neither piece: across the border is ill-defined
/// there. A closed run (a whole loop) is opened at its first corner.
std::vector<Run> splitAtCorners(const TriangleMesh& mesh, Run run, bool closed, double cornerAngle)
{
  const double cosine = std::cos(cornerAngle);
  const std::size_t n = run.size();
  if (closed && n >= 3)
  {
    for (std::size_t k = 0; k < n; ++k)
    {
      if (isCorner(mesh, run[(k + n - 1) % n], run[k], run[(k + 1) % n], cosine))
      {
        std::rotate(run.begin(), run.begin() + static_cast<std::ptrdiff_t>(k), run.end());
        run.erase(run.begin()); // the corner
        break;
      }
    }
  }
  std::vector<Run> pieces(1);
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    if (k > 0 && k + 1 < run.size() && isCorner(mesh, run[k - 1], run[k], run[k + 1], cosine))
    {
      pieces.emplace_back();
      continue;
    }
    pieces.back().push_back(run[k]);
  }
  return pieces;
}

std::vector<Run> selectRuns(const TriangleMesh& mesh,
  std::vector<Run> runs,
  const AutomaticMonitorSettings& settings)
{
  runs.erase(std::remove_if(runs.begin(), runs.end(), [](const Run& r) { return r.size() < 2; }),
    runs.end());
  if (runs.empty())
  {
    return runs;
  }
  if (settings.useNearPoint)
  {
    std::size_t best = 0;
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t r = 0; r < runs.size(); ++r)
    {
      for (const int v : runs[r])
      {
        const double d = (mesh.positions[v] - settings.nearPoint).squaredNorm();
        if (d < nearest)
        {
          nearest = d;
          best = r;
        }
      }
    }
    return { runs[best] };
  }
  double longest = 0.0;
  for (const Run& r : runs)
  {
    longest = std::max(longest, runLength(mesh, r));
  }
  runs.erase(
    std::remove_if(runs.begin(),
      runs.end(),
      [&](const Run& r) { return runLength(mesh, r) < settings.minimumRunFraction * longest; }),
    runs.end());
  return runs;
}

Vector3 closestPointOnMesh(const TriangleMesh& mesh, const Vector3& point)
{
  Vector3 best = mesh.positions.front();
  double nearest = std::numeric_limits<double>::infinity();
  for (const Triangle& t : mesh.triangles)
  {
    const Vector3 q = closestPointOnTriangle(
      point, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
    const double d = (q - point).squaredNorm();
    if (d < nearest)
    {
      nearest = d;
      best = q;
    }
  }
  return best;
}

/// Unit direction at border vertex run[k], in the surface's tangent plane,
/// across the border into the surface.
Vector3 inwardDirection(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const Run& run,
  std::size_t k)
{
  const int v = run[k];
  const Vector3& x = mesh.positions[v];
  const Vector3 tangent =
    mesh.positions[run[std::min(k + 1, run.size() - 1)]] - mesh.positions[run[k > 0 ? k - 1 : 0]];
  Vector3 normal = Vector3::Zero();
  Vector3 towardTriangles = Vector3::Zero();
  for (const int* t = adjacency.vertexTrianglesBegin(v); t != adjacency.vertexTrianglesEnd(v); ++t)
  {
    const Triangle& c = mesh.triangles[*t];
    const Vector3 centroid =
      (mesh.positions[c[0]] + mesh.positions[c[1]] + mesh.positions[c[2]]) / 3.0;
    normal += (mesh.positions[c[1]] - mesh.positions[c[0]])
                .cross(mesh.positions[c[2]] - mesh.positions[c[0]]);
    towardTriangles += centroid - x;
  }
  Vector3 inward = normal.cross(tangent);
  if (inward.squaredNorm() == 0.0)
  {
    inward = towardTriangles;
  }
  if (inward.dot(towardTriangles) < 0.0)
  {
    inward = -inward;
  }
  return inward.normalized();
}

WrinkleDataCurve dataCurveOf(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<double>& radii,
  const Run& run,
  const AutomaticMonitorSettings& settings)
{
  WrinkleDataCurve curve;
  curve.name = mesh.name + " thin border from vertex " + std::to_string(run.front());
  double meanRadius = 0.0;
  for (const int v : run)
  {
    meanRadius += radii[v] / static_cast<double>(run.size());
  }
  const double depth =
    settings.regionDepth > 0.0 ? settings.regionDepth : settings.regionDepthInRadii * meanRadius;
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    const Vector3& x = mesh.positions[run[k]];
    const Vector3 inward = inwardDirection(mesh, adjacency, run, k);
    curve.monitorPoints.push_back(x);
    curve.regionPoints.push_back(closestPointOnMesh(mesh, x + depth * inward));
    curve.thickness.push_back(2.0 * radii[run[k]]);
  }
  return curve;
}

} // namespace

std::vector<WrinkleDataCurve> deriveWrinkleDataCurves(const TriangleMesh& collision,
  const std::vector<double>& radii,
  const AutomaticMonitorSettings& settings)
{
  const std::string name = "'" + collision.name + "'";
  if (radii.size() != collision.vertexCount())
  {
    throw InvalidInputError("wrinkle data of " + name + ": " + std::to_string(radii.size()) +
                            " radii for " + std::to_string(collision.vertexCount()) +
                            " collision vertices");
  }
  collision.checkConsistency();
  const TriangleMeshAdjacency adjacency(collision);
  const std::vector<Run> loops = borderLoops(collision, adjacency);
  if (loops.empty())
  {
    throw InvalidInputError(
      "wrinkle data of " + name + ": the collision mid-surface has no free border");
  }
  double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
  for (const Run& loop : loops)
  {
    for (const int v : loop)
    {
      smallest = std::min(smallest, radii[v]);
      largest = std::max(largest, radii[v]);
    }
  }
  // Radii within a few percent of each other (a slab, the steak): the
  // whole border is thin, not the vertices that happen to be smallest.
  const bool uniform = largest - smallest <= settings.uniformTolerance * largest;
  const double threshold =
    uniform ? largest : smallest + settings.thinFraction * (largest - smallest);
  std::vector<char> thin(collision.vertexCount(), 0);
  std::vector<Run> runs;
  for (const Run& loop : loops)
  {
    for (const int v : loop)
    {
      thin[v] = radii[v] <= threshold ? 1 : 0;
    }
    for (const Run& run : thinRuns(loop, thin))
    {
      const bool closed = run.size() == loop.size();
      for (Run& piece : splitAtCorners(collision, run, closed, settings.cornerAngle))
      {
        runs.push_back(std::move(piece));
      }
    }
  }
  runs = selectRuns(collision, std::move(runs), settings);
  if (runs.empty())
  {
    throw InvalidInputError(
      "wrinkle data of " + name + ": no run of two or more thin border vertices");
  }
  std::vector<WrinkleDataCurve> curves;
  for (const Run& run : runs)
  {
    curves.push_back(dataCurveOf(collision, adjacency, radii, run, settings));
  }
  return curves;
}

} // namespace thintissue
