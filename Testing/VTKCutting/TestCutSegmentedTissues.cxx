// Cutting real-looking anatomy (issue 13 on issue 14's input): the intact
// and torn menisci through the segmentation test bed (voxelized at MRI
// spacing, blurred, noisy, iso-surfaced: rough, stair-stepped, thin-rimmed),
// prepared automatically, then cut by random blade sweeps with every cutting
// invariant checked after each cut; and the MRI-segmented menisci of
// ../shared/data in metres when the data is present. The same prepared
// tissues also take random surgical operations (thesis 6.4: punch bites,
// shaver passes, contouring; RandomOperations of Testing/Operations) placed
// over the thin border curves derived from their collision mesh.
#include "vtkSimulatedSegmentationFilter.h"

#include "AutomaticMonitorCurves.h"
#include "MeniscusModel.h"
#include "MeshImport.h"
#include "MeshRepair.h"
#include "MeshValidation.h"
#include "RandomOperations.h"
#include "RandomSweeps.h"
#include "ThinTissueTestSupport.h"
#include "TissueBundle.h"
#include "vtkThinTissueConversion.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using namespace thintissue;
using thintissue::cutting_test::RandomSweeps;
using thintissue::cutting_test::sweepScale;

/// The meniscus with the given tear as a segmentation gives it: 0.35 x 0.4
/// x 0.8 mm voxels, the default blur, 5 % noise.
TriangleMesh segmentedMeniscus(MeniscusTearType tear, unsigned seed)
{
  MeniscusParameters parameters;
  parameters.tear = defaultMeniscusTear(tear);
  const TriangleMesh tissue = makeMeniscus(parameters).visual;
  vtkNew<vtkSimulatedSegmentationFilter> filter;
  filter->SetInputData(toPolyData(tissue));
  filter->SetVoxelSpacing(0.35, 0.4, 0.8);
  filter->SetNoiseAmplitude(0.05);
  filter->SetSeed(seed);
  filter->Update();
  const TriangleMesh mesh = fromPolyData(filter->GetOutput(), tissue.name + " segmented");
  // Flying edges leaves degenerate triangles where it passes through a
  // sample: repaired, as the preparation's error advises.
  return validateTriangleMesh(mesh).degenerateTriangles.count > 0 ? repairTriangleMesh(mesh) : mesh;
}

/// The bundle's meshes as a tissue model for the sweeps.
TissueModel modelOf(const TissueBundle& bundle, const std::string& name)
{
  TissueModel model;
  model.name = name;
  model.visual = bundle.visual;
  model.collision = bundle.collision;
  model.simulation = bundle.simulation;
  return model;
}

/// `episodes` runs of 20 random sweeps over the prepared tissue, its bound
/// visual mesh cut too; the invariants checked by RandomSweeps. The rough
/// regions of a segmentation fold where procedural ones do not: each sweep
/// must also end as on a twin that finds every region's pieces by the
/// union-find (VisualCutSettings::piecesByLocation).
void sweepPrepared(const TissueBundle& bundle, const std::string& name, unsigned seed, int episodes)
{
  const TissueModel model = modelOf(bundle, name);
  RandomSweeps sweeps(model, seed);
  sweeps.Binding = &bundle.binding;
  sweeps.CompareWith = RandomSweeps::Twin::UnionFindPieces;
  sweeps.run(episodes * sweepScale(), 20);
  EXPECT_EQ(sweeps.Sweeps, 20 * episodes * sweepScale()) << name;
  EXPECT_GT(sweeps.RegionsLocated, sweeps.SplitRegions / 2) << name;
}

/// Random operations on the prepared tissue (in mm): punch bites and
/// shaver passes over its thin border (the curves the wrinkles would get,
/// AutomaticMonitorCurves), contouring on its cut rim, every invariant after
/// each; some bites must remove and some passes smooth.
void operatePrepared(const TissueBundle& bundle, const std::string& name, unsigned seed)
{
  using namespace thintissue::operations_test;
  std::vector<MonitorCurve> curves;
  for (const WrinkleDataCurve& derived :
    deriveWrinkleDataCurves(bundle.collision, bundle.binding.collisionRadii))
  {
    MonitorCurve curve;
    curve.name = derived.name;
    curve.monitorPoints = derived.monitorPoints;
    curve.regionPoints = derived.regionPoints;
    curve.thickness = derived.thickness;
    curves.push_back(std::move(curve));
  }
  const OperatedTissue tissue{ name, bundle.binding, bundle.simulation, curves };
  RandomOperations operations(tissue, seed);
  operations.run(4 * soakScale(), 50);
  EXPECT_EQ(operations.Operations, 200 * soakScale()) << name;
  EXPECT_GT(operations.Removals, 5) << name;
  EXPECT_GT(operations.Contours, 5) << name;
}

