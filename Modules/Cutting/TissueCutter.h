// One tissue that can be cut (thesis 5.3): its collision mesh with radii,
// its hexahedral simulation mesh and the collision-simulation embedding,
// kept consistent cut after cut; the solver, when given, follows every
// topology change locally.
//
// cut(blade) runs 5.3.1: the blade against the collision mesh at the
// current positions (CuttableCollisionMesh), hexahedron duplication by
// branch analysis (HexahedralBranches), the solver updated for what changed
// only (new nodes, copied elements with their rest state, re-noded
// elements), and the collision vertices re-embedded in the copy holding
// their branch. Made from a binding, it cuts the visual mesh too (5.3.2 -
// 5.3.4, CuttableVisualMesh) and re-embeds the visual vertices whose
// hexahedron or binding changed in the copy holding their collision
// triangle (5.3.5).
#ifndef TissueCutter_h
#define TissueCutter_h

#include "CollisionMeshCut.h"
#include "HexahedralEmbedding.h"
#include "HexahedronDuplication.h"
#include "VisualMeshCut.h"

#include "ThinTissueCuttingModule.h"
#include <string>

namespace thintissue
{

class CorotationalHexFem;

/// What becomes of a piece cut free (one attached to nothing, or, when
/// nothing is attached, any but the largest piece).
enum class FreePieceHandling
{
  Keep,    ///< stays in the tissue and moves on its own
  Drop,    ///< removed from the tissue
  HandOver ///< removed, and returned as its own body (TissueCutReport::handedOver)
};

/// A piece cut free as a body of its own: its meshes, rest and current.
struct TissuePiece
{
  /// The visual surface with its cut surfaces at the current positions
  /// (empty without a visual mesh); rest positions in `visualRest`.
  TriangleMesh visual;
  std::vector<Vector3> visualRest;
  /// The collision mesh (rest) with its radius array, and its current
  /// vertex positions.
  TriangleMesh collision;
  std::vector<Vector3> collisionCurrent;
  /// Its hexahedra (rest nodes, fixed-node mask) and their nodes' current
  /// positions.
  HexahedralMesh simulation;
  std::vector<Vector3> nodeCurrent;
  double collisionArea = 0.0;
};

struct TissueCutterSettings
{
  CollisionCutSettings collision;
  std::string radiusArrayName = "Radius";
  /// Used when the cutter is made from a binding.
  VisualCutSettings visual;
  FreePieceHandling freePieces = FreePieceHandling::Keep;
  /// Free pieces whose collision area is below this fraction of the
  /// tissue's are removed whole, whatever freePieces says (0: none).
  double fragmentAreaFraction = 0.0;
};

/// What one cut did, and what it cost.
struct TissueCutReport
{
  CollisionCutResult collision;
  HexahedronDuplicationResult simulation;
  /// Collision vertices whose embedding changed (new ones included).
  std::vector<int> reembeddedCollisionVertices;
  /// The visual cut (empty without a visual mesh) and the visual vertices
  /// whose embedding changed (new ones included).
  VisualCutResult visual;
  std::vector<int> reembeddedVisualVertices;
  /// Pieces removed by this cut (free pieces dropped or handed over, and
  /// fragments), and those handed over.
  int removedPieces = 0;
  /// The collision triangles those pieces held (taken out of the tissue
  /// by this cut), piece by piece.
  std::vector<int> removedTriangles;
  std::vector<TissuePiece> handedOver;
  /// Set when the visual cut failed (a binding it cannot follow, e.g. paths
  /// sharing segments on some prepared tissues): the collision and
  /// simulation meshes are cut; the visual mesh stays as it was and is not
  /// cut again (TissueCutter::visualFailed()).
  std::string visualError;
  /// Milliseconds: blade test and collision re-meshing; hexahedron
  /// duplication and solver update; embedding updates; the whole cut.
  double collisionMilliseconds = 0.0;
  double simulationMilliseconds = 0.0;
  double embeddingMilliseconds = 0.0;
  /// Visual cut, binding update and cut surface (5.3.2 - 5.3.4); visual
  /// re-embedding (5.3.5).
  double visualMilliseconds = 0.0;
  double visualEmbeddingMilliseconds = 0.0;
  /// Free pieces and fragments removed or handed over (6.4.2: a bite's
  /// piece goes at once).
  double removalMilliseconds = 0.0;
  double totalMilliseconds = 0.0;
  bool changed() const { return collision.changed(); }
};

/// What one contouring pass did (6.4.4, TissueCutter::contour).
struct CutRimContourReport
{
  /// Cut-surface vertices moved (rest positions and embedding), each once.
  std::vector<int> movedVertices;
  double milliseconds = 0.0;
};

class THINTISSUECUTTING_EXPORT TissueCutter
{
public:
  /// `collision`: the mid-surface with a per-vertex radius array;
  /// `simulation`: its hexahedra (rest). `solver`, if given, must have been
  /// made from `simulation` and outlive the cutter; it is updated by every
  /// cut and its positions drive the blade test. Throws InvalidInputError
  /// naming the mesh on bad input.
  TissueCutter(const TriangleMesh& collision,
    const HexahedralMesh& simulation,
    CorotationalHexFem* solver = nullptr,
    const TissueCutterSettings& settings = {});

