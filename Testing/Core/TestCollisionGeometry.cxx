// Collision geometry: TriangleBvh against brute force, and the thick-triangle
// proximity primitives against analytic cases and sampling.
#include "MeshQueries.h"
#include "ProximityQueries.h"
#include "ThinTissueError.h"
#include "TriangleBvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

using namespace thintissue;

namespace
{

struct RandomMesh
{
  std::vector<Vector3> positions;
  std::vector<Triangle> triangles;
  std::vector<double> radii;
};

/// Small random triangles scattered in [0, 1]^3 (unshared vertices, which is
/// what matters to the tree), radii in [0, 0.02].
RandomMesh makeRandomMesh(unsigned seed, int triangleCount, const Vector3& offset = Vector3::Zero())
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> jitter(-0.04, 0.04);
  RandomMesh mesh;
  for (int t = 0; t < triangleCount; ++t)
  {
    const Vector3 centre = Vector3(unit(random), unit(random), unit(random)) + offset;
    const int first = static_cast<int>(mesh.positions.size());
    for (int k = 0; k < 3; ++k)
    {
      mesh.positions.push_back(centre + Vector3(jitter(random), jitter(random), jitter(random)));
      mesh.radii.push_back(0.02 * unit(random));
    }
    mesh.triangles.push_back({ first, first + 1, first + 2 });
  }
  return mesh;
}

BoundingBox randomBox(std::mt19937& random)
{
  std::uniform_real_distribution<double> unit(-0.1, 1.1);
  std::uniform_real_distribution<double> size(0.0, 0.3);
  const Vector3 corner(unit(random), unit(random), unit(random));
  return BoundingBox(corner, corner + Vector3(size(random), size(random), size(random)));
}

std::vector<int> bruteForceOverlap(const RandomMesh& mesh, double margin, const BoundingBox& box)
{
  std::vector<int> result;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
  {
    if (TriangleBvh::triangleBox(mesh.positions, mesh.triangles[t], mesh.radii, margin)
          .intersects(box))
    {
      result.push_back(t);
    }
  }
  return result;
}

std::vector<int> bvhOverlap(const TriangleBvh& bvh, const BoundingBox& box)
{
  std::vector<int> result;
  bvh.forEachOverlap(box, [&](int t) { result.push_back(t); });
  std::sort(result.begin(), result.end());
  return result;
}

using PairSet = std::set<std::pair<int, int>>;

PairSet bruteForcePairs(const RandomMesh& a, double marginA, const RandomMesh& b, double marginB)
{
  PairSet result;
  for (int i = 0; i < static_cast<int>(a.triangles.size()); ++i)
  {
    const BoundingBox boxA =
      TriangleBvh::triangleBox(a.positions, a.triangles[i], a.radii, marginA);
    for (int j = 0; j < static_cast<int>(b.triangles.size()); ++j)
    {
      if (boxA.intersects(TriangleBvh::triangleBox(b.positions, b.triangles[j], b.radii, marginB)))
      {
        result.insert({ i, j });
      }
    }
  }
  return result;
}

PairSet bvhPairs(const TriangleBvh& a, const TriangleBvh& b)
{
  PairSet result;
  std::size_t calls = 0;
  a.forEachOverlappingPair(b,
    [&](int i, int j)
    {
      result.insert({ i, j });
      ++calls;
    });
  EXPECT_EQ(calls, result.size()); // each pair reported once
  return result;
}

void deform(RandomMesh& mesh, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> move(-0.2, 0.2);
  for (Vector3& p : mesh.positions)
  {
    // A smooth large deformation plus noise.
    p = Vector3(p.x() + 0.3 * std::sin(3.0 * p.y()), p.y() * 1.5, p.z() - 0.2 * p.x()) +
        Vector3(move(random), move(random), move(random)) * 0.2;
  }
  for (double& r : mesh.radii)
  {
    r *= 1.5;
  }
}

} // namespace

TEST(TriangleBvh, OverlapQueriesMatchBruteForce)
{
  for (unsigned seed = 1; seed <= 5; ++seed)
  {
    const RandomMesh mesh = makeRandomMesh(seed, 400 + 37 * static_cast<int>(seed));
    const double margin = 0.005 * seed;
    TriangleBvh bvh;
    bvh.build(mesh.positions, mesh.triangles, mesh.radii, margin);
    EXPECT_EQ(bvh.triangleCount(), mesh.triangles.size());
    EXPECT_LT(bvh.nodeCount(), 2 * mesh.triangles.size());
    std::mt19937 random(100 + seed);
    for (int query = 0; query < 60; ++query)
    {
      const BoundingBox box = randomBox(random);
      EXPECT_EQ(bvhOverlap(bvh, box), bruteForceOverlap(mesh, margin, box)) << "seed " << seed;
    }
  }
}

