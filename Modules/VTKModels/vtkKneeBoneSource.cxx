#include "vtkKneeBoneSource.h"

#include "KneeModels.h"
#include "ThinTissueError.h"
#include "vtkThinTissueConversion.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(vtkKneeBoneSource);

vtkKneeBoneSource::vtkKneeBoneSource()
  : JointGap(thintissue::knee::DefaultJointGap)
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
}

int vtkKneeBoneSource::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputs)
{
  try
  {
    thintissue::KneeSurroundingsParameters parameters;
    parameters.jointGap = this->JointGap;
    const thintissue::BoneModel bone =
      this->Bone == Tibia ? thintissue::makeTibia(parameters) : thintissue::makeFemur(parameters);
    vtkPolyData::GetData(outputs, 0)->ShallowCopy(thintissue::toPolyData(bone.visual));
    vtkPolyData::GetData(outputs, 1)->ShallowCopy(thintissue::toPolyData(bone.collision));
  }
  catch (const thintissue::Error& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  return 1;
}

void vtkKneeBoneSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Bone: " << (this->Bone == Tibia ? "tibia" : "femur") << "\n"
     << indent << "JointGap: " << this->JointGap << "\n";
}
