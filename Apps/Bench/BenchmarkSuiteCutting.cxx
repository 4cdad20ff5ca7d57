// Suite "cutting": per-cut times of the simulation phase (thesis 5.3), split
// by stage: the blade against the collision mesh with its re-meshing
// (5.3.1), hexahedron duplication with the solver update, the
// collision-simulation embedding update, and the whole cut; then the
// solver's first step after the cut (new pattern and factor). Cases: the
// thin sheet with the collision meshes of table 5-6, the medial meniscus
// (intact, and with a horizontal cleavage),
// the steak of table 5-2 (when ../shared/data holds it), and the counts of
// vertices and elements over 6 consecutive cuts (fig. 5-17); a contouring
// pass over a jagged rim (6.4.4); a basket-punch bite on the meniscus with
// the removal of its piece, by the thesis's stages (6.4.2).
//
// With the visual mesh (table 5-4: the sheets of 881 to 53,633 visual
// vertices on the 65-vertex collision mesh, and the 1M-triangle sheet): the visual cut, binding
// update and cut surface (5.3.2-5.3.4) and the visual-simulation embedding update (5.3.5) too, for
// a sweep across the sheet and for a short cut through a few collision triangles (the thesis's "per
// cut").
#include "BenchmarkRegistry.h"

#include "CorotationalHexFem.h"
#include "MeniscusModel.h"
#include "MeshImport.h"
#include "SurgicalInstruments.h"
#include "ThinSheetModel.h"
#include "TissueBundle.h"
#include "TissueCutter.h"
#include "VisualCollisionBinding.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>

namespace
{
using namespace thintissue;
using namespace thintissue::bench;

LinearMaterial softTissue()
{
  LinearMaterial material; // mm, N, s
  material.youngModulus = 0.5;
  material.poissonRatio = 0.45;
  material.density = 1.0e-9;
  return material;
}

double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// A vertical scalpel across the tissue's box at fraction `at` of its x
/// extent, swept along y over the whole box.
Blade scalpelAcross(const BoundingBox& box, double at)
{
  const double x = box.min().x() + at * box.sizes().x();
  const double z0 = box.min().z() - box.sizes().norm(), z1 = box.max().z() + box.sizes().norm();
  const double y0 = box.min().y() - 1.0, y1 = box.max().y() + 1.0;
  return Blade::sweptSegment(
    Vector3(x, y0, z0), Vector3(x, y0, z1), Vector3(x, y1, z0), Vector3(x, y1, z1));
}

void cutAndReport(const std::string& name,
  const TriangleMesh& collision,
  const HexahedralMesh& simulation,
  int repetitions,
  BenchmarkReporter& reporter)
{
  std::vector<double> stages[6];
  std::size_t touched = 0;
  for (int r = 0; r < repetitions; ++r)
  {
    CorotationalHexFem fem(simulation, softTissue());
    fem.step(); // the factor exists before the cut, as in a running simulation
    TissueCutter cutter(collision, simulation, &fem);
    const auto report = cutter.cut(scalpelAcross(boundingBoxOf(collision.positions), 0.53));
    touched = report.simulation.touchedHexahedra.size();
    // The first step, and the first four: a factor bridged across the cut
    // costs in each step until the new one lands.
    double afterCut = 0.0;
    for (int k = 0; k < 4; ++k)
    {
      const auto stepStart = std::chrono::steady_clock::now();
      fem.step();
      const double step =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - stepStart)
          .count();
      if (k == 0)
        stages[4].push_back(step);
      afterCut += step;
    }
    stages[5].push_back(afterCut);
    stages[0].push_back(report.collisionMilliseconds);
    stages[1].push_back(report.simulationMilliseconds);
    stages[2].push_back(report.embeddingMilliseconds);
    stages[3].push_back(report.totalMilliseconds);
  }
  const std::string what = name + " (" + std::to_string(collision.vertexCount()) +
                           " collision vertices, " + std::to_string(simulation.hexahedronCount()) +
                           " hexahedra, " + std::to_string(touched) + " touched)";
  reporter.report(what, "collision cut and re-meshing (5.3.1)", median(stages[0]), "ms");
  reporter.report(what, "hexahedron duplication and solver update", median(stages[1]), "ms");
  reporter.report(what, "collision-simulation embedding update", median(stages[2]), "ms");
  reporter.report(what, "collision and simulation cut, total", median(stages[3]), "ms");
  reporter.report(what, "first solver step after the cut", median(stages[4]), "ms");
  reporter.report(what, "first four solver steps after the cut, summed", median(stages[5]), "ms");
}

