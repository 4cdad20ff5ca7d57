// The medial meniscus of thesis sections 4.3 and 6.4: intact and torn.
#include "MeniscusModel.h"
#include "ThinTissueError.h"
#include "TissueModelChecks.h"

#include <gtest/gtest.h>

#include <functional>

using namespace thintissue;
using namespace thintissue::testing;

namespace
{
MeniscusParameters withTear(MeniscusTearType type)
{
  MeniscusParameters p;
  p.tear = defaultMeniscusTear(type);
  return p;
}

const MeniscusModel& intactMeniscus()
{
  static const MeniscusModel model = makeMeniscus();
  return model;
}

/// Model-space points on the two lips of a tear (side -1, side +1), taken
/// where the tear is widest and on a hexahedron line so that every mesh has
/// vertices there.
struct Lips
{
  Vector3 negative, positive;
};

Lips lipsAt(const ParametricSolid& solid, std::size_t crack, const ParameterPoint& p)
{
  std::vector<int> sides(solid.cracks().size(), 0);
  sides[crack] = -1;
  const Vector3 negative = solid.openedPoint(p, sides);
  sides[crack] = 1;
  return { negative, solid.openedPoint(p, sides) };
}

/// Points along every tear front (the inner ends of each crack's ranges).
std::vector<Vector3> tearFrontPoints(const ParametricSolid& solid)
{
  std::vector<Vector3> points;
  for (const auto& crack : solid.cracks())
  {
    const int axes[2] = { crack.normalAxis == 0 ? 1 : 0, crack.normalAxis == 2 ? 1 : 2 };
    for (int r = 0; r < 2; ++r)
    {
      for (double end : crack.ranges[r])
      {
        if (end <= 0.0 || end >= 1.0)
        {
          continue; // a mouth, not a front
        }
        const auto& other = crack.ranges[1 - r];
        for (int k = 0; k <= 100; ++k)
        {
          ParameterPoint p;
          p[crack.normalAxis] = crack.position;
          p[axes[r]] = end;
          p[axes[1 - r]] = other[0] + (other[1] - other[0]) * k / 100.0;
          points.push_back(solid.point(p));
        }
      }
    }
  }
  return points;
}

/// A grid line along s inside (begin, end), nearest to its middle.
double lineInside(const std::vector<double>& lines, double begin, double end)
{
  double best = -1.0;
  for (double line : lines)
  {
    if (line > begin && line < end &&
        (best < 0.0 || std::abs(line - 0.5 * (begin + end)) < std::abs(best - 0.5 * (begin + end))))
    {
      best = line;
    }
  }
  return best;
}

/// The lips of crack `crack` are close in space but far apart along each
/// mesh. `lip(s)` gives the parameter point on the crack at s, checked at
/// a collision line (visual and collision meshes) and at a hexahedron line.
void expectSeparated(const MeniscusModel& model,
  const ParametricSolid& solid,
  const MeniscusParameters& p,
  std::size_t crack,
  const std::function<ParameterPoint(double s)>& lip,
  double begin,
  double end,
  const std::string& where)
{
  SCOPED_TRACE(where);
  auto check = [&](const std::vector<Vector3>& points,
                 const std::vector<std::vector<int>>& neighbours,
                 const ParameterPoint& at,
                 const char* mesh)
  {
    const Lips lips = lipsAt(solid, crack, at);
    const double gap = (lips.positive - lips.negative).norm();
    EXPECT_GT(gap, 0.1) << mesh;
    EXPECT_LT(gap, 1.0) << mesh;
    EXPECT_GT(pathLengthBetween(points, neighbours, lips.negative, lips.positive), 4.0 + 3.0 * gap)
      << mesh;
  };
  const double collisionLine =
    end > begin ? lineInside(solid.gridLines(0, p.collisionAlong), begin, end) : begin;
  const double hexahedronLine =
    end > begin ? lineInside(solid.gridLines(0, p.hexahedraAlong), begin, end) : begin;
  check(model.visual.positions, triangleMeshNeighbours(model.visual), lip(collisionLine), "visual");
  check(model.collision.positions,
    triangleMeshNeighbours(model.collision),
    lip(collisionLine),
    "collision");
  ParameterPoint atNode = lip(hexahedronLine);
  if (solid.cracks()[crack].normalAxis != 2)
  {
    atNode[2] = 0.0; // hexahedron nodes lie on the lower and upper surfaces
  }
  check(model.simulation.nodes, hexahedralMeshNeighbours(model.simulation), atNode, "hexahedra");
}
} // namespace

