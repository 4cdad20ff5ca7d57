// The first guess of an iterative solve from the last solutions
// (SolutionHistory.h): the energy minimizer over their span.
#include "SolutionHistory.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <random>

using namespace thintissue;

namespace
{

struct Problem
{
  Eigen::MatrixXd matrix;
  Eigen::VectorXd rhs;
  SolutionHistory::Product multiply() const
  {
    return [this](const Eigen::VectorXd& v, Eigen::VectorXd& y) { y = matrix * v; };
  }
  double energy(const Eigen::VectorXd& x) const { return 0.5 * x.dot(matrix * x) - rhs.dot(x); }
};

Eigen::VectorXd randomVector(int size, std::mt19937& random)
{
  std::normal_distribution<double> normal;
  Eigen::VectorXd v(size);
  for (int i = 0; i < size; ++i)
    v(i) = normal(random);
  return v;
}

Problem randomProblem(int size, std::mt19937& random)
{
  std::normal_distribution<double> normal;
  Eigen::MatrixXd m(size, size);
  for (int i = 0; i < size; ++i)
    for (int j = 0; j < size; ++j)
      m(i, j) = normal(random);
  Problem p;
  p.matrix = m * m.transpose() + size * Eigen::MatrixXd::Identity(size, size);
  p.rhs = randomVector(size, random);
  return p;
}

} // namespace

TEST(SolutionHistory, TheGuessIsTheEnergyMinimizerOverTheLastSolutions)
{
  std::mt19937 random(7);
  const int size = 30;
  const Problem problem = randomProblem(size, random);
  SolutionHistory history;
  history.setDepth(3);
  std::vector<Eigen::VectorXd> pushed;
  for (int k = 0; k < 5; ++k)
  {
    pushed.push_back(randomVector(size, random));
    history.push(pushed.back());
  }
  ASSERT_EQ(history.usable(size), 3);
  EXPECT_EQ(history.newest(), pushed.back());
  Eigen::VectorXd x, product;
  history.firstGuess(problem.multiply(), problem.rhs, x, product);
  // The reference: the Galerkin system on the three newest, solved densely.
  Eigen::MatrixXd basis(size, 3);
  for (int i = 0; i < 3; ++i)
    basis.col(i) = pushed[pushed.size() - 1 - i];
  const Eigen::VectorXd weights =
    (basis.transpose() * problem.matrix * basis).ldlt().solve(basis.transpose() * problem.rhs);
  const Eigen::VectorXd expected = basis * weights;
  EXPECT_LT((x - expected).norm(), 1e-10 * expected.norm());
  EXPECT_LT((product - problem.matrix * x).norm(), 1e-10 * product.norm());
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_LE(problem.energy(x), problem.energy(basis.col(i)) + 1e-12);
  }
  // Depth 1 of the call: the newest alone, as it is.
  history.firstGuess(problem.multiply(), problem.rhs, x, product, 1);
  EXPECT_EQ(x, pushed.back());
  EXPECT_LT((product - problem.matrix * x).norm(), 1e-12 * product.norm());
}

TEST(SolutionHistory, DependentOrMissingSolutionsGetNoWeight)
{
  std::mt19937 random(11);
  const int size = 12;
  const Problem problem = randomProblem(size, random);
  SolutionHistory history;
  history.setDepth(4);
  Eigen::VectorXd x, product;
  // Nothing yet: zero.
  history.firstGuess(problem.multiply(), problem.rhs, x, product);
  EXPECT_EQ(x.size(), size);
  EXPECT_EQ(x.norm(), 0.0);
  // The same solution three times (a steady state): the best multiple of it.
  const Eigen::VectorXd v = randomVector(size, random);
  for (int k = 0; k < 3; ++k)
    history.push(v);
  history.firstGuess(problem.multiply(), problem.rhs, x, product);
  ASSERT_TRUE(x.allFinite());
  const double best = v.dot(problem.rhs) / v.dot(problem.matrix * v);
  EXPECT_LT((x - best * v).norm(), 1e-9 * std::abs(best) * v.norm());
  // Solutions of another size (before a topology change) are not used.
  history.push(randomVector(size + 3, random));
  EXPECT_EQ(history.usable(size), 0);
  EXPECT_EQ(history.usable(size + 3), 1);
  history.push(randomVector(size + 3, random));
  history.keepNewestOnly();
  EXPECT_EQ(history.usable(size + 3), 1);
}

TEST(SolutionHistory, DepthsOutOfRangeAreRefused)
{
  SolutionHistory history;
  EXPECT_THROW(history.setDepth(0), InvalidInputError);
  EXPECT_THROW(history.setDepth(SolutionHistory::MaximumDepth + 1), InvalidInputError);
  history.setDepth(SolutionHistory::MaximumDepth);
  EXPECT_EQ(history.depth(), SolutionHistory::MaximumDepth);
}
