#include "vtkBindingConversion.h"

#include "ThinTissueError.h"
#include "vtkThinTissueConversion.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <algorithm>
#include <map>

namespace thintissue
{

namespace
{

vtkDataArray* requiredArray(vtkDataSetAttributes* data,
  const char* name,
  vtkIdType tuples,
  int components,
  const std::string& label)
{
  vtkDataArray* array = data->GetArray(name);
  if (array == nullptr || array->GetNumberOfTuples() != tuples ||
      array->GetNumberOfComponents() != components)
  {
    throw InvalidInputError(label + " has no " + std::to_string(components) + "-component array '" +
                            name + "' with one tuple per " +
                            (data->IsA("vtkPointData") ? "point" : "cell") +
                            " (bind it with vtkVisualCollisionBindingFilter first)");
  }
  return array;
}

/// Binding kind, element, side and parameters per visual vertex, checked
/// against the collision mesh.
void readVertexBindings(vtkPolyData* visual,
  const std::string& label,
  VisualCollisionBinding& binding)
{
  const vtkIdType points = visual->GetNumberOfPoints();
  vtkPointData* pointData = visual->GetPointData();
  vtkDataArray* kinds = requiredArray(pointData, "BindingKind", points, 1, label);
  vtkDataArray* elements = requiredArray(pointData, "BindingElement", points, 1, label);
  vtkDataArray* sides = requiredArray(pointData, "BindingSide", points, 1, label);
  vtkDataArray* parameters = requiredArray(pointData, "BindingParameters", points, 3, label);
  binding.vertices.resize(static_cast<std::size_t>(points));
  const std::size_t counts[3] = { binding.collisionPositions.size(),
    binding.collisionEdges.size(),
    binding.collisionTriangles.size() };
  for (vtkIdType v = 0; v < points; ++v)
  {
    VisualVertexBinding& b = binding.vertices[static_cast<std::size_t>(v)];
    const int kind = static_cast<int>(kinds->GetComponent(v, 0));
    b.element = static_cast<int>(elements->GetComponent(v, 0));
    b.side = static_cast<int>(sides->GetComponent(v, 0));
    parameters->GetTuple(v, b.parameters.data());
    if (kind < 0 || kind > 2 || b.element < 0 ||
        static_cast<std::size_t>(b.element) >= counts[kind] || b.side < -1 || b.side > 1)
    {
      throw InvalidInputError(label + ": vertex " + std::to_string(v) +
                              " is bound to a collision element that does not exist");
    }
    b.kind = static_cast<BindingKind>(kind);
  }
}

/// Paired vertices and paths, from the vertex bindings: the visual vertices
/// bound to an edge and side, ordered by their parameter, between the
/// visual vertices of the edge's ends. A junction vertex's visual vertex on
/// the cleft's crease is the one bound to it with side 0.
void rebuildPaths(const std::string& label,
  const TriangleMesh& collision,
  VisualCollisionBinding& binding)
{
  const std::size_t n = binding.collisionPositions.size();
  binding.collisionSides = analyseCollisionSides(collision);
  binding.pairedVisualVertices.assign(n, { { -1, -1 } });
  binding.creaseVisualVertices.assign(n, -1);
  std::map<std::pair<int, int>, std::vector<std::pair<double, int>>> onEdge;
  for (std::size_t v = 0; v < binding.vertices.size(); ++v)
  {
    const VisualVertexBinding& b = binding.vertices[v];
    const auto element = static_cast<std::size_t>(b.element);
    if (b.kind == BindingKind::CollisionVertex && b.side == 0 &&
        binding.collisionSides.junctionVertex[element])
      binding.creaseVisualVertices[element] = static_cast<int>(v);
    else if (b.kind == BindingKind::CollisionVertex)
    {
      auto& pair = binding.pairedVisualVertices[element];
      if (b.side >= 0)
        pair[0] = static_cast<int>(v);
      if (b.side <= 0)
        pair[1] = static_cast<int>(v);
    }
    else if (b.kind == BindingKind::CollisionEdge)
      onEdge[{ b.element, b.side }].emplace_back(b.parameters[1], static_cast<int>(v));
  }
  for (std::size_t c = 0; c < n; ++c)
  {
    if (binding.pairedVisualVertices[c][0] < 0 || binding.pairedVisualVertices[c][1] < 0 ||
        (binding.collisionSides.junctionVertex[c] && binding.creaseVisualVertices[c] < 0))
      throw InvalidInputError(
        label + ": collision vertex " + std::to_string(c) + " has no visual vertex on each side");
  }
  const auto ends = binding.pathEnds();
  for (std::size_t e = 0; e < binding.collisionEdges.size(); ++e)
  {
    for (int side : { 1, -1, 0 })
    {
      const auto& [source, target] = ends[e][side + 1];
      if (source < 0)
        continue;
      BindingPath path;
      path.collisionEdge = static_cast<int>(e);
      path.side = side;
      auto inner = onEdge[{ static_cast<int>(e), side }];
      std::sort(inner.begin(), inner.end());
      path.visualVertices.push_back(source);
      for (const auto& [t, v] : inner)
        path.visualVertices.push_back(v);
      path.visualVertices.push_back(target);
      for (std::size_t i = 0; i + 1 < path.visualVertices.size(); ++i)
        path.length += (binding.visual.positions[path.visualVertices[i + 1]] -
                        binding.visual.positions[path.visualVertices[i]])
                         .norm();
      binding.paths.push_back(std::move(path));
    }
  }
}

} // namespace

VisualCollisionBinding bindingFromPolyData(vtkPolyData* visual,
  vtkPolyData* collision,
  const std::string& radiusArrayName)
{
  if (visual == nullptr || collision == nullptr)
    throw InvalidInputError("binding: the bound visual surface and the collision mesh are needed");
  VisualCollisionBinding binding;
  binding.visual = fromPolyData(visual, "bound visual surface");
  for (const char* name : { "BindingKind", "BindingElement", "BindingSide", "BindingParameters" })
    binding.visual.pointAttributes.remove(name);
  const std::string label = "bound visual surface";
  const TriangleMesh mesh = fromPolyData(collision, "collision mesh");
  if (!mesh.pointAttributes.has(radiusArrayName) ||
      mesh.pointAttributes.get(radiusArrayName).components != 1)
  {
    throw InvalidInputError(
      "collision mesh has no one-component point array '" + radiusArrayName + "' (the radii)");
  }
  binding.collisionPositions = mesh.positions;
  binding.collisionTriangles = mesh.triangles;
  binding.collisionRadii = mesh.pointAttributes.get(radiusArrayName).values;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      binding.collisionEdges.push_back(
        { { std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]) } });
  std::sort(binding.collisionEdges.begin(), binding.collisionEdges.end());
  binding.collisionEdges.erase(
    std::unique(binding.collisionEdges.begin(), binding.collisionEdges.end()),
    binding.collisionEdges.end());

  if (static_cast<vtkIdType>(binding.visual.triangleCount()) != visual->GetNumberOfCells())
    throw InvalidInputError(label + " must hold triangles only");
  readVertexBindings(visual, label, binding);
  const vtkIdType cells = visual->GetNumberOfCells();
  vtkDataArray* regions =
    requiredArray(visual->GetCellData(), "CollisionTriangle", cells, 1, label);
  vtkDataArray* sides = requiredArray(visual->GetCellData(), "CollisionSide", cells, 1, label);
  for (vtkIdType t = 0; t < cells; ++t)
  {
    const int region = static_cast<int>(regions->GetComponent(t, 0));
    const int side = static_cast<int>(sides->GetComponent(t, 0));
    if (region < 0 || region >= static_cast<int>(binding.collisionTriangles.size()) ||
        (side != 1 && side != -1))
      throw InvalidInputError(label + ": triangle " + std::to_string(t) + " has no region");
    binding.triangleRegion.push_back(region);
    binding.triangleSide.push_back(static_cast<std::int8_t>(side));
  }
  rebuildPaths(label, mesh, binding);
  return binding;
}

} // namespace thintissue
