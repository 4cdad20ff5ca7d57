// The solver at scale (issue 20): every linear solver and factorization
// choice gives the same motion within the solve tolerance, the stale
// factor refreshed on a worker thread replays bit for bit whatever the
// thread timing, and bad settings are refused clearly.
#include "CorotationalHexFem.h"
#include "LinearAlgebraLibrary.h"
#include "MeniscusModel.h"
#include "SolverTestSupport.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <thread>

using namespace thintissue;
using thintissue::testing::expectRefusedNaming;
using thintissue::testing::fixedBlock;

#if defined(__SANITIZE_THREAD__)
// CHOLMOD runs OpenMP regions in libgomp, which is not instrumented:
// ThreadSanitizer cannot see its barriers and reports the writes of its
// threads as races (every report has a libgomp frame; none of them involves
// the solver's own worker beyond starting CHOLMOD).
extern "C" const char* __tsan_default_suppressions()
{
  return "race:libgomp.so.1\n";
}
#endif

namespace
{

/// Soft tissue in mm, N, s, `stiffer` times stiffer than 0.5 MPa: the
/// tests' loads bend the blocks by a few millimetres.
LinearMaterial tissue(double stiffer)
{
  LinearMaterial m;
  m.youngModulus = 0.5 * stiffer;
  m.poissonRatio = 0.45;
  m.density = 1.0e-9;
  return m;
}

/// Pushes the node farthest along x (an instrument) and steps.
std::vector<Vector3> pushAndStep(const HexahedralMesh& mesh,
  const LinearMaterial& material,
  const CorotationalHexFemSettings& settings,
  int steps,
  const std::function<void()>& backgroundHook = {})
{
  CorotationalHexFem fem(mesh, material, settings);
  if (backgroundHook)
  {
    fem.setBackgroundFactorizationHook(backgroundHook);
  }
  std::size_t loaded = 0;
  for (std::size_t n = 0; n < fem.nodeCount(); ++n)
  {
    if (fem.restPositions()[n].x() > fem.restPositions()[loaded].x() && !fem.isFixed(n))
    {
      loaded = n;
    }
  }
  fem.setExternalForce(loaded, Vector3(0.0, 0.2, -0.5));
  for (int k = 0; k < steps; ++k)
  {
    const SolverResult result = fem.step();
    EXPECT_TRUE(result.ok) << result.message;
  }
  return fem.positions();
}

double largestDifference(const std::vector<Vector3>& a, const std::vector<Vector3>& b)
{
  double largest = 0.0;
  for (std::size_t n = 0; n < a.size(); ++n)
  {
    largest = std::max(largest, (a[n] - b[n]).norm());
  }
  return largest;
}

double largestDisplacement(const HexahedralMesh& mesh, const std::vector<Vector3>& positions)
{
  double largest = 0.0;
  for (std::size_t n = 0; n < positions.size(); ++n)
  {
    largest = std::max(largest, (positions[n] - mesh.nodes[n]).norm());
  }
  return largest;
}

CorotationalHexFemSettings withSolver(LinearSolverKind kind)
{
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.001;
  settings.solver = kind;
  return settings;
}

/// All solver kinds and factorization choices against CHOLMOD (simplicial,
/// minimum degree): the same displacements within the solve tolerance.
void expectAllSolversAgree(const HexahedralMesh& mesh, const LinearMaterial& material, int steps)
{
  CorotationalHexFemSettings reference = withSolver(LinearSolverKind::Cholmod);
  reference.supernodalThreshold = std::numeric_limits<int>::max();
  const std::vector<Vector3> expected = pushAndStep(mesh, material, reference, steps);
  const double moved = largestDisplacement(mesh, expected);
  ASSERT_GT(moved, 0.0);
  std::vector<std::pair<std::string, CorotationalHexFemSettings>> variants;
  for (auto ordering : { FactorOrdering::MinimumDegree,
         FactorOrdering::Metis,
         FactorOrdering::NestedDissection,
         FactorOrdering::CholmodDefault })
  {
    CorotationalHexFemSettings supernodal = withSolver(LinearSolverKind::Cholmod);
    supernodal.supernodalThreshold = 0;
    supernodal.factorOrdering = ordering;
    variants.emplace_back(
      "supernodal, ordering " + std::to_string(static_cast<int>(ordering)), supernodal);
  }
  variants.emplace_back("Jacobi CG", withSolver(LinearSolverKind::ConjugateGradient));
  variants.emplace_back("stale factor", withSolver(LinearSolverKind::StaleFactorConjugateGradient));
  CorotationalHexFemSettings background =
    withSolver(LinearSolverKind::StaleFactorConjugateGradient);
  background.backgroundRefactorizationThreshold = 0;
  variants.emplace_back("stale factor refreshed in the background", background);
  variants.emplace_back("automatic", withSolver(LinearSolverKind::Automatic));
  variants.emplace_back("multigrid", withSolver(LinearSolverKind::MultigridConjugateGradient));
  CorotationalHexFemSettings levels = withSolver(LinearSolverKind::MultigridConjugateGradient);
  levels.multigrid.coarsestUnknowns = 30; // several levels even on the meniscus
  levels.multigridRebuildIterations = 1;  // and a rebuild every step
  variants.emplace_back("multigrid, small coarsest level, rebuilt every step", levels);
  for (const auto& [name, settings] : variants)
  {
    const std::vector<Vector3> positions = pushAndStep(mesh, material, settings, steps);
    EXPECT_LT(largestDifference(positions, expected), 1e-6 * moved + 1e-12)
      << name << " (displacement " << moved << ")";
  }
}

} // namespace

