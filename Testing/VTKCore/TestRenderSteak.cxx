// Image baseline: the thesis's steak (section 5.4.1) as read from
// ../shared/data/steak; skipped when that optional folder is absent.
#include "ThinTissueImageTest.h"
#include "ThinTissueTestSupport.h"
#include "vtkThinTissueMeshReader.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <filesystem>
#include <iostream>

int main(int argc, char* argv[])
{
  const std::string data = thintissue::testing::sharedDataDirectory();
  const std::string path = data + "/steak/steak.obj";
  if (data.empty() || !std::filesystem::exists(path))
  {
    std::cout << "steak not present: skipped\n";
    return thintissue::testing::SkipReturnCode;
  }
  vtkNew<vtkThinTissueMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  if (reader->GetOutput()->GetNumberOfPolys() != 5278)
  {
    std::cerr << "steak: expected 5278 triangles, got " << reader->GetOutput()->GetNumberOfPolys()
              << " " << reader->GetLastErrorMessage() << "\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(reader->GetOutputPort());
  normals->SplittingOff();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.72, 0.25, 0.22);
  actor->GetProperty()->EdgeVisibilityOn();
  actor->GetProperty()->SetEdgeColor(0.40, 0.12, 0.10);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.12, 0.14, 0.18);
  renderer->GetActiveCamera()->Elevation(-50.0);
  renderer->ResetCamera();
  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 300);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
