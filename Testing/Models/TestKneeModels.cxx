// Knee surroundings (issue "Knee surroundings"): bones of table 6-2,
// medial tibial cartilage of 5.4.4, ACL and PCL of table 5-7, and how they
// fit together with the medial meniscus in the frame of KneeAnatomy.h.
#include "KneeAnatomy.h"
#include "KneeModels.h"
#include "MeniscusModel.h"
#include "MeshQueries.h"
#include "ThinTissueError.h"
#include "TissueModelChecks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace
{

using namespace thintissue;
using thintissue::testing::isClosedOutwardSurface;
using thintissue::testing::isCoveredByHexahedra;
using thintissue::testing::isInsideVolume;
using thintissue::testing::isWithinFraction;
using thintissue::testing::radiiMatchHalfThickness;
using thintissue::testing::thicknessToExtentRatio;

constexpr double CountTolerance = 0.05;

/// The default scene, built once for all tests.
const KneeSurroundings& scene()
{
  static const KneeSurroundings knee = makeKneeSurroundings();
  return knee;
}

const MeniscusModel& meniscus()
{
  static const MeniscusModel model = makeMeniscus();
  return model;
}

bool isInside(const TriangleMesh& closedSurface, const Vector3& point)
{
  return windingNumber(closedSurface, point) > 0.5;
}

/// Every `stride`-th vertex of `mesh` for which `allowed` does not hold lies
/// outside `solid`.
::testing::AssertionResult sampledVerticesOutside(const TriangleMesh& mesh,
  const TriangleMesh& solid,
  std::size_t stride,
  const std::function<bool(const Vector3&)>& allowed = {})
{
  for (std::size_t v = 0; v < mesh.vertexCount(); v += stride)
  {
    const Vector3& x = mesh.positions[v];
    if ((!allowed || !allowed(x)) && isInside(solid, x))
    {
      return ::testing::AssertionFailure() << "vertex " << v << " of '" << mesh.name << "' at ("
                                           << x.transpose() << ") is inside '" << solid.name << "'";
    }
  }
  return ::testing::AssertionSuccess();
}

/// Whether a vertex is off the border of an open surface (the border of a
/// mid-surface lies on the visual surface, where the thickness along the
/// normal is not defined).
std::function<bool(std::size_t)> isInteriorVertex(const TriangleMesh& mesh)
{
  std::map<std::pair<int, int>, int> edgeUses;
  for (const auto& t : mesh.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      ++edgeUses[std::minmax(t[k], t[(k + 1) % 3])];
    }
  }
  auto border = std::make_shared<std::vector<bool>>(mesh.vertexCount(), false);
  for (const auto& [edge, uses] : edgeUses)
  {
    if (uses == 1)
    {
      (*border)[edge.first] = true;
      (*border)[edge.second] = true;
    }
  }
  return [border](std::size_t v) { return !(*border)[v]; };
}

/// Height of the first surface met by a vertical ray at (x, y), from above
/// (downward) or from below (upward).
double verticalHit(const TriangleMesh& mesh, double x, double y, bool fromAbove)
{
  const double start = fromAbove ? 200.0 : -200.0;
  const auto hits = rayHits(mesh, Vector3(x, y, start), Vector3(0.0, 0.0, fromAbove ? -1.0 : 1.0));
  if (hits.empty())
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return fromAbove ? start - hits.front() : start + hits.front();
}

// ---------------------------------------------------------------------------
// Bones (thesis table 6-2).

TEST(KneeBones, AreClosedOutwardSurfaces)
{
  const auto& knee = scene();
  for (const BoneModel* bone : { &knee.tibia, &knee.femur })
  {
    SCOPED_TRACE(bone->name);
    EXPECT_TRUE(isClosedOutwardSurface(bone->visual));
    EXPECT_TRUE(isClosedOutwardSurface(bone->collision));
    EXPECT_EQ(bone->visual.normals.size(), bone->visual.vertexCount());
  }
}

