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

// LAPACK-style estimate of 1 / cond_1(A) from a dense LU (out of line, as dense_check).
[[gnu::noinline]] double reciprocal_condition(const SparseC& A) {
  return Eigen::MatrixXcd(A).partialPivLu().rcond();
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

TEST(BandedLU, TermsReproduceTheAssembledValues) {
  // A = K - w^2 M + i (w C + G) from four real terms on one pattern, C non-zero on a few
  // entries only (a bearing, a sparse term): factorize_terms sums each entry over the dense
  // terms, then the sparse one, the values below in the terms' order; the factors then differ
  // by the rounding of that order only. Pivoting is forced by the zero diagonal of K and M.
  const SparseC pattern = chain(50, 4, false, 21);
  const int n = static_cast<int>(pattern.rows());
  const auto nnz = static_cast<std::size_t>(pattern.nonZeros());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> K(nnz), M(nnz), C(nnz, 0.0), G(nnz);
  for (std::size_t k = 0; k < nnz; ++k) {
    K[k] = u(rng);
    M[k] = k % 3 == 0 ? 0.0 : u(rng);
    G[k] = k % 2 == 0 ? 0.0 : u(rng);
  }
  for (std::size_t k = 0; k < nnz; k += 37) C[k] = u(rng);
  for (int j = 0; j < n; ++j)
    for (int k = pattern.outerIndexPtr()[j]; k < pattern.outerIndexPtr()[j + 1]; ++k)
      if (pattern.innerIndexPtr()[k] == j)
        K[static_cast<std::size_t>(k)] = M[static_cast<std::size_t>(k)] = 0.0;
  const double w = 3.0;
  SparseC A = pattern;
  for (std::size_t k = 0; k < nnz; ++k) {
    Complex z = Complex(K[k], 0.0);
    z += Complex(-w * w * M[k], 0.0);
    z += Complex(0.0, w * C[k]);
    z += Complex(0.0, G[k]);
    A.valuePtr()[k] = z;
  }
  const std::vector<Complex> weights{1.0, -w * w, Complex(0.0, w), Complex(0.0, 1.0)};
  BandedLU values, terms;
  values.analyze(n, A.outerIndexPtr(), A.innerIndexPtr());
  terms.analyze(n, A.outerIndexPtr(), A.innerIndexPtr());
  terms.set_terms({K.data(), M.data(), C.data(), G.data()});
  const Eigen::MatrixXcd B = Eigen::MatrixXcd::Ones(n, 1);
  ASSERT_EQ(values.factorize(A.valuePtr()), Status::Ok);
  ASSERT_EQ(terms.factorize_terms(weights.data(), B.data(), 1), Status::Ok);
  Eigen::VectorXcd x1(n), x2(n), work(n);
  values.solve(B.data(), x1.data(), work.data());
  terms.solve_prepared(0, x2.data(), work.data());
  // cond(A) eps (A random, n = 200: cond well below 1e6).
  EXPECT_LT((x1 - x2).cwiseAbs().maxCoeff(), 1e-10 * x1.cwiseAbs().maxCoeff());
  EXPECT_NEAR(values.pivot_ratio(), terms.pivot_ratio(), 1e-12);
  const auto [backward, difference] = dense_check(A, x2, B.col(0));
  EXPECT_LT(backward, 1e-12);  // backward stable, as above
  EXPECT_LT(difference, 1e-8);
  // The row sums are those of |Re a| + |Im a| (RCM numbering: compare as a multiset).
  std::vector<double> expected(static_cast<std::size_t>(n), 0.0);
  for (int k = 0; k < A.nonZeros(); ++k)
    expected[static_cast<std::size_t>(A.innerIndexPtr()[k])] +=
        std::abs(A.valuePtr()[k].real()) + std::abs(A.valuePtr()[k].imag());
  std::vector<double> got(terms.row_sums(), terms.row_sums() + n);
  std::sort(expected.begin(), expected.end());
  std::sort(got.begin(), got.end());
  for (std::size_t i = 0; i < got.size(); ++i)
    EXPECT_NEAR(got[i], expected[i], 1e-14 * expected[i]);
  // The pivot extremes are those of the ratio (they combine the ratios of several blocks).
  EXPECT_EQ(terms.pivot_ratio(), terms.smallest_pivot() / terms.largest_pivot());
  EXPECT_GT(terms.smallest_pivot(), 0.0);
  EXPECT_THROW(BandedLU().set_terms({K.data()}), std::logic_error);
}

TEST(BandedLU, FineBeamKeepsItsBandWithColumnScaling) {
  // Euler-Bernoulli beam, 300 elements over 1.5 m (L = 5 mm), clamped at one end: the rotation
  // stiffness 4EI/L and the coupling 6EI/L^2 differ by a factor of L, and the Schur complement of
  // a node's rotation falls below its coupling to the next node, so partial pivoting would
  // interchange every other row and fill U to kl + ku. With the columns scaled by K_ii^(-1/2)
  // and threshold pivoting the pivots stay on the diagonal (no fill), and the solution of
  // D = K (1 + i eta) - w^2 M is that of dense partial pivoting. Element matrices: Przemieniecki,
  // Theory of Matrix Structural Analysis, 1968, ch. 5 and 11.
  const int elements = 300, n = 2 * elements;
  const double length = 1.5 / elements, EI = 211e9 * 3.07e-7, rhoA = 7810 * 1.96e-3;
  const double L = length;
  const double k[4][4] = {{12, 6 * L, -12, 6 * L},
                          {6 * L, 4 * L * L, -6 * L, 2 * L * L},
                          {-12, -6 * L, 12, -6 * L},
                          {6 * L, 2 * L * L, -6 * L, 4 * L * L}};
  const double m[4][4] = {{156, 22 * L, 54, -13 * L},
                          {22 * L, 4 * L * L, 13 * L, -3 * L * L},
                          {54, 13 * L, 156, -22 * L},
                          {-13 * L, -3 * L * L, -22 * L, 4 * L * L}};
  std::vector<Eigen::Triplet<double>> tk, tm;
  for (int e = 0; e < elements; ++e)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const int r = 2 * e + a - 2, c = 2 * e + b - 2;  // node 0 clamped
        if (r < 0 || c < 0) continue;
        tk.emplace_back(r, c, EI / (L * L * L) * k[a][b]);
        tm.emplace_back(r, c, rhoA * L / 420.0 * m[a][b]);
      }
  Eigen::SparseMatrix<double> K(n, n), M(n, n);
  K.setFromTriplets(tk.begin(), tk.end());
  M.setFromTriplets(tm.begin(), tm.end());
  K.makeCompressed();
  M.makeCompressed();  // same pattern as K
  const double w = 2.0 * 3.14159265358979 * 250.0, eta = 0.01;
  BandedLU lu;
  lu.analyze(n, K.outerIndexPtr(), K.innerIndexPtr(), BandedLU::Ordering::Given);
  lu.set_terms({K.valuePtr(), M.valuePtr()});
  std::vector<double> scale(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) scale[static_cast<std::size_t>(i)] = 1.0 / std::sqrt(K.coeff(i, i));
  lu.set_column_scale(scale.data());
  const std::vector<Complex> weights{Complex(1.0, eta), Complex(-w * w, 0.0)};
  Eigen::VectorXcd b = Eigen::VectorXcd::Zero(n);
  b(n - 2) = 1.0;  // tip force
  ASSERT_EQ(lu.factorize_terms(weights.data(), b.data(), 1), Status::Ok);
  EXPECT_EQ(lu.fill_width(), lu.upper_bandwidth());  // no interchange widened U
  Eigen::VectorXcd x(n), work(n);
  lu.solve_prepared(0, x.data(), work.data());
  SparseC A = (K.cast<Complex>() * Complex(1.0, eta) - (w * w) * M.cast<Complex>()).pruned();
  const auto [backward, difference] = dense_check(A, x, b);
  EXPECT_LT(backward, 1e-13);  // threshold pivoting stays backward stable here
  // Two backward-stable solutions differ by about cond(D) times their backward errors; D of a
  // fine beam is ill-conditioned, so the bound is taken from its estimate.
  EXPECT_LT(difference, 1e-14 / reciprocal_condition(A));
}

TEST(BandedLU, PreparedRightHandSidesMatchSolveBitForBit) {
  // The forward substitution done during the elimination performs the operations of solve()
  // in the same order, so both give the same bits; pivoting is forced by the zero diagonal.
  const SparseC A = chain(60, 4, true, 13);
  const int n = static_cast<int>(A.rows());
  Eigen::MatrixXcd B(n, 2);
  B.col(0) = Eigen::VectorXcd::LinSpaced(n, 1.0, 3.0);
  B.col(1) = Eigen::VectorXcd::Zero(n);
  B(n / 2, 1) = Complex(0.0, 1.0);
  BandedLU lu;
  lu.analyze(n, A.outerIndexPtr(), A.innerIndexPtr());
  ASSERT_EQ(lu.factorize(A.valuePtr(), B.data(), 2), Status::Ok);
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
