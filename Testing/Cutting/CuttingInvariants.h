// Invariants of a cut tissue, checked after every cut by the cutting tests.
#ifndef CuttingInvariants_h
#define CuttingInvariants_h

#include "CollisionMeshCut.h"
#include "TissueCutter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

namespace thintissue
{
namespace cutting_test
{

/// Collision mesh: corners in range and distinct, no NaN, each directed
/// edge once (consistent orientation, at most two triangles an edge), every
/// vertex used and manifold (its triangles form one fan), no triangle of
/// zero area.
inline ::testing::AssertionResult collisionMeshIsValid(const CuttableCollisionMesh& mesh)
{
  const auto& x = mesh.restPositions();
  const auto& tris = mesh.triangles();
  const int n = static_cast<int>(x.size());
  const double scale = boundingBoxOf(x).diagonal().squaredNorm();
  std::set<std::pair<int, int>> directed;
  std::vector<int> used(n, 0);
  for (std::size_t t = 0; t < tris.size(); ++t)
  {
    const Triangle& tri = tris[t];
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] < 0 || tri[k] >= n || tri[k] == tri[(k + 1) % 3])
        return ::testing::AssertionFailure() << "triangle " << t << " has a bad corner";
      if (!directed.insert({ tri[k], tri[(k + 1) % 3] }).second)
        return ::testing::AssertionFailure()
               << "directed edge (" << tri[k] << ", " << tri[(k + 1) % 3] << ") twice";
      ++used[tri[k]];
    }
    const double area2 = (x[tri[1]] - x[tri[0]]).cross(x[tri[2]] - x[tri[0]]).norm();
    if (!(area2 > 1e-14 * scale))
      return ::testing::AssertionFailure() << "triangle " << t << " has no area";
  }
  for (int v = 0; v < n; ++v)
  {
    if (!x[v].allFinite() || !std::isfinite(mesh.radii()[v]))
      return ::testing::AssertionFailure() << "vertex " << v << " is not finite";
    if (used[v] == 0)
      return ::testing::AssertionFailure() << "vertex " << v << " is unused";
    // One fan: the triangles around v connected through edges at v.
    const auto& fan = mesh.trianglesOfVertex(v);
    std::vector<int> group(fan.size());
    std::iota(group.begin(), group.end(), 0);
    bool merged = true;
    while (merged)
    {
      merged = false;
      for (std::size_t i = 0; i < fan.size(); ++i)
        for (int k = 0; k < 3; ++k)
        {
          const int a = tris[fan[i]][k], b = tris[fan[i]][(k + 1) % 3];
          if (a != v && b != v)
            continue;
          for (int other : mesh.trianglesOfEdge(a, b))
          {
            const auto at = std::find(fan.begin(), fan.end(), other);
            if (other < 0 || at == fan.end())
              continue;
            const std::size_t j = static_cast<std::size_t>(at - fan.begin());
            if (group[j] != group[i])
            {
              const int low = std::min(group[i], group[j]);
              group[i] = group[j] = low;
              merged = true;
            }
          }
        }
    }
    if (std::set<int>(group.begin(), group.end()).size() != 1)
      return ::testing::AssertionFailure() << "vertex " << v << " is not manifold (several fans)";
  }
  return ::testing::AssertionSuccess();
}

/// Connected pieces of the collision mesh (through shared edges): the
/// piece of each triangle.
inline std::vector<int> collisionPieces(const CuttableCollisionMesh& mesh, int& count)
{
  const auto& tris = mesh.triangles();
  std::vector<int> piece(tris.size(), -1);
  count = 0;
  for (std::size_t seed = 0; seed < tris.size(); ++seed)
  {
    if (piece[seed] >= 0)
      continue;
    std::vector<int> stack{ static_cast<int>(seed) };
    piece[seed] = count;
    while (!stack.empty())
    {
      const int t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k)
        for (int other : mesh.trianglesOfEdge(tris[t][k], tris[t][(k + 1) % 3]))
          if (other >= 0 && piece[other] < 0)
          {
            piece[other] = count;
            stack.push_back(other);
          }
    }
    ++count;
  }
  return piece;
}

/// Cutter: the collision mesh is valid; every hexahedron (copies too) has
/// its original's rest geometry; pieces of the collision mesh that share no
/// triangle share no node; every collision vertex is embedded in a copy
/// holding one of its triangles when its hexahedron's copies hold any.
inline ::testing::AssertionResult cutterIsConsistent(const TissueCutter& cutter,
  const HexahedralMesh& original)
{
  const auto valid = collisionMeshIsValid(cutter.collision());
  if (!valid)
    return valid;
  const HexahedralMesh& mesh = cutter.simulation();
  const auto& branches = cutter.branches();
  for (std::size_t h = 0; h < mesh.hexahedronCount(); ++h)
  {
    const auto& source = original.hexahedra[branches.originalOf(static_cast<int>(h))];
    for (int a = 0; a < 8; ++a)
    {
      if ((mesh.nodes[mesh.hexahedra[h][a]] - original.nodes[source[a]]).norm() > 1e-12)
        return ::testing::AssertionFailure() << "hexahedron " << h << " lost its rest shape";
    }
  }
  int pieces = 0;
  const std::vector<int> pieceOf = collisionPieces(cutter.collision(), pieces);
  std::map<int, int> pieceOfNode;
  for (std::size_t h = 0; h < mesh.hexahedronCount(); ++h)
  {
    for (int t : branches.trianglesOf(static_cast<int>(h)))
    {
      for (int node : mesh.hexahedra[h])
      {
        const auto [it, inserted] = pieceOfNode.emplace(node, pieceOf[t]);
        if (!inserted && it->second != pieceOf[t])
          return ::testing::AssertionFailure()
                 << "node " << node << " is shared by collision pieces " << it->second << " and "
                 << pieceOf[t];
      }
    }
  }
  const auto& embedding = cutter.collisionEmbedding();
  if (embedding.pointCount() != cutter.collision().vertexCount())
    return ::testing::AssertionFailure() << "collision embedding has a wrong point count";
  for (std::size_t v = 0; v < embedding.pointCount(); ++v)
  {
    const int h = embedding.hexahedron(v);
    const auto& fan = cutter.collision().trianglesOfVertex(static_cast<int>(v));
    if (branches.copyHolding(h, fan) >= 0 && branches.copyHolding(h, fan) != h)
    {
      std::vector<int> sorted(fan);
      std::sort(sorted.begin(), sorted.end());
      const auto& held = branches.trianglesOf(h);
      std::vector<int> common;
      std::set_intersection(
        held.begin(), held.end(), sorted.begin(), sorted.end(), std::back_inserter(common));
      if (common.empty())
        return ::testing::AssertionFailure()
               << "collision vertex " << v << " is embedded in a copy without its triangles";
    }
  }
  return ::testing::AssertionSuccess();
}

} // namespace cutting_test
} // namespace thintissue

#endif