TEST(KneeBones, VertexCountsMatchTable6_2)
{
  const auto& knee = scene();
  // Lower bone 2,206 and upper bone 5,850 visual vertices; reduced collision
  // meshes of 63 and 59 vertices.
  EXPECT_TRUE(isWithinFraction(knee.tibia.visual.vertexCount(), 2206, CountTolerance));
  EXPECT_TRUE(isWithinFraction(knee.femur.visual.vertexCount(), 5850, CountTolerance));
  EXPECT_TRUE(isWithinFraction(knee.tibia.collision.vertexCount(), 63, CountTolerance));
  EXPECT_TRUE(isWithinFraction(knee.femur.collision.vertexCount(), 59, CountTolerance));
}

TEST(KneeBones, CollisionVerticesLieOnTheVisualSurface)
{
  const auto& knee = scene();
  for (const BoneModel* bone : { &knee.tibia, &knee.femur })
  {
    SCOPED_TRACE(bone->name);
    double farthest = 0.0;
    for (const Vector3& x : bone->collision.positions)
    {
      farthest = std::max(farthest, distanceToSurface(bone->visual, x));
    }
    EXPECT_LT(farthest, 1.0);
  }
}

TEST(KneeBones, TibiaHasThePlateauOfTheAnatomicalFrame)
{
  const TriangleMesh& tibia = scene().tibia.visual;
  for (const Vector3& centre :
    { knee::medialCompartmentCentre(), knee::lateralCompartmentCentre() })
  {
    EXPECT_NEAR(verticalHit(tibia, centre.x(), centre.y(), true), 0.0, 0.2)
      << "at (" << centre.transpose() << ")";
  }
  const Vector3 size = tibia.boundingBox().sizes();
  EXPECT_NEAR(size.x(), 75.0, 5.0);
  EXPECT_NEAR(size.y(), 50.0, 5.0);
  EXPECT_GE(size.z(), 60.0);
  EXPECT_LE(size.z(), 80.0);
  // The medial compartment is concave, the lateral one convex, the spines
  // stand above both.
  const double medialRim = verticalHit(tibia, -32.0, 0.0, true);
  const double lateralRim = verticalHit(tibia, 32.0, 0.0, true);
  EXPECT_GT(medialRim, 0.2);
  EXPECT_LT(lateralRim, -0.2);
  EXPECT_GT(verticalHit(tibia, -4.5, -1.5, true), 3.0);
  EXPECT_GT(verticalHit(tibia, 4.5, -3.5, true), 2.5);
}

TEST(KneeBones, FemurRestsOnTheCompartmentsAboveTheTibia)
{
  const auto& knee = scene();
  const double expected = knee::TibialCartilageThickness + knee::DefaultJointGap;
  EXPECT_DOUBLE_EQ(femoralArticularHeight(knee::DefaultJointGap), expected);
  for (const Vector3& centre :
    { knee::medialCompartmentCentre(), knee::lateralCompartmentCentre() })
  {
    EXPECT_NEAR(verticalHit(knee.femur.visual, centre.x(), centre.y(), false), expected, 0.2)
      << "at (" << centre.transpose() << ")";
  }
  // The notch: a vertical ray at x = 0 meets the femur far above the
  // condyles' lowest points.
  EXPECT_GT(verticalHit(knee.femur.visual, 0.0, -5.0, false), expected + 12.0);
  EXPECT_TRUE(sampledVerticesOutside(knee.femur.visual, knee.tibia.visual, 7));
  EXPECT_TRUE(sampledVerticesOutside(knee.tibia.visual, knee.femur.visual, 3));
}

TEST(KneeBones, DoNotIntersectTheMeniscus)
{
  const auto& knee = scene();
  EXPECT_TRUE(sampledVerticesOutside(meniscus().visual, knee.tibia.visual, 3));
  EXPECT_TRUE(sampledVerticesOutside(meniscus().visual, knee.femur.visual, 3));
}

