// Format back-ends of MeshImport (not installed).
#ifndef MeshImportPrivate_h
#define MeshImportPrivate_h

#include "MeshImport.h"

namespace thintissue
{
namespace detail
{

TriangleMesh readWithAssimp(const std::string& path, const MeshImportOptions& options);

/// Stanford PLY (ASCII or binary) from the file's bytes; polygons
/// fan-triangulated, points and lines dropped, identical positions welded
/// when `weld`. FileError naming `path` on a malformed header or body.
TriangleMesh parsePly(const std::string& bytes, const std::string& path, bool weld);

/// Common checks after any reader: non-empty, finite, indices in range.
/// Converts consistency errors into FileErrors naming `path`.
void finishImportedMesh(TriangleMesh& mesh, const std::string& path);

} // namespace detail
} // namespace thintissue

#endif
