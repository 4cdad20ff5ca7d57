#include "SparseHexahedralGrid.h"

#include "MeshQueries.h"
#include "ThinTissueError.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

namespace thintissue
{

namespace
{

// Upper bound on the cells of the full grid (dense bookkeeping arrays).
constexpr double MaximumGridCells = 1 << 27;

std::string surfaceContext(const TriangleMesh& surface)
{
  return "surface '" + surface.name + "'";
}

// Edges used by an odd number of triangles when vertex v is identified with
// canonical[v]; `first` receives one of them. Linear: edges are bucketed by
// their smaller vertex.
std::size_t countOddEdges(const TriangleMesh& surface,
  const std::vector<int>& canonical,
  std::pair<int, int>& first)
{
  const std::size_t vertexCount = surface.vertexCount();
  std::vector<int> start(vertexCount + 1, 0);
  const auto forEachEdge = [&](const auto& visit)
  {
    for (const Triangle& t : surface.triangles)
    {
      for (int k = 0; k < 3; ++k)
      {
        const int a = canonical[t[k]];
        const int b = canonical[t[(k + 1) % 3]];
        if (a != b)
        {
          visit(std::min(a, b), std::max(a, b));
        }
      }
    }
  };
  forEachEdge([&](int a, int) { ++start[static_cast<std::size_t>(a) + 1]; });
  for (std::size_t v = 0; v < vertexCount; ++v)
  {
    start[v + 1] += start[v];
  }
  std::vector<int> partners(static_cast<std::size_t>(start[vertexCount]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  forEachEdge([&](int a, int b) { partners[static_cast<std::size_t>(fill[a]++)] = b; });
  std::size_t odd = 0;
  for (std::size_t a = 0; a < vertexCount; ++a)
  {
    const auto begin = partners.begin() + start[a];
    const auto end = partners.begin() + start[a + 1];
    std::sort(begin, end); // a handful of entries
    for (auto i = begin; i != end;)
    {
      auto j = i + 1;
      while (j != end && *j == *i)
      {
        ++j;
      }
      if ((j - i) % 2 == 1)
      {
        if (odd == 0)
        {
          first = { static_cast<int>(a), *i };
        }
        ++odd;
      }
      i = j;
    }
  }
  return odd;
}

// Throws unless every edge is shared by an even number of triangles. If the
// surface is open as indexed, vertices at the same position are taken as one
// and it is checked again, so a triangle soup (STL) of a closed surface
// passes.
void checkClosed(const TriangleMesh& surface)
{
  std::vector<int> canonical(surface.vertexCount());
  for (std::size_t v = 0; v < canonical.size(); ++v)
  {
    canonical[v] = static_cast<int>(v);
  }
  std::pair<int, int> first{ -1, -1 };
  std::size_t open = countOddEdges(surface, canonical, first);
  if (open > 0)
  {
    std::vector<int> order = canonical;
    const auto less = [&](int a, int b)
    {
      const Vector3& p = surface.positions[a];
      const Vector3& q = surface.positions[b];
      return std::tie(p[0], p[1], p[2], a) < std::tie(q[0], q[1], q[2], b);
    };
    tbb::parallel_sort(order.begin(), order.end(), less);
    for (std::size_t i = 1; i < order.size(); ++i)
    {
      if (surface.positions[order[i]] == surface.positions[order[i - 1]])
      {
        canonical[order[i]] = canonical[order[i - 1]];
      }
    }
    open = countOddEdges(surface, canonical, first);
  }
  if (open > 0)
  {
    throw InvalidInputError(surfaceContext(surface) + ": not closed (" + std::to_string(open) +
                            " border edges, first between vertices " + std::to_string(first.first) +
                            " and " + std::to_string(first.second) +
                            "); a sparse hexahedral grid needs " + "a closed surface");
  }
}

} // namespace

bool triangleOverlapsBox(const Vector3& a,
  const Vector3& b,
  const Vector3& c,
  const BoundingBox& box)
{
  const Vector3 centre = box.center();
  const Vector3 half = 0.5 * box.sizes();
  const Vector3 v[3] = { a - centre, b - centre, c - centre };
  // Box faces: the triangle's bounding box against the box.
  for (int axis = 0; axis < 3; ++axis)
  {
    const double lo = std::min({ v[0][axis], v[1][axis], v[2][axis] });
    const double hi = std::max({ v[0][axis], v[1][axis], v[2][axis] });
    if (lo > half[axis] || hi < -half[axis])
    {
      return false;
    }
  }
  const Vector3 edges[3] = { v[1] - v[0], v[2] - v[1], v[0] - v[2] };
  // Triangle plane.
  const Vector3 normal = edges[0].cross(edges[1]);
  const double radius = half.dot(normal.cwiseAbs());
  if (std::abs(normal.dot(v[0])) > radius)
  {
    return false;
  }
  // The nine cross products of box axes and triangle edges.
  for (const Vector3& edge : edges)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      const Vector3 direction = Vector3::Unit(axis).cross(edge);
      const double p0 = direction.dot(v[0]);
      const double p1 = direction.dot(v[1]);
      const double p2 = direction.dot(v[2]);
      const double r = half.dot(direction.cwiseAbs());
      if (std::min({ p0, p1, p2 }) > r || std::max({ p0, p1, p2 }) < -r)
      {
        return false;
      }
    }
  }
  return true;
}

namespace
{

/// The cell size the settings ask for (a size, or cells along the longest
/// side of `extent`).
double chosenCellSize(const std::string& context,
  const Vector3& extent,
  const SparseHexahedralGridSettings& settings)
{
  if (settings.cellSize > 0.0 && std::isfinite(settings.cellSize))
  {
    return settings.cellSize;
  }
  if (settings.cellSize != 0.0)
  {
    throw InvalidInputError(context + ": cell size must be positive and finite, got " +
                            std::to_string(settings.cellSize));
  }
  if (settings.cellsAlongLongestSide >= 1)
  {
    return extent.maxCoeff() / settings.cellsAlongLongestSide;
  }
  throw InvalidInputError(context + ": cells along the longest side must be at least 1, got " +
                          std::to_string(settings.cellsAlongLongestSide));
}

/// Cell and node numbering of a grid of nx x ny x nz cells.
struct GridIndexing
{
  int nx = 0, ny = 0, nz = 0;
  std::size_t cellCount() const { return static_cast<std::size_t>(nx) * ny * nz; }
  std::size_t cell(int i, int j, int k) const
  {
    return (static_cast<std::size_t>(k) * ny + j) * nx + i;
  }
  std::array<int, 3> cellCoordinates(std::size_t id) const
  {
    return { { static_cast<int>(id % nx),
      static_cast<int>((id / nx) % ny),
      static_cast<int>(id / (static_cast<std::size_t>(nx) * ny)) } };
  }
  std::size_t nodeCount() const { return static_cast<std::size_t>(nx + 1) * (ny + 1) * (nz + 1); }
  std::size_t node(int i, int j, int k) const
  {
    return (static_cast<std::size_t>(k) * (ny + 1) + j) * (nx + 1) + i;
  }
};

/// Per cell, 1 where the surface passes through it: each triangle against
/// the cells of its bounding box.
std::vector<std::uint8_t> cellsCrossedBySurface(const TriangleMesh& surface,
  const SparseHexahedralGrid& grid,
  const GridIndexing& index)
{
  std::vector<std::uint8_t> intersected(index.cellCount(), 0);
  const double h = grid.cellSize;
  const Vector3& origin = grid.origin;
  const double slack = 1e-9 * h;
  for (const Triangle& t : surface.triangles)
  {
    const Vector3& a = surface.positions[t[0]];
    const Vector3& b = surface.positions[t[1]];
    const Vector3& c = surface.positions[t[2]];
    const Vector3 lo = a.cwiseMin(b).cwiseMin(c);
    const Vector3 hi = a.cwiseMax(b).cwiseMax(c);
    std::array<int, 3> first;
    std::array<int, 3> last;
    for (int axis = 0; axis < 3; ++axis)
    {
      const int count = grid.cellCounts[axis];
      first[axis] = std::clamp(
        static_cast<int>(std::floor((lo[axis] - slack - origin[axis]) / h)), 0, count - 1);
      last[axis] = std::clamp(
        static_cast<int>(std::floor((hi[axis] + slack - origin[axis]) / h)), 0, count - 1);
    }
    const bool single = first == last;
    for (int k = first[2]; k <= last[2]; ++k)
      for (int j = first[1]; j <= last[1]; ++j)
        for (int i = first[0]; i <= last[0]; ++i)
        {
          std::uint8_t& cell = intersected[index.cell(i, j, k)];
          if (cell != 0)
            continue;
          BoundingBox box;
          box.min() = origin + h * Vector3(i, j, k) - Vector3::Constant(slack);
          box.max() = origin + h * Vector3(i + 1, j + 1, k + 1) + Vector3::Constant(slack);
          if (single || triangleOverlapsBox(a, b, c, box))
            cell = 1;
        }
  }
  return intersected;
}

/// Per cell, 1 if kept: crossed by the surface, or inside it. The other
/// cells lie wholly inside or outside; their connected pieces (6-neighbours)
/// are labelled; a piece on the grid's border is outside (the surface cannot
/// separate it from the exterior without passing through the border cell),
/// any other is classified by the winding number at one of its cells.
std::vector<std::uint8_t> keptCells(const TriangleMesh& surface,
  const SparseHexahedralGrid& grid,
  const GridIndexing& index,
  std::vector<std::uint8_t> kept)
{
  const int nx = index.nx, ny = index.ny, nz = index.nz;
  std::vector<char> visited(index.cellCount(), 0);
  std::vector<std::size_t> stack, members;
  for (std::size_t seed = 0; seed < index.cellCount(); ++seed)
  {
    if (kept[seed] != 0 || visited[seed] != 0)
      continue;
    bool onBorder = false;
    visited[seed] = 1;
    stack.assign(1, seed);
    members.clear();
    while (!stack.empty())
    {
      const std::size_t id = stack.back();
      stack.pop_back();
      members.push_back(id);
      const auto [i, j, k] = index.cellCoordinates(id);
      onBorder =
        onBorder || i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1;
      const int neighbours[6][3] = { { i - 1, j, k },
        { i + 1, j, k },
        { i, j - 1, k },
        { i, j + 1, k },
        { i, j, k - 1 },
        { i, j, k + 1 } };
      for (const auto& n : neighbours)
      {
        if (n[0] < 0 || n[1] < 0 || n[2] < 0 || n[0] >= nx || n[1] >= ny || n[2] >= nz)
          continue;
        const std::size_t nid = index.cell(n[0], n[1], n[2]);
        if (kept[nid] == 0 && visited[nid] == 0)
        {
          visited[nid] = 1;
          stack.push_back(nid);
        }
      }
    }
    if (onBorder)
      continue;
    const auto [i, j, k] = index.cellCoordinates(seed);
    const Vector3 centre = grid.origin + grid.cellSize * Vector3(i + 0.5, j + 0.5, k + 0.5);
    // |w| so that an inward-facing surface works too.
    if (std::abs(windingNumber(surface, centre)) > 0.5)
      for (std::size_t id : members)
        kept[id] = 2;
  }
  return kept;
}

/// The kept cells as hexahedra, their nodes numbered in grid order.
void addKeptHexahedra(SparseHexahedralGrid& grid,
  const GridIndexing& index,
  const std::vector<std::uint8_t>& kept)
{
  const int nx = index.nx, ny = index.ny, nz = index.nz;
  std::vector<int> nodeIndex(index.nodeCount(), -1);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (kept[index.cell(i, j, k)] != 0)
          for (int c = 0; c < 8; ++c)
          {
            const auto o = HexahedralMesh::cornerOffset(c);
            nodeIndex[index.node(i + o[0], j + o[1], k + o[2])] = 0;
          }
  HexahedralMesh& mesh = grid.mesh;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
      {
        int& node = nodeIndex[index.node(i, j, k)];
        if (node == 0)
        {
          node = static_cast<int>(mesh.nodes.size());
          mesh.nodes.push_back(grid.origin + grid.cellSize * Vector3(i, j, k));
        }
      }
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        const std::size_t id = index.cell(i, j, k);
        if (kept[id] == 0)
          continue;
        Hexahedron hex;
        for (int c = 0; c < 8; ++c)
        {
          const auto o = HexahedralMesh::cornerOffset(c);
          hex[c] = nodeIndex[index.node(i + o[0], j + o[1], k + o[2])];
        }
        mesh.hexahedra.push_back(hex);
        grid.cellIndices.push_back({ { i, j, k } });
        grid.intersectsSurface.push_back(kept[id] == 1 ? 1 : 0);
      }
  mesh.fixedNodes.assign(mesh.nodes.size(), 0);
}

} // namespace

