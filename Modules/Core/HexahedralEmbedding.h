// Embedding of a point set in a hexahedral simulation mesh (thesis 4.3,
// formula 4-1: s = H x). Each point keeps the hexahedron it lies in and its
// trilinear local coordinates there; positions go down with H, forces go up
// with H^T. Visual vertices, collision vertices and monitor points all use it.
//
// Points outside every hexahedron are embedded in the nearest one with
// extrapolated (unclamped) local coordinates, so that they too are
// reproduced exactly at rest. Extrapolation is bounded: when the local
// coordinates would leave [-m, 1 + m]^3 (m = maximumExtrapolation) or Newton
// does not converge, the point takes the coordinates of its closest point on
// the hexahedron instead, and is counted in clampedPointCount().
#ifndef HexahedralEmbedding_h
#define HexahedralEmbedding_h

#include "HexahedralMesh.h"
#include "ReservedVector.h"
#include "ThinTissueCoreModule.h"
#include "TrilinearCoordinates.h"

#include <array>
#include <cstddef>
#include <vector>

namespace thintissue
{

struct HexahedralEmbeddingSettings
{
  /// A point is inside a hexahedron when its local coordinates lie in
  /// [-insideTolerance, 1 + insideTolerance]^3.
  double insideTolerance = 1e-9;
  /// How far (in local units, a cell edge being 1) the local coordinates of
  /// an outside point may extend beyond [0, 1] before they are clamped.
  double maximumExtrapolation = 1.0;
};

/// Distance from `point` to the hexahedron: 0 when its local coordinates are
/// inside (see HexahedralEmbeddingSettings::insideTolerance), else the
/// distance to the boundary, each face being the four triangles that join
/// its edges to its centre (exact for planar faces).
THINTISSUECORE_EXPORT double distanceToHexahedron(const HexahedronCorners& corners,
  const Vector3& point,
  double insideTolerance = 1e-9);

/// Local coordinates of `point` in the hexahedron by Newton's method on the
/// trilinear map, converged to machine precision (unclamped: outside [0,1]
/// means outside). Returns false if Newton does not converge.
THINTISSUECORE_EXPORT bool invertTrilinearMap(const HexahedronCorners& corners,
  const Vector3& point,
  Vector3& local);

/// Where a point lies with respect to a hexahedral mesh.
struct HexahedronLocation
{
  int hexahedron = -1;
  /// Local coordinates in `hexahedron` (extrapolated or clamped if outside).
  Vector3 localCoordinates = Vector3::Constant(0.5);
  /// Distance to the hexahedron, as distanceToHexahedron() (0 inside).
  double distance = 0.0;
  bool inside = false;
  /// Outside, and the extrapolated coordinates were replaced by those of the
  /// closest point on the hexahedron.
  bool clamped = false;
};

/// Uniform grid of hexahedron bounding boxes for point location: the
/// containing hexahedron, else the nearest one. Keeps its own copy of the
/// corner positions; thread-safe for concurrent queries.
class THINTISSUECORE_EXPORT HexahedronLocator
{
public:
  HexahedronLocator() = default;
  explicit HexahedronLocator(const HexahedralMesh& mesh);
  /// Indexes every hexahedron of `mesh` (or only `hexahedra`, if not empty).
  /// Throws InvalidInputError naming the mesh if there is nothing to index.
  void build(const HexahedralMesh& mesh, const std::vector<int>& hexahedra = {});

  /// Containing hexahedron (lowest index among several), else the nearest
  /// (lowest index among equally near ones), with its local coordinates.
  HexahedronLocation locate(const Vector3& point,
    const HexahedralEmbeddingSettings& settings = {}) const;

  std::size_t hexahedronCount() const { return Hexahedra.size(); }

private:
  bool findContaining(const Vector3& point, double tolerance, HexahedronLocation& location) const;
  /// Entry of the nearest hexahedron and its distance.
  int findNearest(const Vector3& point, double& distance) const;