TEST(SolverAtScale, AllSolversAgreeOnTheMeniscus)
{
  LinearMaterial meniscus; // thesis 4.5, in mm, N, s
  meniscus.youngModulus = 150.0;
  meniscus.poissonRatio = 0.49;
  meniscus.density = 1.1e-9;
  expectAllSolversAgree(makeMeniscus().simulation, meniscus, 40);
}

TEST(SolverAtScale, AllSolversAgreeOnTheThousandHexahedraBlock)
{
  expectAllSolversAgree(fixedBlock(20, 10, 5), tissue(10.0), 6);
}

TEST(SolverAtScale, BackgroundRefreshReplaysBitForBitWhateverTheThreadTiming)
{
  // 500 steps of a swinging block, the factor refreshed on a worker thread
  // (swapped in a fixed number of steps after it starts): a run whose
  // worker is delayed at random gives the very same positions.
  const HexahedralMesh mesh = fixedBlock(8, 2, 2);
  CorotationalHexFemSettings settings = withSolver(LinearSolverKind::StaleFactorConjugateGradient);
  settings.backgroundRefactorizationThreshold = 0;
  settings.staleFactorIterationBudget = 4;
  settings.backgroundRefactorizationLag = 3;
  const int steps = 500;
  const std::vector<Vector3> prompt = pushAndStep(mesh, tissue(100.0), settings, steps);
  std::mt19937 random(20);
  std::uniform_int_distribution<int> microseconds(0, 3000);
  std::vector<int> delays(2000);
  for (int& delay : delays)
  {
    delay = microseconds(random);
  }
  std::size_t next = 0;
  const std::vector<Vector3> delayed = pushAndStep(mesh,
    tissue(100.0),
    settings,
    steps,
    [&]
    { std::this_thread::sleep_for(std::chrono::microseconds(delays[next++ % delays.size()])); });
  EXPECT_GT(next, 5u) << "the factor was never refreshed in the background";
  EXPECT_EQ(prompt, delayed);
  // And the same motion as refactorizing inside the step.
  settings.backgroundRefactorizationThreshold = std::numeric_limits<int>::max();
  const std::vector<Vector3> synchronous = pushAndStep(mesh, tissue(100.0), settings, steps);
  EXPECT_LT(largestDifference(prompt, synchronous), 1e-6 * largestDisplacement(mesh, prompt));
}