/// Table 5-4: a cut with the visual mesh, by stage.
void cutVisualAndReport(const std::string& name,
  const VisualCollisionBinding& binding,
  const HexahedralMesh& simulation,
  const Blade& blade,
  int repetitions,
  BenchmarkReporter& reporter,
  std::optional<double> thesisTotal = std::nullopt,
  bool alsoOnOneThread = false)
{
  std::vector<double> stages[4];
  std::vector<double> oneThread;
  std::size_t changed = 0, cutTriangles = 0;
  for (int r = 0; r < repetitions; ++r)
  {
    // The same cut with its region stages on one thread, interleaved with
    // the default (so that both see the same load).
    if (alsoOnOneThread)
    {
      CorotationalHexFem fem(simulation, softTissue());
      TissueCutterSettings serial;
      serial.visual.parallelRegionTriangles = std::numeric_limits<std::size_t>::max();
      TissueCutter cutter(binding, simulation, &fem, serial);
      oneThread.push_back(cutter.cut(blade).totalMilliseconds);
    }
    CorotationalHexFem fem(simulation, softTissue());
    TissueCutter cutter(binding, simulation, &fem);
    const auto report = cutter.cut(blade);
    changed = report.visual.changedTriangles.size();
    cutTriangles = report.collision.splits.size();
    stages[0].push_back(
      report.collisionMilliseconds + report.simulationMilliseconds + report.embeddingMilliseconds);
    stages[1].push_back(report.visualMilliseconds);
    stages[2].push_back(report.visualEmbeddingMilliseconds);
    stages[3].push_back(report.totalMilliseconds);
  }
  const std::string what = name + " (" + std::to_string(binding.visual.vertexCount()) +
                           " visual vertices; " + std::to_string(cutTriangles) +
                           " collision triangles cut, " + std::to_string(changed) +
                           " visual triangles changed)";
  reporter.report(what, "collision and simulation cut (5.3.1)", median(stages[0]), "ms");
  reporter.report(
    what, "visual cut, binding update and cut surface (5.3.2-5.3.4)", median(stages[1]), "ms");
  reporter.report(what, "visual-simulation embedding update (5.3.5)", median(stages[2]), "ms");
  reporter.report(what, "whole cut", median(stages[3]), "ms", thesisTotal);
  if (alsoOnOneThread)
    reporter.report(what, "whole cut, region stages on one thread", median(oneThread), "ms");
  // A cut must write its output (the visual triangles it changes grow as the
  // square root of the visual resolution): what it costs per triangle
  // changed shows whether it costs what it touches.
  if (changed > 0)
    reporter.report(what,
      "whole cut per visual triangle changed",
      1000.0 * median(stages[3]) / static_cast<double>(changed),
      "us");
}

/// The thesis's "per cut": a short vertical cut through a few collision
/// triangles near the middle of the tissue, along y.
Blade shortCutAcross(const BoundingBox& box)
{
  const Vector3 centre = box.center();
  const Vector3 a = centre + Vector3(0.03, -0.08, 0.0).cwiseProduct(box.sizes());
  const Vector3 b = centre + Vector3(0.03, 0.08, 0.0).cwiseProduct(box.sizes());
  const Vector3 up = Vector3::UnitZ() * box.sizes().norm();
  return Blade::sweptSegment(a - up, a + up, b - up, b + up);
}

