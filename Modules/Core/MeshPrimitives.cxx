#include "MeshPrimitives.h"

#include "ThinTissueError.h"

namespace thintissue
{

TriangleMesh makeSlabSurface(const SlabSurfaceParameters& p)
{
  if (!(p.width > 0.0 && p.depth > 0.0 && p.thickness > 0.0))
  {
    throw InvalidInputError("slab surface: width, depth and thickness must be positive");
  }
  if (p.cellsX < 1 || p.cellsY < 1 || p.cellsZ < 1)
  {
    throw InvalidInputError("slab surface: cell counts must be at least 1");
  }
  const int cells[3] = { p.cellsX, p.cellsY, p.cellsZ };
  const Vector3 size(p.width, p.depth, p.thickness);
  const Vector3 origin = -0.5 * size;

  TriangleMesh mesh;
  mesh.name = "slab";
  // Lattice index -> vertex, so that faces sharing a box edge share vertices.
  const std::size_t latticeSize =
    static_cast<std::size_t>(cells[0] + 1) * (cells[1] + 1) * (cells[2] + 1);
  std::vector<int> vertexOfLattice(latticeSize, -1);
  const auto vertexAt = [&](const std::array<int, 3>& ijk)
  {
    const std::size_t key =
      (static_cast<std::size_t>(ijk[2]) * (cells[1] + 1) + ijk[1]) * (cells[0] + 1) + ijk[0];
    int& v = vertexOfLattice[key];
    if (v < 0)
    {
      v = static_cast<int>(mesh.positions.size());
      mesh.positions.push_back(
        origin +
        Vector3(double(ijk[0]) / cells[0], double(ijk[1]) / cells[1], double(ijk[2]) / cells[2])
          .cwiseProduct(size));
    }
    return v;
  };

  for (int axis = 0; axis < 3; ++axis)
  {
    // (axis, u, v) is a cyclic permutation, so e_u x e_v = e_axis.
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side)
    {
      for (int j = 0; j < cells[v]; ++j)
      {
        for (int i = 0; i < cells[u]; ++i)
        {
          int quad[4];
          const int corners[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
          for (int c = 0; c < 4; ++c)
          {
            std::array<int, 3> ijk;
            ijk[axis] = side * cells[axis];
            ijk[u] = i + corners[c][0];
            ijk[v] = j + corners[c][1];
            quad[c] = vertexAt(ijk);
          }
          if (side == 1)
          {
            mesh.triangles.push_back({ quad[0], quad[1], quad[2] });
            mesh.triangles.push_back({ quad[0], quad[2], quad[3] });
          }
          else
          {
            mesh.triangles.push_back({ quad[0], quad[2], quad[1] });
            mesh.triangles.push_back({ quad[0], quad[3], quad[2] });
          }
        }
      }
    }
  }

  mesh.textureCoordinates.reserve(mesh.positions.size());
  for (const Vector3& x : mesh.positions)
  {
    mesh.textureCoordinates.emplace_back(
      (x.x() - origin.x()) / size.x(), (x.y() - origin.y()) / size.y());
  }
  mesh.textureCorners = mesh.triangles;
  mesh.computeVertexNormals();
  return mesh;
}

} // namespace thintissue
