#include "vtkThinTissueConversion.h"

#include "ThinTissueError.h"
#include "vtkHexahedralEmbeddingFilter.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <cstring>
#include <map>

namespace thintissue
{

const char* const CornerTextureCoordinatesArrayName = "CornerTextureCoordinates";
const char* const FixedNodeArrayName = "FixedNode";

namespace
{

vtkSmartPointer<vtkPoints> makePoints(const std::vector<Vector3>& positions)
{
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(static_cast<vtkIdType>(positions.size()));
  // An empty array's pointer is null, and memcpy from or to null is undefined.
  if (!positions.empty())
  {
    std::memcpy(coordinates->GetPointer(0), positions.data(), positions.size() * sizeof(Vector3));
  }
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetData(coordinates);
  return points;
}

std::vector<Vector3> readPoints(vtkPoints* points)
{
  std::vector<Vector3> positions;
  if (points == nullptr)
  {
    return positions;
  }
  positions.resize(static_cast<std::size_t>(points->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    points->GetPoint(i, positions[i].data());
  }
  return positions;
}

void addAttributeArrays(const VertexAttributes& attributes, vtkPointData* pointData)
{
  for (const std::string& name : attributes.names())
  {
    const AttributeArray& source = attributes.get(name);
    vtkNew<vtkDoubleArray> array;
    array->SetName(name.c_str());
    array->SetNumberOfComponents(source.components);
    array->SetNumberOfTuples(static_cast<vtkIdType>(source.elementCount()));
    std::copy(source.values.begin(), source.values.end(), array->GetPointer(0));
    pointData->AddArray(array);
  }
}

/// Every numeric point array not in `skip` becomes an attribute.
void readAttributeArrays(vtkPointData* pointData,
  std::initializer_list<const char*> skip,
  VertexAttributes& attributes)
{
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pointData->GetArray(a);
    if (array == nullptr || array->GetName() == nullptr)
    {
      continue;
    }
    bool skipped = false;
    for (const char* name : skip)
    {
      skipped |= std::strcmp(array->GetName(), name) == 0;
    }
    if (skipped)
    {
      continue;
    }
    const int components = array->GetNumberOfComponents();
    std::vector<double> values(static_cast<std::size_t>(array->GetNumberOfTuples()) * components);
    for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
    {
      array->GetTuple(i, values.data() + i * components);
    }
    attributes.set(array->GetName(), components, std::move(values));
  }
}

vtkSmartPointer<vtkCellArray> makeCells(const int* connectivity, std::size_t cellCount, int size)
{
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfTuples(static_cast<vtkIdType>(cellCount + 1));
  vtkNew<vtkIdTypeArray> ids;
  ids->SetNumberOfTuples(static_cast<vtkIdType>(cellCount * size));
  for (std::size_t c = 0; c <= cellCount; ++c)
  {
    offsets->SetValue(static_cast<vtkIdType>(c), static_cast<vtkIdType>(c * size));
  }
  for (std::size_t i = 0; i < cellCount * size; ++i)
  {
    ids->SetValue(static_cast<vtkIdType>(i), connectivity[i]);
  }
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, ids);
  return cells;
}

} // namespace

vtkSmartPointer<vtkPolyData> toPolyData(const TriangleMesh& mesh)
{
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(makePoints(mesh.positions));
  polyData->SetPolys(makeCells(
    mesh.triangles.empty() ? nullptr : mesh.triangles.data()->data(), mesh.triangles.size(), 3));

  if (mesh.hasNormals())
  {
    vtkNew<vtkDoubleArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(static_cast<vtkIdType>(mesh.normals.size()));
    std::memcpy(normals->GetPointer(0), mesh.normals.data(), mesh.normals.size() * sizeof(Vector3));
    polyData->GetPointData()->SetNormals(normals);
  }
  if (mesh.hasTextureCoordinates())
  {
    vtkNew<vtkDoubleArray> corners;
    corners->SetName(CornerTextureCoordinatesArrayName);
    corners->SetNumberOfComponents(6);
    corners->SetNumberOfTuples(static_cast<vtkIdType>(mesh.triangles.size()));
    // Point coordinates exist only where no vertex has two texture
    // coordinates (no seam); a seam needs the per-corner cell array.
    std::vector<int> pointTexture(mesh.positions.size(), -1);
    bool seamFree = true;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    {
      double* tuple = corners->GetPointer(static_cast<vtkIdType>(6 * t));
      for (int k = 0; k < 3; ++k)
      {
        const int c = mesh.textureCorners[t][k];
        tuple[2 * k] = mesh.textureCoordinates[c].x();
        tuple[2 * k + 1] = mesh.textureCoordinates[c].y();
        int& assigned = pointTexture[mesh.triangles[t][k]];
        if (assigned >= 0 && mesh.textureCoordinates[assigned] != mesh.textureCoordinates[c])
        {
          seamFree = false;
        }
        assigned = c;
      }
    }
    polyData->GetCellData()->AddArray(corners);
    if (seamFree)
    {
      vtkNew<vtkDoubleArray> tcoords;
      tcoords->SetName("TCoords");
      tcoords->SetNumberOfComponents(2);
      tcoords->SetNumberOfTuples(static_cast<vtkIdType>(mesh.positions.size()));
      for (std::size_t v = 0; v < mesh.positions.size(); ++v)
      {
        const Vector2 uv =
          pointTexture[v] >= 0 ? mesh.textureCoordinates[pointTexture[v]] : Vector2::Zero();
        tcoords->SetTuple2(static_cast<vtkIdType>(v), uv.x(), uv.y());
      }
      polyData->GetPointData()->SetTCoords(tcoords);
    }
  }
  addAttributeArrays(mesh.pointAttributes, polyData->GetPointData());
  return polyData;
}

