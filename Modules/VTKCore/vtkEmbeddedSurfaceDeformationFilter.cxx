#include "vtkEmbeddedSurfaceDeformationFilter.h"

#include "HexahedralEmbedding.h"
#include "ThinTissueError.h"
#include "vtkHexahedralEmbeddingFilter.h"
#include "vtkThinTissueConversion.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <exception>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkEmbeddedSurfaceDeformationFilter);

namespace
{

using thintissue::Vector3;

// Twice the area vector of polygon `ids` (Newell's method).
Vector3 polygonAreaVector(vtkIdType size, const vtkIdType* ids, const Vector3* points)
{
  Vector3 sum = Vector3::Zero();
  for (vtkIdType k = 0; k < size; ++k)
  {
    sum += points[ids[k]].cross(points[ids[(k + 1) % size]]);
  }
  return sum;
}

// A new array like `original` (same name and type family) holding `values`.
vtkSmartPointer<vtkDataArray> makeNormalsArray(vtkDataArray* original,
  const std::vector<Vector3>& values)
{
  vtkSmartPointer<vtkDataArray> normals;
  if (vtkFloatArray::SafeDownCast(original) != nullptr)
  {
    normals = vtkSmartPointer<vtkFloatArray>::New();
  }
  else
  {
    normals = vtkSmartPointer<vtkDoubleArray>::New();
  }
  normals->SetName(original->GetName());
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    normals->SetTuple(static_cast<vtkIdType>(i), values[i].data());
  }
  return normals;
}

void recomputeNormals(vtkPolyData* output, const Vector3* points)
{
  vtkDataArray* pointNormals = output->GetPointData()->GetNormals();
  vtkDataArray* cellNormals = output->GetCellData()->GetNormals();
  if (pointNormals == nullptr && cellNormals == nullptr)
  {
    return;
  }
  const vtkIdType pointCount = output->GetNumberOfPoints();
  std::vector<Vector3> atPoints(static_cast<std::size_t>(pointCount), Vector3::Zero());
  std::vector<Vector3> atCells;
  const vtkIdType firstPolygon = output->GetNumberOfVerts() + output->GetNumberOfLines();
  if (cellNormals != nullptr)
  {
    // Cells other than polygons keep their normals.
    atCells.resize(static_cast<std::size_t>(output->GetNumberOfCells()), Vector3::Zero());
    for (vtkIdType c = 0; c < output->GetNumberOfCells(); ++c)
    {
      cellNormals->GetTuple(c, atCells[static_cast<std::size_t>(c)].data());
    }
  }
  auto polygons = vtk::TakeSmartPointer(output->GetPolys()->NewIterator());
  vtkIdType cell = firstPolygon;
  for (polygons->GoToFirstCell(); !polygons->IsDoneWithTraversal();
       polygons->GoToNextCell(), ++cell)
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    polygons->GetCurrentCell(size, ids);
    const Vector3 area = polygonAreaVector(size, ids, points);
    for (vtkIdType k = 0; k < size; ++k)
    {
      atPoints[static_cast<std::size_t>(ids[k])] += area;
    }
    if (!atCells.empty() && static_cast<std::size_t>(cell) < atCells.size())
    {
      const double length = area.norm();
      atCells[static_cast<std::size_t>(cell)] = length > 0.0 ? Vector3(area / length) : area;
    }
  }
  if (pointNormals != nullptr)
  {
    for (Vector3& n : atPoints)
    {
      const double length = n.norm();
      if (length > 0.0)
      {
        n /= length;
      }
    }
    output->GetPointData()->SetNormals(makeNormalsArray(pointNormals, atPoints));
  }
  if (cellNormals != nullptr)
  {
    output->GetCellData()->SetNormals(makeNormalsArray(cellNormals, atCells));
  }
}

} // namespace

vtkEmbeddedSurfaceDeformationFilter::vtkEmbeddedSurfaceDeformationFilter()
{
  this->SetNumberOfInputPorts(2);
}

void vtkEmbeddedSurfaceDeformationFilter::SetGridConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

void vtkEmbeddedSurfaceDeformationFilter::SetGridData(vtkUnstructuredGrid* grid)
{
  this->SetInputData(1, grid);
}

int vtkEmbeddedSurfaceDeformationFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(
    vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkPolyData" : "vtkUnstructuredGrid");
  return 1;
}

int vtkEmbeddedSurfaceDeformationFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkUnstructuredGrid* grid = vtkUnstructuredGrid::GetData(inputVector[1], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (input == nullptr || grid == nullptr)
  {
    vtkErrorMacro(<< "needs an embedded polydata (input 0) and a hexahedral grid (input 1)");
    return 0;
  }
  try
  {
    const thintissue::HexahedralMesh mesh =
      thintissue::fromUnstructuredGrid(grid, "deformed grid, input 1");
    const thintissue::HexahedralEmbedding embedding =
      thintissue::embeddingFromPolyData(input, mesh, "embedded polydata (input 0)");
    const vtkIdType count = input->GetNumberOfPoints();
    this->UpdateProgress(0.3);

    vtkNew<vtkDoubleArray> moved;
    moved->SetNumberOfComponents(3);
    moved->SetNumberOfTuples(count);
    Vector3* movedPoints = reinterpret_cast<Vector3*>(moved->GetPointer(0));
    static_assert(sizeof(Vector3) == 3 * sizeof(double), "Vector3 must be three packed doubles");
    embedding.mapPositions(mesh.nodes.data(), movedPoints);
    this->UpdateProgress(0.7);

    output->ShallowCopy(input);
    vtkNew<vtkPoints> points;
    points->SetData(moved);
    output->SetPoints(points);
    if (this->RecomputeNormals)
    {
      recomputeNormals(output, movedPoints);
    }
  }
  catch (const std::exception& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkEmbeddedSurfaceDeformationFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RecomputeNormals: " << (this->RecomputeNormals ? "On" : "Off") << "\n";
}
