#include "vtkCollisionMidSurfaceFilter.h"

#include "CollisionMeshGeneration.h"
#include "ThinTissueError.h"
#include "vtkThinTissueConversion.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <exception>

vtkStandardNewMacro(vtkCollisionMidSurfaceFilter);

namespace
{
void addFieldValue(vtkPolyData* output, const char* name, const double* values, int components)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->InsertNextTuple(values);
  output->GetFieldData()->AddArray(array);
}
} // namespace

vtkCollisionMidSurfaceFilter::vtkCollisionMidSurfaceFilter()
{
  this->SetRadiusArrayName("Radius");
}

vtkCollisionMidSurfaceFilter::~vtkCollisionMidSurfaceFilter()
{
  this->SetRadiusArrayName(nullptr);
}

int vtkCollisionMidSurfaceFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputs,
  vtkInformationVector* outputs)
{
  vtkPolyData* input = vtkPolyData::GetData(inputs[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputs, 0);
  this->LastErrorMessage.clear();
  this->HausdorffDistance = 0.0;
  this->ThicknessRatio = 0.0;
  this->JoinedHoles = 0;
  output->Initialize();
  thintissue::CollisionMeshSettings settings;
  settings.vertexCount = this->VertexCount;
  settings.maximumThicknessRatio = this->MaximumThicknessRatio;
  settings.joinSeenThroughHoles = this->JoinSeenThroughHoles;
  settings.latticePhase = this->LatticePhase;
  settings.radiusArrayName = this->RadiusArrayName != nullptr ? this->RadiusArrayName : "";
  const thintissue::GenerationProgress progress = [this](double fraction, const char* stage)
  {
    this->SetProgressText(stage);
    this->UpdateProgress(fraction);
    return !this->GetAbortExecute();
  };
  try
  {
    if (input == nullptr)
    {
      throw thintissue::InvalidInputError("vtkCollisionMidSurfaceFilter: no input surface");
    }
    if (settings.radiusArrayName.empty())
    {
      throw thintissue::InvalidInputError("vtkCollisionMidSurfaceFilter: RadiusArrayName is empty");
    }
    const thintissue::TriangleMesh visual = thintissue::fromPolyData(input, "visual input");
    const thintissue::GeneratedCollisionMesh generated =
      thintissue::makeCollisionMidSurface(visual, settings, progress);
    output->ShallowCopy(thintissue::toPolyData(generated.mesh));
    this->HausdorffDistance = generated.hausdorffDistance;
    this->ThicknessRatio = generated.thicknessRatio;
    this->JoinedHoles = generated.joinedHoles;
    addFieldValue(output, "HausdorffDistance", &generated.hausdorffDistance, 1);
    addFieldValue(output, "ThicknessRatio", &generated.thicknessRatio, 1);
    addFieldValue(output, "ThicknessAxis", generated.thicknessAxis.data(), 3);
  }
  catch (const thintissue::GenerationAbortedError& aborted)
  {
    output->Initialize();
    this->LastErrorMessage = aborted.what();
    vtkWarningMacro(<< this->LastErrorMessage);
    return 1;
  }
  catch (const std::exception& error)
  {
    output->Initialize();
    this->LastErrorMessage = error.what();
    vtkErrorMacro(<< this->LastErrorMessage);
    return 0;
  }
  this->SetProgressText("done");
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCollisionMidSurfaceFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VertexCount: " << this->VertexCount << "\n"
     << indent << "MaximumThicknessRatio: " << this->MaximumThicknessRatio << "\n"
     << indent << "RadiusArrayName: " << (this->RadiusArrayName ? this->RadiusArrayName : "(none)")
     << "\n"
     << indent << "HausdorffDistance: " << this->HausdorffDistance << "\n"
     << indent << "JoinSeenThroughHoles: " << (this->JoinSeenThroughHoles ? "on" : "off") << "\n"
     << indent << "LatticePhase: " << this->LatticePhase << "\n"
     << indent << "ThicknessRatio: " << this->ThicknessRatio << "\n"
     << indent << "JoinedHoles: " << this->JoinedHoles << "\n"
     << indent << "LastErrorMessage: " << this->LastErrorMessage << "\n";
}
