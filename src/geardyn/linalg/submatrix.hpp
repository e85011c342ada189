#pragma once
// Rows and columns of a sparse matrix picked by index lists (partitioning a system, e.g. into
// DOFs with and without mass).
#include <Eigen/SparseCore>
#include <vector>

namespace geardyn::linalg {

/// The rows `rows` and columns `cols` of A, in the order listed (each index at most once).
Eigen::SparseMatrix<double> submatrix(const Eigen::SparseMatrix<double>& A,
                                      const std::vector<int>& rows, const std::vector<int>& cols);

}  // namespace geardyn::linalg
