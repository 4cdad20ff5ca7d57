#include "KneeModels.h"

#include "KneeAnatomy.h"
#include "ModelParameterChecks.h"
#include "ThinTissueError.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

namespace thintissue
{

namespace
{

using ImplicitFunction = std::function<double(const Vector3&)>;

double square(double x)
{
  return x * x;
}

/// Hermite step from 0 at e0 to 1 at e1 (e0 > e1 gives a decreasing step).
double smoothStep(double e0, double e1, double x)
{
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

double gaussian(double d, double sigma)
{
  return std::exp(-0.5 * d * d / (sigma * sigma));
}

/// Polynomial smooth maximum (intersection of implicit solids, negative
/// inside) with blend radius k; equals max(a, b) when |a - b| >= k.
double smoothMax(double a, double b, double k)
{
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::max(a, b) + 0.25 * h * h * k;
}

/// Smooth minimum (union).
double smoothMin(double a, double b, double k)
{
  return -smoothMax(-a, -b, k);
}

/// Signed radial distance to the superellipse |dx/ax|^n + |dy/by|^n = 1,
/// along the ray from its centre (negative inside).
double superellipseDistance(double dx, double dy, double ax, double by, double exponent)
{
  const double rho = std::pow(
    std::pow(std::abs(dx) / ax, exponent) + std::pow(std::abs(dy) / by, exponent), 1.0 / exponent);
  const double r = std::hypot(dx, dy);
  if (rho < 1e-12)
  {
    return -std::min(ax, by);
  }
  return r * (1.0 - 1.0 / rho);
}

// ---------------------------------------------------------------------------
// Tibia: the region below the plateau height field, inside a lofted section
// (plateau outline narrowing into the shaft), above the cut.

constexpr double TibiaCutHeight = -60.0;

struct TibiaSection
{
  double centreX, centreY, semiAxisX, anteriorSemiAxisY, posteriorSemiAxisY, exponent, notch;
};

TibiaSection tibiaSection(double z)
{
  // 1 at the plateau (condyles), 0 in the shaft; S-shaped in between.
  const double p = 1.0 - smoothStep(-4.0, -42.0, z);
  TibiaSection section;
  section.centreX = 1.5 * (1.0 - p);
  section.centreY = -1.0 * (1.0 - p);
  section.semiAxisX = 14.5 + (38.0 - 14.5) * p;
  section.anteriorSemiAxisY = 15.0 + (25.0 - 15.0) * p;
  section.posteriorSemiAxisY = 14.0 + (24.0 - 14.0) * p;
  section.exponent = 2.2 + 1.3 * p;
  // Posterior intercondylar notch of the outline (PCL facet).
  section.notch = 2.0 + 2.0 * p;
  return section;
}

double tibiaSideDistance(const Vector3& x)
{
  const TibiaSection section = tibiaSection(x.z());
  const double dx = x.x() - section.centreX;
  const double dy = x.y() - section.centreY;
  const double semiAxisY = dy >= 0.0
                             ? section.anteriorSemiAxisY
                             : section.posteriorSemiAxisY - section.notch * gaussian(dx, 6.0);
  double distance = superellipseDistance(dx, dy, section.semiAxisX, semiAxisY, section.exponent);
  // Tibial tuberosity on the anterior face below the plateau.
  distance -=
    4.0 * gaussian(x.x() - 4.0, 7.0) * gaussian(x.z() + 26.0, 8.0) * smoothStep(0.0, 8.0, dy);
  return distance;
}

double tibiaImplicit(const Vector3& x)
{
  const double top = x.z() - tibialPlateauHeight(x.x(), x.y());
  const double body = smoothMax(top, tibiaSideDistance(x), 5.0);
  return smoothMax(body, TibiaCutHeight - x.z(), 5.0);
}

// ---------------------------------------------------------------------------
// Femur, in a local height zl = z - femoralArticularHeight(gap): condyle
// "wheels" around medial-lateral axes, the trochlea between them in front,
// the metaphysis (epicondyles) narrowing into the shaft, minus the
// intercondylar notch.

constexpr double CondyleSagittalRadius = 22.0;
constexpr double CondyleCoronalRadius = 18.0;
constexpr double CondyleHalfWidth = 12.5;
constexpr double NotchHalfWidth = 9.8;
constexpr double FemurShaftLength = 85.0;

double notchRoof(double y)
{
  return smoothMin(18.0 + 0.75 * (8.0 - y), 32.0, 4.0);
}

double femurImplicitLocal(const Vector3& x)
{
  // One "wheel" around the medial-lateral axis carries both condyles and
  // the trochlea: its radius is largest over the compartment centres (the
  // condyles' lowest points), falls off toward the epicondyles and dips
  // into the trochlear groove at x = 0 (the notch removes the groove's
  // distal-posterior part).
  const double fromCondyle = std::abs(x.x()) - knee::lateralCompartmentCentre().x();
  const double condyleRadius =
    CondyleSagittalRadius - square(fromCondyle) / (2.0 * CondyleCoronalRadius);
  const double grooveRadius = 17.5 + 3.0 * (1.0 - gaussian(x.x(), 6.0));
  const double radius = smoothMax(condyleRadius, grooveRadius, 2.0);
  // Its sides are domes (the epicondyles), not flat faces.
  const double fromAxis = std::hypot(x.y(), x.z() - CondyleSagittalRadius);
  const double halfWidth = knee::lateralCompartmentCentre().x() + CondyleHalfWidth +
                           3.0 * (1.0 - square(fromAxis / CondyleSagittalRadius));
  const double wheel = smoothMax(fromAxis - radius, std::abs(x.x()) - halfWidth, 8.0);
  // Metaphysis and shaft: elliptic sections narrowing upward.
  const double t = smoothStep(28.0, 66.0, x.z());
  const double semiAxisX = 37.0 + (14.0 - 37.0) * t;
  const double semiAxisY = 20.0 + (13.5 - 20.0) * t;
  const double centreY = 2.0 + 3.0 * t;
  const double section =
    superellipseDistance(x.x(), x.y() - centreY, semiAxisX, semiAxisY, 2.4 - 0.4 * t);
  const double block =
    smoothMax(smoothMax(section, 16.0 - x.z(), 10.0), x.z() - FemurShaftLength, 5.0);

  const double body = smoothMin(wheel, block, 6.0);
  // Intercondylar notch: between the condyles, behind the trochlea, below
  // the roof (Blumensaat's line, rising posteriorly).
  const double notch = smoothMax(
    smoothMax(std::abs(x.x()) - NotchHalfWidth, x.z() - notchRoof(x.y()), 8.0), x.y() - 9.0, 4.0);
  return smoothMax(body, -notch, 4.0);
}

// ---------------------------------------------------------------------------
// Meshing of implicit solids.

Vector3 implicitGradient(const ImplicitFunction& f, const Vector3& x)
{
  const double h = 1e-4;
  Vector3 g;
  for (int a = 0; a < 3; ++a)
  {
    Vector3 low = x;
    Vector3 high = x;
    low[a] -= h;
    high[a] += h;
    g[a] = (f(high) - f(low)) / (2.0 * h);
  }
  return g;
}

/// Newton steps onto the zero level set along the gradient.
Vector3 projectOntoSurface(const ImplicitFunction& f, Vector3 x)
{
  for (int iteration = 0; iteration < 8; ++iteration)
  {
    const double value = f(x);
    if (std::abs(value) < 1e-9)
    {
      break;
    }
    const Vector3 g = implicitGradient(f, x);
    const double g2 = g.squaredNorm();
    if (g2 < 1e-12)
    {
      break;
    }
    Vector3 step = value * g / g2;
    // Never jump further than a millimetre in one step.
    const double length = step.norm();
    if (length > 1.0)
    {
      step /= length;
    }
    x -= step;
  }
  return x;
}

/// Level set f = 0 of the piecewise-linear interpolant of f on the
/// Freudenthal tetrahedra of a regular grid: always a closed 2-manifold,
/// triangles oriented outward (toward f > 0).
TriangleMesh marchingTetrahedra(const ImplicitFunction& f, const BoundingBox& box, double spacing)
{
  const Vector3 size = box.sizes();
  const int nx = static_cast<int>(std::ceil(size.x() / spacing));
  const int ny = static_cast<int>(std::ceil(size.y() / spacing));
  const int nz = static_cast<int>(std::ceil(size.z() / spacing));
  const Vector3 origin = box.min();
  auto nodeIndex = [&](int i, int j, int k)
  {
    return static_cast<std::int64_t>(i) +
           (nx + 1) * (static_cast<std::int64_t>(j) + (ny + 1) * static_cast<std::int64_t>(k));
  };
  auto nodePosition = [&](int i, int j, int k)
  { return Vector3(origin + spacing * Vector3(i, j, k)); };

  std::vector<double> values(static_cast<std::size_t>(nx + 1) * (ny + 1) * (nz + 1));
  const double offset = 1e-3 * spacing;
  for (int k = 0; k <= nz; ++k)
  {
    for (int j = 0; j <= ny; ++j)
    {
      for (int i = 0; i <= nx; ++i)
      {
        double value = f(nodePosition(i, j, k));
        // Keep crossings away from the nodes (no degenerate triangles).
        if (std::abs(value) < offset)
        {
          value = offset;
        }
        values[nodeIndex(i, j, k)] = value;
      }
    }
  }

  TriangleMesh mesh;
  std::unordered_map<std::int64_t, int> vertexOfEdge;
  const std::int64_t nodeCount = static_cast<std::int64_t>(values.size());
  // Tetrahedra of the cube: paths 0 -> e_a -> e_a + e_b -> 7 (corner bits x, y, z).
  static const int tetrahedra[6][4] = {
    { 0, 1, 3, 7 }, { 0, 1, 5, 7 }, { 0, 2, 3, 7 }, { 0, 2, 6, 7 }, { 0, 4, 5, 7 }, { 0, 4, 6, 7 }
  };
  struct Node
  {
    std::int64_t index;
    Vector3 position;
    double value;
  };
  auto edgeVertex = [&](const Node& a, const Node& b)
  {
    const std::int64_t key = std::min(a.index, b.index) * nodeCount + std::max(a.index, b.index);
    const auto found = vertexOfEdge.find(key);
    if (found != vertexOfEdge.end())
    {
      return found->second;
    }
    const double t = a.value / (a.value - b.value);
    const int index = static_cast<int>(mesh.positions.size());
    mesh.positions.push_back(a.position + t * (b.position - a.position));
    vertexOfEdge.emplace(key, index);
    return index;
  };
  auto addTriangle = [&](int v0, int v1, int v2, const Node& inside, const Node& outside)
  {
    const Vector3 normal =
      (mesh.positions[v1] - mesh.positions[v0]).cross(mesh.positions[v2] - mesh.positions[v0]);
    if (normal.dot(outside.position - inside.position) < 0.0)
    {
      std::swap(v1, v2);
    }
    mesh.triangles.push_back({ v0, v1, v2 });
  };

  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        std::array<Node, 8> corners;
        for (int c = 0; c < 8; ++c)
        {
          const int ci = i + (c & 1);
          const int cj = j + ((c >> 1) & 1);
          const int ck = k + ((c >> 2) & 1);
          const std::int64_t index = nodeIndex(ci, cj, ck);
          corners[c] = Node{ index, nodePosition(ci, cj, ck), values[index] };
        }
        for (const auto& tetrahedron : tetrahedra)
        {
          std::array<const Node*, 4> inside{};
          std::array<const Node*, 4> outside{};
          int insideCount = 0;
          int outsideCount = 0;
          for (int v : tetrahedron)
          {
            if (corners[v].value < 0.0)
            {
              inside[insideCount++] = &corners[v];
            }
            else
            {
              outside[outsideCount++] = &corners[v];
            }
          }
          if (insideCount == 0 || outsideCount == 0)
          {
            continue;
          }
          if (insideCount == 1)
          {
            const Node& a = *inside[0];
            addTriangle(edgeVertex(a, *outside[0]),
              edgeVertex(a, *outside[1]),
              edgeVertex(a, *outside[2]),
              a,
              *outside[0]);
          }
          else if (outsideCount == 1)
          {
            const Node& a = *outside[0];
            addTriangle(edgeVertex(*inside[0], a),
              edgeVertex(*inside[1], a),
              edgeVertex(*inside[2], a),
              *inside[0],
              a);
          }
          else
          {
            // Quadrilateral (i0,o0) (i0,o1) (i1,o1) (i1,o0).
            const Node& i0 = *inside[0];
            const Node& i1 = *inside[1];
            const Node& o0 = *outside[0];
            const Node& o1 = *outside[1];
            const int q0 = edgeVertex(i0, o0);
            const int q1 = edgeVertex(i0, o1);
            const int q2 = edgeVertex(i1, o1);
            const int q3 = edgeVertex(i1, o0);
            addTriangle(q0, q1, q2, i0, o0);
            addTriangle(q0, q2, q3, i0, o0);
          }
        }
      }
    }
  }
  return mesh;
}

