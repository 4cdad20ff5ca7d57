// Helpers of the binding tests: deterministic pseudo-random numbers (the
// same sequence on every platform and compiler, 64-bit LCG, so that
// jittered meshes and sampled paths are reproducible) and the vertex
// nearest a point.
#ifndef BindingTestHelpers_h
#define BindingTestHelpers_h

#include "TriangleMesh.h"

#include <cstdint>

namespace thintissue::testing
{

class Random
{
public:
  explicit Random(std::uint64_t seed)
    : State(seed)
  {
  }
  std::uint32_t next()
  {
    State = State * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<std::uint32_t>(State >> 33);
  }
  int below(int n) { return static_cast<int>(next() % static_cast<std::uint32_t>(n)); }
  double unit() { return next() / 2147483648.0; }

private:
  std::uint64_t State;
};

/// The mesh vertex nearest `point` (brute force).
inline int vertexAt(const TriangleMesh& mesh, const Vector3& point)
{
  int best = 0;
  for (int v = 1; v < static_cast<int>(mesh.vertexCount()); ++v)
  {
    if ((mesh.positions[v] - point).squaredNorm() < (mesh.positions[best] - point).squaredNorm())
    {
      best = v;
    }
  }
  return best;
}

} // namespace thintissue::testing

#endif
