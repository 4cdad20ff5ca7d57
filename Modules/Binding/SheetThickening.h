// A thickness for tissues segmented as one surface (issue 14). A segmented
// cartilage often comes as a single open sheet (its articular surface, no
// thickness: ../shared/data/knee-smith2019), which the preparation, made
// for closed thin surfaces (a collision mid-surface between two facing
// sides), refuses. Thickening turns each open piece into the closed thin
// slab it stands for: the sheet is taken as the slab's mid-surface, its
// vertices offset by half the thickness both ways along their normals, and
// the two layers joined along every open border by a rim strip. Closed
// pieces are left as they are.
#ifndef SheetThickening_h
#define SheetThickening_h

#include "ThinTissueBindingModule.h"
#include "TriangleMesh.h"

#include <cstddef>
#include <string>

namespace thintissue
{

struct THINTISSUEBINDING_EXPORT SheetThickeningReport
{
  double thickness = 0.0; ///< in the mesh's units
  int thickenedPieces = 0;
  int closedPieces = 0; ///< already closed, left as they were
  int borderLoops = 0;  ///< open borders closed by a rim strip
  std::size_t addedVertices = 0;
  std::size_t addedTriangles = 0;

  /// One line for the console, thickness given in `units` (e.g. "mm").
  std::string summary(const std::string& units) const;
  /// The same as a JSON object (bundle metadata).
  std::string toJson() const;
};

/// `mesh` with every open piece given the thickness `thickness` (mesh
/// units): per vertex of an open piece, p +- n thickness / 2, n its unit
/// normal (angle-weighted over its triangles); the upper layer keeps the
/// triangles (indices, texture corners), the lower one has them reversed,
/// and each border edge gets a quad of two triangles between the layers
/// (texture corners of its upper vertices). Normals are recomputed; point
/// attributes are copied to the lower layer. The result is oriented
/// outward. Throws InvalidInputError naming the mesh when the thickness is
/// not positive and finite, an edge has more than two triangles, a piece
/// is not consistently oriented (--repair orients it), a vertex has no
/// normal (its triangles cancel out), or a layer would fold (a triangle
/// turned over: the thickness exceeds about twice the surface's radius of
/// curvature there).
THINTISSUEBINDING_EXPORT TriangleMesh thickenOpenSheets(const TriangleMesh& mesh,
  double thickness,
  SheetThickeningReport* report = nullptr);

} // namespace thintissue

#endif
