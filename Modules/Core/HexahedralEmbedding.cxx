#include "HexahedralEmbedding.h"

#include "MeshQueries.h"
#include "ThinTissueError.h"

#include <Eigen/Dense>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

namespace thintissue
{

namespace
{

constexpr std::size_t MappingGrain = 4096;

// Row of H for local coordinates l, in VTK corner order; the same products,
// in the same order, as trilinearWeights().
inline void weightsOf(const Vector3& l, double w[8])
{
  const double x = l[0];
  const double y = l[1];
  const double z = l[2];
  const double ax = 1.0 - x;
  const double ay = 1.0 - y;
  const double az = 1.0 - z;
  w[0] = ax * ay * az;
  w[1] = x * ay * az;
  w[2] = x * y * az;
  w[3] = ax * y * az;
  w[4] = ax * ay * z;
  w[5] = x * ay * z;
  w[6] = x * y * z;
  w[7] = ax * y * z;
}

inline Vector3 interpolate(const Hexahedron& hex, const Vector3& local, const Vector3* nodes)
{
  double w[8];
  weightsOf(local, w);
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  for (int k = 0; k < 8; ++k)
  {
    const double* n = nodes[hex[k]].data();
    x += w[k] * n[0];
    y += w[k] * n[1];
    z += w[k] * n[2];
  }
  return Vector3(x, y, z);
}

// Faces of a VTK hexahedron (local corner indices), each split into four
// triangles about its centre for distance queries.
constexpr int HexahedronFaces[6][4] = {
  { 0, 3, 7, 4 },
  { 1, 2, 6, 5 },
  { 0, 1, 5, 4 },
  { 3, 2, 6, 7 },
  { 0, 1, 2, 3 },
  { 4, 5, 6, 7 },
};

double squaredDistanceToBox(const BoundingBox& box, const Vector3& p)
{
  const Vector3 below = (box.min() - p).cwiseMax(0.0);
  const Vector3 above = (p - box.max()).cwiseMax(0.0);
  return below.squaredNorm() + above.squaredNorm();
}

/// Distance from p to the hexahedron's triangulated boundary and its
/// closest point. Faces whose bounding box lies farther than `bound` (or
/// than the best found so far) are skipped: their triangles cannot be
/// nearer. Infinity (closest unset) when every face is farther than bound.
double boundaryDistance(const HexahedronCorners& c,
  const Vector3& p,
  Vector3& closest,
  double bound = std::numeric_limits<double>::infinity())
{
  double best = std::numeric_limits<double>::infinity();
  const double boundSquared = bound * bound;
  for (const auto& face : HexahedronFaces)
  {
    BoundingBox box(c[face[0]], c[face[0]]);
    for (int e = 1; e < 4; ++e)
      box.extend(c[face[e]]);
    const double lower = squaredDistanceToBox(box, p);
    if (lower > boundSquared || lower > best)
      continue;
    const Vector3 centre = 0.25 * (c[face[0]] + c[face[1]] + c[face[2]] + c[face[3]]);
    for (int e = 0; e < 4; ++e)
    {
      const Vector3 q = closestPointOnTriangle(p, c[face[e]], c[face[(e + 1) % 4]], centre);
      const double d = (q - p).squaredNorm();
      if (d < best)
      {
        best = d;
        closest = q;
      }
    }
  }
  return std::sqrt(best);
}

std::string meshContext(const HexahedralMesh& mesh)
{
  return "hexahedral mesh '" + mesh.name + "'";
}

template <typename Body>
void forRange(std::size_t count, std::size_t threshold, std::size_t grain, const Body& body)
{
  if (count >= threshold && count > grain)
  {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain),
      [&](const tbb::blocked_range<std::size_t>& range) { body(range.begin(), range.end()); });
  }
  else
  {
    body(std::size_t(0), count);
  }
}

} // namespace

// --- Trilinear inversion and distance ----------------------------------------

namespace
{

// X(l) - c0 = a1 x + a2 y + a3 z + a4 xy + a5 yz + a6 xz + a7 xyz, relative
// to corner 0 so that rounding scales with the cell, not with its position.
struct TrilinearMap
{
  explicit TrilinearMap(const HexahedronCorners& c)
    : a1(c[1] - c[0])
    , a2(c[3] - c[0])
    , a3(c[4] - c[0])
    , a4((c[2] - c[1]) - (c[3] - c[0]))
    , a5((c[7] - c[3]) - (c[4] - c[0]))
    , a6((c[5] - c[1]) - (c[4] - c[0]))
    , a7(((c[6] - c[2]) - (c[5] - c[1])) - ((c[7] - c[3]) - (c[4] - c[0])))
    , scale(std::max({ a1.norm(), a2.norm(), a3.norm() }))
    , affine(a4.isZero(0.0) && a5.isZero(0.0) && a6.isZero(0.0) && a7.isZero(0.0))
  {
  }

