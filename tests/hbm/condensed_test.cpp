// Condensation of the harmonic balance to the nonlinear coordinates (hbm/condensed.hpp) against
// the uncondensed harmonic balance of the same system (hbm/harmonic_balance.hpp).
//
// System: a chain of three masses (m = 1, 1, 0.5 kg; springs 1, 1, 2 N/m, the first to ground),
// stiffness-proportional damping C = 0.004 K (exactly modal: zeta_r = 0.002 w_r), a force
// 0.02 cos(w t) on mass 0 and a Jenkins friction element (k_t = 0.8 N/m, slip force 0.01 N)
// between mass 2 and the ground -- the only nonlinear coordinate. With every mode kept, the
// receptance form  X_c = X_lin - H F_nl  is an exact rewriting of  D X + F_nl = F_ext  (Krack &
// Gross, "Harmonic Balance for Nonlinear Vibration Problems", Springer 2019, sec. 3.4), so both
// must give the same periodic solutions: the nonlinear coordinate and the recovered sensor (mass
// 0) agree to the Newton tolerance (1e-10 relative is asserted; the solves are at 1e-12).
// With the highest mode left out, the residual flexibility (its static contribution) must bring
// the condensed answer closer to the exact one than the plain truncated modal sum. The static
// correction is exact at w = 0 and misses the left-out mode's dynamic part, of relative order
// (w / w_3)^2 (w_3 = 2.3 rad/s): below 10 % of the truncation error at 0.3 and 0.45 rad/s, below
// 50 % near the second resonance (0.6 and 0.75 rad/s; measured 3e-1 there), where small shifts
// of the peak dominate.
//
// The LocalForce form (element-local forces, matrix-free Newton algebra) on a small damper-ring-
// like system of friction contacts: the same residual, Jacobian and dR/domega as the general
// path, the Jacobian against finite differences, and a continuation identical to the one with
// dense LU solves.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <complex>
#pragma GCC diagnostic pop

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/hbm/condensed.hpp"
#include "geardyn/hbm/friction_contact.hpp"

