// Invariants of a cut tissue, checked after every cut by the cutting tests.
#ifndef CuttingInvariants_h
#define CuttingInvariants_h

#include "CollisionMeshCut.h"
#include "MeshValidation.h"
#include "TissueCutter.h"
#include "VisualMeshCut.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

namespace thintissue
{
namespace cutting_test
{

/// Collision mesh: corners in range and distinct, no NaN, every vertex
/// used, no triangle of zero area; a collision mid-surface still
/// (analyseCollisionSides, edges cut along but not opened counted as rims:
/// consistent orientation, at most three triangles an edge and those a
/// cleavage's junction, every vertex one fan, or a junction's three sheets)
/// whose sides face the halves the cut kept for them (pieces inherit their
/// parent's).
inline ::testing::AssertionResult collisionMeshIsValid(const CuttableCollisionMesh& mesh)
{
  const auto& x = mesh.restPositions();
  const auto& tris = mesh.triangles();
  const int n = static_cast<int>(x.size());
  const double scale = boundingBoxOf(x).diagonal().squaredNorm();
  std::vector<int> used(n, 0);
  for (std::size_t t = 0; t < tris.size(); ++t)
  {
    const Triangle& tri = tris[t];
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] < 0 || tri[k] >= n || tri[k] == tri[(k + 1) % 3])
        return ::testing::AssertionFailure() << "triangle " << t << " has a bad corner";
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
  }
  TriangleMesh surface;
  surface.name = mesh.name();
  surface.positions = x;
  surface.triangles = tris;
  try
  {
    // A leaf cut off its junction faces the cleft still, though the
    // analysis of what is left sees a plain sheet there.
    const CollisionSides sides =
      analyseCollisionSides(surface, TriangleMeshAdjacency(surface), mesh.closedCutEdges());
    for (std::size_t t = 0; t < tris.size(); ++t)
      for (int slot = 0; slot < 2; ++slot)
      {
        const SurfaceHalf kept = mesh.halves()[t][slot];
        const SurfaceHalf plain = slot == 0 ? SurfaceHalf::Positive : SurfaceHalf::Negative;
        if (sides.halves[t][slot] != kept &&
            !(kept == SurfaceHalf::Cleft && sides.halves[t][slot] == plain))
          return ::testing::AssertionFailure()
                 << "triangle " << t << " faces other halves than the cut kept for it: slot "
                 << slot << " kept " << int(kept) << " analysed " << int(sides.halves[t][slot])
                 << " corners " << tris[t][0] << " " << tris[t][1] << " " << tris[t][2];
      }
  }
  catch (const InvalidInputError& e)
  {
    return ::testing::AssertionFailure() << e.what();
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

/// The visual vertex bound to a collision edge that lies farthest beside it
/// (across the surface, in the rest configuration).
struct EdgeBindingOffset
{
  double distance = 0.0;
  int vertex = -1;
  std::array<int, 2> edge{ -1, -1 };
};

inline EdgeBindingOffset largestEdgeBindingOffset(const CuttableVisualMesh& visual,
  const CuttableCollisionMesh& collision)
{
  EdgeBindingOffset largest;
  const TriangleMesh& mesh = visual.mesh();
  const auto& edges = visual.collisionEdges();
  const auto& rest = collision.restPositions();
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
  {
    const VisualVertexBinding b = visual.binding(static_cast<int>(v));
    if (b.kind != BindingKind::CollisionEdge)
      continue;
    const auto& e = edges[b.element];
    // From the nearest point of the edge, not the point of its parameter:
    // a cut that splits a detouring path re-parameterises it.
    const Vector3 along = rest[e[1]] - rest[e[0]];
    const double at = std::clamp(
      (mesh.positions[v] - rest[e[0]]).dot(along) / std::max(along.squaredNorm(), 1e-300),
      0.0,
      1.0);
    const Vector3 onEdge = rest[e[0]] + at * along;
    const int t = collision.trianglesOfEdge(e[0], e[1])[0];
    const Triangle& tri = collision.triangles()[t];
    const Vector3 normal =
      (rest[tri[1]] - rest[tri[0]]).cross(rest[tri[2]] - rest[tri[0]]).normalized();
    Vector3 offset = mesh.positions[v] - onEdge;
    offset -= offset.dot(normal) * normal;
    if (offset.norm() > largest.distance)
      largest = EdgeBindingOffset{ offset.norm(), static_cast<int>(v), { e[0], e[1] } };
  }
  return largest;
}

/// What is open or pinched in a visual mesh that is not a closed manifold:
/// the validation report, the first edges with other than two triangles,
/// the triangles around the first pinched vertex and the first surface
/// sliver, each with the bindings of its vertices.
inline ::testing::AssertionResult openVisualMeshFailure(const CuttableVisualMesh& visual,
  const CuttableCollisionMesh& collision,
  const MeshValidationReport& report)
{
  const TriangleMesh& mesh = visual.mesh();
  auto failure = ::testing::AssertionFailure() << "visual mesh is not a closed manifold:\n"
                                               << report.toString();
  std::map<std::pair<int, int>, std::vector<int>> edgeTriangles;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k)
    {
      const int a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      edgeTriangles[{ std::min(a, b), std::max(a, b) }].push_back(static_cast<int>(t));
    }
  int shown = 0;
  auto describe = [&](int v)
  {
    const VisualVertexBinding b = visual.binding(static_cast<int>(v));
    std::ostringstream text;
    text << v << "[kind " << int(b.kind) << " element " << b.element;
    if (b.kind == BindingKind::CollisionEdge)
      text << " (" << visual.collisionEdges()[b.element][0] << " "
           << visual.collisionEdges()[b.element][1] << ")";
    text << " side " << b.side << " t " << b.parameters[1] << "]";
    return text.str();
  };
  for (const auto& [edge, triangles] : edgeTriangles)
  {
    if (triangles.size() == 2 || shown++ > 8)
      continue;
    failure << "\nedge " << describe(edge.first) << "-" << describe(edge.second) << ":";
    for (int t : triangles)
      failure << " triangle " << t << " (" << mesh.triangles[t][0] << " " << mesh.triangles[t][1]
              << " " << mesh.triangles[t][2] << ", material " << int(visual.triangleMaterials()[t])
              << ", region " << visual.triangleRegions()[t] << " = ("
              << collision.triangles()[visual.triangleRegions()[t]][0] << " "
              << collision.triangles()[visual.triangleRegions()[t]][1] << " "
              << collision.triangles()[visual.triangleRegions()[t]][2] << "), side "
              << int(visual.triangleSides()[t]) << ")";
  }
  if (report.nonManifoldVertices.count > 0)
  {
    // The triangles around the first pinched vertex.
    const std::string& where = report.nonManifoldVertices.firstLocation;
    const int v = std::atoi(where.substr(where.find_last_of(' ') + 1).c_str());
    failure << "\npinched vertex " << describe(v) << ":";
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
      for (int w : mesh.triangles[t])
        if (w == v)
          failure << "\n  triangle " << t << " (" << describe(mesh.triangles[t][0]) << " "
                  << describe(mesh.triangles[t][1]) << " " << describe(mesh.triangles[t][2])
                  << ", material " << int(visual.triangleMaterials()[t]) << ", region "
                  << visual.triangleRegions()[t] << ", side " << int(visual.triangleSides()[t])
                  << ")";
  }
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    if (mesh.triangleArea(t) > 0.0 || visual.triangleMaterials()[t] != VisualMaterial::Surface)
      continue;
    failure << "\nzero-area triangle " << t << " (material " << int(visual.triangleMaterials()[t])
            << ", region " << visual.triangleRegions()[t] << ", side "
            << int(visual.triangleSides()[t]) << "):";
    for (int v : mesh.triangles[t])
    {
      const VisualVertexBinding b = visual.binding(static_cast<int>(v));
      failure << " " << v << " [kind " << int(b.kind) << " element " << b.element << " side "
              << b.side << " t " << b.parameters.transpose() << " at "
              << mesh.positions[v].transpose() << "]";
    }
    break;
  }
  return failure;
}

