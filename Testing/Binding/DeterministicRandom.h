// Deterministic pseudo-random numbers for the binding tests: the same
// sequence on every platform and compiler (64-bit LCG), so that jittered
// meshes and sampled paths are reproducible.
#ifndef DeterministicRandom_h
#define DeterministicRandom_h

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

} // namespace thintissue::testing

#endif
