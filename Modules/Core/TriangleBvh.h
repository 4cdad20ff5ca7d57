// Bounding-volume hierarchy over a triangle mesh whose vertices may carry
// radii (Spillmann's "reduced triangles with radii", thesis 2.4 and 5.1).
//
// A binary tree of axis-aligned boxes, built top-down by a median split of
// the triangle centroids along the longest axis of their bounds, stored as a
// flat array in depth-first order (left child = node + 1). Each triangle's box
// is the box of its three vertices inflated by the largest radius of those
// vertices plus the contact distance given to `build`, so a box overlap is a
// conservative test for "the thick triangles may be within contact distance".
// When two hierarchies built with margins m1 and m2 are queried against each
// other, pairs closer than m1 + m2 (beyond the radii) are reported.
//
// Deformable objects keep the topology and call `refit` every step: a single
// bottom-up pass over the node array, linear in the mesh size, no allocation.
// Leaves also keep each triangle's own box, so queries report exactly the
// triangles (pairs) whose inflated boxes overlap, not whole leaves.
// Queries are iterative (fixed-size stacks, no allocation) and call a
// user-supplied callback for each candidate; the narrow phase
// (ProximityQueries.h) decides the actual contacts.
#ifndef TriangleBvh_h
#define TriangleBvh_h

#include "ThinTissueCoreModule.h"
#include "TriangleMesh.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace thintissue
{

class THINTISSUECORE_EXPORT TriangleBvh
{
public:
  /// Node of the flat tree. A leaf has `triangleCount > 0` and owns
  /// `leafTriangles()[firstTriangle, firstTriangle + triangleCount)`; an
  /// internal node has `triangleCount == 0`, its left child at index + 1 and
  /// its right child at `rightChild`.
  struct Node
  {
    BoundingBox box;
    int firstTriangle = 0;
    int triangleCount = 0;
    int rightChild = -1;
    bool isLeaf() const { return triangleCount > 0; }
  };

  /// Largest number of triangles in a leaf.
  static constexpr int MaximumLeafSize = 4;

  /// Builds the tree. `radii` is empty (all radii zero) or one per vertex;
  /// `contactDistance` >= 0 inflates every triangle box in addition to the
  /// radii. Triangles must index `positions`. Replaces any previous tree.
  void build(const std::vector<Vector3>& positions,
    const std::vector<Triangle>& triangles,
    const std::vector<double>& radii,
    double contactDistance);

  /// Recomputes every box for new vertex positions and radii (same vertex
  /// count and triangles as in `build`; `radii` empty means zero). Linear in
  /// the number of triangles, no allocation.
  void refit(const std::vector<Vector3>& positions, const std::vector<double>& radii);

  std::size_t nodeCount() const { return this->Nodes.size(); }
  std::size_t triangleCount() const { return this->Triangles.size(); }
  bool empty() const { return this->Nodes.empty(); }
  double contactDistance() const { return this->ContactDistance; }
  const std::vector<Node>& nodes() const { return this->Nodes; }
  /// Triangle indices in leaf order (see Node); `leafTriangleBoxes()[i]` is
  /// the inflated box of triangle `leafTriangles()[i]`.
  const std::vector<int>& leafTriangles() const { return this->Order; }
  const std::vector<BoundingBox>& leafTriangleBoxes() const { return this->TriangleBoxes; }
  /// Bit k set: triangle t is the lowest-indexed triangle of its edge
  /// (t[k], t[k + 1 mod 3]). An edge shared by several triangles has one
  /// owner, so a pair query that tests only owned edges meets every edge
  /// pair once: the owners' boxes contain the edges' boxes, so they overlap
  /// whenever any two triangles of the edges do.
  std::uint8_t ownedEdges(int t) const { return this->OwnedEdges[t]; }
  /// Box of the whole mesh (empty box for an empty mesh).
  BoundingBox bounds() const { return this->Nodes.empty() ? BoundingBox() : this->Nodes[0].box; }
  /// Inflated box of one triangle, computed from the given data (same rule
  /// as the tree uses).
  static BoundingBox triangleBox(const std::vector<Vector3>& positions,
    const Triangle& triangle,
    const std::vector<double>& radii,
    double contactDistance);

  /// Calls `callback(int triangle)` for every triangle whose inflated box
  /// overlaps `box` (touching counts).
  template <typename Callback>
  void forEachOverlap(const BoundingBox& box, Callback&& callback) const;

  /// Calls `callback(int triangleOfThis, int triangleOfOther)` for every pair
  /// whose inflated boxes overlap, by simultaneous descent of both trees.
  /// Passing `*this` as `other` reports ordered pairs (a, b) and (b, a) and
  /// (a, a); use `forEachSelfOverlappingPair` for self-collision.
  template <typename Callback>
  void forEachOverlappingPair(const TriangleBvh& other, Callback&& callback) const;

  /// Calls `callback(int a, int b)` once for every unordered pair of distinct
  /// triangles (a != b) of this mesh whose inflated boxes overlap. Adjacent
  /// triangles are included; filtering them is the caller's choice.
  template <typename Callback>
  void forEachSelfOverlappingPair(Callback&& callback) const;

private:
  // Depth of a median-split tree is at most ceil(log2(triangles)) + 1 <= 33
  // for int indices; the stacks below have room for that with a margin.
  static constexpr int StackSize = 96;

  int buildRange(int begin, int end, std::vector<Vector3>& centroids);
  bool descendFirst(int nodeA, const TriangleBvh& other, int nodeB) const;

  std::vector<Node> Nodes;
  std::vector<int> Order;
  std::vector<BoundingBox> TriangleBoxes; // parallel to Order
  std::vector<Triangle> Triangles;
  std::vector<std::uint8_t> OwnedEdges; // by triangle index
  double ContactDistance = 0.0;
};

//------------------------------------------------------------------------------
template <typename Callback>
void TriangleBvh::forEachOverlap(const BoundingBox& box, Callback&& callback) const
{
  if (this->Nodes.empty() || box.isEmpty())
  {
    return;
  }
  int stack[StackSize];
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const int index = stack[--top];
    const Node& node = this->Nodes[index];
    if (!node.box.intersects(box))
    {
      continue;
    }
    if (node.isLeaf())
    {
      for (int i = node.firstTriangle; i < node.firstTriangle + node.triangleCount; ++i)
      {
        if (this->TriangleBoxes[i].intersects(box))
        {
          callback(this->Order[i]);
        }
      }
      continue;
    }
    stack[top++] = node.rightChild;
    stack[top++] = index + 1;
  }
}

