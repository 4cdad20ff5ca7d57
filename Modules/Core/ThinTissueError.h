// Error types of the ThinTissue kernel. Every error names the input and the
// problem, e.g. "mesh file 'x.obj': line 12: face index 3000 out of range".
#ifndef ThinTissueError_h
#define ThinTissueError_h

#include "ThinTissueCoreModule.h"

#include <stdexcept>
#include <string>

namespace thintissue
{

/// Base class of every exception the kernel throws.
class THINTISSUECORE_EXPORT Error : public std::runtime_error
{
public:
  explicit Error(const std::string& message);
};

/// A file could not be read or written: missing, a directory, unknown format,
/// malformed or empty content. `path()` is the file named in the message.
class THINTISSUECORE_EXPORT FileError : public Error
{
public:
  FileError(const std::string& path, const std::string& problem);
  const std::string& path() const { return Path; }
  const std::string& problem() const { return Problem; }

private:
  std::string Path;
  std::string Problem;
};

/// Input data (a mesh, a parameter) violates a requirement of an algorithm.
class THINTISSUECORE_EXPORT InvalidInputError : public Error
{
public:
  explicit InvalidInputError(const std::string& message);
};

} // namespace thintissue

#endif
