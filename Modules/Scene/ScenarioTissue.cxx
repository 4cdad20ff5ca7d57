#include "ScenarioTissue.h"

#include "MeshImport.h"
#include "MeshValidation.h"
#include "SheetThickening.h"
#include "ThinSheetModel.h"
#include "ThinTissueError.h"
#include "TissueBundle.h"

#include <algorithm>

namespace thintissue
{

ScenarioTissue::ScenarioTissue() = default;
ScenarioTissue::~ScenarioTissue() = default;
ScenarioTissue::ScenarioTissue(ScenarioTissue&&) noexcept = default;
ScenarioTissue& ScenarioTissue::operator=(ScenarioTissue&&) noexcept = default;

namespace
{

TissueModel fromBundle(TissueBundle bundle, ScenarioTissue& tissue)
{
  TissueModel model;
  model.name = bundle.visual.name;
  model.visual = bundle.visual;
  model.collision = bundle.collision;
  model.simulation = bundle.simulation;
  tissue.binding = std::make_unique<VisualCollisionBinding>(std::move(bundle.binding));
  return model;
}

/// A mesh file in millimetres (the scene's unit), thickened if asked (an
/// open sheet), prepared.
TissueBundle preparedMesh(const std::string& path, const std::string& units, double thickness)
{
  TriangleMesh mesh = readTriangleMesh(path);
  const double largest = mesh.boundingBox().sizes().maxCoeff();
  const LengthUnits unit =
    units.empty() ? detectLengthUnits(largest).units : *lengthUnitsNamed(units);
  const double toMillimetres = unit.metresPerUnit / 0.001;
  for (Vector3& x : mesh.positions)
    x *= toMillimetres;
  if (thickness > 0.0)
    mesh = thickenOpenSheets(mesh, thickness);
  TissuePreparationSettings settings;
  settings.units = lengthUnitsNamed("mm");
  try
  {
    return prepareTissue(mesh, settings);
  }
  catch (const InvalidInputError& e)
  {
    const bool open = thickness == 0.0 && validateTriangleMesh(mesh).borderEdges.count > 0;
    throw InvalidInputError(e.what() + std::string(open ? " (a tissue segmented as one open "
                                                          "surface: give 'tissue.thickness' in mm, "
                                                          "or --tissue-thickness)"
                                                        : ""));
  }
}

/// A bundle converted to millimetres (the scene's unit) if it was made in
/// others (a segmentation in metres).
TissueBundle bundleInMillimetres(const std::string& path)
{
  TissueBundle bundle = readTissueBundle(path);
  if (bundle.units && bundle.units->name != "mm")
  {
    convertTissueBundleUnits(bundle, *lengthUnitsNamed("mm"));
  }
  return bundle;
}

TissueModel preparedFile(const ScenarioDescription& s, ScenarioTissue& tissue)
{
  const std::string where = "scenario '" + s.source + "': key 'tissue.file': ";
  try
  {
    if (s.tissueModel == "bundle")
      return fromBundle(bundleInMillimetres(s.tissueFile), tissue);
    return fromBundle(preparedMesh(s.tissueFile, s.tissueUnits, s.tissueThickness), tissue);
  }
  catch (const FileError& e)
  {
    throw InvalidInputError(where + e.what());
  }
  catch (const InvalidInputError& e)
  {
    throw InvalidInputError(where + e.what());
  }
}

TissueModel sheetOf(const ScenarioDescription& s)
{
  ThinSheetParameters p;
  p.width = s.sheetSize.x();
  p.depth = s.sheetSize.y();
  p.thickness = s.sheetSize.z();
  try
  {
    return makeThinSheet(p);
  }
  catch (const InvalidInputError& e)
  {
    throw InvalidInputError("scenario '" + s.source + "': key 'tissue.size': " + e.what());
  }
}

} // namespace

ScenarioTissue makeScenarioTissue(const ScenarioDescription& s, const KneeSurroundings& knee)
{
  ScenarioTissue tissue;
  if (s.tissueModel == "meniscus")
  {
    MeniscusParameters p =
      s.examinationResolution ? examinationMeniscusParameters() : MeniscusParameters{};
    p.tear = defaultMeniscusTear(s.tear);
    MeniscusModel meniscus = makeMeniscus(p);
    tissue.monitorCurves = std::move(meniscus.monitorCurves);
    tissue.model = std::move(meniscus);
  }
  else if (s.tissueModel == "anterior_cruciate_ligament")
    tissue.model = knee.anteriorCruciateLigament;
  else if (s.tissueModel == "posterior_cruciate_ligament")
    tissue.model = knee.posteriorCruciateLigament;
  else if (s.tissueModel == "tibial_cartilage")
    tissue.model = knee.tibialCartilage;
  else if (s.tissueModel == "sheet")
    tissue.model = sheetOf(s);
  else
    tissue.model = preparedFile(s, tissue);
  holdNodes(tissue.model.simulation, s.fixedNodes);
  return tissue;
}

void holdNodes(HexahedralMesh& mesh, const std::string& rule)
{
  if (rule == "model")
    return;
  mesh.fixedNodes.assign(mesh.nodeCount(), 0);
  if (rule == "none" || mesh.nodeCount() == 0)
    return;
  BoundingBox box;
  for (const Vector3& x : mesh.nodes)
    box.extend(x);
  const Vector3 size = box.sizes();
  int longest = 0;
  size.maxCoeff(&longest);
  const double margin = 0.05 * size[longest];
  for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
  {
    const Vector3& x = mesh.nodes[n];
    const bool held = rule == "ends" ? x[longest] <= box.min()[longest] + margin ||
                                         x[longest] >= box.max()[longest] - margin
                                     : x.z() <= box.min().z() + 0.1 * size.z(); // "bottom"
    mesh.fixedNodes[n] = held ? 1 : 0;
  }
}

} // namespace thintissue
