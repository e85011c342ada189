// libFuzzer target: arbitrary bytes -> meshio::parse_matrix_market and meshio::parse_dof_map_csv.
//
// Bad input must end in geardyn::InputError; anything else (crash, other exception, sanitizer
// report, a huge allocation from a size line) is a bug. A matrix that parses is checked to be
// square with finite entries and, if the header said symmetric, to be stored symmetric.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/meshio/matrix_market.hpp"

namespace {

void check(const geardyn::meshio::MatrixMarketMatrix& m) {
  const Eigen::SparseMatrix<double>& A = m.matrix;
  if (A.rows() != A.cols()) std::abort();
  for (int k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      if (!std::isfinite(it.value())) std::abort();
      if (m.symmetric && A.coeff(it.col(), it.row()) != it.value()) std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    check(geardyn::meshio::parse_matrix_market(text, "fuzz.mtx"));
  } catch (const geardyn::InputError&) {
  }
  try {
    const auto dofs = geardyn::meshio::parse_dof_map_csv(text, "fuzz.csv");
    for (const auto& d : dofs)
      if (d.component < -1 || d.component > 5 || !d.x.allFinite()) std::abort();
  } catch (const geardyn::InputError&) {
  }
  return 0;
}
