// The visual-collision binding (thesis 5.2) on the thesis's sheet and
// meniscus: every visual vertex bound once with parameters inside its
// collision triangle, one disk per collision triangle and side, the surface
// unchanged, paths continuous and no longer than edge paths, determinism,
// bad input, and the binding file.
#include "BindingCache.h"
#include "BindingInvariants.h"
#include "GeodesicPaths.h"
#include "MeniscusModel.h"
#include "MeshQueries.h"
#include "MeshValidation.h"
#include "ThinSheetModel.h"
#include "TriangleMeshAdjacency.h"
#include "VisualCollisionBinding.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <queue>
#include <set>

using namespace thintissue;

namespace
{
using thintissue::testing::checkBinding;
const TissueModel& sheet()
{
  static const TissueModel model = makeThinSheet(thesisSheetVisualResolution(1));
  return model;
}

const VisualCollisionBinding& sheetBinding()
{
  static const VisualCollisionBinding binding =
    bindVisualToCollision(sheet().visual, sheet().collision);
  return binding;
}

const MeniscusModel& meniscus()
{
  static const MeniscusModel model = makeMeniscus();
  return model;
}

const VisualCollisionBinding& meniscusBinding()
{
  static const VisualCollisionBinding binding =
    bindVisualToCollision(meniscus().visual, meniscus().collision);
  return binding;
}

std::string temporaryPath(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("thintissue-" + name)).string();
}

} // namespace

TEST(VisualCollisionBinding, SheetIsBoundExactly)
{
  SCOPED_TRACE("sheet model 1, collision model 1");
  checkBinding(sheet().visual, sheet().collision, sheetBinding());
}

TEST(VisualCollisionBinding, MeniscusIsBoundExactly)
{
  checkBinding(meniscus().visual, meniscus().collision, meniscusBinding());
}

// Torn menisci: the collision lips lie on the visual lips' walls (a
// round-off outside them, where the rim ray would meet the other lip), the
// border turns back at the tear's ends, and near a radial tear up to seven
// paths meet at one visual vertex before they are moved apart.
TEST(VisualCollisionBinding, TornMenisciAreBoundExactly)
{
  for (MeniscusTearType tear :
    { MeniscusTearType::Longitudinal, MeniscusTearType::Radial, MeniscusTearType::Flap })
  {
    MeniscusParameters parameters;
    parameters.tear = defaultMeniscusTear(tear);
    const MeniscusModel torn = makeMeniscus(parameters);
    SCOPED_TRACE(torn.name);
    const VisualCollisionBinding binding = bindVisualToCollision(torn.visual, torn.collision);
    checkBinding(torn.visual, torn.collision, binding);
    int detours = 0;
    for (const BindingPath& path : binding.paths)
      detours += path.detours;
    if (tear == MeniscusTearType::Radial)
    {
      EXPECT_GT(detours, 0); // the paths that met beside the tear were moved apart
    }
  }
}

