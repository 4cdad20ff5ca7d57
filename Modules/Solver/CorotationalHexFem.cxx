#include "CorotationalHexFem.h"

#include "BlockSymmetricProduct.h"

#include "LinearAlgebraLibrary.h"
#include "SolutionHistory.h"
#include "ThinTissueError.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Geometry>
#include <Eigen/Sparse>

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#endif

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <thread>

namespace thintissue
{

namespace
{
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

void checkSettings(const CorotationalHexFemSettings& s)
{
  std::ostringstream problem;
  if (!(s.timeStep > 0.0) || !std::isfinite(s.timeStep))
  {
    problem << "time step must be positive (got " << s.timeStep << ")";
  }
  else if (!(s.rayleighMass >= 0.0) || !(s.rayleighStiffness >= 0.0) ||
           !std::isfinite(s.rayleighMass) || !std::isfinite(s.rayleighStiffness))
  {
    problem << "Rayleigh damping coefficients must be finite and not negative (got "
            << s.rayleighMass << ", " << s.rayleighStiffness << ")";
  }
  else if (!s.gravity.allFinite())
  {
    problem << "gravity must be finite";
  }
  else if (!(s.conjugateGradientTolerance > 0.0) || s.conjugateGradientMaxIterations < 1)
  {
    problem << "conjugate gradient tolerance and iteration limit must be positive";
  }
  else if (s.refactorizationIterations < 0 || s.staleFactorIterationBudget < 0)
  {
    problem << "refactorization iterations and stale-factor iteration budget must not be "
               "negative (got "
            << s.refactorizationIterations << ", " << s.staleFactorIterationBudget << ")";
  }
  else if (s.supernodalThreshold < 0 || s.backgroundRefactorizationThreshold < 0)
  {
    problem << "supernodal and background-refactorization thresholds must not be negative (got "
            << s.supernodalThreshold << ", " << s.backgroundRefactorizationThreshold << ")";
  }
  else if (s.backgroundRefactorizationLag < 1 || s.staleFactorIterationCap < 1)
  {
    problem << "background-refactorization lag and stale-factor iteration cap must be at least 1 "
               "(got "
            << s.backgroundRefactorizationLag << ", " << s.staleFactorIterationCap << ")";
  }
  else if (s.assemblyThreads < 0)
  {
    problem << "assembly threads must not be negative (got " << s.assemblyThreads << ")";
  }
  else if (s.multigridRebuildIterations < 1)
  {
    problem << "multigrid rebuild iterations must be at least 1 (got "
            << s.multigridRebuildIterations << ")";
  }
  else if (s.warmStartSolutions < 1 || s.warmStartSolutions > SolutionHistory::MaximumDepth ||
           s.warmStartIterations < 0)
  {
    problem << "warm-start solutions must be between 1 and " << SolutionHistory::MaximumDepth
            << " and warm-start iterations not negative (got " << s.warmStartSolutions << ", "
            << s.warmStartIterations << ")";
  }
  if (problem.tellp() != 0)
  {
    throw InvalidInputError("co-rotational FEM settings: " + problem.str());
  }
  checkSmoothedAggregationSettings(s.multigrid);
}

/// Eigen's CHOLMOD wrapper with a solve that reuses its workspace:
/// cholmod_solve2 keeps the solution X and the workspaces Y and E between
/// calls, where Eigen's solve allocates (and frees) a result per call -- a
/// stale-factor step solves two to four times.
class ReusableCholmodDecomposition : public Eigen::CholmodDecomposition<SparseMatrix, Eigen::Upper>
{
public:
  ReusableCholmodDecomposition() = default;
  ReusableCholmodDecomposition(const ReusableCholmodDecomposition&) = delete;
  ReusableCholmodDecomposition& operator=(const ReusableCholmodDecomposition&) = delete;
  ~ReusableCholmodDecomposition()
  {
    // Freed through the common they were allocated with, before Eigen's
    // destructor finishes it.
    cholmod_free_dense(&Solution, &cholmod());
    cholmod_free_dense(&Work, &cholmod());
    cholmod_free_dense(&SupernodalWork, &cholmod());
  }
  /// solution = A^-1 right with the present factor; false if CHOLMOD failed.
  bool solveInto(const Eigen::VectorXd& right, Eigen::VectorXd& solution)
  {
    if (SolveSupernodesHere && isSupernodalLLt())
    {
      solveSupernodal(right, solution);
      return true;
    }
    cholmod_dense view{};
    view.nrow = view.nzmax = view.d = static_cast<std::size_t>(right.size());
    view.ncol = 1;
    view.x = const_cast<double*>(right.data()); // read only: B is input to cholmod_solve2
    view.xtype = CHOLMOD_REAL;
    view.dtype = CHOLMOD_DOUBLE;
    if (!cholmod_solve2(CHOLMOD_A,
          m_cholmodFactor,
          &view,
          nullptr,
          &Solution,
          nullptr,
          &Work,
          &SupernodalWork,
          &cholmod()))
    {
      return false;
    }
    solution =
      Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(Solution->x), right.size());
    return true;
  }

  /// After each analysis: whether solveInto solves the supernodes itself.
  /// Where they are short (under SupernodeHeightLimit entries per column
  /// on average, the rows below included), cholmod_solve2's BLAS call per
  /// supernode and solve (dtrsv, dgemv) costs more than its arithmetic and
  /// our loops win; on taller ones OpenBLAS's kernels do. Callgrind
  /// instructions of whole replays (own against CHOLMOD's): punch
  /// (about 40 per column) 10.03 against 10.87 G, sheet cutting (about 60)
  /// 5.26 against 5.65 G, shaver 3.61 against 3.87 G; stale-factor blocks
  /// over 60 steps: 125 hexahedra (110) 253 against 249 M, 250 (151) 628
  /// against 580 M, 750 (248) 2.37 against 1.95 G.
  void chooseSolve()
  {
    SolveSupernodesHere = false;
    // (The analysis leaves a symbolic factor: its values come later.)
    const cholmod_factor* factor = m_cholmodFactor;
    if (factor == nullptr || !factor->is_super || factor->itype != CHOLMOD_INT || factor->n == 0)
      return;
    std::size_t entries = 0;
    for (std::size_t k = 0; k < factor->nsuper; ++k)
    {
      const Supernode node = supernode(*factor, k);
      entries += static_cast<std::size_t>(node.height) * static_cast<std::size_t>(node.columns);
    }
    SolveSupernodesHere = entries < SupernodeHeightLimit * factor->n;
  }

private:
  static constexpr std::size_t SupernodeHeightLimit = 100;
  bool isSupernodalLLt() const
  {
    const cholmod_factor* factor = m_cholmodFactor;
    return factor != nullptr && factor->is_super && factor->is_ll &&
           factor->xtype == CHOLMOD_REAL && factor->dtype == CHOLMOD_DOUBLE &&
           factor->itype == CHOLMOD_INT;
  }
  /// A = P^T L L^T P solved over the supernodal factor's own arrays (see
  /// chooseSolve for when).
  void solveSupernodal(const Eigen::VectorXd& right, Eigen::VectorXd& solution)
  {
    const cholmod_factor& factor = *m_cholmodFactor;
    const int n = static_cast<int>(factor.n);
    const int* permutation = static_cast<const int*>(factor.Perm);
    Permuted.resize(n);
    double* y = Permuted.data();
    for (int k = 0; k < n; ++k)
      y[k] = right[permutation[k]];
    forwardSupernodal(factor, y);
    backwardSupernodal(factor, y);
    solution.resize(n);
    for (int k = 0; k < n; ++k)
      solution[permutation[k]] = y[k];
  }
  /// Supernode k of the factor: its first column, its dense block (column
  /// major: its own columns' rows on top, then the rows below it) and
  /// those rows below.
  struct Supernode
  {
    int first = 0;
    int columns = 0;
    int height = 0;
    const int* rows = nullptr; ///< all `height` rows; the first `columns` are first, first + 1, ...
    const double* block = nullptr;
  };
  static Supernode supernode(const cholmod_factor& factor, std::size_t k)
  {
    const int* super = static_cast<const int*>(factor.super);
    const int* rowStart = static_cast<const int*>(factor.pi);
    const int* valueStart = static_cast<const int*>(factor.px);
    Supernode node;
    node.first = super[k];
    node.columns = super[k + 1] - node.first;
    node.height = rowStart[k + 1] - rowStart[k];
    node.rows = static_cast<const int*>(factor.s) + rowStart[k];
    node.block = static_cast<const double*>(factor.x) + valueStart[k];
    return node;
  }
  using BlockMap = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
  /// Room for a supernode's rows below it (grown, never shrunk: no
  /// allocation per supernode).
  Eigen::Map<Eigen::VectorXd> belowOf(int rows)
  {
    if (Below.size() < rows)
      Below.resize(rows);
    return Eigen::Map<Eigen::VectorXd>(Below.data(), rows);
  }
  /// y = L^-1 y: each supernode's triangle solved, then its rows below
  /// updated through a gathered product (Below).
  void forwardSupernodal(const cholmod_factor& factor, double* y)
  {
    for (std::size_t k = 0; k < factor.nsuper; ++k)
    {
      const Supernode node = supernode(factor, k);
      const BlockMap block(
        node.block, node.height, node.columns, Eigen::OuterStride<>(node.height));
      Eigen::Map<Eigen::VectorXd> top(y + node.first, node.columns);
      // The triangle by columns (a few unknowns: Eigen's blocked solver
      // allocates and costs more than the arithmetic here).
      for (int j = 0; j < node.columns; ++j)
      {
        const double* column = node.block + static_cast<std::ptrdiff_t>(j) * node.height;
        const double yj = (top[j] /= column[j]);
        for (int i = j + 1; i < node.columns; ++i)
          top[i] -= column[i] * yj;
      }
      const int below = node.height - node.columns;
      if (below == 0)
        continue;
      Eigen::Map<Eigen::VectorXd> gathered = belowOf(below);
      gathered.noalias() = block.bottomRows(below) * top;
      for (int i = 0; i < below; ++i)
        y[node.rows[node.columns + i]] -= gathered[i];
    }
  }
  /// y = L^-T y, the supernodes in reverse.
  void backwardSupernodal(const cholmod_factor& factor, double* y)
  {
    for (std::size_t k = factor.nsuper; k-- > 0;)
    {
      const Supernode node = supernode(factor, k);
      const BlockMap block(
        node.block, node.height, node.columns, Eigen::OuterStride<>(node.height));
      Eigen::Map<Eigen::VectorXd> top(y + node.first, node.columns);
      const int below = node.height - node.columns;
      if (below > 0)
      {
        Eigen::Map<Eigen::VectorXd> gathered = belowOf(below);
        for (int i = 0; i < below; ++i)
          gathered[i] = y[node.rows[node.columns + i]];
        top.noalias() -= block.bottomRows(below).transpose() * gathered;
      }
      for (int j = node.columns; j-- > 0;)
      {
        const int after = node.columns - j - 1;
        const Eigen::Map<const Eigen::VectorXd> column(
          node.block + static_cast<std::ptrdiff_t>(j) * node.height, node.columns);
        top[j] = (top[j] - column.tail(after).dot(top.tail(after))) / column[j];
      }
    }
  }

