// GCC's -Wnull-dereference false positive inside Eigen's sparse wrappers (see
// linalg/sparse_factorization.cpp): the pragma must precede the first Eigen include.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include "geardyn/eig/generalized_eigen_impl.hpp"
#include "geardyn/eig/hermitian_eigen.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::eig {

using Complex = std::complex<double>;
using ComplexSparse = Eigen::SparseMatrix<Complex>;

double automatic_shift(const ComplexSparse& K, const ComplexSparse& M) {
  return detail::automatic_shift(K, M);
}

namespace {

// Factorisation of the Hermitian matrix K - sigma M: complex Cholesky LL^H when it is positive
// definite (sigma below the spectrum, the usual case), UMFPACK's pivoting LU otherwise. Both
// solve to working precision; kind() records which one ran.
class HermitianFactorization {
 public:
  Status compute(const ComplexSparse& A) {
    // CHOLMOD reports "not positive definite" through its error handler, which prints by
    // default; the library stays silent and handles the condition here.
    cholesky_.cholmod().print = 0;
    cholesky_.cholmod().error_handler = nullptr;
    cholesky_.compute(A);
    if (cholesky_.info() == Eigen::Success) {
      kind_ = linalg::FactorizationKind::Cholesky;
      return Status::Ok;
    }
    const Status s = lu_.compute(A);
    if (s != Status::Ok) {
      message_ = lu_.message();
      return s;
    }
    kind_ = linalg::FactorizationKind::LU;
    return Status::Ok;
  }
  Eigen::MatrixXcd solve(const Eigen::MatrixXcd& B) const {
    if (kind_ == linalg::FactorizationKind::Cholesky) return cholesky_.solve(B);
    return lu_.solve(B);
  }
  linalg::FactorizationKind kind() const { return kind_; }
  const std::string& message() const { return message_; }

 private:
  Eigen::CholmodSupernodalLLT<ComplexSparse, Eigen::Lower> cholesky_;
  linalg::SparseLU<Complex> lu_;
  linalg::FactorizationKind kind_ = linalg::FactorizationKind::None;
  std::string message_;
};

}  // namespace

HermitianEigenResult solve_hermitian(const ComplexSparse& K_in, const ComplexSparse& M_in,
                                     const HermitianEigenOptions& options) {
  if (auto problems = options.validate(); !problems.empty())
    detail::throw_options("eig.HermitianEigenOptions", problems);
  detail::check_pencil("eig.solve_hermitian", K_in, M_in);
  HermitianEigenResult r;
  r.asymmetry = detail::self_adjoint_defect(K_in);
  const ComplexSparse K = detail::self_adjoint_part(K_in, r.asymmetry);
  const ComplexSparse M = detail::self_adjoint_part(M_in, detail::self_adjoint_defect(M_in));
  detail::solve_generalized(K, M, options, r, [&](bool band) {
    detail::solve_sparse<Complex, HermitianFactorization>(K, M, options, band, r);
  });
  return r;
}

}  // namespace geardyn::eig
