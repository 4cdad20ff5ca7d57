// Random blade sweeps over a tissue with every cutting invariant checked
// after each cut: shared by the cutting tests of the procedural models and
// of prepared segmentations and MRI meshes.
#ifndef RandomSweeps_h
#define RandomSweeps_h

#include "CorotationalHexFem.h"
#include "CuttingInvariants.h"
#include "SoftTissueMaterial.h"
#include "ThinTissueError.h"
#include "TissueCutter.h"
#include "TissueModel.h"
#include "VisualCollisionBinding.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <random>

namespace thintissue
{
namespace cutting_test
{

/// Random sweeps over a tissue: straight cuts across, short progressive
/// steps, cuts through vertices and along edges, repeated cuts, bite
/// outlines and zero-length (refused) sweeps; the invariants after each.
/// Time step of the FEM stepped after every sweep.
inline CorotationalHexFemSettings sweepStepSettings()
{
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.01;
  return settings;
}

class RandomSweeps
{
public:
  RandomSweeps(const TissueModel& model, unsigned seed)
    : Model(model)
    , Random(seed)
  {
  }

  void run(int episodes, int sweepsPerEpisode)
  {
    for (int e = 0; e < episodes; ++e)
    {
      CorotationalHexFem fem(Model.simulation, test::softTissue(), sweepStepSettings());
      TissueCutterSettings settings;
      settings.visual.cutSurfaceRows = e % 3;
      // Every other episode runs the region stages on several threads
      // whatever the regions' size (the models' regions are small).
      if (e % 2 || CompareWith == Twin::OneThread)
        settings.visual.parallelRegionTriangles = 0;
      // The models' regions are small: their far triangles are set apart
      // whatever the size, so that every sweep checks that path too.
      settings.visual.separatedRegionTriangles = 0;
      TissueCutterSettings twinSettings = settings;
      if (CompareWith == Twin::OneThread)
        twinSettings.visual.parallelRegionTriangles = std::numeric_limits<std::size_t>::max();
      if (CompareWith == Twin::UnionFindPieces)
        twinSettings.visual.piecesByLocation = false;
      if (CompareWith == Twin::EagerBinding)
        twinSettings.visual.lazyBinding = false;
      TissueCutter cutter = Binding ? TissueCutter(*Binding, Model.simulation, &fem, settings)
                                    : TissueCutter(Model.collision, Model.simulation, &fem);
      // The twin cuts the same its own way (CompareWith).
      std::unique_ptr<CorotationalHexFem> twinFem;
      std::unique_ptr<TissueCutter> twin;
      if (CompareWith != Twin::None && Binding)
      {
        twinFem = std::make_unique<CorotationalHexFem>(
          Model.simulation, test::softTissue(), sweepStepSettings());
        twin =
          std::make_unique<TissueCutter>(*Binding, Model.simulation, twinFem.get(), twinSettings);
      }
      // Prepared binding paths may lie beside their collision edges by more
      // than the cut's paths may (segmentations: paths detour around
      // defects, thin rims are inset). The regions between such paths are
      // distorted, and a cut through them, placed by the region's plane
      // embedding (5.3.2), lies as far beside its collision edge: 1.5 times
      // the uncut tissue's worst is allowed (segmented menisci reach 1.25;
      // a vertex bound to a wrong edge lies tens of times farther).
      const double rimOffset =
        cutter.hasVisual()
          ? 1.5 * largestEdgeBindingOffset(cutter.visual(), cutter.collision()).distance
          : 0.0;
      ASSERT_TRUE(cutterIsConsistent(cutter, Model.simulation, rimOffset))
        << Model.name << ", uncut";
      for (int s = 0; s < sweepsPerEpisode; ++s)
      {
        const Blade blade = nextBlade(cutter);
        if (blade.triangles.empty())
          continue;
        const std::size_t vertices = cutter.collision().vertexCount();
        const std::size_t hexahedra = cutter.simulation().hexahedronCount();
        try
        {
          const auto report = cutter.cut(blade);
          ASSERT_EQ(report.visualError, "") << Model.name << ", episode " << e << ", sweep " << s;
          SplitRegions += report.visual.splitRegions;
          RegionsLocated += report.visual.regionsLocated;
          FarTriangles += report.visual.farTriangles;
          LazyVertices += report.visual.leftToHistory.size();
          // Counts grow by what the cut touched only: copies of touched
          // hexahedra, at most one edge point and copies per changed triangle.
          const auto& touched = report.simulation.touchedHexahedra;
          EXPECT_EQ(cutter.simulation().hexahedronCount() - hexahedra,
            report.simulation.newHexahedra.size());
          for (const auto& [copy, source] : report.simulation.newHexahedra)
            EXPECT_TRUE(std::binary_search(touched.begin(), touched.end(), source));
          EXPECT_LE(cutter.collision().vertexCount() - vertices,
            4 * report.collision.changedTriangles.size());
        }
        catch (const InvalidInputError&)
        {
          ++Refused;
          ASSERT_EQ(cutter.collision().vertexCount(), vertices);
        }
        if (twin)
        {
          try
          {
            twin->cut(blade);
          }
          catch (const InvalidInputError&)
          {
          }
          ASSERT_TRUE(sameVisualState(cutter, *twin))
            << Model.name << ", episode " << e << ", sweep " << s << ": against the twin "
            << (CompareWith == Twin::OneThread
                   ? "on one thread"
                   : (CompareWith == Twin::EagerBinding ? "of eager bindings"
                                                        : "of union-find pieces"));
        }
        ++Sweeps;
        ASSERT_TRUE(cutterIsConsistent(cutter, Model.simulation, rimOffset))
          << Model.name << ", episode " << e << ", sweep " << s;
        ASSERT_EQ(fem.nodeCount(), cutter.simulation().nodeCount());
        ASSERT_TRUE(fem.step().ok) << Model.name << ", episode " << e << ", sweep " << s;
        if (twinFem)
          twinFem->step();
      }
    }
  }
  int Sweeps = 0;
  int Refused = 0;
  /// Over all sweeps: regions of split collision triangles, and those whose
  /// pieces were found by location (VisualCutResult).
  std::size_t SplitRegions = 0;
  std::size_t RegionsLocated = 0;
  /// Over all sweeps: triangles of split regions that lay far from the cut
  /// (VisualCutResult::farTriangles).
  std::size_t FarTriangles = 0;
  /// Inner vertices the cuts left to the split history (lazy binding).
  std::size_t LazyVertices = 0;
  /// Cut the bound visual mesh too.
  const VisualCollisionBinding* Binding = nullptr;
  /// With a binding, a twin cutter cuts the same blades and must end each
  /// sweep with the same visual mesh, binding and embedding, bit for bit:
  /// on one thread while every episode cuts on several (OneThread), or
  /// finding the pieces of every split region by the union-find
  /// (UnionFindPieces, against VisualCutSettings::piecesByLocation), or
  /// rebinding every vertex at once (EagerBinding, against
  /// VisualCutSettings::lazyBinding: the same resolved bindings).
  enum class Twin
  {
    None,
    OneThread,
    UnionFindPieces,
    EagerBinding
  };
  Twin CompareWith = Twin::None;

