#include "MeshImport.h"

#include "AtomicFileWriter.h"
#include "MeshImportPrivate.h"
#include "ThinTissueError.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace thintissue
{

const std::vector<std::string>& kernelMeshFormats()
{
  static const std::vector<std::string> formats = {
    ".obj", ".stl", ".ply", ".off", ".gltf", ".glb", ".fbx", ".dae", ".3ds"
  };
  return formats;
}

std::string lowerCaseExtension(const std::string& path)
{
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(),
    extension.end(),
    extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

void checkReadableFile(const std::string& path)
{
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status))
  {
    throw FileError(path, "no such file");
  }
  if (std::filesystem::is_directory(status))
  {
    throw FileError(path, "is a directory, not a mesh file");
  }
  std::ifstream probe(path, std::ios::binary);
  if (!probe)
  {
    throw FileError(path, "cannot be opened for reading");
  }
}

namespace detail
{

void finishImportedMesh(TriangleMesh& mesh, const std::string& path)
{
  if (mesh.triangles.empty())
  {
    throw FileError(path, "contains no triangles (empty mesh)");
  }
  try
  {
    mesh.checkConsistency();
  }
  catch (const InvalidInputError& error)
  {
    // Re-issue naming the file; the kernel message already says what is wrong.
    std::string problem = error.what();
    const std::string prefix = "mesh '" + mesh.name + "': ";
    if (problem.compare(0, prefix.size(), prefix) == 0)
    {
      problem.erase(0, prefix.size());
    }
    throw FileError(path, problem);
  }
}

} // namespace detail

TriangleMesh readTriangleMesh(const std::string& path, const MeshImportOptions& options)
{
  checkReadableFile(path);
  const std::string extension = lowerCaseExtension(path);
  const auto& formats = kernelMeshFormats();
  if (std::find(formats.begin(), formats.end(), extension) == formats.end())
  {
    std::string supported;
    for (const std::string& format : formats)
    {
      supported += (supported.empty() ? "" : " ") + format;
    }
    throw FileError(path,
      "unknown mesh format '" + extension + "' (supported: " + supported +
        "; .vtp .vtk .vtu through vtkThinTissueMeshReader)");
  }
  TriangleMesh mesh;
  if (extension == ".obj" || extension == ".ply")
  {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream buffer;
    buffer << in.rdbuf();
    mesh = extension == ".obj"
             ? parseObj(buffer.str(), path)
             : detail::parsePly(buffer.str(), path, options.weldCoincidentVertices);
  }
  else
  {
    mesh = detail::readWithAssimp(path, options);
  }
  mesh.name = path;
  detail::finishImportedMesh(mesh, path);
  return mesh;
}

void writeObj(const TriangleMesh& mesh, const std::string& path)
{
  writeFileAtomically(path,
    [&](std::ostream& out)
    {
      out.precision(17);
      out << "# written by ThinTissue\n";
      for (const Vector3& p : mesh.positions)
      {
        out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
      }
      for (const Vector2& uv : mesh.textureCoordinates)
      {
        out << "vt " << uv.x() << ' ' << uv.y() << '\n';
      }
      for (const Vector3& n : mesh.normals)
      {
        out << "vn " << n.x() << ' ' << n.y() << ' ' << n.z() << '\n';
      }
      const bool texture = mesh.hasTextureCoordinates();
      const bool normals = mesh.hasNormals();
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      {
        out << 'f';
        for (int k = 0; k < 3; ++k)
        {
          const int v = mesh.triangles[t][k] + 1;
          out << ' ' << v;
          if (texture || normals)
          {
            out << '/';
            if (texture)
            {
              out << mesh.textureCorners[t][k] + 1;
            }
            if (normals)
            {
              out << '/' << v;
            }
          }
        }
        out << '\n';
      }
    });
}

} // namespace thintissue
