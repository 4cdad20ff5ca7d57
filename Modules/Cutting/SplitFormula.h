// Formula 5-2 in a split collision triangle's plane (thesis 5.3.3), shared
// by the eager rebinding (VisualBindingUpdate.cxx) and the split history
// that resolves bindings lazily (CollisionSplitHistory.cxx): both must give
// the same parameters, bit for bit.
#ifndef SplitFormula_h
#define SplitFormula_h

#include "CollisionMeshCut.h"
#include "CollisionSplitHistory.h"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

namespace thintissue
{

/// Formula 5-1's plane: the triangle's rest corners in 2D, lengths and
/// angles kept.
inline std::array<Vector2, 3> planarFrame(const std::vector<Vector3>& rest, const Triangle& corners)
{
  const Vector3 e1 = rest[corners[1]] - rest[corners[0]];
  const Vector3 e2 = rest[corners[2]] - rest[corners[0]];
  const Vector3 xAxis = e1.normalized();
  const Vector3 yAxis = e1.cross(e2).cross(e1).normalized();
  return { Vector2::Zero(), Vector2(e1.norm(), 0.0), Vector2(e2.dot(xAxis), e2.dot(yAxis)) };
}

/// A point given by barycentric parameters in the frame (formula 5-1).
inline Vector2 planarPoint(const std::array<Vector2, 3>& frame, const Vector3& parameters)
{
  return parameters[0] * frame[0] + parameters[1] * frame[1] + parameters[2] * frame[2];
}

inline PlanePiece planePiece(const std::array<Vector2, 3>& corners)
{
  Eigen::Matrix2d m;
  m.col(0) = corners[1] - corners[0];
  m.col(1) = corners[2] - corners[0];
  return { corners[0], m.inverse() };
}

/// The piece a point lies in, or is nearest to: the one where its smallest
/// barycentric coordinate is largest (`pieceAt(c)` gives piece c).
template <typename PieceAt>
int pieceContainingAmong(std::size_t count, const PieceAt& pieceAt, const Vector2& x)
{
  int best = 0;
  double bestMinimum = -std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < count; ++c)
  {
    const PlanePiece& piece = pieceAt(c);
    const Vector2 bc = piece.inverse * (x - piece.origin);
    const double minimum = std::min({ 1.0 - bc.x() - bc.y(), bc.x(), bc.y() });
    if (minimum > bestMinimum)
    {
      bestMinimum = minimum;
      best = static_cast<int>(c);
    }
  }
  return best;
}

inline int pieceContaining(const PlanePiece* pieces, std::size_t count, const Vector2& x)
{
  return pieceContainingAmong(
    count, [pieces](std::size_t c) -> const PlanePiece& { return pieces[c]; }, x);
}

/// The same for pieces given by their corners (each map made as it is
/// tested: the same products as a PlanePiece kept).
inline int pieceContaining(const std::vector<std::array<Vector2, 3>>& pieces, const Vector2& x)
{
  return pieceContainingAmong(
    pieces.size(), [&pieces](std::size_t c) { return planePiece(pieces[c]); }, x);
}

/// Formula 5-2's M^-1 per piece of the split.
inline std::vector<Eigen::Matrix3d> childInverses(const CollisionTriangleSplit& split)
{
  std::vector<Eigen::Matrix3d> inverses;
  inverses.reserve(split.childCorners.size());
  for (const auto& childCorners : split.childCorners)
  {
    Eigen::Matrix3d m;
    for (int k = 0; k < 3; ++k)
      m.row(k) = childCorners[k].transpose();
    inverses.push_back(m.inverse());
  }
  return inverses;
}

/// Formula 5-2 as one affine map of a region's plane: the parent parameters
/// of a point p of the plane are x = e0 + E F^-1 (p - frame[0]) (F the
/// frame's sides, E = [-1 -1; 1 0; 0 1]), and the child's are y = M^-T x.
class PlaneToChild
{
public:
  PlaneToChild(const std::array<Vector2, 3>& frame, const Eigen::Matrix3d& inverse)
  {
    Eigen::Matrix2d frameMatrix;
    frameMatrix.col(0) = frame[1] - frame[0];
    frameMatrix.col(1) = frame[2] - frame[0];
    Eigen::Matrix<double, 3, 2> sides;
    sides << -1.0, -1.0, 1.0, 0.0, 0.0, 1.0;
    Map = inverse.transpose() * sides * frameMatrix.inverse();
    Offset = inverse.transpose().col(0) - Map * frame[0];
  }
  /// The child parameters of plane point p (clamped into the child).
  Vector3 parameters(const Vector2& p) const { return apply(Map, Offset, p); }
  const Eigen::Matrix<double, 3, 2>& map() const { return Map; }
  const Vector3& offset() const { return Offset; }
  /// The same for a map kept elsewhere (CollisionSplitHistory).
  static Vector3 apply(const Eigen::Matrix<double, 3, 2>& map,
    const Vector3& offset,
    const Vector2& p)
  {
    const Vector3 y = (map * p + offset).cwiseMax(0.0);
    return y / y.sum();
  }

private:
  Eigen::Matrix<double, 3, 2> Map;
  Vector3 Offset;
};

} // namespace thintissue

#endif
