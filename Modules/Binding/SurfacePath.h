// A path on a triangle mesh as the thesis's geodesic paths give it (5.2.2):
// straight within each triangle, so it is a sequence of points each of
// which is a mesh vertex or a point inside a mesh edge.
#ifndef SurfacePath_h
#define SurfacePath_h

#include "TriangleMesh.h"

#include <cmath>
#include <cstddef>
#include <vector>

namespace thintissue
{

/// A vertex of the mesh (vertex >= 0), or the point
/// (1 - edgeParameter) p[edgeStart] + edgeParameter p[edgeEnd] inside the
/// edge (edgeStart < edgeEnd, 0 < edgeParameter < 1).
struct SurfacePoint
{
  int vertex = -1;
  int edgeStart = -1;
  int edgeEnd = -1;
  double edgeParameter = 0.0;

  static SurfacePoint atVertex(int v)
  {
    SurfacePoint p;
    p.vertex = v;
    return p;
  }
  /// On edge (a, b) at parameter t from a; stored with edgeStart < edgeEnd.
  static SurfacePoint onEdge(int a, int b, double t)
  {
    SurfacePoint p;
    p.edgeStart = a < b ? a : b;
    p.edgeEnd = a < b ? b : a;
    p.edgeParameter = a < b ? t : 1.0 - t;
    return p;
  }
  bool isVertex() const { return vertex >= 0; }
  Vector3 position(const std::vector<Vector3>& positions) const
  {
    return isVertex() ? positions[vertex]
                      : Vector3((1.0 - edgeParameter) * positions[edgeStart] +
                                edgeParameter * positions[edgeEnd]);
  }
};

/// From the source vertex (first point) to the target vertex (last point);
/// consecutive points lie on a common triangle.
struct SurfacePath
{
  std::vector<SurfacePoint> points;
  double length = 0.0;

  /// Appends `point` unless it is the last point again (the same vertex, or
  /// the same edge within `tolerance` in edge parameter).
  void appendMerged(const SurfacePoint& point, double tolerance)
  {
    if (!points.empty())
    {
      const SurfacePoint& last = points.back();
      const bool same = point.isVertex()
                          ? last.vertex == point.vertex
                          : (!last.isVertex() && last.edgeStart == point.edgeStart &&
                              last.edgeEnd == point.edgeEnd &&
                              std::abs(last.edgeParameter - point.edgeParameter) <= tolerance);
      if (same)
      {
        return;
      }
    }
    points.push_back(point);
  }
  /// Sets `length` to the sum of the straight segments between the points.
  void measure(const std::vector<Vector3>& positions)
  {
    length = 0.0;
    for (std::size_t i = 1; i < points.size(); ++i)
    {
      length += (points[i].position(positions) - points[i - 1].position(positions)).norm();
    }
  }
};

} // namespace thintissue

#endif