  cholmod_dense* Solution = nullptr;
  cholmod_dense* Work = nullptr;
  cholmod_dense* SupernodalWork = nullptr;
  bool SolveSupernodesHere = false;
  Eigen::VectorXd Permuted;
  Eigen::VectorXd Below; ///< a supernode's rows below it, gathered
};

/// A CHOLMOD factor of the system matrix. CHOLMOD keeps its workspace in
/// the object, so each thread that factorizes has its own.
class CholmodFactor
{
public:
  /// Factorizes `matrix` (upper triangle) of pattern `pattern` (a count of
  /// the patterns built), analysing it first if the factor was analysed for
  /// another, with the mode and ordering of `settings`; false if not
  /// positive definite.
  bool factorize(const SparseMatrix& matrix,
    long long pattern,
    const CorotationalHexFemSettings& settings)
  {
    const SerialOpenMpScope serial; // see SerialOpenMpScope: same bits, half the CPU
    if (AnalysedPattern != pattern)
    {
      useOneBlasThread();
      const bool supernodal = matrix.rows() >= settings.supernodalThreshold;
      Decomposition.setMode(supernodal ? Eigen::CholmodSupernodalLLt : Eigen::CholmodLDLt);
      cholmod_common& common = Decomposition.cholmod();
      FactorOrdering ordering = settings.factorOrdering;
      if (ordering == FactorOrdering::Automatic)
      {
        ordering = matrix.rows() >= AutomaticMetisLimit ? FactorOrdering::Metis
                                                        : FactorOrdering::MinimumDegree;
      }
      common.nmethods = ordering == FactorOrdering::CholmodDefault ? 0 : 1;
      common.method[0].ordering = orderingCode(ordering);
      common.postorder = 1;
      Decomposition.analyzePattern(matrix);
      Decomposition.chooseSolve();
      // CHOLMOD's analysis counts the factorization's flops and the
      // factor's entries; a solve pair takes about 4 flops an entry.
      SolvesPerFactorization = common.lnz > 0.0 ? common.fl / (4.0 * common.lnz) : 0.0;
      AnalysedPattern = pattern;
    }
    Decomposition.factorize(matrix);
    return Decomposition.info() == Eigen::Success;
  }
  /// A failed solve (CHOLMOD out of memory) gives NaN, which every caller
  /// refuses as a non-finite solution or residual.
  void solve(const Eigen::VectorXd& right, Eigen::VectorXd& solution)
  {
    if (!Decomposition.solveInto(right, solution))
    {
      solution.setConstant(right.size(), std::numeric_limits<double>::quiet_NaN());
    }
  }

  /// The factorization's flops over a solve's, from the last analysis (0
  /// before one): 18 at thesis sizes, 63 for the 1,000-hexahedra block,
  /// 120 for 4,500 hexahedra (they grow faster than the factor).
  double solvesPerFactorization() const { return SolvesPerFactorization; }

private:
  static int orderingCode(FactorOrdering ordering)
  {
    switch (ordering)
    {
      case FactorOrdering::Metis:
        return CHOLMOD_METIS;
      case FactorOrdering::NestedDissection:
        return CHOLMOD_NESDIS;
      default:
        return CHOLMOD_AMD;
    }
  }
  ReusableCholmodDecomposition Decomposition;
  long long AnalysedPattern = -1;
  double SolvesPerFactorization = 0.0;
};

/// A refactorization running on a worker thread (the stale factor refreshed
/// off the step): the matrix of the step that started it, the factor it
/// fills, and the step at which it is swapped in. The main thread touches
/// `matrix`, `factor` and `ok` only while no worker runs.
struct BackgroundRefactorization
{
  SparseMatrix matrix;
  std::unique_ptr<CholmodFactor> factor = std::make_unique<CholmodFactor>();
  /// The pattern and the step of `matrix`: a refresh of an older pattern
  /// than the system's (a cut came in between), or older than a factor made
  /// in a step since, is dropped when it lands, not waited for at once.
  long long pattern = -1;
  long long startStep = -1;
  /// The nodal rotations of `matrix`'s step (see LinearSystem::factorRotations).
  std::vector<Eigen::Matrix3d> rotations;
  std::thread worker;
  bool ok = false;
  /// Step index at which it lands; -1 when none runs.
  long long dueStep = -1;
  ~BackgroundRefactorization()
  {
    if (worker.joinable())
    {
      worker.join();
    }
  }
};

/// Entries of a matrix taken from the system matrix: built once with their
/// pattern and, per stored entry, the value index in the system it copies
/// (copyValuesInto refreshes them at the cost of the entries).
struct MappedEntries
{
  std::vector<Eigen::Triplet<double, int>> entries; // value: its index here
  std::vector<int> from;

  void add(int row, int column, int systemIndex)
  {
    entries.emplace_back(row, column, static_cast<double>(entries.size()));
    from.push_back(systemIndex);
  }
  /// Each (row, column) added once.
  void build(Eigen::Index rows,
    Eigen::Index columns,
    SparseMatrix& matrix,
    std::vector<int>& valueOf)
  {
    matrix.resize(rows, columns);
    matrix.setFromTriplets(entries.begin(), entries.end());
    valueOf.resize(entries.size());
    for (Eigen::Index k = 0; k < matrix.nonZeros(); ++k)
    {
      valueOf[k] = from[static_cast<std::size_t>(matrix.valuePtr()[k])];
    }
  }
};

void copyValuesInto(const SparseMatrix& system, const std::vector<int>& valueOf, SparseMatrix& into)
{
  double* values = into.valuePtr();
  for (std::size_t k = 0; k < valueOf.size(); ++k)
  {
    values[k] = system.valuePtr()[valueOf[k]];
  }
}
/// The blocks s R K_ab R^T of an element's rotated stiffness, K_ab the 3x3
/// block (a, b) of its rest stiffness, added into the system matrix: the
/// assembly's arithmetic and scatter. With AVX2 and FMA a block's columns
/// are four lanes wide (the fourth lane unused): 18 vector multiply-adds
/// a block against 54 scalar ones, and each column added to the matrix at
/// once, since a block's rows are consecutive in each of its columns
/// (buildPattern: nodes are free or fixed as a whole).
class RotatedStiffness
{
public:
  RotatedStiffness(double scale, const Eigen::Matrix3d& rotation)
  {
#if defined(__AVX2__) && defined(__FMA__)
    for (int k = 0; k < 3; ++k)
    {
      ScaledColumns[k] =
        _mm256_setr_pd(scale * rotation(0, k), scale * rotation(1, k), scale * rotation(2, k), 0.0);
      for (int j = 0; j < 3; ++j)
        Entries[j][k] = _mm256_set1_pd(rotation(j, k));
    }
#else
    ScaledRotation = scale * rotation;
    RotationTransposed = rotation.transpose();
#endif
  }
  /// values += s R K_ab R^T at the block's places `offsets` (9, row-major:
  /// all nine above the diagonal, the upper six on it), for `stiffness`
  /// pointing at K_ab(0, 0) in a column-major 24 x 24 matrix.
  void addBlock(const double* stiffness, const int* offsets, double* values) const
  {
    const bool onDiagonal = offsets[3] < 0; // entry (1, 0) has no place
#if defined(__AVX2__) && defined(__FMA__)
    // left = s R K_ab, column j: the sum over k of (s R)_k K_ab(k, j).
    __m256d left[3];
    for (int j = 0; j < 3; ++j)
    {
      const double* column = stiffness + 24 * j;
      left[j] = _mm256_fmadd_pd(ScaledColumns[2],
        _mm256_set1_pd(column[2]),
        _mm256_fmadd_pd(ScaledColumns[1],
          _mm256_set1_pd(column[1]),
          _mm256_mul_pd(ScaledColumns[0], _mm256_set1_pd(column[0]))));
    }
    // Column j of left R^T (the sum over k of left_k R(j, k)), added at
    // its rows' places: entries (0, j) .. (2, j) follow each other, (0, j)
    // .. (j, j) on the diagonal.
    for (int j = 0; j < 3; ++j)
    {
      const __m256d column = _mm256_fmadd_pd(left[2],
        Entries[j][2],
        _mm256_fmadd_pd(left[1], Entries[j][1], _mm256_mul_pd(left[0], Entries[j][0])));
      const __m256i lanes = onDiagonal ? RowsOnDiagonal[j] : RowsOnDiagonal[2];
      double* at = values + offsets[j];
      _mm256_maskstore_pd(at, lanes, _mm256_add_pd(_mm256_maskload_pd(at, lanes), column));
    }
#else
    const Eigen::Map<const Eigen::Matrix3d, 0, Eigen::OuterStride<24>> k(stiffness);
    const Eigen::Matrix3d block = ScaledRotation * k * RotationTransposed;
    for (int e = 0; e < 9; ++e)
    {
      if (!onDiagonal || e / 3 <= e % 3)
        values[offsets[e]] += block(e / 3, e % 3);
    }
#endif
  }

private:
#if defined(__AVX2__) && defined(__FMA__)
  __m256d ScaledColumns[3]; ///< the columns of s R
  __m256d Entries[3][3];    ///< R(j, k), broadcast
  /// Lanes of a column's rows 0 .. j.
  const __m256i RowsOnDiagonal[3] = { _mm256_setr_epi64x(-1, 0, 0, 0),
    _mm256_setr_epi64x(-1, -1, 0, 0),
    _mm256_setr_epi64x(-1, -1, -1, 0) };
#else
  Eigen::Matrix3d ScaledRotation;
  Eigen::Matrix3d RotationTransposed;
#endif
};
} // namespace

