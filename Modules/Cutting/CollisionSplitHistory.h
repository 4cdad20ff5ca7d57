// The split history of the collision triangles: the first stage of the
// lazy binding (issue 13; Documentation/Architecture.md, "Cutting", the
// lazy binding's plan).
//
// A cut rebinds every visual vertex of a split collision triangle's region
// by formula 5-2 (thesis 5.3.3), so that a cut costs the regions it splits,
// not its line. A lazy binding leaves a vertex far from the cut as it was:
// bound to a node of this history (a collision triangle index in one
// generation: the first piece of a split reuses the parent's index) with
// parameters in that node's triangle. Resolving it follows the splits made
// since: at each, the piece its point lies in, in the parent's plane
// (formula 5-1's frame), and that piece's parameters by formula 5-2 with
// the products the eager rebinding makes (SplitFormula.h), so that the
// resolved binding is the eager one bit for bit wherever the eager cut
// rebinds a vertex from its own parameters (an inner vertex of a region
// without a fold, off the cuts).
#ifndef CollisionSplitHistory_h
#define CollisionSplitHistory_h

#include "CollisionMeshCut.h"
#include "ThinTissueCuttingModule.h"

#include <array>
#include <cstddef>
#include <vector>

namespace thintissue
{

/// A triangle of a plane as its barycentric map: its first corner and the
/// inverse of its sides' matrix (SplitFormula.h's pieceContaining).
struct PlanePiece
{
  Vector2 origin;
  Eigen::Matrix2d inverse;
};

class THINTISSUECUTTING_EXPORT CollisionSplitHistory
{
public:
  /// A history of `triangleCount` triangles, none split (node t is
  /// triangle t).
  explicit CollisionSplitHistory(std::size_t triangleCount = 0);

  /// The node triangle index `triangle` holds now (triangles made since are
  /// added as their splits are recorded).
  int currentNode(int triangle) const { return Current[static_cast<std::size_t>(triangle)]; }
  /// The triangle index of a node.
  int triangleOf(int node) const { return Nodes[static_cast<std::size_t>(node)].triangle; }
  /// Whether the node has not been split (its triangle index holds it).
  bool isCurrent(int node) const { return Nodes[static_cast<std::size_t>(node)].split < 0; }
  std::size_t nodeCount() const { return Nodes.size(); }
  std::size_t splitCount() const { return Splits.size(); }

  /// Records one split, `restPositions` the collision rest positions (the
  /// parent's corners give its plane). Throws InvalidInputError, changing
  /// nothing, when the parent is not a triangle of the history or a piece
  /// index skips past the triangles known (pieces beyond the first are new
  /// triangles, made in order).
  void recordSplit(const CollisionTriangleSplit& split, const std::vector<Vector3>& restPositions);
  /// Records every split of a cut, in order (all checked first).
  void recordCut(const CollisionCutResult& cut, const std::vector<Vector3>& restPositions);

  struct Resolved
  {
    int node = -1;
    Vector3 parameters = Vector3::Zero();
  };
  /// Follows the splits of `node` for the point with barycentric
  /// `parameters` in it, down to the current node holding the point.
  Resolved resolve(int node, const Vector3& parameters) const;

private:
  static void check(const CollisionTriangleSplit& split,
    int known,
    const std::vector<Vector3>& restPositions);
  void record(const CollisionTriangleSplit& split, const std::vector<Vector3>& restPositions);
  struct Node
  {
    int triangle = -1;
    int split = -1; ///< index in Splits once split
  };
  struct Split
  {
    /// The parent's plane (formula 5-1's frame).
    std::array<Vector2, 3> frame;
    /// Its pieces: entries firstPiece to firstPiece + pieceCount - 1 of the
    /// per-piece arrays (one flat array each: a cut adds to them, it does
    /// not allocate per split once they have grown).
    int firstPiece = 0;
    int pieceCount = 0;
  };
  /// Per piece of a split: its corners in the parent's plane, the affine map
  /// of formula 5-2 (child parameters = map * p + offset, p a plane point)
  /// and its node.
  std::vector<PlanePiece> Pieces;
  std::vector<Eigen::Matrix<double, 3, 2>> Maps;
  std::vector<Vector3> Offsets;
  std::vector<int> ChildNodes;
  std::vector<Node> Nodes;
  std::vector<Split> Splits;
  std::vector<int> Current;
};

} // namespace thintissue

#endif
