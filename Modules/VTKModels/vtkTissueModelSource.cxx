#include "vtkTissueModelSource.h"

#include "ThinTissueError.h"
#include "TissueModel.h"
#include "vtkThinTissueConversion.h"
#include "vtkTissueModelBlocks.h"

#include <vtkCompositeDataSet.h>
#include <vtkDataObject.h>
#include <vtkDemandDrivenPipeline.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

vtkTissueModelSource::vtkTissueModelSource()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(4);
}

void vtkTissueModelSource::SetNumberOfTissueOutputPorts(int count)
{
  this->SetNumberOfOutputPorts(count < 4 ? 4 : count);
}

void vtkTissueModelSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Output ports: visual, collision, simulation, all meshes ("
     << this->GetNumberOfOutputPorts() << " in all)\n";
}

int vtkTissueModelSource::FillOutputPortInformation(int port, vtkInformation* info)
{
  switch (port)
  {
    case VisualPort:
    case CollisionPort:
      info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkPolyData");
      return 1;
    case SimulationPort:
      info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkUnstructuredGrid");
      return 1;
    case AllMeshesPort:
      info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkMultiBlockDataSet");
      return 1;
    default:
      info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkPolyData");
      return 1;
  }
}

vtkPolyData* vtkTissueModelSource::GetVisualOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(VisualPort));
}

vtkPolyData* vtkTissueModelSource::GetCollisionOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(CollisionPort));
}

vtkUnstructuredGrid* vtkTissueModelSource::GetSimulationOutput()
{
  return vtkUnstructuredGrid::SafeDownCast(this->GetOutputDataObject(SimulationPort));
}

vtkMultiBlockDataSet* vtkTissueModelSource::GetAllMeshesOutput()
{
  return vtkMultiBlockDataSet::SafeDownCast(this->GetOutputDataObject(AllMeshesPort));
}

void vtkTissueModelSource::FillExtraOutputs(vtkInformationVector*, vtkMultiBlockDataSet*) {}

vtkTypeBool vtkTissueModelSource::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputs,
  vtkInformationVector* outputs)
{
  if (!request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->Superclass::ProcessRequest(request, inputs, outputs);
  }
  auto outputOf = [outputs](int port)
  { return outputs->GetInformationObject(port)->Get(vtkDataObject::DATA_OBJECT()); };
  auto* visual = vtkPolyData::SafeDownCast(outputOf(VisualPort));
  auto* collision = vtkPolyData::SafeDownCast(outputOf(CollisionPort));
  auto* simulation = vtkUnstructuredGrid::SafeDownCast(outputOf(SimulationPort));
  auto* all = vtkMultiBlockDataSet::SafeDownCast(outputOf(AllMeshesPort));
  if (!visual || !collision || !simulation || !all)
  {
    vtkErrorMacro("output data objects of the wrong type");
    return 0;
  }
  this->UpdateProgress(0.0);
  try
  {
    const thintissue::TissueModel model = this->BuildTissueModel();
    this->UpdateProgress(0.7);
    visual->ShallowCopy(thintissue::toPolyData(model.visual));
    collision->ShallowCopy(thintissue::toPolyData(model.collision));
    simulation->ShallowCopy(thintissue::toUnstructuredGrid(model.simulation));
    all->Initialize();
    const char* names[3] = { "Visual", "Collision", "Simulation" };
    vtkDataObject* blocks[3] = { visual, collision, simulation };
    for (int b = 0; b < 3; ++b)
    {
      vtkSmartPointer<vtkDataObject> copy;
      copy.TakeReference(blocks[b]->NewInstance());
      copy->ShallowCopy(blocks[b]);
      thintissue::appendNamedBlock(all, copy, names[b]);
    }
    this->FillExtraOutputs(outputs, all);
  }
  catch (const thintissue::Error& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}
