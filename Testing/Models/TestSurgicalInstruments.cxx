// Procedural instruments and the arthroscope camera: closed outward visual
// pieces, tip and tool frame, centre-line capsules containing the visual
// mesh, cutting edges and bite outlines, bad parameters, determinism.
#include "SurgicalInstruments.h"

#include "MeshValidation.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

namespace
{

using namespace thintissue;

constexpr double Pi = 3.14159265358979323846;

/// Connected pieces of a mesh (triangles sharing vertices), each re-indexed.
std::vector<TriangleMesh> splitIntoPieces(const TriangleMesh& mesh)
{
  std::vector<int> parent(mesh.vertexCount());
  std::iota(parent.begin(), parent.end(), 0);
  const std::function<int(int)> root = [&](int v)
  {
    while (parent[v] != v)
    {
      parent[v] = parent[parent[v]];
      v = parent[v];
    }
    return v;
  };
  for (const Triangle& t : mesh.triangles)
  {
    parent[root(t[1])] = root(t[0]);
    parent[root(t[2])] = root(t[0]);
  }
  std::vector<int> pieceOfRoot(mesh.vertexCount(), -1);
  std::vector<TriangleMesh> pieces;
  std::vector<int> localIndex(mesh.vertexCount(), -1);
  for (const Triangle& t : mesh.triangles)
  {
    const int r = root(t[0]);
    if (pieceOfRoot[r] < 0)
    {
      pieceOfRoot[r] = static_cast<int>(pieces.size());
      pieces.emplace_back();
      pieces.back().name = mesh.name + " piece " + std::to_string(pieces.size() - 1);
    }
    TriangleMesh& piece = pieces[pieceOfRoot[r]];
    Triangle local;
    for (int k = 0; k < 3; ++k)
    {
      if (localIndex[t[k]] < 0)
      {
        localIndex[t[k]] = static_cast<int>(piece.positions.size());
        piece.positions.push_back(mesh.positions[t[k]]);
      }
      local[k] = localIndex[t[k]];
    }
    piece.triangles.push_back(local);
  }
  return pieces;
}

/// Distance from p to the nearest visual vertex.
double distanceToNearestVertex(const TriangleMesh& mesh, const Vector3& p)
{
  double best = std::numeric_limits<double>::infinity();
  for (const Vector3& q : mesh.positions)
  {
    best = std::min(best, (q - p).norm());
  }
  return best;
}

/// Newell normal (twice the vector area) of a closed polygon.
Vector3 polygonAreaVector(const std::vector<Vector3>& polygon)
{
  Vector3 sum = Vector3::Zero();
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    sum += polygon[i].cross(polygon[(i + 1) % polygon.size()]);
  }
  return sum;
}

bool hasSegment(const SurgicalInstrumentModel& model, const std::string& part)
{
  return std::any_of(model.centreLine.begin(),
    model.centreLine.end(),
    [&](const CollisionSegment& s) { return s.part == part; });
}

bool hasCuttingEdge(SurgicalInstrumentType type)
{
  return type == SurgicalInstrumentType::Scissors || type == SurgicalInstrumentType::Scalpel;
}

bool hasBiteOutline(SurgicalInstrumentType type)
{
  return type == SurgicalInstrumentType::Punch || type == SurgicalInstrumentType::SmallShaver ||
         type == SurgicalInstrumentType::LargeShaver;
}

class EveryInstrument : public ::testing::TestWithParam<SurgicalInstrumentType>
{
};

std::string typeLabel(const ::testing::TestParamInfo<SurgicalInstrumentType>& info)
{
  return instrumentTypeName(info.param);
}

bool insideCentreLine(const SurgicalInstrumentModel& model, const Vector3& q)
{
  return std::any_of(model.centreLine.begin(),
    model.centreLine.end(),
    [&](const CollisionSegment& s) { return s.distanceToCentreLine(q) <= s.radius + 1e-9; });
}

/// The visual surface: closed, 2-manifold, consistently oriented, every
/// piece outward; sized.
void expectClosedOutwardSurface(const TriangleMesh& visual)
{
  const MeshValidationReport report = validateTriangleMesh(visual);
  EXPECT_TRUE(report.isClosedManifold()) << report.toString();
  EXPECT_EQ(report.unreferencedVertices.count, 0u) << report.toString();
  const std::vector<TriangleMesh> pieces = splitIntoPieces(visual);
  EXPECT_EQ(pieces.size(), report.connectedComponents);
  for (const TriangleMesh& piece : pieces)
  {
    const MeshValidationReport pieceReport = validateTriangleMesh(piece);
    EXPECT_TRUE(pieceReport.isClosedOutwardSingleSurface()) << pieceReport.toString();
    EXPECT_GT(piece.signedVolume(), 0.0) << piece.name;
  }
  EXPECT_GT(visual.triangleCount(), 200u);
  EXPECT_LE(visual.triangleCount(), 6000u);
}

