// The jagged cut surface, its roughness and contouring (thesis 6.4.4): a
// sheet cut through with and without jaggedness, the same cut each time.
#include "CuttingInvariants.h"
#include "ThinSheetModel.h"
#include "ThinTissueError.h"
#include "TissueCutter.h"
#include "VisualCollisionBinding.h"

#include <gtest/gtest.h>

using namespace thintissue;
using namespace thintissue::cutting_test;

namespace
{

struct BoundSheet
{
  TissueModel sheet = makeThinSheet(thesisSheetVisualResolution(1));
  VisualCollisionBinding binding = bindVisualToCollision(sheet.visual, sheet.collision);
};

const BoundSheet& boundSheet()
{
  static const BoundSheet sheet;
  return sheet;
}

/// The sheet cut through across the middle (x = 3, along y), with the
/// cut surface jagged by `amplitude` (mm).
TissueCutter cutSheet(double amplitude, std::uint32_t seed = 7u, int rows = 1)
{
  TissueCutterSettings settings;
  settings.visual.cutSurfaceRows = rows;
  settings.visual.jaggedAmplitude = amplitude;
  settings.visual.jaggedSeed = seed;
  TissueCutter cutter(boundSheet().binding, boundSheet().sheet.simulation, nullptr, settings);
  const Vector3 up(0.0, 0.0, 10.0);
  cutter.cut(Blade::sweptSegment(Vector3(3.0, -70.0, 0.0) - up,
    Vector3(3.0, -70.0, 0.0) + up,
    Vector3(3.0, 70.0, 0.0) - up,
    Vector3(3.0, 70.0, 0.0) + up));
  return cutter;
}

double enclosedVolume(const TriangleMesh& mesh)
{
  double volume = 0.0;
  for (const Triangle& t : mesh.triangles)
    volume += mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]]));
  return volume / 6.0;
}

std::vector<int> cutSurfaceVertices(const CuttableVisualMesh& visual)
{
  std::vector<int> vertices;
  for (std::size_t t = 0; t < visual.mesh().triangleCount(); ++t)
    if (visual.triangleMaterials()[t] == VisualMaterial::CutSurface)
      vertices.insert(
        vertices.end(), visual.mesh().triangles[t].begin(), visual.mesh().triangles[t].end());
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return vertices;
}

} // namespace

TEST(JaggedCutSurface, ASmoothCutHasNoRoughness)
{
  const TissueCutter cutter = cutSheet(0.0);
  const CutSurfaceRoughness roughness = cutter.cutRimRoughness();
  EXPECT_GT(roughness.vertices, 20u);
  EXPECT_LT(roughness.maximum, 1e-9);
}

// The vertices between the two sides move across the cut in the sheet's
// plane (the collision triangles' plane, z = 0 here), never through its
// thickness, by at most the amplitude; the cut stays valid.
TEST(JaggedCutSurface, RowsMoveAcrossTheCutInTheTissuesPlaneByAtMostTheAmplitude)
{
  const double amplitude = 0.4;
  const TissueCutter smooth = cutSheet(0.0), jagged = cutSheet(amplitude, 7u, 2);
  const TissueCutter smoothTwoRows = cutSheet(0.0, 7u, 2);
  ASSERT_EQ(jagged.visual().mesh().vertexCount(), smoothTwoRows.visual().mesh().vertexCount());
  EXPECT_TRUE(cutterIsConsistent(jagged, boundSheet().sheet.simulation));
  double largest = 0.0;
  int moved = 0;
  for (std::size_t v = 0; v < jagged.visual().mesh().vertexCount(); ++v)
  {
    const Vector3 d =
      jagged.visual().mesh().positions[v] - smoothTwoRows.visual().mesh().positions[v];
    EXPECT_LT(std::abs(d.z()), 1e-9) << "vertex " << v;
    EXPECT_LT(std::abs(d.y()), 1e-9) << "vertex " << v; // the cut runs along y
    largest = std::max(largest, d.norm());
    moved += d.norm() > 1e-3;
  }
  EXPECT_LE(largest, amplitude + 1e-12);
  EXPECT_GT(largest, 0.3 * amplitude);
  EXPECT_GT(moved, 20);
  const CutSurfaceRoughness roughness = jagged.cutRimRoughness();
  EXPECT_NEAR(roughness.maximum, largest, 1e-9);
  EXPECT_GT(roughness.rootMeanSquare, 0.1 * amplitude);
  EXPECT_EQ(smoothTwoRows.cutRimRoughness().vertices, roughness.vertices);
  EXPECT_LT(smooth.cutRimRoughness().vertices, roughness.vertices);
}

