// Craig-Bampton with linear interface constraints (reduce/constrained_modes.hpp and the
// InterfaceConstraints overload of craig_bampton): the constrained pencil against the analytic
// fixed-free chain, the saddle-point solve against springs in series, and the reduction against
// the same reduction made by eliminating the constraints (x = S z).
#include "geardyn/reduce/constrained_modes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "reduce/reduce_test_support.hpp"

namespace geardyn::reduce {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using test::chain;

// Free-free chain of n equal masses m = 1 kg and springs k = 1000 N/m.
struct Uniform {
  SparseMatrix K, M;
};
Uniform uniform_chain(int n) {
  std::vector<Eigen::Triplet<double>> tk, tm;
  for (int i = 0; i < n; ++i) tm.emplace_back(i, i, 1.0);
  for (int i = 0; i + 1 < n; ++i) {
    tk.emplace_back(i, i, 1000.0);
    tk.emplace_back(i + 1, i + 1, 1000.0);
    tk.emplace_back(i, i + 1, -1000.0);
    tk.emplace_back(i + 1, i, -1000.0);
  }
  Uniform u{SparseMatrix(n, n), SparseMatrix(n, n)};
  u.K.setFromTriplets(tk.begin(), tk.end());
  u.M.setFromTriplets(tm.begin(), tm.end());
  return u;
}

// Constraint rows from dense coefficient lists.
SparseMatrix rows(int n, const std::vector<std::vector<std::pair<int, double>>>& list) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t r = 0; r < list.size(); ++r)
    for (const auto& [c, v] : list[r]) t.emplace_back(static_cast<int>(r), c, v);
  SparseMatrix A(static_cast<Eigen::Index>(list.size()), n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// A free-free chain held by the single constraint x_0 = 0 is the fixed-free chain of N = n - 1
// masses, omega_j = 2 sqrt(k/m) sin((2j - 1) pi / (2 (2N + 1))) (Rayleigh, "The Theory of
// Sound", vol. 1, 1877, sections 120-121; e.g. Meirovitch, "Fundamentals of Vibrations", 2001,
// section 7.9). K alone is singular (rigid-body mode): only the saddle-point matrix is regular.
// 600 masses: the sparse (augmented-pencil Lanczos) path; the dense null-space path on the same.
// Tolerance 1e-9 relative: Lanczos converges the shift-inverted Ritz values to 1e-10, and the
// lowest eigenvalue (0.0062 rad^2/s^2 against ||K|| = 4000) loses about 1e-16 * 4000 / 0.0062
// = 6e-11 relative to round-off.
TEST(ConstrainedModes, FixedFreeChainIsTheAnalyticChain) {
  const int n = 600, N = n - 1;
  const Uniform u = uniform_chain(n);
  const SparseMatrix A = rows(n, {{{0, 1.0}}});
  for (const eig::Method method : {eig::Method::Auto, eig::Method::Dense}) {
    eig::SymmetricEigenOptions o;
    o.n_modes = 12;
    o.method = method;
    const auto r = solve_constrained(u.K, u.M, A, o);
    ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
    EXPECT_EQ(r.method_used,
              method == eig::Method::Auto ? eig::Method::Sparse : eig::Method::Dense);
    ASSERT_EQ(r.eigenvalues.size(), 12);
    ASSERT_EQ(r.eigenvectors.rows(), n);
    for (int j = 1; j <= 12; ++j) {
      const double s = std::sin((2 * j - 1) * std::numbers::pi / (2.0 * (2 * N + 1)));
      const double exact = 4.0 * 1000.0 * s * s;
      EXPECT_NEAR(r.eigenvalues[j - 1], exact, 1e-9 * exact) << "mode " << j;
      const Eigen::VectorXd phi = r.eigenvectors.col(j - 1);
      // On the constraint and M-normalised (to round-off of the unit M-norm).
      EXPECT_LE(std::abs(phi[0]), 1e-10 * phi.cwiseAbs().maxCoeff()) << "mode " << j;
      EXPECT_NEAR(phi.dot(u.M * phi), 1.0, 1e-12) << "mode " << j;
    }
  }
}

// Springs in series: the free-free chain, x_0 = c held by the constraint row, force F at the far
// end: x_j = c + F sum_{i<j} 1/k_i. F is held by the constraint force alone (K is singular).
// Tolerance 1e-10 relative: one LU solve of a 601 x 601 system of condition about 1e6.
TEST(ConstrainedModes, SaddlePointSolveIsSpringsInSeries) {
  const int n = 600;
  const Uniform u = uniform_chain(n);
  const SparseMatrix A = rows(n, {{{0, 1.0}}});
  SaddlePointSolver saddle;
  ASSERT_EQ(saddle.compute(u.K, A), Status::Ok) << saddle.message();
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, 1), C(1, 1);
  B(n - 1, 0) = 50.0;
  C(0, 0) = 2e-3;
  const Eigen::MatrixXd x = saddle.solve(B, C);
  for (int j = 0; j < n; ++j) {
    const double exact = 2e-3 + 50.0 * j / 1000.0;
    EXPECT_NEAR(x(j, 0), exact, 1e-10 * std::abs(exact)) << "x_" << j;
  }
}

