// Test helper: writes OUTPUT.obj, an input of the ThinTissuePrepare smoke
// tests, built from the procedural medial meniscus (mm):
//   defective  the visual surface with the defects that --repair fixes (a
//              one-triangle hole, two flipped triangles, a duplicate one);
//   pieces     three pieces: the meniscus, a copy moved beside it and a
//              small closed fragment, scaled by FACTOR when given (0.001:
//              the same in metres).
#include "MeniscusModel.h"
#include "MeshImport.h"
#include "MeshPrimitives.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <utility>

namespace
{

using thintissue::TriangleMesh;

/// Triangle 100 goes (a hole of 3 edges), 200 and 1200 turn over, 300 is
/// listed twice; texture corners follow their triangles.
TriangleMesh defectiveMeniscus()
{
  TriangleMesh mesh = thintissue::makeMeniscus().visual;
  for (const int t : { 200, 1200 })
  {
    std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
    if (mesh.hasTextureCoordinates())
    {
      std::swap(mesh.textureCorners[t][1], mesh.textureCorners[t][2]);
    }
  }
  mesh.triangles.push_back(mesh.triangles[300]);
  mesh.triangles.erase(mesh.triangles.begin() + 100);
  if (mesh.hasTextureCoordinates())
  {
    mesh.textureCorners.push_back(mesh.textureCorners[300]);
    mesh.textureCorners.erase(mesh.textureCorners.begin() + 100);
  }
  return mesh;
}

TriangleMesh severalPieces(double factor)
{
  TriangleMesh mesh = thintissue::makeMeniscus().visual;
  const double extent = mesh.boundingBox().sizes().maxCoeff();
  TriangleMesh copy = mesh;
  for (thintissue::Vector3& x : copy.positions)
  {
    x.x() += 1.5 * extent;
  }
  thintissue::SlabSurfaceParameters fragment;
  fragment.width = fragment.depth = 1.0;
  fragment.cellsX = fragment.cellsY = 2;
  TriangleMesh small = thintissue::makeSlabSurface(fragment);
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
  return mesh;
}

} // namespace

int main(int argc, char* argv[])
{
  const std::string kind = argc > 1 ? argv[1] : "";
  if (!((kind == "defective" && argc == 3) || (kind == "pieces" && (argc == 3 || argc == 4))))
  {
    std::cerr << "usage: ThinTissueWriteTestMeshes defective OUTPUT.obj\n"
                 "       ThinTissueWriteTestMeshes pieces OUTPUT.obj [FACTOR]\n";
    return 2;
  }
  const TriangleMesh mesh =
    kind == "defective" ? defectiveMeniscus() : severalPieces(argc == 4 ? std::atof(argv[3]) : 1.0);
  const std::filesystem::path directory = std::filesystem::path(argv[2]).parent_path();
  if (!directory.empty())
  {
    std::filesystem::create_directories(directory);
  }
  try
  {
    thintissue::writeObj(mesh, argv[2]);
  }
  catch (const std::exception& e)
  {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