TEST(JaggedCutSurface, TheSameSeedGivesTheSameRimAndAnotherSeedAnother)
{
  const TissueCutter first = cutSheet(0.3, 11u), again = cutSheet(0.3, 11u),
                     other = cutSheet(0.3, 12u);
  EXPECT_EQ(first.visual().mesh().positions, again.visual().mesh().positions);
  EXPECT_NE(first.visual().mesh().positions, other.visual().mesh().positions);
}

// Both lips of a cut are jagged alike: the pieces fit (before the fix they
// were jagged in opposite directions, so material appeared or vanished
// between them).
TEST(JaggedCutSurface, TheTwoLipsOfACutFitEachOther)
{
  const TissueCutter cutter = cutSheet(0.4);
  const double uncut = enclosedVolume(boundSheet().binding.visual);
  EXPECT_NEAR(enclosedVolume(cutter.visual().mesh()), uncut, 1e-9 * uncut);
}

TEST(JaggedCutSurface, ContouringSmoothsAroundTheTouchAndMovesNothingElse)
{
  TissueCutter cutter = cutSheet(0.4);
  const std::vector<Vector3> before = cutter.visual().mesh().positions;
  const std::size_t triangles = cutter.collision().triangleCount();
  const double roughness = cutter.cutRimRoughness().rootMeanSquare;
  const std::vector<int> rim = cutSurfaceVertices(cutter.visual());

  // Far from the cut: nothing moves. Strength 0: nothing moves.
  EXPECT_TRUE(cutter.contour(Vector3(-30.0, 0.0, 0.0), 3.0, 1.0).movedVertices.empty());
  EXPECT_TRUE(cutter.contour(Vector3(3.0, 0.0, 0.0), 3.0, 0.0).movedVertices.empty());
  EXPECT_EQ(cutter.visual().mesh().positions, before);

  // On the rim: the cut surface around the touch moves toward the smooth
  // cut, the rest stays; the rim gets smoother, nothing is removed.
  const CutRimContourReport pass = cutter.contour(Vector3(3.0, 0.0, 0.0), 4.0, 0.5);
  ASSERT_FALSE(pass.movedVertices.empty());
  for (int v : pass.movedVertices)
  {
    EXPECT_TRUE(std::binary_search(rim.begin(), rim.end(), v)) << "vertex " << v;
    // (Within the radius, give or take a visual edge: the rim's paths
    // bend around the straight collision edge.)
    EXPECT_LT(std::abs(cutter.visual().mesh().positions[v].y()), 4.5);
  }
  std::vector<int> moved = pass.movedVertices;
  std::sort(moved.begin(), moved.end());
  for (std::size_t v = 0; v < before.size(); ++v)
  {
    if (!std::binary_search(moved.begin(), moved.end(), static_cast<int>(v)))
    {
      EXPECT_EQ(cutter.visual().mesh().positions[v], before[v]) << "vertex " << v;
    }
  }
  EXPECT_LT(cutter.cutRimRoughness().rootMeanSquare, roughness);
  EXPECT_EQ(cutter.collision().triangleCount(), triangles);
  EXPECT_TRUE(cutterIsConsistent(cutter, boundSheet().sheet.simulation));
  // The moved vertices keep their embedding: mapped at rest, they are where
  // they were moved.
  const std::vector<Vector3> mapped = cutter.currentVisualPositions();
  for (int v : pass.movedVertices)
    EXPECT_LT((mapped[v] - cutter.visual().mesh().positions[v]).norm(), 1e-9);

  // Drawn along the whole rim three times at full strength: smooth.
  const BoundingBox box = boundSheet().binding.visual.boundingBox();
  for (int sweep = 0; sweep < 3; ++sweep)
    for (double y = box.min().y() - 2.0; y <= box.max().y() + 2.0; y += 2.0)
      cutter.contour(Vector3(3.0, y, 0.0), 4.0, 1.0);
  EXPECT_LT(cutter.cutRimRoughness().maximum, 1e-3);
}

