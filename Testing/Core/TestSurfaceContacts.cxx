// Vertex against thick-triangle contacts between two surfaces with radii.
#include "SurfaceContacts.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

using namespace thintissue;

namespace
{
/// An n x n grid of the unit square at height z, triangles counter-clockwise
/// seen from +z.
TriangleMesh flatGrid(int n, double z, const std::string& name)
{
  TriangleMesh mesh;
  mesh.name = name;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      mesh.positions.emplace_back(static_cast<double>(i) / n, static_cast<double>(j) / n, z);
    }
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const int v = j * (n + 1) + i;
      mesh.triangles.push_back({ v, v + 1, v + n + 2 });
      mesh.triangles.push_back({ v, v + n + 2, v + n + 1 });
    }
  }
  return mesh;
}
} // namespace

TEST(SurfaceContacts, ParallelThickSheetsTouchEverywhereWithTheRightDepthAndSides)
{
  const TriangleMesh lower = flatGrid(6, 0.0, "lower");
  const TriangleMesh upper = flatGrid(4, 0.15, "upper"); // a coarser mesh of the same plane
  const std::vector<double> lowerRadii(lower.vertexCount(), 0.1);
  const std::vector<double> upperRadii(upper.vertexCount(), 0.1);
  const auto contacts = findSurfaceContacts(upper, upperRadii, lower, lowerRadii, 0.0);
  ASSERT_EQ(contacts.size(), upper.vertexCount() + lower.vertexCount());
  for (const auto& c : contacts)
  {
    EXPECT_NEAR(c.depth, 0.2 - 0.15, 1e-12);
    EXPECT_NEAR(c.normal.z(), 1.0, 1e-12); // from B (lower) toward A (upper)
    // A's vertices are above B's triangles; B's vertices below A's.
    EXPECT_EQ(c.side, c.vertexOfA ? 1 : -1);
  }
}

TEST(SurfaceContacts, FarApartOrWithinTheContactDistanceOnly)
{
  const TriangleMesh lower = flatGrid(3, 0.0, "lower");
  const TriangleMesh upper = flatGrid(3, 1.0, "upper");
  EXPECT_TRUE(findSurfaceContacts(upper, {}, lower, {}, 0.5).empty());
  const auto near = findSurfaceContacts(upper, {}, lower, {}, 1.01);
  ASSERT_FALSE(near.empty());
  for (const auto& c : near)
  {
    EXPECT_NEAR(c.depth, -1.0, 1e-12); // within the distance, not overlapping
  }
}

TEST(SurfaceContacts, BadRadiiAreRejected)
{
  const TriangleMesh mesh = flatGrid(2, 0.0, "grid");
  EXPECT_THROW(findSurfaceContacts(mesh, { 0.1 }, mesh, {}, 0.0), InvalidInputError);
  EXPECT_THROW(
    findSurfaceContacts(mesh, std::vector<double>(mesh.vertexCount(), -0.1), mesh, {}, 0.0),
    InvalidInputError);
  EXPECT_THROW(findSurfaceContacts(mesh, {}, mesh, {}, -1.0), InvalidInputError);
}
