/**
 * @class   vtkCollisionMidSurfaceFilter
 * @brief   collision mid-surface with radii generated from a thin closed surface
 *
 * The automatic counterpart of the hand-made reduced collision meshes of the
 * thesis (its future work, 7.2; kernel `makeCollisionMidSurface`): from a
 * closed, manifold, thin visual surface, a triangle mid-surface with
 * `VertexCount` vertices and a per-point radius array (half the local
 * thickness) whose thick surface approximates the visual one. The output is
 * ready for vtkVisualCollisionBindingFilter (input 1).
 *
 * Field data of the output: `HausdorffDistance` (two-sided, visual surface
 * against the thick surface), `ThicknessRatio` (largest thickness over the
 * extent across) and `ThicknessAxis`. Bad input (open, non-manifold, not
 * thin: the message gives the ratio) leaves an empty output and the message
 * in GetLastErrorMessage(). Progress events with the stage as progress text;
 * SetAbortExecute(1) stops at the next report with an empty output.
 */
#ifndef vtkCollisionMidSurfaceFilter_h
#define vtkCollisionMidSurfaceFilter_h

#include "ThinTissueVTKBindingModule.h"

#include <vtkPolyDataAlgorithm.h>

#include <string>

class THINTISSUEVTKBINDING_EXPORT vtkCollisionMidSurfaceFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkCollisionMidSurfaceFilter* New();
  vtkTypeMacro(vtkCollisionMidSurfaceFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Vertices of the mid-surface (at least 8; default 85, the steak's finer
  /// collision mesh in the thesis).
  vtkSetClampMacro(VertexCount, int, 8, VTK_INT_MAX);
  vtkGetMacro(VertexCount, int);
  ///@}

  ///@{
  /// Largest thickness over the extent across allowed (default 0.35).
  vtkSetClampMacro(MaximumThicknessRatio, double, 1e-6, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumThicknessRatio, double);
  ///@}

  ///@{
  /// Name of the radius array written on the output (default "Radius").
  vtkSetStringMacro(RadiusArrayName);
  vtkGetStringMacro(RadiusArrayName);
  ///@}

  ///@{
  /// Join holes of the outline beyond the surface's tunnels that are seen
  /// through to the hole or the outline near them (a slit seen as two
  /// holes, a notch a flap closes in projection; default on). Off: the
  /// mid-surface spans them.
  vtkSetMacro(JoinSeenThroughHoles, bool);
  vtkGetMacro(JoinSeenThroughHoles, bool);
  vtkBooleanMacro(JoinSeenThroughHoles, bool);
  ///@}

  ///@{
  /// Where the inner lattice of a one-axis mid-surface lies, in [0, 1]: a
  /// shift by this share of a lattice vector (default 0; 1/3 and 2/3 put
  /// its points at the centres of the default's triangles). A preparation
  /// whose binding refuses one lattice tries others (prepareTissue).
  vtkSetClampMacro(LatticePhase, double, 0.0, 1.0);
  vtkGetMacro(LatticePhase, double);
  ///@}

  /// Measured on the last run (0 before one, or after a failure).
  vtkGetMacro(HausdorffDistance, double);
  vtkGetMacro(ThicknessRatio, double);
  /// Holes the last run joined to another loop of the outline.
  vtkGetMacro(JoinedHoles, int);

  /// Empty after a successful run.
  const char* GetLastErrorMessage() const { return this->LastErrorMessage.c_str(); }

protected:
  vtkCollisionMidSurfaceFilter();
  ~vtkCollisionMidSurfaceFilter() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int VertexCount = 85;
  double MaximumThicknessRatio = 0.35;
  char* RadiusArrayName = nullptr;
  bool JoinSeenThroughHoles = true;
  double LatticePhase = 0.0;
  double HausdorffDistance = 0.0;
  double ThicknessRatio = 0.0;
  int JoinedHoles = 0;
  std::string LastErrorMessage;

private:
  vtkCollisionMidSurfaceFilter(const vtkCollisionMidSurfaceFilter&) = delete;
  void operator=(const vtkCollisionMidSurfaceFilter&) = delete;
};

#endif
