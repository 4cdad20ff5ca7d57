// Scenes of the image tests for procedural models, drawn as the thesis's
// figures draw them (fig. 5-19, 6-11): the visual surface translucent, the
// collision mesh as an orange wireframe, the hexahedra as blue edges.
#ifndef TissueModelScene_h
#define TissueModelScene_h

#include <vtkActor.h>
#include <vtkAlgorithmOutput.h>
#include <vtkCamera.h>
#include <vtkDataSetMapper.h>
#include <vtkExtractEdges.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

namespace thintissue::testing
{

struct TissueSceneStyle
{
  double visualColour[3] = { 0.93, 0.88, 0.82 };
  double visualOpacity = 0.45;
  bool showVisual = true;
  bool showCollision = true;
  bool showHexahedra = true;
};

/// Adds the visual surface, collision wireframe and hexahedron edges of the
/// three outputs of a tissue source.
inline void addTissueActors(vtkRenderer* renderer,
  vtkAlgorithmOutput* visual,
  vtkAlgorithmOutput* collision,
  vtkAlgorithmOutput* hexahedra,
  const TissueSceneStyle& style = {})
{
  if (style.showVisual)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(visual);
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(
      style.visualColour[0], style.visualColour[1], style.visualColour[2]);
    actor->GetProperty()->SetOpacity(style.visualOpacity);
    renderer->AddActor(actor);
  }
  if (style.showCollision)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(collision);
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetRepresentationToWireframe();
    actor->GetProperty()->SetColor(1.0, 0.55, 0.1);
    actor->GetProperty()->SetLineWidth(2.0);
    actor->GetProperty()->LightingOff();
    renderer->AddActor(actor);
  }
  if (style.showHexahedra)
  {
    vtkNew<vtkExtractEdges> edges;
    edges->SetInputConnection(hexahedra);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(edges->GetOutputPort());
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.35, 0.6, 1.0);
    actor->GetProperty()->LightingOff();
    renderer->AddActor(actor);
  }
}

/// Oblique view of everything in the renderer.
inline void frameScene(vtkRenderer* renderer, double elevation, double azimuth, double zoom = 1.0)
{
  renderer->SetBackground(0.12, 0.14, 0.18);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Elevation(elevation);
  renderer->GetActiveCamera()->Azimuth(azimuth);
  renderer->GetActiveCamera()->OrthogonalizeViewUp();
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(zoom);
}

/// Camera looking at everything in the renderer from `direction` (from the
/// scene toward the camera) with the given view-up.
inline void viewFrom(vtkRenderer* renderer,
  double dx,
  double dy,
  double dz,
  double upX,
  double upY,
  double upZ,
  double zoom = 1.0)
{
  renderer->SetBackground(0.12, 0.14, 0.18);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetPosition(dx, dy, dz);
  camera->SetViewUp(upX, upY, upZ);
  camera->OrthogonalizeViewUp();
  renderer->ResetCamera();
  camera->Zoom(zoom);
}

/// A window without multisampling (stable pixels).
inline vtkSmartPointer<vtkRenderWindow> makeSceneWindow(int width, int height)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetSize(width, height);
  window->SetMultiSamples(0);
  return window;
}

} // namespace thintissue::testing

#endif
