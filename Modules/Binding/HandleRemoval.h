// Small handles of a closed surface found by growing geodesic balls (after
// Guskov and Wood's topological noise removal): a ball whose triangles are
// not a disk (Euler characteristic V - E + F below 1) holds a loop of the
// surface; when two of its border loops open onto the same piece of the
// rest of the surface, that loop does not separate the surface: the ball
// holds a handle (a tunnel through the tissue) and is cut out, the
// openings filled. A ball around a thin strip is an annulus too, but its
// loop separates the surface: it stays. Module-private (closeSmallTunnels).
#ifndef HandleRemoval_h
#define HandleRemoval_h

#include "TriangleMesh.h"

#include <string>
#include <vector>

namespace thintissue
{

/// `mesh` (closed, manifold) with the handles that fit in balls of up to
/// `largestRadius` cut out and filled, the smallest balls first; each
/// closed handle's place appended to `places`. Kept only while the genus
/// goes down and the surface stays closed and in one piece.
TriangleMesh removeSmallHandles(const TriangleMesh& mesh,
  double largestRadius,
  std::vector<std::string>& places);

} // namespace thintissue

#endif
