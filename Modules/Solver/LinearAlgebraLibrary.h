// Which BLAS the sparse factorizations run on. CHOLMOD's supernodal
// factorization spends its time in dense BLAS kernels, so the library that
// Debian's update-alternatives selects behind libblas.so.3 (reference BLAS
// or OpenBLAS) decides its speed; benchmarks print it beside their figures.
#ifndef LinearAlgebraLibrary_h
#define LinearAlgebraLibrary_h

#include "ThinTissueSolverModule.h"

#include <string>

namespace thintissue
{

/// What selectOpenBlasKernels found and did.
enum class OpenBlasKernelChoice
{
  NotOpenBlas,    ///< the BLAS is not OpenBLAS (or not one built for several CPUs)
  UsersChoice,    ///< OPENBLAS_CORETYPE was set: left alone
  OpenBlasChoice, ///< OpenBLAS's own choice already runs this CPU's best kernels
  Replaced,       ///< OpenBLAS's own choice was replaced by openBlasCoreFor(this CPU)
};

struct BlasLibrary
{
  /// "OpenBLAS", "reference BLAS" or "unknown".
  std::string name;
  /// The configuration OpenBLAS reports (version, kernel, threading), or empty.
  std::string configuration;
  /// The kernel set ("core") OpenBLAS runs, e.g. "SkylakeX", or empty.
  std::string core;
  /// Who chose that core (selectOpenBlasKernels).
  OpenBlasKernelChoice coreChoice = OpenBlasKernelChoice::NotOpenBlas;
  /// The file the BLAS symbols come from, symbolic links resolved.
  std::string path;
  /// Threads OpenBLAS uses (1 for a single-threaded library).
  int threads = 1;
};

/// The BLAS loaded into this process (the one CHOLMOD calls). Throws
/// Error if no BLAS can be found in the process.
THINTISSUESOLVER_EXPORT BlasLibrary loadedBlasLibrary();

/// What a CPU offers that decides which OpenBLAS kernels it can run.
struct CpuVectorFeatures
{
  bool avx2 = false;
  bool fma = false;
  /// AVX-512 F, CD, BW, DQ and VL together (OpenBLAS's SkylakeX kernels).
  bool avx512 = false;
};

/// The features of this CPU, usable by the operating system.
THINTISSUESOLVER_EXPORT CpuVectorFeatures cpuVectorFeatures() noexcept;

/// The fastest OpenBLAS kernel set ("core") a CPU with `features` runs:
/// "SkylakeX" with AVX-512, "Haswell" with AVX2 and FMA, else "" (leave it
/// to OpenBLAS). OpenBLAS picks its kernels from the CPU's model number, and
/// 0.3.21 (Debian 12) does not know recent ones: on this machine's Xeon
/// (Sapphire Rapids, AVX-512) it fell back to "Prescott", SSE3 kernels from
/// 2004. Measured (ThinTissueBench --suite fem, supernodal factorization of
/// the 10,000-hexahedra block, nested dissection): Prescott 1,271 ms,
/// Haswell 734 ms, SkylakeX 621 ms.
THINTISSUESOLVER_EXPORT const char* openBlasCoreFor(const CpuVectorFeatures& features) noexcept;

/// Once per process, when the solver library is loaded (before anything
/// calls BLAS, while the process loads and no thread of ours runs): if
/// OpenBLAS chose weaker kernels than this CPU runs (openBlasCoreFor) and
/// OPENBLAS_CORETYPE is not set, OpenBLAS's kernel table is selected again
/// with that core (its exported gotoblas_dynamic_quit / gotoblas_dynamic_init
/// of builds for several CPUs, which read OPENBLAS_CORETYPE; the variable is
/// set for that call only). OpenBLAS sizes its work buffers for the largest
/// kernels of such a build, so the switch is safe while no BLAS call runs.
/// Calling it again returns the first call's result.
THINTISSUESOLVER_EXPORT OpenBlasKernelChoice selectOpenBlasKernels();

/// Once per process: a multithreaded OpenBLAS is set to one thread, unless
/// OPENBLAS_NUM_THREADS says otherwise. The solver's parallelism is its own
/// (the background refactorization beside the physics, haptics and render
/// threads); OpenBLAS threads that spin for work on a busy 2-core machine
/// made the supernodal factorization of the 1,000-hexahedra block cost 63
/// ms of CPU against 33 with one thread (and up to 30 times the wall time).
THINTISSUESOLVER_EXPORT void useOneBlasThread();

/// While it lives, OpenMP regions started by the calling thread run on that
/// thread alone (its max-active-levels ICV set to 0, restored after).
/// CHOLMOD 3 (SuiteSparse 5.12) opens regions of CHOLMOD_OMP_NUM_THREADS =
/// 4 threads in its supernodal factorization to copy and clear memory, and
/// no setting of cholmod_common limits them; their spinning doubled the CPU
/// of a factorization on the busy 2-core machine (1,000 hexahedra: 33 ms
/// against 16 ms with OMP_THREAD_LIMIT=1). The regions copy disjoint
/// entries, so the factor is the same bits with any number of threads. An
/// ICV is per thread: each thread that factorizes holds one of these. A
/// no-op when no OpenMP runtime is loaded.
class THINTISSUESOLVER_EXPORT SerialOpenMpScope
{
public:
  SerialOpenMpScope();
  ~SerialOpenMpScope();
  SerialOpenMpScope(const SerialOpenMpScope&) = delete;
  SerialOpenMpScope& operator=(const SerialOpenMpScope&) = delete;

private:
  int PreviousLevels = -1;
};

} // namespace thintissue

#endif