TEST(SolverAtScale, BigFactorsAreGivenMoreStepsToBeMadeInTheBackground)
{
  // A refresh is due no sooner than the settings' lag, and later where the
  // factor costs many solves: the 1,000-hexahedra block's (about 63) in a
  // calm step, so that the step it is due at need not wait for it.
  const auto largestLag = [](const HexahedralMesh& mesh, int steps)
  {
    CorotationalHexFemSettings settings =
      withSolver(LinearSolverKind::StaleFactorConjugateGradient);
    settings.backgroundRefactorizationThreshold = 0;
    CorotationalHexFem fem(mesh, tissue(10.0), settings);
    fem.setExternalForce(mesh.nodeCount() - 1, Vector3(0.0, 0.2, -0.5));
    EXPECT_EQ(fem.lastBackgroundRefactorizationLag(), 0);
    int largest = 0;
    for (int k = 0; k < steps; ++k)
    {
      EXPECT_TRUE(fem.step().ok);
      largest = std::max(largest, fem.lastBackgroundRefactorizationLag());
    }
    EXPECT_GT(fem.factorizationCount(), 1) << "no refresh started";
    return largest;
  };
  const int settingsLag = CorotationalHexFemSettings().backgroundRefactorizationLag;
  EXPECT_EQ(largestLag(fixedBlock(8, 2, 2), 200), settingsLag);
  const int bigLag = largestLag(fixedBlock(20, 10, 5), 60);
  EXPECT_GT(bigLag, settingsLag);
  EXPECT_LE(bigLag, MaximumRefactorizationLag);
}

TEST(SolverAtScale, BackgroundRefreshLeavesTheStepsToTheStaleFactor)
{
  // Refactorizations land off the step: after the first, none is done
  // inside a step while the stale factor converges within the cap; with a
  // cap of one iteration it does not, and the step refactorizes itself.
  const HexahedralMesh mesh = fixedBlock(8, 2, 2);
  CorotationalHexFemSettings settings = withSolver(LinearSolverKind::StaleFactorConjugateGradient);
  settings.backgroundRefactorizationThreshold = 0;
  settings.staleFactorIterationBudget = 4;
  CorotationalHexFem fem(mesh, tissue(100.0), settings);
  fem.setExternalForce(mesh.nodeCount() - 1, Vector3(0.0, 0.2, -0.5));
  for (int k = 0; k < 200; ++k)
  {
    ASSERT_TRUE(fem.step().ok);
  }
  EXPECT_EQ(fem.synchronousFactorizationCount(), 1);
  EXPECT_GT(fem.factorizationCount(), 3);
  settings.staleFactorIterationCap = 1;
  settings.conjugateGradientTolerance = 1e-12;
  fem.setSettings(settings);
  for (int k = 0; k < 50; ++k)
  {
    ASSERT_TRUE(fem.step().ok);
  }
  EXPECT_GT(fem.synchronousFactorizationCount(), 1);
}

TEST(SolverAtScale, TheStaleFactorTurnsWithTheTissue)
{
  // A block turned rigidly by 60 degrees: its co-rotational matrix is the
  // rest one turned, A = Q A_f Q^T, so the rest factor turned with the
  // nodal rotations is exact (one iteration, no refactorization). Without
  // the rotations the same factor no longer converges within
  // refactorizationIterations and the step refactorizes.
  const HexahedralMesh mesh = fixedBlock(6, 2, 2); // its fixed end turns with it
  const Eigen::Matrix3d turn =
    Eigen::AngleAxisd(M_PI / 3.0, Vector3(1.0, 2.0, 0.5).normalized()).toRotationMatrix();
  std::vector<Vector3> turned = mesh.nodes;
  for (Vector3& p : turned)
  {
    p = turn * p + Vector3(3.0, -1.0, 2.0);
  }
  for (const bool rotate : { true, false })
  {
    CorotationalHexFemSettings settings =
      withSolver(LinearSolverKind::StaleFactorConjugateGradient);
    settings.backgroundRefactorizationThreshold = std::numeric_limits<int>::max();
    settings.rotateStaleFactor = rotate;
    settings.conjugateGradientTolerance = 1e-10;
    CorotationalHexFem fem(mesh, tissue(100.0), settings);
    ASSERT_TRUE(fem.step().ok); // the factor of the rest state
    ASSERT_EQ(fem.synchronousFactorizationCount(), 1);
    fem.setPositions(turned);
    fem.setExternalForce(mesh.nodeCount() - 1, Vector3(0.0, 0.3, -0.5));
    const SolverResult result = fem.step();
    ASSERT_TRUE(result.ok) << result.message;
    if (rotate)
    {
      EXPECT_LE(result.iterations, 1);
      EXPECT_EQ(fem.synchronousFactorizationCount(), 1);
    }
    else
    {
      EXPECT_EQ(fem.synchronousFactorizationCount(), 2) << result.iterations << " iterations";
    }
  }
}

