// Cutting the visual mesh with the collision mesh (thesis 5.3.2 - 5.3.4),
// through the visual-collision binding (5.2), in the rest configuration.
//
//  5.3.2 Visual cut: every visual vertex of the region of a split collision
//        triangle (one region per side) has barycentric parameters in it
//        (formula 5-1); in the triangle's 2D frame, each new edge between
//        its pieces is intersected with the region's visual edges (a vertex
//        within a round-off of the line is on it). Where a collision edge
//        is split, its visual paths are split at the same edge parameter.
//        The points are inserted as visual vertices (rest position, normal,
//        texture coordinates and point attributes interpolated along the
//        visual edge they cut) and the region re-triangulated around them
//        (PathRemeshing.h, on the triangles the cut touches only); then,
//        wherever the collision mesh opened, the visual vertices bound to
//        the opened collision vertices and edges get one copy per side, so
//        the visual surface opens with it. The plane is the binding's, the
//        border bulged by a thousandth and folds repaired (regionPlane), and
//        each cut is walked through the triangles it crosses.
//  5.3.3 Binding update: a vertex bound to a split triangle is rebound to
//        the piece that holds it, (a', b', c') = (a, b, c) M^-1 (formula
//        5-2, M from CollisionTriangleSplit::childCorners); a vertex on a
//        split collision edge keeps its accumulated-length parameter,
//        rescaled to its half; the visual vertex inserted where a collision
//        edge is split becomes the new collision vertex's visual vertex (one
//        per side, or one on the rim). A vertex on a new edge across a
//        triangle is bound to it by its parameter along the straight 2D cut
//        (the thesis takes the accumulated 3D length there; the straight
//        parameter is the point the cut computed, so it stays consistent
//        with the 5-2 parameters of its neighbours and folds no triangle).
//  5.3.4 Cut surface: each opened collision edge gets a strip joining its
//        + and - visual paths (fig. 5-12): `cutSurfaceRows` rows of
//        vertices in between, at the union of both sides' edge parameters
//        (up-sampling), bound to the edge; the rows at a collision vertex
//        are shared by the strips meeting there, so the surface stays
//        closed. A strip whose edge is cut again is split by comparing
//        parameters (fig. 5-13), not by geometry.
//
// A cut costs what the regions of the split and re-cornered collision
// triangles and the strips on their edges hold (not the whole mesh).
#ifndef VisualMeshCut_h
#define VisualMeshCut_h

#include "CollisionMeshCut.h"
#include "CollisionSplitHistory.h"
#include "SurfacePath.h"
#include "ThinTissueCuttingModule.h"
#include "VisualCollisionBinding.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <utility>
#include <vector>

