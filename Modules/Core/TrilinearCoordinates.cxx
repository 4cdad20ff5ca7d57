#include "TrilinearCoordinates.h"

#include <Eigen/Dense>

#include <cmath>

namespace thintissue
{

HexahedronCorners hexahedronCorners(const HexahedralMesh& mesh, std::size_t h)
{
  HexahedronCorners corners;
  for (int k = 0; k < 8; ++k)
  {
    corners[k] = mesh.nodes[mesh.hexahedra[h][k]];
  }
  return corners;
}

std::array<double, 8> trilinearWeights(const Vector3& local)
{
  std::array<double, 8> weights;
  for (int k = 0; k < 8; ++k)
  {
    const auto offset = HexahedralMesh::cornerOffset(k);
    double w = 1.0;
    for (int axis = 0; axis < 3; ++axis)
    {
      w *= offset[axis] != 0 ? local[axis] : 1.0 - local[axis];
    }
    weights[k] = w;
  }
  return weights;
}

Vector3 trilinearPoint(const HexahedronCorners& corners, const Vector3& local)
{
  const auto weights = trilinearWeights(local);
  Vector3 point = Vector3::Zero();
  for (int k = 0; k < 8; ++k)
  {
    point += weights[k] * corners[k];
  }
  return point;
}

namespace
{
// d(point)/d(local): column a is the derivative along local axis a.
Eigen::Matrix3d trilinearJacobian(const HexahedronCorners& corners, const Vector3& local)
{
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 8; ++k)
  {
    const auto offset = HexahedralMesh::cornerOffset(k);
    for (int a = 0; a < 3; ++a)
    {
      double d = offset[a] != 0 ? 1.0 : -1.0;
      for (int b = 0; b < 3; ++b)
      {
        if (b != a)
        {
          d *= offset[b] != 0 ? local[b] : 1.0 - local[b];
        }
      }
      jacobian.col(a) += d * corners[k];
    }
  }
  return jacobian;
}
} // namespace

bool trilinearCoordinates(const HexahedronCorners& corners, const Vector3& point, Vector3& local)
{
  double scale = 0.0;
  for (int k = 1; k < 8; ++k)
  {
    scale = std::max(scale, (corners[k] - corners[0]).norm());
  }
  if (!(scale > 0.0))
  {
    return false;
  }
  local = Vector3::Constant(0.5);
  for (int iteration = 0; iteration < 50; ++iteration)
  {
    const Vector3 residual = trilinearPoint(corners, local) - point;
    if (residual.norm() <= 1e-12 * scale)
    {
      return true;
    }
    const Eigen::Matrix3d jacobian = trilinearJacobian(corners, local);
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(jacobian);
    if (!lu.isInvertible())
    {
      return false;
    }
    Vector3 step = lu.solve(residual);
    // Damp huge steps far outside the cell: the trilinear map is only
    // meaningful near it, and Newton may otherwise oscillate.
    const double length = step.norm();
    if (length > 2.0)
    {
      step *= 2.0 / length;
    }
    local -= step;
    if (!local.allFinite())
    {
      return false;
    }
  }
  return (trilinearPoint(corners, local) - point).norm() <= 1e-8 * scale;
}

bool isInsideUnitCube(const Vector3& local, double tolerance)
{
  return (local.array() >= -tolerance).all() && (local.array() <= 1.0 + tolerance).all();
}

int findContainingHexahedron(const HexahedralMesh& mesh, const Vector3& point, double tolerance)
{
  for (std::size_t h = 0; h < mesh.hexahedronCount(); ++h)
  {
    const auto corners = hexahedronCorners(mesh, h);
    BoundingBox box;
    for (const auto& c : corners)
    {
      box.extend(c);
    }
    const double pad = tolerance * (box.diagonal().norm() + 1.0);
    if ((point.array() < box.min().array() - pad).any() ||
        (point.array() > box.max().array() + pad).any())
    {
      continue;
    }
    Vector3 local;
    if (trilinearCoordinates(corners, point, local) && isInsideUnitCube(local, tolerance))
    {
      return static_cast<int>(h);
    }
  }
  return -1;
}

} // namespace thintissue