// Each edge has one owner, its lowest (triangle, corner): on random
// triangles over few vertices (shared, non-manifold and repeated edges,
// triangles that repeat a vertex) the tree's owners match the brute-force
// minimum over every side of every triangle.
TEST(TriangleBvh, EdgeOwnersAreTheLowestTriangles)
{
  for (unsigned seed = 1; seed <= 5; ++seed)
  {
    std::mt19937 random(seed);
    const int vertexCount = 12 + static_cast<int>(seed);
    std::uniform_int_distribution<int> vertex(0, vertexCount - 1);
    std::vector<Vector3> positions;
    for (int v = 0; v < vertexCount; ++v)
      positions.emplace_back(0.1 * v, std::sin(v), std::cos(3.0 * v));
    std::vector<Triangle> triangles;
    for (int t = 0; t < 200; ++t)
      triangles.push_back({ vertex(random), vertex(random), vertex(random) });
    TriangleBvh bvh;
    bvh.build(positions, triangles, {}, 0.0);
    std::map<std::pair<int, int>, int> lowest; // edge -> 4 t + k
    for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
      for (int k = 0; k < 3; ++k)
      {
        const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
        lowest.emplace(std::make_pair(std::min(a, b), std::max(a, b)), 4 * t + k);
      }
    std::vector<std::uint8_t> expected(triangles.size(), 0);
    for (const auto& [edge, owner] : lowest)
      expected[owner / 4] |= static_cast<std::uint8_t>(1u << (owner % 4));
    for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
      EXPECT_EQ(bvh.ownedEdges(t), expected[t]) << "seed " << seed << ", triangle " << t;
  }
}

TEST(TriangleBvh, PairQueriesMatchBruteForce)
{
  for (unsigned seed = 1; seed <= 4; ++seed)
  {
    const RandomMesh a = makeRandomMesh(seed, 300);
    const RandomMesh b =
      makeRandomMesh(seed + 50, 200 + 50 * static_cast<int>(seed), Vector3(0.3, 0.0, 0.1));
    TriangleBvh bvhA;
    TriangleBvh bvhB;
    bvhA.build(a.positions, a.triangles, a.radii, 0.01);
    bvhB.build(b.positions, b.triangles, {}, 0.02);
    RandomMesh bNoRadii = b;
    bNoRadii.radii.clear();
    const PairSet expected = bruteForcePairs(a, 0.01, bNoRadii, 0.02);
    EXPECT_FALSE(expected.empty());
    EXPECT_EQ(bvhPairs(bvhA, bvhB), expected) << "seed " << seed;
    // Swapped roles give the transposed set.
    PairSet transposed;
    for (const auto& [i, j] : bvhPairs(bvhB, bvhA))
    {
      transposed.insert({ j, i });
    }
    EXPECT_EQ(transposed, expected);
  }
}

TEST(TriangleBvh, SelfPairsMatchBruteForce)
{
  for (unsigned seed = 1; seed <= 3; ++seed)
  {
    const RandomMesh mesh = makeRandomMesh(seed, 500);
    TriangleBvh bvh;
    bvh.build(mesh.positions, mesh.triangles, mesh.radii, 0.01);
    PairSet expected;
    for (const auto& [i, j] : bruteForcePairs(mesh, 0.01, mesh, 0.01))
    {
      if (i < j)
      {
        expected.insert({ i, j });
      }
    }
    PairSet found;
    std::size_t calls = 0;
    bvh.forEachSelfOverlappingPair(
      [&](int i, int j)
      {
        EXPECT_LT(i, j);
        found.insert({ i, j });
        ++calls;
      });
    EXPECT_EQ(calls, found.size());
    EXPECT_EQ(found, expected) << "seed " << seed;
  }
}

