// 6.4.4: the jagged cut surface and its contouring. The thesis makes the
// cut surface jagged "by introducing random numbers at the cut surface mesh
// generating section" and contours it by "smoothing the cut surface around
// the intersected parameters" of the collision edges the shaver touches.
//
// Here the random numbers are seeded value noise over the rest positions
// (the same rim for the same seed and cuts, neighbouring vertices moved
// alike below the wavelength), applied across the cut in the plane of its
// collision triangle, so the rim's outline is jagged while the rows stay
// between the tissue's two sides. Smoothing pulls a cut-surface vertex
// toward where the smooth cut puts it (between the rim's + and - paths at
// its edge parameter, CuttableVisualMesh::smoothPlaces), so contouring
// evens the rim out and never takes material away; the roughness is the
// distance from that place.
#include "VisualMeshCut.h"

#include <algorithm>
#include <cmath>

namespace thintissue
{

namespace
{

/// A well-mixed 32-bit hash (an avalanche of xor-shifts and multiplies).
std::uint32_t mixBits(std::uint32_t h)
{
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

/// The noise's value in [-1, 1] at lattice point (i, j, k).
double latticeValue(std::int64_t i, std::int64_t j, std::int64_t k, std::uint32_t seed)
{
  std::uint32_t h = mixBits(seed ^ 0x9e3779b9u);
  for (const std::int64_t c : { i, j, k })
    h = mixBits(h ^ static_cast<std::uint32_t>(c));
  return h * (2.0 / 4294967295.0) - 1.0;
}

/// Value noise: the lattice values interpolated trilinearly with smoothed
/// weights (continuous, within [-1, 1]).
double valueNoise(const Vector3& p, std::uint32_t seed)
{
  const Vector3 floor(std::floor(p.x()), std::floor(p.y()), std::floor(p.z()));
  Vector3 f = p - floor;
  f = f.cwiseProduct(f).cwiseProduct(Vector3::Constant(3.0) - 2.0 * f);
  const auto i = static_cast<std::int64_t>(floor.x()), j = static_cast<std::int64_t>(floor.y()),
             k = static_cast<std::int64_t>(floor.z());
  double value = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
    const double weight =
      (dx ? f.x() : 1.0 - f.x()) * (dy ? f.y() : 1.0 - f.y()) * (dz ? f.z() : 1.0 - f.z());
    value += weight * latticeValue(i + dx, j + dy, k + dz, seed);
  }
  return value;
}

} // namespace

Vector3 CuttableVisualMesh::jaggedOffset(const Vector3& restPosition, const Vector3& outward) const
{
  if (Settings.jaggedAmplitude <= 0.0)
    return Vector3::Zero();
  const double noise = valueNoise(restPosition / Settings.jaggedWavelength, Settings.jaggedSeed);
  // Both lips of a cut are made at the same places with opposite outward
  // directions: turned one way, they move alike and stay complementary (no
  // material made or lost between a removed piece and the rim it left).
  const Vector3 oneWay(0.8017837, 0.5345225, 0.2672612); // (3, 2, 1), normalised
  return Settings.jaggedAmplitude * noise * (outward.dot(oneWay) < 0.0 ? -outward : outward);
}

void CuttableVisualMesh::smoothCutSurface(const std::function<bool(int, int)>& near,
  const std::function<double(int, int, double)>& pull,
  std::vector<int>& moved)
{
  std::vector<SmoothPlace> places;
  const std::size_t first = moved.size();
  for (const auto& [key, strip] : Strips)
  {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    if (!near(a, b))
      continue;
    places.clear();
    smoothPlaces(key, strip, places);
    for (const SmoothPlace& place : places)
    {
      // A column at a collision vertex is shared by the strips meeting
      // there: it moves once a pass.
      if (place.u == 0.0 || place.u == 1.0)
      {
        if (std::find(moved.begin() + static_cast<std::ptrdiff_t>(first),
              moved.end(),
              place.vertex) != moved.end())
          continue;
      }
      const double weight = std::clamp(pull(a, b, place.u), 0.0, 1.0);
      if (weight <= 0.0)
        continue;
      Vector3& position = Mesh.positions[place.vertex];
      position += weight * (place.smooth - position);
      moved.push_back(place.vertex);
    }
  }
}

CutSurfaceRoughness CuttableVisualMesh::cutSurfaceRoughness(
  const std::function<bool(int, int)>& counts) const
{
  CutSurfaceRoughness roughness;
  std::vector<SmoothPlace> places;
  std::vector<int> columns; // end-column vertices counted (shared by strips)
  double sum = 0.0;
  for (const auto& [key, strip] : Strips)
  {
    if (!counts(static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu)))
      continue;
    places.clear();
    smoothPlaces(key, strip, places);
    for (const SmoothPlace& place : places)
    {
      if (place.u == 0.0 || place.u == 1.0)
      {
        if (std::find(columns.begin(), columns.end(), place.vertex) != columns.end())
          continue;
        columns.push_back(place.vertex);
      }
      const double distance = (Mesh.positions[place.vertex] - place.smooth).norm();
      sum += distance * distance;
      roughness.maximum = std::max(roughness.maximum, distance);
      ++roughness.vertices;
    }
  }
  if (roughness.vertices > 0)
    roughness.rootMeanSquare = std::sqrt(sum / static_cast<double>(roughness.vertices));
  return roughness;
}

} // namespace thintissue
