// Test helper: writes the thesis's sheet (visual model 1, collision model 1)
// as VISUAL.vtp and COLLISION.vtp (with the point array "Radius"), the input
// of the ThinTissueBind smoke test.
#include "vtkThinSheetSource.h"

#include <vtkNew.h>
#include <vtkXMLPolyDataWriter.h>

#include <filesystem>
#include <iostream>

int main(int argc, char* argv[])
{
  if (argc != 3)
  {
    std::cerr << "usage: ThinTissueWriteSheetMeshes VISUAL.vtp COLLISION.vtp\n";
    return 2;
  }
  vtkNew<vtkThinSheetSource> sheet;
  sheet->SetThesisVisualModel(1);
  sheet->SetThesisCollisionModel(1);
  for (int port = 0; port < 2; ++port)
  {
    const std::filesystem::path directory = std::filesystem::path(argv[1 + port]).parent_path();
    if (!directory.empty())
    {
      std::filesystem::create_directories(directory);
    }
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputConnection(sheet->GetOutputPort(port));
    writer->SetFileName(argv[1 + port]);
    if (writer->Write() != 1)
    {
      std::cerr << "cannot write '" << argv[1 + port] << "'\n";
      return 1;
    }
  }
  return 0;
}