namespace thintissue
{

struct RemeshedSurface;

struct VisualCutSettings
{
  /// Rows of cut-surface vertices between the + and - sides (fig. 5-12c);
  /// 0 joins the two sides directly.
  int cutSurfaceRows = 1;
  /// Jagged cut surface (6.4.4): the rows' vertices are moved across the
  /// cut, in the plane of its collision triangle (never through the
  /// tissue's thickness), by seeded value noise of this amplitude (mm; 0:
  /// a smooth cut) and wavelength (mm), so that a bitten rim looks jagged
  /// (fig. 6-12) and contouring has something to even out (fig. 6-15).
  /// The same seed gives the same rim. Needs cutSurfaceRows >= 1.
  double jaggedAmplitude = 0.0;
  double jaggedWavelength = 0.5;
  std::uint32_t jaggedSeed = 0;
  /// When the regions of the split collision triangles hold at least this
  /// many visual triangles in all, they are traced and rebound on several
  /// threads (up to CuttableVisualMesh::MaxRegionWorkers). The result is
  /// the same either way, bit for bit. 0: always; the largest value: never.
  /// Below the default a second thread costs more than it saves (measured:
  /// Documentation/Architecture.md, "regions on two cores").
  std::size_t parallelRegionTriangles = 4000;
  /// Where a split region lies in its plane without a fold, its triangles
  /// go to the collision pieces their centroids lie in (a few sign tests
  /// each) instead of through the union-find of the region's pieces, which
  /// gives the same pieces there and stays the way wherever the plane
  /// folds or a centroid lies within a round-off of a crossing; and its
  /// triangles far from every cut (all corners inner vertices beyond twice
  /// the on-line tolerance of each crossing's line, on one side) are placed
  /// and rebound in one pass, only the others laid out and traced. false:
  /// the whole region through the union-find always (the reference the
  /// tests compare with, bit for bit).
  bool piecesByLocation = true;
  /// The far triangles of a split region are set apart (piecesByLocation)
  /// when it holds at least this many triangles: below it, the pass over
  /// the region costs more than not laying out the far ones saves
  /// (callgrind, the short cut of the sheets: break-even near 2,000). 0:
  /// always (the property tests), the largest value: never.
  std::size_t separatedRegionTriangles = 2000;
  /// The lazy binding (issue 13): an inner vertex of a split region whose
  /// new binding the split history gives bit for bit (the piece its own
  /// parameters lie in, no fold repaired where it lies) is left bound to
  /// the parent and resolved when read (binding(v)); the cut neither
  /// rebinds nor reports it as rebound (it lists it in
  /// VisualCutResult::leftToHistory, where the visual re-embedding finds
  /// its hexahedron copy once per piece and hexahedron). false: every
  /// vertex rebound at once (the twin the tests compare with, resolved
  /// binding for binding).
  bool lazyBinding = true;
};

/// How far the cut surface departs from the smooth cut (6.4.4): over the
/// cut-surface vertices counted, the distance of each from its place on the
/// surface ruled between the rim's + and - paths (where a smooth cut puts
/// it), root mean square and largest (mm).
struct CutSurfaceRoughness
{
  double rootMeanSquare = 0.0;
  double maximum = 0.0;
  std::size_t vertices = 0;
};

/// What one cut did to the visual mesh.
struct VisualCutResult
{
  /// Visual vertices made (on the cut, copies where the mesh opened, cut
  /// surface), ascending.
  std::vector<int> newVertices;
  /// Vertices whose binding changed (new ones included), each once, in no
  /// particular order (a cut rebinds whole regions: sorting them cost more
  /// than any use of the order).
  std::vector<int> reboundVertices;
  /// Triangles rewritten or added, ascending.
  std::vector<int> changedTriangles;
  /// Milliseconds of the cut surface's update (5.3.4), part of the cut.
  double cutSurfaceMilliseconds = 0.0;
  /// Regions of split collision triangles (one per side), and how many of
  /// them found their pieces by location (VisualCutSettings::
  /// piecesByLocation) rather than by the union-find.
  std::size_t splitRegions = 0;
  std::size_t regionsLocated = 0;
  /// Triangles of those regions that lay far from every cut: placed and
  /// rebound where they lie, neither laid out nor traced (see
  /// piecesByLocation).
  std::size_t farTriangles = 0;
  /// Inner vertices of those regions left to the split history
  /// (VisualCutSettings::lazyBinding), not in reboundVertices: each with
  /// the collision triangle its binding resolves to now (its hexahedron
  /// copy may have to follow it), in region order.
  std::vector<std::array<int, 2>> leftToHistory;
  bool changed() const { return !changedTriangles.empty(); }
};

/// Per visual triangle: what it is part of.
enum class VisualMaterial : std::uint8_t
{
  Surface = 0,   ///< the tissue's own surface
  CutSurface = 1 ///< made by cutting (5.3.4)
};

class THINTISSUECUTTING_EXPORT CuttableVisualMesh
{
public:
  CuttableVisualMesh() = default;
  /// Takes the binding's re-meshed visual surface and bindings. Throws
  /// InvalidInputError on a negative row count or an inconsistent binding.
  explicit CuttableVisualMesh(const VisualCollisionBinding& binding,
    const VisualCutSettings& settings = {});

