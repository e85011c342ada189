// Validation of the eigen-solvers against closed-form results: spring-mass chains (symmetric,
// dense and sparse, 2000 DOFs), damped SDOF / 2DOF roots including overdamped ones, the Jeffcott
// rotor, a gyroscopic disk, and modal (low-rank) damping.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "eig/test_systems.hpp"
#include "geardyn/eig/quadratic_eigen.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"

namespace geardyn::eig {
namespace {

using Complex = std::complex<double>;
using test::chain_stiffness;
using test::diagonal_matrix;
using test::expect_close;
using test::fixed_chain_lambda;
using test::free_chain_lambda;
using test::pencil;
using test::sdof_roots;

// Tolerance for the 2000-DOF chain: a backward-stable solver gives absolute eigenvalue errors of
// about eps * ||K|| / m = 2.2e-16 * 4 k/m; relative to lambda_1 = 4 k/m sin^2(pi/4002)
// (= 6.2e-7 k/m) that is 1.4e-9. 1e-8 leaves a factor 7 for accumulated rounding.
constexpr double kChainTolerance = 1e-8;

TEST(SymmetricEigen, SparseChain2000MatchesAnalytic) {
  const int N = 2000;
  const double k = 1e6, m = 0.5;
  const auto K = chain_stiffness(N, k, true);
  const auto M = diagonal_matrix(N, m);
  SymmetricEigenOptions options;
  options.n_modes = 12;
  const auto r = solve_symmetric(K, M, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  EXPECT_EQ(r.method_used, Method::Sparse);
  EXPECT_EQ(r.factorization, "cholmod_cholesky");
  ASSERT_EQ(r.eigenvalues.size(), 12);
  for (int j = 1; j <= 12; ++j) {
    const double exact = fixed_chain_lambda(j, N, k, m);
    EXPECT_NEAR(r.eigenvalues[j - 1], exact, kChainTolerance * exact) << "mode " << j;
  }
  // Lanczos stops when the Ritz residual is below tol |theta| of the inverted problem, which
  // bounds the backward error of the original pencil by about tol.
  EXPECT_LT(r.max_residual(), options.krylov.tolerance);
  EXPECT_EQ(r.factorizations, 1);
  EXPECT_GT(r.operations, 0);
}

TEST(SymmetricEigen, DenseAndSparseAgreeOnChain2000) {
  const int N = 2000;
  const double k = 1e6, m = 0.5;
  const auto K = chain_stiffness(N, k, true);
  const auto M = diagonal_matrix(N, m);
  SymmetricEigenOptions options;
  options.n_modes = 8;
  options.method = Method::Dense;
  const auto dense = solve_symmetric(K, M, options);
  options.method = Method::Sparse;
  const auto sparse = solve_symmetric(K, M, options);
  ASSERT_EQ(dense.status, Status::Ok) << dense.brief_report();
  ASSERT_EQ(sparse.status, Status::Ok) << sparse.brief_report();
  EXPECT_EQ(dense.method_used, Method::Dense);
  for (int j = 0; j < 8; ++j) {
    const double exact = fixed_chain_lambda(j + 1, N, k, m);
    EXPECT_NEAR(dense.eigenvalues[j], exact, kChainTolerance * exact) << "dense mode " << j + 1;
    EXPECT_NEAR(dense.eigenvalues[j], sparse.eigenvalues[j], kChainTolerance * exact);
    // Simple, well separated eigenvalues: the mass-normalised vectors agree up to sign, which
    // both solvers fix by the same convention. Dense: vector error ~ eps ||K|| / gap ~ 1e-9;
    // Lanczos: Ritz residual < tol |theta| with tol = 1e-10 and a relative gap of the inverted
    // eigenvalues >= 0.2 for these modes, so ~5e-10. 1e-6 is a safe bound for both.
    const double diff = (dense.eigenvectors.col(j) - sparse.eigenvectors.col(j)).norm() /
                        dense.eigenvectors.col(j).norm();
    EXPECT_LT(diff, 1e-6) << "mode " << j + 1;
  }
  EXPECT_LT(dense.max_residual(), 1e-12);
}

TEST(SymmetricEigen, FreeFreeChainFindsRigidBodyModeFirst) {
  for (Method method : {Method::Dense, Method::Sparse}) {
    const int N = 300;
    const double k = 1e4, m = 2.0;
    const auto K = chain_stiffness(N, k, false);  // singular: rigid-body translation
    const auto M = diagonal_matrix(N, m);
    SymmetricEigenOptions options;
    options.n_modes = 5;
    options.method = method;
    const auto r = solve_symmetric(K, M, options);
    ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
    ASSERT_EQ(r.eigenvalues.size(), 5);
    // Rigid-body eigenvalue: zero up to rounding of ||K|| = 4 k.
    EXPECT_LT(std::abs(r.eigenvalues[0]), 1e-9 * 4.0 * k / m) << to_string(method);
    for (int j = 1; j < 5; ++j) {
      const double exact = free_chain_lambda(j, N, k, m);
      EXPECT_NEAR(r.eigenvalues[j], exact, 1e-8 * exact) << to_string(method) << " mode " << j;
    }
    if (method == Method::Sparse) {
      EXPECT_LT(r.shift_used, 0.0);  // automatic shift slightly negative
      EXPECT_EQ(r.factorization, "cholmod_cholesky");
    }
  }
}

// Single DOF  m x'' + c x' + k x = 0 with m = 2 kg, c = 0.8 N s/m, k = 50 N/m (zeta = 0.04):
// lambda = (-c +- sqrt(c^2 - 4 m k)) / (2 m) = -0.2 +- 4.99599840 i. Exact up to rounding, so
// the tolerance is a few hundred eps.
TEST(QuadraticEigen, UnderdampedSdofMatchesQuadraticFormula) {
  const double m = 2.0, c = 0.8, k = 50.0;
  const auto p = pencil(Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, c),
                        Eigen::MatrixXd::Constant(1, 1, k));
  QuadraticEigenOptions options;
  options.n_modes = 1;
  const auto r = solve_quadratic(p, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  ASSERT_EQ(r.eigenvalues.size(), 1);
  expect_close(r.eigenvalues[0], sdof_roots(m, c, k).first, 1e-13, "lambda");
  EXPECT_NEAR(damping_ratio(r.eigenvalues[0]), c / (2.0 * std::sqrt(k * m)), 1e-13);
  EXPECT_NEAR(natural_frequency(r.eigenvalues[0]), std::sqrt(k / m), 1e-12);
  EXPECT_LT(r.max_residual(), 1e-14);
}

// Overdamped single DOF m = 1, c = 10, k = 9: roots -1 and -9, both real and both reported
// (each real root is a mode of its own; its damping ratio -Re/|lambda| is 1).
TEST(QuadraticEigen, OverdampedSdofReportsBothRealRoots) {
  const auto p = pencil(Eigen::MatrixXd::Constant(1, 1, 1.0), Eigen::MatrixXd::Constant(1, 1, 10.0),
                        Eigen::MatrixXd::Constant(1, 1, 9.0));
  QuadraticEigenOptions options;
  options.n_modes = 2;
  const auto r = solve_quadratic(p, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  ASSERT_EQ(r.eigenvalues.size(), 2);
  EXPECT_NEAR(r.eigenvalues[0].real(), -1.0, 1e-13);
  EXPECT_NEAR(r.eigenvalues[1].real(), -9.0, 1e-12);
  EXPECT_EQ(r.eigenvalues[0].imag(), 0.0);
  EXPECT_EQ(r.eigenvalues[1].imag(), 0.0);
  EXPECT_DOUBLE_EQ(damping_ratio(r.eigenvalues[1]), 1.0);
  // Only two roots exist; asking for three is reported.
  options.n_modes = 3;
  const auto fewer = solve_quadratic(p, options);
  EXPECT_EQ(fewer.status, Status::FewerModes);
  EXPECT_EQ(fewer.converged, 2);
}

// Two DOF with stiffness-proportional damping C = beta K (Rayleigh, Theory of Sound, 1877,
// sec. 97: proportional damping keeps the undamped modes, so each mode is an SDOF):
//   M = I, K = k [2 -1; -1 2]  -> omega_1^2 = k, omega_2^2 = 3 k;  zeta_j = beta omega_j / 2.
// k = 100, beta = 0.15: zeta_1 = 0.75 (underdamped pair), zeta_2 = 1.299 (two real roots).
TEST(QuadraticEigen, ProportionallyDampedTwoDofWithAnOverdampedMode) {
  const double k = 100.0, beta = 0.15;
  Eigen::MatrixXd K(2, 2);
  K << 2 * k, -k, -k, 2 * k;
  const auto p = pencil(Eigen::MatrixXd::Identity(2, 2), beta * K, K);
  QuadraticEigenOptions options;
  options.n_modes = 3;
  const auto r = solve_quadratic(p, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  ASSERT_EQ(r.eigenvalues.size(), 3);
  const auto [a1, b1] = sdof_roots(1.0, beta * k, k);          // mode 1: complex pair
  const auto [a2, b2] = sdof_roots(1.0, beta * 3 * k, 3 * k);  // mode 2: two real roots
  std::vector<Complex> exact = {a1, a2, b2};
  std::sort(exact.begin(), exact.end(),
            [](Complex x, Complex y) { return std::abs(x) < std::abs(y); });
  for (int j = 0; j < 3; ++j) expect_close(r.eigenvalues[j], exact[j], 1e-12, "root");
  EXPECT_NEAR(damping_ratio(a1), 0.75, 1e-12);
  EXPECT_LT(r.max_residual(), 1e-14);
}

// Jeffcott rotor without disk tilt (x, y of a point mass on an isotropic shaft):
// m = 10 kg, k = 1e6 N/m, zeta = 0.02 -> omega_n = sqrt(k/m) = 316.227766 rad/s, and
// lambda = -zeta omega_n +- i omega_n sqrt(1 - zeta^2), twice (x and y).
// (Friswell, Penny, Garvey & Lees, Dynamics of Rotating Machines, CUP 2010, sec. 2.x / 3.3.)
TEST(QuadraticEigen, JeffcottRotorDoubleRoot) {
  const double m = 10.0, k = 1e6, zeta = 0.02;
  const double c = 2.0 * zeta * std::sqrt(k * m);
  const auto p = pencil(m * Eigen::MatrixXd::Identity(2, 2), c * Eigen::MatrixXd::Identity(2, 2),
                        k * Eigen::MatrixXd::Identity(2, 2));
  QuadraticEigenOptions options;
  options.n_modes = 2;
  const auto r = solve_quadratic(p, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  ASSERT_EQ(r.eigenvalues.size(), 2);
  const double wn = 316.2277660168379;
  const Complex exact(-zeta * wn, wn * std::sqrt(1.0 - zeta * zeta));
  for (int j = 0; j < 2; ++j) {
    expect_close(r.eigenvalues[j], exact, 1e-13, "Jeffcott");
    EXPECT_NEAR(natural_frequency(r.eigenvalues[j]), wn, 1e-9);
    EXPECT_NEAR(damping_ratio(r.eigenvalues[j]), zeta, 1e-13);
  }
  // The two shapes span the (x, y) plane: the double root keeps both.
  EXPECT_GT(std::abs(r.eigenvectors.determinant()), 1e-6);
}

// Rigid disk tilting on an isotropic angular spring, spinning at Omega (Friswell et al. 2010,
// sec. 3.5; derivation here): with theta_x, theta_y
//   Id th_x'' + Ip Omega th_y' + kt th_x = 0,   Id th_y'' - Ip Omega th_x' + kt th_y = 0.
// lambda = i w: (kt - Id w^2)^2 = (Ip Omega w)^2, i.e. Id w^2 -+ Ip Omega w - kt = 0:
//   w_fwd = ( Ip Omega + sqrt((Ip Omega)^2 + 4 Id kt)) / (2 Id)
//   w_bwd = (-Ip Omega + sqrt((Ip Omega)^2 + 4 Id kt)) / (2 Id).
TEST(QuadraticEigen, GyroscopicDiskSplitsIntoForwardAndBackward) {
  const double Id = 0.02, Ip = 0.035, kt = 4e4, Omega = 800.0;
  Eigen::MatrixXd G(2, 2);
  G << 0.0, Ip, -Ip, 0.0;
  const auto p =
      pencil(Id * Eigen::MatrixXd::Identity(2, 2), Omega * G, kt * Eigen::MatrixXd::Identity(2, 2));
  QuadraticEigenOptions options;
  options.n_modes = 2;
  const auto r = solve_quadratic(p, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  const double a = Ip * Omega, root = std::sqrt(a * a + 4.0 * Id * kt);
  const double w_bwd = (-a + root) / (2.0 * Id), w_fwd = (a + root) / (2.0 * Id);
  EXPECT_NEAR(r.eigenvalues[0].imag(), w_bwd, 1e-12 * w_fwd);
  EXPECT_NEAR(r.eigenvalues[1].imag(), w_fwd, 1e-12 * w_fwd);
  EXPECT_NEAR(r.eigenvalues[0].real(), 0.0, 1e-12 * w_fwd);  // undamped: purely imaginary
}

// Modal damping as a low-rank term: with B = M Phi (mass-normalised undamped modes) and
// c_r = 2 zeta_r omega_r, D = B diag(c) B^T is diagonal in modal coordinates, so mode r is an
// SDOF with exactly zeta_r and modes without a coefficient stay undamped. The chain's omega_r
// are analytic (test_systems.hpp). Sparse path: the Woodbury update must reproduce this.
TEST(QuadraticEigen, LowRankModalDampingGivesTheRequestedRatios) {
  const int N = 500;
  const double k = 1e6, m = 0.5;
  QuadraticPencil p;
  p.K = chain_stiffness(N, k, true);
  p.M = diagonal_matrix(N, m);
  p.C.resize(N, N);
  SymmetricEigenOptions sym;
  sym.n_modes = 10;
  const auto undamped = solve_symmetric(p.K, p.M, sym);
  ASSERT_EQ(undamped.status, Status::Ok);
  p.low_rank_basis = p.M * undamped.eigenvectors;
  p.low_rank_coefficients.resize(10);
  for (int r = 0; r < 10; ++r)
    p.low_rank_coefficients[r] = 2.0 * (0.01 * (r + 1)) * std::sqrt(undamped.eigenvalues[r]);
  QuadraticEigenOptions options;
  options.n_modes = 12;
  const auto res = solve_quadratic(p, options);
  ASSERT_EQ(res.status, Status::Ok) << res.brief_report();
  EXPECT_EQ(res.method_used, Method::Sparse);
  ASSERT_EQ(res.eigenvalues.size(), 12);
  for (int r = 0; r < 12; ++r) {
    const double s = std::sin((r + 1) * std::numbers::pi / (2.0 * (N + 1)));
    const double wn = 2.0 * std::sqrt(k / m) * s;
    const double zeta = r < 10 ? 0.01 * (r + 1) : 0.0;
    // |lambda| = omega_r to Lanczos/Arnoldi accuracy (~1e-10); zeta absolute to 1e-9.
    EXPECT_NEAR(natural_frequency(res.eigenvalues[r]), wn, 1e-8 * wn) << "mode " << r + 1;
    EXPECT_NEAR(damping_ratio(res.eigenvalues[r]), zeta, 1e-9) << "mode " << r + 1;
  }
}

}  // namespace
}  // namespace geardyn::eig
