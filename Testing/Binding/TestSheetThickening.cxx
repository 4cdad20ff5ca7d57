// Thickening of tissues segmented as one open surface (SheetThickening.h,
// issue 14): a flat sheet becomes the slab of that thickness around it, a
// curved one a closed slab of about area x thickness, closed pieces stay,
// bad input is refused, and the real cartilage sheets of
// ../shared/data/knee-smith2019 prepare once thickened.
#include "MeshImport.h"
#include "MeshPrimitives.h"
#include "MeshValidation.h"
#include "SheetThickening.h"
#include "ThinTissueError.h"
#include "ThinTissueTestSupport.h"
#include "TissueBundle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

using namespace thintissue;

namespace
{

/// A grid sheet of cellsX x cellsY unit cells in the plane z = 0, facing +z.
TriangleMesh gridSheet(int cellsX, int cellsY)
{
  TriangleMesh mesh;
  mesh.name = "grid sheet";
  auto index = [&](int i, int j) { return j * (cellsX + 1) + i; };
  for (int j = 0; j <= cellsY; ++j)
  {
    for (int i = 0; i <= cellsX; ++i)
    {
      mesh.positions.emplace_back(i, j, 0.0);
    }
  }
  for (int j = 0; j < cellsY; ++j)
  {
    for (int i = 0; i < cellsX; ++i)
    {
      mesh.triangles.push_back({ index(i, j), index(i + 1, j), index(i + 1, j + 1) });
      mesh.triangles.push_back({ index(i, j), index(i + 1, j + 1), index(i, j + 1) });
    }
  }
  return mesh;
}

/// The sheet bent over a sphere of `radius` (each vertex lifted onto it
/// above its grid point), centred on the grid, facing away from the centre.
TriangleMesh sphericalCap(int cells, double spacing, double radius)
{
  TriangleMesh mesh = gridSheet(cells, cells);
  const double centre = 0.5 * cells;
  for (Vector3& p : mesh.positions)
  {
    const Vector3 planar((p.x() - centre) * spacing, (p.y() - centre) * spacing, 0.0);
    p = Vector3(planar.x(), planar.y(), std::sqrt(radius * radius - planar.squaredNorm()));
  }
  return mesh;
}

} // namespace

