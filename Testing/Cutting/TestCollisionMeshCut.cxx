// Cutting the collision mesh (thesis 5.3.1): splitting, snapping, opening,
// progressive cuts, cuts through vertices and along edges, repeated cuts,
// bad blades.
#include "CollisionMeshCut.h"
#include "CuttingInvariants.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

using namespace thintissue;
using namespace thintissue::cutting_test;

namespace
{

/// A flat n x n grid of unit cells in z = 0, two triangles a cell, radius
/// 0.1.
CuttableCollisionMesh grid(int n)
{
  std::vector<Vector3> x;
  std::vector<Triangle> t;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      x.emplace_back(i, j, 0.0);
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      t.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      t.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  return CuttableCollisionMesh("grid", x, t, std::vector<double>(x.size(), 0.1));
}

/// A vertical scalpel at x = `x` swept from y0 to y1.
Blade scalpelAlongY(double x, double y0, double y1)
{
  return Blade::sweptSegment(
    Vector3(x, y0, -1), Vector3(x, y0, 1), Vector3(x, y1, -1), Vector3(x, y1, 1));
}

/// A horizontal cleavage in miniature: a flat body (x in [-2, 0], z = 0)
/// and, from its edge x = 0 on, an upper and a lower leaf (x in [0, 2],
/// z = +-0.3 x), y in [0, n]. The edges along x = 0 are junctions (three
/// triangles); every triangle's normal points up.
CuttableCollisionMesh cleft(int n, int leaves = 2)
{
  std::vector<Vector3> x;
  std::vector<Triangle> t;
  auto sheet = [&](int first, int last, double slope, int shared)
  {
    // shared >= 0: the column x = 0 is the body's (ids from `shared`).
    std::vector<int> id;
    for (int j = 0; j <= n; ++j)
      for (int i = first; i <= last; ++i)
      {
        if (i == 0 && shared >= 0)
        {
          id.push_back(shared + j * 3 + 2);
          continue;
        }
        id.push_back(static_cast<int>(x.size()));
        x.emplace_back(i, j, slope * i);
      }
    const int w = last - first + 1;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i + 1 < w; ++i)
      {
        const int a = id[j * w + i], b = id[j * w + i + 1];
        const int c = id[(j + 1) * w + i + 1], d = id[(j + 1) * w + i];
        t.push_back({ a, b, c });
        t.push_back({ a, c, d });
      }
  };
  sheet(-2, 0, 0.0, -1);
  for (int leaf = 0; leaf < leaves; ++leaf)
    sheet(0, 2, leaf == 0 ? 0.3 : (leaf == 1 ? -0.3 : 0.6), 0);
  return CuttableCollisionMesh("cleft", x, t, std::vector<double>(x.size(), 0.1));
}

/// A vertical scalpel at y = `y` swept from x0 to x1.
Blade scalpelAlongX(double y, double x0, double x1)
{
  return Blade::sweptSegment(
    Vector3(x0, y, -2), Vector3(x0, y, 2), Vector3(x1, y, -2), Vector3(x1, y, 2));
}

/// Vertices of the mesh on an edge of three triangles.
int junctionVertexCount(const CuttableCollisionMesh& mesh)
{
  std::set<int> on;
  for (const auto& tri : mesh.triangles())
    for (int k = 0; k < 3; ++k)
      if (mesh.trianglesOfEdge(tri[k], tri[(k + 1) % 3])[2] >= 0)
        on.insert({ tri[k], tri[(k + 1) % 3] });
  return static_cast<int>(on.size());
}

int pieceCount(const CuttableCollisionMesh& mesh)
{
  int count = 0;
  collisionPieces(mesh, count);
  return count;
}

int borderEdgeCount(const CuttableCollisionMesh& mesh)
{
  int count = 0;
  for (const auto& tri : mesh.triangles())
    for (int k = 0; k < 3; ++k)
      count += mesh.trianglesOfEdge(tri[k], tri[(k + 1) % 3])[1] < 0 ? 1 : 0;
  return count;
}

