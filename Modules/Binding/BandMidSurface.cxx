#include "BandMidSurface.h"

#include "MeshQueries.h"
#include "ThinTissueError.h"
#include "TriangleBvh.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace thintissue
{

namespace
{

constexpr double Infinity = std::numeric_limits<double>::infinity();

/// A triangle of the surface as a sample of its area.
struct AreaSample
{
  Vector3 centre;
  Vector3 normal;
  double area = 0.0;
};

std::vector<AreaSample> areaSamples(const TriangleMesh& visual)
{
  std::vector<AreaSample> samples;
  samples.reserve(visual.triangleCount());
  for (const Triangle& t : visual.triangles)
  {
    const Vector3& a = visual.positions[t[0]];
    const Vector3& b = visual.positions[t[1]];
    const Vector3& c = visual.positions[t[2]];
    const Vector3 cross = (b - a).cross(c - a);
    const double twice = cross.norm();
    if (twice > 0.0)
    {
      samples.push_back({ (a + b + c) / 3.0, cross / twice, 0.5 * twice });
    }
  }
  return samples;
}

/// Area centre and principal axes (columns, by increasing spread) and
/// their spreads.
void principalAxes(const std::vector<AreaSample>& samples,
  Vector3& centre,
  Eigen::Matrix3d& axes,
  Vector3& spreads)
{
  double area = 0.0;
  centre = Vector3::Zero();
  for (const AreaSample& s : samples)
  {
    area += s.area;
    centre += s.area * s.centre;
  }
  centre /= area;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const AreaSample& s : samples)
  {
    const Vector3 d = s.centre - centre;
    covariance += s.area * d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance / area);
  axes = solver.eigenvectors();
  spreads = solver.eigenvalues().cwiseMax(0.0);
}

/// A polyline parametrised by arc length, extended along its end segments
/// beyond both ends.
class CentreCurve
{
public:
  explicit CentreCurve(std::vector<Vector3> points)
    : Points(std::move(points))
  {
    Lengths.push_back(0.0);
    for (std::size_t i = 1; i < Points.size(); ++i)
    {
      Lengths.push_back(Lengths.back() + (Points[i] - Points[i - 1]).norm());
    }
  }

  double length() const { return Lengths.back(); }

  /// Arc length of the point of the curve nearest to x (beyond the ends
  /// along the end segments: negative or past the length).
  double parameterOf(const Vector3& x) const
  {
    double best = Infinity;
    double parameter = 0.0;
    const std::size_t last = Points.size() - 2;
    for (std::size_t i = 0; i + 1 < Points.size(); ++i)
    {
      const Vector3 d = Points[i + 1] - Points[i];
      const double l = Lengths[i + 1] - Lengths[i];
      double t = l > 0.0 ? (x - Points[i]).dot(d) / (l * l) : 0.0;
      t = std::clamp(t, i == 0 ? -Infinity : 0.0, i == last ? Infinity : 1.0);
      const double distance = (Points[i] + t * d - x).squaredNorm();
      if (distance < best)
      {
        best = distance;
        parameter = Lengths[i] + t * l;
      }
    }
    return parameter;
  }

  Vector3 pointAt(double s) const
  {
    const std::size_t i = segmentOf(s);
    const double l = Lengths[i + 1] - Lengths[i];
    const double t = l > 0.0 ? (s - Lengths[i]) / l : 0.0;
    return Points[i] + t * (Points[i + 1] - Points[i]);
  }

  /// Direction of the chord over `reach` either side of s.
  Vector3 tangentAt(double s, double reach) const
  {
    const Vector3 d = pointAt(s + reach) - pointAt(s - reach);
    return d.norm() > 0.0 ? Vector3(d.normalized()) : Vector3::UnitX();
  }

private:
  std::size_t segmentOf(double s) const
  {
    const auto it = std::upper_bound(Lengths.begin(), Lengths.end(), s);
    const std::ptrdiff_t i = (it - Lengths.begin()) - 1;
    return static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(i, 0, Lengths.size() - 2));
  }

  std::vector<Vector3> Points;
  std::vector<double> Lengths;
};

