// The visual-collision binding of the thesis's pre-processing phase (5.2):
// every vertex of the fine closed visual surface is bound to a vertex, an
// edge or a triangle (and side) of the coarse collision mid-surface, with
// local parameters, so that cutting a collision triangle can cut exactly the
// visual triangles bound to it (5.3).
//
//  5.2.1 Pairing: a border collision vertex takes the closest visual vertex;
//        an inner one the visual vertex closest to its normal line on each
//        side (+ and -). No visual vertex serves two collision vertices.
//  5.2.2 Paths: for every collision edge and side, the exact geodesic path
//        between the two paired visual vertices (GeodesicPaths.h). A border
//        edge has one path, along the rim, between its + and - regions.
//        An edge of three triangles (a horizontal cleavage's junction,
//        CollisionSides.h) has three: the top (+1), the bottom (-1) and the
//        cleft's crease (0); a vertex inside a junction a third paired
//        visual vertex, on the crease.
//  5.2.3 Re-meshing: the paths are inserted into the visual mesh
//        (PathRemeshing.h) and the regions they bound are flood-filled: one
//        region per collision triangle and side, a topological disk.
//  5.2.4 Parameters: a vertex on a path by its accumulated length along the
//        path; a vertex inside a region by Floater's mean value coordinates,
//        the region mapped onto its collision triangle with the boundary
//        fixed (one sparse solve per region). Formula 5-1: every visual
//        vertex bound to collision triangle (v1, v2, v3) is a v1 + b v2 + c v3.
//
// The thesis writes the edge parameter of fig. 5-5(b) as
// v_a = L1/L v1 + (1 - L1/L) v2, which puts a point near v1 near v2; the
// binding uses the intended v_a = (1 - L1/L) v1 + L1/L v2.
#ifndef VisualCollisionBinding_h
#define VisualCollisionBinding_h

