// The smoothed-aggregation multigrid preconditioner (issue 20, item 4): its
// V-cycle is a symmetric positive definite operator (so that conjugate
// gradients may use it), it makes conjugate gradients converge in far fewer
// iterations than block-Jacobi, and bad settings are refused.
#include "CorotationalHexFem.h"
#include "SmoothedAggregation.h"
#include "SolverTestSupport.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <cmath>
#include <random>

using namespace thintissue;
using thintissue::testing::expectRefusedNaming;
using thintissue::testing::fixedBlock;

namespace
{
using SparseMatrix = SmoothedAggregation::SparseMatrix;

LinearMaterial tissue()
{
  LinearMaterial m;
  m.youngModulus = 5.0;
  m.poissonRatio = 0.45;
  m.density = 1.0e-9;
  return m;
}

/// The upper triangle of the stiffness of `mesh` on its free nodes plus a
/// small mass shift (the implicit step's matrix at rest, R = I), and the
/// free nodes' positions.
SparseMatrix restSystem(const HexahedralMesh& mesh, SmoothedAggregation::Coordinates& nodes)
{
  std::vector<int> dof(mesh.nodeCount(), -1);
  int count = 0;
  for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
  {
    if (!mesh.fixedNodes[n])
    {
      dof[n] = count;
      count += 3;
    }
  }
  nodes.resize(count / 3, 3);
  for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
  {
    if (dof[n] >= 0)
    {
      nodes.row(dof[n] / 3) = mesh.nodes[n].transpose();
    }
  }
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t h = 0; h < mesh.hexahedronCount(); ++h)
  {
    HexahedronCorners corners;
    for (int a = 0; a < 8; ++a)
    {
      corners[a] = mesh.nodes[mesh.hexahedra[h][a]];
    }
    const HexahedronRestState rest = computeHexahedronRestState(corners, tissue(), "test");
    for (int a = 0; a < 8; ++a)
    {
      for (int b = 0; b < 8; ++b)
      {
        const int row = dof[mesh.hexahedra[h][a]], column = dof[mesh.hexahedra[h][b]];
        for (int i = 0; i < 3 && row >= 0 && column >= 0; ++i)
        {
          for (int j = 0; j < 3; ++j)
          {
            if (row + i <= column + j)
            {
              entries.emplace_back(row + i, column + j, rest.stiffness(3 * a + i, 3 * b + j));
            }
          }
        }
      }
    }
  }
  for (int k = 0; k < count; ++k)
  {
    entries.emplace_back(k, k, 1e-3);
  }
  SparseMatrix upper(count, count);
  upper.setFromTriplets(entries.begin(), entries.end());
  return upper;
}

/// Pushes the block's far corner for `steps` steps; the median iterations.
int medianIterations(const HexahedralMesh& mesh, const CorotationalHexFemSettings& settings)
{
  CorotationalHexFem fem(mesh, tissue(), settings);
  fem.setExternalForce(mesh.nodeCount() - 1, Vector3(0.0, 0.2, -0.5));
  std::vector<int> iterations;
  for (int k = 0; k < 5; ++k)
  {
    const SolverResult result = fem.step();
    EXPECT_TRUE(result.ok) << result.message;
    iterations.push_back(result.iterations);
  }
  std::sort(iterations.begin(), iterations.end());
  return iterations[iterations.size() / 2];
}
} // namespace

TEST(SmoothedAggregation, TheVCycleIsSymmetricPositiveDefinite)
{
  SmoothedAggregation::Coordinates nodes;
  const SparseMatrix upper = restSystem(fixedBlock(12, 6, 4), nodes);
  SmoothedAggregationSettings settings;
  settings.coarsestUnknowns = 100; // three levels at least
  SmoothedAggregation multigrid(settings);
  std::string message;
  ASSERT_TRUE(multigrid.build(upper, nodes, message)) << message;
  ASSERT_GE(multigrid.levelCount(), 3);
  EXPECT_TRUE(multigrid.finestLevelInNodeBlocks()); // the path these checks are about
  EXPECT_LT(multigrid.levelUnknowns(1), multigrid.levelUnknowns(0) / 4);
  EXPECT_GT(multigrid.operatorComplexity(), 1.0);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const Eigen::Index n = upper.rows();
  for (int trial = 0; trial < 5; ++trial)
  {
    Eigen::VectorXd x(n), y(n), mx, my;
    for (Eigen::Index i = 0; i < n; ++i)
    {
      x[i] = uniform(random);
      y[i] = uniform(random);
    }
    multigrid.apply(x, mx);
    multigrid.apply(y, my);
    const double scale = x.norm() * my.norm() + y.norm() * mx.norm();
    EXPECT_NEAR(x.dot(my), y.dot(mx), 1e-12 * scale);
    EXPECT_GT(x.dot(mx), 0.0);
    EXPECT_GT(y.dot(my), 0.0);
  }
  // Applying it twice gives the same bits (no state kept between applies).
  Eigen::VectorXd again;
  Eigen::VectorXd x = Eigen::VectorXd::Ones(n), first;
  multigrid.apply(x, first);
  multigrid.apply(x, again);
  EXPECT_EQ(first, again);
}

