#include "HexahedralMesh.h"

#include "ThinTissueError.h"

#include <algorithm>

namespace thintissue
{

std::size_t HexahedralMesh::fixedNodeCount() const
{
  return static_cast<std::size_t>(
    std::count_if(fixedNodes.begin(), fixedNodes.end(), [](std::uint8_t f) { return f != 0; }));
}

BoundingBox HexahedralMesh::boundingBox() const
{
  return boundingBoxOf(nodes);
}

void HexahedralMesh::fixLowestNodes(int axis, double tolerance)
{
  if (axis < 0 || axis > 2 || !(tolerance >= 0.0))
  {
    throw InvalidInputError("hexahedral mesh '" + name + "': nodes to fix need an axis 0-2 " +
                            "and a tolerance of at least 0 (got " + std::to_string(axis) + ", " +
                            std::to_string(tolerance) + ")");
  }
  const double lowest = boundingBox().min()[axis];
  fixedNodes.assign(nodes.size(), 0);
  for (std::size_t n = 0; n < nodes.size(); ++n)
  {
    fixedNodes[n] = nodes[n][axis] <= lowest + tolerance ? 1 : 0;
  }
}

Vector3 HexahedralMesh::hexahedronCentre(std::size_t h) const
{
  Vector3 centre = Vector3::Zero();
  for (int n : hexahedra[h])
  {
    centre += nodes[n];
  }
  return centre / 8.0;
}

std::array<int, 3> HexahedralMesh::cornerOffset(int k)
{
  static constexpr int offsets[8][3] = { { 0, 0, 0 },
    { 1, 0, 0 },
    { 1, 1, 0 },
    { 0, 1, 0 },
    { 0, 0, 1 },
    { 1, 0, 1 },
    { 1, 1, 1 },
    { 0, 1, 1 } };
  return { offsets[k][0], offsets[k][1], offsets[k][2] };
}

HexahedralMesh HexahedralMesh::makeRegularGrid(const Vector3& origin,
  const Vector3& spacing,
  int nx,
  int ny,
  int nz)
{
  if (nx < 1 || ny < 1 || nz < 1)
  {
    throw InvalidInputError("regular hexahedral grid: cell counts must be at least 1, got " +
                            std::to_string(nx) + " x " + std::to_string(ny) + " x " +
                            std::to_string(nz));
  }
  if (!(spacing.array() > 0.0).all())
  {
    throw InvalidInputError("regular hexahedral grid: spacing must be positive");
  }
  HexahedralMesh mesh;
  mesh.name = "regular grid";
  const auto nodeIndex = [=](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  mesh.nodes.reserve(static_cast<std::size_t>(nx + 1) * (ny + 1) * (nz + 1));
  for (int k = 0; k <= nz; ++k)
  {
    for (int j = 0; j <= ny; ++j)
    {
      for (int i = 0; i <= nx; ++i)
      {
        mesh.nodes.push_back(origin + Vector3(i, j, k).cwiseProduct(spacing));
      }
    }
  }
  mesh.hexahedra.reserve(static_cast<std::size_t>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        Hexahedron hex;
        for (int c = 0; c < 8; ++c)
        {
          const auto o = cornerOffset(c);
          hex[c] = nodeIndex(i + o[0], j + o[1], k + o[2]);
        }
        mesh.hexahedra.push_back(hex);
      }
    }
  }
  mesh.fixedNodes.assign(mesh.nodes.size(), 0);
  return mesh;
}

void HexahedralMesh::checkConsistency() const
{
  const std::string context = "hexahedral mesh '" + name + "'";
  for (std::size_t i = 0; i < nodes.size(); ++i)
  {
    if (!nodes[i].allFinite())
    {
      throw InvalidInputError(
        context + ": node " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  const long long n = static_cast<long long>(nodes.size());
  for (std::size_t h = 0; h < hexahedra.size(); ++h)
  {
    Hexahedron sorted = hexahedra[h];
    for (int v : sorted)
    {
      if (v < 0 || v >= n)
      {
        throw InvalidInputError(context + ": hexahedron " + std::to_string(h) + " has node index " +
                                std::to_string(v) + " out of range (" + std::to_string(n) +
                                " nodes)");
      }
    }
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    {
      throw InvalidInputError(
        context + ": hexahedron " + std::to_string(h) + " uses the same node twice");
    }
  }
  if (!fixedNodes.empty() && fixedNodes.size() != nodes.size())
  {
    throw InvalidInputError(context + ": fixed-node mask has " + std::to_string(fixedNodes.size()) +
                            " entries for " + std::to_string(n) + " nodes");
  }
  nodeAttributes.checkElementCount(nodes.size(), context);
}

} // namespace thintissue
