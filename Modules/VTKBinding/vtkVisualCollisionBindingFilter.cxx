#include "vtkVisualCollisionBindingFilter.h"

#include "BindingCache.h"
#include "ThinTissueError.h"
#include "VisualCollisionBinding.h"
#include "vtkBindingConversion.h"
#include "vtkThinTissueConversion.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSignedCharArray.h>
#include <vtkUnsignedCharArray.h>

#include <exception>
#include <string>
#include <unordered_map>

vtkStandardNewMacro(vtkVisualCollisionBindingFilter);

namespace
{

} // namespace

vtkSmartPointer<vtkPolyData> thintissue::boundVisualPolyData(
  const thintissue::VisualCollisionBinding& binding)
{
  return boundVisualPolyData(
    binding.visual, binding.vertices, binding.triangleRegion, binding.triangleSide);
}

vtkSmartPointer<vtkPolyData> thintissue::boundVisualPolyData(const TriangleMesh& visual,
  const std::vector<VisualVertexBinding>& vertices,
  const std::vector<int>& triangleRegion,
  const std::vector<std::int8_t>& triangleSide)
{
  vtkSmartPointer<vtkPolyData> output = thintissue::toPolyData(visual);
  const auto vertexCount = static_cast<vtkIdType>(vertices.size());
  vtkNew<vtkUnsignedCharArray> kinds;
  kinds->SetName("BindingKind");
  kinds->SetNumberOfTuples(vertexCount);
  vtkNew<vtkIntArray> elements;
  elements->SetName("BindingElement");
  elements->SetNumberOfTuples(vertexCount);
  vtkNew<vtkSignedCharArray> sides;
  sides->SetName("BindingSide");
  sides->SetNumberOfTuples(vertexCount);
  vtkNew<vtkDoubleArray> parameters;
  parameters->SetName("BindingParameters");
  parameters->SetNumberOfComponents(3);
  parameters->SetNumberOfTuples(vertexCount);
  for (vtkIdType v = 0; v < vertexCount; ++v)
  {
    const thintissue::VisualVertexBinding& vertex = vertices[static_cast<std::size_t>(v)];
    kinds->SetValue(v, static_cast<unsigned char>(vertex.kind));
    elements->SetValue(v, vertex.element);
    sides->SetValue(v, static_cast<signed char>(vertex.side));
    parameters->SetTypedTuple(v, vertex.parameters.data());
  }
  output->GetPointData()->AddArray(kinds);
  output->GetPointData()->AddArray(elements);
  output->GetPointData()->AddArray(sides);
  output->GetPointData()->AddArray(parameters);

  const auto triangleCount = static_cast<vtkIdType>(triangleRegion.size());
  vtkNew<vtkIntArray> regions;
  regions->SetName("CollisionTriangle");
  regions->SetNumberOfTuples(triangleCount);
  vtkNew<vtkSignedCharArray> regionSides;
  regionSides->SetName("CollisionSide");
  regionSides->SetNumberOfTuples(triangleCount);
  for (vtkIdType t = 0; t < triangleCount; ++t)
  {
    regions->SetValue(t, triangleRegion[static_cast<std::size_t>(t)]);
    regionSides->SetValue(t, static_cast<signed char>(triangleSide[static_cast<std::size_t>(t)]));
  }
  output->GetCellData()->AddArray(regions);
  output->GetCellData()->AddArray(regionSides);
  return output;
}

namespace
{

/// Output 1: one polyline per path through the visual vertices it passes.
vtkSmartPointer<vtkPolyData> makePathsOutput(const thintissue::VisualCollisionBinding& binding)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkIdTypeArray> visualVertices;
  visualVertices->SetName("VisualVertex");
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkIntArray> edges;
  edges->SetName("CollisionEdge");
  vtkNew<vtkSignedCharArray> sides;
  sides->SetName("Side");
  vtkNew<vtkDoubleArray> lengths;
  lengths->SetName("Length");
  // Paths meet at their end vertices (and may share segments): one point
  // per visual vertex.
  std::unordered_map<int, vtkIdType> pointOf;
  for (const thintissue::BindingPath& path : binding.paths)
  {
    lines->InsertNextCell(static_cast<vtkIdType>(path.visualVertices.size()));
    for (const int v : path.visualVertices)
    {
      auto found = pointOf.emplace(v, points->GetNumberOfPoints());
      if (found.second)
      {
        points->InsertNextPoint(binding.visual.positions[static_cast<std::size_t>(v)].data());
        visualVertices->InsertNextValue(v);
      }
      lines->InsertCellPoint(found.first->second);
    }
    edges->InsertNextValue(path.collisionEdge);
    sides->InsertNextValue(static_cast<signed char>(path.side));
    lengths->InsertNextValue(path.length);
  }
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->SetPoints(points);
  output->SetLines(lines);
  output->GetPointData()->AddArray(visualVertices);
  output->GetCellData()->AddArray(edges);
  output->GetCellData()->AddArray(sides);
  output->GetCellData()->AddArray(lengths);
  return output;
}

} // namespace