TEST(TriangleBvh, RefitAfterDeformationMatchesFreshBuild)
{
  for (unsigned seed = 1; seed <= 4; ++seed)
  {
    RandomMesh mesh = makeRandomMesh(seed, 600);
    const RandomMesh other = makeRandomMesh(seed + 9, 300);
    TriangleBvh refitted;
    refitted.build(mesh.positions, mesh.triangles, mesh.radii, 0.01);
    deform(mesh, seed);
    refitted.refit(mesh.positions, mesh.radii);
    TriangleBvh fresh;
    fresh.build(mesh.positions, mesh.triangles, mesh.radii, 0.01);
    EXPECT_EQ(refitted.nodeCount(), fresh.nodeCount());
    EXPECT_TRUE(refitted.bounds().isApprox(fresh.bounds()));
    std::mt19937 random(seed);
    for (int query = 0; query < 60; ++query)
    {
      const BoundingBox box = randomBox(random);
      const std::vector<int> expected = bruteForceOverlap(mesh, 0.01, box);
      EXPECT_EQ(bvhOverlap(refitted, box), expected);
      EXPECT_EQ(bvhOverlap(fresh, box), expected);
    }
    TriangleBvh otherBvh;
    otherBvh.build(other.positions, other.triangles, other.radii, 0.0);
    EXPECT_EQ(bvhPairs(refitted, otherBvh), bvhPairs(fresh, otherBvh));
    EXPECT_EQ(bvhPairs(refitted, otherBvh), bruteForcePairs(mesh, 0.01, other, 0.0));
  }
}

TEST(TriangleBvh, InflatedBoxesContainVerticesAndRadii)
{
  const RandomMesh mesh = makeRandomMesh(7, 700);
  const double margin = 0.003;
  TriangleBvh bvh;
  bvh.build(mesh.positions, mesh.triangles, mesh.radii, margin);
  const auto& nodes = bvh.nodes();
  const auto& order = bvh.leafTriangles();
  std::vector<int> seen(mesh.triangles.size(), 0);
  for (std::size_t n = 0; n < nodes.size(); ++n)
  {
    const TriangleBvh::Node& node = nodes[n];
    if (!node.isLeaf())
    {
      EXPECT_TRUE(node.box.contains(nodes[n + 1].box));
      EXPECT_TRUE(node.box.contains(nodes[node.rightChild].box));
      continue;
    }
    EXPECT_LE(node.triangleCount, TriangleBvh::MaximumLeafSize);
    for (int i = node.firstTriangle; i < node.firstTriangle + node.triangleCount; ++i)
    {
      const int t = order[i];
      ++seen[t];
      const BoundingBox& box = bvh.leafTriangleBoxes()[i];
      EXPECT_TRUE(node.box.contains(box));
      for (int v : mesh.triangles[t])
      {
        const Vector3 reach = Vector3::Constant(mesh.radii[v] + margin);
        EXPECT_TRUE(box.contains(mesh.positions[v] + reach));
        EXPECT_TRUE(box.contains(mesh.positions[v] - reach));
      }
    }
  }
  for (int count : seen)
  {
    EXPECT_EQ(count, 1);
  }
}

TEST(TriangleBvh, EmptyAndInvalidInput)
{
  TriangleBvh bvh;
  bvh.build({}, {}, {}, 0.0);
  EXPECT_TRUE(bvh.empty());
  int calls = 0;
  bvh.forEachOverlap(BoundingBox(Vector3::Zero(), Vector3::Ones()), [&](int) { ++calls; });
  bvh.forEachOverlappingPair(bvh, [&](int, int) { ++calls; });
  bvh.forEachSelfOverlappingPair([&](int, int) { ++calls; });
  EXPECT_EQ(calls, 0);
  const std::vector<Vector3> positions = { Vector3::Zero(), Vector3::UnitX(), Vector3::UnitY() };
  EXPECT_THROW(bvh.build(positions, { Triangle{ 0, 1, 3 } }, {}, 0.0), InvalidInputError);
  EXPECT_THROW(bvh.build(positions, { Triangle{ 0, 1, 2 } }, { 1.0 }, 0.0), InvalidInputError);
  bvh.build(positions, { Triangle{ 0, 1, 2 } }, {}, 0.0);
  EXPECT_EQ(bvh.nodeCount(), 1u);
}

//------------------------------------------------------------------------------
namespace
{
const Vector3 A(0.0, 0.0, 0.0);
const Vector3 B(1.0, 0.0, 0.0);
const Vector3 C(0.0, 1.0, 0.0);

/// Brute-force distance from a segment to a triangle: min over 1001 samples.
double sampledSegmentTriangleDistance(const Vector3& p,
  const Vector3& q,
  const Vector3& a,
  const Vector3& b,
  const Vector3& c)
{
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 1000; ++i)
  {
    const Vector3 x = p + (q - p) * (i / 1000.0);
    best = std::min(best, (closestPointOnTriangle(x, a, b, c) - x).norm());
  }
  return best;
}
} // namespace

