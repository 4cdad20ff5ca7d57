// Helpers shared by ThinTissue's tests (header-only, not installed).
#ifndef ThinTissueTestSupport_h
#define ThinTissueTestSupport_h

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace thintissue::testing
{

/// ../shared/data, or "" when the optional real meshes are absent.
#ifndef THINTISSUE_TEST_SHARED_DATA_DEFAULT
#define THINTISSUE_TEST_SHARED_DATA_DEFAULT ""
#endif
#ifndef THINTISSUE_TEST_TEMPORARY_DEFAULT
#define THINTISSUE_TEST_TEMPORARY_DEFAULT ""
#endif

/// $NAME if set, else the build's default.
inline const char* settingOrDefault(const char* name, const char* fallback)
{
  const char* value = std::getenv(name);
  return value != nullptr && value[0] != '\0' ? value : fallback;
}

inline std::string sharedDataDirectory()
{
  const char* directory =
    settingOrDefault("THINTISSUE_SHARED_DATA", THINTISSUE_TEST_SHARED_DATA_DEFAULT);
  if (directory[0] == '\0' || !std::filesystem::is_directory(directory))
  {
    return {};
  }
  return directory;
}

/// A per-test scratch directory under the build tree (or the system's).
inline std::filesystem::path temporaryDirectory()
{
  const std::string directory =
    settingOrDefault("THINTISSUE_TEST_TEMPORARY", THINTISSUE_TEST_TEMPORARY_DEFAULT);
  std::filesystem::path path =
    !directory.empty() ? std::filesystem::path(directory) : std::filesystem::temp_directory_path();
  path /= "thintissue-tests";
  std::filesystem::create_directories(path);
  return path;
}

/// Writes `text` to a scratch file and returns its path.
inline std::string writeTemporaryFile(const std::string& fileName, const std::string& text)
{
  const std::filesystem::path path = temporaryDirectory() / fileName;
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  return path.string();
}

} // namespace thintissue::testing

#endif