/// The free-DOF system: numbering, upper-triangular pattern, where each
/// element block lands in it, the solvers and work buffers (no allocation
/// per step once the topology is set).
struct CorotationalHexFem::LinearSystem
{
  std::vector<int> dofOfNode; // first DOF of a simulated node, else -1
  int dofCount = 0;
  SparseMatrix matrix; // upper triangle
  /// y = A x by its 3x3 node blocks (analysed with each pattern).
  BlockSymmetricProduct blockProduct;
  /// Per element, block (a, b) entry (i, j) -> value index, or -1.
  std::vector<std::array<int, 576>> elementOffsets;
  std::vector<int> diagonalOffsets;
  Eigen::VectorXd rhs;
  Eigen::VectorXd solution;
  /// The last steps' solutions (the newest in node terms across topology
  /// changes): the first guess of the next solve.
  SolutionHistory history;
  /// Iterations of the last conjugate-gradient solve.
  int lastSolveIterations = 0;
  std::vector<Vector3> forces;
  std::unique_ptr<CholmodFactor> factor = std::make_unique<CholmodFactor>();
  /// A factor exists for the present pattern (for the Cholmod kind: of the
  /// current matrix; for the stale-factor kind: of an earlier step's).
  bool factorValid = false;
  /// The step whose matrix `factor` is of.
  long long factorStep = -1;
  /// Per free node (DOF / 3), the rotation of the material around it: the
  /// normalized quaternion mean of its hexahedra's rotations, this step's
  /// and that of the factor's step. Q = R R_f^T takes the factor's matrix
  /// to nearly this step's (A ~ Q A_f Q^T), so the stale factor follows the
  /// tissue's rotations (see CorotationalHexFemSettings::rotateStaleFactor).
  std::vector<Eigen::Matrix3d> nodeRotations;
  std::vector<Eigen::Matrix3d> factorRotations;
  std::vector<Eigen::Matrix3d> relativeRotations;
  std::vector<Eigen::Vector4d> nodeQuaternionSums; // scratch of updateNodeRotations
  bool rotatesFactor = false;                      // this step applies relativeRotations
  Eigen::VectorXd rotatedRight, rotatedSolution;
  /// Patterns built so far: which one a factor was analysed for.
  long long pattern = 0;
  int factorizations = 0;
  int synchronousFactorizations = 0;
  BackgroundRefactorization refresh;
  /// The lag the last background refactorization was given (0: none yet).
  int refreshLag = 0;
  std::function<void()> backgroundHook;
  /// Steps begun so far: the clock of the deterministic background refresh.
  long long stepIndex = 0;
  /// Iterations beyond the first spent with the present factor: the price
  /// of its staleness, paid down by refactorizing (see Settings).
  int excessIterations = 0;
  Eigen::VectorXd residual, direction, preconditioned, product;
  /// Per free node, the value indices of its 3x3 diagonal block's upper
  /// triangle (00 01 02 11 12 22), and the blocks' inverses: the nodal
  /// block-Jacobi preconditioner of the conjugate gradients.
  std::vector<std::array<int, 6>> nodalBlockOffsets;
  std::vector<Eigen::Matrix3d> nodalBlockInverses;
  bool nodalBlocksInverted = false; // of the current matrix
  /// The active elements by colour (no two of a colour share a node) and
  /// where each colour starts; the last colour, if any beyond
  /// ParallelColourLimit, is assembled serially.
  std::vector<int> colouredElements;
  std::vector<int> colourStarts;
  /// The threads of the assembly (Settings.assemblyThreads).
  std::unique_ptr<tbb::task_arena> arena;
  int arenaThreads = -1;
  /// MultigridConjugateGradient's hierarchy, of the matrix of step
  /// factorStep (its rotations in factorRotations, like a stale factor).
  SmoothedAggregation multigrid;
  bool multigridValid = false;
  int multigridBuilds = 0;

  // --- The factor across topology changes (bridgeTopologyChanges) ---------
  /// By node: the node it was copied from (addNodeCopy), else -1.
  std::vector<int> copySource;
  /// By node: its first DOF in the numbering the factor was made for, and
  /// that numbering's DOF count.
  std::vector<int> factorDofOfNode;
  int factorDofCount = 0;
  long long factorPattern = -1;
  /// Nodes of the hexahedra changed since the factor was made.
  std::vector<int> touchedNodes;
  /// The present factor is of an earlier pattern and preconditions through
  /// the bridge until the new pattern's factor lands.
  bool bridging = false;
  /// Per free node: the first DOF of the node (or of the node it was copied
  /// from) in the factor's numbering, else -1.
  std::vector<int> bridgeDof;
  /// The touched free nodes' DOFs, increasing, and their system block:
  /// per entry of its upper triangle, the value index in `matrix`.
  std::vector<int> touchedDofs;
  SparseMatrix touchedMatrix;
  std::vector<int> touchedValueOf;
  /// The system's whole columns of the touched DOFs (both triangles), and
  /// per entry its value index in `matrix`: a vector held on the touched
  /// DOFs is multiplied by the system at the cost of those columns.
  SparseMatrix touchedColumns;
  std::vector<int> touchedColumnValueOf;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper> touchedSolver;
  long long touchedFactorStep = -1;
  Eigen::VectorXd glued, gluedSolution, touchedRight, touchedSolution, touchedFirst, bridgeResidual;
};

CorotationalHexFem::CorotationalHexFem(const HexahedralMesh& mesh,
  const LinearMaterial& material,
  const CorotationalHexFemSettings& settings)
  : RestPositions(mesh.nodes)
  , Positions(mesh.nodes)
  , Velocities(mesh.nodes.size(), Vector3::Zero())
  , ExternalForces(mesh.nodes.size(), Vector3::Zero())
  , Fixed(mesh.nodes.size(), 0)
  , Settings(settings)
  , System(std::make_unique<LinearSystem>())
{
  mesh.checkConsistency();
  checkSettings(settings);
  System->multigrid = SmoothedAggregation(settings.multigrid);
  System->history.setDepth(settings.warmStartSolutions);
  checkMaterial(material, "co-rotational FEM of '" + mesh.name + "'");
  if (!mesh.fixedNodes.empty())
  {
    Fixed = mesh.fixedNodes;
  }
  Elements.reserve(mesh.hexahedronCount());
  for (std::size_t h = 0; h < mesh.hexahedronCount(); ++h)
  {
    Elements.push_back(makeElement(mesh.hexahedra[h], material, h));
  }
  updateNodeMasses();
}

CorotationalHexFem::~CorotationalHexFem() = default;
CorotationalHexFem::CorotationalHexFem(CorotationalHexFem&&) noexcept = default;
CorotationalHexFem& CorotationalHexFem::operator=(CorotationalHexFem&&) noexcept = default;

CorotationalHexFem::Element CorotationalHexFem::makeElement(const Hexahedron& nodes,
  const LinearMaterial& material,
  std::size_t index) const
{
  HexahedronCorners corners;
  for (int k = 0; k < 8; ++k)
  {
    if (nodes[k] < 0 || static_cast<std::size_t>(nodes[k]) >= RestPositions.size())
    {
      throw InvalidInputError("co-rotational FEM: hexahedron " + std::to_string(index) +
                              " refers to node " + std::to_string(nodes[k]) + ", out of range");
    }
    corners[k] = RestPositions[nodes[k]];
  }
  const std::string context = "co-rotational FEM, hexahedron " + std::to_string(index);
  checkMaterial(material, context);
  Element element;
  element.nodes = nodes;
  element.material = material;
  element.rest = computeHexahedronRestState(corners, material, context);
  return element;
}

void CorotationalHexFem::updateNodeMasses()
{
  NodeMasses.assign(RestPositions.size(), 0.0);
  for (const auto& element : Elements)
  {
    if (!element.active)
    {
      continue;
    }
    for (int a = 0; a < 8; ++a)
    {
      NodeMasses[element.nodes[a]] += element.material.density * element.rest.shapeIntegrals[a];
    }
  }
}

std::size_t CorotationalHexFem::activeHexahedronCount() const
{
  return static_cast<std::size_t>(
    std::count_if(Elements.begin(), Elements.end(), [](const Element& e) { return e.active; }));
}

void CorotationalHexFem::checkNode(std::size_t node, const char* what) const
{
  if (node >= Positions.size())
  {
    throw InvalidInputError(std::string("co-rotational FEM: ") + what + " of node " +
                            std::to_string(node) + ", but there are " +
                            std::to_string(Positions.size()) + " nodes");
  }
}

void CorotationalHexFem::setPositions(const std::vector<Vector3>& positions)
{
  if (positions.size() != Positions.size() ||
      !std::all_of(
        positions.begin(), positions.end(), [](const Vector3& p) { return p.allFinite(); }))
  {
    throw InvalidInputError("co-rotational FEM: positions must be finite, one per node");
  }
  Positions = positions;
  ElasticPartAssembled = false;
}

void CorotationalHexFem::setVelocities(const std::vector<Vector3>& velocities)
{
  if (velocities.size() != Velocities.size() ||
      !std::all_of(
        velocities.begin(), velocities.end(), [](const Vector3& v) { return v.allFinite(); }))
  {
    throw InvalidInputError("co-rotational FEM: velocities must be finite, one per node");
  }
  Velocities = velocities;
  ElasticPartAssembled = false;
}

double CorotationalHexFem::kineticEnergy() const
{
  double energy = 0.0;
  for (std::size_t n = 0; n < Velocities.size(); ++n)
  {
    energy += 0.5 * NodeMasses[n] * Velocities[n].squaredNorm();
  }
  return energy;
}

void CorotationalHexFem::setExternalForce(std::size_t node, const Vector3& force)
{
  checkNode(node, "external force");
  if (!force.allFinite())
  {
    throw InvalidInputError(
      "co-rotational FEM: external force on node " + std::to_string(node) + " is not finite");
  }
  ExternalForces[node] = force;
}

void CorotationalHexFem::clearExternalForces()
{
  std::fill(ExternalForces.begin(), ExternalForces.end(), Vector3::Zero());
}

void CorotationalHexFem::setFixed(std::size_t node, bool fixed)
{
  checkNode(node, "fixing");
  if ((Fixed[node] != 0) != fixed)
  {
    Fixed[node] = fixed ? 1 : 0;
    TopologyChanged = true;
    System->touchedNodes.push_back(static_cast<int>(node));
  }
}

void CorotationalHexFem::setSettings(const CorotationalHexFemSettings& settings)
{
  checkSettings(settings);
  if (settings.supernodalThreshold != Settings.supernodalThreshold ||
      settings.factorOrdering != Settings.factorOrdering)
  {
    TopologyChanged = true; // the factor's analysis depends on them
  }
  const SmoothedAggregationSettings &next = settings.multigrid, &now = Settings.multigrid;
  if (next.coarsestUnknowns != now.coarsestUnknowns || next.maximumLevels != now.maximumLevels ||
      next.smootherDegree != now.smootherDegree ||
      next.strengthThreshold != now.strengthThreshold || settings.solver != Settings.solver)
  {
    System->multigridValid = false;
    System->multigrid = SmoothedAggregation(settings.multigrid);
  }
  System->history.setDepth(settings.warmStartSolutions);
  Settings = settings;
  ElasticPartAssembled = false;
}

void CorotationalHexFem::setMaterial(std::size_t hexahedron, const LinearMaterial& material)
{
  if (hexahedron >= Elements.size())
  {
    throw InvalidInputError("co-rotational FEM: no hexahedron " + std::to_string(hexahedron));
  }
  const bool active = Elements[hexahedron].active;
  Elements[hexahedron] = makeElement(Elements[hexahedron].nodes, material, hexahedron);
  Elements[hexahedron].active = active;
  updateNodeMasses();
  ElasticPartAssembled = false;
}

void CorotationalHexFem::reserve(std::size_t nodes, std::size_t hexahedra)
{
  RestPositions.reserve(nodes);
  Positions.reserve(nodes);
  Velocities.reserve(nodes);
  ExternalForces.reserve(nodes);
  Fixed.reserve(nodes);
  NodeMasses.reserve(nodes);
  Elements.reserve(hexahedra);
}

std::size_t CorotationalHexFem::addNode(const Vector3& rest,
  const Vector3& position,
  const Vector3& velocity)
{
  if (!rest.allFinite() || !position.allFinite() || !velocity.allFinite())
  {
    throw InvalidInputError("co-rotational FEM: a new node must have finite coordinates");
  }
  RestPositions.push_back(rest);
  Positions.push_back(position);
  Velocities.push_back(velocity);
  ExternalForces.push_back(Vector3::Zero());
  Fixed.push_back(0);
  NodeMasses.push_back(0.0);
  return Positions.size() - 1;
}

std::size_t CorotationalHexFem::addNodeCopy(std::size_t source)
{
  checkNode(source, "a copy");
  // Copied first: push_back may move the arrays the references point into.
  const Vector3 rest = RestPositions[source], position = Positions[source],
                velocity = Velocities[source];
  const std::size_t copy = addNode(rest, position, velocity);
  Fixed[copy] = Fixed[source];
  System->copySource.resize(Positions.size(), -1);
  System->copySource[copy] = static_cast<int>(source);
  return copy;
}

