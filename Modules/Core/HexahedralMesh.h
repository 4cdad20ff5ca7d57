// Hexahedral simulation mesh (thesis fig. 5-1, section 4.2): nodes,
// 8-node cells in VTK_HEXAHEDRON order, fixed-node mask, node attributes.
#ifndef HexahedralMesh_h
#define HexahedralMesh_h

#include "ThinTissueCoreModule.h"
#include "TriangleMesh.h"
#include "VertexAttributes.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace thintissue
{

/// Node indices of one hexahedron in VTK_HEXAHEDRON order: corners 0-3 at
/// local (0,0,0) (1,0,0) (1,1,0) (0,1,0), then 4-7 the same at z = 1.
using Hexahedron = std::array<int, 8>;

class THINTISSUECORE_EXPORT HexahedralMesh
{
public:
  std::string name;
  std::vector<Vector3> nodes;
  std::vector<Hexahedron> hexahedra;
  /// 1 where the node is fixed (Dirichlet); empty or one per node.
  std::vector<std::uint8_t> fixedNodes;
  VertexAttributes nodeAttributes;

  std::size_t nodeCount() const { return nodes.size(); }
  std::size_t hexahedronCount() const { return hexahedra.size(); }
  bool isFixed(std::size_t node) const { return !fixedNodes.empty() && fixedNodes[node] != 0; }
  std::size_t fixedNodeCount() const;
  BoundingBox boundingBox() const;
  Vector3 hexahedronCentre(std::size_t h) const;
  /// Fixes the nodes within `tolerance` of the smallest coordinate along
  /// `axis` (0, 1, 2: a clamped end) and frees the others. Throws
  /// InvalidInputError on another axis or a negative tolerance.
  void fixLowestNodes(int axis, double tolerance);

  /// Local corner coordinates (0 or 1 per axis) of VTK hexahedron corner k.
  static std::array<int, 3> cornerOffset(int k);

  /// A box of nx * ny * nz hexahedra from `origin` with the given spacing.
  static HexahedralMesh makeRegularGrid(const Vector3& origin,
    const Vector3& spacing,
    int nx,
    int ny,
    int nz);

  /// Throws InvalidInputError naming `name` on an index out of range, a
  /// repeated node in a cell, a non-finite coordinate, a mask or attribute of
  /// the wrong length.
  void checkConsistency() const;
};

} // namespace thintissue

#endif