/// Moves the vertices onto the smooth surface and evens out the triangles
/// with tangential Laplacian steps, never flipping a triangle.
void relaxOnSurface(TriangleMesh& mesh, const ImplicitFunction& f, int iterations)
{
  const std::size_t n = mesh.vertexCount();
  std::vector<std::vector<int>> neighbours(n);
  std::vector<std::vector<int>> trianglesOf(n);
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const auto& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      neighbours[tri[k]].push_back(tri[(k + 1) % 3]);
      neighbours[tri[k]].push_back(tri[(k + 2) % 3]);
      trianglesOf[tri[k]].push_back(static_cast<int>(t));
    }
  }
  for (auto& list : neighbours)
  {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  for (auto& x : mesh.positions)
  {
    x = projectOntoSurface(f, x);
  }
  auto isAcceptable = [&](std::size_t v, const Vector3& candidate)
  {
    const Vector3 normal = implicitGradient(f, candidate).normalized();
    for (int t : trianglesOf[v])
    {
      std::array<Vector3, 3> corners;
      for (int k = 0; k < 3; ++k)
      {
        const int w = mesh.triangles[t][k];
        corners[k] = static_cast<std::size_t>(w) == v ? candidate : mesh.positions[w];
      }
      const Vector3 cross = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
      const double area2 = cross.norm();
      if (!(area2 > 1e-8) || cross.dot(normal) < 0.2 * area2)
      {
        return false;
      }
    }
    return true;
  };
  for (int iteration = 0; iteration < iterations; ++iteration)
  {
    for (std::size_t v = 0; v < n; ++v)
    {
      Vector3 centroid = Vector3::Zero();
      for (int w : neighbours[v])
      {
        centroid += mesh.positions[w];
      }
      centroid /= static_cast<double>(neighbours[v].size());
      const Vector3& x = mesh.positions[v];
      const Vector3 normal = implicitGradient(f, x).normalized();
      Vector3 move = centroid - x;
      move -= move.dot(normal) * normal;
      const Vector3 candidate = projectOntoSurface(f, x + 0.6 * move);
      if (isAcceptable(v, candidate))
      {
        mesh.positions[v] = candidate;
      }
    }
  }
  mesh.normals.resize(n);
  for (std::size_t v = 0; v < n; ++v)
  {
    mesh.normals[v] = implicitGradient(f, mesh.positions[v]).normalized();
  }
}

