#include "MeshImport.h"
#include "MeshPrimitives.h"
#include "ThinTissueTestSupport.h"
#include "vtkThinTissueConversion.h"
#include "vtkThinTissueMeshReader.h"
#include "vtkTriangleMeshValidationFilter.h"

#include <vtkAppendFilter.h>
#include <vtkCellData.h>
#include <vtkDataSetWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <gtest/gtest.h>

#include <filesystem>

using namespace thintissue;
using thintissue::testing::temporaryDirectory;
using thintissue::testing::writeTemporaryFile;

namespace
{

TriangleMesh slab()
{
  SlabSurfaceParameters p;
  p.cellsX = 6;
  p.cellsY = 5;
  return makeSlabSurface(p);
}

/// Reads `path` and returns the reader's error message ("" on success).
std::string readError(const std::string& path)
{
  vtkNew<vtkThinTissueMeshReader> reader;
  reader->SetFileName(path.c_str());
  // Errors are expected here; keep them out of the test log.
  reader->GlobalWarningDisplayOff();
  reader->Update();
  reader->GlobalWarningDisplayOn();
  if (reader->GetLastErrorMessage()[0] != '\0')
  {
    EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
  }
  return reader->GetLastErrorMessage();
}

} // namespace

TEST(MeshReader, ReadsVtpVtkAndVtu)
{
  const TriangleMesh mesh = slab();
  const auto polyData = toPolyData(mesh);
  const std::string vtp = (temporaryDirectory() / "slab.vtp").string();
  const std::string vtk = (temporaryDirectory() / "slab.vtk").string();
  const std::string vtu = (temporaryDirectory() / "slab.vtu").string();
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetFileName(vtp.c_str());
    writer->SetInputData(polyData);
    ASSERT_EQ(writer->Write(), 1);
    vtkNew<vtkDataSetWriter> legacy;
    legacy->SetFileName(vtk.c_str());
    legacy->SetInputData(polyData);
    ASSERT_EQ(legacy->Write(), 1);
    vtkNew<vtkAppendFilter> toGrid;
    toGrid->SetInputData(polyData);
    toGrid->Update();
    vtkNew<vtkXMLUnstructuredGridWriter> gridWriter;
    gridWriter->SetFileName(vtu.c_str());
    gridWriter->SetInputConnection(toGrid->GetOutputPort());
    ASSERT_EQ(gridWriter->Write(), 1);
  }
  for (const std::string& path : { vtp, vtk, vtu })
  {
    vtkNew<vtkThinTissueMeshReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    EXPECT_STREQ(reader->GetLastErrorMessage(), "") << path;
    vtkPolyData* output = reader->GetOutput();
    EXPECT_EQ(output->GetNumberOfPoints(), static_cast<vtkIdType>(mesh.vertexCount())) << path;
    EXPECT_EQ(output->GetNumberOfPolys(), static_cast<vtkIdType>(mesh.triangleCount())) << path;
    vtkNew<vtkTriangleMeshValidationFilter> validation;
    validation->SetInputConnection(reader->GetOutputPort());
    validation->Update();
    EXPECT_TRUE(validation->GetClosedOutwardSingleSurface()) << path << validation->GetReport();
  }
}

TEST(MeshReader, ReadsObjWithCornerTextureCoordinates)
{
  const TriangleMesh mesh = slab();
  const std::string obj = (temporaryDirectory() / "slab-for-reader.obj").string();
  writeObj(mesh, obj);
  vtkNew<vtkThinTissueMeshReader> reader;
  reader->SetFileName(obj.c_str());
  reader->Update();
  vtkPolyData* output = reader->GetOutput();
  EXPECT_EQ(output->GetNumberOfPolys(), static_cast<vtkIdType>(mesh.triangleCount()));
  EXPECT_NE(output->GetCellData()->GetArray(CornerTextureCoordinatesArrayName), nullptr);
  EXPECT_TRUE(vtkThinTissueMeshReader::CanReadFileExtension("a/b/C.OBJ"));
  EXPECT_TRUE(vtkThinTissueMeshReader::CanReadFileExtension("x.vtu"));
  EXPECT_FALSE(vtkThinTissueMeshReader::CanReadFileExtension("x.txt"));
}

TEST(MeshReader, BadInputGetsClearErrorsAndEmptyOutput)
{
  const auto directory = temporaryDirectory();
  const std::string missing = (directory / "missing.vtp").string();
  EXPECT_EQ(readError(missing), "mesh file '" + missing + "': no such file");
  std::filesystem::create_directories(directory / "folder.vtp");
  EXPECT_NE(
    readError((directory / "folder.vtp").string()).find("is a directory"), std::string::npos);
  const std::string unknown = writeTemporaryFile("mesh.abc", "abc");
  EXPECT_NE(readError(unknown).find("unknown mesh format '.abc'"), std::string::npos);
  const std::string garbage = writeTemporaryFile("garbage.vtp", "<VTKFile> not really");
  const std::string garbageError = readError(garbage);
  EXPECT_NE(garbageError.find("'" + garbage + "'"), std::string::npos) << garbageError;
  EXPECT_NE(garbageError.find("cannot be parsed"), std::string::npos) << garbageError;

  // A valid file with no triangles, and one with a NaN coordinate.
  vtkNew<vtkPolyData> empty;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  empty->SetPoints(points);
  const std::string emptyPath = (directory / "empty.vtp").string();
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName(emptyPath.c_str());
  writer->SetInputData(empty);
  writer->Write();
  EXPECT_NE(readError(emptyPath).find("contains no triangles"), std::string::npos);

  auto nan = toPolyData(slab());
  nan->GetPoints()->SetPoint(3, 0.0, std::nan(""), 0.0);
  const std::string nanPath = (directory / "nan.vtp").string();
  writer->SetFileName(nanPath.c_str());
  writer->SetInputData(nan);
  writer->Write();
  EXPECT_NE(readError(nanPath).find("vertex 3 has a non-finite coordinate"), std::string::npos)
    << readError(nanPath);

  vtkNew<vtkThinTissueMeshReader> unnamed;
  unnamed->GlobalWarningDisplayOff();
  unnamed->Update();
  unnamed->GlobalWarningDisplayOn();
  EXPECT_NE(std::string(unnamed->GetLastErrorMessage()).find("no FileName"), std::string::npos);
}

TEST(ValidationFilter, ReportsAnOpenSurface)
{
  TriangleMesh open = slab();
  open.triangles.pop_back();
  open.textureCorners.pop_back();
  vtkNew<vtkTriangleMeshValidationFilter> validation;
  validation->SetInputData(toPolyData(open));
  validation->Update();
  EXPECT_EQ(validation->GetNumberOfBorderEdges(), 3);
  EXPECT_FALSE(validation->GetClosedManifold());
  EXPECT_EQ(validation->GetNumberOfConnectedComponents(), 1);
  EXPECT_NE(std::string(validation->GetReport()).find("open border edges: 3, first at edge"),
    std::string::npos);
  EXPECT_EQ(
    validation->GetOutput()->GetNumberOfPolys(), static_cast<vtkIdType>(open.triangleCount()));
}
