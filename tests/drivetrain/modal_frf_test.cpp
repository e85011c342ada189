// FRF by modal superposition at the operating point (docs/theory.md §16.14,
// drivetrain/modal_frf.hpp): the expansion of P(s)^-1 = (s^2 M + s D + K)^-1 over right and left
// eigenvectors, x_k y_k^T / (s - lambda_k) with y_k^T P'(lambda_k) x_k = 1 (the state-space form
// of the quadratic pencil: F. Tisseur and K. Meerbergen, "The quadratic eigenvalue problem",
// SIAM Review 43(2), 2001, section 3; D. J. Ewins, "Modal Testing: Theory, Practice and
// Application", 2nd ed., 2000, section 2.7 for the non-symmetric case). With every mode kept
// the sum equals the direct solve (K - w^2 M + i w D)^-1 f; a single-DOF oscillator gives the
// textbook receptance 1 / (k - m w^2 + i c w) (Ewins 2000, section 2.2).
#include "geardyn/drivetrain/modal_frf.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/drivetrain_transient.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/drivetrain/linearisation.hpp"

namespace geardyn::drivetrain {
namespace {

using Complex = std::complex<double>;

SparseMatrix sparse(const Eigen::MatrixXd& A) { return A.sparseView(0.0, 0.0); }

/// A linearisation over `free` of a system of n equations, with all its modes and left vectors.
Linearisation make_linearisation(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C,
                                 const Eigen::MatrixXd& K, std::vector<int> free, int n,
                                 const Eigen::MatrixXd& B = {}, const Eigen::VectorXd& c = {}) {
  Linearisation lin;
  lin.M = sparse(M);
  lin.C = sparse(C);
  lin.K = sparse(K);
  lin.low_rank_basis = B;
  lin.low_rank_coefficients = c;
  lin.free = std::move(free);
  solve_linear_modes(lin, n, 2 * static_cast<int>(M.rows()), true);
  return lin;
}

/// The reference: the dense direct solve over the free equations, D = C + B diag(c) B^T.
Eigen::MatrixXcd dense_direct(const Eigen::MatrixXd& M, const Eigen::MatrixXd& D,
                              const Eigen::MatrixXd& K, const Linearisation& lin,
                              const EquationCombination& load,
                              const std::vector<EquationCombination>& outputs,
                              const std::vector<double>& f_hz) {
  const auto m = static_cast<Eigen::Index>(lin.free.size());
  auto on_free = [&](const EquationCombination& c) {
    Eigen::VectorXcd v = Eigen::VectorXcd::Zero(m);
    for (std::size_t k = 0; k < c.equations.size(); ++k)
      for (Eigen::Index i = 0; i < m; ++i)
        if (lin.free[static_cast<std::size_t>(i)] == c.equations[k]) v[i] += c.coefficients[k];
    return v;
  };
  const Eigen::VectorXcd f = on_free(load);
  Eigen::MatrixXcd H(static_cast<Eigen::Index>(f_hz.size()),
                     static_cast<Eigen::Index>(outputs.size()));
  for (std::size_t i = 0; i < f_hz.size(); ++i) {
    const Complex s(0.0, 2.0 * std::numbers::pi * f_hz[i]);
    const Eigen::MatrixXcd A =
        K.cast<Complex>() + s * D.cast<Complex>() + s * s * M.cast<Complex>();
    const Eigen::VectorXcd x = A.fullPivLu().solve(f);
    for (std::size_t j = 0; j < outputs.size(); ++j)
      H(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          on_free(outputs[j]).transpose() * x;
  }
  return H;
}

/// Every entry of `got` within `rel` of `want` relative to |want|, where |want| is at least
/// 1e-5 of that output's largest value over the band: near an antiresonance the modal sum
/// cancels terms up to the peak's size, so its rounding error (about 1e-14 of the peak, n terms
/// of unit round-off) is not relative to the small value there.
void expect_close(const Eigen::MatrixXcd& got, const Eigen::MatrixXcd& want, double rel,
                  const std::vector<double>& f_hz) {
  ASSERT_EQ(got.rows(), want.rows());
  ASSERT_EQ(got.cols(), want.cols());
  int compared = 0;
  for (Eigen::Index j = 0; j < want.cols(); ++j) {
    const double peak = want.col(j).cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < want.rows(); ++i) {
      if (std::abs(want(i, j)) < 1e-5 * peak) continue;
      ++compared;
      EXPECT_LE(std::abs(got(i, j) - want(i, j)), rel * std::abs(want(i, j)))
          << "output " << j << " at " << f_hz[static_cast<std::size_t>(i)] << " Hz: " << got(i, j)
          << " vs " << want(i, j);
    }
  }
  EXPECT_GT(compared, static_cast<int>(want.size()) * 9 / 10);
}

std::vector<double> band(double f0, double f1, int n) {
  std::vector<double> f;
  for (int i = 0; i < n; ++i) f.push_back(f0 + (f1 - f0) * i / (n - 1.0));
  return f;
}

// (a) A chain of six masses with non-proportional viscous damping (one dashpot) and a low-rank
// modal damping term, one equation of the system held: with all six modes kept the modal sum
// equals the direct solve to 1e-8 (observed about 1e-12; the margin covers the eigen-solver's
// backward error 1e-8 limit amplified by well-separated modes' condition numbers of order 1).
TEST(ModalFrf, AllModesKeptEqualTheDirectSolve) {
  const int m = 6;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(m, m), K = M, C = M;
  const double k[7] = {2e5, 1e5, 1.5e5, 1e5, 3e5, 1.2e5, 2e5};
  for (int i = 0; i < m; ++i) {
    M(i, i) = 1.0 + 0.3 * i;
    K(i, i) = k[i] + k[i + 1];
    if (i + 1 < m) K(i, i + 1) = K(i + 1, i) = -k[i + 1];
  }
  C(1, 1) = C(2, 2) = 40.0;  // a dashpot between masses 2 and 3
  C(1, 2) = C(2, 1) = -40.0;
  C(5, 5) = 15.0;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(m, 2);
  B(0, 0) = 1.0;
  B(3, 0) = -0.5;
  B(4, 1) = 1.0;
  Eigen::VectorXd c(2);
  c[0] = 8.0;
  c[1] = 3.0;
  // System equation 3 is held; free equation i is system equation free[i].
  const std::vector<int> free = {0, 1, 2, 4, 5, 6};
  const Linearisation lin = make_linearisation(M, C, K, free, 7, B, c);
  ASSERT_EQ(lin.modes.size(), 6u);
  ASSERT_TRUE(lin.has_left);
  const EquationCombination load{{0, 5, 3}, {1.0, 0.5, 7.0}};  // the held equation adds nothing
  const std::vector<EquationCombination> outputs = {
      {{2}, {1.0}}, {{6}, {1.0}}, {{4, 1}, {1.0, -1.0}}, {{3}, {1.0}}};
  const double top = lin.modes.back().natural_frequency_hz;
  const std::vector<double> f = band(0.0, 1.5 * top, 301);
  const ModalFrf frf = modal_frf(lin, load, outputs, f);
  ASSERT_EQ(frf.status, Status::Ok) << frf.message;
  EXPECT_EQ(frf.modes_used, 6);
  const Eigen::MatrixXd D = C + B * c.asDiagonal() * B.transpose();
  const Eigen::MatrixXcd ref = dense_direct(M, D, K, lin, load, outputs, f);
  expect_close(frf.receptance.leftCols(3), ref.leftCols(3), 1e-8, f);
  // The held equation does not move.
  EXPECT_EQ(frf.receptance.col(3).cwiseAbs().maxCoeff(), 0.0);
  // The library's sparse direct solve (Woodbury for the low-rank term) is the same solve.
  expect_close(direct_frf(lin, load, outputs, f).leftCols(3), ref.leftCols(3), 1e-10, f);
  // All modes kept: nothing truncated at 0 Hz.
  ASSERT_TRUE(frf.static_checked);
  EXPECT_LT(frf.static_truncation, 1e-9);

  // Truncated to the lowest three modes, the static receptance misses the upper modes' part:
  // the residual flexibility is reported, not hidden.
  const ModalFrf cut = modal_frf(lin, load, outputs, f, 3);
  EXPECT_EQ(cut.modes_used, 3);
  EXPECT_GT(cut.static_truncation, 1e-3);
  // With the static correction (Craig & Kurdila, "Fundamentals of Structural Dynamics", 2006,
  // mode-acceleration method) the truncated sum is exact at 0 Hz (to round-off: 1e-10 of the
  // static value) and, well below the lowest truncated mode, closer to the direct solve.
  const ModalFrf corrected = modal_frf(lin, load, outputs, f, 3, true);
  ASSERT_TRUE(corrected.static_corrected);
  for (Eigen::Index j = 0; j < 3; ++j) {
    EXPECT_NEAR(std::abs(corrected.receptance(0, j) - ref(0, j)), 0.0, 1e-10 * std::abs(ref(0, j)));
    const double f_low = 0.3 * lin.modes[3].natural_frequency_hz;
    for (std::size_t i = 1; i < f.size() && f[i] < f_low; ++i) {
      const auto r = static_cast<Eigen::Index>(i);
      EXPECT_LT(std::abs(corrected.receptance(r, j) - ref(r, j)),
                std::abs(cut.receptance(r, j) - ref(r, j)))
          << "output " << j << " at " << f[i] << " Hz";
    }
  }
}

// (b) A two-disk rotor at speed in the two lateral planes: gyroscopic coupling Omega G (skew)
// and cross-coupled stiffness k_xy = -k_yx (a seal or fluid-film bearing), so K and D are not
// symmetric and the left eigenvectors differ from the right ones. All modes kept: the direct
// solve to 1e-8 (as in (a)).
TEST(ModalFrf, GyroscopicNonSymmetricTangentEqualsTheDirectSolve) {
  // DOFs: x1, y1, x2, y2 (disk 1 and disk 2).
  const double m1 = 3.0, m2 = 5.0, Jp1 = 0.02, Jp2 = 0.06, omega = 900.0;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(4, 4), K = M, C = M;
  M(0, 0) = M(1, 1) = m1;
  M(2, 2) = M(3, 3) = m2;
  const double k1 = 4e5, k2 = 6e5, k12 = 2e5, q = 3e4, c1 = 60.0;
  const double kv[4][4] = {{k1 + k12, q, -k12, 0.0},
                           {-q, k1 + k12, 0.0, -k12},
                           {-k12, 0.0, k2 + k12, 0.0},
                           {0.0, -k12, 0.0, k2 + k12}};
  // Gyroscopic terms of the disks' tilt appear here as an effective skew coupling of the planes
  // (a reduced Jeffcott form): Omega Jp / r^2 with r = 0.1 m.
  const double g1 = omega * Jp1 / 0.01, g2 = omega * Jp2 / 0.01;
  const double cv[4][4] = {
      {c1, g1, 0.0, 0.0}, {-g1, c1, 0.0, 0.0}, {0.0, 0.0, c1, g2}, {0.0, 0.0, -g2, c1}};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      K(i, j) = kv[i][j];
      C(i, j) = cv[i][j];
    }
  ASSERT_GT((K - K.transpose()).norm(), 0.1 * q);
  const Linearisation lin = make_linearisation(M, C, K, {0, 1, 2, 3}, 4);
  ASSERT_EQ(lin.modes.size(), 4u);
  ASSERT_TRUE(lin.has_left);
  EXPECT_EQ(lin.unstable_modes, 0);
  const EquationCombination load{{0, 3}, {1.0, 0.3}};
  const std::vector<EquationCombination> outputs = {{{0}, {1.0}}, {{1}, {1.0}}, {{3}, {1.0}}};
  const std::vector<double> f = band(0.0, 1.5 * lin.modes.back().natural_frequency_hz, 301);
  const ModalFrf frf = modal_frf(lin, load, outputs, f);
  ASSERT_EQ(frf.status, Status::Ok) << frf.message;
  const Eigen::MatrixXcd ref = dense_direct(M, C, K, lin, load, outputs, f);
  expect_close(frf.receptance, ref, 1e-8, f);
  expect_close(direct_frf(lin, load, outputs, f), ref, 1e-10, f);
}

// (c) The single-DOF oscillator: H(w) = 1 / (k - m w^2 + i c w) (Ewins, "Modal Testing", 2000,
// eq. 2.3) to 1e-10: one root pair of a 2 x 2 state matrix, exact to a few units of round-off.
TEST(ModalFrf, SingleDofGivesTheTextbookReceptance) {
  const double m = 2.0, k = 8e4, c = 40.0;
  const Linearisation lin =
      make_linearisation(Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, c),
                         Eigen::MatrixXd::Constant(1, 1, k), {0}, 1);
  ASSERT_EQ(lin.modes.size(), 1u);
  const std::vector<double> f = band(0.0, 100.0, 201);
  const ModalFrf frf = modal_frf(lin, {{0}, {1.0}}, {{{0}, {1.0}}}, f);
  ASSERT_EQ(frf.status, Status::Ok) << frf.message;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double w = 2.0 * std::numbers::pi * f[i];
    const Complex h = 1.0 / Complex(k - m * w * w, c * w);
    EXPECT_LE(std::abs(frf.receptance(static_cast<Eigen::Index>(i), 0) - h), 1e-10 * std::abs(h))
        << f[i] << " Hz";
  }
  EXPECT_LT(frf.static_truncation, 1e-12);
}