  /// No bilinear or trilinear term: a parallelepiped.
  bool isAffine() const { return affine; }

  Vector3 relativePoint(const Vector3& l) const
  {
    const double x = l[0];
    const double y = l[1];
    const double z = l[2];
    return a1 * x + a2 * y + a3 * z + a4 * (x * y) + a5 * (y * z) + a6 * (x * z) + a7 * (x * y * z);
  }

  Eigen::Matrix3d jacobian(const Vector3& l) const
  {
    const double x = l[0];
    const double y = l[1];
    const double z = l[2];
    Eigen::Matrix3d j;
    j.col(0) = a1 + a4 * y + a6 * z + a7 * (y * z);
    j.col(1) = a2 + a4 * x + a5 * z + a7 * (x * z);
    j.col(2) = a3 + a5 * y + a6 * x + a7 * (x * y);
    return j;
  }

  Vector3 a1, a2, a3, a4, a5, a6, a7;
  double scale;
  bool affine;
};

// Local coordinates in [0,1]^3 of the point of the hexahedron closest to
// `target` (relative to corner 0): projected Gauss-Newton from `start`,
// coordinates on a bound that the gradient pushes outwards held fixed.
Vector3 closestLocalCoordinates(const TrilinearMap& map, const Vector3& target, Vector3 l)
{
  l = l.cwiseMax(0.0).cwiseMin(1.0);
  for (int iteration = 0; iteration < 50; ++iteration)
  {
    const Vector3 residual = map.relativePoint(l) - target;
    const Eigen::Matrix3d j = map.jacobian(l);
    const Vector3 gradient = j.transpose() * residual;
    std::array<bool, 3> free;
    for (int a = 0; a < 3; ++a)
    {
      free[a] = !((l[a] <= 0.0 && gradient[a] > 0.0) || (l[a] >= 1.0 && gradient[a] < 0.0));
    }
    Eigen::Matrix3d normal = j.transpose() * j;
    Vector3 rhs = -gradient;
    for (int a = 0; a < 3; ++a)
    {
      if (!free[a])
      {
        normal.row(a).setZero();
        normal.col(a).setZero();
        normal(a, a) = 1.0;
        rhs[a] = 0.0;
      }
    }
    const Eigen::LDLT<Eigen::Matrix3d> solver(normal);
    Vector3 step = solver.solve(rhs);
    if (!step.allFinite())
    {
      break;
    }
    // Backtracking: accept only a decrease of the distance.
    const double current = residual.squaredNorm();
    Vector3 next = l;
    bool decreased = false;
    for (int halving = 0; halving < 40 && !decreased; ++halving, step *= 0.5)
    {
      next = (l + step).cwiseMax(0.0).cwiseMin(1.0);
      decreased = (map.relativePoint(next) - target).squaredNorm() < current;
    }
    if (!decreased)
    {
      break;
    }
    const double moved = (next - l).norm();
    l = next;
    if (moved <= 1e-13)
    {
      break;
    }
  }
  return l;
}

} // namespace

bool invertTrilinearMap(const HexahedronCorners& c, const Vector3& point, Vector3& local)
{
  const TrilinearMap map(c);
  const Vector3 target = point - c[0];
  const double scale = map.scale;
  if (!(scale > 0.0) || !std::isfinite(scale) || !target.allFinite())
  {
    return false;
  }
  Vector3 l = Vector3::Constant(0.5);
  for (int iteration = 0; iteration < 60; ++iteration)
  {
    const Vector3 residual = map.relativePoint(l) - target;
    const Eigen::Matrix3d jacobian = map.jacobian(l);
    const double determinant = jacobian.determinant();
    if (!(std::abs(determinant) > 1e-14 * scale * scale * scale))
    {
      return false;
    }
    Vector3 step = jacobian.inverse() * residual;
    const double length = step.norm();
    // Damp huge steps: far from the cell Newton may otherwise oscillate
    // (an affine map's step is exact wherever it starts).
    if (length > 2.0 && !map.isAffine())
    {
      step *= 2.0 / length;
    }
    l -= step;
    if (!l.allFinite())
    {
      return false;
    }
    // A parallelepiped (every cell of a grid at rest) has an affine map:
    // the first step is exact, and a second would only confirm it.
    if (length <= 1e-13 || map.isAffine())
    {
      break;
    }
  }
  if (!((map.relativePoint(l) - target).norm() <= 1e-9 * scale))
  {
    return false;
  }
  local = l;
  return true;
}

