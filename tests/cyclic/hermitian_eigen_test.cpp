// Complex Hermitian generalised eigensolver (eig/hermitian_eigen.hpp): block shift-invert
// Lanczos against analytic spectra and against Eigen's dense solvers.
#include "geardyn/eig/hermitian_eigen.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <numbers>
#include <numeric>
#include <random>
#include <vector>

#include "geardyn/core/error.hpp"

namespace geardyn::eig {
namespace {

using Complex = std::complex<double>;
using ComplexSparse = Eigen::SparseMatrix<Complex>;
constexpr double kPi = std::numbers::pi;

// Ring of n equal masses m joined by n springs k, the closing spring carrying the Bloch phase
// phi (u_{n} = e^{i phi} u_0), the 1-DOF analogue of one nodal diameter of a cyclic structure:
//
//   ... (m)--k--(m)--k-- ... --(m)--k--[e^{i phi}](m_0) ...
//
//   K = k (2 I - S - S^H), S the cyclic shift with S(n-1, 0) = e^{i phi}, M = m I.
// u_j = e^{i theta j} with theta = (2 pi q + phi) / n closes the ring, and substitution gives
//   lambda_q = (2 k / m)(1 - cos theta) = (4 k / m) sin^2((2 pi q + phi) / (2 n)),  q = 0..n-1.
// For phi = 0, q and n - q give the same lambda: every eigenvalue but q = 0 (and q = n/2) is
// exactly double; q = 0 is the rigid-body mode lambda = 0.
ComplexSparse bloch_ring_stiffness(int n, double k, double phi) {
  std::vector<Eigen::Triplet<Complex>> t;
  const Complex closing = std::polar(1.0, phi);
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 * k);
    const int j = (i + 1) % n;
    const Complex c = (i == n - 1) ? closing : Complex(1.0);
    // coupling u_i with u_{i+1} = c u_j: -k (conj(u_i) c u_j + c.c.)
    t.emplace_back(i, j, -k * c);
    t.emplace_back(j, i, -k * std::conj(c));
  }
  ComplexSparse K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

ComplexSparse scaled_identity(int n, double value) {
  ComplexSparse D(n, n);
  D.setIdentity();
  return D * Complex(value);
}

std::vector<double> ring_lambdas(int n, double k, double m, double phi) {
  std::vector<double> out;
  for (int q = 0; q < n; ++q) {
    const double s = std::sin((2.0 * kPi * q + phi) / (2.0 * n));
    out.push_back(4.0 * k / m * s * s);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Random sparse Hermitian pencil: K = B^H B + 0.1 I (positive definite; a random triangular B
// alone is nearly singular) with B banded random upper triangular,
// M = diagonal dominant banded Hermitian. Fixed seed.
std::pair<ComplexSparse, ComplexSparse> random_pencil(int n, int bandwidth, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<Complex>> tb, tm;
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < std::min(n, i + bandwidth + 1); ++j)
      tb.emplace_back(i, j, Complex(u(rng), u(rng)));
    tm.emplace_back(i, i, Complex(2.0 + u(rng), 0.0));
    if (i + 1 < n) {
      const Complex c(0.3 * u(rng), 0.3 * u(rng));
      tm.emplace_back(i, i + 1, c);
      tm.emplace_back(i + 1, i, std::conj(c));
    }
  }
  ComplexSparse B(n, n), M(n, n);
  B.setFromTriplets(tb.begin(), tb.end());
  M.setFromTriplets(tm.begin(), tm.end());
  ComplexSparse K = ComplexSparse(B.adjoint()) * B + scaled_identity(n, 0.1);
  return {K, M};
}

void expect_m_orthonormal(const HermitianEigenResult& r, const ComplexSparse& M, double tol) {
  const Eigen::MatrixXcd G = r.eigenvectors.adjoint() * (M * r.eigenvectors);
  const Eigen::MatrixXcd I = Eigen::MatrixXcd::Identity(G.rows(), G.cols());
  EXPECT_LT((G - I).cwiseAbs().maxCoeff(), tol);
}

TEST(HermitianEigen, BlochRingMatchesClosedFormWithTwistedPhase) {
  const int n = 600;
  const double k = 1e6, m = 2.0, phi = 2.0 * kPi * 3.0 / 7.0;
  const ComplexSparse K = bloch_ring_stiffness(n, k, phi), M = scaled_identity(n, m);
  HermitianEigenOptions options;
  options.n_modes = 12;
  const HermitianEigenResult r = solve_hermitian(K, M, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  EXPECT_EQ(r.method_used, Method::Sparse);
  EXPECT_EQ(r.factorization, "cholmod_cholesky");
  const auto exact = ring_lambdas(n, k, m, phi);
  ASSERT_EQ(r.eigenvalues.size(), 12);
  for (int i = 0; i < 12; ++i)
    EXPECT_NEAR(r.eigenvalues[i], exact[static_cast<std::size_t>(i)], 1e-9 * exact[11]) << i;
  EXPECT_LT(r.max_residual(), 1e-11);
  expect_m_orthonormal(r, M, 1e-10);
}

// phi = 0: rigid-body mode at 0 and exactly double eigenvalues; every copy must be found.
TEST(HermitianEigen, FindsBothCopiesOfExactlyDoubleEigenvaluesAndTheRigidBodyMode) {
  const int n = 500;
  const double k = 1e4, m = 0.5;
  const ComplexSparse K = bloch_ring_stiffness(n, k, 0.0), M = scaled_identity(n, m);
  const auto exact = ring_lambdas(n, k, m, 0.0);  // 0, l1, l1, l2, l2, ...
  for (int block : {2, 3}) {
    HermitianEigenOptions options;
    options.n_modes = 11;
    options.block_size = block;
    const HermitianEigenResult r = solve_hermitian(K, M, options);
    ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
    ASSERT_EQ(r.eigenvalues.size(), 11);
    EXPECT_NEAR(r.eigenvalues[0], 0.0, 1e-9 * exact[10]);
    for (int i = 1; i < 11; ++i)
      EXPECT_NEAR(r.eigenvalues[i], exact[static_cast<std::size_t>(i)], 1e-9 * exact[10])
          << "block " << block << " mode " << i;
    // the two copies span the eigenspace: M-orthonormal, hence independent
    expect_m_orthonormal(r, M, 1e-10);
    // backward error ~ krylov.tolerance (1e-10) times the conditioning of K - sigma M
    EXPECT_LT(r.max_residual(), 1e-10);
  }
}

TEST(HermitianEigen, SparseMatchesDenseOnRandomPencils) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const auto [K, M] = random_pencil(450, 3, seed);
    HermitianEigenOptions sparse_options;
    sparse_options.n_modes = 15;
    sparse_options.method = Method::Sparse;
    const HermitianEigenResult s = solve_hermitian(K, M, sparse_options);
    ASSERT_EQ(s.status, Status::Ok) << s.brief_report();
    // Reference: Eigen's dense generalised Hermitian solver (Cholesky of M + QR iteration).
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXcd> ges{Eigen::MatrixXcd(K),
                                                                         Eigen::MatrixXcd(M)};
    const Eigen::VectorXd ref = ges.eigenvalues();
    for (int i = 0; i < 15; ++i)
      EXPECT_NEAR(s.eigenvalues[i], ref[i], 1e-10 * std::abs(ref[14])) << "seed " << seed;
    EXPECT_LT(s.max_residual(), 1e-11);
    expect_m_orthonormal(s, M, 1e-10);
    // Eigenvectors agree up to phase for simple eigenvalues: |phi_s^H M phi_ref| = 1.
    for (int i = 0; i < 15; ++i) {
      const Eigen::VectorXcd ref_vec = ges.eigenvectors().col(i);
      const double overlap = std::abs(s.eigenvectors.col(i).dot(M * ref_vec)) /
                             std::sqrt(std::abs(ref_vec.dot(M * ref_vec)));
      EXPECT_NEAR(overlap, 1.0, 1e-8);
    }
  }
}

// The same pencil twice, coupled by a unitary permutation: every eigenvalue is exactly double,
// and a tight cluster lambda, lambda (1 + 1e-9) is added by a tiny perturbation of one copy.
TEST(HermitianEigen, ClusteredAndDoubleEigenvaluesOfARandomPencil) {
  const int half = 250;
  const auto [K1, M1] = random_pencil(half, 2, 7u);
  const int n = 2 * half;
  std::vector<int> perm(static_cast<std::size_t>(n));
  std::iota(perm.begin(), perm.end(), 0);
  std::mt19937 rng(11);
  std::shuffle(perm.begin(), perm.end(), rng);
  auto doubled = [&](const ComplexSparse& A, double perturb) {
    std::vector<Eigen::Triplet<Complex>> t;
    for (int copy = 0; copy < 2; ++copy)
      for (int j = 0; j < A.outerSize(); ++j)
        for (ComplexSparse::InnerIterator it(A, j); it; ++it) {
          Complex v = it.value();
          if (copy == 1) v *= 1.0 + perturb;
          t.emplace_back(perm[static_cast<std::size_t>(copy * half + it.row())],
                         perm[static_cast<std::size_t>(copy * half + it.col())], v);
        }
    ComplexSparse D(n, n);
    D.setFromTriplets(t.begin(), t.end());
    return D;
  };
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXcd> ges{Eigen::MatrixXcd(K1),
                                                                       Eigen::MatrixXcd(M1)};
  for (double perturb : {0.0, 1e-9}) {
    const ComplexSparse K = doubled(K1, perturb), M = doubled(M1, 0.0);
    HermitianEigenOptions options;
    options.n_modes = 16;
    options.method = Method::Sparse;
    const HermitianEigenResult r = solve_hermitian(K, M, options);
    ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
    for (int i = 0; i < 8; ++i) {
      const double l = ges.eigenvalues()[i];
      EXPECT_NEAR(r.eigenvalues[2 * i], l, 1e-10 * l) << perturb;
      EXPECT_NEAR(r.eigenvalues[2 * i + 1], l * (1.0 + perturb), 1e-10 * l) << perturb;
    }
    expect_m_orthonormal(r, M, 1e-10);
  }
}

TEST(HermitianEigen, BandModeAndInteriorShiftUseTheRightFactorisation) {
  const int n = 400;
  const double k = 1e4, m = 1.0, phi = 0.9;
  const ComplexSparse K = bloch_ring_stiffness(n, k, phi), M = scaled_identity(n, m);
  const auto exact = ring_lambdas(n, k, m, phi);
  // band [l5, l17] (midpoints between eigenvalues as edges)
  HermitianEigenOptions band;
  band.band_min = 0.5 * (exact[4] + exact[5]);
  band.band_max = 0.5 * (exact[17] + exact[18]);
  band.n_modes = 3;
  band.method = Method::Sparse;
  const HermitianEigenResult b = solve_hermitian(K, M, band);
  ASSERT_EQ(b.status, Status::Ok) << b.brief_report();
  ASSERT_EQ(b.eigenvalues.size(), 13);
  EXPECT_EQ(b.factorization, "umfpack_lu");  // shift inside the spectrum: indefinite
  for (int i = 0; i < 13; ++i)
    EXPECT_NEAR(b.eigenvalues[i], exact[static_cast<std::size_t>(i + 5)], 1e-9 * exact[17]);
  // count mode around an interior shift
  HermitianEigenOptions interior;
  interior.shift = exact[30];
  interior.n_modes = 4;
  interior.method = Method::Sparse;
  const HermitianEigenResult c = solve_hermitian(K, M, interior);
  ASSERT_EQ(c.status, Status::Ok) << c.brief_report();
  const Eigen::VectorXd dense = solve_hermitian(K, M,
                                                [&] {
                                                  HermitianEigenOptions o = interior;
                                                  o.method = Method::Dense;
                                                  return o;
                                                }())
                                    .eigenvalues;
  ASSERT_EQ(dense.size(), 4);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(c.eigenvalues[i], dense[i], 1e-9 * exact[30]);
}

TEST(HermitianEigen, MasslessDofsSparseAgreesWithDense) {
  auto [K, M] = random_pencil(420, 2, 5u);
  // make DOFs 0, 10, 20, ... massless
  for (int j = 0; j < M.outerSize(); ++j)
    for (ComplexSparse::InnerIterator it(M, j); it; ++it)
      if (it.row() % 10 == 0 || it.col() % 10 == 0) it.valueRef() = 0.0;
  M.prune(Complex(0.0));
  HermitianEigenOptions o;
  o.n_modes = 8;
  o.method = Method::Sparse;
  const HermitianEigenResult s = solve_hermitian(K, M, o);
  o.method = Method::Dense;
  const HermitianEigenResult d = solve_hermitian(K, M, o);
  ASSERT_EQ(s.status, Status::Ok) << s.brief_report();
  ASSERT_EQ(d.status, Status::Ok) << d.brief_report();
  EXPECT_EQ(d.factorization, "dense_cholesky_of_K_minus_sigma_M");
  for (int i = 0; i < 8; ++i)
    EXPECT_NEAR(s.eigenvalues[i], d.eigenvalues[i], 1e-9 * d.eigenvalues[7]);
  EXPECT_LT(s.max_residual(), 1e-11);
}

TEST(HermitianEigen, RestartLimitIsReportedNotHidden) {
  const int n = 2000;
  const ComplexSparse K = bloch_ring_stiffness(n, 1.0, 0.3), M = scaled_identity(n, 1.0);
  HermitianEigenOptions o;
  o.n_modes = 30;
  o.krylov.max_restarts = 1;
  o.krylov.subspace_size = 40;
  o.block_size = 1;
  const HermitianEigenResult r = solve_hermitian(K, M, o);
  EXPECT_EQ(r.status, Status::NotConverged);
  EXPECT_NE(r.message.find("max_restarts"), std::string::npos) << r.message;
  EXPECT_LT(r.converged, 30);
}

TEST(HermitianEigen, InvalidInputThrows) {
  const ComplexSparse K = bloch_ring_stiffness(10, 1.0, 0.0), M = scaled_identity(10, 1.0);
  HermitianEigenOptions o;
  o.block_size = 0;
  EXPECT_THROW(solve_hermitian(K, M, o), InputError);
  EXPECT_THROW(solve_hermitian(K, scaled_identity(9, 1.0)), InputError);
  o = {};
  o.band_min = 1.0;
  EXPECT_THROW(solve_hermitian(K, M, o), InputError);
}

}  // namespace
}  // namespace geardyn::eig