vtkVisualCollisionBindingFilter::vtkVisualCollisionBindingFilter()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
  const thintissue::VisualCollisionBindingSettings defaults;
  this->SetRadiusArrayName(defaults.radiusArrayName.c_str());
  this->InsideTolerance = defaults.insideTolerance;
  this->ThinnessFactor = defaults.thinnessFactor;
  this->Parallel = defaults.parallel;
}

vtkVisualCollisionBindingFilter::~vtkVisualCollisionBindingFilter()
{
  this->SetRadiusArrayName(nullptr);
  this->SetCacheFileName(nullptr);
}

int vtkVisualCollisionBindingFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkVisualCollisionBindingFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputs,
  vtkInformationVector* outputs)
{
  vtkPolyData* visualInput = vtkPolyData::GetData(inputs[0], 0);
  vtkPolyData* collisionInput = vtkPolyData::GetData(inputs[1], 0);
  vtkPolyData* visualOutput = vtkPolyData::GetData(outputs, VisualPort);
  vtkPolyData* pathsOutput = vtkPolyData::GetData(outputs, PathsPort);
  this->LastErrorMessage.clear();
  this->LastCacheMessage.clear();
  this->CacheWasRebuilt = false;
  visualOutput->Initialize();
  pathsOutput->Initialize();
  if (visualInput == nullptr || collisionInput == nullptr)
  {
    this->LastErrorMessage =
      "the visual surface (input port 0) and the collision mid-surface (input port 1) are needed";
    vtkErrorMacro(<< this->LastErrorMessage);
    return 0;
  }

  thintissue::VisualCollisionBindingSettings settings;
  settings.radiusArrayName =
    this->RadiusArrayName != nullptr ? this->RadiusArrayName : std::string();
  settings.insideTolerance = this->InsideTolerance;
  settings.thinnessFactor = this->ThinnessFactor;
  settings.parallel = this->Parallel;
  settings.rimPaths = static_cast<thintissue::RimPathMethod>(this->RimPathMethod);
  // The kernel reports progress from this thread (between blocks of
  // parallel work), so the VTK events stay on the pipeline's thread.
  const thintissue::BindingProgress progress = [this](double fraction, const char* stage)
  {
    this->SetProgressText(stage);
    this->UpdateProgress(fraction);
    return !this->GetAbortExecute();
  };

  try
  {
    if (settings.radiusArrayName.empty())
    {
      throw thintissue::InvalidInputError(
        "vtkVisualCollisionBindingFilter: RadiusArrayName is empty");
    }
    const thintissue::TriangleMesh visual = thintissue::fromPolyData(visualInput, "visual input");
    const thintissue::TriangleMesh collision =
      thintissue::fromPolyData(collisionInput, "collision input");
    thintissue::VisualCollisionBinding binding;
    if (this->CacheFileName != nullptr && this->CacheFileName[0] != '\0')
    {
      bool rebuilt = false;
      std::string why;
      binding = thintissue::loadOrBuildBinding(
        this->CacheFileName, visual, collision, settings, progress, &rebuilt, &why);
      this->CacheWasRebuilt = rebuilt;
      this->LastCacheMessage =
        rebuilt ? why : std::string("binding loaded from '") + this->CacheFileName + "'";
    }
    else
    {
      binding = thintissue::bindVisualToCollision(visual, collision, settings, progress);
    }
    visualOutput->ShallowCopy(thintissue::boundVisualPolyData(binding));
    pathsOutput->ShallowCopy(makePathsOutput(binding));
  }
  catch (const thintissue::BindingAbortedError& aborted)
  {
    // Asked for: not a failure of the pipeline, but the outputs are empty.
    visualOutput->Initialize();
    pathsOutput->Initialize();
    this->LastErrorMessage = aborted.what();
    vtkWarningMacro(<< this->LastErrorMessage);
    return 1;
  }
  catch (const thintissue::Error& error)
  {
    visualOutput->Initialize();
    pathsOutput->Initialize();
    this->LastErrorMessage = error.what();
    vtkErrorMacro(<< this->LastErrorMessage);
    return 0;
  }
  catch (const std::exception& error)
  {
    // Not expected from the kernel (e.g. out of memory): still no crash
    // through the pipeline.
    visualOutput->Initialize();
    pathsOutput->Initialize();
    this->LastErrorMessage = std::string("visual-collision binding failed: ") + error.what();
    vtkErrorMacro(<< this->LastErrorMessage);
    return 0;
  }
  this->SetProgressText("done");
  this->UpdateProgress(1.0);
  return 1;
}

void vtkVisualCollisionBindingFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RadiusArrayName: " << (this->RadiusArrayName ? this->RadiusArrayName : "(none)")
     << "\n"
     << indent << "InsideTolerance: " << this->InsideTolerance << "\n"
     << indent << "ThinnessFactor: " << this->ThinnessFactor << "\n"
     << indent << "Parallel: " << (this->Parallel ? "On" : "Off") << "\n"
     << indent << "RimPathMethod: " << this->RimPathMethod << "\n"
     << indent << "CacheFileName: " << (this->CacheFileName ? this->CacheFileName : "(none)")
     << "\n"
     << indent << "CacheWasRebuilt: " << (this->CacheWasRebuilt ? "true" : "false") << "\n"
     << indent << "LastCacheMessage: " << this->LastCacheMessage << "\n"
     << indent << "LastErrorMessage: " << this->LastErrorMessage << "\n";
}
