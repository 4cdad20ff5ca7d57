#include "HexahedronElement.h"

#include "ThinTissueError.h"

#include <Eigen/Dense>
#include <Eigen/SVD>

#include <cmath>
#include <sstream>

namespace thintissue
{

void checkMaterial(const LinearMaterial& material, const std::string& context)
{
  std::ostringstream problem;
  if (!(material.youngModulus > 0.0) || !std::isfinite(material.youngModulus))
  {
    problem << "Young's modulus must be positive (got " << material.youngModulus << ")";
  }
  else if (!(material.poissonRatio > -1.0 && material.poissonRatio < 0.5))
  {
    problem << "Poisson's ratio must be in (-1, 0.5) (got " << material.poissonRatio << ")";
  }
  else if (!(material.density > 0.0) || !std::isfinite(material.density))
  {
    problem << "density must be positive (got " << material.density << ")";
  }
  if (problem.tellp() != 0)
  {
    throw InvalidInputError(context + ": " + problem.str());
  }
}

namespace
{

/// Derivatives of the 8 shape functions with respect to the local
/// coordinates (xi, eta, zeta) in [-1, 1]^3, columns in VTK corner order.
Eigen::Matrix<double, 3, 8> localGradients(const Eigen::Vector3d& local)
{
  Eigen::Matrix<double, 3, 8> gradients;
  for (int a = 0; a < 8; ++a)
  {
    const auto offset = HexahedralMesh::cornerOffset(a);
    const Eigen::Vector3d sign(2.0 * offset[0] - 1.0, 2.0 * offset[1] - 1.0, 2.0 * offset[2] - 1.0);
    const Eigen::Vector3d factor = (Eigen::Vector3d::Ones() + sign.cwiseProduct(local)) / 2.0;
    gradients(0, a) = 0.5 * sign[0] * factor[1] * factor[2];
    gradients(1, a) = 0.5 * sign[1] * factor[0] * factor[2];
    gradients(2, a) = 0.5 * sign[2] * factor[0] * factor[1];
  }
  return gradients;
}

double shapeValue(int a, const Eigen::Vector3d& local)
{
  const auto offset = HexahedralMesh::cornerOffset(a);
  double value = 1.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    value *= 0.5 * (1.0 + (2.0 * offset[axis] - 1.0) * local[axis]);
  }
  return value;
}

/// Gradients with respect to rest coordinates and the Jacobian determinant.
Eigen::Matrix<double, 3, 8> restGradients(const HexahedronCorners& corners,
  const Eigen::Vector3d& local,
  double& determinant)
{
  const Eigen::Matrix<double, 3, 8> dN = localGradients(local);
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero(); // J_ij = dX_i / dxi_j
  for (int a = 0; a < 8; ++a)
  {
    jacobian += corners[a] * dN.col(a).transpose();
  }
  determinant = jacobian.determinant();
  return jacobian.transpose().inverse() * dN;
}

} // namespace