#include "CollisionSides.h"
#include "SurfacePath.h"
#include "ThinTissueBindingModule.h"
#include "ThinTissueError.h"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace thintissue
{

enum class BindingKind : std::uint8_t
{
  CollisionVertex = 0,
  CollisionEdge = 1,
  CollisionTriangle = 2
};

/// The binding of one visual vertex.
struct VisualVertexBinding
{
  BindingKind kind = BindingKind::CollisionTriangle;
  /// Collision vertex, edge (index into VisualCollisionBinding::collisionEdges)
  /// or triangle.
  int element = -1;
  /// +1 / -1: the side of the collision surface; 0 for what lies on the rim
  /// between both (a border collision vertex's visual vertex, the path of a
  /// border edge).
  int side = 0;
  /// Vertex: (1, 0, 0). Edge (a, b) = collisionEdges[element]: (1 - t, t, 0),
  /// the point (1 - t) a + t b. Triangle: barycentric (a, b, c) of its
  /// vertices, in [0, 1], summing to 1.
  Vector3 parameters = Vector3(1.0, 0.0, 0.0);
};

/// One geodesic path of the binding, as vertices of the re-meshed visual
/// mesh from the visual vertex of the edge's first collision vertex to that
/// of its second.
struct BindingPath
{
  int collisionEdge = -1;
  /// +1, -1, or 0 for a border edge's rim path and a junction's crease
  /// path (CollisionSides::pathSide).
  int side = 0;
  std::vector<int> visualVertices;
  double length = 0.0; ///< in the rest configuration
  /// Vertices of the geodesic the path was re-routed around, where another
  /// path touched it (SharedPathRuns.h), and, for an inner path, its
  /// vertices a rim path was re-routed around (its half widened there): 0
  /// for an exact geodesic. Not carried by the VTK binding arrays (0 when
  /// read back from them).
  int detours = 0;
};

/// How the rim paths (the equator between the positive and negative halves
/// of the visual surface, 5.2.2) are found.
enum class RimPathMethod
{
  /// Geodesics between the rim points (the thesis's); where a rough rim
  /// defeats them, the labelled equator before the first error is reported.
  Automatic,
  /// Geodesics between the rim points only.
  Geodesic,
  /// The border between the visual triangles labelled by the side of the
  /// collision mid-surface they lie on; the rim points move onto it (no
  /// junctions: a horizontal cleavage takes the geodesics).
  Labelled
};

struct VisualCollisionBindingSettings
{
  /// Name of the per-vertex radius array of the collision mesh.
  std::string radiusArrayName = "Radius";
  /// A collision vertex counts as inside the visual volume when its winding
  /// number is >= 1/2 or it lies within this distance of the surface
  /// (relative to the visual bounding-box diagonal): border vertices sit on
  /// the rim.
  double insideTolerance = 1e-3;
  /// The visual mesh is thin when, at every inner collision vertex, the
  /// visual surface is hit along the normal on both sides within this many
  /// radii (thickness check).
  double thinnessFactor = 4.0;
  /// Computes the geodesic paths in parallel (the result does not depend on
  /// it).
  bool parallel = true;
  RimPathMethod rimPaths = RimPathMethod::Automatic;
};

/// Progress: `fraction` in [0, 1] and what is being done; return false to
/// abort (bindVisualToCollision then throws BindingAbortedError).
using BindingProgress = std::function<bool(double fraction, const char* stage)>;

class THINTISSUEBINDING_EXPORT BindingAbortedError : public Error
{
public:
  using Error::Error;
};

class THINTISSUEBINDING_EXPORT VisualCollisionBinding
{
public:
  /// The re-meshed visual surface (the input surface with the paths'
  /// points inserted; geometrically identical).
  TriangleMesh visual;
  /// The collision rest positions and triangles the binding was made for.
  std::vector<Vector3> collisionPositions;
  std::vector<Triangle> collisionTriangles;
  /// The collision mesh's radius per vertex (half the local thickness).
  std::vector<double> collisionRadii;
  /// Edges of the collision mesh, each (lower, higher) vertex index.
  std::vector<std::array<int, 2>> collisionEdges;
  /// Per collision vertex: its visual vertex on the + and - side (the same
  /// vertex twice for a border vertex).
  std::vector<std::array<int, 2>> pairedVisualVertices;
  /// Per collision vertex inside a junction: its visual vertex on the
  /// cleft's crease (-1 at every other vertex).
  std::vector<int> creaseVisualVertices;
  /// Which half of the visual surface each collision triangle side faces,
  /// and the junction vertices.
  CollisionSides collisionSides;
  /// Per visual vertex.
  std::vector<VisualVertexBinding> vertices;
  /// Per visual triangle: the collision triangle and side of its region.
  std::vector<int> triangleRegion;
  std::vector<std::int8_t> triangleSide;
  std::vector<BindingPath> paths;

  /// Where visual vertex v projects on the collision mesh with the given
  /// collision positions (formula 5-1).
  Vector3 projectedPoint(std::size_t v, const std::vector<Vector3>& positions) const;
  /// Parameters (a, b, c) of visual vertex v in collision triangle t (fig.
  /// 5-6): the vertex must be bound to t, one of its edges or vertices.
  /// Throws InvalidInputError otherwise.
  Vector3 parametersInTriangle(std::size_t v, int t) const;
  /// Index of collision edge (a, b), -1 if there is none.
  int collisionEdgeIndex(int a, int b) const;
  /// The paired visual vertex of collision vertex v that side `side` of
  /// collision triangle t (one of v's triangles) sees.
  int pairedVisualVertex(int v, int t, int side) const;
  /// Per collision edge and side label + 1 (label -1, 0, +1 as in
  /// BindingPath::side): the visual vertices its path joins, from the
  /// edge's first vertex to its second; -1 where the edge has no such path.
  std::vector<std::array<std::array<int, 2>, 3>> pathEnds() const;
};

/// Builds the binding. `visual`: closed, manifold, consistently oriented,
/// thin; `collision`: the mid-surface with a positive radius per vertex
/// (settings.radiusArrayName), inside the visual volume. Bad input throws
/// InvalidInputError naming the mesh and its first offending element.
THINTISSUEBINDING_EXPORT VisualCollisionBinding bindVisualToCollision(const TriangleMesh& visual,
  const TriangleMesh& collision,
  const VisualCollisionBindingSettings& settings = {},
  const BindingProgress& progress = {});

} // namespace thintissue

#endif
