// Repair of a visual surface on request (issue 14): the defects that make
// preparation refuse a mesh (MeshValidation.h) are fixed with CGAL's Polygon
// Mesh Processing, and every change is reported with the place it was made,
// so that a user can see what happened to their mesh.
//
// What is repaired, in this order: vertices at the same position are merged;
// triangles with a repeated vertex and duplicate triangles are removed;
// non-manifold vertices (and edges) are split; zero-area triangles are
// removed; holes whose border is short relative to the mesh are filled;
// triangles are oriented consistently, and outward when the surface is
// closed. Openings larger than the limit are reported and left open: they
// are part of the shape (a sheet's rim), not damage.
//
// Vertices that stay keep their position and attributes (normals, point
// arrays, texture coordinates); vertices that hole filling adds take the
// attributes of the nearest border vertex and an area-weighted normal.
#ifndef MeshRepair_h
#define MeshRepair_h

#include "ThinTissueBindingModule.h"
#include "TriangleMesh.h"

#include <string>
#include <vector>

namespace thintissue
{

struct MeshRepairSettings
{
  /// A hole is filled when its border is at most this fraction of the
  /// mesh's bounding-box diagonal; longer borders are openings of the shape.
  double maximumHoleFraction = 0.25;
  /// ... and has at most this many border edges (the hole triangulation
  /// costs the cube of the border's edge count).
  int maximumHoleEdges = 300;
  /// Add vertices inside filled holes so that the new triangles are about as
  /// large as their neighbours; false: new triangles join border vertices only.
  bool refineFilledHoles = true;
  /// Triangles are always made consistent within each piece. true: a
  /// closed surface is then turned to bound its volume (outward normals);
  /// false, and for open surfaces: each piece takes the orientation most of
  /// its input triangles had.
  bool orientOutward = true;
  /// Places listed in `changes` for each kind of change; further ones are
  /// counted only.
  int maximumListedPerKind = 10;
};

/// What a repair changed. Counts are of the input mesh's elements, places
/// in `changes` name input vertex and triangle indices and positions.
struct THINTISSUEBINDING_EXPORT MeshRepairReport
{
  std::string meshName;
  int mergedCoincidentVertices = 0;
  int removedUnreferencedVertices = 0;
  int removedDegenerateTriangles = 0;
  /// Vertices removed with a degenerate triangle (an edge collapsed).
  int collapsedVertices = 0;
  int removedDuplicateTriangles = 0;
  /// Non-manifold vertices found and the vertices added to split them.
  int nonManifoldVertices = 0;
  int splitNonManifoldVertices = 0;
  /// Edges with more than two triangles, whose triangles were separated.
  int nonManifoldEdges = 0;
  int filledHoles = 0;
  int filledHoleBorderEdges = 0;
  int addedTriangles = 0;
  int addedVertices = 0;
  /// Borders left open (too long to be holes) and their edges.
  int openBorders = 0;
  int openBorderEdges = 0;
  /// Holes the triangulation could not fill.
  int unfilledHoles = 0;
  int flippedTriangles = 0;
  /// Input normals that pointed against the repaired surface, reversed.
  int reversedNormals = 0;
  /// One line per change (or per kind beyond maximumListedPerKind), each
  /// naming where: vertex or triangle indices of the input and a position.
  std::vector<std::string> changes;

  /// True when the mesh was changed at all.
  bool changed() const;
  /// Counts in one paragraph, then the changes one per line.
  std::string summary() const;
  /// The counts and changes as a JSON object (for bundle metadata).
  std::string toJson() const;
};

/// The repaired mesh (same name). A mesh without defects comes back equal
/// to the input with an empty report. Throws InvalidInputError naming the
/// mesh on indices out of range or non-finite coordinates
/// (TriangleMesh::checkConsistency).
THINTISSUEBINDING_EXPORT TriangleMesh repairTriangleMesh(const TriangleMesh& mesh,
  const MeshRepairSettings& settings = {},
  MeshRepairReport* report = nullptr);

/// A surface with openings cut into it closed again: every hole filled,
/// whatever its length, and only the largest piece kept (islands left
/// between neighbouring openings go); named as `mesh`.
THINTISSUEBINDING_EXPORT TriangleMesh closeOpeningsKeepLargest(const TriangleMesh& mesh);

} // namespace thintissue

#endif