/// Meshes the solid with about `targetVertices` vertices (the grid spacing
/// is searched; the count scales as 1 / spacing^2).
TriangleMesh meshImplicitSolid(const ImplicitFunction& f,
  const BoundingBox& box,
  int targetVertices,
  const std::string& name)
{
  // The count follows a power law of the spacing (about spacing^-2): fit
  // its exponent from the last two tries and step toward the target. Flat
  // parts of the surface make the count jump with the grid's alignment, so
  // finish with a scan of nearby spacings.
  TriangleMesh best;
  double bestError = std::numeric_limits<double>::infinity();
  double bestSpacing = 3.0;
  auto attempt = [&](double spacing)
  {
    TriangleMesh mesh = marchingTetrahedra(f, box, spacing);
    const double count = std::max<double>(1.0, static_cast<double>(mesh.vertexCount()));
    const double error = std::abs(count - targetVertices) / targetVertices;
    if (error < bestError)
    {
      bestError = error;
      bestSpacing = spacing;
      best = std::move(mesh);
    }
    return count;
  };
  constexpr double Tolerance = 0.005;
  double spacing = bestSpacing;
  double previousLogSpacing = 0.0;
  double previousLogCount = 0.0;
  for (int step = 0; step < 6 && bestError > Tolerance; ++step)
  {
    const double count = attempt(spacing);
    double exponent = 2.0;
    if (step > 0 && std::abs(std::log(spacing) - previousLogSpacing) > 1e-9)
    {
      exponent = std::clamp(
        -(std::log(count) - previousLogCount) / (std::log(spacing) - previousLogSpacing), 1.0, 3.0);
    }
    previousLogSpacing = std::log(spacing);
    previousLogCount = std::log(count);
    spacing *= std::pow(count / targetVertices, 1.0 / exponent);
  }
  const double centre = bestSpacing;
  for (int k = 1; k <= 12 && bestError > Tolerance; ++k)
  {
    attempt(centre * (1.0 + 0.0025 * k));
    attempt(centre * (1.0 - 0.0025 * k));
  }
  best.name = name;
  relaxOnSurface(best, f, 12);
  if (best.signedVolume() < 0.0)
  {
    best.reverseOrientation();
  }
  return best;
}

