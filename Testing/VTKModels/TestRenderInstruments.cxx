// The six instruments' working tips (probe hook, punch, small and large
// shaver, scissors, scalpel): visual surface, collision centre line (orange)
// and working features (tip, cutting edges, bite or window outline; red).
#include "ThinTissueImageTest.h"
#include "TissueModelScene.h"
#include "vtkSurgicalInstrumentSource.h"

#include <vtkProperty.h>

int main(int argc, char* argv[])
{
  auto window = thintissue::testing::makeSceneWindow(900, 600);
  for (int type = 0; type < 6; ++type)
  {
    vtkNew<vtkSurgicalInstrumentSource> instrument;
    instrument->SetInstrumentType(type);
    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(
      (type % 3) / 3.0, 0.5 * (1 - type / 3), (type % 3 + 1) / 3.0, 0.5 * (1 - type / 3) + 0.5);
    vtkNew<vtkPolyDataMapper> visualMapper;
    visualMapper->SetInputConnection(instrument->GetOutputPort(0));
    visualMapper->ScalarVisibilityOff();
    vtkNew<vtkActor> visual;
    visual->SetMapper(visualMapper);
    visual->GetProperty()->SetColor(0.75, 0.77, 0.8);
    visual->GetProperty()->SetOpacity(0.6);
    renderer->AddActor(visual);
    const int ports[2] = { 1, 2 };
    const double colours[2][3] = { { 1.0, 0.55, 0.1 }, { 0.95, 0.1, 0.1 } };
    for (int k = 0; k < 2; ++k)
    {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputConnection(instrument->GetOutputPort(ports[k]));
      mapper->ScalarVisibilityOff();
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      actor->GetProperty()->SetColor(colours[k][0], colours[k][1], colours[k][2]);
      actor->GetProperty()->SetLineWidth(3.0);
      actor->GetProperty()->SetPointSize(7.0);
      actor->GetProperty()->LightingOff();
      renderer->AddActor(actor);
    }
    // The working end: 14 mm around the tip, seen from the side and above.
    renderer->SetBackground(0.12, 0.14, 0.18);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetFocalPoint(0.0, 0.0, 5.5);
    camera->SetPosition(25.0, -55.0, 25.0);
    camera->SetViewUp(0.0, 0.0, 1.0);
    camera->SetViewAngle(16.0);
    renderer->ResetCameraClippingRange();
    window->AddRenderer(renderer);
  }
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