  /// The settings of the cuts to come (a settings panel's change between
  /// cuts): jaggedness changes the cut surfaces made from now on only.
  /// Throws InvalidInputError, changing nothing, on bad values or on a new
  /// row count once a cut surface exists (its end columns at the collision
  /// vertices are shared with the strips to come).
  void setSettings(const VisualCutSettings& settings);
  const VisualCutSettings& settings() const { return Settings; }

  /// Follows one cut of the collision mesh: `collision` is the mesh after
  /// the cut, `cut` what CuttableCollisionMesh::cut reported. The collision
  /// mesh must be the one the binding was made for, cut after cut.
  VisualCutResult cut(const CuttableCollisionMesh& collision, const CollisionCutResult& cut);

  /// The visual surface with its cut surfaces (rest positions).
  const TriangleMesh& mesh() const { return Mesh; }
  /// Every visual vertex's binding (binding(v) for each; a copy).
  std::vector<VisualVertexBinding> bindings() const;
  /// Collision edges the bindings refer to (lower, higher): the binding's,
  /// then those made by cuts, in the order made.
  const std::vector<std::array<int, 2>>& collisionEdges() const { return Edges; }
  /// Per triangle: the collision triangle of its region (for a cut-surface
  /// triangle, the triangle on its collision edge) and its side (+1 / -1,
  /// 0 on the cut surface).
  const std::vector<int>& triangleRegions() const { return TriangleRegion; }
  const std::vector<std::int8_t>& triangleSides() const { return TriangleSide; }
  const std::vector<VisualMaterial>& triangleMaterials() const { return TriangleMaterial; }
  /// Per collision vertex: its visual vertex on the - and + side (the same
  /// vertex twice on the rim) and, at a horizontal cleavage's junction
  /// vertex, on the cleft's crease (else -1).
  const std::vector<std::array<int, 3>>& pairedVisualVertices() const { return Paired; }
  /// The visual path of collision edge (a, b) on `side` (+1 / -1; 0: the
  /// crease path of a junction edge), from the lower collision vertex to the
  /// higher; empty if there is none.
  std::vector<int> path(int a, int b, int side) const;
  /// Whether the edge's two sides meet on the rim (one path for both).
  bool isRimEdge(int a, int b) const;
  std::size_t cutSurfaceTriangleCount() const;
  /// Visual vertex v's binding: where a cut left it in a collision triangle
  /// split since, resolved through the split history (the eager binding,
  /// bit for bit; CollisionSplitHistory.h).
  VisualVertexBinding binding(int v) const
  {
    return bindingIsCurrent(v) ? Bindings[static_cast<std::size_t>(v)] : resolvedBinding(v);
  }
  /// The split history's node whose triangle a vertex bound inside one has
  /// its parameters in (-1 for a vertex bound to an edge or a vertex).
  int bindingNode(int v) const { return BindingNodes[static_cast<std::size_t>(v)]; }
  /// What visual vertex v is bound to (never changed by resolving it).
  BindingKind bindingKind(int v) const { return Bindings[static_cast<std::size_t>(v)].kind; }
  /// The splits of the collision triangles so far, in the order cut: a
  /// binding taken before a cut (node = its triangle then) resolves through
  /// it to the eager binding of today (CollisionSplitHistory.h).
  const CollisionSplitHistory& splitHistory() const { return SplitHistory; }
  /// A collision triangle holding visual vertex v's bound element.
  int collisionTriangleOf(int v, const CuttableCollisionMesh& collision) const;
  /// Barycentric parameters of visual vertex v in a collision triangle with
  /// corners `corners` (index `triangle`) that holds its bound element.
  Vector3 parametersIn(int v, int triangle, const Triangle& corners) const;