double worstShape(const CuttableCollisionMesh& mesh)
{
  double worst = 1.0;
  const auto& x = mesh.restPositions();
  for (const auto& t : mesh.triangles())
  {
    const double area2 = (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
    const double longest = std::max({ (x[t[1]] - x[t[0]]).squaredNorm(),
      (x[t[2]] - x[t[1]]).squaredNorm(),
      (x[t[0]] - x[t[2]]).squaredNorm() });
    worst = std::min(worst, area2 / longest);
  }
  return worst;
}

} // namespace

TEST(CollisionMeshCut, ACutThroughSeparatesTheMeshIntoTwoPieces)
{
  CuttableCollisionMesh mesh = grid(4);
  const auto result = mesh.cut(scalpelAlongY(2.4, -1, 5), mesh.restPositions());
  EXPECT_TRUE(collisionMeshIsValid(mesh));
  EXPECT_EQ(pieceCount(mesh), 2);
  // Four cells crossed, two triangles each crossed through two edges.
  EXPECT_EQ(result.splits.size(), 8u);
  for (const auto& split : result.splits)
    EXPECT_EQ(split.children.size(), 3u) << "triangle " << split.parent;
  // Every edge point on the cut is duplicated once: the cut leaves the mesh
  // at both ends, so it has no tip.
  int duplicates = 0;
  for (const auto& v : result.newVertices)
    duplicates += v.duplicateOf >= 0 ? 1 : 0;
  EXPECT_EQ(duplicates, static_cast<int>(result.newVertices.size()) - duplicates);
  // Radii are interpolated: all 0.1 here.
  for (double r : mesh.radii())
    EXPECT_DOUBLE_EQ(r, 0.1);
  // Pieces keep the orientation of their parent (normals +z).
  for (const auto& t : mesh.triangles())
  {
    const auto& x = mesh.restPositions();
    EXPECT_GT((x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).z(), 0.0);
  }
  EXPECT_GT(worstShape(mesh), 0.1);
}

TEST(CollisionMeshCut, TheSplitPiecesCarryTheirBarycentricCorners)
{
  CuttableCollisionMesh mesh = grid(2);
  const auto before = mesh.restPositions();
  const auto result = mesh.cut(scalpelAlongY(0.5, -1, 3), mesh.restPositions());
  ASSERT_FALSE(result.splits.empty());
  for (const auto& split : result.splits)
  {
    for (std::size_t c = 0; c < split.children.size(); ++c)
    {
      const Triangle& piece = mesh.triangles()[split.children[c]];
      for (int k = 0; k < 3; ++k)
      {
        const Vector3& w = split.childCorners[c][k];
        const Vector3 p = w[0] * before[split.parentCorners[0]] +
                          w[1] * before[split.parentCorners[1]] +
                          w[2] * before[split.parentCorners[2]];
        EXPECT_NEAR((p - mesh.restPositions()[piece[k]]).norm(), 0.0, 1e-12);
      }
    }
  }
}

TEST(CollisionMeshCut, ACutThatStopsHalfWayOpensUpToItsTip)
{
  CuttableCollisionMesh mesh = grid(4);
  const int borderBefore = borderEdgeCount(mesh);
  mesh.cut(scalpelAlongY(2.4, -1, 2.3), mesh.restPositions());
  EXPECT_TRUE(collisionMeshIsValid(mesh));
  EXPECT_EQ(pieceCount(mesh), 1);
  EXPECT_GT(borderEdgeCount(mesh), borderBefore + 2);
  EXPECT_FALSE(mesh.cutTips().empty());
}

TEST(CollisionMeshCut, AProgressiveCutContinuesFromItsTip)
{
  CuttableCollisionMesh whole = grid(4);
  whole.cut(scalpelAlongY(2.4, -1, 5), whole.restPositions());
  CuttableCollisionMesh steps = grid(4);
  // Small steps, most ending inside a triangle.
  double y = -1.0;
  for (double next : { -0.2, 0.3, 0.45, 1.1, 1.6, 2.3, 2.9, 3.2, 3.8, 4.4, 5.0 })
  {
    steps.cut(scalpelAlongY(2.4, y, next), steps.restPositions());
    ASSERT_TRUE(collisionMeshIsValid(steps)) << "after the step to y = " << next;
    y = next;
  }
  EXPECT_EQ(pieceCount(steps), 2);
  EXPECT_EQ(pieceCount(whole), 2);
  EXPECT_EQ(steps.closedCutEdgeCount(), 0u);
}

