#pragma once
// Which BLAS the process runs on, and whether it may be called from several threads at once.
//
// SuiteSparse (UMFPACK, CHOLMOD) calls the system BLAS through Debian's libblas.so.3
// alternative, so the library is chosen by the machine, not by geardyn. A sequential OpenBLAS
// (Debian's libopenblas0-serial, built without USE_LOCKING) shares its work buffers between
// callers: two threads factorising at once corrupt each other's results, silently. The
// threaded builds (libopenblas0-pthread, -openmp) lock those buffers, and the reference BLAS
// keeps no state. Parallel drivers (the sweep) ask here before running points on threads.
#include <string>

namespace geardyn::linalg {

struct BlasLibrary {
  /// OpenBLAS's own configuration string ("OpenBLAS 0.3.21 ... SINGLE_THREADED"), or a
  /// description when the library is not OpenBLAS.
  std::string description;
  bool is_openblas = false;
  /// openblas_get_parallel(): 0 sequential, 1 pthreads, 2 OpenMP (-1 when not OpenBLAS).
  int openblas_parallel = -1;
};

/// The BLAS loaded into this process (looked up once; the answer cannot change).
const BlasLibrary& loaded_blas();

/// Whether concurrent calls from several threads into `blas` give the results of serial calls.
/// A sequential OpenBLAS is treated as unsafe: whether it was built with USE_LOCKING cannot be
/// told at run time, and Debian 12's is not.
bool safe_for_concurrent_calls(const BlasLibrary& blas);

}  // namespace geardyn::linalg
