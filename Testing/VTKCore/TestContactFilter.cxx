// vtkThickSurfaceContactFilter: contacts between two surfaces with radii.
#include "vtkThickSurfaceContactFilter.h"
#include "vtkThinSlabSource.h"

#include "ThinTissueVtkErrorObserver.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>

#include <gtest/gtest.h>

#include <sstream>

namespace
{
vtkSmartPointer<vtkPolyData> plane(double z, int resolution, double radius)
{
  vtkNew<vtkPlaneSource> source;
  source->SetOrigin(0.0, 0.0, z);
  source->SetPoint1(1.0, 0.0, z);
  source->SetPoint2(0.0, 1.0, z);
  source->SetResolution(resolution, resolution);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(source->GetOutputPort());
  triangles->Update();
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->DeepCopy(triangles->GetOutput());
  output->GetPointData()->SetNormals(nullptr);
  output->GetPointData()->SetTCoords(nullptr);
  vtkNew<vtkDoubleArray> radii;
  radii->SetName("Radius");
  radii->SetNumberOfTuples(output->GetNumberOfPoints());
  radii->FillComponent(0, radius);
  output->GetPointData()->AddArray(radii);
  return output;
}
} // namespace

TEST(vtkThickSurfaceContactFilter, ReportsContactsWithNormalsDepthsAndSides)
{
  vtkNew<vtkThickSurfaceContactFilter> filter;
  filter->SetInputData(0, plane(0.15, 4, 0.1));
  filter->SetInputData(1, plane(0.0, 5, 0.1));
  filter->Update();
  vtkPolyData* contacts = filter->GetOutput();
  EXPECT_EQ(filter->GetNumberOfContacts(), 25 + 36);
  ASSERT_EQ(contacts->GetNumberOfVerts(), 25 + 36);
  vtkDataArray* depth = contacts->GetPointData()->GetArray("Depth");
  vtkDataArray* normal = contacts->GetPointData()->GetArray("Normal");
  vtkDataArray* side = contacts->GetPointData()->GetArray("Side");
  ASSERT_TRUE(depth && normal && side && contacts->GetPointData()->GetArray("VertexOfA"));
  EXPECT_NEAR(depth->GetRange()[0], 0.05, 1e-6); // float points
  EXPECT_NEAR(depth->GetRange()[1], 0.05, 1e-6);
  EXPECT_NEAR(normal->GetTuple3(0)[2], 1.0, 1e-9);

  // Moved apart: no contact.
  filter->SetInputData(0, plane(1.0, 4, 0.1));
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfContacts(), 0);
  std::ostringstream print;
  filter->Print(print);
  EXPECT_NE(print.str().find("ContactDistance"), std::string::npos);
}

TEST(vtkThickSurfaceContactFilter, BadRadiiAreReported)
{
  vtkNew<vtkThickSurfaceContactFilter> filter;
  vtkNew<thintissue::testing::ErrorCounter> errors;
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->SetInputData(0, plane(0.0, 2, -0.5));
  filter->SetInputData(1, plane(0.1, 2, 0.1));
  filter->Update();
  EXPECT_NE(errors->all.find("negative radius"), std::string::npos) << errors->all;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
}
