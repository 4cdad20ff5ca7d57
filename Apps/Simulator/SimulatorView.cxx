#include "SimulatorView.h"

#include "PortalMapping.h"
#include "vtkThinTissueConversion.h"

#include <vtkActor2D.h>
#include <vtkActorCollection.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCoordinate.h>
#include <vtkDoubleArray.h>
#include <vtkMatrix4x4.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkProperty.h>
#include <vtkProperty2D.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

#include <cmath>

namespace thintissue
{

namespace
{

/// A lit surface; `wet`: a tight bright highlight (synovial fluid).
vtkSmartPointer<vtkActor> surfaceActor(vtkPolyData* surface,
  const std::array<double, 3>& colour,
  bool wet)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(surface);
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  vtkProperty* p = actor->GetProperty();
  p->SetColor(colour[0], colour[1], colour[2]);
  p->SetInterpolationToPhong();
  p->SetSpecular(wet ? 0.7 : 0.2);
  p->SetSpecularPower(wet ? 60.0 : 15.0);
  p->SetDiffuse(0.8);
  p->SetAmbient(0.08);
  return actor;
}

vtkSmartPointer<vtkPolyData> withNormals(const TriangleMesh& mesh)
{
  TriangleMesh copy = mesh;
  copy.textureCoordinates.clear();
  copy.textureCorners.clear();
  copy.pointAttributes = VertexAttributes();
  copy.computeVertexNormals();
  return toPolyData(copy);
}

/// Meniscus and tissues brought in: pale, fibrocartilage white; cartilage:
/// bluish white; ligaments: pink (the posterior a little darker).
std::array<double, 3> tissueColour(const std::string& model)
{
  if (model == "tibial_cartilage")
    return { 0.82, 0.86, 0.92 };
  if (model == "anterior_cruciate_ligament")
    return { 0.88, 0.62, 0.58 };
  if (model == "posterior_cruciate_ligament")
    return { 0.84, 0.58, 0.56 };
  return { 0.96, 0.93, 0.88 };
}

} // namespace

SimulatorView::SimulatorView(const TrainingScene& scene)
  : Scene(scene)
  , Renderer(vtkSmartPointer<vtkRenderer>::New())
{
  // Synovial red-brown beyond the lit tissue.
  Renderer->SetBackground(0.12, 0.03, 0.02);
  addKnee();
  Renderer->AddActor(surfaceActor(Tissue, tissueColour(scene.scenario().tissueModel), true));
  // The cut surfaces (5.3.4): the tissue's inside, pinker and less shiny.
  Renderer->AddActor(surfaceActor(CutSurface, { 0.93, 0.78, 0.74 }, false));
  Instrument =
    surfaceActor(withNormals(scene.instrumentModel().visual), { 0.78, 0.80, 0.84 }, false);
  Instrument->GetProperty()->SetSpecular(0.9);
  Instrument->GetProperty()->SetSpecularPower(80.0);
  Renderer->AddActor(Instrument);
  addRoundFieldOfView();
}

void SimulatorView::addKnee()
{
  // Without the knee (a tissue on the bench) nothing; the knee part that is
  // the scenario's tissue is drawn as the tissue, not here.
  const ScenarioDescription& scenario = Scene.scenario();
  if (!scenario.knee)
  {
    return;
  }
  const KneeSurroundings& knee = Scene.knee();
  const auto add = [&](const auto& part, const std::array<double, 3>& colour, bool wet)
  {
    vtkSmartPointer<vtkActor> actor = surfaceActor(withNormals(part.visual), colour, wet);
    Renderer->AddActor(actor);
    return actor;
  };
  add(knee.tibia, { 0.90, 0.82, 0.60 }, false);
  Femur = add(knee.femur, { 0.90, 0.82, 0.60 }, false);
  const std::pair<const char*, const TissueModel*> softParts[] = {
    { "tibial_cartilage", &knee.tibialCartilage },
    { "anterior_cruciate_ligament", &knee.anteriorCruciateLigament },
    { "posterior_cruciate_ligament", &knee.posteriorCruciateLigament },
  };
  for (const auto& [name, part] : softParts)
  {
    if (scenario.tissueModel != name)
    {
      add(*part, tissueColour(name), true);
    }
  }
}

void SimulatorView::addRoundFieldOfView()
{
  // A black ring from the circle of the scope's image to the window's edge,
  // in normalized viewport coordinates; placeRing() keeps it round.
  vtkNew<vtkCellArray> quads;
  for (int k = 0; k < RingSegments; ++k)
  {
    const vtkIdType i = 2 * k, j = 2 * ((k + 1) % RingSegments);
    const vtkIdType quad[4] = { i, j, j + 1, i + 1 };
    quads->InsertNextCell(4, quad);
  }
  Ring = vtkSmartPointer<vtkPolyData>::New();
  Ring->SetPoints(vtkSmartPointer<vtkPoints>::New());
  Ring->SetPolys(quads);
  placeRing(1.0);
  vtkNew<vtkCoordinate> normalized;
  normalized->SetCoordinateSystemToNormalizedViewport();
  vtkNew<vtkPolyDataMapper2D> mapper;
  mapper->SetInputData(Ring);
  mapper->SetTransformCoordinate(normalized);
  vtkNew<vtkActor2D> mask;
  mask->SetMapper(mapper);
  mask->GetProperty()->SetColor(0.0, 0.0, 0.0);
  Renderer->AddActor2D(mask);
}