  /// A cutter that cuts the bound visual mesh too: the collision mesh is
  /// the binding's (rest positions, triangles, radii).
  TissueCutter(const VisualCollisionBinding& binding,
    const HexahedralMesh& simulation,
    CorotationalHexFem* solver = nullptr,
    const TissueCutterSettings& settings = {});

  /// Cuts with `blade` (world coordinates). A blade that crosses nothing
  /// changes nothing. Throws InvalidInputError, with the tissue untouched,
  /// on a bad blade (empty, NaN, degenerate).
  TissueCutReport cut(const Blade& blade);
  /// cut() in two halves, for a caller that overlaps the visual half with
  /// other work (the training scene runs it beside the physics step, which
  /// reads only the collision side). cutCollision cuts the collision and
  /// simulation meshes, updates the solver, re-embeds the collision mesh
  /// and removes the pieces that came free (their collision and simulation
  /// parts); finishVisualCut then cuts the visual mesh, re-embeds it and
  /// gives the handed-over pieces their visual parts. Between the two only
  /// the collision side may be read (no cut, removal, contouring, settings,
  /// nor any read of the visual mesh); cut() is the two in a row, with the
  /// same result. cutCollision throws InvalidInputError while a visual
  /// half is pending.
  TissueCutReport cutCollision(const Blade& blade);
  void finishVisualCut(TissueCutReport& report);
  /// Whether cutCollision or removeTrianglesCollision left a visual half
  /// for finishVisualCut.
  bool visualCutPending() const { return VisualPending; }
  /// Piecewise removal (6.4.3, a running shaver): the given collision
  /// triangles (inactive ones ignored) go, with the visual triangles bound
  /// to them; the tissue opens along their border, whose cut surface closes
  /// the visual mesh. They are handed over as one piece when freePieces
  /// says so (dropped otherwise), and whatever the removal left apart is
  /// handled like a cut's free pieces. Nothing is split or re-meshed: it
  /// costs what lies around the border. Throws InvalidInputError, the
  /// tissue untouched, on an index that is no triangle.
  TissueCutReport removeTriangles(const std::vector<int>& triangles);
  /// removeTriangles' collision half (see cutCollision); finishVisualCut
  /// completes it.
  TissueCutReport removeTrianglesCollision(const std::vector<int>& triangles);
  /// The collision triangles still in the tissue whose centroid (rest
  /// positions) lies within `radius` of `centre`: what a shaver's window
  /// held there takes (6.4.3), for removeTriangles. Throws
  /// InvalidInputError on a radius that is not positive or a centre that is
  /// not finite.
  std::vector<int> activeTrianglesWithin(const Vector3& centre, double radius) const;