/// First point of the implicit surface met going from `outside` toward
/// `inside` (f(inside) < 0 is required).
Vector3 surfacePointBetween(const ImplicitFunction& f,
  const Vector3& outside,
  const Vector3& inside)
{
  const double length = (inside - outside).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / 0.2)));
  Vector3 previous = outside;
  for (int step = 1; step <= steps; ++step)
  {
    const Vector3 x = outside + (inside - outside) * (static_cast<double>(step) / steps);
    if (f(x) < 0.0)
    {
      Vector3 low = previous; // outside
      Vector3 high = x;       // inside
      for (int bisection = 0; bisection < 50; ++bisection)
      {
        const Vector3 middle = 0.5 * (low + high);
        (f(middle) < 0.0 ? high : low) = middle;
      }
      return 0.5 * (low + high);
    }
    previous = x;
  }
  throw Error("knee models: a collision ray missed the bone (internal error)");
}

/// A coarse closed surface: a pole, `rings` rings of `sectors` points, a
/// pole; every point on the implicit surface.
TriangleMesh ringSurface(const Vector3& firstPole,
  const std::vector<std::vector<Vector3>>& rings,
  const Vector3& lastPole,
  const std::string& name)
{
  TriangleMesh mesh;
  mesh.name = name;
  const int sectors = static_cast<int>(rings.front().size());
  mesh.positions.push_back(firstPole);
  for (const auto& ring : rings)
  {
    mesh.positions.insert(mesh.positions.end(), ring.begin(), ring.end());
  }
  mesh.positions.push_back(lastPole);
  const int last = static_cast<int>(mesh.positions.size()) - 1;
  auto ringVertex = [&](int r, int j) { return 1 + r * sectors + (j % sectors); };
  for (int j = 0; j < sectors; ++j)
  {
    mesh.triangles.push_back({ 0, ringVertex(0, j), ringVertex(0, j + 1) });
  }
  for (int r = 0; r + 1 < static_cast<int>(rings.size()); ++r)
  {
    for (int j = 0; j < sectors; ++j)
    {
      const int a = ringVertex(r, j);
      const int b = ringVertex(r, j + 1);
      const int c = ringVertex(r + 1, j + 1);
      const int d = ringVertex(r + 1, j);
      mesh.triangles.push_back({ a, d, c });
      mesh.triangles.push_back({ a, c, b });
    }
  }
  const int lastRing = static_cast<int>(rings.size()) - 1;
  for (int j = 0; j < sectors; ++j)
  {
    mesh.triangles.push_back({ last, ringVertex(lastRing, j + 1), ringVertex(lastRing, j) });
  }
  if (mesh.signedVolume() < 0.0)
  {
    mesh.reverseOrientation();
  }
  mesh.computeVertexNormals();
  return mesh;
}

// ---------------------------------------------------------------------------
// Parameter checks.

const detail::ParameterChecks Checks("knee surroundings");

void requireResolution(const ParametricResolution& resolution,
  const ParametricResolution& minimum,
  const std::string& what)
{
  Checks.requireAtLeast(resolution.along, minimum.along, what + " cells along");
  Checks.requireAtLeast(resolution.across, minimum.across, what + " cells across");
  Checks.requireAtLeast(resolution.through, minimum.through, what + " cells through");
}

void requireLigament(const LigamentResolution& r, const std::string& name)
{
  requireResolution(r.visual, { 4, 2, 2 }, name + " visual");
  requireResolution(r.collision2000, { 2, 2, 1 }, name + " 2,000-triangle collision surface");
  requireResolution(r.collision500, { 2, 2, 1 }, name + " 500-triangle collision surface");
  Checks.requireAtLeast(r.reducedAlong, 1, name + " reduced collision cells along");
  Checks.requireAtLeast(r.reducedAcross, 1, name + " reduced collision cells across");
  requireResolution(r.hexahedra, { 1, 1, 1 }, name + " hexahedra");
}

// ---------------------------------------------------------------------------
// Cartilage and ligaments.

/// Blunt-cornered square-to-disc map of [-1, 1]^2 (corner angle about 170
/// degrees, Jacobian positive for alpha < 1/3).
Vector2 roundedSquare(double a, double b)
{
  constexpr double alpha = 0.3;
  return Vector2(a * (1.0 - alpha * b * b), b * (1.0 - alpha * a * a));
}

constexpr double CartilageSemiAxisX = 12.0;
constexpr double CartilageSemiAxisY = 19.5;
/// The cartilage's lower surface floats this far above the bone's smooth
/// surface so that the bone's faceted mesh stays below it.
constexpr double CartilageBoneClearance = 0.12;
constexpr double CartilageMinimumThickness = 0.5;