// The labelled equator (RimPathMethod::Labelled, the fallback for rough
// rims): the rim paths run along the border between the visual triangles
// on the positive and negative sides of the collision mid-surface, and the
// rim points move onto it. On the thesis's sheet and on the intact and
// longitudinally torn menisci the binding keeps every invariant, each rim
// point has triangles on both halves, and every rim path edge has one
// triangle on each. A horizontal cleavage (three halves) is refused by
// name.
TEST(VisualCollisionBinding, TheLabelledEquatorBindsTheSheetAndTheMenisci)
{
  VisualCollisionBindingSettings settings;
  settings.rimPaths = RimPathMethod::Labelled;
  MeniscusParameters torn;
  torn.tear = defaultMeniscusTear(MeniscusTearType::Longitudinal);
  const MeniscusModel longitudinal = makeMeniscus(torn);
  const std::vector<std::pair<const TriangleMesh*, const TriangleMesh*>> cases{
    { &sheet().visual, &sheet().collision },
    { &meniscus().visual, &meniscus().collision },
    { &longitudinal.visual, &longitudinal.collision }
  };
  for (const auto& [visual, collision] : cases)
  {
    SCOPED_TRACE(visual->name);
    const VisualCollisionBinding binding = bindVisualToCollision(*visual, *collision, settings);
    checkBinding(*visual, *collision, binding);
    const TriangleMeshAdjacency adjacency(binding.visual);
    std::map<int, int> trianglesOfEdge;
    for (const Triangle& t : binding.collisionTriangles)
      for (int k = 0; k < 3; ++k)
        ++trianglesOfEdge[binding.collisionEdgeIndex(t[k], t[(k + 1) % 3])];
    int rimPaths = 0;
    for (const BindingPath& path : binding.paths)
    {
      if (trianglesOfEdge[path.collisionEdge] != 1)
        continue;
      ++rimPaths;
      for (std::size_t i = 1; i < path.visualVertices.size(); ++i)
      {
        const int e = adjacency.findEdge(path.visualVertices[i - 1], path.visualVertices[i]);
        ASSERT_GE(e, 0);
        const int* t = adjacency.edgeTrianglesBegin(e);
        EXPECT_NE(thintissue::testing::visualTriangleHalf(binding, t[0]),
          thintissue::testing::visualTriangleHalf(binding, t[1]))
          << "rim path of collision edge " << path.collisionEdge << " at visual edge " << e;
      }
      const int rimPoint = path.visualVertices.front();
      std::set<SurfaceHalf> halves;
      for (const int* t = adjacency.vertexTrianglesBegin(rimPoint);
           t != adjacency.vertexTrianglesEnd(rimPoint);
           ++t)
        halves.insert(thintissue::testing::visualTriangleHalf(binding, *t));
      EXPECT_EQ(halves.size(), 2u) << "rim point " << rimPoint;
    }
    EXPECT_GT(rimPaths, 0);
  }
  MeniscusParameters cleavage;
  cleavage.tear = defaultMeniscusTear(MeniscusTearType::HorizontalCleavage);
  const MeniscusModel cleaved = makeMeniscus(cleavage);
  try
  {
    bindVisualToCollision(cleaved.visual, cleaved.collision, settings);
    ADD_FAILURE() << "a cleavage bound with the labelled equator";
  }
  catch (const InvalidInputError& error)
  {
    EXPECT_NE(std::string(error.what()).find("labelled equator"), std::string::npos)
      << error.what();
  }
}