/// Visual mesh after cuts (5.3.2 - 5.3.4): closed, manifold, consistently
/// oriented, every vertex used, no triangle of zero area but slivers of the
/// cut surface; every vertex bound to a live collision
/// vertex, edge or triangle with parameters in [0, 1] summing to 1; every
/// surface triangle's corners bound inside its region's collision triangle,
/// every cut-surface triangle's corners on its collision edge or its ends;
/// as many visual pieces as collision pieces.
inline ::testing::AssertionResult visualMeshIsValid(const CuttableVisualMesh& visual,
  const CuttableCollisionMesh& collision,
  double rimOffset = 0.0)
{
  const TriangleMesh& mesh = visual.mesh();
  const MeshValidationReport report = validateTriangleMesh(mesh, 0.0);
  // The cut surface may hold slivers of no area where both sides' paths
  // run down the same rim wall (the thesis accepts ill-shaped cut-surface
  // triangles); the tissue's own surface may not, and no triangle may
  // repeat a vertex.
  std::size_t surfaceSlivers = 0;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const Triangle& tri = mesh.triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      return ::testing::AssertionFailure() << "visual triangle " << t << " repeats a vertex";
    if (mesh.triangleArea(t) <= 0.0 && visual.triangleMaterials()[t] == VisualMaterial::Surface)
      ++surfaceSlivers;
  }
  const bool closed = report.nonManifoldEdges.count == 0 && report.nonManifoldVertices.count == 0 &&
                      report.borderEdges.count == 0 &&
                      report.inconsistentlyOrientedEdges.count == 0 &&
                      report.duplicateTriangles.count == 0 && surfaceSlivers == 0;
  if (!closed || report.unreferencedVertices.count > 0)
    return openVisualMeshFailure(visual, collision, report);
  const auto& edges = visual.collisionEdges();
  const CollisionSplitHistory& history = visual.splitHistory();
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
  {
    const VisualVertexBinding b = visual.binding(static_cast<int>(v));
    // A binding inside a collision triangle knows its node in the split
    // history: its triangle's current one, or one split since (left to the
    // history by the lazy binding) that resolves to a current node.
    const int node = visual.bindingNode(static_cast<int>(v));
    const bool triangleBound = b.kind == BindingKind::CollisionTriangle;
    const auto resolvesToCurrent = [&]
    {
      const auto resolved = history.resolve(node, Vector3::Constant(1.0 / 3.0));
      return history.isCurrent(resolved.node) &&
             (!history.isCurrent(node) || history.triangleOf(node) == b.element);
    };
    if (triangleBound ? node < 0 || !resolvesToCurrent() : node != -1)
      return ::testing::AssertionFailure()
             << "visual vertex " << v << " (kind " << static_cast<int>(b.kind) << ", element "
             << b.element << ") has split history node " << node;
    bool alive = false;
    if (b.kind == BindingKind::CollisionVertex)
      alive = b.element >= 0 && b.element < static_cast<int>(collision.vertexCount()) &&
              !collision.trianglesOfVertex(b.element).empty();
    else if (b.kind == BindingKind::CollisionEdge)
      alive = b.element >= 0 && b.element < static_cast<int>(edges.size()) &&
              collision.trianglesOfEdge(edges[b.element][0], edges[b.element][1])[0] >= 0;
    else
      alive = b.element >= 0 && b.element < static_cast<int>(collision.triangleCount());
    if (!alive)
    {
      auto failure = ::testing::AssertionFailure()
                     << "visual vertex " << v << " is bound to a dead element " << b.element
                     << " (kind " << static_cast<int>(b.kind) << ")";
      if (b.kind == BindingKind::CollisionEdge)
        failure << " = (" << edges[b.element][0] << ", " << edges[b.element][1] << ")";
      for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (int w : mesh.triangles[t])
          if (w == static_cast<int>(v))
          {
            const Triangle& r = collision.triangles()[visual.triangleRegions()[t]];
            failure << "; in triangle " << t << " of region " << visual.triangleRegions()[t] << " ("
                    << r[0] << " " << r[1] << " " << r[2] << ") side "
                    << int(visual.triangleSides()[t]) << " material "
                    << int(visual.triangleMaterials()[t]);
          }
      return failure;
    }
    if (b.parameters.minCoeff() < -1e-9 || b.parameters.maxCoeff() > 1.0 + 1e-9 ||
        std::abs(b.parameters.sum() - 1.0) > 1e-9)
      return ::testing::AssertionFailure()
             << "visual vertex " << v << " has parameters " << b.parameters.transpose();
  }
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const int region = visual.triangleRegions()[t];
    if (region < 0 || region >= static_cast<int>(collision.triangleCount()))
      return ::testing::AssertionFailure() << "visual triangle " << t << " has no region";
    for (int v : mesh.triangles[t])
    {
      try
      {
        visual.parametersIn(v, region, collision.triangles()[region]);
      }
      catch (const Error& e)
      {
        return ::testing::AssertionFailure() << "visual triangle " << t << " (side "
                                             << int(visual.triangleSides()[t]) << "): " << e.what();
      }
    }
  }
  // The visual cut lies on the collision cut: a visual vertex bound to a
  // collision edge is beside it (across the surface, within twice the
  // longest visual edge: the paths join visual vertices paired with the
  // collision vertices, not exactly above them, and on coarse collision
  // meshes bend away from the straight edge), or within what the
  // preparation left on the rim of the uncut tissue (`rimOffset`).
  double longest = 0.0;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, (mesh.positions[t[k]] - mesh.positions[t[(k + 1) % 3]]).norm());
  const EdgeBindingOffset offset = largestEdgeBindingOffset(visual, collision);
  if (offset.distance > std::max(2.0 * longest, rimOffset))
    return ::testing::AssertionFailure()
           << "visual vertex " << offset.vertex << " bound to collision edge (" << offset.edge[0]
           << ", " << offset.edge[1] << ") lies " << offset.distance
           << " beside it (longest visual edge " << longest << ", rim offset of the uncut tissue "
           << rimOffset << ")";
  int collisionPieceCount = 0;
  collisionPieces(collision, collisionPieceCount);
  if (static_cast<int>(report.connectedComponents) != collisionPieceCount)
    return ::testing::AssertionFailure() << report.connectedComponents << " visual pieces for "
                                         << collisionPieceCount << " collision pieces";
  return ::testing::AssertionSuccess();
}

