// VTK adapter of the visual-collision binding on the thesis's sheet (visual
// model 1, collision model 1): the binding arrays of the re-meshed visual
// surface, the paths output, errors, progress and abort, the binding cache
// and PrintSelf.
#include "vtkVisualCollisionBindingFilter.h"

#include "MeniscusModel.h"
#include "ThinSheetModel.h"
#include "VisualCollisionBinding.h"
#include "vtkBindingConversion.h"
#include "vtkThinSheetSource.h"
#include "vtkThinTissueConversion.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkCellLocator.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSignedCharArray.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include "ThinTissueTestSupport.h"
#include "ThinTissueVtkErrorObserver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
using thintissue::testing::ErrorCounter;

/// The sheet's visual (port 0) and collision (port 1) meshes, made once.
vtkThinSheetSource* sheetSource()
{
  static vtkSmartPointer<vtkThinSheetSource> source = []
  {
    auto s = vtkSmartPointer<vtkThinSheetSource>::New();
    s->SetThesisVisualModel(1);
    s->SetThesisCollisionModel(1);
    s->Update();
    return s;
  }();
  return source;
}

vtkPolyData* sheetVisual()
{
  return sheetSource()->GetVisualOutput();
}

vtkPolyData* sheetCollision()
{
  return sheetSource()->GetCollisionOutput();
}

vtkSmartPointer<vtkVisualCollisionBindingFilter> makeFilter(vtkPolyData* visual,
  vtkPolyData* collision)
{
  auto filter = vtkSmartPointer<vtkVisualCollisionBindingFilter>::New();
  filter->SetInputData(0, visual);
  filter->SetCollisionData(collision);
  return filter;
}

/// The sheet bound once (the binding takes a moment).
vtkVisualCollisionBindingFilter* sheetBinding()
{
  static vtkSmartPointer<vtkVisualCollisionBindingFilter> filter = []
  {
    auto f = makeFilter(sheetVisual(), sheetCollision());
    f->Update();
    return f;
  }();
  return filter;
}

/// Collision edges (lower, higher) -> number of triangles.
std::map<std::pair<vtkIdType, vtkIdType>, int> collisionEdges(vtkPolyData* collision)
{
  std::map<std::pair<vtkIdType, vtkIdType>, int> edges;
  auto cells = vtk::TakeSmartPointer(collision->GetPolys()->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    cells->GetCurrentCell(size, ids);
    for (vtkIdType k = 0; k < size; ++k)
    {
      const vtkIdType a = ids[k];
      const vtkIdType b = ids[(k + 1) % size];
      ++edges[{ std::min(a, b), std::max(a, b) }];
    }
  }
  return edges;
}

void expectEmptyOutputs(vtkVisualCollisionBindingFilter* filter)
{
  EXPECT_EQ(filter->GetVisualOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(filter->GetVisualOutput()->GetNumberOfCells(), 0);
  EXPECT_EQ(filter->GetPathsOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(filter->GetPathsOutput()->GetNumberOfCells(), 0);
}

/// Sets AbortExecute once progress reaches `at`; records the stages seen.
class AbortAt : public vtkCommand
{
public:
  static AbortAt* New() { return new AbortAt; }
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    auto* algorithm = static_cast<vtkAlgorithm*>(caller);
    const double progress = *static_cast<double*>(data);
    if (algorithm->GetProgressText() != nullptr)
    {
      stages.insert(algorithm->GetProgressText());
    }
    if (progress >= at && progress < 1.0)
    {
      algorithm->SetAbortExecute(1);
      ++aborts;
    }
  }
  double at = 2.0;
  int aborts = 0;
  std::set<std::string> stages;
};

/// Records every progress value and text.
class ProgressRecorder : public vtkCommand
{
public:
  static ProgressRecorder* New() { return new ProgressRecorder; }
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    auto* algorithm = static_cast<vtkAlgorithm*>(caller);
    values.push_back(*static_cast<double*>(data));
    const char* text = algorithm->GetProgressText();
    if (text != nullptr && (stages.empty() || stages.back() != text))
    {
      stages.emplace_back(text);
    }
  }
  std::vector<double> values;
  std::vector<std::string> stages;
};

