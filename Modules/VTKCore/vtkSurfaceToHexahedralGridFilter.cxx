#include "vtkSurfaceToHexahedralGridFilter.h"

#include "SparseHexahedralGrid.h"
#include "vtkThinTissueConversion.h"

#include <vtkCellData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <exception>

vtkStandardNewMacro(vtkSurfaceToHexahedralGridFilter);

int vtkSurfaceToHexahedralGridFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkSurfaceToHexahedralGridFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  try
  {
    const thintissue::TriangleMesh surface = thintissue::fromPolyData(input, "input surface");
    this->UpdateProgress(0.2);
    thintissue::SparseHexahedralGridSettings settings;
    settings.cellsAlongLongestSide = this->CellsAlongLongestSide;
    settings.cellSize = this->CellSize;
    const thintissue::SparseHexahedralGrid grid =
      thintissue::SparseHexahedralGrid::fromSurface(surface, settings);
    this->UpdateProgress(0.8);

    output->ShallowCopy(thintissue::toUnstructuredGrid(grid.mesh));
    const vtkIdType cells = static_cast<vtkIdType>(grid.mesh.hexahedronCount());
    vtkNew<vtkIntArray> indices;
    indices->SetName("GridIndex");
    indices->SetNumberOfComponents(3);
    indices->SetNumberOfTuples(cells);
    vtkNew<vtkUnsignedCharArray> intersects;
    intersects->SetName("IntersectsSurface");
    intersects->SetNumberOfTuples(cells);
    for (vtkIdType c = 0; c < cells; ++c)
    {
      indices->SetTypedTuple(c, grid.cellIndices[static_cast<std::size_t>(c)].data());
      intersects->SetValue(c, grid.intersectsSurface[static_cast<std::size_t>(c)]);
    }
    output->GetCellData()->AddArray(indices);
    output->GetCellData()->AddArray(intersects);
    for (int a = 0; a < 3; ++a)
    {
      this->GridOrigin[a] = grid.origin[a];
      this->GridDimensions[a] = grid.cellCounts[a];
    }
    this->GridCellSize = grid.cellSize;
  }
  catch (const std::exception& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkSurfaceToHexahedralGridFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CellsAlongLongestSide: " << this->CellsAlongLongestSide << "\n";
  os << indent << "CellSize: " << this->CellSize << "\n";
  os << indent << "GridCellSize: " << this->GridCellSize << "\n";
  os << indent << "GridDimensions: " << this->GridDimensions[0] << " " << this->GridDimensions[1]
     << " " << this->GridDimensions[2] << "\n";
}
