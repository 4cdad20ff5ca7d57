#include "HexahedralEmbedding.h"
#include "MeshQueries.h"
#include "ThinTissueError.h"
#include "TrilinearCoordinates.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

using namespace thintissue;

namespace
{

// A 4 x 3 x 2 grid far from the origin, with every node moved at random by
// up to a fifth of a cell: hexahedra with warped faces, no parallelepipeds.
HexahedralMesh distortedGrid(std::uint32_t seed)
{
  HexahedralMesh mesh =
    HexahedralMesh::makeRegularGrid(Vector3(100.0, -50.0, 3.0), Vector3(1.0, 2.0, 0.5), 4, 3, 2);
  mesh.name = "distorted grid";
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (Vector3& node : mesh.nodes)
  {
    node += 0.2 * Vector3(1.0 * unit(random), 2.0 * unit(random), 0.5 * unit(random));
  }
  return mesh;
}

// Points at random local coordinates of random hexahedra (inside).
std::vector<Vector3> pointsInside(const HexahedralMesh& mesh, std::size_t count, std::uint32_t seed)
{
  std::mt19937 random(seed);
  std::uniform_int_distribution<std::size_t> cell(0, mesh.hexahedronCount() - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vector3> points(count);
  for (Vector3& p : points)
  {
    const Vector3 local(unit(random), unit(random), unit(random));
    p = trilinearPoint(hexahedronCorners(mesh, cell(random)), local);
  }
  return points;
}

double maximumError(const std::vector<Vector3>& a, const std::vector<Vector3>& b)
{
  double error = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    error = std::max(error, (a[i] - b[i]).norm());
  }
  return error;
}

double relativeTolerance(const HexahedralMesh& mesh)
{
  const BoundingBox box = mesh.boundingBox();
  return 1e-12 * std::max(box.min().cwiseAbs().maxCoeff(), box.max().cwiseAbs().maxCoeff());
}

} // namespace

TEST(HexahedralEmbedding, InvertTrilinearMapAgreesWithTrilinearCoordinates)
{
  const HexahedralMesh mesh = distortedGrid(1);
  std::mt19937 random(2);
  std::uniform_real_distribution<double> unit(-0.3, 1.3);
  for (int trial = 0; trial < 200; ++trial)
  {
    const HexahedronCorners corners = hexahedronCorners(mesh, trial % mesh.hexahedronCount());
    const Vector3 local(unit(random), unit(random), unit(random));
    const Vector3 point = trilinearPoint(corners, local);
    Vector3 found;
    ASSERT_TRUE(invertTrilinearMap(corners, point, found));
    EXPECT_LT((found - local).norm(), 1e-12);
    Vector3 reference;
    ASSERT_TRUE(trilinearCoordinates(corners, point, reference));
    EXPECT_LT((found - reference).norm(), 1e-9);
  }
}

TEST(HexahedralEmbedding, RestPointsInBoxHexahedraAreReproducedExactly)
{
  const HexahedralMesh mesh =
    HexahedralMesh::makeRegularGrid(Vector3(100.0, -50.0, 3.0), Vector3(1.0, 2.0, 0.5), 4, 3, 2);
  const std::vector<Vector3> points = pointsInside(mesh, 5000, 3);
  const HexahedralEmbedding embedding(mesh, points);
  EXPECT_EQ(embedding.pointCount(), points.size());
  EXPECT_EQ(embedding.nodeCount(), mesh.nodeCount());
  EXPECT_EQ(embedding.outsidePointCount(), 0u);
  std::vector<Vector3> mapped;
  embedding.mapPositions(mesh.nodes, mapped);
  EXPECT_LT(maximumError(mapped, points), relativeTolerance(mesh));
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    EXPECT_TRUE(isInsideUnitCube(embedding.localCoordinates(i), 1e-9));
  }
}

