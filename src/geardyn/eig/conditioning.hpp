#pragma once
// Why an eigen-problem is numerically singular or will not converge, in terms of the model.
//
// A stiffness many orders of magnitude above the rest (a "rigid" spring of 1e30 N/m) or a mass
// many orders below it (a density of 1e-300) leaves K - sigma M singular to working precision
// although the model has no mechanism. The diagonal ratios K_ii / M_ii (squared circular
// frequencies of each DOF alone) show it: physical models span well under 1e12.
#include <Eigen/Sparse>
#include <string>

namespace geardyn::eig {

/// A sentence naming the spread of K_ii / M_ii over the DOFs that have both (with its extremes)
/// when it exceeds 1e14, or of K_ii alone when that exceeds 1e16; empty when the scaling is
/// unremarkable. Meant to replace "a mechanism without mass" in a singular-matrix message.
/// `k` and `m` are the diagonals of K and M.
std::string scaling_diagnosis_of_diagonals(const Eigen::VectorXd& k, const Eigen::VectorXd& m);

/// scaling_diagnosis_of_diagonals of K and M (real, or complex Hermitian: real diagonals).
template <class MatrixK, class MatrixM>
std::string scaling_diagnosis(const MatrixK& K, const MatrixM& M) {
  return scaling_diagnosis_of_diagonals(K.diagonal().real(), M.diagonal().real());
}

}  // namespace geardyn::eig
