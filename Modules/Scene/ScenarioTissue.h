// The tissue a scenario names (Scenario.h, key "tissue"), built: a
// procedural model (meniscus with its monitor data, a cruciate ligament or
// the tibial cartilage of the knee, the thin sheet), a mesh file prepared
// as it loads (collision mid-surface, hexahedra, binding), or a bundle made
// by ThinTissuePrepare; then the nodes the scenario holds still.
#ifndef ScenarioTissue_h
#define ScenarioTissue_h

#include "KneeModels.h"
#include "MeniscusModel.h"
#include "Scenario.h"
#include "ThinTissueSceneModule.h"

#include <memory>
#include <vector>

namespace thintissue
{

class VisualCollisionBinding;

struct ScenarioTissue
{
  ScenarioTissue();
  ~ScenarioTissue();
  ScenarioTissue(ScenarioTissue&&) noexcept;
  ScenarioTissue& operator=(ScenarioTissue&&) noexcept;

  TissueModel model;
  /// The meniscus's monitor data (wrinkles); empty for other tissues.
  std::vector<MonitorCurve> monitorCurves;
  /// The binding a file or bundle came with (null for procedural models:
  /// bound when a cutting instrument needs it).
  std::unique_ptr<VisualCollisionBinding> binding;
};

/// Throws InvalidInputError / FileError naming the scenario and the key
/// ("tissue.file": unreadable or unpreparable mesh, bad bundle).
THINTISSUESCENE_EXPORT ScenarioTissue makeScenarioTissue(const ScenarioDescription& scenario,
  const KneeSurroundings& knee);

/// Holds still the nodes `rule` names ("none", "ends", "bottom"; "model"
/// leaves the mesh's own attachments).
THINTISSUESCENE_EXPORT void holdNodes(HexahedralMesh& mesh, const std::string& rule);

} // namespace thintissue

#endif