// A horizontal cleavage: the collision mid-surface splits along a U into an
// upper and a lower leaf, so its junction edges join three triangles (the
// body and both leaves). Each junction edge gets three paths (top, bottom,
// the cleft's crease); each vertex inside the junction three paired visual
// vertices; the cleft's walls are a third half of the visual surface, on
// which the leaves' inner sides are bound. The thesis has no such tear.
TEST(VisualCollisionBinding, HorizontalCleavageIsBoundPerWedge)
{
  MeniscusParameters parameters;
  parameters.tear = defaultMeniscusTear(MeniscusTearType::HorizontalCleavage);
  const MeniscusModel cleaved = makeMeniscus(parameters);
  const VisualCollisionBinding binding = bindVisualToCollision(cleaved.visual, cleaved.collision);
  checkBinding(cleaved.visual, cleaved.collision, binding);

  std::map<int, int> trianglesOfEdge;
  for (const Triangle& t : binding.collisionTriangles)
    for (int k = 0; k < 3; ++k)
      ++trianglesOfEdge[binding.collisionEdgeIndex(t[k], t[(k + 1) % 3])];
  std::map<int, std::set<int>> pathSides;
  for (const BindingPath& path : binding.paths)
    EXPECT_TRUE(pathSides[path.collisionEdge].insert(path.side).second) << "one path per side";
  int junctionEdges = 0;
  for (const auto& [edge, count] : trianglesOfEdge)
  {
    const std::set<int> expected =
      count == 1 ? std::set<int>{ 0 }
                 : (count == 2 ? std::set<int>{ -1, 1 } : std::set<int>{ -1, 0, 1 });
    EXPECT_EQ(pathSides[edge], expected) << "collision edge " << edge << " of " << count;
    junctionEdges += count == 3 ? 1 : 0;
  }
  EXPECT_GE(junctionEdges, 3);

  // Junction vertices: their three visual vertices lie on the top, the
  // bottom and the cleft's walls, on the side their normals say.
  int junctionVertices = 0;
  std::vector<Vector3> normals(binding.collisionPositions.size(), Vector3::Zero());
  for (const Triangle& t : binding.collisionTriangles)
  {
    const auto& p = binding.collisionPositions;
    for (int v : t)
      normals[v] += (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
  }
  for (std::size_t c = 0; c < binding.collisionPositions.size(); ++c)
  {
    if (!binding.collisionSides.junctionVertex[c])
      continue;
    ++junctionVertices;
    const Vector3& origin = binding.collisionPositions[c];
    const Vector3 up = normals[c].normalized();
    const auto& positions = binding.visual.positions;
    const double above = (positions[binding.pairedVisualVertices[c][0]] - origin).dot(up);
    const double below = (positions[binding.pairedVisualVertices[c][1]] - origin).dot(up);
    const double crease = (positions[binding.creaseVisualVertices[c]] - origin).dot(up);
    EXPECT_GT(above, 0.0) << "junction vertex " << c;
    EXPECT_LT(below, 0.0) << "junction vertex " << c;
    EXPECT_LT(crease, above) << "junction vertex " << c;
    EXPECT_GT(crease, below) << "junction vertex " << c;
  }
  EXPECT_GE(junctionVertices, 2);

  // The cleft's walls: the visual triangles bound to the leaves' inner
  // sides, a third half with their own area.
  double cleftArea = 0.0;
  for (std::size_t t = 0; t < binding.visual.triangleCount(); ++t)
    if (binding.collisionSides.halves[binding.triangleRegion[t]]
                                     [sideSlot(binding.triangleSide[t])] == SurfaceHalf::Cleft)
      cleftArea += binding.visual.triangleArea(t);
  EXPECT_GT(cleftArea, 0.05 * binding.visual.surfaceArea());

  // The binding file keeps the crease vertices; the sides come back.
  const auto read = readBindingBytes(bindingCacheBytes(binding, 1), "cleavage");
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->binding.creaseVisualVertices, binding.creaseVisualVertices);
  EXPECT_EQ(read->binding.collisionSides.junctionVertex, binding.collisionSides.junctionVertex);
  EXPECT_EQ(read->binding.pathEnds(), binding.pathEnds());
}