std::size_t CorotationalHexFem::addHexahedron(const Hexahedron& nodes,
  const LinearMaterial& material)
{
  Elements.push_back(makeElement(nodes, material, Elements.size()));
  for (int a = 0; a < 8; ++a)
  {
    NodeMasses[nodes[a]] += material.density * Elements.back().rest.shapeIntegrals[a];
  }
  noteTouchedNodes(nodes);
  TopologyChanged = true;
  return Elements.size() - 1;
}

void CorotationalHexFem::removeHexahedron(std::size_t h)
{
  if (h >= Elements.size())
  {
    throw InvalidInputError("co-rotational FEM: no hexahedron " + std::to_string(h));
  }
  if (!Elements[h].active)
  {
    return;
  }
  Elements[h].active = false;
  // Contacts on it have lost their carrier.
  for (std::size_t k = Contacts.size(); k-- > 0;)
  {
    if (Contacts[k].hexahedron == h)
    {
      Contacts.erase(Contacts.begin() + static_cast<std::ptrdiff_t>(k));
      ContactForces.erase(ContactForces.begin() + static_cast<std::ptrdiff_t>(k));
      ContactFrictionDamping.erase(ContactFrictionDamping.begin() + static_cast<std::ptrdiff_t>(k));
    }
  }
  for (int a = 0; a < 8; ++a)
  {
    NodeMasses[Elements[h].nodes[a]] -=
      Elements[h].material.density * Elements[h].rest.shapeIntegrals[a];
  }
  noteTouchedNodes(Elements[h].nodes);
  TopologyChanged = true;
}

void CorotationalHexFem::checkSameRestNodes(std::size_t h, const Hexahedron& nodes) const
{
  const Element& element = Elements[h];
  for (int a = 0; a < 8; ++a)
  {
    checkNode(static_cast<std::size_t>(std::max(nodes[a], 0)), "replacing a corner");
    if (nodes[a] < 0 || (RestPositions[nodes[a]] - RestPositions[element.nodes[a]]).norm() >
                          1e-9 * (1.0 + RestPositions[element.nodes[a]].norm()))
    {
      throw InvalidInputError(
        "co-rotational FEM: hexahedron " + std::to_string(h) +
        ": a replacement node must have the rest position of the node it replaces");
    }
  }
}

std::size_t CorotationalHexFem::duplicateHexahedron(std::size_t h, const Hexahedron& nodes)
{
  if (h >= Elements.size())
  {
    throw InvalidInputError("co-rotational FEM: no hexahedron " + std::to_string(h));
  }
  checkSameRestNodes(h, nodes);
  Element copy = Elements[h];
  copy.nodes = nodes;
  copy.active = true;
  for (int a = 0; a < 8; ++a)
  {
    NodeMasses[nodes[a]] += copy.material.density * copy.rest.shapeIntegrals[a];
  }
  noteTouchedNodes(Elements[h].nodes);
  noteTouchedNodes(nodes);
  Elements.push_back(std::move(copy));
  TopologyChanged = true;
  return Elements.size() - 1;
}

void CorotationalHexFem::replaceHexahedronNodes(std::size_t h, const Hexahedron& nodes)
{
  if (h >= Elements.size())
  {
    throw InvalidInputError("co-rotational FEM: no hexahedron " + std::to_string(h));
  }
  checkSameRestNodes(h, nodes);
  Element& element = Elements[h];
  if (element.active)
  {
    for (int a = 0; a < 8; ++a)
    {
      const double mass = element.material.density * element.rest.shapeIntegrals[a];
      NodeMasses[element.nodes[a]] -= mass;
      NodeMasses[nodes[a]] += mass;
    }
  }
  noteTouchedNodes(element.nodes);
  noteTouchedNodes(nodes);
  element.nodes = nodes;
  TopologyChanged = true;
}

void CorotationalHexFem::noteTouchedNodes(const Hexahedron& nodes)
{
  System->touchedNodes.insert(System->touchedNodes.end(), nodes.begin(), nodes.end());
}

std::vector<std::vector<int>> CorotationalHexFem::blockRowsAbove() const
{
  // Per simulated node (DOF / 3), the simulated nodes sharing an active
  // hexahedron with it whose DOFs are not higher, itself last: the block
  // rows of its columns in the upper triangle.
  const LinearSystem& s = *System;
  std::vector<std::vector<int>> above(s.dofCount / 3);
  for (const auto& element : Elements)
  {
    if (!element.active)
    {
      continue;
    }
    for (int a : element.nodes)
    {
      for (int b : element.nodes)
      {
        const int ra = s.dofOfNode[a];
        const int cb = s.dofOfNode[b];
        if (ra >= 0 && cb >= 0 && ra <= cb)
        {
          above[cb / 3].push_back(ra / 3);
        }
      }
    }
  }
  for (auto& rows : above)
  {
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  }
  return above;
}

void CorotationalHexFem::buildPattern()
{
  // The upper triangle's CSC pattern straight from the node adjacency (no
  // triplets): column 3b + j holds, for each block row a of `above[b]`,
  // rows 3a .. 3a + 2 (of the diagonal block only up to 3b + j), so entry
  // (3a + i, 3b + j) sits at column start + 3 rank(a) + i.
  LinearSystem& s = *System;
  const std::vector<std::vector<int>> above = blockRowsAbove();
  s.matrix.resize(s.dofCount, s.dofCount);
  std::vector<int> starts(s.dofCount + 1, 0);
  for (int d = 0; d < s.dofCount; ++d)
  {
    starts[d + 1] = starts[d] + 3 * static_cast<int>(above[d / 3].size() - 1) + d % 3 + 1;
  }
  s.matrix.resizeNonZeros(starts.back());
  std::copy(starts.begin(), starts.end(), s.matrix.outerIndexPtr());
  int* rows = s.matrix.innerIndexPtr();
  for (int d = 0; d < s.dofCount; ++d)
  {
    int k = starts[d];
    for (int a : above[d / 3])
    {
      for (int i = 0; i < 3 && 3 * a + i <= d; ++i)
      {
        rows[k++] = 3 * a + i;
      }
    }
  }
  std::fill(s.matrix.valuePtr(), s.matrix.valuePtr() + starts.back(), 0.0);
  auto offsetOf = [&](int row, int column)
  {
    const std::vector<int>& blockRows = above[column / 3];
    const auto rank =
      std::lower_bound(blockRows.begin(), blockRows.end(), row / 3) - blockRows.begin();
    return starts[column] + 3 * static_cast<int>(rank) + row % 3;
  };
  s.diagonalOffsets.resize(s.dofCount);
  for (int d = 0; d < s.dofCount; ++d)
  {
    s.diagonalOffsets[d] = offsetOf(d, d);
  }
  s.nodalBlockOffsets.resize(s.dofCount / 3);
  s.nodalBlockInverses.resize(s.dofCount / 3);
  for (int node = 0; node < s.dofCount / 3; ++node)
  {
    const int d = 3 * node;
    s.nodalBlockOffsets[node] = { offsetOf(d, d),
      offsetOf(d, d + 1),
      offsetOf(d, d + 2),
      offsetOf(d + 1, d + 1),
      offsetOf(d + 1, d + 2),
      offsetOf(d + 2, d + 2) };
  }
  s.elementOffsets.resize(Elements.size());
  for (std::size_t e = 0; e < Elements.size(); ++e)
  {
    auto& offsets = s.elementOffsets[e];
    offsets.fill(-1);
    if (!Elements[e].active)
    {
      continue;
    }
    for (int a = 0; a < 8; ++a)
    {
      for (int b = 0; b < 8; ++b)
      {
        const int ra = s.dofOfNode[Elements[e].nodes[a]];
        const int cb = s.dofOfNode[Elements[e].nodes[b]];
        if (ra < 0 || cb < 0 || ra > cb)
        {
          continue;
        }
        // One search per block: its nine entries share the block row's
        // rank in the columns (offsetOf), which was 75 % of a pattern build.
        const std::vector<int>& blockRows = above[cb / 3];
        const int rank = static_cast<int>(
          std::lower_bound(blockRows.begin(), blockRows.end(), ra / 3) - blockRows.begin());
        for (int k = 0; k < 9; ++k)
        {
          if (ra + k / 3 <= cb + k % 3)
          {
            offsets[(a * 8 + b) * 9 + k] = starts[cb + k % 3] + 3 * rank + k / 3;
          }
        }
      }
    }
  }
}

void CorotationalHexFem::prepareSystem()
{
  LinearSystem& s = *System;
  if (!TopologyChanged)
  {
    return;
  }
  // The last solution in node terms, the warm start of the next solve.
  const std::vector<int> previousDofOfNode = std::move(s.dofOfNode);
  const Eigen::VectorXd previousSolution = std::move(s.history.newest());
  // Simulated nodes: free and used by an active hexahedron.
  std::vector<std::uint8_t> used(Positions.size(), 0);
  for (const auto& element : Elements)
  {
    if (element.active)
    {
      for (int node : element.nodes)
      {
        used[node] = 1;
      }
    }
  }
  s.dofOfNode.assign(Positions.size(), -1);
  s.dofCount = 0;
  for (std::size_t n = 0; n < Positions.size(); ++n)
  {
    if (used[n] && !Fixed[n])
    {
      s.dofOfNode[n] = s.dofCount;
      s.dofCount += 3;
    }
  }
  buildPattern();
  s.blockProduct.analyse(s.matrix);
  colourElements();
  s.rhs.resize(s.dofCount);
  s.solution.setZero(s.dofCount);
  s.history.keepNewestOnly(); // older solutions are of the old numbering
  Eigen::VectorXd& newest = s.history.newest();
  newest.setZero(s.dofCount);
  // A node copied since starts from what it was copied from.
  const auto previousDof = [&](int n)
  {
    while (n >= 0 && (n >= static_cast<int>(previousDofOfNode.size()) || previousDofOfNode[n] < 0))
    {
      n = n < static_cast<int>(s.copySource.size()) ? s.copySource[n] : -1;
    }
    return n >= 0 ? previousDofOfNode[n] : -1;
  };
  for (std::size_t n = 0; n < Positions.size(); ++n)
  {
    const int from = s.dofOfNode[n] >= 0 ? previousDof(static_cast<int>(n)) : -1;
    if (from >= 0)
    {
      newest.segment<3>(s.dofOfNode[n]) = previousSolution.segment<3>(from);
    }
  }
  s.forces.assign(Positions.size(), Vector3::Zero());
  // A refresh under way is left to finish and dropped when due (no wait in
  // this step); the factor is of another numbering, kept as the bridge's.
  const bool hadFactor = s.factorValid || s.bridging;
  ++s.pattern;
  s.factorValid = false;
  s.multigridValid = false;
  TopologyChanged = false;
  s.bridging = hadFactor && Settings.bridgeTopologyChanges && refreshesInBackground() &&
               s.dofCount <= BridgeUnknownLimit && !s.factorDofOfNode.empty();
  if (!s.bridging || !prepareBridge())
  {
    s.bridging = false;
    s.touchedNodes.clear(); // the next factor is of this pattern
  }
}

