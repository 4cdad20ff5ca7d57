// Baseline comparison for image tests: vtkRegressionTestImage with an
// optional "--threshold t" argument; 0 when the image matches.
#ifndef ThinTissueImageTest_h
#define ThinTissueImageTest_h

#include <vtkActor.h>
#include <vtkAlgorithmOutput.h>
#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRegressionTestImage.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <array>
#include <cstdlib>
#include <string>
#include <vector>

namespace thintissue::testing
{

/// Exit code of an image test meaning "optional data missing" (skipped).
constexpr int SkipReturnCode = 77;

/// A surface with its triangle edges drawn, as the thesis figures show meshes.
inline vtkSmartPointer<vtkActor> makeSurfaceActor(vtkAlgorithmOutput* surface,
  const std::array<double, 3>& colour,
  const std::array<double, 3>& edgeColour)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(surface);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(colour[0], colour[1], colour[2]);
  actor->GetProperty()->EdgeVisibilityOn();
  actor->GetProperty()->SetEdgeColor(edgeColour[0], edgeColour[1], edgeColour[2]);
  return actor;
}

/// A 400 x 300 window (no multisampling, for stable pixels) whose renderer
/// shows `actor` on the standard dark background from an oblique camera.
inline vtkSmartPointer<vtkRenderWindow> makeBaselineWindow(vtkActor* actor,
  double elevation,
  double azimuth)
{
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.12, 0.14, 0.18);
  renderer->GetActiveCamera()->Elevation(elevation);
  renderer->GetActiveCamera()->Azimuth(azimuth);
  renderer->ResetCamera();
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetSize(400, 300);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  return window;
}

inline int compareWithBaseline(int argc, char* argv[], vtkRenderWindow* window)
{
  double threshold = 0.15;
  std::vector<char*> arguments;
  for (int i = 0; i < argc; ++i)
  {
    if (std::string(argv[i]) == "--threshold" && i + 1 < argc)
    {
      threshold = std::atof(argv[++i]);
      continue;
    }
    arguments.push_back(argv[i]);
  }
  window->Render();
  const int result =
    vtkTesting::Test(static_cast<int>(arguments.size()), arguments.data(), window, threshold);
  return result == vtkTesting::PASSED ? EXIT_SUCCESS : EXIT_FAILURE;
}

} // namespace thintissue::testing

#endif