/// Two visual meshes cut alike: positions, triangles, texture coordinates
/// and bindings equal bit for bit (the first difference named).
inline ::testing::AssertionResult sameVisualMesh(const CuttableVisualMesh& a,
  const CuttableVisualMesh& b)
{
  const TriangleMesh& x = a.mesh();
  const TriangleMesh& y = b.mesh();
  if (x.positions != y.positions)
    return ::testing::AssertionFailure()
           << "positions differ (" << x.vertexCount() << " and " << y.vertexCount() << " vertices)";
  if (x.triangles != y.triangles)
  {
    std::size_t t = 0;
    while (t < x.triangleCount() && t < y.triangleCount() && x.triangles[t] == y.triangles[t])
      ++t;
    return ::testing::AssertionFailure()
           << "triangles differ from triangle " << t << " (" << x.triangleCount() << " and "
           << y.triangleCount() << " triangles)";
  }
  if (x.textureCoordinates != y.textureCoordinates || x.textureCorners != y.textureCorners)
    return ::testing::AssertionFailure() << "texture coordinates differ";
  if (a.triangleRegions() != b.triangleRegions() || a.triangleSides() != b.triangleSides())
    return ::testing::AssertionFailure() << "the triangles' regions differ";
  if (a.mesh().vertexCount() != b.mesh().vertexCount())
    return ::testing::AssertionFailure() << "binding counts differ";
  for (std::size_t v = 0; v < a.mesh().vertexCount(); ++v)
  {
    const VisualVertexBinding p = a.binding(static_cast<int>(v));
    const VisualVertexBinding q = b.binding(static_cast<int>(v));
    if (p.kind != q.kind || p.element != q.element || p.side != q.side ||
        p.parameters != q.parameters)
      return ::testing::AssertionFailure() << "binding of visual vertex " << v << " differs";
  }
  return ::testing::AssertionSuccess();
}

