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

} // namespace thintissue

#endif
