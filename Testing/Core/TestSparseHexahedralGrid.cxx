#include "HexahedralEmbedding.h"
#include "MeshPrimitives.h"
#include "SparseHexahedralGrid.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <tuple>

using namespace thintissue;

namespace
{

// Closed outward icosphere of `radius` (20 * 4^levels triangles).
TriangleMesh icosphere(double radius, int levels, const Vector3& centre = Vector3::Zero())
{
  TriangleMesh mesh;
  mesh.name = "icosphere";
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  mesh.positions = { { -1, t, 0 },
    { 1, t, 0 },
    { -1, -t, 0 },
    { 1, -t, 0 },
    { 0, -1, t },
    { 0, 1, t },
    { 0, -1, -t },
    { 0, 1, -t },
    { t, 0, -1 },
    { t, 0, 1 },
    { -t, 0, -1 },
    { -t, 0, 1 } };
  mesh.triangles = { { 0, 11, 5 },
    { 0, 5, 1 },
    { 0, 1, 7 },
    { 0, 7, 10 },
    { 0, 10, 11 },
    { 1, 5, 9 },
    { 5, 11, 4 },
    { 11, 10, 2 },
    { 10, 7, 6 },
    { 7, 1, 8 },
    { 3, 9, 4 },
    { 3, 4, 2 },
    { 3, 2, 6 },
    { 3, 6, 8 },
    { 3, 8, 9 },
    { 4, 9, 5 },
    { 2, 4, 11 },
    { 6, 2, 10 },
    { 8, 6, 7 },
    { 9, 8, 1 } };
  for (int level = 0; level < levels; ++level)
  {
    std::map<std::pair<int, int>, int> midpoints;
    const auto midpoint = [&](int a, int b)
    {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto found = midpoints.find(key);
      if (found != midpoints.end())
      {
        return found->second;
      }
      mesh.positions.push_back(0.5 * (mesh.positions[a] + mesh.positions[b]));
      const int index = static_cast<int>(mesh.positions.size() - 1);
      midpoints.emplace(key, index);
      return index;
    };
    std::vector<Triangle> finer;
    for (const Triangle& tri : mesh.triangles)
    {
      const int ab = midpoint(tri[0], tri[1]);
      const int bc = midpoint(tri[1], tri[2]);
      const int ca = midpoint(tri[2], tri[0]);
      finer.push_back({ tri[0], ab, ca });
      finer.push_back({ tri[1], bc, ab });
      finer.push_back({ tri[2], ca, bc });
      finer.push_back({ ab, bc, ca });
    }
    mesh.triangles = finer;
  }
  for (Vector3& p : mesh.positions)
  {
    p = centre + radius * p.normalized();
  }
  return mesh;
}

void expectSharedNodes(const HexahedralMesh& mesh)
{
  std::set<std::tuple<long long, long long, long long>> seen;
  const double scale = 1e6;
  for (const Vector3& node : mesh.nodes)
  {
    const auto key = std::make_tuple(std::llround(node.x() * scale),
      std::llround(node.y() * scale),
      std::llround(node.z() * scale));
    EXPECT_TRUE(seen.insert(key).second) << "duplicate node at " << node.transpose();
  }
  std::vector<int> uses(mesh.nodeCount(), 0);
  for (const Hexahedron& hex : mesh.hexahedra)
  {
    for (int node : hex)
    {
      ++uses[node];
    }
  }
  for (std::size_t v = 0; v < uses.size(); ++v)
  {
    EXPECT_GT(uses[v], 0) << "unused node " << v;
  }
}

// Every vertex inside or on some hexahedron.
void expectVerticesCovered(const TriangleMesh& surface, const HexahedralMesh& mesh)
{
  const HexahedralEmbedding embedding(mesh, surface.positions);
  EXPECT_EQ(embedding.outsidePointCount(), 0u);
}

} // namespace

