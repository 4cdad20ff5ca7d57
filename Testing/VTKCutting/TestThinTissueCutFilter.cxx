// VTK adapter of cutting on the thesis's sheet (visual model 1, collision
// model 1): a pipeline from the sheet source through the binding filter to
// the cut filter; cuts kept between updates, the cut surface marked, bad
// blades and bad tissues reported.
#include "vtkThinTissueCutFilter.h"

#include "MeshValidation.h"
#include "vtkThinSheetSource.h"
#include "vtkThinTissueConversion.h"
#include "vtkVisualCollisionBindingFilter.h"

#include "ThinTissueVtkErrorObserver.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <gtest/gtest.h>

#include <sstream>
#include <vector>

using thintissue::testing::ErrorCounter;

namespace
{

/// The sheet, bound, and a cut filter on it.
struct SheetPipeline
{
  vtkNew<vtkThinSheetSource> sheet;
  vtkNew<vtkVisualCollisionBindingFilter> binding;
  vtkNew<vtkThinTissueCutFilter> cut;

  SheetPipeline()
  {
    sheet->SetThesisVisualModel(1);
    sheet->SetThesisCollisionModel(1);
    binding->SetInputConnection(0, sheet->GetOutputPort(0));
    binding->SetCollisionConnection(sheet->GetOutputPort(1));
    cut->SetInputConnection(0, binding->GetOutputPort(0));
    cut->SetCollisionConnection(sheet->GetOutputPort(1));
    cut->SetSimulationConnection(sheet->GetOutputPort(2));
  }
};

/// A scalpel's swept quad (two triangles) across the sheet at x, from y0
/// to y1, reaching through its thickness.
vtkSmartPointer<vtkPolyData> scalpel(double x, double y0, double y1)
{
  auto blade = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(x, y0, -5.0);
  points->InsertNextPoint(x, y0, 5.0);
  points->InsertNextPoint(x, y1, 5.0);
  points->InsertNextPoint(x, y1, -5.0);
  vtkNew<vtkCellArray> triangles;
  const vtkIdType first[3] = { 0, 1, 2 }, second[3] = { 0, 2, 3 };
  triangles->InsertNextCell(3, first);
  triangles->InsertNextCell(3, second);
  blade->SetPoints(points);
  blade->SetPolys(triangles);
  return blade;
}

thintissue::MeshValidationReport validate(vtkPolyData* surface)
{
  return thintissue::validateTriangleMesh(thintissue::fromPolyData(surface, "cut output"), 0.0);
}

vtkIdType cutSurfaceTriangles(vtkPolyData* visual)
{
  vtkDataArray* material = visual->GetCellData()->GetArray("Material");
  vtkIdType count = 0;
  for (vtkIdType c = 0; material && c < material->GetNumberOfTuples(); ++c)
    count += material->GetComponent(c, 0) == 1.0 ? 1 : 0;
  return count;
}

} // namespace

TEST(vtkThinTissueCutFilter, WithoutABladeTheTissueComesOutUncut)
{
  SheetPipeline pipeline;
  pipeline.cut->Update();
  EXPECT_STREQ(pipeline.cut->GetLastErrorMessage(), "");
  EXPECT_EQ(pipeline.cut->GetNumberOfCuts(), 0);
  vtkPolyData* visual = pipeline.cut->GetVisualOutput();
  EXPECT_EQ(visual->GetNumberOfCells(),
    vtkPolyData::SafeDownCast(pipeline.binding->GetOutputDataObject(0))->GetNumberOfCells());
  EXPECT_EQ(cutSurfaceTriangles(visual), 0);
  EXPECT_EQ(pipeline.cut->GetSimulationOutput()->GetNumberOfCells(),
    pipeline.sheet->GetSimulationOutput()->GetNumberOfCells());
}

TEST(vtkThinTissueCutFilter, ACutThroughGivesTwoClosedPiecesAndKeepsTheCut)
{
  SheetPipeline pipeline;
  pipeline.cut->SetBladeData(scalpel(3.0, -80.0, 80.0));
  pipeline.cut->Update();
  ASSERT_STREQ(pipeline.cut->GetLastErrorMessage(), "");
  EXPECT_EQ(pipeline.cut->GetNumberOfCuts(), 1);
  EXPECT_TRUE(pipeline.cut->GetLastCutChangedTissue());
  vtkPolyData* visual = pipeline.cut->GetVisualOutput();
  const auto report = validate(visual);
  EXPECT_EQ(report.borderEdges.count, 0u) << report.toString();
  EXPECT_EQ(report.nonManifoldEdges.count, 0u) << report.toString();
  EXPECT_EQ(report.inconsistentlyOrientedEdges.count, 0u) << report.toString();
  EXPECT_EQ(report.connectedComponents, 2u);
  EXPECT_GT(cutSurfaceTriangles(visual), 0);
  for (const char* name : { "BindingKind", "BindingElement", "BindingSide", "BindingParameters" })
    EXPECT_NE(visual->GetPointData()->GetArray(name), nullptr) << name;
  EXPECT_EQ(validate(pipeline.cut->GetCollisionOutput()).connectedComponents, 2u);
  EXPECT_GT(pipeline.cut->GetSimulationOutput()->GetNumberOfCells(),
    pipeline.sheet->GetSimulationOutput()->GetNumberOfCells());

  // Updating again without a new blade changes nothing; a new blade cuts
  // the cut tissue again.
  const vtkIdType cells = visual->GetNumberOfCells();
  pipeline.cut->Modified();
  pipeline.cut->Update();
  EXPECT_EQ(pipeline.cut->GetNumberOfCuts(), 1);
  EXPECT_EQ(pipeline.cut->GetVisualOutput()->GetNumberOfCells(), cells);
  pipeline.cut->SetBladeData(scalpel(-20.0, -80.0, 80.0));
  pipeline.cut->Update();
  EXPECT_EQ(pipeline.cut->GetNumberOfCuts(), 2);
  EXPECT_EQ(validate(pipeline.cut->GetVisualOutput()).connectedComponents, 3u);

  // ResetTissue forgets the cuts.
  pipeline.cut->ResetTissue();
  pipeline.cut->SetBladeData(scalpel(-20.0, -80.0, 80.0));
  pipeline.cut->Update();
  EXPECT_EQ(pipeline.cut->GetNumberOfCuts(), 1);
  EXPECT_EQ(validate(pipeline.cut->GetVisualOutput()).connectedComponents, 2u);
}

