/**
 * @class vtkThickSurfaceContactFilter
 * @brief Contacts between two triangle surfaces "with radii" (thesis 2.4,
 * 5.1: Spillmann's reduced triangles with radii), for visualisation and for
 * pipeline users.
 *
 * Input 0 is surface A, input 1 surface B (vtkPolyData; the optional point
 * array "Radius" gives each vertex's radius). The output holds one vertex
 * per contact -- for every vertex of A its deepest contact with a triangle of
 * B within ContactDistance, and the same for B against A -- at the closest
 * point on the touched mid-surface, with the point arrays "Normal" (unit,
 * from B toward A), "Depth" (sum of the radii minus the distance; > 0 when
 * the thick volumes overlap), "Side" (+1/-1: side of the touched triangle)
 * and "VertexOfA" (1 when the contact starts from a vertex of A).
 */
#ifndef vtkThickSurfaceContactFilter_h
#define vtkThickSurfaceContactFilter_h

#include "ThinTissueVTKCoreModule.h"
#include "vtkPolyDataAlgorithm.h"

class THINTISSUEVTKCORE_EXPORT vtkThickSurfaceContactFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkThickSurfaceContactFilter* New();
  vtkTypeMacro(vtkThickSurfaceContactFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Extra distance at which contacts are reported before the radii touch.
  vtkSetClampMacro(ContactDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ContactDistance, double);
  ///@}

  /// Surface B (input port 1).
  void SetSurfaceBConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  /// Number of contacts found by the last update.
  vtkGetMacro(NumberOfContacts, vtkIdType);

protected:
  vtkThickSurfaceContactFilter();
  ~vtkThickSurfaceContactFilter() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double ContactDistance = 0.0;
  vtkIdType NumberOfContacts = 0;

private:
  vtkThickSurfaceContactFilter(const vtkThickSurfaceContactFilter&) = delete;
  void operator=(const vtkThickSurfaceContactFilter&) = delete;
};

#endif
