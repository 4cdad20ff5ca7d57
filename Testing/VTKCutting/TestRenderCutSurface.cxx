// Thesis fig. 5-12(c): the cut surface at two resolutions. The sheet
// (visual model 1, collision model 1) cut through across the middle; the
// right piece is moved 6 mm away to show its cut face. Left: no rows
// between the + and - sides (the two paths zipped); right: three rows,
// each at the parameters of both sides (up-sampling). Cut surface dark
// red, tissue pink, triangle edges drawn.
#include "CutSceneHelpers.h"
#include "ThinSheetModel.h"
#include "ThinTissueImageTest.h"
#include "TissueModelScene.h"
#include "UnionFind.h"
#include "VisualCollisionBinding.h"

#include <iostream>

using namespace thintissue;

namespace
{

/// The cut visual surface with the piece on the right of x = `at` moved
/// by `offset` along x.
vtkSmartPointer<vtkActor> cutSheetActor(const VisualCollisionBinding& binding,
  const HexahedralMesh& simulation,
  int rows)
{
  TissueCutterSettings settings;
  settings.visual.cutSurfaceRows = rows;
  TissueCutter cutter(binding, simulation, nullptr, settings);
  const Vector3 up(0.0, 0.0, 10.0);
  cutter.cut(Blade::sweptSegment(Vector3(3.0, -70.0, 0.0) - up,
    Vector3(3.0, -70.0, 0.0) + up,
    Vector3(3.0, 70.0, 0.0) - up,
    Vector3(3.0, 70.0, 0.0) + up));
  const TriangleMesh& mesh = cutter.visual().mesh();
  UnionFind pieces(mesh.vertexCount());
  for (const Triangle& t : mesh.triangles)
  {
    pieces.unite(t[0], t[1]);
    pieces.unite(t[1], t[2]);
  }
  std::vector<double> sumX(mesh.vertexCount(), 0.0);
  std::vector<int> count(mesh.vertexCount(), 0);
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
  {
    sumX[pieces.find(static_cast<int>(v))] += mesh.positions[v].x();
    ++count[pieces.find(static_cast<int>(v))];
  }
  std::vector<Vector3> moved = mesh.positions;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
  {
    const int root = pieces.find(static_cast<int>(v));
    if (sumX[root] / count[root] > 3.0)
      moved[v].x() += 6.0;
  }
  return testing::materialActor(
    testing::cutVisualPolyData(cutter, moved, { 236, 170, 160 }, { 150, 30, 35 }), true);
}

} // namespace

int main(int argc, char* argv[])
{
  const TissueModel sheet = makeThinSheet(thesisSheetVisualResolution(1));
  const VisualCollisionBinding binding = bindVisualToCollision(sheet.visual, sheet.collision);
  auto window = testing::makeSceneWindow(800, 400);
  for (int view = 0; view < 2; ++view)
  {
    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(0.5 * view, 0.0, 0.5 * (view + 1), 1.0);
    renderer->AddActor(cutSheetActor(binding, sheet.simulation, view == 0 ? 0 : 3));
    testing::viewFrom(renderer, -1.0, -0.35, 0.25, 0.0, 0.0, 1.0, 1.0);
    // Close to the cut face of the right piece.
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetFocalPoint(9.0, -28.0, 0.0);
    camera->SetPosition(-10.0, -44.0, 14.0);
    camera->SetViewUp(0.0, 0.0, 1.0);
    renderer->ResetCameraClippingRange();
    window->AddRenderer(renderer);
  }
  return testing::compareWithBaseline(argc, argv, window);
}
