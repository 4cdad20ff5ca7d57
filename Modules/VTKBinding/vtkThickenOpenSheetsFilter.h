/**
 * @class   vtkThickenOpenSheetsFilter
 * @brief   closed thin slabs from tissues segmented as one open surface
 *
 * VTK adapter of the kernel's `thickenOpenSheets` (SheetThickening.h): each
 * open piece of the input surface (a cartilage segmented as its articular
 * sheet) becomes the closed slab of `Thickness` (input units) it stands
 * for, the sheet its mid-surface; closed pieces pass unchanged. The output
 * is ready for vtkCollisionMidSurfaceFilter. Point data arrays follow their
 * points to both layers; normals are recomputed when the input has them.
 * Field data of the output: `ThickenedPieces`, `BorderLoops`. Bad input
 * (non-manifold, inconsistently oriented, a thickness that folds the
 * layers) leaves an empty output and the message in GetLastErrorMessage().
 */
#ifndef vtkThickenOpenSheetsFilter_h
#define vtkThickenOpenSheetsFilter_h

#include "ThinTissueVTKBindingModule.h"

#include <vtkPolyDataAlgorithm.h>

#include <string>

class THINTISSUEVTKBINDING_EXPORT vtkThickenOpenSheetsFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkThickenOpenSheetsFilter* New();
  vtkTypeMacro(vtkThickenOpenSheetsFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Thickness given to the open pieces, in the input's units (default 2).
  vtkSetMacro(Thickness, double);
  vtkGetMacro(Thickness, double);
  ///@}

  /// Of the last run (0 before one, or after a failure).
  vtkGetMacro(ThickenedPieces, int);
  vtkGetMacro(BorderLoops, int);

  /// Empty after a successful run.
  const char* GetLastErrorMessage() const { return this->LastErrorMessage.c_str(); }

protected:
  vtkThickenOpenSheetsFilter() = default;
  ~vtkThickenOpenSheetsFilter() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double Thickness = 2.0;
  int ThickenedPieces = 0;
  int BorderLoops = 0;
  std::string LastErrorMessage;

private:
  vtkThickenOpenSheetsFilter(const vtkThickenOpenSheetsFilter&) = delete;
  void operator=(const vtkThickenOpenSheetsFilter&) = delete;
};

#endif
