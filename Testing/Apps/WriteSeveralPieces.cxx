// Test helper: writes OUTPUT.obj with three pieces, the input of the smoke
// tests of ThinTissuePrepare on a file of several tissues: the procedural
// medial meniscus (mm), a copy moved beside it, and a small closed
// fragment; scaled by FACTOR when given (0.001: the same in metres).
#include "MeniscusModel.h"
#include "MeshImport.h"
#include "MeshPrimitives.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>

int main(int argc, char* argv[])
{
  if (argc != 2 && argc != 3)
  {
    std::cerr << "usage: ThinTissueWriteSeveralPieces OUTPUT.obj [FACTOR]\n";
    return 2;
  }
  const double factor = argc == 3 ? std::atof(argv[2]) : 1.0;
  thintissue::TriangleMesh mesh = thintissue::makeMeniscus().visual;
  const double extent = mesh.boundingBox().sizes().maxCoeff();
  thintissue::TriangleMesh copy = mesh;
  for (thintissue::Vector3& x : copy.positions)
  {
    x.x() += 1.5 * extent;
  }
  thintissue::SlabSurfaceParameters fragment;
  fragment.width = fragment.depth = 1.0;
  fragment.cellsX = fragment.cellsY = 2;
  thintissue::TriangleMesh small = thintissue::makeSlabSurface(fragment);
  for (thintissue::Vector3& x : small.positions)
  {
    x.y() += 2.0 * extent;
  }
  mesh.append(copy);
  mesh.append(small);
  for (thintissue::Vector3& x : mesh.positions)
  {
    x *= factor;
  }
  const std::filesystem::path directory = std::filesystem::path(argv[1]).parent_path();
  if (!directory.empty())
  {
    std::filesystem::create_directories(directory);
  }
  try
  {
    thintissue::writeObj(mesh, argv[1]);
  }
  catch (const std::exception& e)
  {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
