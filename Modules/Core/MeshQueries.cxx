#include "MeshQueries.h"

#include "ProximityQueries.h"
#include "TriangleBvh.h"

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
  return closestPointOnTriangleWithBarycentric(p, a, b, c).point;
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

double distanceToSurface(const TriangleMesh& mesh, const TriangleBvh& bvh, const Vector3& point)
{
  const auto& nodes = bvh.nodes();
  if (nodes.empty())
  {
    return std::numeric_limits<double>::infinity();
  }
  double best = std::numeric_limits<double>::infinity(); // squared
  constexpr int StackSize = 128;
  int stack[StackSize];
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const TriangleBvh::Node& node = nodes[stack[--top]];
    if (node.box.squaredExteriorDistance(point) >= best)
    {
      continue;
    }
    if (node.isLeaf())
    {
      for (int i = node.firstTriangle; i < node.firstTriangle + node.triangleCount; ++i)
      {
        const Triangle& t = mesh.triangles[bvh.leafTriangles()[i]];
        const Vector3 q = closestPointOnTriangle(
          point, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
        best = std::min(best, (q - point).squaredNorm());
      }
      continue;
    }
    const int left = static_cast<int>(&node - nodes.data()) + 1;
    const int right = node.rightChild;
    const bool leftFirst = nodes[left].box.squaredExteriorDistance(point) <=
                           nodes[right].box.squaredExteriorDistance(point);
    // The nearer child is popped first; a median-split tree is at most
    // about log2(n) deep, far below the stack's size.
    stack[top++] = leftFirst ? right : left;
    stack[top++] = leftFirst ? left : right;
  }
  return std::sqrt(best);
}

double rayTriangleHit(const Vector3& origin,
  const Vector3& direction,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c,
  double tolerance)
{
  constexpr double Miss = std::numeric_limits<double>::quiet_NaN();
  const Vector3 e1 = b - a;
  const Vector3 e2 = c - a;
  const Vector3 p = direction.cross(e2);
  const double determinant = e1.dot(p);
  if (std::abs(determinant) < 1e-300)
  {
    return Miss;
  }
  const double inverse = 1.0 / determinant;
  const Vector3 s = origin - a;
  const double u = s.dot(p) * inverse;
  if (u < -tolerance || u > 1.0 + tolerance)
  {
    return Miss;
  }
  const Vector3 q = s.cross(e1);
  const double v = direction.dot(q) * inverse;
  if (v < -tolerance || u + v > 1.0 + tolerance)
  {
    return Miss;
  }
  return e2.dot(q) * inverse;
}

std::vector<double> rayHits(const TriangleMesh& mesh,
  const Vector3& origin,
  const Vector3& direction)
{
  // A small tolerance so that hits on shared edges count.
  std::vector<double> hits;
  for (const auto& t : mesh.triangles)
  {
    const double distance = rayTriangleHit(
      origin, direction, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], 1e-9);
    if (distance >= 0.0)
    {
      hits.push_back(distance);
    }
  }
  std::sort(hits.begin(), hits.end());
  return hits;
}

bool insidePolygon(const std::vector<Vector2>& polygon, const Vector2& point)
{
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
  {
    const Vector2& a = polygon[i];
    const Vector2& b = polygon[j];
    if ((a.y() > point.y()) != (b.y() > point.y()) &&
        point.x() < (b.x() - a.x()) * (point.y() - a.y()) / (b.y() - a.y()) + a.x())
    {
      inside = !inside;
    }
  }
  return inside;
}

} // namespace thintissue
