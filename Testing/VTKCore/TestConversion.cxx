#include "HexahedralMesh.h"
#include "MeshPrimitives.h"
#include "ThinTissueError.h"
#include "vtkThinTissueConversion.h"

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <gtest/gtest.h>

using namespace thintissue;

TEST(Conversion, TriangleMeshRoundTripKeepsEverything)
{
  SlabSurfaceParameters p;
  p.cellsX = 4;
  p.cellsY = 3;
  TriangleMesh slab = makeSlabSurface(p);
  slab.pointAttributes.set("Radius", 1, std::vector<double>(slab.vertexCount(), 0.25));
  const auto polyData = toPolyData(slab);
  EXPECT_EQ(polyData->GetNumberOfPoints(), static_cast<vtkIdType>(slab.vertexCount()));
  EXPECT_EQ(polyData->GetNumberOfPolys(), static_cast<vtkIdType>(slab.triangleCount()));
  EXPECT_NE(polyData->GetPointData()->GetNormals(), nullptr);
  EXPECT_NE(polyData->GetPointData()->GetTCoords(), nullptr); // seam-free
  EXPECT_NE(polyData->GetCellData()->GetArray(CornerTextureCoordinatesArrayName), nullptr);
  EXPECT_NE(polyData->GetPointData()->GetArray("Radius"), nullptr);

  const TriangleMesh back = fromPolyData(polyData, "round trip");
  EXPECT_EQ(back.positions, slab.positions);
  EXPECT_EQ(back.triangles, slab.triangles);
  EXPECT_EQ(back.normals, slab.normals);
  ASSERT_TRUE(back.hasTextureCoordinates());
  for (std::size_t t = 0; t < slab.triangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(back.textureCoordinates[back.textureCorners[t][k]],
        slab.textureCoordinates[slab.textureCorners[t][k]]);
    }
  }
  ASSERT_TRUE(back.pointAttributes.has("Radius"));
  EXPECT_EQ(back.pointAttributes.get("Radius").values, slab.pointAttributes.get("Radius").values);
  EXPECT_EQ(back.pointAttributes.names().size(), 1u);
}

TEST(Conversion, SeamsLiveInTheCornerArrayOnly)
{
  TriangleMesh quad;
  quad.positions = { Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(1, 1, 0), Vector3(0, 1, 0) };
  quad.triangles = { { 0, 1, 2 }, { 0, 2, 3 } };
  // Vertex 0 and 2 get different coordinates in the two triangles: a seam.
  quad.textureCoordinates = {
    Vector2(0, 0), Vector2(1, 0), Vector2(1, 1), Vector2(0.5, 0.5), Vector2(0.9, 0.9), Vector2(0, 1)
  };
  quad.textureCorners = { { 0, 1, 2 }, { 3, 4, 5 } };
  const auto polyData = toPolyData(quad);
  EXPECT_EQ(polyData->GetPointData()->GetTCoords(), nullptr);
  const TriangleMesh back = fromPolyData(polyData, "seam");
  EXPECT_EQ(back.textureCoordinates.size(), 6u);
  EXPECT_EQ(back.textureCoordinates[back.textureCorners[1][1]], Vector2(0.9, 0.9));
  EXPECT_EQ(back.positions.size(), 4u); // positions stay welded
}

TEST(Conversion, PolygonsAreTriangulatedAndNaNIsRejected)
{
  vtkNew<vtkPolyData> polyData;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(1, 1, 0);
  points->InsertNextPoint(0, 1, 0);
  points->InsertNextPoint(-0.5, 0.5, 0);
  polyData->SetPoints(points);
  vtkNew<vtkCellArray> polys;
  const vtkIdType pentagon[5] = { 0, 1, 2, 3, 4 };
  polys->InsertNextCell(5, pentagon);
  polyData->SetPolys(polys);
  const TriangleMesh mesh = fromPolyData(polyData, "pentagon");
  EXPECT_EQ(mesh.triangleCount(), 3u);
  EXPECT_EQ(mesh.triangles[2], (Triangle{ 0, 3, 4 }));

  points->SetPoint(2, std::nan(""), 1, 0);
  try
  {
    fromPolyData(polyData, "pentagon");
    FAIL() << "NaN accepted";
  }
  catch (const InvalidInputError& error)
  {
    EXPECT_NE(std::string(error.what()).find("mesh 'pentagon': vertex 2 has a non-finite"),
      std::string::npos)
      << error.what();
  }
}

TEST(Conversion, HexahedralMeshRoundTripWithFixedNodes)
{
  HexahedralMesh grid = HexahedralMesh::makeRegularGrid(Vector3::Zero(), Vector3::Ones(), 3, 2, 1);
  grid.fixedNodes[0] = grid.fixedNodes[5] = 1;
  grid.nodeAttributes.set("Mass", 1, std::vector<double>(grid.nodeCount(), 2.0));
  const auto unstructured = toUnstructuredGrid(grid);
  EXPECT_EQ(unstructured->GetNumberOfCells(), 6);
  EXPECT_EQ(unstructured->GetCellType(0), VTK_HEXAHEDRON);
  const HexahedralMesh back = fromUnstructuredGrid(unstructured, "grid");
  EXPECT_EQ(back.nodes, grid.nodes);
  EXPECT_EQ(back.hexahedra, grid.hexahedra);
  EXPECT_EQ(back.fixedNodes, grid.fixedNodes);
  EXPECT_EQ(back.nodeAttributes.get("Mass").values, grid.nodeAttributes.get("Mass").values);

  vtkIdType tetra[4] = { 0, 1, 2, 3 };
  unstructured->InsertNextCell(VTK_TETRA, 4, tetra);
  EXPECT_THROW(fromUnstructuredGrid(unstructured, "grid"), InvalidInputError);
}

// An empty mesh (a source with nothing to output, e.g. a blade source with bad
// parameters) converts to an empty polydata. Before, the conversion copied
// from and to null pointers and called std::array::data on one: undefined
// behaviour that only UndefinedBehaviorSanitizer reports (issue 13).
TEST(Conversion, AnEmptyTriangleMeshGivesAnEmptyPolyData)
{
  const auto polyData = toPolyData(TriangleMesh{});
  ASSERT_NE(polyData, nullptr);
  EXPECT_EQ(polyData->GetNumberOfPoints(), 0);
  EXPECT_EQ(polyData->GetNumberOfPolys(), 0);
}
