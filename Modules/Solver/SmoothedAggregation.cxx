#include "SmoothedAggregation.h"

#include "ThinTissueError.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <numeric>

namespace thintissue
{

namespace
{
using ColumnMatrix = SmoothedAggregation::SparseMatrix;
using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
/// The near-null space of a level: 6 columns (3 translations, 3 rotations).
using NullSpace = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>;
using Graph = std::vector<std::vector<int>>;

/// The column-major view of a symmetric row-major matrix: the same matrix.
Eigen::Map<const ColumnMatrix> symmetricColumnView(const RowMatrix& a)
{
  return Eigen::Map<const ColumnMatrix>(
    a.rows(), a.cols(), a.nonZeros(), a.outerIndexPtr(), a.innerIndexPtr(), a.valuePtr());
}

/// Stored entries from which a level's products run on several threads.
/// Each row's sum is taken by one thread in the row's order, the order of
/// Eigen's serial product: the same bits for any thread count.
constexpr Eigen::Index ParallelProductEntries = 200000;

/// y = m x with m's values taken from `values` (its own, or singlePrecision
/// of it), y sized here, rows in parallel on large levels.
template <typename Value>
void multiplyRows(const RowMatrix& m,
  const Value* values,
  const Eigen::VectorXd& x,
  Eigen::VectorXd& y)
{
  y.resize(m.rows());
  const auto rows = [&](Eigen::Index begin, Eigen::Index end)
  {
    const int* starts = m.outerIndexPtr();
    const int* columns = m.innerIndexPtr();
    for (Eigen::Index i = begin; i < end; ++i)
    {
      double sum = 0.0;
      for (int k = starts[i]; k < starts[i + 1]; ++k)
      {
        sum += static_cast<double>(values[k]) * x[columns[k]];
      }
      y[i] = sum;
    }
  };
  if (m.nonZeros() < ParallelProductEntries)
  {
    rows(0, m.rows());
    return;
  }
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, m.rows(), 512),
    [&](const tbb::blocked_range<Eigen::Index>& range) { rows(range.begin(), range.end()); });
}

/// y = m x in m's own (double) values.
void multiply(const RowMatrix& m, const Eigen::VectorXd& x, Eigen::VectorXd& y)
{
  multiplyRows(m, m.valuePtr(), x, y);
}

/// A row matrix's values in single precision, beside its (double) pattern:
/// what the V-cycle's other products read (8 bytes an entry against 12).
std::vector<float> singlePrecision(const RowMatrix& m)
{
  return std::vector<float>(m.valuePtr(), m.valuePtr() + m.nonZeros());
}

/// y = m x in m's single-precision values (singlePrecision of m).
void multiply(const RowMatrix& m,
  const std::vector<float>& values,
  const Eigen::VectorXd& x,
  Eigen::VectorXd& y)
{
  multiplyRows(m, values.data(), x, y);
}

/// A symmetric matrix of 3x3 node blocks (the finest level's), each block
/// column-major in single precision, block rows in order. The V-cycle's
/// products on the finest level are most of a multigrid step (63 % of the
/// 10,000-hexahedra block's samples) and they wait on memory: 40 bytes a
/// block here against 108 in the double CSR rows. A preconditioner needs
/// no more precision than this (measured: Documentation/Architecture.md).
struct NodeBlockRows
{
  std::vector<int> rowStarts; ///< per block row, its first block (and the end)
  std::vector<int> columns;   ///< per block, its node column
  std::vector<float> values;  ///< 9 per block, then one float of padding

  bool empty() const { return rowStarts.empty(); }
};

/// Whether the rows of `node` in m hold the same whole 3x3 blocks.
bool holdsNodeBlocks(const RowMatrix& m, Eigen::Index node)
{
  const int* starts = m.outerIndexPtr();
  const int* columns = m.innerIndexPtr();
  const int first = starts[3 * node];
  const int width = starts[3 * node + 1] - first;
  if (width % 3 != 0)
    return false;
  for (int i = 0; i < 3; ++i)
  {
    const int row = starts[3 * node + i];
    if (starts[3 * node + i + 1] - row != width)
      return false;
    for (int k = 0; k < width; ++k)
    {
      const int blockStart = columns[first + 3 * (k / 3)];
      if (columns[row + k] != blockStart + k % 3 || blockStart % 3 != 0)
        return false;
    }
  }
  return true;
}

