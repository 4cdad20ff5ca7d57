#include "vtkThickenOpenSheetsFilter.h"

#include "SheetThickening.h"
#include "ThinTissueError.h"
#include "vtkThinTissueConversion.h"

#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <exception>

vtkStandardNewMacro(vtkThickenOpenSheetsFilter);

namespace
{
void addFieldValue(vtkPolyData* output, const char* name, int value)
{
  vtkNew<vtkIntArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  output->GetFieldData()->AddArray(array);
}
} // namespace

int vtkThickenOpenSheetsFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputs,
  vtkInformationVector* outputs)
{
  vtkPolyData* input = vtkPolyData::GetData(inputs[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputs, 0);
  this->LastErrorMessage.clear();
  this->ThickenedPieces = 0;
  this->BorderLoops = 0;
  output->Initialize();
  try
  {
    if (input == nullptr)
    {
      throw thintissue::InvalidInputError("vtkThickenOpenSheetsFilter: no input surface");
    }
    thintissue::TriangleMesh sheet = thintissue::fromPolyData(input, "sheet input");
    thintissue::SheetThickeningReport report;
    output->ShallowCopy(
      thintissue::toPolyData(thintissue::thickenOpenSheets(sheet, this->Thickness, &report)));
    this->ThickenedPieces = report.thickenedPieces;
    this->BorderLoops = report.borderLoops;
    addFieldValue(output, "ThickenedPieces", report.thickenedPieces);
    addFieldValue(output, "BorderLoops", report.borderLoops);
  }
  catch (const std::exception& error)
  {
    output->Initialize();
    this->LastErrorMessage = error.what();
    vtkErrorMacro(<< this->LastErrorMessage);
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkThickenOpenSheetsFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Thickness: " << this->Thickness << "\n"
     << indent << "ThickenedPieces: " << this->ThickenedPieces << "\n"
     << indent << "BorderLoops: " << this->BorderLoops << "\n"
     << indent << "LastErrorMessage: " << this->LastErrorMessage << "\n";
}
