// A tissue cut consistently across its collision and simulation meshes
// (thesis 5.3.1): hexahedron duplication by branch analysis, the solver
// following the cut, separation, and random blade sweeps with the
// invariants checked after every cut.
#include "CorotationalHexFem.h"
#include "CuttingInvariants.h"
#include "MeniscusModel.h"
#include "MeshImport.h"
#include "MeshValidation.h"
#include "RandomSweeps.h"
#include "SoftTissueMaterial.h"
#include "ThinSheetModel.h"
#include "ThinTissueError.h"
#include "ThinTissueTestSupport.h"
#include "TissueBundle.h"
#include "TissueCutter.h"
#include "TriangleMeshAdjacency.h"
#include "VisualCollisionBinding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <random>

using namespace thintissue;
using thintissue::test::softTissue;
using namespace thintissue::cutting_test;

namespace
{

CorotationalHexFemSettings smallSteps()
{
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.01;
  return settings;
}

/// A vertical scalpel at x = `x` swept along y from y0 to y1.
Blade scalpelAlongY(double x, double y0, double y1)
{
  return Blade::sweptSegment(
    Vector3(x, y0, -10), Vector3(x, y0, 10), Vector3(x, y1, -10), Vector3(x, y1, 10));
}

/// Largest displacement of the nodes used by hexahedra holding collision
/// triangles of the given side of x = 0.3.
double largestDisplacement(const CorotationalHexFem& fem, const TissueCutter& cutter, bool left)
{
  double largest = 0.0;
  const auto& mesh = cutter.simulation();
  for (std::size_t h = 0; h < mesh.hexahedronCount(); ++h)
  {
    for (int t : cutter.branches().trianglesOf(static_cast<int>(h)))
    {
      const Triangle& tri = cutter.collision().triangles()[t];
      const Vector3 centre =
        (cutter.collision().restPositions()[tri[0]] + cutter.collision().restPositions()[tri[1]] +
          cutter.collision().restPositions()[tri[2]]) /
        3.0;
      if ((centre.x() < 0.3) != left)
        continue;
      for (int node : mesh.hexahedra[h])
        largest = std::max(largest, (fem.positions()[node] - fem.restPositions()[node]).norm());
    }
  }
  return largest;
}

/// Pulls the nodes left of x = -20 up for `steps` steps.
void pullLeftHalfUp(CorotationalHexFem& fem, int steps)
{
  for (std::size_t n = 0; n < fem.nodeCount(); ++n)
    if (fem.restPositions()[n].x() < -20.0 && !fem.isFixed(n))
      fem.setExternalForce(n, Vector3(0, 0, 1e-4));
  for (int s = 0; s < steps; ++s)
    ASSERT_TRUE(fem.step().ok);
}

} // namespace

TEST(TissueCutter, ASheetCutInTwoSeparates)
{
  const TissueModel sheet = makeThinSheet(ThinSheetParameters{});
  // Control: uncut, pulling the left half moves the right one.
  {
    CorotationalHexFem fem(sheet.simulation, softTissue(), smallSteps());
    TissueCutter cutter(sheet.collision, sheet.simulation, &fem);
    pullLeftHalfUp(fem, 20);
    EXPECT_GT(largestDisplacement(fem, cutter, false), 1e-3);
  }
  CorotationalHexFem fem(sheet.simulation, softTissue(), smallSteps());
  TissueCutter cutter(sheet.collision, sheet.simulation, &fem);
  const auto report = cutter.cut(scalpelAlongY(0.3, -60, 60));
  ASSERT_TRUE(report.changed());
  EXPECT_TRUE(cutterIsConsistent(cutter, sheet.simulation));
  int pieces = 0;
  collisionPieces(cutter.collision(), pieces);
  EXPECT_EQ(pieces, 2);
  // The column of nine hexahedra the cut runs through is duplicated.
  EXPECT_EQ(report.simulation.newHexahedra.size(), 9u);
  EXPECT_EQ(cutter.simulation().hexahedronCount(), fem.hexahedronCount());
  EXPECT_EQ(cutter.simulation().nodeCount(), fem.nodeCount());
  pullLeftHalfUp(fem, 20);
  EXPECT_GT(largestDisplacement(fem, cutter, true), 1e-2);
  // Nothing couples the right half: only the linear solver's round-off.
  EXPECT_LT(largestDisplacement(fem, cutter, false), 1e-9);
  // The collision mesh follows: the left lip is up, the right one is not.
  const auto current = cutter.currentCollisionPositions();
  for (std::size_t v = 0; v < current.size(); ++v)
  {
    const Vector3& rest = cutter.collision().restPositions()[v];
    EXPECT_TRUE(current[v].allFinite());
    if (rest.x() > 10.0)
    {
      EXPECT_NEAR((current[v] - rest).norm(), 0.0, 1e-9) << "vertex " << v;
    }
  }
}

