// Cutting the collision mesh (thesis 5.3.1): the blade is intersected with
// the collision edges at the current (deformed) positions; the crossings are
// carried to the rest configuration by their edge parameter; each triangle
// the cut crosses is split (through two edges: into three, fig. 5-8) and the
// mesh is opened along the cut by duplicating the vertices on it.
//
//  - Snapping ([148]): a crossing within `snapFraction` of an edge's length
//    from an end is moved onto that vertex, so no sliver triangle is made;
//    a cut then runs through vertices or along edges.
//  - Opening: around each vertex on the cut, the triangles are grouped into
//    fans separated by cut (and border) edges; every fan after the first
//    gets its own copy of the vertex. A vertex where the cut ends inside the
//    mesh keeps one fan, so the cut opens up to it and no further.
//  - Progressive cut: a blade that stops inside a triangle leaves the
//    crossing it made as a vertex (the triangle split in two, no sliver) and
//    remembers it as a cut tip; when a later blade crosses another edge of a
//    triangle at that tip, the cut is completed from the tip.
//  - New vertices take the radius interpolated along their edge.
//  - A horizontal cleavage's junction edges join three triangles (the body
//    and the two leaves, CollisionSides.h). The cut treats them like any
//    edge: a crossing splits all three triangles at one edge point, and the
//    opening groups the fans through every triangle of an uncut edge, so
//    each side of the blade gets a copy that is still a junction. The
//    pieces inherit the halves of the visual surface their parent faced.
#ifndef CollisionMeshCut_h
#define CollisionMeshCut_h

