// Narrow-phase kernels of the collision scene: feature contacts between
// thick triangle meshes (vertex-face both ways, edge-edge crossings), each
// feature reported once.
#include "ContactKernels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

using namespace thintissue;
using namespace thintissue::contact_kernels;

namespace
{
struct ThickMesh
{
  std::vector<Vector3> positions;
  std::vector<Triangle> triangles;
  std::vector<double> radii;
  TriangleBvh bvh;

  ThickMesh(std::vector<Vector3> p, std::vector<Triangle> t, double radius)
    : positions(std::move(p))
    , triangles(std::move(t))
    , radii(positions.size(), radius)
  {
    bvh.build(positions, triangles, radii, 0.0);
  }
  ThickMeshView view() const { return { &positions, &triangles, &radii, &bvh, nullptr }; }
};
} // namespace

TEST(ContactKernels, CrossingEdgesGiveOneEdgeEdgeContact)
{
  // Two roofs (two triangles each): A's ridge on top of a valley-up roof,
  // B's ridge below a roof hanging down, the ridges crossing 0.15 apart and
  // every vertex far from the other roof: only the ridges touch.
  const ThickMesh a({ Vector3(-5, -5, 0), Vector3(5, 5, 0), Vector3(5, -5, 8), Vector3(-5, 5, 8) },
    { { 0, 1, 2 }, { 0, 3, 1 } },
    0.1);
  const ThickMesh b(
    { Vector3(-5, 5, -0.15), Vector3(5, -5, -0.15), Vector3(5, 5, -8), Vector3(-5, -5, -8) },
    { { 0, 1, 2 }, { 0, 3, 1 } },
    0.1);
  MeshMeshWorkspace workspace;
  std::vector<FeatureContact> contacts;
  meshMeshContacts(a.view(), b.view(), workspace, contacts);
  ASSERT_EQ(contacts.size(), 1u); // the diagonal pair, met from 4 triangle pairs
  const FeatureContact& c = contacts[0];
  EXPECT_NEAR(c.depth, 0.2 - 0.15, 1e-12);
  EXPECT_TRUE(c.normal.isApprox(Vector3(0, 0, 1), 1e-12)); // from B (below) to A
  EXPECT_TRUE(c.pointA.isApprox(Vector3(0, 0, 0), 1e-12));
  EXPECT_TRUE(c.pointB.isApprox(Vector3(0, 0, -0.15), 1e-12));
  EXPECT_EQ(c.verticesA[0] + c.verticesA[1], 1); // edge (0, 1)
  EXPECT_NEAR(c.weightsA[0], 0.5, 1e-12);
  EXPECT_NEAR(c.weightsB[1], 0.5, 1e-12);
  EXPECT_EQ(c.verticesA[2], -1);

  // Apart by more than the radii: nothing.
  ThickMesh far = b;
  for (auto& p : far.positions)
  {
    p.z() -= 0.1;
  }
  far.bvh.build(far.positions, far.triangles, far.radii, 0.0);
  contacts.clear();
  meshMeshContacts(a.view(), far.view(), workspace, contacts);
  EXPECT_TRUE(contacts.empty());
}

TEST(ContactKernels, VertexFaceContactsBothWaysDeepestPerVertex)
{
  // A small triangle whose apex dips 0.3 into a large flat thick triangle
  // (radius 0.5): one contact for the apex (vertex of A on face of B), none
  // for B's far vertices; swapping the roles swaps the sides.
  const ThickMesh flat(
    { Vector3(-10, -10, 0), Vector3(10, -10, 0), Vector3(0, 10, 0) }, { { 0, 1, 2 } }, 0.5);
  const ThickMesh tip(
    { Vector3(0, 0, 0.2), Vector3(2, 0, 4), Vector3(0, 2, 4) }, { { 0, 1, 2 } }, 0.0);
  MeshMeshWorkspace workspace;
  std::vector<FeatureContact> contacts;
  meshMeshContacts(tip.view(), flat.view(), workspace, contacts);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].verticesA[0], 0);
  EXPECT_NEAR(contacts[0].depth, 0.3, 1e-12);
  EXPECT_TRUE(contacts[0].normal.isApprox(Vector3(0, 0, 1), 1e-12));
  EXPECT_NEAR(contacts[0].weightsB.sum(), 1.0, 1e-12);
  contacts.clear();
  meshMeshContacts(flat.view(), tip.view(), workspace, contacts);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].verticesB[0], 0);
  EXPECT_TRUE(contacts[0].normal.isApprox(Vector3(0, 0, -1), 1e-12)); // from the tip to the flat
}

