#include "ProximityQueries.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thintissue
{

namespace
{

/// Largest squared edge length, used to scale tolerances.
double squaredScale(const Vector3& a, const Vector3& b, const Vector3& c)
{
  return std::max({ (b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm() });
}

double interpolate(const Vector3& barycentric, double ra, double rb, double rc)
{
  return barycentric[0] * ra + barycentric[1] * rb + barycentric[2] * rc;
}

int sideOf(const Vector3& unitNormal, const Vector3& offset)
{
  return unitNormal.dot(offset) >= 0.0 ? 1 : -1;
}

/// Barycentric coordinates for parameter s along edge k = (k, k+1 mod 3).
Vector3 edgeBarycentric(int edge, double s)
{
  Vector3 barycentric = Vector3::Zero();
  barycentric[edge] = 1.0 - s;
  barycentric[(edge + 1) % 3] = s;
  return barycentric;
}

/// Closest point of a degenerate triangle: the best of its three edges.
TriangleClosestPoint closestPointOnDegenerateTriangle(const Vector3& point,
  const std::array<const Vector3*, 3>& vertices)
{
  TriangleClosestPoint best;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k)
  {
    const SegmentClosestPoint s =
      closestPointOnSegment(point, *vertices[k], *vertices[(k + 1) % 3]);
    const double d = (s.point - point).squaredNorm();
    if (d < bestDistance)
    {
      bestDistance = d;
      best.point = s.point;
      best.barycentric = edgeBarycentric(k, s.parameter);
    }
  }
  return best;
}

/// Where segment [p, q] crosses the plane of triangle (a, b, c) inside the
/// triangle (edges included, within a relative tolerance). Coplanar
/// segments do not count as crossing.
bool segmentCrossesTriangle(const Vector3& p,
  const Vector3& q,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c,
  double& parameter,
  Vector3& barycentric)
{
  const Vector3 n = (b - a).cross(c - a);
  const double dp = n.dot(p - a);
  const double dq = n.dot(q - a);
  if ((dp > 0.0 && dq > 0.0) || (dp < 0.0 && dq < 0.0) || dp == dq)
  {
    return false;
  }
  parameter = dp / (dp - dq);
  const Vector3 x = p + parameter * (q - p);
  const double area2 = n.squaredNorm();
  if (area2 <= 0.0)
  {
    return false;
  }
  // Signed sub-areas relative to the whole.
  const double u = n.dot((b - x).cross(c - x)) / area2;
  const double v = n.dot((c - x).cross(a - x)) / area2;
  const double w = 1.0 - u - v;
  const double tolerance = 1e-12;
  if (u < -tolerance || v < -tolerance || w < -tolerance)
  {
    return false;
  }
  barycentric = Vector3(std::max(u, 0.0), std::max(v, 0.0), std::max(w, 0.0));
  barycentric /= barycentric.sum();
  return true;
}

} // namespace

//------------------------------------------------------------------------------
SegmentClosestPoint closestPointOnSegment(const Vector3& point, const Vector3& p, const Vector3& q)
{
  SegmentClosestPoint result;
  const Vector3 d = q - p;
  const double length2 = d.squaredNorm();
  if (length2 <= 0.0)
  {
    result.point = p;
    return result;
  }
  result.parameter = std::clamp(d.dot(point - p) / length2, 0.0, 1.0);
  result.point = p + result.parameter * d;
  return result;
}

//------------------------------------------------------------------------------
SegmentSegmentClosestPoints closestPointsBetweenSegments(const Vector3& p1,
  const Vector3& q1,
  const Vector3& p2,
  const Vector3& q2)
{
  // Ericson, Real-Time Collision Detection, 5.1.9, with relative tolerances.
  const Vector3 d1 = q1 - p1;
  const Vector3 d2 = q2 - p2;
  const Vector3 r = p1 - p2;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double f = d2.dot(r);
  const double tiny = std::numeric_limits<double>::min();
  double s = 0.0;
  double t = 0.0;
  if (a <= tiny && e <= tiny)
  {
    s = t = 0.0;
  }
  else if (a <= tiny)
  {
    s = 0.0;
    t = std::clamp(f / e, 0.0, 1.0);
  }
  else
  {
    const double c = d1.dot(r);
    if (e <= tiny)
    {
      t = 0.0;
      s = std::clamp(-c / a, 0.0, 1.0);
    }
    else
    {
      const double b = d1.dot(d2);
      const double denominator = a * e - b * b; // >= 0, |d1 x d2|^2
      // Parallel (within round-off): any s works; take s = 0 and let the
      // clamping below find the matching t, then re-project s.
      if (denominator > 1e-14 * a * e)
      {
        s = std::clamp((b * f - c * e) / denominator, 0.0, 1.0);
      }
      else
      {
        s = 0.0;
      }
      t = (b * s + f) / e;
      if (t < 0.0)
      {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      }
      else if (t > 1.0)
      {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  SegmentSegmentClosestPoints result;
  result.parameterOnFirst = s;
  result.parameterOnSecond = t;
  result.pointOnFirst = p1 + s * d1;
  result.pointOnSecond = p2 + t * d2;
  result.distance = (result.pointOnFirst - result.pointOnSecond).norm();
  return result;
}

//------------------------------------------------------------------------------
Vector3 orientedTriangleNormal(const Vector3& a, const Vector3& b, const Vector3& c)
{
  const Vector3 n = (b - a).cross(c - a);
  const double length = n.norm();
  if (!(length > 1e-14 * squaredScale(a, b, c)) || length == 0.0)
  {
    return Vector3::Zero();
  }
  return n / length;
}

//------------------------------------------------------------------------------
namespace
{
/// Whether the triangle with edge cross product `cross` is not degenerate
/// (the test of orientedTriangleNormal, without its square root).
bool isProperTriangle(const Vector3& cross, double squaredScaleOfTriangle)
{
  const double bound = 1e-14 * squaredScaleOfTriangle;
  const double squaredLength = cross.squaredNorm();
  return squaredLength > bound * bound && squaredLength > 0.0;
}

TriangleClosestPoint closestPointOnProperTriangle(const Vector3& p,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c);
} // namespace

TriangleClosestPoint closestPointOnTriangleWithBarycentric(const Vector3& p,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c)
{
  if (!isProperTriangle((b - a).cross(c - a), squaredScale(a, b, c)))
  {
    return closestPointOnDegenerateTriangle(p, { &a, &b, &c });
  }
  return closestPointOnProperTriangle(p, a, b, c);
}

namespace
{
TriangleClosestPoint closestPointOnProperTriangle(const Vector3& p,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c)
{
  // Voronoi-region walk (Ericson, Real-Time Collision Detection, 5.1.5).
  TriangleClosestPoint result;
  const Vector3 ab = b - a;
  const Vector3 ac = c - a;
  const Vector3 ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0)
  {
    result.point = a;
    result.barycentric = Vector3(1.0, 0.0, 0.0);
    return result;
  }
  const Vector3 bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3)
  {
    result.point = b;
    result.barycentric = Vector3(0.0, 1.0, 0.0);
    return result;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
  {
    const double v = d1 / (d1 - d3);
    result.point = a + v * ab;
    result.barycentric = Vector3(1.0 - v, v, 0.0);
    return result;
  }
  const Vector3 cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6)
  {
    result.point = c;
    result.barycentric = Vector3(0.0, 0.0, 1.0);
    return result;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
  {
    const double w = d2 / (d2 - d6);
    result.point = a + w * ac;
    result.barycentric = Vector3(1.0 - w, 0.0, w);
    return result;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
  {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    result.point = b + w * (c - b);
    result.barycentric = Vector3(0.0, 1.0 - w, w);
    return result;
  }
  const double denominator = 1.0 / (va + vb + vc);
  const double v = vb * denominator;
  const double w = vc * denominator;
  result.point = a + v * ab + w * ac;
  result.barycentric = Vector3(1.0 - v - w, v, w);
  return result;
}
} // namespace

//------------------------------------------------------------------------------
PointTriangleContact pointTriangleContact(const Vector3& point,
  double pointRadius,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c,
  double ra,
  double rb,
  double rc,
  double contactDistance)
{
  PointTriangleContact contact;
  // One cross product serves the degeneracy test, the side and the
  // fallback normal (this runs for every candidate of every vertex).
  const Vector3 cross = (b - a).cross(c - a);
  const double scale = squaredScale(a, b, c);
  const bool proper = isProperTriangle(cross, scale);
  const TriangleClosestPoint closest = proper
                                         ? closestPointOnProperTriangle(point, a, b, c)
                                         : closestPointOnDegenerateTriangle(point, { &a, &b, &c });
  contact.trianglePoint = closest.point;
  contact.barycentric = closest.barycentric;
  contact.triangleRadius = interpolate(closest.barycentric, ra, rb, rc);
  const Vector3 offset = point - closest.point;
  contact.distance = offset.norm();
  contact.side = proper ? sideOf(cross, point - a) : 1;
  const double tiny = 1e-12 * std::sqrt(scale);
  if (contact.distance > tiny)
  {
    contact.normal = offset / contact.distance;
  }
  else if (proper)
  {
    contact.normal = cross.normalized();
  }
  else
  {
    contact.normal = Vector3::UnitZ();
  }
  contact.depth = pointRadius + contact.triangleRadius - contact.distance;
  contact.withinContactDistance = contact.depth >= -contactDistance;
  return contact;
}

//------------------------------------------------------------------------------
SegmentTriangleContact segmentTriangleContact(const Vector3& p,
  const Vector3& q,
  double segmentRadius,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c,
  double ra,
  double rb,
  double rc,
  double contactDistance)
{
  SegmentTriangleContact contact;
  const Vector3 faceNormal = orientedTriangleNormal(a, b, c);
  double parameter = 0.0;
  Vector3 barycentric;
  if (segmentCrossesTriangle(p, q, a, b, c, parameter, barycentric))
  {
    contact.crossing = true;
    contact.segmentParameter = parameter;
    contact.barycentric = barycentric;
    contact.trianglePoint = barycentric[0] * a + barycentric[1] * b + barycentric[2] * c;
    contact.segmentPoint = p + parameter * (q - p);
    contact.distance = 0.0;
    const double dp = faceNormal.dot(p - a);
    const double dq = faceNormal.dot(q - a);
    contact.side = dp > 0.0 ? 1 : (dp < 0.0 ? -1 : (dq > 0.0 ? -1 : 1));
    contact.normal = contact.side * faceNormal;
  }
  else
  {
    // End points against the face, then the segment against the edges.
    double best = std::numeric_limits<double>::infinity();
    const Vector3* ends[2] = { &p, &q };
    for (int k = 0; k < 2; ++k)
    {
      const TriangleClosestPoint closest = closestPointOnTriangleWithBarycentric(*ends[k], a, b, c);
      const double d = (closest.point - *ends[k]).squaredNorm();
      if (d < best)
      {
        best = d;
        contact.segmentParameter = static_cast<double>(k);
        contact.segmentPoint = *ends[k];
        contact.trianglePoint = closest.point;
        contact.barycentric = closest.barycentric;
      }
    }
    const Vector3* vertices[3] = { &a, &b, &c };
    for (int k = 0; k < 3; ++k)
    {
      const SegmentSegmentClosestPoints s =
        closestPointsBetweenSegments(p, q, *vertices[k], *vertices[(k + 1) % 3]);
      const double d = s.distance * s.distance;
      if (d < best)
      {
        best = d;
        contact.segmentParameter = s.parameterOnFirst;
        contact.segmentPoint = s.pointOnFirst;
        contact.trianglePoint = s.pointOnSecond;
        contact.barycentric = edgeBarycentric(k, s.parameterOnSecond);
      }
    }
    const Vector3 offset = contact.segmentPoint - contact.trianglePoint;
    contact.distance = offset.norm();
    contact.side = sideOf(faceNormal, contact.segmentPoint - a);
    const double tiny = 1e-12 * std::sqrt(squaredScale(a, b, c));
    if (contact.distance > tiny)
    {
      contact.normal = offset / contact.distance;
    }
    else if (!faceNormal.isZero())
    {
      contact.normal = contact.side * faceNormal;
    }
    else
    {
      contact.normal = Vector3::UnitZ();
    }
  }
  contact.triangleRadius = interpolate(contact.barycentric, ra, rb, rc);
  contact.depth = segmentRadius + contact.triangleRadius - contact.distance;
  contact.withinContactDistance = contact.depth >= -contactDistance;
  return contact;
}

//------------------------------------------------------------------------------
TriangleTriangleProximity triangleTriangleProximity(const std::array<Vector3, 3>& a,
  const std::array<double, 3>& radiiA,
  const std::array<Vector3, 3>& b,
  const std::array<double, 3>& radiiB,
  double contactDistance)
{
  TriangleTriangleProximity result;
  const Vector3 normalA = orientedTriangleNormal(a[0], a[1], a[2]);
  const Vector3 normalB = orientedTriangleNormal(b[0], b[1], b[2]);
  const Vector3 centroidOffset = (a[0] + a[1] + a[2] - b[0] - b[1] - b[2]) / 3.0;
  const double tiny =
    1e-12 * std::sqrt(std::max(squaredScale(a[0], a[1], a[2]), squaredScale(b[0], b[1], b[2])));

  auto add = [&](TriangleTriangleContact& contact)
  {
    contact.depth = contact.radiusA + contact.radiusB - contact.distance;
    contact.withinContactDistance = contact.depth >= -contactDistance;
    if (!contact.withinContactDistance)
    {
      return;
    }
    // B touches A from A's positive side when B lies along +normalA from A.
    contact.sideOnA = sideOf(normalA, -contact.normal);
    contact.sideOnB = sideOf(normalB, contact.normal);
    result.contacts[result.count] = contact;
    if (result.deepest < 0 || contact.depth > result.contacts[result.deepest].depth)
    {
      result.deepest = result.count;
    }
    ++result.count;
  };

  for (int i = 0; i < 3; ++i)
  {
    const PointTriangleContact pt = pointTriangleContact(
      a[i], radiiA[i], b[0], b[1], b[2], radiiB[0], radiiB[1], radiiB[2], contactDistance);
    TriangleTriangleContact contact;
    contact.kind = TriangleTriangleContact::Kind::VertexOfAOnFaceOfB;
    contact.featureA = i;
    contact.pointA = a[i];
    contact.barycentricA = Vector3::Unit(i);
    contact.radiusA = radiiA[i];
    contact.pointB = pt.trianglePoint;
    contact.barycentricB = pt.barycentric;
    contact.radiusB = pt.triangleRadius;
    contact.distance = pt.distance;
    contact.normal = pt.normal;
    add(contact);
  }
  for (int j = 0; j < 3; ++j)
  {
    const PointTriangleContact pt = pointTriangleContact(
      b[j], radiiB[j], a[0], a[1], a[2], radiiA[0], radiiA[1], radiiA[2], contactDistance);
    TriangleTriangleContact contact;
    contact.kind = TriangleTriangleContact::Kind::VertexOfBOnFaceOfA;
    contact.featureB = j;
    contact.pointB = b[j];
    contact.barycentricB = Vector3::Unit(j);
    contact.radiusB = radiiB[j];
    contact.pointA = pt.trianglePoint;
    contact.barycentricA = pt.barycentric;
    contact.radiusA = pt.triangleRadius;
    contact.distance = pt.distance;
    contact.normal = -pt.normal;
    add(contact);
  }
  for (int i = 0; i < 3; ++i)
  {
    const int i1 = (i + 1) % 3;
    for (int j = 0; j < 3; ++j)
    {
      const int j1 = (j + 1) % 3;
      const SegmentSegmentClosestPoints s = closestPointsBetweenSegments(a[i], a[i1], b[j], b[j1]);
      TriangleTriangleContact contact;
      contact.kind = TriangleTriangleContact::Kind::EdgeEdge;
      contact.featureA = i;
      contact.featureB = j;
      contact.pointA = s.pointOnFirst;
      contact.pointB = s.pointOnSecond;
      contact.barycentricA = edgeBarycentric(i, s.parameterOnFirst);
      contact.barycentricB = edgeBarycentric(j, s.parameterOnSecond);
      contact.radiusA = (1.0 - s.parameterOnFirst) * radiiA[i] + s.parameterOnFirst * radiiA[i1];
      contact.radiusB = (1.0 - s.parameterOnSecond) * radiiB[j] + s.parameterOnSecond * radiiB[j1];
      contact.distance = s.distance;
      if (s.distance > tiny)
      {
        contact.normal = (s.pointOnFirst - s.pointOnSecond) / s.distance;
      }
      else
      {
        // Crossing edges: the normal of the plane of both edges, or B's face
        // normal for parallel edges, oriented from B toward A.
        Vector3 n = (a[i1] - a[i]).cross(b[j1] - b[j]);
        if (n.norm() <= tiny * tiny)
        {
          n = normalB;
        }
        n = n.isZero() ? Vector3::UnitZ() : n.normalized();
        contact.normal = n.dot(centroidOffset) >= 0.0 ? n : -n;
      }
      add(contact);
    }
  }

  double parameter = 0.0;
  Vector3 barycentric;
  for (int k = 0; k < 3 && !result.intersecting; ++k)
  {
    result.intersecting =
      segmentCrossesTriangle(a[k], a[(k + 1) % 3], b[0], b[1], b[2], parameter, barycentric) ||
      segmentCrossesTriangle(b[k], b[(k + 1) % 3], a[0], a[1], a[2], parameter, barycentric);
  }
  return result;
}

} // namespace thintissue
