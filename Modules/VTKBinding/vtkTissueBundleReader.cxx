#include "vtkTissueBundleReader.h"

#include "ThinTissueError.h"
#include "TissueBundle.h"
#include "vtkBindingConversion.h"
#include "vtkThinTissueConversion.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

#include <exception>
#include <initializer_list>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkTissueBundleReader);

namespace
{

/// The bundle's length units as field data of each output (when recorded).
void addUnits(const thintissue::TissueBundle& bundle, std::initializer_list<vtkDataObject*> outputs)
{
  if (!bundle.units)
  {
    return;
  }
  for (vtkDataObject* output : outputs)
  {
    vtkNew<vtkStringArray> name;
    name->SetName("LengthUnits");
    name->InsertNextValue(bundle.units->name);
    vtkNew<vtkDoubleArray> scale;
    scale->SetName("MetresPerUnit");
    scale->InsertNextValue(bundle.units->metresPerUnit);
    output->GetFieldData()->AddArray(name);
    output->GetFieldData()->AddArray(scale);
  }
}

} // namespace

vtkTissueBundleReader::vtkTissueBundleReader()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(3);
}

vtkTissueBundleReader::~vtkTissueBundleReader()
{
  this->SetFileName(nullptr);
}

int vtkTissueBundleReader::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(),
    port == SimulationPort ? "vtkUnstructuredGrid" : "vtkPolyData");
  return 1;
}

vtkPolyData* vtkTissueBundleReader::GetVisualOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(VisualPort));
}

vtkPolyData* vtkTissueBundleReader::GetCollisionOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(CollisionPort));
}

vtkUnstructuredGrid* vtkTissueBundleReader::GetSimulationOutput()
{
  return vtkUnstructuredGrid::SafeDownCast(this->GetOutputDataObject(SimulationPort));
}

int vtkTissueBundleReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputs)
{
  vtkPolyData* visual = vtkPolyData::GetData(outputs, VisualPort);
  vtkPolyData* collision = vtkPolyData::GetData(outputs, CollisionPort);
  vtkUnstructuredGrid* simulation = vtkUnstructuredGrid::GetData(outputs, SimulationPort);
  this->LastErrorMessage.clear();
  this->NumberOfTissues = 0;
  visual->Initialize();
  collision->Initialize();
  simulation->Initialize();
  try
  {
    if (this->FileName == nullptr || this->FileName[0] == '\0')
    {
      throw thintissue::InvalidInputError("vtkTissueBundleReader: no FileName");
    }
    const std::vector<thintissue::TissueBundle> bundles =
      thintissue::readTissueBundles(this->FileName);
    this->NumberOfTissues = static_cast<int>(bundles.size());
    if (this->TissueIndex >= this->NumberOfTissues)
    {
      throw thintissue::InvalidInputError(
        "vtkTissueBundleReader: TissueIndex " + std::to_string(this->TissueIndex) + " but '" +
        this->FileName + "' holds " + std::to_string(this->NumberOfTissues) + " tissue" +
        (this->NumberOfTissues == 1 ? "" : "s"));
    }
    const thintissue::TissueBundle& bundle = bundles[this->TissueIndex];
    visual->ShallowCopy(thintissue::boundVisualPolyData(bundle.binding));
    vtkNew<vtkStringArray> metadata;
    metadata->SetName("Metadata");
    metadata->InsertNextValue(bundle.metadata);
    visual->GetFieldData()->AddArray(metadata);
    collision->ShallowCopy(thintissue::toPolyData(bundle.collision));
    simulation->ShallowCopy(thintissue::toUnstructuredGrid(bundle.simulation));
    addUnits(bundle, { visual, collision, simulation });
  }
  catch (const std::exception& error)
  {
    visual->Initialize();
    collision->Initialize();
    simulation->Initialize();
    this->LastErrorMessage = error.what();
    vtkErrorMacro(<< this->LastErrorMessage);
    return 0;
  }
  return 1;
}

void vtkTissueBundleReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n"
     << indent << "TissueIndex: " << this->TissueIndex << "\n"
     << indent << "NumberOfTissues: " << this->NumberOfTissues << "\n"
     << indent << "LastErrorMessage: " << this->LastErrorMessage << "\n";
}