TEST(TissueCutter, ACutThatStopsHalfWayLeavesOnePieceThatOpens)
{
  const TissueModel sheet = makeThinSheet(ThinSheetParameters{});
  CorotationalHexFem fem(sheet.simulation, softTissue(), smallSteps());
  TissueCutter cutter(sheet.collision, sheet.simulation, &fem);
  const auto report = cutter.cut(scalpelAlongY(0.3, -60, 5));
  ASSERT_TRUE(report.changed());
  EXPECT_TRUE(cutterIsConsistent(cutter, sheet.simulation));
  int pieces = 0;
  collisionPieces(cutter.collision(), pieces);
  EXPECT_EQ(pieces, 1);
  ASSERT_FALSE(report.simulation.newNodes.empty());
  // Lips pulled apart: each node copy up, its original down.
  for (const auto& [copy, source] : report.simulation.newNodes)
  {
    if (fem.restPositions()[source].y() < -20.0)
    {
      fem.setExternalForce(copy, Vector3(0, 0, 2e-4));
      fem.setExternalForce(source, Vector3(0, 0, -2e-4));
    }
  }
  for (int s = 0; s < 20; ++s)
    ASSERT_TRUE(fem.step().ok);
  double widest = 0.0;
  for (const auto& [copy, source] : report.simulation.newNodes)
    widest = std::max(widest, (fem.positions()[copy] - fem.positions()[source]).norm());
  EXPECT_GT(widest, 1e-2);
}

TEST(TissueCutter, BadBladesLeaveTheTissueUntouched)
{
  const TissueModel sheet = makeThinSheet(ThinSheetParameters{});
  CorotationalHexFem fem(sheet.simulation, softTissue(), smallSteps());
  TissueCutter cutter(sheet.collision, sheet.simulation, &fem);
  Blade nan = scalpelAlongY(0.3, -60, 60);
  nan.points[1].z() = std::nan("");
  EXPECT_THROW(cutter.cut(nan), InvalidInputError);
  EXPECT_THROW(cutter.cut(scalpelAlongY(0.3, 10, 10)), InvalidInputError);
  EXPECT_EQ(cutter.collision().vertexCount(), sheet.collision.vertexCount());
  EXPECT_EQ(cutter.simulation().hexahedronCount(), sheet.simulation.hexahedronCount());
  EXPECT_EQ(fem.nodeCount(), sheet.simulation.nodeCount());
  TriangleMesh noRadius = sheet.collision;
  noRadius.pointAttributes.remove("Radius");
  EXPECT_THROW(TissueCutter(noRadius, sheet.simulation), InvalidInputError);
}

// A blade across the cleaved meniscus, through the middle of its junction
// and square to it, cuts the body and both leaves: the C comes apart in two,
// and its visual mesh with it (5.3.2 - 5.3.4 through a junction: the new
// junction points get a crease vertex each, and the body's cut surface runs
// + -> crease -> - where the leaves' two meet it).
TEST(TissueCutter, AHorizontalCleavageIsCutThroughTheBodyAndBothLeaves)
{
  MeniscusParameters parameters;
  parameters.tear = defaultMeniscusTear(MeniscusTearType::HorizontalCleavage);
  const MeniscusModel cleaved = makeMeniscus(parameters);
  const VisualCollisionBinding binding = bindVisualToCollision(cleaved.visual, cleaved.collision);
  CorotationalHexFem fem(cleaved.simulation, test::softTissue(), sweepStepSettings());
  TissueCutter cutter(binding, cleaved.simulation, &fem);
  // The junction's middle edge: where the leaves part from the body.
  const TriangleMeshAdjacency uncut(cleaved.collision);
  std::vector<int> junction;
  for (int e = 0; e < static_cast<int>(uncut.edgeCount()); ++e)
    if (uncut.edgeTriangleCount(e) == 3)
      junction.push_back(e);
  ASSERT_FALSE(junction.empty());
  const auto& middle = uncut.edge(junction[junction.size() / 2]);
  const auto& x = cleaved.collision.positions;
  const Vector3 at = 0.5 * (x[middle[0]] + x[middle[1]]);
  const Vector3 along = x[middle[1]] - x[middle[0]];
  const Vector3 across = Vector3(-along.y(), along.x(), 0.0).normalized();
  const double reach = 0.25 * boundingBoxOf(x).diagonal().norm();
  const Vector3 up = Vector3::UnitZ() * reach;
  const Vector3 from = at - reach * across, to = at + reach * across;
  const auto report = cutter.cut(Blade::sweptSegment(from - up, from + up, to - up, to + up));
  ASSERT_TRUE(cutterIsConsistent(cutter, cleaved.simulation));
  std::vector<int> junctionPoints;
  for (const NewCollisionVertex& made : report.collision.newVertices)
    if (made.duplicateOf < 0 &&
        uncut.edgeTriangleCount(uncut.findEdge(made.edge[0], made.edge[1])) == 3)
      junctionPoints.push_back(made.vertex);
  ASSERT_EQ(junctionPoints.size(), 1u) << "the blade crossed the junction once";
  int pieces = 0;
  collisionPieces(cutter.collision(), pieces);
  EXPECT_EQ(pieces, 2);
  // The junction point and its copy: each a crease vertex of its own, on
  // the cleft's walls between the top and the bottom ones.
  const CuttableVisualMesh& visual = cutter.visual();
  std::vector<int> creases;
  for (const NewCollisionVertex& made : report.collision.newVertices)
    if (made.vertex == junctionPoints[0] || made.duplicateOf == junctionPoints[0])
    {
      const auto& paired = visual.pairedVisualVertices()[made.vertex];
      ASSERT_GE(paired[2], 0) << "junction point " << made.vertex << " has no crease vertex";
      EXPECT_NE(paired[2], paired[0]);
      EXPECT_NE(paired[2], paired[1]);
      const auto& p = visual.mesh().positions;
      const Vector3 upward = p[paired[1]] - p[paired[0]];
      const double height = (p[paired[2]] - p[paired[0]]).dot(upward) / upward.squaredNorm();
      EXPECT_GT(height, 0.0) << "the crease lies between the bottom and the top";
      EXPECT_LT(height, 1.0) << "the crease lies between the bottom and the top";
      creases.push_back(paired[2]);
    }
  ASSERT_EQ(creases.size(), 2u);
  EXPECT_NE(creases[0], creases[1]);
  EXPECT_GT(visual.cutSurfaceTriangleCount(), 0u);
  ASSERT_TRUE(fem.step().ok);
}

