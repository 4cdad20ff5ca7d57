// vtkTissueBundleReader: a bundle prepared from the thesis's sheet
// (prepareTissue, writeTissueBundle) read back as three VTK outputs with
// the binding arrays, the radii and the metadata; a damaged file reported;
// a bundle of several tissues read one by one.
#include "vtkTissueBundleReader.h"

#include "ThinSheetModel.h"
#include "TissueBundle.h"

#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

#include "ThinTissueTestSupport.h"
#include "ThinTissueVtkErrorObserver.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

using thintissue::testing::ErrorCounter;

TEST(TissueBundleReader, ReadsTheThreeMeshesWithBindingAndMetadata)
{
  const thintissue::TissueModel sheet =
    thintissue::makeThinSheet(thintissue::thesisSheetVisualResolution(1));
  thintissue::TissuePreparationSettings settings;
  settings.collision.vertexCount = 65;
  settings.hexahedronCount = 81;
  const thintissue::TissueBundle bundle = thintissue::prepareTissue(sheet.visual, settings);
  const std::string path =
    (thintissue::testing::temporaryDirectory() / "reader-sheet.ttbundle").string();
  thintissue::writeTissueBundle(path, bundle);

  vtkNew<vtkTissueBundleReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastErrorMessage(), "");
  vtkPolyData* visual = reader->GetVisualOutput();
  ASSERT_EQ(visual->GetNumberOfPoints(), static_cast<vtkIdType>(bundle.visual.vertexCount()));
  EXPECT_EQ(visual->GetNumberOfCells(), static_cast<vtkIdType>(bundle.visual.triangleCount()));
  EXPECT_NE(visual->GetPointData()->GetArray("BindingParameters"), nullptr);
  EXPECT_NE(visual->GetCellData()->GetArray("CollisionTriangle"), nullptr);
  auto* metadata =
    vtkStringArray::SafeDownCast(visual->GetFieldData()->GetAbstractArray("Metadata"));
  ASSERT_NE(metadata, nullptr);
  EXPECT_EQ(metadata->GetValue(0), bundle.metadata);
  vtkPolyData* collision = reader->GetCollisionOutput();
  EXPECT_EQ(collision->GetNumberOfPoints(), 65);
  vtkDataArray* radius = collision->GetPointData()->GetArray("Radius");
  ASSERT_NE(radius, nullptr);
  EXPECT_GT(radius->GetRange()[0], 0.0);
  EXPECT_EQ(reader->GetSimulationOutput()->GetNumberOfCells(),
    static_cast<vtkIdType>(bundle.simulation.hexahedronCount()));

  // Damaged: empty outputs and the reason with the file's name.
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 7);
  vtkNew<ErrorCounter> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->Modified();
  reader->Update();
  const std::string message = reader->GetLastErrorMessage();
  EXPECT_NE(message.find("damaged"), std::string::npos) << message;
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_GT(errors->count, 0);
  EXPECT_EQ(reader->GetVisualOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(reader->GetSimulationOutput()->GetNumberOfCells(), 0);
  std::filesystem::remove(path);
}

// A bundle of two tissues (two sheets in one visual mesh, prepareTissues):
// TissueIndex picks one, GetNumberOfTissues counts them, the recorded units
// come as field data; an index beyond the tissues is an error.
TEST(TissueBundleReader, ReadsEachTissueOfSeveralWithTheirUnits)
{
  thintissue::TriangleMesh visual =
    thintissue::makeThinSheet(thintissue::thesisSheetVisualResolution(1)).visual;
  thintissue::TriangleMesh moved = visual;
  const double extent = visual.boundingBox().sizes().maxCoeff();
  for (thintissue::Vector3& x : moved.positions)
  {
    x.y() += 2.0 * extent;
  }
  visual.append(moved);
  thintissue::TissuePreparationSettings settings;
  settings.collision.vertexCount = 40;
  settings.hexahedronCount = 30;
  settings.units = thintissue::lengthUnitsNamed("mm");
  const thintissue::PreparedTissues prepared = thintissue::prepareTissues(visual, settings);
  ASSERT_EQ(prepared.tissues.size(), 2u);
  const std::string path =
    (thintissue::testing::temporaryDirectory() / "reader-two-sheets.ttbundle").string();
  thintissue::writeTissueBundles(path, prepared.tissues);

  vtkNew<vtkTissueBundleReader> reader;
  reader->SetFileName(path.c_str());
  for (int index : { 0, 1 })
  {
    SCOPED_TRACE(index);
    reader->SetTissueIndex(index);
    reader->Update();
    EXPECT_STREQ(reader->GetLastErrorMessage(), "");
    EXPECT_EQ(reader->GetNumberOfTissues(), 2);
    const thintissue::TissueBundle& tissue = prepared.tissues[index];
    vtkPolyData* collision = reader->GetCollisionOutput();
    ASSERT_EQ(collision->GetNumberOfPoints(), 40);
    double point[3];
    collision->GetPoint(0, point);
    EXPECT_NEAR(point[1], tissue.collision.positions[0].y(), 1e-12);
    EXPECT_EQ(reader->GetVisualOutput()->GetNumberOfPoints(),
      static_cast<vtkIdType>(tissue.visual.vertexCount()));
    for (vtkDataObject* output : { static_cast<vtkDataObject*>(reader->GetVisualOutput()),
           static_cast<vtkDataObject*>(collision),
           static_cast<vtkDataObject*>(reader->GetSimulationOutput()) })
    {
      auto* units =
        vtkStringArray::SafeDownCast(output->GetFieldData()->GetAbstractArray("LengthUnits"));
      ASSERT_NE(units, nullptr);
      EXPECT_EQ(units->GetValue(0), "mm");
      vtkDataArray* scale = output->GetFieldData()->GetArray("MetresPerUnit");
      ASSERT_NE(scale, nullptr);
      EXPECT_EQ(scale->GetTuple1(0), 0.001);
    }
  }
  vtkNew<ErrorCounter> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetTissueIndex(2);
  reader->Update();
  EXPECT_NE(std::string(reader->GetLastErrorMessage()).find("holds 2 tissues"), std::string::npos)
    << reader->GetLastErrorMessage();
  EXPECT_GT(errors->count, 0);
  EXPECT_EQ(reader->GetCollisionOutput()->GetNumberOfPoints(), 0);
  std::filesystem::remove(path);
}