double distanceToHexahedron(const HexahedronCorners& corners,
  const Vector3& point,
  double insideTolerance)
{
  Vector3 local;
  if (invertTrilinearMap(corners, point, local) && isInsideUnitCube(local, insideTolerance))
  {
    return 0.0;
  }
  Vector3 closest;
  return boundaryDistance(corners, point, closest);
}

// --- HexahedronLocator --------------------------------------------------------

HexahedronLocator::HexahedronLocator(const HexahedralMesh& mesh)
{
  this->build(mesh);
}

void HexahedronLocator::build(const HexahedralMesh& mesh, const std::vector<int>& hexahedra)
{
  Hexahedra.clear();
  if (hexahedra.empty())
  {
    Hexahedra.resize(mesh.hexahedronCount());
    for (std::size_t h = 0; h < Hexahedra.size(); ++h)
    {
      Hexahedra[h] = static_cast<int>(h);
    }
  }
  else
  {
    Hexahedra = hexahedra;
    std::sort(Hexahedra.begin(), Hexahedra.end());
    Hexahedra.erase(std::unique(Hexahedra.begin(), Hexahedra.end()), Hexahedra.end());
  }
  if (Hexahedra.empty())
  {
    throw InvalidInputError(meshContext(mesh) + ": no hexahedron to embed points in");
  }
  const std::size_t count = Hexahedra.size();
  Corners.resize(count);
  Boxes.resize(count);
  BoundingBox all;
  double meanEdge = 0.0;
  for (std::size_t e = 0; e < count; ++e)
  {
    const int h = Hexahedra[e];
    if (h < 0 || static_cast<std::size_t>(h) >= mesh.hexahedronCount())
    {
      throw InvalidInputError(meshContext(mesh) + ": hexahedron index " + std::to_string(h) +
                              " out of range (" + std::to_string(mesh.hexahedronCount()) +
                              " hexahedra)");
    }
    for (int k = 0; k < 8; ++k)
    {
      const int node = mesh.hexahedra[h][k];
      if (node < 0 || static_cast<std::size_t>(node) >= mesh.nodeCount())
      {
        throw InvalidInputError(meshContext(mesh) + ": hexahedron " + std::to_string(h) +
                                " has node index " + std::to_string(node) + " out of range");
      }
      Corners[e][k] = mesh.nodes[node];
    }
    BoundingBox box;
    for (const Vector3& corner : Corners[e])
    {
      box.extend(corner);
    }
    if (!box.min().allFinite() || !box.max().allFinite())
    {
      throw InvalidInputError(
        meshContext(mesh) + ": hexahedron " + std::to_string(h) + " has a non-finite corner");
    }
    Boxes[e] = box;
    all.extend(box);
    meanEdge += box.sizes().sum() / 3.0;
  }
  meanEdge /= static_cast<double>(count);

  // Grid cells about the size of a hexahedron, at most ~4 per hexahedron.
  const Vector3 extent = all.sizes();
  double edge = meanEdge > 0.0 ? meanEdge : std::max(extent.maxCoeff(), 1.0);
  const double maximumCells = 4.0 * static_cast<double>(count) + 64.0;
  for (;;)
  {
    double cells = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      GridDimensions[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / edge)));
      cells *= GridDimensions[a];
    }
    if (cells <= maximumCells)
    {
      break;
    }
    edge *= 1.25;
  }
  for (int a = 0; a < 3; ++a)
  {
    GridCellSize[a] = extent[a] > 0.0 ? extent[a] / GridDimensions[a] : 1.0;
  }
  GridOrigin = all.min();

  const auto cellRange = [&](const BoundingBox& box, std::array<int, 3>& lo, std::array<int, 3>& hi)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] =
        std::clamp(static_cast<int>(std::floor((box.min()[a] - GridOrigin[a]) / GridCellSize[a])),
          0,
          GridDimensions[a] - 1);
      hi[a] =
        std::clamp(static_cast<int>(std::floor((box.max()[a] - GridOrigin[a]) / GridCellSize[a])),
          0,
          GridDimensions[a] - 1);
    }
  };
  const std::size_t gridCells =
    static_cast<std::size_t>(GridDimensions[0]) * GridDimensions[1] * GridDimensions[2];
  GridCellStart.assign(gridCells + 1, 0);
  for (int pass = 0; pass < 2; ++pass)
  {
    std::vector<int> fill;
    if (pass == 1)
    {
      for (std::size_t g = 0; g < gridCells; ++g)
      {
        GridCellStart[g + 1] += GridCellStart[g];
      }
      GridCellEntries.resize(static_cast<std::size_t>(GridCellStart[gridCells]));
      fill.assign(GridCellStart.begin(), GridCellStart.end() - 1);
    }
    for (std::size_t e = 0; e < count; ++e)
    {
      std::array<int, 3> lo;
      std::array<int, 3> hi;
      cellRange(Boxes[e], lo, hi);
      for (int k = lo[2]; k <= hi[2]; ++k)
      {
        for (int j = lo[1]; j <= hi[1]; ++j)
        {
          for (int i = lo[0]; i <= hi[0]; ++i)
          {
            const std::size_t g =
              (static_cast<std::size_t>(k) * GridDimensions[1] + j) * GridDimensions[0] + i;
            if (pass == 0)
            {
              ++GridCellStart[g + 1];
            }
            else
            {
              GridCellEntries[fill[g]++] = static_cast<int>(e);
            }
          }
        }
      }
    }
  }
}