TEST(TissueCutterProperty, RandomSweepsOverTheSheetKeepEveryInvariant)
{
  const TissueModel sheet = makeThinSheet(ThinSheetParameters{});
  RandomSweeps sweeps(sheet, 1234u);
  sweeps.run(200 * sweepScale(), 20);
  EXPECT_EQ(sweeps.Sweeps, 4000 * sweepScale());
  EXPECT_GT(sweeps.Refused, 0);
}

TEST(TissueCutterProperty, RandomSweepsOverTheMenisciKeepEveryInvariant)
{
  int total = 0;
  unsigned seed = 99u;
  for (MeniscusTearType tear : { MeniscusTearType::None,
         MeniscusTearType::Longitudinal,
         MeniscusTearType::Radial,
         MeniscusTearType::Flap,
         MeniscusTearType::HorizontalCleavage })
  {
    MeniscusParameters parameters;
    parameters.tear = defaultMeniscusTear(tear);
    const MeniscusModel meniscus = makeMeniscus(parameters);
    RandomSweeps sweeps(meniscus, seed++);
    sweeps.run(80 * sweepScale(), 20);
    total += sweeps.Sweeps;
  }
  EXPECT_EQ(total, 8000 * sweepScale());
}

// Every sweep: the visual mesh with its cut surfaces closed, oriented and
// bound, as many visual pieces as collision pieces, and no visual vertex on
// the nodes of another piece (cutterIsConsistent). A soak of 5 (3,000
// sweeps each) passes too.
TEST(TissueCutterProperty, RandomSweepsCutTheSheetsVisualMeshConsistently)
{
  const TissueModel sheet = makeThinSheet(ThinSheetParameters{});
  const VisualCollisionBinding binding = bindVisualToCollision(sheet.visual, sheet.collision);
  RandomSweeps sweeps(sheet, 4321u);
  sweeps.Binding = &binding;
  sweeps.run(50 * sweepScale(), 20);
  EXPECT_EQ(sweeps.Sweeps, 1000 * sweepScale());
}

TEST(TissueCutterProperty, RandomSweepsCutTheMeniscusVisualMeshConsistently)
{
  const MeniscusModel meniscus = makeMeniscus();
  const VisualCollisionBinding binding = bindVisualToCollision(meniscus.visual, meniscus.collision);
  RandomSweeps sweeps(meniscus, 8765u);
  sweeps.Binding = &binding;
  sweeps.run(50 * sweepScale(), 20);
  EXPECT_EQ(sweeps.Sweeps, 1000 * sweepScale());
}

namespace
{

/// 400 visual sweeps over a torn meniscus (one test per tear, so that they
/// run in parallel).
void sweepTornMeniscusVisually(MeniscusTearType tear, unsigned seed)
{
  MeniscusParameters parameters;
  parameters.tear = defaultMeniscusTear(tear);
  const MeniscusModel meniscus = makeMeniscus(parameters);
  const VisualCollisionBinding binding = bindVisualToCollision(meniscus.visual, meniscus.collision);
  RandomSweeps sweeps(meniscus, seed);
  sweeps.Binding = &binding;
  sweeps.run(20 * sweepScale(), 20);
  EXPECT_EQ(sweeps.Sweeps, 400 * sweepScale()) << meniscus.name;
}

} // namespace

TEST(TissueCutterProperty, RandomSweepsCutTheLongitudinallyTornMeniscusVisualMeshConsistently)
{
  sweepTornMeniscusVisually(MeniscusTearType::Longitudinal, 5511u);
}

TEST(TissueCutterProperty, RandomSweepsCutTheRadiallyTornMeniscusVisualMeshConsistently)
{
  sweepTornMeniscusVisually(MeniscusTearType::Radial, 5512u);
}

TEST(TissueCutterProperty, RandomSweepsCutTheFlapTornMeniscusVisualMeshConsistently)
{
  sweepTornMeniscusVisually(MeniscusTearType::Flap, 5513u);
}

TEST(TissueCutterProperty, RandomSweepsCutTheCleavedMeniscusVisualMeshConsistently)
{
  sweepTornMeniscusVisually(MeniscusTearType::HorizontalCleavage, 5514u);
}

namespace
{

/// 80 random sweeps over the cleaved meniscus (junctions, clefts) and the
/// sheet, each cutter against a twin (RandomSweeps::CompareWith); `check`
/// looks at each model's sweeps afterwards.
template <typename Check>
void sweepAgainstTwin(RandomSweeps::Twin twin, unsigned seed, int episodes, const Check& check)
{
  MeniscusParameters parameters;
  parameters.tear = defaultMeniscusTear(MeniscusTearType::HorizontalCleavage);
  const MeniscusModel meniscus = makeMeniscus(parameters);
  const TissueModel sheet = makeThinSheet(ThinSheetParameters{});
  for (const TissueModel* model : { static_cast<const TissueModel*>(&meniscus), &sheet })
  {
    const VisualCollisionBinding binding = bindVisualToCollision(model->visual, model->collision);
    RandomSweeps sweeps(*model, seed);
    sweeps.Binding = &binding;
    sweeps.CompareWith = twin;
    sweeps.run(episodes, 20);
    EXPECT_EQ(sweeps.Sweeps, 20 * episodes) << model->name;
    check(sweeps, model->name);
  }
}

} // namespace

