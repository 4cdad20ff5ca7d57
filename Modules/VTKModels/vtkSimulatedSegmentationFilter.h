/**
 * @class vtkSimulatedSegmentationFilter
 * @brief Turns a closed surface into what a segmentation of a scan of it
 * gives: the test bed for preparing real anatomy (issue 14).
 *
 * The solid the input surface encloses is sampled on a voxel grid of
 * spacing VoxelSpacing (anisotropic like an MRI series: 0.3 x 0.3 x 0.9 mm
 * by default, in the input's units), blurred (Gaussian, BlurSigma voxels,
 * the partial-volume smear of a scanner), optionally disturbed by Gaussian
 * noise of NoiseAmplitude (a fraction of the tissue's intensity, from
 * Seed: the same seed gives the same surface), and iso-surfaced at half the
 * intensity (flying edges). The result has what real segmentations have:
 * staircase steps along the coarse axis, a rough surface, thin rims eaten
 * away, and with noise small fragments; KeepLargestPiece (on by default)
 * keeps the largest connected piece as segmentation tools do. The output
 * is scaled by OutputScale (0.001 gives metres from millimetres) so that
 * tests see odd units too.
 *
 * Errors (vtkErrorMacro, empty output): an input surface that is empty or
 * not closed, manifold and consistently oriented, a
 * non-positive spacing or scale, a negative sigma or noise amplitude, a
 * phase outside [0, 1), or a grid of more than MaximumVoxels voxels.
 */
#ifndef vtkSimulatedSegmentationFilter_h
#define vtkSimulatedSegmentationFilter_h

#include "ThinTissueVTKModelsModule.h"
#include "vtkPolyDataAlgorithm.h"

class THINTISSUEVTKMODELS_EXPORT vtkSimulatedSegmentationFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkSimulatedSegmentationFilter* New();
  vtkTypeMacro(vtkSimulatedSegmentationFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Voxel spacing along x, y, z in the input's units.
  vtkSetVector3Macro(VoxelSpacing, double);
  vtkGetVector3Macro(VoxelSpacing, double);
  /// Where the samples lie past the surface's lowest bound, in voxels, in
  /// [0, 1) on each axis (0.5 by default: the bounds midway between
  /// samples). Other phases place the staircase differently, as another
  /// positioning of the patient in the scanner would.
  vtkSetVector3Macro(GridPhase, double);
  vtkGetVector3Macro(GridPhase, double);
  /// Standard deviation of the blur, in voxels (0: none).
  vtkSetMacro(BlurSigma, double);
  vtkGetMacro(BlurSigma, double);
  /// Standard deviation of the added noise, as a fraction of the tissue's
  /// intensity (0: none).
  vtkSetMacro(NoiseAmplitude, double);
  vtkGetMacro(NoiseAmplitude, double);
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  /// Output coordinates = input coordinates times this.
  vtkSetMacro(OutputScale, double);
  vtkGetMacro(OutputScale, double);
  vtkSetMacro(KeepLargestPiece, bool);
  vtkGetMacro(KeepLargestPiece, bool);
  vtkBooleanMacro(KeepLargestPiece, bool);
  /// Refuses grids larger than this (a spacing given in the wrong units).
  vtkSetMacro(MaximumVoxels, vtkIdType);
  vtkGetMacro(MaximumVoxels, vtkIdType);

protected:
  vtkSimulatedSegmentationFilter() = default;
  ~vtkSimulatedSegmentationFilter() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double VoxelSpacing[3] = { 0.3, 0.3, 0.9 };
  double GridPhase[3] = { 0.5, 0.5, 0.5 };
  double BlurSigma = 0.7;
  double NoiseAmplitude = 0.0;
  unsigned int Seed = 1;
  double OutputScale = 1.0;
  bool KeepLargestPiece = true;
  vtkIdType MaximumVoxels = 64 * 1024 * 1024;

private:
  vtkSimulatedSegmentationFilter(const vtkSimulatedSegmentationFilter&) = delete;
  void operator=(const vtkSimulatedSegmentationFilter&) = delete;
};

#endif
