#include "BlockSymmetricProduct.h"

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#endif

namespace thintissue
{

namespace
{

/// Whether the three columns of node block `node` hold the same block rows
/// (rows 3a, 3a + 1, 3a + 2 each, a < node, ascending) and end with the
/// diagonal block's upper triangle.
bool isBlockColumn(const Eigen::SparseMatrix<double>& upper, Eigen::Index node)
{
  const int* start = upper.outerIndexPtr();
  const int* rows = upper.innerIndexPtr();
  const Eigen::Index first = 3 * node;
  const int blocks = (start[first + 1] - start[first] - 1) / 3;
  for (int j = 0; j < 3; ++j)
  {
    const int s = start[first + j];
    if (start[first + j + 1] - s != 3 * blocks + j + 1)
      return false;
    for (int k = 0; k < blocks; ++k)
    {
      const int row = rows[start[first] + 3 * k];
      if (row % 3 != 0 || row >= first || (k > 0 && row <= rows[start[first] + 3 * (k - 1)]))
        return false;
      for (int i = 0; i < 3; ++i)
        if (rows[s + 3 * k + i] != row + i)
          return false;
    }
    for (int i = 0; i <= j; ++i)
      if (rows[s + 3 * blocks + i] != first + i)
        return false;
  }
  return true;
}

/// The off-diagonal blocks of node column `first` (their block rows
/// `blockRows[3k]`, columns c0, c1, c2 from entry 3k):
/// y[row..row+2] += B (x0, x1, x2) and (y0, y1, y2) = the sum of
/// B^T x[row..row+2]. With AVX2 and FMA four lanes wide: each 4-wide read
/// stays in the column (its diagonal entries follow the last block) and in
/// x and y (row + 3 <= first), and the fourth lane is masked out of every
/// sum, so whatever it reads never counts.
void offDiagonalBlocks(int blocks,
  const int* blockRows,
  const double* c0,
  const double* c1,
  const double* c2,
  const double* x,
  double* y,
  Eigen::Index first,
  double& y0,
  double& y1,
  double& y2)
{
#if defined(__AVX2__) && defined(__FMA__)
  const __m256d threeLanes = _mm256_castsi256_pd(_mm256_set_epi64x(0, -1, -1, -1));
  const __m256d x0 = _mm256_set1_pd(x[first]);
  const __m256d x1 = _mm256_set1_pd(x[first + 1]);
  const __m256d x2 = _mm256_set1_pd(x[first + 2]);
  __m256d sum0 = _mm256_setzero_pd();
  __m256d sum1 = _mm256_setzero_pd();
  __m256d sum2 = _mm256_setzero_pd();
  for (int k = 0; k < blocks; ++k)
  {
    const int row = blockRows[3 * k];
    const __m256d a = _mm256_loadu_pd(c0 + 3 * k);
    const __m256d b = _mm256_loadu_pd(c1 + 3 * k);
    const __m256d c = _mm256_loadu_pd(c2 + 3 * k);
    const __m256d column = _mm256_fmadd_pd(c, x2, _mm256_fmadd_pd(b, x1, _mm256_mul_pd(a, x0)));
    _mm256_storeu_pd(
      y + row, _mm256_add_pd(_mm256_loadu_pd(y + row), _mm256_and_pd(column, threeLanes)));
    const __m256d u = _mm256_and_pd(_mm256_loadu_pd(x + row), threeLanes);
    sum0 = _mm256_fmadd_pd(a, u, sum0);
    sum1 = _mm256_fmadd_pd(b, u, sum1);
    sum2 = _mm256_fmadd_pd(c, u, sum2);
  }
  alignas(32) double lanes[3][4];
  _mm256_store_pd(lanes[0], sum0);
  _mm256_store_pd(lanes[1], sum1);
  _mm256_store_pd(lanes[2], sum2);
  y0 = lanes[0][0] + lanes[0][1] + lanes[0][2];
  y1 = lanes[1][0] + lanes[1][1] + lanes[1][2];
  y2 = lanes[2][0] + lanes[2][1] + lanes[2][2];
#else
  const double x0 = x[first], x1 = x[first + 1], x2 = x[first + 2];
  y0 = y1 = y2 = 0.0;
  for (int k = 0; k < blocks; ++k)
  {
    const int row = blockRows[3 * k];
    const double* a = c0 + 3 * k;
    const double* b = c1 + 3 * k;
    const double* c = c2 + 3 * k;
    for (int i = 0; i < 3; ++i)
      y[row + i] += a[i] * x0 + b[i] * x1 + c[i] * x2;
    const double u0 = x[row], u1 = x[row + 1], u2 = x[row + 2];
    y0 += a[0] * u0 + a[1] * u1 + a[2] * u2;
    y1 += b[0] * u0 + b[1] * u1 + b[2] * u2;
    y2 += c[0] * u0 + c[1] * u1 + c[2] * u2;
  }
#endif
}

} // namespace

void BlockSymmetricProduct::analyse(const Eigen::SparseMatrix<double>& upper)
{
  Blocked = upper.isCompressed() && upper.rows() == upper.cols() && upper.rows() % 3 == 0;
  for (Eigen::Index node = 0; Blocked && node < upper.rows() / 3; ++node)
    Blocked = isBlockColumn(upper, node);
}

void BlockSymmetricProduct::multiply(const Eigen::SparseMatrix<double>& upper,
  const Eigen::VectorXd& x,
  Eigen::VectorXd& y) const
{
  if (!Blocked)
  {
    y.noalias() = upper.selfadjointView<Eigen::Upper>() * x;
    return;
  }
  const int* start = upper.outerIndexPtr();
  const int* rows = upper.innerIndexPtr();
  const double* values = upper.valuePtr();
  const Eigen::Index nodes = upper.rows() / 3;
  y.setZero(upper.rows());
  for (Eigen::Index node = 0; node < nodes; ++node)
  {
    const Eigen::Index first = 3 * node;
    // The node's three columns: c0[3k + i] = A(3a + i, first), and so on.
    const double* c0 = values + start[first];
    const double* c1 = values + start[first + 1];
    const double* c2 = values + start[first + 2];
    const double x0 = x[first], x1 = x[first + 1], x2 = x[first + 2];
    double y0, y1, y2;
    const int blocks = (start[first + 1] - start[first] - 1) / 3;
    const int* blockRows = rows + start[first];
    offDiagonalBlocks(blocks, blockRows, c0, c1, c2, x.data(), y.data(), first, y0, y1, y2);
    // The diagonal block from its upper triangle: (d00), (d01 d11), (d02 d12 d22).
    const double* d0 = c0 + 3 * blocks;
    const double* d1 = c1 + 3 * blocks;
    const double* d2 = c2 + 3 * blocks;
    y[first] += y0 + d0[0] * x0 + d1[0] * x1 + d2[0] * x2;
    y[first + 1] += y1 + d1[0] * x0 + d1[1] * x1 + d2[1] * x2;
    y[first + 2] += y2 + d2[0] * x0 + d2[1] * x1 + d2[2] * x2;
  }
}

} // namespace thintissue
