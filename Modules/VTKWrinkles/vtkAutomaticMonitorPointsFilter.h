/**
 * @class vtkAutomaticMonitorPointsFilter
 * @brief Monitor and region data points of the wrinkles (thesis 4.3, step
 * one) derived from a tissue's collision mid-surface: along its thin free
 * border (where the radius is smallest, e.g. a meniscus's inner rim),
 * region points inward on the mid-surface, thickness from the radii.
 *
 * Input: the collision mid-surface (vtkPolyData of triangles with the point
 * array "Radius"), e.g. a tissue source's port 1 or
 * vtkCollisionMidSurfaceFilter's output. Output: the monitor data in the
 * format of vtkMeniscusSource's port 4 (one polyline per curve; point
 * arrays "RegionPoint", "Thickness", "CurveId"), ready for
 * vtkWrinkleDisplacementFilter's port 1 (with its MonitorPointSpacing > 0).
 *
 * Errors (no "Radius", no free border, no thin run) are reported with
 * vtkErrorMacro and give an empty output.
 */
#ifndef vtkAutomaticMonitorPointsFilter_h
#define vtkAutomaticMonitorPointsFilter_h

#include "ThinTissueVTKWrinklesModule.h"
#include "vtkPolyDataAlgorithm.h"

class THINTISSUEVTKWRINKLES_EXPORT vtkAutomaticMonitorPointsFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkAutomaticMonitorPointsFilter* New();
  vtkTypeMacro(vtkAutomaticMonitorPointsFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Border vertices with radius at most r_min + ThinFraction (r_max -
  /// r_min) are thin (default 0.35); all are when the radii differ by at
  /// most UniformTolerance r_max (default 0.05).
  vtkSetClampMacro(ThinFraction, double, 0.0, 1.0);
  vtkGetMacro(ThinFraction, double);
  vtkSetClampMacro(UniformTolerance, double, 0.0, 1.0);
  vtkGetMacro(UniformTolerance, double);
  ///@}

  ///@{
  /// Thin runs are split where the border turns by more than CornerAngle
  /// (radians, default 1); every run at least MinimumRunFraction times as
  /// long as the longest is kept (default 0.3), or with UseNearPoint only
  /// the run nearest NearPoint.
  vtkSetClampMacro(CornerAngle, double, 0.0, 3.1416);
  vtkGetMacro(CornerAngle, double);
  vtkSetClampMacro(MinimumRunFraction, double, 0.0, 1.0);
  vtkGetMacro(MinimumRunFraction, double);
  vtkSetMacro(UseNearPoint, vtkTypeBool);
  vtkGetMacro(UseNearPoint, vtkTypeBool);
  vtkBooleanMacro(UseNearPoint, vtkTypeBool);
  vtkSetVector3Macro(NearPoint, double);
  vtkGetVector3Macro(NearPoint, double);
  ///@}

  ///@{
  /// Region data points this far inward (model units); 0 (default):
  /// RegionDepthInRadii (default 8) times the run's mean radius.
  vtkSetClampMacro(RegionDepth, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RegionDepth, double);
  vtkSetClampMacro(RegionDepthInRadii, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RegionDepthInRadii, double);
  ///@}

protected:
  vtkAutomaticMonitorPointsFilter();
  ~vtkAutomaticMonitorPointsFilter() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double ThinFraction;
  double UniformTolerance;
  double CornerAngle;
  double MinimumRunFraction;
  vtkTypeBool UseNearPoint = false;
  double NearPoint[3] = { 0.0, 0.0, 0.0 };
  double RegionDepth;
  double RegionDepthInRadii;

private:
  vtkAutomaticMonitorPointsFilter(const vtkAutomaticMonitorPointsFilter&) = delete;
  void operator=(const vtkAutomaticMonitorPointsFilter&) = delete;
};

#endif
