// Union-find (disjoint sets) over a small index range, with path halving.
// The root of a set is its lowest index, so that groups come out in a
// deterministic order. Used by the branch analyses of tears and cuts.
#ifndef UnionFind_h
#define UnionFind_h

#include <algorithm>
#include <numeric>
#include <vector>

namespace thintissue
{

class UnionFind
{
public:
  UnionFind() = default;
  explicit UnionFind(std::size_t count) { reset(count); }
  /// Every index of [0, count) in a set of its own; keeps the storage, so a
  /// loop over many small ranges allocates once.
  void reset(std::size_t count)
  {
    Parent.resize(count);
    std::iota(Parent.begin(), Parent.end(), 0);
  }
  int find(int i)
  {
    while (Parent[i] != i)
    {
      Parent[i] = Parent[Parent[i]];
      i = Parent[i];
    }
    return i;
  }
  /// Joins the sets of a and b; whether they were apart.
  bool unite(int a, int b)
  {
    a = find(a);
    b = find(b);
    if (a == b)
      return false;
    Parent[std::max(a, b)] = std::min(a, b);
    return true;
  }

private:
  std::vector<int> Parent;
};

} // namespace thintissue

#endif
