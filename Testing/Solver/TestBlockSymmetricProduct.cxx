#include "BlockSymmetricProduct.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <vector>

using namespace thintissue;

namespace
{

/// The upper triangle (CSC) of a random symmetric matrix whose pattern is
/// the FEM's: a full 3x3 block for each pair of coupled nodes (random,
/// with every node coupled to itself).
Eigen::SparseMatrix<double> randomBlockUpper(int nodes, std::mt19937& random)
{
  std::uniform_int_distribution<int> pick(0, nodes - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::set<std::pair<int, int>> pairs;
  for (int a = 0; a < nodes; ++a)
  {
    pairs.insert({ a, a });
    for (int k = 0; k < 4; ++k)
    {
      const int b = pick(random);
      pairs.insert({ std::min(a, b), std::max(a, b) });
    }
  }
  std::vector<Eigen::Triplet<double>> entries;
  for (const auto& [a, b] : pairs)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (a != b || i <= j)
          entries.emplace_back(3 * a + i, 3 * b + j, value(random));
  Eigen::SparseMatrix<double> upper(3 * nodes, 3 * nodes);
  upper.setFromTriplets(entries.begin(), entries.end());
  upper.makeCompressed();
  return upper;
}

void expectProductOfSymmetric(const Eigen::SparseMatrix<double>& upper,
  const BlockSymmetricProduct& product,
  std::mt19937& random)
{
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd x(upper.rows());
  for (Eigen::Index i = 0; i < x.size(); ++i)
    x[i] = value(random);
  const Eigen::VectorXd expected = upper.selfadjointView<Eigen::Upper>() * x;
  Eigen::VectorXd y = Eigen::VectorXd::Constant(x.size(), 7.0); // overwritten, not added to
  product.multiply(upper, x, y);
  ASSERT_EQ(y.size(), expected.size());
  EXPECT_LE((y - expected).norm(), 1e-13 * expected.norm());
}

} // namespace

TEST(BlockSymmetricProduct, NodeBlocksGiveTheSymmetricProduct)
{
  std::mt19937 random(3);
  for (const int nodes : { 1, 2, 7, 60 })
  {
    const Eigen::SparseMatrix<double> upper = randomBlockUpper(nodes, random);
    BlockSymmetricProduct product;
    product.analyse(upper);
    EXPECT_TRUE(product.blocked()) << nodes << " nodes";
    expectProductOfSymmetric(upper, product, random);
  }
}

TEST(BlockSymmetricProduct, AnyOtherPatternFallsBackToTheScalarProduct)
{
  // A node block missing one entry, and a size that is no multiple of 3:
  // refused as blocks, the product is still right.
  std::mt19937 random(5);
  Eigen::SparseMatrix<double> upper = randomBlockUpper(9, random);
  const Eigen::Index row = upper.innerIndexPtr()[upper.outerIndexPtr()[10]];
  upper.prune([&](Eigen::Index r, Eigen::Index c, double) { return !(r == row && c == 10); });
  upper.makeCompressed();
  BlockSymmetricProduct product;
  product.analyse(upper);
  EXPECT_FALSE(product.blocked());
  expectProductOfSymmetric(upper, product, random);

  Eigen::SparseMatrix<double> odd(4, 4);
  odd.insert(0, 0) = 2.0;
  odd.insert(1, 3) = -1.0;
  odd.insert(3, 3) = 4.0;
  odd.makeCompressed();
  product.analyse(odd);
  EXPECT_FALSE(product.blocked());
  expectProductOfSymmetric(odd, product, random);
}
