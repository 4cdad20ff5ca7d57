// Suite "prepare": a ready tissue from its visual mesh alone
// (prepareTissue: collision mid-surface with radii, hexahedra, binding) --
// the steak of tables 5-1 / 5-2 (the thesis: collision meshes made by hand
// in 3ds Max, then 5.1 s of pre-processing for the 50-vertex mesh and
// 10.2 s for the 85-vertex one, table 5-1), the real-size medial meniscus
// and the thin sheet, and the meniscus as a segmentation gives it (voxelized
// at 0.27 x 0.27 x 0.81 mm, blurred, iso-surfaced: 20K vertices; issue 14's
// target 0.5 s; at 0.085 x 0.085 x 0.255 mm, 200K vertices, target 5 s). The Hausdorff distance of
// each collision mesh is reported beside its time.
#include "BenchmarkRegistry.h"

#include "MeniscusModel.h"
#include "MeshImport.h"
#include "ThinSheetModel.h"
#include "TissueBundle.h"
#include "vtkSimulatedSegmentationFilter.h"
#include "vtkThinTissueConversion.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>

namespace
{
using namespace thintissue;
using namespace thintissue::bench;

void prepareAndReport(const std::string& name,
  const TriangleMesh& visual,
  int collisionVertices,
  int hexahedra,
  std::optional<double> thesisSeconds,
  int repetitions,
  BenchmarkReporter& reporter)
{
  TissuePreparationSettings settings;
  settings.collision.vertexCount = collisionVertices;
  settings.hexahedronCount = hexahedra;
  TissueBundle bundle;
  const double seconds =
    medianSeconds([&] { bundle = prepareTissue(visual, settings); }, repetitions, repetitions > 1);
  const GeneratedCollisionMesh check = makeCollisionMidSurface(visual, settings.collision);
  const std::string what = name + " (" + std::to_string(visual.vertexCount()) +
                           " visual vertices; " + std::to_string(bundle.collision.vertexCount()) +
                           " collision vertices / " +
                           std::to_string(bundle.collision.triangleCount()) + " triangles, " +
                           std::to_string(bundle.simulation.hexahedronCount()) + " hexahedra)";
  reporter.report(what, "preparation time", seconds, "s", thesisSeconds);
  reporter.report(what,
    "Hausdorff distance over largest thickness",
    check.hausdorffDistance / check.largestThickness,
    "ratio");
}

} // namespace

THINTISSUE_BENCHMARK_SUITE(prepareSuite,
  "prepare",
  "ready tissue from a visual mesh alone: collision mid-surface, hexahedra and binding (steak, "
  "meniscus, sheet)")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const int repetitions = context.quick ? 1 : 5;
  const std::string steak = context.sharedDataDirectory + "/steak/steak.obj";
  if (std::filesystem::exists(steak))
  {
    const TriangleMesh surface = readTriangleMesh(steak);
    prepareAndReport("steak, 50 collision vertices", surface, 50, 76, 5.1, repetitions, reporter);
    prepareAndReport("steak, 85 collision vertices", surface, 85, 76, 10.2, repetitions, reporter);
  }
  // The sheet runs in the quick smoke run too: every suite reports there,
  // with or without ../shared/data.
  const TissueModel sheet = makeThinSheet(thesisSheetVisualResolution(2));
  prepareAndReport(
    "thin sheet, visual model 2", sheet.visual, 65, 81, std::nullopt, repetitions, reporter);
  if (context.quick)
  {
    return;
  }
  const MeniscusModel meniscus = makeMeniscus();
  prepareAndReport("medial meniscus (real size, mm)",
    meniscus.visual,
    105,
    42,
    std::nullopt,
    repetitions,
    reporter);
  // Issue 14's two sizes: about 20K and 200K vertices (spacing divided by
  // the square root of 10); the large one once (it is the slow one).
  for (const double scale : { 1.0, 1.0 / std::sqrt(10.0) })
  {
    vtkNew<vtkSimulatedSegmentationFilter> segmentation;
    segmentation->SetInputData(toPolyData(meniscus.visual));
    segmentation->SetVoxelSpacing(0.27 * scale, 0.27 * scale, 0.81 * scale);
    segmentation->Update();
    const TriangleMesh segmented =
      fromPolyData(segmentation->GetOutput(), "segmented medial meniscus");
    std::ostringstream name;
    name << std::setprecision(2) << "medial meniscus segmented at " << 0.27 * scale << " x "
         << 0.27 * scale << " x " << 0.81 * scale << " mm";
    prepareAndReport(
      name.str(), segmented, 105, 42, std::nullopt, scale < 1.0 ? 1 : repetitions, reporter);
  }
}
