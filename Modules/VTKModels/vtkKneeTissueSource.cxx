#include "vtkKneeTissueSource.h"

#include "KneeModels.h"

#include <vtkObjectFactory.h>

vtkStandardNewMacro(vtkKneeTissueSource);

vtkKneeTissueSource::vtkKneeTissueSource()
  : JointGap(thintissue::knee::DefaultJointGap)
{
}

thintissue::TissueModel vtkKneeTissueSource::BuildTissueModel()
{
  thintissue::KneeSurroundingsParameters parameters;
  parameters.jointGap = this->JointGap;
  if (this->Tissue == TibialCartilage)
  {
    thintissue::TissueModel model = thintissue::makeTibialCartilage(parameters);
    model.collision = thintissue::tibialCartilageCollisionMesh(
      parameters, static_cast<thintissue::CartilageCollisionSetting>(this->CollisionSetting));
    return model;
  }
  const auto ligament = this->Tissue == AnteriorCruciateLigament
                          ? thintissue::CruciateLigament::Anterior
                          : thintissue::CruciateLigament::Posterior;
  thintissue::TissueModel model = thintissue::makeCruciateLigament(ligament, parameters);
  model.collision = thintissue::cruciateLigamentCollisionMesh(ligament,
    static_cast<thintissue::LigamentCollisionSetting>(this->CollisionSetting),
    parameters);
  return model;
}

void vtkKneeTissueSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Tissue: " << this->Tissue << "\n"
     << indent << "CollisionSetting: " << this->CollisionSetting << "\n"
     << indent << "JointGap: " << this->JointGap << "\n";
}