/// Fig. 5-17: counts over 6 consecutive cuts across the tissue.
void countConsecutiveCuts(const std::string& name,
  const TriangleMesh& collision,
  const HexahedralMesh& simulation,
  BenchmarkReporter& reporter)
{
  CorotationalHexFem fem(simulation, softTissue());
  TissueCutter cutter(collision, simulation, &fem);
  const BoundingBox box = boundingBoxOf(collision.positions);
  for (int c = 1; c <= 6; ++c)
  {
    cutter.cut(scalpelAcross(box, 0.12 * c + 0.03));
    const std::string what = name + ", after cut " + std::to_string(c);
    reporter.report(what, "collision vertices", double(cutter.collision().vertexCount()), "count");
    reporter.report(
      what, "collision triangles", double(cutter.collision().triangleCount()), "count");
    reporter.report(what, "simulation nodes", double(cutter.simulation().nodeCount()), "count");
    reporter.report(what, "hexahedra", double(cutter.simulation().hexahedronCount()), "count");
  }
}

/// Thesis 6.4.4: a contouring pass over a jagged rim. The meniscus's inner
/// border bitten at three places by a round bite 4 mm across (the pieces
/// dropped), then the tool (a sphere of 3.4 mm, the small shaver's reach)
/// held on each bitten rim in turn: the cost of one pass (issue target
/// 0.5 ms), and the rim's roughness before and after 20 passes.
void contourAndReport(int repetitions, BenchmarkReporter& reporter)
{
  const MeniscusModel meniscus = makeMeniscus();
  const VisualCollisionBinding binding = bindVisualToCollision(meniscus.visual, meniscus.collision);
  TissueCutterSettings settings;
  settings.freePieces = FreePieceHandling::Drop;
  settings.visual.jaggedAmplitude = 0.3;
  TissueCutter cutter(binding, meniscus.simulation, nullptr, settings);
  const MonitorCurve& border = meniscus.monitorCurves.front();
  std::vector<Vector3> bitten;
  for (const double at : { 0.3, 0.5, 0.7 })
  {
    const Vector3 centre =
      border.monitorPoints[static_cast<std::size_t>(at * (border.monitorPoints.size() - 1))];
    std::vector<Vector3> low, high;
    for (int i = 0; i < 24; ++i)
    {
      const double angle = 2.0 * M_PI * i / 24.0;
      const Vector3 p = centre + 2.0 * Vector3(std::cos(angle), std::sin(angle), 0.0);
      low.push_back(p - Vector3(0, 0, 10));
      high.push_back(p + Vector3(0, 0, 10));
    }
    cutter.cut(Blade::sweptOutline(low, high));
    bitten.push_back(centre);
  }
  const double before = cutter.cutRimRoughness().rootMeanSquare;
  std::vector<double> times;
  std::size_t moved = 0;
  for (int pass = 0; pass < std::max(20, repetitions); ++pass)
  {
    const auto report = cutter.contour(bitten[pass % bitten.size()], 3.4, 0.3);
    times.push_back(report.milliseconds);
    moved = std::max(moved, report.movedVertices.size());
  }
  const std::string what = "medial meniscus, 3 jagged bites, contouring pass (" +
                           std::to_string(moved) + " cut-surface vertices moved)";
  reporter.report(what, "contouring pass (6.4.4)", median(times), "ms");
  reporter.report(what, "rim roughness before", before, "mm");
  reporter.report(what, "rim roughness after", cutter.cutRimRoughness().rootMeanSquare, "mm");
}