bool CorotationalHexFem::prepareBridge()
{
  LinearSystem& s = *System;
  const int freeNodes = s.dofCount / 3;
  s.bridgeDof.assign(static_cast<std::size_t>(freeNodes), -1);
  std::vector<char> touched(static_cast<std::size_t>(freeNodes), 0);
  for (std::size_t n = 0; n < Positions.size(); ++n)
  {
    const int dof = s.dofOfNode[n];
    if (dof < 0)
    {
      continue;
    }
    // The node itself in the factor's numbering, or what it was copied from.
    for (int m = static_cast<int>(n); m >= 0;)
    {
      if (m < static_cast<int>(s.factorDofOfNode.size()) && s.factorDofOfNode[m] >= 0)
      {
        s.bridgeDof[dof / 3] = s.factorDofOfNode[m];
        break;
      }
      m = m < static_cast<int>(s.copySource.size()) ? s.copySource[m] : -1;
    }
    touched[dof / 3] = s.bridgeDof[dof / 3] < 0;
  }
  for (int node : s.touchedNodes)
  {
    const int dof = s.dofOfNode[node];
    if (dof >= 0)
    {
      touched[dof / 3] = 1;
    }
  }
  // The touched nodes' block of the system: its entries' places in the
  // pattern, and the block's own pattern (analysed once per change).
  s.touchedDofs.clear();
  std::vector<int> localOf(static_cast<std::size_t>(s.dofCount), -1);
  for (int node = 0; node < freeNodes; ++node)
  {
    if (touched[node])
    {
      for (int k = 0; k < 3; ++k)
      {
        localOf[3 * node + k] = static_cast<int>(s.touchedDofs.size());
        s.touchedDofs.push_back(3 * node + k);
      }
    }
  }
  // A change that touches much of the system is cheaper factorized at once
  // (BridgeTouchedFraction).
  if (static_cast<double>(s.touchedDofs.size()) > BridgeTouchedFraction * s.dofCount)
  {
    return false;
  }
  // One pass over the pattern: the touched block's upper entries, and the
  // touched DOFs' whole columns (an upper entry (row, column) serves column
  // `column` and, mirrored, column `row`).
  MappedEntries block, columns;
  for (int column = 0; column < s.dofCount; ++column)
  {
    for (int k = s.matrix.outerIndexPtr()[column]; k < s.matrix.outerIndexPtr()[column + 1]; ++k)
    {
      const int row = s.matrix.innerIndexPtr()[k];
      if (localOf[column] >= 0)
      {
        columns.add(row, localOf[column], k);
        if (localOf[row] >= 0)
        {
          block.add(localOf[row], localOf[column], k);
        }
      }
      if (row != column && localOf[row] >= 0)
      {
        columns.add(column, localOf[row], k);
      }
    }
  }
  const auto size = static_cast<Eigen::Index>(s.touchedDofs.size());
  columns.build(s.dofCount, size, s.touchedColumns, s.touchedColumnValueOf);
  block.build(size, size, s.touchedMatrix, s.touchedValueOf);
  if (size > 0)
  {
    s.touchedSolver.analyzePattern(s.touchedMatrix);
  }
  s.touchedFactorStep = -1;
  return true;
}

void CorotationalHexFem::factorIsCurrent()
{
  LinearSystem& s = *System;
  s.bridging = false;
  if (s.factorPattern != s.pattern) // the Cholmod kind factorizes every step
  {
    s.factorDofOfNode = s.dofOfNode;
    s.factorDofCount = s.dofCount;
    s.factorPattern = s.pattern;
  }
  s.touchedNodes.clear();
}

void CorotationalHexFem::addGluedCorrection(const Eigen::VectorXd& r, Eigen::VectorXd& z)
{
  // P^T Q F^-1 Q^T P r: copies summed into the nodes they were copied from,
  // turned into the factor's frame, solved, and handed back.
  LinearSystem& s = *System;
  s.glued.setZero(s.factorDofCount);
  const bool turn = s.rotatesFactor;
  for (std::size_t n = 0; n < s.bridgeDof.size(); ++n)
  {
    const int to = s.bridgeDof[n];
    if (to >= 0)
    {
      const auto from = r.segment<3>(static_cast<Eigen::Index>(3 * n));
      if (turn)
      {
        s.glued.segment<3>(to).noalias() += s.relativeRotations[n].transpose() * from;
      }
      else
      {
        s.glued.segment<3>(to) += from;
      }
    }
  }
  s.factor->solve(s.glued, s.gluedSolution);
  for (std::size_t n = 0; n < s.bridgeDof.size(); ++n)
  {
    const int from = s.bridgeDof[n];
    if (from >= 0)
    {
      auto to = z.segment<3>(static_cast<Eigen::Index>(3 * n));
      if (turn)
      {
        to.noalias() += s.relativeRotations[n] * s.gluedSolution.segment<3>(from);
      }
      else
      {
        to += s.gluedSolution.segment<3>(from);
      }
    }
  }
}

void CorotationalHexFem::solveTouched()
{
  // touchedSolution = A_TT^-1 touchedRight, A_TT of this step (its pattern
  // is fixed until the next change; the values are copied once a step).
  LinearSystem& s = *System;
  if (s.touchedFactorStep != s.stepIndex)
  {
    copyValuesInto(s.matrix, s.touchedValueOf, s.touchedMatrix);
    copyValuesInto(s.matrix, s.touchedColumnValueOf, s.touchedColumns);
    s.touchedSolver.factorize(s.touchedMatrix);
    s.touchedFactorStep = s.stepIndex;
  }
  s.touchedSolution = s.touchedSolver.solve(s.touchedRight);
}

void CorotationalHexFem::applyBridgedFactor(const Eigen::VectorXd& r, Eigen::VectorXd& z)
{
  // Symmetric multiplicative two-level preconditioner: the touched DOFs'
  // exact solve (S), the old factor on what remains (C), S again:
  // z = S r + (I - S A) C (I - A S) r. Symmetric, and positive definite:
  // outside the touched DOFs the glued map is one to one. The products
  // with A involve a vector held on the touched DOFs only, or only its
  // touched rows: they cost the touched columns, not the system.
  LinearSystem& s = *System;
  const auto touchedCount = static_cast<Eigen::Index>(s.touchedDofs.size());
  s.touchedRight.resize(touchedCount);
  for (Eigen::Index i = 0; i < touchedCount; ++i)
  {
    s.touchedRight[i] = r[s.touchedDofs[i]];
  }
  s.bridgeResidual = r;
  if (touchedCount > 0)
  {
    solveTouched();
    s.bridgeResidual.noalias() -= s.touchedColumns * s.touchedSolution;
  }
  z.setZero(r.size());
  addGluedCorrection(s.bridgeResidual, z);
  if (touchedCount == 0)
  {
    return;
  }
  // z_T += A_TT^-1 (r - A (S r + C r1))_T = -A_TT^-1 (A C r1)_T, since
  // (A S r)_T = r_T.
  s.touchedFirst = s.touchedSolution;
  s.touchedRight.noalias() = -(s.touchedColumns.transpose() * z);
  solveTouched();
  for (Eigen::Index i = 0; i < touchedCount; ++i)
  {
    z[s.touchedDofs[i]] += s.touchedFirst[i] + s.touchedSolution[i];
  }
}

Eigen::Matrix3d CorotationalHexFem::currentRotation(const Element& element) const
{
  // Polar decomposition of the deformation gradient at the element centre.
  if (!Settings.corotational)
  {
    return Eigen::Matrix3d::Identity();
  }
  Eigen::Matrix3d gradient = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 8; ++a)
  {
    gradient += Positions[element.nodes[a]] * element.rest.centreGradients.col(a).transpose();
  }
  return polarRotation(gradient);
}

void CorotationalHexFem::accumulateElasticForce(const Element& element,
  const Eigen::Matrix3d& rotation,
  double velocityScale,
  double sign,
  std::vector<Vector3>& forces) const
{
  // f_e = R K_e (R^T (x + s v) - X): the elastic force, plus s K v for the
  // damping and implicit terms when s > 0.
  ElementVector local;
  for (int a = 0; a < 8; ++a)
  {
    const int n = element.nodes[a];
    local.segment<3>(3 * a) =
      rotation.transpose() * (Positions[n] + velocityScale * Velocities[n]) - RestPositions[n];
  }
  const ElementVector localForce = element.rest.stiffness * local;
  for (int a = 0; a < 8; ++a)
  {
    forces[element.nodes[a]] += sign * (rotation * localForce.segment<3>(3 * a));
  }
}

Vector3 CorotationalHexFem::contactRelativeVelocity(const EmbeddedContact& c) const
{
  const auto weights = trilinearWeights(c.local);
  Vector3 velocity = -c.surfaceVelocity;
  for (int a = 0; a < 8; ++a)
  {
    velocity += weights[a] * Velocities[Elements[c.hexahedron].nodes[a]];
  }
  return velocity;
}

Vector3 CorotationalHexFem::contactForce(const EmbeddedContact& c,
  double h,
  double frictionDamping) const
{
  // Spring at the current depth and damper, with the implicit h k term, and
  // the tangential (friction) damper: the force the linearised step applies
  // at the point's velocity.
  const Vector3 velocity = contactRelativeVelocity(c);
  const double normalSpeed = c.normal.dot(velocity);
  return (c.stiffness * c.depth - (h * c.stiffness + c.damping) * normalSpeed) * c.normal -
         frictionDamping * (velocity - normalSpeed * c.normal);
}

void CorotationalHexFem::colourElements()
{
  // Greedy colouring: no two elements of one colour share a node, so the
  // elements of a colour scatter into disjoint matrix entries and nodal
  // forces and assemble in parallel, and every sum is taken in the same
  // order (colour by colour) whatever the number of threads: the same bits.
  // A regular hexahedral grid takes 8 colours.
  LinearSystem& s = *System;
  std::vector<std::uint64_t> nodeColours(Positions.size(), 0);
  std::vector<int> colourOf(Elements.size(), -1);
  std::vector<int> counts(ParallelColourLimit + 1, 0);
  for (std::size_t e = 0; e < Elements.size(); ++e)
  {
    if (!Elements[e].active)
    {
      continue;
    }
    std::uint64_t used = 0;
    for (int node : Elements[e].nodes)
    {
      used |= nodeColours[node];
    }
    // Beyond 64 colours (a node in more elements than any grid has) the
    // elements go to a last colour assembled serially.
    const int colour = used == ~std::uint64_t(0) ? ParallelColourLimit : __builtin_ctzll(~used);
    if (colour < ParallelColourLimit)
    {
      for (int node : Elements[e].nodes)
      {
        nodeColours[node] |= std::uint64_t(1) << colour;
      }
    }
    colourOf[e] = colour;
    ++counts[colour];
  }
  s.colourStarts.assign(1, 0);
  for (int colour = 0; colour <= ParallelColourLimit; ++colour)
  {
    if (counts[colour] > 0)
    {
      s.colourStarts.push_back(s.colourStarts.back() + counts[colour]);
    }
  }
  s.colouredElements.clear();
  s.colouredElements.reserve(s.colourStarts.back());
  for (int colour = 0; colour <= ParallelColourLimit; ++colour)
  {
    for (std::size_t e = 0; e < Elements.size(); ++e)
    {
      if (colourOf[e] == colour)
      {
        s.colouredElements.push_back(static_cast<int>(e));
      }
    }
  }
}

