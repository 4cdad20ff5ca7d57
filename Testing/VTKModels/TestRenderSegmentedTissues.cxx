// Issue 14: tissues as a segmentation gives them (vtkSimulatedSegmentationFilter:
// voxelized at MRI-like spacing, blurred, iso-surfaced, a little noise) with
// the collision mid-surface generated from them (orange) and a sphere of
// its radius at every collision vertex (blue): left the medial meniscus at
// 0.3 x 0.3 x 0.9 mm, middle the curved posterior cruciate ligament at
// 0.35 x 0.35 x 0.7 mm (a band: its thickness direction turns along it),
// right the tibial cartilage at 0.4 x 0.4 x 0.8 mm.
#include "ThinTissueImageTest.h"
#include "TissueModelScene.h"
#include "vtkCollisionMidSurfaceFilter.h"
#include "vtkKneeTissueSource.h"
#include "vtkMeniscusSource.h"
#include "vtkSimulatedSegmentationFilter.h"

#include <vtkAlgorithmOutput.h>
#include <vtkGlyph3D.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>

#include <cstdio>

namespace
{

/// The segmented surface (translucent), its collision mid-surface and the
/// radius spheres, in `renderer`; false when the preparation fails.
bool addSegmentedTissue(vtkRenderer* renderer,
  vtkAlgorithmOutput* surface,
  double spacingAcross,
  double spacingAlong,
  int collisionVertices)
{
  vtkNew<vtkSimulatedSegmentationFilter> segmentation;
  segmentation->SetInputConnection(surface);
  segmentation->SetVoxelSpacing(spacingAcross, spacingAcross, spacingAlong);
  segmentation->SetNoiseAmplitude(0.05);
  segmentation->SetSeed(1);
  vtkNew<vtkCollisionMidSurfaceFilter> collision;
  collision->SetInputConnection(segmentation->GetOutputPort());
  collision->SetVertexCount(collisionVertices);
  collision->Update();
  if (collision->GetOutput()->GetNumberOfPoints() != collisionVertices)
  {
    std::fprintf(stderr, "collision mid-surface: %s\n", collision->GetLastErrorMessage());
    return false;
  }
  thintissue::testing::TissueSceneStyle style;
  style.showHexahedra = false;
  thintissue::testing::addTissueActors(renderer,
    segmentation->GetOutputPort(),
    collision->GetOutputPort(),
    segmentation->GetOutputPort(),
    style);
  collision->GetOutput()->GetPointData()->SetActiveScalars("Radius");
  vtkNew<vtkSphereSource> ball;
  ball->SetRadius(1.0);
  ball->SetThetaResolution(12);
  ball->SetPhiResolution(8);
  vtkNew<vtkGlyph3D> spheres;
  spheres->SetInputData(collision->GetOutput());
  spheres->SetSourceConnection(ball->GetOutputPort());
  spheres->SetScaleModeToScaleByScalar();
  spheres->SetScaleFactor(1.0);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(spheres->GetOutputPort());
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.2, 0.45, 1.0);
  actor->GetProperty()->SetOpacity(0.3);
  renderer->AddActor(actor);
  return true;
}

} // namespace

int main(int argc, char* argv[])
{
  vtkNew<vtkMeniscusSource> meniscus;
  vtkNew<vtkRenderer> left;
  left->SetViewport(0.0, 0.0, 1.0 / 3.0, 1.0);
  if (!addSegmentedTissue(left, meniscus->GetOutputPort(0), 0.3, 0.9, 105))
  {
    return 1;
  }
  thintissue::testing::viewFrom(left, 0.3, -0.8, 0.9, 0.0, 0.0, 1.0, 1.25);

  vtkNew<vtkKneeTissueSource> ligament;
  ligament->SetTissue(vtkKneeTissueSource::PosteriorCruciateLigament);
  vtkNew<vtkRenderer> middle;
  middle->SetViewport(1.0 / 3.0, 0.0, 2.0 / 3.0, 1.0);
  if (!addSegmentedTissue(middle, ligament->GetOutputPort(0), 0.35, 0.7, 85))
  {
    return 1;
  }
  thintissue::testing::viewFrom(middle, 0.2, -1.0, 0.3, 0.0, 0.0, 1.0, 0.95);

  vtkNew<vtkKneeTissueSource> cartilage;
  cartilage->SetTissue(vtkKneeTissueSource::TibialCartilage);
  vtkNew<vtkRenderer> right;
  right->SetViewport(2.0 / 3.0, 0.0, 1.0, 1.0);
  if (!addSegmentedTissue(right, cartilage->GetOutputPort(0), 0.4, 0.8, 85))
  {
    return 1;
  }
  thintissue::testing::viewFrom(right, 0.1, -0.5, 1.0, 0.0, 0.0, 1.0, 1.1);

  auto window = thintissue::testing::makeSceneWindow(1200, 400);
  window->AddRenderer(left);
  window->AddRenderer(middle);
  window->AddRenderer(right);
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