  /// Contouring (6.4.4, CutSurfaceContour.cxx): every cut-surface vertex
  /// of the strips on collision edges (a, b) that `near(a, b)` accepts
  /// moves `pull(a, b, u)` of the way (0 to 1) toward its place on the
  /// smooth cut, u being its parameter on the edge from a (a < b); the
  /// columns at the edge's ends take pull(a, b, 0) and pull(a, b, 1).
  /// Nothing else moves and nothing is removed. Appends the vertices moved
  /// (rest positions changed) to `moved`, each once.
  void smoothCutSurface(const std::function<bool(int, int)>& near,
    const std::function<double(int, int, double)>& pull,
    std::vector<int>& moved);
  /// The roughness of the cut surface on the collision edges (a, b) that
  /// `counts(a, b)` accepts (e.g. those of pieces still in the tissue).
  CutSurfaceRoughness cutSurfaceRoughness(const std::function<bool(int, int)>& counts) const;

private:
  /// Path slots: [0] side -1, [1] side +1, [2] a junction edge's crease.
  static constexpr int CreaseSlot = 2;
  struct EdgePaths
  {
    /// Per slot, from the lower collision vertex; the crease slot is empty
    /// but on a horizontal cleavage's junction edge.
    std::array<std::vector<int>, 3> sides;
    bool rim = false;
    bool junction() const { return !sides[CreaseSlot].empty(); }
  };
  struct CutStrip
  {
    /// Inner rows (cutSurfaceRows), each ordered along the edge, without
    /// the columns at the edge's ends.
    std::vector<std::vector<int>> rows;
    std::vector<int> triangles;
    /// Per side (-, +): it faces a horizontal cleavage's cleft, so that at a
    /// junction its path and column end are the crease's.
    std::array<bool, 2> cleft{ { false, false } };
  };
  struct CutContext;
  /// Buffers the stages of a cut work in, kept from cut to cut (cleared,
  /// never freed): a cut allocates little. Indices are local to the region
  /// being worked on (RegionWorker::localIndex).
  struct CutBuffers
  {
    /// traceCut: a point where the cut crosses its region, at parameter s
    /// along it; per local vertex its signed distance from the cut's line
    /// and its node; the nodes inside edges as lists per lower local end
    /// (head, then next / other end / node per entry); the joins the
    /// crossed triangles make (from, to).
    struct Node
    {
      double s;
      SurfacePoint point;
    };
    std::vector<Node> nodes;
    std::vector<double> signedDistance;
    /// Per local vertex: 1 beyond the tolerance on the cut line's + side,
    /// 2 on its - side, 0 on the line or a node; | 4 at an end of an edge
    /// holding an end of the cut. A triangle whose corners share bit 1 or
    /// 2 lies wholly on one side (linkCrossedTriangles' quick rejection).
    std::vector<char> lineSide;
    std::vector<int> vertexNode;
    std::vector<int> edgeHead;
    std::vector<std::array<int, 3>> edgeEntries;
    /// The node inside local edge (a, b), or -1.
    int edgeNode(int a, int b) const
    {
      for (int e = edgeHead[std::min(a, b)]; e >= 0; e = edgeEntries[e][0])
        if (edgeEntries[e][1] == std::max(a, b))
          return edgeEntries[e][2];
      return -1;
    }
    void addEdgeNode(int a, int b, int node)
    {
      int& head = edgeHead[std::min(a, b)];
      edgeEntries.push_back({ { head, std::max(a, b), node } });
      head = static_cast<int>(edgeEntries.size()) - 1;
    }
    std::vector<std::pair<int, int>> links;
    std::vector<int> linkOffsets;
    std::vector<int> linkTargets;
    std::vector<char> visited;
    std::vector<int> here;
    /// bindCrossingVertices: (local vertex, traced cut) on a cut's inside.
    std::vector<std::pair<int, int>> crossingsOf;
    /// assignPieces: per local vertex, whether it lies on a traced cut or
    /// the region's border; the traced cuts' edges (local, lower first);
    /// union-find over local vertices then triangles, and each
    /// triangle's set; edges between special vertices (edge key, set); the
    /// pieces (per set root, then as a cursor), their starts in `members`
    /// and centroid sums; per triangle its piece.
    std::vector<char> special;
    std::vector<std::pair<int, int>> cutEdges;
    std::vector<int> parent;
    std::vector<int> representative;
    std::vector<std::pair<std::uint64_t, int>> borderEdges;
    std::vector<int> pieceOf;
    std::vector<int> pieceStart;
    std::vector<Vector2> centroids;
    std::vector<int> triangleIn;
    std::vector<int> members;
    /// rebindPieces: per local vertex, whether formula 5-2 rebinds it.
    std::vector<char> rebindable;
    /// remeshRegions: per texture coordinate, its local index (all -1
    /// between uses).
    std::vector<int> localTexture;
    /// listPiecesInRegionOrder: per piece of a split, its triangles.
    std::vector<std::vector<int>> pieceLists;
    /// separateFarTriangles: the vertices whose cell it noted (to clear).
    std::vector<int> cellVertices;
  };
  struct RegionCut;
  struct EdgePoint;
  struct CrossingPath;
  /// One worker's scratch for the regions it works on, one at a time: per
  /// visual vertex its local index in the active region, else -1 (all -1
  /// between regions), and its buffers. The region stages (tracing the
  /// cuts, rebinding the pieces) run on up to MaxRegionWorkers at once,
  /// each with its own; the serial stages use Workers[0].
  struct RegionWorker
  {
    std::vector<int> localIndex;
    /// Per visual vertex, its cell among a region's crossings + 1 while
    /// separateFarTriangles runs (all 0 otherwise).
    std::vector<std::int8_t> vertexCells;
    CutBuffers buffers;
    int local(int v) const { return v < static_cast<int>(localIndex.size()) ? localIndex[v] : -1; }
    void activate(const RegionCut& region);
    void deactivate(const RegionCut& region);
    /// Appends a vertex to the active region.
    void addToActive(RegionCut& region, int v, const Vector3& parameters, const Vector2& planar);
    void setLocal(int v, int i)
    {
      if (v >= static_cast<int>(localIndex.size()))
        localIndex.resize(static_cast<std::size_t>(v) + 1 + static_cast<std::size_t>(v) / 4, -1);
      localIndex[v] = i;
    }
  };

public:
  /// Up to this many workers run the region stages of one cut.
  static constexpr int MaxRegionWorkers = 4;

private:
  /// Runs `work` on every region of the cut, on several workers when the
  /// regions are large (VisualCutSettings::parallelRegionTriangles) (region r on worker r mod
  /// workers, so that the two sides of a split go to two workers). Regions are independent there:
  /// each writes only its own triangles, inner vertices and lists. The
  /// first failing region's error (in region order) is thrown once all
  /// have run.
  void forEachRegion(CutContext& context,
    const std::function<void(RegionCut&, RegionWorker&)>& work);