/// Unit vertex normals pointing out of their piece (checked on the whole
/// mesh: area-weighted normals agree with the outward triangles).
void expectOutwardNormals(const TriangleMesh& visual)
{
  ASSERT_TRUE(visual.hasNormals());
  ASSERT_EQ(visual.normals.size(), visual.vertexCount());
  for (const Vector3& n : visual.normals)
  {
    EXPECT_NEAR(n.norm(), 1.0, 1e-9);
  }
  double agreement = 0.0;
  for (std::size_t t = 0; t < visual.triangleCount(); ++t)
  {
    const Vector3 face = visual.triangleNormal(t);
    for (const int v : visual.triangles[t])
    {
      agreement += face.dot(visual.normals[v]) > 0.0 ? 1.0 : -1.0;
    }
  }
  EXPECT_GT(agreement, 0.9 * 3.0 * visual.triangleCount());
}

/// Every vertex labelled handle, shaft or working tip; each part present.
void expectPartLabels(const TriangleMesh& visual)
{
  ASSERT_TRUE(visual.pointAttributes.has(InstrumentPartArrayName));
  const AttributeArray& parts = visual.pointAttributes.get(InstrumentPartArrayName);
  ASSERT_EQ(parts.elementCount(), visual.vertexCount());
  int counts[3] = { 0, 0, 0 };
  for (const double value : parts.values)
  {
    ASSERT_TRUE(value == 0.0 || value == 1.0 || value == 2.0);
    ++counts[static_cast<int>(value)];
  }
  EXPECT_GT(counts[static_cast<int>(InstrumentPart::Handle)], 0);
  EXPECT_GT(counts[static_cast<int>(InstrumentPart::Shaft)], 0);
  EXPECT_GT(counts[static_cast<int>(InstrumentPart::WorkingTip)], 0);
}