bool HexahedronLocator::findContaining(const Vector3& p,
  double tolerance,
  HexahedronLocation& location) const
{
  std::array<int, 3> cell;
  for (int a = 0; a < 3; ++a)
  {
    const double t = (p[a] - GridOrigin[a]) / GridCellSize[a];
    const double slack = 1e-9 + tolerance;
    if (!(t >= -slack && t <= GridDimensions[a] + slack))
    {
      return false;
    }
    cell[a] = std::clamp(static_cast<int>(std::floor(t)), 0, GridDimensions[a] - 1);
  }
  const std::size_t g =
    (static_cast<std::size_t>(cell[2]) * GridDimensions[1] + cell[1]) * GridDimensions[0] + cell[0];
  for (int i = GridCellStart[g]; i < GridCellStart[g + 1]; ++i)
  {
    const int e = GridCellEntries[i];
    const BoundingBox& box = Boxes[e];
    const double pad = tolerance * box.diagonal().norm() + 1e-300;
    if ((p.array() < box.min().array() - pad).any() || (p.array() > box.max().array() + pad).any())
    {
      continue;
    }
    Vector3 local;
    if (invertTrilinearMap(Corners[e], p, local) && isInsideUnitCube(local, tolerance))
    {
      location.hexahedron = Hexahedra[e];
      location.localCoordinates = local;
      location.distance = 0.0;
      location.inside = true;
      location.clamped = false;
      return true;
    }
  }
  return false;
}

int HexahedronLocator::findNearest(const Vector3& p, double& distance) const
{
  std::array<int, 3> centre;
  for (int a = 0; a < 3; ++a)
  {
    const double t = std::floor((p[a] - GridOrigin[a]) / GridCellSize[a]);
    centre[a] = static_cast<int>(std::clamp(t, 0.0, static_cast<double>(GridDimensions[a] - 1)));
  }
  // Rings grow only along axes with more than one cell.
  double minimumCellSize = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    if (GridDimensions[a] > 1)
    {
      minimumCellSize = std::min(minimumCellSize, GridCellSize[a]);
    }
  }
  double best = std::numeric_limits<double>::infinity();
  int bestEntry = -1;

  const auto visitCell = [&](int i, int j, int k)
  {
    BoundingBox cellBox;
    cellBox.min() = GridOrigin + Vector3(i, j, k).cwiseProduct(GridCellSize);
    cellBox.max() = cellBox.min() + GridCellSize;
    if (squaredDistanceToBox(cellBox, p) > best * best)
    {
      return;
    }
    const std::size_t g =
      (static_cast<std::size_t>(k) * GridDimensions[1] + j) * GridDimensions[0] + i;
    for (int n = GridCellStart[g]; n < GridCellStart[g + 1]; ++n)
    {
      const int e = GridCellEntries[n];
      if (e == bestEntry || squaredDistanceToBox(Boxes[e], p) > best * best)
      {
        continue;
      }
      Vector3 closest;
      const double d = boundaryDistance(Corners[e], p, closest, best);
      if (d < best || (d == best && Hexahedra[e] < Hexahedra[bestEntry]))
      {
        best = d;
        bestEntry = e;
      }
    }
  };

  for (int ring = 0;; ++ring)
  {
    bool covered = true;
    std::array<int, 3> lo;
    std::array<int, 3> hi;
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::max(0, centre[a] - ring);
      hi[a] = std::min(GridDimensions[a] - 1, centre[a] + ring);
      covered = covered && centre[a] - ring <= 0 && centre[a] + ring >= GridDimensions[a] - 1;
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
    {
      const bool kOnRing = std::abs(k - centre[2]) == ring;
      for (int j = lo[1]; j <= hi[1]; ++j)
      {
        const bool jOnRing = kOnRing || std::abs(j - centre[1]) == ring;
        if (jOnRing)
        {
          for (int i = lo[0]; i <= hi[0]; ++i)
          {
            visitCell(i, j, k);
          }
        }
        else
        {
          if (centre[0] - ring >= 0)
          {
            visitCell(centre[0] - ring, j, k);
          }
          if (ring > 0 && centre[0] + ring < GridDimensions[0])
          {
            visitCell(centre[0] + ring, j, k);
          }
        }
      }
    }
    // Every cell of ring r + 1 is at least r cell sizes away from p.
    if (covered || (bestEntry >= 0 && ring * minimumCellSize >= best))
    {
      break;
    }
  }
  distance = best;
  return bestEntry;
}

