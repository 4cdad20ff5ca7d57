#include "LinearAlgebraLibrary.h"

#include "ThinTissueError.h"

#include <dlfcn.h>

#include <algorithm>
#include <array>
#include <cctype>
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
/// The kernel set OpenBLAS runs ("Prescott", "SkylakeX"...), or empty when
/// the BLAS is not OpenBLAS.
std::string openBlasCoreName()
{
  using CoreFunction = char* (*)();
  auto core = reinterpret_cast<CoreFunction>(blasSymbol("openblas_get_corename"));
  return core != nullptr ? std::string(core()) : std::string();
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
    library.core = openBlasCoreName();
    library.coreChoice = selectOpenBlasKernels();
  }
  else
  {
    library.name = library.path.find("/blas/") != std::string::npos ? "reference BLAS" : "unknown";
  }
  return library;
}

CpuVectorFeatures cpuVectorFeatures() noexcept
{
  // GCC's checks include the operating system's support (XGETBV) of the
  // AVX and AVX-512 register states. The explicit initialisation is needed
  // because this also runs from a static initializer, which may come before
  // libgcc's own.
  __builtin_cpu_init();
  CpuVectorFeatures features;
  features.avx2 = __builtin_cpu_supports("avx2");
  features.fma = __builtin_cpu_supports("fma");
  features.avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
                    __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
                    __builtin_cpu_supports("avx512vl");
  return features;
}

const char* openBlasCoreFor(const CpuVectorFeatures& features) noexcept
{
  if (features.avx512)
  {
    return "SkylakeX";
  }
  if (features.avx2 && features.fma)
  {
    return "Haswell";
  }
  return "";
}

namespace
{
/// Whether OpenBLAS's core `current` runs the kernels of `best` or better.
bool runsAtLeast(std::string current, const std::string& best)
{
  std::transform(current.begin(),
    current.end(),
    current.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // OpenBLAS's cores with AVX-512 kernels, and those with AVX2 and FMA.
  static const std::array<const char*, 3> avx512Cores{ "skylakex", "cooperlake", "sapphirerapids" };
  static const std::array<const char*, 5> avx2Cores{
    "haswell", "zen", "skylakex", "cooperlake", "sapphirerapids"
  };
  auto among = [&current](const auto& cores)
  { return std::find(cores.begin(), cores.end(), current) != cores.end(); };
  return best == "SkylakeX" ? among(avx512Cores) : among(avx2Cores);
}

OpenBlasKernelChoice chooseOpenBlasKernels()
{
  using InitFunction = void (*)();
  const std::string core = openBlasCoreName();
  auto quit = reinterpret_cast<InitFunction>(blasSymbol("gotoblas_dynamic_quit"));
  auto init = reinterpret_cast<InitFunction>(blasSymbol("gotoblas_dynamic_init"));
  if (core.empty() || quit == nullptr || init == nullptr)
  {
    return OpenBlasKernelChoice::NotOpenBlas;
  }
  if (std::getenv("OPENBLAS_CORETYPE") != nullptr)
  {
    return OpenBlasKernelChoice::UsersChoice;
  }
  const std::string best = openBlasCoreFor(cpuVectorFeatures());
  if (best.empty() || runsAtLeast(core, best))
  {
    return OpenBlasKernelChoice::OpenBlasChoice;
  }
  setenv("OPENBLAS_CORETYPE", best.c_str(), 1);
  quit();
  init();
  unsetenv("OPENBLAS_CORETYPE");
  return OpenBlasKernelChoice::Replaced;
}

/// At load time: single-threaded, before anything of ours calls BLAS.
[[maybe_unused]] const OpenBlasKernelChoice LoadTimeKernelChoice = selectOpenBlasKernels();
} // namespace

OpenBlasKernelChoice selectOpenBlasKernels()
{
  static const OpenBlasKernelChoice choice = chooseOpenBlasKernels();
  return choice;
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
