// vtkWrinkleDisplacementFilter in a pipeline: the meniscus source's visual
// surface embedded in its hexahedra, the hexahedra dented and released
// step by step; wrinkles on the release, only where the monitor points
// reach; bad inputs reported.
#include "ThinTissueVtkErrorObserver.h"
#include "vtkAutomaticMonitorPointsFilter.h"
#include "vtkEmbeddedSurfaceDeformationFilter.h"
#include "vtkHexahedralEmbeddingFilter.h"
#include "vtkMeniscusSource.h"
#include "vtkWrinkleDisplacementFilter.h"

#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{

struct WrinklePipeline
{
  vtkNew<vtkMeniscusSource> meniscus;
  vtkNew<vtkHexahedralEmbeddingFilter> embed;
  vtkNew<vtkUnstructuredGrid> grid; // deformed, with "Displacement"
  vtkNew<vtkEmbeddedSurfaceDeformationFilter> deform;
  vtkNew<vtkWrinkleDisplacementFilter> wrinkles;
  double contact[3] = { 0.0, 0.0, 0.0 };

  WrinklePipeline()
  {
    meniscus->SetExaminationResolution();
    meniscus->SetMonitorPointSpacing(0.16);
    meniscus->Update();
    embed->SetInputConnection(meniscus->GetOutputPort(vtkMeniscusSource::VisualPort));
    embed->SetGridConnection(meniscus->GetOutputPort(vtkMeniscusSource::SimulationPort));
    grid->DeepCopy(meniscus->GetSimulationOutput());
    deform->SetInputConnection(embed->GetOutputPort());
    deform->SetGridData(grid);
    wrinkles->SetInputConnection(deform->GetOutputPort());
    wrinkles->SetMonitorPointsConnection(
      meniscus->GetOutputPort(vtkMeniscusSource::MonitorPointsPort));
    wrinkles->SetGridData(grid);
    vtkPolyData* monitors = meniscus->GetMonitorPointsOutput();
    monitors->GetPoint(monitors->GetNumberOfPoints() / 2, contact);
    wrinkles->SetLowerSurfaceContacts(5);
    wrinkles->SetInstrumentTouching(true);
    wrinkles->SetInstrumentContactPoint(contact);
  }

  /// Dents the grid by `depth` around the contact and runs one step.
  void step(double depth)
  {
    vtkDataSet* rest = meniscus->GetSimulationOutput();
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkDoubleArray> displacement;
    displacement->SetName("Displacement");
    displacement->SetNumberOfComponents(3);
    for (vtkIdType i = 0; i < rest->GetNumberOfPoints(); ++i)
    {
      double x[3];
      rest->GetPoint(i, x);
      const double r2 =
        (x[0] - contact[0]) * (x[0] - contact[0]) + (x[1] - contact[1]) * (x[1] - contact[1]);
      const double dz = -depth * std::exp(-r2 / 16.0);
      displacement->InsertNextTuple3(0.0, 0.0, dz);
      x[2] += dz;
      points->InsertNextPoint(x);
    }
    grid->SetPoints(points);
    grid->GetPointData()->AddArray(displacement);
    grid->Modified();
    wrinkles->Update();
  }
};

} // namespace

TEST(WrinkleDisplacementFilter, WrinklesAppearOnTheReleaseAndOnlyNearTheMonitorPoints)
{
  WrinklePipeline p;
  for (int k = 1; k <= 10; ++k)
  {
    p.step(0.1 * k);
    EXPECT_FALSE(p.wrinkles->GetWrinkling()) << "step " << k;
  }
  EXPECT_GT(p.wrinkles->GetNumberOfMonitorPoints(), 250);
  vtkPolyData* deformed = p.deform->GetOutput();
  vtkPolyData* output = p.wrinkles->GetOutput();
  ASSERT_EQ(output->GetNumberOfPoints(), deformed->GetNumberOfPoints());
  for (vtkIdType i = 0; i < output->GetNumberOfPoints(); i += 97)
  {
    EXPECT_EQ(output->GetPoint(i)[2], deformed->GetPoint(i)[2]);
  }
  p.step(0.9); // the reversal
  ASSERT_TRUE(p.wrinkles->GetWrinkling());
  p.step(0.8);
  ASSERT_TRUE(p.wrinkles->GetWrinkling());
  const vtkIdType displaced = p.wrinkles->GetNumberOfDisplacedPoints();
  EXPECT_GT(displaced, 20);
  EXPECT_LT(displaced, output->GetNumberOfPoints() / 4);
  vtkDataArray* wrinkle = output->GetPointData()->GetArray("WrinkleDisplacement");
  ASSERT_NE(wrinkle, nullptr);
  vtkIdType moved = 0;
  for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
  {
    double d[3], x[3], y[3];
    wrinkle->GetTuple(i, d);
    output->GetPoint(i, x);
    p.deform->GetOutput()->GetPoint(i, y);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(x[a] - y[a], d[a], 1e-12);
    }
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    moved += length > 0.0 ? 1 : 0;
    // Near the contact only (the window is 70 points of 0.16 mm).
    if (length > 0.0)
    {
      const double r = std::hypot(x[0] - p.contact[0], x[1] - p.contact[1]);
      EXPECT_LT(r, 12.0);
    }
  }
  EXPECT_GT(moved, 0);
  EXPECT_LE(moved, displaced);
  // The instrument leaves and the lower contacts end: no more wrinkles.
  p.wrinkles->SetInstrumentTouching(false);
  p.wrinkles->SetLowerSurfaceContacts(0);
  p.step(0.5);
  EXPECT_FALSE(p.wrinkles->GetWrinkling());
  EXPECT_EQ(p.wrinkles->GetNumberOfDisplacedPoints(), 0);
}