TEST(ProximityQueries, PointAboveFaceInteriorInterpolatesRadii)
{
  const PointTriangleContact contact =
    pointTriangleContact(Vector3(0.2, 0.2, 0.5), 0.1, A, B, C, 0.1, 0.2, 0.3, 0.3);
  EXPECT_TRUE(contact.trianglePoint.isApprox(Vector3(0.2, 0.2, 0.0)));
  EXPECT_TRUE(contact.barycentric.isApprox(Vector3(0.6, 0.2, 0.2)));
  EXPECT_NEAR(contact.triangleRadius, 0.16, 1e-12);
  EXPECT_NEAR(contact.distance, 0.5, 1e-12);
  EXPECT_NEAR(contact.depth, 0.1 + 0.16 - 0.5, 1e-12);
  EXPECT_FALSE(contact.penetrating());
  EXPECT_TRUE(contact.withinContactDistance); // gap 0.24 <= 0.3
  EXPECT_TRUE(contact.normal.isApprox(Vector3::UnitZ()));
  EXPECT_EQ(contact.side, 1);
  EXPECT_FALSE(pointTriangleContact(Vector3(0.2, 0.2, 0.5), 0.1, A, B, C, 0.1, 0.2, 0.3, 0.2)
                 .withinContactDistance);
}

TEST(ProximityQueries, PointOnNegativeSidePenetrating)
{
  const PointTriangleContact contact =
    pointTriangleContact(Vector3(0.2, 0.3, -0.1), 0.05, A, B, C, 0.1, 0.1, 0.1, 0.0);
  EXPECT_EQ(contact.side, -1);
  EXPECT_TRUE(contact.normal.isApprox(-Vector3::UnitZ()));
  EXPECT_NEAR(contact.depth, 0.05, 1e-12);
  EXPECT_TRUE(contact.penetrating());
  EXPECT_TRUE(contact.withinContactDistance);
}

TEST(ProximityQueries, PointNearEdgeAndVertex)
{
  // Beyond edge ab, above the plane: closest point on the edge.
  const PointTriangleContact edge =
    pointTriangleContact(Vector3(0.5, -0.3, 0.4), 0.0, A, B, C, 0.2, 0.4, 0.0, 0.0);
  EXPECT_TRUE(edge.trianglePoint.isApprox(Vector3(0.5, 0.0, 0.0)));
  EXPECT_TRUE(edge.barycentric.isApprox(Vector3(0.5, 0.5, 0.0)));
  EXPECT_NEAR(edge.triangleRadius, 0.3, 1e-12);
  EXPECT_NEAR(edge.distance, 0.5, 1e-12);
  EXPECT_TRUE(edge.normal.isApprox(Vector3(0.0, -0.6, 0.8)));
  EXPECT_EQ(edge.side, 1);
  // Beyond the hypotenuse, below.
  const PointTriangleContact hypotenuse =
    pointTriangleContact(Vector3(1.0, 1.0, -0.1), 0.0, A, B, C, 0.0, 0.0, 0.0, 0.0);
  EXPECT_TRUE(hypotenuse.barycentric.isApprox(Vector3(0.0, 0.5, 0.5)));
  EXPECT_EQ(hypotenuse.side, -1);
  // In the plane, beyond vertex a.
  const PointTriangleContact vertex =
    pointTriangleContact(Vector3(-0.3, -0.4, 0.0), 0.1, A, B, C, 0.45, 0.0, 0.0, 0.0);
  EXPECT_TRUE(vertex.trianglePoint.isApprox(A));
  EXPECT_TRUE(vertex.barycentric.isApprox(Vector3(1.0, 0.0, 0.0)));
  EXPECT_NEAR(vertex.distance, 0.5, 1e-12);
  EXPECT_NEAR(vertex.depth, 0.05, 1e-12);
  EXPECT_TRUE(vertex.normal.isApprox(Vector3(-0.6, -0.8, 0.0)));
  // On the face itself: normal is the face normal.
  const PointTriangleContact on =
    pointTriangleContact(Vector3(0.25, 0.25, 0.0), 0.0, A, B, C, 0.1, 0.1, 0.1, 0.0);
  EXPECT_NEAR(on.distance, 0.0, 1e-15);
  EXPECT_TRUE(on.normal.isApprox(Vector3::UnitZ()));
  EXPECT_EQ(on.side, 1);
}