struct LigamentShape
{
  std::array<Vector3, 4> control; // cubic Bezier of the centre line
  double tibialWidth, middleWidth, femoralWidth;
  double thickness;
  /// Turn of the band about its axis at the tibial insertion (radians),
  /// relative to a band lying in a sagittal plane; kept over the tibia, it
  /// unwinds in the middle half.
  double tibialTwist;
  /// Extra twist in the middle (radians), zero at the insertions.
  double twist;
};

LigamentShape ligamentShape(CruciateLigament ligament, double jointGap)
{
  // The femur (and the femoral insertion) moves with the joint gap.
  const double lift = jointGap - knee::DefaultJointGap;
  LigamentShape shape;
  if (ligament == CruciateLigament::Anterior)
  {
    // Tibial footprint elongated anterior-posterior in front of the
    // spines; femoral footprint on the medial wall of the lateral condyle.
    const Vector3 tibial(-1.5, 11.0, -3.5);
    const Vector3 femoral(12.5, -11.0, 22.0 + lift);
    const Vector3 tibialDirection = Vector3(0.0, -0.3, 1.0).normalized();
    const Vector3 femoralDirection = Vector3(0.7, -0.45, 0.55).normalized();
    shape.control = {
      tibial, tibial + 9.0 * tibialDirection, femoral - 9.0 * femoralDirection, femoral
    };
    shape.tibialWidth = 11.0;
    shape.middleWidth = 9.5;
    shape.femoralWidth = 11.0;
    shape.thickness = 4.5;
    shape.tibialTwist = 0.0;
    shape.twist = 20.0 * M_PI / 180.0;
  }
  else
  {
    // Tibial footprint wide medial-lateral on the posterior intercondylar
    // slope below the plateau; femoral footprint on the lateral wall of the
    // medial condyle, anteriorly: the band turns through about 90 degrees.
    const Vector3 tibial(0.0, -16.2, -13.0);
    const Vector3 femoral(-12.5, 1.0, 21.0 + lift);
    const Vector3 tibialDirection = Vector3(0.0, 0.1, 1.0).normalized();
    const Vector3 femoralDirection = Vector3(-0.7, 0.35, 0.62).normalized();
    shape.control = {
      tibial, tibial + 12.0 * tibialDirection, femoral - 10.0 * femoralDirection, femoral
    };
    shape.tibialWidth = 11.0;
    shape.middleWidth = 11.0;
    shape.femoralWidth = 13.0;
    shape.thickness = 5.0;
    shape.tibialTwist = 90.0 * M_PI / 180.0;
    shape.twist = -10.0 * M_PI / 180.0;
  }
  return shape;
}

Vector3 bezierPoint(const std::array<Vector3, 4>& c, double s)
{
  const double r = 1.0 - s;
  return r * r * r * c[0] + 3.0 * r * r * s * c[1] + 3.0 * r * s * s * c[2] + s * s * s * c[3];
}

Vector3 bezierTangent(const std::array<Vector3, 4>& c, double s)
{
  const double r = 1.0 - s;
  return (3.0 * r * r * (c[1] - c[0]) + 6.0 * r * s * (c[2] - c[1]) + 3.0 * s * s * (c[3] - c[2]))
    .normalized();
}

/// Thickness across the band, relative to the middle: elliptic, with a
/// blunt edge (30% of the thickness) so that the solid never degenerates.
double bandThicknessProfile(double across)
{
  return std::sqrt(1.0 - 0.91 * across * across);
}

} // namespace

const char* cruciateLigamentName(CruciateLigament ligament)
{
  return ligament == CruciateLigament::Anterior ? "anterior cruciate ligament"
                                                : "posterior cruciate ligament";
}

void validateKneeSurroundingsParameters(const KneeSurroundingsParameters& p)
{
  if (!(p.jointGap >= 0.5 && p.jointGap <= 12.0))
  {
    std::ostringstream message;
    message << "joint gap must be between 0.5 and 12 mm (got " << p.jointGap
            << "): a closed joint leaves no room for instruments, a wider one tears the "
               "cruciate ligaments";
    Checks.fail(message.str());
  }
  Checks.requireAtLeast(p.tibiaVisualVertices, 200, "tibia visual vertices");
  Checks.requireAtLeast(p.femurVisualVertices, 200, "femur visual vertices");
  if (p.tibiaVisualVertices > 2000000 || p.femurVisualVertices > 2000000)
  {
    Checks.fail("bone visual vertices must be at most 2,000,000");
  }
  Checks.requireAtLeast(p.tibiaCollisionRings, 3, "tibia collision rings");
  Checks.requireAtLeast(p.tibiaCollisionSectors, 4, "tibia collision sectors");
  Checks.requireAtLeast(p.femurCollisionRings, 3, "femur collision rings");
  Checks.requireAtLeast(p.femurCollisionSectors, 4, "femur collision sectors");
  requireResolution(p.cartilageVisual, { 2, 2, 1 }, "cartilage visual");
  requireResolution(p.cartilageCollision1000, { 1, 1, 0 }, "cartilage 1,000-triangle collision");
  requireResolution(p.cartilageCollision500, { 1, 1, 0 }, "cartilage 500-triangle collision");
  requireResolution(p.cartilageCollision100, { 1, 1, 0 }, "cartilage 100-triangle collision");
  requireResolution(p.cartilageHexahedra, { 1, 1, 1 }, "cartilage hexahedra");
  const int setting = static_cast<int>(p.cartilageCollisionSetting);
  if (setting < 1 || setting > 4)
  {
    Checks.fail("cartilage collision setting must be 1 to 4 (got " + std::to_string(setting) + ")");
  }
  requireLigament(p.anteriorCruciate, "anterior cruciate ligament");
  requireLigament(p.posteriorCruciate, "posterior cruciate ligament");
  if (!(p.textureScale > 0.0) || !std::isfinite(p.textureScale))
  {
    std::ostringstream message;
    message << "texture scale must be a positive number (got " << p.textureScale << ")";
    Checks.fail(message.str());
  }
}