TEST(MeniscusModel, IntactCountsMatchSection642)
{
  const auto& m = intactMeniscus();
  EXPECT_TRUE(isWithinFraction(m.visual.vertexCount(), 2882, 0.05));
  EXPECT_TRUE(isWithinFraction(m.visual.triangleCount(), 5760, 0.05));
  EXPECT_EQ(m.collision.vertexCount(), 105u);
  EXPECT_EQ(m.collision.triangleCount(), 160u);
  EXPECT_EQ(m.simulation.hexahedronCount(), 42u);
  EXPECT_EQ(m.simulation.nodeCount(), 120u);
  const auto examination = makeMeniscus(examinationMeniscusParameters());
  EXPECT_TRUE(isWithinFraction(examination.visual.triangleCount(), 6096, 0.05));
}

TEST(MeniscusModel, IsAnAnatomicalClosedWedge)
{
  const auto& m = intactMeniscus();
  EXPECT_TRUE(isClosedOutwardSurface(m.visual));
  EXPECT_EQ(m.visual.normals.size(), m.visual.vertexCount());
  EXPECT_EQ(m.visual.textureCorners.size(), m.visual.triangleCount());
  const Vector3 size = m.visual.boundingBox().sizes();
  EXPECT_GT(size.x(), 20.0); // medial-lateral
  EXPECT_LT(size.x(), 35.0);
  EXPECT_GT(size.y(), 35.0); // anterior-posterior
  EXPECT_LT(size.y(), 50.0);
  EXPECT_GE(size.z(), 6.0); // rim
  EXPECT_LE(size.z(), 8.0);
  EXPECT_LT(thicknessToExtentRatio(m.visual), 0.2);
  // Thin inner edge, thick rim: the wedge cross-section.
  const auto solid = makeMeniscusSolid(MeniscusParameters{});
  EXPECT_NEAR(solid.thickness(0.5, 0.0), 1.0, 1e-9);
  EXPECT_NEAR(solid.thickness(0.5, 1.0), 7.0, 1e-9);
  // The C opens laterally (+x): no material on the lateral axis.
  EXPECT_LT(windingNumber(m.visual, Vector3(-22.0 + 12.0, 0.0, 3.0)), 0.5);
  EXPECT_GT(windingNumber(m.visual, solid.point(ParameterPoint(0.5, 0.5, 0.5))), 0.5);
}

TEST(MeniscusModel, CollisionMidSurfaceIsInsideWithHalfThicknessRadii)
{
  const auto& m = intactMeniscus();
  EXPECT_TRUE(isInsideVolume(m.collision, m.visual));
  // Thickness measured vertically: the wedge rests on the plateau.
  EXPECT_TRUE(radiiMatchHalfThickness(m.collision,
    m.collisionRadii(),
    m.visual,
    0.10,
    {},
    [](std::size_t) { return Vector3::UnitZ(); }));
}

TEST(MeniscusModel, HexahedraCoverTheTissueAndFixTheHorns)
{
  const auto& m = intactMeniscus();
  EXPECT_TRUE(isCoveredByHexahedra(m.collision.positions, m.simulation));
  EXPECT_TRUE(isCoveredByHexahedra(m.visual.positions, m.simulation));
  EXPECT_EQ(m.simulation.fixedNodeCount(), 16u); // the two horn end faces
}

