// Narrow-phase kernels of the collision scene: feature contacts between
// thick triangle meshes (vertex-face both ways, edge-edge crossings), each
// feature reported once.
#include "ContactKernels.h"

#include <gtest/gtest.h>

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