// A knife drawn across in steps of any length, straight or slanted, through
// vertex columns or between them, cuts the grid in two and nothing more.
// Long steps put a tip, a crossing and a snapped corner in one triangle:
// joining only two of them cut the third off, and a tip joined to a snapped
// corner in a triangle the blade never crossed cut a triangle out (both
// made 1-triangle fragments before).
TEST(CollisionMeshCut, AKnifeDrawnInStepsOfAnyLengthCutsInTwo)
{
  for (const double step : { 0.05, 0.3, 0.6, 1.0, 1.7 })
    for (const double offset : { 0.0, 0.17, 0.5, 0.93 })
      for (const double angle : { 0.0, 0.3, 0.785, 1.1 })
      {
        CuttableCollisionMesh mesh = grid(8);
        const Vector3 along(std::sin(angle), std::cos(angle), 0.0);
        const Vector3 through(4.0 + offset, 4.0, 0.0);
        const Vector3 up = Vector3::UnitZ();
        for (double s = -8.0; s < 8.0; s += step)
        {
          const Vector3 a = through + s * along, b = through + (s + step) * along;
          mesh.cut(Blade::sweptSegment(a - up, a + up, b - up, b + up), mesh.restPositions());
        }
        const std::string where = "step " + std::to_string(step) + ", offset " +
                                  std::to_string(offset) + ", angle " + std::to_string(angle);
        ASSERT_TRUE(collisionMeshIsValid(mesh)) << where;
        EXPECT_EQ(pieceCount(mesh), 2) << where;
      }
}

TEST(CollisionMeshCut, CutsThroughVerticesAndAlongEdges)
{
  // x = 2 holds a column of vertices and vertical edges.
  CuttableCollisionMesh mesh = grid(4);
  const auto result = mesh.cut(scalpelAlongY(2.0, -1, 5), mesh.restPositions());
  EXPECT_TRUE(collisionMeshIsValid(mesh));
  EXPECT_EQ(pieceCount(mesh), 2);
  EXPECT_TRUE(result.splits.empty()); // along edges: nothing to split
  EXPECT_EQ(mesh.triangleCount(), 32u);
  // Near a vertex column: snapped onto it, no sliver.
  CuttableCollisionMesh near = grid(4);
  near.cut(scalpelAlongY(2.05, -1, 5), near.restPositions());
  EXPECT_TRUE(collisionMeshIsValid(near));
  EXPECT_EQ(pieceCount(near), 2);
  EXPECT_GT(worstShape(near), 0.1);
  // The diagonal through the cells' corners.
  CuttableCollisionMesh diagonal = grid(4);
  diagonal.cut(Blade::sweptSegment(
                 Vector3(-1, -1, -1), Vector3(-1, -1, 1), Vector3(5, 5, -1), Vector3(5, 5, 1)),
    diagonal.restPositions());
  EXPECT_TRUE(collisionMeshIsValid(diagonal));
  EXPECT_EQ(pieceCount(diagonal), 2);
  EXPECT_EQ(diagonal.triangleCount(), 32u);
}

TEST(CollisionMeshCut, ATangentBladeAndARepeatedCutChangeNothing)
{
  CuttableCollisionMesh mesh = grid(4);
  // Touches the mesh's border vertex (4, 4) only.
  const auto tangent = mesh.cut(
    Blade::sweptSegment(Vector3(4, 4, -1), Vector3(4, 4, 1), Vector3(6, 2, -1), Vector3(6, 2, 1)),
    mesh.restPositions());
  EXPECT_FALSE(tangent.changed());
  mesh.cut(scalpelAlongY(2.4, -1, 5), mesh.restPositions());
  const std::size_t vertices = mesh.vertexCount(), triangles = mesh.triangleCount();
  const auto again = mesh.cut(scalpelAlongY(2.4, -1, 5), mesh.restPositions());
  EXPECT_TRUE(collisionMeshIsValid(mesh));
  EXPECT_EQ(mesh.vertexCount(), vertices);
  EXPECT_EQ(mesh.triangleCount(), triangles);
  EXPECT_FALSE(again.changed());
}