// The region stages on several threads (forced, whatever the regions'
// size) cut as on one, bit for bit: the simulator replays sessions exactly.
TEST(TissueCutterProperty, SeveralThreadsCutBitForBitAsOne)
{
  sweepAgainstTwin(
    RandomSweeps::Twin::OneThread, 6161u, 4, [](const RandomSweeps&, const std::string&) {});
}

// VisualCutSettings::piecesByLocation: where a split region lies in its
// plane without a fold, the pieces found by location are the union-find's,
// and the triangles far from the cut, placed without being laid out, lie
// where the whole region's layout puts them; so every sweep ends with the
// same visual mesh, binding, regions and embedding as a twin that takes the
// union-find over whole regions. Most regions are located, and some of
// their triangles lie far.
TEST(TissueCutterProperty, PiecesByLocationAreTheUnionFindPieces)
{
  sweepAgainstTwin(RandomSweeps::Twin::UnionFindPieces,
    7272u,
    4 * sweepScale(),
    [](const RandomSweeps& sweeps, const std::string& name)
    {
      EXPECT_GT(sweeps.RegionsLocated, sweeps.SplitRegions / 2) << name;
      EXPECT_GT(sweeps.FarTriangles, 0u) << name;
    });
}

// VisualCutSettings::lazyBinding: the inner vertices a cut leaves to the
// split history resolve to the bindings a twin that rebinds every vertex at
// once makes, bit for bit, with the same visual mesh, regions and
// embedding (the visual re-embedding need not revisit them) after every
// sweep; and the cuts do leave vertices to it.
TEST(TissueCutterProperty, TheLazyBindingResolvesToTheEagerBinding)
{
  sweepAgainstTwin(RandomSweeps::Twin::EagerBinding,
    8383u,
    4 * sweepScale(),
    [](const RandomSweeps& sweeps, const std::string& name)
    { EXPECT_GT(sweeps.LazyVertices, 100u) << name; });
}

namespace
{

/// The steak of chapter 5 prepared as the thesis did (85 collision
/// vertices, 76 hexahedra); null without ../shared/data.
std::unique_ptr<TissueBundle> preparedSteak()
{
  const std::string steak = thintissue::testing::sharedDataDirectory() + "/steak/steak.obj";
  if (thintissue::testing::sharedDataDirectory().empty() || !std::filesystem::exists(steak))
    return nullptr;
  TissuePreparationSettings settings;
  settings.collision.vertexCount = 85;
  settings.hexahedronCount = 76;
  return std::make_unique<TissueBundle>(prepareTissue(readTriangleMesh(steak), settings));
}

} // namespace

TEST(TissueCutterProperty, RandomSweepsOverTheSteakKeepEveryInvariant)
{
  const auto bundle = preparedSteak();
  if (!bundle)
    GTEST_SKIP() << "../shared/data/steak not present";
  TissueModel model;
  model.name = "steak";
  model.visual = bundle->visual;
  model.collision = bundle->collision;
  model.simulation = bundle->simulation;
  RandomSweeps sweeps(model, 2468u);
  sweeps.Binding = &bundle->binding;
  sweeps.run(20 * sweepScale(), 20);
  EXPECT_EQ(sweeps.Sweeps, 400 * sweepScale());
}

TEST(TissueCutterProperty, TheUncutSteakIsAValidStartForTheVisualCut)
{
  // Vertices on a segment two paths share are bound to one of the edges;
  // the regions beside them still find their parameters (along the path).
  const auto bundle = preparedSteak();
  if (!bundle)
    GTEST_SKIP() << "../shared/data/steak not present";
  const auto& b = bundle->binding;
  CuttableCollisionMesh collision(
    "steak collision", b.collisionPositions, b.collisionTriangles, b.collisionRadii);
  CuttableVisualMesh visual(b);
  EXPECT_TRUE(visualMeshIsValid(visual, collision));
}

namespace
{

/// A punch's bite: a closed outline of radius r around (x, y), through the
/// sheet's thickness.
Blade biteAt(double x, double y, double r)
{
  std::vector<Vector3> low, high;
  for (int i = 0; i < 16; ++i)
  {
    const double a = 2.0 * M_PI * i / 16.0;
    const Vector3 p(x + r * std::cos(a), y + r * std::sin(a), 0.0);
    low.push_back(p - Vector3(0, 0, 10));
    high.push_back(p + Vector3(0, 0, 10));
  }
  return Blade::sweptOutline(low, high);
}

struct BoundSheet
{
  TissueModel model = makeThinSheet(ThinSheetParameters{});
  VisualCollisionBinding binding = bindVisualToCollision(model.visual, model.collision);
};

const BoundSheet& boundSheet()
{
  static const BoundSheet sheet;
  return sheet;
}

} // namespace

