// Suite "fem": one implicit Euler step of the co-rotational hexahedral FEM
// (thesis 4.2) at the thesis's sizes -- meniscus 42 hexahedra (table 6-2),
// sheet 81 hexahedra (table 5-4) -- and scaling to 1K, 10K and 100K
// hexahedra (issue 20), with every linear solver: median, 99th percentile
// and maximum step time. Also the BLAS CHOLMOD runs on, and CHOLMOD's
// factorization with each ordering, simplicial and supernodal.
#include "BenchmarkRegistry.h"

#include "CorotationalHexFem.h"
#include "HexahedralEmbedding.h"
#include "LinearAlgebraLibrary.h"
#include "MeniscusModel.h"
#include "MeshImport.h"
#include "SparseHexahedralGrid.h"
#include "ThinSheetModel.h"

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

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

/// Per-step figures of a run: a real-time loop cares about its worst step.
struct StepStatistics
{
  double medianMilliseconds = 0.0;
  double p99Milliseconds = 0.0;
  double maxMilliseconds = 0.0;
  double medianIterations = 0.0;
  /// CPU time of the stepping thread (a background refactorization not
  /// included): what a step costs when other processes load the machine.
  double medianThreadCpuMilliseconds = 0.0;
  /// Its mean: rare factorizations inside steps count in it.
  double meanThreadCpuMilliseconds = 0.0;
  /// The first step of the run (a warm-up step): it analyses the pattern
  /// and builds the first factor or multigrid hierarchy.
  double firstStepMilliseconds = 0.0;
  /// Measured steps whose solve did not converge (only when tolerated).
  int failedSteps = 0;
};

double threadCpuMilliseconds()
{
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return 1e3 * static_cast<double>(now.tv_sec) + 1e-6 * static_cast<double>(now.tv_nsec);
}

/// Whether a measurement is wanted: THINTISSUE_BENCH_FEM_FILTER, when set,
/// is a substring its label must contain (e.g. "1,000 hexahedra), automatic"),
/// so that a profile or a before/after comparison runs one case only.
bool wanted(const std::string& label)
{
  const char* filter = std::getenv("THINTISSUE_BENCH_FEM_FILTER");
  return filter == nullptr || label.find(filter) != std::string::npos;
}

