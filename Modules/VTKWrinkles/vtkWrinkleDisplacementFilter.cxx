#include "vtkWrinkleDisplacementFilter.h"

#include "MonitorCurves.h"
#include "ThinTissueError.h"
#include "WrinkleGenerator.h"
#include "vtkThinTissueConversion.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <exception>
#include <optional>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkWrinkleDisplacementFilter);

using thintissue::Vector3;

struct vtkWrinkleDisplacementFilter::Internals
{
  std::optional<thintissue::WrinkleGenerator> generator;
  vtkMTimeType monitorTime = 0;
  vtkIdType surfacePoints = -1;
  vtkIdType gridPoints = -1;
};

namespace
{

constexpr const char* MonitorInput = "monitor data (input 1)";

vtkDataArray* requireArray(vtkPolyData* data, const char* name, int components)
{
  vtkDataArray* array = data->GetPointData()->GetArray(name);
  if (array == nullptr || array->GetNumberOfComponents() != components ||
      array->GetNumberOfTuples() != data->GetNumberOfPoints())
  {
    throw thintissue::InvalidInputError(std::string(MonitorInput) + ": needs the point array '" +
                                        name + "' (" + std::to_string(components) +
                                        " components, one tuple per point)");
  }
  return array;
}

/// One data curve per polyline (all points in order if there is none).
std::vector<thintissue::WrinkleDataCurve> monitorDataOf(vtkPolyData* data)
{
  vtkDataArray* region = requireArray(data, "RegionPoint", 3);
  vtkDataArray* thickness = requireArray(data, "Thickness", 1);
  std::vector<std::vector<vtkIdType>> lines;
  auto iterator = vtk::TakeSmartPointer(data->GetLines()->NewIterator());
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    iterator->GetCurrentCell(size, ids);
    lines.emplace_back(ids, ids + size);
  }
  if (lines.empty())
  {
    lines.emplace_back();
    for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
    {
      lines.back().push_back(i);
    }
  }
  std::vector<thintissue::WrinkleDataCurve> curves;
  for (const auto& line : lines)
  {
    thintissue::WrinkleDataCurve curve;
    curve.name = "polyline " + std::to_string(curves.size());
    for (const vtkIdType i : line)
    {
      Vector3 x, r;
      data->GetPoint(i, x.data());
      region->GetTuple(i, r.data());
      curve.monitorPoints.push_back(x);
      curve.regionPoints.push_back(r);
      curve.thickness.push_back(thickness->GetComponent(i, 0));
    }
    curves.push_back(std::move(curve));
  }
  return curves;
}

thintissue::MonitorPointSet monitorPointsOf(vtkPolyData* data, double spacing)
{
  const std::vector<thintissue::WrinkleDataCurve> curves = monitorDataOf(data);
  if (spacing > 0.0)
  {
    return thintissue::resampleMonitorCurves(curves, spacing, MonitorInput);
  }
  thintissue::checkWrinkleDataCurves(curves, MonitorInput);
  thintissue::MonitorPointSet set;
  for (const auto& c : curves)
  {
    set.appendCurve(c.monitorPoints, c.regionPoints, c.thickness);
  }
  return set;
}

} // namespace

vtkWrinkleDisplacementFilter::vtkWrinkleDisplacementFilter()
  : State(std::make_unique<Internals>())
{
  this->SetNumberOfInputPorts(3);
  const thintissue::WrinkleParameters defaults;
  this->Frequency = defaults.frequency;
  this->Scale = defaults.scale;
  this->MagnitudeBound = defaults.magnitudeBound;
  this->CutOffThickness = defaults.cutOffThickness;
  this->WindowSize = defaults.windowSize;
  this->ReversalThreshold = defaults.reversalThreshold;
  this->StartContacts = defaults.startContacts;
  this->EndContacts = defaults.endContacts;
}

vtkWrinkleDisplacementFilter::~vtkWrinkleDisplacementFilter() = default;