TEST(TissueCutterSeparation, APieceCutFreeIsKeptDroppedOrHandedOver)
{
  // The sheet is attached along its left and right edges; a bite in the
  // middle cuts a disk free of both.
  const BoundSheet& sheet = boundSheet();
  for (FreePieceHandling handling :
    { FreePieceHandling::Keep, FreePieceHandling::Drop, FreePieceHandling::HandOver })
  {
    CorotationalHexFem fem(sheet.model.simulation, softTissue(), smallSteps());
    TissueCutterSettings settings;
    settings.freePieces = handling;
    TissueCutter cutter(sheet.binding, sheet.model.simulation, &fem, settings);
    const auto report = cutter.cut(biteAt(2.0, 3.0, 28.0));
    ASSERT_TRUE(report.changed());
    EXPECT_TRUE(cutterIsConsistent(cutter, sheet.model.simulation));
    int pieces = 0;
    collisionPieces(cutter.collision(), pieces);
    EXPECT_EQ(pieces, 2);
    const bool removed = handling != FreePieceHandling::Keep;
    EXPECT_EQ(report.removedPieces, removed ? 1 : 0);
    EXPECT_EQ(cutter.activeTriangleCount() < cutter.collision().triangleCount(), removed);
    EXPECT_EQ(report.handedOver.size(), handling == FreePieceHandling::HandOver ? 1u : 0u);
    const auto visualActive = cutter.activeVisualTriangles();
    EXPECT_EQ(std::count(visualActive.begin(), visualActive.end(), 0) > 0, removed);
    // A removed piece's hexahedra have left the solver, the rest's have not.
    for (std::size_t h = 0; h < cutter.simulation().hexahedronCount(); ++h)
    {
      const auto& held = cutter.branches().trianglesOf(static_cast<int>(h));
      const bool carriesTissue =
        std::any_of(held.begin(), held.end(), [&](int t) { return cutter.isActive(t); });
      if (!held.empty())
      {
        EXPECT_EQ(fem.isActive(h), carriesTissue) << "hexahedron " << h;
      }
    }
    // A removed piece is held still: pushing everything up moves the rest only.
    for (std::size_t n = 0; n < fem.nodeCount(); ++n)
      fem.setExternalForce(n, Vector3(0, 0, 1e-4));
    for (int s = 0; s < 5; ++s)
      ASSERT_TRUE(fem.step().ok);
    const auto current = cutter.currentCollisionPositions();
    for (std::size_t t = 0; t < cutter.collision().triangleCount(); ++t)
    {
      const int v = cutter.collision().triangles()[t][0];
      if (!cutter.isActive(static_cast<int>(t)))
      {
        EXPECT_NEAR((current[v] - cutter.collision().restPositions()[v]).norm(), 0.0, 1e-12);
      }
    }
  }
}

TEST(TissueCutterSeparation, APieceCutFreeOverSeveralCutsGoesWithTheCutThatClosesItsOutline)
{
  // Three sides of a square in the middle of the attached sheet separate
  // nothing; the fourth cuts the square free (the cutter then looks at the
  // pieces again, though the cuts before left the tissue in one piece).
  const BoundSheet& sheet = boundSheet();
  CorotationalHexFem fem(sheet.model.simulation, softTissue(), smallSteps());
  TissueCutterSettings settings;
  settings.freePieces = FreePieceHandling::HandOver;
  TissueCutter cutter(sheet.binding, sheet.model.simulation, &fem, settings);
  auto side = [](const Vector2& a, const Vector2& b)
  {
    const Vector3 p(a.x(), a.y(), 0.0), q(b.x(), b.y(), 0.0), up(0.0, 0.0, 10.0);
    return Blade::sweptSegment(p - up, p + up, q - up, q + up);
  };
  const Vector2 corners[4] = { { -26.0, -25.0 }, { -26.0, 31.0 }, { 30.0, 31.0 }, { 30.0, -25.0 } };
  for (int c = 0; c < 4; ++c)
  {
    // Each side reaches a little past the corners, across its neighbours.
    const Vector2 a = corners[c], b = corners[(c + 1) % 4];
    const Vector2 past = 3.0 * (b - a).normalized();
    const auto report = cutter.cut(side(a - past, b + past));
    ASSERT_TRUE(report.changed()) << "side " << c;
    EXPECT_TRUE(report.visualError.empty()) << report.visualError;
    EXPECT_EQ(report.handedOver.size(), c == 3 ? 1u : 0u) << "side " << c;
    EXPECT_EQ(report.removedPieces, c == 3 ? 1 : 0) << "side " << c;
  }
  EXPECT_TRUE(cutterIsConsistent(cutter, sheet.model.simulation));
  EXPECT_LT(cutter.activeTriangleCount(), cutter.collision().triangleCount());
  // Cuts elsewhere separate nothing more.
  const auto report = cutter.cut(side({ -60.0, -40.0 }, { -60.0, 40.0 }));
  EXPECT_EQ(report.removedPieces, 0);
}

TEST(TissueCutterSeparation, AHandedOverPieceIsABodyOfItsOwn)
{
  const BoundSheet& sheet = boundSheet();
  CorotationalHexFem fem(sheet.model.simulation, softTissue(), smallSteps());
  TissueCutterSettings settings;
  settings.freePieces = FreePieceHandling::HandOver;
  TissueCutter cutter(sheet.binding, sheet.model.simulation, &fem, settings);
  const auto report = cutter.cut(biteAt(2.0, 3.0, 28.0));
  ASSERT_EQ(report.handedOver.size(), 1u);
  const TissuePiece& piece = report.handedOver.front();
  // Its visual surface is closed (the cut surface goes with it).
  const MeshValidationReport visual = validateTriangleMesh(piece.visual, 0.0);
  EXPECT_EQ(visual.borderEdges.count, 0u) << visual.toString();
  EXPECT_EQ(visual.nonManifoldEdges.count, 0u) << visual.toString();
  EXPECT_EQ(visual.connectedComponents, 1u);
  EXPECT_EQ(piece.visualRest.size(), piece.visual.vertexCount());
  // About the bite's disk (the collision cut follows the outline roughly).
  EXPECT_NEAR(piece.collisionArea, M_PI * 28.0 * 28.0, 0.35 * M_PI * 28.0 * 28.0);
  EXPECT_EQ(piece.collisionCurrent.size(), piece.collision.vertexCount());
  EXPECT_TRUE(piece.collision.pointAttributes.has("Radius"));
  piece.simulation.checkConsistency();
  EXPECT_GT(piece.simulation.hexahedronCount(), 0u);
  EXPECT_EQ(piece.simulation.fixedNodeCount(), 0u);
  // It can be simulated on its own.
  CorotationalHexFem own(piece.simulation, softTissue(), smallSteps());
  EXPECT_TRUE(own.step().ok);
}