void expectSameArray(vtkDataArray* a, vtkDataArray* b)
{
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples()) << a->GetName();
  ASSERT_EQ(a->GetNumberOfComponents(), b->GetNumberOfComponents()) << a->GetName();
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      ASSERT_EQ(a->GetComponent(i, c), b->GetComponent(i, c)) << a->GetName() << " tuple " << i;
    }
  }
}

} // namespace

TEST(VisualCollisionBindingFilter, ArraysCoverEveryPointAndCell)
{
  vtkVisualCollisionBindingFilter* filter = sheetBinding();
  ASSERT_STREQ(filter->GetLastErrorMessage(), "");
  vtkPolyData* output = filter->GetVisualOutput();
  const vtkIdType points = output->GetNumberOfPoints();
  const vtkIdType cells = output->GetNumberOfCells();
  // Re-meshed: the input's vertices plus the path points inside edges.
  EXPECT_GE(points, sheetVisual()->GetNumberOfPoints());
  EXPECT_GE(cells, sheetVisual()->GetNumberOfCells());
  EXPECT_EQ(cells, output->GetNumberOfPolys());

  auto* kinds = vtkUnsignedCharArray::SafeDownCast(output->GetPointData()->GetArray("BindingKind"));
  auto* elements = vtkIntArray::SafeDownCast(output->GetPointData()->GetArray("BindingElement"));
  auto* sides = vtkSignedCharArray::SafeDownCast(output->GetPointData()->GetArray("BindingSide"));
  auto* parameters =
    vtkDoubleArray::SafeDownCast(output->GetPointData()->GetArray("BindingParameters"));
  auto* regions = vtkIntArray::SafeDownCast(output->GetCellData()->GetArray("CollisionTriangle"));
  auto* regionSides =
    vtkSignedCharArray::SafeDownCast(output->GetCellData()->GetArray("CollisionSide"));
  ASSERT_NE(kinds, nullptr);
  ASSERT_NE(elements, nullptr);
  ASSERT_NE(sides, nullptr);
  ASSERT_NE(parameters, nullptr);
  ASSERT_NE(regions, nullptr);
  ASSERT_NE(regionSides, nullptr);
  EXPECT_EQ(kinds->GetNumberOfTuples(), points);
  EXPECT_EQ(elements->GetNumberOfTuples(), points);
  EXPECT_EQ(sides->GetNumberOfTuples(), points);
  EXPECT_EQ(parameters->GetNumberOfTuples(), points);
  EXPECT_EQ(parameters->GetNumberOfComponents(), 3);
  EXPECT_EQ(regions->GetNumberOfTuples(), cells);
  EXPECT_EQ(regionSides->GetNumberOfTuples(), cells);

  // What the conversion carries: normals, texture coordinates per corner.
  EXPECT_NE(output->GetPointData()->GetNormals(), nullptr);
  vtkDataArray* corners =
    output->GetCellData()->GetArray(thintissue::CornerTextureCoordinatesArrayName);
  ASSERT_NE(corners, nullptr);
  EXPECT_EQ(corners->GetNumberOfTuples(), cells);

  const vtkIdType collisionPoints = sheetCollision()->GetNumberOfPoints();
  const vtkIdType collisionTriangles = sheetCollision()->GetNumberOfPolys();
  const auto edgeCount = static_cast<vtkIdType>(collisionEdges(sheetCollision()).size());
  std::set<int> kindsSeen;
  for (vtkIdType v = 0; v < points; ++v)
  {
    const int kind = kinds->GetValue(v);
    kindsSeen.insert(kind);
    ASSERT_LE(kind, 2) << "vertex " << v;
    const vtkIdType limit = kind == 0   ? collisionPoints
                            : kind == 1 ? edgeCount
                                        : collisionTriangles;
    ASSERT_GE(elements->GetValue(v), 0) << "vertex " << v;
    ASSERT_LT(elements->GetValue(v), limit) << "vertex " << v;
    ASSERT_GE(sides->GetValue(v), -1);
    ASSERT_LE(sides->GetValue(v), 1);
  }
  EXPECT_EQ(kindsSeen, (std::set<int>{ 0, 1, 2 }));

  // Every visual triangle lies in a region; every collision triangle has a
  // region on each side.
  std::set<std::pair<int, int>> regionsSeen;
  for (vtkIdType t = 0; t < cells; ++t)
  {
    const int region = regions->GetValue(t);
    const int side = regionSides->GetValue(t);
    ASSERT_GE(region, 0) << "cell " << t;
    ASSERT_LT(region, collisionTriangles) << "cell " << t;
    ASSERT_TRUE(side == 1 || side == -1) << "cell " << t << " side " << side;
    regionsSeen.insert({ region, side });
  }
  EXPECT_EQ(static_cast<vtkIdType>(regionsSeen.size()), 2 * collisionTriangles);
}