namespace geardyn::hbm {
namespace {

struct Chain {
  Eigen::MatrixXd M, K, C;
  Chain() {
    M = Eigen::Vector3d(1.0, 1.0, 0.5).asDiagonal();
    K.resize(3, 3);
    K << 2.0, -1.0, 0.0,  //
        -1.0, 3.0, -2.0,  //
        0.0, -2.0, 2.0;
    C = 0.004 * K;
  }
};

constexpr double kForce = 0.02;
const JenkinsElement kElement{0.8, 0.01};

HarmonicBalance physical(const Chain& s, const HarmonicBasis& basis) {
  const Eigen::VectorXd F =
      kForce * Eigen::VectorXd::Unit(3 * basis.size(), HarmonicBasis::cos_index(1));
  return HarmonicBalance(s.M, s.C, s.K, basis, {jenkins_force(2, -1, kElement)}, F);
}

// Coordinate: DOF 2; sensor: DOF 0. `kept` lowest modes; with `residual` the static flexibility
// of the others.
CondensedHarmonicBalance condensed(const Chain& s, const HarmonicBasis& basis, int kept,
                                   bool residual) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(s.K, s.M);
  const Eigen::VectorXd w = eig.eigenvalues().cwiseSqrt();
  const Eigen::MatrixXd phi = eig.eigenvectors();  // mass-normalised
  const Eigen::MatrixXd flex = s.K.inverse();
  std::vector<ModalReceptance> harmonics;
  for (int n = 0; n <= basis.harmonics(); ++n) {
    ModalReceptance r;
    r.natural_frequency = w.head(kept);
    r.damping_ratio = 0.002 * w.head(kept);
    r.left = phi.block(2, 0, 1, kept).cast<std::complex<double>>();
    r.right = r.left;
    r.sensor_left = phi.block(0, 0, 1, kept).cast<std::complex<double>>();
    if (n == 1)
      r.modal_excitation =
          kForce * phi.block(0, 0, 1, kept).transpose().cast<std::complex<double>>();
    if (residual) {
      // Static flexibility minus the kept modes' static part.
      Eigen::MatrixXd modal_static = phi.leftCols(kept) *
                                     w.head(kept).cwiseInverse().cwiseAbs2().asDiagonal() *
                                     phi.leftCols(kept).transpose();
      const Eigen::MatrixXd rest = flex - modal_static;
      r.residual = Eigen::MatrixXcd::Constant(1, 1, rest(2, 2));
      r.sensor_residual = Eigen::MatrixXcd::Constant(1, 1, rest(0, 2));
      if (n == 1) {
        r.residual_excitation = Eigen::VectorXcd::Constant(1, kForce * rest(2, 0));
        r.sensor_residual_excitation = Eigen::VectorXcd::Constant(1, kForce * rest(0, 0));
      }
    }
    harmonics.push_back(r);
  }
  return CondensedHarmonicBalance(1, basis, harmonics, {jenkins_force(0, -1, kElement)});
}

ContinuationOptions options(double x_scale) {
  ContinuationOptions o;
  o.omega_start = 0.3;
  o.omega_end = 0.9;
  o.x_scale = x_scale;
  o.omega_scale = 0.6;
  o.step = 0.02;
  o.max_step = 0.05;
  o.tolerance = 1e-12;
  return o;
}

// Solutions at the frequencies `w` (increasing), by Newton at each, started from the previous
// solution; intermediate frequencies at most 0.005 apart keep each start close.
std::vector<Eigen::VectorXd> solve_points(const HarmonicSystem& hb, const std::vector<double>& w,
                                          Eigen::VectorXd X) {
  std::vector<Eigen::VectorXd> out;
  double current = w.front();
  for (double target : w) {
    const int sub = std::max(1, static_cast<int>(std::ceil((target - current) / 0.005)));
    for (int k = 1; k <= sub; ++k) {
      const double omega = current + (target - current) * k / sub;
      Eigen::MatrixXd J;
      bool converged = false;
      for (int it = 0; it < 50 && !converged; ++it) {
        const Eigen::VectorXd R = hb.residual(X, omega, &J);
        converged = R.norm() <= 1e-13 * hb.residual_scale(X, omega);
        if (!converged) X -= J.partialPivLu().solve(R);
      }
      EXPECT_TRUE(converged) << "at " << omega;
    }
    current = target;
    out.push_back(X);
  }
  return out;
}

TEST(CondensedHarmonicBalance, EqualsTheUncondensedSolutionWithAllModes) {
  const HarmonicBasis basis(5, 256);
  const Chain s;
  const HarmonicBalance full = physical(s, basis);
  const CondensedHarmonicBalance cond = condensed(s, basis, 3, false);
  const int sz = basis.size();
  std::vector<double> w;
  for (int i = 0; i <= 60; ++i) w.push_back(0.3 + 0.01 * i);
  const auto xf = solve_points(full, w, Eigen::VectorXd::Zero(full.size()));
  const auto xc = solve_points(cond, w, Eigen::VectorXd::Zero(cond.size()));
  double worst = 0.0, worst_sensor = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const Eigen::VectorXd coordinate = xf[i].segment(2 * sz, sz);
    worst = std::max(worst, (coordinate - xc[i]).norm() / coordinate.norm());
    largest = std::max(largest, coordinate.norm());
    // Recovery at mass 0, harmonics 1 and 3.
    for (int n : {1, 3}) {
      const std::complex<double> exact(xf[i][HarmonicBasis::cos_index(n)],
                                       -xf[i][HarmonicBasis::sin_index(n)]);
      const std::complex<double> recovered = cond.sensor_response(xc[i], w[i], n)[0];
      worst_sensor =
          std::max(worst_sensor, std::abs(recovered - exact) / xf[i].segment(0, sz).norm());
    }
  }
  EXPECT_LT(worst, 1e-10);
  EXPECT_LT(worst_sensor, 1e-10);
  EXPECT_GT(largest, 0.05);  // the sweep crosses a resonance: the friction element slips
}

TEST(CondensedHarmonicBalance, ContinuationWithScalingMatchesFixedFrequencySolves) {
  const HarmonicBasis basis(3, 128);
  const Chain s;
  const CondensedHarmonicBalance cond = condensed(s, basis, 3, false);
  const ContinuationResult r =
      continue_in_frequency(cond, Eigen::VectorXd::Zero(cond.size()), options(0.05));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_GT(r.points.size(), 20u);
  const HarmonicBalance full = physical(s, basis);
  std::vector<double> w;
  for (const auto& p : r.points) w.push_back(p.omega);
  const auto xf = solve_points(full, w, Eigen::VectorXd::Zero(full.size()));
  for (std::size_t i = 0; i < w.size(); ++i) {
    const auto& p = r.points[i];
    const Eigen::VectorXd c = xf[i].segment(2 * basis.size(), basis.size());
    EXPECT_LT((c - p.X).norm(), 1e-8 * std::max(1e-3, c.norm())) << "at " << p.omega;
  }
}