// Piecewise removal (6.4.3): the collision triangles a shaver touches go
// whole, with the visual triangles bound to them; the tissue opens along
// their border without splitting anything, and the cut surface there closes
// both the tissue and the removed piece.
TEST(TissueCutterSeparation, RemovedTrianglesGoWithTheirVisualAndTheOpeningIsClosed)
{
  const BoundSheet& sheet = boundSheet();
  CorotationalHexFem fem(sheet.model.simulation, softTissue(), smallSteps());
  TissueCutterSettings settings;
  settings.freePieces = FreePieceHandling::HandOver;
  TissueCutter cutter(sheet.binding, sheet.model.simulation, &fem, settings);
  const auto& x = sheet.model.collision.positions;
  const Vector3 centre = boundingBoxOf(x).center();
  std::vector<int> shaved;
  double area = 0.0;
  for (std::size_t t = 0; t < sheet.model.collision.triangleCount(); ++t)
  {
    const Triangle& c = sheet.model.collision.triangles[t];
    if (((x[c[0]] + x[c[1]] + x[c[2]]) / 3.0 - centre).head<2>().norm() < 25.0)
    {
      shaved.push_back(static_cast<int>(t));
      area += sheet.model.collision.triangleArea(t);
    }
  }
  ASSERT_GT(shaved.size(), 3u);
  EXPECT_THROW(cutter.removeTriangles({ -1 }), InvalidInputError);
  ASSERT_EQ(cutter.activeTriangleCount(), sheet.model.collision.triangleCount());
  const std::size_t visualBefore = cutter.visual().mesh().triangleCount();
  const auto report = cutter.removeTriangles(shaved);
  ASSERT_EQ(report.visualError, "");
  ASSERT_TRUE(cutterIsConsistent(cutter, sheet.model.simulation));
  EXPECT_TRUE(report.collision.splits.empty()) << "nothing is split";
  EXPECT_EQ(cutter.activeTriangleCount(), sheet.model.collision.triangleCount() - shaved.size());
  ASSERT_EQ(report.removedPieces, 1);
  // The report names the triangles taken out (nothing was split: the
  // shaved ones themselves).
  std::vector<int> named = report.removedTriangles;
  std::sort(named.begin(), named.end());
  EXPECT_EQ(named, shaved);
  ASSERT_EQ(report.handedOver.size(), 1u);
  const TissuePiece& piece = report.handedOver.front();
  EXPECT_NEAR(piece.collisionArea, area, 1e-9 * area);
  const MeshValidationReport closed = validateTriangleMesh(piece.visual, 0.0);
  EXPECT_EQ(closed.borderEdges.count, 0u) << closed.toString();
  EXPECT_EQ(closed.nonManifoldEdges.count, 0u) << closed.toString();
  // The visual mesh only grew by the cut surface, and the tissue's part
  // of it is still closed (cutterIsConsistent) around the hole.
  EXPECT_GT(cutter.visual().cutSurfaceTriangleCount(), 0u);
  EXPECT_EQ(cutter.visual().mesh().triangleCount(),
    visualBefore + cutter.visual().cutSurfaceTriangleCount());
  const std::vector<char> active = cutter.activeVisualTriangles();
  EXPECT_LT(std::count(active.begin(), active.end(), 1),
    static_cast<long>(cutter.visual().mesh().triangleCount()));
  EXPECT_TRUE(fem.step().ok);
  // Removing them again changes nothing.
  const auto again = cutter.removeTriangles(shaved);
  EXPECT_FALSE(again.changed());
  EXPECT_EQ(again.removedPieces, 0);
  EXPECT_TRUE(again.removedTriangles.empty());
}

TEST(TissueCutterSeparation, FragmentsBelowTheSizeAreRemovedWholeAndAttachedPiecesStay)
{
  const BoundSheet& sheet = boundSheet();
  CorotationalHexFem fem(sheet.model.simulation, softTissue(), smallSteps());
  TissueCutterSettings settings;
  settings.fragmentAreaFraction = 0.4; // the disk is about a quarter of the sheet
  settings.freePieces = FreePieceHandling::Drop;
  TissueCutter cutter(sheet.binding, sheet.model.simulation, &fem, settings);
  // Cut in two: each half hangs from its own edge, nothing is free.
  auto report = cutter.cut(Blade::sweptSegment(
    Vector3(30, -80, -10), Vector3(30, -80, 10), Vector3(30, 80, -10), Vector3(30, 80, 10)));
  EXPECT_EQ(report.removedPieces, 0);
  EXPECT_EQ(cutter.activeTriangleCount(), cutter.collision().triangleCount());
  settings.freePieces = FreePieceHandling::Keep;
  TissueCutter keeping(sheet.binding, sheet.model.simulation, nullptr, settings);
  report = keeping.cut(biteAt(-10.0, 0.0, 28.0));
  // The disk (and any sliver the outline cut off) goes, though free pieces
  // are kept; the attached rest stays.
  EXPECT_GE(report.removedPieces, 1);
  EXPECT_LT(keeping.activeTriangleCount(), keeping.collision().triangleCount());
  EXPECT_GT(keeping.activeTriangleCount(), keeping.collision().triangleCount() / 2);
}

