// A thin solid described as the image of the unit parameter box under a
// smooth map: s runs along the tissue, u across it, w through its thickness.
//
// Every procedural tissue (sheet, meniscus, cartilage, ligaments) is one of
// these, so that its three meshes (thesis fig. 5-1) come from one description
// and agree by construction: the visual surface is the boundary of a fine
// grid of parameter cells, the collision mesh is the mid-surface w = 1/2 with
// radius = half the local thickness, and the hexahedra are a coarse grid of
// the same cells pushed outward by a margin so that they cover the tissue.
//
// Tears are cracks: rectangles on a parameter plane across which cells are
// not connected. Grid lines of every resolution are placed on the cracks, so
// a tear is in all three meshes; a node touched by a crack is duplicated once
// per group of cells still connected around it (the node-level branch
// analysis of thesis 5.3.3), and the two lips are opened by a gap that tapers
// to zero at the tear fronts.
#ifndef ParametricSolid_h
#define ParametricSolid_h

#include "HexahedralMesh.h"
#include "ThinTissueModelsModule.h"
#include "TriangleMesh.h"

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace thintissue
{

/// Parameter point (s, u, w) of the unit box.
using ParameterPoint = Eigen::Vector3d;

/// Maps a parameter point to model space. Must be right-handed
/// ((dX/ds x dX/du) . dX/dw > 0) and injective on the box.
using ParametricMap = std::function<Vector3(const ParameterPoint&)>;

/// A tear: the part of the plane {parameter[normalAxis] == position} with the
/// other two parameters inside `ranges` (in increasing axis order, e.g. for
/// normalAxis 1 the s range then the w range). An end of a range lying on
/// the box boundary is a mouth (the gap is widest there); an inner end is a
/// tear front, where the gap closes (also where two cracks meet: the corner
/// of a flap stays closed, as in real tissue).
struct ParametricCrack
{
  int normalAxis = 1;
  double position = 0.5;
  std::array<std::array<double, 2>, 2> ranges{ { { 0.0, 1.0 }, { 0.0, 1.0 } } };
  /// Largest width of the gap between the two lips, in model units.
  double opening = 0.0;
  /// How far (in parameter units along normalAxis) the opening displaces
  /// the material beside the lips, fading linearly to zero; keeps the cells
  /// next to the lips from being crushed.
  double influence = 0.05;
  /// Share of the opening taken by the lip on the + side (the rest by the
  /// - side): 1/2 for a symmetric tear; 1 when the - side rests on
  /// something (a cleaved meniscus's lower leaf lies on the tibia).
  double positiveShare = 0.5;
};

/// Cells per parameter axis.
struct ParametricResolution
{
  int along = 1;
  int across = 1;
  int through = 1;
  int operator[](int axis) const { return axis == 0 ? along : axis == 1 ? across : through; }
};

/// Parameter point of the closed box and whether a node is fixed there.
using FixedNodePredicate = std::function<bool(const ParameterPoint&)>;

class THINTISSUEMODELS_EXPORT ParametricSolid
{
public:
  /// `name` is used in error messages.
  ParametricSolid(std::string name, ParametricMap map);

  /// Adds a tear. Throws InvalidInputError if it lies outside the box, its
  /// plane is on the box boundary, a range is empty, or the opening is
  /// negative.
  void addCrack(const ParametricCrack& crack);
  const std::vector<ParametricCrack>& cracks() const { return Cracks; }
  const std::string& name() const { return Name; }

  /// The map, without crack openings.
  Vector3 point(const ParameterPoint& p) const { return Map(p); }
  /// Unit derivative direction of the map along `axis` at p.
  Vector3 direction(const ParameterPoint& p, int axis) const;
  /// Distance between the lower and upper surface at (s, u).
  double thickness(double s, double u) const;

  /// `cells` + 1 increasing parameter values from 0 to 1 that include every
  /// crack plane and crack range end on `axis`, uniform between them.
  /// Throws InvalidInputError if `cells` is too small to hold them.
  std::vector<double> gridLines(int axis, int cells) const;

  /// Closed, outward, welded surface of the cell grid (cracks become pairs
  /// of lips), with vertex normals and texture coordinates in model units
  /// divided by `textureScale`.
  TriangleMesh boundarySurface(const ParametricResolution& resolution, double textureScale) const;

  /// Mid-surface triangles of an `along` x `across` grid with the point
  /// attribute "Radius" = half the local thickness. Where a crack runs
  /// through the mid-surface (horizontal cleavage) each leaf gets its own
  /// mid-surface and radius.
  TriangleMesh midSurface(int along, int across) const;

  /// Hexahedra of the cell grid, boundary nodes pushed outward by `margin`
  /// (model units, per axis) so that the curved solid lies inside the
  /// trilinear cells; fixed where `isFixed` says so (may be empty).
  HexahedralMesh hexahedra(const ParametricResolution& resolution,
    const std::array<double, 3>& margin,
    const FixedNodePredicate& isFixed) const;

  /// Model-space point of parameter p on the lip of the piece that lies on
  /// `sides[c]` (+1 or -1) of crack c (0 where it does not matter).
  Vector3 openedPoint(const ParameterPoint& p, const std::vector<int>& sides) const;

private:
  std::string Name;
  ParametricMap Map;
  std::vector<ParametricCrack> Cracks;
};

} // namespace thintissue

#endif