namespace
{
/// A grid of n x n vertices, `spacing` apart, turned by `angle` about z,
/// its heights from `height(x, y)`.
template <typename Height>
ThickMesh grid(int n, double spacing, double angle, double radius, Height height)
{
  std::vector<Vector3> positions;
  std::vector<Triangle> triangles;
  const double c = std::cos(angle), s = std::sin(angle);
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const double u = (i - 0.5 * (n - 1)) * spacing, v = (j - 0.5 * (n - 1)) * spacing;
      const double x = c * u - s * v, y = s * u + c * v;
      positions.emplace_back(x, y, height(x, y));
    }
  }
  for (int j = 0; j + 1 < n; ++j)
  {
    for (int i = 0; i + 1 < n; ++i)
    {
      const int k = j * n + i;
      triangles.push_back({ k, k + 1, k + n + 1 });
      triangles.push_back({ k, k + n + 1, k + n });
    }
  }
  return ThickMesh(std::move(positions), std::move(triangles), radius);
}

void expectSameContacts(const std::vector<FeatureContact>& expected,
  const std::vector<FeatureContact>& found,
  int step)
{
  ASSERT_EQ(expected.size(), found.size()) << "step " << step;
  for (std::size_t k = 0; k < expected.size(); ++k)
  {
    const FeatureContact& e = expected[k];
    const FeatureContact& f = found[k];
    // Bit for bit: the same features, points, normals and depths.
    EXPECT_TRUE(e.verticesA == f.verticesA && e.verticesB == f.verticesB &&
                e.weightsA == f.weightsA && e.weightsB == f.weightsB && e.pointA == f.pointA &&
                e.pointB == f.pointB && e.normal == f.normal && e.depth == f.depth &&
                e.sideOnA == f.sideOnA && e.sideOnB == f.sideOnB)
      << "step " << step << ", contact " << k;
  }
}
} // namespace

TEST(ContactKernels, StaticCandidatesGiveTheSameContactsBitForBit)
{
  // A coarse thick sheet (A) wandering over a bumpy fixed one (B) turned
  // by 30 degrees, each vertex on its own random walk: the candidates kept
  // between searches must give exactly what the full search gives, every
  // kind of contact included, with far fewer searches than steps.
  const ThickMesh obstacle = grid(9,
    2.5,
    0.52,
    0.4,
    [](double x, double y) { return 0.6 * std::sin(0.9 * x) * std::cos(0.7 * y); });
  ThickMesh tissue = grid(7, 2.0, 0.0, 0.3, [](double, double) { return 0.9; });
  const double margin = 0.25;
  StaticPairCandidates candidates;
  MeshMeshWorkspace fullWorkspace, cachedWorkspace;
  std::vector<FeatureContact> full, cached;
  std::mt19937 random(7);
  std::normal_distribution<double> jitter(0.0, 0.02);
  int vertexOnFace = 0, faceOnVertex = 0, edgeEdge = 0;
  const int steps = 600;
  std::uint64_t identity = 1;
  for (int step = 0; step < steps; ++step)
  {
    for (Vector3& p : tissue.positions)
    {
      // A slow drift across and down, and noise.
      p += Vector3(0.004, 0.002, step < 300 ? -0.002 : 0.002) +
           Vector3(jitter(random), jitter(random), jitter(random));
    }
    if (step == 400)
    {
      tissue.radii.assign(tissue.positions.size(), 0.35); // another mesh
      tissue.bvh.build(tissue.positions, tissue.triangles, tissue.radii, 0.0);
      ++identity;
    }
    tissue.bvh.refit(tissue.positions, tissue.radii); // as a deformable mesh does
    ThickMeshView a = tissue.view();
    a.identity = identity;
    full.clear();
    cached.clear();
    meshMeshContacts(a, obstacle.view(), fullWorkspace, full);
    meshStaticContacts(a, obstacle.view(), margin, candidates, cachedWorkspace, cached);
    expectSameContacts(full, cached, step);
    for (const FeatureContact& c : full)
    {
      vertexOnFace += c.verticesA[1] < 0 ? 1 : 0;
      faceOnVertex += c.verticesB[1] < 0 ? 1 : 0;
      edgeEdge += c.verticesA[1] >= 0 && c.verticesA[2] < 0 && c.verticesB[2] < 0 ? 1 : 0;
    }
  }
  EXPECT_GT(vertexOnFace, 0);
  EXPECT_GT(faceOnVertex, 0);
  EXPECT_GT(edgeEdge, 0);
  EXPECT_LT(candidates.searches, steps / 4);
  EXPECT_GE(candidates.searches, 3); // moved beyond the margin, and the new mesh
  std::cout << "contacts: " << vertexOnFace << " vertex-face, " << faceOnVertex << " face-vertex, "
            << edgeEdge << " edge-edge; " << candidates.searches << " searches in " << steps
            << " steps\n";
}
