// The sides of a collision mid-surface and the halves of the visual surface
// they face (5.2). On the thesis's manifold meshes every triangle has a
// positive and a negative side, and the rim paths split the closed visual
// surface into a positive and a negative half. A horizontal cleavage adds
// edges of three triangles: the uncut body and the two leaves the cleft
// separates (a junction). Around such an edge the three triangles bound
// three wedges: the top (the body's and the upper leaf's positive sides),
// the bottom (both negative sides) and the cleft's crease (the upper leaf's
// negative side and the lower leaf's positive side). The crease's side
// belongs to a third half of the visual surface, the cleft's walls.
//
// Side classes are joined through the wedges of the inner edges; the
// border edges' wedges (a triangle's own two sides) are the rim between
// halves. A vertex inside a junction sees three classes (top, bottom,
// crease) and needs three paired visual vertices, one per class.
#ifndef CollisionSides_h
#define CollisionSides_h

#include "ThinTissueBindingModule.h"
#include "TriangleMesh.h"
#include "TriangleMeshAdjacency.h"

#include <array>
#include <cstdint>
#include <vector>

namespace thintissue
{

/// The half a triangle side faces: the positive one, the negative one, or
/// a cleft's (between two leaves of a junction).
enum class SurfaceHalf : std::int8_t
{
  Cleft = 0,
  Positive = 1,
  Negative = -1
};

/// Side slot of a side (+1 -> 0, -1 -> 1).
inline int sideSlot(int side)
{
  return side < 0 ? 1 : 0;
}

struct THINTISSUEBINDING_EXPORT CollisionSides
{
  /// Per triangle, per side slot (0: positive side, 1: negative side).
  std::vector<std::array<SurfaceHalf, 2>> halves;
  /// Per vertex: three side classes meet there (a vertex inside a
  /// junction: top, bottom and crease).
  std::vector<char> junctionVertex;
  /// Per vertex: on a border edge.
  std::vector<char> borderVertex;

  bool hasJunctions() const;
  /// Side label of the binding path that bounds side `side` of triangle t
  /// along an edge of `edgeTriangleCount` triangles: 0 on a border edge
  /// (the rim path) and on a junction's crease, else `side`.
  int pathSide(int t, int side, int edgeTriangleCount) const
  {
    if (edgeTriangleCount == 1)
    {
      return 0;
    }
    if (edgeTriangleCount == 3 && halves[t][sideSlot(side)] == SurfaceHalf::Cleft)
    {
      return 0;
    }
    return side;
  }
  /// Which of a vertex's paired visual vertices side `side` of triangle t
  /// sees at corner vertex v: 0 (positive), 1 (negative) or 2 (the
  /// crease's, at a junction vertex).
  int pairedSlot(int v, int t, int side) const
  {
    if (junctionVertex[v] && halves[t][sideSlot(side)] == SurfaceHalf::Cleft)
    {
      return 2;
    }
    return sideSlot(side);
  }
};

/// The side classes of `collision`: edges of one, two or three triangles;
/// those of two consistently oriented, those of three a junction (one body
/// triangle and two leaves on either side of a cleft, all three oriented
/// alike). Throws InvalidInputError naming the mesh and the first edge or
/// vertex that is none of these (more triangles at an edge, inconsistent
/// normals, fans touching at a vertex).
THINTISSUEBINDING_EXPORT CollisionSides analyseCollisionSides(const TriangleMesh& collision);
/// The same with the mesh's adjacency already built, and for a mesh being
/// cut: `cutEdges` were cut along but not opened yet (neither end was
/// split), so their triangles meet there as at a border. (Two leaves whose
/// body was cut off along their junction edge meet there, oriented alike.)
THINTISSUEBINDING_EXPORT CollisionSides analyseCollisionSides(const TriangleMesh& collision,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<std::array<int, 2>>& cutEdges = {});

} // namespace thintissue

#endif
