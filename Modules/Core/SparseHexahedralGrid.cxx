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
  double h = 0.0;
  if (settings.cellSize > 0.0 && std::isfinite(settings.cellSize))
  {
    h = settings.cellSize;
  }
  else if (settings.cellSize != 0.0)
  {
    throw InvalidInputError(context + ": cell size must be positive and finite, got " +
                            std::to_string(settings.cellSize));
  }
  else if (settings.cellsAlongLongestSide >= 1)
  {
    h = longest / settings.cellsAlongLongestSide;
  }
  else
  {
    throw InvalidInputError(context + ": cells along the longest side must be at least 1, got " +
                            std::to_string(settings.cellsAlongLongestSide));
  }

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
  const int nx = grid.cellCounts[0];
  const int ny = grid.cellCounts[1];
  const int nz = grid.cellCounts[2];
  grid.origin = bounds.center() - 0.5 * h * Vector3(nx, ny, nz);
  const Vector3 origin = grid.origin;
  const std::size_t cellCount = static_cast<std::size_t>(nx) * ny * nz;
  const auto cellId = [=](int i, int j, int k)
  { return (static_cast<std::size_t>(k) * ny + j) * nx + i; };

  // 1. Cells the surface passes through: each triangle against the cells of
  //    its bounding box.
  std::vector<std::uint8_t> intersected(cellCount, 0);
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
    {
      for (int j = first[1]; j <= last[1]; ++j)
      {
        for (int i = first[0]; i <= last[0]; ++i)
        {
          std::uint8_t& cell = intersected[cellId(i, j, k)];
          if (cell != 0)
          {
            continue;
          }
          BoundingBox box;
          box.min() = origin + h * Vector3(i, j, k) - Vector3::Constant(slack);
          box.max() = origin + h * Vector3(i + 1, j + 1, k + 1) + Vector3::Constant(slack);
          if (single || triangleOverlapsBox(a, b, c, box))
          {
            cell = 1;
          }
        }
      }
    }
  }

  // 2. The other cells lie wholly inside or outside. Label their connected
  //    pieces (6-neighbours); a piece on the grid's border is outside (the
  //    surface cannot separate it from the exterior without passing through
  //    the border cell), any other is classified by the winding number at
  //    one of its cells.
  std::vector<int> piece(cellCount, -1);
  std::vector<std::uint8_t> pieceInside;
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < cellCount; ++seed)
  {
    if (intersected[seed] != 0 || piece[seed] >= 0)
    {
      continue;
    }
    const int label = static_cast<int>(pieceInside.size());
    bool onBorder = false;
    piece[seed] = label;
    stack.assign(1, seed);
    while (!stack.empty())
    {
      const std::size_t id = stack.back();
      stack.pop_back();
      const int i = static_cast<int>(id % nx);
      const int j = static_cast<int>((id / nx) % ny);
      const int k = static_cast<int>(id / (static_cast<std::size_t>(nx) * ny));
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
        {
          continue;
        }
        const std::size_t nid = cellId(n[0], n[1], n[2]);
        if (intersected[nid] == 0 && piece[nid] < 0)
        {
          piece[nid] = label;
          stack.push_back(nid);
        }
      }
    }
    bool inside = false;
    if (!onBorder)
    {
      const int i = static_cast<int>(seed % nx);
      const int j = static_cast<int>((seed / nx) % ny);
      const int k = static_cast<int>(seed / (static_cast<std::size_t>(nx) * ny));
      const Vector3 centre = origin + h * Vector3(i + 0.5, j + 0.5, k + 0.5);
      // |w| so that an inward-facing surface works too.
      inside = std::abs(windingNumber(surface, centre)) > 0.5;
    }
    pieceInside.push_back(inside ? 1 : 0);
  }

  // 3. Kept cells, then their nodes numbered in grid order.
  const auto kept = [&](std::size_t id)
  { return intersected[id] != 0 || pieceInside[static_cast<std::size_t>(piece[id])] != 0; };
  const std::size_t nodeGridCount = static_cast<std::size_t>(nx + 1) * (ny + 1) * (nz + 1);
  const auto nodeId = [=](int i, int j, int k)
  { return (static_cast<std::size_t>(k) * (ny + 1) + j) * (nx + 1) + i; };
  std::vector<int> nodeIndex(nodeGridCount, -1);
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        if (!kept(cellId(i, j, k)))
        {
          continue;
        }
        for (int c = 0; c < 8; ++c)
        {
          const auto o = HexahedralMesh::cornerOffset(c);
          nodeIndex[nodeId(i + o[0], j + o[1], k + o[2])] = 0;
        }
      }
    }
  }
  HexahedralMesh& mesh = grid.mesh;
  mesh.name = "sparse grid of '" + surface.name + "'";
  for (int k = 0; k <= nz; ++k)
  {
    for (int j = 0; j <= ny; ++j)
    {
      for (int i = 0; i <= nx; ++i)
      {
        int& index = nodeIndex[nodeId(i, j, k)];
        if (index == 0)
        {
          index = static_cast<int>(mesh.nodes.size());
          mesh.nodes.push_back(origin + h * Vector3(i, j, k));
        }
      }
    }
  }
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        const std::size_t id = cellId(i, j, k);
        if (!kept(id))
        {
          continue;
        }
        Hexahedron hex;
        for (int c = 0; c < 8; ++c)
        {
          const auto o = HexahedralMesh::cornerOffset(c);
          hex[c] = nodeIndex[nodeId(i + o[0], j + o[1], k + o[2])];
        }
        mesh.hexahedra.push_back(hex);
        grid.cellIndices.push_back({ { i, j, k } });
        grid.intersectsSurface.push_back(intersected[id]);
      }
    }
  }
  mesh.fixedNodes.assign(mesh.nodes.size(), 0);
  return grid;
}

HexahedralMesh makeSparseHexahedralMesh(const TriangleMesh& surface, int cellsAlongLongestSide)
{
  SparseHexahedralGridSettings settings;
  settings.cellsAlongLongestSide = cellsAlongLongestSide;
  return SparseHexahedralGrid::fromSurface(surface, settings).mesh;
}

} // namespace thintissue