TEST(CondensedHarmonicBalance, ResidualFlexibilityCorrectsATruncatedModalSum) {
  const HarmonicBasis basis(3, 128);
  const Chain s;
  const HarmonicBalance full = physical(s, basis);
  const CondensedHarmonicBalance truncated = condensed(s, basis, 2, false);
  const CondensedHarmonicBalance corrected = condensed(s, basis, 2, true);
  const std::vector<double> w{0.3, 0.45, 0.6, 0.75};
  const auto xf = solve_points(full, w, Eigen::VectorXd::Zero(full.size()));
  const auto xt = solve_points(truncated, w, Eigen::VectorXd::Zero(truncated.size()));
  const auto xr = solve_points(corrected, w, Eigen::VectorXd::Zero(corrected.size()));
  for (std::size_t i = 0; i < w.size(); ++i) {
    const Eigen::VectorXd c = xf[i].segment(2 * basis.size(), basis.size());
    const double e_trunc = (xt[i] - c).norm(), e_corr = (xr[i] - c).norm();
    EXPECT_LT(e_corr, (w[i] < 0.5 ? 0.1 : 0.5) * e_trunc) << "at " << w[i];
  }
}

TEST(CondensedHarmonicBalance, AMeanWithoutReceptanceIsHeldAtZero) {
  // A static load on mass 0 moves the mean of the coordinate when harmonic 0 has its
  // receptance, and not when the harmonic-0 entry is empty.
  const HarmonicBasis basis(2, 64);
  const Chain s;
  std::vector<ModalReceptance> h = condensed(s, basis, 3, false).harmonics();
  h[0].modal_excitation = 0.01 * h[0].sensor_left.row(0).transpose();
  const CondensedHarmonicBalance free(1, basis, h, {cubic_spring(0, 5.0)});
  h[0] = ModalReceptance{};
  const CondensedHarmonicBalance fixed(1, basis, h, {cubic_spring(0, 5.0)});
  const auto xf = solve_points(free, {0.5}, Eigen::VectorXd::Zero(free.size()))[0];
  const auto xh = solve_points(fixed, {0.5}, Eigen::VectorXd::Zero(fixed.size()))[0];
  EXPECT_GT(std::abs(xf[0]), 1e-3);
  EXPECT_EQ(xh[0], 0.0);
  EXPECT_GT(std::abs(xh[HarmonicBasis::cos_index(1)]), 1e-3);
}

TEST(CondensedHarmonicBalance, RejectsMismatchedReceptances) {
  const HarmonicBasis basis(1, 16);
  ModalReceptance r;
  r.natural_frequency = Eigen::VectorXd::Ones(2);
  r.damping_ratio = Eigen::VectorXd::Zero(2);
  r.left = Eigen::MatrixXcd::Zero(1, 2);
  r.right = Eigen::MatrixXcd::Zero(1, 3);
  EXPECT_THROW(
      CondensedHarmonicBalance(1, basis, {ModalReceptance{}, r}, std::vector<NonlinearForce>{}),
      InputError);
  EXPECT_THROW(
      CondensedHarmonicBalance(1, basis, {ModalReceptance{}}, std::vector<NonlinearForce>{}),
      InputError);
}

// ---- LocalForce form ----------------------------------------------------------------------
//
// A sector with `pairs` contact pairs along its groove (pair p at s_p = (p + 1/2) / pairs;
// coordinate 2p the normal approach, 2p + 1 the tangential slip), per harmonic n >= 1 `modes`
// complex modes smooth in s_p (a standing wave times the travelling phase of nodal diameter
// 3n of 40 sectors), a dense Hermitian residual flexibility that couples neighbouring pairs,
// and, when `mean` is set, a harmonic 0 with modes (complex shapes: its real part acts) and a
// residual, else an empty one. Contacts: k_n = 5e7 N/m, k_t = 3e7 N/m, mu = 0.3,
// N_0 = 150 N + c omega^2 (c = kPreloadRate: +50 N at 2 kHz).
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kPreloadRate = 50.0 / (kTwoPi * 2000.0) / (kTwoPi * 2000.0);

FrictionContact ring_contact() { return {1, 5e7, 3e7, 0.3, 150.0}; }