/// Times `steps` single steps under a load at the node farthest from the
/// fixed ones, after `warmUp` steps have set the deformation going. A step
/// that fails throws, unless `tolerateFailures` (then it is counted).
StepStatistics measureSteps(const FemCase& c,
  const CorotationalHexFemSettings& base,
  int steps,
  int warmUp,
  bool tolerateFailures = false)
{
  CorotationalHexFemSettings settings = base;
  settings.timeStep = c.timeStep;
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
  double firstStepMilliseconds = 0.0;
  for (int k = 0; k < warmUp; ++k)
  {
    const auto start = std::chrono::steady_clock::now();
    fem.step();
    if (k == 0)
    {
      firstStepMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
  }
  int failedSteps = 0;
  std::vector<double> milliseconds;
  std::vector<double> iterations;
  std::vector<double> cpuMilliseconds;
  for (int k = 0; k < steps; ++k)
  {
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = threadCpuMilliseconds();
    const SolverResult result = fem.step();
    cpuMilliseconds.push_back(threadCpuMilliseconds() - cpuStart);
    milliseconds.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    if (!result.ok && !tolerateFailures)
    {
      throw std::runtime_error(c.name + ": " + result.message);
    }
    failedSteps += result.ok ? 0 : 1;
    iterations.push_back(result.iterations);
    if (std::getenv("THINTISSUE_BENCH_FEM_TRACE") != nullptr)
    {
      std::fprintf(stderr,
        "%s step %d: %.3f ms, %d iterations, %d factorizations (%d in steps)\n",
        c.name.c_str(),
        k,
        milliseconds.back(),
        result.iterations,
        fem.factorizationCount(),
        fem.synchronousFactorizationCount());
    }
  }
  return { percentile(milliseconds, 0.5),
    percentile(milliseconds, 0.99),
    percentile(milliseconds, 1.0),
    percentile(iterations, 0.5),
    percentile(cpuMilliseconds, 0.5),
    std::accumulate(cpuMilliseconds.begin(), cpuMilliseconds.end(), 0.0) /
      static_cast<double>(cpuMilliseconds.size()),
    firstStepMilliseconds,
    failedSteps };
}

void reportSteps(BenchmarkReporter& reporter,
  const std::string& label,
  const StepStatistics& statistics,
  std::optional<double> thesis)
{
  reporter.report(label, "step time", statistics.medianMilliseconds, "ms", thesis);
  reporter.report(label, "step time p99", statistics.p99Milliseconds, "ms");
  reporter.report(label, "step time max", statistics.maxMilliseconds, "ms");
  reporter.report(label,
    "step CPU time (stepping thread, median)",
    std::max(1e-6, statistics.medianThreadCpuMilliseconds),
    "ms");
  reporter.report(
    label, "iterations per step (median)", std::max(1.0, statistics.medianIterations), "");
  if (statistics.firstStepMilliseconds > 0.0)
  {
    reporter.report(label,
      "first step time (pattern, first factor or multigrid hierarchy)",
      statistics.firstStepMilliseconds,
      "ms");
  }
  if (statistics.failedSteps > 0)
  {
    reporter.report(label, "steps not converged", statistics.failedSteps, "");
  }
}

/// Which kernels OpenBLAS runs, and who chose them.
std::string blasCoreText(const BlasLibrary& blas)
{
  switch (blas.coreChoice)
  {
    case OpenBlasKernelChoice::Replaced:
      return ", kernels " + blas.core + " (chosen by ThinTissue for this CPU)";
    case OpenBlasKernelChoice::UsersChoice:
      return ", kernels " + blas.core + " (OPENBLAS_CORETYPE)";
    case OpenBlasKernelChoice::OpenBlasChoice:
      return ", kernels " + blas.core + " (OpenBLAS's choice)";
    case OpenBlasKernelChoice::NotOpenBlas:
      break;
  }
  return "";
}

CorotationalHexFemSettings solverSettings(LinearSolverKind kind)
{
  CorotationalHexFemSettings settings;
  settings.solver = kind;
  return settings;
}

struct NamedSolver
{
  const char* name;
  LinearSolverKind kind;
};

const std::array<NamedSolver, 5> allSolvers{ { { "CHOLMOD", LinearSolverKind::Cholmod },
  { "block-Jacobi conjugate gradient", LinearSolverKind::ConjugateGradient },
  { "stale-factor conjugate gradient", LinearSolverKind::StaleFactorConjugateGradient },
  { "multigrid conjugate gradient", LinearSolverKind::MultigridConjugateGradient },
  { "automatic", LinearSolverKind::Automatic } } };

/// CHOLMOD's factorization (a CHOLMOD step is ~95% of it) with each
/// fill-reducing ordering, simplicial and supernodal: the measurements
/// behind the defaults of CorotationalHexFemSettings.
void reportFactorizationChoices(BenchmarkReporter& reporter,
  const FemCase& c,
  int steps,
  int warmUp)
{
  const std::array<std::pair<const char*, FactorOrdering>, 4> orderings{ {
    { "minimum degree", FactorOrdering::MinimumDegree },
    { "METIS", FactorOrdering::Metis },
    { "nested dissection", FactorOrdering::NestedDissection },
    { "CHOLMOD default", FactorOrdering::CholmodDefault },
  } };
  for (const bool supernodal : { false, true })
  {
    for (const auto& [name, ordering] : orderings)
    {
      const std::string label = c.name + ", CHOLMOD " + (supernodal ? "supernodal" : "simplicial") +
                                ", " + name + " ordering";
      if (!wanted(label))
      {
        continue;
      }
      CorotationalHexFemSettings settings = solverSettings(LinearSolverKind::Cholmod);
      settings.factorOrdering = ordering;
      settings.supernodalThreshold = supernodal ? 0 : std::numeric_limits<int>::max();
      const StepStatistics statistics = measureSteps(c, settings, steps, warmUp);
      reporter.report(label, "step time", statistics.medianMilliseconds, "ms");
    }
  }
}

/// The stale-factor step with a simplicial and with a supernodal factor:
/// at small sizes one factorization serves tens of solves, so the solves'
/// cost decides, at large ones the factorization's (the measurements behind
/// CorotationalHexFemSettings::supernodalThreshold).
void reportFactorKinds(BenchmarkReporter& reporter, const FemCase& c, int steps, int warmUp)
{
  for (const bool supernodal : { false, true })
  {
    const std::string label = c.name + ", stale-factor conjugate gradient, " +
                              (supernodal ? "supernodal" : "simplicial") + " factor";
    if (!wanted(label))
    {
      continue;
    }
    CorotationalHexFemSettings settings =
      solverSettings(LinearSolverKind::StaleFactorConjugateGradient);
    settings.supernodalThreshold = supernodal ? 0 : std::numeric_limits<int>::max();
    const StepStatistics statistics = measureSteps(c, settings, steps, warmUp);
    reporter.report(label, "step time", statistics.medianMilliseconds, "ms");
    reporter.report(label,
      "step CPU time (stepping thread, mean)",
      std::max(1e-6, statistics.meanThreadCpuMilliseconds),
      "ms");
  }
}

HexahedralMesh block(int nx, int ny, int nz)
{
  HexahedralMesh mesh =
    HexahedralMesh::makeRegularGrid(Vector3::Zero(), Vector3::Ones(), nx, ny, nz);
  mesh.fixLowestNodes(0, 1e-12);
  return mesh;
}

/// The factor kinds on blocks between the thesis sizes and the 1,000
/// block, where they cross.
void reportFactorKindsBetween(BenchmarkReporter& reporter, const LinearMaterial& material)
{
  for (const auto& [nx, ny, nz] : { std::array<int, 3>{ 10, 5, 5 }, { 10, 10, 5 } })
  {
    const FemCase between{ "block (" + std::to_string(nx * ny * nz) + " hexahedra)",
      block(nx, ny, nz),
      material,
      0.001,
      std::nullopt };
    reportFactorKinds(reporter, between, 200, 5);
  }
}

/// A slit through the block (issue 20, item 6): the hexahedra left of the
/// plane x = `cutX` and below y = `cutY` take copies of their nodes on that
/// plane, as the cutter's duplication does. Returns the nodes copied.
int slitBlock(CorotationalHexFem& fem, double cutX, double cutY)
{
  std::map<int, int> copies;
  for (std::size_t h = 0; h < fem.hexahedronCount(); ++h)
  {
    Hexahedron nodes = fem.hexahedronNodes(h);
    Vector3 centre = Vector3::Zero();
    for (int node : nodes)
    {
      centre += fem.restPositions()[node] / 8.0;
    }
    if (centre.x() < cutX - 1.0 || centre.x() > cutX || centre.y() > cutY)
    {
      continue;
    }
    for (int& node : nodes)
    {
      if (std::abs(fem.restPositions()[node].x() - cutX) < 1e-9)
      {
        const auto [copy, isNew] = copies.try_emplace(node, -1);
        if (isNew)
        {
          copy->second = static_cast<int>(fem.addNodeCopy(static_cast<std::size_t>(node)));
        }
        node = copy->second;
      }
    }
    fem.replaceHexahedronNodes(h, nodes);
  }
  return static_cast<int>(copies.size());
}

/// The step right after a cut of the block and the worst of the 20 after
/// it: the price of a topology change (pattern, analysis, factor).
void reportCutBlock(BenchmarkReporter& reporter,
  const LinearMaterial& material,
  int nx,
  int ny,
  int nz)
{
  const std::string label =
    "block (" + std::to_string(nx * ny * nz) + " hexahedra) just cut, automatic";
  if (!wanted(label))
  {
    return;
  }
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.001;
  CorotationalHexFem fem(block(nx, ny, nz), material, settings);
  fem.setExternalForce(fem.nodeCount() - 1, Vector3(0.0, 0.2, -0.5));
  std::vector<double> milliseconds;
  const auto timedStep = [&]
  {
    const auto start = std::chrono::steady_clock::now();
    const SolverResult result = fem.step();
    milliseconds.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    if (!result.ok)
    {
      throw std::runtime_error(label + ": " + result.message);
    }
  };
  for (int k = 0; k < 20; ++k)
  {
    timedStep();
  }
  const double beforeCut = percentile(milliseconds, 0.5);
  const int copied = slitBlock(fem, std::floor(nx / 2.0), std::ceil(ny * 0.6));
  milliseconds.clear();
  for (int k = 0; k < 21; ++k)
  {
    timedStep();
  }
  reporter.report(label, "step time before the cut (median)", beforeCut, "ms");
  reporter.report(label, "first step after the cut", milliseconds.front(), "ms");
  milliseconds.erase(milliseconds.begin());
  reporter.report(label, "worst of the next 20 steps", percentile(milliseconds, 1.0), "ms");
  reporter.report(label, "nodes copied", copied, "");
  // The first step's factorization included (values are positive): 1
  // means none after the cut, as below BridgeUnknownLimit, where the old
  // factor bridges the change.
  reporter.report(label,
    "factorizations inside steps, the 20 before and 21 after the cut",
    fem.synchronousFactorizationCount(),
    "count");
}

} // namespace