TEST(VisualCollisionBindingFilter, BindingParametersSumToOne)
{
  vtkPolyData* output = sheetBinding()->GetVisualOutput();
  vtkDataArray* parameters = output->GetPointData()->GetArray("BindingParameters");
  vtkDataArray* kinds = output->GetPointData()->GetArray("BindingKind");
  ASSERT_NE(parameters, nullptr);
  ASSERT_GT(parameters->GetNumberOfTuples(), 0);
  for (vtkIdType v = 0; v < parameters->GetNumberOfTuples(); ++v)
  {
    double p[3];
    parameters->GetTuple(v, p);
    ASSERT_NEAR(p[0] + p[1] + p[2], 1.0, 1e-9) << "vertex " << v;
    for (const double value : p)
    {
      ASSERT_GE(value, -1e-9) << "vertex " << v;
      ASSERT_LE(value, 1.0 + 1e-9) << "vertex " << v;
    }
    const int kind = static_cast<int>(kinds->GetComponent(v, 0));
    if (kind == 0)
    {
      EXPECT_EQ(p[0], 1.0) << "vertex " << v;
    }
    if (kind <= 1)
    {
      EXPECT_EQ(p[2], 0.0) << "vertex " << v;
    }
  }
}

TEST(VisualCollisionBindingFilter, PathsArePolylinesOnTheVisualSurface)
{
  vtkVisualCollisionBindingFilter* filter = sheetBinding();
  vtkPolyData* visual = filter->GetVisualOutput();
  vtkPolyData* paths = filter->GetPathsOutput();

  // One path per inner collision edge and side, one per border edge.
  int expected = 0;
  for (const auto& edge : collisionEdges(sheetCollision()))
  {
    expected += edge.second == 1 ? 1 : 2;
  }
  EXPECT_EQ(paths->GetNumberOfCells(), expected);
  EXPECT_EQ(paths->GetNumberOfLines(), expected);
  EXPECT_EQ(paths->GetNumberOfPolys(), 0);
  EXPECT_EQ(paths->GetNumberOfVerts(), 0);

  vtkDataArray* edges = paths->GetCellData()->GetArray("CollisionEdge");
  vtkDataArray* sides = paths->GetCellData()->GetArray("Side");
  vtkDataArray* lengths = paths->GetCellData()->GetArray("Length");
  vtkDataArray* visualVertices = paths->GetPointData()->GetArray("VisualVertex");
  ASSERT_NE(edges, nullptr);
  ASSERT_NE(sides, nullptr);
  ASSERT_NE(lengths, nullptr);
  ASSERT_NE(visualVertices, nullptr);
  EXPECT_EQ(edges->GetNumberOfTuples(), expected);
  EXPECT_EQ(sides->GetNumberOfTuples(), expected);
  EXPECT_EQ(lengths->GetNumberOfTuples(), expected);
  EXPECT_EQ(visualVertices->GetNumberOfTuples(), paths->GetNumberOfPoints());

  // Every point is a vertex of the re-meshed visual surface.
  vtkNew<vtkCellLocator> locator;
  locator->SetDataSet(visual);
  locator->BuildLocator();
  const double scale = visual->GetLength();
  vtkDataArray* kinds = visual->GetPointData()->GetArray("BindingKind");
  for (vtkIdType i = 0; i < paths->GetNumberOfPoints(); ++i)
  {
    double point[3];
    paths->GetPoint(i, point);
    const auto v = static_cast<vtkIdType>(visualVertices->GetComponent(i, 0));
    ASSERT_GE(v, 0);
    ASSERT_LT(v, visual->GetNumberOfPoints());
    double vertex[3];
    visual->GetPoint(v, vertex);
    ASSERT_EQ(vtkMath::Distance2BetweenPoints(point, vertex), 0.0) << "path point " << i;
    double closest[3];
    vtkIdType cell = -1;
    int subId = 0;
    double distance2 = 0.0;
    locator->FindClosestPoint(point, closest, cell, subId, distance2);
    ASSERT_LT(std::sqrt(distance2), 1e-9 * scale) << "path point " << i;
    // A path point is bound to the edge's vertices or to the edge itself.
    ASSERT_LE(kinds->GetComponent(v, 0), 1.0) << "path point " << i;
  }

  // Each polyline: at least two points, ends at collision-vertex bindings,
  // as long as its straight segments.
  std::map<std::pair<int, int>, int> pathsPerEdgeAndSide;
  vtkIdType cellId = 0;
  auto lines = vtk::TakeSmartPointer(paths->GetLines()->NewIterator());
  for (lines->GoToFirstCell(); !lines->IsDoneWithTraversal(); lines->GoToNextCell(), ++cellId)
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    lines->GetCurrentCell(size, ids);
    ASSERT_GE(size, 2) << "path " << cellId;
    for (const vtkIdType end : { ids[0], ids[size - 1] })
    {
      const auto v = static_cast<vtkIdType>(visualVertices->GetComponent(end, 0));
      EXPECT_EQ(kinds->GetComponent(v, 0), 0.0) << "path " << cellId;
    }
    double length = 0.0;
    for (vtkIdType k = 0; k + 1 < size; ++k)
    {
      double a[3];
      double b[3];
      paths->GetPoint(ids[k], a);
      paths->GetPoint(ids[k + 1], b);
      length += std::sqrt(vtkMath::Distance2BetweenPoints(a, b));
    }
    EXPECT_NEAR(length, lengths->GetComponent(cellId, 0), 1e-9 * scale) << "path " << cellId;
    const int side = static_cast<int>(sides->GetComponent(cellId, 0));
    ASSERT_TRUE(side >= -1 && side <= 1);
    ++pathsPerEdgeAndSide[{ static_cast<int>(edges->GetComponent(cellId, 0)), side }];
  }
  EXPECT_EQ(static_cast<int>(pathsPerEdgeAndSide.size()), expected);
}

