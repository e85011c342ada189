// The BLAS probe behind the sweep's choice of threads.
#include "geardyn/linalg/blas_library.hpp"

#include <gtest/gtest.h>

namespace geardyn::linalg {
namespace {

TEST(BlasLibrary, NamesTheLibraryThisProcessRunsOn) {
  const BlasLibrary& blas = loaded_blas();
  EXPECT_FALSE(blas.description.empty());
  if (blas.is_openblas) {
    EXPECT_NE(blas.description.find("OpenBLAS"), std::string::npos) << blas.description;
    EXPECT_GE(blas.openblas_parallel, 0);
    EXPECT_LE(blas.openblas_parallel, 2);
  } else {
    EXPECT_EQ(blas.openblas_parallel, -1);
  }
  EXPECT_EQ(&loaded_blas(), &blas);  // probed once
}

TEST(BlasLibrary, OnlyASequentialOpenBlasIsUnsafeForConcurrentCalls) {
  BlasLibrary blas;
  EXPECT_TRUE(safe_for_concurrent_calls(blas));  // reference BLAS and others: no shared state
  blas.is_openblas = true;
  blas.openblas_parallel = 0;  // Debian's libopenblas0-serial: shared buffers, no locking
  EXPECT_FALSE(safe_for_concurrent_calls(blas));
  blas.openblas_parallel = 1;  // pthreads build: buffers locked
  EXPECT_TRUE(safe_for_concurrent_calls(blas));
  blas.openblas_parallel = 2;  // OpenMP build
  EXPECT_TRUE(safe_for_concurrent_calls(blas));
}

}  // namespace
}  // namespace geardyn::linalg