/// The punch's basket outline (its jaw's face) laid flat, centred on `at`,
/// swept through the tissue along z: one bite.
Blade punchBiteAt(const Vector3& at)
{
  const std::vector<Vector3> outline =
    makeSurgicalInstrument(SurgicalInstrumentType::Punch).biteOutline;
  Vector3 centre = Vector3::Zero();
  Vector3 normal = Vector3::Zero(); // Newell's normal of the planar outline
  for (std::size_t i = 0; i < outline.size(); ++i)
  {
    centre += outline[i] / static_cast<double>(outline.size());
    normal += outline[i].cross(outline[(i + 1) % outline.size()]);
  }
  normal.normalize();
  const Vector3 u =
    (outline.front() - centre - (outline.front() - centre).dot(normal) * normal).normalized();
  const Vector3 v = normal.cross(u);
  std::vector<Vector3> low, high;
  for (const Vector3& p : outline)
  {
    const Vector3 flat = at + Vector3((p - centre).dot(u), (p - centre).dot(v), 0.0);
    low.push_back(flat - Vector3(0, 0, 10));
    high.push_back(flat + Vector3(0, 0, 10));
  }
  return Blade::sweptOutline(low, high);
}

/// Thesis 6.4.2: a basket-punch bite on the meniscus's inner border (one
/// cut and the removal of the bitten piece), split by the thesis's stages
/// (48.2 ms = 6.2 cut and binding update + 32.8 embeddings + 8.1 cut
/// surface; issue target 2 ms): the first bite into the intact meniscus,
/// and a third one beside two earlier bites (the cost over cut tissue).
void punchAndReport(int repetitions, BenchmarkReporter& reporter)
{
  const MeniscusModel meniscus = makeMeniscus();
  const VisualCollisionBinding binding = bindVisualToCollision(meniscus.visual, meniscus.collision);
  TissueCutterSettings settings;
  settings.freePieces = FreePieceHandling::Drop;
  const MonitorCurve& border = meniscus.monitorCurves.front();
  auto borderPoint = [&](double at) // by arc length along the border
  {
    const auto& points = border.monitorPoints;
    double length = 0.0;
    for (std::size_t i = 1; i < points.size(); ++i)
      length += (points[i] - points[i - 1]).norm();
    double left = at * length;
    for (std::size_t i = 1; i < points.size(); ++i)
    {
      const double step = (points[i] - points[i - 1]).norm();
      if (left <= step)
        return Vector3(points[i - 1] + (left / step) * (points[i] - points[i - 1]));
      left -= step;
    }
    return points.back();
  };
  for (const bool third : { false, true })
  {
    std::vector<double> stages[5];
    double removed = 0.0;
    for (int r = 0; r < repetitions; ++r)
    {
      CorotationalHexFem fem(meniscus.simulation, softTissue());
      TissueCutter cutter(binding, meniscus.simulation, &fem, settings);
      if (third)
        for (const double at : { 0.44, 0.48 })
          cutter.cut(punchBiteAt(borderPoint(at)));
      const auto report = cutter.cut(punchBiteAt(borderPoint(third ? 0.52 : 0.5)));
      removed = report.removedPieces;
      const double cutSurface = report.visual.cutSurfaceMilliseconds;
      stages[0].push_back(report.collisionMilliseconds + report.simulationMilliseconds +
                          report.visualMilliseconds - cutSurface);
      stages[1].push_back(report.embeddingMilliseconds + report.visualEmbeddingMilliseconds);
      stages[2].push_back(cutSurface);
      stages[3].push_back(report.removalMilliseconds);
      stages[4].push_back(report.totalMilliseconds);
    }
    const std::string what = std::string("medial meniscus, punch bite on the inner border") +
                             (third ? ", the third beside two bites" : ", the first") + " (" +
                             std::to_string(static_cast<int>(removed)) + " pieces removed)";
    reporter.report(what, "cut and binding update", median(stages[0]), "ms", 6.2);
    reporter.report(what, "embedding updates", median(stages[1]), "ms", 32.8);
    reporter.report(what, "cut surface", median(stages[2]), "ms", 8.1);
    reporter.report(what, "piece removal", median(stages[3]), "ms");
    reporter.report(what, "whole bite", median(stages[4]), "ms", 48.2);
  }
}