std::vector<ModalReceptance> ring_receptances(int pairs, int H, int modes, bool mean,
                                              bool residual) {
  const int nc = 2 * pairs;
  std::vector<ModalReceptance> out;
  for (int n = 0; n <= H; ++n) {
    ModalReceptance r;
    if (n == 0 && !mean) {
      out.push_back(r);
      continue;
    }
    const int h = 3 * std::max(n, 1);
    r.natural_frequency.resize(modes);
    r.damping_ratio = Eigen::VectorXd::Constant(modes, 0.003);
    r.left.resize(nc, modes);
    for (int m = 0; m < modes; ++m) {
      r.natural_frequency(m) = kTwoPi * (m == 1 ? 2000.0 : 900.0 * std::pow(1.35, m));
      for (int p = 0; p < pairs; ++p) {
        const double sp = (p + 0.5) / pairs;
        const std::complex<double> phase = std::polar(1.0, kTwoPi * h * sp / 40.0);
        r.left(2 * p, m) = 0.03 * std::cos(std::numbers::pi * (1 + m % 3) * sp + 0.4 * m) * phase;
        r.left(2 * p + 1, m) =
            0.1 * std::cos(std::numbers::pi * (1 + m % 4) * sp + 0.9 * m) * phase;
      }
    }
    r.right = r.left;
    if (residual) {
      r.residual.resize(nc, nc);
      for (int p = 0; p < nc; ++p)
        for (int q = 0; q < nc; ++q) {
          const double ds = (p / 2 - q / 2) / double(pairs);
          r.residual(p, q) = p % 2 == q % 2 ? 3e-10 * std::exp(-ds * ds / 0.04) *
                                                  std::polar(1.0, kTwoPi * h * ds / 40.0)
                                            : 0.0;
        }
    }
    if (n == 1) {
      r.modal_excitation.resize(modes);
      for (int m = 0; m < modes; ++m) r.modal_excitation(m) = std::polar(1.0, 0.3 * m);
    }
    out.push_back(r);
  }
  return out;
}

std::vector<LocalForce> ring_forces(int pairs) {
  std::vector<LocalForce> forces;
  for (int p = 0; p < pairs; ++p)
    forces.push_back(local_friction_contact({2 * p, 2 * p + 1}, ring_contact(), kPreloadRate));
  return forces;
}

// The same contacts written for the general path: the force of friction_contact_response, its
// Jacobian scattered into the N x N one, and dF/domega by df/dN_0 = J e / k_n - e.
std::vector<FrequencyDependentForce> ring_forces_general(int pairs) {
  std::vector<FrequencyDependentForce> forces;
  for (int p = 0; p < pairs; ++p)
    forces.push_back([p](const HarmonicBasis& b, const Eigen::VectorXd& X, double omega,
                         Eigen::VectorXd& F, Eigen::MatrixXd* J, Eigen::VectorXd* dF) {
      const int s = b.size(), row = 2 * p * s;
      FrictionContact c = ring_contact();
      c.normal_preload += kPreloadRate * omega * omega;
      const ContactResponse r = friction_contact_response(c, b, X.segment(row, 2 * s));
      F.segment(row, 2 * s) += r.coefficients;
      if (J) J->block(row, row, 2 * s, 2 * s) += r.jacobian;
      if (dF) {
        Eigen::VectorXd d = r.jacobian.col(0) / c.normal_stiffness;
        d -= Eigen::VectorXd::Unit(2 * s, 0);
        dF->segment(row, 2 * s) += 2.0 * kPreloadRate * omega * d;
      }
    });
  return forces;
}

// A state in stick-slip: tangential amplitudes of 2 to 3 stick limits (mu N_0 / k_t = 1.5 um
// with the preload of 2 kHz), normal ones below the lift-off amplitude N_0 / k_n = 4 um, a few
// higher harmonics.
Eigen::VectorXd stick_slip_state(int pairs, int H) {
  const int s = 2 * H + 1;
  std::vector<double> x(static_cast<std::size_t>(2 * pairs * s), 0.0);
  for (int p = 0; p < pairs; ++p) {
    double* v = &x[static_cast<std::size_t>(2 * p * s)];
    double* u = v + s;
    v[0] = 2e-7;
    v[HarmonicBasis::cos_index(1)] = 1.5e-6 * std::cos(p);
    v[HarmonicBasis::sin_index(1)] = 1e-6 * std::sin(p + 0.3);
    u[0] = 1e-7 * p;
    u[HarmonicBasis::cos_index(1)] = 3e-6 * (1.0 + 0.2 * p);
    u[HarmonicBasis::sin_index(1)] = -1e-6;
    for (int n = 2; n <= H; ++n) {
      v[HarmonicBasis::cos_index(n)] = 2e-7 / n;
      u[HarmonicBasis::sin_index(n)] = -3e-7 / n;
    }
  }
  return Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
}

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / b.norm();
}