void SimulatorView::placeRing(double aspect)
{
  // Radius 0.47 of the height; x scaled by height / width.
  vtkPoints* points = Ring->GetPoints();
  points->SetNumberOfPoints(2 * RingSegments);
  const double sx = 1.0 / aspect;
  for (int k = 0; k < RingSegments; ++k)
  {
    const double a = 2.0 * M_PI * k / RingSegments;
    points->SetPoint(2 * k, 0.5 + 0.47 * sx * std::cos(a), 0.5 + 0.47 * std::sin(a), 0.0);
    points->SetPoint(2 * k + 1, 0.5 + 2.0 * std::cos(a), 0.5 + 2.0 * std::sin(a), 0.0);
  }
  points->Modified();
  RingAspect = aspect;
}

vtkRenderer* SimulatorView::overview()
{
  if (Overview)
  {
    return Overview;
  }
  Overview = vtkSmartPointer<vtkRenderer>::New();
  Overview->SetBackground(0.10, 0.11, 0.14);
  vtkActorCollection* actors = Renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor())
  {
    if (actor != Femur) // every actor but the femur (it hides the joint)
    {
      Overview->AddActor(actor);
    }
  }
  // The arthroscope's shaft: a line from its tip out through its portal.
  ScopeShaft = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetNumberOfPoints(2);
  ScopeShaft->SetPoints(points);
  vtkNew<vtkCellArray> line;
  const vtkIdType ends[2] = { 0, 1 };
  line->InsertNextCell(2, ends);
  ScopeShaft->SetLines(line);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(ScopeShaft);
  vtkNew<vtkActor> shaft;
  shaft->SetMapper(mapper);
  shaft->GetProperty()->SetColor(0.3, 0.8, 1.0);
  shaft->GetProperty()->SetLineWidth(3.0);
  Overview->AddActor(shaft);
  vtkCamera* camera = Overview->GetActiveCamera();
  camera->SetFocalPoint(-15.0, 5.0, 5.0);
  camera->SetPosition(-15.0, 125.0, 95.0);
  camera->SetViewUp(0.0, 0.0, 1.0);
  Overview->ResetCameraClippingRange();
  return Overview;
}

void SimulatorView::update(const SceneSnapshot& snapshot)
{
  if (Renderer->GetRenderWindow() != nullptr)
  {
    const int* size = Renderer->GetSize();
    const double aspect = size[1] > 0 ? static_cast<double>(size[0]) / size[1] : 1.0;
    if (std::abs(aspect - RingAspect) > 1e-6)
    {
      placeRing(aspect);
    }
  }
  if (snapshot.topology && snapshot.topology->version != TopologyVersion)
  {
    rebuildTissue(*snapshot.topology);
  }
  // The tissue where the scene put it (with its wrinkles). Normals: the
  // rest normals the mesh carries (interpolated from the model's, smooth)
  // turned by how the normals computed from the positions changed since
  // rest; computed normals alone streak along the binding's re-meshed
  // slivers, and their change still shows the wrinkles and the bending.
  TriangleMesh& moved = Shading;
  if (snapshot.visualPositions.size() == RestNormals.size())
  {
    moved.positions.assign(snapshot.visualPositions.begin(), snapshot.visualPositions.end());
    moved.computeVertexNormals();
    vtkPoints* points = Tissue->GetPoints();
    vtkDataArray* normals = Tissue->GetPointData()->GetNormals();
    for (std::size_t i = 0; i < moved.positions.size(); ++i)
    {
      points->SetPoint(static_cast<vtkIdType>(i), moved.positions[i].data());
      const Vector3 normal =
        (RestNormals[i] + moved.normals[i] - ComputedRestNormals[i]).normalized();
      normals->SetTuple(static_cast<vtkIdType>(i), normal.data());
    }
    updateCutSurfaceNormals(moved.positions);
    points->Modified();
    normals->Modified();
    Tissue->Modified();
    CutSurface->Modified();
  }
  placeInstrumentAndCamera(snapshot);
}