// Overdamped: two real roots each enter once (no conjugate) and the sum is still exact.
TEST(ModalFrf, OverdampedRealRootsEnterOnce) {
  const double m = 1.0, k = 1e4, c = 500.0;  // zeta = 2.5
  const Linearisation lin =
      make_linearisation(Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, c),
                         Eigen::MatrixXd::Constant(1, 1, k), {0}, 1, {}, {});
  const std::vector<double> f = band(0.0, 50.0, 51);
  const ModalFrf frf = modal_frf(lin, {{0}, {1.0}}, {{{0}, {1.0}}}, f);
  ASSERT_EQ(frf.status, Status::Ok) << frf.message;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double w = 2.0 * std::numbers::pi * f[i];
    const Complex h = 1.0 / Complex(k - m * w * w, c * w);
    EXPECT_LE(std::abs(frf.receptance(static_cast<Eigen::Index>(i), 0) - h), 1e-10 * std::abs(h));
  }
}

// Without left eigenvectors the FRF fails and says so rather than returning a wrong sum.
TEST(ModalFrf, WithoutLeftVectorsItFails) {
  Linearisation lin;
  lin.M = sparse(Eigen::MatrixXd::Constant(1, 1, 1.0));
  lin.C = sparse(Eigen::MatrixXd::Constant(1, 1, 1.0));
  lin.K = sparse(Eigen::MatrixXd::Constant(1, 1, 100.0));
  lin.free = {0};
  solve_linear_modes(lin, 1, 1, false);
  const ModalFrf frf = modal_frf(lin, {{0}, {1.0}}, {{{0}, {1.0}}}, {1.0});
  EXPECT_EQ(frf.status, Status::Failed);
  EXPECT_NE(frf.message.find("left eigenvector"), std::string::npos);
}