/// The band's centre curve: area centroids of slabs along the length, the
/// slabs taken again along the curve a few times (a principal curve).
/// `parameters` gets each sample's arc length on it.
CentreCurve fitCentreCurve(const std::vector<AreaSample>& samples,
  const Vector3& centre,
  const Vector3& longAxis,
  std::vector<double>& parameters,
  const std::string& name)
{
  parameters.resize(samples.size());
  for (std::size_t t = 0; t < samples.size(); ++t)
  {
    parameters[t] = (samples[t].centre - centre).dot(longAxis);
  }
  constexpr int Slabs = 12;
  CentreCurve curve({ centre - longAxis, centre + longAxis });
  for (int iteration = 0; iteration < 5; ++iteration)
  {
    const auto [low, high] = std::minmax_element(parameters.begin(), parameters.end());
    const double start = *low;
    const double width = (*high - *low) / Slabs;
    std::vector<Vector3> sums(Slabs, Vector3::Zero());
    std::vector<double> areas(Slabs, 0.0);
    for (std::size_t t = 0; t < samples.size(); ++t)
    {
      const int k = std::clamp(static_cast<int>((parameters[t] - start) / width), 0, Slabs - 1);
      sums[k] += samples[t].area * samples[t].centre;
      areas[k] += samples[t].area;
    }
    // The end slabs hold the insertions' end faces, which a slab cut
    // askew cuts unevenly: their centroids would turn the curve's ends
    // towards one side. The curve runs through the inner slabs and goes
    // on straight beyond them.
    std::vector<Vector3> points;
    for (int k = 1; k + 1 < Slabs; ++k)
    {
      if (areas[k] > 0.0)
      {
        points.push_back(sums[k] / areas[k]);
      }
    }
    if (points.size() < 3 || !(width > 0.0))
    {
      throw InvalidInputError(name + ": no centre curve along the band");
    }
    std::vector<Vector3> smooth = points;
    for (std::size_t i = 1; i + 1 < points.size(); ++i)
    {
      smooth[i] = 0.25 * points[i - 1] + 0.5 * points[i] + 0.25 * points[i + 1];
    }
    curve = CentreCurve(std::move(smooth));
    for (std::size_t t = 0; t < samples.size(); ++t)
    {
      parameters[t] = curve.parameterOf(samples[t].centre);
    }
  }
  return curve;
}

/// Frames along the curve: at each station its tangent, the local
/// thickness direction (dominant axis of the normal tensor across the
/// tangent, signs made to agree, smoothed) and the width direction.
struct Station
{
  double s = 0.0;
  Vector3 centre;
  Vector3 tangent;
  Vector3 normal;
};