/// The tool frame, and the tip at the far end of the mesh.
void expectToolFrameAtTheTip(const SurgicalInstrumentModel& model)
{
  const TriangleMesh& visual = model.visual;
  const SurgicalInstrumentParameters& p = model.parameters;
  const ToolFrame& frame = model.frame;
  // Tool frame: orthonormal, right-handed, at the tip, handle axis +z.
  EXPECT_NEAR(frame.handleAxis.norm(), 1.0, 1e-12);
  EXPECT_NEAR(frame.up.norm(), 1.0, 1e-12);
  EXPECT_NEAR(frame.handleAxis.dot(frame.up), 0.0, 1e-12);
  EXPECT_NEAR(frame.rotation().determinant(), 1.0, 1e-12);
  EXPECT_TRUE(
    (frame.rotation().transpose() * frame.rotation()).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_TRUE(frame.origin.isApprox(model.tip));
  EXPECT_TRUE(model.tip.isZero(0.0));
  EXPECT_TRUE(frame.handleAxis.isApprox(Vector3::UnitZ()));
  EXPECT_TRUE(frame.up.isApprox(Vector3::UnitX()));

  // The tip is a vertex at the far end: the mesh lies on the handle side.
  EXPECT_LT(distanceToNearestVertex(visual, model.tip), 1e-9);
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -lowest;
  for (const Vector3& q : visual.positions)
  {
    lowest = std::min(lowest, (q - model.tip).dot(frame.handleAxis));
    highest = std::max(highest, (q - model.tip).dot(frame.handleAxis));
  }
  EXPECT_GT(lowest, -1e-9);
  EXPECT_GE(highest, p.shaftLength + p.handleLength - 1e-9);
  EXPECT_LE(highest, p.shaftLength + p.handleLength + 40.0);
}

/// The collision centre line: capsules holding the shaft and the tip.
void expectCentreLineHoldsTheShaft(const SurgicalInstrumentModel& model)
{
  const TriangleMesh& visual = model.visual;
  const SurgicalInstrumentParameters& p = model.parameters;
  const ToolFrame& frame = model.frame;
  // Centre line: a shaft capsule of the shaft radius up to the handle;
  // radii no larger than the shaft's; the capsules contain the tip and
  // every visual vertex between the tip plane and the handle.
  EXPECT_DOUBLE_EQ(model.shaftRadius, 0.5 * p.shaftDiameter);
  ASSERT_FALSE(model.centreLine.empty());
  ASSERT_TRUE(hasSegment(model, "shaft"));
  double reach = 0.0;
  for (const CollisionSegment& segment : model.centreLine)
  {
    EXPECT_GT(segment.radius, 0.0) << segment.part;
    EXPECT_LE(segment.radius, model.shaftRadius * (1.0 + 1e-12)) << segment.part;
    EXPECT_GE(segment.radius, 0.2 * model.shaftRadius) << segment.part;
    if (segment.part == "shaft")
    {
      EXPECT_DOUBLE_EQ(segment.radius, model.shaftRadius);
      // The shaft capsule runs along the handle axis.
      EXPECT_NEAR((segment.end - segment.start).normalized().dot(frame.handleAxis), 1.0, 1e-12);
    }
    reach =
      std::max({ reach, segment.start.dot(frame.handleAxis), segment.end.dot(frame.handleAxis) });
  }
  EXPECT_NEAR(reach, p.shaftLength, 1e-9);
  const auto insideCapsules = [&](const Vector3& q) { return insideCentreLine(model, q); };
  EXPECT_TRUE(insideCapsules(model.tip));
  int outside = 0;
  int checked = 0;
  for (const Vector3& q : visual.positions)
  {
    if ((q - model.tip).dot(frame.handleAxis) <= p.shaftLength)
    {
      ++checked;
      if (!insideCapsules(q))
      {
        if (outside++ == 0)
        {
          ADD_FAILURE() << "vertex " << q.transpose() << " outside every capsule";
        }
      }
    }
  }
  EXPECT_EQ(outside, 0);
  EXPECT_GT(checked, 50);
}

/// The cutting edge (scissors, scalpel) and the bite outline (punch, shavers).
void expectCuttingFeatures(const SurgicalInstrumentModel& model)
{
  const TriangleMesh& visual = model.visual;
  const ToolFrame& frame = model.frame;
  // Cutting edge: scissors and scalpel, from the tip toward the handle, on
  // the visual surface.
  if (hasCuttingEdge(model.type))
  {
    ASSERT_GE(model.cuttingEdge.size(), 5u);
    EXPECT_TRUE(model.cuttingEdge.front().isApprox(model.tip, 1e-12) ||
                model.cuttingEdge.front().isZero(1e-12));
    double previous = -1.0;
    for (const Vector3& q : model.cuttingEdge)
    {
      EXPECT_LT(distanceToNearestVertex(visual, q), 1e-9);
      const double along = q.dot(frame.handleAxis);
      EXPECT_GT(along, previous);
      previous = along;
    }
  }
  else
  {
    EXPECT_TRUE(model.cuttingEdge.empty());
  }
  EXPECT_EQ(model.opposingCuttingEdge.empty(), model.type != SurgicalInstrumentType::Scissors);

  // Bite outline: punch and shavers, a closed planar polygon facing up.
  if (hasBiteOutline(model.type))
  {
    ASSERT_GE(model.biteOutline.size(), 8u);
    const Vector3 areaVector = polygonAreaVector(model.biteOutline);
    ASSERT_GT(areaVector.norm(), 1e-6);
    const Vector3 normal = areaVector.normalized();
    EXPECT_NEAR(std::abs(normal.dot(frame.up)), 1.0, 1e-9);
    for (std::size_t i = 0; i < model.biteOutline.size(); ++i)
    {
      const Vector3& q = model.biteOutline[i];
      EXPECT_NEAR((q - model.biteOutline.front()).dot(normal), 0.0, 1e-9);
      EXPECT_GT((model.biteOutline[(i + 1) % model.biteOutline.size()] - q).norm(), 1e-9)
        << "repeated point " << i;
      EXPECT_TRUE(insideCentreLine(model, q));
    }
  }
  else
  {
    EXPECT_TRUE(model.biteOutline.empty());
  }
}

/// All the geometric invariants of one model; used for the defaults and
/// for other valid parameter sets.
void expectWellFormed(const SurgicalInstrumentModel& model)
{
  SCOPED_TRACE(model.name);
  ASSERT_NO_THROW(model.visual.checkConsistency());
  expectClosedOutwardSurface(model.visual);
  expectOutwardNormals(model.visual);
  expectPartLabels(model.visual);
  expectToolFrameAtTheTip(model);
  expectCentreLineHoldsTheShaft(model);
  expectCuttingFeatures(model);
}

TEST_P(EveryInstrument, DefaultModelIsWellFormed)
{
  const SurgicalInstrumentModel model = makeSurgicalInstrument(GetParam());
  EXPECT_EQ(model.type, GetParam());
  EXPECT_EQ(model.name, instrumentTypeName(GetParam()));
  EXPECT_EQ(model.visual.name, model.name);
  expectWellFormed(model);
  std::cout << "[ instrument ] " << model.name << ": " << model.visual.triangleCount()
            << " triangles, " << model.visual.vertexCount() << " vertices, "
            << splitIntoPieces(model.visual).size() << " pieces, " << model.centreLine.size()
            << " capsules\n";
}

TEST_P(EveryInstrument, OtherValidResolutionsAndSizesAreWellFormed)
{
  for (const int segments : { 8, 9, 13, 40 })
  {
    SurgicalInstrumentParameters p = defaultInstrumentParameters(GetParam());
    p.segmentsAround = segments;
    SCOPED_TRACE("segmentsAround " + std::to_string(segments));
    expectWellFormed(makeSurgicalInstrument(p));
  }
  SurgicalInstrumentParameters p = defaultInstrumentParameters(GetParam());
  p.shaftDiameter *= 1.3;
  p.shaftLength = 80.0;
  p.handleDiameter = p.shaftDiameter; // thinnest handle allowed
  p.handleLength = 20.0;
  SCOPED_TRACE("thick short shaft, thin handle");
  expectWellFormed(makeSurgicalInstrument(p));
}

TEST_P(EveryInstrument, IsDeterministic)
{
  const SurgicalInstrumentModel a = makeSurgicalInstrument(GetParam());
  const SurgicalInstrumentModel b = makeSurgicalInstrument(GetParam());
  ASSERT_EQ(a.visual.positions.size(), b.visual.positions.size());
  EXPECT_EQ(a.visual.positions, b.visual.positions);
  EXPECT_EQ(a.visual.triangles, b.visual.triangles);
  EXPECT_EQ(a.visual.normals, b.visual.normals);
  ASSERT_EQ(a.centreLine.size(), b.centreLine.size());
  for (std::size_t i = 0; i < a.centreLine.size(); ++i)
  {
    EXPECT_EQ(a.centreLine[i].start, b.centreLine[i].start);
    EXPECT_EQ(a.centreLine[i].end, b.centreLine[i].end);
    EXPECT_EQ(a.centreLine[i].radius, b.centreLine[i].radius);
  }
  EXPECT_EQ(a.cuttingEdge, b.cuttingEdge);
  EXPECT_EQ(a.biteOutline, b.biteOutline);
}

TEST_P(EveryInstrument, MovesRigidly)
{
  const SurgicalInstrumentModel model = makeSurgicalInstrument(GetParam());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(0.7, Vector3(1.0, 2.0, -0.5).normalized()));
  pose.pretranslate(Vector3(10.0, -20.0, 35.0));
  const SurgicalInstrumentModel moved = transformedInstrument(model, pose);
  EXPECT_TRUE(moved.tip.isApprox(pose.translation()));
  EXPECT_TRUE(moved.frame.origin.isApprox(pose.translation()));
  EXPECT_TRUE(moved.frame.handleAxis.isApprox(pose.linear() * Vector3::UnitZ()));
  EXPECT_NEAR(moved.frame.rotation().determinant(), 1.0, 1e-12);
  EXPECT_NEAR(
    moved.visual.signedVolume(), model.visual.signedVolume(), 1e-9 * model.visual.signedVolume());
  for (std::size_t i = 0; i < model.visual.vertexCount(); i += 97)
  {
    EXPECT_TRUE(moved.visual.positions[i].isApprox(pose * model.visual.positions[i], 1e-12));
    EXPECT_TRUE(moved.visual.normals[i].isApprox(pose.linear() * model.visual.normals[i], 1e-12));
  }
  for (std::size_t i = 0; i < model.centreLine.size(); ++i)
  {
    EXPECT_TRUE(moved.centreLine[i].end.isApprox(pose * model.centreLine[i].end, 1e-12));
  }
}

