#include "ThinTissueError.h"

namespace thintissue
{

Error::Error(const std::string& message)
  : std::runtime_error(message)
{
}

FileError::FileError(const std::string& path, const std::string& problem)
  : Error("mesh file '" + path + "': " + problem)
  , Path(path)
  , Problem(problem)
{
}

InvalidInputError::InvalidInputError(const std::string& message)
  : Error(message)
{
}

} // namespace thintissue
