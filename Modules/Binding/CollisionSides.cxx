#include "CollisionSides.h"

#include "ThinTissueError.h"
#include "UnionFind.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace thintissue
{

namespace
{

/// Two triangle sides (2 t + slot) facing each other across an edge.
using Wedge = std::array<int, 2>;

std::string meshName(const TriangleMesh& collision)
{
  return "collision mesh '" + collision.name + "'";
}

std::string edgeName(const std::array<int, 2>& edge)
{
  return "edge (" + std::to_string(edge[0]) + ", " + std::to_string(edge[1]) + ")";
}

/// +1 when triangle t runs a -> b, -1 when it runs b -> a.
int traversal(const Triangle& t, int a, int b)
{
  for (int k = 0; k < 3; ++k)
  {
    if (t[k] == a && t[(k + 1) % 3] == b)
    {
      return 1;
    }
  }
  return -1;
}

int sideId(int triangle, int side)
{
  return 2 * triangle + sideSlot(side);
}

/// The three wedges around a junction edge (a, b): its triangles in
/// counter-clockwise order around a -> b; the side of a triangle facing
/// the wedge that starts at it is its traversal sign, the side of the one
/// where the wedge ends the opposite sign (a triangle running a -> b has
/// its normal along (b - a) x (its direction away from the edge)).
std::array<Wedge, 3> junctionWedges(const TriangleMesh& collision,
  const std::array<int, 2>& edge,
  const int* triangles)
{
  const Vector3& a = collision.positions[edge[0]];
  const Vector3 along = (collision.positions[edge[1]] - a).normalized();
  std::array<std::pair<double, int>, 3> order;
  Vector3 first = Vector3::Zero();
  for (int i = 0; i < 3; ++i)
  {
    const Triangle& t = collision.triangles[triangles[i]];
    int apex = t[0];
    for (int c : t)
    {
      apex = c != edge[0] && c != edge[1] ? c : apex;
    }
    Vector3 away = collision.positions[apex] - a;
    away -= away.dot(along) * along;
    if (i == 0)
    {
      first = away.normalized();
    }
    double angle = std::atan2(away.dot(along.cross(first)), away.dot(first));
    order[i] = { angle < 0.0 ? angle + 2.0 * M_PI : angle, triangles[i] };
  }
  std::sort(order.begin(), order.end());
  std::array<Wedge, 3> wedges;
  for (int i = 0; i < 3; ++i)
  {
    const int start = order[i].second;
    const int end = order[(i + 1) % 3].second;
    const int startSide = traversal(collision.triangles[start], edge[0], edge[1]);
    const int endSide = -traversal(collision.triangles[end], edge[0], edge[1]);
    wedges[i] = { { sideId(start, startSide), sideId(end, endSide) } };
  }
  return wedges;
}

/// The wedges of every edge: a border edge's one (its triangle's two
/// sides: the rim), a manifold edge's two, a junction's three; an edge cut
/// along but not opened yet, one rim per triangle.
std::vector<std::vector<Wedge>> edgeWedges(const TriangleMesh& collision,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<char>& cutEdge)
{
  std::vector<std::vector<Wedge>> wedges(adjacency.edgeCount());
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e)
  {
    const auto& edge = adjacency.edge(static_cast<int>(e));
    const int* triangles = adjacency.edgeTrianglesBegin(static_cast<int>(e));
    const int count = adjacency.edgeTriangleCount(static_cast<int>(e));
    if (count == 1 || (cutEdge[e] && count <= 3))
    {
      for (int i = 0; i < count; ++i)
      {
        wedges[e].push_back({ { sideId(triangles[i], 1), sideId(triangles[i], -1) } });
      }
    }
    else if (count == 2)
    {
      const int t0 = triangles[0];
      const int t1 = triangles[1];
      if (traversal(collision.triangles[t0], edge[0], edge[1]) ==
          traversal(collision.triangles[t1], edge[0], edge[1]))
      {
        throw InvalidInputError(meshName(collision) + ": triangles " + std::to_string(t0) +
                                " and " + std::to_string(t1) +
                                " are oriented inconsistently across " + edgeName(edge) +
                                " (their normals must lie on one side)");
      }
      wedges[e] = { { { sideId(t0, 1), sideId(t1, 1) } }, { { sideId(t0, -1), sideId(t1, -1) } } };
    }
    else if (count == 3)
    {
      const std::array<Wedge, 3> around = junctionWedges(collision, edge, triangles);
      wedges[e].assign(around.begin(), around.end());
    }
    else
    {
      throw InvalidInputError(meshName(collision) + ": " + edgeName(edge) + " has " +
                              std::to_string(count) +
                              " triangles (at most three: a cleavage's body and its two leaves)");
    }
  }
  return wedges;
}

/// Every class of sides joined through inner wedges labelled: all positive
/// sides, all negative, or both (a cleft). A junction must have one wedge
/// of each.
std::vector<std::array<SurfaceHalf, 2>> sideHalves(const TriangleMesh& collision,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<std::vector<Wedge>>& wedges,
  const std::vector<char>& rimEdge)
{
  const std::size_t triangleCount = collision.triangleCount();
  UnionFind classes(2 * triangleCount);
  for (std::size_t e = 0; e < wedges.size(); ++e)
  {
    if (rimEdge[e])
    {
      continue; // the rim: between halves
    }
    int kinds = 0; // bit 0: ++, bit 1: --, bit 2: mixed
    for (const Wedge& w : wedges[e])
    {
      classes.unite(w[0], w[1]);
      kinds |= (w[0] % 2) != (w[1] % 2) ? 4 : (w[0] % 2 == 0 ? 1 : 2);
    }
    if (wedges[e].size() == 3 && kinds != 7)
    {
      throw InvalidInputError(meshName(collision) + ": the three triangles at " +
                              edgeName(adjacency.edge(static_cast<int>(e))) +
                              " are no cleavage's junction (a body and two leaves oriented "
                              "alike, the cleft between the leaves)");
    }
  }
  std::vector<int> signs(2 * triangleCount, 0); // bit 0: has +, bit 1: has -
  for (std::size_t s = 0; s < 2 * triangleCount; ++s)
  {
    signs[classes.find(static_cast<int>(s))] |= s % 2 == 0 ? 1 : 2;
  }
  std::vector<std::array<SurfaceHalf, 2>> halves(triangleCount);
  for (std::size_t t = 0; t < triangleCount; ++t)
  {
    for (int slot = 0; slot < 2; ++slot)
    {
      const int kind = signs[classes.find(static_cast<int>(2 * t) + slot)];
      halves[t][slot] = kind == 3 ? SurfaceHalf::Cleft
                                  : (kind == 1 ? SurfaceHalf::Positive : SurfaceHalf::Negative);
    }
  }
  return halves;
}

/// The side classes meeting at vertex v, joined through the wedges of its
/// edges (the rim's too): one on a border, two inside, three inside a
/// junction.
int sideClassesAt(int v,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<std::vector<Wedge>>& wedges,
  bool& touchesJunction)
{
  const int* begin = adjacency.vertexTrianglesBegin(v);
  const int* end = adjacency.vertexTrianglesEnd(v);
  const auto localSide = [&](int id)
  { return 2 * static_cast<int>(std::find(begin, end, id / 2) - begin) + id % 2; };
  UnionFind classes(2 * static_cast<std::size_t>(end - begin));
  touchesJunction = false;
  for (const int* t = begin; t != end; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int e = adjacency.triangleEdges(*t)[k];
      const auto& edge = adjacency.edge(e);
      if (edge[0] != v && edge[1] != v)
      {
        continue;
      }
      touchesJunction = touchesJunction || wedges[e].size() == 3;
      for (const Wedge& w : wedges[e])
      {
        classes.unite(localSide(w[0]), localSide(w[1]));
      }
    }
  }
  int count = 0;
  for (int s = 0; s < 2 * static_cast<int>(end - begin); ++s)
  {
    count += classes.find(s) == s ? 1 : 0;
  }
  return count;
}

