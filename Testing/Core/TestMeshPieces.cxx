// Pieces of a surface (MeshPieces.h) and the units of a mesh file
// (LengthUnits.h): what the preparation of several tissues in one file and
// in any unit rests on.
#include "LengthUnits.h"
#include "MeshPieces.h"
#include "MeshPrimitives.h"
#include "ThinTissueError.h"
#include "TriangleMeshAdjacency.h"

#include <gtest/gtest.h>

using namespace thintissue;

namespace
{

TriangleMesh slab(double width, const Vector3& offset)
{
  SlabSurfaceParameters parameters;
  parameters.width = width;
  parameters.depth = width;
  parameters.cellsX = parameters.cellsY = 4;
  TriangleMesh mesh = makeSlabSurface(parameters);
  for (Vector3& x : mesh.positions)
  {
    x += offset;
  }
  return mesh;
}

} // namespace

TEST(MeshPieces, PiecesComeLargestFirstWithTheirAttributes)
{
  TriangleMesh mesh = slab(2.0, Vector3(0.0, 0.0, 0.0));
  mesh.append(slab(10.0, Vector3(20.0, 0.0, 0.0)));
  mesh.append(slab(5.0, Vector3(-20.0, 0.0, 0.0)));
  mesh.name = "three.obj";
  std::vector<double> tags(mesh.vertexCount());
  for (std::size_t v = 0; v < tags.size(); ++v)
  {
    tags[v] = static_cast<double>(v);
  }
  mesh.pointAttributes.set("Tag", 1, tags);
  EXPECT_EQ(countPieces(mesh), 3u);
  const std::vector<MeshPiece> pieces = splitIntoPieces(mesh);
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_NEAR(pieces[0].centre.x(), 20.0, 1e-9);
  EXPECT_NEAR(pieces[1].centre.x(), -20.0, 1e-9);
  EXPECT_NEAR(pieces[2].centre.x(), 0.0, 1e-9);
  EXPECT_NEAR(pieces[0].largestExtent, 10.0, 1e-9);
  for (const MeshPiece& piece : pieces)
  {
    SCOPED_TRACE(piece.description());
    EXPECT_EQ(piece.mesh.name, "three.obj piece " + std::to_string(piece.number));
    EXPECT_NO_THROW(piece.mesh.checkConsistency());
    EXPECT_TRUE(piece.mesh.hasTextureCoordinates());
    const auto& tag = piece.mesh.pointAttributes.get("Tag").values;
    for (std::size_t v = 0; v < piece.mesh.vertexCount(); ++v)
    {
      const int original = piece.originalVertices[v];
      EXPECT_EQ(tag[v], static_cast<double>(original));
      EXPECT_EQ(piece.mesh.positions[v], mesh.positions[original]);
    }
  }
  EXPECT_NE(pieces[2].description().find("piece 3: "), std::string::npos);
}

TEST(MeshPieces, TissuesTouchingAtOneVertexStayTwo)
{
  // Two slabs sharing one corner vertex (a bow-tie where two labels touch).
  TriangleMesh first = slab(2.0, Vector3::Zero());
  TriangleMesh second = slab(2.0, Vector3(2.0, 2.0, 0.5));
  int corner = 0;
  for (int v = 0; v < static_cast<int>(second.vertexCount()); ++v)
  {
    if ((second.positions[v] - second.positions[corner]).sum() < 0.0)
    {
      corner = v; // the lowest corner of the second slab: (1, 1, 0.25)
    }
  }
  const Vector3 shared = second.positions[corner];
  int match = -1;
  for (int v = 0; v < static_cast<int>(first.vertexCount()); ++v)
  {
    match = (first.positions[v] - shared).norm() < 1e-12 ? v : match;
  }
  ASSERT_GE(match, 0);
  const int offset = static_cast<int>(first.vertexCount());
  first.append(second);
  for (Triangle& t : first.triangles)
  {
    for (int& v : t)
    {
      v = v == offset + corner ? match : v;
    }
  }
  EXPECT_EQ(countPieces(first), 2u);
  const std::vector<MeshPiece> pieces = splitIntoPieces(first);
  ASSERT_EQ(pieces.size(), 2u);
  // The shared vertex is copied into both pieces.
  EXPECT_EQ(pieces[0].mesh.vertexCount(), second.vertexCount());
  EXPECT_EQ(pieces[1].mesh.vertexCount(), second.vertexCount());
}

TEST(MeshPieces, FragmentsBelowTheFractionAreDropped)
{
  TriangleMesh mesh = slab(10.0, Vector3::Zero());
  mesh.append(slab(9.0, Vector3(30.0, 0.0, 0.0)));
  mesh.append(slab(0.5, Vector3(0.0, 30.0, 0.0)));
  const PieceSelection selection = selectPieces(mesh, 0.05);
  ASSERT_EQ(selection.kept.size(), 2u);
  ASSERT_EQ(selection.dropped.size(), 1u);
  EXPECT_EQ(selection.dropped[0].number, 3);
  EXPECT_NEAR(selection.dropped[0].centre.y(), 30.0, 1e-9);
  EXPECT_EQ(selectPieces(mesh, 0.0).kept.size(), 3u);
  EXPECT_EQ(selectPieces(mesh, 1.0).kept.size(), 1u);
  EXPECT_THROW(selectPieces(mesh, 1.5), InvalidInputError);
  EXPECT_TRUE(splitIntoPieces(TriangleMesh()).empty());
}

