// Format back-ends of MeshImport (not installed).
#ifndef MeshImportPrivate_h
#define MeshImportPrivate_h

#include "MeshImport.h"

namespace thintissue
{
namespace detail
{

TriangleMesh readWithAssimp(const std::string& path, const MeshImportOptions& options);

/// Common checks after any reader: non-empty, finite, indices in range.
/// Converts consistency errors into FileErrors naming `path`.
void finishImportedMesh(TriangleMesh& mesh, const std::string& path);

} // namespace detail
} // namespace thintissue

#endif