TEST(ProximityQueries, ClosestPointMatchesMeshQueriesOnRandomInput)
{
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto v = [&] { return Vector3(unit(random), unit(random), unit(random)); };
  for (int i = 0; i < 2000; ++i)
  {
    const Vector3 a = v(), b = v(), c = v(), x = 2.0 * v();
    const TriangleClosestPoint closest = closestPointOnTriangleWithBarycentric(x, a, b, c);
    EXPECT_LT((closest.point - closestPointOnTriangle(x, a, b, c)).norm(), 1e-9);
    EXPECT_LT((closest.barycentric[0] * a + closest.barycentric[1] * b +
                closest.barycentric[2] * c - closest.point)
                .norm(),
      1e-9);
    EXPECT_GE(closest.barycentric.minCoeff(), -1e-12);
    EXPECT_NEAR(closest.barycentric.sum(), 1.0, 1e-12);
  }
  // Degenerate (collinear) triangle.
  const TriangleClosestPoint degenerate =
    closestPointOnTriangleWithBarycentric(Vector3(0.5, 1.0, 0.0), A, B, Vector3(2.0, 0.0, 0.0));
  EXPECT_TRUE(degenerate.point.isApprox(Vector3(0.5, 0.0, 0.0)));
}

TEST(ProximityQueries, SegmentClosestPointsMatchBruteForce)
{
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto v = [&] { return Vector3(unit(random), unit(random), unit(random)); };
  for (int i = 0; i < 300; ++i)
  {
    Vector3 p1 = v(), q1 = v(), p2 = v(), q2 = v();
    const int kind = i % 5;
    if (kind == 1) // parallel
    {
      q2 = p2 + (q1 - p1) * (0.3 + unit(random));
    }
    else if (kind == 2) // collinear, overlapping or not
    {
      p2 = p1 + (q1 - p1) * unit(random) * 1.5;
      q2 = p1 + (q1 - p1) * unit(random) * 1.5;
    }
    else if (kind == 3) // first zero-length
    {
      q1 = p1;
    }
    else if (kind == 4) // both zero-length
    {
      q1 = p1;
      q2 = p2;
    }
    const SegmentSegmentClosestPoints s = closestPointsBetweenSegments(p1, q1, p2, q2);
    double sampled = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= 1000; ++k)
    {
      const Vector3 x = p1 + (q1 - p1) * (k / 1000.0);
      sampled = std::min(sampled, (closestPointOnSegment(x, p2, q2).point - x).norm());
    }
    EXPECT_LE(s.distance, sampled + 1e-12) << "case " << i;
    EXPECT_LE(sampled, s.distance + 1e-3) << "case " << i;
    EXPECT_TRUE(s.pointOnFirst.isApprox(p1 + s.parameterOnFirst * (q1 - p1)));
    EXPECT_TRUE(s.pointOnSecond.isApprox(p2 + s.parameterOnSecond * (q2 - p2)));
    EXPECT_NEAR(s.distance, (s.pointOnFirst - s.pointOnSecond).norm(), 1e-12);
    EXPECT_GE(s.parameterOnFirst, 0.0);
    EXPECT_LE(s.parameterOnFirst, 1.0);
    EXPECT_GE(s.parameterOnSecond, 0.0);
    EXPECT_LE(s.parameterOnSecond, 1.0);
  }
  // Exactly parallel, offset: distance is the offset.
  const SegmentSegmentClosestPoints parallel = closestPointsBetweenSegments(
    Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0.5, 0.3, 0), Vector3(2, 0.3, 0));
  EXPECT_NEAR(parallel.distance, 0.3, 1e-12);
  // Point on segment.
  const SegmentClosestPoint onSegment =
    closestPointOnSegment(Vector3(0.25, 1.0, 0.0), Vector3::Zero(), Vector3::UnitX());
  EXPECT_NEAR(onSegment.parameter, 0.25, 1e-12);
  EXPECT_EQ(
    closestPointOnSegment(Vector3::UnitY(), Vector3::UnitX(), Vector3::UnitX()).parameter, 0.0);
}

TEST(ProximityQueries, SegmentParallelAboveFace)
{
  const SegmentTriangleContact contact = segmentTriangleContact(
    Vector3(0.1, 0.1, 0.3), Vector3(0.5, 0.1, 0.3), 0.05, A, B, C, 0.1, 0.1, 0.1, 0.2);
  EXPECT_FALSE(contact.crossing);
  EXPECT_NEAR(contact.distance, 0.3, 1e-12);
  EXPECT_NEAR(contact.depth, 0.15 - 0.3, 1e-12);
  EXPECT_TRUE(contact.withinContactDistance);
  EXPECT_TRUE(contact.normal.isApprox(Vector3::UnitZ()));
  EXPECT_EQ(contact.side, 1);
  EXPECT_NEAR(contact.segmentPoint.z(), 0.3, 1e-12);
  EXPECT_TRUE((
    contact.segmentPoint - (Vector3(0.1, 0.1, 0.3) + contact.segmentParameter * Vector3(0.4, 0, 0)))
                .isZero(1e-12));
}

