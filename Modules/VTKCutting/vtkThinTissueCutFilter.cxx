#include "vtkThinTissueCutFilter.h"

#include "ThinTissueError.h"
#include "TissueCutter.h"
#include "vtkBindingConversion.h"
#include "vtkThinTissueConversion.h"

#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkTrivialProducer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <exception>
#include <utility>

vtkStandardNewMacro(vtkThinTissueCutFilter);

/// The cut tissue and what it was built from.
struct vtkThinTissueCutFilter::Internals
{
  std::unique_ptr<thintissue::TissueCutter> Cutter;
  vtkMTimeType BuiltFrom = 0; ///< newest input MTime when built
  vtkMTimeType LastBlade = 0; ///< MTime of the last blade applied
  /// Contouring passes asked for since the last update: centre, radius,
  /// strength.
  struct ContourPass
  {
    thintissue::Vector3 centre;
    double radius;
    double strength;
  };
  std::vector<ContourPass> PendingPasses;
  /// Shaving passes asked for since the last update: the window's centre
  /// and radius.
  std::vector<std::pair<thintissue::Vector3, double>> PendingShavingPasses;
  int ContouredVertices = 0; ///< moved by the last update's passes
};

vtkThinTissueCutFilter::vtkThinTissueCutFilter()
  : Tissue(new Internals)
{
  this->SetNumberOfInputPorts(4);
  this->SetNumberOfOutputPorts(3);
}

vtkThinTissueCutFilter::~vtkThinTissueCutFilter() = default;

void vtkThinTissueCutFilter::SetCollisionData(vtkPolyData* collision)
{
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(collision);
  this->SetInputConnection(CollisionInputPort, producer->GetOutputPort());
}

void vtkThinTissueCutFilter::SetSimulationData(vtkUnstructuredGrid* simulation)
{
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(simulation);
  this->SetInputConnection(SimulationInputPort, producer->GetOutputPort());
}

void vtkThinTissueCutFilter::SetBladeData(vtkPolyData* blade)
{
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(blade);
  this->SetInputConnection(BladeInputPort, producer->GetOutputPort());
}

void vtkThinTissueCutFilter::AddContourPass(double centreX,
  double centreY,
  double centreZ,
  double radius,
  double strength)
{
  this->Tissue->PendingPasses.push_back({ { centreX, centreY, centreZ }, radius, strength });
  this->Modified();
}

void vtkThinTissueCutFilter::AddShavingPass(double centreX,
  double centreY,
  double centreZ,
  double radius)
{
  this->Tissue->PendingShavingPasses.emplace_back(
    thintissue::Vector3(centreX, centreY, centreZ), radius);
  this->Modified();
}

void vtkThinTissueCutFilter::ApplyShavingPasses()
{
  Internals& tissue = *this->Tissue;
  this->LastShavedTriangles = 0;
  std::vector<std::pair<thintissue::Vector3, double>> passes;
  passes.swap(tissue.PendingShavingPasses); // applied once, even if one fails
  for (const auto& [centre, radius] : passes)
  {
    const std::vector<int> held = tissue.Cutter->activeTrianglesWithin(centre, radius);
    if (held.empty())
      continue;
    const thintissue::TissueCutReport report = tissue.Cutter->removeTriangles(held);
    if (!report.visualError.empty())
    {
      vtkWarningMacro(<< report.visualError);
    }
    this->LastShavedTriangles += static_cast<int>(held.size());
    ++this->NumberOfShavingPasses;
  }
}

void vtkThinTissueCutFilter::ApplyContourPasses()
{
  Internals& tissue = *this->Tissue;
  tissue.ContouredVertices = 0;
  std::vector<Internals::ContourPass> passes;
  passes.swap(tissue.PendingPasses); // applied once, even if one fails
  for (const Internals::ContourPass& pass : passes)
  {
    const thintissue::CutRimContourReport report =
      tissue.Cutter->contour(pass.centre, pass.radius, pass.strength);
    tissue.ContouredVertices += static_cast<int>(report.movedVertices.size());
    ++this->NumberOfContourPasses;
  }
}

void vtkThinTissueCutFilter::WriteRoughness(vtkPolyData* output)
{
  const thintissue::CutSurfaceRoughness rim = this->Tissue->Cutter->cutRimRoughness();
  this->RimRoughness = rim.rootMeanSquare;
  this->RimRoughnessMaximum = rim.maximum;
  const auto value = [output](const char* name, double x)
  {
    vtkNew<vtkDoubleArray> array;
    array->SetName(name);
    array->InsertNextValue(x);
    output->GetFieldData()->AddArray(array);
  };
  value("RimRoughness", rim.rootMeanSquare);
  value("RimRoughnessMaximum", rim.maximum);
  vtkNew<vtkIntArray> moved;
  moved->SetName("ContouredVertices");
  moved->InsertNextValue(this->Tissue->ContouredVertices);
  output->GetFieldData()->AddArray(moved);
}

