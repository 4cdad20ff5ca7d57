// Simple generated surfaces for demos, tests and benchmarks. The faithful
// tissue models (sheets of thesis tables 5-3 to 5-6, meniscus, knee) live in
// the models module; this is the kernel's minimal closed thin slab.
#ifndef MeshPrimitives_h
#define MeshPrimitives_h

#include "ThinTissueCoreModule.h"
#include "TriangleMesh.h"

namespace thintissue
{

/// A box [-w/2, w/2] x [-d/2, d/2] x [-t/2, t/2] whose faces are regular grids.
struct SlabSurfaceParameters
{
  double width = 10.0;    ///< along x
  double depth = 10.0;    ///< along y
  double thickness = 0.5; ///< along z
  int cellsX = 16;
  int cellsY = 16;
  int cellsZ = 1;
};

/// Closed, outward-oriented, welded triangle surface of a slab, with planar
/// texture coordinates (x / width, y / depth). Triangle count:
/// 4 (cx cy + cx cz + cy cz). Throws InvalidInputError on non-positive sizes
/// or cell counts.
THINTISSUECORE_EXPORT TriangleMesh makeSlabSurface(const SlabSurfaceParameters& parameters);

} // namespace thintissue

#endif