// Regressions found by longer soaks (THINTISSUE_CUT_SOAK=3), each the
// shortest run of the soak's blades that still failed without its fix.
namespace
{

/// A blade given by its four corners (Blade::sweptSegment's order).
Blade quad(const std::array<Vector3, 4>& corners)
{
  return Blade::sweptSegment(corners[0], corners[1], corners[3], corners[2]);
}

/// Cuts `model` (bound visual mesh, `rows` cut-surface rows) with each
/// blade in turn, a solver step after each, and checks every invariant.
void cutInTurn(const TissueModel& model,
  const VisualCollisionBinding& binding,
  int rows,
  const std::vector<Blade>& blades)
{
  CorotationalHexFem fem(model.simulation, softTissue(), smallSteps());
  TissueCutterSettings settings;
  settings.visual.cutSurfaceRows = rows;
  TissueCutter cutter(binding, model.simulation, &fem, settings);
  for (std::size_t b = 0; b < blades.size(); ++b)
  {
    const auto report = cutter.cut(blades[b]);
    ASSERT_TRUE(report.changed()) << "blade " << b;
    ASSERT_EQ(report.visualError, "") << "blade " << b;
    ASSERT_TRUE(cutterIsConsistent(cutter, model.simulation)) << "blade " << b;
    ASSERT_TRUE(fem.step().ok) << "blade " << b;
  }
}

} // namespace

// A split triangle's pieces are tested against the hexahedra of their
// parent, each grown by the largest radius of its own corners (often less
// than the parent's), so a hexahedron can lose the parent without holding
// any piece of it. Such a hexahedron had been left out of the branch
// analysis, and where the lost parent had joined its other triangles into
// one branch, two pieces of the torn meniscus (third blade) kept sharing
// its nodes.
TEST(TissueCutterRegression, AHexahedronThatLosesASplitTriangleIsAnalysedAgain)
{
  MeniscusParameters parameters;
  parameters.tear = defaultMeniscusTear(MeniscusTearType::Radial);
  const MeniscusModel meniscus = makeMeniscus(parameters);
  const VisualCollisionBinding binding = bindVisualToCollision(meniscus.visual, meniscus.collision);
  const std::vector<Blade> blades = {
    quad({ Vector3(-23.928363607988011, 4.8695372601716809, -44.163514477299941),
      Vector3(-43.115232325486595, 31.089413895821089, 53.228288410185556),
      Vector3(-37.941445984833294, 9.5596924716645919, 52.436939177426297),
      Vector3(-18.75457726733471, -16.660184163984816, -44.9548637100592) }),
    quad({ Vector3(-28.215281016746463, 22.472703129838468, -43.475472287255158),
      Vector3(-32.601679288852161, 4.6165919079463613, 53.916330600230339),
      Vector3(-35.479957236575046, -10.70540741007348, 53.788700876767329),
      Vector3(-31.093558964469349, 7.1507038118186266, -43.603102010718167) }),
    quad({ Vector3(-36.971747743716747, 15.008250115106238, -44.67921266824041),
      Vector3(-32.1881559461157, -12.726632966939201, 52.712590219245087),
      Vector3(-10.446934630786597, -32.15030594831979, 52.845438070373348),
      Vector3(-15.230526428387652, -4.4154228662743531, -44.546364817112149) }),
  };
  cutInTurn(meniscus, binding, 2, blades);
}

// A visual vertex bound to a collision edge hangs on the edge's first
// triangle. When a cut splits that triangle the edge may go to a piece its
// hexahedron does not hold; the hexahedron is touched but not copied, and
// the vertex (a cut-surface vertex on the steak's second cut, which
// separates that piece) had stayed on the other piece's nodes.
TEST(TissueCutterRegression, AVisualVertexOnAnEdgeOfASplitTriangleFollowsItsPiece)
{
  const auto bundle = preparedSteak();
  if (!bundle)
    GTEST_SKIP() << "../shared/data/steak not present";
  TissueModel steak;
  steak.simulation = bundle->simulation;
  const std::vector<Blade> blades = {
    quad({ Vector3(2.26270343908317, -2.4188549867780798, -9.5373007892664283),
      Vector3(2.26270343908317, -2.4188549867780798, 9.5422577892664293),
      Vector3(-3.2622234505314021, -0.92291285418609548, 9.5422577892664293),
      Vector3(-3.2622234505314021, -0.92291285418609548, -9.5373007892664283) }),
    quad({ Vector3(-2.9975047430694688, -3.8828950247726817, -9.5373012096473389),
      Vector3(-2.9975047430694688, -3.8828950247726817, 9.5422573688855188),
      Vector3(-2.9825903213873048, 1.8409531178387106, 9.5422573688855188),
      Vector3(-2.9825903213873048, 1.8409531178387106, -9.5373012096473389) }),
  };
  cutInTurn(steak, bundle->binding, 1, blades);
}

