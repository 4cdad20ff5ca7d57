// The four torn menisci (fig. 4-5 b, 6-9): longitudinal (bucket handle),
// radial, flap and horizontal cleavage, each with its collision mesh, seen
// obliquely from the joint's centre so that the cleavage shows too.
#include "ThinTissueImageTest.h"
#include "TissueModelScene.h"
#include "vtkMeniscusSource.h"

int main(int argc, char* argv[])
{
  auto window = thintissue::testing::makeSceneWindow(800, 600);
  const int tears[4] = { vtkMeniscusSource::LongitudinalTear,
    vtkMeniscusSource::RadialTear,
    vtkMeniscusSource::FlapTear,
    vtkMeniscusSource::HorizontalCleavageTear };
  for (int k = 0; k < 4; ++k)
  {
    vtkNew<vtkMeniscusSource> meniscus;
    meniscus->SetTearType(tears[k]);
    meniscus->SetTearOpening(1.2);
    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(
      0.5 * (k % 2), 0.5 * (1 - k / 2), 0.5 * (k % 2) + 0.5, 0.5 * (1 - k / 2) + 0.5);
    thintissue::testing::TissueSceneStyle style;
    style.visualOpacity = 1.0;
    style.showHexahedra = false;
    thintissue::testing::addTissueActors(renderer,
      meniscus->GetOutputPort(0),
      meniscus->GetOutputPort(1),
      meniscus->GetOutputPort(2),
      style);
    // From above and the lateral side: the tears and the inner edge show.
    thintissue::testing::viewFrom(renderer, 0.6, -0.2, 1.0, 0.0, 1.0, 0.0, 1.05);
    window->AddRenderer(renderer);
  }
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
