// Validation of a triangle surface: every defect that breaks binding,
// cutting or simulation, with a count and the first place it occurs.
#ifndef MeshValidation_h
#define MeshValidation_h

#include "ThinTissueCoreModule.h"
#include "TriangleMesh.h"

#include <string>

namespace thintissue
{

/// How often one defect occurs and where it occurs first (empty if never).
struct ValidationFinding
{
  std::size_t count = 0;
  std::string firstLocation;
};

struct THINTISSUECORE_EXPORT MeshValidationReport
{
  std::string meshName;
  std::size_t vertexCount = 0;
  std::size_t triangleCount = 0;
  std::size_t edgeCount = 0;

  /// Edges used by more than two triangles.
  ValidationFinding nonManifoldEdges;
  /// Vertices whose triangle fan is not one connected fan (bow-ties).
  ValidationFinding nonManifoldVertices;
  /// Triangles with a repeated vertex or (near-)zero area.
  ValidationFinding degenerateTriangles;
  /// Triangles with the same three vertices as an earlier one.
  ValidationFinding duplicateTriangles;
  /// Manifold edges that both triangles traverse in the same direction.
  ValidationFinding inconsistentlyOrientedEdges;
  /// Edges with a single triangle (the surface is open there).
  ValidationFinding borderEdges;
  /// Vertices used by no triangle.
  ValidationFinding unreferencedVertices;
  /// Connected pieces of the surface (1 for a single tissue).
  std::size_t connectedComponents = 0;
  /// Signed enclosed volume; meaningful when the surface is closed.
  double signedVolume = 0.0;

  /// Closed, manifold, consistently oriented, no degenerate or duplicate
  /// triangles: what binding (5.2) requires of a visual mesh.
  bool isClosedManifold() const;
  /// Closed manifold, one piece, enclosed volume positive (outward normals).
  bool isClosedOutwardSingleSurface() const;
  /// Multi-line human-readable report.
  std::string toString() const;
};

/// Checks `mesh` (whose indices must be in range; see
/// TriangleMesh::checkConsistency). `degenerateAreaTolerance` is relative to
/// the squared bounding-box diagonal.
THINTISSUECORE_EXPORT MeshValidationReport validateTriangleMesh(const TriangleMesh& mesh,
  double degenerateAreaTolerance = 1e-14);

/// Throws InvalidInputError "<description> must be closed, manifold and
/// consistently oriented: N <problem>, first at <where>" for the first of:
/// non-manifold edges, non-manifold vertices, border edges, inconsistently
/// oriented edges (and, with `rejectDegenerate`, degenerate triangles).
/// Returns the report for further checks. Indices must be in range.
THINTISSUECORE_EXPORT MeshValidationReport requireClosedOrientedManifold(const TriangleMesh& mesh,
  const std::string& description,
  bool rejectDegenerate = false);

} // namespace thintissue

#endif