void vtkThinTissueCutFilter::ResetTissue()
{
  this->Tissue->Cutter.reset();
  this->Modified();
}

int vtkThinTissueCutFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(),
    port == SimulationInputPort ? "vtkUnstructuredGrid" : "vtkPolyData");
  if (port == BladeInputPort)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

int vtkThinTissueCutFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(),
    port == SimulationPort ? "vtkUnstructuredGrid" : "vtkPolyData");
  return 1;
}

vtkPolyData* vtkThinTissueCutFilter::GetVisualOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(VisualPort));
}

vtkPolyData* vtkThinTissueCutFilter::GetCollisionOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(CollisionPort));
}

vtkUnstructuredGrid* vtkThinTissueCutFilter::GetSimulationOutput()
{
  return vtkUnstructuredGrid::SafeDownCast(this->GetOutputDataObject(SimulationPort));
}

namespace
{

/// Output 0: the cut visual surface with its binding and materials. Edge
/// bindings refer to the sorted edges of the cut collision mesh, as those
/// of vtkVisualCollisionBindingFilter do.
vtkSmartPointer<vtkPolyData> visualOutputOf(const thintissue::TissueCutter& cutter)
{
  const thintissue::CuttableVisualMesh& visual = cutter.visual();
  const thintissue::CuttableCollisionMesh& collision = cutter.collision();
  std::vector<std::array<int, 2>> edges;
  for (const thintissue::Triangle& t : collision.triangles())
    for (int k = 0; k < 3; ++k)
      edges.push_back({ { std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]) } });
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<thintissue::VisualVertexBinding> bindings = visual.bindings();
  for (thintissue::VisualVertexBinding& b : bindings)
  {
    if (b.kind == thintissue::BindingKind::CollisionEdge)
      b.element = static_cast<int>(
        std::lower_bound(edges.begin(), edges.end(), visual.collisionEdges()[b.element]) -
        edges.begin());
  }
  // Only the triangles of pieces still in the tissue.
  thintissue::TriangleMesh mesh = visual.mesh();
  std::vector<int> regions;
  std::vector<std::int8_t> sides;
  vtkNew<vtkUnsignedCharArray> materials;
  materials->SetName("Material");
  const std::vector<char> active = cutter.activeVisualTriangles();
  mesh.triangles.clear();
  mesh.textureCorners.clear();
  for (std::size_t t = 0; t < active.size(); ++t)
  {
    if (!active[t])
      continue;
    mesh.triangles.push_back(visual.mesh().triangles[t]);
    if (visual.mesh().hasTextureCoordinates())
      mesh.textureCorners.push_back(visual.mesh().textureCorners[t]);
    regions.push_back(visual.triangleRegions()[t]);
    sides.push_back(visual.triangleSides()[t]);
    materials->InsertNextValue(static_cast<unsigned char>(visual.triangleMaterials()[t]));
  }
  vtkSmartPointer<vtkPolyData> output =
    thintissue::boundVisualPolyData(mesh, bindings, regions, sides);
  output->GetCellData()->AddArray(materials);
  return output;
}

} // namespace

namespace
{

thintissue::TissueCutterSettings cutterSettings(vtkThinTissueCutFilter& filter)
{
  thintissue::TissueCutterSettings settings;
  settings.collision.snapFraction = filter.GetSnapFraction();
  settings.visual.cutSurfaceRows = filter.GetCutSurfaceRows();
  settings.freePieces = filter.GetFreePieces() == vtkThinTissueCutFilter::DROP_FREE_PIECES
                          ? thintissue::FreePieceHandling::Drop
                          : thintissue::FreePieceHandling::Keep;
  settings.fragmentAreaFraction = filter.GetFragmentAreaFraction();
  settings.visual.jaggedAmplitude = filter.GetJaggedAmplitude();
  settings.visual.jaggedWavelength = filter.GetJaggedWavelength();
  settings.visual.jaggedSeed = filter.GetJaggedSeed();
  return settings;
}

} // namespace

int vtkThinTissueCutFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  this->LastErrorMessage.clear();
  vtkPolyData* visualInput = vtkPolyData::GetData(inputVector[VisualInputPort], 0);
  vtkPolyData* collisionInput = vtkPolyData::GetData(inputVector[CollisionInputPort], 0);
  vtkUnstructuredGrid* simulationInput =
    vtkUnstructuredGrid::GetData(inputVector[SimulationInputPort], 0);
  vtkPolyData* blade = vtkPolyData::GetData(inputVector[BladeInputPort], 0);
  vtkPolyData* visualOutput = vtkPolyData::GetData(outputVector, VisualPort);
  vtkPolyData* collisionOutput = vtkPolyData::GetData(outputVector, CollisionPort);
  vtkUnstructuredGrid* simulationOutput =
    vtkUnstructuredGrid::GetData(outputVector, SimulationPort);
  Internals& tissue = *this->Tissue;
  const vtkMTimeType tissueTime =
    std::max({ visualInput->GetMTime(), collisionInput->GetMTime(), simulationInput->GetMTime() });
  this->UpdateProgress(0.0);
  try
  {
    const thintissue::TissueCutterSettings settings = cutterSettings(*this);
    if (tissue.Cutter && tissueTime <= tissue.BuiltFrom)
    {
      // The settings of the cuts to come (a new row count after a cut is
      // refused: the tissue stays as it is, ResetTissue() builds it again).
      tissue.Cutter->setSettings(settings);
    }
    else
    {
      this->SetProgressText("building the tissue");
      const thintissue::VisualCollisionBinding binding =
        thintissue::bindingFromPolyData(visualInput, collisionInput, settings.radiusArrayName);
      tissue.Cutter = std::make_unique<thintissue::TissueCutter>(
        binding, thintissue::fromUnstructuredGrid(simulationInput, "hexahedra"), nullptr, settings);
      tissue.BuiltFrom = tissueTime;
      tissue.LastBlade = 0; // a blade present now cuts the new tissue
      this->NumberOfCuts = 0;
      this->LastCutMilliseconds = 0.0;
      this->LastCutChangedTissue = 0;
      this->NumberOfContourPasses = 0;
      this->NumberOfShavingPasses = 0;
    }
    if (blade && blade->GetMTime() > tissue.LastBlade && blade->GetNumberOfCells() > 0)
    {
      tissue.LastBlade = blade->GetMTime();
      this->SetProgressText("cutting");
      this->UpdateProgress(0.5);
      const thintissue::Blade cut =
        thintissue::Blade::fromSurface(thintissue::fromPolyData(blade, "blade"));
      const thintissue::TissueCutReport report = tissue.Cutter->cut(cut);
      ++this->NumberOfCuts;
      this->LastCutMilliseconds = report.totalMilliseconds;
      this->LastCutChangedTissue = report.changed();
      if (!report.visualError.empty())
      {
        vtkWarningMacro(<< report.visualError);
      }
      vtkLogF(TRACE,
        "cut %d: %zu collision triangles split, %zu visual triangles changed, %.3f ms",
        this->NumberOfCuts,
        report.collision.splits.size(),
        report.visual.changedTriangles.size(),
        report.totalMilliseconds);
    }
    this->ApplyShavingPasses();
    this->ApplyContourPasses();
  }
  catch (const std::exception& error)
  {
    this->LastErrorMessage = error.what();
    vtkErrorMacro(<< this->LastErrorMessage);
    if (!tissue.Cutter)
    {
      visualOutput->Initialize();
      collisionOutput->Initialize();
      simulationOutput->Initialize();
      return 0;
    }
  }
  visualOutput->ShallowCopy(visualOutputOf(*tissue.Cutter));
  this->WriteRoughness(visualOutput);
  thintissue::TriangleMesh collision = tissue.Cutter->collisionMesh();
  collision.triangles.clear();
  for (std::size_t t = 0; t < tissue.Cutter->collision().triangleCount(); ++t)
    if (tissue.Cutter->isActive(static_cast<int>(t)))
      collision.triangles.push_back(tissue.Cutter->collision().triangles()[t]);
  collisionOutput->ShallowCopy(thintissue::toPolyData(collision));
  simulationOutput->ShallowCopy(thintissue::toUnstructuredGrid(tissue.Cutter->simulation()));
  this->SetProgressText("done");
  this->UpdateProgress(1.0);
  return this->LastErrorMessage.empty() ? 1 : 0;
}

void vtkThinTissueCutFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CutSurfaceRows: " << this->CutSurfaceRows << "\n";
  os << indent << "SnapFraction: " << this->SnapFraction << "\n";
  os << indent << "FreePieces: "
     << (this->FreePieces == DROP_FREE_PIECES ? "DROP_FREE_PIECES" : "KEEP_FREE_PIECES") << "\n";
  os << indent << "FragmentAreaFraction: " << this->FragmentAreaFraction << "\n";
  os << indent << "JaggedAmplitude: " << this->JaggedAmplitude << "\n";
  os << indent << "JaggedWavelength: " << this->JaggedWavelength << "\n";
  os << indent << "JaggedSeed: " << this->JaggedSeed << "\n";
  os << indent << "NumberOfContourPasses: " << this->NumberOfContourPasses << "\n";
  os << indent << "NumberOfShavingPasses: " << this->NumberOfShavingPasses << "\n";
  os << indent << "LastShavedTriangles: " << this->LastShavedTriangles << "\n";
  os << indent << "RimRoughness: " << this->RimRoughness << "\n";
  os << indent << "RimRoughnessMaximum: " << this->RimRoughnessMaximum << "\n";
  os << indent << "NumberOfCuts: " << this->NumberOfCuts << "\n";
  os << indent << "LastCutMilliseconds: " << this->LastCutMilliseconds << "\n";
  os << indent << "LastCutChangedTissue: " << this->LastCutChangedTissue << "\n";
  os << indent << "LastErrorMessage: " << this->LastErrorMessage << "\n";
}
