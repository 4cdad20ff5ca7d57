// Separation (thesis 5.3, the cut-through case): after a cut, the pieces
// of the collision mesh are found; a piece attached to nothing (no fixed
// node) is cut free and kept, dropped or handed over as its own body, and
// small fragments are removed whole. A removed piece is deactivated: its
// collision and visual triangles are no longer part of the tissue and its
// nodes are held still in the solver (pieces share no node, so nothing
// else is held).
#include "TissueCutter.h"

#include "CorotationalHexFem.h"
#include "UnionFind.h"

#include <algorithm>

namespace thintissue
{

namespace
{

double triangleArea(const std::vector<Vector3>& x, const Triangle& t)
{
  return 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
}

/// Re-indexes the used entries of a list of `count`: old index -> new, in
/// first-use order. A dense table (a piece's extraction already walks the
/// whole visual mesh; a hash node per vertex had cost thousands of
/// allocations a bite).
struct Renumbering
{
  explicit Renumbering(std::size_t count)
    : newOf(count, -1)
  {
  }
  std::vector<int> newOf;
  std::vector<int> oldOf;
  int operator()(int old)
  {
    int& index = newOf[static_cast<std::size_t>(old)];
    if (index < 0)
    {
      index = static_cast<int>(oldOf.size());
      oldOf.push_back(old);
    }
    return index;
  }
};

} // namespace

std::size_t TissueCutter::activeTriangleCount() const
{
  return static_cast<std::size_t>(std::count(Active.begin(), Active.end(), 1));
}

std::vector<char> TissueCutter::activeVisualTriangles() const
{
  std::vector<char> active(Visual.mesh().triangleCount(), 1);
  for (std::size_t t = 0; t < active.size(); ++t)
    active[t] = Active[Visual.triangleRegions()[t]];
  return active;
}

bool TissueCutter::activeMeshIsOnePiece() const
{
  const auto& triangles = Collision.triangles();
  const int count = static_cast<int>(triangles.size());
  UnionFind pieces(triangles.size());
  int first = -1;
  for (int t = 0; t < count; ++t)
  {
    if (!Active[t])
      continue;
    first = first < 0 ? t : first;
    for (int k = 0; k < 3; ++k)
      for (int other : Collision.trianglesOfEdge(triangles[t][k], triangles[t][(k + 1) % 3]))
        if (other > t && Active[other])
          pieces.unite(t, other);
  }
  for (int t = 0; t < count; ++t)
    if (Active[t] && pieces.find(t) != pieces.find(first))
      return false;
  return first >= 0;
}

// Whether the triangles a cut changed, and those around the vertices it
// opened, may have come apart. Every triangle the cut left apart from the
// rest is among them or joined to one of them (a triangle keeps its
// neighbours unless one of them changed or it lies at an opened vertex), so
// when a flood from each of them meets all the others the tissue is still
// in one piece. The floods advance together and stop as soon as they have
// all met: a cut that separates nothing costs what lies around it.
bool TissueCutter::cutMaySeparate(const TissueCutReport& report)
{
  const auto& triangles = Collision.triangles();
  std::vector<int>& label = PieceLabel; // per triangle: its seed, or -1
  label.resize(triangles.size(), -1);
  std::vector<int>& queue = PieceQueue;
  queue.clear();
  std::vector<int> parent;   // per seed: union-find over the seeds
  std::vector<int> frontier; // per set root: triangles queued
  auto root = [&parent](int x)
  {
    while (parent[x] != x)
      x = parent[x] = parent[parent[x]];
    return x;
  };
  auto seed = [&](int t)
  {
    if (!Active[t] || label[t] >= 0)
      return;
    label[t] = static_cast<int>(parent.size());
    parent.push_back(label[t]);
    frontier.push_back(1);
    queue.push_back(t);
  };
  for (int t : report.collision.changedTriangles)
    seed(t);
  for (const NewCollisionVertex& made : report.collision.newVertices)
    if (made.duplicateOf >= 0)
      for (int t : Collision.trianglesOfVertex(made.duplicateOf))
        seed(t);
  std::size_t sets = parent.size();
  bool separate = false;
  for (std::size_t next = 0; next < queue.size() && sets > 1 && !separate; ++next)
  {
    const int t = queue[next];
    for (int k = 0; k < 3 && sets > 1; ++k)
      for (int other : Collision.trianglesOfEdge(triangles[t][k], triangles[t][(k + 1) % 3]))
      {
        if (other < 0 || other == t || !Active[other])
          continue;
        const int a = root(label[t]);
        if (label[other] < 0)
        {
          label[other] = a;
          ++frontier[a];
          queue.push_back(other);
        }
        else if (const int b = root(label[other]); b != a)
        {
          parent[std::max(a, b)] = std::min(a, b);
          frontier[std::min(a, b)] += frontier[std::max(a, b)];
          --sets;
        }
      }
    // A set whose flood has run out is a piece of its own.
    separate = --frontier[root(label[t])] == 0 && sets > 1;
  }
  for (int t : queue)
    label[t] = -1;
  return sets > 1;
}

void TissueCutter::handleFreePieces(TissueCutReport& report)
{
  // A tissue in one piece stays in one piece unless the cut separated it:
  // then nothing else is looked at.
  if (SinglePiece && !cutMaySeparate(report))
    return;
  // Pieces of the active collision mesh, through shared edges.
  const auto& triangles = Collision.triangles();
  const int count = static_cast<int>(triangles.size());
  UnionFind pieces(triangles.size());
  for (int t = 0; t < count; ++t)
  {
    if (!Active[t])
      continue;
    for (int k = 0; k < 3; ++k)
      for (int other : Collision.trianglesOfEdge(triangles[t][k], triangles[t][(k + 1) % 3]))
        if (other > t && Active[other])
          pieces.unite(t, other);
  }
  // Per piece, by its root (ascending): its triangles, its area, and
  // whether a fixed node holds it (dense tables: a map entry per triangle
  // and node had cost more than the search).
  std::vector<std::vector<int>> members(triangles.size());
  std::vector<double> area(triangles.size(), 0.0);
  std::vector<char> attached(triangles.size(), 0);
  std::vector<int> roots;
  for (int t = 0; t < count; ++t)
  {
    if (!Active[t])
      continue;
    const int root = pieces.find(t);
    if (members[root].empty())
      roots.push_back(root);
    members[root].push_back(t);
    area[root] += triangleArea(Collision.restPositions(), triangles[t]);
    for (int h : Branches.hexahedraOf(t))
      for (int node : Simulation.hexahedra[h])
        attached[root] =
          attached[root] || (Solver ? Solver->isFixed(node) : Simulation.isFixed(node));
  }
  std::sort(roots.begin(), roots.end());
  SinglePiece = roots.size() < 2;
  if (SinglePiece)
    return;
  // With nothing attached anywhere, the largest piece is the tissue.
  int largest = roots.front();
  bool anyAttached = false;
  for (int root : roots)
  {
    anyAttached = anyAttached || attached[root];
    largest = area[root] > area[largest] ? root : largest;
  }
  std::size_t remaining = roots.size();
  for (int root : roots)
  {
    const std::vector<int>& list = members[root];
    const bool free = anyAttached ? !attached[root] : root != largest;
    if (!free)
      continue;
    const bool fragment = area[root] < Settings.fragmentAreaFraction * InitialArea;
    if (!fragment && Settings.freePieces == FreePieceHandling::Keep)
      continue;
    if (!fragment && Settings.freePieces == FreePieceHandling::HandOver)
      handOver(list, report);
    removePiece(list, report);
    ++report.removedPieces;
    --remaining;
  }
  SinglePiece = remaining == 1;
}

void TissueCutter::handOver(const std::vector<int>& triangles, TissueCutReport& report)
{
  TissuePiece& piece = report.handedOver.emplace_back();
  const std::vector<Vector3>& nodeCurrent = Solver ? Solver->positions() : Simulation.nodes;
  Renumbering collisionVertices(Collision.vertexCount());
  piece.collision.name = Collision.name() + " piece";
  for (int t : triangles)
  {
    const Triangle& tri = Collision.triangles()[t];
    piece.collision.triangles.push_back(
      { { collisionVertices(tri[0]), collisionVertices(tri[1]), collisionVertices(tri[2]) } });
    piece.collisionArea += triangleArea(Collision.restPositions(), tri);
  }
  std::vector<double> radii;
  for (int v : collisionVertices.oldOf)
  {
    piece.collision.positions.push_back(Collision.restPositions()[v]);
    piece.collisionCurrent.push_back(CollisionEmbedding.mapPosition(v, nodeCurrent));
    radii.push_back(Collision.radii()[v]);
  }
  piece.collision.pointAttributes.set(Settings.radiusArrayName, 1, radii);

  // Its hexahedra: those holding its triangles (pieces share no node).
  std::vector<int> hexahedra;
  for (int t : triangles)
    hexahedra.insert(
      hexahedra.end(), Branches.hexahedraOf(t).begin(), Branches.hexahedraOf(t).end());
  std::sort(hexahedra.begin(), hexahedra.end());
  hexahedra.erase(std::unique(hexahedra.begin(), hexahedra.end()), hexahedra.end());
  Renumbering nodes(Simulation.nodeCount());
  piece.simulation.name = Simulation.name + " piece";
  for (int h : hexahedra)
  {
    Hexahedron corners;
    for (int a = 0; a < 8; ++a)
      corners[a] = nodes(Simulation.hexahedra[h][a]);
    piece.simulation.hexahedra.push_back(corners);
  }
  for (int n : nodes.oldOf)
  {
    piece.simulation.nodes.push_back(Simulation.nodes[n]);
    piece.simulation.fixedNodes.push_back(Simulation.isFixed(n) ? 1 : 0);
    piece.nodeCurrent.push_back(nodeCurrent[n]);
  }
  if (HasVisual)
    PendingPieces.push_back({ report.handedOver.size() - 1, triangles, nodeCurrent });
}

// The visual part of a piece handed over (handOver): the visual
// triangles of its collision triangles' regions, placed by the node
// positions of when it came free.
void TissueCutter::pieceVisual(const std::vector<int>& triangles,
  const std::vector<Vector3>& nodeCurrent,
  TissuePiece& piece) const
{
  std::vector<char> inPiece(Collision.triangleCount(), 0);
  for (int t : triangles)
    inPiece[t] = 1;
  Renumbering visualVertices(Visual.mesh().vertexCount());
  piece.visual.name = Visual.mesh().name + " piece";
  for (std::size_t t = 0; t < Visual.mesh().triangleCount(); ++t)
  {
    if (!inPiece[Visual.triangleRegions()[t]])
      continue;
    const Triangle& tri = Visual.mesh().triangles[t];
    piece.visual.triangles.push_back(
      { { visualVertices(tri[0]), visualVertices(tri[1]), visualVertices(tri[2]) } });
  }
  // Only the piece's own vertices mapped (not the whole visual mesh).
  for (int v : visualVertices.oldOf)
  {
    piece.visual.positions.push_back(VisualEmbedding.mapPosition(v, nodeCurrent));
    piece.visualRest.push_back(Visual.mesh().positions[v]);
  }
  piece.visual.computeVertexNormals();
}

void TissueCutter::removePiece(const std::vector<int>& triangles, TissueCutReport& report)
{
  for (int t : triangles)
    Active[t] = 0;
  report.removedTriangles.insert(report.removedTriangles.end(), triangles.begin(), triangles.end());
  if (!Solver)
    return;
  // Its nodes are held, and its hexahedra (a piece shares none with the
  // rest) leave the solver: held still they would move nothing, yet each
  // would be rotated and assembled every step (a shaver's 41 bites left
  // 1,012 hexahedra, 45 of them carrying tissue).
  for (int t : triangles)
  {
    for (int h : Branches.hexahedraOf(t))
    {
      for (int node : Simulation.hexahedra[h])
        Solver->setFixed(static_cast<std::size_t>(node), true);
      const auto& held = Branches.trianglesOf(h);
      if (std::none_of(held.begin(), held.end(), [this](int other) { return Active[other] != 0; }))
        Solver->removeHexahedron(static_cast<std::size_t>(h));
    }
  }
}

} // namespace thintissue