std::vector<Station> stationsAlong(const CentreCurve& curve,
  const std::vector<AreaSample>& samples,
  const std::vector<double>& parameters,
  double start,
  double end)
{
  constexpr int Count = 24;
  const double step = (end - start) / (Count - 1);
  const double window = 1.5 * step;
  std::vector<Station> stations(Count);
  for (int k = 0; k < Count; ++k)
  {
    Station& station = stations[k];
    station.s = start + k * step;
    station.centre = curve.pointAt(station.s);
    station.tangent = curve.tangentAt(station.s, step);
    Eigen::Matrix3d tensor = Eigen::Matrix3d::Zero();
    for (std::size_t t = 0; t < samples.size(); ++t)
    {
      const double weight = 1.0 - std::abs(parameters[t] - station.s) / window;
      if (weight > 0.0)
      {
        const Vector3 n =
          samples[t].normal - samples[t].normal.dot(station.tangent) * station.tangent;
        tensor += weight * samples[t].area * n * n.transpose();
      }
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(tensor);
    station.normal = tensor.trace() > 0.0 ? Vector3(solver.eigenvectors().col(2))
                     : k > 0              ? stations[k - 1].normal
                                          : Vector3(station.tangent.unitOrthogonal());
    if (k > 0 && station.normal.dot(stations[k - 1].normal) < 0.0)
    {
      station.normal = -station.normal;
    }
  }
  std::vector<Station> smoothed = stations;
  for (int k = 0; k < Count; ++k)
  {
    Vector3 n = stations[k].normal;
    n +=
      0.5 * stations[std::max(0, k - 1)].normal + 0.5 * stations[std::min(Count - 1, k + 1)].normal;
    const Vector3& tangent = stations[k].tangent;
    smoothed[k].normal = (n - n.dot(tangent) * tangent).normalized();
  }
  return smoothed;
}

/// The band's local frame at arc length s: centre, tangent (T), thickness
/// direction (N) and width direction W = N x T.
struct Frame
{
  Vector3 centre;
  Vector3 tangent;
  Vector3 normal;
  Vector3 width;
};

Frame frameAt(const CentreCurve& curve, const std::vector<Station>& stations, double s)
{
  const double step = stations[1].s - stations[0].s;
  const double x = std::clamp((s - stations.front().s) / step, 0.0, stations.size() - 1.0);
  const std::size_t k = std::min(static_cast<std::size_t>(x), stations.size() - 2);
  const double f = x - static_cast<double>(k);
  Frame frame;
  frame.centre = curve.pointAt(s);
  frame.tangent = curve.tangentAt(s, step);
  const Vector3 n = (1.0 - f) * stations[k].normal + f * stations[k + 1].normal;
  frame.normal = (n - n.dot(frame.tangent) * frame.tangent).normalized();
  frame.width = frame.normal.cross(frame.tangent).normalized();
  return frame;
}

/// Crossings of the surface by lines: the first and last within `reach`
/// either side of a point, through a tree of the visual triangles.
class LineCrossings
{
public:
  LineCrossings(const TriangleMesh& visual, double reach)
    : Visual(visual)
    , Reach(reach)
  {
    Tree.build(visual.positions, visual.triangles, {}, 0.0);
  }

  /// Half the distance between the first and last crossings of the line
  /// through p along n (unit) within the reach, and their middle (offset
  /// along n from p); -1 when it meets the surface fewer than twice.
  double halfThickness(const Vector3& p, const Vector3& n, double& middle) const
  {
    const Vector3 origin = p - Reach * n;
    BoundingBox box;
    box.extend(origin);
    box.extend(p + Reach * n);
    double bottom = Infinity;
    double top = -Infinity;
    Tree.forEachOverlap(box,
      [&](int t)
      {
        const Triangle& c = Visual.triangles[t];
        const double hit = rayTriangleHit(
          origin, n, Visual.positions[c[0]], Visual.positions[c[1]], Visual.positions[c[2]], 1e-9);
        if (std::isfinite(hit) && hit >= 0.0 && hit <= 2.0 * Reach)
        {
          bottom = std::min(bottom, hit - Reach);
          top = std::max(top, hit - Reach);
        }
      });
    if (!(top > bottom))
    {
      return -1.0;
    }
    middle = 0.5 * (bottom + top);
    return 0.5 * (top - bottom);
  }

private:
  const TriangleMesh& Visual;
  double Reach;
  TriangleBvh Tree;
};

/// Where the tissue ends going from `from` along `direction` (unit), the
/// lines through its points along `normal`: the last point that crosses,
/// to a 2^-12 of `distance`; then moved back in until the local half
/// thickness reaches the rim, and to tissue at least `thinnest` thick.
/// Returns the offset along direction; -1 when `from` sees no tissue.
double rimInset(const LineCrossings& lines,
  const Vector3& from,
  const Vector3& direction,
  const Vector3& normal,
  double distance,
  double thinnest)
{
  double middle = 0.0;
  auto thickness = [&](double w)
  { return lines.halfThickness(from + w * direction, normal, middle); };
  if (thickness(0.0) <= 0.0)
  {
    return -1.0;
  }
  constexpr int Steps = 64;
  double inside = 0.0;
  double outside = distance;
  for (int k = 1; k <= Steps; ++k)
  {
    const double w = distance * k / Steps;
    if (thickness(w) <= 0.0)
    {
      outside = w;
      break;
    }
    inside = w;
  }
  for (int iteration = 0; iteration < 12; ++iteration)
  {
    const double w = 0.5 * (inside + outside);
    (thickness(w) > 0.0 ? inside : outside) = w;
  }
  double depth = 0.0;
  for (int iteration = 0; iteration < 12; ++iteration)
  {
    const double half = thickness(std::max(0.0, inside - depth));
    depth = half > 0.0 ? std::min(half, inside) : std::min(1.5 * depth + 1e-3 * distance, inside);
  }
  double w = std::max(0.0, inside - depth);
  while (w > 0.0 && thickness(w) < thinnest)
  {
    w = std::max(0.0, w - distance / Steps);
  }
  return w;
}

/// Rows and columns of the grid: the count nearest `vertexCount` (or the
/// fewest with at least `triangleCount` triangles) with cells nearest to
/// square for a band of this length and width.
std::pair<int, int> gridSize(int vertexCount, int triangleCount, double length, double width)
{
  std::pair<int, int> best{ 2, 2 };
  double bestScore = Infinity;
  const int most = triangleCount > 0 ? triangleCount + 2 : 2 * vertexCount;
  for (int columns = 2; columns <= most; ++columns)
  {
    for (int rows = 2; rows * columns <= 2 * most; ++rows)
    {
      const int triangles = 2 * (rows - 1) * (columns - 1);
      const double cellAspect = std::abs(std::log((length / (rows - 1)) / (width / (columns - 1))));
      double score = 0.0;
      if (triangleCount > 0)
      {
        if (triangles < triangleCount)
          continue;
        score = (triangles - triangleCount) + 0.01 * cellAspect; // fewest, then squarest
      }
      else
      {
        score = std::abs(rows * columns - vertexCount) / static_cast<double>(vertexCount) +
                0.3 * cellAspect;
      }
      if (score < bestScore)
      {
        bestScore = score;
        best = { rows, columns };
      }
    }
  }
  return best;
}

/// The two rims of the row at arc length s (offsets along the width
/// direction from the centre, negative first), moved in; false when the
/// centre of the row sees no tissue.
bool rowRims(const LineCrossings& lines,
  const Frame& frame,
  double reach,
  double thinnest,
  double& low,
  double& high)
{
  high = rimInset(lines, frame.centre, frame.width, frame.normal, reach, thinnest);
  low = -rimInset(lines, frame.centre, -frame.width, frame.normal, reach, thinnest);
  return high >= 0.0 && low <= 0.0;
}

/// The vertex of the mid-surface at p: the middle of the line's crossings
/// along the frame's thickness direction, or the nearest point around p
/// (rings across the band) where the tissue is at least `thinnest` thick.
bool liftToMiddle(const LineCrossings& lines,
  const Frame& frame,
  Vector3 p,
  double thinnest,
  double reach,
  Vector3& vertex,
  double& radius)
{
  double middle = 0.0;
  for (double ring = 1e-3 * reach; ring < reach; ring *= 1.5)
  {
    const double half = lines.halfThickness(p, frame.normal, middle);
    if (half >= thinnest)
    {
      vertex = p + middle * frame.normal;
      radius = half;
      return true;
    }
    for (int k = 0; k < 16; ++k)
    {
      const double angle = 2.0 * M_PI * k / 16.0;
      const Vector3 q =
        p + ring * (std::cos(angle) * frame.tangent + std::sin(angle) * frame.width);
      const double h = lines.halfThickness(q, frame.normal, middle);
      if (h >= thinnest)
      {
        vertex = q + middle * frame.normal;
        radius = h;
        return true;
      }
    }
  }
  return false;
}

/// Both ends of the band along its curve, moved in by the half thickness
/// at each (the end rows' spheres reach the insertions).
std::pair<double, double> bandEnds(const LineCrossings& lines,
  const CentreCurve& curve,
  const std::vector<Station>& stations,
  double thinnest)
{
  const double middleS = 0.5 * (stations.front().s + stations.back().s);
  const double reach = stations.back().s - stations.front().s;
  auto endFrom = [&](double sign)
  {
    // Walk the curve (straight beyond its ends) from its middle.
    double inside = 0.0;
    double outside = reach;
    constexpr int Steps = 128;
    double middle = 0.0;
    auto crosses = [&](double d)
    {
      const Frame f = frameAt(curve, stations, middleS + sign * d);
      return lines.halfThickness(f.centre, f.normal, middle) > 0.0;
    };
    for (int k = 1; k <= Steps; ++k)
    {
      const double d = reach * k / Steps;
      if (!crosses(d))
      {
        outside = d;
        break;
      }
      inside = d;
    }
    for (int iteration = 0; iteration < 12; ++iteration)
    {
      const double d = 0.5 * (inside + outside);
      (crosses(d) ? inside : outside) = d;
    }
    double depth = 0.0;
    for (int iteration = 0; iteration < 12; ++iteration)
    {
      const Frame f = frameAt(curve, stations, middleS + sign * (inside - depth));
      const double half = lines.halfThickness(f.centre, f.normal, middle);
      depth =
        half > thinnest ? std::min(half, inside) : std::min(1.5 * depth + 1e-3 * reach, inside);
    }
    return middleS + sign * (inside - depth);
  };
  return { endFrom(-1.0), endFrom(1.0) };
}

/// Quads of the grid split along their shorter diagonal, each triangle
/// turning from the length towards the width (normal along N).
std::vector<Triangle> gridTriangles(const std::vector<Vector3>& positions, int rows, int columns)
{
  std::vector<Triangle> triangles;
  auto at = [columns](int i, int j) { return i * columns + j; };
  for (int i = 0; i + 1 < rows; ++i)
  {
    for (int j = 0; j + 1 < columns; ++j)
    {
      const int a = at(i, j);
      const int b = at(i + 1, j);
      const int c = at(i + 1, j + 1);
      const int d = at(i, j + 1);
      if ((positions[a] - positions[c]).squaredNorm() <=
          (positions[b] - positions[d]).squaredNorm())
      {
        triangles.push_back({ a, b, c });
        triangles.push_back({ a, c, d });
      }
      else
      {
        triangles.push_back({ a, b, d });
        triangles.push_back({ b, c, d });
      }
    }
  }
  return triangles;
}

/// Mean thickness direction (signs agreeing along the curve) and the
/// largest angle between two stations' directions.
void thicknessTurn(const std::vector<Station>& stations, BandMidSurface& band)
{
  Vector3 mean = Vector3::Zero();
  for (const Station& a : stations)
  {
    mean += a.normal;
    for (const Station& b : stations)
    {
      band.thicknessTurn =
        std::max(band.thicknessTurn, std::acos(std::clamp(a.normal.dot(b.normal), -1.0, 1.0)));
    }
  }
  band.meanThicknessDirection =
    mean.norm() > 0.0 ? Vector3(mean.normalized()) : stations.front().normal;
}

} // namespace

