// Narrow-phase kernels shared by the tool, obstacle and scene contact
// routines (private to the Solver module): a thick triangle mesh seen
// through references, the deepest contact of a sphere or a capsule with it,
// and the feature contacts between two thick meshes (vertex-face both ways,
// edge-edge), each feature reported once.
#ifndef ContactKernels_h
#define ContactKernels_h

#include "ProximityQueries.h"
#include "ToolContacts.h"
#include "TriangleBvh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace thintissue
{
namespace contact_kernels
{

/// A triangle mesh with radii and its (built or refitted) BVH. Vertex
/// normals are optional (null): they decide which side of a tissue a
/// contact touches.
struct ThickMeshView
{
  const std::vector<Vector3>* positions = nullptr;
  const std::vector<Triangle>* triangles = nullptr;
  const std::vector<double>* radii = nullptr;
  const TriangleBvh* bvh = nullptr;
  const std::vector<Vector3>* vertexNormals = nullptr;
  /// Added to the thickness in every query with this mesh (its BVH boxes
  /// are inflated by it): contacts start when the thick surfaces are this
  /// close, and the response holds them this far apart.
  double contactDistance = 0.0;
  /// Same value while the mesh keeps its triangles and radii
  /// (DeformableCollisionMesh::identity); 0: unknown (nothing is cached).
  std::uint64_t identity = 0;
};

ThickMeshView viewOf(const DeformableCollisionMesh& mesh);
ThickMeshView viewOf(const StaticObstacle& obstacle);

struct DeepestPointContact
{
  PointTriangleContact contact;
  int triangle = -1; ///< -1: no penetration
};
/// The deepest penetrating thick triangle of `mesh` for a sphere.
DeepestPointContact deepestSphereContact(const Vector3& centre,
  double radius,
  const ThickMeshView& mesh);

struct DeepestSegmentContact
{
  SegmentTriangleContact contact;
  int triangle = -1; ///< -1: no penetration
};
/// The deepest penetrating thick triangle of `mesh` for a capsule.
DeepestSegmentContact deepestCapsuleContact(const ToolCapsule& capsule, const ThickMeshView& mesh);

/// A contact between features of meshes A and B: the contact point on each
/// mid-surface as a combination of up to three of its vertices.
struct FeatureContact
{
  std::array<int, 3> verticesA{ { -1, -1, -1 } };
  Vector3 weightsA = Vector3::Zero();
  std::array<int, 3> verticesB{ { -1, -1, -1 } };
  Vector3 weightsB = Vector3::Zero();
  Vector3 pointA = Vector3::Zero();
  Vector3 pointB = Vector3::Zero();
  Vector3 normal = Vector3::UnitZ(); ///< unit, from B toward A
  double depth = 0.0;
  /// Side of A (of B) that the other mesh touches, from A's (B's) vertex
  /// normals when given, else +1.
  int sideOnA = 1;
  int sideOnB = 1;
};

/// Reused buffers of meshMeshContacts (no allocation once warm).
struct MeshMeshWorkspace
{
  struct EdgeContact
  {
    std::uint64_t edgeOfA = 0; ///< lower vertex << 32 | upper vertex
    std::uint64_t edgeOfB = 0;
    FeatureContact contact;
  };
  std::vector<EdgeContact> edgeContacts;
  /// Vertices of A / B with a vertex-face contact (all false between calls).
  std::vector<char> touchingA;
  std::vector<char> touchingB;
  /// Boxes of A's edges (3 per triangle; those near B filled per call).
  std::vector<BoundingBox> edgeBoxesOfA;
};

/// Penetrating feature contacts between two thick meshes: every vertex of A
/// against B's triangles and every vertex of B against A's (the deepest per
/// vertex), and edge-edge pairs whose closest points are inside both edges
/// (one per edge pair; the end points are the vertex contacts' business),
/// kept only where no end of either edge has a vertex contact: there the
/// vertex contacts already hold the surfaces (face to face), and edge-edge
/// contacts would count the same overlap again; they are needed where
/// edges cross with their ends free (a blade across a coarse triangle).
/// Appends to `contacts`.
void meshMeshContacts(const ThickMeshView& a,
  const ThickMeshView& b,
  MeshMeshWorkspace& workspace,
  std::vector<FeatureContact>& contacts);

/// The features of a deformable mesh A that may touch a static mesh B
/// while no vertex of A moves more than `margin` from where it was when
/// they were found (temporal coherence: a tissue resting on a bone moves
/// little from step to step). Kept by meshStaticContacts.
struct StaticPairCandidates
{
  std::uint64_t identityOfA = 0; ///< 0: nothing found yet
  const TriangleBvh* treeOfB = nullptr;
  double margin = 0.0;
  std::vector<Vector3> positionsOfA; ///< when found
  /// B's triangles near each vertex of A: vertexTriangles[vertexStart[v],
  /// vertexStart[v + 1]), in the order B's tree visits them, each with its
  /// (fixed) inflated box.
  std::vector<int> vertexStart;
  std::vector<int> vertexTriangles;
  std::vector<BoundingBox> vertexTriangleBoxes;
  /// Per candidate pair (vertexTriangles, trianglesOfA, edgePairs): how far
  /// its features were from touching when found (distance less the largest
  /// thickness they can have). A pair whose features moved less than that
  /// since cannot touch, and is skipped before any box or distance test.
  std::vector<double> vertexTriangleClearances;
  /// B's vertices near A, ascending, and A's triangles near each:
  /// triangleOfA[triangleStart[k], triangleStart[k + 1]) for verticesOfB[k],
  /// in the order A's tree visits them (refitting keeps that order).
  std::vector<int> verticesOfB;
  std::vector<int> triangleStart;
  std::vector<int> trianglesOfA;
  std::vector<double> triangleOfAClearances;
  /// Owned edges of A and B (as their owning triangles orient them) that
  /// may come within reach, with B's edge box.
  struct EdgePair
  {
    int a0 = 0, a1 = 0, triangleA = 0;
    int b0 = 0, b1 = 0, triangleB = 0;
    BoundingBox boxB;
    double clearance = 0.0;
  };
  std::vector<EdgePair> edgePairs;
  /// Per vertex of A: how far it is from where it was when found (this
  /// step's).
  std::vector<double> movesOfA;
  int searches = 0; ///< times the candidates were found (for tests, benchmarks)
};

/// meshMeshContacts(a, b, ...) for a static `b` (an obstacle: positions,
/// radii and tree never change), the same contacts in the same order,
/// bit for bit; the candidate features are searched again only when a
/// vertex of `a` has moved more than `margin` since the last search, or
/// `a` changed (another identity; an identity of 0 searches every call).
/// While its identity holds, `a`'s tree must only be refitted (the order in
/// which its leaves are visited decides between equally deep contacts).
void meshStaticContacts(const ThickMeshView& a,
  const ThickMeshView& b,
  double margin,
  StaticPairCandidates& candidates,
  MeshMeshWorkspace& workspace,
  std::vector<FeatureContact>& contacts);

} // namespace contact_kernels
} // namespace thintissue

#endif