/// Visual mesh of a cutter (5.3.5): valid (visualMeshIsValid), embedded
/// point for point, and every visual vertex in a hexahedron whose nodes
/// belong to the collision piece of its own collision triangle (a visual
/// piece never hangs on the nodes of another piece).
inline ::testing::AssertionResult visualFollowsTheCut(const TissueCutter& cutter,
  const std::vector<int>& pieceOf,
  const std::map<int, int>& pieceOfNode,
  double rimOffset)
{
  const auto valid = visualMeshIsValid(cutter.visual(), cutter.collision(), rimOffset);
  if (!valid)
    return valid;
  const auto& embedding = cutter.visualEmbedding();
  if (embedding.pointCount() != cutter.visual().mesh().vertexCount())
    return ::testing::AssertionFailure() << "visual embedding has a wrong point count";
  for (std::size_t v = 0; v < embedding.pointCount(); ++v)
  {
    const int t = cutter.visual().collisionTriangleOf(static_cast<int>(v), cutter.collision());
    for (int node : cutter.simulation().hexahedra[embedding.hexahedron(v)])
    {
      const auto found = pieceOfNode.find(node);
      if (found != pieceOfNode.end() && found->second != pieceOf[t])
        return ::testing::AssertionFailure()
               << "visual vertex " << v << " (collision piece " << pieceOf[t] << ") hangs on node "
               << node << " of piece " << found->second;
    }
  }
  return ::testing::AssertionSuccess();
}

/// Cutter: the collision mesh is valid; every hexahedron (copies too) has
/// its original's rest geometry; pieces of the collision mesh that share no
/// triangle share no node; every collision vertex is embedded in a copy
/// holding one of its triangles when its hexahedron's copies hold any.
inline ::testing::AssertionResult cutterIsConsistent(const TissueCutter& cutter,
  const HexahedralMesh& original,
  double rimOffset = 0.0)
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
  return cutter.hasVisual() ? visualFollowsTheCut(cutter, pieceOf, pieceOfNode, rimOffset)
                            : ::testing::AssertionSuccess();
}

} // namespace cutting_test
} // namespace thintissue

#endif
