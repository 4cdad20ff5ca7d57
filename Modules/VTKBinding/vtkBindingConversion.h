// A visual-collision binding as vtkPolyData (not wrapped): the re-meshed
// visual surface with the per-vertex binding arrays BindingKind,
// BindingElement, BindingSide, BindingParameters and the per-triangle
// arrays CollisionTriangle, CollisionSide. Shared by
// vtkVisualCollisionBindingFilter and vtkTissueBundleReader.
#ifndef vtkBindingConversion_h
#define vtkBindingConversion_h

#include "ThinTissueVTKBindingModule.h"
#include "VisualCollisionBinding.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace thintissue
{
THINTISSUEVTKBINDING_EXPORT vtkSmartPointer<vtkPolyData> boundVisualPolyData(
  const VisualCollisionBinding& binding);
} // namespace thintissue

#endif