/// Thesis 6.4.3: shaving by piecewise removal. The running shaver's
/// window (a ball of 1.7 mm, the small shaver's) moved along the
/// meniscus's inner border 0.5 mm a pass; each pass removes the active
/// collision triangles whose centroid it holds (TissueCutter::
/// removeTriangles, as the simulator's shaver does): the cost of a pass
/// that removes something (issue target 0.5 ms), by stage.
void shaveAndReport(int repetitions, BenchmarkReporter& reporter)
{
  const MeniscusModel meniscus = makeMeniscus();
  const VisualCollisionBinding binding = bindVisualToCollision(meniscus.visual, meniscus.collision);
  TissueCutterSettings settings;
  settings.freePieces = FreePieceHandling::Drop;
  const std::vector<Vector3>& border = meniscus.monitorCurves.front().monitorPoints;
  std::vector<double> whole, visual, embedding, removal;
  std::size_t removedTriangles = 0;
  for (int r = 0; r < std::max(1, repetitions / 7); ++r)
  {
    CorotationalHexFem fem(meniscus.simulation, softTissue());
    TissueCutter cutter(binding, meniscus.simulation, &fem, settings);
    Vector3 last = border[border.size() / 3];
    for (std::size_t i = border.size() / 3; i < 2 * border.size() / 3; ++i)
    {
      if (i > border.size() / 3 && (border[i] - last).norm() < 0.5)
        continue;
      last = border[i];
      const std::vector<int> held = cutter.activeTrianglesWithin(last, 1.7);
      if (held.empty())
        continue;
      const TissueCutReport report = cutter.removeTriangles(held);
      removedTriangles += held.size();
      whole.push_back(report.totalMilliseconds);
      visual.push_back(report.visualMilliseconds);
      embedding.push_back(report.embeddingMilliseconds + report.visualEmbeddingMilliseconds);
      removal.push_back(report.removalMilliseconds);
    }
  }
  if (whole.empty())
    throw std::runtime_error("shaving bench: the window held no triangle");
  const std::string what = "medial meniscus, shaving pass along the inner border (" +
                           std::to_string(removedTriangles / whole.size()) +
                           " collision triangles a pass)";
  reporter.report(what, "visual opening and cut surface", median(visual), "ms");
  reporter.report(what, "embedding updates", median(embedding), "ms");
  reporter.report(what, "piece removal", median(removal), "ms");
  reporter.report(what, "whole pass", median(whole), "ms");
  reporter.report(what, "passes", static_cast<double>(whole.size()), "count");
}

} // namespace