TEST(KneeBones, FemurFollowsTheJointGap)
{
  KneeSurroundingsParameters parameters;
  parameters.jointGap = 7.0;
  parameters.femurVisualVertices = 1500;
  const BoneModel femur = makeFemur(parameters);
  const Vector3 centre = knee::medialCompartmentCentre();
  EXPECT_NEAR(
    verticalHit(femur.visual, centre.x(), centre.y(), false), femoralArticularHeight(7.0), 0.3);
  EXPECT_TRUE(isClosedOutwardSurface(femur.visual));
  EXPECT_TRUE(isWithinFraction(femur.visual.vertexCount(), 1500, CountTolerance));
}

// ---------------------------------------------------------------------------
// Medial tibial cartilage (thesis 5.4.4).

TEST(KneeCartilage, VisualIsAThinClosedLayerOf5062Triangles)
{
  const TissueModel& cartilage = scene().tibialCartilage;
  EXPECT_TRUE(isClosedOutwardSurface(cartilage.visual));
  EXPECT_TRUE(cartilage.visual.hasTextureCoordinates());
  EXPECT_TRUE(isWithinFraction(cartilage.visual.triangleCount(), 5062, CountTolerance));
  EXPECT_LT(thicknessToExtentRatio(cartilage.visual), 0.15);
}

TEST(KneeCartilage, CollisionSettingsMatchTheThesis)
{
  const KneeSurroundingsParameters parameters;
  const TissueModel& cartilage = scene().tibialCartilage;
  const struct
  {
    CartilageCollisionSetting setting;
    double triangles;
  } settings[] = { { CartilageCollisionSetting::Triangles1000, 1000 },
    { CartilageCollisionSetting::Triangles500, 500 },
    { CartilageCollisionSetting::Triangles100, 100 } };
  for (const auto& expected : settings)
  {
    SCOPED_TRACE(expected.triangles);
    const TriangleMesh mesh = tibialCartilageCollisionMesh(parameters, expected.setting);
    EXPECT_TRUE(isWithinFraction(mesh.triangleCount(), expected.triangles, CountTolerance));
    ASSERT_TRUE(mesh.pointAttributes.has(CollisionRadiusArrayName));
    const auto& radii = mesh.pointAttributes.get(CollisionRadiusArrayName).values;
    EXPECT_TRUE(isInsideVolume(mesh, cartilage.visual));
    EXPECT_TRUE(
      radiiMatchHalfThickness(mesh, radii, cartilage.visual, 0.10, isInteriorVertex(mesh)));
    EXPECT_TRUE(isCoveredByHexahedra(mesh.positions, cartilage.simulation));
  }
  // Setting 1: the visual mesh itself, with zero radii.
  const TriangleMesh visual =
    tibialCartilageCollisionMesh(parameters, CartilageCollisionSetting::VisualMesh);
  EXPECT_EQ(visual.triangleCount(), cartilage.visual.triangleCount());
  EXPECT_TRUE(isClosedOutwardSurface(visual));
  // The scene keeps the 100-triangle mid-surface.
  EXPECT_EQ(cartilage.collision.triangleCount(), 100u);
  EXPECT_EQ(cartilage.collisionRadii().size(), cartilage.collision.vertexCount());
}

TEST(KneeCartilage, IsFixedOnTheBoneSide)
{
  const HexahedralMesh& hexahedra = scene().tibialCartilage.simulation;
  ASSERT_GT(hexahedra.hexahedronCount(), 0u);
  ASSERT_EQ(hexahedra.fixedNodes.size(), hexahedra.nodeCount());
  // Local z of the hexahedra runs through the thickness: corners 0-3 lie on
  // the bone, 4-7 on the joint side.
  for (const auto& hexahedron : hexahedra.hexahedra)
  {
    for (int k = 0; k < 8; ++k)
    {
      EXPECT_EQ(hexahedra.isFixed(hexahedron[k]), k < 4);
      if (k < 4)
      {
        EXPECT_LT(hexahedra.nodes[hexahedron[k]].z(), hexahedra.nodes[hexahedron[k + 4]].z());
      }
    }
  }
}