HexahedronLocation HexahedronLocator::locate(const Vector3& point,
  const HexahedralEmbeddingSettings& settings) const
{
  HexahedronLocation location;
  if (Hexahedra.empty())
  {
    throw InvalidInputError("hexahedron locator: nothing indexed (call build first)");
  }
  if (this->findContaining(point, settings.insideTolerance, location))
  {
    return location;
  }
  const int entry = this->findNearest(point, location.distance);
  const HexahedronCorners& corners = Corners[entry];
  location.hexahedron = Hexahedra[entry];
  location.inside = false;
  location.clamped = false;
  const double m = std::max(0.0, settings.maximumExtrapolation);
  Vector3 local;
  if (invertTrilinearMap(corners, point, local) && (local.array() >= -m).all() &&
      (local.array() <= 1.0 + m).all())
  {
    location.localCoordinates = local;
    return location;
  }
  // Too far out (or no convergence): the closest point on the hexahedron,
  // refined from the closest point on its triangulated boundary.
  Vector3 closest;
  boundaryDistance(corners, point, closest);
  if (!invertTrilinearMap(corners, closest, local))
  {
    local = Vector3::Constant(0.5);
  }
  location.localCoordinates =
    closestLocalCoordinates(TrilinearMap(corners), point - corners[0], local);
  location.clamped = true;
  return location;
}

// --- HexahedralEmbedding ------------------------------------------------------

HexahedralEmbedding::HexahedralEmbedding(const HexahedralMesh& mesh,
  const std::vector<Vector3>& points,
  const HexahedralEmbeddingSettings& settings)
{
  this->embed(mesh, points, settings);
}

void HexahedralEmbedding::embed(const HexahedralMesh& mesh,
  const std::vector<Vector3>& points,
  const HexahedralEmbeddingSettings& settings)
{
  mesh.checkConsistency();
  if (mesh.hexahedra.empty())
  {
    throw InvalidInputError(meshContext(mesh) + ": no hexahedron to embed points in");
  }
  HexahedronTable = mesh.hexahedra;
  NodeCount = mesh.nodeCount();
  HexahedronOfPoint.assign(points.size(), -1);
  LocalCoordinates.assign(points.size(), Vector3::Zero());
  this->locatePoints(points, {}, mesh, {}, settings);
}

void HexahedralEmbedding::locatePoints(const std::vector<Vector3>& points,
  const std::vector<int>& targets,
  const HexahedralMesh& mesh,
  const std::vector<int>& candidateHexahedra,
  const HexahedralEmbeddingSettings& settings,
  const std::vector<int>& firstTry)
{
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (!points[i].allFinite())
    {
      throw InvalidInputError("embedding in " + meshContext(mesh) + ": point " + std::to_string(i) +
                              " has a non-finite coordinate");
    }
  }
  if (!(settings.insideTolerance >= 0.0) || !(settings.maximumExtrapolation >= 0.0))
  {
    throw InvalidInputError("embedding in " + meshContext(mesh) +
                            ": tolerance and maximum extrapolation must be non-negative");
  }
  auto targetOf = [&](std::size_t i)
  { return targets.empty() ? i : static_cast<std::size_t>(targets[i]); };
  // Points inside their first try are placed at once; the rest searched.
  std::vector<std::size_t> searched;
  searched.reserve(firstTry.empty() ? points.size() : 0);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    Vector3 local;
    const int first = firstTry.empty() ? -1 : firstTry[i];
    if (first >= 0 && invertTrilinearMap(hexahedronCorners(mesh, first), points[i], local) &&
        isInsideUnitCube(local, settings.insideTolerance))
    {
      HexahedronOfPoint[targetOf(i)] = first;
      LocalCoordinates[targetOf(i)] = local;
    }
    else
      searched.push_back(i);
  }
  OutsidePoints = 0;
  ClampedPoints = 0;
  if (searched.empty())
  {
    return;
  }
  HexahedronLocator index;
  index.build(mesh, candidateHexahedra);
  std::atomic<std::size_t> outside{ 0 };
  std::atomic<std::size_t> clamped{ 0 };
  forRange(searched.size(),
    1024,
    256,
    [&](std::size_t begin, std::size_t end)
    {
      std::size_t localOutside = 0;
      std::size_t localClamped = 0;
      for (std::size_t k = begin; k < end; ++k)
      {
        const std::size_t i = searched[k];
        const HexahedronLocation location = index.locate(points[i], settings);
        HexahedronOfPoint[targetOf(i)] = location.hexahedron;
        LocalCoordinates[targetOf(i)] = location.localCoordinates;
        localOutside += location.inside ? 0 : 1;
        localClamped += location.clamped ? 1 : 0;
      }
      outside += localOutside;
      clamped += localClamped;
    });
  OutsidePoints = outside;
  ClampedPoints = clamped;
}