TEST(VisualCollisionBindingFilter, CollisionWithoutRadiusIsAnError)
{
  vtkNew<vtkPolyData> collision;
  collision->DeepCopy(sheetCollision());
  collision->GetPointData()->RemoveArray("Radius");
  auto filter = makeFilter(sheetVisual(), collision);
  vtkNew<ErrorCounter> errors;
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->GlobalWarningDisplayOn();
  filter->Update();
  EXPECT_GE(errors->count, 1);
  EXPECT_NE(errors->all.find("'Radius'"), std::string::npos) << errors->all;
  EXPECT_NE(std::string(filter->GetLastErrorMessage()).find("'Radius'"), std::string::npos)
    << filter->GetLastErrorMessage();
  expectEmptyOutputs(filter);

  // Another radius array name is used when set.
  vtkNew<vtkDoubleArray> thickness;
  thickness->DeepCopy(sheetCollision()->GetPointData()->GetArray("Radius"));
  thickness->SetName("Thickness");
  collision->GetPointData()->AddArray(thickness);
  filter->SetRadiusArrayName("Thickness");
  filter->Update();
  EXPECT_STREQ(filter->GetLastErrorMessage(), "");
  EXPECT_EQ(filter->GetVisualOutput()->GetNumberOfPoints(),
    sheetBinding()->GetVisualOutput()->GetNumberOfPoints());
}

TEST(VisualCollisionBindingFilter, OpenVisualMeshIsAnError)
{
  thintissue::TissueModel sheet = thintissue::makeThinSheet(
    thintissue::thesisSheetCollisionResolution(1, thintissue::thesisSheetVisualResolution(1)));
  sheet.visual.triangles.erase(sheet.visual.triangles.begin());
  if (sheet.visual.hasTextureCoordinates())
  {
    sheet.visual.textureCorners.erase(sheet.visual.textureCorners.begin());
  }
  auto filter =
    makeFilter(thintissue::toPolyData(sheet.visual), thintissue::toPolyData(sheet.collision));
  vtkNew<ErrorCounter> errors;
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->GlobalWarningDisplayOn();
  filter->Update();
  EXPECT_GE(errors->count, 1);
  EXPECT_NE(errors->all.find("open"), std::string::npos) << errors->all;
  EXPECT_NE(errors->all.find("visual input"), std::string::npos) << errors->all;
  expectEmptyOutputs(filter);
}

