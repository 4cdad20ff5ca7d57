// The thin sheet of the thesis's cutting experiments (section 5.4.2,
// tables 5-3 to 5-6, fig. 5-19 to 5-22): a rectangular slab with a fine
// visual surface, a near-equilateral collision mid-surface with radii and a
// single layer of hexahedra, fixed along two opposite edges.
#ifndef ThinSheetModel_h
#define ThinSheetModel_h

#include "ThinTissueModelsModule.h"
#include "TissueModel.h"

namespace thintissue
{

/// Which edges of the sheet are attached (fixed hexahedron nodes).
enum class SheetAttachment
{
  None,
  LeftEdge,          ///< x = -width/2
  LeftAndRightEdges, ///< x = -width/2 and x = +width/2
  AllEdges
};

struct ThinSheetParameters
{
  double width = 100.0;   ///< along x, millimetres
  double depth = 100.0;   ///< along y
  double thickness = 2.0; ///< along z; centred on z = 0
  /// Visual surface: cells of the top and bottom grids and of the rims.
  int visualCellsX = 40;
  int visualCellsY = 40;
  int visualCellsZ = 1;
  /// Collision mid-surface: a lattice of near-equilateral triangles with
  /// `collisionColumns` triangle edges along x on even rows and
  /// `collisionRows` rows of triangles along y.
  int collisionColumns = 6;
  int collisionRows = 8;
  /// Hexahedra per side (thesis: 9 x 9 x 1, 200 nodes, 81 hexahedra).
  int hexahedraX = 9;
  int hexahedraY = 9;
  int hexahedraZ = 1;
  SheetAttachment attachment = SheetAttachment::LeftAndRightEdges;
  /// Texture repeats every this many millimetres.
  double textureScale = 25.0;
};

/// Visual resolutions closest to the thesis's sheets (table 5-3), model
/// 1 to 4: 881, 3,425, 13,505 and 53,633 vertices; model 5 is a
/// 1M-triangle sheet beyond the thesis. Sets only the visual cell counts.
THINTISSUEMODELS_EXPORT ThinSheetParameters thesisSheetVisualResolution(int model,
  ThinSheetParameters parameters = {});

/// Collision resolutions closest to table 5-5, model 1 to 3: 65 v / 104 t,
/// 280 v / 500 t, 796 v / 1,500 t. Sets only the collision lattice.
THINTISSUEMODELS_EXPORT ThinSheetParameters thesisSheetCollisionResolution(int model,
  ThinSheetParameters parameters = {});

/// Throws InvalidInputError on non-positive sizes, a thickness not smaller
/// than the width or depth, or resolutions below the workable minimum.
THINTISSUEMODELS_EXPORT TissueModel makeThinSheet(const ThinSheetParameters& parameters);

} // namespace thintissue

#endif
