#include "vtkEmbeddedSurfaceDeformationFilter.h"
#include "vtkHexahedralEmbeddingFilter.h"
#include "vtkSurfaceToHexahedralGridFilter.h"
#include "vtkThinSlabSource.h"

#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkIdTypeArray.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTransform.h>
#include <vtkTransformFilter.h>
#include <vtkUnstructuredGrid.h>

#include <gtest/gtest.h>

#include <string>

namespace
{

vtkSmartPointer<vtkThinSlabSource> makeSlab()
{
  auto slab = vtkSmartPointer<vtkThinSlabSource>::New();
  slab->SetWidth(8.0);
  slab->SetDepth(6.0);
  slab->SetThickness(2.0);
  slab->SetCellsX(16);
  slab->SetCellsY(12);
  slab->SetCellsZ(4);
  return slab;
}

// Runs `algorithm` and returns its error message ("" if none), keeping the
// expected errors out of the test log.
std::string updateError(vtkAlgorithm* algorithm)
{
  std::string message;
  vtkNew<vtkCallbackCommand> callback;
  callback->SetClientData(&message);
  callback->SetCallback([](vtkObject*, unsigned long, void* clientData, void* callData)
    { *static_cast<std::string*>(clientData) = static_cast<const char*>(callData); });
  const unsigned long tag = algorithm->AddObserver(vtkCommand::ErrorEvent, callback);
  // The executive reports the failure again: keep that quiet too.
  vtkNew<vtkCallbackCommand> ignore;
  vtkExecutive* executive = algorithm->GetExecutive();
  const unsigned long executiveTag = executive->AddObserver(vtkCommand::ErrorEvent, ignore);
  algorithm->Update();
  algorithm->RemoveObserver(tag);
  executive->RemoveObserver(executiveTag);
  return message;
}

double maximumPointDistance(vtkPolyData* a, vtkPolyData* b, const double offset[3])
{
  double worst = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double p[3];
    double q[3];
    a->GetPoint(i, p);
    b->GetPoint(i, q);
    double d = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      d += (q[k] - p[k] - offset[k]) * (q[k] - p[k] - offset[k]);
    }
    worst = std::max(worst, std::sqrt(d));
  }
  return worst;
}

} // namespace

TEST(EmbeddingFilters, SurfaceToHexahedralGrid)
{
  auto slab = makeSlab();
  vtkNew<vtkSurfaceToHexahedralGridFilter> voxelize;
  voxelize->SetInputConnection(slab->GetOutputPort());
  voxelize->SetCellsAlongLongestSide(8);
  ASSERT_EQ(updateError(voxelize), "");
  vtkUnstructuredGrid* grid = voxelize->GetOutput();
  // The slab is 8 x 6 x 2 and aligned with the cells of size 1.
  EXPECT_EQ(grid->GetNumberOfCells(), 8 * 6 * 2);
  EXPECT_EQ(grid->GetNumberOfPoints(), 9 * 7 * 3);
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    ASSERT_EQ(grid->GetCellType(c), VTK_HEXAHEDRON);
  }
  EXPECT_DOUBLE_EQ(voxelize->GetGridCellSize(), 1.0);
  EXPECT_EQ(voxelize->GetGridDimensions()[0], 8);
  EXPECT_EQ(voxelize->GetGridDimensions()[1], 6);
  EXPECT_EQ(voxelize->GetGridDimensions()[2], 2);
  vtkDataArray* indices = grid->GetCellData()->GetArray("GridIndex");
  ASSERT_NE(indices, nullptr);
  EXPECT_EQ(indices->GetNumberOfComponents(), 3);
  ASSERT_NE(grid->GetCellData()->GetArray("IntersectsSurface"), nullptr);
  ASSERT_NE(grid->GetPointData()->GetArray("FixedNode"), nullptr);

  voxelize->SetCellSize(2.0);
  ASSERT_EQ(updateError(voxelize), "");
  EXPECT_EQ(voxelize->GetOutput()->GetNumberOfCells(), 4 * 3 * 1);
}

TEST(EmbeddingFilters, SurfaceToHexahedralGridErrors)
{
  auto slab = makeSlab();
  vtkNew<vtkSurfaceToHexahedralGridFilter> voxelize;
  voxelize->SetInputConnection(slab->GetOutputPort());
  voxelize->SetCellsAlongLongestSide(0);
  EXPECT_NE(updateError(voxelize).find("cells along the longest side must be at least 1"),
    std::string::npos);
  vtkNew<vtkPlaneSource> plane;
  voxelize->SetInputConnection(plane->GetOutputPort());
  voxelize->SetCellsAlongLongestSide(4);
  const std::string open = updateError(voxelize);
  EXPECT_NE(open.find("surface 'input surface': not closed"), std::string::npos) << open;
  EXPECT_EQ(voxelize->GetOutput()->GetNumberOfCells(), 0);
}

