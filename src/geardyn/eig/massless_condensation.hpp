#pragma once
// Static (Guyan) condensation of the DOFs of a quadratic pencil (lambda^2 M + lambda D + K) x = 0
// that carry neither mass nor damping: their rows and columns of M and D (C and the low-rank
// term B diag(c) B^T) are zero, so their equations are K_ss x_s + K_sp x_p = 0 for every lambda
// and
//     x_s = -K_ss^{-1} K_sp x_p,   (lambda^2 M_pp + lambda D_pp + K_pp - K_ps K_ss^{-1} K_sp) x_p =
//     0
// holds exactly (R. J. Guyan, "Reduction of stiffness and mass matrices", AIAA J. 3 (1965) 380,
// exact here because the condensed DOFs have no inertia). Such DOFs (the nodes of a massless
// shaft away from its disks) otherwise give the first-order form infinite eigenvalues with
// Jordan blocks of size 2, which rounding moves to about 1/sqrt(eps) of the scale, where they
// pass for finite, spuriously growing modes.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "geardyn/eig/quadratic_eigen.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::eig {

class MasslessCondensation {
 public:
  /// Finds the DOFs without mass and damping; `active()` is false when there are none. When
  /// K_ss is singular (a mechanism of those DOFs: neither mass, damping nor stiffness), `ok()`
  /// is false and `message()` says so.
  explicit MasslessCondensation(const QuadraticPencil& pencil);

  bool active() const { return !condensed_.empty(); }
  bool ok() const { return ok_; }
  const std::string& message() const { return message_; }
  /// The pencil on the kept DOFs.
  const QuadraticPencil& reduced() const { return reduced_; }
  /// The full vectors (n x m) from vectors on the kept DOFs (n_p x m).
  Eigen::MatrixXcd expand(const Eigen::MatrixXcd& kept) const;

 private:
  std::vector<int> kept_, condensed_;
  QuadraticPencil reduced_;
  linalg::SparseLU<double> stiffness_;  // K_ss
  Eigen::SparseMatrix<double> K_sp_;
  bool ok_ = true;
  std::string message_;
};

}  // namespace geardyn::eig
