#include "vtkAutomaticMonitorPointsFilter.h"

#include "AutomaticMonitorCurves.h"
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

#include <exception>

vtkStandardNewMacro(vtkAutomaticMonitorPointsFilter);

vtkAutomaticMonitorPointsFilter::vtkAutomaticMonitorPointsFilter()
{
  const thintissue::AutomaticMonitorSettings defaults;
  this->ThinFraction = defaults.thinFraction;
  this->UniformTolerance = defaults.uniformTolerance;
  this->CornerAngle = defaults.cornerAngle;
  this->MinimumRunFraction = defaults.minimumRunFraction;
  this->RegionDepth = defaults.regionDepth;
  this->RegionDepthInRadii = defaults.regionDepthInRadii;
}

int vtkAutomaticMonitorPointsFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  try
  {
    const thintissue::TriangleMesh collision =
      thintissue::fromPolyData(input, "collision mid-surface (input 0)");
    if (!collision.pointAttributes.has("Radius"))
    {
      vtkErrorMacro(<< "collision mid-surface (input 0): needs the point array 'Radius'");
      return 0;
    }
    thintissue::AutomaticMonitorSettings settings;
    settings.thinFraction = this->ThinFraction;
    settings.uniformTolerance = this->UniformTolerance;
    settings.cornerAngle = this->CornerAngle;
    settings.minimumRunFraction = this->MinimumRunFraction;
    settings.useNearPoint = this->UseNearPoint;
    settings.nearPoint =
      thintissue::Vector3(this->NearPoint[0], this->NearPoint[1], this->NearPoint[2]);
    settings.regionDepth = this->RegionDepth;
    settings.regionDepthInRadii = this->RegionDepthInRadii;
    const auto curves = thintissue::deriveWrinkleDataCurves(
      collision, collision.pointAttributes.get("Radius").values, settings);
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkCellArray> lines;
    vtkNew<vtkDoubleArray> region;
    region->SetName("RegionPoint");
    region->SetNumberOfComponents(3);
    vtkNew<vtkDoubleArray> thickness;
    thickness->SetName("Thickness");
    vtkNew<vtkIntArray> curveId;
    curveId->SetName("CurveId");
    for (std::size_t c = 0; c < curves.size(); ++c)
    {
      lines->InsertNextCell(static_cast<vtkIdType>(curves[c].monitorPoints.size()));
      for (std::size_t k = 0; k < curves[c].monitorPoints.size(); ++k)
      {
        lines->InsertCellPoint(points->InsertNextPoint(curves[c].monitorPoints[k].data()));
        region->InsertNextTuple(curves[c].regionPoints[k].data());
        thickness->InsertNextValue(curves[c].thickness[k]);
        curveId->InsertNextValue(static_cast<int>(c));
      }
    }
    output->SetPoints(points);
    output->SetLines(lines);
    output->GetPointData()->AddArray(region);
    output->GetPointData()->AddArray(thickness);
    output->GetPointData()->AddArray(curveId);
  }
  catch (const std::exception& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  return 1;
}

void vtkAutomaticMonitorPointsFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ThinFraction: " << this->ThinFraction << "\n"
     << indent << "UniformTolerance: " << this->UniformTolerance << "\n"
     << indent << "CornerAngle: " << this->CornerAngle << "\n"
     << indent << "MinimumRunFraction: " << this->MinimumRunFraction << "\n"
     << indent << "UseNearPoint: " << (this->UseNearPoint ? "On" : "Off") << "\n"
     << indent << "NearPoint: " << this->NearPoint[0] << " " << this->NearPoint[1] << " "
     << this->NearPoint[2] << "\n"
     << indent << "RegionDepth: " << this->RegionDepth << "\n"
     << indent << "RegionDepthInRadii: " << this->RegionDepthInRadii << "\n";
}