TEST(KneeCartilage, LiesOnTheTibiaUnderTheMeniscus)
{
  const auto& knee = scene();
  const TriangleMesh& cartilage = knee.tibialCartilage.visual;
  // On the bone: no vertex inside the tibia, the lower side close to it.
  EXPECT_TRUE(sampledVerticesOutside(cartilage, knee.tibia.visual, 3));
  double farthestBelow = 0.0;
  for (std::size_t v = 0; v < cartilage.vertexCount(); v += 5)
  {
    const Vector3& x = cartilage.positions[v];
    if (cartilage.normals[v].z() < -0.9)
    {
      farthestBelow = std::max(farthestBelow, distanceToSurface(knee.tibia.visual, x));
    }
  }
  EXPECT_GT(farthestBelow, 0.0);
  EXPECT_LT(farthestBelow, 0.35);
  // Under the meniscus: the joint surface stays below its base, about
  // TibialCartilageThickness at the compartment centre.
  EXPECT_LE(cartilage.boundingBox().max().z(), knee::MeniscusBaseHeight + 1e-9);
  const Vector3 centre = knee::medialCompartmentCentre();
  EXPECT_NEAR(
    verticalHit(cartilage, centre.x(), centre.y(), true), knee::TibialCartilageThickness, 0.05);
  EXPECT_TRUE(sampledVerticesOutside(meniscus().visual, cartilage, 3));
}

// ---------------------------------------------------------------------------
// Cruciate ligaments (thesis 5.4.3, table 5-7).

struct LigamentCase
{
  CruciateLigament ligament;
  double visualVertices, visualTriangles;
  double vertices2000, triangles2000;
  double vertices500, triangles500;
  std::size_t reducedVertices, reducedTriangles;
};

const LigamentCase ligamentCases[] = {
  { CruciateLigament::Anterior, 5702, 12064, 1012, 2001, 252, 500, 25, 32 },
  { CruciateLigament::Posterior, 5634, 11264, 998, 1999, 249, 499, 45, 64 },
};

const TissueModel& ligamentModel(CruciateLigament ligament)
{
  return ligament == CruciateLigament::Anterior ? scene().anteriorCruciateLigament
                                                : scene().posteriorCruciateLigament;
}

TEST(KneeLigaments, CountsMatchTable5_7)
{
  const KneeSurroundingsParameters parameters;
  for (const auto& expected : ligamentCases)
  {
    SCOPED_TRACE(cruciateLigamentName(expected.ligament));
    const TissueModel& model = ligamentModel(expected.ligament);
    EXPECT_TRUE(
      isWithinFraction(model.visual.vertexCount(), expected.visualVertices, CountTolerance));
    EXPECT_TRUE(
      isWithinFraction(model.visual.triangleCount(), expected.visualTriangles, CountTolerance));
    const TriangleMesh setting2 = cruciateLigamentCollisionMesh(
      expected.ligament, LigamentCollisionSetting::Triangles2000, parameters);
    const TriangleMesh setting3 = cruciateLigamentCollisionMesh(
      expected.ligament, LigamentCollisionSetting::Triangles500, parameters);
    EXPECT_TRUE(setting2.pointAttributes.has(CollisionRadiusArrayName));
    EXPECT_TRUE(isClosedOutwardSurface(setting2));
    EXPECT_TRUE(isClosedOutwardSurface(setting3));
    EXPECT_TRUE(isWithinFraction(setting2.vertexCount(), expected.vertices2000, CountTolerance));
    EXPECT_TRUE(isWithinFraction(setting2.triangleCount(), expected.triangles2000, CountTolerance));
    EXPECT_TRUE(isWithinFraction(setting3.vertexCount(), expected.vertices500, CountTolerance));
    EXPECT_TRUE(isWithinFraction(setting3.triangleCount(), expected.triangles500, CountTolerance));
    // Setting 4, the reduced triangles with radii, is the tissue's collision mesh.
    EXPECT_EQ(model.collision.vertexCount(), expected.reducedVertices);
    EXPECT_EQ(model.collision.triangleCount(), expected.reducedTriangles);
    const TriangleMesh setting4 = cruciateLigamentCollisionMesh(
      expected.ligament, LigamentCollisionSetting::ReducedWithRadii, parameters);
    EXPECT_EQ(setting4.positions, model.collision.positions);
    EXPECT_EQ(cruciateLigamentCollisionMesh(
                expected.ligament, LigamentCollisionSetting::VisualMesh, parameters)
                .triangleCount(),
      model.visual.triangleCount());
  }
}

