#include "AtomicFileWriter.h"

#include "ThinTissueError.h"

#include <filesystem>
#include <fstream>
#include <system_error>

namespace thintissue
{

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write)
{
  const std::filesystem::path target(path);
  const std::filesystem::path temporary = target.string() + ".writing";
  auto discard = [&]
  {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
  };
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out)
    {
      throw FileError(path, "cannot be opened for writing (directory missing or not writable?)");
    }
    try
    {
      write(out);
    }
    catch (...)
    {
      out.close();
      discard();
      throw;
    }
    if (!out.flush())
    {
      out.close();
      discard();
      throw FileError(path, "write failed (disk full?)");
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, target, error);
  if (error)
  {
    discard();
    throw FileError(path, "cannot replace the file: " + error.message());
  }
}

} // namespace thintissue
