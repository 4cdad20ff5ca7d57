// Thesis fig. 6-11 (a): the meniscus's visual (translucent), collision
// (orange) and simulation (blue hexahedron edges) meshes, seen from above
// and in front, plus the monitor data points of fig. 4-5 (red) in a second
// view from above (region data points blue).
#include "ThinTissueImageTest.h"
#include "TissueModelScene.h"
#include "vtkMeniscusSource.h"

#include <vtkDataArray.h>
#include <vtkGlyph3D.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>

int main(int argc, char* argv[])
{
  vtkNew<vtkMeniscusSource> meniscus;
  vtkNew<vtkRenderer> meshes;
  meshes->SetViewport(0.0, 0.0, 0.5, 1.0);
  thintissue::testing::addTissueActors(
    meshes, meniscus->GetOutputPort(0), meniscus->GetOutputPort(1), meniscus->GetOutputPort(2));
  thintissue::testing::viewFrom(meshes, 0.3, -0.8, 0.9, 0.0, 0.0, 1.0, 1.25);

  vtkNew<vtkRenderer> monitor;
  monitor->SetViewport(0.5, 0.0, 1.0, 1.0);
  thintissue::testing::TissueSceneStyle style;
  style.showCollision = false;
  style.showHexahedra = false;
  style.visualOpacity = 0.3;
  thintissue::testing::addTissueActors(monitor,
    meniscus->GetOutputPort(0),
    meniscus->GetOutputPort(1),
    meniscus->GetOutputPort(2),
    style);
  vtkNew<vtkSphereSource> ball;
  ball->SetRadius(0.45);
  vtkNew<vtkGlyph3D> glyphs;
  glyphs->SetInputConnection(meniscus->GetOutputPort(vtkMeniscusSource::MonitorPointsPort));
  glyphs->SetSourceConnection(ball->GetOutputPort());
  glyphs->ScalingOff();
  vtkNew<vtkPolyDataMapper> glyphMapper;
  glyphMapper->SetInputConnection(glyphs->GetOutputPort());
  glyphMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> glyphActor;
  glyphActor->SetMapper(glyphMapper);
  glyphActor->GetProperty()->SetColor(0.9, 0.1, 0.1);
  monitor->AddActor(glyphActor);
  // Region data points (blue), from the monitor points' "RegionPoint" array.
  meniscus->Update();
  vtkDataArray* regionArray =
    meniscus->GetMonitorPointsOutput()->GetPointData()->GetArray("RegionPoint");
  vtkNew<vtkPoints> regionPoints;
  for (vtkIdType k = 0; k < regionArray->GetNumberOfTuples(); ++k)
  {
    regionPoints->InsertNextPoint(regionArray->GetTuple3(k));
  }
  vtkNew<vtkPolyData> region;
  region->SetPoints(regionPoints);
  vtkNew<vtkGlyph3D> regionGlyphs;
  regionGlyphs->SetInputData(region);
  regionGlyphs->SetSourceConnection(ball->GetOutputPort());
  regionGlyphs->ScalingOff();
  vtkNew<vtkPolyDataMapper> regionMapper;
  regionMapper->SetInputConnection(regionGlyphs->GetOutputPort());
  vtkNew<vtkActor> regionActor;
  regionActor->SetMapper(regionMapper);
  regionActor->GetProperty()->SetColor(0.15, 0.35, 1.0);
  monitor->AddActor(regionActor);
  thintissue::testing::viewFrom(monitor, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0);

  auto window = thintissue::testing::makeSceneWindow(800, 400);
  window->AddRenderer(meshes);
  window->AddRenderer(monitor);
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