INSTANTIATE_TEST_SUITE_P(SurgicalInstruments,
  EveryInstrument,
  ::testing::ValuesIn(allSurgicalInstrumentTypes()),
  typeLabel);

TEST(SurgicalInstruments, NamesRoundTripAndParseLeniently)
{
  for (const SurgicalInstrumentType type : allSurgicalInstrumentTypes())
  {
    EXPECT_EQ(parseSurgicalInstrumentType(instrumentTypeName(type)), type);
  }
  EXPECT_EQ(parseSurgicalInstrumentType("ProbeHook"), SurgicalInstrumentType::ProbeHook);
  EXPECT_EQ(parseSurgicalInstrumentType("probe hook"), SurgicalInstrumentType::ProbeHook);
  EXPECT_EQ(parseSurgicalInstrumentType("LARGE-SHAVER"), SurgicalInstrumentType::LargeShaver);
  EXPECT_EQ(parseSurgicalInstrumentType("SmallShaver"), SurgicalInstrumentType::SmallShaver);
  try
  {
    parseSurgicalInstrumentType("laser");
    FAIL() << "no exception";
  }
  catch (const InvalidInputError& error)
  {
    const std::string message = error.what();
    EXPECT_NE(message.find("laser"), std::string::npos) << message;
    for (const SurgicalInstrumentType type : allSurgicalInstrumentTypes())
    {
      EXPECT_NE(message.find(instrumentTypeName(type)), std::string::npos) << message;
    }
  }
  EXPECT_THROW(parseSurgicalInstrumentType(""), InvalidInputError);
}

TEST(SurgicalInstruments, DefaultsAreArthroscopicSizes)
{
  for (const SurgicalInstrumentType type : allSurgicalInstrumentTypes())
  {
    const SurgicalInstrumentParameters p = defaultInstrumentParameters(type);
    EXPECT_EQ(p.type, type);
    EXPECT_GE(p.shaftDiameter, 3.0);
    EXPECT_LE(p.shaftDiameter, 5.5);
    EXPECT_GE(p.shaftLength, 100.0);
    EXPECT_LE(p.shaftLength, 130.0);
    EXPECT_NO_THROW(checkInstrumentParameters(p));
  }
  EXPECT_DOUBLE_EQ(defaultInstrumentParameters(SurgicalInstrumentType::ProbeHook).hookLength, 3.0);
  EXPECT_DOUBLE_EQ(
    defaultInstrumentParameters(SurgicalInstrumentType::SmallShaver).shaftDiameter, 3.5);
  EXPECT_DOUBLE_EQ(
    defaultInstrumentParameters(SurgicalInstrumentType::LargeShaver).shaftDiameter, 5.5);
}