  /// The settings of the cuts to come, changed between cuts (a settings
  /// panel): snapping, free-piece handling, fragment size and the visual
  /// cut's (CuttableVisualMesh::setSettings). Throws InvalidInputError,
  /// changing nothing, on bad values, on another radius array name (read
  /// once, when the cutter was made) or on a new cut-surface row count once
  /// the tissue has a cut surface.
  void setSettings(const TissueCutterSettings& settings);
  const TissueCutterSettings& settings() const { return Settings; }

  const CuttableCollisionMesh& collision() const { return Collision; }
  /// The hexahedra with their copies (rest nodes).
  const HexahedralMesh& simulation() const { return Simulation; }
  const HexahedralBranches& branches() const { return Branches; }
  /// Copies made when the cutter was built (a tissue torn in places).
  const HexahedronDuplicationResult& initialSeparation() const { return InitialSeparation; }
  const HexahedralEmbedding& collisionEmbedding() const { return CollisionEmbedding; }
  /// Collision vertex positions from the solver's (or the rest) node positions.
  std::vector<Vector3> currentCollisionPositions() const;
  /// The collision mesh as a TriangleMesh with its radius array.
  TriangleMesh collisionMesh() const;

  /// Whether a collision triangle is still part of the tissue (a removed
  /// piece's are not: they neither collide nor show, and its nodes are held
  /// still in the solver).
  bool isActive(int collisionTriangle) const { return Active[collisionTriangle] != 0; }
  std::size_t activeTriangleCount() const;
  /// Per visual triangle: whether it belongs to an active collision
  /// triangle's region.
  std::vector<char> activeVisualTriangles() const;

  bool hasVisual() const { return HasVisual; }
  /// Whether a visual cut failed (see TissueCutReport::visualError).
  bool visualFailed() const { return VisualFailed; }
  /// The visual mesh with its cut surfaces (rest) and bindings; empty
  /// without a binding.
  const CuttableVisualMesh& visual() const { return Visual; }
  const HexahedralEmbedding& visualEmbedding() const { return VisualEmbedding; }
  /// Visual vertex positions from the solver's (or the rest) node positions.
  std::vector<Vector3> currentVisualPositions() const;

  /// Contouring (6.4.4, TissueContour.cxx): a tool held on the cut rim
  /// within `radius` of `centre` (world, current positions) smooths the cut
  /// surface around the parameters it touches: on each collision edge of
  /// the tissue's cut that passes within the radius, the cut-surface
  /// vertices move toward the smooth cut by strength (1 - (d/r)^2)^2 of the
  /// way, d being the distance of their point on the edge from the centre.
  /// Nothing else moves, nothing is cut or removed; the moved vertices keep
  /// their hexahedra. Throws InvalidInputError, changing nothing, on a
  /// non-finite centre, a radius <= 0 or a strength outside [0, 1].
  CutRimContourReport contour(const Vector3& centre, double radius, double strength);
  /// The roughness of the cut surface of the pieces still in the tissue
  /// (6.4.4; zero without a visual mesh or a jagged cut).
  CutSurfaceRoughness cutRimRoughness() const;

private:
  /// The simulation and collision embedding stages of a collision cut in
  /// `report`.
  void followCollisionCut(TissueCutReport& report);
  /// Its visual stages; false when the visual cut failed (visualError set).
  bool followWithVisualCut(TissueCutReport& report);
  /// Refuses (InvalidInputError naming `what`) while a visual half is
  /// pending.
  void requireNoVisualPending(const char* what) const;
  void updateSolver(const HexahedronDuplicationResult& duplication);
  std::vector<int> reembedCollision(const TissueCutReport& report);
  std::vector<int> reembedVisual(const TissueCutReport& report);
  static constexpr int NoCollisionTriangle = -2;
  /// The copy of a visual vertex's hexahedron holding its collision
  /// triangle, -1 if none, NoCollisionTriangle if it has none.
  int branchHolder(int visualVertex) const;
  bool moveToBranchCopy(int visualVertex);
  bool moveToBranchCopy(int visualVertex, int holder);
  /// The vertices the visual cut left to the split history, moved to the
  /// copy holding their resolved triangle where it changed (appended to
  /// `moved`).
  void followLeftToHistory(const TissueCutReport& report, std::vector<int>& moved);
  void noteRevisits(int visualVertex);
  void takeRevisits(const TissueCutReport& report, std::vector<int>& vertices);
  void handleFreePieces(TissueCutReport& report);
  bool cutMaySeparate(const TissueCutReport& report);
  bool activeMeshIsOnePiece() const;
  /// A free piece handed over (report.handedOver): its collision and
  /// simulation parts; its visual part is noted for finishVisualCut
  /// (pieceVisual).
  void handOver(const std::vector<int>& triangles, TissueCutReport& report);
  void pieceVisual(const std::vector<int>& triangles,
    const std::vector<Vector3>& nodeCurrent,
    TissuePiece& piece) const;
  void removePiece(const std::vector<int>& triangles, TissueCutReport& report);