TEST(HexahedralEmbedding, RestPointsInDistortedHexahedraAreReproducedExactly)
{
  const HexahedralMesh mesh = distortedGrid(4);
  const std::vector<Vector3> points = pointsInside(mesh, 5000, 5);
  const HexahedralEmbedding embedding(mesh, points);
  EXPECT_EQ(embedding.outsidePointCount(), 0u);
  std::vector<Vector3> mapped;
  embedding.mapPositions(mesh.nodes, mapped);
  EXPECT_LT(maximumError(mapped, points), relativeTolerance(mesh));
  for (std::size_t i = 0; i < points.size(); i += 97)
  {
    // The chosen hexahedron contains the point.
    Vector3 local;
    ASSERT_TRUE(
      invertTrilinearMap(hexahedronCorners(mesh, static_cast<std::size_t>(embedding.hexahedron(i))),
        points[i],
        local));
    EXPECT_TRUE(isInsideUnitCube(local, 1e-9));
    // Row i of H: the trilinear weights, summing to 1.
    const auto w = embedding.weights(i);
    const auto reference = trilinearWeights(embedding.localCoordinates(i));
    double sum = 0.0;
    for (int k = 0; k < 8; ++k)
    {
      EXPECT_DOUBLE_EQ(w[k], reference[k]);
      sum += w[k];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_EQ(embedding.nodesOf(i), mesh.hexahedra[embedding.hexahedron(i)]);
  }
}

TEST(HexahedralEmbedding, OutsidePointsGoToTheNearestHexahedron)
{
  const HexahedralMesh mesh = distortedGrid(6);
  const BoundingBox box = mesh.boundingBox();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Within half a cell of the mesh's box: outside points, no clamping.
  const Vector3 margin(0.5, 1.0, 0.25);
  std::vector<Vector3> points(3000);
  for (Vector3& p : points)
  {
    const Vector3 t(unit(random), unit(random), unit(random));
    p = (box.min() - margin) + t.cwiseProduct(box.sizes() + 2.0 * margin);
  }
  // Warped thin cells extrapolate fast: allow it, then check every point
  // that was not clamped.
  HexahedralEmbeddingSettings settings;
  settings.maximumExtrapolation = 3.0;
  const HexahedralEmbedding embedding(mesh, points, settings);
  EXPECT_GT(embedding.outsidePointCount(), 500u);
  EXPECT_LT(embedding.clampedPointCount(), points.size() / 100);
  const HexahedronLocator locator(mesh);
  std::size_t clamped = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const HexahedronLocation location = locator.locate(points[i], settings);
    EXPECT_EQ(location.hexahedron, embedding.hexahedron(i));
    EXPECT_EQ(location.localCoordinates, embedding.localCoordinates(i));
    if (location.clamped)
    {
      ++clamped;
      // Then the point maps to the closest point of its hexahedron.
      const double distance = (embedding.mapPosition(i, mesh.nodes) - points[i]).norm();
      const HexahedronCorners corners =
        hexahedronCorners(mesh, static_cast<std::size_t>(location.hexahedron));
      for (int a = 0; a < 3; ++a)
      {
        for (double side : { 0.0, 1.0 })
        {
          for (int u = 0; u <= 20; ++u)
          {
            for (int v = 0; v <= 20; ++v)
            {
              Vector3 local;
              local[a] = side;
              local[(a + 1) % 3] = u / 20.0;
              local[(a + 2) % 3] = v / 20.0;
              ASSERT_LE(distance, (trilinearPoint(corners, local) - points[i]).norm() + 1e-9)
                << "point " << i;
            }
          }
        }
      }
      continue;
    }
    // Extrapolated coordinates reproduce outside points exactly too.
    EXPECT_LT((embedding.mapPosition(i, mesh.nodes) - points[i]).norm(), relativeTolerance(mesh))
      << "point " << i;
  }
  EXPECT_EQ(clamped, embedding.clampedPointCount());

  std::size_t checked = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const double chosen = distanceToHexahedron(
      hexahedronCorners(mesh, static_cast<std::size_t>(embedding.hexahedron(i))), points[i]);
    if (chosen == 0.0 && i % 10 != 0)
    {
      continue; // inside: check only a sample
    }
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t h = 0; h < mesh.hexahedronCount(); ++h)
    {
      nearest = std::min(nearest, distanceToHexahedron(hexahedronCorners(mesh, h), points[i]));
    }
    EXPECT_LE(chosen, nearest + 1e-12) << "point " << i;
    ++checked;
  }
  EXPECT_GT(checked, 500u);
}

