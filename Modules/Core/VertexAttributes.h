// Named per-element data arrays (per vertex of a triangle mesh, per node of a
// hexahedral mesh): radii, fixed-node masks, monitor flags, ...
#ifndef VertexAttributes_h
#define VertexAttributes_h

#include "ThinTissueCoreModule.h"

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace thintissue
{

/// One named array: `components` doubles per element, element-major.
struct AttributeArray
{
  int components = 1;
  std::vector<double> values;

  std::size_t elementCount() const { return components > 0 ? values.size() / components : 0; }
  double* element(std::size_t i) { return values.data() + i * components; }
  const double* element(std::size_t i) const { return values.data() + i * components; }
};

/// A set of named arrays that all describe the same elements.
class THINTISSUECORE_EXPORT VertexAttributes
{
public:
  /// Adds or replaces an array; throws InvalidInputError if `values.size()`
  /// is not a multiple of `components` or `components < 1`.
  void set(const std::string& name, int components, std::vector<double> values);
  bool has(const std::string& name) const;
  /// Throws InvalidInputError if there is no such array.
  const AttributeArray& get(const std::string& name) const;
  AttributeArray& get(const std::string& name);
  void remove(const std::string& name);
  std::vector<std::string> names() const;
  bool empty() const { return Arrays.empty(); }

  /// Throws InvalidInputError naming `context` and the first array whose
  /// element count differs from `elementCount`.
  void checkElementCount(std::size_t elementCount, const std::string& context) const;

  /// Appends one element to every array, copied from element `source`
  /// (used when a vertex is split or duplicated).
  void appendCopyOf(std::size_t source);

private:
  std::map<std::string, AttributeArray> Arrays;
};

} // namespace thintissue

#endif
