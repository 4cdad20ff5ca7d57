/**
 * @class vtkThinSheetSource
 * @brief The thin sheet of the thesis's cutting experiments (5.4.2): visual
 * surface, collision mid-surface with radii and hexahedra (see
 * vtkTissueModelSource for the output ports).
 *
 * Defaults: 100 x 100 x 2 mm, visual model 2 of table 5-3, collision model 1
 * of table 5-5, 9 x 9 x 1 hexahedra fixed along the left and right edges.
 */
#ifndef vtkThinSheetSource_h
#define vtkThinSheetSource_h

#include "ThinTissueVTKModelsModule.h"
#include "vtkTissueModelSource.h"

class THINTISSUEVTKMODELS_EXPORT vtkThinSheetSource : public vtkTissueModelSource
{
public:
  static vtkThinSheetSource* New();
  vtkTypeMacro(vtkThinSheetSource, vtkTissueModelSource);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Attachment
  {
    NoAttachment = 0,
    LeftEdge = 1,
    LeftAndRightEdges = 2,
    AllEdges = 3
  };

  ///@{
  /// Size in millimetres (positive; thickness smaller than width and depth).
  vtkSetMacro(Width, double);
  vtkGetMacro(Width, double);
  vtkSetMacro(Depth, double);
  vtkGetMacro(Depth, double);
  vtkSetMacro(Thickness, double);
  vtkGetMacro(Thickness, double);
  ///@}

  ///@{
  /// Visual surface cells along x, y, z.
  vtkSetVector3Macro(VisualCells, int);
  vtkGetVector3Macro(VisualCells, int);
  ///@}

  ///@{
  /// Collision lattice: triangle edges along x and rows along y.
  vtkSetMacro(CollisionColumns, int);
  vtkGetMacro(CollisionColumns, int);
  vtkSetMacro(CollisionRows, int);
  vtkGetMacro(CollisionRows, int);
  ///@}

  ///@{
  /// Hexahedra along x, y, z.
  vtkSetVector3Macro(Hexahedra, int);
  vtkGetVector3Macro(Hexahedra, int);
  ///@}

  ///@{
  /// Which edges are fixed (Attachment).
  vtkSetClampMacro(Attachment, int, NoAttachment, AllEdges);
  vtkGetMacro(Attachment, int);
  ///@}

  ///@{
  /// Texture repeat length in millimetres.
  vtkSetMacro(TextureScale, double);
  vtkGetMacro(TextureScale, double);
  ///@}

  /// Visual resolution of thesis table 5-3 model 1-4, or 5 for 1M triangles.
  void SetThesisVisualModel(int model);
  /// Collision resolution of thesis table 5-5 model 1-3.
  void SetThesisCollisionModel(int model);

protected:
  vtkThinSheetSource();
  ~vtkThinSheetSource() override = default;

  thintissue::TissueModel BuildTissueModel() override;

  double Width;
  double Depth;
  double Thickness;
  int VisualCells[3];
  int CollisionColumns;
  int CollisionRows;
  int Hexahedra[3];
  int Attachment;
  double TextureScale;

private:
  vtkThinSheetSource(const vtkThinSheetSource&) = delete;
  void operator=(const vtkThinSheetSource&) = delete;
};

#endif