TEST(VisualCollisionBindingFilter, ReportsProgressByStage)
{
  auto filter = makeFilter(sheetVisual(), sheetCollision());
  filter->ParallelOff();
  vtkNew<ProgressRecorder> recorder;
  filter->AddObserver(vtkCommand::ProgressEvent, recorder);
  filter->Update();
  ASSERT_STREQ(filter->GetLastErrorMessage(), "");
  ASSERT_GE(recorder->values.size(), 4U);
  for (std::size_t i = 1; i < recorder->values.size(); ++i)
  {
    EXPECT_GE(recorder->values[i], recorder->values[i - 1]) << "progress event " << i;
  }
  EXPECT_EQ(recorder->values.back(), 1.0);
  const std::set<std::string> stages(recorder->stages.begin(), recorder->stages.end());
  EXPECT_EQ(stages.count("computing geodesic paths"), 1U);
  EXPECT_GE(stages.size(), 3U);

  // Serial and parallel give the same binding.
  expectSameArray(filter->GetVisualOutput()->GetPoints()->GetData(),
    sheetBinding()->GetVisualOutput()->GetPoints()->GetData());
  expectSameArray(filter->GetVisualOutput()->GetPointData()->GetArray("BindingParameters"),
    sheetBinding()->GetVisualOutput()->GetPointData()->GetArray("BindingParameters"));
}

TEST(VisualCollisionBindingFilter, AbortLeavesEmptyOutputs)
{
  auto filter = makeFilter(sheetVisual(), sheetCollision());
  vtkNew<AbortAt> abort;
  abort->at = 0.1; // while computing the geodesic paths
  filter->AddObserver(vtkCommand::ProgressEvent, abort);
  vtkNew<ErrorCounter> warnings;
  filter->AddObserver(vtkCommand::WarningEvent, warnings);
  filter->GlobalWarningDisplayOn();
  filter->Update();
  EXPECT_GE(abort->aborts, 1);
  EXPECT_NE(std::string(filter->GetLastErrorMessage()).find("aborted"), std::string::npos)
    << filter->GetLastErrorMessage();
  EXPECT_NE(warnings->all.find("aborted"), std::string::npos) << warnings->all;
  EXPECT_EQ(abort->stages.count("checking the meshes"), 1U);
  expectEmptyOutputs(filter);

  // Without the observer's abort, the next run completes.
  abort->at = 2.0;
  filter->Modified();
  filter->Update();
  EXPECT_STREQ(filter->GetLastErrorMessage(), "");
  EXPECT_EQ(filter->GetVisualOutput()->GetNumberOfPoints(),
    sheetBinding()->GetVisualOutput()->GetNumberOfPoints());
}

