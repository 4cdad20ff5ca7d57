#include "vtkTriangleMeshValidationFilter.h"

#include "MeshValidation.h"
#include "vtkThinTissueConversion.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(vtkTriangleMeshValidationFilter);

int vtkTriangleMeshValidationFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->ShallowCopy(input);
  try
  {
    const thintissue::TriangleMesh mesh = thintissue::fromPolyData(input, "input");
    const thintissue::MeshValidationReport report = thintissue::validateTriangleMesh(mesh);
    this->NumberOfNonManifoldEdges = static_cast<vtkIdType>(report.nonManifoldEdges.count);
    this->NumberOfNonManifoldVertices = static_cast<vtkIdType>(report.nonManifoldVertices.count);
    this->NumberOfDegenerateTriangles = static_cast<vtkIdType>(report.degenerateTriangles.count);
    this->NumberOfDuplicateTriangles = static_cast<vtkIdType>(report.duplicateTriangles.count);
    this->NumberOfInconsistentlyOrientedEdges =
      static_cast<vtkIdType>(report.inconsistentlyOrientedEdges.count);
    this->NumberOfBorderEdges = static_cast<vtkIdType>(report.borderEdges.count);
    this->NumberOfUnreferencedVertices = static_cast<vtkIdType>(report.unreferencedVertices.count);
    this->NumberOfConnectedComponents = static_cast<vtkIdType>(report.connectedComponents);
    this->SignedVolume = report.signedVolume;
    this->ClosedManifold = report.isClosedManifold();
    this->ClosedOutwardSingleSurface = report.isClosedOutwardSingleSurface();
    this->Report = report.toString();
  }
  catch (const std::exception& error)
  {
    this->Report = error.what();
    this->ClosedManifold = false;
    this->ClosedOutwardSingleSurface = false;
    vtkErrorMacro(<< error.what());
    return 0;
  }
  return 1;
}

void vtkTriangleMeshValidationFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Report: " << this->Report << "\n";
}