void HexahedralEmbedding::assign(const HexahedralMesh& mesh,
  std::vector<int> hexahedronOfPoint,
  std::vector<Vector3> localCoordinates)
{
  const std::string context = "embedding in " + meshContext(mesh);
  if (hexahedronOfPoint.size() != localCoordinates.size())
  {
    throw InvalidInputError(context + ": " + std::to_string(hexahedronOfPoint.size()) +
                            " hexahedron indices for " + std::to_string(localCoordinates.size()) +
                            " local coordinates");
  }
  mesh.checkConsistency();
  for (std::size_t i = 0; i < hexahedronOfPoint.size(); ++i)
  {
    const int h = hexahedronOfPoint[i];
    if (h < 0 || static_cast<std::size_t>(h) >= mesh.hexahedronCount())
    {
      throw InvalidInputError(context + ": point " + std::to_string(i) + " has hexahedron " +
                              std::to_string(h) + " out of range (" +
                              std::to_string(mesh.hexahedronCount()) + " hexahedra)");
    }
    if (!localCoordinates[i].allFinite())
    {
      throw InvalidInputError(
        context + ": point " + std::to_string(i) + " has non-finite local coordinates");
    }
  }
  HexahedronTable = mesh.hexahedra;
  NodeCount = mesh.nodeCount();
  HexahedronOfPoint = std::move(hexahedronOfPoint);
  LocalCoordinates = std::move(localCoordinates);
  OutsidePoints = 0;
  ClampedPoints = 0;
}

std::array<double, 8> HexahedralEmbedding::weights(std::size_t point) const
{
  std::array<double, 8> w;
  weightsOf(LocalCoordinates[point], w.data());
  return w;
}

Vector3 HexahedralEmbedding::mapPosition(std::size_t point,
  const std::vector<Vector3>& nodePositions) const
{
  return interpolate(
    HexahedronTable[HexahedronOfPoint[point]], LocalCoordinates[point], nodePositions.data());
}

void HexahedralEmbedding::mapPositions(const std::vector<Vector3>& nodePositions,
  std::vector<Vector3>& out) const
{
  if (nodePositions.size() != NodeCount)
  {
    throw InvalidInputError("embedding: " + std::to_string(nodePositions.size()) +
                            " node positions for a mesh of " + std::to_string(NodeCount) +
                            " nodes");
  }
  if (out.size() != this->pointCount())
  {
    out.resize(this->pointCount());
  }
  this->mapPositions(nodePositions.data(), out.data());
}

void HexahedralEmbedding::mapPositions(const Vector3* nodePositions, Vector3* out) const
{
  const int* cells = HexahedronOfPoint.data();
  const Vector3* locals = LocalCoordinates.data();
  const Hexahedron* table = HexahedronTable.data();
  forRange(this->pointCount(),
    ParallelThreshold,
    MappingGrain,
    [=](std::size_t begin, std::size_t end)
    {
      for (std::size_t i = begin; i < end; ++i)
      {
        out[i] = interpolate(table[cells[i]], locals[i], nodePositions);
      }
    });
}

void HexahedralEmbedding::accumulateForce(std::size_t point,
  const Vector3& force,
  std::vector<Vector3>& nodeForces) const
{
  double w[8];
  weightsOf(LocalCoordinates[point], w);
  const Hexahedron& hex = HexahedronTable[HexahedronOfPoint[point]];
  for (int k = 0; k < 8; ++k)
  {
    nodeForces[hex[k]] += w[k] * force;
  }
}