TEST(KneeLigaments, AreThinBandsWithRadiiInsideTheirVisualSurface)
{
  const KneeSurroundingsParameters parameters;
  for (const auto& expected : ligamentCases)
  {
    SCOPED_TRACE(cruciateLigamentName(expected.ligament));
    const TissueModel& model = ligamentModel(expected.ligament);
    EXPECT_TRUE(isClosedOutwardSurface(model.visual));
    EXPECT_TRUE(model.visual.hasTextureCoordinates());
    const auto& radii = model.collisionRadii();
    ASSERT_EQ(radii.size(), model.collision.vertexCount());
    EXPECT_TRUE(isInsideVolume(model.collision, model.visual));
    EXPECT_TRUE(radiiMatchHalfThickness(
      model.collision, radii, model.visual, 0.10, isInteriorVertex(model.collision)));
    EXPECT_TRUE(isCoveredByHexahedra(model.collision.positions, model.simulation));

    // Thin: thickness and width small against the length between the
    // insertions (ACL about 32 mm, PCL about 38 mm of free length).
    const Vector3 tibial = cruciateLigamentAttachment(expected.ligament, 0.0, parameters);
    const Vector3 femoral = cruciateLigamentAttachment(expected.ligament, 1.0, parameters);
    const double length = (femoral - tibial).norm();
    EXPECT_GT(length, 30.0);
    EXPECT_LT(length, 45.0);
    const double thickness = 2.0 * *std::max_element(radii.begin(), radii.end());
    EXPECT_LT(thickness / length, 0.2);
    const ParametricSolid solid = makeCruciateLigamentSolid(expected.ligament, parameters);
    const double width =
      (solid.point(ParameterPoint(0.5, 1.0, 0.5)) - solid.point(ParameterPoint(0.5, 0.0, 0.5)))
        .norm();
    EXPECT_GT(width, 8.0);
    EXPECT_LT(width, 14.0);
    EXPECT_LT(width / length, 0.5);
  }
  EXPECT_GT((cruciateLigamentAttachment(CruciateLigament::Posterior, 1.0, parameters) -
              cruciateLigamentAttachment(CruciateLigament::Posterior, 0.0, parameters))
              .norm(),
    (cruciateLigamentAttachment(CruciateLigament::Anterior, 1.0, parameters) -
      cruciateLigamentAttachment(CruciateLigament::Anterior, 0.0, parameters))
      .norm());
}