namespace
{

/// A flat 4 x 4 grid of squares (5 x 5 vertices, two triangles a square),
/// without the two triangles of square (1, 1) when `hole`.
TriangleMesh flatGrid(bool hole)
{
  TriangleMesh mesh;
  mesh.name = "grid";
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i)
      mesh.positions.emplace_back(i, j, 0.0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
    {
      if (hole && i == 1 && j == 1)
        continue;
      const int a = 5 * j + i;
      mesh.triangles.push_back({ { a, a + 1, a + 6 } });
      mesh.triangles.push_back({ { a, a + 6, a + 5 } });
    }
  return mesh;
}

} // namespace

// The border loops of a grid with a hole: the outline's 16 vertices and
// the hole's 4, each loop running along border edges; a vertex joining
// four border edges (two triangles touching at a corner) is refused by
// the mesh's name.
TEST(MeshPieces, BorderLoopsRunAlongTheBorderEdges)
{
  const TriangleMesh mesh = flatGrid(true);
  const TriangleMeshAdjacency adjacency(mesh);
  const std::vector<std::vector<int>> loops = borderLoops(adjacency, mesh.vertexCount(), "grid");
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].size(), 16u);
  EXPECT_EQ(loops[1].size(), 4u);
  for (const std::vector<int>& loop : loops)
    for (std::size_t i = 0; i < loop.size(); ++i)
    {
      const int e = adjacency.findEdge(loop[i], loop[(i + 1) % loop.size()]);
      ASSERT_GE(e, 0);
      EXPECT_TRUE(adjacency.isBorderEdge(e));
    }
  const TriangleMesh closed = slab(1.0, Vector3::Zero());
  EXPECT_TRUE(borderLoops(TriangleMeshAdjacency(closed), closed.vertexCount(), "slab").empty());

  TriangleMesh bowTie;
  bowTie.positions = {
    Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(-1, 0, 0), Vector3(0, -1, 0)
  };
  bowTie.triangles = { { { 0, 1, 2 } }, { { 0, 3, 4 } } };
  try
  {
    borderLoops(TriangleMeshAdjacency(bowTie), bowTie.vertexCount(), "mesh 'bow tie'");
    ADD_FAILURE() << "a vertex of four border edges was accepted";
  }
  catch (const InvalidInputError& error)
  {
    EXPECT_NE(
      std::string(error.what()).find("mesh 'bow tie': border vertex 0 joins 4"), std::string::npos)
      << error.what();
  }
}

// Pieces flooded across the edges a predicate joins: all of them (one
// piece), none (a piece per triangle), all but those crossing the grid's
// middle column line (two pieces, numbered by their first triangle).
TEST(MeshPieces, TrianglePiecesFloodAcrossJoinedEdges)
{
  const TriangleMesh mesh = flatGrid(false);
  const TriangleMeshAdjacency adjacency(mesh);
  std::vector<int> piece;
  EXPECT_EQ(floodTrianglePieces(
              adjacency, mesh.triangleCount(), [](int, int) { return true; }, piece),
    1);
  EXPECT_EQ(floodTrianglePieces(
              adjacency, mesh.triangleCount(), [](int, int) { return false; }, piece),
    static_cast<int>(mesh.triangleCount()));
  auto onMiddleLine = [&](int t, int k)
  {
    const Triangle& tri = mesh.triangles[t];
    return mesh.positions[tri[k]].x() == 2.0 && mesh.positions[tri[(k + 1) % 3]].x() == 2.0;
  };
  EXPECT_EQ(
    floodTrianglePieces(
      adjacency, mesh.triangleCount(), [&](int t, int k) { return !onMiddleLine(t, k); }, piece),
    2);
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const Triangle& tri = mesh.triangles[t];
    const double x = (mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]).x();
    EXPECT_EQ(piece[t], x < 6.0 ? 0 : 1) << "triangle " << t;
  }
}

TEST(LengthUnits, NamesScalesAndDetection)
{
  EXPECT_EQ(lengthUnitsNamed("mm")->metresPerUnit, 0.001);
  EXPECT_EQ(lengthUnitsNamed("Millimeters")->name, "mm");
  EXPECT_EQ(lengthUnitsNamed("centimetre")->metresPerUnit, 0.01);
  EXPECT_EQ(lengthUnitsNamed("m")->metresPerUnit, 1.0);
  EXPECT_EQ(lengthUnitsNamed("\xC2\xB5m")->name, "um");
  EXPECT_FALSE(lengthUnitsNamed("inch").has_value());
  EXPECT_EQ(lengthUnitsOfScale(0.001).name, "mm");
  EXPECT_EQ(lengthUnitsOfScale(0.0254).name, "");
  EXPECT_EQ(lengthUnitsOfScale(0.0254).description(), "1 unit = 0.0254 m");
  EXPECT_THROW(lengthUnitsOfScale(0.0), InvalidInputError);
  EXPECT_THROW(lengthUnitsOfScale(-1.0), InvalidInputError);

  // A meniscus (~40 mm) in each unit, the extent 2.4 and 2,000.
  EXPECT_EQ(detectLengthUnits(41.2).units.name, "mm");
  EXPECT_EQ(detectLengthUnits(0.0412).units.name, "m");
  EXPECT_EQ(detectLengthUnits(4.12).units.name, "cm");
  EXPECT_EQ(detectLengthUnits(2.4).units.name, "cm");
  EXPECT_EQ(detectLengthUnits(41200.0).units.name, "um");
  const DetectedLengthUnits unknown = detectLengthUnits(2000.0);
  EXPECT_FALSE(unknown.confident);
  EXPECT_EQ(unknown.units.name, "mm");
  EXPECT_NE(unknown.reason.find("millimetres assumed"), std::string::npos) << unknown.reason;
  EXPECT_TRUE(detectLengthUnits(41.2).confident);
  EXPECT_NE(detectLengthUnits(41.2).reason.find("41.2 mm"), std::string::npos);
}
