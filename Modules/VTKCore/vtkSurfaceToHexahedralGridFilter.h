/**
 * @class vtkSurfaceToHexahedralGridFilter
 * @brief Makes a hexahedral simulation grid from a closed surface: the
 * cubic cells of a regular grid over the surface's bounding box that the
 * surface passes through or that lie inside it (a sparse grid, as SOFA's
 * SparseGridTopology), with shared nodes.
 *
 * Input: a closed vtkPolyData (polygons; triangle strips are split).
 * Output: a vtkUnstructuredGrid of VTK_HEXAHEDRON cells with cell arrays
 * "GridIndex" (3 ints: the cell's i, j, k in the full grid) and
 * "IntersectsSurface" (1 where the surface passes through the cell) and the
 * point array "FixedNode" (all 0).
 *
 * The resolution is CellsAlongLongestSide, or CellSize when it is positive.
 */
#ifndef vtkSurfaceToHexahedralGridFilter_h
#define vtkSurfaceToHexahedralGridFilter_h

#include "ThinTissueVTKCoreModule.h"
#include "vtkUnstructuredGridAlgorithm.h"

class THINTISSUEVTKCORE_EXPORT vtkSurfaceToHexahedralGridFilter
  : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkSurfaceToHexahedralGridFilter* New();
  vtkTypeMacro(vtkSurfaceToHexahedralGridFilter, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Cubic cells along the longest side of the bounding box (at least 1;
  /// used when CellSize is 0). Default 10.
  vtkSetMacro(CellsAlongLongestSide, int);
  vtkGetMacro(CellsAlongLongestSide, int);
  ///@}

  ///@{
  /// Edge length of the cells; overrides CellsAlongLongestSide when
  /// positive. Default 0.
  vtkSetMacro(CellSize, double);
  vtkGetMacro(CellSize, double);
  ///@}

  ///@{
  /// After Update(): the full grid's corner, cell edge length and cell
  /// counts along x, y, z.
  vtkGetVector3Macro(GridOrigin, double);
  vtkGetMacro(GridCellSize, double);
  vtkGetVector3Macro(GridDimensions, int);
  ///@}

protected:
  vtkSurfaceToHexahedralGridFilter() = default;
  ~vtkSurfaceToHexahedralGridFilter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int CellsAlongLongestSide = 10;
  double CellSize = 0.0;
  double GridOrigin[3] = { 0.0, 0.0, 0.0 };
  double GridCellSize = 0.0;
  int GridDimensions[3] = { 0, 0, 0 };

private:
  vtkSurfaceToHexahedralGridFilter(const vtkSurfaceToHexahedralGridFilter&) = delete;
  void operator=(const vtkSurfaceToHexahedralGridFilter&) = delete;
};

#endif