TriangleMesh fromPolyData(vtkPolyData* polyData, const std::string& name)
{
  if (polyData == nullptr)
  {
    throw InvalidInputError("mesh '" + name + "': no polydata");
  }
  TriangleMesh mesh;
  mesh.name = name;
  mesh.positions = readPoints(polyData->GetPoints());

  // Polygons, fan-triangulated; remember the source cell of each triangle.
  std::vector<vtkIdType> sourceCell;
  vtkIdType cellId = polyData->GetNumberOfVerts() + polyData->GetNumberOfLines();
  auto polygons = vtk::TakeSmartPointer(polyData->GetPolys()->NewIterator());
  bool allTriangles = true;
  for (polygons->GoToFirstCell(); !polygons->IsDoneWithTraversal();
       polygons->GoToNextCell(), ++cellId)
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    polygons->GetCurrentCell(size, ids);
    allTriangles &= size == 3;
    for (vtkIdType k = 1; k + 1 < size; ++k)
    {
      mesh.triangles.push_back(
        { static_cast<int>(ids[0]), static_cast<int>(ids[k]), static_cast<int>(ids[k + 1]) });
      sourceCell.push_back(cellId);
    }
  }
  auto strips = vtk::TakeSmartPointer(polyData->GetStrips()->NewIterator());
  for (strips->GoToFirstCell(); !strips->IsDoneWithTraversal(); strips->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    strips->GetCurrentCell(size, ids);
    allTriangles = false;
    for (vtkIdType k = 0; k + 2 < size; ++k)
    {
      // Every other triangle of a strip is reversed to keep the orientation.
      const int a = static_cast<int>(ids[k]);
      const int b = static_cast<int>(ids[k + 1]);
      const int c = static_cast<int>(ids[k + 2]);
      mesh.triangles.push_back(k % 2 == 0 ? Triangle{ a, b, c } : Triangle{ b, a, c });
    }
  }
  mesh.checkConsistency();

  vtkPointData* pointData = polyData->GetPointData();
  vtkDataArray* normals = pointData->GetNormals();
  if (normals == nullptr)
  {
    normals = pointData->GetArray("Normals");
  }
  if (normals != nullptr && normals->GetNumberOfComponents() == 3)
  {
    mesh.normals.resize(mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    {
      normals->GetTuple(static_cast<vtkIdType>(v), mesh.normals[v].data());
    }
  }

  vtkDataArray* corners = polyData->GetCellData()->GetArray(CornerTextureCoordinatesArrayName);
  vtkDataArray* tcoords = pointData->GetTCoords();
  if (corners != nullptr && corners->GetNumberOfComponents() == 6 && allTriangles &&
      polyData->GetNumberOfVerts() + polyData->GetNumberOfLines() == 0)
  {
    // Per-corner data: rebuild the list of distinct coordinates.
    std::map<std::pair<double, double>, int> distinct;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    {
      double tuple[6];
      corners->GetTuple(sourceCell[t], tuple);
      Triangle corner;
      for (int k = 0; k < 3; ++k)
      {
        const auto key = std::make_pair(tuple[2 * k], tuple[2 * k + 1]);
        auto found = distinct.emplace(key, static_cast<int>(mesh.textureCoordinates.size()));
        if (found.second)
        {
          mesh.textureCoordinates.emplace_back(key.first, key.second);
        }
        corner[k] = found.first->second;
      }
      mesh.textureCorners.push_back(corner);
    }
  }
  else if (tcoords != nullptr && tcoords->GetNumberOfComponents() >= 2)
  {
    mesh.textureCoordinates.resize(mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    {
      const double* uv = tcoords->GetTuple(static_cast<vtkIdType>(v));
      mesh.textureCoordinates[v] = Vector2(uv[0], uv[1]);
    }
    mesh.textureCorners = mesh.triangles;
  }

  const char* normalsName = normals != nullptr ? normals->GetName() : nullptr;
  const char* tcoordsName = tcoords != nullptr ? tcoords->GetName() : nullptr;
  readAttributeArrays(pointData,
    { normalsName ? normalsName : "Normals", tcoordsName ? tcoordsName : "TCoords" },
    mesh.pointAttributes);
  mesh.checkConsistency();
  return mesh;
}

vtkSmartPointer<vtkUnstructuredGrid> toUnstructuredGrid(const HexahedralMesh& mesh)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(makePoints(mesh.nodes));
  grid->SetCells(VTK_HEXAHEDRON,
    makeCells(
      mesh.hexahedra.empty() ? nullptr : mesh.hexahedra.data()->data(), mesh.hexahedra.size(), 8));
  if (!mesh.fixedNodes.empty())
  {
    vtkNew<vtkUnsignedCharArray> fixed;
    fixed->SetName(FixedNodeArrayName);
    fixed->SetNumberOfTuples(static_cast<vtkIdType>(mesh.fixedNodes.size()));
    std::copy(mesh.fixedNodes.begin(), mesh.fixedNodes.end(), fixed->GetPointer(0));
    grid->GetPointData()->AddArray(fixed);
  }
  addAttributeArrays(mesh.nodeAttributes, grid->GetPointData());
  return grid;
}

