// The first guess of an implicit step's iterative solve from the solutions
// of the last few steps: their combination closest to the new solution in
// the energy norm of the new matrix (a Galerkin projection onto their span).
//
// Over a transient (a sudden load, a grasp, a cut opening) the step's
// solution changes smoothly from step to step, so a combination of the
// last solutions predicts it better than the last one alone, and conjugate
// gradients start nearer. Since CG minimizes the same energy, the guess is
// never worse than the last solution in that norm; the solve's result and
// tolerance are unchanged. It costs one product with the matrix per
// solution, against one for the last solution alone, so the solver uses it
// only after a solve that needed several iterations
// (CorotationalHexFemSettings::warmStartIterations).
//
// Measured with callgrind (stepping thread; the fem bench's sudden load,
// stale factor; depth 1 / depth 3 always / depth 3 after 3 iterations):
// - 1,000-hexahedra block, 200 steps: 3.66 / 2.33 / 3.04 iterations a
//   step, 5.67 / 4.98 / 5.39 G instructions; 600 steps 12.52 / 12.56 /
//   12.23 G;
// - 250-hexahedra block, 200 steps: 1.31 / 1.18 / 1.24 G; 600 steps
//   2.98 / 3.06 / 2.91 G;
// - the simulator's punch replay (504 unknowns, contacts; 4,150 steps):
//   9.84 / 10.24 / 9.82 G;
// - 10,000-hexahedra block, multigrid, 12 steps: 19.1 -> 17.3 iterations a
//   step (wall time within the noise).
#ifndef SolutionHistory_h
#define SolutionHistory_h

#include "ThinTissueSolverModule.h"

#include <Eigen/Core>

#include <array>
#include <functional>

namespace thintissue
{

class THINTISSUESOLVER_EXPORT SolutionHistory
{
public:
  /// Most solutions a history keeps.
  static constexpr int MaximumDepth = 4;
  using Product = std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>;

  /// Keeps the last `depth` solutions (1 <= depth <= MaximumDepth; 1 is the
  /// last solution alone).
  void setDepth(int depth);
  int depth() const { return Depth; }

  /// The newest solution; older ones move down, the oldest is dropped.
  /// Allocates only when the size changes.
  void push(const Eigen::VectorXd& solution);
  /// Forgets every solution older than the newest (a topology change:
  /// their numbering is gone); the newest may be replaced with set().
  void keepNewestOnly();
  /// The newest solution (zero-size before the first push).
  const Eigen::VectorXd& newest() const { return Solutions[0]; }
  Eigen::VectorXd& newest() { return Solutions[0]; }
  /// Solutions kept that have `size` entries, newest first, up to the depth.
  int usable(Eigen::Index size) const;

  /// x = the combination of the newest `depth` usable solutions minimizing
  /// 1/2 x^T A x - b^T x, and product = A x, with `multiply` giving A v
  /// (symmetric positive definite A). No usable solution: x = 0. Directions
  /// that are (nearly) dependent on the others get no weight.
  void firstGuess(const Product& multiply,
    const Eigen::VectorXd& rhs,
    Eigen::VectorXd& x,
    Eigen::VectorXd& product,
    int depth = MaximumDepth);

private:
  int Depth = 1;
  int Count = 0;
  std::array<Eigen::VectorXd, MaximumDepth> Solutions;
  std::array<Eigen::VectorXd, MaximumDepth> Products;
};

} // namespace thintissue

#endif
