// Shared by the operations image tests: the meniscus with a longitudinal
// tear cut by the instruments, drawn as the thesis's figures draw it
// (tissue pink, cut surface dark red, triangle edges shown), the removed
// pieces left out.
#ifndef OperationSceneHelpers_h
#define OperationSceneHelpers_h

#include "OperationTestHelpers.h"
#include "ThinTissueImageTest.h"
#include "TissueModelScene.h"
#include "vtkThinTissueConversion.h"

#include <vtkCellData.h>
#include <vtkUnsignedCharArray.h>

namespace thintissue::testing
{

/// The meniscus (with a tear of `tear` type), bound.
struct BoundMeniscusModel
{
  explicit BoundMeniscusModel(MeniscusTearType tear)
    : model(makeMeniscus(
        [tear]
        {
          MeniscusParameters p;
          p.tear = defaultMeniscusTear(tear);
          return p;
        }()))
    , binding(bindVisualToCollision(model.visual, model.collision))
  {
  }
  MeniscusModel model;
  VisualCollisionBinding binding;
};

/// A cutter whose free pieces drop out, its cut surface jagged.
inline TissueCutter jaggedCutter(const BoundMeniscusModel& m, double amplitude)
{
  TissueCutterSettings settings;
  settings.freePieces = FreePieceHandling::Drop;
  settings.visual.jaggedAmplitude = amplitude;
  settings.visual.jaggedSeed = 3u;
  return TissueCutter(m.binding, m.model.simulation, nullptr, settings);
}

/// The punch bites `count` times along the inner border, from fraction
/// `from` to `to` of it, each 1 mm into the tissue.
inline void punchAlongTheBorder(TissueCutter& cutter,
  const MeniscusModel& model,
  int count,
  double from = 0.35,
  double to = 0.65)
{
  const MonitorCurve& border = model.monitorCurves.front();
  for (int k = 0; k < count; ++k)
  {
    InstrumentAction punch(makeSurgicalInstrument(SurgicalInstrumentType::Punch));
    const double at = from + (to - from) * k / std::max(1, count - 1);
    const auto i = static_cast<std::size_t>(at * (border.monitorPoints.size() - 1));
    const RigidPose pose = operations_test::punchOverBorder(punch.instrument(), border, i, 1.0);
    punch.apply(cutter, operations_test::command(0.0, pose, 1.0));
    punch.apply(cutter, operations_test::command(0.1, pose, 0.0));
  }
}

/// The tissue still there (rest positions), coloured by material.
inline vtkSmartPointer<vtkActor> remainingTissueActor(const TissueCutter& cutter)
{
  TriangleMesh mesh = cutter.visual().mesh();
  const std::vector<char> active = cutter.activeVisualTriangles();
  std::vector<Triangle> kept;
  std::vector<VisualMaterial> materials;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    if (active[t])
    {
      kept.push_back(mesh.triangles[t]);
      materials.push_back(cutter.visual().triangleMaterials()[t]);
    }
  mesh.triangles = kept;
  mesh.textureCoordinates.clear();
  mesh.textureCorners.clear();
  mesh.computeVertexNormals();
  auto polyData = toPolyData(mesh);
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("MaterialColour");
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(static_cast<vtkIdType>(materials.size()));
  const unsigned char tissue[3] = { 236, 170, 160 }, cut[3] = { 150, 30, 35 };
  for (std::size_t t = 0; t < materials.size(); ++t)
    colours->SetTypedTuple(
      static_cast<vtkIdType>(t), materials[t] == VisualMaterial::CutSurface ? cut : tissue);
  polyData->GetCellData()->AddArray(colours);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(polyData);
  mapper->SetScalarModeToUseCellFieldData();
  mapper->SelectColorArray("MaterialColour");
  mapper->SetColorModeToDirectScalars();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->EdgeVisibilityOn();
  actor->GetProperty()->SetEdgeColor(0.35, 0.2, 0.2);
  return actor;
}

/// A viewport looking at `focus` from `from` (z up).
inline vtkSmartPointer<vtkRenderer> viewport(vtkActor* actor,
  const std::array<double, 4>& where,
  const Vector3& focus,
  const Vector3& from)
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetViewport(where[0], where[1], where[2], where[3]);
  renderer->SetBackground(0.12, 0.14, 0.18);
  renderer->AddActor(actor);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(focus.x(), focus.y(), focus.z());
  camera->SetPosition(from.x(), from.y(), from.z());
  camera->SetViewUp(0.0, 0.0, 1.0);
  renderer->ResetCameraClippingRange();
  return renderer;
}

} // namespace thintissue::testing

#endif