TEST(SheetThickening, FlatSheetBecomesTheSlabAroundIt)
{
  const TriangleMesh sheet = gridSheet(10, 8);
  SheetThickeningReport report;
  const TriangleMesh slab = thickenOpenSheets(sheet, 0.5, &report);
  const MeshValidationReport validation = validateTriangleMesh(slab);
  EXPECT_TRUE(validation.isClosedManifold());
  EXPECT_NEAR(slab.signedVolume(), 80.0 * 0.5, 1e-9);
  const std::size_t n = sheet.vertexCount();
  ASSERT_EQ(slab.vertexCount(), 2 * n);
  for (std::size_t v = 0; v < n; ++v)
  {
    // The sheet is the mid-surface: the layers at z = +-0.25 above it.
    EXPECT_NEAR(
      (slab.positions[v] - sheet.positions[v] - Vector3(0.0, 0.0, 0.25)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(
      (slab.positions[n + v] - sheet.positions[v] + Vector3(0.0, 0.0, 0.25)).norm(), 0.0, 1e-12);
  }
  EXPECT_EQ(report.thickenedPieces, 1);
  EXPECT_EQ(report.closedPieces, 0);
  EXPECT_EQ(report.borderLoops, 1);
  EXPECT_EQ(report.addedVertices, n);
  EXPECT_EQ(report.addedTriangles, sheet.triangleCount() + 2 * 2 * (10 + 8));
  EXPECT_NE(report.summary("mm").find("thickened 1 open piece to 0.5 mm"), std::string::npos);
  EXPECT_NE(report.toJson().find("\"borderLoops\": 1"), std::string::npos);
}

TEST(SheetThickening, CurvedSheetKeepsItsTextureAndAttributes)
{
  TriangleMesh cap = sphericalCap(12, 1.0, 15.0);
  cap.name = "cap";
  for (std::size_t v = 0; v < cap.vertexCount(); ++v)
  {
    cap.textureCoordinates.emplace_back(cap.positions[v].x(), cap.positions[v].y());
  }
  cap.textureCorners = cap.triangles;
  std::vector<double> marks(cap.vertexCount());
  for (std::size_t v = 0; v < marks.size(); ++v)
  {
    marks[v] = static_cast<double>(v);
  }
  cap.pointAttributes.set("Mark", 1, marks);
  cap.computeVertexNormals();
  const TriangleMesh slab = thickenOpenSheets(cap, 1.0);
  EXPECT_TRUE(validateTriangleMesh(slab).isClosedManifold());
  // A shell of the cap's area and thickness 1 (the layers' areas differ by
  // the curvature, evenly about the cap's).
  EXPECT_NEAR(slab.signedVolume(), cap.surfaceArea(), 0.02 * cap.surfaceArea());
  EXPECT_EQ(slab.textureCorners.size(), slab.triangleCount());
  EXPECT_EQ(slab.normals.size(), slab.vertexCount());
  const AttributeArray& copied = slab.pointAttributes.get("Mark");
  ASSERT_EQ(copied.elementCount(), slab.vertexCount());
  EXPECT_EQ(copied.values[cap.vertexCount() + 7], 7.0); // the lower copy of vertex 7
  slab.checkConsistency();
}

TEST(SheetThickening, ClosedPiecesStayAsTheyWere)
{
  SlabSurfaceParameters box;
  box.cellsX = box.cellsY = 4;
  TriangleMesh mesh = makeSlabSurface(box);
  const std::size_t closedVertices = mesh.vertexCount();
  const std::size_t closedTriangles = mesh.triangleCount();
  TriangleMesh sheet = gridSheet(4, 4);
  for (Vector3& p : sheet.positions)
  {
    p += Vector3(20.0, 0.0, 0.0);
  }
  mesh.append(sheet);
  SheetThickeningReport report;
  const TriangleMesh result = thickenOpenSheets(mesh, 0.2, &report);
  EXPECT_EQ(report.thickenedPieces, 1);
  EXPECT_EQ(report.closedPieces, 1);
  for (std::size_t v = 0; v < closedVertices; ++v)
  {
    EXPECT_EQ(result.positions[v], mesh.positions[v]);
  }
  for (std::size_t t = 0; t < closedTriangles; ++t)
  {
    EXPECT_EQ(result.triangles[t], mesh.triangles[t]);
  }
  EXPECT_TRUE(validateTriangleMesh(result).isClosedManifold());
  EXPECT_NEAR(result.signedVolume(), mesh.signedVolume() + 16.0 * 0.2, 1e-9);
  // Nothing open: the mesh comes back as it was.
  TriangleMesh closed = makeSlabSurface(box);
  EXPECT_EQ(thickenOpenSheets(closed, 0.2).triangles, closed.triangles);
}

TEST(SheetThickening, BadInputIsRefused)
{
  const TriangleMesh sheet = gridSheet(4, 4);
  for (double thickness : { 0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity() })
  {
    EXPECT_THROW(thickenOpenSheets(sheet, thickness), InvalidInputError);
  }
  TriangleMesh flipped = sheet;
  std::swap(flipped.triangles[5][1], flipped.triangles[5][2]);
  try
  {
    thickenOpenSheets(flipped, 0.1);
    ADD_FAILURE() << "an inconsistently oriented sheet was thickened";
  }
  catch (const InvalidInputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("not consistently oriented (--repair"), std::string::npos)
      << e.what();
  }
  // An open tube of radius 1 (facing out): 4 thick, its inner layer turns
  // inside out.
  TriangleMesh tube = gridSheet(24, 6);
  tube.name = "tube";
  for (Vector3& p : tube.positions)
  {
    const double angle = -2.0 * M_PI * p.x() / 25.0; // 24 of 25 cells: a slit
    p = Vector3(std::cos(angle), std::sin(angle), p.y());
  }
  try
  {
    thickenOpenSheets(tube, 4.0);
    ADD_FAILURE() << "a fold was not refused";
  }
  catch (const InvalidInputError& e)
  {
    EXPECT_NE(
      std::string(e.what()).find("'tube': the thickness folds the layers"), std::string::npos)
      << e.what();
  }
  EXPECT_NO_THROW(thickenOpenSheets(tube, 0.2));
}

// The cartilage sheets segmented from MRI (../shared/data/knee-smith2019, in
// metres; skipped without them): refused as tissues while open, prepared
// once 2 mm thick (each plateau's sheet a tissue of its own).
TEST(SheetThickening, RealCartilageSheetsPrepare)
{
  const std::string data = thintissue::testing::sharedDataDirectory();
  const std::string directory = data + "/knee-smith2019";
  if (data.empty() || !std::filesystem::is_directory(directory))
  {
    GTEST_SKIP() << "../shared/data/knee-smith2019 not present";
  }
  for (const auto& [name, pieces] :
    { std::pair<std::string, std::size_t>{ "smith2019-R-tibia-cartilage.stl", 2 },
      std::pair<std::string, std::size_t>{ "smith2019-R-patella-cartilage.stl", 1 } })
  {
    SCOPED_TRACE(name);
    const TriangleMesh sheet = readTriangleMesh(directory + "/" + name);
    EXPECT_THROW(prepareTissues(sheet), InvalidInputError);
    SheetThickeningReport report;
    const TriangleMesh slab = thickenOpenSheets(sheet, 0.002, &report);
    EXPECT_EQ(static_cast<std::size_t>(report.thickenedPieces), pieces);
    EXPECT_EQ(static_cast<std::size_t>(report.borderLoops), pieces);
    const MeshValidationReport validation = validateTriangleMesh(slab);
    EXPECT_TRUE(validation.isClosedManifold());
    EXPECT_GT(validation.signedVolume, 0.0);
    const PreparedTissues prepared = prepareTissues(slab);
    EXPECT_EQ(prepared.tissues.size(), pieces);
    EXPECT_EQ(prepared.units.name, "m");
    for (const TissueBundle& tissue : prepared.tissues)
    {
      EXPECT_GT(tissue.collision.vertexCount(), 0u);
      EXPECT_GT(tissue.simulation.hexahedronCount(), 0u);
    }
  }
}
