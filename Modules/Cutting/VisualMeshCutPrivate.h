// State of one visual cut, shared by the stages of CuttableVisualMesh::cut
// (VisualMeshCut.cxx, VisualBindingUpdate.cxx, CutSurface.cxx).
#ifndef VisualMeshCutPrivate_h
#define VisualMeshCutPrivate_h

#include "SplitFormula.h"
#include "VisualMeshCut.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <unordered_map>
#include <utility>
#include <vector>

namespace thintissue
{

/// A visual vertex this near a traced cut's line lies on it (of the split
/// triangle's longest side in its plane).
constexpr double OnLineTolerance = 1e-7;

/// The longest side of a triangle's corners in its plane (the scale of
/// OnLineTolerance).
inline double frameScale(const std::array<Vector2, 3>& frame)
{
  return std::max(
    { (frame[1] - frame[0]).norm(), (frame[2] - frame[1]).norm(), (frame[0] - frame[2]).norm() });
}

/// The region's border bulges out of the triangle by this fraction of a
/// side times t (1 - t) along it: with straight sides, a visual triangle
/// with all three corners on one path (where the path turns around it) is
/// flat, and cuts ending beside it would meet there. Small: the cut moves
/// by at most a 4,000th of the side near the border.
constexpr double BoundaryBulge = 1e-3;

/// A vertex's point in the frame, border vertices bulged outward.
inline Vector2 bulgedPoint(const std::array<Vector2, 3>& frame, const Vector3& parameters)
{
  Vector2 p = planarPoint(frame, parameters);
  for (int j = 0; j < 3; ++j)
  {
    const int from = (j + 1) % 3, to = (j + 2) % 3;
    if (parameters[j] != 0.0 || parameters[from] <= 0.0 || parameters[to] <= 0.0)
      continue;
    const Vector2 side = frame[to] - frame[from];
    Vector2 outward(side.y(), -side.x());
    if (outward.dot(frame[j] - frame[from]) > 0.0)
      outward = -outward;
    p += BoundaryBulge * parameters[from] * parameters[to] * outward;
  }
  return p;
}

/// The collision pieces of a split in its region's plane: its crossings'
/// lines (unit normals), and the piece on the inner side of all its
/// crossings per combination of sides (bit l: normal l . (x - from l) > 0).
struct CuttableVisualMesh::PieceLocator
{
  static constexpr int MaxLines = 3;
  static constexpr int MaxPieces = 4;
  int lineCount = 0;
  std::array<Vector2, MaxLines> from;
  std::array<Vector2, MaxLines> normal;
  std::array<std::int8_t, 1u << MaxLines> pieceOfSides{};
  /// The lines for points given by barycentric parameters x in the frame
  /// (the plane point is sum x_j frame_j): distance g_l . x - c_l.
  std::array<Vector3, MaxLines> g;
  std::array<double, MaxLines> c{};
  void expressInParameters(const std::array<Vector2, 3>& frame)
  {
    for (int l = 0; l < lineCount; ++l)
    {
      g[l] = Vector3(normal[l].dot(frame[0]), normal[l].dot(frame[1]), normal[l].dot(frame[2]));
      c[l] = normal[l].dot(from[l]);
    }
  }
  /// The cell of parameters x (bit l: on line l's positive side), -1
  /// within `margin` of a line (expressInParameters first).
  int cellOf(const Vector3& x, double margin) const
  {
    int cell = 0;
    for (int l = 0; l < lineCount; ++l)
    {
      const double d = g[l].dot(x) - c[l];
      if (std::abs(d) <= margin)
        return -1;
      cell |= (d > 0.0 ? 1 : 0) << l;
    }
    return cell;
  }
};

/// A collision vertex made inside collision edge (a, b), a < b, at
/// parameter u from a, and where it lies on the edge's visual paths.
struct CuttableVisualMesh::EdgePoint
{
  int vertex = -1;
  int a = -1;
  int b = -1;
  double u = 0.0;
  bool rim = false;
  /// On a junction edge: the point is a junction vertex, with a crease slot.
  bool junction = false;
  /// Per path slot (-, +, crease): the point on the path, the path segment
  /// it is in, and the visual vertex it became.
  std::array<SurfacePoint, 3> visual;
  std::array<int, 3> pathPosition{ { 0, 0, 0 } };
  std::array<int, 3> visualVertex{ { -1, -1, -1 } };
  int slotCount() const { return junction ? 3 : 2; }
};

/// A new collision edge across a split triangle, traced on one side.
struct CuttableVisualMesh::CrossingPath
{
  /// Its collision vertices (as before the mesh opened), lower first, and
  /// their barycentric coordinates in the parent.
  std::array<int, 2> ends{ { -1, -1 } };
  std::array<Vector3, 2> barycentric{ { Vector3::Zero(), Vector3::Zero() } };
  /// The split's pieces on either side of it (indices into its children).
  std::array<int, 2> pieces{ { -1, -1 } };
  SurfacePath path; ///< in visual vertices before re-meshing
  /// Its ends in the region's plane.
  std::array<Vector2, 2> planar{ { Vector2::Zero(), Vector2::Zero() } };
  std::vector<int> vertices; ///< the visual vertices it became
};

/// The region of a split collision triangle on one side.
struct CuttableVisualMesh::RegionCut
{
  int split = -1; ///< index into CollisionCutResult::splits
  int side = 0;   ///< 0: -, 1: +
  /// The side faces a horizontal cleavage's cleft: at junction edges and
  /// vertices its border is the crease's path and vertex.
  bool cleft = false;
  /// The path slot its border takes at a junction (the crease's, or its
  /// side's), and elsewhere.
  int junctionSlot() const { return cleft ? CuttableVisualMesh::CreaseSlot : side; }
  /// The triangles worked on: the region's, or only those near a traced
  /// cut when the rest lie far from every cut (`far`).
  std::vector<int> triangles;
  /// Triangles of inner vertices only, each corner beyond the on-line
  /// tolerance on one side of every crossing, so no traced cut touches
  /// them and their piece is where they lie (separateFarTriangles). They
  /// are neither laid out nor traced; their vertices are rebound by
  /// formula 5-2 at once.
  struct FarTriangle
  {
    int triangle;
    int piece;    ///< index into the split's children
    int position; ///< in the region's list
  };
  std::vector<FarTriangle> far;
  /// Where separated: per near triangle, and per untouched one (the first
  /// of newTriangles), its position in the region's list, so that the
  /// pieces list their triangles in the region's order (rebindFarTriangles).
  std::vector<int> nearPositions;
  std::vector<int> untouchedPositions;
  /// The sign of the far triangles' areas in the plane (all the same).
  double farOrientation = 0.0;
  /// Per triangle: its corners as local vertices, and whether a traced
  /// cut comes near it (only those can hold a point of a traced path).
  std::vector<Triangle> localTriangles;
  std::vector<char> candidate;
  /// The region's vertices (local index -> visual vertex) and, per local
  /// vertex, its barycentric parameters in the parent and its point in the
  /// plane the cuts are traced in (regionPlane). Dense arrays: a region is
  /// walked whole, and hash maps keyed by visual vertex cost more than the
  /// work (CutContext::localIndex maps back while the region is active).
  std::vector<int> vertices;
  std::vector<Vector3> parameters;
  std::vector<Vector2> planar;
  std::array<Vector2, 3> frame; ///< the parent's corners in the plane
  /// The binding's parameters laid the region out without a fold (no
  /// repair): its pieces are the collision pieces (locatePieces).
  bool foldFree = false;
  /// Its pieces were found by location (locatePieces).
  bool locatedPieces = false;
  /// The pieces of the split triangle in that plane (border bulged), and
  /// as the split history places them (corners not bulged: the lazy
  /// binding's test, leftToHistory).
  std::vector<std::array<Vector2, 3>> pieces;
  std::array<PlanePiece, 4> historyPieces;
  std::size_t historyPieceCount = 0; ///< 0 when a split has more (none left)
  /// Inner vertices left bound to the parent for the split history to
  /// resolve (VisualCutSettings::lazyBinding), each with the piece's
  /// collision triangle it resolves to.
  std::vector<std::array<int, 2>> leftToHistory;
  std::vector<CrossingPath> crossings;
  /// The triangles a traced cut touches (re-meshed), and the region's
  /// triangles once re-meshed.
  std::vector<int> touched;
  std::vector<int> newTriangles;
  std::vector<Triangle> newLocalTriangles; ///< their corners as local vertices
  /// What the region stages (forEachRegion) made for the cut as a whole,
  /// merged in region order once all regions are done: the visual vertices
  /// rebound, and the visual vertex at each end of a traced cut that is an
  /// edge point (edge point, path slot, visual vertex).
  std::vector<int> rebound;
  std::vector<std::array<int, 3>> endVertices;
  std::exception_ptr error;
};

inline void CuttableVisualMesh::RegionWorker::activate(const RegionCut& region)
{
  for (std::size_t i = 0; i < region.vertices.size(); ++i)
    setLocal(region.vertices[i], static_cast<int>(i));
}

inline void CuttableVisualMesh::RegionWorker::deactivate(const RegionCut& region)
{
  for (int v : region.vertices)
    localIndex[v] = -1;
}

inline void CuttableVisualMesh::RegionWorker::addToActive(RegionCut& region,
  int v,
  const Vector3& parameters,
  const Vector2& planar)
{
  setLocal(v, static_cast<int>(region.vertices.size()));
  region.vertices.push_back(v);
  region.parameters.push_back(parameters);
  region.planar.push_back(planar);
}

struct CuttableVisualMesh::CutContext
{
  const CuttableCollisionMesh* collision = nullptr;
  const CollisionCutResult* cut = nullptr;
  /// Collision vertex copies made by this cut -> the vertex copied, from
  /// collision vertex `firstCopy` on (-1: not a copy). The copies are the
  /// last vertices made, so the array is as long as the cut is.
  int firstCopy = 0;
  std::vector<int> originalOf;
  std::vector<EdgePoint> edgePoints;
  std::unordered_map<int, int> edgePointOf; ///< collision vertex -> edgePoints
  std::vector<RegionCut> regions;
  /// (visual vertex, element code) -> the visual vertex serving it: codes
  /// 2 v for collision vertex v, 2 e + 1 for collision edge e. Keys
  /// (vertex << 32 | code), sorted once the opening has made them all (a
  /// vector, not a map: a cut makes hundreds).
  std::vector<std::pair<std::uint64_t, int>> copies;
  static std::uint64_t copyKey(int vertex, int code)
  {
    return (static_cast<std::uint64_t>(vertex) << 32) | static_cast<std::uint32_t>(code);
  }
  /// The visual vertex serving (w, code): its copy, or w itself.
  int copyOf(int w, int code) const
  {
    const std::uint64_t key = copyKey(w, code);
    const auto at = std::lower_bound(copies.begin(),
      copies.end(),
      key,
      [](const std::pair<std::uint64_t, int>& entry, std::uint64_t k) { return entry.first < k; });
    return at != copies.end() && at->first == key ? at->second : w;
  }
  /// Cut strips to rebuild (edge keys).
  std::vector<std::uint64_t> strips;
  std::vector<int> newVertices;
  std::vector<int> rebound;
  std::vector<int> changedTriangles;

  /// The serial stages' worker (CuttableVisualMesh::Workers[0]); none
  /// while the region stages run on several.
  RegionWorker* worker = nullptr;
  void activate(const RegionCut& region) { worker->activate(region); }
  void deactivate(const RegionCut& region) { worker->deactivate(region); }
  int local(int v) const { return worker->local(v); }
  void addToActive(RegionCut& region, int v, const Vector3& parameters, const Vector2& planar)
  {
    worker->addToActive(region, v, parameters, planar);
  }

  void addCopy(int copy, int original)
  {
    if (originalOf.empty())
      firstCopy = copy;
    if (copy < firstCopy)
    {
      originalOf.insert(originalOf.begin(), static_cast<std::size_t>(firstCopy - copy), -1);
      firstCopy = copy;
    }
    const auto i = static_cast<std::size_t>(copy - firstCopy);
    if (i >= originalOf.size())
      originalOf.resize(i + 1, -1);
    if (originalOf[i] < 0)
      originalOf[i] = original;
  }
  int root(int v) const
  {
    const int i = v - firstCopy;
    return i >= 0 && i < static_cast<int>(originalOf.size()) && originalOf[i] >= 0 ? originalOf[i]
                                                                                   : v;
  }
};

} // namespace thintissue

#endif