double tibialPlateauHeight(double x, double y)
{
  // Medial compartment: a bowl (about 1 mm deep at the meniscus rim);
  // lateral compartment: a low dome. Blended across the eminence.
  const double medial =
    1.0 * (square((x - knee::medialCompartmentCentre().x()) / 13.5) + square(y / 21.0));
  const double lateral =
    -0.8 * (square((x - knee::lateralCompartmentCentre().x()) / 15.0) + square(y / 20.0));
  const double blend = smoothStep(-12.0, 12.0, x);
  double h = (1.0 - blend) * medial + blend * lateral;
  // Intercondylar eminence: a low ridge carrying the two tibial spines
  // (the medial one taller).
  const double ridgeWindow = smoothStep(-14.0, -6.0, y) * (1.0 - smoothStep(1.0, 7.0, y));
  h += 1.0 * gaussian(x, 5.0) * ridgeWindow;
  h += 3.5 * gaussian(x + 4.5, 2.2) * gaussian(y + 1.5, 3.5);
  h += 3.0 * gaussian(x - 4.5, 2.2) * gaussian(y + 3.5, 3.5);
  // Anterior intercondylar area (ACL footprint): a shallow hollow.
  const double intercondylar = 1.0 - smoothStep(4.0, 10.0, std::abs(x));
  h -= 2.0 * intercondylar * smoothStep(1.0, 9.0, y);
  // Posterior intercondylar area sloping down to the PCL facet.
  const double fossa = 1.0 - smoothStep(3.0, 14.0, std::abs(x));
  h -= 8.0 * fossa * smoothStep(-6.0, -19.0, y);
  return h;
}

double femoralArticularHeight(double jointGap)
{
  return knee::TibialCartilageThickness + jointGap;
}

BoneModel makeTibia(const KneeSurroundingsParameters& parameters)
{
  validateKneeSurroundingsParameters(parameters);
  const ImplicitFunction f = tibiaImplicit;
  BoneModel bone;
  bone.name = "tibia";
  const BoundingBox box(Vector3(-44.0, -32.0, TibiaCutHeight - 4.0), Vector3(44.0, 34.0, 10.0));
  bone.visual = meshImplicitSolid(f, box, parameters.tibiaVisualVertices, "tibia");

  // Reduced collision mesh: the plateau pole, rings on the plateau (rays
  // from above), rings down the sides (rays toward the axis), the shaft pole.
  const int sectors = parameters.tibiaCollisionSectors;
  const int rings = parameters.tibiaCollisionRings;
  const int capRings = std::max(1, rings / 3);
  const int sideRings = rings - capRings;
  const Vector3 inside(0.0, 0.0, -20.0);
  std::vector<std::vector<Vector3>> ringPoints;
  for (int r = 0; r < capRings; ++r)
  {
    const double fraction = 0.93 * (r + 1) / capRings;
    std::vector<Vector3> ring;
    for (int j = 0; j < sectors; ++j)
    {
      const double angle = 2.0 * M_PI * j / sectors;
      const Vector3 direction(std::cos(angle), std::sin(angle), 0.0);
      // Outline radius at the plateau level in this direction.
      const Vector3 rim = surfacePointBetween([](const Vector3& x) { return tibiaSideDistance(x); },
        Vector3(0.0, 0.0, -1.0) + 80.0 * direction,
        Vector3(0.0, 0.0, -1.0));
      const double radius = rim.head<2>().norm();
      const Vector3 above = Vector3(0.0, 0.0, 30.0) + fraction * radius * direction;
      ring.push_back(projectOntoSurface(f, surfacePointBetween(f, above, inside)));
    }
    ringPoints.push_back(ring);
  }
  for (int r = 0; r < sideRings; ++r)
  {
    const double z =
      sideRings > 1 ? -6.0 + (TibiaCutHeight + 4.0 + 6.0) * r / (sideRings - 1) : -20.0;
    const TibiaSection section = tibiaSection(z);
    const Vector3 axis(section.centreX, section.centreY, z);
    std::vector<Vector3> ring;
    for (int j = 0; j < sectors; ++j)
    {
      const double angle = 2.0 * M_PI * j / sectors;
      const Vector3 direction(std::cos(angle), std::sin(angle), 0.0);
      ring.push_back(projectOntoSurface(f, surfacePointBetween(f, axis + 100.0 * direction, axis)));
    }
    ringPoints.push_back(ring);
  }
  const Vector3 top = surfacePointBetween(f, Vector3(0.0, 0.0, 30.0), inside);
  const TibiaSection shaft = tibiaSection(TibiaCutHeight);
  const Vector3 bottom = surfacePointBetween(f,
    Vector3(shaft.centreX, shaft.centreY, TibiaCutHeight - 30.0),
    Vector3(shaft.centreX, shaft.centreY, TibiaCutHeight + 10.0));
  bone.collision = ringSurface(top, ringPoints, bottom, "tibia collision");
  return bone;
}

