// The steps of the graph searches behind the geodesic paths (private to
// the Binding module: GeodesicPaths.cxx, SleeveGeodesic.cxx): along the
// edges, and straight across an edge through its two triangles unfolded.
#ifndef SurfaceSteps_h
#define SurfaceSteps_h

#include "TriangleMask.h"
#include "TriangleMesh.h"
#include "TriangleMeshAdjacency.h"

#include <algorithm>
#include <cmath>

namespace thintissue
{

/// Calls f(u, length, near, across) for the steps of the graph searches
/// from v: along
/// each edge (twice for an inner edge: once per triangle) and, with
/// `acrossEdges`, straight across each edge opposite v to the far vertex of
/// the next triangle, where that segment stays on the two triangles
/// (unfolded, it crosses the edge inside), through triangles `near` (v's)
/// and `across` (-1 both for a step along an edge). Every step is a path on the
/// surface, so the search distances bound geodesic distances from above;
/// and no step is shorter than its chord, so the straight-line distance
/// stays a consistent A* heuristic. The steps across edges make the search
/// metric close to the geodesic one on grid-like meshes, whose edge paths
/// zigzag up to sqrt(2) times longer against the diagonals.
template <class Function>
void forEachStep(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const TriangleMask& mask,
  int v,
  bool acrossEdges,
  Function&& f)
{
  const std::vector<Vector3>& p = mesh.positions;
  for (const int* t = adjacency.vertexTrianglesBegin(v); t != adjacency.vertexTrianglesEnd(v); ++t)
  {
    if (!mask(*t))
    {
      continue;
    }
    const Triangle& corners = mesh.triangles[*t];
    const int i = corners[0] == v ? 0 : (corners[1] == v ? 1 : 2);
    const int a = corners[(i + 1) % 3];
    const int b = corners[(i + 2) % 3];
    f(a, (p[a] - p[v]).norm(), -1, -1);
    f(b, (p[b] - p[v]).norm(), -1, -1);
    if (!acrossEdges)
    {
      continue;
    }
    const int next = adjacency.neighbourAcross(*t, (i + 1) % 3);
    if (next < 0 || !mask(next))
    {
      continue;
    }
    const Triangle& far = mesh.triangles[next];
    const int w =
      far[0] != a && far[0] != b ? far[0] : (far[1] != a && far[1] != b ? far[1] : far[2]);
    // Unfolded about edge (a, b), the angles of the two triangles add up
    // to A at a and to B at b; the segment v-w crosses the edge inside iff
    // both are below pi, and its length follows from A (law of cosines).
    auto sumOfAngles = [&](int corner, int other, double& cosine, double& sine)
    {
      const Vector3 edge = (p[other] - p[corner]).normalized();
      const Vector3 toV = (p[v] - p[corner]).normalized();
      const Vector3 toW = (p[w] - p[corner]).normalized();
      const double c1 = toV.dot(edge), s1 = toV.cross(edge).norm();
      const double c2 = toW.dot(edge), s2 = toW.cross(edge).norm();
      cosine = c1 * c2 - s1 * s2;
      sine = s1 * c2 + c1 * s2;
    };
    double cosA, sinA, cosB, sinB;
    sumOfAngles(a, b, cosA, sinA);
    sumOfAngles(b, a, cosB, sinB);
    if (!(sinA > 0.0 && sinB > 0.0))
    {
      continue;
    }
    const double lv = (p[v] - p[a]).norm();
    const double lw = (p[w] - p[a]).norm();
    const double squared = lv * lv + lw * lw - 2.0 * lv * lw * cosA;
    f(w, std::max(std::sqrt(std::max(squared, 0.0)), (p[w] - p[v]).norm()), *t, next);
  }
}

} // namespace thintissue

#endif
