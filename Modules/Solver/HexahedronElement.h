// The 8-node trilinear hexahedron of the co-rotational FEM (thesis 4.2):
// rest-state stiffness by 2x2x2 Gauss integration of an isotropic linear
// material, lumped nodal masses, and the rotation of the current shape.
#ifndef HexahedronElement_h
#define HexahedronElement_h

#include "ThinTissueSolverModule.h"
#include "TrilinearCoordinates.h"

#include <Eigen/Core>

namespace thintissue
{

using ElementStiffness = Eigen::Matrix<double, 24, 24>;
using ElementVector = Eigen::Matrix<double, 24, 1>;

/// Isotropic linear elastic material. Units must be consistent (e.g. SI; or
/// mm, N, s with E in MPa and density in t/mm^3).
struct LinearMaterial
{
  double youngModulus = 1.0e5;
  double poissonRatio = 0.3;
  double density = 1.0e3;
};

/// Throws InvalidInputError (naming `context`) if E <= 0, nu outside
/// (-1, 0.5), or density not positive / not finite.
THINTISSUESOLVER_EXPORT void checkMaterial(const LinearMaterial& material,
  const std::string& context);

/// Rest-state data of one hexahedron.
struct HexahedronRestState
{
  ElementStiffness stiffness;
  /// Gradients of the 8 shape functions at the cell centre (rest
  /// coordinates), columns in VTK corner order: F = sum_a x_a grad_a^T.
  Eigen::Matrix<double, 3, 8> centreGradients;
  /// Integral of each shape function (times density: the lumped mass).
  Eigen::Matrix<double, 8, 1> shapeIntegrals;
  double volume = 0.0;
};

/// Rest state of a hexahedron with corners in VTK order. Throws
/// InvalidInputError (naming `context`) if the Jacobian determinant is not
/// positive at a Gauss point or the centre (inverted or degenerate cell).
THINTISSUESOLVER_EXPORT HexahedronRestState computeHexahedronRestState(
  const HexahedronCorners& corners,
  const LinearMaterial& material,
  const std::string& context);

/// Rotation of the polar decomposition F = R S (R proper: det R = +1), by
/// a scaled Newton iteration; an inverted or degenerate F (det F <= 1e-6
/// |F|^3) takes polarRotationBySvd.
THINTISSUESOLVER_EXPORT Eigen::Matrix3d polarRotation(const Eigen::Matrix3d& deformationGradient);
/// The same by an SVD F = U S V^T, R = U V^T, with U's last column (the
/// smallest singular direction) flipped when that is a reflection: the
/// rotation convention for inverted elements.
THINTISSUESOLVER_EXPORT Eigen::Matrix3d polarRotationBySvd(
  const Eigen::Matrix3d& deformationGradient);

} // namespace thintissue

#endif