/// The test bed's meniscus prepared for the sweeps and the operations.
TissueBundle preparedSegmentedMeniscus(MeniscusTearType tear)
{
  TissuePreparationSettings settings;
  settings.collision.vertexCount = 105;
  settings.hexahedronCount = 42;
  return prepareTissue(segmentedMeniscus(tear, 7u + static_cast<unsigned>(tear)), settings);
}

/// The MRI menisci of ../shared/data (Smith 2019, right knee, medial and
/// lateral); none when the data is not there.
std::vector<std::string> mriMeniscusFiles()
{
  const std::string data = thintissue::testing::sharedDataDirectory();
  const std::string directory = data + "/knee-smith2019";
  if (data.empty() || !std::filesystem::exists(directory))
    return {};
  return { directory + "/smith2019-R-medial-meniscus.stl",
    directory + "/smith2019-R-lateral-meniscus.stl" };
}

/// An MRI meniscus of ../shared/data (metres) in millimetres, as the
/// simulator takes it, prepared as ThinTissuePrepare does.
TissueBundle preparedMriMeniscus(const std::string& file)
{
  TriangleMesh mesh = readTriangleMesh(file);
  for (Vector3& x : mesh.positions)
    x *= 1000.0;
  const PreparedTissues prepared = prepareTissues(mesh, {});
  if (prepared.tissues.size() != 1u)
    throw std::runtime_error(file + ": " + std::to_string(prepared.tissues.size()) + " tissues");
  return prepared.tissues.front();
}

class CutSegmentedMeniscus : public ::testing::TestWithParam<MeniscusTearType>
{
};

} // namespace

TEST_P(CutSegmentedMeniscus, RandomSweepsKeepEveryInvariant)
{
  const TissueBundle bundle = preparedSegmentedMeniscus(GetParam());
  sweepPrepared(bundle, "segmented " + bundle.visual.name, 31u, 10);
}

TEST_P(CutSegmentedMeniscus, RandomOperationsKeepEveryInvariant)
{
  const TissueBundle bundle = preparedSegmentedMeniscus(GetParam());
  operatePrepared(bundle, "segmented " + bundle.visual.name, 1901u);
}

INSTANTIATE_TEST_SUITE_P(Tears,
  CutSegmentedMeniscus,
  ::testing::Values(MeniscusTearType::None,
    MeniscusTearType::Longitudinal,
    MeniscusTearType::Radial,
    MeniscusTearType::Flap),
  [](const ::testing::TestParamInfo<MeniscusTearType>& info)
  {
    std::string name = thintissue::meniscusTearTypeName(info.param);
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
  });

// The medial and lateral menisci segmented from MRI (Smith 2019), in metres,
// prepared as ThinTissuePrepare does, cut at random.
TEST(CutMriMeniscus, RandomSweepsKeepEveryInvariant)
{
  const std::vector<std::string> files = mriMeniscusFiles();
  if (files.empty())
    GTEST_SKIP() << "no shared data (knee-smith2019)";
  for (const std::string& file : files)
  {
    const PreparedTissues prepared = prepareTissues(readTriangleMesh(file), {});
    ASSERT_EQ(prepared.tissues.size(), 1u) << file;
    sweepPrepared(prepared.tissues.front(), file, 57u, 10);
  }
}

// The MRI menisci in millimetres under random operations.
TEST(CutMriMeniscus, RandomOperationsKeepEveryInvariant)
{
  const std::vector<std::string> files = mriMeniscusFiles();
  if (files.empty())
    GTEST_SKIP() << "no shared data (knee-smith2019)";
  for (const std::string& file : files)
  {
    operatePrepared(preparedMriMeniscus(file), file, 1911u);
  }
}
