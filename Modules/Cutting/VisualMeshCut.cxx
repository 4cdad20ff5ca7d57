#include "VisualMeshCut.h"

#include "PathRemeshing.h"
#include "SplitFormula.h"
#include "VisualMeshCutPrivate.h"

#include "ReservedVector.h"

#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_set>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace thintissue
{

namespace
{

constexpr double CutEndMargin = 1e-7; ///< of the cut's length
constexpr double PathSnap =
  1e-3; ///< of a visual edge: a cut this near a path vertex goes through it
constexpr double BorderClearance = 1e-6; ///< of a visual edge, off the border

/// The region triangles as a mesh of their own, with the maps back.
struct LocalMesh
{
  TriangleMesh mesh;
  std::vector<int> globalVertex;
  std::vector<int> globalTexture;
  std::vector<int> globalTriangle;
};

/// `localVertex` (per vertex of `mesh`) and `localTexture` (per texture
/// coordinate) come all -1 and are grown as needed; `localVertex` returns
/// with the local index of each vertex of `local.globalVertex` (the caller
/// resets those), `localTexture` all -1 again.
void extractTriangles(const TriangleMesh& mesh,
  const std::vector<int>& triangles,
  std::vector<int>& localVertex,
  std::vector<int>& localTexture,
  LocalMesh& local)
{
  local.mesh.name = mesh.name;
  const std::vector<std::string> names = mesh.pointAttributes.names();
  std::vector<std::vector<double>> attributes(names.size());
  // Room for a patch's vertices (about half its triangles, plus its rim).
  const std::size_t vertices = triangles.size() + 16;
  if (localVertex.size() < mesh.vertexCount())
    localVertex.resize(mesh.vertexCount() + mesh.vertexCount() / 4, -1);
  if (localTexture.size() < mesh.textureCoordinates.size())
    localTexture.resize(mesh.textureCoordinates.size() + mesh.textureCoordinates.size() / 4, -1);
  local.globalVertex.reserve(vertices);
  local.mesh.positions.reserve(vertices);
  if (mesh.hasNormals())
    local.mesh.normals.reserve(vertices);
  local.mesh.triangles.reserve(triangles.size());
  local.globalTriangle.reserve(triangles.size());
  for (std::size_t a = 0; a < names.size(); ++a)
    attributes[a].reserve(vertices * mesh.pointAttributes.get(names[a]).components);
  for (int t : triangles)
  {
    Triangle corners{};
    Triangle textures{};
    for (int k = 0; k < 3; ++k)
    {
      const int v = mesh.triangles[t][k];
      if (localVertex[v] < 0)
      {
        localVertex[v] = static_cast<int>(local.globalVertex.size());
        local.globalVertex.push_back(v);
        local.mesh.positions.push_back(mesh.positions[v]);
        if (mesh.hasNormals())
          local.mesh.normals.push_back(mesh.normals[v]);
        for (std::size_t a = 0; a < names.size(); ++a)
        {
          const AttributeArray& array = mesh.pointAttributes.get(names[a]);
          attributes[a].insert(
            attributes[a].end(), array.element(v), array.element(v) + array.components);
        }
      }
      corners[k] = localVertex[v];
      if (mesh.hasTextureCoordinates())
      {
        const int c = mesh.textureCorners[t][k];
        if (localTexture[c] < 0)
        {
          localTexture[c] = static_cast<int>(local.globalTexture.size());
          local.globalTexture.push_back(c);
          local.mesh.textureCoordinates.push_back(mesh.textureCoordinates[c]);
        }
        textures[k] = localTexture[c];
      }
    }
    local.mesh.triangles.push_back(corners);
    if (mesh.hasTextureCoordinates())
      local.mesh.textureCorners.push_back(textures);
    local.globalTriangle.push_back(t);
  }
  for (int c : local.globalTexture)
    localTexture[c] = -1;
  for (std::size_t a = 0; a < names.size(); ++a)
  {
    local.mesh.pointAttributes.set(
      names[a], mesh.pointAttributes.get(names[a]).components, std::move(attributes[a]));
  }
}

/// Tutte's embedding of a region: border vertices at their (bulged)
/// parameters, inner vertices each at the average of its neighbours. With
/// a strictly convex border no triangle folds or flattens. Local vertex
/// indices (RegionCut).
std::vector<Vector2> tutteEmbedding(const std::vector<Vector3>& parameters,
  const std::vector<Triangle>& triangles,
  const std::vector<char>& isInner,
  const std::array<Vector2, 3>& frame)
{
  const std::size_t count = parameters.size();
  std::vector<Vector2> planar(count, Vector2::Zero());
  std::vector<int> innerIndex(count, -1);
  std::vector<int> innerVertices;
  for (std::size_t v = 0; v < count; ++v)
  {
    if (isInner[v])
    {
      innerIndex[v] = static_cast<int>(innerVertices.size());
      innerVertices.push_back(static_cast<int>(v));
    }
    else
      planar[v] = bulgedPoint(frame, parameters[v]);
  }
  if (innerVertices.empty())
    return planar;
  std::vector<std::vector<int>> neighbours(innerVertices.size());
  for (const Triangle& tri : triangles)
    for (int k = 0; k < 3; ++k)
    {
      const int i = innerIndex[tri[k]];
      if (i < 0)
        continue;
      for (int w : { tri[(k + 1) % 3], tri[(k + 2) % 3] })
        if (std::find(neighbours[i].begin(), neighbours[i].end(), w) == neighbours[i].end())
          neighbours[i].push_back(w);
    }
  const int n = static_cast<int>(innerVertices.size());
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(n, 2);
  for (int i = 0; i < n; ++i)
  {
    entries.emplace_back(i, i, static_cast<double>(neighbours[i].size()));
    for (int w : neighbours[i])
    {
      if (innerIndex[w] >= 0)
        entries.emplace_back(i, innerIndex[w], -1.0);
      else
        rhs.row(i) += planar[w].transpose();
    }
  }
  Eigen::SparseMatrix<double> laplacian(n, n);
  laplacian.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(laplacian);
  const Eigen::MatrixX2d x = solver.solve(rhs);
  for (int i = 0; i < n; ++i)
    planar[innerVertices[i]] = x.row(i).transpose();
  return planar;
}

double cross2(const Vector2& a, const Vector2& b)
{
  return a.x() * b.y() - a.y() * b.x();
}

/// Triangles whose orientation in the plane differs from the region's.
std::vector<int> foldedTriangles(const std::vector<Vector2>& planar,
  const std::vector<Triangle>& triangles)
{
  auto area = [&](const Triangle& t)
  { return cross2(planar[t[1]] - planar[t[0]], planar[t[2]] - planar[t[0]]); };
  double total = 0.0;
  double smallest = std::numeric_limits<double>::infinity();
  double largest = -smallest;
  for (const Triangle& t : triangles)
  {
    const double a = area(t);
    total += a;
    smallest = std::min(smallest, a);
    largest = std::max(largest, a);
  }
  std::vector<int> folded;
  // Rounded products keep the order of their factors: if neither extreme
  // has a product <= 0 with the total, no area has (the usual case, one
  // pass).
  if (smallest * total > 0.0 && largest * total > 0.0)
    return folded;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (area(triangles[t]) * total <= 0.0)
      folded.push_back(static_cast<int>(t));
  return folded;
}

/// The plane a region is cut in (5.3.2): each vertex at its binding
/// parameters in the triangle's 2D frame (formula 5-1), the border bulged.
/// Where the binding's parameterisation folds (rare, on curved tissue) the
/// inner vertices around the fold are moved to the average of their
/// neighbours until it unfolds (Tutte's embedding of the whole region if
/// that does not do); every other vertex stays where its binding puts it.
/// Local vertex indices (RegionCut). `foldFree`: no repair was needed.
std::vector<Vector2> regionPlane(const std::vector<Vector3>& parameters,
  const std::vector<Triangle>& triangles,
  const std::vector<char>& isInner,
  const std::array<Vector2, 3>& frame,
  bool& foldFree)
{
  const std::size_t count = parameters.size();
  std::vector<Vector2> planar(count);
  for (std::size_t v = 0; v < count; ++v)
    planar[v] = bulgedPoint(frame, parameters[v]);
  for (int round = 0; round < 32; ++round)
  {
    const std::vector<int> folded = foldedTriangles(planar, triangles);
    foldFree = round == 0 && folded.empty();
    if (folded.empty())
      return planar;
    std::vector<char> moving(count, 0);
    for (int t : folded)
      for (int v : triangles[t])
        moving[v] = isInner[v];
    std::vector<Vector2> sums(count, Vector2::Zero());
    std::vector<int> neighbourCount(count, 0);
    for (const Triangle& t : triangles)
      for (int k = 0; k < 3; ++k)
        if (moving[t[k]])
          for (int w : { t[(k + 1) % 3], t[(k + 2) % 3] })
          {
            sums[t[k]] += planar[w];
            ++neighbourCount[t[k]];
          }
    for (std::size_t v = 0; v < count; ++v)
      if (neighbourCount[v] > 0)
        planar[v] = sums[v] / neighbourCount[v];
  }
  return foldedTriangles(planar, triangles).empty()
           ? planar
           : tutteEmbedding(parameters, triangles, isInner, frame);
}

/// The traced path: a walk from node 0 (the cut's start) to node 1 (its
/// end) through the links the crossed triangles make (per node, the nodes
/// linked to it: targets[offsets[n]] to targets[offsets[n + 1] - 1], in the
/// order made). A fold in the region's parameterisation (rare) makes the
/// order along the line differ from the order through the mesh, and the
/// mesh order is the one that makes a path. False if the walk loses its
/// way.
template <typename Node>
bool walkCut(const std::vector<Node>& nodes,
  const std::vector<int>& offsets,
  const std::vector<int>& targets,
  std::vector<char>& visited,
  SurfacePath& traced)
{
  traced.points.clear();
  visited.assign(nodes.size(), 0);
  int current = 0;
  visited[0] = 1;
  traced.points.push_back(nodes[0].point);
  while (current != 1)
  {
    int next = -1;
    for (int j = offsets[current]; j < offsets[current + 1]; ++j)
    {
      const int candidate = targets[j];
      if (visited[candidate] || next == 1)
        continue;
      if (next < 0 || candidate == 1 || nodes[candidate].s < nodes[next].s)
        next = candidate;
    }
    if (next < 0)
      return false;
    visited[next] = 1;
    traced.points.push_back(nodes[next].point);
    current = next;
  }
  return true;
}

/// Links (from, to) grouped by their first node, in the order made
/// (compressed rows: offsets per node, then targets).
void groupLinks(const std::vector<std::pair<int, int>>& links,
  std::size_t nodeCount,
  std::vector<int>& offsets,
  std::vector<int>& targets)
{
  offsets.assign(nodeCount + 1, 0);
  for (const auto& link : links)
    ++offsets[link.first + 1];
  for (std::size_t n = 0; n < nodeCount; ++n)
    offsets[n + 1] += offsets[n];
  targets.resize(links.size());
  for (const auto& link : links)
    targets[offsets[link.first]++] = link.second;
  for (std::size_t n = nodeCount; n > 0; --n)
    offsets[n] = offsets[n - 1];
  offsets[0] = 0;
}

/// Whether the segment between two points given in a triangle's
/// barycentric coordinates runs along one of its sides.
bool alongParentSide(const Vector3& p, const Vector3& q)
{
  return (p[0] == 0.0 && q[0] == 0.0) || (p[1] == 0.0 && q[1] == 0.0) ||
         (p[2] == 0.0 && q[2] == 0.0);
}

int cornerIndex(const Vector3& barycentric)
{
  for (int k = 0; k < 3; ++k)
  {
    if (barycentric[k] == 1.0)
      return k;
  }
  return -1;
}

} // namespace

//------------------------------------------------------------------------------
namespace
{

void checkSettings(const std::string& label, const VisualCutSettings& settings)
{
  if (settings.cutSurfaceRows < 0)
  {
    throw InvalidInputError(
      label + ": cut surface rows " + std::to_string(settings.cutSurfaceRows) + " (must be >= 0)");
  }
  if (!(settings.jaggedAmplitude >= 0.0 && settings.jaggedWavelength > 0.0) ||
      !std::isfinite(settings.jaggedAmplitude + settings.jaggedWavelength))
  {
    throw InvalidInputError(label + ": jagged cut surface amplitude " +
                            std::to_string(settings.jaggedAmplitude) + " and wavelength " +
                            std::to_string(settings.jaggedWavelength) +
                            " (must be >= 0 and > 0, finite)");
  }
}

} // namespace

CuttableVisualMesh::CuttableVisualMesh(const VisualCollisionBinding& binding,
  const VisualCutSettings& settings)
  : Settings(settings)
  , Mesh(binding.visual)
  , Bindings(binding.vertices)
  , Edges(binding.collisionEdges)
  , TriangleRegion(binding.triangleRegion)
  , TriangleSide(binding.triangleSide)
{
  const std::string label = "visual mesh '" + Mesh.name + "'";
  checkSettings(label, settings);
  const std::size_t collisionVertices = binding.collisionPositions.size();
  if (Bindings.size() != Mesh.vertexCount() || TriangleRegion.size() != Mesh.triangleCount() ||
      TriangleSide.size() != Mesh.triangleCount() ||
      binding.pairedVisualVertices.size() != collisionVertices ||
      (!binding.creaseVisualVertices.empty() &&
        binding.creaseVisualVertices.size() != collisionVertices))
  {
    throw InvalidInputError(label + ": the binding does not match its visual mesh");
  }
  TriangleMaterial.assign(Mesh.triangleCount(), VisualMaterial::Surface);
  // Before any cut, node t is collision triangle t.
  BindingNodes.resize(Bindings.size());
  for (std::size_t v = 0; v < Bindings.size(); ++v)
    BindingNodes[v] = Bindings[v].kind == BindingKind::CollisionTriangle ? Bindings[v].element : -1;
  reserveRoom();
  // The binding pairs (+, -); here slots are - then +, as paths, then the
  // crease's.
  Paired.resize(collisionVertices);
  for (std::size_t v = 0; v < collisionVertices; ++v)
  {
    const auto& pair = binding.pairedVisualVertices[v];
    const int crease = binding.creaseVisualVertices.empty() ? -1 : binding.creaseVisualVertices[v];
    Paired[v] = { { pair[1], pair[0], crease } };
  }
  for (std::size_t e = 0; e < Edges.size(); ++e)
  {
    EdgeIndex.emplace(edgeKey(Edges[e][0], Edges[e][1]), static_cast<int>(e));
  }
  Regions.resize(binding.collisionTriangles.size());
  SplitHistory = CollisionSplitHistory(binding.collisionTriangles.size());
  for (std::size_t t = 0; t < TriangleRegion.size(); ++t)
  {
    const int region = TriangleRegion[t];
    if (region < 0 || region >= static_cast<int>(Regions.size()) || TriangleSide[t] == 0)
    {
      throw InvalidInputError(label + ": triangle " + std::to_string(t) + " has no region");
    }
    Regions[region][TriangleSide[t] > 0 ? 1 : 0].push_back(static_cast<int>(t));
  }
  // A path of side 0 is a border edge's rim path, or the crease path of a
  // junction edge (which also has a + and a - path).
  for (const bool sided : { true, false })
  {
    for (const BindingPath& p : binding.paths)
    {
      if ((p.side != 0) != sided)
        continue;
      const auto& e = binding.collisionEdges[p.collisionEdge];
      EdgePaths& paths = Paths[edgeKey(e[0], e[1])];
      if (p.side != 0)
        paths.sides[p.side > 0 ? 1 : 0] = p.visualVertices;
      else if (!paths.sides[0].empty() || !paths.sides[1].empty())
        paths.sides[CreaseSlot] = p.visualVertices;
      else
      {
        paths.rim = true;
        paths.sides[0] = paths.sides[1] = p.visualVertices;
      }
    }
  }
  HasJunctions = std::any_of(
    Paths.begin(), Paths.end(), [](const auto& entry) { return entry.second.junction(); });
}

bool CuttableVisualMesh::facesCleft(const CuttableCollisionMesh& collision, int T, int side)
{
  // halves() slots are + then -; a side index here is - then +.
  return collision.halves()[T][side > 0 ? 0 : 1] == SurfaceHalf::Cleft;
}

void CuttableVisualMesh::setSettings(const VisualCutSettings& settings)
{
  const std::string label = "visual mesh '" + Mesh.name + "'";
  checkSettings(label, settings);
  if (settings.cutSurfaceRows != Settings.cutSurfaceRows &&
      (!Strips.empty() || !EndColumns.empty()))
  {
    throw InvalidInputError(label + ": cut surface rows cannot change from " +
                            std::to_string(Settings.cutSurfaceRows) + " to " +
                            std::to_string(settings.cutSurfaceRows) +
                            " once the tissue is cut (its cut surfaces meet the new ones)");
  }
  Settings = settings;
}

void CuttableVisualMesh::reserveRoom()
{
  // Cuts append vertices and triangles: room for a quarter more up front,
  // so that the first cuts do not copy the whole mesh to grow it, with its
  // pages touched now rather than by the cuts (reserveTouched).
  const std::size_t vertices = Mesh.vertexCount() + Mesh.vertexCount() / 4 + 64;
  const std::size_t triangles = Mesh.triangleCount() + Mesh.triangleCount() / 4 + 64;
  reserveTouched(Mesh.positions, vertices, Vector3::Zero().eval());
  if (Mesh.hasNormals())
    reserveTouched(Mesh.normals, vertices, Vector3::Zero().eval());
  reserveTouched(Bindings, vertices);
  reserveTouched(BindingNodes, vertices);
  // Point attributes and texture coordinates too: growing one of them in a
  // cut copied it into fresh pages (on the 1M-triangle sheet, 2,000 page
  // faults, three quarters of the cut).
  for (const std::string& name : Mesh.pointAttributes.names())
  {
    AttributeArray& array = Mesh.pointAttributes.get(name);
    reserveTouched(array.values, vertices * static_cast<std::size_t>(array.components));
  }
  const std::size_t textures = Mesh.textureCoordinates.size();
  reserveTouched(Mesh.textureCoordinates, textures + textures / 4 + 64, Vector2::Zero().eval());
  reserveTouched(Mesh.triangles, triangles);
  if (Mesh.hasTextureCoordinates())
    reserveTouched(Mesh.textureCorners, triangles);
  reserveTouched(TriangleRegion, triangles);
  reserveTouched(TriangleSide, triangles);
  reserveTouched(TriangleMaterial, triangles);
  // The per-vertex scratch at its full size now, for every worker a cut of
  // this mesh may use: grown (and its pages first touched) during the first
  // cut, it had cost that cut a copy of the mesh's size.
  if (Mesh.triangleCount() >= Settings.parallelRegionTriangles)
    Workers.resize(static_cast<std::size_t>(
      std::clamp(tbb::this_task_arena::max_concurrency(), 1, MaxRegionWorkers)));
  for (RegionWorker& worker : Workers)
  {
    worker.localIndex.assign(vertices, -1);
    worker.vertexCells.assign(vertices, 0);
  }
  Workers.front().buffers.localTexture.assign(
    Mesh.textureCoordinates.size() + Mesh.textureCoordinates.size() / 4, -1);
}

int CuttableVisualMesh::edgeIndex(int a, int b)
{
  // Looked up first: emplace makes a node even for a key it has.
  const std::uint64_t key = edgeKey(a, b);
  const auto found = EdgeIndex.find(key);
  if (found != EdgeIndex.end())
    return found->second;
  EdgeIndex.emplace(key, static_cast<int>(Edges.size()));
  Edges.push_back({ { std::min(a, b), std::max(a, b) } });
  return static_cast<int>(Edges.size()) - 1;
}

int CuttableVisualMesh::addVertexCopy(int source)
{
  const int v = static_cast<int>(Mesh.positions.size());
  Mesh.positions.push_back(Mesh.positions[source]);
  if (Mesh.hasNormals())
    Mesh.normals.push_back(Mesh.normals[source]);
  Mesh.pointAttributes.appendCopyOf(source);
  Bindings.push_back(Bindings[source]);
  BindingNodes.push_back(BindingNodes[source]);
  return v;
}

int CuttableVisualMesh::addTriangle(const Triangle& corners,
  int region,
  int side,
  VisualMaterial material)
{
  int t = -1;
  if (!FreeTriangles.empty())
  {
    t = FreeTriangles.back();
    FreeTriangles.pop_back();
    Mesh.triangles[t] = corners;
  }
  else
  {
    t = static_cast<int>(Mesh.triangles.size());
    Mesh.triangles.push_back(corners);
    if (Mesh.hasTextureCoordinates())
      Mesh.textureCorners.push_back({ { 0, 0, 0 } });
    TriangleRegion.push_back(-1);
    TriangleSide.push_back(0);
    TriangleMaterial.push_back(material);
  }
  TriangleRegion[t] = region;
  TriangleSide[t] = static_cast<std::int8_t>(side);
  TriangleMaterial[t] = material;
  if (side != 0)
    Regions[region][side > 0 ? 1 : 0].push_back(t);
  return t;
}

void CuttableVisualMesh::freeTriangle(int t)
{
  Mesh.triangles[t] = { { -1, -1, -1 } };
  FreeTriangles.push_back(t);
}

void CuttableVisualMesh::compactTriangles()
{
  // Holes left by strips that shrank: the last triangles move into them.
  std::sort(FreeTriangles.begin(), FreeTriangles.end());
  while (!FreeTriangles.empty())
  {
    const int last = static_cast<int>(Mesh.triangles.size()) - 1;
    if (FreeTriangles.back() == last)
    {
      FreeTriangles.pop_back();
    }
    else
    {
      const int hole = FreeTriangles.front();
      FreeTriangles.erase(FreeTriangles.begin());
      Mesh.triangles[hole] = Mesh.triangles[last];
      if (Mesh.hasTextureCoordinates())
        Mesh.textureCorners[hole] = Mesh.textureCorners[last];
      TriangleRegion[hole] = TriangleRegion[last];
      TriangleSide[hole] = TriangleSide[last];
      TriangleMaterial[hole] = TriangleMaterial[last];
      auto replaceIn = [&](std::vector<int>& list)
      { std::replace(list.begin(), list.end(), last, hole); };
      if (TriangleSide[last] != 0)
        replaceIn(Regions[TriangleRegion[last]][TriangleSide[last] > 0 ? 1 : 0]);
      else
        for (auto& [key, strip] : Strips)
          replaceIn(strip.triangles);
    }
    Mesh.triangles.pop_back();
    if (Mesh.hasTextureCoordinates())
      Mesh.textureCorners.pop_back();
    TriangleRegion.pop_back();
    TriangleSide.pop_back();
    TriangleMaterial.pop_back();
  }
}

double CuttableVisualMesh::edgeParameter(int v, int a, int b) const
{
  const VisualVertexBinding& binding = Bindings[v];
  if (binding.kind == BindingKind::CollisionVertex &&
      (binding.element == a || binding.element == b))
    return binding.element == a ? 0.0 : 1.0;
  if (binding.kind == BindingKind::CollisionEdge && Edges[binding.element][0] == std::min(a, b) &&
      Edges[binding.element][1] == std::max(a, b))
    return a < b ? binding.parameters[1] : binding.parameters[0];
  throw InvalidInputError("visual mesh '" + Mesh.name + "': vertex " + std::to_string(v) +
                          " is not bound to collision edge (" + std::to_string(a) + ", " +
                          std::to_string(b) + ")");
}

bool CuttableVisualMesh::boundToEdge(int v, int a, int b) const
{
  const VisualVertexBinding& binding = Bindings[v];
  if (binding.kind == BindingKind::CollisionVertex)
    return binding.element == a || binding.element == b;
  return binding.kind == BindingKind::CollisionEdge &&
         edgeKey(Edges[binding.element][0], Edges[binding.element][1]) == edgeKey(a, b);
}

std::vector<double> CuttableVisualMesh::pathParameters(const std::vector<int>& path,
  int a,
  int b) const
{
  // Vertices bound to the edge (or its ends) carry their parameter; a
  // vertex of a segment this path shares with another edge's path (the
  // binding lets paths touch) is bound to that edge: it gets the parameter
  // its accumulated length puts it at between its bound neighbours.
  std::vector<double> at(path.size(), -1.0);
  std::vector<double> length(path.size(), 0.0);
  for (std::size_t i = 0; i < path.size(); ++i)
  {
    if (i > 0)
      length[i] = length[i - 1] + (Mesh.positions[path[i]] - Mesh.positions[path[i - 1]]).norm();
    if (boundToEdge(path[i], a, b))
      at[i] = edgeParameter(path[i], a, b);
  }
  at.front() = std::max(at.front(), 0.0);
  at.back() = at.back() < 0.0 ? 1.0 : at.back();
  for (std::size_t i = 1; i + 1 < path.size(); ++i)
  {
    if (at[i] >= 0.0)
      continue;
    std::size_t next = i + 1;
    while (at[next] < 0.0)
      ++next;
    const double span = length[next] - length[i - 1];
    const double s = span > 0.0 ? (length[i] - length[i - 1]) / span : 0.5;
    at[i] = at[i - 1] + s * (at[next] - at[i - 1]);
  }
  return at;
}

void CuttableVisualMesh::bindToEdge(int v, int a, int b, double fromA, int side)
{
  VisualVertexBinding& binding = Bindings[v];
  binding.kind = BindingKind::CollisionEdge;
  binding.element = edgeIndex(a, b);
  binding.side = side;
  const double t = a < b ? fromA : 1.0 - fromA;
  binding.parameters = Vector3(1.0 - t, t, 0.0);
}

Vector3 CuttableVisualMesh::parametersIn(int v, int triangle, const Triangle& corners) const
{
  const VisualVertexBinding b = binding(v);
  Vector3 result = Vector3::Zero();
  if (b.kind == BindingKind::CollisionTriangle && b.element == triangle)
    return b.parameters;
  for (int k = 0; k < 3; ++k)
  {
    if (b.kind == BindingKind::CollisionVertex && corners[k] == b.element)
    {
      result[k] = 1.0;
      return result;
    }
    const int next = corners[(k + 1) % 3];
    if (b.kind == BindingKind::CollisionEdge &&
        edgeKey(corners[k], next) == edgeKey(Edges[b.element][0], Edges[b.element][1]))
    {
      const double t = edgeParameter(v, corners[k], next);
      result[k] = 1.0 - t;
      result[(k + 1) % 3] = t;
      return result;
    }
  }
  // On a segment one of the triangle's paths shares with another edge's.
  for (int k = 0; k < 3; ++k)
  {
    const int from = corners[k], to = corners[(k + 1) % 3];
    const auto paths = Paths.find(edgeKey(from, to));
    if (paths == Paths.end())
      continue;
    for (const std::vector<int>& p : paths->second.sides)
    {
      const auto found = std::find(p.begin(), p.end(), v);
      if (found == p.end())
        continue;
      const double t = pathParameters(
        p, std::min(from, to), std::max(from, to))[static_cast<std::size_t>(found - p.begin())];
      const double fromStart = from < to ? t : 1.0 - t;
      result[k] = 1.0 - fromStart;
      result[(k + 1) % 3] = fromStart;
      return result;
    }
  }
  throw InvalidInputError("visual mesh '" + Mesh.name + "': vertex " + std::to_string(v) +
                          " is not bound to collision triangle " + std::to_string(triangle) +
                          " or one of its edges or corners");
}

std::vector<int> CuttableVisualMesh::path(int a, int b, int side) const
{
  const auto it = Paths.find(edgeKey(a, b));
  if (it == Paths.end())
    return {};
  return it->second.sides[side > 0 ? 1 : (side < 0 || !it->second.junction() ? 0 : CreaseSlot)];
}

bool CuttableVisualMesh::isRimEdge(int a, int b) const
{
  const auto it = Paths.find(edgeKey(a, b));
  return it != Paths.end() && it->second.rim;
}

std::size_t CuttableVisualMesh::cutSurfaceTriangleCount() const
{
  return static_cast<std::size_t>(
    std::count(TriangleMaterial.begin(), TriangleMaterial.end(), VisualMaterial::CutSurface));
}

VisualVertexBinding CuttableVisualMesh::resolvedBinding(int v, int* node) const
{
  VisualVertexBinding b = Bindings[v];
  const CollisionSplitHistory::Resolved resolved =
    SplitHistory.resolve(BindingNodes[v], b.parameters);
  b.element = SplitHistory.triangleOf(resolved.node);
  b.parameters = resolved.parameters;
  if (node)
    *node = resolved.node;
  return b;
}

void CuttableVisualMesh::resolveBinding(int v)
{
  if (!bindingIsCurrent(v))
    Bindings[v] = resolvedBinding(v, &BindingNodes[v]);
}

void CuttableVisualMesh::noteBindingNodes(const std::vector<int>& vertices)
{
  for (int v : vertices)
    BindingNodes[v] = Bindings[v].kind == BindingKind::CollisionTriangle
                        ? SplitHistory.currentNode(Bindings[v].element)
                        : -1;
}

int CuttableVisualMesh::collisionTriangleOf(int v, const CuttableCollisionMesh& collision) const
{
  const VisualVertexBinding& b = Bindings[v];
  switch (b.kind)
  {
    case BindingKind::CollisionTriangle:
      return bindingIsCurrent(v) ? b.element : resolvedBinding(v).element;
    case BindingKind::CollisionEdge:
      return collision.trianglesOfEdge(Edges[b.element][0], Edges[b.element][1])[0];
    case BindingKind::CollisionVertex:
    default:
      return collision.trianglesOfVertex(b.element).empty()
               ? -1
               : collision.trianglesOfVertex(b.element).front();
  }
}

//------------------------------------------------------------------------------
// 5.3.2, first half: where each split collision edge's paths are split.
void CuttableVisualMesh::splitEdgePaths(CutContext& context)
{
  for (const NewCollisionVertex& made : context.cut->newVertices)
  {
    if (made.duplicateOf >= 0)
      continue;
    EdgePoint point;
    point.vertex = made.vertex;
    point.a = std::min(made.edge[0], made.edge[1]);
    point.b = std::max(made.edge[0], made.edge[1]);
    point.u = made.edge[0] < made.edge[1] ? made.t : 1.0 - made.t;
    const auto found = Paths.find(edgeKey(point.a, point.b));
    if (found == Paths.end())
    {
      throw InvalidInputError("visual mesh '" + Mesh.name + "': collision edge (" +
                              std::to_string(point.a) + ", " + std::to_string(point.b) +
                              ") has no visual path");
    }
    point.rim = found->second.rim;
    point.junction = found->second.junction();
    for (int side = 0; side < point.slotCount(); ++side)
    {
      const std::vector<int>& p = found->second.sides[side];
      const std::vector<double> at = pathParameters(p, point.a, point.b);
      std::size_t i = 0;
      while (i + 2 < p.size() && at[i + 1] <= point.u)
        ++i;
      const double from = at[i];
      const double to = at[i + 1];
      double lambda = to > from ? (point.u - from) / (to - from) : 0.5;
      point.pathPosition[side] = static_cast<int>(i);
      if (lambda < PathSnap && i > 0)
        point.visual[side] = SurfacePoint::atVertex(p[i]);
      else if (lambda > 1.0 - PathSnap && i + 2 < p.size())
        point.visual[side] = SurfacePoint::atVertex(p[i + 1]);
      else
      {
        lambda = std::clamp(lambda, PathSnap, 1.0 - PathSnap);
        point.visual[side] = SurfacePoint::onEdge(p[i], p[i + 1], lambda);
      }
    }
    context.edgePointOf.emplace(made.vertex, static_cast<int>(context.edgePoints.size()));
    context.edgePoints.push_back(point);
  }
}

void CuttableVisualMesh::forEachRegion(CutContext& context,
  const std::function<void(RegionCut&, RegionWorker&)>& work)
{
  std::vector<RegionCut>& regions = context.regions;
  std::size_t triangles = 0;
  for (const RegionCut& region : regions)
    triangles += region.triangles.size() + region.far.size();
  const int workers = triangles < Settings.parallelRegionTriangles
                        ? 1
                        : std::min({ tbb::this_task_arena::max_concurrency(),
                            MaxRegionWorkers,
                            static_cast<int>(regions.size()) });
  while (static_cast<int>(Workers.size()) < workers)
    Workers.emplace_back().localIndex.assign(Workers.front().localIndex.size(), -1);
  auto run = [&](int w)
  {
    for (std::size_t r = static_cast<std::size_t>(w); r < regions.size(); r += workers)
    {
      try
      {
        work(regions[r], Workers[w]);
      }
      catch (...)
      {
        regions[r].error = std::current_exception();
      }
    }
  };
  // The serial stages' worker is among them (and may have moved): no
  // region stage uses it through the context meanwhile.
  context.worker = nullptr;
  if (workers == 1)
    run(0);
  else
    tbb::parallel_for(0, workers, run);
  context.worker = &Workers.front();
  for (const RegionCut& region : regions)
    if (region.error)
      std::rethrow_exception(region.error);
}

// 5.3.2, second half: each new edge across a split triangle, traced in the
// triangle's 2D frame through the visual edges of its region on each side
// (the regions on several workers: traceRegion).
void CuttableVisualMesh::traceRegionCuts(CutContext& context)
{
  const auto& rest = context.collision->restPositions();
  for (std::size_t s = 0; s < context.cut->splits.size(); ++s)
  {
    const CollisionTriangleSplit& split = context.cut->splits[s];
    // The pieces' edges that cross the parent (not along one of its sides).
    std::vector<CrossingPath> crossings;
    for (std::size_t c = 0; c < split.children.size(); ++c)
    {
      const Triangle& piece = context.collision->triangles()[split.children[c]];
      for (int k = 0; k < 3; ++k)
      {
        const Vector3& p = split.childCorners[c][k];
        const Vector3& q = split.childCorners[c][(k + 1) % 3];
        if (alongParentSide(p, q))
          continue;
        CrossingPath crossing;
        crossing.ends = { { context.root(piece[k]), context.root(piece[(k + 1) % 3]) } };
        crossing.barycentric = { { p, q } };
        if (crossing.ends[0] > crossing.ends[1])
        {
          std::swap(crossing.ends[0], crossing.ends[1]);
          std::swap(crossing.barycentric[0], crossing.barycentric[1]);
        }
        const auto same = std::find_if(crossings.begin(),
          crossings.end(),
          [&](const CrossingPath& other) { return other.ends == crossing.ends; });
        if (same != crossings.end())
          same->pieces[1] = static_cast<int>(c);
        else
        {
          crossing.pieces[0] = static_cast<int>(c);
          crossings.push_back(std::move(crossing));
        }
      }
    }
    for (int side = 0; side < 2; ++side)
    {
      RegionCut& region = context.regions.emplace_back();
      region.split = static_cast<int>(s);
      region.side = side;
      region.cleft = facesCleft(*context.collision, split.children.front(), side);
      region.triangles = Regions[split.parent][side];
      region.frame = planarFrame(rest, split.parentCorners);
      region.crossings = crossings;
    }
  }
  forEachRegion(context,
    [&](RegionCut& region, RegionWorker& worker) { traceRegion(region, worker, context); });
}

// One region: its local vertices and triangles, its plane, its traced cuts
// and the triangles they touch (it reads the visual mesh and binding only).
// Where most of it lies far from the cuts, only the triangles near them are
// laid out and traced (separateFarTriangles): a cut costs its line and a
// pass over the rest.
void CuttableVisualMesh::traceRegion(RegionCut& region,
  RegionWorker& worker,
  const CutContext& context)
{
  const CollisionTriangleSplit& split = context.cut->splits[region.split];
  const bool separated = Settings.piecesByLocation &&
                         region.triangles.size() >= Settings.separatedRegionTriangles &&
                         separateFarTriangles(region, worker, context);
  layOutRegion(region, worker, context);
  if (separated && !farTrianglesAgree(region))
  {
    // A fold (rare): the region is laid out and repaired whole.
    worker.deactivate(region);
    region.vertices.clear();
    region.parameters.clear();
    region.localTriangles.clear();
    region.far.clear();
    region.nearPositions.clear();
    region.triangles = Regions[split.parent][region.side];
    layOutRegion(region, worker, context);
  }
  const double scale = frameScale(region.frame);
  region.candidate.assign(region.triangles.size(), 0);
  const bool fits = split.childCorners.size() <= region.historyPieces.size();
  region.historyPieceCount = fits ? split.childCorners.size() : 0;
  for (std::size_t c = 0; c < split.childCorners.size(); ++c)
  {
    const auto& corners = split.childCorners[c];
    region.pieces.push_back({ { bulgedPoint(region.frame, corners[0]),
      bulgedPoint(region.frame, corners[1]),
      bulgedPoint(region.frame, corners[2]) } });
    if (fits)
      region.historyPieces[c] = planePiece({ { planarPoint(region.frame, corners[0]),
        planarPoint(region.frame, corners[1]),
        planarPoint(region.frame, corners[2]) } });
  }
  for (CrossingPath& crossing : region.crossings)
    traceCut(region, scale, crossing, worker, context);
  selectTouchedTriangles(region, worker);
  worker.deactivate(region);
}

Vector3 CuttableVisualMesh::parentParameters(int v, const CollisionTriangleSplit& split) const
{
  // Most are inner vertices, bound to the parent itself.
  const VisualVertexBinding& b = Bindings[v];
  return b.kind == BindingKind::CollisionTriangle && b.element == split.parent
           ? b.parameters
           : parametersIn(v, split.parent, split.parentCorners);
}

// The region's triangles (region.triangles) as local vertices and triangles
// (RegionWorker::localIndex), and its plane (regionPlane).
void CuttableVisualMesh::layOutRegion(RegionCut& region,
  RegionWorker& worker,
  const CutContext& context)
{
  const CollisionTriangleSplit& split = context.cut->splits[region.split];
  // A region has fewer vertices than triangles (plus its border).
  std::vector<Triangle>& triangles = region.localTriangles;
  triangles.reserve(region.triangles.size());
  region.vertices.reserve(region.triangles.size() + 64);
  region.parameters.reserve(region.triangles.size() + 64);
  for (int t : region.triangles)
  {
    Triangle local;
    for (int k = 0; k < 3; ++k)
    {
      const int v = Mesh.triangles[t][k];
      local[k] = worker.local(v);
      if (local[k] >= 0)
        continue;
      local[k] = static_cast<int>(region.vertices.size());
      worker.addToActive(region, v, parentParameters(v, split), Vector2::Zero());
    }
    triangles.push_back(local);
  }
  // Room for the vertices the re-meshing adds (a reallocation would copy
  // the whole region).
  const std::size_t room = region.vertices.size() + 64 + region.vertices.size() / 8;
  region.vertices.reserve(room);
  region.parameters.reserve(room);
  std::vector<char> isInner(region.vertices.size());
  for (std::size_t i = 0; i < region.vertices.size(); ++i)
    isInner[i] = Bindings[region.vertices[i]].kind == BindingKind::CollisionTriangle;
  region.planar = regionPlane(region.parameters, triangles, isInner, region.frame, region.foldFree);
  region.planar.reserve(room);
}

// The lines the region's cuts will be traced along (CrossingPath::planar):
// traceCut's, from the same feature points in the same plane, before the
// region is laid out. A cut from a collision corner starts at the corner's
// paired visual vertex: `pairedEnds` gets those, which must be in the
// region (featurePoint looks elsewhere otherwise). False where a corner
// has no paired vertex or there are more crossings than a locator takes.
bool CuttableVisualMesh::crossingLines(RegionCut& region,
  const CutContext& context,
  std::vector<int>& pairedEnds) const
{
  const CollisionTriangleSplit& split = context.cut->splits[region.split];
  if (region.crossings.size() > PieceLocator::MaxLines)
    return false;
  auto planarOf = [&](int v) { return bulgedPoint(region.frame, parentParameters(v, split)); };
  for (CrossingPath& crossing : region.crossings)
  {
    for (int end = 0; end < 2; ++end)
    {
      const int vertex = crossing.ends[end];
      SurfacePoint p;
      if (cornerIndex(crossing.barycentric[end]) < 0)
      {
        const EdgePoint& edgePoint = context.edgePoints[context.edgePointOf.at(vertex)];
        p = edgePoint.visual[edgePoint.junction ? region.junctionSlot() : region.side];
      }
      else
      {
        const int paired = Paired[vertex][pairedSlot(vertex, region.side, region.cleft)];
        if (paired < 0)
          return false;
        pairedEnds.push_back(paired);
        p = SurfacePoint::atVertex(paired);
      }
      crossing.planar[end] = p.isVertex()
                               ? planarOf(p.vertex)
                               : Vector2((1.0 - p.edgeParameter) * planarOf(p.edgeStart) +
                                         p.edgeParameter * planarOf(p.edgeEnd));
    }
  }
  return true;
}

// The far triangles of a region (RegionCut::far), found before it is laid
// out along the lines its cuts will be traced on (crossingLines), so that
// they are exactly the triangles traceCut would pass by and locatePieces
// would place: three corners in one cell, each an inner vertex strictly
// inside the parent (border vertices are bulged) beyond twice the on-line
// tolerance of every line (traceCut's own distances, rounded otherwise,
// still put it off the line). False, nothing separated, where the lines or
// pieces are degenerate, a cut starts at a vertex outside the region, the
// far triangles' orientations differ, or nothing lies far.
bool CuttableVisualMesh::separateFarTriangles(RegionCut& region,
  RegionWorker& worker,
  const CutContext& context) const
{
  const CollisionTriangleSplit& split = context.cut->splits[region.split];
  std::vector<int> pairedEnds;
  const double tolerance = OnLineTolerance * frameScale(region.frame);
  PieceLocator locator;
  if (!crossingLines(region, context, pairedEnds) ||
      !pieceLocator(region, split, tolerance, locator))
    return false;
  locator.expressInParameters(region.frame);
  // Each vertex's cell once: kept + 1 in `cells` (all 0 between regions)
  // until the pass ends; -1 for a vertex that is not far.
  std::vector<std::int8_t>& cells = worker.vertexCells;
  if (cells.size() < Mesh.vertexCount())
    cells.resize(Mesh.vertexCount(), 0);
  std::vector<int>& seen = worker.buffers.cellVertices;
  seen.clear();
  auto cellOf = [&](int v)
  {
    if (cells[v] == 0)
    {
      const VisualVertexBinding& b = Bindings[v];
      const bool inner = b.kind == BindingKind::CollisionTriangle && b.element == split.parent &&
                         b.parameters.minCoeff() > 0.0;
      cells[v] =
        static_cast<std::int8_t>(1 + (inner ? locator.cellOf(b.parameters, 2.0 * tolerance) : -1));
      seen.push_back(v);
    }
    return cells[v] - 1;
  };
  std::vector<int> near;
  near.reserve(region.triangles.size() / 4 + 16);
  region.nearPositions.clear();
  region.nearPositions.reserve(near.capacity());
  region.far.clear();
  region.far.reserve(region.triangles.size());
  // The frame's sides turn counterclockwise (planarFrame): the areas of
  // the parameters' last two coordinates have the signs of the plane's.
  double smallestArea = std::numeric_limits<double>::infinity();
  double largestArea = -smallestArea;
  for (std::size_t i = 0; i < region.triangles.size(); ++i)
  {
    const Triangle& corners = Mesh.triangles[region.triangles[i]];
    const int cell = cellOf(corners[0]);
    const int piece = cell >= 0 && cellOf(corners[1]) == cell && cellOf(corners[2]) == cell
                        ? locator.pieceOfSides[cell]
                        : -1;
    if (piece < 0)
    {
      near.push_back(region.triangles[i]);
      region.nearPositions.push_back(static_cast<int>(i));
      continue;
    }
    const Vector3& x0 = Bindings[corners[0]].parameters;
    const Vector3& x1 = Bindings[corners[1]].parameters;
    const Vector3& x2 = Bindings[corners[2]].parameters;
    const double area = (x1[1] - x0[1]) * (x2[2] - x0[2]) - (x1[2] - x0[2]) * (x2[1] - x0[1]);
    smallestArea = std::min(smallestArea, area);
    largestArea = std::max(largestArea, area);
    region.far.push_back({ region.triangles[i], piece, static_cast<int>(i) });
  }
  for (int v : seen)
    cells[v] = 0;
  const bool endsNear = std::all_of(pairedEnds.begin(),
    pairedEnds.end(),
    [&](int paired)
    {
      return std::any_of(near.begin(),
        near.end(),
        [&](int t)
        {
          const Triangle& c = Mesh.triangles[t];
          return c[0] == paired || c[1] == paired || c[2] == paired;
        });
    });
  if (region.far.empty() || !endsNear || !(smallestArea * largestArea > 0.0))
  {
    region.far.clear();
    region.nearPositions.clear();
    return false;
  }
  region.farOrientation = largestArea > 0.0 ? 1.0 : -1.0;
  region.triangles = std::move(near);
  return true;
}

bool CuttableVisualMesh::farTrianglesAgree(const RegionCut& region) const
{
  if (!region.foldFree)
    return false;
  double total = 0.0;
  for (const Triangle& t : region.localTriangles)
    total +=
      cross2(region.planar[t[1]] - region.planar[t[0]], region.planar[t[2]] - region.planar[t[0]]);
  return total * region.farOrientation > 0.0;
}

SurfacePoint CuttableVisualMesh::featurePoint(const RegionCut& region,
  int vertex,
  const Vector3& barycentric,
  const RegionWorker& worker,
  const CutContext& context) const
{
  const int corner = cornerIndex(barycentric);
  if (corner < 0)
  {
    const EdgePoint& point = context.edgePoints[context.edgePointOf.at(vertex)];
    return point.visual[point.junction ? region.junctionSlot() : region.side];
  }
  const int paired = Paired[vertex][pairedSlot(vertex, region.side, region.cleft)];
  if (worker.local(paired) >= 0)
    return SurfacePoint::atVertex(paired);
  // The paths from this corner share their first segment with another
  // edge's path (a touch the binding could not undo), so the region starts
  // where they part: at its vertex nearest the corner.
  if (region.vertices.empty())
    throw Error("visual cut of '" + Mesh.name + "': an empty region");
  std::size_t nearest = 0;
  for (std::size_t i = 1; i < region.parameters.size(); ++i)
    if (region.parameters[i][corner] > region.parameters[nearest][corner])
      nearest = i;
  return SurfacePoint::atVertex(region.vertices[nearest]);
}

void CuttableVisualMesh::traceCut(RegionCut& region,
  double scale,
  CrossingPath& crossing,
  RegionWorker& worker,
  const CutContext& context)
{
  // The region is active (RegionWorker::localIndex): its vertices' planar
  // points, signed distances and nodes are dense arrays (its buffers).
  auto localOf = [&](int v)
  {
    const int i = worker.local(v);
    if (i < 0)
      throw Error("visual cut of '" + Mesh.name + "': the cut from collision vertex " +
                  std::to_string(crossing.ends[0]) + " to " + std::to_string(crossing.ends[1]) +
                  " starts or ends at visual vertex " + std::to_string(v) +
                  ", outside its region on side " + std::to_string(region.side));
    return i;
  };
  auto pointOf = [&](const SurfacePoint& p) -> Vector2
  {
    return p.isVertex() ? region.planar[localOf(p.vertex)]
                        : Vector2((1.0 - p.edgeParameter) * region.planar[localOf(p.edgeStart)] +
                                  p.edgeParameter * region.planar[localOf(p.edgeEnd)]);
  };
  const SurfacePoint start =
    featurePoint(region, crossing.ends[0], crossing.barycentric[0], worker, context);
  const SurfacePoint end =
    featurePoint(region, crossing.ends[1], crossing.barycentric[1], worker, context);
  const Vector2 from = pointOf(start);
  const Vector2 along = pointOf(end) - from;
  crossing.planar = { { from, pointOf(end) } };
  const double length = along.norm();
  const double tolerance = OnLineTolerance * scale;
  // Crossing points: nodes 0 and 1 are the cut's ends, then vertices within
  // a round-off of the line and points inside edges whose ends lie apart.
  CutBuffers& buffers = worker.buffers;
  buffers.nodes.clear();
  buffers.nodes.push_back({ 0.0, start });
  buffers.nodes.push_back({ 1.0, end });
  const std::size_t count = region.vertices.size();
  buffers.signedDistance.resize(count);
  buffers.lineSide.resize(count);
  buffers.vertexNode.assign(count, -1);
  buffers.edgeHead.assign(count, -1);
  buffers.edgeEntries.clear();
  for (int n = 0; n < 2; ++n)
  {
    const SurfacePoint& p = buffers.nodes[n].point;
    if (p.isVertex())
      buffers.vertexNode[localOf(p.vertex)] = n;
    else
      buffers.addEdgeNode(localOf(p.edgeStart), localOf(p.edgeEnd), n);
  }
  for (std::size_t i = 0; i < count; ++i)
  {
    const Vector2 x = region.planar[i] - from;
    const double d = cross2(along, x) / length;
    buffers.signedDistance[i] = d;
    buffers.lineSide[i] = d > tolerance ? 1 : (d < -tolerance ? 2 : 0);
    if (buffers.vertexNode[i] >= 0)
      buffers.lineSide[i] = 0;
    if (std::abs(d) >= tolerance)
      continue;
    const double s = x.dot(along) / (length * length);
    // Only inner vertices: the cut meets the region's border at its ends.
    if (Bindings[region.vertices[i]].kind == BindingKind::CollisionTriangle && s > CutEndMargin &&
        s < 1.0 - CutEndMargin && buffers.vertexNode[i] < 0)
    {
      buffers.vertexNode[i] = static_cast<int>(buffers.nodes.size());
      buffers.nodes.push_back({ s, SurfacePoint::atVertex(region.vertices[i]) });
    }
  }
  for (int n = 0; n < 2; ++n)
  {
    const SurfacePoint& p = buffers.nodes[n].point;
    if (!p.isVertex())
    {
      buffers.lineSide[localOf(p.edgeStart)] |= 4;
      buffers.lineSide[localOf(p.edgeEnd)] |= 4;
    }
  }
  linkCrossedTriangles(region, tolerance, from, along, buffers);
  groupLinks(buffers.links, buffers.nodes.size(), buffers.linkOffsets, buffers.linkTargets);
  if (!walkCut(
        buffers.nodes, buffers.linkOffsets, buffers.linkTargets, buffers.visited, crossing.path))
  {
    throw Error("visual cut of '" + Mesh.name + "': the cut from collision vertex " +
                std::to_string(crossing.ends[0]) + " to " + std::to_string(crossing.ends[1]) +
                " loses its way in the visual region on side " + std::to_string(region.side));
  }
}

// Per region triangle, the crossing points on its border; a triangle with
// two joins them (the cut passes through it): buffers.links. Points inside
// edges are made here, once per edge.
void CuttableVisualMesh::linkCrossedTriangles(RegionCut& region,
  double tolerance,
  const Vector2& from,
  const Vector2& along,
  CutBuffers& buffers)
{
  const auto& nodes = buffers.nodes;
  const auto& signedDistance = buffers.signedDistance;
  const auto& lineSide = buffers.lineSide;
  const auto& vertexNode = buffers.vertexNode;
  const double squaredLength = along.squaredNorm();
  // The cut's ends lie on the line whatever round-off says (local indices).
  auto onLine = [&](int i)
  {
    return (vertexNode[i] >= 0 && vertexNode[i] < 2) ||
           (Bindings[region.vertices[i]].kind == BindingKind::CollisionTriangle &&
             std::abs(signedDistance[i]) < tolerance);
  };
  buffers.links.clear();
  auto& here = buffers.here;
  // Before the loop the only nodes inside edges are the cut's ends; those
  // made in it lie on edges whose ends are apart (never in a triangle
  // wholly on one side).
  const bool endsOnEdges = !nodes[0].point.isVertex() || !nodes[1].point.isVertex();
  for (std::size_t i = 0; i < region.triangles.size(); ++i)
  {
    const Triangle& locals = region.localTriangles[i];
    // Most triangles lie wholly on one side of the line, off the nodes:
    // nothing to do (bits of lineSide; an end of the cut inside one of
    // their edges is looked up only beside such an edge).
    const char s0 = lineSide[locals[0]], s1 = lineSide[locals[1]], s2 = lineSide[locals[2]];
    if ((s0 & s1 & s2 & 3) && (!((s0 | s1 | s2) & 4) || !endsOnEdges ||
                                (buffers.edgeNode(locals[0], locals[1]) < 0 &&
                                  buffers.edgeNode(locals[1], locals[2]) < 0 &&
                                  buffers.edgeNode(locals[2], locals[0]) < 0)))
      continue;
    // Only these triangles can hold a point of the traced path.
    region.candidate[i] = 1;
    here.clear();
    for (int k = 0; k < 3; ++k)
    {
      const int la = locals[k], lb = locals[(k + 1) % 3];
      const int a = region.vertices[la], b = region.vertices[lb];
      if (vertexNode[la] >= 0 && (vertexNode[la] < 2 || onLine(la)))
        here.push_back(vertexNode[la]);
      int found = buffers.edgeNode(la, lb);
      if (found < 0 && !onLine(la) && !onLine(lb) &&
          (signedDistance[la] > 0) != (signedDistance[lb] > 0))
      {
        // Never onto a vertex of the region's border (it keeps its own
        // binding): a round-off crossing there stays a little inside.
        double lambda = signedDistance[la] / (signedDistance[la] - signedDistance[lb]);
        if (Bindings[a].kind != BindingKind::CollisionTriangle)
          lambda = std::max(lambda, BorderClearance);
        if (Bindings[b].kind != BindingKind::CollisionTriangle)
          lambda = std::min(lambda, 1.0 - BorderClearance);
        const Vector2 x = (1.0 - lambda) * region.planar[la] + lambda * region.planar[lb] - from;
        // Near an end the parameterisation may put a crossing a little
        // beyond it: kept (only the walk decides what the path visits).
        const double s = x.dot(along) / squaredLength;
        if (s > -0.5 && s < 1.5)
        {
          found = static_cast<int>(nodes.size());
          buffers.addEdgeNode(la, lb, found);
          buffers.nodes.push_back({ s, SurfacePoint::onEdge(a, b, lambda) });
        }
      }
      if (found >= 0)
        here.push_back(found);
    }
    std::sort(here.begin(), here.end());
    here.erase(std::unique(here.begin(), here.end()), here.end());
    if (here.size() < 2)
      continue;
    // Two points (more only at round-off): the first and last along the cut.
    const auto [first, last] = std::minmax_element(
      here.begin(), here.end(), [&](int x, int y) { return nodes[x].s < nodes[y].s; });
    buffers.links.emplace_back(*first, *last);
    buffers.links.emplace_back(*last, *first);
  }
}

// The triangles of the (active) region a traced path touches (to re-mesh)
// go to region.touched; the others stay as they are.
void CuttableVisualMesh::selectTouchedTriangles(RegionCut& region, const RegionWorker& worker)
{
  // Per local vertex: 1 if a traced path passes it, 2 if a path crosses
  // an edge from it (then the edge is looked up).
  region.newTriangles.reserve(region.triangles.size() + region.triangles.size() / 2);
  region.newLocalTriangles.reserve(region.newTriangles.capacity());
  std::vector<char> mark(region.vertices.size(), 0);
  std::vector<std::uint64_t> edgePoints;
  for (const CrossingPath& crossing : region.crossings)
    for (const SurfacePoint& point : crossing.path.points)
    {
      if (point.isVertex())
        mark[worker.local(point.vertex)] |= 1;
      else
      {
        mark[worker.local(point.edgeStart)] |= 2;
        mark[worker.local(point.edgeEnd)] |= 2;
        edgePoints.push_back(edgeKey(point.edgeStart, point.edgeEnd));
      }
    }
  std::sort(edgePoints.begin(), edgePoints.end());
  auto crossed = [&](int a, int b, char ma, char mb)
  {
    return (ma & 2) && (mb & 2) &&
           std::binary_search(
             edgePoints.begin(), edgePoints.end(), edgeKey(region.vertices[a], region.vertices[b]));
  };
  for (std::size_t i = 0; i < region.triangles.size(); ++i)
  {
    const int t = region.triangles[i];
    bool touched = false;
    if (region.candidate[i])
    {
      const Triangle& tri = region.localTriangles[i];
      const char m[3] = { mark[tri[0]], mark[tri[1]], mark[tri[2]] };
      touched = (m[0] | m[1] | m[2]) & 1;
      for (int k = 0; k < 3 && !touched; ++k)
        touched = crossed(tri[k], tri[(k + 1) % 3], m[k], m[(k + 1) % 3]);
    }
    if (touched)
      region.touched.push_back(t);
    else
    {
      if (!region.far.empty())
        region.untouchedPositions.push_back(region.nearPositions[i]);
      region.newTriangles.push_back(t);
      region.newLocalTriangles.push_back(region.localTriangles[i]);
    }
  }
}

//------------------------------------------------------------------------------
// The traced cuts inserted into the regions (PathRemeshing on the regions
// only) and spliced back into the visual mesh.
void CuttableVisualMesh::remeshRegions(CutContext& context)
{
  // Only the triangles a traced path touches are re-meshed (the rest of
  // each region keeps its triangles; they are relabelled afterwards).
  std::vector<int> triangles;
  std::vector<int> regionOfLocal;
  for (std::size_t r = 0; r < context.regions.size(); ++r)
  {
    const std::vector<int>& touched = context.regions[r].touched;
    triangles.insert(triangles.end(), touched.begin(), touched.end());
    regionOfLocal.insert(regionOfLocal.end(), touched.size(), static_cast<int>(r));
  }
  if (triangles.empty())
    return;
  // The touched triangles as a mesh of their own, numbered through the
  // (all -1: no region is active) local-index scratch, reset right after.
  LocalMesh local;
  std::vector<SurfacePath> paths;
  try
  {
    extractTriangles(
      Mesh, triangles, context.worker->localIndex, context.worker->buffers.localTexture, local);
    auto localOf = [&](int v)
    {
      const int i = context.local(v);
      if (i < 0)
        throw Error("visual cut of '" + Mesh.name + "': traced cut through visual vertex " +
                    std::to_string(v) + " outside the triangles it touches");
      return i;
    };
    for (const RegionCut& region : context.regions)
    {
      for (const CrossingPath& crossing : region.crossings)
      {
        SurfacePath& p = paths.emplace_back();
        p.points.reserve(crossing.path.points.size());
        for (const SurfacePoint& point : crossing.path.points)
        {
          // onEdge orders the ends by their local indices.
          if (point.isVertex())
            p.points.push_back(SurfacePoint::atVertex(localOf(point.vertex)));
          else
            p.points.push_back(SurfacePoint::onEdge(
              localOf(point.edgeStart), localOf(point.edgeEnd), point.edgeParameter));
        }
      }
    }
  }
  catch (...)
  {
    for (int v : local.globalVertex)
      context.worker->localIndex[v] = -1;
    throw;
  }
  for (int v : local.globalVertex)
    context.worker->localIndex[v] = -1;
  const RemeshedSurface remeshed = insertPaths(local.mesh, paths);
  const TriangleMesh& out = remeshed.mesh;
  const int localCount = static_cast<int>(local.globalVertex.size());

  // New vertices, their attributes and texture coordinates.
  std::vector<int> global(local.globalVertex);
  std::vector<int> globalTexture(local.globalTexture);
  appendInserted(out, global, globalTexture, context);

  // Parameters of every vertex in its region's parent (inserted vertices
  // interpolated along the edge they were inserted in), then the triangles,
  // region by region (each active in turn).
  std::vector<std::vector<int>> outputOf(context.regions.size());
  for (std::size_t j = 0; j < out.triangleCount(); ++j)
    outputOf[regionOfLocal[remeshed.inputTriangle[j]]].push_back(static_cast<int>(j));
  for (RegionCut& region : context.regions)
    Regions[context.cut->splits[region.split].parent][region.side].clear();
  // Room for every inserted vertex in each region (a reallocation copies
  // the region's arrays).
  const std::size_t inserted = out.vertexCount() - static_cast<std::size_t>(localCount);
  for (std::size_t r = 0; r < context.regions.size(); ++r)
  {
    RegionCut& region = context.regions[r];
    const std::size_t room = region.vertices.size() + inserted;
    region.vertices.reserve(room);
    region.parameters.reserve(room);
    region.planar.reserve(room);
    context.activate(region);
    for (int j : outputOf[r])
      spliceTriangle(region, remeshed, j, global, globalTexture, local.globalTriangle, context);
    context.deactivate(region);
  }
  // The traced paths as visual vertices.
  std::size_t p = 0;
  for (RegionCut& region : context.regions)
  {
    for (CrossingPath& crossing : region.crossings)
    {
      crossing.vertices.clear();
      for (int i : remeshed.pathVertices[p++])
        crossing.vertices.push_back(global[i]);
    }
  }
}

// The vertices and texture coordinates the re-meshing inserted (after the
// local mesh's own), appended to the visual mesh; `global` and
// `globalTexture` (local index -> visual mesh) grow by them.
void CuttableVisualMesh::appendInserted(const TriangleMesh& out,
  std::vector<int>& global,
  std::vector<int>& globalTexture,
  CutContext& context)
{
  const std::vector<std::string> names = Mesh.pointAttributes.names();
  for (int i = static_cast<int>(global.size()); i < static_cast<int>(out.vertexCount()); ++i)
  {
    const int v = static_cast<int>(Mesh.positions.size());
    global.push_back(v);
    context.newVertices.push_back(v);
    Mesh.positions.push_back(out.positions[i]);
    if (Mesh.hasNormals())
      Mesh.normals.push_back(out.normals[i]);
    for (const std::string& name : names)
    {
      const AttributeArray& from = out.pointAttributes.get(name);
      AttributeArray& into = Mesh.pointAttributes.get(name);
      into.values.insert(into.values.end(), from.element(i), from.element(i) + from.components);
    }
    Bindings.emplace_back();
    BindingNodes.push_back(-1);
  }
  for (std::size_t c = globalTexture.size(); c < out.textureCoordinates.size(); ++c)
  {
    globalTexture.push_back(static_cast<int>(Mesh.textureCoordinates.size()));
    Mesh.textureCoordinates.push_back(out.textureCoordinates[c]);
  }
}

// Re-meshed triangle j back in the visual mesh, in its (active) region: an
// input triangle keeps its index, a new piece is added; an inserted corner
// joins the region with parameters interpolated along the edge it was
// inserted in.
void CuttableVisualMesh::spliceTriangle(RegionCut& region,
  const RemeshedSurface& remeshed,
  int j,
  const std::vector<int>& global,
  const std::vector<int>& globalTexture,
  const std::vector<int>& globalTriangle,
  CutContext& context)
{
  const TriangleMesh& out = remeshed.mesh;
  // The local mesh's vertices come first, then the inserted ones.
  const int localCount = static_cast<int>(remeshed.inputVertex.size() - remeshed.insertedOn.size());
  const Triangle& corners = out.triangles[j];
  const Triangle mapped{ { global[corners[0]], global[corners[1]], global[corners[2]] } };
  for (int k = 0; k < 3; ++k)
  {
    if (context.local(mapped[k]) >= 0)
      continue;
    const auto misplaced = [&]
    {
      return Error("visual cut of '" + Mesh.name + "': re-meshing put visual vertex " +
                   std::to_string(mapped[k]) + " in a region it does not belong to");
    };
    if (corners[k] < localCount)
      throw misplaced();
    const SurfacePoint& on = remeshed.insertedOn[corners[k] - localCount];
    const int a = context.local(global[on.edgeStart]);
    const int b = context.local(global[on.edgeEnd]);
    if (a < 0 || b < 0)
      throw misplaced();
    const double u = on.edgeParameter;
    context.addToActive(region,
      mapped[k],
      (1.0 - u) * region.parameters[a] + u * region.parameters[b],
      (1.0 - u) * region.planar[a] + u * region.planar[b]);
  }
  int t = -1;
  if (static_cast<std::size_t>(j) < globalTriangle.size())
  {
    t = globalTriangle[j];
    Mesh.triangles[t] = mapped;
  }
  else
  {
    t = addTriangle(mapped, -1, 0, VisualMaterial::Surface);
  }
  if (Mesh.hasTextureCoordinates())
  {
    const Triangle& tex = out.textureCorners[j];
    Mesh.textureCorners[t] = {
      { globalTexture[tex[0]], globalTexture[tex[1]], globalTexture[tex[2]] }
    };
  }
  region.newTriangles.push_back(t);
  region.newLocalTriangles.push_back(
    { { context.local(mapped[0]), context.local(mapped[1]), context.local(mapped[2]) } });
  context.changedTriangles.push_back(t);
}

} // namespace thintissue