/// Fans of triangles around vertex v: joined through every triangle of
/// each edge at v.
int fansAt(int v, const TriangleMeshAdjacency& adjacency)
{
  const int* begin = adjacency.vertexTrianglesBegin(v);
  const int* end = adjacency.vertexTrianglesEnd(v);
  UnionFind fans(static_cast<std::size_t>(end - begin));
  for (const int* t = begin; t != end; ++t)
  {
    for (int e : adjacency.triangleEdges(*t))
    {
      const auto& edge = adjacency.edge(e);
      if (edge[0] != v && edge[1] != v)
      {
        continue;
      }
      for (const int* other = adjacency.edgeTrianglesBegin(e);
           other != adjacency.edgeTrianglesEnd(e);
           ++other)
      {
        fans.unite(
          static_cast<int>(t - begin), static_cast<int>(std::find(begin, end, *other) - begin));
      }
    }
  }
  int count = 0;
  for (int i = 0; i < static_cast<int>(end - begin); ++i)
  {
    count += fans.find(i) == i ? 1 : 0;
  }
  return count;
}

[[noreturn]] void throwTouchingFans(const TriangleMesh& collision,
  std::size_t v,
  int classes,
  int expected)
{
  throw InvalidInputError(meshName(collision) + ": vertex " + std::to_string(v) + " joins " +
                          std::to_string(classes) + " separate sheets of sides (" +
                          std::to_string(expected) +
                          " expected: its triangles form fans that touch at it only)");
}

} // namespace

