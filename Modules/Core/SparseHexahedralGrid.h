// Hexahedral simulation mesh generated from a closed triangle surface: a
// regular grid of cubic cells over the surface's bounding box that keeps
// only the cells touching the interior (the surface passes through them, or
// they lie inside it), as SOFA's SparseGridTopology does. Nodes are shared
// between kept cells; nodes of no kept cell are dropped.
#ifndef SparseHexahedralGrid_h
#define SparseHexahedralGrid_h

#include "HexahedralMesh.h"
#include "ThinTissueCoreModule.h"
#include "TriangleMesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace thintissue
{

struct SparseHexahedralGridSettings
{
  /// Cells along the longest side of the surface's bounding box; the cells
  /// are cubes, so the other sides get proportionally fewer (at least 1).
  /// Used when cellSize is 0.
  int cellsAlongLongestSide = 10;
  /// Edge length of the cubic cells; overrides cellsAlongLongestSide when
  /// positive.
  double cellSize = 0.0;
};

/// The generated mesh and where its cells sit in the full grid.
class THINTISSUECORE_EXPORT SparseHexahedralGrid
{
public:
  /// Kept cells as hexahedra (VTK_HEXAHEDRON order, x fastest), named after
  /// the surface, no fixed node.
  HexahedralMesh mesh;
  /// Corner of the full grid (minimum), edge length of the cubic cells and
  /// cell counts of the full grid along x, y, z. The full grid is centred on
  /// the surface's bounding box.
  Vector3 origin = Vector3::Zero();
  double cellSize = 0.0;
  std::array<int, 3> cellCounts{ { 0, 0, 0 } };
  /// Per hexahedron: its (i, j, k) cell in the full grid.
  std::vector<std::array<int, 3>> cellIndices;
  /// Per hexahedron: 1 if the surface passes through (or touches) the cell,
  /// 0 if the cell lies inside.
  std::vector<std::uint8_t> intersectsSurface;

  /// Builds the grid. Throws InvalidInputError naming the surface when it is
  /// empty, inconsistent or open (an edge with an odd number of triangles),
  /// when all its vertices coincide, or when the resolution is not positive
  /// or too fine (more than 2^27 cells in the full grid).
  static SparseHexahedralGrid fromSurface(const TriangleMesh& surface,
    const SparseHexahedralGridSettings& settings);
};

/// Convenience: the mesh of SparseHexahedralGrid::fromSurface with
/// `cellsAlongLongestSide` cells along the longest side.
THINTISSUECORE_EXPORT HexahedralMesh makeSparseHexahedralMesh(const TriangleMesh& surface,
  int cellsAlongLongestSide);

/// True if triangle (a, b, c) and the axis-aligned box overlap, touching
/// included (separating-axis test, Akenine-Moller 2001).
THINTISSUECORE_EXPORT bool triangleOverlapsBox(const Vector3& a,
  const Vector3& b,
  const Vector3& c,
  const BoundingBox& box);

} // namespace thintissue

#endif
