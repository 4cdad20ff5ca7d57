#include "HexahedronDuplication.h"

#include "UnionFind.h"

#include <algorithm>
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

bool sortedIntersect(const std::vector<int>& x, const std::vector<int>& y)
{
  auto i = x.begin();
  auto j = y.begin();
  while (i != x.end() && j != y.end())
  {
    if (*i == *j)
      return true;
    (*i < *j) ? ++i : ++j;
  }
  return false;
}

void insertSorted(std::vector<int>& list, int value)
{
  const auto at = std::lower_bound(list.begin(), list.end(), value);
  if (at == list.end() || *at != value)
  {
    list.insert(at, value);
  }
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
  return box.intersects(triangleBox) && triangleMeetsBox(x[tri[0]], x[tri[1]], x[tri[2]], box);
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
  const std::vector<int>& triangles = HexTriangles[h];
  const int n = static_cast<int>(triangles.size());
  UnionFind groups(n);
  int roots = n;
  for (int i = 0; i < n; ++i)
  {
    const Triangle& tri = collision.triangles()[triangles[i]];
    for (int k = 0; k < 3; ++k)
    {
      for (int other : collision.trianglesOfEdge(tri[k], tri[(k + 1) % 3]))
      {
        const auto at = std::lower_bound(triangles.begin(), triangles.end(), other);
        if (other >= 0 && at != triangles.end() && *at == other)
          roots -= groups.unite(i, static_cast<int>(at - triangles.begin())) ? 1 : 0;
      }
    }
  }
  // Most touched hexahedra keep one branch: nothing to copy, nothing made.
  if (roots < 2)
    return;
  std::vector<std::vector<int>> branches(n);
  for (int i = 0; i < n; ++i)
  {
    branches[groups.find(i)].push_back(triangles[i]);
  }
  branches.erase(
    std::remove_if(
      branches.begin(), branches.end(), [](const std::vector<int>& b) { return b.empty(); }),
    branches.end());
  // The largest branch stays (ties: the one with the lowest triangle).
  std::stable_sort(branches.begin(),
    branches.end(),
    [](const std::vector<int>& x, const std::vector<int>& y) { return x.size() > y.size(); });
  HexTriangles[h] = branches[0];
  for (std::size_t b = 1; b < branches.size(); ++b)
  {
    const int copy = static_cast<int>(mesh.hexahedra.size());
    mesh.hexahedra.push_back(mesh.hexahedra[h]);
    HexTriangles.push_back(branches[b]);
    Original.push_back(Original[h]);
    Copies[Original[h]].push_back(copy);
    for (int t : branches[b])
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

void HexahedralBranches::regroupNode(int node,
  HexahedralMesh& mesh,
  HexahedronDuplicationResult& result)
{
  const std::vector<int> around = NodeHexes[node];
  const int n = static_cast<int>(around.size());
  UnionFind groups(n);
  int firstHolding = -1;
  for (int i = 0; i < n; ++i)
  {
    if (HexTriangles[around[i]].empty())
      continue;
    firstHolding = firstHolding < 0 ? i : firstHolding;
    for (int j = i + 1; j < n; ++j)
    {
      if (sortedIntersect(HexTriangles[around[i]], HexTriangles[around[j]]))
        groups.unite(i, j);
    }
  }
  // Hexahedra without collision surface stay with the first group.
  for (int i = 0; i < n; ++i)
  {
    if (HexTriangles[around[i]].empty() && firstHolding >= 0)
      groups.unite(i, firstHolding);
  }
  std::vector<int> groupSize(n, 0);
  for (int i = 0; i < n; ++i)
    ++groupSize[groups.find(i)];
  const int keeper =
    static_cast<int>(std::max_element(groupSize.begin(), groupSize.end()) - groupSize.begin());
  std::vector<int> nodeOfGroup(n, -1);
  for (int i = 0; i < n; ++i)
  {
    const int group = groups.find(i);
    if (group == keeper)
      continue;
    if (nodeOfGroup[group] < 0)
    {
      nodeOfGroup[group] = static_cast<int>(mesh.nodes.size());
      mesh.nodes.push_back(mesh.nodes[node]);
      if (!mesh.fixedNodes.empty())
        mesh.fixedNodes.push_back(mesh.fixedNodes[node]);
      NodeHexes.emplace_back();
      result.newNodes.push_back({ nodeOfGroup[group], node });
    }
    const int h = around[i];
    std::replace(mesh.hexahedra[h].begin(), mesh.hexahedra[h].end(), node, nodeOfGroup[group]);
    eraseValue(NodeHexes[node], h);
    NodeHexes[nodeOfGroup[group]].push_back(h);
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
