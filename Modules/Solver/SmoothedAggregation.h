// Smoothed-aggregation algebraic multigrid (Vanek, Mandel and Brezina) for
// the co-rotational elasticity system of CorotationalHexFem (issue 20, item
// 4): a preconditioner for conjugate gradients on meshes whose factor is too
// big or too slow to refresh.
//
// Setup, per level: nodes (blocks of unknowns: 3 per mesh node on the
// finest level, up to 6 per aggregate below) are grouped into aggregates on
// the graph of strongly coupled blocks; the near-null space (the 6 rigid
// motions of the mesh nodes, carried down as the R factors) is
// orthonormalized per aggregate (the tentative prolongator T, by QR); T is
// smoothed by one damped block-Jacobi step, P = (I - w D^-1 A) T with
// w = 4 / (3 lambda_max(D^-1 A)); the coarse matrix is P^T A P. The coarsest
// level is factorized (sparse Cholesky).
//
// Apply: one V-cycle from a zero guess with the same Chebyshev polynomial in
// D^-1 A (D the diagonal blocks) before and after the coarse correction, so
// that the preconditioner is symmetric positive definite (the smoother
// converges on [0, lambda_max]) and conjugate gradients can use it. No
// allocation per apply once set up.
#ifndef SmoothedAggregation_h
#define SmoothedAggregation_h

#include "ThinTissueSolverModule.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>
#include <string>
#include <vector>

namespace thintissue
{

struct SmoothedAggregationSettings
{
  /// Levels are added until a level has at most this many unknowns; that
  /// one is factorized. At least 1. Measured on the 10,000-hexahedra block
  /// (`ThinTissueBench --suite fem`, CPU per step, 2 cores under load):
  /// 500 (three levels) 384 ms, 19 iterations, against 430 ms with 2,000
  /// (two levels, a bigger coarse factor to solve per V-cycle), 18
  /// iterations with 6,000.
  int coarsestUnknowns = 500;
  /// At most this many levels (the finest included). At least 1.
  int maximumLevels = 10;
  /// Degree of the Chebyshev smoother before and after each coarse
  /// correction (level matrix products per smoothing). At least 1.
  /// Measured on the 10,000 block (CPU per step, noisy machine): degree 1
  /// 350-380 ms at 30 iterations, 2 384-430 ms at 19, 3 502 ms at 18;
  /// 2 keeps the iterations (and the margin to a rebuild) lower.
  int smootherDegree = 2;
  /// Blocks i, j are coupled strongly (aggregated together) when
  /// |A_ij|_F >= threshold sqrt(|A_ii|_F |A_jj|_F). In [0, 1).
  double strengthThreshold = 0.0;
};

/// Throws InvalidInputError on settings out of their ranges.
THINTISSUESOLVER_EXPORT void checkSmoothedAggregationSettings(
  const SmoothedAggregationSettings& settings);

class THINTISSUESOLVER_EXPORT SmoothedAggregation
{
public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  using Coordinates = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

  explicit SmoothedAggregation(const SmoothedAggregationSettings& settings = {});
  ~SmoothedAggregation();
  SmoothedAggregation(SmoothedAggregation&&) noexcept;
  SmoothedAggregation& operator=(SmoothedAggregation&&) noexcept;
  SmoothedAggregation(const SmoothedAggregation&) = delete;
  SmoothedAggregation& operator=(const SmoothedAggregation&) = delete;

  /// Builds the hierarchy of `upper` (the upper triangle of a symmetric
  /// positive definite matrix, 3 unknowns per node in node order) with the
  /// nodes at `nodes` (one row per node: the rigid motions). False, with
  /// `message`, if a level is not positive definite.
  bool build(const SparseMatrix& upper, const Coordinates& nodes, std::string& message);
  bool ready() const;
  /// z = M^-1 r: one V-cycle from zero. r has the finest level's size.
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z);

  int levelCount() const;
  /// Unknowns of a level (0 the finest).
  Eigen::Index levelUnknowns(int level) const;
  /// Stored entries of all level matrices over those of the finest.
  double operatorComplexity() const;
  /// Whether the finest level's products read its 3x3 node blocks in
  /// single precision (a matrix of whole node blocks, as the FEM's is);
  /// else its double rows.
  bool finestLevelInNodeBlocks() const;

private:
  struct Level;
  struct Hierarchy;
  SmoothedAggregationSettings Settings;
  std::unique_ptr<Hierarchy> Levels;
};

} // namespace thintissue

#endif
