#include "vtkThinSheetSource.h"

#include "ThinSheetModel.h"
#include "ThinTissueError.h"

#include <vtkObjectFactory.h>

vtkStandardNewMacro(vtkThinSheetSource);

vtkThinSheetSource::vtkThinSheetSource()
{
  const auto p =
    thintissue::thesisSheetCollisionResolution(1, thintissue::thesisSheetVisualResolution(2));
  this->Width = p.width;
  this->Depth = p.depth;
  this->Thickness = p.thickness;
  this->VisualCells[0] = p.visualCellsX;
  this->VisualCells[1] = p.visualCellsY;
  this->VisualCells[2] = p.visualCellsZ;
  this->CollisionColumns = p.collisionColumns;
  this->CollisionRows = p.collisionRows;
  this->Hexahedra[0] = p.hexahedraX;
  this->Hexahedra[1] = p.hexahedraY;
  this->Hexahedra[2] = p.hexahedraZ;
  this->Attachment = static_cast<int>(p.attachment);
  this->TextureScale = p.textureScale;
}

void vtkThinSheetSource::SetThesisVisualModel(int model)
{
  try
  {
    const auto p = thintissue::thesisSheetVisualResolution(model);
    this->SetVisualCells(p.visualCellsX, p.visualCellsY, p.visualCellsZ);
  }
  catch (const thintissue::Error& error)
  {
    vtkErrorMacro(<< error.what());
  }
}

void vtkThinSheetSource::SetThesisCollisionModel(int model)
{
  try
  {
    const auto p = thintissue::thesisSheetCollisionResolution(model);
    this->SetCollisionColumns(p.collisionColumns);
    this->SetCollisionRows(p.collisionRows);
  }
  catch (const thintissue::Error& error)
  {
    vtkErrorMacro(<< error.what());
  }
}

thintissue::TissueModel vtkThinSheetSource::BuildTissueModel()
{
  thintissue::ThinSheetParameters p;
  p.width = this->Width;
  p.depth = this->Depth;
  p.thickness = this->Thickness;
  p.visualCellsX = this->VisualCells[0];
  p.visualCellsY = this->VisualCells[1];
  p.visualCellsZ = this->VisualCells[2];
  p.collisionColumns = this->CollisionColumns;
  p.collisionRows = this->CollisionRows;
  p.hexahedraX = this->Hexahedra[0];
  p.hexahedraY = this->Hexahedra[1];
  p.hexahedraZ = this->Hexahedra[2];
  p.attachment = static_cast<thintissue::SheetAttachment>(this->Attachment);
  p.textureScale = this->TextureScale;
  return thintissue::makeThinSheet(p);
}

void vtkThinSheetSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Width: " << this->Width << "\n"
     << indent << "Depth: " << this->Depth << "\n"
     << indent << "Thickness: " << this->Thickness << "\n"
     << indent << "VisualCells: " << this->VisualCells[0] << " " << this->VisualCells[1] << " "
     << this->VisualCells[2] << "\n"
     << indent << "CollisionColumns: " << this->CollisionColumns << "\n"
     << indent << "CollisionRows: " << this->CollisionRows << "\n"
     << indent << "Hexahedra: " << this->Hexahedra[0] << " " << this->Hexahedra[1] << " "
     << this->Hexahedra[2] << "\n"
     << indent << "Attachment: " << this->Attachment << "\n"
     << indent << "TextureScale: " << this->TextureScale << "\n";
}
