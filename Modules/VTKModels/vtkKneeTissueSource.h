/**
 * @class vtkKneeTissueSource
 * @brief The deformable tissues around the meniscus, in the knee frame of
 * KneeAnatomy.h: the medial tibial cartilage (thesis 5.4.4) and the
 * anterior and posterior cruciate ligaments (5.4.3), as the three meshes of
 * vtkTissueModelSource.
 *
 * CollisionSetting picks the collision mesh of the thesis's experiments:
 * cartilage 1 = the visual mesh, 2/3/4 = mid-surfaces with radii of about
 * 1,000 / 500 / 100 triangles (fig. 5-27); ligaments 1 = the visual mesh,
 * 2/3 = closed surfaces of about 2,000 / 500 triangles, 4 = the reduced
 * mid-surface with radii (table 5-7). The closed surfaces (ligament settings
 * 1 to 3, cartilage setting 1) have "Radius" 0.
 */
#ifndef vtkKneeTissueSource_h
#define vtkKneeTissueSource_h

#include "ThinTissueVTKModelsModule.h"
#include "vtkTissueModelSource.h"

class THINTISSUEVTKMODELS_EXPORT vtkKneeTissueSource : public vtkTissueModelSource
{
public:
  static vtkKneeTissueSource* New();
  vtkTypeMacro(vtkKneeTissueSource, vtkTissueModelSource);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Tissue
  {
    TibialCartilage = 0,
    AnteriorCruciateLigament = 1,
    PosteriorCruciateLigament = 2
  };

  ///@{
  /// Which tissue (Tissue).
  vtkSetClampMacro(Tissue, int, TibialCartilage, PosteriorCruciateLigament);
  vtkGetMacro(Tissue, int);
  ///@}

  ///@{
  /// Collision setting 1 to 4 (see the class description).
  vtkSetClampMacro(CollisionSetting, int, 1, 4);
  vtkGetMacro(CollisionSetting, int);
  ///@}

  ///@{
  /// Distance between tibial and femoral cartilage, millimetres.
  vtkSetMacro(JointGap, double);
  vtkGetMacro(JointGap, double);
  ///@}

protected:
  vtkKneeTissueSource();
  ~vtkKneeTissueSource() override = default;

  thintissue::TissueModel BuildTissueModel() override;

  int Tissue = TibialCartilage;
  int CollisionSetting = 4;
  double JointGap;

private:
  vtkKneeTissueSource(const vtkKneeTissueSource&) = delete;
  void operator=(const vtkKneeTissueSource&) = delete;
};

#endif
