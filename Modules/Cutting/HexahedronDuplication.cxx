#include "HexahedronDuplication.h"

#include "UnionFind.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace thintissue
{

namespace
{

/// Separating-axis test of a triangle against an axis-aligned box: the box
/// axes, the triangle's normal and the nine products of the two.
bool triangleMeetsBox(const Vector3& a, const Vector3& b, const Vector3& c, const BoundingBox& box)
{
  const Vector3 centre = box.center();
  const Vector3 half = 0.5 * box.sizes();
  const std::array<Vector3, 3> v = { a - centre, b - centre, c - centre };
  const std::array<Vector3, 3> edges = { v[1] - v[0], v[2] - v[1], v[0] - v[2] };
  auto separated = [&](const Vector3& axis)
  {
    const double p0 = axis.dot(v[0]), p1 = axis.dot(v[1]), p2 = axis.dot(v[2]);
    const double r = half.cwiseProduct(axis.cwiseAbs()).sum();
    return std::min({ p0, p1, p2 }) > r || std::max({ p0, p1, p2 }) < -r;
  };
  for (int i = 0; i < 3; ++i)
  {
    if (separated(Vector3::Unit(i)))
      return false;
  }
  if (separated(edges[0].cross(edges[1])))
    return false;
  for (int i = 0; i < 3; ++i)
  {
    for (const Vector3& e : edges)
    {
      if (separated(Vector3::Unit(i).cross(e)))
        return false;
    }
  }
  return true;
}

void insertSorted(std::vector<int>& list, int value)
{
  const auto at = std::lower_bound(list.begin(), list.end(), value);
  if (at == list.end() || *at != value)
  {
    list.insert(at, value);
  }
}

/// An undirected edge by its two corners.
std::uint64_t cornerPairKey(int a, int b)
{
  const auto low = static_cast<std::uint32_t>(std::min(a, b));
  const auto high = static_cast<std::uint32_t>(std::max(a, b));
  return (std::uint64_t{ low } << 32) | high;
}

void eraseValue(std::vector<int>& list, int value)
{
  list.erase(std::remove(list.begin(), list.end(), value), list.end());
}

} // namespace

HexahedralBranches::HexahedralBranches(const HexahedralMesh& mesh,
  const CuttableCollisionMesh& collision)
{
  const int hexCount = static_cast<int>(mesh.hexahedronCount());
  RestBoxes.resize(hexCount);
  HexTriangles.assign(hexCount, {});
  NodeHexes.assign(mesh.nodeCount(), {});
  Original.resize(hexCount);
  Copies.resize(hexCount);
  for (int h = 0; h < hexCount; ++h)
  {
    for (int node : mesh.hexahedra[h])
    {
      RestBoxes[h].extend(mesh.nodes[node]);
      NodeHexes[node].push_back(h);
    }
    Original[h] = h;
    Copies[h] = { h };
  }
  TriangleHexes.assign(collision.triangleCount(), {});
  for (int t = 0; t < static_cast<int>(collision.triangleCount()); ++t)
  {
    for (int h = 0; h < hexCount; ++h)
    {
      if (meets(collision, t, h))
      {
        HexTriangles[h].push_back(t); // t ascending: lists stay sorted
        TriangleHexes[t].push_back(h);
      }
    }
  }
}

bool HexahedralBranches::meets(const CuttableCollisionMesh& collision, int triangle, int h) const
{
  const Triangle& tri = collision.triangles()[triangle];
  const auto& x = collision.restPositions();
  const auto& r = collision.radii();
  const double grow = std::max({ r[tri[0]], r[tri[1]], r[tri[2]], 0.0 });
  BoundingBox box = RestBoxes[Original[h]];
  box.min().array() -= grow;
  box.max().array() += grow;
  BoundingBox triangleBox(x[tri[0]]);
  triangleBox.extend(x[tri[1]]).extend(x[tri[2]]);
  // A triangle inside the box meets it (most pieces of a cut in a coarse
  // hexahedron): no separating axis to look for.
  return box.contains(triangleBox) ||
         (box.intersects(triangleBox) && triangleMeetsBox(x[tri[0]], x[tri[1]], x[tri[2]], box));
}

int HexahedralBranches::copyHolding(int h, const std::vector<int>& triangles) const
{
  int holder = -1;
  for (int t : triangles)
  {
    const int copy = copyHolding(h, t);
    if (copy >= 0 && (holder < 0 || copy < holder))
      holder = copy;
  }
  return holder;
}

int HexahedralBranches::copyHolding(int h, int triangle) const
{
  // A triangle meets few hexahedra (those its grown box meets), an original
  // may have many copies after a shaver has passed: look among the first.
  // Copies are appended, so the first copy in Copies is the lowest index.
  const int original = Original[h];
  int holder = -1;
  for (int copy : TriangleHexes[triangle])
  {
    if (Original[copy] == original && (holder < 0 || copy < holder))
      holder = copy;
  }
  return holder;
}

void HexahedralBranches::assignPieces(const CuttableCollisionMesh& collision,
  const CollisionCutResult& cut,
  std::vector<int>& touched)
{
  TriangleHexes.resize(collision.triangleCount());
  for (const auto& split : cut.splits)
  {
    // The parent's index is the first piece's: take its hexahedra first.
    // Each of them is touched, also one that no piece meets (a piece is
    // grown by the largest radius of its own corners, often less than the
    // parent's): it lost the parent, and with it perhaps what joined its
    // other triangles into one branch.
    const std::vector<int> parentHexes = TriangleHexes[split.parent];
    touched.insert(touched.end(), parentHexes.begin(), parentHexes.end());
    for (int h : parentHexes)
    {
      eraseValue(HexTriangles[h], split.parent);
    }
    TriangleHexes[split.parent].clear();
    for (int piece : split.children)
    {
      for (int h : parentHexes)
      {
        if (meets(collision, piece, h))
        {
          insertSorted(HexTriangles[h], piece);
          TriangleHexes[piece].push_back(h);
        }
      }
    }
  }
}

void HexahedralBranches::splitBranches(const CuttableCollisionMesh& collision,
  int h,
  HexahedralMesh& mesh,
  HexahedronDuplicationResult& result)
{
  // Branches: the hexahedron's triangles joined through shared collision
  // edges. The collision adjacency's edges are its triangles' corner pairs,
  // so the triangles' edges sorted by their corners bring the triangles of
  // an edge side by side (no lookup per edge).
  Scratch& work = Work;
  work.triangles.assign(HexTriangles[h].begin(), HexTriangles[h].end());
  const int n = static_cast<int>(work.triangles.size());
  work.edges.clear();
  for (int i = 0; i < n; ++i)
  {
    const Triangle& tri = collision.triangles()[work.triangles[i]];
    for (int k = 0; k < 3; ++k)
      work.edges.emplace_back(cornerPairKey(tri[k], tri[(k + 1) % 3]), i);
  }
  std::sort(work.edges.begin(), work.edges.end());
  work.groups.reset(n);
  int roots = n;
  for (std::size_t j = 1; j < work.edges.size(); ++j)
  {
    if (work.edges[j].first == work.edges[j - 1].first)
      roots -= work.groups.unite(work.edges[j - 1].second, work.edges[j].second) ? 1 : 0;
  }
  // Most touched hexahedra keep one branch: nothing to copy, nothing made.
  if (roots < 2)
    return;
  // The largest branch stays (ties: the one with the lowest triangle, the
  // root of a set being its lowest index).
  work.rootOf.resize(n);
  work.size.assign(n, 0);
  for (int i = 0; i < n; ++i)
    ++work.size[work.rootOf[i] = work.groups.find(i)];
  work.roots.clear();
  for (int i = 0; i < n; ++i)
  {
    if (work.size[i] > 0)
      work.roots.push_back(i);
  }
  std::stable_sort(work.roots.begin(),
    work.roots.end(),
    [&work](int x, int y) { return work.size[x] > work.size[y]; });
  branchMembers(work.roots[0], HexTriangles[h]);
  for (std::size_t b = 1; b < work.roots.size(); ++b)
  {
    const int copy = static_cast<int>(mesh.hexahedra.size());
    mesh.hexahedra.push_back(mesh.hexahedra[h]);
    branchMembers(work.roots[b], HexTriangles.emplace_back());
    Original.push_back(Original[h]);
    Copies[Original[h]].push_back(copy);
    for (int t : HexTriangles[copy])
    {
      std::replace(TriangleHexes[t].begin(), TriangleHexes[t].end(), h, copy);
    }
    for (int node : mesh.hexahedra[copy])
    {
      NodeHexes[node].push_back(copy);
    }
    result.newHexahedra.push_back({ copy, h });
  }
}

// The triangles of the branch with this root (splitBranches' scratch), in
// ascending order.
void HexahedralBranches::branchMembers(int root, std::vector<int>& members)
{
  members.clear();
  members.reserve(static_cast<std::size_t>(Work.size[root]));
  for (std::size_t i = 0; i < Work.triangles.size(); ++i)
  {
    if (Work.rootOf[i] == root)
      members.push_back(Work.triangles[i]);
  }
}

void HexahedralBranches::regroupNode(int node,
  HexahedralMesh& mesh,
  HexahedronDuplicationResult& result)
{
  Scratch& work = Work;
  work.around.assign(NodeHexes[node].begin(), NodeHexes[node].end());
  const std::vector<int>& around = work.around;
  const int n = static_cast<int>(around.size());
  UnionFind& groups = work.groups;
  groups.reset(n);
  // Hexahedra that share a collision triangle join: each triangle remembers
  // the first hexahedron around the node that holds it (stamped per node,
  // so nothing is cleared between nodes).
  if (work.triangleStamp.size() < TriangleHexes.size())
  {
    work.triangleStamp.resize(TriangleHexes.size(), 0);
    work.firstHolder.resize(TriangleHexes.size(), -1);
  }
  if (++work.stamp == std::numeric_limits<int>::max())
  {
    std::fill(work.triangleStamp.begin(), work.triangleStamp.end(), 0);
    work.stamp = 1;
  }
  int firstHolding = -1;
  for (int i = 0; i < n; ++i)
  {
    if (HexTriangles[around[i]].empty())
      continue;
    firstHolding = firstHolding < 0 ? i : firstHolding;
    for (int t : HexTriangles[around[i]])
    {
      if (work.triangleStamp[t] == work.stamp)
        groups.unite(work.firstHolder[t], i);
      else
      {
        work.triangleStamp[t] = work.stamp;
        work.firstHolder[t] = i;
      }
    }
  }
  // Hexahedra without collision surface stay with the first group.
  for (int i = 0; i < n; ++i)
  {
    if (HexTriangles[around[i]].empty() && firstHolding >= 0)
      groups.unite(i, firstHolding);
  }
  work.size.assign(n, 0);
  for (int i = 0; i < n; ++i)
    ++work.size[groups.find(i)];
  const int keeper =
    static_cast<int>(std::max_element(work.size.begin(), work.size.end()) - work.size.begin());
  work.nodeOfGroup.assign(n, -1);
  for (int i = 0; i < n; ++i)
  {
    const int group = groups.find(i);
    if (group == keeper)
      continue;
    int& copy = work.nodeOfGroup[group];
    if (copy < 0)
    {
      copy = static_cast<int>(mesh.nodes.size());
      mesh.nodes.push_back(mesh.nodes[node]);
      if (!mesh.fixedNodes.empty())
        mesh.fixedNodes.push_back(mesh.fixedNodes[node]);
      NodeHexes.emplace_back();
      result.newNodes.push_back({ copy, node });
    }
    const int h = around[i];
    std::replace(mesh.hexahedra[h].begin(), mesh.hexahedra[h].end(), node, copy);
    eraseValue(NodeHexes[node], h);
    NodeHexes[copy].push_back(h);
    result.renodedHexahedra.push_back(h);
  }
}

HexahedronDuplicationResult HexahedralBranches::update(const CuttableCollisionMesh& collision,
  const CollisionCutResult& cut,
  HexahedralMesh& mesh)
{
  std::vector<int> touched;
  assignPieces(collision, cut, touched);
  for (int t : cut.changedTriangles)
  {
    touched.insert(touched.end(), TriangleHexes[t].begin(), TriangleHexes[t].end());
  }
  return duplicate(collision, std::move(touched), mesh);
}

HexahedronDuplicationResult HexahedralBranches::separateAll(const CuttableCollisionMesh& collision,
  HexahedralMesh& mesh)
{
  std::vector<int> all(mesh.hexahedronCount());
  std::iota(all.begin(), all.end(), 0);
  return duplicate(collision, std::move(all), mesh);
}

HexahedronDuplicationResult HexahedralBranches::duplicate(const CuttableCollisionMesh& collision,
  std::vector<int> touched,
  HexahedralMesh& mesh)
{
  HexahedronDuplicationResult result;
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  for (int h : touched)
  {
    splitBranches(collision, h, mesh, result);
  }
  std::vector<int> nodes;
  for (int h : touched)
  {
    nodes.insert(nodes.end(), mesh.hexahedra[h].begin(), mesh.hexahedra[h].end());
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  for (int node : nodes)
  {
    regroupNode(node, mesh, result);
  }
  // Copies made this time are reported as new, not as re-noded.
  const int firstCopy = result.newHexahedra.empty() ? static_cast<int>(mesh.hexahedra.size())
                                                    : result.newHexahedra.front()[0];
  auto& renoded = result.renodedHexahedra;
  renoded.erase(
    std::remove_if(renoded.begin(), renoded.end(), [firstCopy](int h) { return h >= firstCopy; }),
    renoded.end());
  std::sort(renoded.begin(), renoded.end());
  renoded.erase(std::unique(renoded.begin(), renoded.end()), renoded.end());
  result.touchedHexahedra = touched;
  return result;
}

} // namespace thintissue