TEST(KneeLigaments, AreAttachedAtBothEnds)
{
  const KneeSurroundingsParameters parameters;
  for (const auto& expected : ligamentCases)
  {
    SCOPED_TRACE(cruciateLigamentName(expected.ligament));
    const HexahedralMesh& hexahedra = ligamentModel(expected.ligament).simulation;
    const ParametricResolution resolution = expected.ligament == CruciateLigament::Anterior
                                              ? parameters.anteriorCruciate.hexahedra
                                              : parameters.posteriorCruciate.hexahedra;
    ASSERT_EQ(hexahedra.fixedNodes.size(), hexahedra.nodeCount());
    const std::size_t perEnd =
      static_cast<std::size_t>(resolution.across + 1) * (resolution.through + 1);
    EXPECT_EQ(hexahedra.fixedNodeCount(), 2 * perEnd);
    // Fixed nodes gather at the insertions, half at each.
    const Vector3 tibial = cruciateLigamentAttachment(expected.ligament, 0.0, parameters);
    const Vector3 femoral = cruciateLigamentAttachment(expected.ligament, 1.0, parameters);
    std::size_t atTibia = 0;
    std::size_t atFemur = 0;
    for (std::size_t n = 0; n < hexahedra.nodeCount(); ++n)
    {
      if (hexahedra.isFixed(n))
      {
        atTibia += (hexahedra.nodes[n] - tibial).norm() < 9.0;
        atFemur += (hexahedra.nodes[n] - femoral).norm() < 9.0;
      }
    }
    EXPECT_EQ(atTibia, perEnd);
    EXPECT_EQ(atFemur, perEnd);
    // The insertions are inside the bones.
    EXPECT_TRUE(isInside(scene().tibia.visual, tibial));
    EXPECT_TRUE(isInside(scene().femur.visual, femoral));
  }
}

TEST(KneeLigaments, CrossInTheNotchWithoutTouching)
{
  const auto& knee = scene();
  const TriangleMesh& anterior = knee.anteriorCruciateLigament.visual;
  const TriangleMesh& posterior = knee.posteriorCruciateLigament.visual;
  EXPECT_TRUE(sampledVerticesOutside(anterior, posterior, 4));
  EXPECT_TRUE(sampledVerticesOutside(posterior, anterior, 4));

  // They cross: seen from the side (x), the ACL runs from anterior-distal to
  // posterior-proximal, the PCL from posterior-distal to anterior-proximal.
  const KneeSurroundingsParameters parameters;
  const Vector3 a0 = cruciateLigamentAttachment(CruciateLigament::Anterior, 0.0, parameters);
  const Vector3 a1 = cruciateLigamentAttachment(CruciateLigament::Anterior, 1.0, parameters);
  const Vector3 p0 = cruciateLigamentAttachment(CruciateLigament::Posterior, 0.0, parameters);
  const Vector3 p1 = cruciateLigamentAttachment(CruciateLigament::Posterior, 1.0, parameters);
  EXPECT_GT(a0.y(), a1.y());
  EXPECT_LT(p0.y(), p1.y());
  // Femoral insertions in the condyles' walls on either side of the notch.
  EXPECT_GT(a1.x(), 9.0);
  EXPECT_LT(p1.x(), -9.0);

  // Through the notch: the middle of each band is between the condyles and
  // under the femur.
  for (auto ligament : { CruciateLigament::Anterior, CruciateLigament::Posterior })
  {
    const Vector3 middle = cruciateLigamentAttachment(ligament, 0.5, parameters);
    EXPECT_LT(std::abs(middle.x()), 9.0) << cruciateLigamentName(ligament);
    EXPECT_GT(verticalHit(knee.femur.visual, middle.x(), middle.y(), false), middle.z());
  }
}