// A visual vertex beyond the radius boxes of its collision triangle's
// hexahedra hangs on a hexahedron holding a triangle around its own. When
// the collision mesh opens at the corner the two triangles share, they go
// to different pieces and nothing of that hexahedron is copied; the vertex
// (on the steak, after a bite and two cuts through it) had stayed on the
// other piece's nodes.
TEST(TissueCutterRegression, AVisualVertexHangingOnANeighbouringTriangleFollowsItsPiece)
{
  const auto bundle = preparedSteak();
  if (!bundle)
    GTEST_SKIP() << "../shared/data/steak not present";
  TissueModel steak;
  steak.simulation = bundle->simulation;
  const std::vector<Vector2> bite = { Vector2(-2.1954497422256685, 0.26968498292957355),
    Vector2(-2.3905011642540637, 0.85115822362987381),
    Vector2(-3.0347590724136202, 1.3860994812339502),
    Vector2(-3.5972386707004436, 1.4744227028535586),
    Vector2(-4.2409667071105446, 1.26200978076599),
    Vector2(-4.7255931872751349, 0.69796897137595726),
    Vector2(-4.822166519206629, -0.090456709060841162),
    Vector2(-4.6356404706517935, -0.56419868301212583),
    Vector2(-3.9690034881590615, -1.0978982849114827),
    Vector2(-3.3797450025157376, -1.170103568692656),
    Vector2(-2.7381142109599561, -0.92455904954688584),
    Vector2(-2.3343576536350401, -0.45205323079854121) };
  std::vector<Vector3> low, high;
  for (const Vector2& p : bite)
  {
    low.emplace_back(p.x(), p.y(), -9.5372997261180696);
    high.emplace_back(p.x(), p.y(), 9.542258852414788);
  }
  const std::vector<Blade> blades = {
    Blade::sweptOutline(low, high),
    quad({ Vector3(-4.0281457347170928, 3.0185651175909163, -9.5373011489161978),
      Vector3(-0.53062148268087062, 0.19779000323978368, 9.5422574296166598),
      Vector3(1.4517482498712535, -2.6967904539852983, 9.5422592344408734),
      Vector3(-2.0457760021649687, 0.12398466036583478, -9.5372993440919842) }),
    quad({ Vector3(-2.9975047430694688, -3.8828950247726817, -9.5373012096473389),
      Vector3(-2.9975047430694688, -3.8828950247726817, 9.5422573688855188),
      Vector3(-2.9825903213873048, 1.8409531178387106, 9.5422573688855188),
      Vector3(-2.9825903213873048, 1.8409531178387106, -9.5373012096473389) }),
  };
  cutInTurn(steak, bundle->binding, 1, blades);
}

// A copy of a junction vertex that keeps the lower leaf alone has no +
// paired visual vertex (-1). The cut-surface vertices of its column were
// copied from that missing vertex: positions, normals and bindings were
// overwritten afterwards, but point attributes kept what lay before their
// arrays (found by AddressSanitizer on the cleaved soak, episode 4; the
// two of its blades that still fail). A constant attribute must stay so.
TEST(TissueCutterRegression, ACutSurfaceVertexAtALowerLeafJunctionCopyKeepsItsAttributes)
{
  MeniscusParameters parameters;
  parameters.tear = defaultMeniscusTear(MeniscusTearType::HorizontalCleavage);
  const MeniscusModel meniscus = makeMeniscus(parameters);
  VisualCollisionBinding binding = bindVisualToCollision(meniscus.visual, meniscus.collision);
  const double label = 7.0;
  binding.visual.pointAttributes.set(
    "Label", 1, std::vector<double>(binding.visual.vertexCount(), label));
  CorotationalHexFem fem(meniscus.simulation, softTissue(), smallSteps());
  TissueCutterSettings settings;
  settings.visual.cutSurfaceRows = 1;
  TissueCutter cutter(binding, meniscus.simulation, &fem, settings);
  const std::vector<Blade> blades = {
    quad({ Vector3(-44.331798569154898, -11.096932841269819, -46.039685231055472),
      Vector3(-23.650537887947891, -15.783357078992744, 51.384199261787586),
      Vector3(-7.626829667893551, 10.225801853188919, 52.853132909429661),
      Vector3(-28.30809034910056, 14.912226090911844, -44.570751583413397) }),
    quad({ Vector3(-29.896424530946252, -6.8505944092327304, -45.105329386891938),
      Vector3(-29.896424530946252, -6.8505944092327304, 52.31855510595112),
      Vector3(-27.43261655498409, -4.7525101461534298, 52.443058672996898),
      Vector3(-27.43261655498409, -4.7525101461534298, -44.98082581984616) }),
  };
  for (std::size_t b = 0; b < blades.size(); ++b)
  {
    const auto report = cutter.cut(blades[b]);
    ASSERT_TRUE(report.changed()) << "blade " << b;
    ASSERT_EQ(report.visualError, "") << "blade " << b;
    ASSERT_TRUE(cutterIsConsistent(cutter, meniscus.simulation)) << "blade " << b;
  }
  // The case: a junction vertex (crease slot) with a - but no + vertex.
  const auto& paired = cutter.visual().pairedVisualVertices();
  EXPECT_TRUE(std::any_of(paired.begin(),
    paired.end(),
    [](const std::array<int, 3>& p) { return p[0] >= 0 && p[1] < 0 && p[2] >= 0; }));
  const auto& labels = cutter.visual().mesh().pointAttributes.get("Label").values;
  ASSERT_EQ(labels.size(), cutter.visual().mesh().vertexCount());
  for (std::size_t v = 0; v < labels.size(); ++v)
    EXPECT_NEAR(labels[v], label, 1e-9) << "visual vertex " << v;
}