// distanceToHexahedron skips the faces whose bounding boxes lie farther
// than the best triangle so far: the distance is still the least over all
// 24 boundary triangles (each face joined to its centre), bit for bit.
TEST(HexahedralEmbedding, BoundaryDistanceIsTheLeastOverAllFaceTriangles)
{
  constexpr int faces[6][4] = {
    { 0, 3, 7, 4 }, { 1, 2, 6, 5 }, { 0, 1, 5, 4 }, { 3, 2, 6, 7 }, { 0, 1, 2, 3 }, { 4, 5, 6, 7 }
  };
  const HexahedralMesh mesh = distortedGrid(12);
  std::mt19937 random(13);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::size_t outside = 0;
  for (std::size_t h = 0; h < mesh.hexahedronCount(); ++h)
  {
    const HexahedronCorners c = hexahedronCorners(mesh, h);
    Vector3 centre = Vector3::Zero();
    for (const Vector3& corner : c)
      centre += corner / 8.0;
    for (int i = 0; i < 200; ++i)
    {
      // Around the cell, and on its corners and edges (ties between faces).
      Vector3 p = centre + Vector3(1.2 * unit(random), 2.4 * unit(random), 0.6 * unit(random));
      if (i % 10 == 0)
        p = c[i % 8];
      if (i % 10 == 5)
        p = 0.5 * (c[i % 8] + c[(i + 1) % 8]) + Vector3(0.0, 0.0, 0.3);
      double expected = std::numeric_limits<double>::infinity();
      for (const auto& face : faces)
      {
        const Vector3 middle = 0.25 * (c[face[0]] + c[face[1]] + c[face[2]] + c[face[3]]);
        for (int e = 0; e < 4; ++e)
          expected = std::min(expected,
            (closestPointOnTriangle(p, c[face[e]], c[face[(e + 1) % 4]], middle) - p)
              .squaredNorm());
      }
      const double distance = distanceToHexahedron(c, p);
      if (distance == 0.0)
        continue;
      ++outside;
      ASSERT_EQ(distance, std::sqrt(expected)) << "hexahedron " << h << ", point " << i;
    }
  }
  EXPECT_GT(outside, 2000u);
}

TEST(HexahedralEmbedding, FarPointsAreClampedToTheNearestHexahedron)
{
  const HexahedralMesh mesh =
    HexahedralMesh::makeRegularGrid(Vector3::Zero(), Vector3::Ones(), 3, 3, 1);
  const std::vector<Vector3> points = {
    Vector3(1.5, 1.5, 10.0), Vector3(-6.0, 0.5, 0.5), Vector3(1.5, 1.5, 1.5)
  };
  const HexahedralEmbedding embedding(mesh, points);
  EXPECT_EQ(embedding.outsidePointCount(), 3u);
  // Points 0 and 1 lie 9 and 6 cells out (beyond maximumExtrapolation = 1);
  // point 2 only half a cell above.
  EXPECT_EQ(embedding.clampedPointCount(), 2u);
  EXPECT_EQ(embedding.hexahedron(0), 4);
  EXPECT_EQ(embedding.hexahedron(1), 0);
  std::vector<Vector3> mapped;
  embedding.mapPositions(mesh.nodes, mapped);
  EXPECT_LT((mapped[0] - Vector3(1.5, 1.5, 1.0)).norm(), 1e-12);
  EXPECT_LT((mapped[1] - Vector3(0.0, 0.5, 0.5)).norm(), 1e-12);
  EXPECT_LT((mapped[2] - points[2]).norm(), 1e-12);

  // Allowing more extrapolation keeps point 1 exact as well.
  HexahedralEmbeddingSettings settings;
  settings.maximumExtrapolation = 7.0;
  const HexahedralEmbedding wide(mesh, points, settings);
  EXPECT_EQ(wide.clampedPointCount(), 1u);
  EXPECT_LT((wide.mapPosition(1, mesh.nodes) - points[1]).norm(), 1e-12);
}

