// Suite "collision": a full physics step (collision meshes updated from the
// hexahedra, tool and obstacle contacts, implicit FEM step) for the knee
// scene of thesis table 6-2 -- the meniscus pressed onto the tibia by the
// hook -- at the three multi-resolution settings. The tool is its centre
// line in every setting (triangle-mesh tools are not supported yet), so
// setting 1 here is lighter than the thesis's.
#include "BenchmarkRegistry.h"

#include "CorotationalHexFem.h"
#include "KneeModels.h"
#include "MeniscusModel.h"
#include "SurgicalInstruments.h"
#include "ToolContacts.h"

namespace
{
using namespace thintissue;
using namespace thintissue::bench;

struct KneeSetting
{
  std::string name;
  bool fullResolutionMeniscus;
  bool fullResolutionBones;
  double thesisMilliseconds;
};

} // namespace

THINTISSUE_BENCHMARK_SUITE(collisionSuite,
  "collision",
  "full physics step with contacts: meniscus pressed onto the tibia by the hook (table 6-2)")
(const BenchmarkContext& context, BenchmarkReporter& reporter)
{
  const MeniscusModel meniscus = makeMeniscus();
  const KneeSurroundings knee = makeKneeSurroundings();
  LinearMaterial material; // thesis 4.5, in mm, N, s
  material.youngModulus = 150.0;
  material.poissonRatio = 0.49;
  material.density = 1.1e-9;
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.001;

  // The hook's centre line, placed with its tip 0.3 mm into the meniscus's
  // upper surface near the inner edge, handle up and forward.
  const SurgicalInstrumentModel hook = makeSurgicalInstrument(SurgicalInstrumentType::ProbeHook);
  const ParametricSolid solid = makeMeniscusSolid(MeniscusParameters{});
  const Vector3 touch = solid.point(ParameterPoint(0.5, 0.2, 1.0)) - Vector3(0.0, 0.0, 0.3);
  const Vector3 handle = Vector3(-0.3, 0.6, 0.75).normalized();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond::FromTwoVectors(Vector3::UnitZ(), handle).toRotationMatrix();
  pose.translation() = touch;
  std::vector<ToolCapsule> tool;
  for (const auto& segment : hook.centreLine)
  {
    tool.push_back({ pose * segment.start, pose * segment.end, segment.radius });
  }

  const std::vector<KneeSetting> knees = {
    { "setting 1 (meniscus and bones full resolution)", true, true, 29.5 },
    { "setting 2 (bones reduced)", true, false, 8.95 },
    { "setting 3 (meniscus reduced to 105 vertices with radii)", false, false, 6.5 },
  };
  for (const auto& setting : knees)
  {
    CorotationalHexFem fem(meniscus.simulation, material, settings);
    TriangleMesh meniscusCollision =
      setting.fullResolutionMeniscus ? meniscus.visual : meniscus.collision;
    DeformableCollisionMesh collision(meniscusCollision, meniscus.simulation);
    const StaticObstacle tibia(
      setting.fullResolutionBones ? knee.tibia.visual : knee.tibia.collision);
    const StaticObstacle femur(
      setting.fullResolutionBones ? knee.femur.visual : knee.femur.collision);
    const StaticObstacle cartilage(knee.tibialCartilage.visual);
    std::vector<EmbeddedContact> springs;
    std::vector<ToolContact> toolContacts;
    std::vector<ObstacleContact> obstacleContacts;
    auto physicsStep = [&]
    {
      springs.clear();
      toolContacts.clear();
      obstacleContacts.clear();
      collision.update(fem.positions());
      findToolContacts(collision, tool, 50.0, 0.01, springs, toolContacts);
      for (const StaticObstacle* obstacle : { &tibia, &femur, &cartilage })
      {
        findObstacleContacts(collision, *obstacle, 50.0, 0.01, springs, obstacleContacts);
      }
      fem.setContacts(springs);
      fem.step();
    };
    for (int k = 0; k < 20; ++k)
    {
      physicsStep();
    }
    const int steps = context.quick ? 2 : 100;
    const double milliseconds = 1e3 *
                                medianSeconds(
                                  [&]
                                  {
                                    for (int k = 0; k < steps; ++k)
                                    {
                                      physicsStep();
                                    }
                                  },
                                  context.quick ? 1 : 5,
                                  false) /
                                steps;
    reporter.report("knee " + setting.name + ", " + std::to_string(collision.positions().size()) +
                      " meniscus collision vertices, " + std::to_string(toolContacts.size()) +
                      " tool and " + std::to_string(obstacleContacts.size()) + " obstacle contacts",
      "physics step",
      milliseconds,
      "ms",
      setting.thesisMilliseconds);
  }
}
