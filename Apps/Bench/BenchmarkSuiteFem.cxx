// Suite "fem": one implicit Euler step of the co-rotational hexahedral FEM
// (thesis 4.2) at the thesis's sizes -- meniscus 42 hexahedra (table 6-2),
// sheet 81 hexahedra (table 5-4) -- and scaling to 1K and 10K hexahedra,
// with CHOLMOD and with warm-started conjugate gradients.
#include "BenchmarkRegistry.h"

#include "CorotationalHexFem.h"
#include "HexahedralEmbedding.h"
#include "MeniscusModel.h"
#include "MeshImport.h"
#include "SparseHexahedralGrid.h"
#include "ThinSheetModel.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>

namespace
{
using namespace thintissue;
using namespace thintissue::bench;

struct FemCase
{
  std::string name;
  HexahedralMesh mesh;
  LinearMaterial material;
  double timeStep;
  std::optional<double> thesisMilliseconds;
};

/// Milliseconds per step: median over blocks of steps, under a load at the
/// node farthest from the fixed ones, after the deformation has set in.
double millisecondsPerStep(const FemCase& c, LinearSolverKind solver, int steps)
{
  CorotationalHexFemSettings settings;
  settings.timeStep = c.timeStep;
  settings.solver = solver;
  CorotationalHexFem fem(c.mesh, c.material, settings);
  std::size_t loaded = 0;
  for (std::size_t n = 0; n < fem.nodeCount(); ++n)
  {
    if (fem.restPositions()[n].x() > fem.restPositions()[loaded].x() && !fem.isFixed(n))
    {
      loaded = n;
    }
  }
  fem.setExternalForce(loaded, Vector3(0.0, 0.0, -0.5)); // an instrument's push
  for (int k = 0; k < 5; ++k)
  {
    fem.step();
  }
  return 1e3 *
         medianSeconds(
           [&]
           {
             for (int k = 0; k < steps; ++k)
             {
               fem.step();
             }
           },
           5,
           false) /
         steps;
}

HexahedralMesh block(int nx, int ny, int nz)
{
  HexahedralMesh mesh =
    HexahedralMesh::makeRegularGrid(Vector3::Zero(), Vector3::Ones(), nx, ny, nz);
  mesh.fixedNodes.assign(mesh.nodeCount(), 0);
  for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
  {
    mesh.fixedNodes[n] = mesh.nodes[n].x() < 1e-12 ? 1 : 0;
  }
  return mesh;
}

} // namespace