/// The node blocks of `m` (3 unknowns per node); empty if m is not made of
/// whole node blocks.
NodeBlockRows nodeBlockRows(const RowMatrix& m)
{
  NodeBlockRows blocks;
  if (m.rows() % 3 != 0 || m.rows() != m.cols() || !m.isCompressed())
    return blocks;
  const int* starts = m.outerIndexPtr();
  const int* columns = m.innerIndexPtr();
  const double* values = m.valuePtr();
  const Eigen::Index nodes = m.rows() / 3;
  blocks.rowStarts.reserve(static_cast<std::size_t>(nodes) + 1);
  blocks.rowStarts.push_back(0);
  for (Eigen::Index node = 0; node < nodes; ++node)
  {
    if (!holdsNodeBlocks(m, node))
      return {};
    const int first = starts[3 * node];
    for (int k = 0; k < starts[3 * node + 1] - first; k += 3)
    {
      blocks.columns.push_back(columns[first + k] / 3);
      for (int j = 0; j < 3; ++j) // column j of the block
        for (int i = 0; i < 3; ++i)
          blocks.values.push_back(static_cast<float>(values[starts[3 * node + i] + k + j]));
    }
    blocks.rowStarts.push_back(static_cast<int>(blocks.columns.size()));
  }
  blocks.values.push_back(0.0f); // the last block's third column reads one more
  return blocks;
}

/// y[3r .. 3r + 2] = the sum over the blocks of row r of B x[3c .. 3c + 2],
/// for rows [begin, end).
void multiplyBlockRows(const NodeBlockRows& m,
  const double* x,
  double* y,
  Eigen::Index begin,
  Eigen::Index end)
{
  for (Eigen::Index r = begin; r < end; ++r)
  {
#if defined(__AVX2__) && defined(__FMA__)
    // Each column read four wide: its fourth lane (the next column's
    // first entry) is left out of y.
    __m256d sum = _mm256_setzero_pd();
    for (int k = m.rowStarts[r]; k < m.rowStarts[r + 1]; ++k)
    {
      const float* block = m.values.data() + 9 * static_cast<std::size_t>(k);
      const double* u = x + 3 * static_cast<std::ptrdiff_t>(m.columns[k]);
      sum = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(block)), _mm256_set1_pd(u[0]), sum);
      sum = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(block + 3)), _mm256_set1_pd(u[1]), sum);
      sum = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(block + 6)), _mm256_set1_pd(u[2]), sum);
    }
    alignas(32) double lanes[4];
    _mm256_store_pd(lanes, sum);
    y[3 * r] = lanes[0];
    y[3 * r + 1] = lanes[1];
    y[3 * r + 2] = lanes[2];
#else
    double sum[3] = { 0.0, 0.0, 0.0 };
    for (int k = m.rowStarts[r]; k < m.rowStarts[r + 1]; ++k)
    {
      const float* block = m.values.data() + 9 * static_cast<std::size_t>(k);
      const double* u = x + 3 * static_cast<std::ptrdiff_t>(m.columns[k]);
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
          sum[i] += static_cast<double>(block[3 * j + i]) * u[j];
    }
    y[3 * r] = sum[0];
    y[3 * r + 1] = sum[1];
    y[3 * r + 2] = sum[2];
#endif
  }
}

/// y = m x (y sized here), block rows in parallel on large matrices (each
/// row by one thread: the same bits for any thread count).
void multiply(const NodeBlockRows& m, const Eigen::VectorXd& x, Eigen::VectorXd& y)
{
  const Eigen::Index rows = static_cast<Eigen::Index>(m.rowStarts.size()) - 1;
  y.resize(3 * rows);
  if (9 * m.columns.size() < static_cast<std::size_t>(ParallelProductEntries))
  {
    multiplyBlockRows(m, x.data(), y.data(), 0, rows);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, rows, 256),
    [&](const tbb::blocked_range<Eigen::Index>& range)
    { multiplyBlockRows(m, x.data(), y.data(), range.begin(), range.end()); });
}
} // namespace