TEST(EmbeddingFilters, EmbedThenFollowTheGrid)
{
  auto slab = makeSlab();
  vtkNew<vtkSurfaceToHexahedralGridFilter> voxelize;
  voxelize->SetInputConnection(slab->GetOutputPort());
  voxelize->SetCellsAlongLongestSide(5); // not aligned with the slab
  vtkNew<vtkHexahedralEmbeddingFilter> embed;
  embed->SetInputConnection(slab->GetOutputPort());
  embed->SetGridConnection(voxelize->GetOutputPort());
  ASSERT_EQ(updateError(embed), "");
  vtkPolyData* embedded = embed->GetOutput();
  const vtkIdType count = slab->GetOutput()->GetNumberOfPoints();
  vtkDataArray* ids = embedded->GetPointData()->GetArray("HexahedronId");
  vtkDataArray* locals = embedded->GetPointData()->GetArray("TrilinearCoordinates");
  ASSERT_NE(ids, nullptr);
  ASSERT_NE(locals, nullptr);
  EXPECT_NE(vtkIdTypeArray::SafeDownCast(ids), nullptr);
  EXPECT_EQ(ids->GetNumberOfTuples(), count);
  EXPECT_EQ(locals->GetNumberOfComponents(), 3);
  EXPECT_EQ(locals->GetNumberOfTuples(), count);
  EXPECT_EQ(embed->GetNumberOfOutsidePoints(), 0);
  EXPECT_EQ(embedded->GetNumberOfPolys(), slab->GetOutput()->GetNumberOfPolys());
  // The input is passed through untouched.
  EXPECT_EQ(slab->GetOutput()->GetPointData()->GetArray("HexahedronId"), nullptr);

  // With the rest grid the surface stays where it is.
  vtkNew<vtkEmbeddedSurfaceDeformationFilter> deform;
  deform->SetInputConnection(embed->GetOutputPort());
  deform->SetGridConnection(voxelize->GetOutputPort());
  ASSERT_EQ(updateError(deform), "");
  const double zero[3] = { 0.0, 0.0, 0.0 };
  EXPECT_LT(maximumPointDistance(slab->GetOutput(), deform->GetOutput(), zero), 1e-12);
  vtkSmartPointer<vtkDataArray> restNormals = deform->GetOutput()->GetPointData()->GetNormals();
  ASSERT_NE(restNormals, nullptr);

  // A translated grid carries the surface along; normals do not change.
  vtkNew<vtkTransform> translation;
  translation->Translate(1.0, -2.0, 3.5);
  vtkNew<vtkTransformFilter> move;
  move->SetInputConnection(voxelize->GetOutputPort());
  move->SetTransform(translation);
  deform->SetGridConnection(move->GetOutputPort());
  ASSERT_EQ(updateError(deform), "");
  const double offset[3] = { 1.0, -2.0, 3.5 };
  EXPECT_LT(maximumPointDistance(slab->GetOutput(), deform->GetOutput(), offset), 1e-12);
  vtkDataArray* movedNormals = deform->GetOutput()->GetPointData()->GetNormals();
  ASSERT_NE(movedNormals, nullptr);
  EXPECT_STREQ(movedNormals->GetName(), restNormals->GetName());
  for (vtkIdType i = 0; i < count; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      ASSERT_NEAR(movedNormals->GetComponent(i, k), restNormals->GetComponent(i, k), 1e-12);
    }
  }

  // A rotation of the grid rotates the normals (recomputed, not copied).
  vtkNew<vtkTransform> rotation;
  rotation->RotateZ(90.0);
  move->SetTransform(rotation);
  ASSERT_EQ(updateError(deform), "");
  vtkDataArray* rotatedNormals = deform->GetOutput()->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < count; ++i)
  {
    ASSERT_NEAR(rotatedNormals->GetComponent(i, 0), -restNormals->GetComponent(i, 1), 1e-9);
    ASSERT_NEAR(rotatedNormals->GetComponent(i, 1), restNormals->GetComponent(i, 0), 1e-9);
    ASSERT_NEAR(rotatedNormals->GetComponent(i, 2), restNormals->GetComponent(i, 2), 1e-9);
  }
}

TEST(EmbeddingFilters, DeformationNeedsTheEmbeddingArrays)
{
  auto slab = makeSlab();
  vtkNew<vtkSurfaceToHexahedralGridFilter> voxelize;
  voxelize->SetInputConnection(slab->GetOutputPort());
  vtkNew<vtkEmbeddedSurfaceDeformationFilter> deform;
  deform->SetInputConnection(slab->GetOutputPort());
  deform->SetGridConnection(voxelize->GetOutputPort());
  EXPECT_NE(updateError(deform).find("run vtkHexahedralEmbeddingFilter first"), std::string::npos);

  // A grid with fewer cells than the embedding refers to.
  vtkNew<vtkHexahedralEmbeddingFilter> embed;
  embed->SetInputConnection(slab->GetOutputPort());
  embed->SetGridConnection(voxelize->GetOutputPort());
  embed->Update();
  vtkNew<vtkSurfaceToHexahedralGridFilter> coarse;
  coarse->SetInputConnection(slab->GetOutputPort());
  coarse->SetCellsAlongLongestSide(1);
  deform->SetInputConnection(embed->GetOutputPort());
  deform->SetGridConnection(coarse->GetOutputPort());
  const std::string message = updateError(deform);
  EXPECT_NE(message.find("out of range"), std::string::npos) << message;
}

TEST(EmbeddingFilters, PrintSelfNamesParameters)
{
  vtkNew<vtkHexahedralEmbeddingFilter> embed;
  vtkNew<vtkEmbeddedSurfaceDeformationFilter> deform;
  vtkNew<vtkSurfaceToHexahedralGridFilter> voxelize;
  std::ostringstream text;
  embed->Print(text);
  deform->Print(text);
  voxelize->Print(text);
  EXPECT_NE(text.str().find("MaximumExtrapolation: 1"), std::string::npos);
  EXPECT_NE(text.str().find("RecomputeNormals: On"), std::string::npos);
  EXPECT_NE(text.str().find("CellsAlongLongestSide: 10"), std::string::npos);
}
