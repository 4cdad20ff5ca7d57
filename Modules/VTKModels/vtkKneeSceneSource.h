/**
 * @class vtkKneeSceneSource
 * @brief The whole knee scene of the simulator in one multiblock: blocks
 * "Tibia" and "Femur" (each with "Visual" and "Collision"), and
 * "TibialCartilage", "AnteriorCruciateLigament", "PosteriorCruciateLigament"
 * and "MedialMeniscus" (each with "Visual", "Collision", "Simulation"), in
 * the knee frame of KneeAnatomy.h (mm; +x lateral, +y anterior, +z up).
 */
#ifndef vtkKneeSceneSource_h
#define vtkKneeSceneSource_h

#include "ThinTissueVTKModelsModule.h"
#include "vtkMultiBlockDataSetAlgorithm.h"

class THINTISSUEVTKMODELS_EXPORT vtkKneeSceneSource : public vtkMultiBlockDataSetAlgorithm
{
public:
  static vtkKneeSceneSource* New();
  vtkTypeMacro(vtkKneeSceneSource, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Distance between tibial and femoral cartilage, millimetres.
  vtkSetMacro(JointGap, double);
  vtkGetMacro(JointGap, double);
  ///@}

  ///@{
  /// Tear of the medial meniscus (vtkMeniscusSource::TearType), at the
  /// typical place of its type.
  vtkSetClampMacro(MeniscusTearType, int, 0, 4);
  vtkGetMacro(MeniscusTearType, int);
  ///@}

protected:
  vtkKneeSceneSource();
  ~vtkKneeSceneSource() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double JointGap;
  int MeniscusTearType = 0;

private:
  vtkKneeSceneSource(const vtkKneeSceneSource&) = delete;
  void operator=(const vtkKneeSceneSource&) = delete;
};

#endif
