// Banded LU with RCM ordering (linalg/banded_lu.hpp) against dense Gaussian elimination and
// against matrices whose bandwidth is known in closed form.
#include "geardyn/linalg/banded_lu.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <numeric>
#include <random>

namespace {

using geardyn::Status;
using geardyn::linalg::BandedLU;
using Complex = std::complex<double>;
using SparseC = Eigen::SparseMatrix<Complex>;

// Random symmetric renumbering q[old] of 0..n-1 (fixed seed: the test is deterministic).
std::vector<int> shuffled(int n, unsigned seed) {
  std::vector<int> q(static_cast<std::size_t>(n));
  std::iota(q.begin(), q.end(), 0);
  std::mt19937 rng(seed);
  std::shuffle(q.begin(), q.end(), rng);
  return q;
}

// A chain of `blocks` nodes with `dofs` unknowns each, every node coupled to the next (the
// pattern of a shaft line), values random complex, diagonal zero where `zero_diagonal` (so
// that partial pivoting must interchange rows), renumbered by a random permutation.
SparseC chain(int blocks, int dofs, bool zero_diagonal, unsigned seed) {
  const int n = blocks * dofs;
  const std::vector<int> q = shuffled(n, seed);
  std::mt19937 rng(seed + 1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<Complex>> t;
  for (int b = 0; b < blocks; ++b)
    for (int i = 0; i < dofs; ++i)
      for (int j = 0; j < 2 * dofs && b * dofs + j < n; ++j) {
        const int row = b * dofs + i, col = b * dofs + j;
        for (auto [r, c] : {std::pair{row, col}, std::pair{col, row}}) {
          if (zero_diagonal && r == c) continue;
          t.emplace_back(q[static_cast<std::size_t>(r)], q[static_cast<std::size_t>(c)],
                         Complex(u(rng), u(rng)));
        }
      }
  SparseC A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

// Out of line: GCC 12's -Wnull-dereference misfires on Eigen's sparse-to-dense conversion when
// it is inlined into a test body. Returns the normwise backward error of x for A x = b and the
// relative difference of x from the dense partial-pivoting LU solution.
[[gnu::noinline]] std::pair<double, double> dense_check(const SparseC& A, const Eigen::VectorXcd& x,
                                                        const Eigen::VectorXcd& b) {
  const Eigen::MatrixXcd dense = Eigen::MatrixXcd(A);
  const Eigen::VectorXcd x_dense = dense.partialPivLu().solve(b);
  const double scale = dense.cwiseAbs().rowwise().sum().maxCoeff() * x.cwiseAbs().maxCoeff();
  return {(dense * x - b).cwiseAbs().maxCoeff() / scale, (x - x_dense).norm() / x_dense.norm()};
}

TEST(ReverseCuthillMcKee, RecoversTheBandOfAShuffledPath) {
  // A path graph has bandwidth 1 in its natural order, and RCM from a peripheral vertex of a
  // path numbers it along the path (George & Liu 1981, ch. 4), so the bandwidth is exactly 1.
  const int n = 500;
  const std::vector<int> q = shuffled(n, 7);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(q[static_cast<std::size_t>(i)], q[static_cast<std::size_t>(i)], 2.0);
    if (i + 1 < n) {
      t.emplace_back(q[static_cast<std::size_t>(i)], q[static_cast<std::size_t>(i) + 1], -1.0);
      t.emplace_back(q[static_cast<std::size_t>(i) + 1], q[static_cast<std::size_t>(i)], -1.0);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  const auto perm = geardyn::linalg::reverse_cuthill_mckee(n, A.outerIndexPtr(), A.innerIndexPtr());
  std::vector<int> sorted = perm;
  std::sort(sorted.begin(), sorted.end());
  for (int k = 0; k < n; ++k) ASSERT_EQ(sorted[static_cast<std::size_t>(k)], k);
  const auto [kl, ku] = geardyn::linalg::bandwidths(n, A.outerIndexPtr(), A.innerIndexPtr(), perm);
  EXPECT_EQ(kl, 1);
  EXPECT_EQ(ku, 1);
}

TEST(BandedLU, SolvesAShuffledChainLikeDenseElimination) {
  // 100 nodes x 4 unknowns coupled to the next node: the natural order has half-bandwidth
  // 2 x 4 - 1 = 7, so RCM must find a band no wider than that; zero diagonal forces pivoting.
  const SparseC A = chain(100, 4, true, 3);
  const int n = static_cast<int>(A.rows());
  BandedLU lu;
  lu.analyze(n, A.outerIndexPtr(), A.innerIndexPtr());
  EXPECT_LE(lu.lower_bandwidth(), 7);
  EXPECT_LE(lu.upper_bandwidth(), 7);
  ASSERT_EQ(lu.factorize(A.valuePtr()), Status::Ok);

  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXcd x_true(n);
  for (int i = 0; i < n; ++i) x_true[i] = Complex(u(rng), u(rng));
  const Eigen::VectorXcd b = A * x_true;
  Eigen::VectorXcd x(n), work(n);
  lu.solve(b.data(), x.data(), work.data());
  const auto [backward, difference] = dense_check(A, x, b);
  // Gaussian elimination with partial pivoting is backward stable: the residual is a small
  // multiple of eps |A| |x| (growth factors of random matrices stay below ~10, n = 400 gives
  // a few hundred eps at most), so 1e-12 relative to |A| |x| has a wide margin.
  EXPECT_LT(backward, 1e-12);
  // The same system by dense LU: both solutions agree to the conditioning times round-off.
  EXPECT_LT(difference, 1e-8);
  // In-place solve (b and x the same array) gives the same numbers.
  Eigen::VectorXcd y = b;
  lu.solve(y.data(), y.data(), work.data());
  EXPECT_EQ((y - x).cwiseAbs().maxCoeff(), 0.0);
}

TEST(BandedLU, RefactorWithNewValuesMatchesAFreshAnalysis) {
  // Same pattern, new values: factorize() reuses the ordering and storage; the result must be
  // bit-identical to a factor analysed afresh (the elimination is deterministic).
  const SparseC A = chain(50, 6, false, 5);
  SparseC B = A;
  for (int k = 0; k < B.nonZeros(); ++k) B.valuePtr()[k] *= Complex(0.5, 0.25 * (k % 3));
  const int n = static_cast<int>(A.rows());
  BandedLU reused, fresh;
  reused.analyze(n, A.outerIndexPtr(), A.innerIndexPtr());
  ASSERT_EQ(reused.factorize(A.valuePtr()), Status::Ok);
  ASSERT_EQ(reused.factorize(B.valuePtr()), Status::Ok);
  fresh.analyze(n, B.outerIndexPtr(), B.innerIndexPtr());
  ASSERT_EQ(fresh.factorize(B.valuePtr()), Status::Ok);
  const Eigen::VectorXcd b = Eigen::VectorXcd::Ones(n);
  Eigen::VectorXcd x1(n), x2(n), work(n);
  reused.solve(b.data(), x1.data(), work.data());
  fresh.solve(b.data(), x2.data(), work.data());
  EXPECT_EQ((x1 - x2).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(reused.pivot_ratio(), fresh.pivot_ratio());
}

TEST(BandedLU, ReportsAZeroColumnAsSingular) {
  // A column of exact zeros leaves no pivot: the factor is singular by construction.
  SparseC A = chain(20, 3, false, 9);
  for (SparseC::InnerIterator it(A, 5); it; ++it) it.valueRef() = 0.0;
  BandedLU lu;
  lu.analyze(static_cast<int>(A.rows()), A.outerIndexPtr(), A.innerIndexPtr());
  EXPECT_EQ(lu.factorize(A.valuePtr()), Status::Singular);
  EXPECT_EQ(lu.pivot_ratio(), 0.0);
}

TEST(BandedLU, WideBandTakesTheGenericKernelAndMatchesDense) {
  // 10 unknowns per node: half-bandwidth about 19, above the unrolled kernels (kl <= 16), so
  // the generic elimination runs; the same backward-stability bounds as above apply.
  const SparseC A = chain(30, 10, true, 21);
  const int n = static_cast<int>(A.rows());
  BandedLU lu;
  lu.analyze(n, A.outerIndexPtr(), A.innerIndexPtr());
  ASSERT_GT(lu.lower_bandwidth(), 16);
  ASSERT_EQ(lu.factorize(A.valuePtr()), Status::Ok);
  const Eigen::VectorXcd b = Eigen::VectorXcd::LinSpaced(n, 1.0, 2.0);
  Eigen::VectorXcd x(n), work(n);
  lu.solve(b.data(), x.data(), work.data());
  const auto [backward, difference] = dense_check(A, x, b);
  EXPECT_LT(backward, 1e-12);
  EXPECT_LT(difference, 1e-8);
}

TEST(BandedLU, GivenRowSumsReproduceTheOwnScalingBitForBit) {
  // factorize(values, row_sums) with the absolute row sums summed in the pattern's order must
  // give the same factor as factorize(values), which sums them itself in that order.
  const SparseC A = chain(40, 4, true, 7);
  const int n = static_cast<int>(A.rows());
  std::vector<double> sums(static_cast<std::size_t>(n), 0.0);
  for (int k = 0; k < A.nonZeros(); ++k) {
    const Complex z = A.valuePtr()[k];
    sums[static_cast<std::size_t>(A.innerIndexPtr()[k])] +=
        std::sqrt(z.real() * z.real() + z.imag() * z.imag());
  }
  BandedLU own, given;
  own.analyze(n, A.outerIndexPtr(), A.innerIndexPtr());
  given.analyze(n, A.outerIndexPtr(), A.innerIndexPtr());
  ASSERT_EQ(own.factorize(A.valuePtr()), Status::Ok);
  ASSERT_EQ(given.factorize(A.valuePtr(), sums.data()), Status::Ok);
  const Eigen::VectorXcd b = Eigen::VectorXcd::Ones(n);
  Eigen::VectorXcd x1(n), x2(n), work(n);
  own.solve(b.data(), x1.data(), work.data());
  given.solve(b.data(), x2.data(), work.data());
  EXPECT_EQ((x1 - x2).cwiseAbs().maxCoeff(), 0.0);
  // The pivot extremes are those of the ratio (they combine the ratios of several blocks).
  EXPECT_EQ(given.pivot_ratio(), given.smallest_pivot() / given.largest_pivot());
  EXPECT_GT(given.smallest_pivot(), 0.0);
}

TEST(BandedLU, PreparedRightHandSidesMatchSolveBitForBit) {
  // The forward substitution done during the elimination performs the operations of solve()
  // in the same order, so both give the same bits; pivoting is forced by the zero diagonal.
  const SparseC A = chain(60, 4, true, 13);
  const int n = static_cast<int>(A.rows());
  std::vector<double> sums(static_cast<std::size_t>(n), 0.0);
  for (int k = 0; k < A.nonZeros(); ++k)
    sums[static_cast<std::size_t>(A.innerIndexPtr()[k])] += std::abs(A.valuePtr()[k]);
  Eigen::MatrixXcd B(n, 2);
  B.col(0) = Eigen::VectorXcd::LinSpaced(n, 1.0, 3.0);
  B.col(1) = Eigen::VectorXcd::Zero(n);
  B(n / 2, 1) = Complex(0.0, 1.0);
  BandedLU lu;
  lu.analyze(n, A.outerIndexPtr(), A.innerIndexPtr());
  ASSERT_EQ(lu.factorize(A.valuePtr(), sums.data(), B.data(), 2), Status::Ok);
  Eigen::VectorXcd x(n), y(n), work(n);
  for (int c = 0; c < 2; ++c) {
    lu.solve(B.col(c).data(), x.data(), work.data());
    lu.solve_prepared(c, y.data(), work.data());
    EXPECT_EQ((x - y).cwiseAbs().maxCoeff(), 0.0);
    const auto [backward, difference] = dense_check(A, y, B.col(c));
    EXPECT_LT(backward, 1e-12);  // backward stable, as above
    EXPECT_LT(difference, 1e-8);
  }
  EXPECT_THROW(lu.solve_prepared(2, y.data(), work.data()), std::logic_error);
}

}  // namespace