// The reduction with constraints kept equals the reduction of the eliminated system. Chain of
// 600 unequal masses; constraints: u_0 = mean of x_0..x_49, u_1 = (x_300 + 2 x_301 + x_310) / 4;
// masters u_0, u_1 and x_599; 15 modes. Reference: pivots x_0 (row 0) and x_301 (row 1)
// eliminated, x = S z, z = [x_F; u], craig_bampton on (S^T K S, S^T M S) with masters u and
// x_599 (the fill path that spider_system used). Both span the same subspace (docs/theory.md
// §9), so the eigenvalues of the reduced pairs agree, with the masters free and with u_0 held;
// tolerance 1e-8 relative (the two Lanczos runs each converge to 1e-10).
TEST(ConstrainedModes, CraigBamptonEqualsTheEliminatedReduction) {
  const int n = 600;
  const auto t = chain(n);
  std::vector<std::pair<int, double>> mean;
  for (int i = 0; i < 50; ++i) mean.emplace_back(i, 1.0 / 50.0);
  InterfaceConstraints con;
  con.A = rows(n, {mean, {{300, 0.25}, {301, 0.5}, {310, 0.25}}});
  con.dofs = {{1001, 0, Eigen::Vector3d(25, 0, 0)}, {1002, 0, Eigen::Vector3d(301, 0, 0)}};
  CraigBamptonOptions o;
  o.n_modes = 15;
  const ReducedComponent kept = craig_bampton(t.K, t.M, t.dofs, con, {n, n + 1, n - 1}, o);
  ASSERT_EQ(kept.size(), 18);
  ASSERT_EQ(kept.n_full(), n + 2);

  // x = S z: z = [x without x_0, x_301 (598); u_0; u_1].
  std::vector<int> position(n, -1);
  for (int j = 0, next = 0; j < n; ++j)
    if (j != 0 && j != 301) position[static_cast<std::size_t>(j)] = next++;
  std::vector<Eigen::Triplet<double>> ts;
  for (int j = 0; j < n; ++j)
    if (position[static_cast<std::size_t>(j)] >= 0)
      ts.emplace_back(j, position[static_cast<std::size_t>(j)], 1.0);
  // x_0 = 50 u_0 - sum_{i=1..49} x_i; x_301 = 2 u_1 - (x_300 + x_310) / 2.
  ts.emplace_back(0, n - 2, 50.0);
  for (int i = 1; i < 50; ++i) ts.emplace_back(0, position[static_cast<std::size_t>(i)], -1.0);
  ts.emplace_back(301, n - 1, 2.0);
  ts.emplace_back(301, position[300], -0.5);
  ts.emplace_back(301, position[310], -0.5);
  SparseMatrix S(n, n);
  S.setFromTriplets(ts.begin(), ts.end());
  const SparseMatrix St = S.transpose();
  SparseMatrix Kz = St * t.K * S, Mz = St * t.M * S;
  Kz = 0.5 * (Kz + SparseMatrix(Kz.transpose()));
  Mz = 0.5 * (Mz + SparseMatrix(Mz.transpose()));
  std::vector<solid::DofInfo> zdofs(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j)
    if (position[static_cast<std::size_t>(j)] >= 0)
      zdofs[static_cast<std::size_t>(position[static_cast<std::size_t>(j)])] =
          t.dofs[static_cast<std::size_t>(j)];
  zdofs[static_cast<std::size_t>(n - 2)] = con.dofs[0];
  zdofs[static_cast<std::size_t>(n - 1)] = con.dofs[1];
  const ReducedComponent eliminated =
      craig_bampton(Kz, Mz, zdofs, {n - 2, n - 1, position[n - 1]}, o);

  for (int k = 0; k < 15; ++k)
    EXPECT_NEAR(kept.fixed_interface_hz[k], eliminated.fixed_interface_hz[k],
                1e-8 * eliminated.fixed_interface_hz[k])
        << "fixed-interface mode " << k + 1;
  for (const std::vector<int>& held : {std::vector<int>{}, std::vector<int>{0}}) {
    const Eigen::VectorXd a = reduced_eigenvalues(kept, held);
    const Eigen::VectorXd b = reduced_eigenvalues(eliminated, held);
    ASSERT_EQ(a.size(), b.size());
    const double top = b.cwiseAbs().maxCoeff();
    for (Eigen::Index k = 0; k < a.size(); ++k)
      EXPECT_NEAR(a[k], b[k], 1e-8 * std::max(std::abs(b[k]), 1e-6 * top))
          << "mode " << k + 1 << " with " << held.size() << " held";
  }
  // The master block (constraint modes: no sign freedom) agrees entry by entry.
  const double k_scale = eliminated.K.topLeftCorner(3, 3).cwiseAbs().maxCoeff();
  EXPECT_LE((kept.K.topLeftCorner(3, 3) - eliminated.K.topLeftCorner(3, 3)).cwiseAbs().maxCoeff(),
            1e-9 * k_scale);
  const double m_scale = eliminated.M.topLeftCorner(3, 3).cwiseAbs().maxCoeff();
  EXPECT_LE((kept.M.topLeftCorner(3, 3) - eliminated.M.topLeftCorner(3, 3)).cwiseAbs().maxCoeff(),
            1e-9 * m_scale);
}

// A chain cut in two whose far part no master or constraint holds: the same InputError as the
// plain reduction, naming the free motion.
TEST(ConstrainedModes, UnheldPartIsAnInputError) {
  const int n = 600;
  const auto t = chain(n, 400);
  InterfaceConstraints con;
  con.A = rows(n, {{{0, 0.5}, {1, 0.5}}});
  con.dofs = {{1001, 0, Eigen::Vector3d(0.5, 0, 0)}};
  CraigBamptonOptions o;
  o.n_modes = 5;
  try {
    (void)craig_bampton(t.K, t.M, t.dofs, con, {n}, o);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("free motion"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rigid-body translation along x"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace geardyn::reduce