TEST(SparseHexahedralGrid, BoxAlignedWithTheGridFillsIt)
{
  SlabSurfaceParameters parameters;
  parameters.width = 10.0;
  parameters.depth = 6.0;
  parameters.thickness = 4.0;
  parameters.cellsX = 7;
  parameters.cellsY = 5;
  parameters.cellsZ = 3;
  TriangleMesh box = makeSlabSurface(parameters);
  box.name = "box";
  SparseHexahedralGridSettings settings;
  settings.cellsAlongLongestSide = 10;
  const SparseHexahedralGrid grid = SparseHexahedralGrid::fromSurface(box, settings);
  EXPECT_DOUBLE_EQ(grid.cellSize, 1.0);
  EXPECT_EQ(grid.cellCounts, (std::array<int, 3>{ { 10, 6, 4 } }));
  EXPECT_EQ(grid.mesh.hexahedronCount(), 240u);
  EXPECT_EQ(grid.mesh.nodeCount(), 11u * 7u * 5u);
  EXPECT_EQ(grid.cellIndices.size(), 240u);
  EXPECT_EQ(grid.mesh.name, "sparse grid of 'box'");
  EXPECT_NO_THROW(grid.mesh.checkConsistency());
  EXPECT_TRUE(grid.mesh.boundingBox().isApprox(box.boundingBox(), 1e-12));
  expectSharedNodes(grid.mesh);
  expectVerticesCovered(box, grid.mesh);
  // Cubic cells of the given size; hexahedra have positive volume in VTK order.
  for (std::size_t h = 0; h < grid.mesh.hexahedronCount(); ++h)
  {
    const Hexahedron& hex = grid.mesh.hexahedra[h];
    const Vector3 diagonal = grid.mesh.nodes[hex[6]] - grid.mesh.nodes[hex[0]];
    EXPECT_LT((diagonal - Vector3::Ones()).norm(), 1e-12);
    const auto& ijk = grid.cellIndices[h];
    EXPECT_LT(
      (grid.mesh.nodes[hex[0]] - (grid.origin + Vector3(ijk[0], ijk[1], ijk[2]))).norm(), 1e-12);
  }
  // The same with an explicit cell size.
  settings.cellSize = 2.0;
  EXPECT_EQ(SparseHexahedralGrid::fromSurface(box, settings).mesh.hexahedronCount(), 5u * 3u * 2u);
}

TEST(SparseHexahedralGrid, SphereKeepsTheCellsTouchingItsInterior)
{
  const double radius = 5.0;
  const TriangleMesh sphere = icosphere(radius, 4, Vector3(1.0, -2.0, 3.0));
  const int n = 12;
  const SparseHexahedralGrid grid =
    SparseHexahedralGrid::fromSurface(sphere, SparseHexahedralGridSettings{ n, 0.0 });
  const double h = grid.cellSize;
  EXPECT_NEAR(h, sphere.boundingBox().sizes().maxCoeff() / n, 1e-12);
  const std::size_t count = grid.mesh.hexahedronCount();
  // Between the cells inside the sphere shrunk by a cell diagonal and those
  // inside the sphere grown by one.
  const double reach = std::sqrt(3.0) * h;
  const double cellVolume = h * h * h;
  const double inner = 4.0 / 3.0 * M_PI * std::pow(radius - reach, 3) / cellVolume;
  const double outer = 4.0 / 3.0 * M_PI * std::pow(radius + reach, 3) / cellVolume;
  EXPECT_GT(static_cast<double>(count), inner);
  EXPECT_LT(static_cast<double>(count), outer);
  EXPECT_LT(count, static_cast<std::size_t>(n * n * n));
  expectSharedNodes(grid.mesh);
  expectVerticesCovered(sphere, grid.mesh);

  // Exactly the cells that touch the interior: a cell is kept iff its centre
  // is inside, or it is within reach of the surface (tested both ways with a
  // margin for the triangulated sphere).
  std::set<std::array<int, 3>> kept(grid.cellIndices.begin(), grid.cellIndices.end());
  const Vector3 centre(1.0, -2.0, 3.0);
  for (int k = 0; k < grid.cellCounts[2]; ++k)
  {
    for (int j = 0; j < grid.cellCounts[1]; ++j)
    {
      for (int i = 0; i < grid.cellCounts[0]; ++i)
      {
        const Vector3 c = grid.origin + h * Vector3(i + 0.5, j + 0.5, k + 0.5);
        const double r = (c - centre).norm();
        const bool isKept = kept.count({ { i, j, k } }) != 0;
        if (r < radius * 0.98)
        {
          EXPECT_TRUE(isKept) << i << " " << j << " " << k;
        }
        if (r > radius + 0.5 * reach)
        {
          EXPECT_FALSE(isKept) << i << " " << j << " " << k;
        }
      }
    }
  }
  std::size_t surfaceCells = 0;
  for (std::uint8_t flag : grid.intersectsSurface)
  {
    surfaceCells += flag;
  }
  EXPECT_GT(surfaceCells, 0u);
  EXPECT_LT(surfaceCells, count);
}