TEST(vtkThinTissueCutFilter, MoreRowsMakeAFinerCutSurface)
{
  vtkIdType previous = 0;
  for (int rows : { 0, 2 })
  {
    SheetPipeline pipeline;
    pipeline.cut->SetCutSurfaceRows(rows);
    pipeline.cut->SetBladeData(scalpel(3.0, -80.0, 80.0));
    pipeline.cut->Update();
    const vtkIdType count = cutSurfaceTriangles(pipeline.cut->GetVisualOutput());
    EXPECT_GT(count, previous) << rows << " rows";
    previous = count;
  }
}

TEST(vtkThinTissueCutFilter, ADegenerateBladeIsReportedAndCutsNothing)
{
  SheetPipeline pipeline;
  pipeline.cut->SetBladeData(scalpel(3.0, -80.0, 0.0));
  pipeline.cut->Update();
  const vtkIdType cells = pipeline.cut->GetVisualOutput()->GetNumberOfCells();
  vtkNew<ErrorCounter> errors;
  pipeline.cut->AddObserver(vtkCommand::ErrorEvent, errors);
  pipeline.cut->SetBladeData(scalpel(10.0, 5.0, 5.0)); // no length
  pipeline.cut->Update();
  EXPECT_EQ(errors->count, 1);
  EXPECT_NE(std::string(pipeline.cut->GetLastErrorMessage()).find("degenerate"), std::string::npos)
    << pipeline.cut->GetLastErrorMessage();
  EXPECT_EQ(pipeline.cut->GetNumberOfCuts(), 1);
  EXPECT_EQ(pipeline.cut->GetVisualOutput()->GetNumberOfCells(), cells);
}

TEST(vtkThinTissueCutFilter, AnUnboundSurfaceIsReported)
{
  SheetPipeline pipeline;
  pipeline.cut->SetInputConnection(0, pipeline.sheet->GetOutputPort(0)); // no binding arrays
  vtkNew<ErrorCounter> errors;
  pipeline.cut->AddObserver(vtkCommand::ErrorEvent, errors);
  pipeline.cut->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  pipeline.cut->Update();
  EXPECT_GE(errors->count, 1);
  EXPECT_NE(std::string(pipeline.cut->GetLastErrorMessage()).find("BindingKind"), std::string::npos)
    << pipeline.cut->GetLastErrorMessage();
  EXPECT_EQ(pipeline.cut->GetVisualOutput()->GetNumberOfCells(), 0);
}

TEST(vtkThinTissueCutFilter, PrintSelfNamesTheSettings)
{
  vtkNew<vtkThinTissueCutFilter> cut;
  std::ostringstream text;
  cut->Print(text);
  EXPECT_NE(text.str().find("CutSurfaceRows: 1"), std::string::npos);
  EXPECT_NE(text.str().find("SnapFraction: 0.15"), std::string::npos);
}

TEST(vtkThinTissueCutFilter, ADroppedPieceLeavesTheOutputs)
{
  // Two cuts across the sheet free its middle strip from both attached
  // edges; dropped, the outputs keep the two attached halves.
  for (int drop : { 0, 1 })
  {
    SheetPipeline pipeline;
    pipeline.cut->SetFreePieces(drop);
    pipeline.cut->SetBladeData(scalpel(-12.0, -80.0, 80.0));
    pipeline.cut->Update();
    pipeline.cut->SetBladeData(scalpel(14.0, -80.0, 80.0));
    pipeline.cut->Update();
    ASSERT_STREQ(pipeline.cut->GetLastErrorMessage(), "");
    const auto visual = validate(pipeline.cut->GetVisualOutput());
    EXPECT_EQ(visual.connectedComponents, drop ? 2u : 3u);
    EXPECT_EQ(visual.borderEdges.count, 0u) << visual.toString();
    EXPECT_EQ(validate(pipeline.cut->GetCollisionOutput()).connectedComponents, drop ? 2u : 3u);
  }
}

TEST(vtkThinTissueCutFilter, ReportsProgress)
{
  SheetPipeline pipeline;
  pipeline.binding->Update();
  std::vector<double> fractions;
  vtkNew<vtkCallbackCommand> progress;
  progress->SetClientData(&fractions);
  progress->SetCallback(
    [](vtkObject* caller, unsigned long, void* data, void*)
    {
      static_cast<std::vector<double>*>(data)->push_back(
        static_cast<vtkAlgorithm*>(caller)->GetProgress());
    });
  pipeline.cut->AddObserver(vtkCommand::ProgressEvent, progress);
  pipeline.cut->SetBladeData(scalpel(3.0, -80.0, 80.0));
  pipeline.cut->Update();
  ASSERT_GE(fractions.size(), 2u);
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
}
