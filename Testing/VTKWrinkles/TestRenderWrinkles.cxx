// Thesis fig. 4-14 (c)-(h) and 6-9: the examination meniscus (6,104 faces,
// 42 hexahedra, monitor points every 0.16 mm along its inner border) pressed
// down 2 mm at the middle of the inner border and released by 0.8 mm: the
// release reverses the monitor points (4.4.1) and the inner border wrinkles
// (4.4.2). Seen from inside the C, looking at the inner border; the surface
// is coloured by the wrinkle displacement (white: none, red: 0.3 mm or more).
//
// TestRenderWrinkles: eight viewports,
//   top row:    default | e - s = 140 | e - s = 30 | theta^d = 7 pi
//   bottom row: theta^d = 3 pi | s = 2, m^up = 1 | s = 0.4 | r^c above the
//               thinnest window point (thin points keep still)
// TestRenderWrinklesTorn (same source, THINTISSUE_WRINKLES_TORN): a
// radial tear, pressed beside the tear; the wrinkles stay on the inner
// border on the pressed side of the tear.
#include "MeniscusModel.h"
#include "ThinTissueImageTest.h"
#include "WrinkleGenerator.h"
#include "vtkThinTissueConversion.h"

#include <vtkCamera.h>
#include <vtkDoubleArray.h>
#include <vtkLookupTable.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <cmath>
#include <iostream>

using namespace thintissue;

namespace
{

struct PressedMeniscus
{
  MeniscusModel model;
  MonitorPointSet monitors;
  Vector3 contact;
};

PressedMeniscus pressedMeniscus(MeniscusTearType tear)
{
  MeniscusParameters p = examinationMeniscusParameters();
  p.tear = defaultMeniscusTear(tear);
  PressedMeniscus m{ makeMeniscus(p), {}, Vector3::Zero() };
  m.monitors = resampleMonitorCurves(wrinkleDataCurves(m.model.monitorCurves), 0.16);
  // The middle of the inner border, or beside a radial tear (the first
  // curve ends at the tear): 4 mm before that end.
  const int curveEnd = m.monitors.curveStarts[1];
  const int at = tear == MeniscusTearType::None ? static_cast<int>(m.monitors.size() / 2)
                                                : std::max(0, curveEnd - 25);
  m.contact = m.monitors.monitorPoints[at];
  return m;
}

/// The surface after 20 steps down by 0.1 mm and 8 steps back up, a smooth
/// dent of radius 4 mm around the contact, with the wrinkles of `p`.
vtkSmartPointer<vtkPolyData> wrinkledSurface(const PressedMeniscus& m, const WrinkleParameters& p)
{
  WrinkleGenerator generator(m.monitors, m.model.simulation, m.model.visual, p);
  WrinkleContactState contacts;
  contacts.lowerSurfaceContacts = 5;
  contacts.instrumentTouches = true;
  contacts.instrumentContact = m.contact;
  std::vector<Vector3> nodes;
  double depth = 0.0;
  for (int k = 0; k < 28; ++k)
  {
    depth += k < 20 ? 0.1 : -0.1;
    nodes = m.model.simulation.nodes;
    for (Vector3& x : nodes)
    {
      x.z() -= depth * std::exp(-(x - m.contact).head<2>().squaredNorm() / 16.0);
    }
    generator.update(nodes, contacts);
  }
  if (!generator.wrinkling())
  {
    std::cerr << "no wrinkles after the release\n";
  }
  TriangleMesh surface = m.model.visual;
  HexahedralEmbedding(m.model.simulation, m.model.visual.positions)
    .mapPositions(nodes, surface.positions);
  generator.applyTo(surface.positions);
  surface.computeVertexNormals();
  surface.textureCoordinates.clear();
  surface.textureCorners.clear();
  auto polyData = toPolyData(surface);
  vtkNew<vtkDoubleArray> magnitude;
  magnitude->SetName("Wrinkle");
  magnitude->SetNumberOfTuples(polyData->GetNumberOfPoints());
  magnitude->FillValue(0.0);
  for (std::size_t s = 0; s < generator.displacedPoints().size(); ++s)
  {
    magnitude->SetValue(generator.displacedPoints()[s], generator.displacements()[s].norm());
  }
  polyData->GetPointData()->SetScalars(magnitude);
  return polyData;
}

vtkSmartPointer<vtkRenderer> viewOf(vtkPolyData* surface, const Vector3& contact)
{
  vtkNew<vtkLookupTable> colours;
  colours->SetHueRange(0.0, 0.0);
  colours->SetSaturationRange(0.0, 0.85);
  colours->SetValueRange(0.95, 0.85);
  colours->SetTableRange(0.0, 0.3);
  colours->Build();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(surface);
  mapper->SetLookupTable(colours);
  mapper->SetScalarRange(0.0, 0.3);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetInterpolationToGouraud();
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->AddActor(actor);
  renderer->SetBackground(0.12, 0.14, 0.18);
  // From inside the C (the inner border faces the C's centre), above it.
  const Vector3 towardCentre = (Vector3(-20.5, 2.5, contact.z()) - contact).normalized();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(contact.data());
  const Vector3 eye = contact + 16.0 * towardCentre + Vector3(0.0, 0.0, 6.0);
  camera->SetPosition(eye.data());
  camera->SetViewUp(0.0, 0.0, 1.0);
  camera->SetViewAngle(40.0);
  renderer->ResetCameraClippingRange();
  return renderer;
}

[[maybe_unused]] vtkSmartPointer<vtkRenderWindow> variationsWindow()
{
  const PressedMeniscus m = pressedMeniscus(MeniscusTearType::None);
  std::vector<WrinkleParameters> variants(8);
  variants[1].windowSize = 140;
  variants[2].windowSize = 30;
  variants[3].frequency = 7.0 * M_PI;
  variants[4].frequency = 3.0 * M_PI;
  variants[5].scale = 2.0;
  variants[5].magnitudeBound = 1.0;
  variants[6].scale = 0.4;
  // r^c between the thinnest and thickest monitor points near the contact.
  variants[7].cutOffThickness = 1.06;
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetSize(1000, 500);
  window->SetMultiSamples(0);
  for (int v = 0; v < 8; ++v)
  {
    auto renderer = viewOf(wrinkledSurface(m, variants[v]), m.contact);
    const double x = (v % 4) / 4.0, y = v < 4 ? 0.5 : 0.0;
    renderer->SetViewport(x, y, x + 0.25, y + 0.5);
    window->AddRenderer(renderer);
  }
  return window;
}

[[maybe_unused]] vtkSmartPointer<vtkRenderWindow> tornWindow()
{
  const PressedMeniscus m = pressedMeniscus(MeniscusTearType::Radial);
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetSize(400, 300);
  window->SetMultiSamples(0);
  window->AddRenderer(viewOf(wrinkledSurface(m, WrinkleParameters{}), m.contact));
  return window;
}

} // namespace

int main(int argc, char* argv[])
{
#ifdef THINTISSUE_WRINKLES_TORN
  auto window = tornWindow();
#else
  auto window = variationsWindow();
#endif
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