  TissueCutterSettings Settings;
  CuttableCollisionMesh Collision;
  HexahedralMesh Simulation;
  HexahedralBranches Branches;
  HexahedralEmbedding CollisionEmbedding;
  HexahedronDuplicationResult InitialSeparation;
  CorotationalHexFem* Solver = nullptr;
  bool HasVisual = false;
  bool VisualFailed = false;
  /// Between cutCollision and finishVisualCut: the visual half is due, and
  /// the handed-over pieces whose visual parts it makes (report.handedOver
  /// index, collision triangles, node positions when the piece came free).
  bool VisualPending = false;
  struct PendingPieceVisual
  {
    std::size_t piece = 0;
    std::vector<int> triangles;
    std::vector<Vector3> nodeCurrent;
  };
  std::vector<PendingPieceVisual> PendingPieces;
  CuttableVisualMesh Visual;
  HexahedralEmbedding VisualEmbedding;
  /// Per original hexahedron: the visual vertices embedded in it or a copy.
  std::vector<std::vector<int>> VisualOfHexahedron;
  /// Per visual vertex, 0 between cuts: marks while a cut re-embeds.
  std::vector<char> VisualSeen;
  std::vector<char> CollisionSeen; ///< per collision vertex, all 0 between cuts
  /// Per hexahedron (copies too), all 0 between cuts: 1 + its place among
  /// the candidates of the new visual vertices (each once, its rest centre
  /// computed once), else 0.
  std::vector<int> CandidateSlot;
  /// Visual vertices a cut may move to another piece without copying
  /// their hexahedron, revisited by the cuts that may have done so:
  /// - those embedded in a hexahedron that holds a triangle around their
  ///   collision triangle but not that triangle (moveToBranchCopy), each
  ///   once (flagged per vertex), revisited by every cut: the triangle they
  ///   hang on goes to another piece when the collision mesh opens at a
  ///   corner it shares with theirs;
  /// - those bound to a collision edge or vertex, listed per original
  ///   hexahedron (WatchedIn: per vertex the one whose list holds it, or
  ///   -1), revisited by the cuts that touch it: their triangle is the
  ///   edge's or vertex's first, which a split of a triangle beside them
  ///   changes.
  std::vector<int> IndirectVisual;
  std::vector<char> VisualIndirect;
  std::vector<std::vector<int>> WatchedOfHexahedron;
  std::vector<int> WatchedIn;
  /// Per collision triangle: 1 while it is part of the tissue.
  std::vector<char> Active;
  /// Whether the active collision mesh was one piece after the last cut
  /// (then a cut that separates nothing leaves the pieces alone), and the
  /// floods' scratch (per triangle -1 between cuts; the queue).
  bool SinglePiece = false;
  std::vector<int> PieceLabel;
  std::vector<int> PieceQueue;
  double InitialArea = 0.0;
};

} // namespace thintissue

#endif