/// Beyond what a factor can refresh: the iterative paths only, on a
/// 100,000-hexahedra block. A solve that does not converge is counted, not
/// thrown (block-Jacobi needs more than the 1,000-iteration cap here).
void reportHundredThousandBlock(BenchmarkReporter& reporter, const LinearMaterial& material)
{
  const FemCase hundredThousand{
    "block (100,000 hexahedra)", block(100, 50, 20), material, 0.001, std::nullopt
  };
  const std::array<NamedSolver, 2> iterativeSolvers{ {
    { "block-Jacobi conjugate gradient", LinearSolverKind::ConjugateGradient },
    { "multigrid conjugate gradient", LinearSolverKind::MultigridConjugateGradient },
  } }; // Automatic is the multigrid here (beyond AutomaticDirectLimit)
  for (const NamedSolver& solver : iterativeSolvers)
  {
    const std::string label = hundredThousand.name + ", " + solver.name;
    if (!wanted(label))
    {
      continue;
    }
    const bool jacobi = solver.kind == LinearSolverKind::ConjugateGradient;
    reportSteps(reporter,
      label,
      measureSteps(hundredThousand, solverSettings(solver.kind), jacobi ? 2 : 5, 1, true),
      std::nullopt);
  }
}

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
    grid.fixLowestNodes(0, 1e-9);
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
  useOneBlasThread(); // what the solver does at its first factorization
  const BlasLibrary blas = loadedBlasLibrary();
  reporter.report("BLAS under CHOLMOD: " + blas.name + " " + blas.configuration + " (" + blas.path +
                    ")" + blasCoreText(blas),
    "threads",
    blas.threads,
    "");
  for (const auto& c : cases)
  {
    const std::size_t hexahedra = c.mesh.hexahedronCount();
    const bool huge = hexahedra > 5000;
    const int steps = context.quick ? 2 : (huge ? 10 : 200);
    const int warmUp = huge ? 2 : 5;
    for (const NamedSolver& solver : allSolvers)
    {
      const bool slow = huge && solver.kind == LinearSolverKind::ConjugateGradient;
      if (!wanted(c.name + ", " + solver.name))
      {
        continue;
      }
      reportSteps(reporter,
        c.name + ", " + solver.name,
        measureSteps(c, solverSettings(solver.kind), slow ? 3 : steps, slow ? 1 : warmUp),
        c.thesisMilliseconds);
    }
    if (hexahedra <= 1000)
    {
      reportFactorKinds(reporter, c, steps, warmUp);
    }
    const std::string serialLabel = c.name + ", automatic, assembly on one thread";
    if (hexahedra >= 1000 && wanted(serialLabel))
    {
      // Against "automatic": what the parallel (coloured) assembly gains.
      CorotationalHexFemSettings serial = solverSettings(LinearSolverKind::Automatic);
      serial.assemblyThreads = 1;
      reportSteps(reporter, serialLabel, measureSteps(c, serial, steps, warmUp), std::nullopt);
    }
    if (hexahedra >= 1000 && !context.quick)
    {
      reportFactorizationChoices(reporter, c, huge ? 2 : 20, 1);
    }
  }
  if (!context.quick)
  {
    reportFactorKindsBetween(reporter, softMaterial);
  }
  // A thesis-size block (64 hexahedra) and the 1,000 one.
  reportCutBlock(reporter, softMaterial, 8, 4, 2);
  reportCutBlock(reporter, softMaterial, 20, 10, 5);
  if (!context.quick)
  {
    reportHundredThousandBlock(reporter, softMaterial);
  }

  if (!wanted("visual vertices"))
  {
    return;
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
