#include "vtkSurgicalInstrumentSource.h"

#include "SurgicalInstruments.h"
#include "ThinTissueError.h"
#include "vtkThinTissueConversion.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

vtkStandardNewMacro(vtkSurgicalInstrumentSource);

vtkSurgicalInstrumentSource::vtkSurgicalInstrumentSource()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(3);
  this->SetInstrumentType(ProbeHook);
}

void vtkSurgicalInstrumentSource::SetInstrumentType(int type)
{
  if (type < ProbeHook || type > Scalpel)
  {
    vtkErrorMacro("instrument type " << type << " is not one of 0 (probe hook) to 5 (scalpel)");
    return;
  }
  const auto defaults =
    thintissue::defaultInstrumentParameters(static_cast<thintissue::SurgicalInstrumentType>(type));
  this->InstrumentType = type;
  this->SegmentsAround = defaults.segmentsAround;
  this->JawOpeningDegrees = defaults.jawOpeningDegrees;
  this->ShaftDiameter = defaults.shaftDiameter;
  this->ShaftLength = defaults.shaftLength;
  this->Modified();
}

void vtkSurgicalInstrumentSource::SetInstrumentTypeByName(const char* name)
{
  try
  {
    this->SetInstrumentType(
      static_cast<int>(thintissue::parseSurgicalInstrumentType(name ? name : "")));
  }
  catch (const thintissue::Error& error)
  {
    vtkErrorMacro(<< error.what());
  }
}

int vtkSurgicalInstrumentSource::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputs)
{
  auto* visual = vtkPolyData::GetData(outputs, VisualPort);
  auto* collision = vtkPolyData::GetData(outputs, CollisionPort);
  auto* features = vtkPolyData::GetData(outputs, WorkingFeaturesPort);
  try
  {
    auto p = thintissue::defaultInstrumentParameters(
      static_cast<thintissue::SurgicalInstrumentType>(this->InstrumentType));
    p.segmentsAround = this->SegmentsAround;
    p.jawOpeningDegrees = this->JawOpeningDegrees;
    p.shaftDiameter = this->ShaftDiameter;
    p.shaftLength = this->ShaftLength;
    const auto model = thintissue::makeSurgicalInstrument(p);
    this->UpdateProgress(0.5);
    visual->ShallowCopy(thintissue::toPolyData(model.visual));

    vtkNew<vtkPoints> segmentPoints;
    segmentPoints->SetDataTypeToDouble();
    vtkNew<vtkCellArray> segments;
    vtkNew<vtkDoubleArray> radius;
    radius->SetName("Radius");
    vtkNew<vtkStringArray> part;
    part->SetName("Part");
    for (const auto& segment : model.centreLine)
    {
      const vtkIdType ids[2] = { segmentPoints->InsertNextPoint(segment.start.data()),
        segmentPoints->InsertNextPoint(segment.end.data()) };
      segments->InsertNextCell(2, ids);
      radius->InsertNextValue(segment.radius);
      part->InsertNextValue(segment.part);
    }
    collision->SetPoints(segmentPoints);
    collision->SetLines(segments);
    collision->GetCellData()->AddArray(radius);
    collision->GetCellData()->AddArray(part);

    vtkNew<vtkPoints> featurePoints;
    featurePoints->SetDataTypeToDouble();
    vtkNew<vtkCellArray> tipCells;
    vtkNew<vtkCellArray> lineCells;
    const vtkIdType tip = featurePoints->InsertNextPoint(model.tip.data());
    tipCells->InsertNextCell(1, &tip);
    auto addPolyline = [&](const std::vector<thintissue::Vector3>& points, bool closed)
    {
      if (points.size() < 2)
      {
        return;
      }
      lineCells->InsertNextCell(static_cast<vtkIdType>(points.size() + (closed ? 1 : 0)));
      const vtkIdType first = featurePoints->GetNumberOfPoints();
      for (const auto& point : points)
      {
        lineCells->InsertCellPoint(featurePoints->InsertNextPoint(point.data()));
      }
      if (closed)
      {
        lineCells->InsertCellPoint(first);
      }
    };
    addPolyline(model.cuttingEdge, false);
    addPolyline(model.opposingCuttingEdge, false);
    addPolyline(model.biteOutline, true);
    features->SetPoints(featurePoints);
    features->SetVerts(tipCells);
    features->SetLines(lineCells);
  }
  catch (const thintissue::Error& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkSurgicalInstrumentSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "InstrumentType: " << this->InstrumentType << " ("
     << thintissue::instrumentTypeName(
          static_cast<thintissue::SurgicalInstrumentType>(this->InstrumentType))
     << ")\n"
     << indent << "SegmentsAround: " << this->SegmentsAround << "\n"
     << indent << "JawOpeningDegrees: " << this->JawOpeningDegrees << "\n"
     << indent << "ShaftDiameter: " << this->ShaftDiameter << "\n"
     << indent << "ShaftLength: " << this->ShaftLength << "\n";
}