  std::vector<int> Hexahedra;             // mesh index of each entry
  std::vector<HexahedronCorners> Corners; // per entry
  std::vector<BoundingBox> Boxes;         // per entry
  Vector3 GridOrigin = Vector3::Zero();
  Vector3 GridCellSize = Vector3::Ones();
  std::array<int, 3> GridDimensions{ { 0, 0, 0 } };
  std::vector<int> GridCellStart;   // CSR offsets, one per grid cell + 1
  std::vector<int> GridCellEntries; // entries, ascending per cell
};

/// H of formula 4-1 for a point set: per point a hexahedron and trilinear
/// local coordinates. The embedding keeps a copy of the hexahedron table, so
/// that mapping needs only the node positions; after local topology changes
/// call updateHexahedra / reembed / appendPoints (each costs in proportion
/// to what it is given, except where documented).
class THINTISSUECORE_EXPORT HexahedralEmbedding
{
public:
  HexahedralEmbedding() = default;
  /// Same as embed().
  HexahedralEmbedding(const HexahedralMesh& mesh,
    const std::vector<Vector3>& points,
    const HexahedralEmbeddingSettings& settings = {});

  /// Embeds `points` (rest positions) in `mesh` (rest node positions), in
  /// parallel. Throws InvalidInputError naming the mesh if it has no
  /// hexahedron or is inconsistent, or if a point is not finite.
  void embed(const HexahedralMesh& mesh,
    const std::vector<Vector3>& points,
    const HexahedralEmbeddingSettings& settings = {});

  /// An embedding from known hexahedron indices and local coordinates (one
  /// per point), e.g. read back from VTK arrays. Throws InvalidInputError on
  /// a size mismatch, an index out of range or a non-finite coordinate.
  void assign(const HexahedralMesh& mesh,
    std::vector<int> hexahedronOfPoint,
    std::vector<Vector3> localCoordinates);

  std::size_t pointCount() const { return HexahedronOfPoint.size(); }
  /// Node count of the mesh the embedding refers to.
  std::size_t nodeCount() const { return NodeCount; }
  std::size_t hexahedronCount() const { return HexahedronTable.size(); }

  int hexahedron(std::size_t point) const { return HexahedronOfPoint[point]; }
  const Vector3& localCoordinates(std::size_t point) const { return LocalCoordinates[point]; }
  /// Node indices of the point's hexahedron, in the order of weights().
  const Hexahedron& nodesOf(std::size_t point) const
  {
    return HexahedronTable[HexahedronOfPoint[point]];
  }
  /// The eight entries of row `point` of H (sum 1; negative entries only
  /// for extrapolated outside points).
  std::array<double, 8> weights(std::size_t point) const;
  const std::vector<int>& hexahedra() const { return HexahedronOfPoint; }
  const std::vector<Vector3>& localCoordinates() const { return LocalCoordinates; }

  /// Of the points located by the last embed(), reembed() or appendPoints():
  /// those outside every hexahedron / of those, the ones whose coordinates
  /// had to be clamped.
  std::size_t outsidePointCount() const { return OutsidePoints; }
  std::size_t clampedPointCount() const { return ClampedPoints; }

  /// x = H u for one point.
  Vector3 mapPosition(std::size_t point, const std::vector<Vector3>& nodePositions) const;
  /// x = H u for every point: `out` is resized to pointCount() only if its
  /// size differs (no allocation otherwise). Parallel above
  /// parallelThreshold() points; the result does not depend on it.
  /// Throws InvalidInputError if nodePositions.size() != nodeCount().
  void mapPositions(const std::vector<Vector3>& nodePositions, std::vector<Vector3>& out) const;
  /// Raw form: `nodePositions` has nodeCount() entries, `out` pointCount().
  void mapPositions(const Vector3* nodePositions, Vector3* out) const;

  /// f_nodes += H^T f for every point (pointForces.size() == pointCount(),
  /// nodeForces.size() == nodeCount(), else InvalidInputError). Above
  /// parallelThreshold() points it sums in a fixed number of chunks, so the
  /// result is deterministic (it may differ from the serial sum by rounding).
  void accumulateForces(const std::vector<Vector3>& pointForces,
    std::vector<Vector3>& nodeForces) const;
  /// f_nodes += H^T f for a few points (contact): forces[i] acts on point
  /// pointIndices[i]. Serial, no allocation.
  void accumulateForces(const std::vector<int>& pointIndices,
    const std::vector<Vector3>& forces,
    std::vector<Vector3>& nodeForces) const;
  void accumulateForce(std::size_t point,
    const Vector3& force,
    std::vector<Vector3>& nodeForces) const;

