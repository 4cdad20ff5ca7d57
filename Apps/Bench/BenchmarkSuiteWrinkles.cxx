// Suite "wrinkles": the wrinkle step of thesis 6.4.1 (296 monitor points,
// 70 selected, the 6,096-face meniscus: 0.4 ms a step, 12.9 KB of monitor
// and region points) and the automatic derivation of the data points.
#include "BenchmarkRegistry.h"

#include "AutomaticMonitorCurves.h"
#include "MeniscusModel.h"
#include "WrinkleGenerator.h"

#include <cmath>

namespace
{
using namespace thintissue;
using namespace thintissue::bench;

/// The spacing that gives `count` monitor points along the data curves.
double spacingFor(const std::vector<WrinkleDataCurve>& data, int count)
{
  const MonitorPointSet fine = resampleMonitorCurves(data, 0.01);
  double length = 0.0;
  for (std::size_t k = 1; k < fine.size(); ++k)
  {
    length += (fine.monitorPoints[k] - fine.monitorPoints[k - 1]).norm();
  }
  return length / (count - 1) * 1.0005;
}

/// Hexahedron nodes pressed down around `centre` by `depth` (a smooth dent).
std::vector<Vector3> dented(const HexahedralMesh& mesh, const Vector3& centre, double depth)
{
  std::vector<Vector3> nodes = mesh.nodes;
  for (Vector3& x : nodes)
  {
    x.z() -= depth * std::exp(-(x - centre).head<2>().squaredNorm() / 16.0);
  }
  return nodes;
}

/// Seconds per step of update + applyTo, wrinkling, over `steps` steps.
double wrinklingStep(const MeniscusModel& model, const MonitorPointSet& monitors, int steps)
{
  WrinkleGenerator generator(monitors, model.simulation, model.visual);
  WrinkleContactState contacts;
  contacts.lowerSurfaceContacts = 5;
  contacts.instrumentTouches = true;
  contacts.instrumentContact = monitors.monitorPoints[monitors.size() / 2];
  const Vector3 centre = contacts.instrumentContact;
  for (int k = 1; k <= 10; ++k)
  {
    generator.update(dented(model.simulation, centre, 0.1 * k), contacts);
  }
  const std::vector<Vector3> a = dented(model.simulation, centre, 0.9);
  const std::vector<Vector3> b = dented(model.simulation, centre, 0.85);
  generator.update(a, contacts); // the reversal: wrinkling from here on
  std::vector<Vector3> surface = model.visual.positions;
  return medianSeconds(
           [&]
           {
             for (int k = 0; k < steps; ++k)
             {
               generator.update(k % 2 ? a : b, contacts);
               generator.applyTo(surface);
             }
           },
           5) /
         steps;
}

} // namespace

THINTISSUE_BENCHMARK_SUITE(wrinklesSuite,
  "wrinkles",
  "procedural wrinkles (ch. 4): step time and storage for 296 monitor points on the 6,096-face "
  "meniscus, automatic data points")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const MeniscusModel model = makeMeniscus(examinationMeniscusParameters());
  const std::vector<WrinkleDataCurve> data = wrinkleDataCurves(model.monitorCurves);
  const MonitorPointSet monitors = resampleMonitorCurves(data, spacingFor(data, 296));
  const std::string name = std::to_string(monitors.size()) + " monitor points, 70 selected, " +
                           std::to_string(model.visual.triangleCount()) + "-face meniscus";
  const int steps = context.quick ? 100 : 2000;
  reporter.report(name, "step", wrinklingStep(model, monitors, steps) * 1e3, "ms", 0.4);
  reporter.report(name,
    "stored monitor and region points",
    static_cast<double>(monitors.storedBytes()) / 1024.0,
    "KB",
    12.9);
  const WrinkleInfluence influence(monitors, model.visual.positions, model.visual.triangles);
  reporter.report(name,
    "affected surface points (runtime)",
    static_cast<double>(influence.memoryBytes()) / 1024.0,
    "KB");

  // Derivation (4.3 step one) and resampling (steps two and three) apart.
  const std::string automaticName = "automatic data points, " +
                                    std::to_string(model.collision.vertexCount()) +
                                    "-vertex collision mesh of the meniscus";
  std::vector<WrinkleDataCurve> automatic;
  const double derive = medianSeconds([&]
    { automatic = deriveWrinkleDataCurves(model.collision, model.collisionRadii()); },
    context.quick ? 1 : 11);
  reporter.report(automaticName, "derivation", derive * 1e3, "ms");
  const double spacing = spacingFor(data, 296);
  MonitorPointSet resampled;
  const double resample = medianSeconds(
    [&] { resampled = resampleMonitorCurves(automatic, spacing); }, context.quick ? 1 : 11);
  reporter.report(automaticName + ", resampled to " + std::to_string(resampled.size()) + " points",
    "resampling",
    resample * 1e3,
    "ms");
}