BoneModel makeFemur(const KneeSurroundingsParameters& parameters)
{
  validateKneeSurroundingsParameters(parameters);
  const double base = femoralArticularHeight(parameters.jointGap);
  const ImplicitFunction f = [base](const Vector3& x)
  { return femurImplicitLocal(Vector3(x.x(), x.y(), x.z() - base)); };
  BoneModel bone;
  bone.name = "femur";
  const BoundingBox box(
    Vector3(-44.0, -30.0, base - 4.0), Vector3(44.0, 30.0, base + FemurShaftLength + 4.0));
  bone.visual = meshImplicitSolid(f, box, parameters.femurVisualVertices, "femur");

  // Reduced collision mesh: the notch pole, rings on the distal surface
  // (rays from below toward the metaphysis), rings up the sides (rays
  // toward the shaft axis), the shaft pole.
  const int sectors = parameters.femurCollisionSectors;
  const int rings = parameters.femurCollisionRings;
  const int capRings = std::max(1, rings / 3);
  const int sideRings = rings - capRings;
  const Vector3 inside(0.0, 3.0, base + 35.0);
  std::vector<std::vector<Vector3>> ringPoints;
  for (int r = 0; r < capRings; ++r)
  {
    const double fraction = 0.93 * (r + 1) / capRings;
    std::vector<Vector3> ring;
    for (int j = 0; j < sectors; ++j)
    {
      const double angle = 2.0 * M_PI * j / sectors;
      const Vector3 below(
        fraction * 34.5 * std::cos(angle), fraction * 22.0 * std::sin(angle), base - 30.0);
      ring.push_back(projectOntoSurface(f, surfacePointBetween(f, below, inside)));
    }
    ringPoints.push_back(ring);
  }
  for (int r = 0; r < sideRings; ++r)
  {
    const double zl =
      sideRings > 1 ? 30.0 + (FemurShaftLength - 4.0 - 30.0) * r / (sideRings - 1) : 45.0;
    const double t = smoothStep(28.0, 66.0, zl);
    const Vector3 axis(0.0, 2.0 + 3.0 * t, base + zl);
    std::vector<Vector3> ring;
    for (int j = 0; j < sectors; ++j)
    {
      const double angle = 2.0 * M_PI * j / sectors;
      const Vector3 direction(std::cos(angle), std::sin(angle), 0.0);
      ring.push_back(projectOntoSurface(f, surfacePointBetween(f, axis + 100.0 * direction, axis)));
    }
    ringPoints.push_back(ring);
  }
  const Vector3 notch = surfacePointBetween(f, Vector3(0.0, 0.0, base - 30.0), inside);
  const Vector3 top = surfacePointBetween(f,
    Vector3(0.0, 5.0, base + FemurShaftLength + 30.0),
    Vector3(0.0, 5.0, base + FemurShaftLength - 10.0));
  bone.collision = ringSurface(notch, ringPoints, top, "femur collision");
  return bone;
}

ParametricSolid makeTibialCartilageSolid(const KneeSurroundingsParameters& parameters)
{
  validateKneeSurroundingsParameters(parameters);
  const Vector3 centre = knee::medialCompartmentCentre();
  auto map = [centre](const ParameterPoint& p)
  {
    // s: posterior -> anterior (+y); u: intercondylar side -> medial (-x);
    // w: bone -> joint (+z). Right-handed.
    const Vector2 disc = roundedSquare(2.0 * p[0] - 1.0, 2.0 * p[1] - 1.0);
    const double y = centre.y() + CartilageSemiAxisY * disc.x();
    const double x = centre.x() - CartilageSemiAxisX * disc.y();
    const double bottom = tibialPlateauHeight(x, y) + CartilageBoneClearance;
    // The joint surface stays below the meniscus's flat base, a little
    // more toward the periphery, reaching TibialCartilageThickness at the
    // compartment centre.
    const double spread = square((x - centre.x()) / 13.5) + square((y - centre.y()) / 21.0);
    const double top =
      std::max(knee::TibialCartilageThickness - 0.25 * spread, bottom + CartilageMinimumThickness);
    return Vector3(x, y, bottom + p[2] * (top - bottom));
  };
  return ParametricSolid("medial tibial cartilage", map);
}

TriangleMesh tibialCartilageCollisionMesh(const KneeSurroundingsParameters& parameters,
  CartilageCollisionSetting setting)
{
  const ParametricSolid solid = makeTibialCartilageSolid(parameters);
  switch (setting)
  {
    case CartilageCollisionSetting::VisualMesh:
    {
      TriangleMesh mesh =
        solid.boundarySurface(parameters.cartilageVisual, parameters.textureScale);
      mesh.name = "medial tibial cartilage collision";
      // Collision on the surface itself: no thickness.
      mesh.pointAttributes.set(
        CollisionRadiusArrayName, 1, std::vector<double>(mesh.vertexCount(), 0.0));
      return mesh;
    }
    case CartilageCollisionSetting::Triangles1000:
      return solid.midSurface(
        parameters.cartilageCollision1000.along, parameters.cartilageCollision1000.across);
    case CartilageCollisionSetting::Triangles500:
      return solid.midSurface(
        parameters.cartilageCollision500.along, parameters.cartilageCollision500.across);
    case CartilageCollisionSetting::Triangles100:
      return solid.midSurface(
        parameters.cartilageCollision100.along, parameters.cartilageCollision100.across);
  }
  Checks.fail("unknown cartilage collision setting " + std::to_string(static_cast<int>(setting)));
}

