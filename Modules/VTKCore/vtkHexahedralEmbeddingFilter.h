/**
 * @class vtkHexahedralEmbeddingFilter
 * @brief Embeds the points of a polydata in a hexahedral grid (thesis 4.3):
 * per point the hexahedron that contains it (or the nearest one) and its
 * trilinear local coordinates there.
 *
 * Input 0: the polydata whose points are embedded (e.g. a visual surface).
 * Input 1: the rest configuration of a vtkUnstructuredGrid of
 * VTK_HEXAHEDRON cells (set with SetGridConnection / SetGridData).
 * Output: input 0 with point arrays "HexahedronId" (vtkIdType) and
 * "TrilinearCoordinates" (3 doubles), which
 * vtkEmbeddedSurfaceDeformationFilter uses to follow a deformed grid.
 *
 * Points outside every hexahedron take the nearest one with extrapolated
 * local coordinates, clamped to the hexahedron when they would extend more
 * than MaximumExtrapolation cells beyond it.
 */
#ifndef vtkHexahedralEmbeddingFilter_h
#define vtkHexahedralEmbeddingFilter_h

#include "ThinTissueVTKCoreModule.h"
#include "vtkPolyDataAlgorithm.h"

class vtkUnstructuredGrid;

class THINTISSUEVTKCORE_EXPORT vtkHexahedralEmbeddingFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkHexahedralEmbeddingFilter* New();
  vtkTypeMacro(vtkHexahedralEmbeddingFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Names of the point arrays written by this filter.
  static const char* GetHexahedronIdArrayName() { return "HexahedronId"; }
  static const char* GetTrilinearCoordinatesArrayName() { return "TrilinearCoordinates"; }

  ///@{
  /// The hexahedral grid (input 1) in its rest configuration.
  void SetGridConnection(vtkAlgorithmOutput* output);
  void SetGridData(vtkUnstructuredGrid* grid);
  ///@}

  ///@{
  /// How far, in local units (a cell edge is 1), the coordinates of an
  /// outside point may extend beyond its hexahedron before they are clamped
  /// to the hexahedron's closest point. Default 1.
  vtkSetMacro(MaximumExtrapolation, double);
  vtkGetMacro(MaximumExtrapolation, double);
  ///@}

  ///@{
  /// Local-coordinate tolerance of "inside a hexahedron". Default 1e-9.
  vtkSetMacro(InsideTolerance, double);
  vtkGetMacro(InsideTolerance, double);
  ///@}

  ///@{
  /// After Update(): points outside every hexahedron, and of those the ones
  /// whose local coordinates were clamped.
  vtkGetMacro(NumberOfOutsidePoints, vtkIdType);
  vtkGetMacro(NumberOfClampedPoints, vtkIdType);
  ///@}

protected:
  vtkHexahedralEmbeddingFilter();
  ~vtkHexahedralEmbeddingFilter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double MaximumExtrapolation = 1.0;
  double InsideTolerance = 1e-9;
  vtkIdType NumberOfOutsidePoints = 0;
  vtkIdType NumberOfClampedPoints = 0;

private:
  vtkHexahedralEmbeddingFilter(const vtkHexahedralEmbeddingFilter&) = delete;
  void operator=(const vtkHexahedralEmbeddingFilter&) = delete;
};

#endif
