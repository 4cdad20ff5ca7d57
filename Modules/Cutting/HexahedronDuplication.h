// Hexahedron duplication by branch analysis (thesis 5.3.1, figs 5-8, 5-9;
// after the virtual node algorithm of Molino et al. and Nesme et al.).
//
// The material of a hexahedron is the part of the collision surface in it:
// the collision triangles that meet its rest box, the box grown by the
// triangle's radius (so that a hexahedron holding only the rim of the
// visual surface still holds the triangle the rim belongs to). After a cut,
// the triangles of each touched hexahedron fall into branches (connected
// through shared collision edges); the hexahedron keeps its largest branch
// and a copy is made for every other, with the same nodes and rest shape.
// Then, around every node of a touched hexahedron, the hexahedra (copies
// included) are grouped by sharing a collision triangle: each group after
// the largest gets its own copy of the node. Pieces of the collision
// surface that no longer share a triangle therefore share no node.
#ifndef HexahedronDuplication_h
#define HexahedronDuplication_h

#include "CollisionMeshCut.h"
#include "HexahedralMesh.h"
#include "ThinTissueCuttingModule.h"
#include "UnionFind.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace thintissue
{

/// What a cut changed in the hexahedral mesh.
struct HexahedronDuplicationResult
{
  /// New hexahedra (copies), each with the hexahedron it copies.
  std::vector<std::array<int, 2>> newHexahedra; ///< (copy, source)
  /// New nodes, each with the node it copies.
  std::vector<std::array<int, 2>> newNodes; ///< (copy, source)
  /// Existing hexahedra whose nodes changed (sorted).
  std::vector<int> renodedHexahedra;
  /// Hexahedra whose branch was analysed (sorted).
  std::vector<int> touchedHexahedra;
};

class THINTISSUECUTTING_EXPORT HexahedralBranches
{
public:
  HexahedralBranches() = default;
  /// Assigns every collision triangle to the hexahedra it meets (rest).
  HexahedralBranches(const HexahedralMesh& mesh, const CuttableCollisionMesh& collision);

  /// Collision triangles in hexahedron h (sorted).
  const std::vector<int>& trianglesOf(int h) const { return HexTriangles[h]; }
  /// Hexahedra a collision triangle meets.
  const std::vector<int>& hexahedraOf(int triangle) const { return TriangleHexes[triangle]; }
  /// The hexahedron of the input mesh that h is a copy of (h itself if none).
  int originalOf(int h) const { return Original[h]; }
  /// Every hexahedron with the same original as h (h included).
  const std::vector<int>& copiesOf(int h) const { return Copies[Original[h]]; }
  /// Among the copies of h, one that holds any of `triangles`; -1 if none.
  int copyHolding(int h, const std::vector<int>& triangles) const;
  /// Among the copies of h, one that holds `triangle`; -1 if none.
  int copyHolding(int h, int triangle) const;

  /// Follows a collision cut: pieces take their parent's place in the
  /// hexahedra they meet, touched hexahedra are split into branches (new
  /// copies appended to `mesh`), nodes regrouped (new nodes appended).
  HexahedronDuplicationResult update(const CuttableCollisionMesh& collision,
    const CollisionCutResult& cut,
    HexahedralMesh& mesh);

  /// Branch analysis of every hexahedron: for a tissue whose collision
  /// surface is already torn, or folded back, inside some hexahedra.
  HexahedronDuplicationResult separateAll(const CuttableCollisionMesh& collision,
    HexahedralMesh& mesh);

private:
  HexahedronDuplicationResult duplicate(const CuttableCollisionMesh& collision,
    std::vector<int> touched,
    HexahedralMesh& mesh);
  void assignPieces(const CuttableCollisionMesh& collision,
    const CollisionCutResult& cut,
    std::vector<int>& touched);
  void splitBranches(const CuttableCollisionMesh& collision,
    int h,
    HexahedralMesh& mesh,
    HexahedronDuplicationResult& result);
  void branchMembers(int root, std::vector<int>& members);
  void regroupNode(int node, HexahedralMesh& mesh, HexahedronDuplicationResult& result);
  bool meets(const CuttableCollisionMesh& collision, int triangle, int h) const;

  std::vector<BoundingBox> RestBoxes; ///< per original hexahedron
  std::vector<std::vector<int>> HexTriangles;
  std::vector<std::vector<int>> TriangleHexes;
  std::vector<std::vector<int>> NodeHexes;
  std::vector<int> Original;
  std::vector<std::vector<int>> Copies; ///< per original

  /// Scratch of the branch analysis, kept from cut to cut: a cut allocates
  /// only what it adds to the mesh.
  struct Scratch
  {
    std::vector<std::pair<std::uint64_t, int>> edges; ///< (edge, local triangle)
    std::vector<int> triangles;                       ///< of the hexahedron analysed
    std::vector<int> rootOf;                          ///< per triangle of `triangles`
    std::vector<int> size;                            ///< per root (branch or node group)
    std::vector<int> roots;                           ///< by size, ties by lowest index
    std::vector<int> around;                          ///< hexahedra around a node
    std::vector<int> nodeOfGroup;
    std::vector<int> triangleStamp; ///< per collision triangle: the node visit
    std::vector<int> firstHolder;   ///< ... and the first hexahedron around it
    int stamp = 0;
    UnionFind groups;
  };
  Scratch Work;
};

} // namespace thintissue

#endif
