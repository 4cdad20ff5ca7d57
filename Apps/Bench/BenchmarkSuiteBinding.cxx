// Suite "binding": the visual-collision binding of the pre-processing
// phase (thesis 5.2) -- pairing, geodesic paths, re-meshing, flood fill and
// mean value parameters -- for the thesis's tables:
// - table 5-3: the thin sheet's visual models 1 to 4 (881 .. 53,633
//   vertices) bound to the 65-vertex collision mesh;
// - table 5-5: visual model 2 bound to the collision meshes of 65, 280 and
//   796 vertices;
// - the medial meniscus (6.4.2: 12.7 s) and a 1M-triangle sheet.
// Per case the pre-processing time and, as the thesis reports them, the
// visual vertices and triangles per collision triangle afterwards (both
// sides; a vertex on a region's border counts for every region it
// borders).
#include "BenchmarkRegistry.h"

#include "MeniscusModel.h"
#include "ThinSheetModel.h"
#include "VisualCollisionBinding.h"

#include <optional>
#include <set>
#include <string>
#include <vector>

namespace
{
using namespace thintissue;
using namespace thintissue::bench;

struct ThesisRow
{
  std::optional<double> seconds;
  std::optional<double> verticesPerTriangle;
  std::optional<double> trianglesPerTriangle;
};

void bindAndReport(const std::string& name,
  const TriangleMesh& visual,
  const TriangleMesh& collision,
  const ThesisRow& thesis,
  int repetitions,
  BenchmarkReporter& reporter)
{
  VisualCollisionBinding binding;
  // Repeated cases get one warm-up run (thread pool, first touch of memory).
  const double seconds = medianSeconds(
    [&] { binding = bindVisualToCollision(visual, collision); }, repetitions, repetitions > 1);
  // Distinct visual vertices of each collision triangle's two regions.
  const std::size_t regions = collision.triangleCount();
  std::vector<std::vector<int>> vertices(regions);
  for (std::size_t t = 0; t < binding.visual.triangleCount(); ++t)
  {
    for (int v : binding.visual.triangles[t])
    {
      vertices[binding.triangleRegion[t]].push_back(v);
    }
  }
  std::size_t vertexSum = 0;
  for (auto& list : vertices)
  {
    vertexSum += std::set<int>(list.begin(), list.end()).size();
  }
  const std::string counts = std::to_string(visual.vertexCount()) + " visual vertices / " +
                             std::to_string(visual.triangleCount()) + " triangles, " +
                             std::to_string(collision.vertexCount()) + " collision vertices / " +
                             std::to_string(collision.triangleCount()) + " triangles";
  reporter.report(name + " (" + counts + ")", "pre-processing time", seconds, "s", thesis.seconds);
  const double perTriangleVertices = static_cast<double>(vertexSum) / regions;
  const double perTriangleTriangles = static_cast<double>(binding.visual.triangleCount()) / regions;
  reporter.report(name,
    "visual vertices per collision triangle",
    perTriangleVertices,
    "vertices",
    thesis.verticesPerTriangle);
  reporter.report(name,
    "visual triangles per collision triangle",
    perTriangleTriangles,
    "triangles",
    thesis.trianglesPerTriangle);
}

} // namespace

THINTISSUE_BENCHMARK_SUITE(bindingSuite,
  "binding",
  "visual-collision binding (thesis 5.2): sheets of table 5-3 and 5-5, meniscus, 1M triangles")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const int repetitions = context.quick ? 1 : 7;
  // Table 5-3: visual models 1-4, collision model 1.
  const std::vector<ThesisRow> table53 = {
    { 0.8, 26, 31 }, { 7.1, 73, 102 }, { 57.5, 214, 337 }, { 422.2, 688, 1193 }
  };
  const int lastVisual = context.quick ? 1 : 4;
  for (int model = 1; model <= lastVisual; ++model)
  {
    const TissueModel sheet = makeThinSheet(thesisSheetVisualResolution(model));
    bindAndReport("table 5-3, sheet visual model " + std::to_string(model),
      sheet.visual,
      sheet.collision,
      table53[static_cast<std::size_t>(model - 1)],
      model == 4 ? 1 : repetitions,
      reporter);
  }
  if (context.quick)
  {
    return;
  }
  // Table 5-5: visual model 2, collision models 1-3.
  const std::vector<ThesisRow> table55 = { { 6.9, 73, 102 }, { 35.1, 25, 29 }, { 105.9, 11, 10 } };
  for (int model = 1; model <= 3; ++model)
  {
    const TissueModel sheet =
      makeThinSheet(thesisSheetVisualResolution(2, thesisSheetCollisionResolution(model)));
    bindAndReport("table 5-5, sheet collision model " + std::to_string(model),
      sheet.visual,
      sheet.collision,
      table55[static_cast<std::size_t>(model - 1)],
      repetitions,
      reporter);
  }
  const MeniscusModel meniscus = makeMeniscus();
  bindAndReport("medial meniscus (6.4.2)",
    meniscus.visual,
    meniscus.collision,
    { 12.7, std::nullopt, std::nullopt },
    repetitions,
    reporter);
  const TissueModel million = makeThinSheet(thesisSheetVisualResolution(5));
  bindAndReport("sheet of 1M visual triangles, collision model 1",
    million.visual,
    million.collision,
    {},
    1,
    reporter);
}