TEST(KneeLigaments, EnterTheBonesOnlyAtTheirInsertions)
{
  const auto& knee = scene();
  const KneeSurroundingsParameters parameters;
  for (const auto& expected : ligamentCases)
  {
    SCOPED_TRACE(cruciateLigamentName(expected.ligament));
    const TriangleMesh& visual = ligamentModel(expected.ligament).visual;
    const Vector3 tibial = cruciateLigamentAttachment(expected.ligament, 0.0, parameters);
    const Vector3 femoral = cruciateLigamentAttachment(expected.ligament, 1.0, parameters);
    // Through the femur nowhere but within 12 mm of the femoral insertion.
    EXPECT_TRUE(sampledVerticesOutside(
      visual, knee.femur.visual, 3, [&](const Vector3& x) { return (x - femoral).norm() < 12.0; }));
    // Into the tibia near the tibial insertion, elsewhere at most grazing it.
    for (std::size_t v = 0; v < visual.vertexCount(); v += 3)
    {
      const Vector3& x = visual.positions[v];
      if ((x - tibial).norm() > 12.0 && isInside(knee.tibia.visual, x))
      {
        EXPECT_LT(distanceToSurface(knee.tibia.visual, x), 1.6) << "at (" << x.transpose() << ")";
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Parameters and determinism.

void expectInvalid(const std::function<void(KneeSurroundingsParameters&)>& change,
  const std::string& named)
{
  KneeSurroundingsParameters parameters;
  change(parameters);
  try
  {
    validateKneeSurroundingsParameters(parameters);
    ADD_FAILURE() << "no error for bad " << named;
  }
  catch (const InvalidInputError& error)
  {
    EXPECT_NE(std::string(error.what()).find(named), std::string::npos) << error.what();
  }
  EXPECT_THROW(makeTibia(parameters), InvalidInputError) << named;
  EXPECT_THROW(makeCruciateLigament(CruciateLigament::Anterior, parameters), InvalidInputError)
    << named;
}

TEST(KneeParameters, BadValuesAreRejectedByName)
{
  expectInvalid([](auto& p) { p.jointGap = 0.0; }, "joint gap");
  expectInvalid([](auto& p) { p.jointGap = -2.0; }, "joint gap");
  expectInvalid([](auto& p) { p.jointGap = 30.0; }, "joint gap");
  expectInvalid([](auto& p) { p.jointGap = std::nan(""); }, "joint gap");
  expectInvalid([](auto& p) { p.tibiaVisualVertices = 10; }, "tibia visual vertices");
  expectInvalid([](auto& p) { p.femurVisualVertices = -1; }, "femur visual vertices");
  expectInvalid([](auto& p) { p.tibiaCollisionRings = 2; }, "tibia collision rings");
  expectInvalid([](auto& p) { p.femurCollisionSectors = 3; }, "femur collision sectors");
  expectInvalid([](auto& p) { p.cartilageVisual.along = 0; }, "cartilage visual cells along");
  expectInvalid(
    [](auto& p) { p.cartilageCollision100.across = 0; }, "cartilage 100-triangle collision");
  expectInvalid([](auto& p) { p.cartilageHexahedra.through = 0; }, "cartilage hexahedra");
  expectInvalid([](auto& p)
    { p.cartilageCollisionSetting = static_cast<CartilageCollisionSetting>(7); },
    "cartilage collision setting");
  expectInvalid(
    [](auto& p) { p.anteriorCruciate.visual.through = 1; }, "anterior cruciate ligament visual");
  expectInvalid([](auto& p) { p.posteriorCruciate.reducedAlong = 0; },
    "posterior cruciate ligament reduced collision");
  expectInvalid([](auto& p) { p.textureScale = 0.0; }, "texture scale");
  EXPECT_THROW(makeKneeSurroundings(
                 []
                 {
                   KneeSurroundingsParameters p;
                   p.jointGap = 0.1;
                   return p;
                 }()),
    InvalidInputError);
  EXPECT_THROW(cruciateLigamentCollisionMesh(CruciateLigament::Posterior,
                 static_cast<LigamentCollisionSetting>(0),
                 KneeSurroundingsParameters()),
    InvalidInputError);
}

TEST(KneeParameters, ScenesAreDeterministic)
{
  KneeSurroundingsParameters parameters;
  parameters.tibiaVisualVertices = 800;
  const BoneModel first = makeTibia(parameters);
  const BoneModel second = makeTibia(parameters);
  EXPECT_EQ(first.visual.positions, second.visual.positions);
  EXPECT_EQ(first.visual.triangles, second.visual.triangles);
  EXPECT_EQ(first.collision.positions, second.collision.positions);
  const TissueModel ligament = makeCruciateLigament(CruciateLigament::Anterior, parameters);
  EXPECT_EQ(ligament.visual.positions, scene().anteriorCruciateLigament.visual.positions);
  EXPECT_EQ(ligament.collision.positions, scene().anteriorCruciateLigament.collision.positions);
}

} // namespace
