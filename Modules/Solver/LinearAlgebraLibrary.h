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

struct BlasLibrary
{
  /// "OpenBLAS", "reference BLAS" or "unknown".
  std::string name;
  /// The configuration OpenBLAS reports (version, kernel, threading), or empty.
  std::string configuration;
  /// The file the BLAS symbols come from, symbolic links resolved.
  std::string path;
  /// Threads OpenBLAS uses (1 for a single-threaded library).
  int threads = 1;
};

/// The BLAS loaded into this process (the one CHOLMOD calls). Throws
/// Error if no BLAS can be found in the process.
THINTISSUESOLVER_EXPORT BlasLibrary loadedBlasLibrary();

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
