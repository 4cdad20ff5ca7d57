#include "SurfaceContacts.h"

#include "ProximityQueries.h"
#include "ThinTissueError.h"
#include "TriangleBvh.h"

#include <algorithm>

namespace thintissue
{

namespace
{

void checkRadii(const TriangleMesh& mesh, const std::vector<double>& radii)
{
  if (!radii.empty() && radii.size() != mesh.vertexCount())
  {
    throw InvalidInputError("surface contacts: '" + mesh.name + "' has " +
                            std::to_string(radii.size()) + " radii for " +
                            std::to_string(mesh.vertexCount()) + " vertices");
  }
  if (std::any_of(radii.begin(), radii.end(), [](double r) { return !(r >= 0.0); }))
  {
    throw InvalidInputError("surface contacts: '" + mesh.name + "' has a negative radius");
  }
}

double radiusOf(const std::vector<double>& radii, int vertex)
{
  return radii.empty() ? 0.0 : radii[vertex];
}

/// Deepest contact of each vertex of `points` with the triangles of `mesh`.
void vertexContacts(const TriangleMesh& points,
  const std::vector<double>& pointRadii,
  const TriangleMesh& mesh,
  const std::vector<double>& meshRadii,
  double contactDistance,
  bool pointsAreA,
  std::vector<SurfaceContact>& contacts)
{
  if (points.vertexCount() == 0 || mesh.triangleCount() == 0)
  {
    return;
  }
  TriangleBvh tree;
  tree.build(mesh.positions, mesh.triangles, meshRadii, contactDistance);
  for (std::size_t v = 0; v < points.vertexCount(); ++v)
  {
    const Vector3& p = points.positions[v];
    const double r = radiusOf(pointRadii, static_cast<int>(v));
    BoundingBox query(p);
    query.extend(p + Vector3::Constant(r));
    query.extend(p - Vector3::Constant(r));
    SurfaceContact best;
    bool found = false;
    tree.forEachOverlap(query,
      [&](int t)
      {
        const Triangle& tri = mesh.triangles[t];
        const PointTriangleContact c = pointTriangleContact(p,
          r,
          mesh.positions[tri[0]],
          mesh.positions[tri[1]],
          mesh.positions[tri[2]],
          radiusOf(meshRadii, tri[0]),
          radiusOf(meshRadii, tri[1]),
          radiusOf(meshRadii, tri[2]),
          contactDistance);
        if (c.withinContactDistance && (!found || c.depth > best.depth))
        {
          found = true;
          best.depth = c.depth;
          best.side = c.side;
          best.triangle = t;
          best.vertex = static_cast<int>(v);
          best.vertexOfA = pointsAreA;
          // Keep both kinds on one convention: normal from B toward A.
          best.normal = pointsAreA ? c.normal : Vector3(-c.normal);
          best.point = c.trianglePoint;
        }
      });
    if (found)
    {
      contacts.push_back(best);
    }
  }
}

} // namespace

std::vector<SurfaceContact> findSurfaceContacts(const TriangleMesh& a,
  const std::vector<double>& radiiA,
  const TriangleMesh& b,
  const std::vector<double>& radiiB,
  double contactDistance)
{
  checkRadii(a, radiiA);
  checkRadii(b, radiiB);
  if (!(contactDistance >= 0.0))
  {
    throw InvalidInputError("surface contacts: the contact distance must not be negative");
  }
  std::vector<SurfaceContact> contacts;
  vertexContacts(a, radiiA, b, radiiB, contactDistance, true, contacts);
  vertexContacts(b, radiiB, a, radiiA, contactDistance, false, contacts);
  return contacts;
}

} // namespace thintissue