TEST(MeniscusModel, MonitorAndRegionDataPointsFollowTheInnerBorder)
{
  const auto& m = intactMeniscus();
  ASSERT_EQ(m.monitorCurves.size(), 1u);
  const auto& curve = m.monitorCurves[0];
  ASSERT_GE(curve.monitorPoints.size(), 8u);
  ASSERT_EQ(curve.regionPoints.size(), curve.monitorPoints.size());
  ASSERT_EQ(curve.thickness.size(), curve.monitorPoints.size());
  for (std::size_t k = 0; k < curve.monitorPoints.size(); ++k)
  {
    EXPECT_GT(windingNumber(m.visual, curve.monitorPoints[k]), 0.5) << "monitor point " << k;
    EXPECT_GT(windingNumber(m.visual, curve.regionPoints[k]), 0.5) << "region point " << k;
    // The thickness sample is the real thickness there (vertical rays).
    const double measured = thicknessAlong(m.visual, curve.monitorPoints[k], Vector3::UnitZ());
    EXPECT_NEAR(curve.thickness[k], measured, 0.1 * measured) << "monitor point " << k;
    // Region points lie deeper, where the wedge is thicker, about 4 mm in.
    EXPECT_GT(
      thicknessAlong(m.visual, curve.regionPoints[k], Vector3::UnitZ()), curve.thickness[k]);
    EXPECT_NEAR((curve.regionPoints[k] - curve.monitorPoints[k]).norm(), 4.0, 1.0);
  }
  const auto dense = sampleMonitorCurves(MeniscusParameters{}, m.monitorCurves, 0.2);
  ASSERT_EQ(dense.size(), 1u);
  EXPECT_GT(dense[0].monitorPoints.size(), 200u);
  for (std::size_t k = 1; k < dense[0].monitorPoints.size(); ++k)
  {
    EXPECT_LE((dense[0].monitorPoints[k] - dense[0].monitorPoints[k - 1]).norm(), 0.2);
  }
}

TEST(MeniscusModel, EveryTearIsInAllThreeMeshes)
{
  for (auto type : { MeniscusTearType::Longitudinal,
         MeniscusTearType::Radial,
         MeniscusTearType::Flap,
         MeniscusTearType::HorizontalCleavage })
  {
    SCOPED_TRACE(meniscusTearTypeName(type));
    const auto p = withTear(type);
    const auto m = makeMeniscus(p);
    const auto solid = makeMeniscusSolid(p);
    EXPECT_TRUE(isClosedOutwardSurface(m.visual));
    EXPECT_TRUE(isInsideVolume(m.collision, m.visual));
    // The lips of the coarse hexahedra are chords of the curved C: a lip
    // vertex may lie up to their sagitta outside, where the embedding takes
    // the nearest hexahedron (4.3).
    EXPECT_TRUE(isNearHexahedra(m.collision.positions, m.simulation, 0.35));
    // Each piece's (and each leaf's) radius is half its own thickness;
    // exactly at a tear front (where the pieces join) thickness is ill-posed.
    const auto fronts = tearFrontPoints(solid);
    EXPECT_TRUE(radiiMatchHalfThickness(
      m.collision,
      m.collisionRadii(),
      m.visual,
      0.10,
      [&](std::size_t v)
      {
        for (const auto& front : fronts)
        {
          if ((m.collision.positions[v] - front).norm() < 0.3)
          {
            return false;
          }
        }
        return true;
      },
      [](std::size_t) { return Vector3::UnitZ(); }));
    const auto& tear = p.tear;
    const double across = tear.across;
    switch (type)
    {
      case MeniscusTearType::Longitudinal:
        expectSeparated(
          m,
          solid,
          p,
          0,
          [&](double s) { return ParameterPoint(s, across, 0.5); },
          tear.alongBegin,
          tear.alongEnd,
          "bucket handle");
        ASSERT_EQ(m.monitorCurves.size(), 2u);
        break;
      case MeniscusTearType::Radial:
        expectSeparated(
          m,
          solid,
          p,
          0,
          [&](double s) { return ParameterPoint(s, 0.0, 0.5); },
          tear.alongBegin,
          tear.alongBegin,
          "radial");
        ASSERT_EQ(m.monitorCurves.size(), 2u);
        break;
      case MeniscusTearType::Flap:
        expectSeparated(
          m,
          solid,
          p,
          0,
          [&](double s) { return ParameterPoint(s, 0.0, 0.5); },
          tear.alongBegin,
          tear.alongBegin,
          "flap, radial part");
        expectSeparated(
          m,
          solid,
          p,
          1,
          [&](double s) { return ParameterPoint(s, across, 0.5); },
          tear.alongBegin,
          tear.alongEnd,
          "flap, longitudinal part");
        ASSERT_EQ(m.monitorCurves.size(), 3u);
        break;
      case MeniscusTearType::HorizontalCleavage:
        expectSeparated(
          m,
          solid,
          p,
          0,
          [&](double s) { return ParameterPoint(s, 0.0, 0.5); },
          tear.alongBegin,
          tear.alongEnd,
          "cleavage");
        ASSERT_EQ(m.monitorCurves.size(), 4u);
        break;
      case MeniscusTearType::None:
        break;
    }
    for (const auto& curve : m.monitorCurves)
    {
      for (const auto& point : curve.monitorPoints)
      {
        EXPECT_GT(windingNumber(m.visual, point), 0.5) << curve.name;
      }
    }
  }
}

