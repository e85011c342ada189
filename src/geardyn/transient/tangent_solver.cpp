#include "geardyn/transient/tangent_solver.hpp"

#include <fmt/format.h>

#include <Eigen/SparseCholesky>
#include <Eigen/UmfPackSupport>

namespace geardyn::transient {
namespace {

// Eigen keeps UMFPACK's info array protected; the reciprocal pivot ratio is in it.
class UmfPackLUWithInfo : public Eigen::UmfPackLU<Eigen::SparseMatrix<double>> {
 public:
  double reciprocal_pivot_ratio() const { return m_umfpackInfo[UMFPACK_RCOND]; }
};

}  // namespace

struct TangentSolver::Impl {
  using Sparse = Eigen::SparseMatrix<double>;
  Eigen::SimplicialLLT<Sparse, Eigen::Lower, Eigen::AMDOrdering<int>> llt;
  UmfPackLUWithInfo lu;
  bool llt_analysed = false, lu_analysed = false;
  Sparse pattern_llt, pattern_lu;  // the patterns the symbolic analyses belong to
  // UMFPACK's solve reads the matrix again (iterative refinement), and Eigen's wrapper keeps only
  // a reference to it: the factorised matrix must live as long as the factor.
  Sparse factored;

  // Woodbury data: U (n x m), d, W = S^{-1} U, and the LU of I + U^T W D.
  Eigen::MatrixXd U, W;
  Eigen::VectorXd d;
  Eigen::PartialPivLU<Eigen::MatrixXd> capacitance;

  // No iterative refinement in UMFPACK's solves: the Newton iterations that use them correct the
  // solution anyway, and the refinement was about half the integration time of a drivetrain
  // run-up (perf, docs/performance.md).
  Impl() { lu.umfpackControl()(UMFPACK_IRSTEP) = 0; }

  static bool same_pattern(const Sparse& a, const Sparse& b) {
    if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
    for (Eigen::Index j = 0; j <= a.outerSize(); ++j)
      if (a.outerIndexPtr()[j] != b.outerIndexPtr()[j]) return false;
    for (Eigen::Index k = 0; k < a.nonZeros(); ++k)
      if (a.innerIndexPtr()[k] != b.innerIndexPtr()[k]) return false;
    return true;
  }

  void solve_sparse(Method method, const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    x = method == Method::Cholesky ? Eigen::VectorXd(llt.solve(b)) : Eigen::VectorXd(lu.solve(b));
  }
};

TangentSolver::TangentSolver() : impl_(std::make_unique<Impl>()) {}
TangentSolver::~TangentSolver() = default;
TangentSolver::TangentSolver(TangentSolver&&) noexcept = default;
TangentSolver& TangentSolver::operator=(TangentSolver&&) noexcept = default;

bool TangentSolver::factorize(const Eigen::SparseMatrix<double>& S_in, const Eigen::MatrixXd& U,
                              const Eigen::VectorXd& d) {
  method_ = Method::None;
  failure_.clear();
  n_ = static_cast<int>(S_in.rows());
  if (S_in.rows() != S_in.cols()) {
    failure_ = fmt::format("iteration matrix is {} x {}, not square", S_in.rows(), S_in.cols());
    return false;
  }
  Impl::Sparse S = S_in;
  S.makeCompressed();

  // Symmetry to rounding: gyroscopic (skew) and cross-coupled bearing terms make S unsymmetric.
  const double norm = S.norm();
  const Impl::Sparse asym = S - Impl::Sparse(S.transpose());
  const bool symmetric = asym.norm() <= 1e-13 * norm;

  if (symmetric) {
    if (!impl_->llt_analysed || !Impl::same_pattern(S, impl_->pattern_llt)) {
      impl_->llt.analyzePattern(S);
      impl_->pattern_llt = S;
      impl_->llt_analysed = true;
    }
    impl_->llt.factorize(S);
    if (impl_->llt.info() == Eigen::Success) method_ = Method::Cholesky;
    // Not positive definite (e.g. negative stiffness): LU below, reported by method().
  }
  if (method_ == Method::None) {
    if (!impl_->lu_analysed || !Impl::same_pattern(S, impl_->pattern_lu)) {
      impl_->lu.analyzePattern(S);
      impl_->pattern_lu = S;
      impl_->lu_analysed = true;
    }
    impl_->factored = S;
    impl_->lu.factorize(impl_->factored);
    if (impl_->lu.info() != Eigen::Success) {
      failure_ = fmt::format(
          "sparse LU (UMFPACK) of the {} x {} iteration matrix failed: "
          "the matrix is singular",
          n_, n_);
      return false;
    }
    // UMFPACK reports an exactly zero pivot as success with a warning; check the pivots.
    const double rcond = impl_->lu.reciprocal_pivot_ratio();
    if (!(rcond > 1e-15)) {
      failure_ = fmt::format(
          "iteration matrix of size {} is singular to working precision "
          "(UMFPACK reciprocal pivot ratio {:.3g})",
          n_, rcond);
      return false;
    }
    method_ = Method::LU;
  }

  impl_->U.resize(0, 0);
  impl_->W.resize(0, 0);
  impl_->d.resize(0);
  if (U.cols() > 0) {
    if (U.rows() != n_ || d.size() != U.cols()) {
      failure_ = fmt::format("low-rank part has U {} x {} and d of size {}, expected {} rows",
                             U.rows(), U.cols(), d.size(), n_);
      method_ = Method::None;
      return false;
    }
    impl_->U = U;
    impl_->d = d;
    impl_->W.resize(n_, U.cols());
    Eigen::VectorXd column;
    for (Eigen::Index j = 0; j < U.cols(); ++j) {
      impl_->solve_sparse(method_, U.col(j), column);
      impl_->W.col(j) = column;
    }
    const Eigen::MatrixXd cap =
        Eigen::MatrixXd::Identity(U.cols(), U.cols()) + (U.transpose() * impl_->W) * d.asDiagonal();
    impl_->capacitance.compute(cap);
    if (!(std::abs(impl_->capacitance.determinant()) > 0.0)) {
      failure_ = "the low-rank (modal damping) update makes the iteration matrix singular";
      method_ = Method::None;
      return false;
    }
  }
  return true;
}

void TangentSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  impl_->solve_sparse(method_, b, x);
  if (impl_->U.cols() > 0) {
    const Eigen::VectorXd z = impl_->capacitance.solve(impl_->U.transpose() * x);
    x.noalias() -= impl_->W * (impl_->d.asDiagonal() * z);
  }
}

std::string TangentSolver::description() const {
  std::string s = method_ == Method::Cholesky ? "sparse Cholesky (Eigen SimplicialLLT)"
                  : method_ == Method::LU     ? "sparse LU (UMFPACK)"
                                              : "none";
  if (impl_->U.cols() > 0) s += fmt::format(" + Woodbury update of rank {}", impl_->U.cols());
  return s;
}

}  // namespace geardyn::transient
