#include "LinearAlgebraLibrary.h"

#include "ThinTissueError.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <utility>

namespace thintissue
{

namespace
{
/// A function of the loaded BLAS, or null. CHOLMOD depends on libblas.so.3
/// (Debian's alternative); a process that loaded the solver privately
/// (Python) still has it loaded under that name. The handle is released at
/// once: CHOLMOD keeps the library loaded, so the address stays valid.
void* blasSymbol(const char* name)
{
  void* handle = dlopen("libblas.so.3", RTLD_LAZY | RTLD_NOLOAD);
  void* symbol = dlsym(handle != nullptr ? handle : RTLD_DEFAULT, name);
  if (handle != nullptr)
  {
    dlclose(handle);
  }
  return symbol;
}
} // namespace

BlasLibrary loadedBlasLibrary()
{
  Dl_info info{};
  void* gemm = blasSymbol("dgemm_");
  if (gemm == nullptr || dladdr(gemm, &info) == 0 || info.dli_fname == nullptr)
  {
    throw Error("linear algebra: no BLAS is loaded (dgemm_ not found in any library)");
  }
  BlasLibrary library;
  std::error_code error;
  const std::filesystem::path resolved = std::filesystem::canonical(info.dli_fname, error);
  library.path = error ? std::string(info.dli_fname) : resolved.string();
  // OpenBLAS names itself; the reference BLAS has no such function.
  using ConfigurationFunction = char* (*)();
  using ThreadsFunction = int (*)();
  auto configuration = reinterpret_cast<ConfigurationFunction>(blasSymbol("openblas_get_config"));
  auto threads = reinterpret_cast<ThreadsFunction>(blasSymbol("openblas_get_num_threads"));
  if (configuration != nullptr)
  {
    library.name = "OpenBLAS";
    library.configuration = configuration();
    library.threads = threads != nullptr ? threads() : 1;
  }
  else
  {
    library.name = library.path.find("/blas/") != std::string::npos ? "reference BLAS" : "unknown";
  }
  return library;
}

void useOneBlasThread()
{
  static std::once_flag once;
  std::call_once(once,
    []
    {
      if (std::getenv("OPENBLAS_NUM_THREADS") != nullptr)
      {
        return; // the user's choice
      }
      using SetThreadsFunction = void (*)(int);
      auto setThreads =
        reinterpret_cast<SetThreadsFunction>(blasSymbol("openblas_set_num_threads"));
      if (setThreads != nullptr)
      {
        setThreads(1);
      }
    });
}

namespace
{
using GetLevelsFunction = int (*)();
using SetLevelsFunction = void (*)(int);

/// The OpenMP runtime's max-active-levels functions (libgomp, loaded with
/// CHOLMOD), or null.
std::pair<GetLevelsFunction, SetLevelsFunction> openMpLevelFunctions()
{
  static const auto functions = std::make_pair(
    reinterpret_cast<GetLevelsFunction>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels")),
    reinterpret_cast<SetLevelsFunction>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels")));
  return functions;
}
} // namespace

SerialOpenMpScope::SerialOpenMpScope()
{
  const auto [getLevels, setLevels] = openMpLevelFunctions();
  if (getLevels != nullptr && setLevels != nullptr)
  {
    PreviousLevels = getLevels();
    setLevels(0);
  }
}

SerialOpenMpScope::~SerialOpenMpScope()
{
  if (PreviousLevels >= 0)
  {
    openMpLevelFunctions().second(PreviousLevels);
  }
}

} // namespace thintissue