TEST(SolverAtScale, ParallelAssemblyGivesTheSameBitsWithOneOrTwoThreads)
{
  // The elements are coloured (no two of a colour share a node), each
  // colour assembled in parallel: every sum is taken in the same order.
  const HexahedralMesh mesh = fixedBlock(20, 10, 5); // beyond ParallelAssemblyMinimumElements
  ASSERT_GE(static_cast<int>(mesh.hexahedronCount()), ParallelAssemblyMinimumElements);
  CorotationalHexFemSettings settings = withSolver(LinearSolverKind::Cholmod);
  settings.assemblyThreads = 1;
  const std::vector<Vector3> serial = pushAndStep(mesh, tissue(10.0), settings, 8);
  ASSERT_GT(largestDisplacement(mesh, serial), 0.0);
  settings.assemblyThreads = 2;
  EXPECT_EQ(serial, pushAndStep(mesh, tissue(10.0), settings, 8));
  settings.assemblyThreads = 0; // all cores
  EXPECT_EQ(serial, pushAndStep(mesh, tissue(10.0), settings, 8));
}

namespace
{
/// Cuts the block's hexahedra of x in (cutX - 1, cutX) and y < cutY from
/// their neighbours across x = cutX: their corners on that plane are
/// replaced by new nodes (a cut's node duplication, thesis 5.3.1), plain
/// ones or copies of the nodes (addNodeCopy).
void cutBlock(CorotationalHexFem& fem, double cutX, double cutY, bool copyNodes = false)
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
    if (!(centre.x() > cutX - 1.0 && centre.x() < cutX && centre.y() < cutY))
    {
      continue;
    }
    for (int& node : nodes)
    {
      if (std::abs(fem.restPositions()[node].x() - cutX) < 1e-9)
      {
        if (copies.count(node) == 0)
        {
          copies[node] = static_cast<int>(
            copyNodes
              ? fem.addNodeCopy(static_cast<std::size_t>(node))
              : fem.addNode(
                  fem.restPositions()[node], fem.positions()[node], fem.velocities()[node]));
        }
        node = copies[node];
      }
    }
    fem.replaceHexahedronNodes(h, nodes);
  }
}

/// A block of nx x ny x nz pushed 5 steps, cut by cutBlock (and, with
/// `removeOne`, its last hexahedron removed), then stepped 12 more.
struct BlockCut
{
  int nx, ny, nz;
  double cutX, cutY;
  bool copyNodes = false;
  bool removeOne = false;
};

struct CutBlockRun
{
  std::vector<Vector3> positions;
  int factorizationsAfterCut = 0; ///< inside the steps after the cut
};