void checkSmoothedAggregationSettings(const SmoothedAggregationSettings& s)
{
  if (s.coarsestUnknowns < 1 || s.maximumLevels < 1 || s.smootherDegree < 1 ||
      !(s.strengthThreshold >= 0.0 && s.strengthThreshold < 1.0))
  {
    throw InvalidInputError(
      "smoothed aggregation: coarsest unknowns, levels and smoother degree "
      "must be at least 1 and the strength threshold in [0, 1) (got " +
      std::to_string(s.coarsestUnknowns) + ", " + std::to_string(s.maximumLevels) + ", " +
      std::to_string(s.smootherDegree) + ", " + std::to_string(s.strengthThreshold) + ")");
  }
}

struct SmoothedAggregation::Level
{
  RowMatrix matrix; // full symmetric
  /// First unknown of each block (and the end): 3 per mesh node on the
  /// finest level, the rank of an aggregate's near-null space below.
  std::vector<int> blockStarts;
  /// The inverses of the diagonal blocks, packed (column-major each).
  std::vector<double> blockInverses;
  std::vector<int> inverseStarts;
  /// The Chebyshev smoother's interval of the spectrum of D^-1 A.
  double lowest = 0.0, highest = 0.0;
  /// To the next coarser level (empty on the coarsest).
  RowMatrix prolongator, restrictor;
  Eigen::VectorXd x, b, residual, direction, work;
  /// The finest level's matrix again, as 3x3 node blocks in single
  /// precision (NodeBlockRows): what its products read.
  NodeBlockRows nodeBlocks;
  /// The values of the matrix (when it has no node blocks), prolongator
  /// and restrictor in single precision: what the V-cycle reads.
  std::vector<float> matrixValues, prolongatorValues, restrictorValues;

  /// y = A x, through the node blocks when the level has them.
  void product(const Eigen::VectorXd& v, Eigen::VectorXd& y) const;

