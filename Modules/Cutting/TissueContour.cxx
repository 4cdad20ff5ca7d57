// 6.4.4: contouring the cut rim and measuring its roughness, for the tissue
// as a whole (the pieces still in it, at their current positions). The cut
// surface is smoothed by CuttableVisualMesh (JaggedCutSurface.cxx); here
// the tool's touch is turned into weights on the collision edges' parameters
// and the moved vertices are re-embedded where they are (5.3.5).
#include "TissueCutter.h"

#include "CorotationalHexFem.h"
#include "ThinTissueError.h"
#include "TrilinearCoordinates.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace thintissue
{

namespace
{

/// Distance from `point` to the segment (a, b).
double distanceToSegment(const Vector3& point, const Vector3& a, const Vector3& b)
{
  const Vector3 along = b - a;
  const double length2 = along.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((point - a).dot(along) / length2, 0.0, 1.0) : 0.0;
  return (a + t * along - point).norm();
}

} // namespace

CutRimContourReport TissueCutter::contour(const Vector3& centre, double radius, double strength)
{
  if (!centre.allFinite() || !(radius > 0.0) || !std::isfinite(radius) || !(strength >= 0.0) ||
      !(strength <= 1.0))
  {
    throw InvalidInputError("contouring '" + Collision.name() +
                            "': the tool needs a finite centre, a radius > 0 and a strength in "
                            "[0, 1] (radius " +
                            std::to_string(radius) + ", strength " + std::to_string(strength) +
                            ")");
  }
  requireNoVisualPending("contouring");
  const auto start = std::chrono::steady_clock::now();
  CutRimContourReport report;
  if (!HasVisual || VisualFailed)
    return report;
  const std::vector<Vector3>& nodes = Solver ? Solver->positions() : Simulation.nodes;
  // The edge last found near, at its current position (pull follows near).
  Vector3 from = Vector3::Zero(), to = Vector3::Zero();
  const auto near = [&](int a, int b)
  {
    const int t = Collision.trianglesOfEdge(a, b)[0];
    if (t < 0 || !Active[t])
      return false;
    from = CollisionEmbedding.mapPosition(a, nodes);
    to = CollisionEmbedding.mapPosition(b, nodes);
    return distanceToSegment(centre, from, to) < radius;
  };
  const auto pull = [&](int, int, double u)
  {
    const double d2 = ((1.0 - u) * from + u * to - centre).squaredNorm() / (radius * radius);
    return d2 < 1.0 ? strength * (1.0 - d2) * (1.0 - d2) : 0.0;
  };
  Visual.smoothCutSurface(near, pull, report.movedVertices);
  // The moved vertices stay in their hexahedra, at their new rest places.
  const auto& rest = Visual.mesh().positions;
  for (int v : report.movedVertices)
  {
    const int h = VisualEmbedding.hexahedron(v);
    Vector3 local = VisualEmbedding.localCoordinates(v);
    if (trilinearCoordinates(hexahedronCorners(Simulation, h), rest[v], local))
      VisualEmbedding.setPoint(v, h, local);
    else
      VisualEmbedding.reembed({ v }, { rest[v] }, Simulation, { h });
  }
  report.milliseconds =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return report;
}

CutSurfaceRoughness TissueCutter::cutRimRoughness() const
{
  if (!HasVisual)
    return {};
  return Visual.cutSurfaceRoughness(
    [&](int a, int b)
    {
      const int t = Collision.trianglesOfEdge(a, b)[0];
      return t >= 0 && Active[t];
    });
}

} // namespace thintissue