TEST(WrinkleDisplacementFilter, BadInputsAreReportedWithAnEmptyOutput)
{
  WrinklePipeline p;
  // Monitor data without its region points.
  vtkNew<vtkPolyData> bare;
  bare->DeepCopy(p.meniscus->GetMonitorPointsOutput());
  bare->GetPointData()->RemoveArray("RegionPoint");
  p.wrinkles->SetMonitorPointsData(bare);
  vtkNew<thintissue::testing::ErrorCounter> errors;
  p.wrinkles->AddObserver(vtkCommand::ErrorEvent, errors);
  p.step(0.1);
  EXPECT_NE(errors->all.find("RegionPoint"), std::string::npos) << errors->all;
  EXPECT_EQ(p.wrinkles->GetOutput()->GetNumberOfPoints(), 0);
  // A surface without its embedding.
  p.wrinkles->SetMonitorPointsConnection(
    p.meniscus->GetOutputPort(vtkMeniscusSource::MonitorPointsPort));
  p.wrinkles->SetInputConnection(p.meniscus->GetOutputPort(vtkMeniscusSource::VisualPort));
  errors->all.clear();
  p.step(0.1);
  EXPECT_NE(errors->all.find("HexahedronId"), std::string::npos) << errors->all;
  // A bad parameter.
  p.wrinkles->SetInputConnection(p.deform->GetOutputPort());
  p.wrinkles->SetWindowSize(1);
  errors->all.clear();
  p.step(0.1);
  EXPECT_NE(errors->all.find("window size"), std::string::npos) << errors->all;
  p.wrinkles->SetWindowSize(70);
  errors->all.clear();
  p.step(0.1);
  EXPECT_TRUE(errors->all.empty()) << errors->all;
  EXPECT_GT(p.wrinkles->GetOutput()->GetNumberOfPoints(), 0);
}

TEST(AutomaticMonitorPointsFilter, DerivedMonitorPointsDriveTheWrinkles)
{
  WrinklePipeline p;
  vtkNew<vtkAutomaticMonitorPointsFilter> automatic;
  automatic->SetInputConnection(p.meniscus->GetOutputPort(vtkMeniscusSource::CollisionPort));
  automatic->Update();
  vtkPolyData* data = automatic->GetOutput();
  ASSERT_GT(data->GetNumberOfPoints(), 10);
  EXPECT_EQ(data->GetNumberOfLines(), 1);
  ASSERT_NE(data->GetPointData()->GetArray("RegionPoint"), nullptr);
  ASSERT_NE(data->GetPointData()->GetArray("Thickness"), nullptr);
  // On the inner border: near the model's own monitor points.
  vtkPolyData* model = p.meniscus->GetMonitorPointsOutput();
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    double x[3];
    data->GetPoint(i, x);
    double nearest = 1e9;
    for (vtkIdType j = 0; j < model->GetNumberOfPoints(); ++j)
    {
      double y[3];
      model->GetPoint(j, y);
      nearest = std::min(nearest, std::hypot(x[0] - y[0], x[1] - y[1]));
    }
    EXPECT_LT(nearest, 1.5) << "automatic monitor data point " << i;
  }
  p.wrinkles->SetMonitorPointsConnection(automatic->GetOutputPort());
  p.wrinkles->SetMonitorPointSpacing(0.16);
  for (int k = 1; k <= 10; ++k)
  {
    p.step(0.1 * k);
  }
  p.step(0.9);
  EXPECT_TRUE(p.wrinkles->GetWrinkling());
  EXPECT_GT(p.wrinkles->GetNumberOfDisplacedPoints(), 20);
  // Without radii: reported.
  vtkNew<vtkPolyData> bare;
  bare->DeepCopy(p.meniscus->GetCollisionOutput());
  bare->GetPointData()->RemoveArray("Radius");
  automatic->SetInputData(bare);
  vtkNew<thintissue::testing::ErrorCounter> errors;
  automatic->AddObserver(vtkCommand::ErrorEvent, errors);
  automatic->Update();
  EXPECT_NE(errors->all.find("Radius"), std::string::npos) << errors->all;
  EXPECT_EQ(automatic->GetOutput()->GetNumberOfPoints(), 0);
}