CutBlockRun stepCutBlock(const CorotationalHexFemSettings& settings,
  const BlockCut& cut,
  const std::function<void()>& backgroundHook = {})
{
  const HexahedralMesh mesh = fixedBlock(cut.nx, cut.ny, cut.nz);
  CorotationalHexFem fem(mesh, tissue(10.0), settings);
  fem.setBackgroundFactorizationHook(backgroundHook);
  fem.setExternalForce(mesh.nodeCount() - 1, Vector3(0.0, 0.2, -0.5));
  for (int k = 0; k < 5; ++k)
  {
    EXPECT_TRUE(fem.step().ok);
  }
  const int before = fem.synchronousFactorizationCount();
  cutBlock(fem, cut.cutX, cut.cutY, cut.copyNodes);
  if (cut.removeOne)
  {
    fem.removeHexahedron(fem.hexahedronCount() - 1);
  }
  for (int k = 0; k < 12; ++k)
  {
    const SolverResult result = fem.step();
    EXPECT_TRUE(result.ok) << result.message;
  }
  EXPECT_GT(fem.nodeCount(), mesh.nodeCount());
  return { fem.positions(), fem.synchronousFactorizationCount() - before };
}

/// A background hook sleeping a random 0 to `longest` microseconds, counting
/// its calls in `delayed`.
std::function<void()> randomDelays(unsigned seed, int longest, int& delayed)
{
  return [random = std::mt19937(seed),
           microseconds = std::uniform_int_distribution<int>(0, longest),
           &delayed]() mutable
  {
    ++delayed;
    std::this_thread::sleep_for(std::chrono::microseconds(microseconds(random)));
  };
}

/// `positions` after `cut` are those of CHOLMOD refactorizing every step,
/// to a millionth of the largest motion.
void expectMovesAsRefactorizingEveryStep(const std::vector<Vector3>& positions, const BlockCut& cut)
{
  const std::vector<Vector3> exact =
    stepCutBlock(withSolver(LinearSolverKind::Cholmod), cut).positions;
  const HexahedralMesh mesh = fixedBlock(cut.nx, cut.ny, cut.nz);
  const double moved = largestDisplacement(
    mesh, std::vector<Vector3>(exact.begin(), exact.begin() + mesh.nodeCount()));
  ASSERT_GT(moved, 0.0);
  EXPECT_LT(largestDifference(positions, exact), 1e-6 * moved);
}

/// The 1,000 block cut during a refresh (the cut after 5 steps).
const BlockCut ThousandBlockCut{ 20, 10, 5, 10.0, 6.0 };
} // namespace

TEST(SolverAtScale, ACutDuringABackgroundRefreshReplaysAndMovesAsRefactorizingEveryStep)
{
  // The cut changes the pattern while a refresh of the old one runs: that
  // refresh is dropped when due (never swapped in, whatever the timing),
  // the step of the cut does not wait for it, and the motion is the one a
  // factorization every step gives.
  CorotationalHexFemSettings background =
    withSolver(LinearSolverKind::StaleFactorConjugateGradient);
  background.backgroundRefactorizationThreshold = 0;
  background.staleFactorIterationBudget = 2;
  const std::vector<Vector3> prompt = stepCutBlock(background, ThousandBlockCut).positions;
  int delayed = 0;
  const std::vector<Vector3> late =
    stepCutBlock(background, ThousandBlockCut, randomDelays(13, 30000, delayed)).positions;
  EXPECT_GT(delayed, 1);
  EXPECT_EQ(prompt, late);
  const std::vector<Vector3> exact =
    stepCutBlock(withSolver(LinearSolverKind::Cholmod), ThousandBlockCut).positions;
  const HexahedralMesh mesh = fixedBlock(20, 10, 5);
  double moved = 0.0;
  for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
  {
    moved = std::max(moved, (exact[n] - mesh.nodes[n]).norm());
  }
  ASSERT_GT(moved, 0.0);
  EXPECT_LT(largestDifference(prompt, exact), 1e-6 * moved);
}

