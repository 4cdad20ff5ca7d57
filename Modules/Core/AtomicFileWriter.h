// Writing a file so that it is never seen half-written: the content goes to
// a temporary file beside it, which is renamed over the target only once
// complete (DESIGN.md: never write a half-result over a good file).
#ifndef AtomicFileWriter_h
#define AtomicFileWriter_h

#include "ThinTissueCoreModule.h"

#include <functional>
#include <ostream>
#include <string>

namespace thintissue
{

/// Calls `write` with a binary stream to "<path>.writing", then renames it to
/// `path`. Throws FileError naming `path` when the file cannot be created,
/// written or renamed; the temporary file is removed and an existing
/// `path` is left as it was. Exceptions from `write` propagate the same way.
THINTISSUECORE_EXPORT void writeFileAtomically(const std::string& path,
  const std::function<void(std::ostream&)>& write);

} // namespace thintissue

#endif
