// Quadratic eigenproblem (lambda^2 M + lambda D + K) x = 0: dense vs sparse on a damped
// gyroscopic chain, real and complex targets, start vectors, input checks.
// (Analytic references: eigen_validation_test.cpp.)
#include "geardyn/eig/quadratic_eigen.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "eig/test_systems.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"

namespace geardyn::eig {
namespace {

using Complex = std::complex<double>;
using test::chain_stiffness;
using test::diagonal_matrix;
using SparseMatrix = Eigen::SparseMatrix<double>;

using test::expect_close;

// A gyroscopic, damped, non-proportional chain: 150 stations with x and y, springs k between
// stations, a gyroscopic coupling g between x_i and y_i, and dampers c at every tenth station.
QuadraticPencil gyroscopic_chain(int stations, double speed) {
  const int n = 2 * stations;
  const double k = 1e6, m = 0.8, g = 0.05, c = 30.0;
  SparseMatrix Kx = chain_stiffness(stations, k, true);
  std::vector<Eigen::Triplet<double>> tk, tc;
  for (int e = 0; e < Kx.outerSize(); ++e)
    for (SparseMatrix::InnerIterator it(Kx, e); it; ++it) {
      tk.emplace_back(2 * it.row(), 2 * it.col(), it.value());
      // y slightly stiffer than x: anisotropic supports, so no exact double roots
      tk.emplace_back(2 * it.row() + 1, 2 * it.col() + 1, 1.1 * it.value());
    }
  for (int i = 0; i < stations; ++i) {
    tc.emplace_back(2 * i, 2 * i + 1, speed * g);
    tc.emplace_back(2 * i + 1, 2 * i, -speed * g);
    if (i % 10 == 0) {
      tc.emplace_back(2 * i, 2 * i, c);
      tc.emplace_back(2 * i + 1, 2 * i + 1, c);
    }
  }
  QuadraticPencil p;
  p.K.resize(n, n);
  p.K.setFromTriplets(tk.begin(), tk.end());
  p.C.resize(n, n);
  p.C.setFromTriplets(tc.begin(), tc.end());
  p.M = diagonal_matrix(n, m);
  return p;
}

// Dense (all eigenvalues of the 2n state operator) and sparse (Arnoldi) are independent
// computations. Eigenvalue errors are ~ eps |lambda|^2 / |lambda_1| ~ 1e-14 |lambda| for the
// dense path and <= tol = 1e-10 (relative, on the inverted eigenvalue) for Arnoldi.
TEST(QuadraticEigen, DenseAndSparseAgreeOnGyroscopicChain) {
  const auto p = gyroscopic_chain(150, 3000.0);
  QuadraticEigenOptions options;
  options.n_modes = 10;
  options.method = Method::Dense;
  const auto dense = solve_quadratic(p, options);
  options.method = Method::Sparse;
  const auto sparse = solve_quadratic(p, options);
  ASSERT_EQ(dense.status, Status::Ok) << dense.brief_report();
  ASSERT_EQ(sparse.status, Status::Ok) << sparse.brief_report();
  EXPECT_EQ(sparse.method_used, Method::Sparse);
  ASSERT_EQ(dense.eigenvalues.size(), 10);
  ASSERT_EQ(sparse.eigenvalues.size(), 10);
  for (int j = 0; j < 10; ++j)
    expect_close(sparse.eigenvalues[j], dense.eigenvalues[j], 1e-9, "mode " + std::to_string(j));
  EXPECT_LT(dense.max_residual(), 1e-13);
  EXPECT_LT(sparse.max_residual(), 1e-12);
  // The defining equation, relative to its terms, for every sparse mode.
  for (int j = 0; j < 10; ++j) {
    const Complex l = sparse.eigenvalues[j];
    const Eigen::VectorXcd x = sparse.eigenvectors.col(j);
    Eigen::VectorXcd Kx(x.size()), Mx(x.size());
    Kx.real() = p.K * x.real();
    Kx.imag() = p.K * x.imag();
    Mx.real() = p.M * x.real();
    Mx.imag() = p.M * x.imag();
    const Eigen::VectorXcd res = l * l * Mx + l * p.apply_damping(x) + Kx;
    EXPECT_LT(res.norm() / Kx.norm(), 1e-8) << "mode " << j;
  }
}

// Complex target i w: the sparse solver (Parlett-Saad real operator on a complex LU) must find
// the modes nearest the target, the same ones the dense solver selects.
TEST(QuadraticEigen, ComplexTargetFindsModesNearAFrequency) {
  const auto p = gyroscopic_chain(150, 3000.0);
  QuadraticEigenOptions options;
  options.n_modes = 6;
  options.method = Method::Dense;
  // The chain's spectrum spans about 20 to 2400 rad/s; 1500 rad/s is inside, where modes are
  // about 10 to 20 rad/s apart, so the six nearest lie within +-100 rad/s.
  options.target = Complex(0.0, 1500.0);
  const auto dense = solve_quadratic(p, options);
  options.method = Method::Sparse;
  const auto sparse = solve_quadratic(p, options);
  ASSERT_EQ(dense.status, Status::Ok) << dense.brief_report();
  ASSERT_EQ(sparse.status, Status::Ok) << sparse.brief_report();
  EXPECT_EQ(sparse.factorization, "umfpack_lu_complex");
  ASSERT_EQ(sparse.eigenvalues.size(), 6);
  for (int j = 0; j < 6; ++j) {
    expect_close(sparse.eigenvalues[j], dense.eigenvalues[j], 1e-9, "mode " + std::to_string(j));
    EXPECT_NEAR(sparse.eigenvalues[j].imag(), 1500.0, 100.0);  // near the target
  }
}

TEST(QuadraticEigen, StartVectorFromNeighbouringSolveGivesTheSameModes) {
  const auto p0 = gyroscopic_chain(200, 2000.0);
  const auto p1 = gyroscopic_chain(200, 2100.0);
  QuadraticEigenOptions options;
  options.n_modes = 8;
  options.method = Method::Sparse;
  const auto r0 = solve_quadratic(p0, options);
  const auto cold = solve_quadratic(p1, options);
  options.start = start_vector(r0);
  ASSERT_EQ(options.start.size(), 800);
  const auto warm = solve_quadratic(p1, options);
  ASSERT_EQ(cold.status, Status::Ok);
  ASSERT_EQ(warm.status, Status::Ok);
  for (int j = 0; j < 8; ++j)
    expect_close(warm.eigenvalues[j], cold.eigenvalues[j], 1e-9, "mode " + std::to_string(j));
}

TEST(QuadraticEigen, InvalidInputThrows) {
  QuadraticPencil p;
  p.M = diagonal_matrix(3, 1.0);
  p.K = diagonal_matrix(3, 1.0);
  p.C.resize(2, 2);  // wrong size
  EXPECT_THROW(solve_quadratic(p, {}), InputError);
  p.C.resize(3, 3);
  QuadraticEigenOptions bad;
  bad.n_modes = -1;
  EXPECT_THROW(solve_quadratic(p, bad), InputError);
}

}  // namespace
}  // namespace geardyn::eig
