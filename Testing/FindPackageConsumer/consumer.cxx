// Uses a kernel class and a VTK-layer class of the installed ThinTissue.
#include "MeshPrimitives.h"
#include "MeshValidation.h"
#include "vtkThinSlabSource.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <iostream>

int main()
{
  const thintissue::TriangleMesh slab = thintissue::makeSlabSurface({});
  const thintissue::MeshValidationReport report = thintissue::validateTriangleMesh(slab);
  vtkNew<vtkThinSlabSource> source;
  source->Update();
  const bool ok =
    report.isClosedOutwardSingleSurface() &&
    source->GetOutput()->GetNumberOfPolys() == static_cast<vtkIdType>(slab.triangleCount());
  std::cout << "consumer: " << slab.triangleCount() << " triangles, "
            << (ok ? "package works" : "MISMATCH") << "\n";
  return ok ? 0 : 1;
}