#include "Blade.h"
#include "CollisionSides.h"
#include "ThinTissueCuttingModule.h"
#include "TriangleMesh.h"
#include "UnionFind.h"

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace thintissue
{

struct CollisionCutSettings
{
  /// A crossing nearer than this fraction of the edge to an end snaps to it.
  double snapFraction = 0.15;
};

/// One collision triangle replaced by its pieces.
struct CollisionTriangleSplit
{
  int parent = -1;
  /// Corners of the parent before the cut.
  Triangle parentCorners{ { -1, -1, -1 } };
  /// Indices of the pieces (the first reuses the parent's index).
  std::vector<int> children;
  /// Per piece: the barycentric coordinates in the parent of its three
  /// corners (rows) — the matrix M of formula 5-2.
  std::vector<std::array<Vector3, 3>> childCorners;
};

/// Where a vertex made by a cut came from.
struct NewCollisionVertex
{
  int vertex = -1;
  /// Copy of an existing vertex (the mesh opened there), or -1.
  int duplicateOf = -1;
  /// A point on edge (edge[0], edge[1]) at parameter t (duplicateOf < 0).
  std::array<int, 2> edge{ { -1, -1 } };
  double t = 0.0;
};

struct CollisionCutResult
{
  /// Triangles split (their pieces listed).
  std::vector<CollisionTriangleSplit> splits;
  /// Vertices made: edge points first, then duplicates.
  std::vector<NewCollisionVertex> newVertices;
  /// Triangles whose corners changed (pieces, and triangles moved to a
  /// vertex copy), sorted, no repeats.
  std::vector<int> changedTriangles;
  /// Edges the cut runs along (rest vertex pairs, before opening).
  std::vector<std::array<int, 2>> cutEdges;
  /// Vertices that were split into fans (each with its copies in newVertices).
  std::vector<int> openedVertices;
  bool changed() const { return !changedTriangles.empty(); }
};

/// A collision mesh that can be cut: rest positions, triangles, radii, and
/// the adjacency a cut needs, kept up to date locally.
class THINTISSUECUTTING_EXPORT CuttableCollisionMesh
{
public:
  CuttableCollisionMesh() = default;
  /// Throws InvalidInputError naming `name` if an index is out of range, a
  /// coordinate or radius is not finite, or the triangles are no collision
  /// mid-surface (analyseCollisionSides: an edge of more than three
  /// triangles, neighbours oriented differently, a junction that is no
  /// cleavage's, fans touching at a vertex).
  CuttableCollisionMesh(std::string name,
    std::vector<Vector3> restPositions,
    std::vector<Triangle> triangles,
    std::vector<double> radii);

  const std::string& name() const { return Name; }
  std::size_t vertexCount() const { return RestPositions.size(); }
  std::size_t triangleCount() const { return Triangles.size(); }
  const std::vector<Vector3>& restPositions() const { return RestPositions; }
  const std::vector<Triangle>& triangles() const { return Triangles; }
  const std::vector<double>& radii() const { return Radii; }
  const std::vector<int>& trianglesOfVertex(int v) const { return VertexTriangles[v]; }
  /// Triangles on edge (a, b), in no particular order: -1 where there is
  /// none (the third is there only at a cleavage's junction).
  std::array<int, 3> trianglesOfEdge(int a, int b) const;
  /// Per triangle, per side slot (0: +, 1: -): the half of the visual
  /// surface it faces (CollisionSides); pieces inherit their parent's.
  const std::vector<std::array<SurfaceHalf, 2>>& halves() const { return Halves; }
  /// Cut edges that have not opened (neither end was split).
  std::size_t closedCutEdgeCount() const { return CutEdges.size(); }
  /// Those edges (lower, higher), sorted. A junction edge the cut ran
  /// along may be one with two leaves left on it (the body gone), which
  /// meet there oriented alike until a later cut opens it.
  std::vector<std::array<int, 2>> closedCutEdges() const;
  /// Where the last blade that crossed an edge left the cut: the next blade
  /// continues from there (progressive cut).
  const std::unordered_set<int>& cutTips() const { return Tips; }

  /// Cuts with `blade` at the current positions `current` (one per vertex).
  /// Throws InvalidInputError (mesh untouched) on a bad blade or a wrong
  /// count of positions.
  CollisionCutResult cut(const Blade& blade,
    const std::vector<Vector3>& current,
    const CollisionCutSettings& settings = {});
  /// Cuts along existing edges, each between two or three triangles (the
  /// border of what a shaver removes, 6.4.3): no triangle is split, the
  /// mesh opens along them. Throws InvalidInputError (mesh untouched) on a
  /// pair that is no such edge.
  CollisionCutResult cutAlongEdges(std::vector<std::array<int, 2>> edges);

private:
  struct Crossing;
  struct TriangleFeatures;
  static std::uint64_t edgeKey(int a, int b);
  void addToAdjacency(int t);
  void checkTriangles() const;
  void removeFromAdjacency(int t);
  int addVertex(const Vector3& rest, double radius);
  std::unordered_map<std::uint64_t, Crossing> findCrossings(const Blade& blade,
    const std::vector<Vector3>& current) const;
  std::vector<TriangleFeatures> collectFeatures(
    const std::unordered_map<std::uint64_t, Crossing>& crossings,
    double snapFraction,
    CollisionCutResult& result);
  void keepNearestTipLinks(std::vector<TriangleFeatures>& reached) const;
  void splitTriangle(const TriangleFeatures& features, CollisionCutResult& result);
  void recordCutAlongEdge(const TriangleFeatures& features,
    int i,
    int j,
    CollisionCutResult& result) const;
  void openAlongCut(CollisionCutResult& result);
  /// Branch label per triangle of v's fan (5.3.1): fans joined through
  /// uncut edges, a junction's three sheets one fan while their edge is.
  std::vector<int> fanBranches(int v, const std::vector<int>& fan) const;
  /// v's fan joined through its uncut edges, among the triangles `member`
  /// accepts.
  template <typename Member>
  UnionFind joinAcrossUncutEdges(int v, const std::vector<int>& fan, Member member) const;
  std::array<int, 2> notchedJunctionCut(int v,
    const std::vector<int>& fan,
    const std::vector<int>& branch,
    SurfaceHalf half) const;
  template <typename Faces>
  std::array<int, 2> wholeLeafEdge(int v,
    const std::vector<int>& fan,
    const std::vector<int>& branch,
    int component,
    Faces faces) const;
  /// Whether vertex w lies on the mesh's border (an edge with one triangle).
  bool onBorder(int w) const;
  void keepCutEdgesOfCopy(int t, int v, int copy);
  /// A closed cut edge left to two leaves oriented alike (their body cut
  /// off along their junction edge).
  bool isLeavesFold(int a, int b) const;
  void updateTips(const std::vector<int>& sweepFeatures,
    const std::vector<int>& reachedTips,
    const std::vector<std::array<int, 2>>& sweepCutEdges);

  std::string Name;
  std::vector<Vector3> RestPositions;
  std::vector<Triangle> Triangles;
  std::vector<double> Radii;
  std::vector<std::vector<int>> VertexTriangles;
  std::vector<std::array<SurfaceHalf, 2>> Halves;
  std::unordered_map<std::uint64_t, std::array<int, 3>> EdgeTriangles;
  std::unordered_set<std::uint64_t> CutEdges;
  std::unordered_set<int> Tips;
};

} // namespace thintissue

#endif