  /// Point count above which mapPositions / accumulateForces run in parallel.
  void setParallelThreshold(std::size_t points) { ParallelThreshold = points; }
  std::size_t parallelThreshold() const { return ParallelThreshold; }

  // --- Local topology changes (cutting) -------------------------------------

  /// Copies the listed hexahedra of `mesh` into the embedding's table, and
  /// any hexahedra appended to `mesh` since; takes the mesh's node count.
  /// Points keep their hexahedron index and local coordinates.
  void updateHexahedra(const HexahedralMesh& mesh, const std::vector<int>& changedHexahedra);

  /// Embeds the listed points anew in the hexahedra `candidateHexahedra` of
  /// `mesh` (all hexahedra if empty: then it costs a search structure over
  /// the whole mesh). Their rest positions are taken as H times the rest
  /// node positions `mesh.nodes` under the current embedding, so the mesh's
  /// node indices must still be valid for them (nodes only appended, and
  /// duplicated nodes at the rest position of their originals). The
  /// candidate hexahedra and any appended ones are copied as by
  /// updateHexahedra().
  void reembed(const std::vector<int>& pointIndices,
    const HexahedralMesh& mesh,
    const std::vector<int>& candidateHexahedra = {},
    const HexahedralEmbeddingSettings& settings = {});
  /// Same with explicit rest positions (one per index).
  void reembed(const std::vector<int>& pointIndices,
    const std::vector<Vector3>& restPositions,
    const HexahedralMesh& mesh,
    const std::vector<int>& candidateHexahedra = {},
    const HexahedralEmbeddingSettings& settings = {});
  /// Appends points (rest positions) embedded in `candidateHexahedra` of
  /// `mesh` (all if empty). Returns the index of the first new point.
  std::size_t appendPoints(const std::vector<Vector3>& restPositions,
    const HexahedralMesh& mesh,
    const std::vector<int>& candidateHexahedra = {},
    const HexahedralEmbeddingSettings& settings = {});
  /// Same, trying first for each point the hexahedron `firstTry[i]` (-1:
  /// none; e.g. the cut copy holding the point's collision triangle): a
  /// point inside it costs one inversion, and the search structure is built
  /// over the candidates only for the points outside their first try.
  std::size_t appendPoints(const std::vector<Vector3>& restPositions,
    const std::vector<int>& firstTry,
    const HexahedralMesh& mesh,
    const std::vector<int>& candidateHexahedra,
    const HexahedralEmbeddingSettings& settings = {});
  /// Room for `pointCount` points without reallocating (appendPoints on a
  /// cut would otherwise copy every point's coordinates once in a while).
  void reserve(std::size_t pointCount)
  {
    reserveTouched(HexahedronOfPoint, pointCount);
    reserveTouched(LocalCoordinates, pointCount, Vector3::Zero().eval());
  }
  /// Sets the hexahedron and local coordinates of one point directly (e.g. a
  /// vertex moved to the duplicate of its hexahedron by a cut). The
  /// hexahedron must be in the table (see updateHexahedra).
  void setPoint(std::size_t point, int hexahedron, const Vector3& localCoordinates);

private:
  void locatePoints(const std::vector<Vector3>& points,
    const std::vector<int>& targets,
    const HexahedralMesh& mesh,
    const std::vector<int>& candidateHexahedra,
    const HexahedralEmbeddingSettings& settings,
    const std::vector<int>& firstTry = {});
  void checkPointIndex(std::size_t point, const char* operation) const;

  std::vector<int> HexahedronOfPoint;
  std::vector<Vector3> LocalCoordinates;
  std::vector<Hexahedron> HexahedronTable;
  std::size_t NodeCount = 0;
  std::size_t OutsidePoints = 0;
  std::size_t ClampedPoints = 0;
  std::size_t ParallelThreshold = 16384;
};

} // namespace thintissue

#endif