//------------------------------------------------------------------------------
template <typename Callback>
void TriangleBvh::forEachOverlappingPair(const TriangleBvh& other, Callback&& callback) const
{
  if (this->Nodes.empty() || other.Nodes.empty())
  {
    return;
  }
  std::pair<int, int> stack[2 * StackSize];
  int top = 0;
  stack[top++] = { 0, 0 };
  while (top > 0)
  {
    const auto [a, b] = stack[--top];
    const Node& nodeA = this->Nodes[a];
    const Node& nodeB = other.Nodes[b];
    if (!nodeA.box.intersects(nodeB.box))
    {
      continue;
    }
    if (nodeA.isLeaf() && nodeB.isLeaf())
    {
      for (int i = nodeA.firstTriangle; i < nodeA.firstTriangle + nodeA.triangleCount; ++i)
      {
        const BoundingBox& boxA = this->TriangleBoxes[i];
        if (!boxA.intersects(nodeB.box))
        {
          continue;
        }
        for (int j = nodeB.firstTriangle; j < nodeB.firstTriangle + nodeB.triangleCount; ++j)
        {
          if (boxA.intersects(other.TriangleBoxes[j]))
          {
            callback(this->Order[i], other.Order[j]);
          }
        }
      }
      continue;
    }
    if (this->descendFirst(a, other, b))
    {
      stack[top++] = { nodeA.rightChild, b };
      stack[top++] = { a + 1, b };
    }
    else
    {
      stack[top++] = { a, nodeB.rightChild };
      stack[top++] = { a, b + 1 };
    }
  }
}

//------------------------------------------------------------------------------
template <typename Callback>
void TriangleBvh::forEachSelfOverlappingPair(Callback&& callback) const
{
  if (this->Nodes.empty())
  {
    return;
  }
  std::pair<int, int> stack[3 * StackSize];
  int top = 0;
  stack[top++] = { 0, 0 };
  while (top > 0)
  {
    const auto [a, b] = stack[--top];
    const Node& nodeA = this->Nodes[a];
    const Node& nodeB = this->Nodes[b];
    if (a == b)
    {
      if (nodeA.isLeaf())
      {
        const int end = nodeA.firstTriangle + nodeA.triangleCount;
        for (int i = nodeA.firstTriangle; i < end; ++i)
        {
          for (int j = i + 1; j < end; ++j)
          {
            if (this->TriangleBoxes[i].intersects(this->TriangleBoxes[j]))
            {
              const int ti = this->Order[i];
              const int tj = this->Order[j];
              callback(ti < tj ? ti : tj, ti < tj ? tj : ti);
            }
          }
        }
        continue;
      }
      stack[top++] = { a + 1, nodeA.rightChild };
      stack[top++] = { nodeA.rightChild, nodeA.rightChild };
      stack[top++] = { a + 1, a + 1 };
      continue;
    }
    if (!nodeA.box.intersects(nodeB.box))
    {
      continue;
    }
    if (nodeA.isLeaf() && nodeB.isLeaf())
    {
      for (int i = nodeA.firstTriangle; i < nodeA.firstTriangle + nodeA.triangleCount; ++i)
      {
        for (int j = nodeB.firstTriangle; j < nodeB.firstTriangle + nodeB.triangleCount; ++j)
        {
          if (this->TriangleBoxes[i].intersects(this->TriangleBoxes[j]))
          {
            const int ti = this->Order[i];
            const int tj = this->Order[j];
            callback(ti < tj ? ti : tj, ti < tj ? tj : ti);
          }
        }
      }
      continue;
    }
    if (this->descendFirst(a, *this, b))
    {
      stack[top++] = { nodeA.rightChild, b };
      stack[top++] = { a + 1, b };
    }
    else
    {
      stack[top++] = { a, nodeB.rightChild };
      stack[top++] = { a, b + 1 };
    }
  }
}

} // namespace thintissue

#endif