void CorotationalHexFem::assembleElement(std::size_t e,
  double stiffnessScale,
  double velocityStiffnessScale,
  std::vector<Vector3>& forces)
{
  Element& element = Elements[e];
  const Eigen::Matrix3d rotation = currentRotation(element);
  element.rotation = rotation;
  accumulateElasticForce(element, rotation, velocityStiffnessScale, -1.0, forces);
  // Rotated stiffness blocks R K_ab R^T into the matrix's upper triangle:
  // a block whose first entry has no place lies below the diagonal or on a
  // fixed node (a diagonal block, a == b, is half in).
  const auto& offsets = System->elementOffsets[e];
  double* values = System->matrix.valuePtr();
  const RotatedStiffness rotated(stiffnessScale, rotation);
  for (int a = 0; a < 8; ++a)
  {
    for (int b = 0; b < 8; ++b)
    {
      const int* blockOffsets = offsets.data() + (a * 8 + b) * 9;
      if (blockOffsets[2] < 0)
      {
        continue; // entry (0, 2) is in the upper triangle of every block that has one
      }
      rotated.addBlock(element.rest.stiffness.data() + 24 * 3 * b + 3 * a, blockOffsets, values);
    }
  }
}

void CorotationalHexFem::assemble(double stiffnessScale,
  double massScale,
  double velocityStiffnessScale,
  std::vector<Vector3>& forces)
{
  LinearSystem& s = *System;
  std::fill(forces.begin(), forces.end(), Vector3::Zero());
  double* values = s.matrix.valuePtr();
  std::fill(values, values + s.matrix.nonZeros(), 0.0);
  s.nodalBlocksInverted = false;
  const int threads = Settings.assemblyThreads;
  const bool parallel = threads != 1 && s.colourStarts.back() >= ParallelAssemblyMinimumElements;
  if (parallel && s.arenaThreads != threads)
  {
    const int automatic = tbb::task_arena::automatic; // a value, not the static member
    s.arena = std::make_unique<tbb::task_arena>(threads > 0 ? threads : automatic);
    s.arenaThreads = threads;
  }
  for (std::size_t colour = 0; colour + 1 < s.colourStarts.size(); ++colour)
  {
    const int* first = s.colouredElements.data() + s.colourStarts[colour];
    const int count = s.colourStarts[colour + 1] - s.colourStarts[colour];
    const bool serialColour =
      colour + 2 == s.colourStarts.size() && s.colourStarts.size() > ParallelColourLimit + 1;
    auto assembleRange = [&](int begin, int end)
    {
      for (int k = begin; k < end; ++k)
      {
        assembleElement(first[k], stiffnessScale, velocityStiffnessScale, forces);
      }
    };
    if (!parallel || serialColour)
    {
      assembleRange(0, count);
      continue;
    }
    s.arena->execute(
      [&]
      {
        tbb::parallel_for(tbb::blocked_range<int>(0, count, 64),
          [&](const tbb::blocked_range<int>& range) { assembleRange(range.begin(), range.end()); });
      });
  }
  for (std::size_t n = 0; n < Positions.size(); ++n)
  {
    const int dof = s.dofOfNode[n];
    if (dof >= 0)
    {
      for (int i = 0; i < 3; ++i)
      {
        values[s.diagonalOffsets[dof + i]] += massScale * NodeMasses[n];
      }
    }
  }
}

bool CorotationalHexFem::solveSystem(Eigen::VectorXd& solution,
  int& iterations,
  std::string& message)
{
  LinearSystem& s = *System;
  iterations = 0;
  const LinearSolverKind kind = effectiveSolver();
  if (kind == LinearSolverKind::StaleFactorConjugateGradient)
  {
    return solveWithStaleFactor(solution, iterations, message);
  }
  if (kind == LinearSolverKind::MultigridConjugateGradient)
  {
    return solveWithMultigrid(solution, iterations, message);
  }
  if (kind == LinearSolverKind::Cholmod)
  {
    if (!factorize(message))
    {
      return false;
    }
    s.factor->solve(s.rhs, solution);
    iterations = 1;
  }
  else
  {
    invertNodalBlocks();
    if (!iteratePreconditioned(solution,
          Settings.conjugateGradientMaxIterations,
          iterations,
          [this](const Eigen::VectorXd& r, Eigen::VectorXd& z) { applyNodalBlockJacobi(r, z); }))
    {
      message = "conjugate gradient did not converge in " + std::to_string(iterations) +
                " iterations (relative residual " +
                std::to_string(s.residual.norm() / s.rhs.norm()) + ")";
      return false;
    }
  }
  if (!solution.allFinite())
  {
    message = "the solution is not finite (NaN or infinity)";
    return false;
  }
  return true;
}

void CorotationalHexFem::setContacts(const std::vector<EmbeddedContact>& contacts)
{
  for (std::size_t k = 0; k < contacts.size(); ++k)
  {
    const EmbeddedContact& c = contacts[k];
    const bool valid =
      c.hexahedron < Elements.size() && Elements[c.hexahedron].active && c.local.allFinite() &&
      c.normal.allFinite() && std::abs(c.normal.norm() - 1.0) < 1e-6 && std::isfinite(c.depth) &&
      c.stiffness >= 0.0 && std::isfinite(c.stiffness) && c.damping >= 0.0 &&
      std::isfinite(c.damping) && c.surfaceVelocity.allFinite() && c.friction >= 0.0 &&
      std::isfinite(c.friction) && c.slipVelocity > 0.0 && std::isfinite(c.slipVelocity);
    if (!valid)
    {
      throw InvalidInputError(
        "co-rotational FEM: contact " + std::to_string(k) +
        " is invalid (hexahedron out of range or inactive, normal not unit, negative or "
        "non-finite stiffness, damping, friction or depth, non-positive slip velocity or "
        "non-finite surface velocity)");
    }
  }
  Contacts = contacts;
  ContactForces.assign(Contacts.size(), Vector3::Zero());
  ContactFrictionDamping.assign(Contacts.size(), 0.0);
}

void CorotationalHexFem::assembleContacts(double h)
{
  LinearSystem& s = *System;
  double* values = s.matrix.valuePtr();
  for (std::size_t k = 0; k < Contacts.size(); ++k)
  {
    const EmbeddedContact& c = Contacts[k];
    const Element& element = Elements[c.hexahedron];
    const auto weights = trilinearWeights(c.local);
    const double implicitDamping = h * c.stiffness + c.damping;
    // Regularised Coulomb friction as a tangential damper whose coefficient
    // is fixed from the start-of-step normal force and slip speed.
    double frictionDamping = 0.0;
    if (c.friction > 0.0)
    {
      const Vector3 velocity = contactRelativeVelocity(c);
      const double normalSpeed = c.normal.dot(velocity);
      const double normalForce =
        std::max(0.0, c.stiffness * c.depth - implicitDamping * normalSpeed);
      const double slip = (velocity - normalSpeed * c.normal).norm();
      frictionDamping = c.friction * normalForce / std::max(slip, c.slipVelocity);
    }
    ContactFrictionDamping[k] = frictionDamping;
    const Vector3 force = contactForce(c, h, frictionDamping); // at the start-of-step velocity
    const Eigen::Matrix3d normalProjector = c.normal * c.normal.transpose();
    const Eigen::Matrix3d block =
      h * (implicitDamping * normalProjector +
            frictionDamping * (Eigen::Matrix3d::Identity() - normalProjector));
    const auto& offsets = s.elementOffsets[c.hexahedron];
    for (int a = 0; a < 8; ++a)
    {
      const int dof = s.dofOfNode[element.nodes[a]];
      if (dof >= 0)
      {
        s.rhs.segment<3>(dof) += h * weights[a] * force;
      }
      for (int b = 0; b < 8; ++b)
      {
        const int* blockOffsets = offsets.data() + (a * 8 + b) * 9;
        for (int i = 0; i < 3; ++i)
        {
          for (int j = 0; j < 3; ++j)
          {
            if (blockOffsets[i * 3 + j] >= 0)
            {
              values[blockOffsets[i * 3 + j]] += weights[a] * weights[b] * block(i, j);
            }
          }
        }
      }
    }
  }
}

bool CorotationalHexFem::factorize(std::string& message)
{
  LinearSystem& s = *System;
  s.factorValid = s.factor->factorize(s.matrix, s.pattern, Settings);
  factorIsCurrent();
  s.factorStep = s.stepIndex;
  s.factorRotations = s.nodeRotations;
  s.rotatesFactor = false; // the factor is of this step's matrix
  ++s.factorizations;
  ++s.synchronousFactorizations;
  s.excessIterations = 0;
  if (!s.factorValid)
  {
    message = "the system matrix is not positive definite (CHOLMOD factorization failed)";
  }
  return s.factorValid;
}

bool CorotationalHexFem::refreshesInBackground() const
{
  return effectiveSolver() == LinearSolverKind::StaleFactorConjugateGradient &&
         System->dofCount >= Settings.backgroundRefactorizationThreshold;
}

void CorotationalHexFem::startBackgroundRefactorization()
{
  LinearSystem& s = *System;
  BackgroundRefactorization& refresh = s.refresh;
  if (refresh.dueStep >= 0)
  {
    return; // one at a time
  }
  refresh.matrix = s.matrix; // this step's matrix; the next steps reassemble theirs
  refresh.pattern = s.pattern;
  refresh.startStep = s.stepIndex;
  refresh.rotations = s.nodeRotations;
  s.refreshLag = refreshLagAfter(s.lastSolveIterations);
  refresh.dueStep = s.stepIndex + s.refreshLag;
  refresh.worker = std::thread(
    [&refresh, pattern = s.pattern, settings = Settings, hook = s.backgroundHook]
    {
      if (hook)
      {
        hook();
      }
      refresh.ok = refresh.factor->factorize(refresh.matrix, pattern, settings);
    });
}

int CorotationalHexFem::refreshLagAfter(int iterations) const
{
  // Due at least Settings.backgroundRefactorizationLag steps after it
  // starts, and late enough that it is done by then, or that step waits
  // for it. A factorization costs r solves in flops (CHOLMOD's count), but
  // its dense supernodal kernels run about 3.5 times as many flops a second
  // as a solve's, and a step costs about (iterations + 3) solves (the
  // assembly and products about 3); with margin for the cores the worker
  // shares with the step's parallel assembly, r / 2 / (iterations + 3)
  // steps. From the factor's pattern and this step's iterations only: the
  // same on every replay. The 1,000-hexahedra block (r = 63) in steady
  // state (1-3 iterations) gets 7-8 steps, where 4 made every refresh's
  // due step wait about 10 ms for it (`ThinTissueBench --suite fem`,
  // Documentation/Architecture.md); thesis sizes (r = 18) keep the setting;
  // a transient's many iterations keep the refresh near.
  const double solves = System->factor->solvesPerFactorization();
  const double steps = std::ceil(0.5 * solves / (std::max(iterations, 0) + 3));
  return std::max(Settings.backgroundRefactorizationLag,
    static_cast<int>(std::min(steps, static_cast<double>(MaximumRefactorizationLag))));
}

int CorotationalHexFem::lastBackgroundRefactorizationLag() const
{
  return System->refreshLag;
}