TEST(ProximityQueries, SegmentCrossingFaceKeepsStartSide)
{
  const Vector3 top(0.2, 0.2, 0.5);
  const Vector3 bottom(0.2, 0.2, -0.3);
  const SegmentTriangleContact down =
    segmentTriangleContact(top, bottom, 0.05, A, B, C, 0.1, 0.2, 0.3, 0.0);
  EXPECT_TRUE(down.crossing);
  EXPECT_EQ(down.distance, 0.0);
  EXPECT_NEAR(down.segmentParameter, 0.5 / 0.8, 1e-12);
  EXPECT_TRUE(down.barycentric.isApprox(Vector3(0.6, 0.2, 0.2)));
  EXPECT_NEAR(down.depth, 0.05 + 0.16, 1e-12);
  EXPECT_TRUE(down.normal.isApprox(Vector3::UnitZ())); // pushed back up, not through
  EXPECT_EQ(down.side, 1);
  const SegmentTriangleContact up =
    segmentTriangleContact(bottom, top, 0.05, A, B, C, 0.1, 0.2, 0.3, 0.0);
  EXPECT_TRUE(up.crossing);
  EXPECT_TRUE(up.normal.isApprox(-Vector3::UnitZ()));
  EXPECT_EQ(up.side, -1);
  // Start point exactly on the face, heading down: treated as coming from above.
  const SegmentTriangleContact startOn =
    segmentTriangleContact(Vector3(0.2, 0.2, 0.0), bottom, 0.05, A, B, C, 0.1, 0.1, 0.1, 0.0);
  EXPECT_EQ(startOn.distance, 0.0);
  EXPECT_TRUE(startOn.normal.isApprox(Vector3::UnitZ()));
}

TEST(ProximityQueries, SegmentSkewNearEdgeMatchesSampling)
{
  const Vector3 p(0.5, -0.4, -0.3);
  const Vector3 q(0.7, -0.1, 0.5);
  const SegmentTriangleContact contact =
    segmentTriangleContact(p, q, 0.0, A, B, C, 0.0, 0.0, 0.0, 0.0);
  EXPECT_FALSE(contact.crossing);
  EXPECT_NEAR(contact.distance, sampledSegmentTriangleDistance(p, q, A, B, C), 1e-3);
  EXPECT_NEAR(contact.barycentric[2], 0.0, 1e-12); // on edge ab
  EXPECT_LT(contact.normal.y(), 0.0);

  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto v = [&] { return Vector3(unit(random), unit(random), unit(random)); };
  for (int i = 0; i < 200; ++i)
  {
    const Vector3 a = v(), b = v(), c = v();
    const Vector3 s = v();
    const Vector3 e = s + 0.7 * v();
    const std::array<double, 3> r = { 0.1 * (1 + unit(random)), 0.1, 0.05 };
    const SegmentTriangleContact st =
      segmentTriangleContact(s, e, 0.02, a, b, c, r[0], r[1], r[2], 0.01);
    const double sampled = sampledSegmentTriangleDistance(s, e, a, b, c);
    EXPECT_LE(st.distance, sampled + 1e-9) << "case " << i;
    EXPECT_LE(sampled, st.distance + 1e-3) << "case " << i;
    EXPECT_TRUE((st.barycentric[0] * a + st.barycentric[1] * b + st.barycentric[2] * c)
                  .isApprox(st.trianglePoint, 1e-9));
    EXPECT_TRUE((s + st.segmentParameter * (e - s)).isApprox(st.segmentPoint, 1e-9));
    EXPECT_NEAR(st.normal.norm(), 1.0, 1e-12);
    EXPECT_NEAR(
      st.depth, 0.02 + st.barycentric.dot(Vector3(r[0], r[1], r[2])) - st.distance, 1e-12);
    if (st.distance > 1e-9)
    {
      EXPECT_TRUE(st.normal.isApprox((st.segmentPoint - st.trianglePoint) / st.distance, 1e-9));
    }
  }
}