TEST(CondensedLocalForce, MatchesTheGeneralPath) {
  const int pairs = 3, H = 3;
  const HarmonicBasis basis(H, 64);
  for (bool mean : {false, true}) {
    const auto rec = ring_receptances(pairs, H, 5, mean, true);
    const CondensedHarmonicBalance local(2 * pairs, basis, rec, ring_forces(pairs));
    const CondensedHarmonicBalance general(2 * pairs, basis, rec, ring_forces_general(pairs));
    ASSERT_TRUE(local.has_local_forces());
    ASSERT_FALSE(general.has_local_forces());
    const Eigen::VectorXd X = stick_slip_state(pairs, H);
    const double omega = kTwoPi * 1950.0;
    Eigen::MatrixXd Jl, Jg;
    Eigen::VectorXd dl, dg;
    const Eigen::VectorXd Rl = local.residual(X, omega, &Jl, &dl);
    const Eigen::VectorXd Rg = general.residual(X, omega, &Jg, &dg);
    EXPECT_LT(relative(Rl, Rg), 1e-12) << "mean " << mean;
    EXPECT_LT(relative(Jl, Jg), 1e-12) << "mean " << mean;
    EXPECT_LT(relative(dl, dg), 1e-12) << "mean " << mean;
    EXPECT_LT(relative(local.residual(X, omega), Rg), 1e-12);
    EXPECT_LT(relative(local.nonlinear_forces(X, omega), general.nonlinear_forces(X, omega)),
              1e-12);
    // The operator form: J v from the parts, and the dense J assembled from the blocks.
    const CondensedJacobian lin = local.linearize(X, omega);
    EXPECT_LT(relative(lin.residual(), Rg), 1e-12);
    EXPECT_LT(relative(lin.dense(), Jg), 1e-12);
    const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(X.size(), -1.0, 2.0).array().sin();
    EXPECT_LT(relative(lin.apply(v), Jg * v), 1e-12);
  }
}

TEST(CondensedLocalForce, JacobianAndFrequencyDerivativeMatchFiniteDifferences) {
  // Central differences of R(X, omega) with the preload N_0 = 150 N + c omega^2. The AFT march is
  // piecewise smooth in X (each sample sticks or slips), so the steps (1e-4 of the amplitudes,
  // 1e-7 of omega) are small enough not to move a sample across a switch; the truncation error
  // is then of order step^2 relative: 1e-6 is asserted.
  const int pairs = 3, H = 3;
  const HarmonicBasis basis(H, 64);
  const CondensedHarmonicBalance hb(2 * pairs, basis, ring_receptances(pairs, H, 5, true, true),
                                    ring_forces(pairs));
  const Eigen::VectorXd X = stick_slip_state(pairs, H);
  const double omega = kTwoPi * 1950.0;
  Eigen::MatrixXd J;
  Eigen::VectorXd dR;
  hb.residual(X, omega, &J, &dR);
  Eigen::MatrixXd fd(J.rows(), J.cols());
  const double h = 1e-4 * 1e-6;
  for (Eigen::Index j = 0; j < X.size(); ++j) {
    Eigen::VectorXd up = X, down = X;
    up(j) += h;
    down(j) -= h;
    fd.col(j) = (hb.residual(up, omega) - hb.residual(down, omega)) / (2.0 * h);
  }
  EXPECT_LT(relative(J, fd), 1e-6);
  const double hw = 1e-7 * omega;
  const Eigen::VectorXd fdw =
      (hb.residual(X, omega + hw) - hb.residual(X, omega - hw)) / (2.0 * hw);
  EXPECT_LT(relative(dR, fdw), 1e-6);
  // The preload's share of dR/domega is not negligible: with the preload frozen at its value the
  // residual is the same and the derivative differs.
  Eigen::VectorXd dR_constant;
  std::vector<LocalForce> constant;
  for (int p = 0; p < pairs; ++p) {
    FrictionContact c = ring_contact();
    c.normal_preload += kPreloadRate * omega * omega;
    constant.push_back(local_friction_contact({2 * p, 2 * p + 1}, c));
  }
  const CondensedHarmonicBalance frozen(2 * pairs, basis, ring_receptances(pairs, H, 5, true, true),
                                        std::move(constant));
  const Eigen::VectorXd R_frozen = frozen.residual(X, omega, nullptr, &dR_constant);
  EXPECT_LT(relative(R_frozen, hb.residual(X, omega)), 1e-14);
  EXPECT_GT(relative(dR_constant, dR), 1e-3);
}

