#include "MeshPrimitives.h"
#include "ThinTissueError.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

using namespace thintissue;

namespace
{
SlabSurfaceParameters slabParameters(double w, double d, double t, int cx, int cy, int cz)
{
  SlabSurfaceParameters p;
  p.width = w;
  p.depth = d;
  p.thickness = t;
  p.cellsX = cx;
  p.cellsY = cy;
  p.cellsZ = cz;
  return p;
}
} // namespace

TEST(TriangleMesh, SlabHasExpectedCountsVolumeAndArea)
{
  const TriangleMesh slab = makeSlabSurface(slabParameters(4.0, 3.0, 0.5, 8, 6, 2));
  // 4 (cx cy + cx cz + cy cz) triangles; vertices = lattice surface points.
  EXPECT_EQ(slab.triangleCount(), 4u * (8 * 6 + 8 * 2 + 6 * 2));
  EXPECT_EQ(slab.vertexCount(), 9u * 7 * 3 - 7u * 5 * 1);
  EXPECT_NEAR(slab.signedVolume(), 4.0 * 3.0 * 0.5, 1e-12);
  EXPECT_NEAR(slab.surfaceArea(), 2 * (4.0 * 3.0 + 4.0 * 0.5 + 3.0 * 0.5), 1e-12);
  const BoundingBox box = slab.boundingBox();
  EXPECT_TRUE(box.min().isApprox(Vector3(-2.0, -1.5, -0.25)));
  EXPECT_TRUE(box.max().isApprox(Vector3(2.0, 1.5, 0.25)));
  EXPECT_TRUE(slab.hasTextureCoordinates());
  EXPECT_TRUE(slab.hasNormals());
  EXPECT_NO_THROW(slab.checkConsistency());
}

TEST(TriangleMesh, SlabRejectsBadParameters)
{
  EXPECT_THROW(makeSlabSurface(slabParameters(0.0, 1.0, 1.0, 1, 1, 1)), InvalidInputError);
  EXPECT_THROW(makeSlabSurface(slabParameters(1.0, 1.0, 1.0, 0, 1, 1)), InvalidInputError);
}

TEST(TriangleMesh, ReverseOrientationNegatesVolumeAndNormals)
{
  TriangleMesh slab = makeSlabSurface(slabParameters(2.0, 2.0, 0.2, 2, 2, 1));
  const double volume = slab.signedVolume();
  const Vector3 normal0 = slab.normals[0];
  slab.reverseOrientation();
  EXPECT_NEAR(slab.signedVolume(), -volume, 1e-12);
  EXPECT_TRUE(slab.normals[0].isApprox(-normal0));
  slab.computeVertexNormals();
  EXPECT_TRUE(slab.normals[0].isApprox(-normal0, 1e-12));
}

TEST(TriangleMesh, VertexNormalsPointOutward)
{
  const TriangleMesh slab = makeSlabSurface(slabParameters(2.0, 2.0, 0.2, 4, 4, 1));
  for (std::size_t v = 0; v < slab.vertexCount(); ++v)
  {
    // Outward: positive component along the position for a centred box.
    EXPECT_GT(slab.normals[v].dot(slab.positions[v]), 0.0) << "vertex " << v;
    EXPECT_NEAR(slab.normals[v].norm(), 1.0, 1e-12);
  }
}

TEST(TriangleMesh, CheckConsistencyNamesTheProblem)
{
  TriangleMesh mesh;
  mesh.name = "probe";
  mesh.positions = { Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0) };
  mesh.triangles = { { 0, 1, 3 } };
  try
  {
    mesh.checkConsistency();
    FAIL() << "out-of-range index accepted";
  }
  catch (const InvalidInputError& error)
  {
    EXPECT_NE(
      std::string(error.what()).find("mesh 'probe': triangle 0 has vertex index 3 out of range"),
      std::string::npos)
      << error.what();
  }
  mesh.triangles = { { 0, 1, 2 } };
  mesh.positions[1].y() = std::nan("");
  EXPECT_THROW(mesh.checkConsistency(), InvalidInputError);
  mesh.positions[1].y() = 0.0;
  mesh.normals = { Vector3::UnitZ() };
  EXPECT_THROW(mesh.checkConsistency(), InvalidInputError);
  mesh.normals.clear();
  mesh.pointAttributes.set("Radius", 1, { 0.1, 0.2 });
  EXPECT_THROW(mesh.checkConsistency(), InvalidInputError);
  mesh.pointAttributes.set("Radius", 1, { 0.1, 0.2, 0.3 });
  EXPECT_NO_THROW(mesh.checkConsistency());
}

TEST(TriangleMesh, AppendShiftsIndicesAndKeepsSharedAttributes)
{
  TriangleMesh a = makeSlabSurface(slabParameters(1.0, 1.0, 0.1, 1, 1, 1));
  TriangleMesh b = a;
  a.pointAttributes.set("Radius", 1, std::vector<double>(a.vertexCount(), 0.05));
  b.pointAttributes.set("Radius", 1, std::vector<double>(b.vertexCount(), 0.07));
  b.pointAttributes.set("OnlyInB", 1, std::vector<double>(b.vertexCount(), 1.0));
  const std::size_t vertices = a.vertexCount();
  const std::size_t triangles = a.triangleCount();
  a.append(b);
  EXPECT_EQ(a.vertexCount(), 2 * vertices);
  EXPECT_EQ(a.triangleCount(), 2 * triangles);
  EXPECT_EQ(a.triangles[triangles][0], b.triangles[0][0] + static_cast<int>(vertices));
  EXPECT_TRUE(a.hasTextureCoordinates());
  EXPECT_TRUE(a.pointAttributes.has("Radius"));
  EXPECT_FALSE(a.pointAttributes.has("OnlyInB"));
  EXPECT_DOUBLE_EQ(a.pointAttributes.get("Radius").values.back(), 0.07);
  EXPECT_NO_THROW(a.checkConsistency());
}

TEST(VertexAttributes, SetGetRemoveAndAppendCopies)
{
  VertexAttributes attributes;
  EXPECT_THROW(attributes.set("bad", 3, { 1.0, 2.0 }), InvalidInputError);
  EXPECT_THROW(attributes.get("missing"), InvalidInputError);
  attributes.set("Velocity", 3, { 1, 2, 3, 4, 5, 6 });
  EXPECT_EQ(attributes.get("Velocity").elementCount(), 2u);
  attributes.appendCopyOf(0);
  EXPECT_EQ(attributes.get("Velocity").elementCount(), 3u);
  EXPECT_DOUBLE_EQ(attributes.get("Velocity").element(2)[2], 3.0);
  EXPECT_NO_THROW(attributes.checkElementCount(3, "test"));
  EXPECT_THROW(attributes.checkElementCount(2, "test"), InvalidInputError);
  attributes.remove("Velocity");
  EXPECT_TRUE(attributes.empty());
}
