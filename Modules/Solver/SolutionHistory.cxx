#include "SolutionHistory.h"

#include "ThinTissueError.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <string>

namespace thintissue
{

static_assert(SolutionHistory::MaximumDepth == 4, "firstGuess solves on a fixed 4 x 4 Gram matrix");

void SolutionHistory::setDepth(int depth)
{
  if (depth < 1 || depth > MaximumDepth)
  {
    throw InvalidInputError("solution history: the depth must be between 1 and " +
                            std::to_string(MaximumDepth) + " (got " + std::to_string(depth) + ")");
  }
  Depth = depth;
  Count = std::min(Count, Depth);
}

void SolutionHistory::push(const Eigen::VectorXd& solution)
{
  // The oldest's storage becomes the newest's (no allocation at a fixed size).
  std::rotate(Solutions.begin(), Solutions.begin() + Depth - 1, Solutions.begin() + Depth);
  Solutions[0] = solution;
  Count = std::min(Count + 1, Depth);
}

void SolutionHistory::keepNewestOnly()
{
  Count = std::min(Count, 1);
}

int SolutionHistory::usable(Eigen::Index size) const
{
  int k = 0;
  while (k < Count && Solutions[k].size() == size)
  {
    ++k;
  }
  return k;
}

void SolutionHistory::firstGuess(const Product& multiply,
  const Eigen::VectorXd& rhs,
  Eigen::VectorXd& x,
  Eigen::VectorXd& product,
  int depth)
{
  const int k = std::min(depth, usable(rhs.size()));
  if (k == 0)
  {
    x.setZero(rhs.size());
    product.setZero(rhs.size());
    return;
  }
  if (k == 1)
  {
    x = Solutions[0];
    multiply(x, product);
    return;
  }
  // Fixed 4 x 4 (no allocation): the unused rows and columns hold the mean
  // diagonal entry on the diagonal and no load, so they get no weight.
  Eigen::Matrix4d gram = Eigen::Matrix4d::Zero();
  Eigen::Vector4d load = Eigen::Vector4d::Zero();
  for (int i = 0; i < k; ++i)
  {
    multiply(Solutions[i], Products[i]);
  }
  for (int i = 0; i < k; ++i)
  {
    load(i) = Solutions[i].dot(rhs);
    for (int j = 0; j <= i; ++j)
    {
      // Symmetrized: A is symmetric, the two dot products differ by rounding.
      gram(i, j) = gram(j, i) =
        0.5 * (Solutions[i].dot(Products[j]) + Solutions[j].dot(Products[i]));
    }
  }
  const double padding = gram.trace() / k;
  for (int i = k; i < MaximumDepth; ++i)
  {
    gram(i, i) = padding;
  }
  // Pseudo-inverse on the eigenvectors: consecutive solutions of a steady
  // state are nearly parallel, and their differences carry no information
  // above rounding.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(gram);
  const Eigen::Vector4d values = eigen.eigenvalues();
  const double floor = 1e-12 * std::max(0.0, values.maxCoeff());
  Eigen::Vector4d weights = Eigen::Vector4d::Zero();
  for (int i = 0; i < MaximumDepth; ++i)
  {
    if (values(i) > floor)
    {
      weights += (eigen.eigenvectors().col(i).dot(load) / values(i)) * eigen.eigenvectors().col(i);
    }
  }
  if (!weights.allFinite() || eigen.info() != Eigen::Success)
  {
    weights = Eigen::Vector4d::UnitX();
  }
  x = weights(0) * Solutions[0];
  product = weights(0) * Products[0];
  for (int i = 1; i < k; ++i)
  {
    x += weights(i) * Solutions[i];
    product += weights(i) * Products[i];
  }
}

} // namespace thintissue
