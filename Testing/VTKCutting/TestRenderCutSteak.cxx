// Thesis fig. 5-16: the steak of chapter 5 (../shared/data/steak; skipped
// when absent) prepared as the thesis did (85 collision vertices, 76
// hexahedra), after three straight cuts across it; the four pieces are
// moved apart along the cuts to show their cut surfaces (dark red). The
// cut surface must be closed.
#include "CutSceneHelpers.h"
#include "MeshImport.h"
#include "MeshValidation.h"
#include "ThinTissueImageTest.h"
#include "ThinTissueTestSupport.h"
#include "TissueBundle.h"
#include "TissueModelScene.h"
#include "UnionFind.h"

#include <filesystem>
#include <iostream>

using namespace thintissue;

int main(int argc, char* argv[])
{
  const std::string data = testing::sharedDataDirectory();
  const std::string path = data + "/steak/steak.obj";
  if (data.empty() || !std::filesystem::exists(path))
  {
    std::cout << "steak not present: skipped\n";
    return testing::SkipReturnCode;
  }
  TissuePreparationSettings preparation;
  preparation.collision.vertexCount = 85;
  preparation.hexahedronCount = 76;
  const TissueBundle bundle = prepareTissue(readTriangleMesh(path), preparation);
  TissueCutterSettings settings;
  settings.visual.cutSurfaceRows = 2;
  TissueCutter cutter(bundle.binding, bundle.simulation, nullptr, settings);
  const BoundingBox box = bundle.visual.boundingBox();
  const Vector3 size = box.sizes();
  const Vector3 up = Vector3::UnitZ() * size.norm();
  for (double at : { 0.3, 0.55, 0.75 })
  {
    const double x = box.min().x() + at * size.x();
    const Vector3 a(x - 0.05 * size.x(), box.min().y() - 0.1 * size.y(), box.center().z());
    const Vector3 b(x + 0.05 * size.x(), box.max().y() + 0.1 * size.y(), box.center().z());
    const auto report = cutter.cut(Blade::sweptSegment(a - up, a + up, b - up, b + up));
    if (!report.changed() || !report.visualError.empty())
    {
      std::cerr << "the cut at " << at << ": " << report.visualError << "\n";
      return EXIT_FAILURE;
    }
  }
  const TriangleMesh& mesh = cutter.visual().mesh();
  const MeshValidationReport closed = validateTriangleMesh(mesh, 0.0);
  if (closed.borderEdges.count + closed.nonManifoldEdges.count +
        closed.inconsistentlyOrientedEdges.count !=
      0)
  {
    std::cerr << "the cut steak is not closed:\n" << closed.toString() << "\n";
    return EXIT_FAILURE;
  }
  // Pieces of the visual surface, moved apart along x by their order.
  UnionFind pieces(mesh.vertexCount());
  for (const Triangle& t : mesh.triangles)
  {
    pieces.unite(t[0], t[1]);
    pieces.unite(t[1], t[2]);
  }
  std::vector<Vector3> moved = mesh.positions;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
  {
    const Vector3& p = mesh.positions[pieces.find(static_cast<int>(v))];
    moved[v].x() += 0.08 * size.x() * std::floor((p.x() - box.min().x()) / size.x() * 4.0);
  }
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(testing::materialActor(
    testing::cutVisualPolyData(cutter, moved, { 200, 80, 70 }, { 110, 20, 25 }), false));
  testing::frameScene(renderer, -50.0, 0.0, 1.0);
  auto window = testing::makeSceneWindow(400, 300);
  window->AddRenderer(renderer);
  return testing::compareWithBaseline(argc, argv, window);
}
