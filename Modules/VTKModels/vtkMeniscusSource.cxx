#include "vtkMeniscusSource.h"

#include "MeniscusModel.h"
#include "ThinTissueError.h"
#include "vtkTissueModelBlocks.h"

#include <vtkCellArray.h>
#include <vtkCompositeDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(vtkMeniscusSource);

struct vtkMeniscusSource::Internals
{
  thintissue::MeniscusParameters parameters;
  std::vector<thintissue::MonitorCurve> curves;
};

vtkMeniscusSource::vtkMeniscusSource()
{
  this->SetNumberOfTissueOutputPorts(5);
  const thintissue::MeniscusParameters p;
  this->TearAlongBegin = p.tear.alongBegin;
  this->TearAlongEnd = p.tear.alongEnd;
  this->TearAcross = p.tear.across;
  this->TearOpening = p.tear.opening;
  this->VisualCells[0] = p.visualAlong;
  this->VisualCells[1] = p.visualAcross;
  this->VisualCells[2] = p.visualThrough;
  this->CollisionCells[0] = p.collisionAlong;
  this->CollisionCells[1] = p.collisionAcross;
  this->Hexahedra[0] = p.hexahedraAlong;
  this->Hexahedra[1] = p.hexahedraAcross;
  this->Hexahedra[2] = p.hexahedraThrough;
  this->RimHeight = p.rimHeight;
  this->InnerEdgeHeight = p.innerEdgeHeight;
}

void vtkMeniscusSource::SetTearType(int type)
{
  if (type < NoTear || type > HorizontalCleavageTear)
  {
    vtkErrorMacro("tear type " << type << " is not one of 0 (none) to 4 (horizontal cleavage)");
    return;
  }
  const auto tear =
    thintissue::defaultMeniscusTear(static_cast<thintissue::MeniscusTearType>(type));
  this->TearType = type;
  this->TearAlongBegin = tear.alongBegin;
  this->TearAlongEnd = tear.alongEnd;
  this->TearAcross = tear.across;
  this->TearOpening = tear.opening;
  this->Modified();
}

void vtkMeniscusSource::SetExaminationResolution()
{
  const auto p = thintissue::examinationMeniscusParameters();
  this->SetVisualCells(p.visualAlong, p.visualAcross, p.visualThrough);
}

vtkPolyData* vtkMeniscusSource::GetMonitorPointsOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(MonitorPointsPort));
}

thintissue::TissueModel vtkMeniscusSource::BuildTissueModel()
{
  thintissue::MeniscusParameters p;
  p.tear.type = static_cast<thintissue::MeniscusTearType>(this->TearType);
  p.tear.alongBegin = this->TearAlongBegin;
  p.tear.alongEnd = this->TearAlongEnd;
  p.tear.across = this->TearAcross;
  p.tear.opening = this->TearOpening;
  p.visualAlong = this->VisualCells[0];
  p.visualAcross = this->VisualCells[1];
  p.visualThrough = this->VisualCells[2];
  p.collisionAlong = this->CollisionCells[0];
  p.collisionAcross = this->CollisionCells[1];
  p.hexahedraAlong = this->Hexahedra[0];
  p.hexahedraAcross = this->Hexahedra[1];
  p.hexahedraThrough = this->Hexahedra[2];
  p.rimHeight = this->RimHeight;
  p.innerEdgeHeight = this->InnerEdgeHeight;
  thintissue::MeniscusModel model = thintissue::makeMeniscus(p);
  auto internals = std::make_shared<Internals>();
  internals->parameters = p;
  internals->curves =
    this->MonitorPointSpacing > 0.0
      ? thintissue::sampleMonitorCurves(p, model.monitorCurves, this->MonitorPointSpacing)
      : model.monitorCurves;
  this->LastModel = internals;
  return std::move(model);
}

void vtkMeniscusSource::FillExtraOutputs(vtkInformationVector* outputs, vtkMultiBlockDataSet* all)
{
  auto* monitor = vtkPolyData::SafeDownCast(
    outputs->GetInformationObject(MonitorPointsPort)->Get(vtkDataObject::DATA_OBJECT()));
  if (!monitor || !this->LastModel)
  {
    return;
  }
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
  int id = 0;
  for (const auto& curve : this->LastModel->curves)
  {
    lines->InsertNextCell(static_cast<vtkIdType>(curve.monitorPoints.size()));
    for (std::size_t k = 0; k < curve.monitorPoints.size(); ++k)
    {
      lines->InsertCellPoint(points->InsertNextPoint(curve.monitorPoints[k].data()));
      region->InsertNextTuple(curve.regionPoints[k].data());
      thickness->InsertNextValue(curve.thickness[k]);
      curveId->InsertNextValue(id);
    }
    ++id;
  }
  monitor->SetPoints(points);
  monitor->SetLines(lines);
  monitor->GetPointData()->AddArray(region);
  monitor->GetPointData()->AddArray(thickness);
  monitor->GetPointData()->AddArray(curveId);
  vtkNew<vtkPolyData> copy;
  copy->ShallowCopy(monitor);
  thintissue::appendNamedBlock(all, copy, "MonitorPoints");
}

void vtkMeniscusSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TearType: " << this->TearType << "\n"
     << indent << "TearAlongBegin: " << this->TearAlongBegin << "\n"
     << indent << "TearAlongEnd: " << this->TearAlongEnd << "\n"
     << indent << "TearAcross: " << this->TearAcross << "\n"
     << indent << "TearOpening: " << this->TearOpening << "\n"
     << indent << "VisualCells: " << this->VisualCells[0] << " " << this->VisualCells[1] << " "
     << this->VisualCells[2] << "\n"
     << indent << "CollisionCells: " << this->CollisionCells[0] << " " << this->CollisionCells[1]
     << "\n"
     << indent << "Hexahedra: " << this->Hexahedra[0] << " " << this->Hexahedra[1] << " "
     << this->Hexahedra[2] << "\n"
     << indent << "RimHeight: " << this->RimHeight << "\n"
     << indent << "InnerEdgeHeight: " << this->InnerEdgeHeight << "\n"
     << indent << "MonitorPointSpacing: " << this->MonitorPointSpacing << "\n";
}
