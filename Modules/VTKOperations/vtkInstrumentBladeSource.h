/**
 * @class vtkInstrumentBladeSource
 * @brief The cutting surface an arthroscopic instrument makes (thesis 6.4),
 * as triangles for vtkThinTissueCutFilter's blade port.
 *
 * The instrument (Instrument: 0 probe hook, 1 punch, 2 small shaver, 3
 * large shaver, 4 scissors, 5 scalpel; the order of
 * SurgicalInstrumentType) is placed by Pose, a 4x4 matrix from its tool
 * frame (tip at the origin, shaft along +z to the handle, working side +x)
 * to the world; strokes go from PreviousPose (and PreviousJawOpening) to
 * Pose (and JawOpening):
 *  - punch: its bite outline swept across the open jaws' gap (6.4.2; with
 *    DROP_FREE_PIECES the bitten piece goes);
 *  - shavers: the window's outline swept through the window (6.4.3);
 *  - scissors: where the blades closed on each other between the openings
 *    (1 open, 0 closed);
 *  - scalpel: the surface its edge swept;
 *  - probe hook: nothing (an empty output).
 * Bad parameters are reported with vtkErrorMacro and give an empty output.
 */
#ifndef vtkInstrumentBladeSource_h
#define vtkInstrumentBladeSource_h

#include "ThinTissueVTKOperationsModule.h"
#include "vtkNew.h" // for vtkNew
#include "vtkPolyDataAlgorithm.h"

class vtkMatrix4x4;

class THINTISSUEVTKOPERATIONS_EXPORT vtkInstrumentBladeSource : public vtkPolyDataAlgorithm
{
public:
  static vtkInstrumentBladeSource* New();
  vtkTypeMacro(vtkInstrumentBladeSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The instrument type (see the class description); default 1, punch.
  vtkSetClampMacro(Instrument, int, 0, 5);
  vtkGetMacro(Instrument, int);
  ///@}

  ///@{
  /// Tool frame to world, now and at the previous step (identity by
  /// default). The matrices are copied.
  void SetPose(vtkMatrix4x4* pose);
  vtkMatrix4x4* GetPose() { return this->Pose; }
  void SetPreviousPose(vtkMatrix4x4* pose);
  vtkMatrix4x4* GetPreviousPose() { return this->PreviousPose; }
  ///@}

  ///@{
  /// Scissors: the jaw opening now and before (1 open, 0 closed).
  vtkSetClampMacro(JawOpening, double, 0.0, 1.0);
  vtkGetMacro(JawOpening, double);
  vtkSetClampMacro(PreviousJawOpening, double, 0.0, 1.0);
  vtkGetMacro(PreviousJawOpening, double);
  ///@}

protected:
  vtkInstrumentBladeSource();
  ~vtkInstrumentBladeSource() override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  vtkMTimeType GetMTime() override;

  int Instrument = 1;
  double JawOpening = 0.0;
  double PreviousJawOpening = 1.0;
  vtkNew<vtkMatrix4x4> Pose;
  vtkNew<vtkMatrix4x4> PreviousPose;

private:
  vtkInstrumentBladeSource(const vtkInstrumentBladeSource&) = delete;
  void operator=(const vtkInstrumentBladeSource&) = delete;
};

#endif
