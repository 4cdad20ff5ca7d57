/**
 * @class vtkKneeBoneSource
 * @brief Proximal tibia or distal femur in the knee frame of KneeAnatomy.h:
 * port 0 the visual surface, port 1 the reduced collision surface (thesis
 * table 6-2, setting 2 and 3: about 63 and 59 vertices). Bones are rigid.
 */
#ifndef vtkKneeBoneSource_h
#define vtkKneeBoneSource_h

#include "ThinTissueVTKModelsModule.h"
#include "vtkPolyDataAlgorithm.h"

class THINTISSUEVTKMODELS_EXPORT vtkKneeBoneSource : public vtkPolyDataAlgorithm
{
public:
  static vtkKneeBoneSource* New();
  vtkTypeMacro(vtkKneeBoneSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Bone
  {
    Tibia = 0,
    Femur = 1
  };

  ///@{
  /// Which bone (Bone).
  vtkSetClampMacro(Bone, int, Tibia, Femur);
  vtkGetMacro(Bone, int);
  ///@}

  ///@{
  /// Distance between tibial and femoral cartilage, millimetres (places
  /// the femur).
  vtkSetMacro(JointGap, double);
  vtkGetMacro(JointGap, double);
  ///@}

protected:
  vtkKneeBoneSource();
  ~vtkKneeBoneSource() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Bone = Tibia;
  double JointGap;

private:
  vtkKneeBoneSource(const vtkKneeBoneSource&) = delete;
  void operator=(const vtkKneeBoneSource&) = delete;
};

#endif
