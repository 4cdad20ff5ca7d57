#include "ContactKernels.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thintissue
{
namespace contact_kernels
{

ThickMeshView viewOf(const DeformableCollisionMesh& mesh)
{
  return { &mesh.positions(),
    &mesh.triangles(),
    &mesh.radii(),
    &mesh.bvh(),
    &mesh.vertexNormals(),
    mesh.contactDistance(),
    mesh.identity() };
}

ThickMeshView viewOf(const StaticObstacle& obstacle)
{
  return { &obstacle.surface().positions,
    &obstacle.surface().triangles,
    &obstacle.radii(),
    &obstacle.bvh(),
    nullptr,
    obstacle.contactDistance() };
}

namespace
{

/// The sphere (centre, thickness) against triangle t of `mesh`, kept in
/// `deepest` when it penetrates deeper than what is kept (the first of
/// equal depths stays).
void keepDeeperPointContact(const Vector3& centre,
  double thickness,
  const ThickMeshView& mesh,
  int t,
  DeepestPointContact& deepest)
{
  const auto& positions = *mesh.positions;
  const auto& radii = *mesh.radii;
  const Triangle& tri = (*mesh.triangles)[t];
  const PointTriangleContact c = pointTriangleContact(centre,
    thickness,
    positions[tri[0]],
    positions[tri[1]],
    positions[tri[2]],
    radii[tri[0]],
    radii[tri[1]],
    radii[tri[2]],
    0.0);
  if (c.penetrating() && (deepest.triangle < 0 || c.depth > deepest.contact.depth))
  {
    deepest.contact = c;
    deepest.triangle = t;
  }
}

} // namespace

DeepestPointContact deepestSphereContact(const Vector3& centre,
  double radius,
  const ThickMeshView& mesh)
{
  const double thickness = radius + mesh.contactDistance;
  BoundingBox query(centre);
  query.min().array() -= radius;
  query.max().array() += radius;
  DeepestPointContact deepest;
  mesh.bvh->forEachOverlap(
    query, [&](int t) { keepDeeperPointContact(centre, thickness, mesh, t, deepest); });
  return deepest;
}

DeepestSegmentContact deepestCapsuleContact(const ToolCapsule& capsule, const ThickMeshView& mesh)
{
  const auto& positions = *mesh.positions;
  const auto& radii = *mesh.radii;
  BoundingBox query(capsule.start);
  query.extend(capsule.end);
  query.min().array() -= capsule.radius;
  query.max().array() += capsule.radius;
  DeepestSegmentContact deepest;
  mesh.bvh->forEachOverlap(query,
    [&](int t)
    {
      const Triangle& tri = (*mesh.triangles)[t];
      const SegmentTriangleContact c = segmentTriangleContact(capsule.start,
        capsule.end,
        capsule.radius + mesh.contactDistance,
        positions[tri[0]],
        positions[tri[1]],
        positions[tri[2]],
        radii[tri[0]],
        radii[tri[1]],
        radii[tri[2]],
        0.0);
      if (c.penetrating() && (deepest.triangle < 0 || c.depth > deepest.contact.depth))
      {
        deepest.contact = c;
        deepest.triangle = t;
      }
    });
  return deepest;
}

namespace
{

/// Side of `mesh` that a body lying in `towardOther` touches, from the
/// vertex normals interpolated at the feature (+1 without normals).
int sideOf(const ThickMeshView& mesh,
  const std::array<int, 3>& vertices,
  const Vector3& weights,
  const Vector3& towardOther)
{
  if (mesh.vertexNormals == nullptr)
  {
    return 1;
  }
  Vector3 normal = Vector3::Zero();
  for (int k = 0; k < 3; ++k)
  {
    if (vertices[k] >= 0)
    {
      normal += weights[k] * (*mesh.vertexNormals)[vertices[k]];
    }
  }
  return normal.dot(towardOther) >= 0.0 ? 1 : -1;
}

/// The contact of vertex v of `from` with the triangle `deepest` of
/// `onto`. `fromIsA` says which side of the FeatureContact `from` fills.
void addVertexContact(const ThickMeshView& from,
  const ThickMeshView& onto,
  bool fromIsA,
  int v,
  const DeepestPointContact& deepest,
  std::vector<FeatureContact>& contacts)
{
  const Vector3& position = (*from.positions)[v];
  const Triangle& tri = (*onto.triangles)[deepest.triangle];
  // pointTriangleContact's normal points from the triangle to the vertex.
  const std::array<int, 3> vertex{ { v, -1, -1 } };
  const std::array<int, 3> face{ { tri[0], tri[1], tri[2] } };
  const Vector3 unit(1.0, 0.0, 0.0);
  const Vector3& n = deepest.contact.normal;
  FeatureContact c;
  c.depth = deepest.contact.depth;
  if (fromIsA)
  {
    c.verticesA = vertex;
    c.weightsA = unit;
    c.pointA = position;
    c.verticesB = face;
    c.weightsB = deepest.contact.barycentric;
    c.pointB = deepest.contact.trianglePoint;
    c.normal = n;
  }
  else
  {
    c.verticesA = face;
    c.weightsA = deepest.contact.barycentric;
    c.pointA = deepest.contact.trianglePoint;
    c.verticesB = vertex;
    c.weightsB = unit;
    c.pointB = position;
    c.normal = -n;
  }
  contacts.push_back(c);
}

/// The box of a vertex's sphere (its radius and the mesh's contact distance).
BoundingBox sphereBox(const ThickMeshView& mesh, int v, double reach)
{
  BoundingBox sphere((*mesh.positions)[v]);
  sphere.min().array() -= reach;
  sphere.max().array() += reach;
  return sphere;
}

/// Vertex v of `from` against the triangles of `onto` (the deepest).
void vertexFaceContact(const ThickMeshView& from,
  const ThickMeshView& onto,
  bool fromIsA,
  int v,
  std::vector<FeatureContact>& contacts)
{
  const double radius = (*from.radii)[v] + from.contactDistance;
  if (!sphereBox(from, v, radius).intersects(onto.bvh->bounds()))
  {
    return;
  }
  const DeepestPointContact deepest = deepestSphereContact((*from.positions)[v], radius, onto);
  if (deepest.triangle >= 0)
  {
    addVertexContact(from, onto, fromIsA, v, deepest, contacts);
  }
}

/// Every vertex of `from` against the triangles of `onto` (deepest each).
void vertexFaceContacts(const ThickMeshView& from,
  const ThickMeshView& onto,
  bool fromIsA,
  std::vector<FeatureContact>& contacts)
{
  const int count = static_cast<int>(from.positions->size());
  for (int v = 0; v < count; ++v)
  {
    vertexFaceContact(from, onto, fromIsA, v, contacts);
  }
}

/// Parameters closer than this to an edge's end are the vertex contacts'.
constexpr double InsideEdge = 1e-6;

/// False when the closest points of segments p1q1 and p2q2 cannot both be
/// inside (InsideEdge from the ends): where the lines' closest points lie
/// off either segment, the segments' lie at an end. It evaluates the same
/// expressions as closestPointsBetweenSegments (Ericson 5.1.9), so exactly
/// the pairs it would reject are rejected; near-parallel edges pass (that
/// function decides them). Of the edge pairs of a meniscus resting on the
/// cartilage that pass the box and line-distance tests, 90 % stop here.
bool linesMeetInsideBoth(const Vector3& p1, const Vector3& q1, const Vector3& p2, const Vector3& q2)
{
  const Vector3 d1 = q1 - p1;
  const Vector3 d2 = q2 - p2;
  const Vector3 r = p1 - p2;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double tiny = std::numeric_limits<double>::min();
  if (a <= tiny || e <= tiny)
  {
    return true;
  }
  const double b = d1.dot(d2);
  const double denominator = a * e - b * b;
  if (!(denominator > 1e-14 * a * e))
  {
    return true;
  }
  const double c = d1.dot(r);
  const double f = d2.dot(r);
  const double s = (b * f - c * e) / denominator;
  if (s <= InsideEdge || s >= 1.0 - InsideEdge)
  {
    return false;
  }
  const double t = (b * s + f) / e;
  return t > InsideEdge && t < 1.0 - InsideEdge;
}

std::uint64_t edgeKey(int v0, int v1)
{
  const auto lo = static_cast<std::uint64_t>(std::min(v0, v1));
  const auto hi = static_cast<std::uint64_t>(std::max(v0, v1));
  return (lo << 32) | hi;
}

/// Box of edge pq inflated by `reach` (an edge's radius and contact distance).
BoundingBox edgeBox(const Vector3& p, const Vector3& q, double reach)
{
  BoundingBox box(p);
  box.extend(q);
  box.min().array() -= reach;
  box.max().array() += reach;
  return box;
}

/// The contact of A's edge (a0, a1) of triangle triA with B's edge (b0, b1)
/// of triB, if their closest points are inside both and the thick edges
/// overlap; appended to workspace.edgeContacts.
void testEdgePair(const ThickMeshView& a,
  const ThickMeshView& b,
  int a0,
  int a1,
  int b0,
  int b1,
  const Triangle& triA,
  const Triangle& triB,
  MeshMeshWorkspace& workspace)
{
  const auto& pa = *a.positions;
  const auto& pb = *b.positions;
  const auto& ra = *a.radii;
  const auto& rb = *b.radii;
  const double margin = a.contactDistance + b.contactDistance;
  // The distance between the two lines bounds the segments' from below:
  // many pairs the boxes let through are rejected here, cheaply.
  const Vector3 normal = (pa[a1] - pa[a0]).cross(pb[b1] - pb[b0]);
  const double gap = normal.dot(pa[a0] - pb[b0]);
  const double reach = std::max(ra[a0], ra[a1]) + std::max(rb[b0], rb[b1]) + margin;
  if (gap * gap > reach * reach * normal.squaredNorm() ||
      !linesMeetInsideBoth(pa[a0], pa[a1], pb[b0], pb[b1]))
  {
    return;
  }
  const SegmentSegmentClosestPoints closest =
    closestPointsBetweenSegments(pa[a0], pa[a1], pb[b0], pb[b1]);
  const double s = closest.parameterOnFirst;
  const double t = closest.parameterOnSecond;
  if (s <= InsideEdge || s >= 1.0 - InsideEdge || t <= InsideEdge || t >= 1.0 - InsideEdge)
  {
    return;
  }
  const double radius = (1.0 - s) * ra[a0] + s * ra[a1] + (1.0 - t) * rb[b0] + t * rb[b1] + margin;
  const double depth = radius - closest.distance;
  if (!(depth > 0.0))
  {
    return;
  }
  FeatureContact c;
  c.verticesA = { { a0, a1, -1 } };
  c.weightsA = Vector3(1.0 - s, s, 0.0);
  c.verticesB = { { b0, b1, -1 } };
  c.weightsB = Vector3(1.0 - t, t, 0.0);
  c.pointA = closest.pointOnFirst;
  c.pointB = closest.pointOnSecond;
  c.depth = depth;
  const Vector3 offset = c.pointA - c.pointB;
  const double scale = (pa[a1] - pa[a0]).norm() + (pb[b1] - pb[b0]).norm();
  if (closest.distance > 1e-12 * scale)
  {
    c.normal = offset / closest.distance;
  }
  else
  {
    // Crossing edges: perpendicular to both, toward A's triangle.
    Vector3 n = (pa[a1] - pa[a0]).cross(pb[b1] - pb[b0]);
    const Vector3 centreA = (pa[triA[0]] + pa[triA[1]] + pa[triA[2]]) / 3.0;
    const Vector3 centreB = (pb[triB[0]] + pb[triB[1]] + pb[triB[2]]) / 3.0;
    if (n.dot(centreA - centreB) < 0.0)
    {
      n = -n;
    }
    c.normal = n.norm() > 0.0 ? Vector3(n.normalized()) : Vector3(Vector3::UnitZ());
  }
  workspace.edgeContacts.push_back({ edgeKey(a0, a1), edgeKey(b0, b1), c });
}

/// workspace.edgeBoxesOfA[3 t + i]: the box of edge i of A's triangle t,
/// for the triangles near B only (every triangle an edge box of B can reach
/// lies in B's bounds): each is tested against many of B's edges.
void boxEdgesOfANearB(const ThickMeshView& a, const ThickMeshView& b, MeshMeshWorkspace& workspace)
{
  const auto& pa = *a.positions;
  const auto& ra = *a.radii;
  workspace.edgeBoxesOfA.resize(3 * a.triangles->size());
  a.bvh->forEachOverlap(b.bvh->bounds(),
    [&](int ta)
    {
      const Triangle& triA = (*a.triangles)[ta];
      for (int i = 0; i < 3; ++i)
      {
        const int a0 = triA[i];
        const int a1 = triA[(i + 1) % 3];
        workspace.edgeBoxesOfA[3 * ta + i] =
          edgeBox(pa[a0], pa[a1], std::max(ra[a0], ra[a1]) + a.contactDistance);
      }
    });
}

/// Edge-edge: crossings of edges inside both (an edge of a coarse tissue
/// triangle across a tool's edge). Each edge pair is tested once, by the
/// triangles owning the two edges (TriangleBvh::ownedEdges), and only when
/// no end of either edge has a vertex contact (workspace.touchingA/B): there
/// the vertex contacts already hold the surfaces (face to face) and an edge
/// contact would count the same overlap again. Box tests reject most pairs
/// before the closest points are computed. Fills workspace.edgeContacts
/// (in the order the trees visit the pairs).
void edgeEdgeContacts(const ThickMeshView& a, const ThickMeshView& b, MeshMeshWorkspace& workspace)
{
  const auto& pb = *b.positions;
  const auto& rb = *b.radii;
  boxEdgesOfANearB(a, b, workspace);
  // Each owned edge of B whose ends are free queries A's tree with its box
  // (tighter than its triangle's); each owned, free edge of A in the
  // triangles found is tested once. (Measured on the knee of table 6-2
  // against descending both trees to triangle pairs: 1.6 vs 2.2 ms per
  // step in setting 2, 0.54 vs 0.60 ms in setting 3.)
  // B's triangles near A only (its tree prunes the rest).
  b.bvh->forEachOverlap(a.bvh->bounds(),
    [&](int tb)
    {
      const std::uint8_t ownedB = b.bvh->ownedEdges(tb);
      const Triangle& triB = (*b.triangles)[tb];
      for (int j = 0; j < 3; ++j)
      {
        const int b0 = triB[j];
        const int b1 = triB[(j + 1) % 3];
        if (!(ownedB & (1u << j)) || workspace.touchingB[b0] || workspace.touchingB[b1])
        {
          continue;
        }
        const BoundingBox boxB =
          edgeBox(pb[b0], pb[b1], std::max(rb[b0], rb[b1]) + b.contactDistance);
        a.bvh->forEachOverlap(boxB,
          [&](int ta)
          {
            const std::uint8_t ownedA = a.bvh->ownedEdges(ta);
            const Triangle& triA = (*a.triangles)[ta];
            for (int i = 0; i < 3; ++i)
            {
              const int a0 = triA[i];
              const int a1 = triA[(i + 1) % 3];
              if ((ownedA & (1u << i)) && !workspace.touchingA[a0] && !workspace.touchingA[a1] &&
                  workspace.edgeBoxesOfA[3 * ta + i].intersects(boxB))
              {
                testEdgePair(a, b, a0, a1, b0, b1, triA, triB, workspace);
              }
            }
          });
      }
    });
}

/// What both narrow phases share once the vertex-face contacts are in
/// contacts[firstContact, end): the edge-edge contacts of the edges with no
/// vertex contact at an end (found by `edgeSearch`, which fills
/// workspace.edgeContacts) in a fixed order (by edges, whatever order the
/// search met them), then each contact's sides.
template <typename EdgeSearch>
void finishContacts(const ThickMeshView& a,
  const ThickMeshView& b,
  std::size_t firstContact,
  MeshMeshWorkspace& workspace,
  std::vector<FeatureContact>& contacts,
  EdgeSearch&& edgeSearch)
{
  const std::size_t vertexContactsEnd = contacts.size();
  workspace.touchingA.resize(a.positions->size(), 0);
  workspace.touchingB.resize(b.positions->size(), 0);
  auto markVertices = [&](char flag)
  {
    for (std::size_t k = firstContact; k < vertexContactsEnd; ++k)
    {
      const FeatureContact& c = contacts[k];
      if (c.verticesA[1] < 0)
      {
        workspace.touchingA[c.verticesA[0]] = flag;
      }
      if (c.verticesB[1] < 0)
      {
        workspace.touchingB[c.verticesB[0]] = flag;
      }
    }
  };
  markVertices(1);
  workspace.edgeContacts.clear();
  edgeSearch();
  markVertices(0);
  auto byEdges = [](
                   const MeshMeshWorkspace::EdgeContact& x, const MeshMeshWorkspace::EdgeContact& y)
  { return x.edgeOfA != y.edgeOfA ? x.edgeOfA < y.edgeOfA : x.edgeOfB < y.edgeOfB; };
  std::sort(workspace.edgeContacts.begin(), workspace.edgeContacts.end(), byEdges);
  for (const MeshMeshWorkspace::EdgeContact& edge : workspace.edgeContacts)
  {
    contacts.push_back(edge.contact);
  }
  for (std::size_t k = firstContact; k < contacts.size(); ++k)
  {
    FeatureContact& c = contacts[k];
    c.sideOnA = sideOf(a, c.verticesA, c.weightsA, -c.normal);
    c.sideOnB = sideOf(b, c.verticesB, c.weightsB, c.normal);
  }
}

// --- Candidates of a deformable mesh A against a static mesh B. While no
// vertex of A has moved more than the margin m, a feature pair further
// apart than its reach plus m when found cannot touch (distances between
// a moving and a fixed feature change by at most m), and every box of A
// lies within its box when found, inflated by m. The search inflates by a
// little more than m so that rounding never drops a pair that may touch;
// the contacts are then computed exactly as meshMeshContacts does, with
// the same box tests, so they come out bit for bit the same.

/// Inflation of the search beyond the margin (relative).
constexpr double SearchSlack = 1.001;

BoundingBox inflated(BoundingBox box, double by)
{
  box.min().array() -= by;
  box.max().array() += by;
  return box;
}

double largestRadius(const std::vector<double>& radii, const Triangle& t)
{
  return std::max({ radii[t[0]], radii[t[1]], radii[t[2]] });
}

/// B's triangles that vertex v of A may reach, in the order B's tree
/// visits them (so that the deepest keeps its tie-breaking).
void findVertexTriangles(const ThickMeshView& a,
  const ThickMeshView& b,
  int v,
  double reach,
  StaticPairCandidates& candidates)
{
  const Vector3& x = (*a.positions)[v];
  const auto& pb = *b.positions;
  const auto& rb = *b.radii;
  const double radius = (*a.radii)[v] + a.contactDistance;
  b.bvh->forEachOverlap(sphereBox(a, v, radius + reach),
    [&](int t)
    {
      const Triangle& tri = (*b.triangles)[t];
      const double distance =
        pointTriangleContact(x, 0.0, pb[tri[0]], pb[tri[1]], pb[tri[2]], 0.0, 0.0, 0.0, 0.0)
          .distance;
      const double clearance = distance - (radius + b.contactDistance + largestRadius(rb, tri));
      if (clearance < reach)
      {
        candidates.vertexTriangles.push_back(t);
        candidates.vertexTriangleBoxes.push_back(
          TriangleBvh::triangleBox(pb, tri, rb, b.bvh->contactDistance()));
        candidates.vertexTriangleClearances.push_back(clearance);
      }
    });
}

/// A's triangles that B's vertex w may reach (a triangle whose vertices
/// move at most m moves at most m), in the order A's tree visits them.
/// False when there is none.
bool findTrianglesOfA(const ThickMeshView& a,
  const ThickMeshView& b,
  int w,
  double reach,
  StaticPairCandidates& candidates)
{
  const Vector3& x = (*b.positions)[w];
  const auto& pa = *a.positions;
  const auto& ra = *a.radii;
  const double radius = (*b.radii)[w] + b.contactDistance;
  const std::size_t before = candidates.trianglesOfA.size();
  a.bvh->forEachOverlap(sphereBox(b, w, radius + reach),
    [&](int t)
    {
      const Triangle& tri = (*a.triangles)[t];
      const double distance =
        pointTriangleContact(x, 0.0, pa[tri[0]], pa[tri[1]], pa[tri[2]], 0.0, 0.0, 0.0, 0.0)
          .distance;
      const double clearance = distance - (radius + a.contactDistance + largestRadius(ra, tri));
      if (clearance < reach)
      {
        candidates.trianglesOfA.push_back(t);
        candidates.triangleOfAClearances.push_back(clearance);
      }
    });
  return candidates.trianglesOfA.size() > before;
}

/// Owned edge pairs of A's triangles near B's edge (b0, b1) of triangle tb.
void findEdgePairsOf(const ThickMeshView& a,
  const ThickMeshView& b,
  int b0,
  int b1,
  int tb,
  double reach,
  StaticPairCandidates& candidates)
{
  const auto& pa = *a.positions;
  const auto& ra = *a.radii;
  const auto& pb = *b.positions;
  const auto& rb = *b.radii;
  const double reachB = std::max(rb[b0], rb[b1]) + b.contactDistance;
  const BoundingBox boxB = edgeBox(pb[b0], pb[b1], reachB);
  const BoundingBox query = inflated(boxB, reach);
  a.bvh->forEachOverlap(query,
    [&](int ta)
    {
      const std::uint8_t ownedA = a.bvh->ownedEdges(ta);
      const Triangle& triA = (*a.triangles)[ta];
      for (int i = 0; i < 3; ++i)
      {
        const int a0 = triA[i];
        const int a1 = triA[(i + 1) % 3];
        const double reachA = std::max(ra[a0], ra[a1]) + a.contactDistance;
        if (!(ownedA & (1u << i)) || !edgeBox(pa[a0], pa[a1], reachA).intersects(query))
        {
          continue;
        }
        const double clearance =
          closestPointsBetweenSegments(pa[a0], pa[a1], pb[b0], pb[b1]).distance - (reachA + reachB);
        if (clearance < reach)
        {
          candidates.edgePairs.push_back({ a0, a1, ta, b0, b1, tb, boxB, clearance });
        }
      }
    });
}

/// Searches every candidate again around A's current positions.
void findCandidates(const ThickMeshView& a,
  const ThickMeshView& b,
  double margin,
  StaticPairCandidates& candidates)
{
  const double reach = SearchSlack * margin;
  candidates.identityOfA = a.identity;
  candidates.treeOfB = b.bvh;
  candidates.margin = margin;
  candidates.positionsOfA = *a.positions;
  ++candidates.searches;
  const int countA = static_cast<int>(a.positions->size());
  candidates.vertexStart.assign(1, 0);
  candidates.vertexTriangles.clear();
  candidates.vertexTriangleBoxes.clear();
  candidates.vertexTriangleClearances.clear();
  candidates.movesOfA.assign(a.positions->size(), 0.0);
  for (int v = 0; v < countA; ++v)
  {
    findVertexTriangles(a, b, v, reach, candidates);
    candidates.vertexStart.push_back(static_cast<int>(candidates.vertexTriangles.size()));
  }
  candidates.verticesOfB.clear();
  candidates.triangleStart.assign(1, 0);
  candidates.trianglesOfA.clear();
  candidates.triangleOfAClearances.clear();
  const BoundingBox boundsOfA = inflated(a.bvh->bounds(), reach);
  const int countB = static_cast<int>(b.positions->size());
  for (int w = 0; w < countB; ++w)
  {
    if (sphereBox(b, w, (*b.radii)[w] + b.contactDistance + reach).intersects(boundsOfA) &&
        findTrianglesOfA(a, b, w, reach, candidates))
    {
      candidates.verticesOfB.push_back(w);
      candidates.triangleStart.push_back(static_cast<int>(candidates.trianglesOfA.size()));
    }
  }
  candidates.edgePairs.clear();
  b.bvh->forEachOverlap(boundsOfA,
    [&](int tb)
    {
      const Triangle& triB = (*b.triangles)[tb];
      for (int j = 0; j < 3; ++j)
      {
        if (b.bvh->ownedEdges(tb) & (1u << j))
        {
          findEdgePairsOf(a, b, triB[j], triB[(j + 1) % 3], tb, reach, candidates);
        }
      }
    });
}

/// Whether the candidates still hold: the same meshes, no vertex of A
/// further than the margin from where it was (how far each is goes to
/// candidates.movesOfA).
bool candidatesHold(const ThickMeshView& a,
  const ThickMeshView& b,
  double margin,
  StaticPairCandidates& candidates)
{
  if (a.identity == 0 || candidates.identityOfA != a.identity || candidates.treeOfB != b.bvh ||
      candidates.margin != margin || candidates.positionsOfA.size() != a.positions->size())
  {
    return false;
  }
  const double squaredMargin = margin * margin;
  const auto& positions = *a.positions;
  for (std::size_t v = 0; v < positions.size(); ++v)
  {
    const double squaredMove = (positions[v] - candidates.positionsOfA[v]).squaredNorm();
    if (squaredMove > squaredMargin)
    {
      return false;
    }
    candidates.movesOfA[v] = std::sqrt(squaredMove);
  }
  return true;
}

/// A candidate pair whose clearance when found exceeds how far its moving
/// features have gone since cannot touch (a distance between a moving and
/// a fixed feature changes by at most the move): skipped. The allowance
/// (SearchSlack, relative to the margin) keeps rounding from skipping a
/// pair that touches.
bool outOfReach(double clearance, double move, double margin)
{
  return clearance > move + (SearchSlack - 1.0) * margin;
}

/// Vertex v of A against its candidate triangles of B: what
/// deepestSphereContact finds in B's tree (same box test, same order).
void vertexCandidateContact(const ThickMeshView& a,
  const ThickMeshView& b,
  int v,
  const StaticPairCandidates& candidates,
  std::vector<FeatureContact>& contacts)
{
  const int first = candidates.vertexStart[v];
  const int end = candidates.vertexStart[v + 1];
  if (first == end)
  {
    return;
  }
  const Vector3& x = (*a.positions)[v];
  const double radius = (*a.radii)[v] + a.contactDistance;
  const double thickness = radius + b.contactDistance;
  const BoundingBox query = sphereBox(a, v, radius);
  const double move = candidates.movesOfA[v];
  DeepestPointContact deepest;
  for (int k = first; k < end; ++k)
  {
    if (!outOfReach(candidates.vertexTriangleClearances[k], move, candidates.margin) &&
        candidates.vertexTriangleBoxes[k].intersects(query))
    {
      keepDeeperPointContact(x, thickness, b, candidates.vertexTriangles[k], deepest);
    }
  }
  if (deepest.triangle >= 0)
  {
    addVertexContact(a, b, true, v, deepest, contacts);
  }
}

/// B's vertex verticesOfB[k] against its candidate triangles of A: what
/// deepestSphereContact finds in A's tree (same boxes, same order).
void vertexOfBCandidateContact(const ThickMeshView& a,
  const ThickMeshView& b,
  std::size_t k,
  const StaticPairCandidates& candidates,
  std::vector<FeatureContact>& contacts)
{
  const int w = candidates.verticesOfB[k];
  const Vector3& x = (*b.positions)[w];
  const double radius = (*b.radii)[w] + b.contactDistance;
  const double thickness = radius + a.contactDistance;
  const BoundingBox query = sphereBox(b, w, radius);
  const auto& pa = *a.positions;
  const auto& ra = *a.radii;
  DeepestPointContact deepest;
  const auto& moves = candidates.movesOfA;
  for (int i = candidates.triangleStart[k]; i < candidates.triangleStart[k + 1]; ++i)
  {
    const int t = candidates.trianglesOfA[i];
    const Triangle& tri = (*a.triangles)[t];
    const double move = std::max({ moves[tri[0]], moves[tri[1]], moves[tri[2]] });
    if (!outOfReach(candidates.triangleOfAClearances[i], move, candidates.margin) &&
        TriangleBvh::triangleBox(pa, tri, ra, a.bvh->contactDistance()).intersects(query))
    {
      keepDeeperPointContact(x, thickness, a, t, deepest);
    }
  }
  if (deepest.triangle >= 0)
  {
    addVertexContact(b, a, false, w, deepest, contacts);
  }
}

/// The candidate edge pairs whose ends are free and whose boxes overlap.
void edgeCandidateContacts(const ThickMeshView& a,
  const ThickMeshView& b,
  const StaticPairCandidates& candidates,
  MeshMeshWorkspace& workspace)
{
  const auto& pa = *a.positions;
  const auto& ra = *a.radii;
  const auto& moves = candidates.movesOfA;
  for (const StaticPairCandidates::EdgePair& e : candidates.edgePairs)
  {
    if (outOfReach(e.clearance, std::max(moves[e.a0], moves[e.a1]), candidates.margin) ||
        workspace.touchingA[e.a0] || workspace.touchingA[e.a1] || workspace.touchingB[e.b0] ||
        workspace.touchingB[e.b1])
    {
      continue;
    }
    const double reachA = std::max(ra[e.a0], ra[e.a1]) + a.contactDistance;
    if (edgeBox(pa[e.a0], pa[e.a1], reachA).intersects(e.boxB))
    {
      testEdgePair(a,
        b,
        e.a0,
        e.a1,
        e.b0,
        e.b1,
        (*a.triangles)[e.triangleA],
        (*b.triangles)[e.triangleB],
        workspace);
    }
  }
}

} // namespace

void meshMeshContacts(const ThickMeshView& a,
  const ThickMeshView& b,
  MeshMeshWorkspace& workspace,
  std::vector<FeatureContact>& contacts)
{
  const std::size_t firstContact = contacts.size();
  vertexFaceContacts(a, b, true, contacts);
  vertexFaceContacts(b, a, false, contacts);
  finishContacts(
    a, b, firstContact, workspace, contacts, [&] { edgeEdgeContacts(a, b, workspace); });
}

void meshStaticContacts(const ThickMeshView& a,
  const ThickMeshView& b,
  double margin,
  StaticPairCandidates& candidates,
  MeshMeshWorkspace& workspace,
  std::vector<FeatureContact>& contacts)
{
  if (!(margin > 0.0) || a.identity == 0)
  {
    meshMeshContacts(a, b, workspace, contacts);
    return;
  }
  if (!candidatesHold(a, b, margin, candidates))
  {
    findCandidates(a, b, margin, candidates);
  }
  const std::size_t firstContact = contacts.size();
  const int countA = static_cast<int>(a.positions->size());
  for (int v = 0; v < countA; ++v)
  {
    vertexCandidateContact(a, b, v, candidates, contacts);
  }
  for (std::size_t k = 0; k < candidates.verticesOfB.size(); ++k)
  {
    vertexOfBCandidateContact(a, b, k, candidates, contacts);
  }
  finishContacts(a,
    b,
    firstContact,
    workspace,
    contacts,
    [&] { edgeCandidateContacts(a, b, candidates, workspace); });
}

} // namespace contact_kernels
} // namespace thintissue