void CorotationalHexFem::landBackgroundRefactorization()
{
  LinearSystem& s = *System;
  BackgroundRefactorization& refresh = s.refresh;
  if (refresh.dueStep < 0 || s.stepIndex < refresh.dueStep)
  {
    return;
  }
  refresh.worker.join(); // waits if unfinished: the swap step is fixed
  refresh.dueStep = -1;
  ++s.factorizations;
  if (refresh.ok && refresh.pattern == s.pattern && refresh.startStep > s.factorStep)
  {
    std::swap(s.factor, refresh.factor); // the old factor is reused for the next refresh
    std::swap(s.factorRotations, refresh.rotations);
    s.factorValid = true;
    factorIsCurrent();
    s.factorStep = refresh.startStep;
    updateRelativeRotations();
    s.excessIterations = 0;
  }
}

void CorotationalHexFem::cancelBackgroundRefactorization()
{
  BackgroundRefactorization& refresh = System->refresh;
  if (refresh.worker.joinable())
  {
    refresh.worker.join();
  }
  refresh.dueStep = -1;
}

bool CorotationalHexFem::iteratePreconditioned(Eigen::VectorXd& x,
  int limit,
  int& iterations,
  const Preconditioner& precondition)
{
  LinearSystem& s = *System;
  const double target = Settings.conjugateGradientTolerance * s.rhs.norm();
  s.history.firstGuess([&s](const Eigen::VectorXd& v, Eigen::VectorXd& y)
    { s.blockProduct.multiply(s.matrix, v, y); },
    s.rhs,
    x,
    s.product,
    s.lastSolveIterations >= Settings.warmStartIterations ? Settings.warmStartSolutions : 1);
  s.residual = s.rhs - s.product;
  precondition(s.residual, s.preconditioned);
  s.direction = s.preconditioned;
  double rho = s.residual.dot(s.preconditioned);
  for (iterations = 0; iterations < limit && s.residual.norm() > target;)
  {
    s.blockProduct.multiply(s.matrix, s.direction, s.product);
    const double step = rho / s.direction.dot(s.product);
    x += step * s.direction;
    s.residual -= step * s.product;
    ++iterations;
    if (s.residual.norm() <= target || iterations == limit)
    {
      break; // no preconditioner solve for a direction never taken
    }
    precondition(s.residual, s.preconditioned);
    const double next = s.residual.dot(s.preconditioned);
    s.direction = s.preconditioned + (next / rho) * s.direction;
    rho = next;
  }
  s.lastSolveIterations = iterations;
  return s.residual.norm() <= target;
}

bool CorotationalHexFem::tracksFactorRotations() const
{
  const LinearSolverKind kind = effectiveSolver();
  return Settings.rotateStaleFactor && Settings.corotational &&
         (kind == LinearSolverKind::StaleFactorConjugateGradient ||
           kind == LinearSolverKind::MultigridConjugateGradient);
}

void CorotationalHexFem::updateNodeRotations()
{
  // R_n = the normalized sum of the unit quaternions of the active
  // hexahedra at node n, each taken on the sum's side (q and -q are one
  // rotation): neighbouring elements turn alike, and this mean costs a
  // tenth of a polar factor of the summed matrices (4 % of an examination
  // step); a rigid turn gives its rotation exactly.
  LinearSystem& s = *System;
  s.rotatesFactor = false;
  if (!tracksFactorRotations())
  {
    s.nodeRotations.clear();
    return;
  }
  const std::size_t freeNodes = static_cast<std::size_t>(s.dofCount / 3);
  s.nodeQuaternionSums.assign(freeNodes, Eigen::Vector4d::Zero());
  for (const Element& element : Elements)
  {
    if (!element.active)
    {
      continue;
    }
    const Eigen::Vector4d q = Eigen::Quaterniond(element.rotation).coeffs();
    for (int node : element.nodes)
    {
      const int dof = s.dofOfNode[node];
      if (dof >= 0)
      {
        Eigen::Vector4d& sum = s.nodeQuaternionSums[dof / 3];
        sum += sum.dot(q) < 0.0 ? Eigen::Vector4d(-q) : q;
      }
    }
  }
  s.nodeRotations.resize(freeNodes);
  for (std::size_t n = 0; n < freeNodes; ++n)
  {
    const Eigen::Vector4d& sum = s.nodeQuaternionSums[n];
    const double length = sum.norm();
    s.nodeRotations[n] = length > 0.0 ? Eigen::Quaterniond(sum / length).toRotationMatrix()
                                      : Eigen::Matrix3d::Identity();
  }
  updateRelativeRotations();
}

void CorotationalHexFem::updateRelativeRotations()
{
  LinearSystem& s = *System;
  if (s.bridging && !s.nodeRotations.empty() &&
      s.factorRotations.size() == static_cast<std::size_t>(s.factorDofCount / 3))
  {
    // Each node against the factor's node it maps to.
    s.rotatesFactor = true;
    s.relativeRotations.resize(s.nodeRotations.size());
    for (std::size_t n = 0; n < s.nodeRotations.size(); ++n)
    {
      const int to = s.bridgeDof[n];
      s.relativeRotations[n] =
        to < 0 ? Eigen::Matrix3d::Identity()
               : Eigen::Matrix3d(s.nodeRotations[n] * s.factorRotations[to / 3].transpose());
    }
    return;
  }
  s.rotatesFactor =
    !s.bridging && !s.nodeRotations.empty() && s.factorRotations.size() == s.nodeRotations.size();
  if (!s.rotatesFactor)
  {
    return;
  }
  s.relativeRotations.resize(s.nodeRotations.size());
  for (std::size_t n = 0; n < s.nodeRotations.size(); ++n)
  {
    s.relativeRotations[n].noalias() = s.nodeRotations[n] * s.factorRotations[n].transpose();
  }
}

void CorotationalHexFem::applyStaleFactor(const Eigen::VectorXd& r, Eigen::VectorXd& z)
{
  // z = Q A_f^-1 Q^T r, with A ~ Q A_f Q^T (Q block-diagonal, orthogonal);
  // A_f^-1 is the stale factor's solve or the multigrid hierarchy's V-cycle.
  LinearSystem& s = *System;
  const bool multigrid = effectiveSolver() == LinearSolverKind::MultigridConjugateGradient;
  const auto solveStale = [&](const Eigen::VectorXd& right, Eigen::VectorXd& solution)
  {
    if (multigrid)
    {
      s.multigrid.apply(right, solution);
    }
    else
    {
      s.factor->solve(right, solution);
    }
  };
  if (!s.rotatesFactor)
  {
    solveStale(r, z);
    return;
  }
  s.rotatedRight.resize(r.size());
  for (std::size_t n = 0; n < s.relativeRotations.size(); ++n)
  {
    const Eigen::Index d = static_cast<Eigen::Index>(3 * n);
    s.rotatedRight.segment<3>(d).noalias() = s.relativeRotations[n].transpose() * r.segment<3>(d);
  }
  solveStale(s.rotatedRight, s.rotatedSolution);
  z.resize(r.size());
  for (std::size_t n = 0; n < s.relativeRotations.size(); ++n)
  {
    const Eigen::Index d = static_cast<Eigen::Index>(3 * n);
    z.segment<3>(d).noalias() = s.relativeRotations[n] * s.rotatedSolution.segment<3>(d);
  }
}

void CorotationalHexFem::invertNodalBlocks()
{
  LinearSystem& s = *System;
  if (s.nodalBlocksInverted)
  {
    return;
  }
  s.nodalBlocksInverted = true;
  const double* values = s.matrix.valuePtr();
  for (std::size_t node = 0; node < s.nodalBlockOffsets.size(); ++node)
  {
    const auto& o = s.nodalBlockOffsets[node];
    Eigen::Matrix3d block;
    block << values[o[0]], values[o[1]], values[o[2]], values[o[1]], values[o[3]], values[o[4]],
      values[o[2]], values[o[4]], values[o[5]];
    s.nodalBlockInverses[node] = block.inverse(); // positive definite: M + h D + h^2 K
  }
}

void CorotationalHexFem::applyNodalBlockJacobi(const Eigen::VectorXd& r, Eigen::VectorXd& z) const
{
  const LinearSystem& s = *System;
  z.resize(r.size());
  for (std::size_t node = 0; node < s.nodalBlockInverses.size(); ++node)
  {
    const Eigen::Index d = static_cast<Eigen::Index>(3 * node);
    z.segment<3>(d).noalias() = s.nodalBlockInverses[node] * r.segment<3>(d);
  }
}

bool CorotationalHexFem::solveWithStaleFactor(Eigen::VectorXd& x,
  int& iterations,
  std::string& message)
{
  // Preconditioned conjugate gradients (M^-1 = the last factor), started
  // from the previous step's solution. A factor gone too stale is renewed:
  // in the step (small systems: the factorization is cheap), or on a worker
  // thread while this factor keeps preconditioning, with a synchronous
  // refactorization only when it no longer converges within the cap.
  LinearSystem& s = *System;
  const bool background = refreshesInBackground();
  if (!background && s.excessIterations > Settings.staleFactorIterationBudget)
  {
    s.factorValid = false;
  }
  if (s.bridging && !s.factorValid)
  {
    // Across a topology change: the old factor through the bridge, until
    // the new pattern's factor lands (started by beginCoupledStep).
    if (iteratePreconditioned(x,
          Settings.staleFactorIterationCap,
          iterations,
          [this](const Eigen::VectorXd& r, Eigen::VectorXd& z) { applyBridgedFactor(r, z); }))
    {
      if (!x.allFinite())
      {
        message = "the solution is not finite (NaN or infinity)";
        return false;
      }
      return true;
    }
    s.bridging = false; // it does not serve: factorize this step's matrix
  }
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    if (!s.factorValid)
    {
      if (!factorize(message)) // a refresh under way, of an older matrix, will be dropped
      {
        return false;
      }
    }
    const int staleLimit =
      background ? Settings.staleFactorIterationCap : Settings.refactorizationIterations;
    const int limit = attempt == 0 ? staleLimit : Settings.conjugateGradientMaxIterations;
    if (iteratePreconditioned(x,
          limit,
          iterations,
          [this](const Eigen::VectorXd& r, Eigen::VectorXd& z) { applyStaleFactor(r, z); }))
    {
      s.excessIterations += std::max(0, iterations - 1);
      if (background && (iterations > Settings.refactorizationIterations ||
                          s.excessIterations > Settings.staleFactorIterationBudget))
      {
        startBackgroundRefactorization();
      }
      if (!x.allFinite())
      {
        message = "the solution is not finite (NaN or infinity)";
        return false;
      }
      return true;
    }
    s.factorValid = false; // too stale: factorize the current matrix
  }
  message = "preconditioned conjugate gradient did not converge";
  return false;
}

LinearSolverKind CorotationalHexFem::effectiveSolver() const
{
  if (Settings.solver != LinearSolverKind::Automatic)
  {
    return Settings.solver;
  }
  return System->dofCount <= AutomaticDirectLimit ? LinearSolverKind::StaleFactorConjugateGradient
                                                  : LinearSolverKind::MultigridConjugateGradient;
}

