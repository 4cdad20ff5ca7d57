// Room reserved in a std::vector with its pages touched at once.
//
// A cut appends vertices, triangles, hexahedron copies and embeddings into
// room reserved at load time. Reserved pages are first touched by the
// append, so every cut paid the kernel's page faults (on the shaver's
// bites, a seventh of the cut). Touching them when the room is reserved
// moves that cost to loading.
#ifndef ReservedVector_h
#define ReservedVector_h

#include <vector>

namespace thintissue
{

/// Reserves room for `count` elements and writes every element of the
/// room once (filling it with `fill`, then shrinking back), so the room's
/// pages are mapped before a hot path appends into them.
template <typename T>
void reserveTouched(std::vector<T>& list, std::size_t count, const T& fill = T())
{
  const std::size_t size = list.size();
  list.reserve(count);
  list.resize(list.capacity(), fill);
  list.resize(size);
}

} // namespace thintissue

#endif
