// Suites "io" (mesh import) and "mesh" (adjacency, validation, conversion).
#include "BenchmarkRegistry.h"

#include "MeshImport.h"
#include "MeshPrimitives.h"
#include "MeshValidation.h"
#include "TriangleMeshAdjacency.h"
#include "vtkThinTissueConversion.h"
#include "vtkThinTissueMeshReader.h"

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <filesystem>

namespace
{

using namespace thintissue;
using namespace thintissue::bench;

/// The generated 1M-triangle slab (4 (500*500 + 2*500) = 1,004,000 triangles);
/// 20K triangles in quick mode.
TriangleMesh largeSlab(bool quick)
{
  SlabSurfaceParameters parameters;
  parameters.cellsX = parameters.cellsY = quick ? 70 : 500;
  parameters.cellsZ = 1;
  return makeSlabSurface(parameters);
}

std::string sizeLabel(const TriangleMesh& mesh)
{
  return std::to_string(mesh.triangleCount()) + " triangles";
}

void reportThroughput(BenchmarkReporter& reporter,
  const std::string& caseName,
  std::size_t triangles,
  double seconds)
{
  reporter.report(caseName, "time", seconds * 1e3, "ms");
  reporter.report(caseName, "throughput", static_cast<double>(triangles) / seconds, "triangles/s");
}

} // namespace

THINTISSUE_BENCHMARK_SUITE(ioSuite, "io", "mesh import: steak OBJ, 1M-triangle OBJ and VTP")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const int repetitions = context.quick ? 1 : 5;
  const std::string steak = context.sharedDataDirectory + "/steak/steak.obj";
  if (std::filesystem::exists(steak))
  {
    std::size_t triangles = 0;
    const double seconds =
      medianSeconds([&] { triangles = readTriangleMesh(steak).triangleCount(); }, repetitions);
    reportThroughput(
      reporter, "steak obj (" + std::to_string(triangles) + " triangles)", triangles, seconds);
  }
  else
  {
    reporter.skip("steak obj", steak + " not found");
  }

  const TriangleMesh slab = largeSlab(context.quick);
  const std::string base = context.temporaryDirectory + "/thintissue-bench-slab";
  writeObj(slab, base + ".obj");
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetFileName((base + ".vtp").c_str());
    writer->SetInputData(toPolyData(slab));
    writer->SetDataModeToAppended();
    writer->Write();
  }
  const double objSeconds =
    medianSeconds([&] { readTriangleMesh(base + ".obj"); }, context.quick ? 1 : 3);
  reportThroughput(
    reporter, "slab obj (" + sizeLabel(slab) + ")", slab.triangleCount(), objSeconds);
  const double vtpSeconds = medianSeconds(
    [&]
    {
      vtkNew<vtkThinTissueMeshReader> reader;
      reader->SetFileName((base + ".vtp").c_str());
      reader->Update();
    },
    context.quick ? 1 : 3);
  reportThroughput(
    reporter, "slab vtp (" + sizeLabel(slab) + ")", slab.triangleCount(), vtpSeconds);
  std::filesystem::remove(base + ".obj");
  std::filesystem::remove(base + ".vtp");
}

THINTISSUE_BENCHMARK_SUITE(meshSuite, "mesh", "adjacency, validation and VTK conversion")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const int repetitions = context.quick ? 1 : 5;
  const TriangleMesh slab = largeSlab(context.quick);
  const std::string label = " (" + sizeLabel(slab) + ")";
  reportThroughput(reporter,
    "adjacency" + label,
    slab.triangleCount(),
    medianSeconds([&] { TriangleMeshAdjacency adjacency(slab); }, repetitions));
  reportThroughput(reporter,
    "validation" + label,
    slab.triangleCount(),
    medianSeconds([&] { validateTriangleMesh(slab); }, repetitions));
  reportThroughput(reporter,
    "to vtkPolyData" + label,
    slab.triangleCount(),
    medianSeconds([&] { toPolyData(slab); }, repetitions));
  const auto polyData = toPolyData(slab);
  reportThroughput(reporter,
    "from vtkPolyData" + label,
    slab.triangleCount(),
    medianSeconds([&] { fromPolyData(polyData, "bench"); }, repetitions));
}