HexahedronRestState computeHexahedronRestState(const HexahedronCorners& corners,
  const LinearMaterial& material,
  const std::string& context)
{
  const double E = material.youngModulus;
  const double nu = material.poissonRatio;
  const double lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = E / (2.0 * (1.0 + nu));
  Eigen::Matrix<double, 6, 6> elasticity = Eigen::Matrix<double, 6, 6>::Zero();
  elasticity.topLeftCorner<3, 3>().setConstant(lambda);
  elasticity.topLeftCorner<3, 3>().diagonal().array() += 2.0 * mu;
  elasticity.bottomRightCorner<3, 3>().diagonal().setConstant(mu);

  HexahedronRestState state;
  state.stiffness.setZero();
  state.shapeIntegrals.setZero();
  const double gauss = 1.0 / std::sqrt(3.0);
  for (int g = 0; g < 8; ++g)
  {
    const Eigen::Vector3d local(
      (g & 1) ? gauss : -gauss, (g & 2) ? gauss : -gauss, (g & 4) ? gauss : -gauss);
    double determinant = 0.0;
    const Eigen::Matrix<double, 3, 8> gradients = restGradients(corners, local, determinant);
    if (!(determinant > 0.0))
    {
      std::ostringstream message;
      message << context << ": inverted or degenerate hexahedron (Jacobian determinant "
              << determinant << " at a Gauss point)";
      throw InvalidInputError(message.str());
    }
    // Strain-displacement matrix, Voigt order xx yy zz xy yz zx with
    // engineering shear strains.
    Eigen::Matrix<double, 6, 24> strain = Eigen::Matrix<double, 6, 24>::Zero();
    for (int a = 0; a < 8; ++a)
    {
      const double bx = gradients(0, a);
      const double by = gradients(1, a);
      const double bz = gradients(2, a);
      strain(0, 3 * a) = bx;
      strain(1, 3 * a + 1) = by;
      strain(2, 3 * a + 2) = bz;
      strain(3, 3 * a) = by;
      strain(3, 3 * a + 1) = bx;
      strain(4, 3 * a + 1) = bz;
      strain(4, 3 * a + 2) = by;
      strain(5, 3 * a) = bz;
      strain(5, 3 * a + 2) = bx;
    }
    state.stiffness.noalias() += determinant * strain.transpose() * elasticity * strain;
    for (int a = 0; a < 8; ++a)
    {
      state.shapeIntegrals[a] += determinant * shapeValue(a, local);
    }
    state.volume += determinant;
  }
  double centreDeterminant = 0.0;
  state.centreGradients = restGradients(corners, Eigen::Vector3d::Zero(), centreDeterminant);
  if (!(centreDeterminant > 0.0))
  {
    throw InvalidInputError(context + ": degenerate hexahedron at its centre");
  }
  state.stiffness = 0.5 * (state.stiffness + state.stiffness.transpose()).eval();
  return state;
}

Eigen::Matrix3d polarRotationBySvd(const Eigen::Matrix3d& deformationGradient)
{
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(
    deformationGradient, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  const Eigen::Matrix3d v = svd.matrixV();
  if ((u * v.transpose()).determinant() < 0.0)
  {
    u.col(2) = -u.col(2); // reflection: flip the smallest singular direction
  }
  return u * v.transpose();
}

Eigen::Matrix3d polarRotation(const Eigen::Matrix3d& deformationGradient)
{
  // Higham's scaled Newton iteration X <- (g X + X^-T / g) / 2 (Higham,
  // "Computing the polar decomposition", 1986): it converges quadratically
  // to the orthogonal polar factor of a nonsingular X, a rotation when
  // det F > 0, at a fraction of an SVD's cost (3 iterations for the small
  // strains of a step). X^-T is the cofactor matrix over det X, whose
  // columns are cross products of X's columns. g = |det X|^(-1/3) brings
  // the singular values around 1 while they are far from it. An inverted,
  // flat or non-converging element takes the SVD, whose convention (flip
  // the smallest singular direction) then decides.
  const double normSquared = deformationGradient.squaredNorm();
  const double smallestDeterminant = 1e-6 * normSquared * std::sqrt(normSquared);
  Eigen::Matrix3d x = deformationGradient;
  bool scaled = true;
  for (int iteration = 0; iteration < 20; ++iteration)
  {
    Eigen::Matrix3d cofactors;
    cofactors.col(0) = x.col(1).cross(x.col(2));
    cofactors.col(1) = x.col(2).cross(x.col(0));
    cofactors.col(2) = x.col(0).cross(x.col(1));
    const double determinant = x.col(0).dot(cofactors.col(0));
    if (!(determinant > (iteration == 0 ? smallestDeterminant : 0.0)))
    {
      break; // inverted or degenerate (or not finite)
    }
    const double gain = scaled ? 1.0 / std::cbrt(determinant) : 1.0;
    const Eigen::Matrix3d next = 0.5 * (gain * x + cofactors / (gain * determinant));
    const double change = (next - x).squaredNorm();
    x = next;
    // The error after a step is about its change squared (over twice the
    // smallest singular value): a change of 1e-9 leaves round-off.
    if (change <= 1e-18)
    {
      return x;
    }
    scaled = change > 1e-4;
  }
  return polarRotationBySvd(deformationGradient);
}

} // namespace thintissue