TEST(MeniscusModel, IntactMeniscusIsNotSeparated)
{
  // The control for the tear test: without a tear the same two points are
  // joined by a short path.
  const auto& m = intactMeniscus();
  const auto solid = makeMeniscusSolid(MeniscusParameters{});
  const Vector3 a = solid.point(ParameterPoint(0.5, 0.45, 0.0));
  const Vector3 b = solid.point(ParameterPoint(0.5, 0.55, 0.0));
  EXPECT_LT(pathLengthBetween(m.visual.positions, triangleMeshNeighbours(m.visual), a, b),
    3.0 * (b - a).norm() + 1.0);
}

TEST(MeniscusModel, IsDeterministic)
{
  const auto a = makeMeniscus(withTear(MeniscusTearType::Flap));
  const auto b = makeMeniscus(withTear(MeniscusTearType::Flap));
  EXPECT_EQ(a.visual.positions, b.visual.positions);
  EXPECT_EQ(a.collision.triangles, b.collision.triangles);
  EXPECT_EQ(a.simulation.nodes, b.simulation.nodes);
}

TEST(MeniscusModel, BadParametersAreNamed)
{
  auto expectError = [](MeniscusParameters p, const std::string& word)
  {
    try
    {
      makeMeniscus(p);
      ADD_FAILURE() << "no error for bad " << word;
    }
    catch (const InvalidInputError& error)
    {
      EXPECT_NE(std::string(error.what()).find(word), std::string::npos) << error.what();
    }
  };
  MeniscusParameters p;
  p.rimHeight = 0.0;
  expectError(p, "rim height");
  p = {};
  p.outerSemiAxisY = -1.0;
  expectError(p, "outer semi-axis");
  p = {};
  p.innerSemiAxisX = 14.0;
  expectError(p, "inner edge ellipse");
  p = {};
  p.innerEdgeHeight = 8.0;
  expectError(p, "thinner");
  p = {};
  p.visualAlong = 3;
  expectError(p, "visual cells");
  p = {};
  p.hexahedraAcross = 0;
  expectError(p, "hexahedra");
  p = withTear(MeniscusTearType::Longitudinal);
  p.tear.alongEnd = 1.5;
  expectError(p, "tear");
  p = withTear(MeniscusTearType::Radial);
  p.tear.across = 0.0;
  expectError(p, "tear");
  EXPECT_THROW(meniscusTearTypeFromName("bucket"), InvalidInputError);
  EXPECT_EQ(meniscusTearTypeFromName("flap"), MeniscusTearType::Flap);
}
