// The knee surroundings together (thesis fig. 6-6 a, 5-23, 5-27): left, the
// anatomy seen from the front and above with the femur lifted out of the
// way -- tibia and femur (bone yellow), medial tibial cartilage, medial
// meniscus, ACL and PCL; right, the ligaments and the cartilage with their
// collision meshes (orange) and hexahedra (blue).
#include "ThinTissueImageTest.h"
#include "TissueModelScene.h"
#include "vtkKneeSceneSource.h"
#include "vtkKneeTissueSource.h"

#include <vtkMultiBlockDataSet.h>
#include <vtkPolyData.h>
#include <vtkTransform.h>

namespace
{
vtkPolyData* visualOf(vtkMultiBlockDataSet* scene, unsigned int block)
{
  auto* meshes = vtkMultiBlockDataSet::SafeDownCast(scene->GetBlock(block));
  return vtkPolyData::SafeDownCast(meshes->GetBlock(0));
}

void addSurface(vtkRenderer* renderer,
  vtkPolyData* surface,
  double r,
  double g,
  double b,
  double opacity = 1.0)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(surface);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r, g, b);
  actor->GetProperty()->SetOpacity(opacity);
  actor->GetProperty()->SetSpecular(0.2);
  renderer->AddActor(actor);
}
} // namespace

int main(int argc, char* argv[])
{
  vtkNew<vtkKneeSceneSource> knee;
  knee->SetJointGap(10.0); // opened wide, as under valgus stress, to show the menisci
  knee->Update();
  vtkMultiBlockDataSet* scene = knee->GetOutput();

  vtkNew<vtkRenderer> anatomy;
  anatomy->SetViewport(0.0, 0.0, 0.55, 1.0);
  addSurface(anatomy, visualOf(scene, 0), 0.93, 0.85, 0.55);      // tibia
  addSurface(anatomy, visualOf(scene, 1), 0.93, 0.85, 0.55, 0.6); // femur
  addSurface(anatomy, visualOf(scene, 2), 0.70, 0.80, 0.95);      // tibial cartilage
  addSurface(anatomy, visualOf(scene, 3), 0.90, 0.55, 0.55);      // ACL
  addSurface(anatomy, visualOf(scene, 4), 0.80, 0.45, 0.50);      // PCL
  addSurface(anatomy, visualOf(scene, 5), 0.97, 0.96, 0.93);      // medial meniscus
  thintissue::testing::viewFrom(anatomy, 0.15, 1.0, 0.55, 0.0, 0.0, 1.0, 1.6);

  vtkNew<vtkRenderer> meshes;
  meshes->SetViewport(0.55, 0.0, 1.0, 1.0);
  for (int tissue = vtkKneeTissueSource::TibialCartilage;
       tissue <= vtkKneeTissueSource::PosteriorCruciateLigament;
       ++tissue)
  {
    vtkNew<vtkKneeTissueSource> source;
    source->SetTissue(tissue);
    source->SetCollisionSetting(tissue == vtkKneeTissueSource::TibialCartilage ? 3 : 4);
    thintissue::testing::TissueSceneStyle style;
    style.visualOpacity = 0.35;
    thintissue::testing::addTissueActors(
      meshes, source->GetOutputPort(0), source->GetOutputPort(1), source->GetOutputPort(2), style);
  }
  thintissue::testing::viewFrom(meshes, 1.0, 0.6, 0.5, 0.0, 0.0, 1.0, 1.1);

  auto window = thintissue::testing::makeSceneWindow(900, 500);
  window->AddRenderer(anatomy);
  window->AddRenderer(meshes);
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
