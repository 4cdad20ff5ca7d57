// Reading triangle meshes from files, without VTK.
//
// Wavefront OBJ is parsed here directly (it indexes positions and texture
// coordinates separately, which is exactly TriangleMesh's layout); STL, PLY,
// OFF, glTF, FBX, Collada and 3DS go through assimp, with positions welded
// afterwards because assimp splits vertices at texture seams. VTK formats
// (VTP, VTK, VTU) are read by vtkThinTissueMeshReader in the VTK layer.
#ifndef MeshImport_h
#define MeshImport_h

#include "ThinTissueCoreModule.h"
#include "TriangleMesh.h"

#include <string>
#include <vector>

namespace thintissue
{

struct MeshImportOptions
{
  /// Merge vertices at identical positions for formats that do not share
  /// them (STL) or that split them at texture seams (assimp's loaders).
  bool weldCoincidentVertices = true;
};

/// File extensions (lower case, with the dot) that readTriangleMesh reads.
THINTISSUECORE_EXPORT const std::vector<std::string>& kernelMeshFormats();

/// Lower-case extension of `path` with the dot ("" if none).
THINTISSUECORE_EXPORT std::string lowerCaseExtension(const std::string& path);

/// Throws FileError if `path` does not exist, is a directory or cannot be
/// opened for reading.
THINTISSUECORE_EXPORT void checkReadableFile(const std::string& path);

/// Reads a triangle mesh; polygons are triangulated. Throws FileError naming
/// the file and the problem: missing, a directory, unknown format, malformed,
/// empty, non-finite coordinates, indices out of range.
THINTISSUECORE_EXPORT TriangleMesh readTriangleMesh(const std::string& path,
  const MeshImportOptions& options = {});

/// Parses Wavefront OBJ text; `name` is used in messages and as mesh name.
THINTISSUECORE_EXPORT TriangleMesh parseObj(const std::string& text, const std::string& name);

/// Writes Wavefront OBJ (positions, texture coordinates per corner, normals).
/// Writes to a temporary file first, so an existing file is replaced only by
/// a complete one. Throws FileError on failure.
THINTISSUECORE_EXPORT void writeObj(const TriangleMesh& mesh, const std::string& path);

} // namespace thintissue

#endif