  /// (lower, higher) in one key; inline: looked up per region vertex.
  static std::uint64_t edgeKey(int a, int b)
  {
    const auto lo = static_cast<std::uint64_t>(std::min(a, b));
    const auto hi = static_cast<std::uint64_t>(std::max(a, b));
    return (lo << 32) | hi;
  }
  /// The paired visual vertex slot side `side` (0: -, 1: +) of a triangle
  /// sees at collision vertex v: the crease's at a junction vertex if that
  /// side faces the cleft.
  int pairedSlot(int v, int side, bool cleft) const
  {
    return cleft && Paired[v][CreaseSlot] >= 0 ? CreaseSlot : side;
  }
  /// The path slot of the same along an edge with paths `paths`.
  static int pathSlot(const EdgePaths& paths, int side, bool cleft)
  {
    return cleft && paths.junction() ? CreaseSlot : side;
  }
  /// Whether side `side` (0: -, 1: +) of collision triangle T faces a
  /// horizontal cleavage's cleft.
  static bool facesCleft(const CuttableCollisionMesh& collision, int T, int side);
  void reserveRoom();
  int edgeIndex(int a, int b);
  int addVertexCopy(int source);
  int addTriangle(const Triangle& corners, int region, int side, VisualMaterial material);
  void freeTriangle(int t);
  void compactTriangles();
  double edgeParameter(int v, int a, int b) const;
  bool boundToEdge(int v, int a, int b) const;
  std::vector<double> pathParameters(const std::vector<int>& path, int a, int b) const;
  void bindToEdge(int v, int a, int b, double fromA, int side);
  /// Whether v's stored binding is its binding (not left in a node split
  /// since).
  bool bindingIsCurrent(int v) const
  {
    const int node = BindingNodes[static_cast<std::size_t>(v)];
    return node < 0 || SplitHistory.isCurrent(node);
  }
  /// binding(v) for a vertex whose node was split since, and the node it
  /// resolves to (in `node` if given).
  VisualVertexBinding resolvedBinding(int v, int* node = nullptr) const;
  /// Writes v's resolved binding back (nothing if it is current).
  void resolveBinding(int v);
  /// Each of `vertices` (bound anew by this cut) bound to the current node
  /// of its triangle (vertices are made with -1, copies with their
  /// source's node).
  void noteBindingNodes(const std::vector<int>& vertices);

