#include "ToolContacts.h"

#include "ContactKernels.h"
#include "ThinTissueError.h"

#include <atomic>
#include <string>
#include <utility>

namespace thintissue
{

namespace
{

/// Identities of the collision meshes built so far (never 0).
std::atomic<std::uint64_t> LastIdentity{ 0 };

std::vector<double> radiiOf(const TriangleMesh& collision)
{
  return collision.pointAttributes.has("Radius")
           ? collision.pointAttributes.get("Radius").values
           : std::vector<double>(collision.vertexCount(), 0.0);
}

} // namespace

DeformableCollisionMesh::DeformableCollisionMesh(const TriangleMesh& collision,
  const HexahedralMesh& hexahedra,
  double contactDistance)
  : DeformableCollisionMesh(collision,
      HexahedralEmbedding(hexahedra, collision.positions),
      contactDistance)
{
}

DeformableCollisionMesh::DeformableCollisionMesh(const TriangleMesh& collision,
  HexahedralEmbedding embedding,
  double contactDistance)
  : Triangles(collision.triangles)
  , Radii(radiiOf(collision))
  , Embedding(std::move(embedding))
  , Positions(collision.positions)
  , ContactDistance(contactDistance)
  , Identity(++LastIdentity)
{
  if (!(contactDistance >= 0.0))
  {
    throw InvalidInputError("collision mesh '" + collision.name + "': negative contact distance");
  }
  if (Embedding.pointCount() != Positions.size())
  {
    throw InvalidInputError(
      "collision mesh '" + collision.name + "': " + std::to_string(Positions.size()) +
      " vertices but an embedding of " + std::to_string(Embedding.pointCount()) + " points");
  }
  Bvh.build(Positions, Triangles, Radii, ContactDistance);
  VertexNormals.resize(Positions.size());
  updateVertexNormals();
}

void DeformableCollisionMesh::update(const std::vector<Vector3>& nodePositions)
{
  Embedding.mapPositions(nodePositions, Positions);
  Bvh.refit(Positions, Radii);
  updateVertexNormals();
}

void DeformableCollisionMesh::updateVertexNormals()
{
  // Area-weighted, unnormalised: only their direction is used (which side
  // of the tissue touches an obstacle).
  std::fill(VertexNormals.begin(), VertexNormals.end(), Vector3::Zero());
  for (const Triangle& t : Triangles)
  {
    const Vector3 n = (Positions[t[1]] - Positions[t[0]]).cross(Positions[t[2]] - Positions[t[0]]);
    for (int k = 0; k < 3; ++k)
    {
      VertexNormals[t[k]] += n;
    }
  }
}

void findToolContacts(const DeformableCollisionMesh& tissue,
  const std::vector<ToolCapsule>& tool,
  double stiffness,
  double damping,
  std::vector<EmbeddedContact>& embedded,
  std::vector<ToolContact>& contacts)
{
  const contact_kernels::ThickMeshView view = contact_kernels::viewOf(tissue);
  const auto& embedding = tissue.embedding();
  for (const ToolCapsule& capsule : tool)
  {
    // The deepest overlap of this capsule: one contact per capsule, so the
    // force does not grow with the collision mesh's resolution.
    const contact_kernels::DeepestSegmentContact deepest =
      contact_kernels::deepestCapsuleContact(capsule, view);
    if (deepest.triangle < 0)
    {
      continue;
    }
    ToolContact contact;
    contact.point = deepest.contact.trianglePoint;
    contact.normal = deepest.contact.normal;
    contact.depth = deepest.contact.depth;
    contact.stiffness = stiffness;
    contact.triangle = deepest.triangle;
    contact.side = deepest.contact.side;
    contacts.push_back(contact);
    // The tissue is pushed away from the tool (along -normal), the spring
    // spread over the triangle's vertices by their barycentric weights.
    const Triangle& tri = tissue.triangles()[deepest.triangle];
    for (int k = 0; k < 3; ++k)
    {
      const double share = deepest.contact.barycentric[k];
      if (share <= 0.0)
      {
        continue;
      }
      EmbeddedContact spring;
      spring.hexahedron = static_cast<std::size_t>(embedding.hexahedron(tri[k]));
      spring.local = embedding.localCoordinates(tri[k]);
      spring.normal = -deepest.contact.normal;
      spring.depth = deepest.contact.depth;
      spring.stiffness = share * stiffness;
      spring.damping = share * damping;
      embedded.push_back(spring);
    }
  }
}

StaticObstacle::StaticObstacle(const TriangleMesh& surface, double contactDistance)
  : Surface(surface)
  , Radii(surface.pointAttributes.has("Radius") ? surface.pointAttributes.get("Radius").values
                                                : std::vector<double>(surface.vertexCount(), 0.0))
{
  Bvh.build(Surface.positions, Surface.triangles, Radii, contactDistance);
}

void findObstacleContacts(const DeformableCollisionMesh& tissue,
  const StaticObstacle& obstacle,
  double stiffness,
  double damping,
  std::vector<EmbeddedContact>& embedded,
  std::vector<ObstacleContact>& contacts)
{
  const auto& positions = tissue.positions();
  const auto& radii = tissue.radii();
  const auto& vertexNormals = tissue.vertexNormals();
  const contact_kernels::ThickMeshView view = contact_kernels::viewOf(obstacle);
  for (std::size_t v = 0; v < positions.size(); ++v)
  {
    const contact_kernels::DeepestPointContact deepest =
      contact_kernels::deepestSphereContact(positions[v], radii[v], view);
    if (deepest.triangle < 0)
    {
      continue;
    }
    ObstacleContact contact;
    contact.vertex = static_cast<int>(v);
    contact.triangle = deepest.triangle;
    contact.point = deepest.contact.trianglePoint;
    contact.normal = deepest.contact.normal;
    contact.depth = deepest.contact.depth;
    contact.tissueSide = vertexNormals[v].dot(deepest.contact.normal) > 0.0 ? -1 : 1;
    contacts.push_back(contact);
    EmbeddedContact spring;
    spring.hexahedron = static_cast<std::size_t>(tissue.embedding().hexahedron(v));
    spring.local = tissue.embedding().localCoordinates(v);
    spring.normal = deepest.contact.normal;
    spring.depth = deepest.contact.depth;
    spring.stiffness = stiffness;
    spring.damping = damping;
    embedded.push_back(spring);
  }
}

} // namespace thintissue
