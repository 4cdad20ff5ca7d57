#include "vtkInstrumentBladeSource.h"

#include "InstrumentAction.h"
#include "vtkThinTissueConversion.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMatrix4x4.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <algorithm>

vtkStandardNewMacro(vtkInstrumentBladeSource);

namespace
{

thintissue::RigidPose poseOf(vtkMatrix4x4* matrix)
{
  thintissue::RigidPose pose;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      pose.rotation(r, c) = matrix->GetElement(r, c);
    }
    pose.translation[r] = matrix->GetElement(r, 3);
  }
  return pose;
}

} // namespace

vtkInstrumentBladeSource::vtkInstrumentBladeSource()
{
  this->SetNumberOfInputPorts(0);
}

vtkInstrumentBladeSource::~vtkInstrumentBladeSource() = default;

void vtkInstrumentBladeSource::SetPose(vtkMatrix4x4* pose)
{
  if (pose)
  {
    this->Pose->DeepCopy(pose);
    this->Modified();
  }
}

void vtkInstrumentBladeSource::SetPreviousPose(vtkMatrix4x4* pose)
{
  if (pose)
  {
    this->PreviousPose->DeepCopy(pose);
    this->Modified();
  }
}

vtkMTimeType vtkInstrumentBladeSource::GetMTime()
{
  return std::max(
    { this->Superclass::GetMTime(), this->Pose->GetMTime(), this->PreviousPose->GetMTime() });
}

int vtkInstrumentBladeSource::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  using namespace thintissue;
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  try
  {
    const SurgicalInstrumentType type = allSurgicalInstrumentTypes()[this->Instrument];
    const InstrumentAction action(makeSurgicalInstrument(type));
    InstrumentCommand before, now;
    before.pose = poseOf(this->PreviousPose);
    before.jawOpening = this->PreviousJawOpening;
    now.pose = poseOf(this->Pose);
    now.jawOpening = this->JawOpening;
    const Blade blade = action.bladeBetween(before, now);
    TriangleMesh mesh;
    mesh.name = instrumentTypeName(type) + " blade";
    mesh.positions = blade.points;
    mesh.triangles = blade.triangles;
    output->ShallowCopy(toPolyData(mesh));
  }
  catch (const std::exception& error)
  {
    vtkErrorMacro(<< error.what());
    output->Initialize();
  }
  return 1;
}

void vtkInstrumentBladeSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Instrument: " << this->Instrument << "\n";
  os << indent << "JawOpening: " << this->JawOpening << "\n";
  os << indent << "PreviousJawOpening: " << this->PreviousJawOpening << "\n";
  os << indent << "Pose:\n";
  this->Pose->PrintSelf(os, indent.GetNextIndent());
  os << indent << "PreviousPose:\n";
  this->PreviousPose->PrintSelf(os, indent.GetNextIndent());
}
