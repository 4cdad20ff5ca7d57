#include "VertexAttributes.h"

#include "ThinTissueError.h"

namespace thintissue
{

void VertexAttributes::set(const std::string& name, int components, std::vector<double> values)
{
  if (components < 1 || values.size() % static_cast<std::size_t>(components) != 0)
  {
    throw InvalidInputError("attribute '" + name + "': " + std::to_string(values.size()) +
                            " values do not form elements of " + std::to_string(components) +
                            " components");
  }
  AttributeArray& array = Arrays[name];
  array.components = components;
  array.values = std::move(values);
}

bool VertexAttributes::has(const std::string& name) const
{
  return Arrays.count(name) != 0;
}

const AttributeArray& VertexAttributes::get(const std::string& name) const
{
  auto it = Arrays.find(name);
  if (it == Arrays.end())
  {
    throw InvalidInputError("no attribute named '" + name + "'");
  }
  return it->second;
}

AttributeArray& VertexAttributes::get(const std::string& name)
{
  const auto& self = *this;
  return const_cast<AttributeArray&>(self.get(name));
}

void VertexAttributes::remove(const std::string& name)
{
  Arrays.erase(name);
}

std::vector<std::string> VertexAttributes::names() const
{
  std::vector<std::string> result;
  result.reserve(Arrays.size());
  for (const auto& entry : Arrays)
  {
    result.push_back(entry.first);
  }
  return result;
}

void VertexAttributes::checkElementCount(std::size_t elementCount, const std::string& context) const
{
  for (const auto& [name, array] : Arrays)
  {
    if (array.elementCount() != elementCount || array.values.size() % array.components != 0)
    {
      throw InvalidInputError(context + ": attribute '" + name + "' has " +
                              std::to_string(array.elementCount()) + " elements, expected " +
                              std::to_string(elementCount));
    }
  }
}

void VertexAttributes::appendCopyOf(std::size_t source)
{
  for (auto& entry : Arrays)
  {
    AttributeArray& array = entry.second;
    const std::size_t begin = source * array.components;
    for (int c = 0; c < array.components; ++c)
    {
      array.values.push_back(array.values[begin + c]);
    }
  }
}

} // namespace thintissue
