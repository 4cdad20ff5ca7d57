#include "vtkSimulatedSegmentationFilter.h"

#include "MeshValidation.h"
#include "vtkThinTissueConversion.h"

#include <vtkCleanPolyData.h>
#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkImageGaussianSmooth.h>
#include <vtkImageStencil.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataConnectivityFilter.h>
#include <vtkPolyDataToImageStencil.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

vtkStandardNewMacro(vtkSimulatedSegmentationFilter);

namespace
{

/// The voxel grid around the input's bounds: a margin of the blur's reach
/// (3 sigma) and two voxels, so that the iso-surface closes inside it. The
/// samples lie `phase` voxels past the lowest bound (a flat face exactly on
/// a sample plane would count as inside and shift by half a voxel).
struct VoxelGrid
{
  double origin[3];
  int extent[6];
  vtkIdType voxels = 1;
};

VoxelGrid gridAround(const double bounds[6],
  const double spacing[3],
  const double phase[3],
  double sigma)
{
  VoxelGrid grid;
  const int margin = 2 + static_cast<int>(std::ceil(3.0 * sigma));
  for (int axis = 0; axis < 3; ++axis)
  {
    const double low = bounds[2 * axis], high = bounds[2 * axis + 1];
    const int cells = static_cast<int>(std::ceil((high - low) / spacing[axis])) + 1;
    grid.origin[axis] = low + (phase[axis] - margin) * spacing[axis];
    grid.extent[2 * axis] = 0;
    grid.extent[2 * axis + 1] = cells + 2 * margin;
    grid.voxels *= static_cast<vtkIdType>(cells + 2 * margin + 1);
  }
  return grid;
}

/// 1 inside the surface, 0 outside (the tissue's intensity).
vtkSmartPointer<vtkImageData> solidImage(vtkPolyData* surface,
  VoxelGrid grid,
  const double spacing[3])
{
  vtkNew<vtkImageData> full;
  full->SetOrigin(grid.origin);
  full->SetSpacing(spacing);
  full->SetExtent(grid.extent);
  full->AllocateScalars(VTK_FLOAT, 1);
  auto* values = vtkFloatArray::SafeDownCast(full->GetPointData()->GetScalars());
  values->FillValue(1.0f);
  vtkNew<vtkPolyDataToImageStencil> stencil;
  stencil->SetInputData(surface);
  stencil->SetOutputOrigin(grid.origin);
  stencil->SetOutputSpacing(spacing);
  stencil->SetOutputWholeExtent(grid.extent);
  vtkNew<vtkImageStencil> cut;
  cut->SetInputData(full);
  cut->SetStencilConnection(stencil->GetOutputPort());
  cut->SetBackgroundValue(0.0);
  cut->Update();
  vtkSmartPointer<vtkImageData> image = cut->GetOutput();
  return image;
}

} // namespace

int vtkSimulatedSegmentationFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  try
  {
    if (input->GetNumberOfCells() == 0)
    {
      throw std::runtime_error("the input surface must be closed: it has no triangle");
    }
    thintissue::requireClosedOrientedManifold(
      thintissue::fromPolyData(input, "input surface"), "the input surface");
    const double* spacing = this->VoxelSpacing;
    const double* phase = this->GridPhase;
    if (!(phase[0] >= 0.0 && phase[0] < 1.0 && phase[1] >= 0.0 && phase[1] < 1.0 &&
          phase[2] >= 0.0 && phase[2] < 1.0))
    {
      throw std::runtime_error("the grid phase must lie in [0, 1) voxels");
    }
    if (!(spacing[0] > 0.0 && spacing[1] > 0.0 && spacing[2] > 0.0) || !(this->OutputScale > 0.0) ||
        !(this->BlurSigma >= 0.0) || !(this->NoiseAmplitude >= 0.0))
    {
      throw std::runtime_error(
        "spacing and output scale must be positive, sigma and noise not negative");
    }
    const VoxelGrid grid =
      gridAround(input->GetBounds(), spacing, this->GridPhase, this->BlurSigma);
    if (grid.voxels > this->MaximumVoxels)
    {
      std::ostringstream text;
      text << "a grid of " << grid.voxels << " voxels (more than " << this->MaximumVoxels
           << "): is the spacing in the surface's units?";
      throw std::runtime_error(text.str());
    }
    vtkSmartPointer<vtkImageData> image = solidImage(input, grid, spacing);
    this->UpdateProgress(0.3);
    if (this->BlurSigma > 0.0)
    {
      vtkNew<vtkImageGaussianSmooth> blur;
      blur->SetInputData(image);
      blur->SetDimensionality(3);
      blur->SetStandardDeviations(this->BlurSigma, this->BlurSigma, this->BlurSigma);
      blur->SetRadiusFactors(3.0, 3.0, 3.0);
      blur->Update();
      image = blur->GetOutput();
    }
    this->UpdateProgress(0.6);
    if (this->NoiseAmplitude > 0.0)
    {
      // Deterministic: one draw per voxel in index order.
      std::mt19937 random(this->Seed);
      std::normal_distribution<float> noise(0.0f, static_cast<float>(this->NoiseAmplitude));
      vtkDataArray* values = image->GetPointData()->GetScalars();
      for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
      {
        values->SetComponent(i, 0, values->GetComponent(i, 0) + noise(random));
      }
    }
    vtkNew<vtkFlyingEdges3D> surface;
    surface->SetInputData(image);
    surface->SetValue(0, 0.5);
    surface->ComputeNormalsOff();
    surface->ComputeGradientsOff();
    surface->ComputeScalarsOff();
    surface->Update();
    this->UpdateProgress(0.9);
    vtkSmartPointer<vtkPolyData> result = surface->GetOutput();
    if (this->KeepLargestPiece)
    {
      vtkNew<vtkPolyDataConnectivityFilter> largest;
      largest->SetInputData(result);
      largest->SetExtractionModeToLargestRegion();
      // The dropped fragments' points go too (no unreferenced vertex).
      vtkNew<vtkCleanPolyData> used;
      used->SetInputConnection(largest->GetOutputPort());
      used->PointMergingOff();
      used->Update();
      result = used->GetOutput();
    }
    output->ShallowCopy(result);
    vtkNew<vtkPoints> scaled;
    scaled->SetDataTypeToDouble();
    scaled->SetNumberOfPoints(result->GetNumberOfPoints());
    for (vtkIdType i = 0; i < result->GetNumberOfPoints(); ++i)
    {
      double p[3];
      result->GetPoint(i, p);
      scaled->SetPoint(
        i, p[0] * this->OutputScale, p[1] * this->OutputScale, p[2] * this->OutputScale);
    }
    output->SetPoints(scaled);
  }
  catch (const std::exception& error)
  {
    output->Initialize();
    vtkErrorMacro(<< error.what());
    return 0;
  }
  return 1;
}

void vtkSimulatedSegmentationFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VoxelSpacing: " << this->VoxelSpacing[0] << " " << this->VoxelSpacing[1] << " "
     << this->VoxelSpacing[2] << "\n";
  os << indent << "GridPhase: " << this->GridPhase[0] << " " << this->GridPhase[1] << " "
     << this->GridPhase[2] << "\n";
  os << indent << "BlurSigma: " << this->BlurSigma << "\n";
  os << indent << "NoiseAmplitude: " << this->NoiseAmplitude << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "OutputScale: " << this->OutputScale << "\n";
  os << indent << "KeepLargestPiece: " << this->KeepLargestPiece << "\n";
  os << indent << "MaximumVoxels: " << this->MaximumVoxels << "\n";
}
