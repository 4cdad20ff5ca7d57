// Exact geodesic paths on a triangle mesh (thesis 5.2.2): the algorithm of
// Xin and Wang (the thesis's reference [165]) as CGAL's
// Surface_mesh_shortest_path implements it, run on a local patch of the
// mesh around the two end vertices so that the cost does not grow with the
// whole mesh (GeodesicAlgorithm::CgalPatch, the default).
//
// GeodesicAlgorithm::Sleeve (SleeveGeodesic.h) is 10 to 20 times faster:
// the funnel through a sleeve of triangles along the path, rerouted round
// vertices until the path is locally shortest. A locally shortest path is
// not always the shortest: on the sheets' faces, the meniscus and round
// slits it gives CGAL's paths, but where several geodesics join two
// vertices (over a thin rim, round the bumps of a rough segmentation) it
// can keep a longer one (measured in Documentation/Architecture.md), which
// the binding does not accept. It is kept for what needs a fast geodesic
// or a tight upper bound of the distance.
//
// Patch: the triangles having a vertex v with d(s, v) + d(v, t) <= lambda
// * d(s, t) (the stars of those vertices), d being Dijkstra distances from
// the source s and the target t along edges and straight across each edge
// between the two far corners of its triangles, where that segment stays on
// them (an ellipse in a metric close to the geodesic one; every step is a
// path on the surface, so d(s, t) bounds the geodesic length from above).
// Plain edge paths would not do: on the grid-like sheets they zigzag up to
// sqrt(2) times longer than geodesics against the diagonals, and the
// ellipse, and CGAL's time, would balloon for such directions.
//
// If the exact path on the patch touches the patch's border (a vertex or
// edge of the patch that is not on the mesh's own border), the patch grows
// (lambda - 1 doubled, at least +0.1) and the path is recomputed, until it
// does not (or the patch is the whole connected component): the path is
// then the shortest on the whole surface. Strictly, that holds when the true
// geodesic lies in the patch, i.e. when search distances near it are at
// most about lambda times the geodesic ones. On a planar region a path that
// keeps off the patch border is the straight segment, hence the shortest;
// on a curved surface it can be a longer local geodesic if the patch is too
// small (seen with lambda = 1 on a grid jittered until triangles fold
// over), which a larger lambda prevents.
//
// The ellipse follows the surface: paths around a slit or over the rim of a
// thin sheet get a patch along the detour, not a straight Euclidean
// ellipse. Both searches are pruned (A*-style, the straight-line distance
// bounding the search distance from below), so a path costs time and
// memory in proportion to its patch, not to the mesh.
//
// Cost: CGAL treats every flat vertex as a pseudo-source (its "relaxed
// pruning", for robustness), so on flat regions its time grows about with
// the square of the patch size. On the 53K-vertex sheet a 15 mm path costs
// about 5-12 ms at lambda = 1.1 (~550 triangles), 20 ms at 1.2, 35-50 ms
// at 1.5 (~1700 triangles) and 120 ms at 2. Hence the default lambda of
// 1.1: on the thesis's sheets, the meniscus and jittered grids no patch had
// to grow from lambda = 1.05 on, and every sampled path equalled CGAL's on
// the whole surface.
#ifndef GeodesicPaths_h
#define GeodesicPaths_h

#include "SurfacePath.h"
#include "ThinTissueBindingModule.h"
#include "ThinTissueError.h"
#include "TriangleMeshAdjacency.h"

#include <cstddef>
#include <vector>

namespace thintissue
{

struct GeodesicPathStatistics
{
  std::size_t patchTriangles = 0; ///< of the last (accepted) patch
  int patchGrowths = 0;           ///< times the patch had to grow
  /// The straight segment between the ends lies on the surface and is the
  /// path (no patch, no CGAL).
  bool straight = false;
  /// The path came through a sleeve of triangles (SleeveGeodesic.h): the
  /// sleeve's triangles and the bends moved round a vertex.
  bool sleeve = false;
  std::size_t sleeveTriangles = 0;
  int sleeveReroutes = 0;
};

/// No path on the surface (or on the triangles a mask allows) joins the two
/// vertices: they lie on different pieces. A caller that knows why the
/// surface is in pieces there can say so.
class THINTISSUEBINDING_EXPORT DisconnectedPathError : public InvalidInputError
{
public:
  using InvalidInputError::InvalidInputError;
};

/// How GeodesicPathFinder finds a path that is not a straight segment.
enum class GeodesicAlgorithm
{
  /// The funnel through a sleeve of triangles (from the shortest edge path
  /// and from A* over triangle centroids), rerouted round vertices until it
  /// is locally shortest, saddle vertices tried on both sides; the shorter
  /// of the two (SleeveGeodesic.h). CGAL's patch where a sleeve
  /// degenerates. Linear in the path's triangles; a locally shortest path.
  Sleeve,
  /// CGAL's Xin-Wang algorithm on a growing patch (the shortest path on the
  /// whole surface); about quadratic in the patch.
  CgalPatch
};

class THINTISSUEBINDING_EXPORT GeodesicPathFinder
{
public:
  /// Keeps references: `mesh` and `adjacency` (of `mesh`) must outlive the
  /// finder and stay unchanged. The mesh must be an edge-manifold triangle
  /// mesh (InvalidInputError otherwise, naming the mesh); also rejected:
  /// indices out of range, a vertex joining two fans of triangles (bow-tie),
  /// a triangle repeating a vertex or of zero area, a non-orientable piece.
  /// Inconsistently oriented (but orientable) pieces are accepted.
  GeodesicPathFinder(const TriangleMesh& mesh, const TriangleMeshAdjacency& adjacency);