void HexahedralEmbedding::accumulateForces(const std::vector<Vector3>& pointForces,
  std::vector<Vector3>& nodeForces) const
{
  if (pointForces.size() != this->pointCount() || nodeForces.size() != NodeCount)
  {
    throw InvalidInputError("embedding: forces on " + std::to_string(pointForces.size()) +
                            " points to " + std::to_string(nodeForces.size()) +
                            " nodes, expected " + std::to_string(this->pointCount()) +
                            " points and " + std::to_string(NodeCount) + " nodes");
  }
  const std::size_t count = this->pointCount();
  if (count < ParallelThreshold || count <= MappingGrain)
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      this->accumulateForce(i, pointForces[i], nodeForces);
    }
    return;
  }
  // A fixed number of chunks (not of threads): the sum order, hence the
  // result, is the same on every machine.
  constexpr std::size_t chunks = 16;
  std::vector<Vector3> partial(chunks * NodeCount, Vector3::Zero());
  tbb::parallel_for(std::size_t(0),
    chunks,
    [&](std::size_t c)
    {
      const std::size_t begin = count * c / chunks;
      const std::size_t end = count * (c + 1) / chunks;
      Vector3* sums = partial.data() + c * NodeCount;
      for (std::size_t i = begin; i < end; ++i)
      {
        double w[8];
        weightsOf(LocalCoordinates[i], w);
        const Hexahedron& hex = HexahedronTable[HexahedronOfPoint[i]];
        for (int k = 0; k < 8; ++k)
        {
          sums[hex[k]] += w[k] * pointForces[i];
        }
      }
    });
  for (std::size_t c = 0; c < chunks; ++c)
  {
    const Vector3* sums = partial.data() + c * NodeCount;
    for (std::size_t v = 0; v < NodeCount; ++v)
    {
      nodeForces[v] += sums[v];
    }
  }
}

void HexahedralEmbedding::accumulateForces(const std::vector<int>& pointIndices,
  const std::vector<Vector3>& forces,
  std::vector<Vector3>& nodeForces) const
{
  if (pointIndices.size() != forces.size() || nodeForces.size() != NodeCount)
  {
    throw InvalidInputError("embedding: " + std::to_string(forces.size()) + " forces for " +
                            std::to_string(pointIndices.size()) + " points, " +
                            std::to_string(nodeForces.size()) + " node forces for " +
                            std::to_string(NodeCount) + " nodes");
  }
  for (std::size_t i = 0; i < pointIndices.size(); ++i)
  {
    this->checkPointIndex(static_cast<std::size_t>(pointIndices[i]), "force on");
    this->accumulateForce(static_cast<std::size_t>(pointIndices[i]), forces[i], nodeForces);
  }
}

void HexahedralEmbedding::checkPointIndex(std::size_t point, const char* operation) const
{
  if (point >= this->pointCount())
  {
    throw InvalidInputError(std::string("embedding: ") + operation + " point " +
                            std::to_string(static_cast<long long>(point)) + " out of range (" +
                            std::to_string(this->pointCount()) + " points)");
  }
}

// --- Local topology changes -------------------------------------------------

void HexahedralEmbedding::updateHexahedra(const HexahedralMesh& mesh,
  const std::vector<int>& changedHexahedra)
{
  const std::size_t oldCount = HexahedronTable.size();
  const std::size_t newCount = mesh.hexahedronCount();
  if (newCount < oldCount)
  {
    for (std::size_t i = 0; i < this->pointCount(); ++i)
    {
      if (static_cast<std::size_t>(HexahedronOfPoint[i]) >= newCount)
      {
        throw InvalidInputError(meshContext(mesh) + ": hexahedron " +
                                std::to_string(HexahedronOfPoint[i]) +
                                " was removed but embeds point " + std::to_string(i));
      }
    }
  }
  const auto copy = [&](std::size_t h)
  {
    for (int node : mesh.hexahedra[h])
    {
      if (node < 0 || static_cast<std::size_t>(node) >= mesh.nodeCount())
      {
        throw InvalidInputError(meshContext(mesh) + ": hexahedron " + std::to_string(h) +
                                " has node index " + std::to_string(node) + " out of range");
      }
    }
    HexahedronTable[h] = mesh.hexahedra[h];
  };
  HexahedronTable.resize(newCount);
  for (std::size_t h = oldCount; h < newCount; ++h)
  {
    copy(h);
  }
  for (int h : changedHexahedra)
  {
    if (h < 0 || static_cast<std::size_t>(h) >= newCount)
    {
      throw InvalidInputError(meshContext(mesh) + ": changed hexahedron " + std::to_string(h) +
                              " out of range (" + std::to_string(newCount) + " hexahedra)");
    }
    copy(static_cast<std::size_t>(h));
  }
  NodeCount = mesh.nodeCount();
}