  int blockCount() const { return static_cast<int>(blockStarts.size()) - 1; }
  bool invertDiagonalBlocks();
  void applyBlockInverse(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  void estimateSpectrum();
  Graph strongCouplings(double threshold) const;
  /// x += S (b - A x), S the Chebyshev polynomial; x = S b when `fromZero`.
  void smooth(int degree, bool fromZero);
};

struct SmoothedAggregation::Hierarchy
{
  std::vector<Level> levels;
  Eigen::SimplicialLLT<ColumnMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> coarsest;
  Eigen::VectorXd coarsestWork;
  double complexity = 1.0;
};

bool SmoothedAggregation::Level::invertDiagonalBlocks()
{
  inverseStarts.assign(1, 0);
  for (int block = 0; block < blockCount(); ++block)
  {
    const int size = blockStarts[block + 1] - blockStarts[block];
    inverseStarts.push_back(inverseStarts.back() + size * size);
  }
  blockInverses.assign(static_cast<std::size_t>(inverseStarts.back()), 0.0);
  Eigen::MatrixXd diagonal;
  for (int block = 0; block < blockCount(); ++block)
  {
    const int start = blockStarts[block], size = blockStarts[block + 1] - start;
    diagonal.setZero(size, size);
    for (int row = start; row < start + size; ++row)
    {
      for (RowMatrix::InnerIterator it(matrix, row); it; ++it)
      {
        if (it.col() >= start && it.col() < start + size)
        {
          diagonal(row - start, it.col() - start) = it.value();
        }
      }
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(diagonal);
    if (llt.info() != Eigen::Success)
    {
      return false;
    }
    Eigen::Map<Eigen::MatrixXd>(blockInverses.data() + inverseStarts[block], size, size) =
      llt.solve(Eigen::MatrixXd::Identity(size, size));
  }
  return true;
}

void SmoothedAggregation::Level::applyBlockInverse(const Eigen::VectorXd& r,
  Eigen::VectorXd& z) const
{
  for (int block = 0; block < blockCount(); ++block)
  {
    const int start = blockStarts[block], size = blockStarts[block + 1] - start;
    const double* inverse = blockInverses.data() + inverseStarts[block];
    if (size == 3) // the finest level: fixed-size products
    {
      z.segment<3>(start).noalias() =
        Eigen::Map<const Eigen::Matrix3d>(inverse) * r.segment<3>(start);
    }
    else if (size == 6)
    {
      z.segment<6>(start).noalias() =
        Eigen::Map<const Eigen::Matrix<double, 6, 6>>(inverse) * r.segment<6>(start);
    }
    else
    {
      z.segment(start, size).noalias() =
        Eigen::Map<const Eigen::MatrixXd>(inverse, size, size) * r.segment(start, size);
    }
  }
}

void SmoothedAggregation::Level::product(const Eigen::VectorXd& v, Eigen::VectorXd& y) const
{
  if (!nodeBlocks.empty())
    multiply(nodeBlocks, v, y);
  else if (!matrixValues.empty())
    multiply(matrix, matrixValues, v, y);
  else
    multiply(matrix, v, y);
}

void SmoothedAggregation::Level::estimateSpectrum()
{
  // Power iterations on D^-1 A from a fixed, rough start (deterministic).
  // The estimate is from below; 10 % more covers the gap, and the smoother
  // damps [highest / 30, highest], the part the coarse levels cannot see.
  const Eigen::Index n = matrix.rows();
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i)
  {
    v[i] = 1.0 + static_cast<double>((i * 7919) % 17) / 17.0;
  }
  double estimate = 1.0;
  for (int iteration = 0; iteration < 20; ++iteration)
  {
    v /= v.norm();
    product(v, work);
    applyBlockInverse(work, v);
    estimate = v.norm();
  }
  highest = 1.1 * estimate;
  lowest = highest / 30.0;
}

Graph SmoothedAggregation::Level::strongCouplings(double threshold) const
{
  std::vector<int> blockOf(static_cast<std::size_t>(matrix.rows()));
  for (int block = 0; block < blockCount(); ++block)
  {
    std::fill(
      blockOf.begin() + blockStarts[block], blockOf.begin() + blockStarts[block + 1], block);
  }
  Graph graph(static_cast<std::size_t>(blockCount()));
  std::vector<double> normSquared(static_cast<std::size_t>(blockCount()), 0.0);
  std::vector<double> diagonalNorm(static_cast<std::size_t>(blockCount()), 0.0);
  std::vector<std::vector<double>> norms(static_cast<std::size_t>(blockCount()));
  for (int block = 0; block < blockCount(); ++block)
  {
    std::vector<int>& neighbours = graph[block];
    for (int row = blockStarts[block]; row < blockStarts[block + 1]; ++row)
    {
      for (RowMatrix::InnerIterator it(matrix, row); it; ++it)
      {
        const int other = blockOf[it.col()];
        if (normSquared[other] == 0.0)
        {
          neighbours.push_back(other);
        }
        normSquared[other] += it.value() * it.value() + 1e-300; // marks it as seen
      }
    }
    for (int other : neighbours)
    {
      norms[block].push_back(std::sqrt(normSquared[other]));
      if (other == block)
      {
        diagonalNorm[block] = norms[block].back();
      }
      normSquared[other] = 0.0;
    }
  }
  for (int block = 0; block < blockCount(); ++block)
  {
    std::vector<int> strong;
    for (std::size_t k = 0; k < graph[block].size(); ++k)
    {
      const int other = graph[block][k];
      if (other != block &&
          norms[block][k] >= threshold * std::sqrt(diagonalNorm[block] * diagonalNorm[other]))
      {
        strong.push_back(other);
      }
    }
    std::sort(strong.begin(), strong.end());
    graph[block] = std::move(strong);
  }
  return graph;
}

void SmoothedAggregation::Level::smooth(int degree, bool fromZero)
{
  // Chebyshev iteration on D^-1 A over [lowest, highest] (Saad, Iterative
  // Methods for Sparse Linear Systems, algorithm 12.1).
  const double centre = 0.5 * (highest + lowest), halfWidth = 0.5 * (highest - lowest);
  const double sigma = centre / halfWidth;
  double rho = 1.0 / sigma;
  if (fromZero)
  {
    residual = b;
  }
  else
  {
    product(x, work);
    residual = b - work;
  }
  applyBlockInverse(residual, direction);
  direction /= centre;
  for (int k = 0; k < degree; ++k)
  {
    if (fromZero && k == 0)
    {
      x = direction;
    }
    else
    {
      x += direction;
    }
    if (k + 1 == degree)
    {
      break;
    }
    product(direction, work);
    residual -= work;
    const double next = 1.0 / (2.0 * sigma - rho);
    applyBlockInverse(residual, work);
    direction = (next * rho) * direction + (2.0 * next / halfWidth) * work;
    rho = next;
  }
}

namespace
{
/// Aggregates of strongly coupled blocks (Vanek, Mandel, Brezina 1996):
/// first whole neighbourhoods of untouched blocks, then the rest joins a
/// neighbouring aggregate, and what is still alone groups with its free
/// neighbours. Returns the aggregate of each block and their count.
int aggregateBlocks(const Graph& graph, std::vector<int>& aggregateOf)
{
  const int blocks = static_cast<int>(graph.size());
  aggregateOf.assign(static_cast<std::size_t>(blocks), -1);
  int count = 0;
  for (int block = 0; block < blocks; ++block)
  {
    const auto& neighbours = graph[block];
    if (aggregateOf[block] >= 0 ||
        std::any_of(
          neighbours.begin(), neighbours.end(), [&](int n) { return aggregateOf[n] >= 0; }))
    {
      continue;
    }
    aggregateOf[block] = count;
    for (int n : neighbours)
    {
      aggregateOf[n] = count;
    }
    ++count;
  }
  std::vector<int> joined = aggregateOf; // joins see the first pass only
  for (int block = 0; block < blocks; ++block)
  {
    if (aggregateOf[block] >= 0)
    {
      continue;
    }
    for (int n : graph[block])
    {
      if (aggregateOf[n] >= 0)
      {
        joined[block] = aggregateOf[n];
        break;
      }
    }
  }
  aggregateOf = std::move(joined);
  for (int block = 0; block < blocks; ++block)
  {
    if (aggregateOf[block] >= 0)
    {
      continue;
    }
    aggregateOf[block] = count;
    for (int n : graph[block])
    {
      if (aggregateOf[n] < 0)
      {
        aggregateOf[n] = count;
      }
    }
    ++count;
  }
  return count;
}

/// The rigid motions of nodes at `nodes` (about their centroid), 3 rows per node.
NullSpace rigidMotions(const SmoothedAggregation::Coordinates& nodes)
{
  const Eigen::RowVector3d centroid = nodes.colwise().mean();
  NullSpace modes = NullSpace::Zero(3 * nodes.rows(), 6);
  for (Eigen::Index n = 0; n < nodes.rows(); ++n)
  {
    const Eigen::RowVector3d p = nodes.row(n) - centroid;
    modes.block<3, 3>(3 * n, 0).setIdentity();
    // omega x p for omega = e_x, e_y, e_z.
    modes.block<3, 3>(3 * n, 3) << 0.0, p.z(), -p.y(), -p.z(), 0.0, p.x(), p.y(), -p.x(), 0.0;
  }
  return modes;
}

/// The tentative prolongator: per aggregate, an orthonormal basis of its
/// part of the near-null space (QR, rank-revealing: a small aggregate spans
/// fewer rigid motions), and the coarse near-null space (the R factors).
ColumnMatrix tentativeProlongator(const std::vector<int>& blockStarts,
  const std::vector<int>& aggregateOf,
  int aggregates,
  const NullSpace& modes,
  NullSpace& coarseModes,
  std::vector<int>& coarseBlockStarts)
{
  std::vector<std::vector<int>> members(static_cast<std::size_t>(aggregates));
  for (std::size_t block = 0; block < aggregateOf.size(); ++block)
  {
    members[aggregateOf[block]].push_back(static_cast<int>(block));
  }
  std::vector<Eigen::Triplet<double, int>> entries;
  std::vector<Eigen::Matrix<double, 1, 6>> coarseRows;
  coarseBlockStarts.assign(1, 0);
  std::vector<int> rows;
  for (const auto& aggregate : members)
  {
    rows.clear();
    for (int block : aggregate)
    {
      for (int row = blockStarts[block]; row < blockStarts[block + 1]; ++row)
      {
        rows.push_back(row);
      }
    }
    Eigen::MatrixXd local(static_cast<Eigen::Index>(rows.size()), 6);
    for (std::size_t k = 0; k < rows.size(); ++k)
    {
      local.row(static_cast<Eigen::Index>(k)) = modes.row(rows[k]);
    }
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(local);
    qr.setThreshold(1e-10);
    const Eigen::Index rank = qr.rank();
    const Eigen::MatrixXd basis = qr.householderQ() * Eigen::MatrixXd::Identity(local.rows(), rank);
    const Eigen::MatrixXd coefficients = basis.transpose() * local;
    const int first = coarseBlockStarts.back();
    for (Eigen::Index c = 0; c < rank; ++c)
    {
      for (std::size_t k = 0; k < rows.size(); ++k)
      {
        entries.emplace_back(
          rows[k], first + static_cast<int>(c), basis(static_cast<Eigen::Index>(k), c));
      }
      coarseRows.push_back(coefficients.row(c));
    }
    coarseBlockStarts.push_back(first + static_cast<int>(rank));
  }
  coarseModes.resize(static_cast<Eigen::Index>(coarseRows.size()), 6);
  for (std::size_t k = 0; k < coarseRows.size(); ++k)
  {
    coarseModes.row(static_cast<Eigen::Index>(k)) = coarseRows[k];
  }
  ColumnMatrix tentative(modes.rows(), coarseBlockStarts.back());
  tentative.setFromTriplets(entries.begin(), entries.end());
  return tentative;
}

/// The block diagonal of D^-1 as a sparse matrix.
ColumnMatrix blockInverseMatrix(const std::vector<int>& blockStarts,
  const std::vector<double>& inverses,
  const std::vector<int>& inverseStarts,
  Eigen::Index size)
{
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(inverses.size());
  for (std::size_t block = 0; block + 1 < blockStarts.size(); ++block)
  {
    const int start = blockStarts[block], width = blockStarts[block + 1] - start;
    for (int j = 0; j < width; ++j)
    {
      for (int i = 0; i < width; ++i)
      {
        entries.emplace_back(start + i, start + j, inverses[inverseStarts[block] + j * width + i]);
      }
    }
  }
  ColumnMatrix inverse(size, size);
  inverse.setFromTriplets(entries.begin(), entries.end());
  return inverse;
}
} // namespace

SmoothedAggregation::SmoothedAggregation(const SmoothedAggregationSettings& settings)
  : Settings(settings)
{
  checkSmoothedAggregationSettings(settings);
}

SmoothedAggregation::~SmoothedAggregation() = default;
SmoothedAggregation::SmoothedAggregation(SmoothedAggregation&&) noexcept = default;
SmoothedAggregation& SmoothedAggregation::operator=(SmoothedAggregation&&) noexcept = default;

bool SmoothedAggregation::build(const SparseMatrix& upper,
  const Coordinates& nodes,
  std::string& message)
{
  Levels.reset();
  auto hierarchy = std::make_unique<Hierarchy>();
  const Eigen::Index n = upper.rows();
  if (upper.cols() != n || nodes.rows() * 3 != n)
  {
    message = "smoothed aggregation: the matrix must be square with 3 unknowns per node";
    return false;
  }
  hierarchy->levels.emplace_back();
  {
    Level& finest = hierarchy->levels.back();
    finest.matrix = upper.selfadjointView<Eigen::Upper>();
    finest.nodeBlocks = nodeBlockRows(finest.matrix);
    finest.blockStarts.resize(static_cast<std::size_t>(nodes.rows()) + 1);
    for (std::size_t k = 0; k < finest.blockStarts.size(); ++k)
    {
      finest.blockStarts[k] = static_cast<int>(3 * k);
    }
  }
  NullSpace modes = rigidMotions(nodes);
  for (;;)
  {
    Level& level = hierarchy->levels.back();
    const Eigen::Index size = level.matrix.rows();
    for (Eigen::VectorXd* v :
      { &level.x, &level.b, &level.residual, &level.direction, &level.work })
    {
      v->setZero(size);
    }
    if (!level.invertDiagonalBlocks())
    {
      message = "smoothed aggregation: a diagonal block of level " +
                std::to_string(hierarchy->levels.size() - 1) + " is not positive definite";
      return false;
    }
    if (size <= Settings.coarsestUnknowns ||
        static_cast<int>(hierarchy->levels.size()) >= Settings.maximumLevels)
    {
      break;
    }
    // The smoother's spectrum from the operator it will apply.
    if (level.nodeBlocks.empty())
      level.matrixValues = singlePrecision(level.matrix);
    level.estimateSpectrum();
    std::vector<int> aggregateOf;
    const int aggregates =
      aggregateBlocks(level.strongCouplings(Settings.strengthThreshold), aggregateOf);
    NullSpace coarseModes;
    std::vector<int> coarseBlockStarts;
    const ColumnMatrix tentative = tentativeProlongator(
      level.blockStarts, aggregateOf, aggregates, modes, coarseModes, coarseBlockStarts);
    if (tentative.cols() >= size)
    {
      break; // no coarsening left: this level is the coarsest
    }
    const auto a = symmetricColumnView(level.matrix);
    const ColumnMatrix inverse =
      blockInverseMatrix(level.blockStarts, level.blockInverses, level.inverseStarts, size);
    const ColumnMatrix product = a * tentative;
    const double weight = 4.0 / (3.0 * level.highest / 1.1);
    const ColumnMatrix prolongator = tentative - weight * (inverse * product);
    const ColumnMatrix restrictor = prolongator.transpose();
    const ColumnMatrix coarse = restrictor * ColumnMatrix(a * prolongator);
    const ColumnMatrix coarseTransposed = coarse.transpose();
    level.prolongator = prolongator;
    level.restrictor = restrictor;
    level.prolongatorValues = singlePrecision(level.prolongator);
    level.restrictorValues = singlePrecision(level.restrictor);
    Level next;
    next.matrix = 0.5 * (coarse + coarseTransposed); // symmetric to the last bit
    next.blockStarts = std::move(coarseBlockStarts);
    modes = std::move(coarseModes);
    hierarchy->levels.push_back(std::move(next));
  }
  Level& coarsest = hierarchy->levels.back();
  hierarchy->coarsest.compute(ColumnMatrix(coarsest.matrix));
  if (hierarchy->coarsest.info() != Eigen::Success)
  {
    message = "smoothed aggregation: the coarsest matrix is not positive definite";
    return false;
  }
  hierarchy->coarsestWork.setZero(coarsest.matrix.rows());
  double entries = 0.0;
  for (const Level& level : hierarchy->levels)
  {
    entries += static_cast<double>(level.matrix.nonZeros());
  }
  hierarchy->complexity = entries / static_cast<double>(hierarchy->levels[0].matrix.nonZeros());
  Levels = std::move(hierarchy);
  return true;
}

bool SmoothedAggregation::ready() const
{
  return Levels != nullptr;
}

void SmoothedAggregation::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z)
{
  std::vector<Level>& levels = Levels->levels;
  const int last = static_cast<int>(levels.size()) - 1;
  levels[0].b = r;
  for (int l = 0; l < last; ++l) // down: pre-smoothing, restricted residual
  {
    Level& level = levels[l];
    level.smooth(Settings.smootherDegree, true);
    level.product(level.x, level.work);
    level.residual = level.b - level.work;
    multiply(level.restrictor, level.restrictorValues, level.residual, levels[l + 1].b);
  }
  Level& coarsest = levels[last];
  auto& factor = Levels->coarsest;
  Levels->coarsestWork.noalias() = factor.permutationP() * coarsest.b;
  factor.matrixL().solveInPlace(Levels->coarsestWork);
  factor.matrixU().solveInPlace(Levels->coarsestWork);
  coarsest.x.noalias() = factor.permutationPinv() * Levels->coarsestWork;
  for (int l = last - 1; l >= 0; --l) // up: coarse correction, post-smoothing
  {
    Level& level = levels[l];
    multiply(level.prolongator, level.prolongatorValues, levels[l + 1].x, level.work);
    level.x += level.work;
    level.smooth(Settings.smootherDegree, false);
  }
  z = levels[0].x;
}

int SmoothedAggregation::levelCount() const
{
  return Levels ? static_cast<int>(Levels->levels.size()) : 0;
}

Eigen::Index SmoothedAggregation::levelUnknowns(int level) const
{
  return Levels->levels[static_cast<std::size_t>(level)].matrix.rows();
}

bool SmoothedAggregation::finestLevelInNodeBlocks() const
{
  return Levels && !Levels->levels.front().nodeBlocks.empty();
}

double SmoothedAggregation::operatorComplexity() const
{
  return Levels ? Levels->complexity : 0.0;
}

} // namespace thintissue
