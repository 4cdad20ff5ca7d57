// The connected pieces of a triangle surface: a segmentation often holds
// several tissues (both menisci in one file) and fragments of noise, and
// each tissue must be prepared on its own (a collision mid-surface spanning
// two menisci would bind one to the other).
//
// Triangles are in one piece when a chain of shared edges joins them. Two
// tissues that only touch at a vertex (a bow-tie, as marching cubes leaves
// where two labels touch) stay two pieces: the shared vertex is copied into
// each. Pieces are sorted by surface area, largest first; a piece is a
// fragment when its area is below a fraction of the largest piece's.
#ifndef MeshPieces_h
#define MeshPieces_h

#include "ThinTissueCoreModule.h"
#include "TriangleMesh.h"
#include "TriangleMeshAdjacency.h"

#include <functional>
#include <string>
#include <vector>

namespace thintissue
{

struct MeshPiece
{
  /// The piece as a mesh of its own (normals, texture, point attributes
  /// kept), named "<mesh name> piece <number>".
  TriangleMesh mesh;
  /// 1 for the largest piece, 2 for the next, ...
  int number = 0;
  /// Per vertex of `mesh`: its index in the input mesh.
  std::vector<int> originalVertices;
  double area = 0.0;
  /// Area-weighted centre of the surface.
  Vector3 centre = Vector3::Zero();
  /// Largest side of the bounding box.
  double largestExtent = 0.0;

  /// "piece 3: 24 vertices, 44 triangles, area 0.31, centre (1.2, 3.4, 5.6)".
  std::string description() const;
};

/// The triangles of each piece (joined through shared edges), each list in
/// increasing order, pieces in the order of their first triangle.
THINTISSUECORE_EXPORT std::vector<std::vector<int>> edgeConnectedTriangles(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency);

/// Per triangle its piece, flooded across the edges where `joined(t, k)`
/// (triangle t and its neighbour across its edge k belong together; asked
/// of manifold edges only), pieces numbered in the order of their first
/// triangle. Returns the number of pieces.
THINTISSUECORE_EXPORT int floodTrianglePieces(const TriangleMeshAdjacency& adjacency,
  std::size_t triangleCount,
  const std::function<bool(int triangle, int edge)>& joined,
  std::vector<int>& piece);

/// The border loops of a mesh: its border edges joined end to end, each
/// loop as its vertices in order (in either direction), loops in the order
/// of their lowest vertex. InvalidInputError naming `meshLabel` when a
/// border vertex joins other than two border edges.
THINTISSUECORE_EXPORT std::vector<std::vector<int>> borderLoops(
  const TriangleMeshAdjacency& adjacency,
  std::size_t vertexCount,
  const std::string& meshLabel);

/// How many pieces `mesh` has (without copying them).
THINTISSUECORE_EXPORT std::size_t countPieces(const TriangleMesh& mesh);

/// The pieces of `mesh`, largest area first; a mesh without triangles has
/// none. Vertices used by no triangle are left out.
THINTISSUECORE_EXPORT std::vector<MeshPiece> splitIntoPieces(const TriangleMesh& mesh);

struct PieceSelection
{
  std::vector<MeshPiece> kept;
  /// Fragments: area below minimumFraction times the largest piece's area.
  std::vector<MeshPiece> dropped;
};

/// Splits `mesh` and sorts its pieces into kept and dropped (fragments).
/// `minimumFraction` in [0, 1]: 0 keeps every piece. Throws
/// InvalidInputError for a fraction outside [0, 1].
THINTISSUECORE_EXPORT PieceSelection selectPieces(const TriangleMesh& mesh, double minimumFraction);

} // namespace thintissue

#endif