void HexahedralEmbedding::reembed(const std::vector<int>& pointIndices,
  const HexahedralMesh& mesh,
  const std::vector<int>& candidateHexahedra,
  const HexahedralEmbeddingSettings& settings)
{
  std::vector<Vector3> restPositions(pointIndices.size());
  for (std::size_t i = 0; i < pointIndices.size(); ++i)
  {
    const std::size_t point = static_cast<std::size_t>(pointIndices[i]);
    this->checkPointIndex(point, "re-embedding");
    for (int node : this->nodesOf(point))
    {
      if (static_cast<std::size_t>(node) >= mesh.nodeCount())
      {
        throw InvalidInputError(meshContext(mesh) + ": node " + std::to_string(node) +
                                " of point " + std::to_string(point) + "'s hexahedron is gone");
      }
    }
    restPositions[i] = this->mapPosition(point, mesh.nodes);
  }
  this->reembed(pointIndices, restPositions, mesh, candidateHexahedra, settings);
}

void HexahedralEmbedding::reembed(const std::vector<int>& pointIndices,
  const std::vector<Vector3>& restPositions,
  const HexahedralMesh& mesh,
  const std::vector<int>& candidateHexahedra,
  const HexahedralEmbeddingSettings& settings)
{
  if (pointIndices.size() != restPositions.size())
  {
    throw InvalidInputError("embedding: " + std::to_string(restPositions.size()) +
                            " rest positions for " + std::to_string(pointIndices.size()) +
                            " points to re-embed");
  }
  for (int point : pointIndices)
  {
    this->checkPointIndex(static_cast<std::size_t>(point), "re-embedding");
  }
  if (pointIndices.empty())
  {
    return;
  }
  this->updateHexahedra(mesh, candidateHexahedra);
  this->locatePoints(restPositions, pointIndices, mesh, candidateHexahedra, settings);
}

std::size_t HexahedralEmbedding::appendPoints(const std::vector<Vector3>& restPositions,
  const HexahedralMesh& mesh,
  const std::vector<int>& candidateHexahedra,
  const HexahedralEmbeddingSettings& settings)
{
  return this->appendPoints(restPositions, {}, mesh, candidateHexahedra, settings);
}

std::size_t HexahedralEmbedding::appendPoints(const std::vector<Vector3>& restPositions,
  const std::vector<int>& firstTry,
  const HexahedralMesh& mesh,
  const std::vector<int>& candidateHexahedra,
  const HexahedralEmbeddingSettings& settings)
{
  if (!firstTry.empty() && firstTry.size() != restPositions.size())
  {
    throw InvalidInputError("embedding in " + meshContext(mesh) + ": " +
                            std::to_string(firstTry.size()) + " first tries for " +
                            std::to_string(restPositions.size()) + " points to append");
  }
  for (const int h : firstTry)
  {
    if (h >= static_cast<int>(mesh.hexahedronCount()))
    {
      throw InvalidInputError("embedding in " + meshContext(mesh) + ": first try " +
                              std::to_string(h) + " out of range (" +
                              std::to_string(mesh.hexahedronCount()) + " hexahedra)");
    }
  }
  const std::size_t first = this->pointCount();
  if (restPositions.empty())
  {
    return first;
  }
  this->updateHexahedra(mesh, candidateHexahedra);
  std::vector<int> targets(restPositions.size());
  for (std::size_t i = 0; i < targets.size(); ++i)
  {
    targets[i] = static_cast<int>(first + i);
  }
  HexahedronOfPoint.resize(first + restPositions.size(), -1);
  LocalCoordinates.resize(first + restPositions.size(), Vector3::Zero());
  try
  {
    this->locatePoints(restPositions, targets, mesh, candidateHexahedra, settings, firstTry);
  }
  catch (...)
  {
    HexahedronOfPoint.resize(first);
    LocalCoordinates.resize(first);
    throw;
  }
  return first;
}

void HexahedralEmbedding::setPoint(std::size_t point,
  int hexahedron,
  const Vector3& localCoordinates)
{
  this->checkPointIndex(point, "setting");
  if (hexahedron < 0 || static_cast<std::size_t>(hexahedron) >= HexahedronTable.size())
  {
    throw InvalidInputError("embedding: hexahedron " + std::to_string(hexahedron) +
                            " out of range (" + std::to_string(HexahedronTable.size()) +
                            " hexahedra)");
  }
  if (!localCoordinates.allFinite())
  {
    throw InvalidInputError(
      "embedding: non-finite local coordinates for point " + std::to_string(point));
  }
  HexahedronOfPoint[point] = hexahedron;
  LocalCoordinates[point] = localCoordinates;
}

} // namespace thintissue