  SurfacePoint featurePoint(const RegionCut& region,
    int vertex,
    const Vector3& barycentric,
    const RegionWorker& worker,
    const CutContext& context) const;
  void traceRegion(RegionCut& region, RegionWorker& worker, const CutContext& context);
  /// A region vertex's barycentric parameters in the split's parent.
  Vector3 parentParameters(int v, const CollisionTriangleSplit& split) const;
  bool crossingLines(RegionCut& region,
    const CutContext& context,
    std::vector<int>& pairedEnds) const;
  bool separateFarTriangles(RegionCut& region,
    RegionWorker& worker,
    const CutContext& context) const;
  void layOutRegion(RegionCut& region, RegionWorker& worker, const CutContext& context);
  /// Whether the laid-out near triangles and the far ones lie in the plane
  /// without a fold together (else the region is laid out whole).
  bool farTrianglesAgree(const RegionCut& region) const;
  void traceCut(RegionCut& region,
    double scale,
    CrossingPath& crossing,
    RegionWorker& worker,
    const CutContext& context);
  void linkCrossedTriangles(RegionCut& region,
    double tolerance,
    const Vector2& from,
    const Vector2& along,
    CutBuffers& buffers);

  void splitEdgePaths(CutContext& context);
  void traceRegionCuts(CutContext& context);
  void remeshRegions(CutContext& context);
  void appendInserted(const TriangleMesh& out,
    std::vector<int>& global,
    std::vector<int>& globalTexture,
    CutContext& context);
  void spliceTriangle(RegionCut& region,
    const RemeshedSurface& remeshed,
    int j,
    const std::vector<int>& global,
    const std::vector<int>& globalTexture,
    const std::vector<int>& globalTriangle,
    CutContext& context);
  void selectTouchedTriangles(RegionCut& region, const RegionWorker& worker);
  void rebindSplitRegions(CutContext& context);
  void rebindRegion(RegionCut& region, RegionWorker& worker, const CutContext& context);
  void rebindFarTriangles(RegionCut& region, RegionWorker& worker, const CutContext& context);
  void listPiecesInRegionOrder(RegionCut& region,
    CutBuffers& buffers,
    const CollisionTriangleSplit& split);
  std::vector<char> bindCrossingVertices(RegionCut& region,
    RegionWorker& worker,
    const CutContext& context);
  struct PieceLocator;
  bool pieceLocator(const RegionCut& region,
    const CollisionTriangleSplit& split,
    double margin,
    PieceLocator& locator) const;
  bool locatePieces(RegionCut& region,
    const std::vector<char>& onCut,
    CutBuffers& buffers,
    const CutContext& context);
  void assignPieces(RegionCut& region,
    const std::vector<char>& onCut,
    RegionWorker& worker,
    const CutContext& context);
  void rebindPieces(RegionCut& region,
    const std::vector<char>& onCut,
    CutBuffers& buffers,
    const CutContext& context);
  void rebindPiece(RegionCut& region,
    const int* members,
    int memberCount,
    int piece,
    int child,
    const Eigen::Matrix3d& inverse,
    CutBuffers& buffers);
  /// Whether a vertex with parent parameters `parameters`, going to piece
  /// `piece`, may be left to the split history
  /// (VisualCutSettings::lazyBinding): it resolves to what formula 5-2
  /// gives here, bit for bit. `planar` must be the parameters' own point in
  /// the region's plane (planarPoint): the caller checks that no bulge or
  /// fold repair moved the vertex.
  bool leftToHistory(const RegionCut& region,
    const Vector3& parameters,
    const Vector2& planar,
    int piece) const;
  /// Resolves the bindings of the split triangles' regions before a cut
  /// reads them (once a cut has left some to the history).
  void resolveSplitRegions(const CollisionCutResult& cut);
  /// Per local vertex: whether formula 5-2 rebinds it (bound to the parent,
  /// off the traced cuts); rebindPiece clears it once done.
  void markRebindable(const RegionCut& region,
    int parent,
    const std::vector<char>& onCut,
    CutBuffers& buffers) const;
  void finishEdgePoints(CutContext& context);
  bool rootStillUses(const CuttableCollisionMesh& collision, int v) const;
  /// A corner of a visual triangle that needs the copy of its vertex a
  /// collision vertex or edge copy serves (openVisualMesh).
  struct Claim
  {
    int triangle;
    int corner;
    int vertex;
    int element; ///< collision vertex, or edge (x, y) in `edge`
    std::array<int, 2> edge;
  };
  void claimsOf(int T,
    const CuttableCollisionMesh& collision,
    const CutContext& context,
    std::vector<Claim>& claims) const;
  void openVisualMesh(const CuttableCollisionMesh& collision, CutContext& context);
  /// A junction edge left with one triangle keeps the two paths it sees.
  void dropUnseenJunctionPaths(const CuttableCollisionMesh& collision, CutContext& context);
  void updateEdgePaths(const CuttableCollisionMesh& collision, CutContext& context);
  void updateCutSurface(const CuttableCollisionMesh& collision, CutContext& context);
  void splitStrip(std::uint64_t key, int a, int b, int middle, double at, CutContext& context);
  struct EndColumn;
  /// Collision vertex v's column of cut-surface vertices (entries not made
  /// yet are -1), and entry `index` of it, made if needed.
  EndColumn& endColumn(const CuttableCollisionMesh& collision, int collisionVertex);
  int columnVertex(int collisionVertex, int index, const Vector3& outward);
  /// A strip's lip: the triangle whose region on `side` (0: -, 1: +)
  /// borders its + path, and which of the strip's sides (-, +) take the
  /// cleft's crease at a junction.
  struct StripLip
  {
    int triangle = -1;
    int side = 1;
    std::array<bool, 2> cleft{ { false, false } };
  };
  /// Whether collision edge (a, b) carries a strip (an opened edge, or a
  /// junction edge left with two of its three sheets) and its lip.
  bool stripSides(const CuttableCollisionMesh& collision, int a, int b, StripLip& lip) const;
  /// The lips of the strips at collision vertex v, each strip once.
  std::vector<StripLip> stripLipsAt(const CuttableCollisionMesh& collision, int v) const;
  bool creaseOnTheCut(const CuttableCollisionMesh& collision, int v) const;
  /// Throws Error where more than two cut walls would share a segment of
  /// junction vertex v's column.
  void checkColumnWalls(const CuttableCollisionMesh& collision, int v);
  /// Per entry of v's column: whether a strip at v (an edge of one triangle
  /// there) spans it.
  std::vector<bool> columnNeeds(const CuttableCollisionMesh& collision, int v) const;
  /// Whether v's column runs through its crease vertex for a strip at v.
  bool bodyColumnUsesCrease(const CuttableCollisionMesh& collision, int v) const;
  void handOverColumns(const CuttableCollisionMesh& collision, CutContext& context);
  void upgradeColumns(const CuttableCollisionMesh& collision,
    std::vector<std::array<int, 2>>& edges,
    CutContext& context);
  /// Adds the edges of the strips at v to `edges` (to be rebuilt).
  void addStripsAt(const CuttableCollisionMesh& collision,
    int v,
    std::vector<std::array<int, 2>>& edges) const;
  /// The rows a strip needs: as many as its longer end column has entries.
  int stripRowCount(const CuttableCollisionMesh& collision, int a, int b, const CutStrip& strip);
  /// Gives a strip the rows its end columns have grown to.
  void growStrip(const CuttableCollisionMesh& collision,
    int a,
    int b,
    CutStrip& strip,
    CutContext& context);
  /// Where a smooth cut puts entry `index` of collision vertex v's end
  /// column: between its + and - paired vertices (at a junction vertex,
  /// + to crease, then crease to -).
  Vector3 columnPlace(int v, int index) const;
  /// The part of v's end column a strip with sides facing `cleft` joins:
  /// from its + paired vertex to its - one, both included.
  std::vector<int> stripColumn(const CuttableCollisionMesh& collision,
    int v,
    const std::array<bool, 2>& cleft,
    const Vector3& outward);
  /// The positions of that part in the column with its ends (0: the +
  /// paired vertex; the - one after the inner entries).
  std::array<int, 2> columnSpan(const CuttableCollisionMesh& collision,
    int v,
    const std::array<bool, 2>& cleft);
  std::array<int, 2> columnSpan(const EndColumn& column,
    int v,
    const std::array<bool, 2>& cleft) const;
  /// A strip's + and - paths on edge (a, b).
  std::array<const std::vector<int>*, 2> stripPaths(int a, int b, const CutStrip& strip) const;
  std::vector<int> openPart(const std::vector<int>& path, int a, int b) const;
  void makeStripRows(const CuttableCollisionMesh& collision,
    int a,
    int b,
    int rowCount,
    CutStrip& strip,
    CutContext& context);
  void buildStrip(const CuttableCollisionMesh& collision, int a, int b, CutStrip& strip);
  /// The jagged cut surface's offset of a cut-surface vertex made at
  /// `restPosition` (JaggedCutSurface.cxx).
  Vector3 jaggedOffset(const Vector3& restPosition, const Vector3& outward) const;
  /// A cut-surface vertex, its parameter on its strip's collision edge and
  /// where a smooth cut puts it.
  struct SmoothPlace
  {
    int vertex;
    double u;
    Vector3 smooth;
  };
  /// The places of the strip's rows and end columns (CutSurface.cxx).
  void smoothPlaces(std::uint64_t key,
    const CutStrip& strip,
    std::vector<SmoothPlace>& places) const;