void SimulatorView::updateCutSurfaceNormals(const std::vector<Vector3>& positions)
{
  // The cut surface is the cutter's own triangulation: its computed
  // normals are smooth already. Only its vertices are touched.
  if (CutTriangles.empty())
    return;
  for (int v : CutVertices)
    CutNormals[v].setZero();
  for (const Triangle& t : CutTriangles)
  {
    const Vector3 n = (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
    for (int v : t)
      CutNormals[v] += n;
  }
  vtkDataArray* normals = CutSurface->GetPointData()->GetNormals();
  for (int v : CutVertices)
  {
    const double length = CutNormals[v].norm();
    const Vector3 n = length > 0.0 ? Vector3(CutNormals[v] / length) : Vector3::UnitZ();
    normals->SetTuple(static_cast<vtkIdType>(v), n.data());
  }
  normals->Modified();
}

void SimulatorView::placeInstrumentAndCamera(const SceneSnapshot& snapshot)
{
  const RigidPose& tool = snapshot.instrument;
  vtkNew<vtkMatrix4x4> matrix;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      matrix->SetElement(r, c, tool.rotation(r, c));
    }
    matrix->SetElement(r, 3, tool.translation[r]);
  }
  Instrument->SetUserMatrix(matrix);
  showJaws(snapshot.jawOpening);
  // The arthroscope: eye at the scope tip, VTK's headlight there too.
  const ArthroscopeView view = arthroscopeView(snapshot.scope, Scene.scenario().viewingAngle);
  vtkCamera* camera = Renderer->GetActiveCamera();
  camera->SetPosition(view.eye.data());
  camera->SetFocalPoint(view.focalPoint.data());
  camera->SetViewUp(view.viewUp.data());
  camera->SetViewAngle(70.0);
  camera->SetClippingRange(0.5, 300.0);
  if (ScopeShaft)
  {
    const RigidPose& scope = snapshot.scope;
    const Vector3 handle = scope * Vector3(0.0, 0.0, 60.0);
    ScopeShaft->GetPoints()->SetPoint(0, scope.translation.data());
    ScopeShaft->GetPoints()->SetPoint(1, handle.data());
    ScopeShaft->GetPoints()->Modified();
    Overview->ResetCameraClippingRange();
  }
}

void SimulatorView::showJaws(double jawOpening)
{
  // The punch's and the scissors' jaws drawn as open as the scene has them
  // (remade only when they moved by a twentieth of their travel).
  const SurgicalInstrumentType type = Scene.instrumentModel().type;
  const bool jaws =
    type == SurgicalInstrumentType::Punch || type == SurgicalInstrumentType::Scissors;
  if (!jaws || std::abs(jawOpening - JawsShown) < 0.05)
  {
    return;
  }
  SurgicalInstrumentParameters parameters = Scene.instrumentModel().parameters;
  parameters.jawOpeningDegrees *= jawOpening;
  auto* mapper = vtkPolyDataMapper::SafeDownCast(Instrument->GetMapper());
  mapper->SetInputData(withNormals(makeSurgicalInstrument(parameters).visual));
  JawsShown = jawOpening;
}

void SimulatorView::rebuildTissue(const SceneTopology& topology)
{
  // After a cut: the visual mesh's vertices, its triangles still in the
  // tissue (removed pieces are not drawn), split into the outer surface and
  // the cut surfaces, on one point set with a normal array each.
  const TriangleMesh& mesh = topology.mesh;
  const std::vector<char>& active = topology.active;
  const std::vector<VisualMaterial>* materials =
    topology.materials.empty() ? nullptr : &topology.materials;
  const auto count = static_cast<vtkIdType>(mesh.vertexCount());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(count);
  vtkNew<vtkCellArray> outer;
  vtkNew<vtkCellArray> inner;
  Shading.triangles.clear();
  CutTriangles.clear();
  std::vector<char> onCut(mesh.vertexCount(), 0);
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    if (!active[t])
    {
      continue;
    }
    const Triangle& corners = mesh.triangles[t];
    const vtkIdType ids[3] = { corners[0], corners[1], corners[2] };
    const bool cut = materials && (*materials)[t] == VisualMaterial::CutSurface;
    (cut ? inner : outer)->InsertNextCell(3, ids);
    (cut ? CutTriangles : Shading.triangles).push_back(corners);
    for (int v : corners)
      onCut[v] = onCut[v] || cut;
  }
  CutVertices.clear();
  for (std::size_t v = 0; v < onCut.size(); ++v)
    if (onCut[v])
      CutVertices.push_back(static_cast<int>(v));
  CutNormals.assign(mesh.vertexCount(), Vector3::Zero());
  for (vtkPolyData* part : { Tissue.GetPointer(), CutSurface.GetPointer() })
  {
    vtkNew<vtkDoubleArray> normals;
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(count);
    part->Initialize();
    part->SetPoints(points);
    part->GetPointData()->SetNormals(normals);
  }
  Tissue->SetPolys(outer);
  CutSurface->SetPolys(inner);
  Shading.positions = mesh.positions;
  Shading.computeVertexNormals();
  ComputedRestNormals = Shading.normals;
  RestNormals = mesh.normals.size() == mesh.vertexCount() ? mesh.normals : Shading.normals;
  TopologyVersion = topology.version;
}

void SimulatorView::writePicture(vtkRenderWindow* window, const std::string& path)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
}

} // namespace thintissue
