#include "vtkKneeSceneSource.h"

#include "KneeModels.h"
#include "MeniscusModel.h"
#include "ThinTissueError.h"
#include "vtkTissueModelBlocks.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>

vtkStandardNewMacro(vtkKneeSceneSource);

vtkKneeSceneSource::vtkKneeSceneSource()
  : JointGap(thintissue::knee::DefaultJointGap)
{
  this->SetNumberOfInputPorts(0);
}

int vtkKneeSceneSource::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputs)
{
  auto* scene = vtkMultiBlockDataSet::GetData(outputs, 0);
  try
  {
    thintissue::KneeSurroundingsParameters parameters;
    parameters.jointGap = this->JointGap;
    const auto knee = thintissue::makeKneeSurroundings(parameters);
    this->UpdateProgress(0.6);
    thintissue::MeniscusParameters meniscusParameters;
    meniscusParameters.tear = thintissue::defaultMeniscusTear(
      static_cast<thintissue::MeniscusTearType>(this->MeniscusTearType));
    const auto meniscus = thintissue::makeMeniscus(meniscusParameters);
    this->UpdateProgress(0.8);
    scene->Initialize();
    thintissue::appendNamedBlock(scene, thintissue::toMultiBlock(knee.tibia), "Tibia");
    thintissue::appendNamedBlock(scene, thintissue::toMultiBlock(knee.femur), "Femur");
    thintissue::appendNamedBlock(
      scene, thintissue::toMultiBlock(knee.tibialCartilage), "TibialCartilage");
    thintissue::appendNamedBlock(
      scene, thintissue::toMultiBlock(knee.anteriorCruciateLigament), "AnteriorCruciateLigament");
    thintissue::appendNamedBlock(
      scene, thintissue::toMultiBlock(knee.posteriorCruciateLigament), "PosteriorCruciateLigament");
    thintissue::appendNamedBlock(scene, thintissue::toMultiBlock(meniscus), "MedialMeniscus");
  }
  catch (const thintissue::Error& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkKneeSceneSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "JointGap: " << this->JointGap << "\n"
     << indent << "MeniscusTearType: " << this->MeniscusTearType << "\n";
}
