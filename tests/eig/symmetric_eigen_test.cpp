// Real symmetric generalised eigenproblem K phi = lambda M phi: the eigen equation's residual,
// mass orthonormality, shift and band selection, massless DOFs, option checks and reporting.
// (Analytic references: eigen_validation_test.cpp.)
#include "geardyn/eig/symmetric_eigen.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "eig/test_systems.hpp"
#include "geardyn/core/error.hpp"

namespace geardyn::eig {
namespace {

using test::chain_stiffness;
using test::diagonal_matrix;

using test::fixed_chain_lambda;
using test::free_chain_lambda;

TEST(SymmetricEigen, ModesAreMassOrthonormalAndSatisfyTheEigenEquation) {
  const int N = 600;  // sparse by default (> dense_limit)
  const double k = 2e5, m = 1.5;
  const auto K = chain_stiffness(N, k, true);
  const auto M = diagonal_matrix(N, m);
  SymmetricEigenOptions options;
  options.n_modes = 6;
  const auto r = solve_symmetric(K, M, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  const Eigen::MatrixXd gram = r.eigenvectors.transpose() * (M * r.eigenvectors);
  EXPECT_LT((gram - Eigen::MatrixXd::Identity(6, 6)).cwiseAbs().maxCoeff(), 1e-10);
  for (int j = 0; j < 6; ++j) {
    const Eigen::VectorXd phi = r.eigenvectors.col(j);
    const Eigen::VectorXd res = K * phi - r.eigenvalues[j] * (M * phi);
    // Relative to the size of the terms, not the backward error: the defining equation itself.
    // The Lanczos stopping test is ||Op y - theta y||_M <= tol |theta| (tol = 1e-10) on the
    // inverted operator; mapped back to the pencil, the residual relative to ||K phi|| can grow
    // like lambda_max / lambda_j, about 4e3 for mode 6 of this chain (bound 4e-7; 1e-8
    // observed). The normwise backward error stays below 1e-11 (2.5e-12 observed).
    EXPECT_LT(res.norm() / (K * phi).norm(), 1e-7) << "mode " << j + 1;
    EXPECT_LT(r.residuals[j], 1e-11) << "backward error, mode " << j + 1;
  }
}

// Two identical, uncoupled fixed chains: every eigenvalue is exactly double. Single-vector
// Lanczos finds one copy in exact arithmetic; the block engine (p = 4 >= 2) must return both,
// each equal to the analytic lambda_j of test_systems.hpp to 1e-10 relative (tolerance 1e-10
// of the inverted operator's Ritz values, conditioning ~1 for the lowest modes).
TEST(SymmetricEigen, BlockEngineReturnsBothCopiesOfDoubleEigenvalues) {
  const int N = 400;
  const double k = 1e6, m = 2.0;
  const auto chain = chain_stiffness(N, k, true);
  Eigen::SparseMatrix<double> K(2 * N, 2 * N);
  std::vector<Eigen::Triplet<double>> t;
  for (int copy = 0; copy < 2; ++copy)
    for (int j = 0; j < chain.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(chain, j); it; ++it)
        t.emplace_back(copy * N + it.row(), copy * N + it.col(), it.value());
  K.setFromTriplets(t.begin(), t.end());
  const auto M = diagonal_matrix(2 * N, m);
  SymmetricEigenOptions options;
  options.n_modes = 10;
  const auto r = solve_symmetric(K, M, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  ASSERT_EQ(r.eigenvalues.size(), 10);
  for (int j = 1; j <= 5; ++j) {
    const double exact = fixed_chain_lambda(j, N, k, m);
    EXPECT_NEAR(r.eigenvalues[2 * j - 2], exact, 1e-10 * exact) << "first copy, j = " << j;
    EXPECT_NEAR(r.eigenvalues[2 * j - 1], exact, 1e-10 * exact) << "second copy, j = " << j;
  }
  // The two copies span the eigenspace: M-orthonormal, so not the same vector twice.
  const Eigen::MatrixXd gram = r.eigenvectors.transpose() * (M * r.eigenvectors);
  EXPECT_LT((gram - Eigen::MatrixXd::Identity(10, 10)).cwiseAbs().maxCoeff(), 1e-10);
}

// The block engine against the independent Spectra engine on a free-free chain (one rigid-body
// mode): the same 12 eigenvalues to 1e-9 relative to the largest (both converge their Ritz
// values to 1e-10 relative).
TEST(SymmetricEigen, BlockAndSpectraEnginesAgree) {
  const int N = 900;
  const auto K = chain_stiffness(N, 3e5, false);
  const auto M = diagonal_matrix(N, 0.7);
  SymmetricEigenOptions options;
  options.n_modes = 12;
  const auto block = solve_symmetric(K, M, options);
  options.engine = KrylovEngine::Spectra;
  const auto spectra = solve_symmetric(K, M, options);
  ASSERT_EQ(block.status, Status::Ok) << block.brief_report();
  ASSERT_EQ(spectra.status, Status::Ok) << spectra.brief_report();
  ASSERT_EQ(block.eigenvalues.size(), 12);
  ASSERT_EQ(spectra.eigenvalues.size(), 12);
  const double scale = spectra.eigenvalues.maxCoeff();
  EXPECT_LT((block.eigenvalues - spectra.eigenvalues).cwiseAbs().maxCoeff(), 1e-9 * scale);
  EXPECT_NEAR(block.eigenvalues[5], free_chain_lambda(5, N, 3e5, 0.7), 1e-9 * scale);
}

TEST(SymmetricEigen, ShiftSelectsNearestModesAndUsesLUWhenIndefinite) {
  const int N = 500;
  const double k = 1e6, m = 1.0;
  const auto K = chain_stiffness(N, k, true);
  const auto M = diagonal_matrix(N, m);
  // Shift between analytic modes 40 and 41: K - sigma M is indefinite, so LU is used.
  const double sigma = 0.5 * (fixed_chain_lambda(40, N, k, m) + fixed_chain_lambda(41, N, k, m));
  SymmetricEigenOptions options;
  options.n_modes = 4;
  options.shift = sigma;
  const auto r = solve_symmetric(K, M, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  EXPECT_EQ(r.factorization, "umfpack_lu");
  ASSERT_EQ(r.eigenvalues.size(), 4);
  for (int j = 0; j < 4; ++j) {
    const double exact = fixed_chain_lambda(39 + j, N, k, m);
    EXPECT_NEAR(r.eigenvalues[j], exact, 1e-9 * exact) << "mode " << 39 + j;
  }
}

TEST(SymmetricEigen, BandReturnsEveryEigenvalueInside) {
  const int N = 800;
  const double k = 1e6, m = 1.0;
  const auto K = chain_stiffness(N, k, true);
  const auto M = diagonal_matrix(N, m);
  // Band from just below mode 10 to just above mode 55: 46 modes, more than the first guess.
  const double lo = 0.999 * fixed_chain_lambda(10, N, k, m);
  const double hi = 1.001 * fixed_chain_lambda(55, N, k, m);
  SymmetricEigenOptions options;
  options.n_modes = 8;
  options.band_min = lo;
  options.band_max = hi;
  const auto r = solve_symmetric(K, M, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  ASSERT_EQ(r.eigenvalues.size(), 46);
  for (int j = 0; j < 46; ++j) {
    const double exact = fixed_chain_lambda(10 + j, N, k, m);
    EXPECT_NEAR(r.eigenvalues[j], exact, 1e-9 * exact);
  }
  // Dense agrees on the count.
  options.method = Method::Dense;
  EXPECT_EQ(solve_symmetric(K, M, options).eigenvalues.size(), 46);
}

TEST(SymmetricEigen, MasslessDofIsCondensedByTheDenseSolver) {
  // (m)--k1--(massless)--k2--|  : the massless node is static, k_eff = k1 k2 / (k1 + k2),
  // so the only finite eigenvalue is k_eff / m.
  const double m = 3.0, k1 = 2e4, k2 = 6e4;
  Eigen::SparseMatrix<double> K(2, 2), M(2, 2);
  K.insert(0, 0) = k1;
  K.insert(0, 1) = -k1;
  K.insert(1, 0) = -k1;
  K.insert(1, 1) = k1 + k2;
  M.insert(0, 0) = m;
  SymmetricEigenOptions options;
  options.n_modes = 1;
  const auto r = solve_symmetric(K, M, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  ASSERT_EQ(r.eigenvalues.size(), 1);
  const double exact = k1 * k2 / (k1 + k2) / m;
  EXPECT_NEAR(r.eigenvalues[0], exact, 1e-12 * exact);
  EXPECT_EQ(r.factorization, "dense_cholesky_of_K_minus_sigma_M");
  // Asking for both: only one mode exists, which is reported, not hidden.
  options.n_modes = 2;
  const auto fewer = solve_symmetric(K, M, options);
  EXPECT_EQ(fewer.status, Status::FewerModes);
  EXPECT_FALSE(fewer.message.empty());
}

TEST(SymmetricEigen, NonSymmetricStiffnessIsSymmetrisedAndReported) {
  auto K = chain_stiffness(50, 1e3, true);
  K.coeffRef(0, 1) += 10.0;  // cross-coupling term
  const auto M = diagonal_matrix(50, 1.0);
  const auto r = solve_symmetric(K, M, {});
  EXPECT_EQ(r.status, Status::Ok);
  EXPECT_GT(r.asymmetry, 0.0);
}

TEST(SymmetricEigen, InvalidOptionsThrowInputError) {
  const auto K = chain_stiffness(10, 1.0, true);
  const auto M = diagonal_matrix(10, 1.0);
  SymmetricEigenOptions bad;
  bad.n_modes = 0;
  bad.band_min = 1.0;  // band_max missing
  try {
    solve_symmetric(K, M, bad);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("n_modes"), std::string::npos) << what;
    EXPECT_NE(what.find("band_max"), std::string::npos) << what;
  }
  EXPECT_THROW(solve_symmetric(K, diagonal_matrix(9, 1.0), {}), InputError);
}

TEST(SymmetricEigen, FewerModesThanAskedIsReported) {
  const auto K = chain_stiffness(5, 1.0, true);
  const auto M = diagonal_matrix(5, 1.0);
  SymmetricEigenOptions options;
  options.n_modes = 8;
  const auto r = solve_symmetric(K, M, options);
  EXPECT_EQ(r.status, Status::FewerModes);
  EXPECT_EQ(r.converged, 5);
  EXPECT_EQ(r.requested, 8);
  EXPECT_NE(r.message.find("5"), std::string::npos);
}

}  // namespace
}  // namespace geardyn::eig