TEST(SurgicalInstruments, ProbeHookPointsUpWithItsLength)
{
  const SurgicalInstrumentModel probe = makeSurgicalInstrument(SurgicalInstrumentType::ProbeHook);
  const SurgicalInstrumentParameters& p = probe.parameters;
  ASSERT_TRUE(hasSegment(probe, "hook"));
  // The hook reaches hookLength from the shaft axis, toward +x (up).
  const CollisionSegment& shaft = *std::find_if(probe.centreLine.begin(),
    probe.centreLine.end(),
    [](const CollisionSegment& s) { return s.part == "shaft"; });
  double farthest = -std::numeric_limits<double>::infinity();
  for (const Vector3& q : probe.visual.positions)
  {
    if (q.z() < p.shaftLength)
    {
      farthest = std::max(farthest, q.x() - shaft.end.x());
    }
  }
  EXPECT_NEAR(farthest, p.hookLength, 1e-9);
  // The hook is bent 90 degrees: its capsule is perpendicular to the shaft.
  const CollisionSegment& hook = probe.centreLine.front();
  EXPECT_EQ(hook.part, "hook");
  EXPECT_NEAR((hook.start - hook.end).normalized().dot(probe.frame.up), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(hook.radius, 0.5 * p.hookDiameter);
}

TEST(SurgicalInstruments, PunchBiteHasTheRequestedSize)
{
  for (const double opening : { 0.0, 30.0, 60.0 })
  {
    SurgicalInstrumentParameters p = defaultInstrumentParameters(SurgicalInstrumentType::Punch);
    p.jawOpeningDegrees = opening;
    const SurgicalInstrumentModel punch = makeSurgicalInstrument(p);
    expectWellFormed(punch);
    Eigen::AlignedBox3d box;
    for (const Vector3& q : punch.biteOutline)
    {
      box.extend(q);
    }
    EXPECT_NEAR(box.sizes().z(), p.biteLength, 1e-9);
    EXPECT_NEAR(box.sizes().y(), p.biteWidth, 1e-9);
    EXPECT_NEAR(box.sizes().x(), 0.0, 1e-12);
    // Area of the rounded 3.5 x 2 mm bite (stadium), polygon slightly inside.
    const double stadium =
      p.biteWidth * (p.biteLength - p.biteWidth) + Pi * 0.25 * p.biteWidth * p.biteWidth;
    const double area = 0.5 * polygonAreaVector(punch.biteOutline).norm();
    EXPECT_LT(area, stadium);
    EXPECT_GT(area, 0.97 * stadium);
    // Fixed jaw, moving jaw, shaft with handle, two finger rings with shanks.
    EXPECT_EQ(splitIntoPieces(punch.visual).size(), 7u);
    // The moving jaw's capsule opens by the requested angle.
    const auto moving = std::find_if(punch.centreLine.begin(),
      punch.centreLine.end(),
      [](const CollisionSegment& s) { return s.part == "moving jaw"; });
    ASSERT_NE(moving, punch.centreLine.end());
    const Vector3 direction = (moving->end - moving->start).normalized();
    EXPECT_NEAR(std::acos(std::clamp(direction.dot(Vector3::UnitZ()), -1.0, 1.0)) * 180.0 / Pi,
      opening,
      1e-9);
    EXPECT_GE(-direction.x(), -1e-12); // the distal end lifts toward +x
  }
}

TEST(SurgicalInstruments, ShaverWindowFacesUpAndShowsTheInnerCutter)
{
  for (const SurgicalInstrumentType type :
    { SurgicalInstrumentType::SmallShaver, SurgicalInstrumentType::LargeShaver })
  {
    const SurgicalInstrumentModel shaver = makeSurgicalInstrument(type);
    const SurgicalInstrumentParameters& p = shaver.parameters;
    SCOPED_TRACE(shaver.name);
    EXPECT_EQ(splitIntoPieces(shaver.visual).size(), 1u);
    Eigen::AlignedBox3d box;
    for (const Vector3& q : shaver.biteOutline)
    {
      box.extend(q);
    }
    EXPECT_NEAR(box.sizes().z(), p.windowLength, 1e-9);
    EXPECT_NEAR(box.sizes().y(), p.windowWidth, 1e-9);
    EXPECT_GT(box.min().x(), 0.0); // on the +x (up) side
    // Some tube vertices near the window are recessed to the inner cutter.
    int recessed = 0;
    for (const Vector3& q : shaver.visual.positions)
    {
      const double radial = std::hypot(q.x(), q.y());
      if (q.z() > shaver.shaftRadius && q.z() < box.max().z() - 0.2 && q.x() > 0.0 &&
          radial < 0.8 * shaver.shaftRadius && std::abs(q.y()) < 0.5 * p.windowWidth)
      {
        ++recessed;
      }
    }
    EXPECT_GT(recessed, 5);
  }
}

TEST(SurgicalInstruments, ScissorBladesCloseOntoEachOther)
{
  SurgicalInstrumentParameters p = defaultInstrumentParameters(SurgicalInstrumentType::Scissors);
  p.jawOpeningDegrees = 0.0;
  const SurgicalInstrumentModel closed = makeSurgicalInstrument(p);
  ASSERT_EQ(closed.cuttingEdge.size(), closed.opposingCuttingEdge.size());
  for (std::size_t i = 0; i < closed.cuttingEdge.size(); ++i)
  {
    EXPECT_TRUE(closed.cuttingEdge[i].isApprox(closed.opposingCuttingEdge[i], 1e-12) ||
                (closed.cuttingEdge[i] - closed.opposingCuttingEdge[i]).norm() < 1e-12);
  }
  // The fixed edge runs along the handle axis for the blade length.
  EXPECT_NEAR(closed.cuttingEdge.back().z(), p.bladeLength, 1e-9);
  const SurgicalInstrumentModel open = makeSurgicalInstrument(SurgicalInstrumentType::Scissors);
  const Vector3 tipOfMovingBlade = open.opposingCuttingEdge.front();
  EXPECT_GT(tipOfMovingBlade.x(),
    0.5 * open.parameters.bladeLength * std::sin(open.parameters.jawOpeningDegrees * Pi / 180.0));
  EXPECT_EQ(splitIntoPieces(open.visual).size(), 7u);
}

TEST(SurgicalInstruments, ScalpelEdgeFacesUp)
{
  const SurgicalInstrumentModel knife = makeSurgicalInstrument(SurgicalInstrumentType::Scalpel);
  double widest = 0.0;
  for (const Vector3& q : knife.cuttingEdge)
  {
    EXPECT_GE(q.x(), -1e-12);
    EXPECT_NEAR(q.y(), 0.0, 1e-12);
    widest = std::max(widest, q.x());
  }
  EXPECT_NEAR(widest, 0.5 * knife.parameters.bladeWidth, 1e-9);
  EXPECT_EQ(splitIntoPieces(knife.visual).size(), 2u);
}

struct BadParameter
{
  SurgicalInstrumentType type;
  std::string parameter;
  std::function<void(SurgicalInstrumentParameters&)> change;
};

TEST(SurgicalInstruments, BadParametersThrowNamingTheParameter)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<BadParameter> cases;
  for (const SurgicalInstrumentType type : allSurgicalInstrumentTypes())
  {
    cases.push_back({ type, "shaftDiameter", [](auto& p) { p.shaftDiameter = 0.0; } });
    cases.push_back({ type, "shaftDiameter", [](auto& p) { p.shaftDiameter = -3.0; } });
    cases.push_back({ type, "shaftDiameter", [nan](auto& p) { p.shaftDiameter = nan; } });
    cases.push_back({ type, "shaftLength", [](auto& p) { p.shaftLength = 0.0; } });
    cases.push_back({ type, "shaftLength", [](auto& p) { p.shaftLength = 6.0; } });
    cases.push_back({ type, "shaftLength", [](auto& p) {
                       p.shaftLength = std::numeric_limits<double>::infinity();
                     } });
    cases.push_back({ type, "handleDiameter", [](auto& p) { p.handleDiameter = 0.0; } });
    cases.push_back({ type, "handleDiameter", [](auto& p) { p.handleDiameter = 2.0; } });
    cases.push_back({ type, "handleLength", [](auto& p) { p.handleLength = -1.0; } });
    cases.push_back({ type, "segmentsAround", [](auto& p) { p.segmentsAround = 5; } });
    cases.push_back({ type, "segmentsAround", [](auto& p) { p.segmentsAround = 0; } });
    cases.push_back({ type, "segmentsAround", [](auto& p) { p.segmentsAround = 100000; } });
  }
  using T = SurgicalInstrumentType;
  cases.push_back({ T::ProbeHook, "hookLength", [](auto& p) { p.hookLength = 0.0; } });
  cases.push_back({ T::ProbeHook, "hookLength", [](auto& p) { p.hookLength = 1.0; } });
  cases.push_back({ T::ProbeHook, "hookDiameter", [](auto& p) { p.hookDiameter = 0.0; } });
  cases.push_back({ T::ProbeHook, "hookDiameter", [](auto& p) { p.hookDiameter = 3.5; } });
  cases.push_back({ T::Punch, "biteLength", [](auto& p) { p.biteLength = 0.0; } });
  cases.push_back({ T::Punch, "biteLength", [](auto& p) { p.biteLength = 1.5; } });
  cases.push_back({ T::Punch, "biteWidth", [](auto& p) { p.biteWidth = -2.0; } });
  cases.push_back({ T::Punch, "biteWidth", [](auto& p) { p.biteWidth = 3.0; } });
  cases.push_back({ T::Punch, "jawThickness", [](auto& p) { p.jawThickness = 0.0; } });
  cases.push_back({ T::Punch, "jawThickness", [](auto& p) { p.jawThickness = 1.6; } });
  cases.push_back({ T::Punch, "jawOpeningDegrees", [](auto& p) { p.jawOpeningDegrees = -5.0; } });
  cases.push_back({ T::Punch, "jawOpeningDegrees", [](auto& p) { p.jawOpeningDegrees = 90.0; } });
  for (const T shaver : { T::SmallShaver, T::LargeShaver })
  {
    cases.push_back({ shaver, "windowLength", [](auto& p) { p.windowLength = 0.0; } });
    cases.push_back({ shaver, "windowLength", [](auto& p) { p.windowLength = 1.0; } });
    cases.push_back({ shaver, "windowWidth", [](auto& p) { p.windowWidth = 0.0; } });
    cases.push_back({ shaver, "windowWidth", [](auto& p) { p.windowWidth = 5.4; } });
  }
  cases.push_back({ T::Scissors, "bladeLength", [](auto& p) { p.bladeLength = 0.0; } });
  cases.push_back({ T::Scissors, "bladeWidth", [](auto& p) { p.bladeWidth = 0.0; } });
  cases.push_back({ T::Scissors, "bladeWidth", [](auto& p) { p.bladeWidth = 2.0; } });
  cases.push_back({ T::Scissors, "bladeThickness", [](auto& p) { p.bladeThickness = -0.1; } });
  cases.push_back(
    { T::Scissors, "jawOpeningDegrees", [nan](auto& p) { p.jawOpeningDegrees = nan; } });
  cases.push_back({ T::Scalpel, "bladeLength", [](auto& p) { p.bladeLength = -7.0; } });
  cases.push_back({ T::Scalpel, "bladeWidth", [](auto& p) { p.bladeWidth = 0.0; } });
  cases.push_back({ T::Scalpel, "bladeWidth", [](auto& p) { p.bladeWidth = 3.5; } });
  cases.push_back({ T::Scalpel, "bladeThickness", [](auto& p) { p.bladeThickness = 0.0; } });
  cases.push_back({ T::Scalpel, "bladeThickness", [](auto& p) { p.bladeThickness = 2.0; } });

  for (const BadParameter& bad : cases)
  {
    SurgicalInstrumentParameters p = defaultInstrumentParameters(bad.type);
    bad.change(p);
    SCOPED_TRACE(instrumentTypeName(bad.type) + " " + bad.parameter);
    try
    {
      makeSurgicalInstrument(p);
      ADD_FAILURE() << "no exception";
    }
    catch (const InvalidInputError& error)
    {
      const std::string message = error.what();
      EXPECT_NE(message.find(bad.parameter), std::string::npos) << message;
      EXPECT_NE(message.find(instrumentTypeName(bad.type)), std::string::npos) << message;
    }
  }
  // Parameters of other instruments are ignored.
  SurgicalInstrumentParameters probe = defaultInstrumentParameters(T::ProbeHook);
  probe.biteWidth = -1.0;
  probe.bladeLength = 0.0;
  EXPECT_NO_THROW(makeSurgicalInstrument(probe));
  SurgicalInstrumentParameters undefined = probe;
  undefined.type = static_cast<SurgicalInstrumentType>(42);
  EXPECT_THROW(makeSurgicalInstrument(undefined), InvalidInputError);
}

