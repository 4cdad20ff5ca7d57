// Thesis fig. 5-3 and 5-5: the visual-collision binding of the thin sheet
// (visual model 1 of table 5-3, collision model 1 of table 5-5; left) and
// of the meniscus (right). The re-meshed visual surfaces are coloured by
// the collision triangle each visual triangle is bound to (a categorical
// palette, darker on the negative side), with the geodesic paths that bound
// the regions drawn as thick dark lines.
//
// The meniscus's collision grid has inner edges joining two rim vertices
// at its corners: each gets a positive and a negative path, over the upper
// and the lower surface.
#include "ThinTissueImageTest.h"
#include "TissueModelScene.h"
#include "vtkMeniscusSource.h"
#include "vtkThinSheetSource.h"
#include "vtkVisualCollisionBindingFilter.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkLookupTable.h>
#include <vtkMath.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <iostream>

namespace
{

/// Categorical palette: neighbouring indices get far-apart hues (golden
/// ratio steps) and alternating saturation; entry 2 t is collision triangle
/// t on the positive side, 2 t + 1 the same colour darker (negative side).
vtkSmartPointer<vtkLookupTable> regionPalette(vtkIdType triangles)
{
  auto table = vtkSmartPointer<vtkLookupTable>::New();
  table->SetNumberOfTableValues(2 * triangles);
  for (vtkIdType t = 0; t < triangles; ++t)
  {
    const double hue = std::fmod(0.07 + 0.6180339887 * static_cast<double>(t), 1.0);
    const double saturation = t % 3 == 0 ? 0.45 : (t % 3 == 1 ? 0.6 : 0.75);
    double rgb[3];
    vtkMath::HSVToRGB(hue, saturation, 0.95, rgb, rgb + 1, rgb + 2);
    table->SetTableValue(2 * t, rgb[0], rgb[1], rgb[2], 1.0);
    table->SetTableValue(2 * t + 1, 0.5 * rgb[0], 0.5 * rgb[1], 0.5 * rgb[2], 1.0);
  }
  return table;
}

/// The re-meshed surface coloured by region (cell array "CollisionTriangle",
/// darker where "CollisionSide" is -1) and the paths on top.
bool addBinding(vtkRenderer* renderer, vtkAlgorithmOutput* visual, vtkPolyData* collision)
{
  vtkNew<vtkVisualCollisionBindingFilter> binding;
  binding->SetInputConnection(0, visual);
  binding->SetCollisionData(collision);
  binding->Update();
  if (binding->GetVisualOutput()->GetNumberOfCells() == 0)
  {
    std::cerr << "binding failed: " << binding->GetLastErrorMessage() << "\n";
    return false;
  }
  vtkPolyData* bound = binding->GetVisualOutput();
  vtkDataArray* regions = bound->GetCellData()->GetArray("CollisionTriangle");
  vtkDataArray* sides = bound->GetCellData()->GetArray("CollisionSide");
  double range[2];
  regions->GetRange(range);
  const auto triangles = static_cast<vtkIdType>(range[1]) + 1;
  auto palette = regionPalette(triangles);
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("RegionColour");
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(bound->GetNumberOfCells());
  for (vtkIdType c = 0; c < bound->GetNumberOfCells(); ++c)
  {
    const vtkIdType index = 2 * static_cast<vtkIdType>(regions->GetComponent(c, 0)) +
                            (sides->GetComponent(c, 0) < 0.0 ? 1 : 0);
    double rgba[4];
    palette->GetTableValue(index, rgba);
    const unsigned char rgb[3] = { static_cast<unsigned char>(255.0 * rgba[0] + 0.5),
      static_cast<unsigned char>(255.0 * rgba[1] + 0.5),
      static_cast<unsigned char>(255.0 * rgba[2] + 0.5) };
    colours->SetTypedTuple(c, rgb);
  }
  vtkNew<vtkPolyData> coloured;
  coloured->ShallowCopy(bound);
  coloured->GetCellData()->AddArray(colours);

  vtkNew<vtkPolyDataMapper> surfaceMapper;
  surfaceMapper->SetInputData(coloured);
  surfaceMapper->SetScalarModeToUseCellFieldData();
  surfaceMapper->SelectColorArray("RegionColour");
  surfaceMapper->SetColorModeToDirectScalars();
  surfaceMapper->ScalarVisibilityOn();
  // Push the surface back so that the paths on it are drawn in front.
  surfaceMapper->SetResolveCoincidentTopologyToPolygonOffset();
  surfaceMapper->SetRelativeCoincidentTopologyPolygonOffsetParameters(2.0, 4.0);
  vtkNew<vtkActor> surface;
  surface->SetMapper(surfaceMapper);
  surface->GetProperty()->SetAmbient(0.25);
  surface->GetProperty()->SetDiffuse(0.8);
  renderer->AddActor(surface);

  vtkNew<vtkPolyDataMapper> pathMapper;
  pathMapper->SetInputConnection(
    binding->GetOutputPort(vtkVisualCollisionBindingFilter::PathsPort));
  pathMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> paths;
  paths->SetMapper(pathMapper);
  paths->GetProperty()->SetColor(0.05, 0.05, 0.08);
  paths->GetProperty()->SetLineWidth(3.0);
  paths->GetProperty()->LightingOff();
  renderer->AddActor(paths);
  return true;
}

} // namespace

int main(int argc, char* argv[])
{
  vtkNew<vtkThinSheetSource> sheet;
  sheet->SetThesisVisualModel(1);
  sheet->SetThesisCollisionModel(1);
  vtkNew<vtkRenderer> sheetView;
  sheetView->SetViewport(0.0, 0.0, 0.5, 1.0);
  sheet->Update();
  if (!addBinding(sheetView, sheet->GetOutputPort(0), sheet->GetCollisionOutput()))
  {
    return EXIT_FAILURE;
  }
  thintissue::testing::viewFrom(sheetView, 0.35, -0.9, 1.1, 0.0, 0.0, 1.0, 1.05);

  vtkNew<vtkMeniscusSource> meniscus;
  vtkNew<vtkRenderer> meniscusView;
  meniscusView->SetViewport(0.5, 0.0, 1.0, 1.0);
  meniscus->Update();
  if (!addBinding(meniscusView, meniscus->GetOutputPort(0), meniscus->GetCollisionOutput()))
  {
    return EXIT_FAILURE;
  }
  thintissue::testing::viewFrom(meniscusView, 0.45, -0.8, 0.75, 0.0, 0.0, 1.0, 1.3);

  auto window = thintissue::testing::makeSceneWindow(800, 400);
  window->AddRenderer(sheetView);
  window->AddRenderer(meniscusView);
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
