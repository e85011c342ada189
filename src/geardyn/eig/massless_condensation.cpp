#include "geardyn/eig/massless_condensation.hpp"

#include <fmt/format.h>

#include "geardyn/linalg/submatrix.hpp"

namespace geardyn::eig {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Marks the rows and columns of A that hold a non-zero entry.
void mark(const SparseMatrix& A, std::vector<bool>& used) {
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
      if (it.value() != 0.0) {
        used[static_cast<std::size_t>(it.row())] = true;
        used[static_cast<std::size_t>(it.col())] = true;
      }
}

}  // namespace

MasslessCondensation::MasslessCondensation(const QuadraticPencil& p) {
  const Eigen::Index n = p.size();
  std::vector<bool> inertial(static_cast<std::size_t>(n), false);
  mark(p.M, inertial);
  mark(p.C, inertial);
  for (Eigen::Index i = 0; i < p.low_rank_basis.rows(); ++i)
    if (p.low_rank_basis.row(i).cwiseAbs().maxCoeff() > 0.0)
      inertial[static_cast<std::size_t>(i)] = true;
  for (Eigen::Index i = 0; i < n; ++i)
    (inertial[static_cast<std::size_t>(i)] ? kept_ : condensed_).push_back(static_cast<int>(i));
  if (condensed_.empty()) return;
  if (kept_.empty()) {
    ok_ = false;
    message_ =
        "the model has neither mass nor damping, so it has no modes: give a material a density "
        "> 0 (materials[i].density), or add [[disks]] or [[point_masses]]";
    return;
  }
  // Columns of K_sp that couple to the condensed DOFs: only they change K_pp.
  K_sp_ = linalg::submatrix(p.K, condensed_, kept_);
  if (stiffness_.compute(linalg::submatrix(p.K, condensed_, condensed_)) != Status::Ok) {
    ok_ = false;
    message_ = fmt::format(
        "{} DOFs have neither mass nor damping and their stiffness matrix is singular ({}): a "
        "massless part of the model can move freely. Give it mass (a density > 0, a disk or a "
        "point mass), support it (bearings, constraints) or leave those DOFs out with `dofs`",
        condensed_.size(), stiffness_.message());
    return;
  }
  const Eigen::MatrixXd X = stiffness_.solve(Eigen::MatrixXd(K_sp_));  // K_ss^{-1} K_sp
  const SparseMatrix K_ps = linalg::submatrix(p.K, kept_, condensed_);
  SparseMatrix correction = (K_ps * X).sparseView(0.0, 0.0);
  reduced_.M = linalg::submatrix(p.M, kept_, kept_);
  reduced_.C = linalg::submatrix(p.C, kept_, kept_);
  reduced_.K = SparseMatrix(linalg::submatrix(p.K, kept_, kept_) - correction);
  reduced_.K.makeCompressed();
  if (p.low_rank_basis.cols() > 0) {
    reduced_.low_rank_basis.resize(static_cast<Eigen::Index>(kept_.size()),
                                   p.low_rank_basis.cols());
    for (std::size_t i = 0; i < kept_.size(); ++i)
      reduced_.low_rank_basis.row(static_cast<Eigen::Index>(i)) = p.low_rank_basis.row(kept_[i]);
    reduced_.low_rank_coefficients = p.low_rank_coefficients;
  }
}

Eigen::MatrixXcd MasslessCondensation::expand(const Eigen::MatrixXcd& x) const {
  const Eigen::Index n = static_cast<Eigen::Index>(kept_.size() + condensed_.size());
  Eigen::MatrixXcd full(n, x.cols());
  const Eigen::MatrixXd re = x.real(), im = x.imag();
  const Eigen::MatrixXd s_re = -stiffness_.solve(Eigen::MatrixXd(K_sp_ * re));
  const Eigen::MatrixXd s_im = -stiffness_.solve(Eigen::MatrixXd(K_sp_ * im));
  for (std::size_t i = 0; i < kept_.size(); ++i)
    full.row(kept_[i]) = x.row(static_cast<Eigen::Index>(i));
  for (std::size_t i = 0; i < condensed_.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    full.row(condensed_[i]).real() = s_re.row(k);
    full.row(condensed_[i]).imag() = s_im.row(k);
  }
  return full;
}

}  // namespace geardyn::eig