bool CollisionSides::hasJunctions() const
{
  return std::find(junctionVertex.begin(), junctionVertex.end(), 1) != junctionVertex.end();
}

CollisionSides analyseCollisionSides(const TriangleMesh& collision)
{
  return analyseCollisionSides(collision, TriangleMeshAdjacency(collision));
}

CollisionSides analyseCollisionSides(const TriangleMesh& collision,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<std::array<int, 2>>& cutEdges)
{
  // A cut edge not opened yet is a rim for every triangle on it.
  std::vector<char> rimEdge(adjacency.edgeCount(), 0);
  for (const auto& edge : cutEdges)
  {
    const int e = adjacency.findEdge(edge[0], edge[1]);
    if (e < 0)
    {
      throw InvalidInputError(meshName(collision) + ": cut " + edgeName(edge) + " is no edge");
    }
    rimEdge[e] = 1;
  }
  const std::vector<std::vector<Wedge>> wedges = edgeWedges(collision, adjacency, rimEdge);
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e)
  {
    rimEdge[e] = rimEdge[e] || adjacency.isBorderEdge(static_cast<int>(e));
  }
  CollisionSides sides;
  sides.halves = sideHalves(collision, adjacency, wedges, rimEdge);
  sides.junctionVertex.assign(collision.vertexCount(), 0);
  sides.borderVertex.assign(collision.vertexCount(), 0);
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e)
  {
    if (rimEdge[e])
    {
      for (int v : adjacency.edge(static_cast<int>(e)))
      {
        sides.borderVertex[v] = 1;
      }
    }
  }
  for (std::size_t v = 0; v < collision.vertexCount(); ++v)
  {
    const auto vertex = static_cast<int>(v);
    if (adjacency.vertexTriangleCount(vertex) == 0)
    {
      continue;
    }
    bool touchesJunction = false;
    const int classes = sideClassesAt(vertex, adjacency, wedges, touchesJunction);
    sides.junctionVertex[v] = classes == 3 ? 1 : 0;
    if (sides.borderVertex[v])
    {
      // A rim joins the two sides of each sheet it borders, so a junction
      // vertex on a rim of only some of its sheets (a cut through the body
      // up to the junction) keeps two classes: one fan is what counts.
      const int fans = fansAt(vertex, adjacency);
      if (fans != 1)
      {
        throwTouchingFans(collision, v, fans, 1);
      }
      continue;
    }
    const int expected = touchesJunction ? 3 : 2;
    if (classes != expected)
    {
      throwTouchingFans(collision, v, classes, expected);
    }
  }
  return sides;
}

} // namespace thintissue
