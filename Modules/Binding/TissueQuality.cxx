#include "TissueQuality.h"

#include "MeshQueries.h"
#include "ProximityQueries.h"
#include "ThinTissueError.h"
#include "TriangleBvh.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace thintissue
{

namespace
{

constexpr double Infinity = std::numeric_limits<double>::infinity();

/// Nearest point of the thick collision surface: signed distance (negative
/// inside), the radius at the nearest mid-surface point, which triangle.
struct ThickPoint
{
  double distance = Infinity;
  double radius = 0.0;
  int triangle = -1;
};

/// The collision mesh with radii, queried through a BVH of its triangles
/// inflated by their radii: a triangle can be nearer than a distance d only
/// if its inflated box comes within d.
class ThickSurface
{
public:
  explicit ThickSurface(const VisualCollisionBinding& binding)
    : Positions(binding.collisionPositions)
    , Triangles(binding.collisionTriangles)
    , Radii(binding.collisionRadii)
  {
    Bvh.build(Positions, Triangles, Radii, 0.0);
  }

  /// `hint`: a triangle likely near `x`, to start the search small.
  ThickPoint nearest(const Vector3& x, int hint) const
  {
    ThickPoint best;
    consider(x, hint, best);
    const double reach = std::max(best.distance, 0.0);
    Bvh.forEachOverlap(BoundingBox(x - Vector3::Constant(reach), x + Vector3::Constant(reach)),
      [&](int t) { consider(x, t, best); });
    return best;
  }

  const std::vector<Vector3>& positions() const { return Positions; }
  const std::vector<Triangle>& triangles() const { return Triangles; }
  const std::vector<double>& radii() const { return Radii; }

private:
  void consider(const Vector3& x, int t, ThickPoint& best) const
  {
    const Triangle& tri = Triangles[t];
    const TriangleClosestPoint closest = closestPointOnTriangleWithBarycentric(
      x, Positions[tri[0]], Positions[tri[1]], Positions[tri[2]]);
    const Vector3& b = closest.barycentric;
    const double r = b[0] * Radii[tri[0]] + b[1] * Radii[tri[1]] + b[2] * Radii[tri[2]];
    const double d = (x - closest.point).norm() - r;
    if (d < best.distance)
    {
      best = { d, r, t };
    }
  }

  const std::vector<Vector3>& Positions;
  const std::vector<Triangle>& Triangles;
  const std::vector<double>& Radii;
  TriangleBvh Bvh;
};

/// The visual surface, for distances from points of the thick surface.
class VisualSurface
{
public:
  explicit VisualSurface(const TriangleMesh& mesh)
    : Mesh(mesh)
  {
    Bvh.build(mesh.positions, mesh.triangles, {}, 0.0);
  }

  /// `bound`: an upper bound of the distance (e.g. to a visual vertex).
  double distance(const Vector3& x, double bound) const
  {
    double best = bound;
    Bvh.forEachOverlap(BoundingBox(x - Vector3::Constant(bound), x + Vector3::Constant(bound)),
      [&](int t)
      {
        const Triangle& tri = Mesh.triangles[t];
        best = std::min(best,
          (closestPointOnTriangle(
             x, Mesh.positions[tri[0]], Mesh.positions[tri[1]], Mesh.positions[tri[2]]) -
            x)
            .norm());
      });
    return best;
  }

private:
  const TriangleMesh& Mesh;
  TriangleBvh Bvh;
};

/// Keeps the largest absolute distance, the largest relative deviation and
/// every relative deviation (for the percentile).
struct DeviationTracker
{
  double floor = 0.0;
  double largest = 0.0;
  SurfaceDeviation worst;
  std::vector<double> relative;

  void add(double distance, double radius, const Vector3& point, int triangle, bool fromVisual)
  {
    distance = std::abs(distance);
    largest = std::max(largest, distance);
    const double thickness = std::max(2.0 * radius, floor);
    relative.push_back(distance / thickness);
    if (distance / thickness > worst.relative)
    {
      worst = { distance, thickness, distance / thickness, point, triangle, fromVisual };
    }
  }

  /// The 95th percentile of the relative deviations.
  double percentile95()
  {
    if (relative.empty())
    {
      return 0.0;
    }
    const auto at = relative.begin() + static_cast<std::ptrdiff_t>(relative.size() * 95 / 100);
    std::nth_element(relative.begin(), at, relative.end());
    return *at;
  }
};

/// Visual vertices to the thick surface.
void measureVisualToThick(const VisualCollisionBinding& binding,
  const ThickSurface& thick,
  DeviationTracker& tracker)
{
  // Start each vertex's search at the collision triangle it is bound to.
  std::vector<int> hint(binding.visual.vertexCount(), 0);
  for (std::size_t t = 0; t < binding.visual.triangleCount(); ++t)
  {
    for (int v : binding.visual.triangles[t])
    {
      hint[v] = std::max(binding.triangleRegion[t], 0);
    }
  }
  for (std::size_t v = 0; v < binding.visual.vertexCount(); ++v)
  {
    const Vector3& x = binding.visual.positions[v];
    const ThickPoint nearest = thick.nearest(x, hint[v]);
    tracker.add(nearest.distance, nearest.radius, x, nearest.triangle, true);
  }
}

/// Area-weighted unit vertex normals of the collision mid-surface.
std::vector<Vector3> collisionVertexNormals(const ThickSurface& thick)
{
  std::vector<Vector3> normals(thick.positions().size(), Vector3::Zero());
  for (const Triangle& t : thick.triangles())
  {
    const Vector3 n = (thick.positions()[t[1]] - thick.positions()[t[0]])
                        .cross(thick.positions()[t[2]] - thick.positions()[t[0]]);
    for (int k : t)
    {
      normals[k] += n;
    }
  }
  for (Vector3& n : normals)
  {
    n.normalize();
  }
  return normals;
}

struct ThickSample
{
  Vector3 point;
  double radius;
  int triangle; ///< a collision triangle at the sample
};

/// The generator's samples of the thick surface: each collision vertex and
/// triangle centre one radius along the normal, on both sides.
std::vector<ThickSample> thickSamples(const ThickSurface& thick)
{
  const std::vector<Vector3> normals = collisionVertexNormals(thick);
  const auto& P = thick.positions();
  const auto& R = thick.radii();
  std::vector<ThickSample> samples;
  std::vector<int> vertexTriangle(P.size(), -1);
  for (int t = 0; t < static_cast<int>(thick.triangles().size()); ++t)
  {
    const Triangle& tri = thick.triangles()[t];
    const Vector3 centre = (P[tri[0]] + P[tri[1]] + P[tri[2]]) / 3.0;
    const double radius = (R[tri[0]] + R[tri[1]] + R[tri[2]]) / 3.0;
    const Vector3 normal = (P[tri[1]] - P[tri[0]]).cross(P[tri[2]] - P[tri[0]]).normalized();
    samples.push_back({ centre + radius * normal, radius, t });
    samples.push_back({ centre - radius * normal, radius, t });
    for (int k : tri)
    {
      vertexTriangle[k] = t;
    }
  }
  for (std::size_t k = 0; k < P.size(); ++k)
  {
    if (vertexTriangle[k] >= 0)
    {
      samples.push_back({ P[k] + R[k] * normals[k], R[k], vertexTriangle[k] });
      samples.push_back({ P[k] - R[k] * normals[k], R[k], vertexTriangle[k] });
    }
  }
  return samples;
}

/// Points of the thick surface to the visual surface; samples inside
/// another part of the thick surface are not on its boundary: skipped.
void measureThickToVisual(const VisualCollisionBinding& binding,
  const ThickSurface& thick,
  DeviationTracker& tracker)
{
  const VisualSurface visual(binding.visual);
  const double inside = -1e-9 * binding.visual.boundingBox().diagonal().norm();
  for (const ThickSample& sample : thickSamples(thick))
  {
    if (thick.nearest(sample.point, sample.triangle).distance < inside)
    {
      continue;
    }
    // Upper bound of the distance: the nearest paired visual vertex of the
    // triangle's corners (the search then looks no further).
    double bound = Infinity;
    for (int k : thick.triangles()[sample.triangle])
    {
      for (int v : binding.pairedVisualVertices[k])
      {
        bound = std::min(bound, (binding.visual.positions[v] - sample.point).norm());
      }
    }
    tracker.add(
      visual.distance(sample.point, bound), sample.radius, sample.point, sample.triangle, false);
  }
}

/// Visual vertices per collision triangle (both sides).
void countVerticesPerTriangle(const VisualCollisionBinding& binding, TissueQuality& quality)
{
  std::vector<std::pair<int, int>> triangleVertex;
  for (std::size_t t = 0; t < binding.visual.triangleCount(); ++t)
  {
    for (int v : binding.visual.triangles[t])
    {
      triangleVertex.emplace_back(binding.triangleRegion[t], v);
    }
  }
  std::sort(triangleVertex.begin(), triangleVertex.end());
  triangleVertex.erase(
    std::unique(triangleVertex.begin(), triangleVertex.end()), triangleVertex.end());
  std::vector<int> counts(binding.collisionTriangles.size(), 0);
  for (const auto& [t, v] : triangleVertex)
  {
    if (t >= 0 && t < static_cast<int>(counts.size()))
    {
      ++counts[t];
    }
  }
  const auto fewest = std::min_element(counts.begin(), counts.end());
  quality.sparsestCollisionTriangle = static_cast<int>(fewest - counts.begin());
  quality.fewestVisualVerticesPerTriangle = *fewest;
  quality.mostVisualVerticesPerTriangle = *std::max_element(counts.begin(), counts.end());
  double total = 0.0;
  for (int c : counts)
  {
    total += c;
  }
  quality.meanVisualVerticesPerTriangle = total / static_cast<double>(counts.size());
}

/// One visual triangle mapped into its collision triangle.
struct MappedTriangle
{
  double area = 0.0;   ///< visual
  double mapped = 0.0; ///< signed, along the collision triangle's normal
};

MappedTriangle mapTriangle(const VisualCollisionBinding& binding, std::size_t t, int region)
{
  const Triangle& tri = binding.visual.triangles[t];
  const Triangle& collision = binding.collisionTriangles[region];
  const auto& P = binding.collisionPositions;
  Vector3 image[3];
  for (int k = 0; k < 3; ++k)
  {
    const Vector3 abc = binding.parametersInTriangle(tri[k], region);
    image[k] = abc[0] * P[collision[0]] + abc[1] * P[collision[1]] + abc[2] * P[collision[2]];
  }
  const Vector3 normal =
    (P[collision[1]] - P[collision[0]]).cross(P[collision[2]] - P[collision[0]]).normalized();
  return { binding.visual.triangleArea(t),
    0.5 * (image[1] - image[0]).cross(image[2] - image[0]).dot(normal) };
}

/// Distortion and folds of one region from its mapped triangles.
void assessRegion(const std::vector<MappedTriangle>& mapped, BindingRegionQuality& region)
{
  double area = 0.0;
  double signedMapped = 0.0;
  double absoluteMapped = 0.0;
  for (const MappedTriangle& m : mapped)
  {
    area += m.area;
    signedMapped += m.mapped;
    absoluteMapped += std::abs(m.mapped);
  }
  if (!(area > 0.0) || !(absoluteMapped > 0.0))
  {
    return;
  }
  const double orientation = signedMapped >= 0.0 ? 1.0 : -1.0;
  const double meanStretch = absoluteMapped / area;
  double weighted = 0.0;
  double weight = 0.0;
  for (const MappedTriangle& m : mapped)
  {
    const double stretch = orientation * m.mapped / m.area;
    // A triangle whose corners all lie on one path maps onto a segment
    // (stretch 0): a degenerate image, not a fold; it is left out.
    if (std::abs(stretch) <= 1e-9 * meanStretch || !(m.area > 0.0))
    {
      continue;
    }
    if (stretch < 0.0)
    {
      ++region.foldedTriangles;
      continue;
    }
    const double logarithm = std::log(stretch / meanStretch);
    weighted += m.area * logarithm * logarithm;
    weight += m.area;
  }
  region.areaDistortion = weight > 0.0 ? std::exp(std::sqrt(weighted / weight)) : 1.0;
}

/// The region with the most folded triangles, then the largest distortion.
BindingRegionQuality worstBindingRegion(const VisualCollisionBinding& binding)
{
  std::map<std::pair<int, int>, std::vector<std::size_t>> regions;
  for (std::size_t t = 0; t < binding.visual.triangleCount(); ++t)
  {
    regions[{ binding.triangleRegion[t], binding.triangleSide[t] }].push_back(t);
  }
  BindingRegionQuality worst;
  for (const auto& [key, triangles] : regions)
  {
    BindingRegionQuality region;
    region.collisionTriangle = key.first;
    region.side = key.second;
    region.visualTriangles = static_cast<int>(triangles.size());
    std::vector<MappedTriangle> mapped;
    std::vector<int> vertices;
    Vector3 weighted = Vector3::Zero();
    for (std::size_t t : triangles)
    {
      mapped.push_back(mapTriangle(binding, t, key.first));
      const Triangle& tri = binding.visual.triangles[t];
      vertices.insert(vertices.end(), tri.begin(), tri.end());
      const auto& X = binding.visual.positions;
      weighted += mapped.back().area * (X[tri[0]] + X[tri[1]] + X[tri[2]]) / 3.0;
    }
    std::sort(vertices.begin(), vertices.end());
    region.visualVertices =
      static_cast<int>(std::unique(vertices.begin(), vertices.end()) - vertices.begin());
    assessRegion(mapped, region);
    double area = 0.0;
    for (const MappedTriangle& m : mapped)
    {
      area += m.area;
    }
    region.centre = area > 0.0 ? Vector3(weighted / area) : binding.visual.positions[vertices[0]];
    if (worst.collisionTriangle < 0 || region.foldedTriangles > worst.foldedTriangles ||
        (region.foldedTriangles == worst.foldedTriangles &&
          region.areaDistortion > worst.areaDistortion))
    {
      worst = region;
    }
  }
  return worst;
}

std::string number(double value)
{
  std::ostringstream out;
  out.precision(3);
  out << value;
  return out.str();
}

std::string pointText(const Vector3& x)
{
  return "(" + number(x.x()) + ", " + number(x.y()) + ", " + number(x.z()) + ")";
}

std::string sideText(int side)
{
  return side > 0 ? "+" : side < 0 ? "-" : "rim";
}

void addWarnings(const TissueQualitySettings& settings, TissueQuality& quality)
{
  const SurfaceDeviation& d = quality.worstDeviation;
  if (quality.relativeDeviation95 > settings.maximumRelativeDeviation95 ||
      d.relative > settings.maximumRelativeDeviation)
  {
    quality.warnings.push_back(
      "the collision mesh represents the tissue poorly: the visual and the thick collision "
      "surface are more than " +
      number(quality.relativeDeviation95) +
      " local thicknesses apart over 5% of their samples (at most " +
      number(settings.maximumRelativeDeviation95) + "), " + number(d.relative) + " at worst (" +
      number(d.distance) + " where the tissue is " + number(d.localThickness) + " thick; at most " +
      number(settings.maximumRelativeDeviation) + ") near " + pointText(d.point) +
      "; more collision vertices follow the shape closer");
  }
  const BindingRegionQuality& r = quality.worstRegion;
  const std::string region = "the binding region of collision triangle " +
                             std::to_string(r.collisionTriangle) + " (side " + sideText(r.side) +
                             ", near " + pointText(r.centre) + ")";
  if (r.foldedTriangles > 0)
  {
    quality.warnings.push_back(region + " folds " + std::to_string(r.foldedTriangles) +
                               " visual triangles over: cuts there misplace the visual surface");
  }
  else if (r.areaDistortion > settings.maximumAreaDistortion)
  {
    quality.warnings.push_back(region + " is distorted: area distortion " +
                               number(r.areaDistortion) + " (at most " +
                               number(settings.maximumAreaDistortion) + ")");
  }
  if (quality.fewestVisualVerticesPerTriangle < settings.minimumVisualVerticesPerTriangle)
  {
    quality.warnings.push_back(
      "collision triangle " + std::to_string(quality.sparsestCollisionTriangle) + " binds only " +
      std::to_string(quality.fewestVisualVerticesPerTriangle) + " visual vertices (at least " +
      std::to_string(settings.minimumVisualVerticesPerTriangle) +
      "): the collision mesh is nearly as fine as the visual mesh; fewer collision vertices "
      "or a finer visual mesh");
  }
}

} // namespace

TissueQuality measureTissueQuality(const VisualCollisionBinding& binding,
  const TissueQualitySettings& settings)
{
  if (binding.collisionTriangles.empty() ||
      binding.collisionRadii.size() != binding.collisionPositions.size())
  {
    throw InvalidInputError(
      "tissue quality: the binding has no collision triangles or no radius per collision vertex");
  }
  TissueQuality quality;
  quality.largestThickness =
    2.0 * *std::max_element(binding.collisionRadii.begin(), binding.collisionRadii.end());
  const ThickSurface thick(binding);
  DeviationTracker tracker;
  tracker.floor = settings.minimumThicknessFraction * quality.largestThickness;
  measureVisualToThick(binding, thick, tracker);
  measureThickToVisual(binding, thick, tracker);
  quality.hausdorffDistance = tracker.largest;
  quality.relativeDeviation95 = tracker.percentile95();
  quality.worstDeviation = tracker.worst;
  countVerticesPerTriangle(binding, quality);
  quality.worstRegion = worstBindingRegion(binding);
  addWarnings(settings, quality);
  return quality;
}

std::string TissueQuality::toJson() const
{
  auto point = [](const Vector3& x) { return nlohmann::json::array({ x.x(), x.y(), x.z() }); };
  nlohmann::json json;
  json["hausdorffDistance"] = hausdorffDistance;
  json["largestThickness"] = largestThickness;
  json["relativeDeviation95"] = relativeDeviation95;
  json["worstDeviation"] = { { "relativeToLocalThickness", worstDeviation.relative },
    { "distance", worstDeviation.distance },
    { "localThickness", worstDeviation.localThickness },
    { "point", point(worstDeviation.point) },
    { "collisionTriangle", worstDeviation.collisionTriangle },
    { "direction", worstDeviation.fromVisual ? "visual to thick" : "thick to visual" } };
  json["visualVerticesPerCollisionTriangle"] = { { "fewest", fewestVisualVerticesPerTriangle },
    { "mean", meanVisualVerticesPerTriangle },
    { "most", mostVisualVerticesPerTriangle },
    { "sparsestCollisionTriangle", sparsestCollisionTriangle } };
  json["worstBindingRegion"] = { { "collisionTriangle", worstRegion.collisionTriangle },
    { "side", worstRegion.side },
    { "visualVertices", worstRegion.visualVertices },
    { "visualTriangles", worstRegion.visualTriangles },
    { "foldedTriangles", worstRegion.foldedTriangles },
    { "areaDistortion", worstRegion.areaDistortion },
    { "centre", point(worstRegion.centre) } };
  json["warnings"] = warnings;
  return json.dump();
}

bool TissueQuality::fromJson(const std::string& text)
{
  auto point = [](const nlohmann::json& x)
  { return Vector3(x.at(0).get<double>(), x.at(1).get<double>(), x.at(2).get<double>()); };
  try
  {
    const nlohmann::json json = nlohmann::json::parse(text);
    TissueQuality q;
    q.hausdorffDistance = json.at("hausdorffDistance").get<double>();
    q.largestThickness = json.at("largestThickness").get<double>();
    q.relativeDeviation95 = json.at("relativeDeviation95").get<double>();
    const nlohmann::json& d = json.at("worstDeviation");
    q.worstDeviation.relative = d.at("relativeToLocalThickness").get<double>();
    q.worstDeviation.distance = d.at("distance").get<double>();
    q.worstDeviation.localThickness = d.at("localThickness").get<double>();
    q.worstDeviation.point = point(d.at("point"));
    q.worstDeviation.collisionTriangle = d.at("collisionTriangle").get<int>();
    q.worstDeviation.fromVisual = d.at("direction").get<std::string>() == "visual to thick";
    const nlohmann::json& v = json.at("visualVerticesPerCollisionTriangle");
    q.fewestVisualVerticesPerTriangle = v.at("fewest").get<int>();
    q.meanVisualVerticesPerTriangle = v.at("mean").get<double>();
    q.mostVisualVerticesPerTriangle = v.at("most").get<int>();
    q.sparsestCollisionTriangle = v.at("sparsestCollisionTriangle").get<int>();
    const nlohmann::json& r = json.at("worstBindingRegion");
    q.worstRegion.collisionTriangle = r.at("collisionTriangle").get<int>();
    q.worstRegion.side = r.at("side").get<int>();
    q.worstRegion.visualVertices = r.at("visualVertices").get<int>();
    q.worstRegion.visualTriangles = r.at("visualTriangles").get<int>();
    q.worstRegion.foldedTriangles = r.at("foldedTriangles").get<int>();
    q.worstRegion.areaDistortion = r.at("areaDistortion").get<double>();
    q.worstRegion.centre = point(r.at("centre"));
    q.warnings = json.at("warnings").get<std::vector<std::string>>();
    *this = std::move(q);
    return true;
  }
  catch (const nlohmann::json::exception&)
  {
    return false;
  }
}

std::string TissueQuality::summary(const std::string& unit) const
{
  const std::string u = unit.empty() ? std::string() : " " + unit;
  const SurfaceDeviation& d = worstDeviation;
  std::string text =
    "quality: Hausdorff distance " + number(hausdorffDistance) + u + " (largest thickness " +
    number(largestThickness) + u +
    "); relative to the local thickness: 95% of the surface "
    "within " +
    number(relativeDeviation95) + ", worst " + number(d.relative) + " (" + number(d.distance) + u +
    " where the tissue is " + number(d.localThickness) + u + " thick) near " + pointText(d.point) +
    "\n" + "quality: visual vertices per collision triangle: fewest " +
    std::to_string(fewestVisualVerticesPerTriangle) + ", mean " +
    number(meanVisualVerticesPerTriangle) + ", most " +
    std::to_string(mostVisualVerticesPerTriangle) + "\n" +
    "quality: worst binding region: collision triangle " +
    std::to_string(worstRegion.collisionTriangle) + " side " + sideText(worstRegion.side) + ", " +
    std::to_string(worstRegion.visualVertices) + " visual vertices, area distortion " +
    number(worstRegion.areaDistortion) + ", " + std::to_string(worstRegion.foldedTriangles) +
    " folded triangles\n";
  for (const std::string& warning : warnings)
  {
    text += "warning: " + warning + "\n";
  }
  return text;
}

} // namespace thintissue