TEST(SolverAtScale, ACutRebuildsTheMultigridHierarchyAndMovesAsRefactorizingEveryStep)
{
  // A cut (new nodes) and a removed hexahedron renumber the system: the
  // hierarchy of the old numbering is dropped and rebuilt in the next step,
  // which converges to the motion a factorization every step gives.
  CorotationalHexFemSettings multigrid = withSolver(LinearSolverKind::MultigridConjugateGradient);
  multigrid.multigrid.coarsestUnknowns = 300; // three levels on the 1,000 block
  const HexahedralMesh mesh = fixedBlock(20, 10, 5);
  auto cutAndStep = [&](const CorotationalHexFemSettings& settings, bool isMultigrid)
  {
    CorotationalHexFem fem(mesh, tissue(10.0), settings);
    fem.setExternalForce(mesh.nodeCount() - 1, Vector3(0.0, 0.2, -0.5));
    for (int k = 0; k < 5; ++k)
    {
      EXPECT_TRUE(fem.step().ok);
    }
    const int builds = fem.multigridBuildCount();
    EXPECT_EQ(builds >= 1, isMultigrid);
    cutBlock(fem, 10.0, 6.0, true);
    fem.removeHexahedron(fem.hexahedronCount() - 1);
    for (int k = 0; k < 12; ++k)
    {
      const SolverResult result = fem.step();
      EXPECT_TRUE(result.ok) << result.message;
      if (isMultigrid)
      {
        EXPECT_LT(result.iterations, 100);
        EXPECT_EQ(fem.multigridBuildCount() > builds, true) << "step " << k;
      }
    }
    EXPECT_GT(fem.nodeCount(), mesh.nodeCount());
    return fem.positions();
  };
  const std::vector<Vector3> expected = cutAndStep(withSolver(LinearSolverKind::Cholmod), false);
  const double moved = largestDisplacement(
    mesh, std::vector<Vector3>(expected.begin(), expected.begin() + mesh.nodeCount()));
  ASSERT_GT(moved, 0.0);
  EXPECT_LT(largestDifference(cutAndStep(multigrid, true), expected), 1e-6 * moved);
}

TEST(SolverAtScale, TheOldFactorBridgesACutUntilTheNewOneLands)
{
  // Issue 20 item 6: after a cut the old pattern's factor keeps
  // preconditioning (glued copies plus the touched nodes' exact solve) while
  // the new pattern is analysed and factorized in the background: no step
  // factorizes, the motion is the exact one, and replays are bit for bit
  // whatever the worker's timing. Without the bridge the step after the
  // cut factorizes.
  // A 10 x 5 x 2 block (thesis size, below BridgeUnknownLimit) cut with
  // node copies and one hexahedron removed.
  const BlockCut slit{ 10, 5, 2, 5.0, 3.0, true, true };
  CorotationalHexFemSettings bridged = withSolver(LinearSolverKind::StaleFactorConjugateGradient);
  const CutBlockRun prompt = stepCutBlock(bridged, slit);
  EXPECT_EQ(prompt.factorizationsAfterCut, 0);

  int delayed = 0;
  const CutBlockRun late = stepCutBlock(bridged, slit, randomDelays(7, 3000, delayed));
  EXPECT_GT(delayed, 1);
  EXPECT_EQ(prompt.positions, late.positions);

  CorotationalHexFemSettings unbridged = bridged;
  unbridged.bridgeTopologyChanges = false;
  EXPECT_GE(stepCutBlock(unbridged, slit).factorizationsAfterCut, 1);

  expectMovesAsRefactorizingEveryStep(prompt.positions, slit);
}

TEST(SolverAtScale, ACutTouchingMostOfTheSystemIsFactorizedAtOnce)
{
  // Beyond BridgeTouchedFraction the touched block's exact solve costs
  // about a whole factorization at every bridged iteration: the step after
  // the cut factorizes instead, and moves as refactorizing every step.
  // A 4 x 3 x 2 block cut through its whole width: half its free nodes
  // belong to the copied hexahedra.
  const BlockCut across{ 4, 3, 2, 2.0, 100.0, true, false };
  const CutBlockRun bridged =
    stepCutBlock(withSolver(LinearSolverKind::StaleFactorConjugateGradient), across);
  EXPECT_GE(bridged.factorizationsAfterCut, 1);
  expectMovesAsRefactorizingEveryStep(bridged.positions, across);
}