  VisualCutSettings Settings;
  TriangleMesh Mesh;
  std::vector<VisualVertexBinding> Bindings;
  std::vector<std::array<int, 2>> Edges;
  std::unordered_map<std::uint64_t, int> EdgeIndex;
  std::vector<int> TriangleRegion;
  std::vector<std::int8_t> TriangleSide;
  std::vector<VisualMaterial> TriangleMaterial;
  /// Per collision vertex, per path slot (- / + / crease, -1 if none).
  std::vector<std::array<int, 3>> Paired;
  /// The collision mesh has a horizontal cleavage's junction (cuts never
  /// make one): the junction-only stages run only then.
  bool HasJunctions = false;
  /// Per collision triangle: its region's visual triangles on side -1, +1.
  std::vector<std::array<std::vector<int>, 2>> Regions;
  CollisionSplitHistory SplitHistory;
  /// Per visual vertex: its binding's node in SplitHistory (bindingNode).
  std::vector<int> BindingNodes;
  /// A cut has left bindings to the history (resolveSplitRegions has work).
  bool LeftToHistory = false;
  std::unordered_map<std::uint64_t, EdgePaths> Paths;
  std::unordered_map<std::uint64_t, CutStrip> Strips;
  /// Per collision vertex on a cut: the cut-surface vertices of its column
  /// (on the rim, its one visual vertex once per row).
  struct EndColumn
  {
    std::vector<int> vertices;
    bool rim = false;
    /// At a junction vertex whose leaves are cut: + to crease, the crease,
    /// crease to - (a cut through the body alone passes the crease by).
    bool throughCrease = false;
  };
  std::unordered_map<int, EndColumn> EndColumns;
  std::vector<int> FreeTriangles;
  int CutSurfaceTexture = -1;
  /// At least one; each one's local indices all -1 between cuts.
  std::vector<RegionWorker> Workers = std::vector<RegionWorker>(1);
};

} // namespace thintissue

#endif