TEST(JaggedCutSurface, BadSettingsAndToolsAreRefused)
{
  TissueCutterSettings settings;
  settings.visual.jaggedAmplitude = -0.1;
  EXPECT_THROW(TissueCutter(boundSheet().binding, boundSheet().sheet.simulation, nullptr, settings),
    InvalidInputError);
  settings.visual.jaggedAmplitude = 0.1;
  settings.visual.jaggedWavelength = 0.0;
  EXPECT_THROW(TissueCutter(boundSheet().binding, boundSheet().sheet.simulation, nullptr, settings),
    InvalidInputError);
  TissueCutter cutter = cutSheet(0.3);
  const std::vector<Vector3> before = cutter.visual().mesh().positions;
  EXPECT_THROW(cutter.contour(Vector3(3.0, 0.0, std::nan("")), 3.0, 1.0), InvalidInputError);
  EXPECT_THROW(cutter.contour(Vector3(3.0, 0.0, 0.0), 0.0, 1.0), InvalidInputError);
  EXPECT_THROW(cutter.contour(Vector3(3.0, 0.0, 0.0), 3.0, 1.5), InvalidInputError);
  EXPECT_EQ(cutter.visual().mesh().positions, before);
}

// A settings panel's change between cuts (issue 17's live settings): the
// next cut's surface is jagged, the earlier one stays as it was; changes
// the cutter cannot honour are refused and change nothing.
TEST(JaggedCutSurface, SettingsChangedBetweenCutsApplyToTheCutsToCome)
{
  TissueCutter cutter = cutSheet(0.0);
  ASSERT_LT(cutter.cutRimRoughness().maximum, 1e-9);
  const std::vector<Vector3> smoothCut = cutter.visual().mesh().positions;

  TissueCutterSettings jagged = cutter.settings();
  jagged.visual.jaggedAmplitude = 0.4;
  jagged.visual.jaggedSeed = 5u;
  cutter.setSettings(jagged);
  EXPECT_EQ(cutter.visual().settings().jaggedAmplitude, 0.4);
  const Vector3 up(0.0, 0.0, 10.0);
  const TissueCutReport second = cutter.cut(Blade::sweptSegment(Vector3(-15.0, -70.0, 0.0) - up,
    Vector3(-15.0, -70.0, 0.0) + up,
    Vector3(-15.0, 70.0, 0.0) - up,
    Vector3(-15.0, 70.0, 0.0) + up));
  ASSERT_TRUE(second.changed());
  EXPECT_GT(cutter.cutRimRoughness().maximum, 0.05);
  EXPECT_TRUE(cutterIsConsistent(cutter, boundSheet().sheet.simulation));
  // The first cut's surface (its vertices at x = 3) did not move.
  for (std::size_t v = 0; v < smoothCut.size(); ++v)
    if (std::abs(smoothCut[v].x() - 3.0) < 1.0)
    {
      EXPECT_EQ(cutter.visual().mesh().positions[v], smoothCut[v]) << "vertex " << v;
    }

  const std::vector<Vector3> before = cutter.visual().mesh().positions;
  TissueCutterSettings bad = cutter.settings();
  bad.visual.cutSurfaceRows = 3; // the cut surfaces have 1 row
  EXPECT_THROW(cutter.setSettings(bad), InvalidInputError);
  bad = cutter.settings();
  bad.visual.jaggedWavelength = -1.0;
  EXPECT_THROW(cutter.setSettings(bad), InvalidInputError);
  bad = cutter.settings();
  bad.fragmentAreaFraction = 1.5;
  EXPECT_THROW(cutter.setSettings(bad), InvalidInputError);
  bad = cutter.settings();
  bad.collision.snapFraction = 0.5;
  EXPECT_THROW(cutter.setSettings(bad), InvalidInputError);
  bad = cutter.settings();
  bad.radiusArrayName = "Thickness";
  EXPECT_THROW(cutter.setSettings(bad), InvalidInputError);
  EXPECT_EQ(cutter.settings().visual.jaggedAmplitude, 0.4);
  EXPECT_EQ(cutter.settings().visual.cutSurfaceRows, 1);
  EXPECT_EQ(cutter.visual().mesh().positions, before);

  // Before any cut, the row count may change.
  TissueCutter uncut(boundSheet().binding, boundSheet().sheet.simulation);
  TissueCutterSettings rows = uncut.settings();
  rows.visual.cutSurfaceRows = 3;
  uncut.setSettings(rows);
  EXPECT_EQ(uncut.visual().settings().cutSurfaceRows, 3);
}