THINTISSUE_BENCHMARK_SUITE(femSuite,
  "fem",
  "co-rotational hexahedral FEM step (meniscus, sheet, 1K, 10K hexahedra; CHOLMOD and CG)")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  LinearMaterial meniscusMaterial; // thesis 4.5, in mm, N, s
  meniscusMaterial.youngModulus = 150.0;
  meniscusMaterial.poissonRatio = 0.49;
  meniscusMaterial.density = 1.1e-9;
  LinearMaterial softMaterial; // soft tissue, 0.5 MPa, 1000 kg/m^3 in mm, N, s
  softMaterial.youngModulus = 0.5;
  softMaterial.poissonRatio = 0.45;
  softMaterial.density = 1.0e-9;
  std::vector<FemCase> cases;
  cases.push_back({ "meniscus (42 hexahedra, 120 nodes)",
    makeMeniscus().simulation,
    meniscusMaterial,
    0.001,
    6.5 });
  cases.push_back({ "sheet (81 hexahedra, 200 nodes)",
    makeThinSheet(ThinSheetParameters{}).simulation,
    softMaterial,
    0.001,
    3.0 });
  cases.push_back(
    { "block (1,000 hexahedra)", block(20, 10, 5), softMaterial, 0.001, std::nullopt });
  if (!context.quick)
  {
    cases.push_back(
      { "block (10,000 hexahedra)", block(40, 25, 10), softMaterial, 0.001, std::nullopt });
  }
  // The steak of tables 5-1/5-2 (76 hexahedra in the thesis), when the
  // optional data is there: a sparse grid of its surface.
  const std::string steak = context.sharedDataDirectory + "/steak/steak.obj";
  if (std::filesystem::exists(steak))
  {
    // The resolution whose sparse grid is closest to the thesis's 76 cells.
    const TriangleMesh surface = readTriangleMesh(steak);
    HexahedralMesh grid;
    for (int cells = 4; cells <= 16; ++cells)
    {
      HexahedralMesh candidate = makeSparseHexahedralMesh(surface, cells);
      if (grid.hexahedronCount() == 0 ||
          std::abs(static_cast<int>(candidate.hexahedronCount()) - 76) <
            std::abs(static_cast<int>(grid.hexahedronCount()) - 76))
      {
        grid = std::move(candidate);
      }
    }
    grid.fixedNodes.assign(grid.nodeCount(), 0);
    const double left = grid.boundingBox().min().x();
    for (std::size_t n = 0; n < grid.nodeCount(); ++n)
    {
      grid.fixedNodes[n] = grid.nodes[n].x() < left + 1e-9 ? 1 : 0;
    }
    cases.push_back({ "steak (" + std::to_string(grid.hexahedronCount()) + " hexahedra)",
      grid,
      softMaterial,
      0.001,
      3.0 });
  }
  else
  {
    reporter.skip("steak", steak + " not found");
  }
  for (const auto& c : cases)
  {
    const bool huge = c.mesh.hexahedronCount() > 5000;
    const int steps = huge ? 1 : (c.mesh.hexahedronCount() > 500 ? 10 : 200);
    if (huge)
    {
      // Factorizations take seconds here; only what Automatic uses.
      reporter.report(c.name + ", Jacobi conjugate gradient",
        "step time",
        millisecondsPerStep(c, LinearSolverKind::ConjugateGradient, steps),
        "ms",
        c.thesisMilliseconds);
      continue;
    }
    reporter.report(c.name + ", CHOLMOD",
      "step time",
      millisecondsPerStep(c, LinearSolverKind::Cholmod, context.quick ? 2 : steps),
      "ms",
      c.thesisMilliseconds);
    reporter.report(c.name + ", Jacobi conjugate gradient",
      "step time",
      millisecondsPerStep(c, LinearSolverKind::ConjugateGradient, context.quick ? 2 : steps),
      "ms",
      c.thesisMilliseconds);
    reporter.report(c.name + ", stale-factor conjugate gradient",
      "step time",
      millisecondsPerStep(
        c, LinearSolverKind::StaleFactorConjugateGradient, context.quick ? 2 : steps),
      "ms",
      c.thesisMilliseconds);
  }

  // Positions down from the hexahedra to a 1M-vertex visual mesh (x = H u).
  ThinSheetParameters big;
  big.visualCellsX = big.visualCellsY = context.quick ? 100 : 707; // 1,002,528 vertices
  const TissueModel sheet = makeThinSheet(big);
  HexahedralEmbedding embedding(sheet.simulation, sheet.visual.positions);
  std::vector<Vector3> mapped(embedding.pointCount());
  std::vector<Vector3> nodes = sheet.simulation.nodes;
  for (auto& node : nodes)
  {
    node.z() += 0.01 * node.x();
  }
  const std::string label = std::to_string(embedding.pointCount()) + " visual vertices";
  reporter.report("embed " + label + " in 81 hexahedra",
    "time",
    1e3 * medianSeconds([&] { HexahedralEmbedding(sheet.simulation, sheet.visual.positions); },
            context.quick ? 1 : 3),
    "ms");
  reporter.report("map " + label + " (x = H u)",
    "time",
    1e3 * medianSeconds([&] { embedding.mapPositions(nodes, mapped); }, context.quick ? 3 : 21),
    "ms");
}
