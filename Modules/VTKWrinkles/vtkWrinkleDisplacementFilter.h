/**
 * @class vtkWrinkleDisplacementFilter
 * @brief Procedural wrinkles on a deformed embedded surface (thesis ch. 4):
 * monitor points embedded in the hexahedra watch the coarse deformation;
 * when the instrument's push reverses (4.4.1) the surface points near them
 * are displaced by the wrinkle function of formula 4-16 (4.4.2).
 *
 * Input port 0: the deformed visual surface, embedded (point arrays
 * "HexahedronId" and "TrilinearCoordinates" of vtkHexahedralEmbeddingFilter,
 * e.g. the output of vtkEmbeddedSurfaceDeformationFilter). Port 1: the
 * monitor and region data (vtkMeniscusSource's port 4: a vtkPolyData of
 * monitor data points, one polyline per curve, point arrays "RegionPoint"
 * (3 components) and "Thickness"). Port 2: the deformed hexahedral grid;
 * its rest shape is its points minus the point array "Displacement" (as
 * vtkCorotationalHexFemFilter writes it) or, without that array, its points
 * when the filter is built.
 *
 * State: every update is one step of 4.4 (monitor points, reference
 * configuration, wrinkles). The filter is built (monitor points resampled
 * with B-splines when MonitorPointSpacing > 0, embedded, affected surface
 * points found at rest) at the first update and again when port 1 is
 * modified, a point count changes, or after Reset(). The contact state of
 * the step is set with SetLowerSurfaceContacts, SetInstrumentTouching and
 * SetInstrumentContactPoint (from the collision scene: see
 * thintissue::wrinkleContactState).
 *
 * Output: input 0 with its points displaced and the point array
 * "WrinkleDisplacement" (3 doubles; zero where nothing moved).
 *
 * Errors (missing embedding arrays, monitor data without RegionPoint or
 * Thickness, a bad parameter, a grid that is not hexahedral) are reported
 * with vtkErrorMacro and give an empty output; the state is dropped.
 */
#ifndef vtkWrinkleDisplacementFilter_h
#define vtkWrinkleDisplacementFilter_h

#include "ThinTissueVTKWrinklesModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr

class vtkUnstructuredGrid;