TEST(VisualCollisionBindingFilter, CacheFileIsWrittenThenLoaded)
{
  const std::filesystem::path cache =
    thintissue::testing::temporaryDirectory() / "vtk-binding-filter-sheet.ttbind";
  std::filesystem::remove(cache);

  auto first = makeFilter(sheetVisual(), sheetCollision());
  first->SetCacheFileName(cache.string().c_str());
  first->Update();
  ASSERT_STREQ(first->GetLastErrorMessage(), "");
  EXPECT_TRUE(first->GetCacheWasRebuilt());
  EXPECT_STRNE(first->GetLastCacheMessage(), "");
  EXPECT_TRUE(std::filesystem::exists(cache));

  auto second = makeFilter(sheetVisual(), sheetCollision());
  second->SetCacheFileName(cache.string().c_str());
  second->Update();
  ASSERT_STREQ(second->GetLastErrorMessage(), "");
  EXPECT_FALSE(second->GetCacheWasRebuilt()) << second->GetLastCacheMessage();
  EXPECT_NE(std::string(second->GetLastCacheMessage()).find("loaded"), std::string::npos)
    << second->GetLastCacheMessage();

  vtkPolyData* a = first->GetVisualOutput();
  vtkPolyData* b = second->GetVisualOutput();
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
  ASSERT_EQ(a->GetNumberOfCells(), b->GetNumberOfCells());
  expectSameArray(a->GetPoints()->GetData(), b->GetPoints()->GetData());
  for (const char* name : { "BindingKind", "BindingElement", "BindingSide", "BindingParameters" })
  {
    expectSameArray(a->GetPointData()->GetArray(name), b->GetPointData()->GetArray(name));
  }
  for (const char* name : { "CollisionTriangle", "CollisionSide" })
  {
    expectSameArray(a->GetCellData()->GetArray(name), b->GetCellData()->GetArray(name));
  }
  expectSameArray(a->GetPolys()->GetConnectivityArray(), b->GetPolys()->GetConnectivityArray());
  vtkPolyData* pathsA = first->GetPathsOutput();
  vtkPolyData* pathsB = second->GetPathsOutput();
  expectSameArray(pathsA->GetPoints()->GetData(), pathsB->GetPoints()->GetData());
  expectSameArray(
    pathsA->GetLines()->GetConnectivityArray(), pathsB->GetLines()->GetConnectivityArray());
  expectSameArray(pathsA->GetCellData()->GetArray("CollisionEdge"),
    pathsB->GetCellData()->GetArray("CollisionEdge"));
  // And the same as without a cache.
  expectSameArray(a->GetPointData()->GetArray("BindingParameters"),
    sheetBinding()->GetVisualOutput()->GetPointData()->GetArray("BindingParameters"));

  // Other settings make the file stale: rebuilt.
  second->SetThinnessFactor(5.0);
  second->Update();
  ASSERT_STREQ(second->GetLastErrorMessage(), "");
  EXPECT_TRUE(second->GetCacheWasRebuilt());
  std::filesystem::remove(cache);
}

TEST(VisualCollisionBindingFilter, PrintSelfNamesSettings)
{
  vtkNew<vtkVisualCollisionBindingFilter> filter;
  EXPECT_STREQ(filter->GetRadiusArrayName(), "Radius");
  EXPECT_TRUE(filter->GetParallel());
  EXPECT_EQ(filter->GetCacheFileName(), nullptr);
  filter->SetCacheFileName("sheet.ttbind");
  std::ostringstream text;
  filter->Print(text);
  EXPECT_NE(text.str().find("RadiusArrayName: Radius"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("ThinnessFactor: 4"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("InsideTolerance: 0.001"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("CacheFileName: sheet.ttbind"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("Parallel: On"), std::string::npos) << text.str();
}

// The binding arrays carry a horizontal cleavage's binding: its crease
// vertices (bound to their junction vertex with side 0) and the three paths
// of each junction edge come back from the arrays as they were made.
TEST(VisualCollisionBindingFilter, AHorizontalCleavageBindingRoundTripsThroughTheArrays)
{
  using namespace thintissue;
  MeniscusParameters parameters;
  parameters.tear = defaultMeniscusTear(MeniscusTearType::HorizontalCleavage);
  const MeniscusModel cleaved = makeMeniscus(parameters);
  const VisualCollisionBinding made = bindVisualToCollision(cleaved.visual, cleaved.collision);
  const VisualCollisionBinding read =
    bindingFromPolyData(boundVisualPolyData(made), toPolyData(cleaved.collision));
  EXPECT_EQ(read.pairedVisualVertices, made.pairedVisualVertices);
  EXPECT_EQ(read.creaseVisualVertices, made.creaseVisualVertices);
  EXPECT_TRUE(read.collisionSides.hasJunctions());
  ASSERT_EQ(read.paths.size(), made.paths.size());
  std::map<std::pair<int, int>, std::vector<int>> madePaths;
  for (const BindingPath& path : made.paths)
    madePaths[{ path.collisionEdge, path.side }] = path.visualVertices;
  for (const BindingPath& path : read.paths)
    EXPECT_EQ(path.visualVertices, (madePaths[{ path.collisionEdge, path.side }]))
      << "path of collision edge " << path.collisionEdge << " side " << path.side;
}