TEST(SmoothedAggregation, TheVCycleGivesTheSameBitsOnOneOrTwoThreads)
{
  // A finest level beyond the parallel products' threshold (200,000
  // stored entries): its rows are summed by one thread each, in order.
  SmoothedAggregation::Coordinates nodes;
  const SparseMatrix upper = restSystem(fixedBlock(20, 10, 5), nodes);
  ASSERT_GT(2 * upper.nonZeros() - upper.rows(), 200000);
  SmoothedAggregation multigrid;
  std::string message;
  ASSERT_TRUE(multigrid.build(upper, nodes, message)) << message;
  EXPECT_TRUE(multigrid.finestLevelInNodeBlocks());
  Eigen::VectorXd r(upper.rows());
  for (Eigen::Index i = 0; i < r.size(); ++i)
  {
    r[i] = std::sin(0.37 * static_cast<double>(i));
  }
  Eigen::VectorXd serial, parallel;
  tbb::task_arena(1).execute([&] { multigrid.apply(r, serial); });
  tbb::task_arena(2).execute([&] { multigrid.apply(r, parallel); });
  ASSERT_GT(serial.norm(), 0.0);
  EXPECT_EQ(serial, parallel);
}

TEST(SmoothedAggregation, ConjugateGradientsNeedFarFewerIterationsThanWithBlockJacobi)
{
  const HexahedralMesh mesh = fixedBlock(16, 8, 4); // 2,160 unknowns
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.001;
  settings.solver = LinearSolverKind::ConjugateGradient;
  const int jacobi = medianIterations(mesh, settings);
  settings.solver = LinearSolverKind::MultigridConjugateGradient;
  settings.multigrid.coarsestUnknowns = 200; // a real hierarchy, not a direct solve
  const int multigrid = medianIterations(mesh, settings);
  RecordProperty("multigridIterations", multigrid);
  RecordProperty("blockJacobiIterations", jacobi);
  EXPECT_GT(multigrid, 1);
  EXPECT_LT(4 * multigrid, jacobi) << "multigrid " << multigrid << ", block-Jacobi " << jacobi;
}

TEST(SmoothedAggregation, BadSettingsAreRefusedClearly)
{
  auto expectError = [](const SmoothedAggregationSettings& settings, const std::string& word)
  { expectRefusedNaming([&] { SmoothedAggregation multigrid(settings); }, word); };
  SmoothedAggregationSettings settings;
  settings.coarsestUnknowns = 0;
  expectError(settings, "coarsest unknowns");
  settings = {};
  settings.maximumLevels = 0;
  expectError(settings, "levels");
  settings = {};
  settings.smootherDegree = 0;
  expectError(settings, "smoother degree");
  settings = {};
  settings.strengthThreshold = 1.0;
  expectError(settings, "strength threshold");

  CorotationalHexFemSettings fem;
  fem.multigrid.smootherDegree = -1;
  EXPECT_THROW(CorotationalHexFem(fixedBlock(2, 1, 1), tissue(), fem), InvalidInputError);
  fem = {};
  fem.multigridRebuildIterations = 0;
  expectRefusedNaming(
    [&] { CorotationalHexFem solver(fixedBlock(2, 1, 1), tissue(), fem); }, "multigrid rebuild");
}

TEST(SmoothedAggregation, AMatrixWhoseBlocksAreNotPositiveDefiniteIsRefused)
{
  SmoothedAggregation::Coordinates nodes;
  SparseMatrix upper = restSystem(fixedBlock(4, 2, 2), nodes);
  upper.coeffRef(0, 0) = -1.0;
  SmoothedAggregation multigrid;
  std::string message;
  EXPECT_FALSE(multigrid.build(upper, nodes, message));
  EXPECT_NE(message.find("not positive definite"), std::string::npos) << message;
  EXPECT_FALSE(multigrid.ready());
}

TEST(SmoothedAggregation, AMatrixNotMadeOfWholeNodeBlocksKeepsItsDoubleRows)
{
  // A weak coupling of one unknown of the first node with one of the last
  // (nodes no hexahedron joins): a partial 3x3 block, so the finest level
  // keeps its double rows, and the V-cycle is still symmetric positive
  // definite.
  SmoothedAggregation::Coordinates nodes;
  SparseMatrix upper = restSystem(fixedBlock(6, 3, 2), nodes);
  const Eigen::Index last = upper.rows() - 1;
  ASSERT_EQ(upper.coeff(0, last), 0.0);
  upper.coeffRef(0, last) = 1e-6 * upper.coeff(0, 0);
  upper.makeCompressed();
  SmoothedAggregation multigrid;
  std::string message;
  ASSERT_TRUE(multigrid.build(upper, nodes, message)) << message;
  EXPECT_FALSE(multigrid.finestLevelInNodeBlocks());
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(upper.rows(), -1.0, 1.0);
  Eigen::VectorXd y = Eigen::VectorXd::Ones(upper.rows());
  Eigen::VectorXd mx, my;
  multigrid.apply(x, mx);
  multigrid.apply(y, my);
  EXPECT_NEAR(x.dot(my), y.dot(mx), 1e-12 * (x.norm() * my.norm() + y.norm() * mx.norm()));
  EXPECT_GT(x.dot(mx), 0.0);
}
