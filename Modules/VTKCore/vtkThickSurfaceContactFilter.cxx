#include "vtkThickSurfaceContactFilter.h"

#include "SurfaceContacts.h"
#include "ThinTissueError.h"
#include "vtkThinTissueConversion.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(vtkThickSurfaceContactFilter);

namespace
{
std::vector<double> radiiOf(const thintissue::TriangleMesh& mesh)
{
  return mesh.pointAttributes.has("Radius") ? mesh.pointAttributes.get("Radius").values
                                            : std::vector<double>();
}
} // namespace

vtkThickSurfaceContactFilter::vtkThickSurfaceContactFilter()
{
  this->SetNumberOfInputPorts(2);
}

int vtkThickSurfaceContactFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputs,
  vtkInformationVector* outputs)
{
  vtkPolyData* inputA = vtkPolyData::GetData(inputs[0], 0);
  vtkPolyData* inputB = vtkPolyData::GetData(inputs[1], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputs, 0);
  this->NumberOfContacts = 0;
  if (!inputA || !inputB)
  {
    vtkErrorMacro("two surfaces are needed (input ports 0 and 1)");
    return 0;
  }
  try
  {
    const thintissue::TriangleMesh a = thintissue::fromPolyData(inputA, "surface A");
    const thintissue::TriangleMesh b = thintissue::fromPolyData(inputB, "surface B");
    const auto contacts =
      thintissue::findSurfaceContacts(a, radiiOf(a), b, radiiOf(b), this->ContactDistance);
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkCellArray> vertices;
    vtkNew<vtkDoubleArray> normals;
    normals->SetName("Normal");
    normals->SetNumberOfComponents(3);
    vtkNew<vtkDoubleArray> depths;
    depths->SetName("Depth");
    vtkNew<vtkIntArray> sides;
    sides->SetName("Side");
    vtkNew<vtkIntArray> fromA;
    fromA->SetName("VertexOfA");
    for (const auto& contact : contacts)
    {
      const vtkIdType id = points->InsertNextPoint(contact.point.data());
      vertices->InsertNextCell(1, &id);
      normals->InsertNextTuple(contact.normal.data());
      depths->InsertNextValue(contact.depth);
      sides->InsertNextValue(contact.side);
      fromA->InsertNextValue(contact.vertexOfA ? 1 : 0);
    }
    output->SetPoints(points);
    output->SetVerts(vertices);
    output->GetPointData()->AddArray(normals);
    output->GetPointData()->AddArray(depths);
    output->GetPointData()->AddArray(sides);
    output->GetPointData()->AddArray(fromA);
    this->NumberOfContacts = static_cast<vtkIdType>(contacts.size());
  }
  catch (const thintissue::Error& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  return 1;
}

void vtkThickSurfaceContactFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ContactDistance: " << this->ContactDistance << "\n"
     << indent << "NumberOfContacts: " << this->NumberOfContacts << "\n";
}