TEST(HexahedralEmbedding, TransposeIsTheAdjointOfTheMapping)
{
  const HexahedralMesh mesh = distortedGrid(8);
  std::vector<Vector3> points = pointsInside(mesh, 20000, 9);
  points.push_back(mesh.boundingBox().max() + Vector3(0.3, 0.3, 0.1)); // outside, extrapolated
  HexahedralEmbedding embedding(mesh, points);
  std::mt19937 random(10);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Vector3> u(mesh.nodeCount());
  for (Vector3& v : u)
  {
    v = Vector3(unit(random), unit(random), unit(random));
  }
  std::vector<Vector3> f(points.size());
  for (Vector3& v : f)
  {
    v = Vector3(unit(random), unit(random), unit(random));
  }
  std::vector<Vector3> hu;
  embedding.mapPositions(u, hu);
  double left = 0.0;
  double scale = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i)
  {
    left += hu[i].dot(f[i]);
    scale += hu[i].norm() * f[i].norm();
  }
  for (const std::size_t threshold : { std::numeric_limits<std::size_t>::max(), std::size_t(0) })
  {
    embedding.setParallelThreshold(threshold);
    std::vector<Vector3> htf(mesh.nodeCount(), Vector3::Zero());
    embedding.accumulateForces(f, htf);
    double right = 0.0;
    for (std::size_t v = 0; v < u.size(); ++v)
    {
      right += u[v].dot(htf[v]);
    }
    EXPECT_NEAR(left, right, 1e-13 * scale) << "parallel threshold " << threshold;
  }

  // Forces on a few points (contact) equal the full sum with zeros elsewhere.
  const std::vector<int> contact = { 3, 17, static_cast<int>(points.size() - 1) };
  const std::vector<Vector3> forces = { Vector3(1, 2, 3), Vector3(-1, 0, 2), Vector3(0, 0, -4) };
  std::vector<Vector3> sparse(mesh.nodeCount(), Vector3::Zero());
  embedding.accumulateForces(contact, forces, sparse);
  std::vector<Vector3> dense(points.size(), Vector3::Zero());
  for (std::size_t i = 0; i < contact.size(); ++i)
  {
    dense[contact[i]] = forces[i];
  }
  std::vector<Vector3> full(mesh.nodeCount(), Vector3::Zero());
  embedding.setParallelThreshold(std::numeric_limits<std::size_t>::max());
  embedding.accumulateForces(dense, full);
  EXPECT_LT(maximumError(sparse, full), 1e-14);
  // Total force is preserved (rows of H sum to 1).
  Vector3 total = Vector3::Zero();
  for (const Vector3& v : sparse)
  {
    total += v;
  }
  EXPECT_LT((total - Vector3(0, 2, 1)).norm(), 1e-13);
}

TEST(HexahedralEmbedding, ParallelMappingEqualsSerialWithoutAllocation)
{
  const HexahedralMesh mesh = distortedGrid(11);
  HexahedralEmbedding embedding(mesh, pointsInside(mesh, 60000, 12));
  std::vector<Vector3> moved = mesh.nodes;
  for (std::size_t v = 0; v < moved.size(); ++v)
  {
    moved[v] += Vector3(std::sin(0.3 * v), std::cos(0.7 * v), 0.1 * v);
  }
  std::vector<Vector3> serial;
  embedding.setParallelThreshold(std::numeric_limits<std::size_t>::max());
  embedding.mapPositions(moved, serial);
  std::vector<Vector3> parallel(serial.size(), Vector3::Zero());
  const Vector3* storage = parallel.data();
  embedding.setParallelThreshold(0);
  embedding.mapPositions(moved, parallel);
  EXPECT_EQ(parallel.data(), storage);
  EXPECT_EQ(parallel, serial);
  // Parallel force accumulation is deterministic.
  std::vector<Vector3> f(serial.size(), Vector3(0.5, -1.0, 2.0));
  std::vector<Vector3> first(mesh.nodeCount(), Vector3::Zero());
  std::vector<Vector3> second(mesh.nodeCount(), Vector3::Zero());
  embedding.accumulateForces(f, first);
  embedding.accumulateForces(f, second);
  EXPECT_EQ(first, second);
}