  /// The exact shortest path from vertex `source` to vertex `target` on the
  /// surface. Thread-safe (const; all work in per-call buffers), so paths
  /// can be computed in parallel. The result depends only on the mesh, the
  /// two vertices and the initial patch scale (deterministic, bit for bit).
  /// Consecutive points share a mesh triangle; a point whose edge parameter
  /// is within 1e-12 of an end is that vertex; coinciding consecutive points
  /// are merged; `length` sums the straight segments. source == target
  /// gives a one-point path of length 0. Throws InvalidInputError when a
  /// vertex index is out of range, DisconnectedPathError when the two
  /// vertices are not connected.
  SurfacePath shortestPath(int source,
    int target,
    GeodesicPathStatistics* statistics = nullptr) const;

  /// The exact shortest path from `source` to `target` on the part of the
  /// surface made of the triangles marked non-zero in `allowedTriangles`
  /// (one entry per mesh triangle), which acts as a surface with border
  /// where unmarked triangles begin: the binding keeps each side's paths on
  /// that side of a thin surface (5.2.2). Otherwise as shortestPath; throws
  /// DisconnectedPathError when the two vertices are not connected through
  /// marked triangles, InvalidInputError when the mask has the wrong size.
  SurfacePath shortestPathWithin(int source,
    int target,
    const std::vector<char>& allowedTriangles,
    GeodesicPathStatistics* statistics = nullptr) const;

  /// As above, with the triangles in `alsoAllowedTriangles` (sorted
  /// indices, a handful) allowed as well: a shared mask plus a few
  /// triangles of one path's own, without copying the mask.
  SurfacePath shortestPathWithin(int source,
    int target,
    const std::vector<char>& allowedTriangles,
    const std::vector<int>& alsoAllowedTriangles,
    GeodesicPathStatistics* statistics = nullptr) const;

  /// The Dijkstra (edge-path) distance between two vertices (A* search),
  /// an upper bound of the geodesic length, for tests (the patch bound also
  /// steps across edges). Throws InvalidInputError like shortestPath.
  double edgePathLength(int source, int target) const;

  /// lambda of the first patch (>= 1; default 1.1; InvalidInputError
  /// otherwise). A huge value (1e9) makes the patch the whole connected
  /// component: CGAL on the whole surface, for reference.
  void setInitialPatchScale(double scale);

  /// Whether a straight segment between the two vertices that lies on the
  /// surface is taken as it is (default on). It is the shortest of all
  /// curves, so the result is the same; off, CGAL computes it on a patch
  /// (tests compare the two).
  void setStraightSegmentShortcut(bool on) { StraightSegmentShortcut = on; }

  /// The algorithm of the paths that are not straight (default CgalPatch).
  void setAlgorithm(GeodesicAlgorithm algorithm) { Algorithm = algorithm; }
  GeodesicAlgorithm algorithm() const { return Algorithm; }

private:
  void checkVertices(int source, int target) const;
  SurfacePath shortestPathOn(int source,
    int target,
    const std::vector<char>* allowedTriangles,
    const std::vector<int>* alsoAllowedTriangles,
    GeodesicPathStatistics* statistics) const;

  const TriangleMesh& Mesh;
  const TriangleMeshAdjacency& Adjacency;
  double InitialPatchScale = 1.1;
  bool StraightSegmentShortcut = true;
  GeodesicAlgorithm Algorithm = GeodesicAlgorithm::CgalPatch;
  /// Per triangle: reversed in the patches so that each piece is
  /// consistently oriented.
  std::vector<char> Flipped;
};

} // namespace thintissue

#endif