// A real structure (the same real modes and residual flexibility for every harmonic,
// H_n(w) = H(n w), as the string of bench/nonlinear_hbm_bench.cpp) takes the shared path of
// CondensedJacobian::apply, U D V^T and R_res on all coefficient columns at once: it equals the
// product with the dense Jacobian, formed harmonic by harmonic from the complex receptances. Both
// sum the same few terms in another order, so they agree to round-off (1e-15 relative measured
// order); 1e-12 asserted.
TEST(CondensedLocalForce, SharedRealModesApplyEqualsTheDenseJacobian) {
  const int pairs = 3, H = 3;
  const HarmonicBasis basis(H, 64);
  std::vector<ModalReceptance> shared = ring_receptances(pairs, H, 5, true, true);
  const Eigen::MatrixXcd left = shared[1].left.real().cast<std::complex<double>>();
  const Eigen::MatrixXcd residual = shared[1].residual.real().cast<std::complex<double>>();
  for (auto& r : shared) {
    r.left = left;
    r.right = left;
    r.residual = residual;
  }
  const CondensedHarmonicBalance hb(2 * pairs, basis, shared, ring_forces(pairs));
  const CondensedJacobian J = hb.linearize(stick_slip_state(pairs, H), kTwoPi * 1950.0);
  const Eigen::MatrixXd D = J.dense();
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd v = 1e-6 * Eigen::VectorXd::Random(hb.size());
    EXPECT_LT(relative(J.apply(v), D * v), 1e-12);
  }
}

TEST(CondensedLocalForce, PreconditionerIsTheInverseWhenTheResidualStaysInsideClusters) {
  // M = J exactly when the residual flexibility does not couple clusters; here also two elements
  // share a coordinate (a unilateral spring on the normal coordinate of pair 0), which merges
  // them into one cluster.
  const int pairs = 3, H = 2;
  const HarmonicBasis basis(H, 64);
  const Eigen::VectorXd X = stick_slip_state(pairs, H);
  const double omega = kTwoPi * 1980.0;
  const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(X.size(), 0.5, 3.0).array().cos();
  for (bool residual : {false, true}) {
    auto rec = ring_receptances(pairs, H, 4, true, residual);
    if (residual)  // keep only the blocks of each pair
      for (auto& r : rec)
        if (r.residual.size())
          for (int p = 0; p < 2 * pairs; ++p)
            for (int q = 0; q < 2 * pairs; ++q)
              if (p / 2 != q / 2) r.residual(p, q) = 0.0;
    std::vector<LocalForce> forces = ring_forces(pairs);
    LocalForce spring;
    spring.coordinates = {0};
    spring.evaluate = [](const HarmonicBasis& b, const Eigen::VectorXd& w, double,
                         Eigen::VectorXd& f, Eigen::MatrixXd* J, Eigen::VectorXd*) {
      const UnilateralResponse r = unilateral_spring_response(2e7, -1e-6, b, w);
      f += r.coefficients;
      if (J) *J += r.jacobian;
    };
    forces.push_back(spring);
    const CondensedHarmonicBalance hb(2 * pairs, basis, rec, std::move(forces));
    const CondensedJacobian J = hb.linearize(X, omega);
    const CondensedPreconditioner M(hb, J);
    ASSERT_EQ(M.status(), Status::Ok);
    EXPECT_TRUE(M.exact());
    EXPECT_LT((J.apply(M.solve(v)) - v).norm(), 1e-12 * v.norm()) << "residual " << residual;
    // The general path agrees with the merged cluster.
    std::vector<NonlinearForce> general;
    for (int p = 0; p < pairs; ++p)
      general.push_back(friction_contact_force({2 * p, 2 * p + 1}, [] {
        FrictionContact c = ring_contact();
        c.normal_preload += kPreloadRate * (kTwoPi * 1980.0) * (kTwoPi * 1980.0);
        return c;
      }()));
    general.push_back(unilateral_spring(0, 2e7, -1e-6));
    const CondensedHarmonicBalance g(2 * pairs, basis, rec, std::move(general));
    Eigen::MatrixXd Jg;
    const Eigen::VectorXd Rg = g.residual(X, omega, &Jg);
    EXPECT_LT(relative(J.residual(), Rg), 1e-12);
    EXPECT_LT(relative(J.dense(), Jg), 1e-12);
  }
  // With the dense residual the preconditioner is an approximation only.
  const CondensedHarmonicBalance coupled(
      2 * pairs, basis, ring_receptances(pairs, H, 4, true, true), ring_forces(pairs));
  const CondensedPreconditioner M(coupled, coupled.linearize(X, omega));
  EXPECT_FALSE(M.exact());
}