THINTISSUE_BENCHMARK_SUITE(cuttingSuite,
  "cutting",
  "per-cut times by stage (collision cut, hexahedron duplication, embeddings) and counts over 6 "
  "cuts: sheet (table 5-6), meniscus, steak (table 5-2)")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const int repetitions = context.quick ? 3 : 21;
  // Table 5-6: the 3,425-vertex visual sheet on three collision meshes
  // (thesis totals per cut 13.6 / 12.8 / 11.9 ms).
  const double table56[3] = { 13.6, 12.8, 11.9 };
  for (int model = 1; model <= (context.quick ? 1 : 3); ++model)
  {
    const TissueModel sheet =
      makeThinSheet(thesisSheetCollisionResolution(model, thesisSheetVisualResolution(2)));
    const std::string name = "thin sheet, collision model " + std::to_string(model);
    cutAndReport(name, sheet.collision, sheet.simulation, repetitions, reporter);
    const VisualCollisionBinding binding = bindVisualToCollision(sheet.visual, sheet.collision);
    cutVisualAndReport(name + " with visual model 2, short cut",
      binding,
      sheet.simulation,
      shortCutAcross(boundingBoxOf(sheet.collision.positions)),
      repetitions,
      reporter,
      table56[model - 1]);
  }
  // Table 5-4: visual models 1-4 on the 65-vertex collision mesh (thesis
  // totals per cut 10.5 / 14.6 / 21.9 / 49.9 ms); model 5 is the
  // 1M-triangle sheet (binding it takes about 25 s).
  const double table54[4] = { 10.5, 14.6, 21.9, 49.9 };
  for (int model = 1; model <= (context.quick ? 1 : 5); ++model)
  {
    const TissueModel visualSheet = makeThinSheet(thesisSheetVisualResolution(model));
    const VisualCollisionBinding binding =
      bindVisualToCollision(visualSheet.visual, visualSheet.collision);
    const BoundingBox box = boundingBoxOf(visualSheet.collision.positions);
    const int runs = model <= 2 ? repetitions : (model <= 4 ? std::max(3, repetitions / 4) : 3);
    const std::string name = "thin sheet, visual model " + std::to_string(model);
    cutVisualAndReport(name + ", sweep across",
      binding,
      visualSheet.simulation,
      scalpelAcross(box, 0.53),
      runs,
      reporter);
    cutVisualAndReport(name + ", short cut",
      binding,
      visualSheet.simulation,
      shortCutAcross(box),
      runs,
      reporter,
      model <= 4 ? std::optional<double>(table54[model - 1]) : std::nullopt,
      true);
  }
  const TissueModel sheet = makeThinSheet(ThinSheetParameters{});
  countConsecutiveCuts(
    "thin sheet, collision model 1", sheet.collision, sheet.simulation, reporter);
  contourAndReport(repetitions, reporter);
  punchAndReport(repetitions, reporter);
  shaveAndReport(repetitions, reporter);
  if (context.quick)
  {
    return;
  }
  const MeniscusModel meniscus = makeMeniscus();
  cutAndReport("medial meniscus", meniscus.collision, meniscus.simulation, repetitions, reporter);
  // A cut across the C through a horizontal cleavage's leaves and body
  // (junction edges shared by three collision triangles).
  MeniscusParameters cleavedParameters;
  cleavedParameters.tear = defaultMeniscusTear(MeniscusTearType::HorizontalCleavage);
  const MeniscusModel cleaved = makeMeniscus(cleavedParameters);
  const std::string cleavedName = "medial meniscus with a horizontal cleavage";
  cutAndReport(cleavedName, cleaved.collision, cleaved.simulation, repetitions, reporter);
  cutVisualAndReport(cleavedName + ", visual, sweep across",
    bindVisualToCollision(cleaved.visual, cleaved.collision),
    cleaved.simulation,
    scalpelAcross(boundingBoxOf(cleaved.collision.positions), 0.53),
    repetitions,
    reporter);
  const std::string steak = context.sharedDataDirectory + "/steak/steak.obj";
  if (!std::filesystem::exists(steak))
  {
    reporter.skip("steak", "no " + steak);
    return;
  }
  // Table 5-2: the steak on 50 and 85 collision vertices (thesis totals per
  // cut 17.6 / 9.4 ms).
  const TriangleMesh steakMesh = readTriangleMesh(steak);
  const std::pair<int, double> table52[2] = { { 50, 17.6 }, { 85, 9.4 } };
  for (const auto& [collisionVertices, thesisTotal] : table52)
  {
    TissuePreparationSettings settings;
    settings.collision.vertexCount = collisionVertices;
    settings.hexahedronCount = 76;
    const TissueBundle bundle = prepareTissue(steakMesh, settings);
    const std::string name = "steak, " + std::to_string(collisionVertices) + " collision vertices";
    cutAndReport(name, bundle.collision, bundle.simulation, repetitions, reporter);
    cutVisualAndReport(name + ", visual, short cut",
      bundle.binding,
      bundle.simulation,
      shortCutAcross(boundingBoxOf(bundle.collision.positions)),
      repetitions,
      reporter,
      thesisTotal);
    if (collisionVertices == 85)
      countConsecutiveCuts(name, bundle.collision, bundle.simulation, reporter);
  }
}
