/**
 * @class vtkThinSlabSource
 * @brief Closed triangle surface of a thin slab (a box whose faces are
 * regular grids), centred at the origin, with normals and texture
 * coordinates: the default tissue of the demo and of many tests.
 */
#ifndef vtkThinSlabSource_h
#define vtkThinSlabSource_h

#include "ThinTissueVTKCoreModule.h"
#include "vtkPolyDataAlgorithm.h"

class THINTISSUEVTKCORE_EXPORT vtkThinSlabSource : public vtkPolyDataAlgorithm
{
public:
  static vtkThinSlabSource* New();
  vtkTypeMacro(vtkThinSlabSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Extent along x, y and z (positive).
  vtkSetMacro(Width, double);
  vtkGetMacro(Width, double);
  vtkSetMacro(Depth, double);
  vtkGetMacro(Depth, double);
  vtkSetMacro(Thickness, double);
  vtkGetMacro(Thickness, double);
  ///@}

  ///@{
  /// Grid cells along x, y and z (at least 1).
  vtkSetMacro(CellsX, int);
  vtkGetMacro(CellsX, int);
  vtkSetMacro(CellsY, int);
  vtkGetMacro(CellsY, int);
  vtkSetMacro(CellsZ, int);
  vtkGetMacro(CellsZ, int);
  ///@}

protected:
  vtkThinSlabSource();
  ~vtkThinSlabSource() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double Width = 10.0;
  double Depth = 10.0;
  double Thickness = 0.5;
  int CellsX = 16;
  int CellsY = 16;
  int CellsZ = 1;

private:
  vtkThinSlabSource(const vtkThinSlabSource&) = delete;
  void operator=(const vtkThinSlabSource&) = delete;
};

#endif