TEST(SparseHexahedralGrid, CavityOfAHollowBallIsLeftOut)
{
  TriangleMesh shell = icosphere(5.0, 3);
  TriangleMesh cavity = icosphere(3.0, 3);
  cavity.reverseOrientation();
  shell.append(cavity);
  shell.name = "hollow ball";
  const SparseHexahedralGrid grid =
    SparseHexahedralGrid::fromSurface(shell, SparseHexahedralGridSettings{ 20, 0.0 });
  const double h = grid.cellSize;
  for (std::size_t c = 0; c < grid.cellIndices.size(); ++c)
  {
    const auto& ijk = grid.cellIndices[c];
    const double r = (grid.origin + h * Vector3(ijk[0] + 0.5, ijk[1] + 0.5, ijk[2] + 0.5)).norm();
    EXPECT_GT(r, 3.0 - std::sqrt(3.0) * h);
  }
  // The solid shell is there.
  const HexahedralEmbedding embedding(grid.mesh, { Vector3(4.0, 0, 0), Vector3(0, 0, -4.0) });
  EXPECT_EQ(embedding.outsidePointCount(), 0u);
  const HexahedralEmbedding hole(grid.mesh, { Vector3::Zero() });
  EXPECT_EQ(hole.outsidePointCount(), 1u);
}

TEST(SparseHexahedralGrid, TriangleSoupOfAClosedSurfaceIsAccepted)
{
  // As read from STL: three vertices of its own per triangle.
  const TriangleMesh welded = icosphere(2.0, 2);
  TriangleMesh soup;
  soup.name = "soup";
  for (const Triangle& t : welded.triangles)
  {
    const int first = static_cast<int>(soup.positions.size());
    for (int k = 0; k < 3; ++k)
    {
      soup.positions.push_back(welded.positions[t[k]]);
    }
    soup.triangles.push_back({ first, first + 1, first + 2 });
  }
  EXPECT_EQ(
    makeSparseHexahedralMesh(soup, 8).hexahedra, makeSparseHexahedralMesh(welded, 8).hexahedra);
}

TEST(SparseHexahedralGrid, BadInputGivesClearErrors)
{
  TriangleMesh sphere = icosphere(1.0, 1);
  sphere.name = "ball";
  EXPECT_THROW(makeSparseHexahedralMesh(sphere, 0), InvalidInputError);
  EXPECT_THROW(makeSparseHexahedralMesh(sphere, -3), InvalidInputError);
  EXPECT_THROW(SparseHexahedralGrid::fromSurface(sphere, SparseHexahedralGridSettings{ 5, -1.0 }),
    InvalidInputError);
  EXPECT_THROW(SparseHexahedralGrid::fromSurface(sphere, SparseHexahedralGridSettings{ 5, 1e-7 }),
    InvalidInputError);
  TriangleMesh open = sphere;
  open.triangles.pop_back();
  try
  {
    makeSparseHexahedralMesh(open, 5);
    FAIL() << "no error for an open surface";
  }
  catch (const InvalidInputError& error)
  {
    const std::string message = error.what();
    EXPECT_NE(message.find("'ball'"), std::string::npos) << message;
    EXPECT_NE(message.find("not closed (3 border edges"), std::string::npos) << message;
  }
  TriangleMesh empty;
  empty.name = "empty";
  EXPECT_THROW(makeSparseHexahedralMesh(empty, 5), InvalidInputError);
}

TEST(SparseHexahedralGrid, TriangleBoxOverlap)
{
  BoundingBox box(Vector3(0, 0, 0), Vector3(1, 1, 1));
  EXPECT_TRUE(
    triangleOverlapsBox(Vector3(0.5, 0.5, -1), Vector3(0.5, 0.5, 2), Vector3(2, 2, 0.5), box));
  // Beyond the corner (1, 1) in the plane z = 0.5: only an edge-cross axis
  // separates them.
  EXPECT_FALSE(triangleOverlapsBox(
    Vector3(1.6, 0.8, 0.5), Vector3(0.8, 1.6, 0.5), Vector3(1.6, 1.6, 0.5), box));
  // Beyond the corner (1, 1, 1): only the triangle's plane separates them.
  EXPECT_FALSE(
    triangleOverlapsBox(Vector3(3.5, 0, 0), Vector3(0, 3.5, 0), Vector3(0, 0, 3.5), box));
  EXPECT_TRUE(triangleOverlapsBox(Vector3(2.5, 0, 0), Vector3(0, 2.5, 0), Vector3(0, 0, 2.5), box));
  // Touching counts.
  EXPECT_TRUE(triangleOverlapsBox(Vector3(1, 0, 0), Vector3(2, 0, 0), Vector3(2, 1, 0), box));
  // A large triangle through the box with all vertices outside.
  EXPECT_TRUE(
    triangleOverlapsBox(Vector3(-5, -5, 0.5), Vector3(10, -5, 0.5), Vector3(-5, 10, 0.5), box));
  EXPECT_FALSE(
    triangleOverlapsBox(Vector3(-5, -5, 1.5), Vector3(10, -5, 1.5), Vector3(-5, 10, 1.5), box));
}