HexahedralMesh fromUnstructuredGrid(vtkDataSet* grid, const std::string& name)
{
  if (grid == nullptr)
  {
    throw InvalidInputError("hexahedral mesh '" + name + "': no data set");
  }
  HexahedralMesh mesh;
  mesh.name = name;
  mesh.nodes.resize(static_cast<std::size_t>(grid->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    grid->GetPoint(i, mesh.nodes[i].data());
  }
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    if (grid->GetCellType(c) != VTK_HEXAHEDRON)
    {
      throw InvalidInputError("hexahedral mesh '" + name + "': cell " + std::to_string(c) +
                              " is of VTK type " + std::to_string(grid->GetCellType(c)) +
                              ", not a hexahedron (12)");
    }
    grid->GetCellPoints(c, ids);
    Hexahedron hex;
    for (int k = 0; k < 8; ++k)
    {
      hex[k] = static_cast<int>(ids->GetId(k));
    }
    mesh.hexahedra.push_back(hex);
  }
  vtkDataArray* fixed = grid->GetPointData()->GetArray(FixedNodeArrayName);
  if (fixed != nullptr)
  {
    mesh.fixedNodes.resize(mesh.nodes.size());
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
    {
      mesh.fixedNodes[i] = fixed->GetComponent(static_cast<vtkIdType>(i), 0) != 0.0 ? 1 : 0;
    }
  }
  readAttributeArrays(grid->GetPointData(), { FixedNodeArrayName }, mesh.nodeAttributes);
  mesh.checkConsistency();
  return mesh;
}

HexahedralEmbedding embeddingFromPolyData(vtkPolyData* polyData,
  const HexahedralMesh& mesh,
  const std::string& name)
{
  const char* idName = vtkHexahedralEmbeddingFilter::GetHexahedronIdArrayName();
  const char* localName = vtkHexahedralEmbeddingFilter::GetTrilinearCoordinatesArrayName();
  vtkDataArray* ids = polyData->GetPointData()->GetArray(idName);
  vtkDataArray* locals = polyData->GetPointData()->GetArray(localName);
  const vtkIdType count = polyData->GetNumberOfPoints();
  if (ids == nullptr || locals == nullptr || ids->GetNumberOfComponents() != 1 ||
      locals->GetNumberOfComponents() != 3 || ids->GetNumberOfTuples() != count ||
      locals->GetNumberOfTuples() != count)
  {
    throw InvalidInputError(name + ": needs point arrays '" + idName + "' (1 component) and '" +
                            localName +
                            "' (3 components), one tuple per point; run "
                            "vtkHexahedralEmbeddingFilter first");
  }
  std::vector<int> hexahedra(static_cast<std::size_t>(count));
  std::vector<Vector3> coordinates(static_cast<std::size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    const double id = ids->GetComponent(i, 0);
    // Out-of-range values are caught by assign(); keep them out of range.
    hexahedra[static_cast<std::size_t>(i)] =
      std::isfinite(id) && id >= 0.0 && id < 2147483647.0 ? static_cast<int>(id) : -1;
    locals->GetTuple(i, coordinates[static_cast<std::size_t>(i)].data());
  }
  HexahedralEmbedding embedding;
  embedding.assign(mesh, std::move(hexahedra), std::move(coordinates));
  return embedding;
}

} // namespace thintissue