TEST(HexahedralEmbedding, RigidMotionOfTheNodesMovesThePointsRigidly)
{
  const HexahedralMesh mesh = distortedGrid(13);
  std::vector<Vector3> points = pointsInside(mesh, 3000, 14);
  points.push_back(mesh.boundingBox().min() - Vector3(0.2, 0.2, 0.1));
  const HexahedralEmbedding embedding(mesh, points);
  const Eigen::Matrix3d rotation =
    Eigen::AngleAxisd(1.1, Vector3(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const Vector3 translation(-30.0, 12.0, 7.5);
  std::vector<Vector3> moved(mesh.nodeCount());
  for (std::size_t v = 0; v < moved.size(); ++v)
  {
    moved[v] = rotation * mesh.nodes[v] + translation;
  }
  std::vector<Vector3> mapped;
  embedding.mapPositions(moved, mapped);
  // Rows of H sum to 1: H (R x + t) = R H x + t, clamped points included.
  std::vector<Vector3> expected;
  embedding.mapPositions(mesh.nodes, expected);
  for (Vector3& p : expected)
  {
    p = rotation * p + translation;
  }
  EXPECT_LT(maximumError(mapped, expected), relativeTolerance(mesh) * 10.0);
}

TEST(HexahedralEmbedding, LocalTopologyChanges)
{
  // Two cells side by side; a "cut" duplicates cell 1 with new nodes.
  HexahedralMesh mesh = HexahedralMesh::makeRegularGrid(Vector3::Zero(), Vector3::Ones(), 2, 1, 1);
  const std::vector<Vector3> points = {
    Vector3(0.5, 0.5, 0.5), Vector3(1.25, 0.5, 0.25), Vector3(1.75, 0.25, 0.75)
  };
  HexahedralEmbedding embedding(mesh, points);
  EXPECT_EQ(embedding.hexahedron(0), 0);
  EXPECT_EQ(embedding.hexahedron(1), 1);
  EXPECT_EQ(embedding.hexahedron(2), 1);

  Hexahedron duplicate;
  for (int k = 0; k < 8; ++k)
  {
    duplicate[k] = static_cast<int>(mesh.nodes.size());
    mesh.nodes.push_back(mesh.nodes[mesh.hexahedra[1][k]]);
  }
  mesh.hexahedra.push_back(duplicate);
  mesh.fixedNodes.assign(mesh.nodes.size(), 0);
  // Points 1 and 2 follow the duplicate; rest positions from the embedding.
  embedding.reembed({ 1, 2 }, mesh, { 2 });
  EXPECT_EQ(embedding.hexahedronCount(), 3u);
  EXPECT_EQ(embedding.nodeCount(), mesh.nodeCount());
  EXPECT_EQ(embedding.hexahedron(1), 2);
  EXPECT_EQ(embedding.hexahedron(2), 2);
  std::vector<Vector3> moved = mesh.nodes;
  for (int node : duplicate)
  {
    moved[node] += Vector3(0.0, 0.0, 5.0);
  }
  std::vector<Vector3> mapped;
  embedding.mapPositions(moved, mapped);
  EXPECT_LT((mapped[0] - points[0]).norm(), 1e-14);
  EXPECT_LT((mapped[1] - (points[1] + Vector3(0, 0, 5))).norm(), 1e-14);
  EXPECT_LT((mapped[2] - (points[2] + Vector3(0, 0, 5))).norm(), 1e-14);

  // Appended points (e.g. new vertices of a cut surface).
  const std::size_t first = embedding.appendPoints({ Vector3(0.25, 0.75, 0.5) }, mesh, { 0 });
  EXPECT_EQ(first, 3u);
  EXPECT_EQ(embedding.pointCount(), 4u);
  EXPECT_EQ(embedding.hexahedron(3), 0);
  EXPECT_LT((embedding.mapPosition(3, mesh.nodes) - Vector3(0.25, 0.75, 0.5)).norm(), 1e-14);

  // Direct assignment, and explicit rest positions over the whole mesh.
  embedding.setPoint(0, 1, Vector3(0.5, 0.5, 0.5));
  EXPECT_LT((embedding.mapPosition(0, mesh.nodes) - Vector3(1.5, 0.5, 0.5)).norm(), 1e-14);
  embedding.reembed({ 0 }, { Vector3(0.5, 0.5, 0.5) }, mesh);
  EXPECT_EQ(embedding.hexahedron(0), 0);

  EXPECT_THROW(embedding.setPoint(9, 0, Vector3::Zero()), InvalidInputError);
  EXPECT_THROW(embedding.setPoint(0, 3, Vector3::Zero()), InvalidInputError);
  EXPECT_THROW(embedding.reembed({ 7 }, mesh), InvalidInputError);
  EXPECT_THROW(embedding.reembed({ 0 }, mesh, { 5 }), InvalidInputError);
}

TEST(HexahedralEmbedding, AssignFromStoredCoordinates)
{
  const HexahedralMesh mesh = distortedGrid(15);
  const std::vector<Vector3> points = pointsInside(mesh, 100, 16);
  const HexahedralEmbedding embedding(mesh, points);
  HexahedralEmbedding copy;
  copy.assign(mesh, embedding.hexahedra(), embedding.localCoordinates());
  std::vector<Vector3> a;
  std::vector<Vector3> b;
  embedding.mapPositions(mesh.nodes, a);
  copy.mapPositions(mesh.nodes, b);
  EXPECT_EQ(a, b);
  EXPECT_THROW(copy.assign(mesh, { 0, 1 }, { Vector3::Zero() }), InvalidInputError);
  EXPECT_THROW(copy.assign(mesh, { 24 }, { Vector3::Zero() }), InvalidInputError);
  EXPECT_THROW(copy.assign(mesh, { 0 }, { Vector3::Constant(std::nan("")) }), InvalidInputError);
}

TEST(HexahedralEmbedding, BadInputGivesClearErrors)
{
  HexahedralMesh empty;
  empty.name = "nothing";
  try
  {
    HexahedralEmbedding embedding(empty, { Vector3::Zero() });
    FAIL() << "no error for a mesh without hexahedra";
  }
  catch (const InvalidInputError& error)
  {
    EXPECT_NE(std::string(error.what()).find("'nothing'"), std::string::npos) << error.what();
  }
  const HexahedralMesh mesh =
    HexahedralMesh::makeRegularGrid(Vector3::Zero(), Vector3::Ones(), 1, 1, 1);
  EXPECT_THROW(HexahedralEmbedding(mesh, { Vector3(0.5, std::nan(""), 0.5) }), InvalidInputError);
  const HexahedralEmbedding embedding(mesh, { Vector3(0.5, 0.5, 0.5) });
  std::vector<Vector3> out;
  EXPECT_THROW(embedding.mapPositions(std::vector<Vector3>(3), out), InvalidInputError);
  std::vector<Vector3> nodeForces(8, Vector3::Zero());
  EXPECT_THROW(embedding.accumulateForces(std::vector<Vector3>(2), nodeForces), InvalidInputError);
  EXPECT_THROW(
    embedding.accumulateForces({ 1 }, { Vector3::Zero() }, nodeForces), InvalidInputError);
  // An empty point set is legal.
  const HexahedralEmbedding none(mesh, {});
  EXPECT_EQ(none.pointCount(), 0u);
  none.mapPositions(mesh.nodes, out);
  EXPECT_TRUE(out.empty());
}
