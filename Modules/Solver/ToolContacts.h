// Contacts between a rigid tool made of capsules (centre-line segments with
// a radius: the thesis replaces the tool's collision mesh by its centre line,
// 6.3, table 6-2) and a deformable collision mesh with radii whose vertices
// are embedded in the hexahedra (thesis 5.1, 4.3). The result feeds
// CorotationalHexFem::setContacts.
#ifndef ToolContacts_h
#define ToolContacts_h

#include "CorotationalHexFem.h"
#include "HexahedralEmbedding.h"
#include "ThinTissueSolverModule.h"
#include "TriangleBvh.h"

#include <cstdint>
#include <vector>

namespace thintissue
{

/// A capsule of a tool, in world coordinates for the current pose.
struct ToolCapsule
{
  Vector3 start = Vector3::Zero(); ///< the handle side: a crossing pushes back toward it
  Vector3 end = Vector3::Zero();
  double radius = 0.0;
};

/// One contact of the tool with the tissue, for the tool's reaction and the
/// haptic loop (point, normal, depth, stiffness: enough to extrapolate the
/// force between physics steps).
struct ToolContact
{
  Vector3 point = Vector3::Zero();   ///< on the tissue's mid-surface
  Vector3 normal = Vector3::UnitZ(); ///< unit, from the tissue toward the tool
  double depth = 0.0;                ///< overlap of the radii
  double stiffness = 0.0;
  int triangle = -1;
  int side = 1; ///< side of the collision triangle touched (lower surface: -1)
};

/// The collision mesh of a tissue: triangles with per-vertex radii, vertices
/// embedded in the simulation hexahedra, positions and BVH refreshed from
/// the node positions each step (cost linear in the collision mesh).
class THINTISSUESOLVER_EXPORT DeformableCollisionMesh
{
public:
  /// `collision` holds rest positions, triangles and the "Radius" array
  /// (zero radii when absent); `hexahedra` the rest simulation mesh. The
  /// contact distance (>= 0) thickens the mesh in every contact query: the
  /// response keeps other bodies that far from its thick surface.
  DeformableCollisionMesh(const TriangleMesh& collision,
    const HexahedralMesh& hexahedra,
    double contactDistance = 0.0);
  /// The same from an embedding made elsewhere (a tissue being cut keeps
  /// its collision vertices in the hexahedron copy holding their branch,
  /// which a nearest-hexahedron search cannot tell from the original: they
  /// share their rest geometry). `embedding` has one point per vertex of
  /// `collision` (rest positions; update() maps the current ones).
  DeformableCollisionMesh(const TriangleMesh& collision,
    HexahedralEmbedding embedding,
    double contactDistance = 0.0);
  /// x = H u, then a BVH refit and the vertex normals. No allocation.
  void update(const std::vector<Vector3>& nodePositions);
  /// Area-weighted (unnormalised) vertex normals of the current positions.
  const std::vector<Vector3>& vertexNormals() const { return VertexNormals; }
  const std::vector<Vector3>& positions() const { return Positions; }
  const std::vector<Triangle>& triangles() const { return Triangles; }
  const std::vector<double>& radii() const { return Radii; }
  const HexahedralEmbedding& embedding() const { return Embedding; }
  const TriangleBvh& bvh() const { return Bvh; }
  double contactDistance() const { return ContactDistance; }
  /// Made anew with each mesh built (copies keep it): what a contact cache
  /// keyed on it found stays valid while the identity does (same
  /// triangles, radii and contact distance).
  std::uint64_t identity() const { return Identity; }

private:
  std::vector<Triangle> Triangles;
  std::vector<double> Radii;
  HexahedralEmbedding Embedding;
  std::vector<Vector3> Positions;
  TriangleBvh Bvh;
  std::vector<Vector3> VertexNormals;
  double ContactDistance = 0.0;
  std::uint64_t Identity = 0;

  void updateVertexNormals();
};

/// Penalty contacts of the capsules with the tissue: for each capsule its
/// deepest overlap with the thick collision triangles (one contact per
/// capsule, so the force does not depend on the mesh resolution), spread to
/// the triangle's three vertices by their barycentric weights (each an
/// EmbeddedContact with that share of `stiffness` and `damping`, so the
/// springs sum to the full one).
/// Appends to `embedded` (for the FEM) and `contacts` (for the tool).
THINTISSUESOLVER_EXPORT void findToolContacts(const DeformableCollisionMesh& tissue,
  const std::vector<ToolCapsule>& tool,
  double stiffness,
  double damping,
  std::vector<EmbeddedContact>& embedded,
  std::vector<ToolContact>& contacts);

/// A rigid obstacle (bone, cartilage treated as rigid, 5.4.4): a closed or
/// open triangle mesh, optionally with radii, and its BVH; the contact
/// distance thickens it in every query.
class THINTISSUESOLVER_EXPORT StaticObstacle
{
public:
  explicit StaticObstacle(const TriangleMesh& surface, double contactDistance = 0.0);
  const TriangleMesh& surface() const { return Surface; }
  const std::vector<double>& radii() const { return Radii; }
  const TriangleBvh& bvh() const { return Bvh; }
  double contactDistance() const { return Bvh.contactDistance(); }

private:
  TriangleMesh Surface;
  std::vector<double> Radii;
  TriangleBvh Bvh;
};

/// A tissue vertex pressing on an obstacle.
struct ObstacleContact
{
  int vertex = -1;                   ///< collision vertex of the tissue
  int triangle = -1;                 ///< triangle of the obstacle
  Vector3 point = Vector3::Zero();   ///< on the obstacle
  Vector3 normal = Vector3::UnitZ(); ///< unit, from the obstacle toward the tissue
  double depth = 0.0;
  /// Side of the tissue that touches: -1 when the obstacle lies on the
  /// negative side of the collision mesh (the meniscus's lower surface on
  /// the tibia; the wrinkles count these, 4.4), +1 otherwise.
  int tissueSide = 1;
};

/// Penalty contacts of the tissue's collision vertices (spheres of their
/// radius) with the obstacle: per vertex the deepest overlap, one
/// EmbeddedContact each. Appends to `embedded` and `contacts`.
THINTISSUESOLVER_EXPORT void findObstacleContacts(const DeformableCollisionMesh& tissue,
  const StaticObstacle& obstacle,
  double stiffness,
  double damping,
  std::vector<EmbeddedContact>& embedded,
  std::vector<ObstacleContact>& contacts);

} // namespace thintissue

#endif
