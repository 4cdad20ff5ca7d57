// Image baseline: the thesis's steak (section 5.4.1) as read from
// ../shared/data/steak; skipped when that optional folder is absent.
#include "ThinTissueImageTest.h"
#include "ThinTissueTestSupport.h"
#include "vtkThinTissueMeshReader.h"

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkRenderWindow.h>

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
  const auto actor = thintissue::testing::makeSurfaceActor(
    normals->GetOutputPort(), { 0.72, 0.25, 0.22 }, { 0.40, 0.12, 0.10 });
  const auto window = thintissue::testing::makeBaselineWindow(actor, -50.0, 0.0);
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