TEST(SolverAtScale, ANodeCopyIsItsSourcesTwinAndACutOfCopiesMovesLikeOneOfNewNodes)
{
  // A copy has its source's rest and current position, velocity and fixed
  // flag; a cut made of copies moves as one made of new nodes.
  const HexahedralMesh mesh = fixedBlock(10, 4, 2);
  const CorotationalHexFemSettings settings = withSolver(LinearSolverKind::Cholmod);
  auto cutAndStep = [&](bool copyNodes)
  {
    CorotationalHexFem fem(mesh, tissue(10.0), settings);
    fem.setExternalForce(mesh.nodeCount() - 1, Vector3(0.0, 0.2, -0.5));
    for (int k = 0; k < 5; ++k)
    {
      EXPECT_TRUE(fem.step().ok);
    }
    const std::size_t before = fem.nodeCount();
    cutBlock(fem, 5.0, 2.0, copyNodes);
    EXPECT_GT(fem.nodeCount(), before);
    for (int k = 0; k < 5; ++k)
    {
      EXPECT_TRUE(fem.step().ok);
    }
    return fem.positions();
  };
  const std::vector<Vector3> fromCopies = cutAndStep(true);
  EXPECT_EQ(fromCopies, cutAndStep(false));

  CorotationalHexFem fem(mesh, tissue(10.0), settings);
  fem.setFixed(3, true);
  std::vector<Vector3> velocities(fem.nodeCount(), Vector3::Zero());
  velocities[3] = Vector3(1.0, 2.0, 3.0);
  fem.setVelocities(velocities);
  const std::size_t copy = fem.addNodeCopy(3);
  EXPECT_EQ(fem.restPositions()[copy], fem.restPositions()[3]);
  EXPECT_EQ(fem.velocities()[copy], Vector3(1.0, 2.0, 3.0));
  EXPECT_TRUE(fem.isFixed(copy));
  EXPECT_THROW(fem.addNodeCopy(fem.nodeCount()), InvalidInputError);
}

TEST(SolverAtScale, BadSettingsAreRefusedClearly)
{
  const HexahedralMesh mesh = fixedBlock(2, 1, 1);
  auto expectError = [&](const CorotationalHexFemSettings& settings, const std::string& word)
  { expectRefusedNaming([&] { CorotationalHexFem fem(mesh, tissue(100.0), settings); }, word); };
  CorotationalHexFemSettings settings;
  settings.staleFactorIterationCap = 0;
  expectError(settings, "iteration cap");
  settings = {};
  settings.conjugateGradientMaxIterations = 0;
  expectError(settings, "iteration limit");
  settings = {};
  settings.backgroundRefactorizationLag = 0;
  expectError(settings, "lag");
  settings = {};
  settings.supernodalThreshold = -1;
  expectError(settings, "threshold");
  settings = {};
  settings.backgroundRefactorizationThreshold = -5;
  expectError(settings, "threshold");
  settings = {};
  settings.assemblyThreads = -1;
  expectError(settings, "assembly threads");
  settings = {};
  settings.warmStartSolutions = 0;
  expectError(settings, "warm-start solutions");
  settings = {};
  settings.warmStartSolutions = 5;
  expectError(settings, "warm-start solutions");
  settings = {};
  settings.warmStartIterations = -1;
  expectError(settings, "warm-start iterations");
}