TEST(CollisionMeshCut, ABiteOutlineCutsAPieceFree)
{
  CuttableCollisionMesh mesh = grid(6);
  std::vector<Vector3> low, high;
  for (int i = 0; i < 24; ++i)
  {
    const double a = 2.0 * M_PI * (i + 0.37) / 24.0;
    low.emplace_back(3.1 + 1.7 * std::cos(a), 2.9 + 1.7 * std::sin(a), -1.0);
    high.emplace_back(3.1 + 1.7 * std::cos(a), 2.9 + 1.7 * std::sin(a), 1.0);
  }
  mesh.cut(Blade::sweptOutline(low, high), mesh.restPositions());
  EXPECT_TRUE(collisionMeshIsValid(mesh));
  EXPECT_EQ(pieceCount(mesh), 2);
}

TEST(CollisionMeshCut, BadBladesAndPositionsLeaveTheMeshUntouched)
{
  CuttableCollisionMesh mesh = grid(3);
  const auto triangles = mesh.triangles();
  Blade nan = scalpelAlongY(1.5, -1, 4);
  nan.points[2].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(mesh.cut(nan, mesh.restPositions()), InvalidInputError);
  EXPECT_THROW(mesh.cut(Blade{}, mesh.restPositions()), InvalidInputError);
  EXPECT_THROW(mesh.cut(scalpelAlongY(1.5, 2, 2), mesh.restPositions()), InvalidInputError);
  EXPECT_THROW(mesh.cut(scalpelAlongY(1.5, -1, 4), {}), InvalidInputError);
  CollisionCutSettings snapTooLarge;
  snapTooLarge.snapFraction = 0.6;
  EXPECT_THROW(
    mesh.cut(scalpelAlongY(1.5, -1, 4), mesh.restPositions(), snapTooLarge), InvalidInputError);
  EXPECT_EQ(mesh.triangles(), triangles);
  EXPECT_EQ(mesh.vertexCount(), 16u);
}

TEST(CollisionMeshCut, NonManifoldOrInconsistentMeshesAreRefused)
{
  std::vector<Vector3> x = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } };
  EXPECT_THROW(CuttableCollisionMesh("flipped", x, { { 0, 1, 2 }, { 1, 2, 3 } }, { 1, 1, 1, 1 }),
    InvalidInputError);
  EXPECT_THROW(CuttableCollisionMesh("radii", x, { { 0, 1, 2 } }, { 1, 1 }), InvalidInputError);
  EXPECT_THROW(
    CuttableCollisionMesh("index", x, { { 0, 1, 9 } }, { 1, 1, 1, 1 }), InvalidInputError);
}

// A horizontal cleavage's junction (edges of three triangles, 5.3.1 with
// CollisionSides.h): a blade across the cleft splits the body and both
// leaves and the junction edge at one point; each side of the cut keeps a
// copy of that point, a junction still, and the pieces face the halves
// their parents faced.
TEST(CollisionMeshCut, ACleavageIsCutThroughItsJunction)
{
  CuttableCollisionMesh mesh = cleft(3);
  ASSERT_TRUE(collisionMeshIsValid(mesh));
  ASSERT_EQ(junctionVertexCount(mesh), 4);
  const auto result = mesh.cut(scalpelAlongX(1.5, -3, 3), mesh.restPositions());
  EXPECT_TRUE(collisionMeshIsValid(mesh));
  EXPECT_EQ(pieceCount(mesh), 2);
  // Two cells of the body and two of each leaf, two triangles each.
  EXPECT_EQ(result.splits.size(), 12u);
  // The junction point and its copy: both still join three triangles.
  EXPECT_EQ(junctionVertexCount(mesh), 6);
  int onJunction = 0;
  for (const auto& made : result.newVertices)
  {
    const int source = made.duplicateOf >= 0 ? made.duplicateOf : made.vertex;
    onJunction += std::abs(mesh.restPositions()[source].x()) < 1e-12 ? 1 : 0;
  }
  EXPECT_EQ(onJunction, 2);
}

