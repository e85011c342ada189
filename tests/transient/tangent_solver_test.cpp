// TangentSolver: residual of the defining equation (S + U diag(d) U^T) x = b for symmetric
// positive definite, indefinite and unsymmetric S, with and without a low-rank part.
#include "geardyn/transient/tangent_solver.hpp"

#include <gtest/gtest.h>

#include <random>

namespace geardyn::transient {
namespace {

Eigen::SparseMatrix<double> banded(int n, double diagonal, double skew, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, diagonal + u(rng));
    if (i + 1 < n) {
      const double off = u(rng);
      t.emplace_back(i, i + 1, off + skew);
      t.emplace_back(i + 1, i, off - skew);
    }
  }
  Eigen::SparseMatrix<double> S(n, n);
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

double relative_residual(const Eigen::SparseMatrix<double>& S, const Eigen::MatrixXd& U,
                         const Eigen::VectorXd& d, const Eigen::VectorXd& x,
                         const Eigen::VectorXd& b) {
  Eigen::VectorXd r = S * x - b;
  if (U.cols() > 0) r += U * d.cwiseProduct(U.transpose() * x);
  return r.norm() / b.norm();
}

TEST(TangentSolver, SolvesSymmetricIndefiniteAndUnsymmetricSystems) {
  const int n = 200;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1, 2);
  Eigen::MatrixXd U = Eigen::MatrixXd::Random(n, 3);
  const Eigen::Vector3d d(2.0, 0.0, 0.5);
  struct Case {
    double diagonal, skew;
    TangentSolver::Method method;
  };
  for (const Case& c : {Case{4.0, 0.0, TangentSolver::Method::Cholesky},
                        Case{0.3, 0.0, TangentSolver::Method::LU},  // indefinite
                        Case{4.0, 0.7, TangentSolver::Method::LU}}) {
    const auto S = banded(n, c.diagonal, c.skew, 5);
    for (bool low_rank : {false, true}) {
      TangentSolver solver;
      const bool ok = low_rank ? solver.factorize(S, U, d) : solver.factorize(S);
      ASSERT_TRUE(ok) << solver.failure();
      EXPECT_EQ(solver.method(), c.method) << solver.description();
      Eigen::VectorXd x;
      solver.solve(b, x);
      EXPECT_LT(relative_residual(S, low_rank ? U : Eigen::MatrixXd(), d, x, b), 1e-10)
          << solver.description();
    }
  }
}

TEST(TangentSolver, ReportsSingularMatrix) {
  Eigen::SparseMatrix<double> S(3, 3);
  S.insert(0, 0) = 1.0;
  S.insert(1, 1) = 1.0;  // row and column 2 empty
  TangentSolver solver;
  EXPECT_FALSE(solver.factorize(S));
  EXPECT_FALSE(solver.ok());
  EXPECT_NE(solver.failure().find("singular"), std::string::npos) << solver.failure();
}

}  // namespace
}  // namespace geardyn::transient