TEST(SolverAtScale, TheLastSolutionsStartATransientsSolvesNearerAndMoveAlike)
{
  // A sudden push on a 250-hexahedra block: over its transient the steps'
  // solutions change smoothly, and the energy-best combination of the last
  // three starts conjugate gradients nearer than the last one alone (fewer
  // iterations, every solver kind that iterates), with the same motion
  // within the solve tolerance.
  const HexahedralMesh mesh = fixedBlock(10, 5, 5);
  for (const LinearSolverKind kind : { LinearSolverKind::StaleFactorConjugateGradient,
         LinearSolverKind::MultigridConjugateGradient,
         LinearSolverKind::ConjugateGradient })
  {
    int iterations[2] = { 0, 0 };
    std::vector<Vector3> positions[2];
    for (int depth : { 1, 3 })
    {
      CorotationalHexFemSettings settings = withSolver(kind);
      settings.warmStartSolutions = depth;
      CorotationalHexFem fem(mesh, tissue(1.0), settings);
      fem.setExternalForce(mesh.nodeCount() - 1, Vector3(0.0, 0.2, -0.5));
      for (int k = 0; k < 40; ++k)
      {
        const SolverResult result = fem.step();
        ASSERT_TRUE(result.ok) << result.message;
        iterations[depth == 3] += result.iterations;
      }
      positions[depth == 3] = fem.positions();
    }
    const double moved = largestDisplacement(mesh, positions[0]);
    ASSERT_GT(moved, 1e-3);
    EXPECT_LT(largestDifference(positions[0], positions[1]), 1e-6 * moved)
      << static_cast<int>(kind);
    EXPECT_LT(iterations[1], iterations[0]) << static_cast<int>(kind);
  }
}

TEST(SolverAtScale, TheLoadedBlasIsNamed)
{
  const BlasLibrary blas = loadedBlasLibrary();
  EXPECT_TRUE(blas.name == "OpenBLAS" || blas.name == "reference BLAS") << blas.name;
  EXPECT_TRUE(std::filesystem::exists(blas.path)) << blas.path;
  EXPECT_GE(blas.threads, 1);
  if (blas.name == "OpenBLAS")
  {
    EXPECT_NE(blas.configuration.find("OpenBLAS"), std::string::npos) << blas.configuration;
  }
}

TEST(SolverAtScale, OpenBlasKernelsFollowTheCpusVectorUnits)
{
  CpuVectorFeatures features;
  EXPECT_STREQ(openBlasCoreFor(features), "");
  features.avx2 = true;
  EXPECT_STREQ(openBlasCoreFor(features), "") << "AVX2 without FMA";
  features.fma = true;
  EXPECT_STREQ(openBlasCoreFor(features), "Haswell");
  features.avx512 = true;
  EXPECT_STREQ(openBlasCoreFor(features), "SkylakeX");
}

// The solver library selected OpenBLAS's kernels when it was loaded:
// OpenBLAS runs those this CPU can run best. On this machine's Xeon
// OpenBLAS 0.3.21 alone ran its SSE3 kernels ("Prescott").
TEST(SolverAtScale, OpenBlasRunsTheKernelsThisCpuCanRun)
{
  const BlasLibrary blas = loadedBlasLibrary();
  const std::string expected = openBlasCoreFor(cpuVectorFeatures());
  if (blas.name != "OpenBLAS" || expected.empty())
  {
    GTEST_SKIP() << "not OpenBLAS (" << blas.name << "), or a CPU without AVX2";
  }
  auto lower = [](std::string text)
  {
    std::transform(text.begin(),
      text.end(),
      text.begin(),
      [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
  };
  ASSERT_NE(blas.coreChoice, OpenBlasKernelChoice::UsersChoice)
    << "OPENBLAS_CORETYPE is set: the user's choice is kept";
  ASSERT_NE(blas.coreChoice, OpenBlasKernelChoice::NotOpenBlas) << blas.configuration;
  if (blas.coreChoice == OpenBlasKernelChoice::Replaced)
  {
    EXPECT_EQ(lower(blas.core), lower(expected));
  }
  else
  {
    // OpenBLAS's own choice was kept: it must be at least as capable.
    const std::string core = lower(blas.core);
    EXPECT_TRUE(core == "skylakex" || core == "cooperlake" || core == "sapphirerapids" ||
                (expected == "Haswell" && (core == "haswell" || core == "zen")))
      << blas.core << " on a CPU for " << expected;
  }
  EXPECT_EQ(std::getenv("OPENBLAS_CORETYPE"), nullptr) << "the environment is left as it was";
}
