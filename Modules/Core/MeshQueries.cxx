#include "MeshQueries.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thintissue
{

double windingNumber(const TriangleMesh& mesh, const Vector3& point)
{
  double solidAngle = 0.0;
  for (const auto& t : mesh.triangles)
  {
    const Vector3 a = mesh.positions[t[0]] - point;
    const Vector3 b = mesh.positions[t[1]] - point;
    const Vector3 c = mesh.positions[t[2]] - point;
    const double la = a.norm();
    const double lb = b.norm();
    const double lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    solidAngle += 2.0 * std::atan2(numerator, denominator);
  }
  return solidAngle / (4.0 * M_PI);
}

Vector3 closestPointOnTriangle(const Vector3& p,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c)
{
  // Voronoi-region walk (Ericson, Real-Time Collision Detection, 5.1.5).
  const Vector3 ab = b - a;
  const Vector3 ac = c - a;
  const Vector3 ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0)
  {
    return a;
  }
  const Vector3 bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3)
  {
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
  {
    return a + ab * (d1 / (d1 - d3));
  }
  const Vector3 cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6)
  {
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
  {
    return a + ac * (d2 / (d2 - d6));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
  {
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double denominator = 1.0 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

double distanceToSurface(const TriangleMesh& mesh, const Vector3& point)
{
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles)
  {
    const Vector3 q = closestPointOnTriangle(
      point, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
    best = std::min(best, (q - point).squaredNorm());
  }
  return std::sqrt(best);
}

std::vector<double> rayHits(const TriangleMesh& mesh,
  const Vector3& origin,
  const Vector3& direction)
{
  // Moller-Trumbore with a small tolerance so that hits on shared edges count.
  std::vector<double> hits;
  const double tolerance = 1e-9;
  for (const auto& t : mesh.triangles)
  {
    const Vector3& a = mesh.positions[t[0]];
    const Vector3 e1 = mesh.positions[t[1]] - a;
    const Vector3 e2 = mesh.positions[t[2]] - a;
    const Vector3 p = direction.cross(e2);
    const double determinant = e1.dot(p);
    if (std::abs(determinant) < 1e-300)
    {
      continue;
    }
    const double inverse = 1.0 / determinant;
    const Vector3 s = origin - a;
    const double u = s.dot(p) * inverse;
    if (u < -tolerance || u > 1.0 + tolerance)
    {
      continue;
    }
    const Vector3 q = s.cross(e1);
    const double v = direction.dot(q) * inverse;
    if (v < -tolerance || u + v > 1.0 + tolerance)
    {
      continue;
    }
    const double distance = e2.dot(q) * inverse;
    if (distance >= 0.0)
    {
      hits.push_back(distance);
    }
  }
  std::sort(hits.begin(), hits.end());
  return hits;
}

} // namespace thintissue
