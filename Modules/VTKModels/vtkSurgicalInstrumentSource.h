/**
 * @class vtkSurgicalInstrumentSource
 * @brief An arthroscopic instrument in its tool frame (tip at the origin,
 * handle along +z, working side +x; millimetres).
 *
 * Output ports (all vtkPolyData):
 * 0 the visual surface (normals, point array "InstrumentPart": 0 handle,
 *   1 shaft, 2 working tip);
 * 1 the collision primitives: one line per centre-line segment with the
 *   cell array "Radius" (capsules; the thesis replaces the tool's collision
 *   mesh by its centre line, 6.3 / table 6-2);
 * 2 the working features: the tip as a vertex, cutting edges as polylines,
 *   the bite or window outline as a closed polyline.
 */
#ifndef vtkSurgicalInstrumentSource_h
#define vtkSurgicalInstrumentSource_h

#include "ThinTissueVTKModelsModule.h"
#include "vtkPolyDataAlgorithm.h"

class THINTISSUEVTKMODELS_EXPORT vtkSurgicalInstrumentSource : public vtkPolyDataAlgorithm
{
public:
  static vtkSurgicalInstrumentSource* New();
  vtkTypeMacro(vtkSurgicalInstrumentSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum InstrumentType
  {
    ProbeHook = 0,
    Punch = 1,
    SmallShaver = 2,
    LargeShaver = 3,
    Scissors = 4,
    Scalpel = 5
  };
  enum
  {
    VisualPort = 0,
    CollisionPort = 1,
    WorkingFeaturesPort = 2
  };

  ///@{
  /// The instrument (InstrumentType); resets the sizes to its defaults.
  void SetInstrumentType(int type);
  vtkGetMacro(InstrumentType, int);
  /// By name: probe_hook, punch, small_shaver, large_shaver, scissors,
  /// scalpel (case, spaces and dashes ignored). Reports unknown names.
  void SetInstrumentTypeByName(const char* name);
  ///@}

  ///@{
  /// Segments around the shaft (8 to 256).
  vtkSetMacro(SegmentsAround, int);
  vtkGetMacro(SegmentsAround, int);
  ///@}

  ///@{
  /// Jaw opening of punch and scissors, degrees (0 to 60).
  vtkSetMacro(JawOpeningDegrees, double);
  vtkGetMacro(JawOpeningDegrees, double);
  ///@}

  ///@{
  /// Shaft diameter and length, millimetres.
  vtkSetMacro(ShaftDiameter, double);
  vtkGetMacro(ShaftDiameter, double);
  vtkSetMacro(ShaftLength, double);
  vtkGetMacro(ShaftLength, double);
  ///@}

protected:
  vtkSurgicalInstrumentSource();
  ~vtkSurgicalInstrumentSource() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int InstrumentType = ProbeHook;
  int SegmentsAround;
  double JawOpeningDegrees;
  double ShaftDiameter;
  double ShaftLength;

private:
  vtkSurgicalInstrumentSource(const vtkSurgicalInstrumentSource&) = delete;
  void operator=(const vtkSurgicalInstrumentSource&) = delete;
};

#endif
