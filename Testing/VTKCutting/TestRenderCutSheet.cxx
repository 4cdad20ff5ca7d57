// Thesis fig. 5-19: the thin sheet (visual model 2 of table 5-3, 3,425
// vertices; collision model 1, 65 vertices; 81 hexahedra) attached along
// its left and right edges, cut through across the middle; the lips are
// then pushed apart (the left one down, the right one up) and the halves
// move on their own: the cut opens on its cut surfaces. Left: the visual
// surface (tissue pink, cut surface dark red). Right: the collision mesh
// (yellow) and the hexahedra with their copies (blue) after the cut.
#include "CorotationalHexFem.h"
#include "CutSceneHelpers.h"
#include "SoftTissueMaterial.h"
#include "ThinSheetModel.h"
#include "ThinTissueImageTest.h"
#include "TissueModelScene.h"
#include "VisualCollisionBinding.h"

#include <vtkDataSetMapper.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <iostream>

using namespace thintissue;

int main(int argc, char* argv[])
{
  const TissueModel sheet = makeThinSheet(thesisSheetVisualResolution(2));
  const VisualCollisionBinding binding = bindVisualToCollision(sheet.visual, sheet.collision);
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.01;
  CorotationalHexFem fem(sheet.simulation, test::softTissue(), settings);
  TissueCutterSettings cutting;
  cutting.visual.cutSurfaceRows = 2;
  TissueCutter cutter(binding, sheet.simulation, &fem, cutting);
  const Vector3 up(0.0, 0.0, 10.0);
  const auto report = cutter.cut(Blade::sweptSegment(Vector3(3.0, -70.0, 0.0) - up,
    Vector3(3.0, -70.0, 0.0) + up,
    Vector3(5.0, 70.0, 0.0) - up,
    Vector3(5.0, 70.0, 0.0) + up));
  if (!report.changed())
  {
    std::cerr << "the blade cut nothing\n";
    return EXIT_FAILURE;
  }
  // The hexahedra beside the cut (copies included), pushed apart by the
  // side of the collision triangles they hold.
  const auto& rest = cutter.collision().restPositions();
  for (std::size_t h = 0; h < cutter.simulation().hexahedronCount(); ++h)
  {
    const auto& held = cutter.branches().trianglesOf(static_cast<int>(h));
    if (held.empty())
      continue;
    const Triangle& t = cutter.collision().triangles()[held.front()];
    const double x = (rest[t[0]].x() + rest[t[1]].x() + rest[t[2]].x()) / 3.0;
    const double centre = cutter.simulation().nodes[cutter.simulation().hexahedra[h][0]].x() + 5.5;
    if (std::abs(centre - 4.0) > 12.0)
      continue;
    for (int node : cutter.simulation().hexahedra[h])
      fem.setExternalForce(
        static_cast<std::size_t>(node), Vector3(0.0, 0.0, x < 4.0 ? -5e-3 : 5e-3));
  }
  for (int step = 0; step < 40; ++step)
  {
    if (!fem.step().ok)
    {
      std::cerr << "solver failed at step " << step << "\n";
      return EXIT_FAILURE;
    }
  }

  vtkNew<vtkRenderer> visualView;
  visualView->SetViewport(0.0, 0.0, 0.5, 1.0);
  auto visual = testing::cutVisualPolyData(
    cutter, cutter.currentVisualPositions(), { 236, 170, 160 }, { 150, 30, 35 });
  visualView->AddActor(testing::materialActor(visual, false));
  testing::viewFrom(visualView, -0.5, -1.0, 0.9, 0.0, 0.0, 1.0, 1.0);

  vtkNew<vtkRenderer> meshView;
  meshView->SetViewport(0.5, 0.0, 1.0, 1.0);
  TriangleMesh collision = cutter.collisionMesh();
  collision.positions = cutter.currentCollisionPositions();
  HexahedralMesh hexahedra = cutter.simulation();
  hexahedra.nodes = fem.positions();
  meshView->AddActor(testing::wireActor(toUnstructuredGrid(hexahedra), { 0.35, 0.6, 0.95 }, 1.0));
  meshView->AddActor(testing::wireActor(toPolyData(collision), { 0.95, 0.85, 0.3 }, 2.0));
  testing::viewFrom(meshView, -0.5, -1.0, 0.9, 0.0, 0.0, 1.0, 1.0);

  auto window = testing::makeSceneWindow(800, 400);
  window->AddRenderer(visualView);
  window->AddRenderer(meshView);
  return testing::compareWithBaseline(argc, argv, window);
}
