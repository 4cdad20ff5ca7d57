// Baseline comparison for image tests: vtkRegressionTestImage with an
// optional "--threshold t" argument; 0 when the image matches.
#ifndef ThinTissueImageTest_h
#define ThinTissueImageTest_h

#include <vtkRegressionTestImage.h>
#include <vtkRenderWindow.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace thintissue::testing
{

/// Exit code of an image test meaning "optional data missing" (skipped).
constexpr int SkipReturnCode = 77;

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