TEST(CollisionMeshCut, ACutStoppingAtTheJunctionOpensUpToItAndGoesOnLater)
{
  CuttableCollisionMesh mesh = cleft(3);
  // Through both leaves, stopping in the body's first cell.
  mesh.cut(scalpelAlongX(1.5, 3, -0.5), mesh.restPositions());
  EXPECT_TRUE(collisionMeshIsValid(mesh));
  EXPECT_EQ(pieceCount(mesh), 1);
  EXPECT_FALSE(mesh.cutTips().empty());
  mesh.cut(scalpelAlongX(1.5, -0.5, -3), mesh.restPositions());
  EXPECT_TRUE(collisionMeshIsValid(mesh));
  EXPECT_EQ(pieceCount(mesh), 2);
}

// Along the junction itself the cut runs through its vertices and along its
// edges: the body and the two leaves come apart, three pieces, the leaves'
// cleft sides facing the cleft's walls still.
TEST(CollisionMeshCut, ACutAlongTheJunctionSeparatesTheBodyAndBothLeaves)
{
  CuttableCollisionMesh mesh = cleft(3);
  const auto halves = mesh.halves();
  mesh.cut(
    Blade::sweptSegment(Vector3(0, -1, -2), Vector3(0, -1, 2), Vector3(0, 4, -2), Vector3(0, 4, 2)),
    mesh.restPositions());
  EXPECT_TRUE(collisionMeshIsValid(mesh));
  EXPECT_EQ(pieceCount(mesh), 3);
  EXPECT_EQ(junctionVertexCount(mesh), 0);
  ASSERT_EQ(mesh.halves().size(), halves.size());
  EXPECT_EQ(mesh.halves(), halves);
}

// A bite through the body and the lower leaf whose outline passes a
// junction vertex (two V notches, tips at the vertex, the upper leaf whole)
// would leave the two sides of the notches held at one point by the upper
// leaf alone; the upper leaf is cracked along one of its edges there
// instead, so each side keeps a junction vertex of its own.
TEST(CollisionMeshCut, ANotchedJunctionCracksTheWholeLeaf)
{
  CuttableCollisionMesh mesh = cleft(4);
  const Vector3 tip(0, 2, 0);
  auto bodyRay = [&](double y)
  {
    return Blade::sweptSegment(
      Vector3(-2.5, y, -1), Vector3(-2.5, y, 1), tip - Vector3(0, 0, 1), tip + Vector3(0, 0, 1));
  };
  // Below the upper leaf (z = 0.3 x) but for its edge at the tip.
  auto lowerLeafRay = [&](double y)
  {
    return Blade::sweptSegment(
      tip - Vector3(0, 0, 1), tip, Vector3(2.5, y, -1), Vector3(2.5, y, 0.12 * 2.5));
  };
  for (const Blade& stroke : { bodyRay(0.5), bodyRay(3.5), lowerLeafRay(0.5), lowerLeafRay(3.5) })
  {
    mesh.cut(stroke, mesh.restPositions());
    ASSERT_TRUE(collisionMeshIsValid(mesh));
  }
  // The body's and the lower leaf's wedges come free; the rest holds.
  EXPECT_EQ(pieceCount(mesh), 3);
  std::vector<int> atTip;
  for (int v = 0; v < static_cast<int>(mesh.vertexCount()); ++v)
    if ((mesh.restPositions()[v] - tip).norm() < 1e-9)
      atTip.push_back(v);
  int junctions = 0, upperLeafBorders = 0;
  for (int v : atTip)
  {
    bool junction = false;
    for (int t : mesh.trianglesOfVertex(v))
      for (int w : mesh.triangles()[t])
      {
        const auto onEdge = mesh.trianglesOfEdge(v, w);
        junction = junction || (w != v && onEdge[2] >= 0);
        const bool upper = mesh.restPositions()[w].z() > 1e-9;
        upperLeafBorders += (w != v && upper && onEdge[1] < 0) ? 1 : 0;
      }
    junctions += junction ? 1 : 0;
  }
  EXPECT_EQ(junctions, 2) << "each side of the notches keeps a junction of its own";
  // The crack's two lips (each border edge seen from its one triangle).
  EXPECT_EQ(upperLeafBorders, 2);
}

TEST(CollisionMeshCut, AnEdgeOfFourTrianglesIsRefusedByName)
{
  try
  {
    cleft(2, 3);
    ADD_FAILURE() << "four triangles at an edge were taken";
  }
  catch (const InvalidInputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("'cleft'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("4 triangles"), std::string::npos) << e.what();
  }
}
