/**
 * @class vtkEmbeddedSurfaceDeformationFilter
 * @brief Moves an embedded polydata with its deformed hexahedral grid:
 * x = H u (thesis formula 4-1).
 *
 * Input 0: a polydata embedded by vtkHexahedralEmbeddingFilter (point arrays
 * "HexahedronId" and "TrilinearCoordinates").
 * Input 1: the deformed hexahedral grid, with the same cells and point
 * numbering as the rest grid it was embedded in (set with
 * SetGridConnection / SetGridData).
 * Output: input 0 with its points moved; point and cell normals, if
 * present, are recomputed from the moved polygons (RecomputeNormals).
 */
#ifndef vtkEmbeddedSurfaceDeformationFilter_h
#define vtkEmbeddedSurfaceDeformationFilter_h

#include "ThinTissueVTKCoreModule.h"
#include "vtkPolyDataAlgorithm.h"

class vtkUnstructuredGrid;

class THINTISSUEVTKCORE_EXPORT vtkEmbeddedSurfaceDeformationFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkEmbeddedSurfaceDeformationFilter* New();
  vtkTypeMacro(vtkEmbeddedSurfaceDeformationFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The deformed hexahedral grid (input 1).
  void SetGridConnection(vtkAlgorithmOutput* output);
  void SetGridData(vtkUnstructuredGrid* grid);
  ///@}

  ///@{
  /// Recompute the normals of the input, if it has any, from the moved
  /// polygons (area-weighted at the points). Default on.
  vtkSetMacro(RecomputeNormals, bool);
  vtkGetMacro(RecomputeNormals, bool);
  vtkBooleanMacro(RecomputeNormals, bool);
  ///@}

protected:
  vtkEmbeddedSurfaceDeformationFilter();
  ~vtkEmbeddedSurfaceDeformationFilter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool RecomputeNormals = true;

private:
  vtkEmbeddedSurfaceDeformationFilter(const vtkEmbeddedSurfaceDeformationFilter&) = delete;
  void operator=(const vtkEmbeddedSurfaceDeformationFilter&) = delete;
};

#endif
