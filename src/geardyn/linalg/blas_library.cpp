#include "geardyn/linalg/blas_library.hpp"

#include <dlfcn.h>

namespace geardyn::linalg {
namespace {

BlasLibrary probe() {
  BlasLibrary blas;
  // The BLAS is a dependency of the executable (through SuiteSparse), so its symbols are in
  // the global scope; OpenBLAS exports these two functions, other libraries do not.
  using ConfigFn = char* (*)();
  using ParallelFn = int (*)();
  auto config = reinterpret_cast<ConfigFn>(dlsym(RTLD_DEFAULT, "openblas_get_config"));
  auto parallel = reinterpret_cast<ParallelFn>(dlsym(RTLD_DEFAULT, "openblas_get_parallel"));
  if (config != nullptr && parallel != nullptr) {
    blas.is_openblas = true;
    blas.description = config();
    blas.openblas_parallel = parallel();
  } else {
    blas.description = "a BLAS other than OpenBLAS (reference BLAS, BLIS, ATLAS or MKL)";
  }
  return blas;
}

}  // namespace

const BlasLibrary& loaded_blas() {
  static const BlasLibrary blas = probe();
  return blas;
}

bool safe_for_concurrent_calls(const BlasLibrary& blas) {
  return !(blas.is_openblas && blas.openblas_parallel == 0);
}

}  // namespace geardyn::linalg