// ---------------------------------------------------------------------------
// Arthroscope camera
// ---------------------------------------------------------------------------

double angleBetweenDegrees(const Vector3& a, const Vector3& b)
{
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / Pi;
}

TEST(ArthroscopeCamera, ThirtyDegreeOpticsAtEveryRotation)
{
  ArthroscopeCamera camera = defaultArthroscopeCamera();
  EXPECT_NO_THROW(camera.check());
  EXPECT_DOUBLE_EQ(camera.opticsAngleDegrees, 30.0);
  EXPECT_DOUBLE_EQ(camera.scopeDiameter, 4.0);
  EXPECT_GT(camera.fieldOfViewDegrees, 60.0);
  EXPECT_LT(camera.fieldOfViewDegrees, 130.0);
  EXPECT_GT(camera.nearClipDistance, 0.0);
  EXPECT_LT(camera.nearClipDistance, 2.0);
  EXPECT_GT(camera.farClipDistance, 100.0);
  EXPECT_TRUE(camera.scopeAxis().isApprox(-Vector3::UnitZ()));

  std::vector<Vector3> directions;
  for (const double rotation : { -135.0, -90.0, 0.0, 30.0, 90.0, 137.0, 180.0 })
  {
    camera.opticsRotationDegrees = rotation;
    SCOPED_TRACE(rotation);
    const Vector3 view = camera.viewDirection();
    const Vector3 up = camera.viewUp();
    EXPECT_NEAR(view.norm(), 1.0, 1e-12);
    EXPECT_NEAR(up.norm(), 1.0, 1e-12);
    EXPECT_NEAR(angleBetweenDegrees(view, camera.scopeAxis()), 30.0, 1e-9);
    EXPECT_NEAR(view.dot(up), 0.0, 1e-12);
    EXPECT_GT(up.dot(camera.imageUp), 0.0); // the horizon stays with the camera head
    EXPECT_NEAR(camera.tiltDirection().dot(camera.scopeAxis()), 0.0, 1e-12);
    EXPECT_TRUE(camera.lightPostDirection().isApprox(-camera.tiltDirection()));
    // The optics look away from the light post.
    EXPECT_LT(view.dot(camera.lightPostDirection()), 0.0);
    EXPECT_NEAR(
      angleBetweenDegrees(camera.tiltDirection(), camera.imageUp), std::abs(rotation), 1e-9);
    EXPECT_TRUE(camera.focalPoint(10.0).isApprox(camera.tip + 10.0 * view));
    directions.push_back(view);
  }
  // At 0 the view tilts toward the top of the image, at 180 away from it.
  camera.opticsRotationDegrees = 0.0;
  EXPECT_NEAR(camera.viewDirection().dot(camera.imageUp), 0.5, 1e-12);
  camera.opticsRotationDegrees = 180.0;
  EXPECT_NEAR(camera.viewDirection().dot(camera.imageUp), -0.5, 1e-12);
  // Rotating the optics sweeps the view around the cone.
  EXPECT_GT((directions[2] - directions[6]).norm(), 0.9);
  // Positive rotation is right-handed about the viewing axis.
  camera.opticsRotationDegrees = 90.0;
  EXPECT_TRUE(camera.tiltDirection().isApprox(camera.scopeAxis().cross(camera.imageUp), 1e-12));
}

