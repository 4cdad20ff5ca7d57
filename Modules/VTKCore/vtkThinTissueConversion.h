// Conversion between kernel meshes and VTK data sets, at the boundary of the
// VTK layer. Array conventions:
//  - point "Normals" (3 doubles) <-> TriangleMesh::normals
//  - point "TCoords" (2 doubles) when every vertex has one texture coordinate
//  - cell "CornerTextureCoordinates" (6 doubles: u0 v0 u1 v1 u2 v2) whenever
//    the mesh is textured: the exact per-corner data, seams included
//  - any other numeric point array <-> a VertexAttributes array
//  - unstructured grid point "FixedNode" (unsigned char) <-> fixedNodes
#ifndef vtkThinTissueConversion_h
#define vtkThinTissueConversion_h

#include "HexahedralEmbedding.h"
#include "HexahedralMesh.h"
#include "ThinTissueVTKCoreModule.h"
#include "TriangleMesh.h"

#include <vtkSmartPointer.h>

#include <string>

class vtkDataSet;
class vtkPolyData;
class vtkUnstructuredGrid;

namespace thintissue
{

THINTISSUEVTKCORE_EXPORT extern const char* const CornerTextureCoordinatesArrayName;
THINTISSUEVTKCORE_EXPORT extern const char* const FixedNodeArrayName;

/// Triangle mesh -> polydata with the arrays above.
THINTISSUEVTKCORE_EXPORT vtkSmartPointer<vtkPolyData> toPolyData(const TriangleMesh& mesh);

/// Polydata -> triangle mesh. Polygons are fan-triangulated and strips
/// split; vertices, lines and empty cells are ignored. Throws
/// InvalidInputError naming `name` on NaN coordinates or inconsistent arrays.
THINTISSUEVTKCORE_EXPORT TriangleMesh fromPolyData(vtkPolyData* polyData, const std::string& name);

/// Hexahedral mesh -> unstructured grid of VTK_HEXAHEDRON cells.
THINTISSUEVTKCORE_EXPORT vtkSmartPointer<vtkUnstructuredGrid> toUnstructuredGrid(
  const HexahedralMesh& mesh);

/// Unstructured grid (or any data set) of hexahedra -> hexahedral mesh.
/// Throws InvalidInputError naming `name` if a cell is not a hexahedron.
THINTISSUEVTKCORE_EXPORT HexahedralMesh fromUnstructuredGrid(vtkDataSet* grid,
  const std::string& name);

/// The embedding a polydata carries (point arrays "HexahedronId" and
/// "TrilinearCoordinates" of vtkHexahedralEmbeddingFilter) in `mesh`.
/// Throws InvalidInputError naming `name` when the arrays are missing or
/// malformed or refer to hexahedra `mesh` does not have.
THINTISSUEVTKCORE_EXPORT HexahedralEmbedding embeddingFromPolyData(vtkPolyData* polyData,
  const HexahedralMesh& mesh,
  const std::string& name);

} // namespace thintissue

#endif