TEST(ProximityQueries, TriangleTriangleVertexFace)
{
  // A hangs above B with its vertex 1 pointing down onto B's interior.
  const std::array<Vector3, 3> a = {
    Vector3(0.0, 0.5, 0.6), Vector3(0.2, 0.2, 0.05), Vector3(0.6, 0.0, 0.6)
  };
  const std::array<Vector3, 3> b = { A, B, C };
  const TriangleTriangleProximity result =
    triangleTriangleProximity(a, { 0.03, 0.03, 0.03 }, b, { 0.04, 0.04, 0.04 }, 0.0);
  ASSERT_TRUE(result.inContact());
  EXPECT_FALSE(result.intersecting);
  const TriangleTriangleContact& deepest = result.contacts[result.deepest];
  EXPECT_EQ(deepest.kind, TriangleTriangleContact::Kind::VertexOfAOnFaceOfB);
  EXPECT_EQ(deepest.featureA, 1);
  EXPECT_NEAR(deepest.distance, 0.05, 1e-12);
  EXPECT_NEAR(deepest.depth, 0.02, 1e-12);
  EXPECT_TRUE(deepest.normal.isApprox(Vector3::UnitZ()));
  EXPECT_TRUE(deepest.pointB.isApprox(Vector3(0.2, 0.2, 0.0)));
  EXPECT_EQ(deepest.sideOnB, 1);
  for (int k = 0; k < result.count; ++k)
  {
    EXPECT_LE(result.contacts[k].depth, deepest.depth);
    EXPECT_GE(result.contacts[k].depth, 0.0);
  }
  // Same from the other side: roles of A and B swapped, normal reversed.
  const TriangleTriangleProximity swapped =
    triangleTriangleProximity(b, { 0.04, 0.04, 0.04 }, a, { 0.03, 0.03, 0.03 }, 0.0);
  ASSERT_TRUE(swapped.inContact());
  const TriangleTriangleContact& s = swapped.contacts[swapped.deepest];
  EXPECT_EQ(s.kind, TriangleTriangleContact::Kind::VertexOfBOnFaceOfA);
  EXPECT_EQ(s.featureB, 1);
  EXPECT_TRUE(s.normal.isApprox(-Vector3::UnitZ()));
  EXPECT_EQ(s.sideOnA, 1);
  // Lowered below B: the contact is on B's negative side.
  std::array<Vector3, 3> below = a;
  for (Vector3& x : below)
  {
    x.z() = -x.z();
  }
  const TriangleTriangleProximity under =
    triangleTriangleProximity(below, { 0.03, 0.03, 0.03 }, b, { 0.04, 0.04, 0.04 }, 0.0);
  ASSERT_TRUE(under.inContact());
  EXPECT_EQ(under.contacts[under.deepest].sideOnB, -1);
  EXPECT_TRUE(under.contacts[under.deepest].normal.isApprox(-Vector3::UnitZ()));
}

TEST(ProximityQueries, TriangleTriangleEdgeEdge)
{
  // A stands in the plane x = 0 with its edge 0 along y at height 0.1; B
  // hangs in the plane y = 0 with its edge 0 along x at height 0.
  const std::array<Vector3, 3> a = {
    Vector3(0.0, -1.0, 0.1), Vector3(0.0, 1.0, 0.1), Vector3(0.0, 0.0, 1.1)
  };
  const std::array<Vector3, 3> b = {
    Vector3(-1.0, 0.0, 0.0), Vector3(1.0, 0.0, 0.0), Vector3(0.0, 0.0, -1.0)
  };
  const TriangleTriangleProximity result =
    triangleTriangleProximity(a, { 0.06, 0.06, 0.06 }, b, { 0.02, 0.06, 0.06 }, 0.0);
  ASSERT_TRUE(result.inContact());
  EXPECT_FALSE(result.intersecting);
  const TriangleTriangleContact& deepest = result.contacts[result.deepest];
  EXPECT_EQ(deepest.kind, TriangleTriangleContact::Kind::EdgeEdge);
  EXPECT_EQ(deepest.featureA, 0);
  EXPECT_EQ(deepest.featureB, 0);
  EXPECT_NEAR(deepest.distance, 0.1, 1e-12);
  EXPECT_TRUE(deepest.pointA.isApprox(Vector3(0.0, 0.0, 0.1)));
  EXPECT_TRUE((deepest.pointB - Vector3(0.0, 0.0, 0.0)).isZero(1e-12));
  EXPECT_NEAR(deepest.radiusB, 0.04, 1e-12); // halfway between 0.02 and 0.06
  EXPECT_NEAR(deepest.depth, 0.06 + 0.04 - 0.1, 1e-12);
  EXPECT_TRUE(deepest.normal.isApprox(Vector3::UnitZ()));
  EXPECT_TRUE(deepest.barycentricA.isApprox(Vector3(0.5, 0.5, 0.0)));
  // Far apart: nothing.
  std::array<Vector3, 3> far = a;
  for (Vector3& x : far)
  {
    x.z() += 1.0;
  }
  EXPECT_FALSE(
    triangleTriangleProximity(far, { 0.06, 0.06, 0.06 }, b, { 0.06, 0.06, 0.06 }, 0.1).inContact());
  // Within the contact distance only.
  const TriangleTriangleProximity near =
    triangleTriangleProximity(a, { 0.01, 0.01, 0.01 }, b, { 0.01, 0.01, 0.01 }, 0.09);
  ASSERT_TRUE(near.inContact());
  EXPECT_LT(near.contacts[near.deepest].depth, 0.0);
}