bool CorotationalHexFem::buildMultigrid(std::string& message)
{
  // The rigid motions of the free nodes at their current positions: the
  // near-null space of this step's (rotated) stiffness.
  LinearSystem& s = *System;
  SmoothedAggregation::Coordinates nodes(s.dofCount / 3, 3);
  for (std::size_t n = 0; n < Positions.size(); ++n)
  {
    if (s.dofOfNode[n] >= 0)
    {
      nodes.row(s.dofOfNode[n] / 3) = Positions[n].transpose();
    }
  }
  ++s.multigridBuilds;
  s.multigridValid = s.multigrid.build(s.matrix, nodes, message);
  s.factorStep = s.stepIndex;
  s.factorRotations = s.nodeRotations;
  s.rotatesFactor = false; // the hierarchy is of this step's matrix
  return s.multigridValid;
}

bool CorotationalHexFem::solveWithMultigrid(Eigen::VectorXd& x,
  int& iterations,
  std::string& message)
{
  // Conjugate gradients preconditioned by the (rotated) hierarchy of an
  // earlier step. A solve that needs many iterations marks it for a
  // rebuild at the next step, so that the rebuild happens at a fixed step
  // (replays are exact); one that does not converge rebuilds at once.
  LinearSystem& s = *System;
  const auto precondition = [this](const Eigen::VectorXd& r, Eigen::VectorXd& z)
  { applyStaleFactor(r, z); };
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    const bool fresh = !s.multigridValid;
    if (fresh && !buildMultigrid(message))
    {
      return false;
    }
    if (iteratePreconditioned(x, Settings.conjugateGradientMaxIterations, iterations, precondition))
    {
      s.multigridValid = iterations <= Settings.multigridRebuildIterations;
      if (!x.allFinite())
      {
        message = "the solution is not finite (NaN or infinity)";
        return false;
      }
      return true;
    }
    if (fresh)
    {
      break;
    }
    s.multigridValid = false;
  }
  message = "multigrid-preconditioned conjugate gradient did not converge in " +
            std::to_string(iterations) + " iterations (relative residual " +
            std::to_string(s.residual.norm() / s.rhs.norm()) + ")";
  return false;
}

SolverResult CorotationalHexFem::step()
{
  SolverResult result = beginCoupledStep();
  if (!result.ok || System->dofCount == 0)
  {
    return result; // failed, or everything fixed: nothing moves
  }
  LinearSystem& s = *System;
  if (!solveSystem(s.solution, result.iterations, result.message))
  {
    result.ok = false;
    result.message = "co-rotational FEM step: " + result.message + "; the last good state is kept";
    return result;
  }
  const SolverResult finished = finishCoupledStep(s.solution);
  result.ok = finished.ok;
  result.message = finished.message;
  return result;
}

void CorotationalHexFem::assembleElasticPart()
{
  prepareSystem();
  LinearSystem& s = *System;
  if (!StepOpened)
  {
    ++s.stepIndex;
    landBackgroundRefactorization();
    StepOpened = true;
  }
  if (s.dofCount > 0)
  {
    const double h = Settings.timeStep;
    const double alpha = Settings.rayleighMass;
    const double beta = Settings.rayleighStiffness;
    // (M + h D + h^2 K) dv = h (f_ext - f_int - alpha M v - (beta + h) K v)
    assemble(h * beta + h * h, 1.0 + h * alpha, beta + h, s.forces);
    updateNodeRotations();
  }
  ElasticPartAssembled = true;
}

SolverResult CorotationalHexFem::beginCoupledStep()
{
  SolverResult result;
  if (!ElasticPartAssembled || TopologyChanged)
  {
    assembleElasticPart();
  }
  ElasticPartAssembled = false;
  StepOpened = false;
  LinearSystem& s = *System;
  if (s.dofCount == 0)
  {
    return result;
  }
  const double h = Settings.timeStep;
  const double alpha = Settings.rayleighMass;
  for (std::size_t n = 0; n < Positions.size(); ++n)
  {
    const int dof = s.dofOfNode[n];
    if (dof >= 0)
    {
      s.rhs.segment<3>(dof) = h * (ExternalForces[n] + NodeMasses[n] * Settings.gravity +
                                    s.forces[n] - alpha * NodeMasses[n] * Velocities[n]);
    }
  }
  assembleContacts(h);
  if (s.bridging && s.refresh.dueStep < 0)
  {
    // The new pattern's factor, analysed and made off the step (a refresh
    // of the old pattern still running lands first, dropped).
    startBackgroundRefactorization();
  }
  if (!s.rhs.allFinite())
  {
    result.ok = false;
    result.message = "co-rotational FEM: the forces are not finite; the last good state is kept";
  }
  return result;
}

Eigen::Index CorotationalHexFem::systemSize() const
{
  return System->dofCount;
}

int CorotationalHexFem::degreeOfFreedom(std::size_t node) const
{
  return System->dofOfNode[node];
}

const Eigen::VectorXd& CorotationalHexFem::systemRightHandSide() const
{
  return System->rhs;
}

const Eigen::VectorXd& CorotationalHexFem::previousSystemSolution() const
{
  return System->history.newest();
}

void CorotationalHexFem::multiplySystem(const Eigen::VectorXd& x, Eigen::VectorXd& y) const
{
  System->blockProduct.multiply(System->matrix, x, y);
}

bool CorotationalHexFem::preconditionSystem(const Eigen::VectorXd& r,
  Eigen::VectorXd& z,
  std::string& message)
{
  LinearSystem& s = *System;
  const LinearSolverKind kind = effectiveSolver();
  if (kind == LinearSolverKind::ConjugateGradient)
  {
    invertNodalBlocks(); // once per matrix
    applyNodalBlockJacobi(r, z);
    return true;
  }
  if (kind == LinearSolverKind::MultigridConjugateGradient)
  {
    if (!s.multigridValid && !buildMultigrid(message))
    {
      return false;
    }
    applyStaleFactor(r, z);
    return true;
  }
  if (s.bridging && !s.factorValid)
  {
    applyBridgedFactor(r, z);
    return true;
  }
  if (!s.factorValid && !factorize(message))
  {
    return false;
  }
  applyStaleFactor(r, z);
  return true;
}

void CorotationalHexFem::invalidateFactor()
{
  System->factorValid = false;
  System->bridging = false;
  System->multigridValid = false;
}

void CorotationalHexFem::chargeStaleIterations(int iterations)
{
  LinearSystem& s = *System;
  if (effectiveSolver() == LinearSolverKind::MultigridConjugateGradient)
  {
    s.multigridValid = s.multigridValid && iterations <= Settings.multigridRebuildIterations;
    return;
  }
  s.excessIterations += std::max(0, iterations - 1);
  if (s.excessIterations > Settings.staleFactorIterationBudget)
  {
    if (refreshesInBackground())
    {
      startBackgroundRefactorization();
    }
    else
    {
      s.factorValid = false;
    }
  }
}

SolverResult CorotationalHexFem::finishCoupledStep(const Eigen::VectorXd& solution)
{
  SolverResult result;
  ElasticPartAssembled = false; // it moves the nodes
  LinearSystem& s = *System;
  if (solution.size() != s.dofCount)
  {
    result.ok = false;
    result.message = "co-rotational FEM step: the solution has " + std::to_string(solution.size()) +
                     " entries, the system " + std::to_string(s.dofCount);
    return result;
  }
  if (Settings.solver == LinearSolverKind::Cholmod)
  {
    s.factorValid = false; // refactorized every step
  }
  const double h = Settings.timeStep;
  // Never write a non-finite state: check the update before applying it.
  for (std::size_t n = 0; n < Positions.size(); ++n)
  {
    const int dof = s.dofOfNode[n];
    if (dof >= 0)
    {
      const Vector3 velocity = Velocities[n] + solution.segment<3>(dof);
      if (!velocity.allFinite() || !(Positions[n] + h * velocity).allFinite())
      {
        result.ok = false;
        result.message = "co-rotational FEM step: node " + std::to_string(n) +
                         " would leave the finite range; the last good state is kept";
        return result;
      }
    }
  }
  s.history.push(solution);
  for (std::size_t n = 0; n < Positions.size(); ++n)
  {
    const int dof = s.dofOfNode[n];
    if (dof >= 0)
    {
      Velocities[n] += solution.segment<3>(dof);
      Positions[n] += h * Velocities[n];
    }
  }
  // The contact forces as the implicit step applied them (end velocity).
  for (std::size_t k = 0; k < Contacts.size(); ++k)
  {
    // at the end-of-step velocity
    ContactForces[k] = contactForce(Contacts[k], h, ContactFrictionDamping[k]);
  }
  return result;
}

SolverResult CorotationalHexFem::solveStatic(int maxIterations, double relativeTolerance)
{
  SolverResult result;
  ElasticPartAssembled = false; // it moves the nodes
  prepareSystem();
  LinearSystem& s = *System;
  if (s.dofCount == 0)
  {
    return result;
  }
  if (std::none_of(Fixed.begin(), Fixed.end(), [](std::uint8_t f) { return f != 0; }))
  {
    result.ok = false;
    result.message = "co-rotational FEM static solve: no fixed node, the equilibrium is not unique";
    return result;
  }
  const double scale = boundingBoxOf(RestPositions).diagonal().norm();
  const std::vector<Vector3> start = Positions;
  for (int iteration = 1; iteration <= maxIterations; ++iteration)
  {
    assemble(1.0, 0.0, 0.0, s.forces);
    for (std::size_t n = 0; n < Positions.size(); ++n)
    {
      const int dof = s.dofOfNode[n];
      if (dof >= 0)
      {
        s.rhs.segment<3>(dof) = ExternalForces[n] + NodeMasses[n] * Settings.gravity + s.forces[n];
      }
    }
    if (!s.rhs.allFinite() || !solveSystem(s.solution, result.iterations, result.message))
    {
      Positions = start;
      result.ok = false;
      result.message =
        "co-rotational FEM static solve: " +
        (result.message.empty() ? std::string("forces are not finite") : result.message) +
        "; the last good state is kept";
      return result;
    }
    for (std::size_t n = 0; n < Positions.size(); ++n)
    {
      const int dof = s.dofOfNode[n];
      if (dof >= 0)
      {
        Positions[n] += s.solution.segment<3>(dof);
      }
    }
    result.iterations = iteration;
    if (s.solution.norm() <= relativeTolerance * scale || !Settings.corotational)
    {
      return result; // linear FEM converges in one solve
    }
  }
  result.ok = false;
  result.message = "co-rotational FEM static solve: not converged in " +
                   std::to_string(maxIterations) + " iterations";
  return result;
}

int CorotationalHexFem::factorizationCount() const
{
  return System->factorizations;
}

int CorotationalHexFem::synchronousFactorizationCount() const
{
  return System->synchronousFactorizations;
}

int CorotationalHexFem::multigridBuildCount() const
{
  return System->multigridBuilds;
}

void CorotationalHexFem::setBackgroundFactorizationHook(std::function<void()> hook)
{
  cancelBackgroundRefactorization(); // a running worker holds the old hook
  System->backgroundHook = std::move(hook);
}

std::vector<Vector3> CorotationalHexFem::elasticForces() const
{
  std::vector<Vector3> forces(Positions.size(), Vector3::Zero());
  for (const auto& element : Elements)
  {
    if (!element.active)
    {
      continue;
    }
    accumulateElasticForce(element, currentRotation(element), 0.0, 1.0, forces);
  }
  return forces;
}

} // namespace thintissue