TEST(ArthroscopeCamera, RotateOpticsWrapsAndWorksForAnyPose)
{
  ArthroscopeCamera camera = defaultArthroscopeCamera();
  camera.rotateOptics(170.0);
  EXPECT_DOUBLE_EQ(camera.opticsRotationDegrees, 170.0);
  camera.rotateOptics(20.0);
  EXPECT_NEAR(camera.opticsRotationDegrees, -170.0, 1e-12);
  camera.rotateOptics(-10.0);
  EXPECT_NEAR(camera.opticsRotationDegrees, 180.0, 1e-12);
  camera.rotateOptics(720.0);
  EXPECT_NEAR(camera.opticsRotationDegrees, 180.0, 1e-12);

  // A posed scope with non-unit, non-orthogonal input directions.
  camera.tip = Vector3(5.0, 40.0, 10.0);
  camera.handleAxis = Vector3(0.0, 3.0, 1.0);
  camera.imageUp = Vector3(0.2, 0.0, 1.0);
  for (double rotation = -180.0; rotation < 180.0; rotation += 45.0)
  {
    camera.opticsRotationDegrees = rotation;
    EXPECT_NEAR(angleBetweenDegrees(camera.viewDirection(), camera.scopeAxis()), 30.0, 1e-9);
    EXPECT_NEAR(camera.viewDirection().norm(), 1.0, 1e-12);
    EXPECT_NEAR(camera.viewUp().dot(camera.viewDirection()), 0.0, 1e-12);
  }
  EXPECT_NO_THROW(camera.check());
  camera.opticsAngleDegrees = 70.0;
  EXPECT_NEAR(angleBetweenDegrees(camera.viewDirection(), camera.scopeAxis()), 70.0, 1e-9);
}

