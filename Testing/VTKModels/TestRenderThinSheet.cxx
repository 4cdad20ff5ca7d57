// Thesis fig. 5-19 (d): the thin sheet's visual, collision and simulation
// meshes overlapped (visual model 1 of table 5-3, collision model 1 of 5-5,
// 9 x 9 x 1 hexahedra).
#include "ThinTissueImageTest.h"
#include "TissueModelScene.h"
#include "vtkThinSheetSource.h"

int main(int argc, char* argv[])
{
  vtkNew<vtkThinSheetSource> sheet;
  sheet->SetThesisVisualModel(1);
  sheet->SetThesisCollisionModel(1);
  vtkNew<vtkRenderer> renderer;
  thintissue::testing::addTissueActors(
    renderer, sheet->GetOutputPort(0), sheet->GetOutputPort(1), sheet->GetOutputPort(2));
  thintissue::testing::frameScene(renderer, -55.0, 20.0, 1.3);
  auto window = thintissue::testing::makeSceneWindow(500, 400);
  window->AddRenderer(renderer);
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