  static ::testing::AssertionResult sameVisualState(const TissueCutter& a, const TissueCutter& b)
  {
    const ::testing::AssertionResult mesh = sameVisualMesh(a.visual(), b.visual());
    if (!mesh)
      return mesh;
    const HexahedralEmbedding& x = a.visualEmbedding();
    const HexahedralEmbedding& y = b.visualEmbedding();
    if (x.localCoordinates() != y.localCoordinates())
      return ::testing::AssertionFailure() << "visual embeddings differ";
    for (std::size_t v = 0; v < x.pointCount(); ++v)
      if (x.hexahedron(v) != y.hexahedron(v))
        return ::testing::AssertionFailure() << "visual vertex " << v << " in another hexahedron";
    return ::testing::AssertionSuccess();
  }

private:
  double uniform(double a, double b)
  {
    return std::uniform_real_distribution<double>(a, b)(Random);
  }
  Vector3 pointIn(const BoundingBox& box)
  {
    return Vector3(uniform(box.min().x(), box.max().x()),
      uniform(box.min().y(), box.max().y()),
      uniform(box.min().z(), box.max().z()));
  }

  Blade nextBlade(const TissueCutter& cutter)
  {
    const auto current = cutter.currentCollisionPositions();
    const BoundingBox box = boundingBoxOf(current);
    const double size = box.diagonal().norm();
    const Vector3 up = Vector3::UnitZ() * size;
    const int kind = std::uniform_int_distribution<int>(0, 9)(Random);
    const auto& tris = cutter.collision().triangles();
    const Triangle& tri =
      tris[std::uniform_int_distribution<std::size_t>(0, tris.size() - 1)(Random)];
    switch (kind)
    {
      case 0: // along an edge of the collision mesh
        return Blade::sweptSegment(
          current[tri[0]] - up, current[tri[0]] + up, current[tri[1]] - up, current[tri[1]] + up);
      case 1: // through a vertex
      {
        const Vector3 through = current[tri[0]];
        const Vector3 d = Vector3(uniform(-1, 1), uniform(-1, 1), 0).normalized() * 0.3 * size;
        return Blade::sweptSegment(
          through - d - up, through - d + up, through + d - up, through + d + up);
      }
      case 2: // zero length: refused
      {
        const Vector3 p = pointIn(box);
        return Blade::sweptSegment(p - up, p + up, p - up, p + up);
      }
      case 3: // repeated in place
        if (!Last.empty())
          return Last;
        [[fallthrough]];
      case 4: // short progressive step from the last blade's end
      {
        const Vector3 from = Last.empty() ? pointIn(box) : Vector3(Last.points[3] + up);
        const Vector3 to = from + Vector3(uniform(-1, 1), uniform(-1, 1), 0) * 0.08 * size;
        Last = Blade::sweptSegment(from - up, from + up, to - up, to + up);
        return Last;
      }
      case 5: // a bite outline
      {
        const Vector3 centre = pointIn(box);
        const double radius = uniform(0.03, 0.2) * size;
        std::vector<Vector3> low, high;
        for (int i = 0; i < 12; ++i)
        {
          const double a = 2.0 * M_PI * (i + uniform(0, 0.5)) / 12.0;
          const Vector3 p = centre + radius * Vector3(std::cos(a), std::sin(a), 0);
          low.push_back(p - up);
          high.push_back(p + up);
        }
        return Blade::sweptOutline(low, high);
      }
      default: // a straight sweep across, tilted
      {
        const Vector3 a = pointIn(box), b = pointIn(box);
        const Vector3 tilt(uniform(-0.3, 0.3), uniform(-0.3, 0.3), 1.0);
        Last =
          Blade::sweptSegment(a - tilt * size, a + tilt * size, b - tilt * size, b + tilt * size);
        return Last;
      }
    }
  }

  const TissueModel& Model;
  std::mt19937 Random;
  Blade Last;
};

inline int sweepScale()
{
  // THINTISSUE_CUT_SOAK=N runs N times as many sweeps (a longer soak).
  const char* soak = std::getenv("THINTISSUE_CUT_SOAK");
  return soak ? std::max(1, std::atoi(soak)) : 1;
}
} // namespace cutting_test
} // namespace thintissue

#endif
