/**
 * @class vtkMeniscusSource
 * @brief The medial meniscus (thesis ch. 4 and 6.4), intact or torn, in the
 * knee frame of KneeAnatomy.h (mm; +x lateral, +y anterior, +z proximal).
 *
 * Ports 0-3 as vtkTissueModelSource; port 4 the monitor data points of
 * thesis 4.3 (vtkPolyData: one polyline per curve along the inner border or
 * a tear lip; point arrays "RegionPoint" (3 components), "Thickness",
 * "CurveId"), also the block "MonitorPoints" of port 3. With
 * MonitorPointSpacing > 0 they are re-sampled densely (fig. 4-7).
 */
#ifndef vtkMeniscusSource_h
#define vtkMeniscusSource_h

#include "ThinTissueVTKModelsModule.h"
#include "vtkTissueModelSource.h"

#include <memory> // for std::shared_ptr

class THINTISSUEVTKMODELS_EXPORT vtkMeniscusSource : public vtkTissueModelSource
{
public:
  static vtkMeniscusSource* New();
  vtkTypeMacro(vtkMeniscusSource, vtkTissueModelSource);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum TearType
  {
    NoTear = 0,
    LongitudinalTear = 1,
    RadialTear = 2,
    FlapTear = 3,
    HorizontalCleavageTear = 4
  };
  enum
  {
    MonitorPointsPort = 4
  };

  /// Sets the tear type and places the tear where that type typically is;
  /// set the placement afterwards to move it.
  void SetTearType(int type);
  vtkGetMacro(TearType, int);

  ///@{
  /// Tear placement in parameters of the C: along from the posterior horn
  /// (0) to the anterior horn (1), across from the inner edge (0) to the
  /// rim (1); opening in millimetres.
  vtkSetMacro(TearAlongBegin, double);
  vtkGetMacro(TearAlongBegin, double);
  vtkSetMacro(TearAlongEnd, double);
  vtkGetMacro(TearAlongEnd, double);
  vtkSetMacro(TearAcross, double);
  vtkGetMacro(TearAcross, double);
  vtkSetMacro(TearOpening, double);
  vtkGetMacro(TearOpening, double);
  ///@}

  ///@{
  /// Cells along, across and through (visual), along and across
  /// (collision), along, across and through (hexahedra).
  vtkSetVector3Macro(VisualCells, int);
  vtkGetVector3Macro(VisualCells, int);
  vtkSetVector2Macro(CollisionCells, int);
  vtkGetVector2Macro(CollisionCells, int);
  vtkSetVector3Macro(Hexahedra, int);
  vtkGetVector3Macro(Hexahedra, int);
  ///@}

  /// The 6,096-face visual resolution of section 6.4.1.
  void SetExaminationResolution();

  ///@{
  /// Rim height and inner edge height, millimetres.
  vtkSetMacro(RimHeight, double);
  vtkGetMacro(RimHeight, double);
  vtkSetMacro(InnerEdgeHeight, double);
  vtkGetMacro(InnerEdgeHeight, double);
  ///@}

  ///@{
  /// 0: the monitor data points; > 0: re-sampled at most this far apart (mm).
  vtkSetMacro(MonitorPointSpacing, double);
  vtkGetMacro(MonitorPointSpacing, double);
  ///@}

  vtkPolyData* GetMonitorPointsOutput();

protected:
  vtkMeniscusSource();
  ~vtkMeniscusSource() override = default;

  thintissue::TissueModel BuildTissueModel() override;
  void FillExtraOutputs(vtkInformationVector* outputs, vtkMultiBlockDataSet* all) override;

  int TearType = NoTear;
  double TearAlongBegin;
  double TearAlongEnd;
  double TearAcross;
  double TearOpening;
  int VisualCells[3];
  int CollisionCells[2];
  int Hexahedra[3];
  double RimHeight;
  double InnerEdgeHeight;
  double MonitorPointSpacing = 0.0;

private:
  vtkMeniscusSource(const vtkMeniscusSource&) = delete;
  void operator=(const vtkMeniscusSource&) = delete;

  struct Internals;
  std::shared_ptr<Internals> LastModel;
};

#endif
