// Image baseline: the generated thin slab, surface with its triangle edges,
// seen obliquely from above, as the demo shows it.
#include "ThinTissueImageTest.h"
#include "vtkThinSlabSource.h"
#include "vtkTriangleMeshValidationFilter.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <iostream>

int main(int argc, char* argv[])
{
  vtkNew<vtkThinSlabSource> slab;
  slab->SetWidth(40.0);
  slab->SetDepth(30.0);
  slab->SetThickness(2.0);
  slab->SetCellsX(20);
  slab->SetCellsY(15);
  slab->SetCellsZ(2);
  vtkNew<vtkTriangleMeshValidationFilter> validation;
  validation->SetInputConnection(slab->GetOutputPort());
  validation->Update();
  if (!validation->GetClosedOutwardSingleSurface())
  {
    std::cerr << "slab is not a closed outward surface:\n" << validation->GetReport() << "\n";
    return EXIT_FAILURE;
  }

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(validation->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.93, 0.62, 0.58);
  actor->GetProperty()->EdgeVisibilityOn();
  actor->GetProperty()->SetEdgeColor(0.45, 0.22, 0.20);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.12, 0.14, 0.18);
  renderer->GetActiveCamera()->Elevation(-55.0);
  renderer->GetActiveCamera()->Azimuth(25.0);
  renderer->ResetCamera();
  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 300);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