// continue_in_frequency through HarmonicSystem only: the dense path (an LU per solve).
class DenseView final : public HarmonicSystem {
 public:
  explicit DenseView(const HarmonicSystem& s) : s_(s) {}
  int size() const override { return s_.size(); }
  Eigen::VectorXd residual(const Eigen::VectorXd& X, double omega, Eigen::MatrixXd* J,
                           Eigen::VectorXd* dR) const override {
    return s_.residual(X, omega, J, dR);
  }
  double residual_scale(const Eigen::VectorXd& X, double omega) const override {
    return s_.residual_scale(X, omega);
  }

 private:
  const HarmonicSystem& s_;
};

TEST(CondensedLocalForce, ContinuationEqualsTheOneWithDenseSolves) {
  // The matrix-free algebra (GMRES with the Woodbury preconditioner, inexact here: the residual
  // couples the pairs) leaves at most 1 % of the Newton tolerance in each linear solve, so the
  // curve is the dense one: the same points, iteration counts and, to far below the tolerance
  // of 1e-10, the same solutions. The excitation drives the contacts through stick-slip into
  // gross slip at the peak.
  const int pairs = 6, H = 3;
  const HarmonicBasis basis(H, 64);
  auto rec = ring_receptances(pairs, H, 6, false, true);
  rec[1].modal_excitation *= 150.0;
  CondensedHarmonicBalance hb(2 * pairs, basis, rec, ring_forces(pairs));
  CondensedStatistics stats;
  hb.set_statistics(&stats);
  ContinuationOptions o;
  o.omega_start = kTwoPi * 1850.0;
  o.omega_end = kTwoPi * 2250.0;
  o.omega_scale = o.omega_end - o.omega_start;
  o.x_scale = 5e-5;
  o.step = 0.02;
  o.max_step = 0.05;
  const ContinuationResult fast = continue_in_frequency(hb, Eigen::VectorXd::Zero(hb.size()), o);
  hb.set_statistics(nullptr);
  ASSERT_EQ(fast.status, Status::Ok) << fast.message;
  EXPECT_GT(fast.points.size(), 20u);
  // The condensed form predicts along the secant, the dense algebra along the tangent, so the
  // points are placed differently; each point of the matrix-free curve is checked instead as the
  // start point of a dense continuation at its own frequency (Newton in X at fixed omega, from
  // the point itself): it must already be the dense solution there.
  double largest = 0.0;
  for (std::size_t i = 0; i < fast.points.size(); ++i) {
    const auto& a = fast.points[i];
    EXPECT_LE(a.residual, o.tolerance * hb.residual_scale(a.X, a.omega));
    largest = std::max(largest, hb.complex_harmonic(a.X, 1).cwiseAbs().maxCoeff());
    if (i % 4 != 0) continue;
    ContinuationOptions at = o;
    at.omega_start = a.omega;
    at.omega_end = a.omega * (1.0 + 1e-6);
    at.max_points = 1;
    const ContinuationResult dense = continue_in_frequency(DenseView(hb), a.X, at);
    ASSERT_FALSE(dense.points.empty()) << "point " << i;
    EXPECT_LT((dense.points[0].X - a.X).norm(), 1e-8 * a.X.norm()) << "point " << i;
  }
  // Gross slip at the peak: harmonic-1 slip well beyond the stick limit mu N_0 / k_t (1.5 um).
  EXPECT_GT(largest, 5e-6);
  EXPECT_GT(stats.krylov_iterations, stats.linear_solves);  // the preconditioner is inexact
  EXPECT_EQ(stats.dense_factorizations, 0);
}

