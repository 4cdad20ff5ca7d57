#include "SharedPathRuns.h"

#include <cstddef>

namespace thintissue
{
namespace
{

/// Around `centre`, the vertex after `from` turning counter-clockwise (seen
/// from outside, as the triangles are oriented) or clockwise; -1 at a
/// border.
int nextAround(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  int centre,
  int from,
  bool counterClockwise)
{
  const int e = adjacency.findEdge(centre, from);
  if (e < 0)
  {
    return -1;
  }
  for (const int* t = adjacency.edgeTrianglesBegin(e); t != adjacency.edgeTrianglesEnd(e); ++t)
  {
    const Triangle& tri = mesh.triangles[*t];
    for (int k = 0; k < 3; ++k)
    {
      // Triangle (centre, a, b) turns counter-clockwise from a to b.
      const int first = counterClockwise ? centre : from;
      const int second = counterClockwise ? from : centre;
      if (tri[k] == first && tri[(k + 1) % 3] == second)
      {
        return tri[(k + 2) % 3];
      }
    }
  }
  return -1;
}

/// Edge state while runs are re-routed: how many paths run along it and
/// whether a re-routed path crosses it already.
struct EdgeUse
{
  std::vector<int> paths;
  std::vector<char> crossed;
};

/// The edges around `centre` strictly between `before` and `after` on one
/// side, as the points a re-routed path crosses them at; false when one of
/// them carries or is crossed by a path (the side is not free).
bool fanPoints(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const EdgeUse& use,
  int centre,
  int before,
  int after,
  bool counterClockwise,
  double offsetFraction,
  std::vector<SurfacePoint>& points,
  std::vector<int>& edges)
{
  constexpr int MaximumValence = 256;
  int x = nextAround(mesh, adjacency, centre, before, counterClockwise);
  for (int count = 0; x != after; ++count)
  {
    if (x < 0 || x == before || count > MaximumValence)
    {
      return false;
    }
    const int e = adjacency.findEdge(centre, x);
    if (use.paths[e] > 0 || use.crossed[e])
    {
      return false;
    }
    points.push_back(SurfacePoint::onEdge(centre, x, offsetFraction));
    edges.push_back(e);
    x = nextAround(mesh, adjacency, centre, x, counterClockwise);
  }
  return true;
}

/// A run of interior path vertices [first, last] that other paths touch.
struct Run
{
  std::size_t first = 0;
  std::size_t last = 0;
};

/// Points replacing the run's vertices, on the side where nothing is in the
/// way; false if neither side is free.
bool rerouteRun(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const EdgeUse& use,
  const std::vector<int>& path,
  const Run& run,
  double offsetFraction,
  std::vector<SurfacePoint>& points,
  std::vector<int>& edges)
{
  for (bool counterClockwise : { true, false })
  {
    points.clear();
    edges.clear();
    bool free = true;
    for (std::size_t j = run.first; j <= run.last && free; ++j)
    {
      free = fanPoints(mesh,
        adjacency,
        use,
        path[j],
        path[j - 1],
        path[j + 1],
        counterClockwise,
        offsetFraction,
        points,
        edges);
    }
    if (free)
    {
      return true;
    }
  }
  return false;
}

/// The runs of interior vertices of `path` that another path passes
/// through or ends at.
std::vector<Run> touchedRuns(const std::vector<int>& path, const std::vector<int>& vertexUses)
{
  std::vector<Run> runs;
  for (std::size_t i = 1; i + 1 < path.size(); ++i)
  {
    if (vertexUses[path[i]] < 2)
    {
      continue;
    }
    if (!runs.empty() && runs.back().last + 1 == i)
    {
      runs.back().last = i;
    }
    else
    {
      runs.push_back({ i, i });
    }
  }
  return runs;
}

} // namespace

SharedRunSeparation separateSharedRuns(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<std::vector<int>>& pathVertices,
  double offsetFraction)
{
  EdgeUse use;
  use.paths.assign(adjacency.edgeCount(), 0);
  use.crossed.assign(adjacency.edgeCount(), 0);
  std::vector<int> vertexUses(mesh.vertexCount(), 0);
  for (const std::vector<int>& path : pathVertices)
  {
    for (std::size_t i = 0; i < path.size(); ++i)
    {
      ++vertexUses[path[i]];
      if (i > 0)
      {
        ++use.paths[adjacency.findEdge(path[i - 1], path[i])];
      }
    }
  }
  SharedRunSeparation result;
  result.paths.resize(pathVertices.size());
  result.detours.assign(pathVertices.size(), 0);
  result.aroundVertices.resize(pathVertices.size());
  std::vector<SurfacePoint> runPoints;
  std::vector<int> runEdges;
  for (std::size_t k = 0; k < pathVertices.size(); ++k)
  {
    const std::vector<int>& path = pathVertices[k];
    std::vector<SurfacePoint>& points = result.paths[k].points;
    std::size_t next = 0; // next path vertex to copy
    for (const Run& run : touchedRuns(path, vertexUses))
    {
      if (!rerouteRun(mesh, adjacency, use, path, run, offsetFraction, runPoints, runEdges))
      {
        ++result.runsKept;
        continue;
      }
      for (; next < run.first; ++next)
      {
        points.push_back(SurfacePoint::atVertex(path[next]));
      }
      points.insert(points.end(), runPoints.begin(), runPoints.end());
      for (int e : runEdges)
      {
        use.crossed[e] = 1;
      }
      for (; next <= run.last; ++next)
      {
        --vertexUses[path[next]];
        result.aroundVertices[k].push_back(path[next]);
      }
      result.detours[k] += static_cast<int>(run.last - run.first + 1);
      ++result.runsSeparated;
    }
    for (; next < path.size(); ++next)
    {
      points.push_back(SurfacePoint::atVertex(path[next]));
    }
  }
  return result;
}

} // namespace thintissue
