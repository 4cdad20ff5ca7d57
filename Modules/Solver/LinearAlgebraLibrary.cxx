#include "LinearAlgebraLibrary.h"

#include "ThinTissueError.h"

#include <dlfcn.h>

#include <filesystem>

namespace thintissue
{

BlasLibrary loadedBlasLibrary()
{
  // CHOLMOD depends on libblas.so.3 (Debian's alternative); a process that
  // loaded the solver privately (Python) still has it loaded under that name.
  void* handle = dlopen("libblas.so.3", RTLD_LAZY | RTLD_NOLOAD);
  void* scope = handle != nullptr ? handle : RTLD_DEFAULT;
  Dl_info info{};
  void* gemm = dlsym(scope, "dgemm_");
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
  auto configuration = reinterpret_cast<ConfigurationFunction>(dlsym(scope, "openblas_get_config"));
  auto threads = reinterpret_cast<ThreadsFunction>(dlsym(scope, "openblas_get_num_threads"));
  if (handle != nullptr)
  {
    dlclose(handle); // drops the reference dlopen took; the library stays loaded
  }
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

} // namespace thintissue
