// Shared by the cutting image tests: the cut visual surface coloured by
// material (tissue, cut surface) and meshes drawn as the thesis's figures
// draw them.
#ifndef CutSceneHelpers_h
#define CutSceneHelpers_h

#include "TissueCutter.h"
#include "vtkThinTissueConversion.h"

#include <vtkActor.h>
#include <vtkCellData.h>
#include <vtkDataSetMapper.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include <array>

namespace thintissue::testing
{

/// The cutter's visual surface at `positions` (its rest positions if
/// empty), tissue in `tissue`, cut surface in `cut`, normals recomputed.
inline vtkSmartPointer<vtkPolyData> cutVisualPolyData(const TissueCutter& cutter,
  const std::vector<Vector3>& positions,
  const std::array<unsigned char, 3>& tissue,
  const std::array<unsigned char, 3>& cut)
{
  TriangleMesh mesh = cutter.visual().mesh();
  if (!positions.empty())
    mesh.positions = positions;
  mesh.computeVertexNormals();
  mesh.textureCoordinates.clear();
  mesh.textureCorners.clear();
  auto polyData = toPolyData(mesh);
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("MaterialColour");
  colours->SetNumberOfComponents(3);
  const auto& materials = cutter.visual().triangleMaterials();
  colours->SetNumberOfTuples(static_cast<vtkIdType>(materials.size()));
  for (std::size_t t = 0; t < materials.size(); ++t)
    colours->SetTypedTuple(static_cast<vtkIdType>(t),
      (materials[t] == VisualMaterial::CutSurface ? cut : tissue).data());
  polyData->GetCellData()->AddArray(colours);
  return polyData;
}

inline vtkSmartPointer<vtkActor> materialActor(vtkPolyData* surface, bool edges)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(surface);
  mapper->SetScalarModeToUseCellFieldData();
  mapper->SelectColorArray("MaterialColour");
  mapper->SetColorModeToDirectScalars();
  mapper->ScalarVisibilityOn();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetAmbient(0.2);
  actor->GetProperty()->SetDiffuse(0.8);
  if (edges)
  {
    actor->GetProperty()->EdgeVisibilityOn();
    actor->GetProperty()->SetEdgeColor(0.35, 0.2, 0.2);
  }
  return actor;
}

/// A mesh as lines of one colour.
inline vtkSmartPointer<vtkActor> wireActor(vtkDataSet* mesh,
  const std::array<double, 3>& colour,
  double width)
{
  vtkNew<vtkDataSetMapper> mapper;
  mapper->SetInputData(mesh);
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetRepresentationToWireframe();
  actor->GetProperty()->SetColor(colour[0], colour[1], colour[2]);
  actor->GetProperty()->SetLineWidth(width);
  actor->GetProperty()->LightingOff();
  return actor;
}

} // namespace thintissue::testing

#endif
