#include "geardyn/linalg/submatrix.hpp"

namespace geardyn::linalg {

Eigen::SparseMatrix<double> submatrix(const Eigen::SparseMatrix<double>& A,
                                      const std::vector<int>& rows, const std::vector<int>& cols) {
  std::vector<int> row_of(static_cast<std::size_t>(A.rows()), -1),
      col_of(static_cast<std::size_t>(A.cols()), -1);
  for (std::size_t i = 0; i < rows.size(); ++i)
    row_of[static_cast<std::size_t>(rows[i])] = static_cast<int>(i);
  for (std::size_t j = 0; j < cols.size(); ++j)
    col_of[static_cast<std::size_t>(cols[j])] = static_cast<int>(j);
  std::vector<Eigen::Triplet<double>> triplets;
  for (int k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      const int i = row_of[static_cast<std::size_t>(it.row())];
      const int j = col_of[static_cast<std::size_t>(it.col())];
      if (i >= 0 && j >= 0) triplets.emplace_back(i, j, it.value());
    }
  Eigen::SparseMatrix<double> out(static_cast<Eigen::Index>(rows.size()),
                                  static_cast<Eigen::Index>(cols.size()));
  out.setFromTriplets(triplets.begin(), triplets.end());
  return out;
}

}  // namespace geardyn::linalg
