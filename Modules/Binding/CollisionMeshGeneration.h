// Automatic collision and simulation meshes for a thin visual mesh: the
// thesis built its reduced collision meshes by hand in 3ds Max and names
// their automatic generation as its first future work (7.2).
//
// Collision mid-surface ("reduced triangles with radii", 2.4 / 5.1):
//  1. The thickness axis is the direction of least spread of the surface
//     (principal axes of its area); the object must be thin along it: the
//     largest thickness at most maximumThicknessRatio times the extent
//     across (else "not a thin object", with the measured ratio).
//  2. The outline is the silhouette of the surface seen along that axis
//     (edges between triangles facing up and facing down), its longest
//     loop resampled uniformly; its points move inward until the local half
//     thickness reaches them, so the border spheres touch the rim.
//  3. Inside, a triangular lattice of points; the spacing is found by
//     bisection so that the mesh has the requested vertex count; a
//     constrained Delaunay triangulation (CGAL) of outline and points gives
//     the triangles (2V - B - 2 for B border vertices).
//  4. Each point is lifted to the middle of the surface along the axis (the
//     first and last crossings of the line), radius half the distance.
// The two-sided Hausdorff distance between the visual surface and the thick
// surface of the result (mid-surface swept by its radii) is measured and
// returned. A band whose thickness direction turns along its length (a
// twisted ligament) gets a grid along its centre curve with a local
// thickness direction instead (BandMidSurface.h, MidSurfaceMethod).
//
// Simulation hexahedra: a sparse grid of cubes over the visual surface
// (SparseHexahedralGrid), the cube size found so that the count is the one
// requested, or the nearest reachable.
#ifndef CollisionMeshGeneration_h
#define CollisionMeshGeneration_h

#include "HexahedralMesh.h"
#include "ThinTissueBindingModule.h"
#include "ThinTissueError.h"
#include "TriangleMesh.h"

#include <functional>
#include <string>
#include <vector>

namespace thintissue
{

/// How the mid-surface follows the tissue's thickness.
enum class MidSurfaceMethod
{
  /// Band for a clearly elongated tissue (length over width at least 3,
  /// from the area's principal spreads), one axis otherwise; the other
  /// when the first fails on a tissue elongated at least 2.
  Automatic,
  /// One thickness axis for the whole tissue (sheets, slabs, menisci).
  OneAxis,
  /// A grid along the band's centre curve, the thickness direction local
  /// (ligaments; see BandMidSurface.h).
  Band
};

struct CollisionMeshSettings
{
  /// Vertices of the collision mid-surface (at least 8).
  int vertexCount = 85;
  /// When positive, the triangle count asked for instead: the fewest
  /// vertices whose mesh has at least this many triangles (a disk with B
  /// border vertices has 2V - B - 2).
  int triangleCount = 0;
  /// The largest thickness must be at most this fraction of the extent
  /// across the thickness axis.
  double maximumThicknessRatio = 0.35;
  /// Name of the radius array written on the result.
  std::string radiusArrayName = "Radius";
  MidSurfaceMethod method = MidSurfaceMethod::Automatic;
  /// Holes of the outline beyond the surface's genus (its tunnels) that are
  /// seen through are joined to the kept hole or the outline near them: a
  /// tear's slit seen as two holes where its lips overlap in projection, a
  /// notch whose mouth a flap lying on the body closes. false: filled, as
  /// the holes seen through little are (the collision mesh spans them).
  bool joinSeenThroughHoles = true;
  /// Where the inner lattice lies, in [0, 1): a shift along its rows and
  /// across them by this share of its spacing.
  double latticePhase = 0.0;
};

struct GeneratedCollisionMesh
{
  /// The mid-surface, with a per-vertex radius array.
  TriangleMesh mesh;
  int borderVertexCount = 0;
  /// Holes of the outline joined to another loop (joinSeenThroughHoles).
  int joinedHoles = 0;
  /// The inner lattice's phase (CollisionMeshSettings::latticePhase).
  double latticePhase = 0.0;
  /// The method used (never Automatic) and, for a band, the largest angle
  /// (radians) between its local thickness directions.
  MidSurfaceMethod method = MidSurfaceMethod::OneAxis;
  double thicknessTurn = 0.0;
  /// The thickness axis (a band's: the mean of its local directions).
  Vector3 thicknessAxis = Vector3::UnitZ();
  /// Largest thickness over the extent across the axis.
  double thicknessRatio = 0.0;
  double largestThickness = 0.0;
  /// One-sided distances, largest over samples: visual vertices to the
  /// thick surface, and points of the thick surface (each vertex's sphere
  /// along the normal both ways, triangle centres likewise) to the visual
  /// surface. hausdorffDistance is the larger.
  double visualToThick = 0.0;
  double thickToVisual = 0.0;
  double hausdorffDistance = 0.0;
};

/// Progress: fraction in [0, 1] and stage; return false to abort
/// (GenerationAbortedError).
using GenerationProgress = std::function<bool(double fraction, const char* stage)>;

class THINTISSUEBINDING_EXPORT GenerationAbortedError : public Error
{
public:
  using Error::Error;
};

/// What closeSmallTunnels did.
struct TunnelClosingReport
{
  /// Genus of the surface before and after (holes through it: a tear's gap
  /// is one, a segmentation's tunnels through a thin rim are others).
  int genusBefore = 0;
  int genusAfter = 0;
  /// Tunnels found (small holes of the shadow along the thickness axis)
  /// and closed; one line per tunnel with its place.
  int tunnels = 0;
  int closed = 0;
  std::vector<std::string> changes;
};

/// A closed thin surface with its small tunnels closed: holes through the
/// tissue whose shadow along the thickness axis is at most 8 x 8 cells of
/// a 256th of the extent (a segmentation's holes through a thin, blurred
/// rim; a tear's gap is larger and stays). Each tunnel's walls and the
/// surface around its two mouths are cut out and the two openings filled
/// (repairTriangleMesh), kept only if the genus went down and the surface
/// stays closed and manifold. Rim paths cannot separate the two sides of
/// a surface with such tunnels (the binding refuses it). With
/// `collisionVertexCount` > 0, also the tunnels whose shadow is no larger
/// than one cell of a collision mesh of that many vertices (the shadow's
/// area per vertex) and no longer than two of its spacings: that mesh
/// could not run around them (a lace-like segmentation of a sheet thinner
/// than two slices); a tear's slit is longer and stays. Returns the input
/// unchanged when it has no tunnel.
THINTISSUEBINDING_EXPORT TriangleMesh closeSmallTunnels(const TriangleMesh& visual,
  TunnelClosingReport* report = nullptr,
  int collisionVertexCount = 0);

/// The collision mid-surface of a closed, manifold, thin visual surface.
/// Throws InvalidInputError naming the mesh: open, non-manifold or
/// inconsistently oriented ("must be closed ..."), not thin ("not a thin
/// object: thickness-to-extent ratio R, at most M"), an outline that cannot
/// be found, or a vertex count below 8.
THINTISSUEBINDING_EXPORT GeneratedCollisionMesh makeCollisionMidSurface(const TriangleMesh& visual,
  const CollisionMeshSettings& settings = {},
  const GenerationProgress& progress = {});

/// Sparse grid hexahedra covering the closed surface, as close to
/// `hexahedronCount` cells as the cube sizes allow (bisection on the size;
/// the counts of neighbouring sizes can jump).
THINTISSUEBINDING_EXPORT HexahedralMesh makeSimulationHexahedra(const TriangleMesh& visual,
  int hexahedronCount);

} // namespace thintissue

#endif
