// Re-meshing of the visual mesh along surface paths (thesis 5.2.3, fig.
// 5-4): every path point becomes a vertex (points inside edges split the
// edges, so that all triangles beside an edge are split consistently and the
// mesh stays conforming), every path segment becomes a mesh edge, and each
// triangle crossed by paths is re-triangulated inside its own plane. The
// surface is geometrically the same (new vertices lie on the old edges);
// texture coordinates (per corner, seams kept), normals and point attributes
// are interpolated linearly along the split edges.
//
// Triangulation: a triangle's border (its corners and the vertices inserted
// on its sides) is cut along the path chords into convex faces, and each
// face is triangulated by clipping ears, best shaped first, never across
// three points of one straight side or chord. Collinearity is decided from
// which side or chord a point lies on, not by floating-point tests, so no
// triangle has three collinear corners (a piece is thin only where inserted
// vertices lie close to each other or to a corner) and every piece keeps
// the parent's orientation. No vertex is added inside a triangle.
#ifndef PathRemeshing_h
#define PathRemeshing_h

#include "SurfacePath.h"
#include "ThinTissueBindingModule.h"
#include "ThinTissueError.h"

#include <vector>

namespace thintissue
{

struct RemeshedSurface
{
  /// The re-meshed surface. Vertices: the input's, unchanged and in order,
  /// then the inserted ones, edge by edge in the order the paths first
  /// reach each edge (path by path, point by point), along each edge from
  /// its smaller-index end. Triangles: triangle t < input triangle count is
  /// input triangle t if no path touches it, else the first piece of it;
  /// the other pieces follow, grouped by increasing input triangle. Texture
  /// coordinates: the input's, then the inserted vertices' (one entry per
  /// vertex and distinct value: two on a texture seam). Normals and point
  /// attributes: one per vertex as in the input.
  TriangleMesh mesh;
  /// Per input path, its points as vertices of `mesh`, source to target.
  /// Consecutive vertices are distinct and joined by an edge of `mesh`: a
  /// path running along an edge visits the vertices inserted on it by
  /// other paths; repeated consecutive points are kept once.
  std::vector<std::vector<int>> pathVertices;
  /// Per vertex of `mesh`: the input vertex it is (old vertices keep their
  /// indices: vertex v < input vertex count is input vertex v), -1 for an
  /// inserted one.
  std::vector<int> inputVertex;
  /// Per inserted vertex (vertex input vertex count + i): the input edge it
  /// lies inside and its parameter there (SurfacePoint::onEdge form).
  std::vector<SurfacePoint> insertedOn;
  /// Per triangle of `mesh`: the input triangle it lies in.
  std::vector<int> inputTriangle;
};

/// Two paths crossing inside a triangle (insertPaths): which ones, so that
/// a caller can find one of them again off the other's triangles.
class THINTISSUEBINDING_EXPORT PathsCrossError : public InvalidInputError
{
public:
  PathsCrossError(const std::string& message, int firstPath, int secondPath, int triangle)
    : InvalidInputError(message)
    , FirstPath(firstPath)
    , SecondPath(secondPath)
    , CrossedTriangle(triangle)
  {
  }
  int firstPath() const { return FirstPath; }
  int secondPath() const { return SecondPath; }
  int triangle() const { return CrossedTriangle; }

private:
  int FirstPath;
  int SecondPath;
  int CrossedTriangle;
};

/// Inserts the paths into `mesh` (closed or open, edge-manifold; non-manifold
/// edges are split in all their triangles). Points of paths on the same edge
/// within `mergeTolerance` times the edge length of the smallest of them are
/// one vertex, placed there (paths may share points); points that close to
/// an edge's end are that end vertex.
///
/// Inserted vertices: position, normal (renormalised; the first triangle's
/// normal where the end normals cancel) and every point attribute
/// interpolated linearly along the edge; texture coordinates interpolated
/// in each triangle from that triangle's own corners.
///
/// Throws InvalidInputError naming the mesh on an inconsistent mesh
/// (TriangleMesh::checkConsistency), a merge tolerance outside [0, 0.5),
/// when a path point refers to a missing vertex or edge (or an edge given
/// end first, or a parameter outside [0, 1]), when two consecutive path
/// points do not share a triangle, when a crossed triangle repeats a
/// vertex, or when two paths cross inside a triangle (PathsCrossError,
/// naming the paths and the triangle; they may touch, i.e. share a point,
/// never cross).
///
/// Cost: one copy of the mesh and one pass over its triangles, plus time in
/// proportion to the path points and the triangles they cross. Deterministic
/// (same input, bit-identical output).
THINTISSUEBINDING_EXPORT RemeshedSurface insertPaths(const TriangleMesh& mesh,
  const std::vector<SurfacePath>& paths,
  double mergeTolerance = 1e-9);

} // namespace thintissue

#endif
