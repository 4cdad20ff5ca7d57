#include "vtkHexahedralEmbeddingFilter.h"

#include "HexahedralEmbedding.h"
#include "vtkThinTissueConversion.h"

#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <exception>
#include <vector>

vtkStandardNewMacro(vtkHexahedralEmbeddingFilter);

vtkHexahedralEmbeddingFilter::vtkHexahedralEmbeddingFilter()
{
  this->SetNumberOfInputPorts(2);
}

void vtkHexahedralEmbeddingFilter::SetGridConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

void vtkHexahedralEmbeddingFilter::SetGridData(vtkUnstructuredGrid* grid)
{
  this->SetInputData(1, grid);
}

int vtkHexahedralEmbeddingFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(
    vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkPolyData" : "vtkUnstructuredGrid");
  return 1;
}

int vtkHexahedralEmbeddingFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkUnstructuredGrid* grid = vtkUnstructuredGrid::GetData(inputVector[1], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->NumberOfOutsidePoints = 0;
  this->NumberOfClampedPoints = 0;
  if (input == nullptr || grid == nullptr)
  {
    vtkErrorMacro(<< "needs a polydata (input 0) and a hexahedral grid (input 1)");
    return 0;
  }
  try
  {
    const thintissue::HexahedralMesh mesh = thintissue::fromUnstructuredGrid(grid, "input 1");
    const vtkIdType count = input->GetNumberOfPoints();
    std::vector<thintissue::Vector3> points(static_cast<std::size_t>(count));
    for (vtkIdType i = 0; i < count; ++i)
    {
      input->GetPoint(i, points[static_cast<std::size_t>(i)].data());
    }
    this->UpdateProgress(0.1);
    thintissue::HexahedralEmbeddingSettings settings;
    settings.maximumExtrapolation = this->MaximumExtrapolation;
    settings.insideTolerance = this->InsideTolerance;
    const thintissue::HexahedralEmbedding embedding(mesh, points, settings);
    this->UpdateProgress(0.9);

    vtkNew<vtkIdTypeArray> hexahedra;
    hexahedra->SetName(GetHexahedronIdArrayName());
    hexahedra->SetNumberOfTuples(count);
    vtkNew<vtkDoubleArray> coordinates;
    coordinates->SetName(GetTrilinearCoordinatesArrayName());
    coordinates->SetNumberOfComponents(3);
    coordinates->SetNumberOfTuples(count);
    for (vtkIdType i = 0; i < count; ++i)
    {
      const std::size_t point = static_cast<std::size_t>(i);
      hexahedra->SetValue(i, embedding.hexahedron(point));
      coordinates->SetTypedTuple(i, embedding.localCoordinates(point).data());
    }
    output->ShallowCopy(input);
    output->GetPointData()->AddArray(hexahedra);
    output->GetPointData()->AddArray(coordinates);
    this->NumberOfOutsidePoints = static_cast<vtkIdType>(embedding.outsidePointCount());
    this->NumberOfClampedPoints = static_cast<vtkIdType>(embedding.clampedPointCount());
  }
  catch (const std::exception& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkHexahedralEmbeddingFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumExtrapolation: " << this->MaximumExtrapolation << "\n";
  os << indent << "InsideTolerance: " << this->InsideTolerance << "\n";
  os << indent << "NumberOfOutsidePoints: " << this->NumberOfOutsidePoints << "\n";
  os << indent << "NumberOfClampedPoints: " << this->NumberOfClampedPoints << "\n";
}