// (d) Bad FRF keys: located errors (InputError at the key: exit code 2 from the program; the
// command-line side is tests/cli/ptu_runup_example_test.cpp).
TEST(ModalFrf, BadKeysAreLocatedErrors) {
  model::Model model;
  model::VirtualSensorSpec s;
  s.name = "seat";
  s.node = "n1";
  s.component = 0;
  model.virtual_sensors.push_back(s);
  model::DriverSpec d;
  d.name = "input";
  d.node = "n1";
  d.speeds = {10.0};
  model.drivers.push_back(d);
  analyses::DrivetrainTransientSettings ok;
  ok.frf_excitation = "seat";
  ok.modes = 10;
  ok.frf_band = {0.0, units::hz_to_rad_per_s(100.0)};
  EXPECT_FALSE(analyses::frf_settings_problem(model, ok));
  auto key_of = [&](const analyses::DrivetrainTransientSettings& bad) {
    const auto p = analyses::frf_settings_problem(model, bad);
    return p ? p->key : std::string("none");
  };
  analyses::DrivetrainTransientSettings bad = ok;
  bad.frf_excitation = "nowhere";  // no sensor or mesh of that name
  EXPECT_EQ(key_of(bad), "frf_excitation");
  bad = ok;
  bad.frf_band = {units::hz_to_rad_per_s(100.0), units::hz_to_rad_per_s(100.0)};  // empty
  EXPECT_EQ(key_of(bad), "frf_band_hz");
  bad.frf_band = {units::hz_to_rad_per_s(200.0), units::hz_to_rad_per_s(100.0)};  // reversed
  EXPECT_EQ(key_of(bad), "frf_band_hz");
  bad.frf_band = {units::hz_to_rad_per_s(100.0)};  // one value
  EXPECT_EQ(key_of(bad), "frf_band_hz");
  bad = ok;
  bad.frf_modes = 11;  // more than the linearisation computes
  EXPECT_EQ(key_of(bad), "frf_modes");
  bad = ok;
  bad.modes = 0;  // no linearisation
  EXPECT_EQ(key_of(bad), "modes");

  // Through the analysis: an InputError at analyses[...].frf_excitation before any work.
  analyses::DrivetrainTransientSettings run = ok;
  run.duration = 0.1;
  run.sample_angular_rate = units::hz_to_rad_per_s(1000.0);
  run.frf_excitation = "nowhere";
  try {
    analyses::run_drivetrain_transient(model, run, analyses::Context("dt", "analyses[0]"));
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("frf_excitation"), std::string::npos) << e.what();
    EXPECT_NE(e.hint().find("sensor"), std::string::npos);
  }
}

}  // namespace
}  // namespace geardyn::drivetrain