TEST(ArthroscopeCamera, BadFieldsThrowNamingTheField)
{
  const auto expectBad =
    [](const std::string& field, const std::function<void(ArthroscopeCamera&)>& change)
  {
    ArthroscopeCamera camera = defaultArthroscopeCamera();
    change(camera);
    SCOPED_TRACE(field);
    try
    {
      camera.check();
      ADD_FAILURE() << "no exception";
    }
    catch (const InvalidInputError& error)
    {
      EXPECT_NE(std::string(error.what()).find(field), std::string::npos) << error.what();
    }
  };
  expectBad("handleAxis", [](auto& c) { c.handleAxis = Vector3::Zero(); });
  expectBad("imageUp", [](auto& c) { c.imageUp = Vector3(0.0, 0.0, 2.0); });
  expectBad("imageUp", [](auto& c) { c.imageUp = Vector3::Zero(); });
  expectBad("opticsAngleDegrees", [](auto& c) { c.opticsAngleDegrees = 90.0; });
  expectBad("opticsAngleDegrees", [](auto& c) { c.opticsAngleDegrees = -1.0; });
  expectBad("fieldOfViewDegrees", [](auto& c) { c.fieldOfViewDegrees = 0.0; });
  expectBad("fieldOfViewDegrees", [](auto& c) { c.fieldOfViewDegrees = 200.0; });
  expectBad("nearClipDistance", [](auto& c) { c.nearClipDistance = 0.0; });
  expectBad("farClipDistance", [](auto& c) { c.farClipDistance = 0.1; });
  expectBad("scopeDiameter", [](auto& c) { c.scopeDiameter = -4.0; });
  expectBad("sheathDiameter", [](auto& c) { c.sheathDiameter = 3.0; });
  expectBad("scopeLength", [](auto& c) { c.scopeLength = 0.0; });
  expectBad("opticsRotationDegrees",
    [](auto& c) { c.opticsRotationDegrees = std::numeric_limits<double>::quiet_NaN(); });
  expectBad("tip", [](auto& c) { c.tip.x() = std::numeric_limits<double>::infinity(); });
}

} // namespace