TEST(CondensedLocalForce, FallsBackToTheDenseJacobianWhenThePreconditionerFails) {
  // A spring of stiffness -1 / r_0 on a coordinate whose residual flexibility is r_0 makes
  // I + R_b J_nl singular on that coordinate (the preconditioner's cluster solve fails), while
  // J itself, I - H / r_0 there, stays regular through its modal part. The continuation must
  // then take the LU of the dense J and still trace the curve of the dense path.
  const int pairs = 2, H = 2;
  const double r0 = 3e-10;
  const HarmonicBasis basis(H, 64);
  auto rec = ring_receptances(pairs, H, 6, false, false);
  for (auto& r : rec)
    if (r.modes()) r.residual = r0 * Eigen::MatrixXcd::Identity(2 * pairs, 2 * pairs);
  rec[1].modal_excitation *= 150.0;
  std::vector<LocalForce> forces;
  forces.push_back(local_friction_contact({0, 1}, ring_contact(), kPreloadRate));
  LocalForce spring;
  spring.coordinates = {2};
  spring.evaluate = [r0](const HarmonicBasis&, const Eigen::VectorXd& w, double, Eigen::VectorXd& f,
                         Eigen::MatrixXd* J, Eigen::VectorXd*) {
    f -= w / r0;
    if (J) J->diagonal().array() -= 1.0 / r0;
  };
  forces.push_back(spring);
  CondensedHarmonicBalance hb(2 * pairs, basis, rec, std::move(forces));
  CondensedStatistics stats;
  hb.set_statistics(&stats);
  ContinuationOptions o;
  o.omega_start = kTwoPi * 1900.0;
  o.omega_end = kTwoPi * 2100.0;
  o.omega_scale = o.omega_end - o.omega_start;
  o.x_scale = 5e-5;
  o.step = 0.05;
  o.max_step = 0.1;
  const ContinuationResult fast = continue_in_frequency(hb, Eigen::VectorXd::Zero(hb.size()), o);
  hb.set_statistics(nullptr);
  ASSERT_EQ(fast.status, Status::Ok) << fast.message;
  // Each point is the dense solution at its frequency (see the test above).
  for (std::size_t i = 0; i < fast.points.size(); ++i) {
    ContinuationOptions at = o;
    at.omega_start = fast.points[i].omega;
    at.omega_end = fast.points[i].omega * (1.0 + 1e-6);
    at.max_points = 1;
    const ContinuationResult dense = continue_in_frequency(DenseView(hb), fast.points[i].X, at);
    ASSERT_FALSE(dense.points.empty()) << "point " << i;
    EXPECT_LT((fast.points[i].X - dense.points[0].X).norm(), 1e-8 * fast.points[i].X.norm());
  }
  EXPECT_GT(stats.dense_factorizations, 0);
}

TEST(CondensedLocalForce, RejectsInvalidElements) {
  const HarmonicBasis basis(1, 16);
  const auto rec = ring_receptances(1, 1, 2, false, false);
  auto with = [&](std::vector<int> coordinates, bool evaluate) {
    LocalForce f;
    f.coordinates = std::move(coordinates);
    if (evaluate)
      f.evaluate = [](const HarmonicBasis&, const Eigen::VectorXd&, double, Eigen::VectorXd&,
                      Eigen::MatrixXd*, Eigen::VectorXd*) {};
    return CondensedHarmonicBalance(2, basis, rec, std::vector<LocalForce>{f});
  };
  EXPECT_NO_THROW(with({0, 1}, true));
  EXPECT_THROW(with({0, 2}, true), InputError);
  EXPECT_THROW(with({1, 1}, true), InputError);
  EXPECT_THROW(with({}, true), InputError);
  EXPECT_THROW(with({0}, false), InputError);
  EXPECT_THROW(local_friction_contact({0}, ring_contact()), InputError);
  FrictionContact rigid = ring_contact();
  rigid.normal_stiffness = 0.0;
  EXPECT_NO_THROW(local_friction_contact({0, 1}, rigid));
  EXPECT_THROW(local_friction_contact({0, 1}, rigid, 1e-6), InputError);
  EXPECT_THROW(local_friction_contact({0, 1}, ring_contact(), -1.0), InputError);
  // An element that returns the wrong size is named.
  LocalForce bad;
  bad.coordinates = {0};
  bad.evaluate = [](const HarmonicBasis&, const Eigen::VectorXd&, double, Eigen::VectorXd& f,
                    Eigen::MatrixXd*, Eigen::VectorXd*) { f.resize(1); };
  const CondensedHarmonicBalance hb(2, basis, rec, std::vector<LocalForce>{bad});
  EXPECT_THROW(hb.residual(Eigen::VectorXd::Zero(hb.size()), 1.0), InputError);
}

}  // namespace
}  // namespace geardyn::hbm
