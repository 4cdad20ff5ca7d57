// A visual-collision binding as vtkPolyData and back (not wrapped): the
// re-meshed visual surface with the per-vertex binding arrays BindingKind,
// BindingElement, BindingSide, BindingParameters and the per-triangle
// arrays CollisionTriangle, CollisionSide. Shared by
// vtkVisualCollisionBindingFilter, vtkTissueBundleReader and the cutting
// filter.
#ifndef vtkBindingConversion_h
#define vtkBindingConversion_h

#include "ThinTissueVTKBindingModule.h"
#include "VisualCollisionBinding.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstdint>
#include <string>
#include <vector>

namespace thintissue
{
THINTISSUEVTKBINDING_EXPORT vtkSmartPointer<vtkPolyData> boundVisualPolyData(
  const VisualCollisionBinding& binding);

/// The same arrays for any bound surface (e.g. one cut since).
THINTISSUEVTKBINDING_EXPORT vtkSmartPointer<vtkPolyData> boundVisualPolyData(
  const TriangleMesh& visual,
  const std::vector<VisualVertexBinding>& vertices,
  const std::vector<int>& triangleRegion,
  const std::vector<std::int8_t>& triangleSide);

/// The binding back from a bound visual surface (the arrays above) and its
/// collision mid-surface (with the per-point radius array `radiusArrayName`):
/// collision edges, paired vertices and paths are rebuilt from the arrays.
/// Throws InvalidInputError naming the mesh and the problem when an array
/// is missing, has the wrong size, or refers to an element that does not
/// exist, or when a collision vertex has no visual vertex.
THINTISSUEVTKBINDING_EXPORT VisualCollisionBinding bindingFromPolyData(vtkPolyData* visual,
  vtkPolyData* collision,
  const std::string& radiusArrayName = "Radius");
} // namespace thintissue

#endif
