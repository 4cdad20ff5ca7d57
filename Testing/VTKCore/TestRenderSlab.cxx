// Image baseline: the generated thin slab, surface with its triangle edges,
// seen obliquely from above, as the demo shows it.
#include "ThinTissueImageTest.h"
#include "vtkThinSlabSource.h"
#include "vtkTriangleMeshValidationFilter.h"

#include <vtkNew.h>
#include <vtkRenderWindow.h>

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

  const auto actor = thintissue::testing::makeSurfaceActor(
    validation->GetOutputPort(), { 0.93, 0.62, 0.58 }, { 0.45, 0.22, 0.20 });
  const auto window = thintissue::testing::makeBaselineWindow(actor, -55.0, 25.0);
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
