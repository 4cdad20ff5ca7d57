// Suite "models": generation time of the procedural models (the thesis
// made its models by hand in 3ds Max; no figure to compare with).
#include "BenchmarkRegistry.h"

#include "KneeModels.h"
#include "MeniscusModel.h"
#include "SurgicalInstruments.h"
#include "ThinSheetModel.h"

namespace
{
using namespace thintissue;
using namespace thintissue::bench;
} // namespace

THINTISSUE_BENCHMARK_SUITE(modelsSuite,
  "models",
  "procedural model generation: thesis sheets up to 1M triangles, meniscus, knee, instruments")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const int repetitions = context.quick ? 1 : 5;
  const int lastSheet = context.quick ? 2 : 5;
  for (int model = 1; model <= lastSheet; ++model)
  {
    const auto parameters = thesisSheetVisualResolution(model);
    std::size_t triangles = 0;
    const double seconds =
      medianSeconds([&] { triangles = makeThinSheet(parameters).visual.triangleCount(); },
        model == 5 ? 1 : repetitions);
    const std::string name = "thin sheet " + std::to_string(model) + " (" +
                             std::to_string(triangles) + " visual triangles)";
    reporter.report(name, "time", seconds * 1e3, "ms");
  }
  for (auto type : { MeniscusTearType::None,
         MeniscusTearType::Longitudinal,
         MeniscusTearType::HorizontalCleavage })
  {
    MeniscusParameters parameters;
    parameters.tear = defaultMeniscusTear(type);
    const double seconds = medianSeconds([&] { makeMeniscus(parameters); }, repetitions);
    reporter.report(
      std::string("meniscus, tear ") + meniscusTearTypeName(type), "time", seconds * 1e3, "ms");
  }
  const double knee = medianSeconds([&] { makeKneeSurroundings(); }, context.quick ? 1 : 3);
  reporter.report(
    "knee surroundings (tibia, femur, cartilage, ACL, PCL)", "time", knee * 1e3, "ms");
  const double instruments = medianSeconds(
    [&]
    {
      for (auto type : allSurgicalInstrumentTypes())
      {
        makeSurgicalInstrument(type);
      }
    },
    repetitions);
  reporter.report("six instruments", "time", instruments * 1e3, "ms");
}