TissueModel makeTibialCartilage(const KneeSurroundingsParameters& parameters)
{
  const ParametricSolid solid = makeTibialCartilageSolid(parameters);
  TissueModel model;
  model.name = solid.name();
  model.visual = solid.boundarySurface(parameters.cartilageVisual, parameters.textureScale);
  model.collision = tibialCartilageCollisionMesh(parameters, parameters.cartilageCollisionSetting);
  // Fixed on the bone side (w = 0); the cartilage is non-deformable in most
  // procedures (5.4.4) but the hexahedra let a scene soften it.
  // The margin in the plane covers the outline's bulge between nodes.
  model.simulation = solid.hexahedra(parameters.cartilageHexahedra,
    { 1.0, 1.0, 0.2 },
    [](const ParameterPoint& p) { return p[2] < 1e-9; });
  model.simulation.name = model.name + " hexahedra";
  return model;
}

Vector3 cruciateLigamentAttachment(CruciateLigament ligament,
  double s,
  const KneeSurroundingsParameters& parameters)
{
  return bezierPoint(ligamentShape(ligament, parameters.jointGap).control, std::clamp(s, 0.0, 1.0));
}

ParametricSolid makeCruciateLigamentSolid(CruciateLigament ligament,
  const KneeSurroundingsParameters& parameters)
{
  validateKneeSurroundingsParameters(parameters);
  const LigamentShape shape = ligamentShape(ligament, parameters.jointGap);
  auto map = [shape](const ParameterPoint& p)
  {
    const double s = std::clamp(p[0], 0.0, 1.0);
    const Vector3 centre = bezierPoint(shape.control, s);
    const Vector3 tangent = bezierTangent(shape.control, s);
    // Thickness direction: lateral (+x) made normal to the axis, so the
    // band lies in a sagittal plane, twisted about the axis in between.
    const Vector3 lateral =
      (Vector3::UnitX() - Vector3::UnitX().dot(tangent) * tangent).normalized();
    const Vector3 sideways = lateral.cross(tangent);
    const double twist =
      shape.tibialTwist * (1.0 - smoothStep(0.25, 0.75, s)) + shape.twist * std::sin(M_PI * s);
    const Vector3 normal = std::cos(twist) * lateral + std::sin(twist) * sideways;
    const Vector3 widthDirection = normal.cross(tangent);
    // Width fans out toward the insertions.
    const double ends = (1.0 - s) * shape.tibialWidth + s * shape.femoralWidth;
    const double middle = std::sin(M_PI * s);
    const double width = ends + (shape.middleWidth - ends) * middle;
    const double across = 2.0 * p[1] - 1.0;
    const double through = 2.0 * p[2] - 1.0;
    return Vector3(centre + 0.5 * width * across * widthDirection +
                   0.5 * shape.thickness * bandThicknessProfile(across) * through * normal);
  };
  return ParametricSolid(cruciateLigamentName(ligament), map);
}

TriangleMesh cruciateLigamentCollisionMesh(CruciateLigament ligament,
  LigamentCollisionSetting setting,
  const KneeSurroundingsParameters& parameters)
{
  const ParametricSolid solid = makeCruciateLigamentSolid(ligament, parameters);
  const LigamentResolution& resolution = ligament == CruciateLigament::Anterior
                                           ? parameters.anteriorCruciate
                                           : parameters.posteriorCruciate;
  TriangleMesh mesh;
  switch (setting)
  {
    case LigamentCollisionSetting::VisualMesh:
      mesh = solid.boundarySurface(resolution.visual, parameters.textureScale);
      break;
    case LigamentCollisionSetting::Triangles2000:
      mesh = solid.boundarySurface(resolution.collision2000, parameters.textureScale);
      break;
    case LigamentCollisionSetting::Triangles500:
      mesh = solid.boundarySurface(resolution.collision500, parameters.textureScale);
      break;
    case LigamentCollisionSetting::ReducedWithRadii:
      return solid.midSurface(resolution.reducedAlong, resolution.reducedAcross);
    default:
      Checks.fail(
        "unknown ligament collision setting " + std::to_string(static_cast<int>(setting)));
  }
  mesh.name = solid.name() + " collision";
  // Collision on the closed surface itself: no thickness.
  mesh.pointAttributes.set(
    CollisionRadiusArrayName, 1, std::vector<double>(mesh.vertexCount(), 0.0));
  return mesh;
}

TissueModel makeCruciateLigament(CruciateLigament ligament,
  const KneeSurroundingsParameters& parameters)
{
  const ParametricSolid solid = makeCruciateLigamentSolid(ligament, parameters);
  const LigamentResolution& resolution = ligament == CruciateLigament::Anterior
                                           ? parameters.anteriorCruciate
                                           : parameters.posteriorCruciate;
  TissueModel model;
  model.name = solid.name();
  model.visual = solid.boundarySurface(resolution.visual, parameters.textureScale);
  model.collision = solid.midSurface(resolution.reducedAlong, resolution.reducedAcross);
  // Attached at both insertions; the margins make the trilinear cells
  // contain the curved, twisted band.
  model.simulation = solid.hexahedra(resolution.hexahedra,
    { 0.3, 0.5, 0.3 },
    [](const ParameterPoint& p) { return p[0] < 1e-9 || p[0] > 1.0 - 1e-9; });
  model.simulation.name = model.name + " hexahedra";
  return model;
}

KneeSurroundings makeKneeSurroundings(const KneeSurroundingsParameters& parameters)
{
  validateKneeSurroundingsParameters(parameters);
  KneeSurroundings knee;
  knee.tibia = makeTibia(parameters);
  knee.femur = makeFemur(parameters);
  knee.tibialCartilage = makeTibialCartilage(parameters);
  knee.anteriorCruciateLigament = makeCruciateLigament(CruciateLigament::Anterior, parameters);
  knee.posteriorCruciateLigament = makeCruciateLigament(CruciateLigament::Posterior, parameters);
  return knee;
}

} // namespace thintissue
