// 5.3.3: the visual-collision binding after a cut, and the visual mesh
// opened where the collision mesh opened.
#include "SplitFormula.h"
#include "VisualMeshCut.h"
#include "VisualMeshCutPrivate.h"

#include <Eigen/LU>

#include <algorithm>
#include <chrono>
#include <limits>
#include <numeric>
#include <tuple>

#include <tbb/parallel_for.h>

namespace thintissue
{

namespace
{

/// The region's triangles grouped by piece: `members` lists them piece by
/// piece, piece p from pieceStart[p] (given each piece's count in
/// pieceStart[p + 1] and each triangle's piece in triangleIn).
template <typename Buffers>
void groupByPiece(Buffers& buffers)
{
  auto& pieceStart = buffers.pieceStart;
  for (std::size_t p = 1; p < pieceStart.size(); ++p)
    pieceStart[p] += pieceStart[p - 1];
  buffers.members.resize(buffers.triangleIn.size());
  auto& cursor = buffers.pieceOf; // scratch
  cursor.assign(pieceStart.begin(), pieceStart.end() - 1);
  for (std::size_t i = 0; i < buffers.triangleIn.size(); ++i)
    buffers.members[cursor[buffers.triangleIn[i]]++] = static_cast<int>(i);
}

} // namespace

void CuttableVisualMesh::rebindSplitRegions(CutContext& context)
{
  // The new edges across the pieces get their indices here, in region
  // order, not by whichever region binds a vertex to one first.
  for (const RegionCut& region : context.regions)
    for (const CrossingPath& crossing : region.crossings)
      edgeIndex(crossing.ends[0], crossing.ends[1]);
  forEachRegion(context,
    [&](RegionCut& region, RegionWorker& worker) { rebindRegion(region, worker, context); });
  for (const RegionCut& region : context.regions)
  {
    context.rebound.insert(context.rebound.end(), region.rebound.begin(), region.rebound.end());
    for (const auto& [point, slot, vertex] : region.endVertices)
      context.edgePoints[point].visualVertex[slot] = vertex;
  }
}

void CuttableVisualMesh::rebindRegion(RegionCut& region,
  RegionWorker& worker,
  const CutContext& context)
{
  worker.activate(region);
  const std::vector<char> onCut = bindCrossingVertices(region, worker, context);
  region.locatedPieces = Settings.piecesByLocation && region.foldFree &&
                         locatePieces(region, onCut, worker.buffers, context);
  if (!region.locatedPieces)
    assignPieces(region, onCut, worker, context);
  rebindFarTriangles(region, worker, context);
  worker.deactivate(region);
}

// The far triangles (RegionCut::far) go to their pieces, and their vertices
// that no near triangle holds (those are rebound with the near ones) by
// formula 5-2, each once, as rebindPiece would in the same plane (the
// binding's own parameters there: the region has no fold).
void CuttableVisualMesh::rebindFarTriangles(RegionCut& region,
  RegionWorker& worker,
  const CutContext& context)
{
  if (region.far.empty())
    return;
  const CollisionTriangleSplit& split = context.cut->splits[region.split];
  const std::vector<Eigen::Matrix3d> inverses = childInverses(split);
  std::vector<PlaneToChild> toChild;
  for (const Eigen::Matrix3d& inverse : inverses)
    toChild.emplace_back(region.frame, inverse);
  const std::size_t firstFar = region.rebound.size();
  const std::size_t firstLeft = region.leftToHistory.size();
  std::vector<int>& localIndex = worker.localIndex;
  if (localIndex.size() < Mesh.vertexCount())
    localIndex.resize(Mesh.vertexCount(), -1);
  for (const RegionCut::FarTriangle& far : region.far)
  {
    // Its side stays the region's.
    TriangleRegion[far.triangle] = split.children[far.piece];
    for (const int v : Mesh.triangles[far.triangle])
    {
      // Near vertices are local (>= 0), far ones done are marked -2.
      if (localIndex[v] != -1)
        continue;
      localIndex[v] = -2;
      VisualVertexBinding& b = Bindings[v];
      // Strictly inside the parent (separateFarTriangles): not bulged.
      const Vector2 planar = planarPoint(region.frame, b.parameters);
      if (leftToHistory(region, b.parameters, planar, far.piece))
      {
        region.leftToHistory.push_back({ { v, split.children[far.piece] } });
        continue;
      }
      b.element = split.children[far.piece];
      b.parameters = toChild[far.piece].parameters(planar);
      region.rebound.push_back(v);
    }
  }
  for (std::size_t i = firstFar; i < region.rebound.size(); ++i)
    localIndex[region.rebound[i]] = -1;
  for (std::size_t i = firstLeft; i < region.leftToHistory.size(); ++i)
    localIndex[region.leftToHistory[i][0]] = -1;
  listPiecesInRegionOrder(region, worker.buffers, split);
}

// Each piece's list of triangles as the region laid out whole would give
// it (rebindPiece): its untouched triangles in the region's order (near
// and far interleaved by position), then its re-meshed ones; the cut
// does not depend on how much of the region lay far.
void CuttableVisualMesh::listPiecesInRegionOrder(RegionCut& region,
  CutBuffers& buffers,
  const CollisionTriangleSplit& split)
{
  auto& lists = buffers.pieceLists;
  lists.resize(split.children.size());
  for (auto& list : lists)
    list.clear();
  auto pieceOf = [&](int t)
  {
    const int child = TriangleRegion[t];
    int piece = 0;
    while (split.children[piece] != child)
      ++piece;
    return piece;
  };
  const std::size_t untouched = region.untouchedPositions.size();
  std::size_t m = 0;
  for (const RegionCut::FarTriangle& far : region.far)
  {
    for (; m < untouched && region.untouchedPositions[m] < far.position; ++m)
      lists[pieceOf(region.newTriangles[m])].push_back(region.newTriangles[m]);
    lists[far.piece].push_back(far.triangle);
  }
  for (; m < region.newTriangles.size(); ++m)
    lists[pieceOf(region.newTriangles[m])].push_back(region.newTriangles[m]);
  for (std::size_t c = 0; c < lists.size(); ++c)
    Regions[split.children[c]][region.side].swap(lists[c]);
}

// A vertex on a traced cut is bound to its collision edge by its parameter
// along the straight 2D cut. Two cuts from one collision vertex at a very
// small angle may share their first visual vertices: those are bound to
// that collision vertex.
std::vector<char> CuttableVisualMesh::bindCrossingVertices(RegionCut& region,
  RegionWorker& worker,
  const CutContext& context)
{
  const int side = region.side > 0 ? 1 : -1;
  // (local vertex, crossing) for the inner vertices of each traced cut,
  // grouped by vertex (a vertex a cut visits twice counts twice, as on two
  // cuts).
  auto& crossingsOf = worker.buffers.crossingsOf;
  crossingsOf.clear();
  for (std::size_t c = 0; c < region.crossings.size(); ++c)
  {
    const auto& vertices = region.crossings[c].vertices;
    for (std::size_t i = 1; i + 1 < vertices.size(); ++i)
    {
      const int local = worker.local(vertices[i]);
      if (local < 0)
        throw Error("visual cut of '" + Mesh.name + "': visual vertex " +
                    std::to_string(vertices[i]) + " of a traced cut lies outside its region");
      crossingsOf.emplace_back(local, static_cast<int>(c));
    }
  }
  std::sort(crossingsOf.begin(), crossingsOf.end());
  std::vector<char> onCut(region.vertices.size(), 0); // per local vertex
  for (std::size_t i = 0; i < crossingsOf.size();)
  {
    const int local = crossingsOf[i].first;
    const int w = region.vertices[local];
    std::size_t j = i;
    while (j < crossingsOf.size() && crossingsOf[j].first == local)
      ++j;
    const CrossingPath& first = region.crossings[crossingsOf[i].second];
    if (j - i == 1)
    {
      // Along the cut in the plane it was traced in: increasing along it.
      const Vector2 d = first.planar[1] - first.planar[0];
      const double s =
        std::clamp((region.planar[local] - first.planar[0]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      bindToEdge(w, first.ends[0], first.ends[1], s, side);
    }
    else
    {
      int common = -1;
      for (int end : first.ends)
      {
        bool shared = true;
        for (std::size_t k = i; k < j; ++k)
        {
          const auto& ends = region.crossings[crossingsOf[k].second].ends;
          shared = shared && std::find(ends.begin(), ends.end(), end) != ends.end();
        }
        common = shared ? end : common;
      }
      if (common < 0)
      {
        throw Error("visual cut of '" + Mesh.name + "': visual vertex " + std::to_string(w) +
                    " lies on two cuts that share no collision vertex");
      }
      VisualVertexBinding& b = Bindings[w];
      b.kind = BindingKind::CollisionVertex;
      b.element = common;
      // The crease's side label is 0 (CollisionSides::pathSide).
      b.side = pairedSlot(common, region.side, region.cleft) == CreaseSlot ? 0 : side;
      b.parameters = Vector3(1.0, 0.0, 0.0);
    }
    onCut[local] = 1;
    region.rebound.push_back(w);
    i = j;
  }
  for (const CrossingPath& crossing : region.crossings)
  {
    for (int end = 0; end < 2; ++end)
    {
      const auto found = context.edgePointOf.find(crossing.ends[end]);
      if (found != context.edgePointOf.end())
      {
        const EdgePoint& point = context.edgePoints[found->second];
        region.endVertices.push_back({ { found->second,
          point.junction ? region.junctionSlot() : region.side,
          end == 0 ? crossing.vertices.front() : crossing.vertices.back() } });
      }
    }
  }
  return onCut;
}

namespace
{

int findSet(std::vector<int>& parent, int x)
{
  while (parent[x] != x)
  {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

// Sets hang on their lowest member (parent[x] <= x always), so that one
// pass in increasing order flattens them (flattenSets).
void joinSets(std::vector<int>& parent, int x, int y)
{
  // Most joins inside a region are of vertices hanging on one root already
  // (each inner edge is met from both its triangles): no walk then.
  if (parent[x] == parent[y])
    return;
  x = findSet(parent, x);
  y = findSet(parent, y);
  if (x != y)
    parent[std::max(x, y)] = std::min(x, y);
}

/// Every element's parent becomes its root: parent[x] < x was flattened
/// before x.
void flattenSets(std::vector<int>& parent)
{
  for (std::size_t x = 0; x < parent.size(); ++x)
    parent[x] = parent[parent[x]];
}

} // namespace

// The region's triangles fall into pieces separated by the traced cuts;
// each piece goes to the collision piece most of its triangles lie in, and
// its inner vertices are rebound there by formula 5-2. Deciding per piece,
// not per triangle, keeps a vertex and all its triangles in one region
// where the parameterisation folds.
//
// Pieces without a flood: an inner vertex off the traced cuts has all its
// triangles in the region and none of its edges on a cut, so its triangles
// are one piece (union-find over local vertices, and triangles without such
// a corner); triangles meet otherwise only across edges between border or
// cut vertices, which are few (along the region's border and the cuts) and
// matched by sorting.
void CuttableVisualMesh::assignPieces(RegionCut& region,
  const std::vector<char>& onCut,
  RegionWorker& worker,
  const CutContext& context)
{
  const std::size_t count = region.vertices.size();
  const std::size_t triangleCount = region.newTriangles.size();
  CutBuffers& buffers = worker.buffers;
  // Local vertices on a traced cut or the region's border: their triangles
  // are joined through edges only.
  auto& special = buffers.special;
  special.assign(count, 0);
  for (std::size_t i = 0; i < count; ++i)
    special[i] = Bindings[region.vertices[i]].kind != BindingKind::CollisionTriangle;
  auto& cutEdges = buffers.cutEdges;
  cutEdges.clear();
  for (const CrossingPath& crossing : region.crossings)
    for (std::size_t i = 0; i + 1 < crossing.vertices.size(); ++i)
    {
      const int a = worker.local(crossing.vertices[i]);
      const int b = worker.local(crossing.vertices[i + 1]);
      cutEdges.emplace_back(std::min(a, b), std::max(a, b));
      special[a] = special[b] = 1;
    }
  std::sort(cutEdges.begin(), cutEdges.end());
  // Sets: local vertices, then triangles (count + i).
  auto& parent = buffers.parent;
  parent.resize(count + triangleCount);
  std::iota(parent.begin(), parent.end(), 0);
  const auto& corners = region.newLocalTriangles;
  auto& borderEdges = buffers.borderEdges; // (edge key, set)
  borderEdges.clear();
  auto& representative = buffers.representative; // per triangle: its set
  representative.resize(triangleCount);
  for (std::size_t i = 0; i < triangleCount; ++i)
  {
    const Triangle& tri = corners[i];
    // A triangle is in the set of its first inner corner (joined with the
    // others), else in its own.
    int self = -1;
    int specialCorners = 0;
    for (int v : tri)
      if (!special[v])
      {
        if (self < 0)
          self = v;
        else
          joinSets(parent, self, v);
      }
      else
        ++specialCorners;
    if (self < 0)
      self = static_cast<int>(count + i);
    representative[i] = self;
    // An edge between special corners needs two of them (most triangles
    // of a region have none).
    if (specialCorners < 2)
      continue;
    for (int k = 0; k < 3; ++k)
    {
      const int a = tri[k], b = tri[(k + 1) % 3];
      if (special[a] && special[b] &&
          !std::binary_search(
            cutEdges.begin(), cutEdges.end(), std::make_pair(std::min(a, b), std::max(a, b))))
        borderEdges.emplace_back(edgeKey(a, b), self);
    }
  }
  // By edge (one key: sorting triples had cost more than the joins).
  std::sort(borderEdges.begin(), borderEdges.end());
  for (std::size_t e = 0; e + 1 < borderEdges.size(); ++e)
    if (borderEdges[e].first == borderEdges[e + 1].first)
      joinSets(parent, borderEdges[e].second, borderEdges[e + 1].second);
  flattenSets(parent);
  rebindPieces(region, onCut, buffers, context);
}

// The pieces assignPieces found (buffers.parent), in the order of their
// first triangles, each with its triangles in order: the centroid decides
// the collision piece, rebindPiece the rest.
void CuttableVisualMesh::rebindPieces(RegionCut& region,
  const std::vector<char>& onCut,
  CutBuffers& buffers,
  const CutContext& context)
{
  const CollisionTriangleSplit& split = context.cut->splits[region.split];
  const std::size_t count = region.vertices.size();
  const std::size_t triangleCount = region.newTriangles.size();
  auto& pieceOf = buffers.pieceOf; // per set root: its piece
  pieceOf.assign(count + triangleCount, -1);
  auto& pieceStart = buffers.pieceStart;
  auto& centroids = buffers.centroids;
  pieceStart.assign(1, 0);
  centroids.clear();
  auto& triangleIn = buffers.triangleIn;
  triangleIn.resize(triangleCount);
  for (std::size_t i = 0; i < triangleCount; ++i)
  {
    int& piece = pieceOf[buffers.parent[buffers.representative[i]]]; // flattened
    if (piece < 0)
    {
      piece = static_cast<int>(centroids.size());
      centroids.push_back(Vector2::Zero());
      pieceStart.push_back(0);
    }
    triangleIn[i] = piece;
    ++pieceStart[piece + 1];
    for (int v : region.newLocalTriangles[i])
      centroids[piece] += region.planar[v];
  }
  const std::size_t pieces = centroids.size();
  groupByPiece(buffers);
  const std::vector<int>& members = buffers.members;
  const std::vector<Eigen::Matrix3d> inverses = childInverses(split);
  markRebindable(region, split.parent, onCut, buffers);
  for (std::size_t p = 0; p < pieces; ++p)
  {
    const int size = pieceStart[p + 1] - pieceStart[p];
    const int c = pieceContaining(region.pieces, centroids[p] / (3.0 * size));
    rebindPiece(
      region, members.data() + pieceStart[p], size, c, split.children[c], inverses[c], buffers);
  }
}

void CuttableVisualMesh::markRebindable(const RegionCut& region,
  int parent,
  const std::vector<char>& onCut,
  CutBuffers& buffers) const
{
  auto& rebindable = buffers.rebindable;
  rebindable.resize(region.vertices.size());
  for (std::size_t i = 0; i < region.vertices.size(); ++i)
  {
    const VisualVertexBinding& b = Bindings[region.vertices[i]];
    rebindable[i] = b.kind == BindingKind::CollisionTriangle && b.element == parent && !onCut[i];
  }
}

// Where the region lies in its plane without a fold, each collision piece
// is convex there and bounded inside the parent by traced crossings, which
// the re-meshing made straight and lined with visual vertices (within
// OnLineTolerance of the line): no triangle straddles one, so a triangle
// lies in the piece on whose inner side of each of its crossings its
// centroid lies. Those are the union-find's pieces (assignPieces), found
// with a sign test per crossing and triangle. False, having changed
// nothing, where a centroid lies within that tolerance of a crossing (a
// corner snapped onto the line may put it on the wrong side) or not in
// exactly one piece.
bool CuttableVisualMesh::locatePieces(RegionCut& region,
  const std::vector<char>& onCut,
  CutBuffers& buffers,
  const CutContext& context)
{
  const CollisionTriangleSplit& split = context.cut->splits[region.split];
  const double margin = OnLineTolerance * frameScale(region.frame);
  PieceLocator locator;
  if (!pieceLocator(region, split, margin, locator))
    return false;
  const int pieces = static_cast<int>(split.children.size());
  const std::size_t triangleCount = region.newTriangles.size();
  auto& triangleIn = buffers.triangleIn;
  triangleIn.resize(triangleCount);
  auto& pieceStart = buffers.pieceStart;
  pieceStart.assign(static_cast<std::size_t>(pieces) + 1, 0);
  for (std::size_t i = 0; i < triangleCount; ++i)
  {
    const Triangle& corners = region.newLocalTriangles[i];
    const Vector2 centroid =
      (region.planar[corners[0]] + region.planar[corners[1]] + region.planar[corners[2]]) / 3.0;
    unsigned sides = 0;
    for (int l = 0; l < locator.lineCount; ++l)
    {
      const double d = locator.normal[l].dot(centroid - locator.from[l]);
      if (std::abs(d) <= margin)
        return false;
      sides |= (d > 0.0 ? 1u : 0u) << l;
    }
    const int in = locator.pieceOfSides[sides];
    if (in < 0)
      return false;
    triangleIn[i] = in;
    ++pieceStart[in + 1];
  }
  groupByPiece(buffers);
  const std::vector<int>& members = buffers.members;
  const std::vector<Eigen::Matrix3d> inverses = childInverses(split);
  markRebindable(region, split.parent, onCut, buffers);
  for (int c = 0; c < pieces; ++c)
    if (pieceStart[c + 1] > pieceStart[c])
      rebindPiece(region,
        members.data() + pieceStart[c],
        pieceStart[c + 1] - pieceStart[c],
        c,
        split.children[c],
        inverses[c],
        buffers);
  return true;
}

// The crossings of the split in the region's plane (the lines its traced
// paths run along) and, per combination of sides of them, the collision
// piece inside all its crossings there (-1: none or several). False where
// a line or a piece is degenerate.
bool CuttableVisualMesh::pieceLocator(const RegionCut& region,
  const CollisionTriangleSplit& split,
  double margin,
  PieceLocator& locator) const
{
  const std::array<Vector2, 3>& frame = region.frame;
  const int pieces = static_cast<int>(split.children.size());
  if (pieces > PieceLocator::MaxPieces || region.crossings.size() > PieceLocator::MaxLines)
    return false;
  // Per piece: the lines it lies beside (bit per line), and on which side.
  std::array<std::pair<unsigned, unsigned>, PieceLocator::MaxPieces> needs{};
  locator.lineCount = static_cast<int>(region.crossings.size());
  for (int l = 0; l < locator.lineCount; ++l)
  {
    const CrossingPath& crossing = region.crossings[l];
    const Vector2 along = crossing.planar[1] - crossing.planar[0];
    const double length = along.norm();
    if (!(length > margin))
      return false;
    locator.from[l] = crossing.planar[0];
    locator.normal[l] = Vector2(-along.y(), along.x()) / length;
    for (const int c : crossing.pieces)
    {
      if (c < 0)
        continue;
      const auto& corners = split.childCorners[c];
      const Vector3 middle = (corners[0] + corners[1] + corners[2]) / 3.0;
      const Vector2 inner = middle[0] * frame[0] + middle[1] * frame[1] + middle[2] * frame[2];
      const double d = locator.normal[l].dot(inner - locator.from[l]);
      if (std::abs(d) <= margin)
        return false;
      needs[c].first |= 1u << l;
      needs[c].second |= (d > 0.0 ? 1u : 0u) << l;
    }
  }
  for (unsigned sides = 0; sides < locator.pieceOfSides.size(); ++sides)
  {
    int in = -1;
    for (int c = 0; c < pieces; ++c)
      if ((sides & needs[c].first) == needs[c].second)
        in = in == -1 ? c : -2;
    locator.pieceOfSides[sides] = static_cast<std::int8_t>(std::max(in, -1));
  }
  return true;
}

// A piece of a split region goes to collision triangle `child`; its inner
// vertices are rebound there by formula 5-2, (a', b', c') = (a, b, c) M^-1.
void CuttableVisualMesh::rebindPiece(RegionCut& region,
  const int* members,
  int memberCount,
  int piece,
  int child,
  const Eigen::Matrix3d& inverse,
  CutBuffers& buffers)
{
  const std::vector<Triangle>& corners = region.newLocalTriangles;
  std::vector<char>& rebindable = buffers.rebindable;
  const int side = region.side > 0 ? 1 : -1;
  const PlaneToChild toChild(region.frame, inverse);
  std::vector<int>& childRegion = Regions[child][region.side];
  if (childRegion.empty())
    childRegion.reserve(region.newTriangles.size());
  for (int j = 0; j < memberCount; ++j)
  {
    const int m = members[j];
    const int t = region.newTriangles[m];
    TriangleRegion[t] = child;
    TriangleSide[t] = static_cast<std::int8_t>(side);
    childRegion.push_back(t);
    for (int local : corners[m])
    {
      // Each vertex bound to the parent, off the cuts, once (marked).
      if (!rebindable[local])
        continue;
      rebindable[local] = 0;
      const int v = region.vertices[local];
      VisualVertexBinding& b = Bindings[v];
      // Its point in the plane must be the binding's own (no bulge, no
      // fold repair moved it): the history resolves from the parameters.
      const Vector2& planar = region.planar[local];
      if (planar == planarPoint(region.frame, b.parameters) &&
          leftToHistory(region, b.parameters, planar, piece))
      {
        region.leftToHistory.push_back({ { v, child } });
        continue;
      }
      // The parent parameters of where the vertex lies in the plane it
      // was cut in (its binding's own, unless a fold was repaired there).
      b.element = child;
      b.parameters = toChild.parameters(region.planar[local]);
      region.rebound.push_back(v);
    }
  }
}

// The history resolves a vertex from its own parameters, at the plane
// point they give, to the piece whose smallest barycentric coordinate is
// largest there, with the same map.
bool CuttableVisualMesh::leftToHistory(const RegionCut& region,
  const Vector3& parameters,
  const Vector2& planar,
  int piece) const
{
  return Settings.lazyBinding && region.historyPieceCount > 0 && parameters.minCoeff() > 0.0 &&
         pieceContaining(region.historyPieces.data(), region.historyPieceCount, planar) == piece;
}

void CuttableVisualMesh::resolveSplitRegions(const CollisionCutResult& cut)
{
  if (!LeftToHistory)
    return;
  for (const CollisionTriangleSplit& split : cut.splits)
    for (const std::vector<int>& region : Regions[split.parent])
      for (int t : region)
        for (int v : Mesh.triangles[t])
          resolveBinding(v);
}

std::vector<VisualVertexBinding> CuttableVisualMesh::bindings() const
{
  std::vector<VisualVertexBinding> all(Bindings.size());
  for (std::size_t v = 0; v < all.size(); ++v)
    all[v] = binding(static_cast<int>(v));
  return all;
}

// The visual vertex of each new collision vertex inside an edge, and the
// edge's paths split there (accumulated-length parameters rescaled).
void CuttableVisualMesh::finishEdgePoints(CutContext& context)
{
  Paired.resize(context.collision->vertexCount(), { { -1, -1, -1 } });
  for (EdgePoint& point : context.edgePoints)
  {
    EdgePaths& paths = Paths.at(edgeKey(point.a, point.b));
    for (int side = 0; side < point.slotCount(); ++side)
    {
      if (point.visualVertex[side] < 0 && point.visual[side].isVertex())
        point.visualVertex[side] = point.visual[side].vertex;
      if (point.rim && point.visualVertex[side] < 0)
        point.visualVertex[side] = point.visualVertex[1 - side];
      if (point.visualVertex[side] < 0)
      {
        throw Error("visual cut of '" + Mesh.name + "': no visual vertex for collision vertex " +
                    std::to_string(point.vertex) + " on side " + std::to_string(side));
      }
    }
    for (int side = 0; side < point.slotCount(); ++side)
    {
      const int w = point.visualVertex[side];
      Paired[point.vertex][side] = w;
      VisualVertexBinding& b = Bindings[w];
      b.kind = BindingKind::CollisionVertex;
      b.element = point.vertex;
      b.side = point.rim || side == CreaseSlot ? 0 : (side > 0 ? 1 : -1);
      b.parameters = Vector3(1.0, 0.0, 0.0);
      context.rebound.push_back(w);
    }
    EdgePaths before, after;
    before.rim = after.rim = point.rim;
    for (int side = 0; side < point.slotCount(); ++side)
    {
      std::vector<int> p = paths.sides[side];
      const int w = point.visualVertex[side];
      const std::size_t i = static_cast<std::size_t>(point.pathPosition[side]);
      std::size_t at = i + 1;
      if (p[i] == w)
        at = i;
      else if (p[i + 1] != w)
        p.insert(p.begin() + static_cast<std::ptrdiff_t>(i + 1), w);
      if (side == 1 && point.rim)
      {
        before.sides[1] = before.sides[0];
        after.sides[1] = after.sides[0];
        continue;
      }
      before.sides[side].assign(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(at) + 1);
      after.sides[side].assign(p.rbegin(), p.rend() - static_cast<std::ptrdiff_t>(at));
      // Vertices a shared segment binds to another edge keep that binding.
      for (std::size_t j = 1; j + 1 < p.size(); ++j)
      {
        const int v = p[j];
        if (j == at || Bindings[v].kind != BindingKind::CollisionEdge ||
            !boundToEdge(v, point.a, point.b))
          continue;
        const double t = edgeParameter(v, point.a, point.b);
        if (j < at)
          bindToEdge(v, point.a, point.vertex, t / point.u, Bindings[v].side);
        else
          bindToEdge(v, point.vertex, point.b, (t - point.u) / (1.0 - point.u), Bindings[v].side);
        context.rebound.push_back(v);
      }
    }
    if (Strips.count(edgeKey(point.a, point.b)))
      splitStrip(edgeKey(point.a, point.b), point.a, point.b, point.vertex, point.u, context);
    Paths.erase(edgeKey(point.a, point.b));
    Paths[edgeKey(point.a, point.vertex)] = std::move(before);
    Paths[edgeKey(point.b, point.vertex)] = std::move(after);
  }
  // The traced cuts are the paths of the new edges across the pieces.
  for (const RegionCut& region : context.regions)
  {
    for (const CrossingPath& crossing : region.crossings)
    {
      EdgePaths& paths = Paths[edgeKey(crossing.ends[0], crossing.ends[1])];
      paths.sides[region.side] = crossing.vertices;
    }
  }
}

//------------------------------------------------------------------------------
// Whether a triangle still on the collision element visual vertex v is
// bound to uses v, so that each claim on v needs a copy. On a manifold mesh
// every triangle there does; at a horizontal cleavage's junction a triangle
// sees only two of its three paths and paired vertices (a leaf left alone
// there does not see the top's or the bottom's).
bool CuttableVisualMesh::rootStillUses(const CuttableCollisionMesh& collision, int v) const
{
  const VisualVertexBinding& b = Bindings[v];
  // The slot v serves, or -1 if every triangle there uses it.
  int slot = -1;
  std::array<int, 3> lips{ { -1, -1, -1 } };
  const std::vector<int>* fan = nullptr;
  const EdgePaths* paths = nullptr;
  if (b.kind == BindingKind::CollisionVertex)
  {
    fan = &collision.trianglesOfVertex(b.element);
    if (fan->empty())
      return false;
    const auto& paired = Paired[b.element];
    if (paired[CreaseSlot] < 0)
      return true;
    for (int k = 0; k < 3; ++k)
      slot = paired[k] == v ? k : slot;
    // The body's cut surface there runs through the crease (its leaves were
    // cut there): it keeps the crease vertex when the leaves leave.
    if (slot == CreaseSlot && bodyColumnUsesCrease(collision, b.element))
      return true;
  }
  else
  {
    const auto& e = Edges[b.element];
    lips = collision.trianglesOfEdge(e[0], e[1]);
    if (lips[0] < 0)
      return false;
    const auto found = Paths.find(edgeKey(e[0], e[1]));
    if (found == Paths.end() || !found->second.junction())
      return true;
    paths = &found->second;
    slot = b.side > 0 ? 1 : (b.side < 0 ? 0 : CreaseSlot);
  }
  if (slot < 0)
    return true;
  auto uses = [&](int T)
  {
    for (int side = 0; side < 2; ++side)
    {
      const bool cleft = facesCleft(collision, T, side);
      if ((paths ? pathSlot(*paths, side, cleft) : pairedSlot(b.element, side, cleft)) == slot)
        return true;
    }
    return false;
  };
  if (fan)
    return std::any_of(fan->begin(), fan->end(), uses);
  return std::any_of(lips.begin(), lips.end(), [&](int T) { return T >= 0 && uses(T); });
}

// Where the collision mesh opened, the visual vertices bound to an opened
// collision vertex or edge get one copy per side of the opening.
// The claims on visual vertices a collision triangle's regions make: a
// corner bound to a collision vertex or edge whose original this cut copied
// (CutContext::root) needs the copy serving that triangle.
void CuttableVisualMesh::claimsOf(int T,
  const CuttableCollisionMesh& collision,
  const CutContext& context,
  std::vector<Claim>& claims) const
{
  const Triangle& tri = collision.triangles()[T];
  for (int side = 0; side < 2; ++side)
  {
    for (int t : Regions[T][side])
    {
      for (int k = 0; k < 3; ++k)
      {
        const int v = Mesh.triangles[t][k];
        const VisualVertexBinding& b = Bindings[v];
        if (b.kind == BindingKind::CollisionVertex)
        {
          if (tri[0] == b.element || tri[1] == b.element || tri[2] == b.element)
            continue;
          for (int x : tri)
            if (context.root(x) == b.element)
              claims.push_back({ t, k, v, x, { { -1, -1 } } });
        }
        else if (b.kind == BindingKind::CollisionEdge)
        {
          const auto& e = Edges[b.element];
          const bool has0 = tri[0] == e[0] || tri[1] == e[0] || tri[2] == e[0];
          const bool has1 = tri[0] == e[1] || tri[1] == e[1] || tri[2] == e[1];
          if (has0 && has1)
            continue;
          for (int j = 0; j < 3; ++j)
          {
            const int x = tri[j], y = tri[(j + 1) % 3];
            if (edgeKey(context.root(x), context.root(y)) == edgeKey(e[0], e[1]))
              claims.push_back({ t, k, v, -1, { { x, y } } });
          }
        }
      }
    }
  }
}

void CuttableVisualMesh::openVisualMesh(const CuttableCollisionMesh& collision, CutContext& context)
{
  // A claim needs a corner copied by this cut (a vertex bound to that
  // corner's original, or an edge whose ends are not both corners): the
  // regions of a triangle that kept its corners (most pieces of the split
  // ones on the side that stays) are not scanned. The scans only read, so
  // large regions are scanned on several threads, each triangle's claims
  // kept apart and joined in order.
  const auto& collisionTriangles = collision.triangles();
  std::vector<int> scanned;
  std::size_t regionTriangles = 0;
  for (int T : context.cut->changedTriangles)
  {
    const Triangle& tri = collisionTriangles[T];
    if (context.root(tri[0]) == tri[0] && context.root(tri[1]) == tri[1] &&
        context.root(tri[2]) == tri[2])
      continue;
    scanned.push_back(T);
    regionTriangles += Regions[T][0].size() + Regions[T][1].size();
  }
  std::vector<Claim> claims;
  if (regionTriangles < Settings.parallelRegionTriangles || scanned.size() < 2)
  {
    for (int T : scanned)
      claimsOf(T, collision, context, claims);
  }
  else
  {
    std::vector<std::vector<Claim>> claimsPerTriangle(scanned.size());
    tbb::parallel_for(std::size_t(0),
      scanned.size(),
      [&](std::size_t i) { claimsOf(scanned[i], collision, context, claimsPerTriangle[i]); });
    for (const std::vector<Claim>& some : claimsPerTriangle)
      claims.insert(claims.end(), some.begin(), some.end());
  }
  // By vertex, then triangle and corner: the copies made do not depend on
  // the order the regions list their triangles in.
  std::sort(claims.begin(),
    claims.end(),
    [](const Claim& p, const Claim& q) {
      return std::tie(p.vertex, p.triangle, p.corner) < std::tie(q.vertex, q.triangle, q.corner);
    });
  context.copies.clear();
  for (std::size_t i = 0; i < claims.size();)
  {
    std::size_t j = i;
    const int v = claims[i].vertex;
    const std::size_t copiesOfV = context.copies.size();
    const VisualVertexBinding original = Bindings[v];
    bool rootAlive = rootStillUses(collision, v);
    for (; j < claims.size() && claims[j].vertex == v; ++j)
    {
      const Claim& claim = claims[j];
      const int code =
        claim.element >= 0 ? 2 * claim.element : 2 * edgeIndex(claim.edge[0], claim.edge[1]) + 1;
      const std::uint64_t key = CutContext::copyKey(v, code);
      auto it = std::find_if(context.copies.begin() + copiesOfV,
        context.copies.end(),
        [key](const std::pair<std::uint64_t, int>& entry) { return entry.first == key; });
      if (it == context.copies.end())
      {
        context.copies.emplace_back(key, rootAlive ? addVertexCopy(v) : v);
        it = context.copies.end() - 1;
        rootAlive = true; // the vertex itself serves the first claim at most
        const int w = it->second;
        if (w != v)
          context.newVertices.push_back(w);
        context.rebound.push_back(w);
        VisualVertexBinding& b = Bindings[w];
        if (claim.element >= 0)
        {
          auto& paired = Paired[claim.element];
          if (Paired[b.element][CreaseSlot] == v)
            paired[CreaseSlot] = w;
          else
          {
            const int sideIndex = b.side > 0 ? 1 : 0;
            paired[sideIndex] = w;
            if (b.side == 0)
              paired[1 - sideIndex] = w;
          }
          b.element = claim.element;
        }
        else
        {
          const auto& e = Edges[original.element];
          const int x = claim.edge[0], y = claim.edge[1];
          const double t = original.parameters[1]; // from e[0]
          const double fromX = context.root(x) == e[0] ? t : 1.0 - t;
          bindToEdge(w, x, y, fromX, original.side);
        }
      }
      Mesh.triangles[claim.triangle][claim.corner] = it->second;
      context.changedTriangles.push_back(claim.triangle);
    }
    i = j;
  }
  std::sort(context.copies.begin(), context.copies.end());
}

// The paths of the edges the opening made: the paths they were copied
// from, through the vertex copies; strips move with their edge.
void CuttableVisualMesh::updateEdgePaths(const CuttableCollisionMesh& collision,
  CutContext& context)
{
  std::vector<std::uint64_t> gone;
  for (int T : context.cut->changedTriangles)
  {
    const Triangle& tri = collision.triangles()[T];
    for (int k = 0; k < 3; ++k)
    {
      const int x = tri[k], y = tri[(k + 1) % 3];
      const std::uint64_t key = edgeKey(x, y);
      if (Paths.count(key))
        continue;
      const int rx = context.root(x), ry = context.root(y);
      const std::uint64_t rootKey = edgeKey(rx, ry);
      const auto found = Paths.find(rootKey);
      if (found == Paths.end())
      {
        throw Error("visual cut of '" + Mesh.name + "': collision edge (" + std::to_string(x) +
                    ", " + std::to_string(y) + ") has no visual path");
      }
      const int edgeCode = 2 * edgeIndex(x, y) + 1;
      auto mapped = [&](int w)
      {
        const VisualVertexBinding& b = Bindings[w];
        int code = edgeCode;
        if (b.kind == BindingKind::CollisionVertex)
        {
          const int r = context.root(b.element);
          code = 2 * (r == rx ? x : (r == ry ? y : b.element));
        }
        return context.copyOf(w, code);
      };
      EdgePaths paths;
      paths.rim = found->second.rim;
      const bool reverse = (rx < ry) != (x < y);
      for (int side = 0; side < 3; ++side)
      {
        for (int w : found->second.sides[side])
          paths.sides[side].push_back(mapped(w));
        if (reverse)
          std::reverse(paths.sides[side].begin(), paths.sides[side].end());
      }
      const bool rootAlive = collision.trianglesOfEdge(rx, ry)[0] >= 0;
      if (!rootAlive)
      {
        gone.push_back(rootKey);
        const auto strip = Strips.find(rootKey);
        if (strip != Strips.end())
        {
          for (auto& row : strip->second.rows)
          {
            for (int w : row)
              bindToEdge(w, x, y, edgeParameter(w, rx, ry), 0);
            if (reverse)
              std::reverse(row.begin(), row.end());
          }
          Strips[key] = std::move(strip->second);
          Strips.erase(rootKey);
        }
      }
      Paths[key] = std::move(paths);
    }
  }
  for (std::uint64_t key : gone)
    Paths.erase(key);
}

// A junction edge the opening left with one triangle is an edge of one
// sheet: it keeps the two paths that triangle sees as its - and + paths (a
// lower leaf's + path is the crease's), so that later cuts and its cut
// surface treat it as any edge.
void CuttableVisualMesh::dropUnseenJunctionPaths(const CuttableCollisionMesh& collision,
  CutContext& context)
{
  for (int T : context.cut->changedTriangles)
  {
    const Triangle& tri = collision.triangles()[T];
    for (int k = 0; k < 3; ++k)
    {
      const int x = tri[k], y = tri[(k + 1) % 3];
      for (const std::uint64_t key : { edgeKey(x, y), edgeKey(context.root(x), context.root(y)) })
      {
        const auto found = Paths.find(key);
        if (found == Paths.end() || !found->second.junction())
          continue;
        const auto lips = collision.trianglesOfEdge(
          static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu));
        if (lips[0] < 0 || lips[1] >= 0)
          continue;
        EdgePaths& paths = found->second;
        std::array<std::vector<int>, 3> seen;
        for (int side = 0; side < 2; ++side)
          seen[side] = paths.sides[pathSlot(paths, side, facesCleft(collision, lips[0], side))];
        paths.sides = std::move(seen);
      }
    }
  }
}

//------------------------------------------------------------------------------
VisualCutResult CuttableVisualMesh::cut(const CuttableCollisionMesh& collision,
  const CollisionCutResult& cut)
{
  VisualCutResult result;
  if (!cut.changed())
    return result;
  CutContext context;
  context.collision = &collision;
  context.cut = &cut;
  for (const NewCollisionVertex& made : cut.newVertices)
  {
    if (made.duplicateOf >= 0)
      context.addCopy(made.vertex, made.duplicateOf);
  }
  Regions.resize(collision.triangleCount());
  // The workers' local indices come back all -1 (on an error too: the
  // regions active then are unknown).
  context.worker = &Workers.front();
  try
  {
    resolveSplitRegions(cut);
    splitEdgePaths(context);
    traceRegionCuts(context);
    remeshRegions(context);
    rebindSplitRegions(context);
  }
  catch (...)
  {
    for (RegionWorker& worker : Workers)
      std::fill(worker.localIndex.begin(), worker.localIndex.end(), -1);
    throw;
  }
  SplitHistory.recordCut(cut, collision.restPositions());
  result.splitRegions = context.regions.size();
  result.regionsLocated = static_cast<std::size_t>(std::count_if(context.regions.begin(),
    context.regions.end(),
    [](const RegionCut& region) { return region.locatedPieces; }));
  for (const RegionCut& region : context.regions)
  {
    result.farTriangles += region.far.size();
    result.leftToHistory.insert(
      result.leftToHistory.end(), region.leftToHistory.begin(), region.leftToHistory.end());
  }
  LeftToHistory = LeftToHistory || !result.leftToHistory.empty();
  finishEdgePoints(context);
  openVisualMesh(collision, context);
  updateEdgePaths(collision, context);
  if (HasJunctions)
    dropUnseenJunctionPaths(collision, context);
  const auto cutSurfaceStart = std::chrono::steady_clock::now();
  updateCutSurface(collision, context);
  result.cutSurfaceMilliseconds =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cutSurfaceStart)
      .count();
  compactTriangles();
  auto sorted = [](std::vector<int> list)
  {
    // New vertices are made in increasing order: most lists need no sort.
    if (!std::is_sorted(list.begin(), list.end()))
      std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    return list;
  };
  result.newVertices = sorted(std::move(context.newVertices));
  // Each rebound vertex once, marked in the (all -1) local-index scratch.
  std::vector<int>& seen = Workers.front().localIndex;
  if (seen.size() < Mesh.vertexCount())
    seen.resize(Mesh.vertexCount(), -1);
  result.reboundVertices.reserve(context.rebound.size() + result.newVertices.size());
  for (const std::vector<int>* list : { &context.rebound, &result.newVertices })
    for (int v : *list)
      if (seen[v] == -1)
      {
        seen[v] = -2;
        result.reboundVertices.push_back(v);
      }
  for (int v : result.reboundVertices)
    seen[v] = -1;
  noteBindingNodes(result.reboundVertices);
  result.changedTriangles = sorted(std::move(context.changedTriangles));
  while (!result.changedTriangles.empty() &&
         result.changedTriangles.back() >= static_cast<int>(Mesh.triangleCount()))
    result.changedTriangles.pop_back();
  return result;
}

} // namespace thintissue
