// Sparse direct factorisations (linalg/sparse_factorization.hpp) against dense Eigen solves of the
// same systems. References: the dense LU/LDLT of Eigen, and exact arithmetic for the small
// hand-made matrices. Tolerances: a backward-stable direct solve of a system with condition
// number kappa has a relative error of order kappa * eps; the test matrices have kappa < 1e3,
// so 1e-10 leaves a margin of about 1e3 over the expected error.
#include "geardyn/linalg/sparse_factorization.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <cmath>
#include <complex>
#include <vector>

namespace geardyn::linalg {
namespace {

/// The 1D Laplacian (tridiagonal 2, -1) of size n plus `shift` on the diagonal: symmetric,
/// positive definite for shift > -4 sin^2(pi / (2 (n + 1))), indefinite below.
Eigen::SparseMatrix<double> laplacian(int n, double shift) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 + shift);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

double relative_error(const Eigen::MatrixXd& x, const Eigen::MatrixXd& ref) {
  return (x - ref).norm() / ref.norm();
}

TEST(SymmetricFactorization, PositiveDefiniteUsesCholeskyAndMatchesDense) {
  const auto A = laplacian(50, 0.1);
  SymmetricFactorization f;
  ASSERT_EQ(f.compute(A), Status::Ok) << f.message();
  EXPECT_EQ(f.kind(), FactorizationKind::Cholesky);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(50, -1.0, 2.0);
  const Eigen::VectorXd ref = Eigen::MatrixXd(A).ldlt().solve(b);
  EXPECT_LT(relative_error(f.solve(b), ref), 1e-10);
  // The raw-pointer form (Spectra's operators) and the block form agree with the vector form.
  Eigen::VectorXd y(50);
  f.solve(b.data(), y.data());
  EXPECT_LT(relative_error(y, ref), 1e-10);
  Eigen::MatrixXd B(50, 2);
  B << b, 2.0 * b;
  const Eigen::MatrixXd X = f.solve(B);
  EXPECT_LT(relative_error(X.col(1), 2.0 * ref), 1e-10);
}

TEST(SymmetricFactorization, IndefiniteUsesLuAndMatchesDense) {
  // Shift -1, n = 40: eigenvalues 1 - 2 cos(k pi / 41), k = 1..40, straddle zero and none is
  // zero (that would need k = 41 / 3); the smallest in magnitude is about 0.04.
  const auto A = laplacian(40, -1.0);
  SymmetricFactorization f;
  ASSERT_EQ(f.compute(A), Status::Ok) << f.message();
  EXPECT_EQ(f.kind(), FactorizationKind::LU);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(40);
  const Eigen::VectorXd ref = Eigen::MatrixXd(A).fullPivLu().solve(b);
  EXPECT_LT(relative_error(f.solve(b), ref), 1e-10);
}

TEST(SymmetricFactorization, SingularMatrixIsReportedNotHidden) {
  // The free-free Laplacian (row sums zero) is singular: constants are in its null space.
  Eigen::SparseMatrix<double> A = laplacian(5, 0.0);
  A.coeffRef(0, 0) = 1.0;
  A.coeffRef(4, 4) = 1.0;
  SymmetricFactorization f;
  EXPECT_EQ(f.compute(A), Status::Singular);
  EXPECT_FALSE(f.message().empty());
}

TEST(SparseLU, RealUnsymmetricMatchesDense) {
  Eigen::SparseMatrix<double> A = laplacian(30, 0.5);
  A.coeffRef(0, 29) = 0.3;  // unsymmetric coupling
  A.coeffRef(10, 3) = -0.7;
  SparseLU<double> lu;
  ASSERT_EQ(lu.compute(A), Status::Ok) << lu.message();
  EXPECT_TRUE(lu.ok());
  EXPECT_EQ(lu.rows(), 30);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(30, 1.0, 3.0);
  EXPECT_LT(relative_error(lu.solve(b), Eigen::MatrixXd(A).fullPivLu().solve(b)), 1e-10);
  // Without iterative refinement the pivoted LU is still backward stable.
  SparseLU<double> plain;
  ASSERT_EQ(plain.compute(A, /*refine=*/false), Status::Ok);
  EXPECT_LT(relative_error(plain.solve(b), lu.solve(b)), 1e-10);
}

TEST(SparseLU, ComplexDynamicStiffnessMatchesDense) {
  // K - w^2 M + i w C with K the Laplacian, M = I, C = 0.05 I at w = 0.3: the frequency-domain
  // system every FRF solves.
  const int n = 20;
  const double w = 0.3;
  const Eigen::SparseMatrix<double> K = laplacian(n, 0.0);
  Eigen::SparseMatrix<std::complex<double>> D = K.cast<std::complex<double>>();
  for (int i = 0; i < n; ++i) D.coeffRef(i, i) += std::complex<double>(-w * w, 0.05 * w);
  SparseLU<std::complex<double>> lu;
  ASSERT_EQ(lu.compute(D), Status::Ok) << lu.message();
  Eigen::VectorXcd b = Eigen::VectorXcd::Zero(n);
  b(3) = 1.0;
  const Eigen::VectorXcd ref = Eigen::MatrixXcd(D).fullPivLu().solve(b);
  EXPECT_LT((lu.solve(b) - ref).norm() / ref.norm(), 1e-10);
}

TEST(SparseLU, ZeroPivotIsSingular) {
  Eigen::SparseMatrix<double> A(3, 3);
  A.coeffRef(0, 0) = 1.0;
  A.coeffRef(1, 1) = 1.0;  // row and column 2 empty
  SparseLU<double> lu;
  EXPECT_EQ(lu.compute(A), Status::Singular);
  EXPECT_FALSE(lu.ok());
  EXPECT_FALSE(lu.message().empty());
}

TEST(SparseHelpers, NormAsymmetryAndComplexProduct) {
  Eigen::SparseMatrix<double> A(2, 2);
  A.coeffRef(0, 0) = 1.0;
  A.coeffRef(0, 1) = -3.0;
  A.coeffRef(1, 0) = 2.0;
  A.coeffRef(1, 1) = 0.5;
  EXPECT_DOUBLE_EQ(norm1(A), 3.5);  // column 2: |-3| + |0.5|
  // ||A - A^T||_F = sqrt(2) * 5, ||A||_F = sqrt(1 + 9 + 4 + 0.25)
  EXPECT_NEAR(relative_asymmetry(A), std::sqrt(50.0) / std::sqrt(14.25), 1e-15);
  EXPECT_EQ(relative_asymmetry(laplacian(4, 0.0)), 0.0);
  const Eigen::VectorXcd x = Eigen::VectorXcd::Constant(2, std::complex<double>(1.0, 2.0));
  const Eigen::VectorXcd y = multiply(A, x);
  EXPECT_EQ(y(0), std::complex<double>(-2.0, -4.0));
  EXPECT_EQ(y(1), std::complex<double>(2.5, 5.0));
}

}  // namespace
}  // namespace geardyn::linalg