void vtkWrinkleDisplacementFilter::SetMonitorPointsData(vtkPolyData* monitors)
{
  this->SetInputData(1, monitors);
}

void vtkWrinkleDisplacementFilter::SetGridData(vtkUnstructuredGrid* grid)
{
  this->SetInputData(2, grid);
}

void vtkWrinkleDisplacementFilter::Reset()
{
  this->State = std::make_unique<Internals>();
  this->Modified();
}

int vtkWrinkleDisplacementFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(
    vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 2 ? "vtkUnstructuredGrid" : "vtkPolyData");
  return 1;
}

int vtkWrinkleDisplacementFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* surface = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* monitors = vtkPolyData::GetData(inputVector[1], 0);
  vtkUnstructuredGrid* grid = vtkUnstructuredGrid::GetData(inputVector[2], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->Wrinkling = false;
  this->NumberOfDisplacedPoints = 0;
  if (surface == nullptr || monitors == nullptr || grid == nullptr)
  {
    vtkErrorMacro(<< "needs the embedded surface (input 0), the monitor data (input 1) and the "
                     "hexahedral grid (input 2)");
    return 0;
  }
  try
  {
    const thintissue::HexahedralMesh mesh =
      thintissue::fromUnstructuredGrid(grid, "grid (input 2)");
    Internals& state = *this->State;
    if (!state.generator || state.monitorTime != monitors->GetMTime() ||
        state.surfacePoints != surface->GetNumberOfPoints() ||
        state.gridPoints != grid->GetNumberOfPoints())
    {
      this->Build(surface, monitors, grid);
    }
    thintissue::WrinkleParameters p;
    p.frequency = this->Frequency;
    p.scale = this->Scale;
    p.magnitudeBound = this->MagnitudeBound;
    p.cutOffThickness = this->CutOffThickness;
    p.windowSize = this->WindowSize;
    p.reversalThreshold = this->ReversalThreshold;
    p.startContacts = this->StartContacts;
    p.endContacts = this->EndContacts;
    p.anchor = this->Anchor == ANCHOR_REFERENCE ? thintissue::WrinkleAnchor::Reference
                                                : thintissue::WrinkleAnchor::Current;
    state.generator->setParameters(p);
    thintissue::WrinkleContactState contacts;
    contacts.lowerSurfaceContacts = this->LowerSurfaceContacts;
    contacts.instrumentTouches = this->InstrumentTouching;
    contacts.instrumentContact = Vector3(this->InstrumentContactPoint[0],
      this->InstrumentContactPoint[1],
      this->InstrumentContactPoint[2]);
    state.generator->update(mesh.nodes, contacts);
    this->UpdateProgress(0.5);
    this->WriteOutput(surface, output);
  }
  catch (const std::exception& error)
  {
    this->State = std::make_unique<Internals>();
    vtkErrorMacro(<< error.what());
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkWrinkleDisplacementFilter::Build(vtkPolyData* surface,
  vtkPolyData* monitors,
  vtkUnstructuredGrid* grid)
{
  Internals& state = *this->State;
  thintissue::HexahedralMesh rest = thintissue::fromUnstructuredGrid(grid, "grid (input 2)");
  vtkDataArray* displacement = grid->GetPointData()->GetArray("Displacement");
  if (displacement != nullptr && displacement->GetNumberOfComponents() == 3 &&
      displacement->GetNumberOfTuples() == grid->GetNumberOfPoints())
  {
    for (std::size_t n = 0; n < rest.nodes.size(); ++n)
    {
      Vector3 d;
      displacement->GetTuple(static_cast<vtkIdType>(n), d.data());
      rest.nodes[n] -= d;
    }
  }
  const thintissue::HexahedralEmbedding embedding =
    thintissue::embeddingFromPolyData(surface, rest, "embedded surface (input 0)");
  // The surface's triangles keep the lips of a cut apart (WrinkleInfluence).
  thintissue::TriangleMesh surfaceRest = thintissue::fromPolyData(surface, "surface (input 0)");
  embedding.mapPositions(rest.nodes, surfaceRest.positions);
  thintissue::WrinkleInfluenceSettings influence;
  influence.sphereRadius = this->SphereRadius;
  influence.gaussianWidth = this->GaussianWidth;
  influence.blendWidth = this->BlendWidth;
  state.generator.emplace(monitorPointsOf(monitors, this->MonitorPointSpacing),
    rest,
    surfaceRest,
    thintissue::WrinkleParameters{},
    influence);
  state.monitorTime = monitors->GetMTime();
  state.surfacePoints = surface->GetNumberOfPoints();
  state.gridPoints = grid->GetNumberOfPoints();
  this->NumberOfMonitorPoints = static_cast<vtkIdType>(state.generator->monitors().size());
}

void vtkWrinkleDisplacementFilter::WriteOutput(vtkPolyData* surface, vtkPolyData* output)
{
  const thintissue::WrinkleGenerator& generator = *this->State->generator;
  const vtkIdType count = surface->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> moved;
  moved->SetNumberOfComponents(3);
  moved->SetNumberOfTuples(count);
  vtkNew<vtkDoubleArray> wrinkle;
  wrinkle->SetName("WrinkleDisplacement");
  wrinkle->SetNumberOfComponents(3);
  wrinkle->SetNumberOfTuples(count);
  wrinkle->FillValue(0.0);
  for (vtkIdType i = 0; i < count; ++i)
  {
    moved->SetTuple(i, surface->GetPoint(i));
  }
  const auto& points = generator.displacedPoints();
  const auto& displacements = generator.displacements();
  for (std::size_t s = 0; s < points.size(); ++s)
  {
    double* x = moved->GetPointer(3 * static_cast<vtkIdType>(points[s]));
    for (int a = 0; a < 3; ++a)
    {
      x[a] += displacements[s][a];
    }
    wrinkle->SetTuple(points[s], displacements[s].data());
  }
  output->ShallowCopy(surface);
  vtkNew<vtkPoints> outputPoints;
  outputPoints->SetData(moved);
  output->SetPoints(outputPoints);
  output->GetPointData()->AddArray(wrinkle);
  this->Wrinkling = generator.wrinkling();
  this->NumberOfDisplacedPoints = static_cast<vtkIdType>(points.size());
}

void vtkWrinkleDisplacementFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LowerSurfaceContacts: " << this->LowerSurfaceContacts << "\n"
     << indent << "InstrumentTouching: " << (this->InstrumentTouching ? "On" : "Off") << "\n"
     << indent << "InstrumentContactPoint: " << this->InstrumentContactPoint[0] << " "
     << this->InstrumentContactPoint[1] << " " << this->InstrumentContactPoint[2] << "\n"
     << indent << "Frequency: " << this->Frequency << "\n"
     << indent << "Scale: " << this->Scale << "\n"
     << indent << "MagnitudeBound: " << this->MagnitudeBound << "\n"
     << indent << "CutOffThickness: " << this->CutOffThickness << "\n"
     << indent << "WindowSize: " << this->WindowSize << "\n"
     << indent << "ReversalThreshold: " << this->ReversalThreshold << "\n"
     << indent << "StartContacts: " << this->StartContacts << "\n"
     << indent << "EndContacts: " << this->EndContacts << "\n"
     << indent << "Anchor: " << (this->Anchor == ANCHOR_REFERENCE ? "Reference" : "Current") << "\n"
     << indent << "SphereRadius: " << this->SphereRadius << "\n"
     << indent << "GaussianWidth: " << this->GaussianWidth << "\n"
     << indent << "BlendWidth: " << this->BlendWidth << "\n"
     << indent << "MonitorPointSpacing: " << this->MonitorPointSpacing << "\n"
     << indent << "Wrinkling: " << (this->Wrinkling ? "yes" : "no") << "\n"
     << indent << "NumberOfMonitorPoints: " << this->NumberOfMonitorPoints << "\n"
     << indent << "NumberOfDisplacedPoints: " << this->NumberOfDisplacedPoints << "\n";
}
