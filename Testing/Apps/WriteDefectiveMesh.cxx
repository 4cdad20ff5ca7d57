// Test helper: writes the meniscus model's visual surface with the defects
// that ThinTissuePrepare --repair fixes (a one-triangle hole, two flipped
// triangles, a duplicate triangle) as OUTPUT.obj, the input of the repair
// smoke tests.
#include "MeniscusModel.h"
#include "MeshImport.h"

#include <filesystem>
#include <iostream>
#include <utility>

int main(int argc, char* argv[])
{
  if (argc != 2)
  {
    std::cerr << "usage: ThinTissueWriteDefectiveMesh OUTPUT.obj\n";
    return 2;
  }
  thintissue::TriangleMesh mesh = thintissue::makeMeniscus().visual;
  // Triangle 100 goes (a hole of 3 edges), 200 and 1200 turn over, 300 is
  // listed twice; texture corners follow their triangles.
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
