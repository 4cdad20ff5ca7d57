#include "vtkThinSlabSource.h"

#include "MeshPrimitives.h"
#include "vtkThinTissueConversion.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(vtkThinSlabSource);

vtkThinSlabSource::vtkThinSlabSource()
{
  this->SetNumberOfInputPorts(0);
}

int vtkThinSlabSource::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  try
  {
    thintissue::SlabSurfaceParameters parameters;
    parameters.width = this->Width;
    parameters.depth = this->Depth;
    parameters.thickness = this->Thickness;
    parameters.cellsX = this->CellsX;
    parameters.cellsY = this->CellsY;
    parameters.cellsZ = this->CellsZ;
    output->ShallowCopy(thintissue::toPolyData(thintissue::makeSlabSurface(parameters)));
  }
  catch (const std::exception& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  return 1;
}

void vtkThinSlabSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Width: " << this->Width << "\n";
  os << indent << "Depth: " << this->Depth << "\n";
  os << indent << "Thickness: " << this->Thickness << "\n";
  os << indent << "Cells: " << this->CellsX << " x " << this->CellsY << " x " << this->CellsZ
     << "\n";
}