SparseHexahedralGrid SparseHexahedralGrid::fromSurface(const TriangleMesh& surface,
  const SparseHexahedralGridSettings& settings)
{
  const std::string context = surfaceContext(surface);
  if (surface.triangles.empty())
  {
    throw InvalidInputError(context + ": no triangles to make a hexahedral grid from");
  }
  surface.checkConsistency();
  checkClosed(surface);

  const BoundingBox bounds = surface.boundingBox();
  const Vector3 extent = bounds.sizes();
  const double longest = extent.maxCoeff();
  if (!(longest > 0.0))
  {
    throw InvalidInputError(context + ": all vertices at one point");
  }
  const double h = chosenCellSize(context, extent, settings);
  SparseHexahedralGrid grid;
  grid.cellSize = h;
  double totalCells = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    // Tolerance: an extent of exactly n cells gives n cells, not n + 1.
    const double cells = std::ceil(extent[a] / h - 1e-9);
    totalCells *= std::max(1.0, cells);
    if (totalCells > MaximumGridCells)
    {
      throw InvalidInputError(context + ": resolution too fine (cell size " + std::to_string(h) +
                              " for a bounding box of " + std::to_string(longest) +
                              "): more than " + std::to_string(MaximumGridCells) + " grid cells");
    }
    grid.cellCounts[a] = std::max(1, static_cast<int>(cells));
  }
  const GridIndexing index{ grid.cellCounts[0], grid.cellCounts[1], grid.cellCounts[2] };
  grid.origin = bounds.center() - 0.5 * h * Vector3(index.nx, index.ny, index.nz);
  grid.mesh.name = "sparse grid of '" + surface.name + "'";
  // Crossed cells (1), then the cells inside (2), as hexahedra.
  addKeptHexahedra(
    grid, index, keptCells(surface, grid, index, cellsCrossedBySurface(surface, grid, index)));
  return grid;
}

HexahedralMesh makeSparseHexahedralMesh(const TriangleMesh& surface, int cellsAlongLongestSide)
{
  SparseHexahedralGridSettings settings;
  settings.cellsAlongLongestSide = cellsAlongLongestSide;
  return SparseHexahedralGrid::fromSurface(surface, settings).mesh;
}

} // namespace thintissue
