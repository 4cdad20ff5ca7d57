#include "BlockSymmetricProduct.h"

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
    double y0 = 0.0, y1 = 0.0, y2 = 0.0;
    const int blocks = (start[first + 1] - start[first] - 1) / 3;
    for (int k = 0; k < blocks; ++k)
    {
      const int row = rows[start[first] + 3 * k];
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