//------------------------------------------------------------------------------
double elongationOf(const TriangleMesh& visual)
{
  Vector3 centre;
  Eigen::Matrix3d axes;
  Vector3 spreads;
  const std::vector<AreaSample> samples = areaSamples(visual);
  if (samples.empty())
  {
    return 1.0;
  }
  principalAxes(samples, centre, axes, spreads);
  return spreads(1) > 0.0 ? std::sqrt(spreads(2) / spreads(1)) : Infinity;
}

BandMidSurface makeBandMidSurface(const TriangleMesh& visual,
  int vertexCount,
  int triangleCount,
  const std::string& name)
{
  const std::vector<AreaSample> samples = areaSamples(visual);
  if (samples.size() < 4)
  {
    throw InvalidInputError(name + ": too few triangles for a band");
  }
  Vector3 centre;
  Eigen::Matrix3d axes;
  Vector3 spreads;
  principalAxes(samples, centre, axes, spreads);
  std::vector<double> parameters;
  const CentreCurve curve = fitCentreCurve(samples, centre, axes.col(2), parameters, name);
  const auto [first, last] = std::minmax_element(parameters.begin(), parameters.end());
  const std::vector<Station> stations = stationsAlong(curve, samples, parameters, *first, *last);
  const double span = *last - *first;
  const double reach = 0.5 * span; // no band is thicker or wider than half its length
  const LineCrossings lines(visual, reach);

  // The thinnest tissue a vertex may sit on: a twentieth of the thickest.
  double largest = 0.0;
  double middle = 0.0;
  for (const Station& station : stations)
  {
    largest = std::max(largest, 2.0 * lines.halfThickness(station.centre, station.normal, middle));
  }
  const double thinnest = 0.025 * largest;
  const auto [start, end] = bandEnds(lines, curve, stations, thinnest);
  if (!(end > start))
  {
    throw InvalidInputError(name + ": the band has no length between its ends");
  }

  // Width: the rows at a few places along the band.
  double width = 0.0;
  int measured = 0;
  for (int k = 1; k < 8; ++k)
  {
    double low = 0.0;
    double high = 0.0;
    if (rowRims(lines,
          frameAt(curve, stations, start + (end - start) * k / 8.0),
          reach,
          thinnest,
          low,
          high))
    {
      width += high - low;
      ++measured;
    }
  }
  if (measured == 0 || !(width > 0.0))
  {
    throw InvalidInputError(name + ": no width across the band");
  }
  width /= measured;
  const auto [rows, columns] = gridSize(vertexCount, triangleCount, end - start, width);

  BandMidSurface band;
  band.rows = rows;
  band.columns = columns;
  band.length = end - start;
  for (int i = 0; i < rows; ++i)
  {
    const Frame frame = frameAt(curve, stations, start + (end - start) * i / (rows - 1.0));
    double low = 0.0;
    double high = 0.0;
    if (!rowRims(lines, frame, reach, thinnest, low, high))
    {
      throw InvalidInputError(
        name + ": row " + std::to_string(i) + " across the band finds no tissue at its centre");
    }
    for (int j = 0; j < columns; ++j)
    {
      const Vector3 p = frame.centre + (low + (high - low) * j / (columns - 1.0)) * frame.width;
      Vector3 vertex;
      double radius = 0.0;
      if (!liftToMiddle(lines, frame, p, thinnest, reach, vertex, radius))
      {
        throw InvalidInputError(name + ": collision vertex " +
                                std::to_string(band.mesh.vertexCount()) +
                                " finds no surface above and below it across the band");
      }
      band.mesh.positions.push_back(vertex);
      band.radii.push_back(radius);
      band.largestThickness = std::max(band.largestThickness, 2.0 * radius);
    }
  }
  band.mesh.triangles = gridTriangles(band.mesh.positions, rows, columns);
  band.borderVertexCount = 2 * (rows + columns) - 4;
  thicknessTurn(stations, band);
  return band;
}

} // namespace thintissue