TEST(VisualCollisionBinding, InnerEdgesBetweenRimVerticesGetAPathOnEachSide)
{
  // The meniscus's collision grid cuts its four corners with inner edges
  // joining two border vertices: the positive path must run over the upper
  // surface, the negative one under the lower, meeting only at their ends.
  const VisualCollisionBinding& b = meniscusBinding();
  std::vector<int> borderEdges(b.collisionPositions.size(), 0);
  std::map<std::pair<int, int>, int> triangleCount;
  for (const Triangle& t : b.collisionTriangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      ++triangleCount[std::minmax(t[k], t[(k + 1) % 3])];
    }
  }
  for (const auto& [edge, count] : triangleCount)
  {
    if (count == 1)
    {
      ++borderEdges[edge.first];
      ++borderEdges[edge.second];
    }
  }
  int chords = 0;
  for (const BindingPath& positive : b.paths)
  {
    const auto& e = b.collisionEdges[positive.collisionEdge];
    if (positive.side != 1 || borderEdges[e[0]] == 0 || borderEdges[e[1]] == 0)
    {
      continue;
    }
    ++chords;
    const BindingPath* negative = nullptr;
    for (const BindingPath& p : b.paths)
    {
      negative = p.collisionEdge == positive.collisionEdge && p.side == -1 ? &p : negative;
    }
    ASSERT_NE(negative, nullptr);
    EXPECT_EQ(positive.visualVertices.front(), negative->visualVertices.front());
    EXPECT_EQ(positive.visualVertices.back(), negative->visualVertices.back());
    std::set<int> shared(positive.visualVertices.begin() + 1, positive.visualVertices.end() - 1);
    for (std::size_t i = 1; i + 1 < negative->visualVertices.size(); ++i)
    {
      EXPECT_EQ(shared.count(negative->visualVertices[i]), 0u);
    }
    // Height above the collision edge's mid-point, along the collision
    // normal there: the positive path rises above it, the negative one
    // falls below.
    Vector3 normal = Vector3::Zero();
    for (const Triangle& t : b.collisionTriangles)
    {
      if (std::count(t.begin(), t.end(), e[0]) + std::count(t.begin(), t.end(), e[1]) == 2)
      {
        normal += (b.collisionPositions[t[1]] - b.collisionPositions[t[0]])
                    .cross(b.collisionPositions[t[2]] - b.collisionPositions[t[0]]);
      }
    }
    normal.normalize();
    const Vector3 middle = 0.5 * (b.collisionPositions[e[0]] + b.collisionPositions[e[1]]);
    auto highest = [&](const BindingPath& path, double sign)
    {
      double h = -1e300;
      for (int v : path.visualVertices)
      {
        h = std::max(h, sign * (b.visual.positions[v] - middle).dot(normal));
      }
      return h;
    };
    EXPECT_GT(highest(positive, 1.0), 0.0);
    EXPECT_GT(highest(*negative, -1.0), 0.0);
  }
  EXPECT_GE(chords, 1);
}

TEST(VisualCollisionBinding, ParametersPerTriangleFollowFigure5To6)
{
  const VisualCollisionBinding& b = sheetBinding();
  // A vertex bound to an edge has its two parameters at that edge's
  // vertices in either triangle beside it, zero at the third.
  bool checked = false;
  for (std::size_t v = 0; v < b.vertices.size() && !checked; ++v)
  {
    if (b.vertices[v].kind != BindingKind::CollisionEdge || b.vertices[v].side == 0)
    {
      continue;
    }
    const auto& e = b.collisionEdges[b.vertices[v].element];
    for (std::size_t t = 0; t < b.collisionTriangles.size(); ++t)
    {
      const Triangle& tri = b.collisionTriangles[t];
      const bool hasEdge = std::count(tri.begin(), tri.end(), e[0]) == 1 &&
                           std::count(tri.begin(), tri.end(), e[1]) == 1;
      if (!hasEdge)
      {
        EXPECT_THROW(b.parametersInTriangle(v, static_cast<int>(t)), InvalidInputError);
        continue;
      }
      const Vector3 p = b.parametersInTriangle(v, static_cast<int>(t));
      const Vector3 point = p[0] * b.collisionPositions[tri[0]] +
                            p[1] * b.collisionPositions[tri[1]] +
                            p[2] * b.collisionPositions[tri[2]];
      EXPECT_LT((point - b.projectedPoint(v, b.collisionPositions)).norm(), 1e-12);
      checked = true;
    }
  }
  EXPECT_TRUE(checked);
}

TEST(VisualCollisionBinding, SameInputSameOutputBitForBit)
{
  VisualCollisionBindingSettings serial;
  serial.parallel = false;
  const VisualCollisionBinding again =
    bindVisualToCollision(sheet().visual, sheet().collision, serial);
  const VisualCollisionBinding& first = sheetBinding();
  ASSERT_EQ(again.visual.positions.size(), first.visual.positions.size());
  EXPECT_TRUE(again.visual.positions == first.visual.positions);
  EXPECT_TRUE(again.visual.triangles == first.visual.triangles);
  EXPECT_TRUE(again.visual.textureCoordinates == first.visual.textureCoordinates);
  EXPECT_TRUE(again.triangleRegion == first.triangleRegion);
  ASSERT_EQ(again.vertices.size(), first.vertices.size());
  for (std::size_t v = 0; v < again.vertices.size(); ++v)
  {
    ASSERT_EQ(again.vertices[v].kind, first.vertices[v].kind);
    ASSERT_EQ(again.vertices[v].element, first.vertices[v].element);
    ASSERT_EQ(again.vertices[v].parameters, first.vertices[v].parameters) << v;
  }
}