class THINTISSUEVTKWRINKLES_EXPORT vtkWrinkleDisplacementFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkWrinkleDisplacementFilter* New();
  vtkTypeMacro(vtkWrinkleDisplacementFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Monitor data (port 1) and the deformed hexahedra (port 2).
  void SetMonitorPointsConnection(vtkAlgorithmOutput* output)
  {
    this->SetInputConnection(1, output);
  }
  void SetMonitorPointsData(vtkPolyData* monitors);
  void SetGridConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(2, output); }
  void SetGridData(vtkUnstructuredGrid* grid);
  ///@}

  ///@{
  /// Contacts of the step (4.4.1): lower-surface contacts with other bodies
  /// than instruments, whether the instrument touches, and where.
  vtkSetClampMacro(LowerSurfaceContacts, int, 0, VTK_INT_MAX);
  vtkGetMacro(LowerSurfaceContacts, int);
  vtkSetMacro(InstrumentTouching, vtkTypeBool);
  vtkGetMacro(InstrumentTouching, vtkTypeBool);
  vtkBooleanMacro(InstrumentTouching, vtkTypeBool);
  vtkSetVector3Macro(InstrumentContactPoint, double);
  vtkGetVector3Macro(InstrumentContactPoint, double);
  ///@}

  ///@{
  /// Parameters of 4.4 (defaults of thintissue::WrinkleParameters):
  /// theta^d (5 pi), s (1), m^up (0.5; <= 0: no bound), r^c (0), e - s
  /// (70), N_c (< 0: 0.5 (e - s)), N_s (0), N_e (1).
  vtkSetMacro(Frequency, double);
  vtkGetMacro(Frequency, double);
  vtkSetMacro(Scale, double);
  vtkGetMacro(Scale, double);
  vtkSetMacro(MagnitudeBound, double);
  vtkGetMacro(MagnitudeBound, double);
  vtkSetMacro(CutOffThickness, double);
  vtkGetMacro(CutOffThickness, double);
  vtkSetMacro(WindowSize, int);
  vtkGetMacro(WindowSize, int);
  vtkSetMacro(ReversalThreshold, double);
  vtkGetMacro(ReversalThreshold, double);
  vtkSetMacro(StartContacts, int);
  vtkGetMacro(StartContacts, int);
  vtkSetMacro(EndContacts, int);
  vtkGetMacro(EndContacts, int);
  ///@}

  enum Anchors
  {
    ANCHOR_CURRENT = 0,
    ANCHOR_REFERENCE = 1
  };
  ///@{
  /// Where the wrinkle offset is added (thintissue::WrinkleAnchor): to the
  /// current monitor points (ANCHOR_CURRENT, the default: continuous, never
  /// more than m^up) or to the reference points as formula 4-16 writes it.
  vtkSetClampMacro(Anchor, int, ANCHOR_CURRENT, ANCHOR_REFERENCE);
  vtkGetMacro(Anchor, int);
  ///@}

  ///@{
  /// Affected surface points (4.3): sphere radius, Gaussian width of the
  /// attenuation along the region lines, blend width across them; 0
  /// (default): from the monitor data (see thintissue::WrinkleInfluence).
  /// Take effect when the filter is built.
  vtkSetMacro(SphereRadius, double);
  vtkGetMacro(SphereRadius, double);
  vtkSetMacro(GaussianWidth, double);
  vtkGetMacro(GaussianWidth, double);
  vtkSetMacro(BlendWidth, double);
  vtkGetMacro(BlendWidth, double);
  ///@}

  ///@{
  /// Largest distance between consecutive monitor points: > 0 resamples
  /// the data curves with cubic B-splines (4.3); 0 (default) takes the
  /// points as given. Takes effect when the filter is built.
  vtkSetClampMacro(MonitorPointSpacing, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MonitorPointSpacing, double);
  ///@}

  /// Drops the state: the next update builds the filter again.
  void Reset();

  ///@{
  /// After an update: whether the surface wrinkles, the monitor points and
  /// the surface points that moved.
  vtkGetMacro(Wrinkling, vtkTypeBool);
  vtkGetMacro(NumberOfMonitorPoints, vtkIdType);
  vtkGetMacro(NumberOfDisplacedPoints, vtkIdType);
  ///@}

protected:
  vtkWrinkleDisplacementFilter();
  ~vtkWrinkleDisplacementFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int LowerSurfaceContacts = 0;
  vtkTypeBool InstrumentTouching = false;
  double InstrumentContactPoint[3] = { 0.0, 0.0, 0.0 };
  double Frequency;
  double Scale;
  double MagnitudeBound;
  double CutOffThickness;
  int WindowSize;
  double ReversalThreshold;
  int StartContacts;
  int EndContacts;
  int Anchor = ANCHOR_CURRENT;
  double SphereRadius = 0.0;
  double GaussianWidth = 0.0;
  double BlendWidth = 0.0;
  double MonitorPointSpacing = 0.0;
  vtkTypeBool Wrinkling = false;
  vtkIdType NumberOfMonitorPoints = 0;
  vtkIdType NumberOfDisplacedPoints = 0;

private:
  vtkWrinkleDisplacementFilter(const vtkWrinkleDisplacementFilter&) = delete;
  void operator=(const vtkWrinkleDisplacementFilter&) = delete;

  struct Internals;
  std::unique_ptr<Internals> State;
  void Build(vtkPolyData* surface, vtkPolyData* monitors, vtkUnstructuredGrid* grid);
  void WriteOutput(vtkPolyData* surface, vtkPolyData* output);
};

#endif
