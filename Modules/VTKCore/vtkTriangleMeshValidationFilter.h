/**
 * @class vtkTriangleMeshValidationFilter
 * @brief Checks a triangle surface for the defects that break binding,
 * cutting and simulation; passes the input through unchanged.
 *
 * After Update() the getters report non-manifold edges and vertices,
 * degenerate and duplicate triangles, inconsistently oriented edges, open
 * border edges, unreferenced vertices and connected pieces, and GetReport()
 * gives the full text with the first location of each defect.
 */
#ifndef vtkTriangleMeshValidationFilter_h
#define vtkTriangleMeshValidationFilter_h

#include "ThinTissueVTKCoreModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>

class THINTISSUEVTKCORE_EXPORT vtkTriangleMeshValidationFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkTriangleMeshValidationFilter* New();
  vtkTypeMacro(vtkTriangleMeshValidationFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkGetMacro(NumberOfNonManifoldEdges, vtkIdType);
  vtkGetMacro(NumberOfNonManifoldVertices, vtkIdType);
  vtkGetMacro(NumberOfDegenerateTriangles, vtkIdType);
  vtkGetMacro(NumberOfDuplicateTriangles, vtkIdType);
  vtkGetMacro(NumberOfInconsistentlyOrientedEdges, vtkIdType);
  vtkGetMacro(NumberOfBorderEdges, vtkIdType);
  vtkGetMacro(NumberOfUnreferencedVertices, vtkIdType);
  vtkGetMacro(NumberOfConnectedComponents, vtkIdType);
  vtkGetMacro(SignedVolume, double);
  /// Closed 2-manifold, consistently oriented, no degenerate/duplicate faces.
  vtkGetMacro(ClosedManifold, bool);
  /// ClosedManifold, a single piece and outward-facing (positive volume).
  vtkGetMacro(ClosedOutwardSingleSurface, bool);
  /// Text report, one line per defect with count and first location.
  const char* GetReport() const { return this->Report.c_str(); }

protected:
  vtkTriangleMeshValidationFilter() = default;
  ~vtkTriangleMeshValidationFilter() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkIdType NumberOfNonManifoldEdges = 0;
  vtkIdType NumberOfNonManifoldVertices = 0;
  vtkIdType NumberOfDegenerateTriangles = 0;
  vtkIdType NumberOfDuplicateTriangles = 0;
  vtkIdType NumberOfInconsistentlyOrientedEdges = 0;
  vtkIdType NumberOfBorderEdges = 0;
  vtkIdType NumberOfUnreferencedVertices = 0;
  vtkIdType NumberOfConnectedComponents = 0;
  double SignedVolume = 0.0;
  bool ClosedManifold = false;
  bool ClosedOutwardSingleSurface = false;
  std::string Report;

private:
  vtkTriangleMeshValidationFilter(const vtkTriangleMeshValidationFilter&) = delete;
  void operator=(const vtkTriangleMeshValidationFilter&) = delete;
};

#endif