TEST(ProximityQueries, TriangleTriangleIntersectingFlag)
{
  const std::array<Vector3, 3> b = { A, B, C };
  // A pierces B's interior vertically.
  const std::array<Vector3, 3> a = {
    Vector3(0.2, 0.2, -0.5), Vector3(0.3, 0.2, 0.5), Vector3(0.2, 0.3, 0.5)
  };
  const TriangleTriangleProximity result =
    triangleTriangleProximity(a, { 0.0, 0.0, 0.0 }, b, { 0.0, 0.0, 0.0 }, 0.0);
  EXPECT_TRUE(result.intersecting);
  const std::array<Vector3, 3> apart = {
    Vector3(0.2, 0.2, 0.5), Vector3(0.3, 0.2, 0.5), Vector3(0.2, 0.3, 0.6)
  };
  EXPECT_FALSE(
    triangleTriangleProximity(apart, { 0.0, 0.0, 0.0 }, b, { 0.0, 0.0, 0.0 }, 0.0).intersecting);
}

// The distance to a surface through its tree equals the brute-force one
// (the tree only prunes), for points inside and far outside the cloud,
// whatever radii and margin the tree was built with.
TEST(TriangleBvh, DistanceToSurfaceMatchesBruteForce)
{
  for (unsigned seed : { 1u, 2u, 3u })
  {
    const RandomMesh random = makeRandomMesh(seed, 300);
    TriangleMesh mesh;
    mesh.positions = random.positions;
    mesh.triangles = random.triangles;
    TriangleBvh tree;
    tree.build(mesh.positions,
      mesh.triangles,
      seed == 3 ? random.radii : std::vector<double>(),
      seed == 2 ? 0.05 : 0.0);
    std::mt19937 points(200 + seed);
    std::uniform_real_distribution<double> coordinate(-1.0, 2.0);
    for (int i = 0; i < 200; ++i)
    {
      const Vector3 x(coordinate(points), coordinate(points), coordinate(points));
      EXPECT_DOUBLE_EQ(distanceToSurface(mesh, tree, x), distanceToSurface(mesh, x));
    }
  }
  TriangleBvh empty;
  EXPECT_TRUE(std::isinf(distanceToSurface(TriangleMesh{}, empty, Vector3::Zero())));
}

// Even-odd inside test of a closed polygon (the collision outline's loops,
// a shaver's window): convex and concave, either orientation.
TEST(CollisionGeometry, InsidePolygonFollowsConcaveOutlinesInEitherOrientation)
{
  using thintissue::Vector2;
  // An L: the square [0, 2]^2 without its upper right quarter.
  std::vector<Vector2> l{ { 0, 0 }, { 2, 0 }, { 2, 1 }, { 1, 1 }, { 1, 2 }, { 0, 2 } };
  for (int pass = 0; pass < 2; ++pass)
  {
    EXPECT_TRUE(thintissue::insidePolygon(l, Vector2(0.5, 0.5)));
    EXPECT_TRUE(thintissue::insidePolygon(l, Vector2(1.5, 0.5)));
    EXPECT_TRUE(thintissue::insidePolygon(l, Vector2(0.5, 1.5)));
    EXPECT_FALSE(thintissue::insidePolygon(l, Vector2(1.5, 1.5))); // the notch
    EXPECT_FALSE(thintissue::insidePolygon(l, Vector2(-0.5, 0.5)));
    EXPECT_FALSE(thintissue::insidePolygon(l, Vector2(0.5, 2.5)));
    std::reverse(l.begin(), l.end());
  }
  EXPECT_FALSE(thintissue::insidePolygon({}, Vector2(0, 0)));
}