TEST(VisualCollisionBinding, BadInputIsNamed)
{
  auto expectError =
    [](const TriangleMesh& visual, const TriangleMesh& collision, const std::string& fragment)
  {
    try
    {
      bindVisualToCollision(visual, collision);
      ADD_FAILURE() << "no error, expected one mentioning '" << fragment << "'";
    }
    catch (const InvalidInputError& e)
    {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  const TissueModel& s = sheet();
  // Collision mesh outside the visual volume.
  TriangleMesh lifted = s.collision;
  lifted.positions[5].z() += 10.0;
  expectError(s.visual, lifted, "vertex 5 lies outside");
  // Open visual mesh.
  TriangleMesh open = s.visual;
  open.triangles.pop_back();
  open.textureCorners.pop_back();
  expectError(open, s.collision, "border edges");
  // Non-manifold visual mesh: a triangle repeated with another third vertex.
  TriangleMesh nonManifold = s.visual;
  const Triangle t0 = nonManifold.triangles[0];
  nonManifold.triangles.push_back({ t0[1], t0[0], t0[2] == 0 ? 1 : 0 });
  nonManifold.textureCorners.push_back(nonManifold.textureCorners[0]);
  expectError(nonManifold, s.collision, "non-manifold");
  // Radii missing, non-positive.
  TriangleMesh noRadius = s.collision;
  noRadius.pointAttributes.remove("Radius");
  expectError(s.visual, noRadius, "'Radius'");
  TriangleMesh zeroRadius = s.collision;
  zeroRadius.pointAttributes.get("Radius").values[3] = 0.0;
  expectError(s.visual, zeroRadius, "vertex 3 has radius 0");
  // Not thin: the radii claim a surface far closer than it is.
  TriangleMesh thinRadii = s.collision;
  for (double& r : thinRadii.pointAttributes.get("Radius").values)
  {
    r = 0.01;
  }
  expectError(s.visual, thinRadii, "not thin");
  // Collision triangles oriented against their neighbours.
  TriangleMesh flipped = s.collision;
  std::swap(flipped.triangles[0][0], flipped.triangles[0][1]);
  expectError(s.visual, flipped, "oriented inconsistently");
  // An edge of four or more triangles: three extra ones on an edge (at most
  // three, a cleavage's junction, join at an edge).
  TriangleMesh fourAtAnEdge = s.collision;
  const Triangle c0 = fourAtAnEdge.triangles[0];
  const Vector3 middle = (fourAtAnEdge.positions[c0[0]] + fourAtAnEdge.positions[c0[1]]) / 2.0;
  const double radius = fourAtAnEdge.pointAttributes.get("Radius").values[c0[0]];
  for (double dz : { 0.5 * radius, -0.5 * radius, 0.25 * radius })
  {
    fourAtAnEdge.positions.push_back(middle + Vector3(0.0, 0.0, dz));
    if (fourAtAnEdge.hasNormals())
      fourAtAnEdge.normals.push_back(fourAtAnEdge.normals[c0[0]]);
    fourAtAnEdge.pointAttributes.get("Radius").values.push_back(0.25 * radius);
    fourAtAnEdge.triangles.push_back(
      { c0[1], c0[0], static_cast<int>(fourAtAnEdge.positions.size()) - 1 });
  }
  expectError(s.visual, fourAtAnEdge, "triangles (at most three");
}

TEST(BindingCache, RoundTripStaleAndDamagedFiles)
{
  const TissueModel& s = sheet();
  const VisualCollisionBinding& binding = sheetBinding();
  const std::uint64_t checksum = bindingInputChecksum(s.visual, s.collision, {});
  const std::string path = temporaryPath("sheet.binding");
  writeBindingCache(path, binding, checksum, &s.simulation);

  std::string why;
  auto read = readBindingCache(path, checksum, &why);
  ASSERT_TRUE(read.has_value()) << why;
  EXPECT_TRUE(read->binding.visual.positions == binding.visual.positions);
  EXPECT_TRUE(read->binding.triangleRegion == binding.triangleRegion);
  ASSERT_EQ(read->binding.vertices.size(), binding.vertices.size());
  for (std::size_t v = 0; v < binding.vertices.size(); ++v)
  {
    ASSERT_EQ(read->binding.vertices[v].parameters, binding.vertices[v].parameters);
  }
  ASSERT_TRUE(read->simulation.has_value());
  EXPECT_TRUE(read->simulation->nodes == s.simulation.nodes);
  ASSERT_EQ(read->binding.paths.size(), binding.paths.size());
  for (std::size_t k = 0; k < binding.paths.size(); ++k)
  {
    EXPECT_EQ(read->binding.paths[k].visualVertices, binding.paths[k].visualVertices);
    EXPECT_EQ(read->binding.paths[k].length, binding.paths[k].length);
    EXPECT_EQ(read->binding.paths[k].detours, binding.paths[k].detours);
  }

  // Stale: another collision mesh.
  TriangleMesh moved = s.collision;
  moved.positions[0].x() += 1e-6;
  EXPECT_NE(bindingInputChecksum(s.visual, moved, {}), checksum);
  EXPECT_FALSE(readBindingCache(path, bindingInputChecksum(s.visual, moved, {}), &why));
  EXPECT_NE(why.find("stale"), std::string::npos) << why;

  // Damaged: one byte flipped, then truncated.
  const auto size = std::filesystem::file_size(path);
  {
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(static_cast<std::streamoff>(size / 2));
    char byte = 0;
    file.seekg(static_cast<std::streamoff>(size / 2));
    file.get(byte);
    file.seekp(static_cast<std::streamoff>(size / 2));
    file.put(static_cast<char>(byte ^ 0x5a));
  }
  EXPECT_FALSE(readBindingCache(path, checksum, &why));
  EXPECT_NE(why.find("damaged"), std::string::npos) << why;
  std::filesystem::resize_file(path, size / 3);
  EXPECT_FALSE(readBindingCache(path, checksum, &why));
  EXPECT_NE(why.find("damaged"), std::string::npos) << why;

  // loadOrBuild rebuilds the damaged file, then trusts the new one.
  bool rebuilt = false;
  const VisualCollisionBinding rebuiltBinding =
    loadOrBuildBinding(path, s.visual, s.collision, {}, {}, &rebuilt, &why);
  EXPECT_TRUE(rebuilt);
  EXPECT_TRUE(rebuiltBinding.visual.positions == binding.visual.positions);
  loadOrBuildBinding(path, s.visual, s.collision, {}, {}, &rebuilt);
  EXPECT_FALSE(rebuilt);
  std::filesystem::remove(path);
  EXPECT_FALSE(readBindingCache(path, checksum, &why));
  EXPECT_NE(why.find("missing"), std::string::npos);
}

TEST(VisualCollisionBinding, ProgressIsReportedAndAbortStops)
{
  std::vector<double> fractions;
  VisualCollisionBindingSettings settings;
  bindVisualToCollision(sheet().visual,
    sheet().collision,
    settings,
    [&](double fraction, const char*)
    {
      fractions.push_back(fraction);
      return true;
    });
  ASSERT_GT(fractions.size(), 5u);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_EQ(fractions.back(), 1.0);
  EXPECT_THROW(bindVisualToCollision(sheet().visual,
                 sheet().collision,
                 settings,
                 [](double fraction, const char*) { return fraction < 0.2; }),
    BindingAbortedError);
}
