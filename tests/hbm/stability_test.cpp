// Floquet exponents by Hill's method (hbm/stability.hpp), against
//  (a) the exact exponents of linear oscillators: 1 DOF m q'' + c q' + k q = 0 has
//      lambda = -zeta w_n +- i w_d (w_n = sqrt(k/m), zeta = c / (2 m w_n), w_d = w_n sqrt(1 -
//      zeta^2)) whatever the frequency omega of the (zero) periodic solution it is linearised on,
//      and the centroid selection must return exactly these representatives (not lambda + i k
//      omega); n DOF: the eigenvalues of the state matrix [0 I; -M^-1 K, -M^-1 C];
//  (b) the folds of the Duffing response curve q'' + 0.05 q' + q + 0.1 q^3 = 0.18 cos(Omega t)
//      (duffing_problem.hpp): where dOmega/ds changes sign the HB Jacobian is singular, so a real
//      exponent crosses zero there (a turning point of a branch of periodic solutions has a
//      Floquet multiplier +1: Seydel, "Practical Bifurcation and Stability Analysis", 3rd ed.,
//      Springer (2010), ch. 7); the middle branch is unstable, the outer ones stable; and
//      Liouville's formula rho_1 rho_2 = det Phi(T) = exp(-(c/m) T), i.e.
//      Re(lambda_1 + lambda_2) = -c/m = -0.05 (ibid.), which the truncated Hill problem keeps;
//  (c) the monodromy matrix Phi(T) of the variational equation, integrated over one period by
//      RK4 from the HB solution (H = 7), on the three branches of the Duffing curve; and the
//      Mathieu equation q'' + 0.05 q' + (1 + 0.8 cos(omega t)) q = 0 (the parametric excitation
//      of a gear mesh), whose principal tongue around omega = 2 is a period doubling (two real
//      negative multipliers) and whose second tongue around omega = 1 has a real multiplier > 1
//      (Nayfeh & Mook, "Nonlinear Oscillations", Wiley (1979), ch. 5).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <complex>
#pragma GCC diagnostic pop

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/hbm/harmonic_balance.hpp"
#include "geardyn/hbm/stability.hpp"
#include "hbm/duffing_problem.hpp"

namespace geardyn::hbm {
namespace {

using Complex = std::complex<double>;
using Instability = FloquetResult::Instability;
using testing::kDamping;
using testing::kMass;

// dR/dX of the linear system (no nonlinear force) at X = 0.
Eigen::MatrixXd linear_jacobian(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C,
                                const Eigen::MatrixXd& K, int harmonics, double omega) {
  const HarmonicBasis basis(harmonics, 2 * harmonics + 2);
  const auto n = M.rows() * basis.size();
  const HarmonicBalance hb(M, C, K, basis, {}, Eigen::VectorXd::Zero(n));
  Eigen::MatrixXd J;
  hb.residual(Eigen::VectorXd::Zero(n), omega, &J);
  return J;
}

// Largest distance between two sets of two complex numbers, under the better pairing.
double pair_distance(Complex a0, Complex a1, Complex b0, Complex b1) {
  return std::min(std::max(std::abs(a0 - b0), std::abs(a1 - b1)),
                  std::max(std::abs(a0 - b1), std::abs(a1 - b0)));
}

// (a) Tolerance 1e-10 relative: no truncation is involved (the exact eigenvector is harmonic 0
// alone), only the rounding of a dense eigen-solve of a matrix of norm up to (2 H omega)^2 ~ 1e4
// here, ~1e-12 relative; observed <= 1e-15.
TEST(HillStability, SingleDofLinearOscillatorExact) {
  const double m = 2.0, c = 0.4, k = 50.0;
  const double wn = std::sqrt(k / m), zeta = c / (2.0 * m * wn);
  const Complex exact(-zeta * wn, wn * std::sqrt(1.0 - zeta * zeta));
  const Eigen::MatrixXd M = Eigen::MatrixXd::Constant(1, 1, m);
  const Eigen::MatrixXd C = Eigen::MatrixXd::Constant(1, 1, c);
  const Eigen::MatrixXd K = Eigen::MatrixXd::Constant(1, 1, k);
  // w_d = 4.999 sits between harmonics of every omega, far from the folding of families.
  for (int H : {0, 3, 7}) {
    for (double omega : {1.3, 3.0, 7.7}) {
      const FloquetResult r = hill_stability(linear_jacobian(M, C, K, H, omega), M, C, H, omega);
      ASSERT_EQ(r.status, Status::Ok) << r.message;
      ASSERT_EQ(r.exponents.size(), 2);
      EXPECT_LE(std::abs(r.exponents[0] - exact), 1e-10 * std::abs(exact)) << H << " " << omega;
      EXPECT_LE(std::abs(r.exponents[1] - std::conj(exact)), 1e-10 * std::abs(exact));
      EXPECT_NEAR(r.max_real_part, -zeta * wn, 1e-10 * std::abs(exact));
      EXPECT_TRUE(r.stable);
      EXPECT_EQ(r.kind, Instability::None);
      if (H > 0) {
        EXPECT_NEAR(r.sorting_gap, 1.0, 1e-9);  // centred vs first shifted member
      }
    }
  }
}

TEST(HillStability, MultiDofNonProportionalDampingMatchesStateMatrix) {
  Eigen::MatrixXd M(2, 2), C(2, 2), K(2, 2);
  M << 1.0, 0.0, 0.0, 2.0;
  C << 0.3, -0.1, -0.1, 0.1;  // not a combination of M and K: complex modes
  K << 30.0, -10.0, -10.0, 20.0;
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(4, 4);
  S.topRightCorner(2, 2).setIdentity();
  S.bottomLeftCorner(2, 2) = -M.inverse() * K;
  S.bottomRightCorner(2, 2) = -M.inverse() * C;
  Eigen::VectorXcd exact = Eigen::EigenSolver<Eigen::MatrixXd>(S).eigenvalues();
  std::sort(exact.begin(), exact.end(), [](Complex a, Complex b) {
    return a.real() != b.real() ? a.real() > b.real() : a.imag() > b.imag();
  });
  const double omega = 2.2;
  const FloquetResult r = hill_stability(linear_jacobian(M, C, K, 5, omega), M, C, 5, omega);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.exponents.size(), 4);
  for (int j = 0; j < 4; ++j)
    EXPECT_LE(std::abs(r.exponents[j] - exact[j]), 1e-10 * std::abs(exact[j])) << j;
  EXPECT_TRUE(r.stable);
}

TEST(HillStability, RejectsBadInput) {
  const Eigen::MatrixXd J = Eigen::MatrixXd::Identity(6, 6);
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::MatrixXd C = Eigen::MatrixXd::Zero(2, 2);
  Eigen::MatrixXd singular(2, 2);
  singular << 1.0, 1.0, 1.0, 1.0;
  EXPECT_THROW(hill_stability(J, singular, C, 1, 1.0), InputError);
  EXPECT_THROW(hill_stability(J, I, C, 2, 1.0), InputError);  // J is not 2 (2H + 1)
  EXPECT_THROW(hill_stability(J, I, C, 1, 0.0), InputError);
  EXPECT_THROW(hill_stability(J, I, C, -1, 1.0), InputError);
  HillOptions o;
  o.kind_tolerance = 0.5;
  EXPECT_THROW(hill_stability(J, I, C, 1, 1.0, o), InputError);
  EXPECT_EQ(hill_stability(J, I, C, 1, 1.0).status, Status::Ok);
}

// (b) Every point of the curve except the two nearest the folds, whose side of the fold is
// undecided at the continuation's step; Liouville's sum to 1e-12 (observed 3e-15: the truncated
// problem keeps the pairing of the exponents about -c / 2m exactly, up to rounding).
void check_duffing_branches(int harmonics) {
  const HarmonicBalance hb = testing::duffing_system(harmonics);
  const ContinuationResult curve = testing::duffing_continuation(hb);
  ASSERT_EQ(curve.status, Status::Ok) << curve.message;
  const auto [upper_fold, lower_fold] = testing::fold_points(curve);
  ASSERT_GT(upper_fold, 0);
  ASSERT_GT(lower_fold, upper_fold);
  const Eigen::MatrixXd M = Eigen::MatrixXd::Constant(1, 1, kMass);
  const Eigen::MatrixXd C = Eigen::MatrixXd::Constant(1, 1, kDamping);
  int changes = 0;
  bool previous = true;
  const std::vector<FloquetResult> along = stability_along(hb, curve);
  ASSERT_EQ(along.size(), curve.points.size());
  for (int i = 0; i < static_cast<int>(curve.points.size()); ++i) {
    const ContinuationPoint& p = curve.points[static_cast<std::size_t>(i)];
    Eigen::MatrixXd J;
    hb.residual(p.X, p.omega, &J);
    const FloquetResult r = hill_stability(J, M, C, harmonics, p.omega);
    EXPECT_EQ(along[static_cast<std::size_t>(i)].stable, r.stable);  // the convenience loop
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    ASSERT_EQ(r.exponents.size(), 2);
    EXPECT_NEAR(r.exponents.real().sum(), -kDamping / kMass, 1e-12) << "omega " << p.omega;
    if (r.stable != previous) ++changes;
    previous = r.stable;
    if (i == upper_fold || i == lower_fold) continue;
    const bool middle = i > upper_fold && i < lower_fold;
    EXPECT_EQ(r.stable, !middle) << "omega " << p.omega << ", point " << i;
    if (middle) {
      EXPECT_EQ(r.kind, Instability::Fold) << "omega " << p.omega;
      EXPECT_LE(std::abs(r.exponents[0].imag()), 1e-12 * p.omega);
      EXPECT_GT(r.exponents[0].real(), 0.0);
    } else {
      EXPECT_EQ(r.kind, Instability::None) << "omega " << p.omega;
    }
  }
  EXPECT_EQ(changes, 2);  // stable -> unstable at the upper fold, back at the lower one
}

// The fold count needs no Jacobian: it must give Hill's verdict at every point of the Duffing
// curve off the two turning points, and an unstable middle branch only.
TEST(FoldCount, AgreesWithHillOnTheDuffingCurve) {
  const HarmonicBalance hb = testing::duffing_system(3);
  const ContinuationResult curve = testing::duffing_continuation(hb);
  ASSERT_EQ(curve.status, Status::Ok) << curve.message;
  const auto [upper_fold, lower_fold] = testing::fold_points(curve);
  std::vector<double> omega;
  for (const auto& p : curve.points) omega.push_back(p.omega);
  const std::vector<char> folds = fold_unstable(omega);
  ASSERT_EQ(folds.size(), omega.size());
  const std::vector<FloquetResult> hill = stability_along(hb, curve);
  int unstable = 0;
  for (int i = 0; i < static_cast<int>(omega.size()); ++i) {
    if (i == upper_fold || i == lower_fold) continue;
    EXPECT_EQ(folds[static_cast<std::size_t>(i)] != 0, !hill[static_cast<std::size_t>(i)].stable)
        << "omega " << omega[static_cast<std::size_t>(i)];
    unstable += folds[static_cast<std::size_t>(i)];
  }
  EXPECT_GT(unstable, 10);
  EXPECT_EQ(fold_unstable({1.0, 2.0, 2.0, 3.0}), (std::vector<char>{0, 0, 0, 0}));
  EXPECT_EQ(fold_unstable({1.0, 3.0, 2.0, 2.5, 4.0}), (std::vector<char>{0, 0, 1, 0, 0}));
  EXPECT_TRUE(fold_unstable({}).empty());
}

TEST(HillStability, DuffingSingleHarmonicUnstableBetweenTheFolds) { check_duffing_branches(1); }
TEST(HillStability, DuffingFiveHarmonicsUnstableBetweenTheFolds) { check_duffing_branches(5); }

// Monodromy matrix of the Duffing variational equation over one period, by RK4 from theta = 0
// on the periodic solution X; `closure` = |state(T) - state(0)|, a check of the HB orbit.
Eigen::Matrix2d duffing_monodromy(const Eigen::VectorXd& X, int harmonics, double omega, int steps,
                                  double& closure) {
  const auto [q0, dq0] = testing::series_at(X, harmonics, 0.0);
  testing::DuffingState s;
  s.q = q0;
  s.v = omega * dq0;
  const double h = 2.0 * std::numbers::pi / omega / steps;
  for (int k = 0; k < steps; ++k) s = testing::rk4_step(k * h, s, h, omega, true);
  closure = std::hypot(s.q - q0, s.v - omega * dq0);
  return s.Phi;
}

// (c) Tolerance. The monodromy side is exact to ~1e-12 (RK4, 4000 steps per period: doubling
// them changes the multipliers by < 1e-11). The difference is the harmonic truncation of the
// HB orbit and of Hill's problem, measured by the amplitude a_H of the last kept harmonic: the
// multipliers differ by 0.2-0.4 a_7 (4.3e-6 next to the upper fold, where a_7 = 1.2e-5, and
// 2e-12 at Omega = 0.8; at H = 9 and 11 the difference falls with a_H, to 8e-8 and 1.4e-9).
// Asserted: |rho_Hill - rho_RK4| <= a_7 + 1e-9, i.e. < 1.2e-5 < the brief's 1e-4 everywhere.
TEST(HillStability, DuffingMultipliersMatchTheMonodromyMatrix) {
  constexpr int H = 7;
  const HarmonicBalance hb = testing::duffing_system(H);
  const ContinuationResult curve = testing::duffing_continuation(hb);
  ASSERT_EQ(curve.status, Status::Ok) << curve.message;
  const auto [upper_fold, lower_fold] = testing::fold_points(curve);
  ASSERT_GT(lower_fold, upper_fold + 6);
  const auto& pts = curve.points;
  const double w_mid = 0.5 * (pts[static_cast<std::size_t>(upper_fold)].omega +
                              pts[static_cast<std::size_t>(lower_fold)].omega);
  auto nearest = [&pts](double target, int from, int to) {  // on points [from, to)
    int best = from;
    for (int i = from; i < to; ++i)
      if (std::abs(pts[static_cast<std::size_t>(i)].omega - target) <
          std::abs(pts[static_cast<std::size_t>(best)].omega - target))
        best = i;
    return best;
  };
  const int n = static_cast<int>(pts.size());
  struct Pick {
    int index;
    bool stable;
  };
  // Below the hysteresis; the three branches at one frequency in it; next to both folds on the
  // unstable branch (three continuation steps in); above the hysteresis.
  const std::vector<Pick> picks = {{nearest(0.8, 0, upper_fold), true},
                                   {nearest(w_mid, 0, upper_fold), true},
                                   {nearest(w_mid, upper_fold + 1, lower_fold), false},
                                   {upper_fold + 3, false},
                                   {lower_fold - 3, false},
                                   {nearest(w_mid, lower_fold + 1, n), true},
                                   {nearest(1.8, lower_fold + 1, n), true}};
  const Eigen::MatrixXd M = Eigen::MatrixXd::Constant(1, 1, kMass);
  const Eigen::MatrixXd C = Eigen::MatrixXd::Constant(1, 1, kDamping);
  for (const Pick& pick : picks) {
    const ContinuationPoint& p = pts[static_cast<std::size_t>(pick.index)];
    Eigen::MatrixXd J;
    hb.residual(p.X, p.omega, &J);
    const FloquetResult r = hill_stability(J, M, C, H, p.omega);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    double closure = 0.0;
    const Eigen::Vector2cd rho =
        Eigen::EigenSolver<Eigen::Matrix2d>(duffing_monodromy(p.X, H, p.omega, 4000, closure))
            .eigenvalues();
    const double tol = hb.amplitude(p.X, 0, H) + 1e-9;
    EXPECT_LE(closure, tol) << "omega " << p.omega;
    EXPECT_LE(pair_distance(r.multipliers[0], r.multipliers[1], rho[0], rho[1]), tol)
        << "omega " << p.omega;
    // The real parts: max Re lambda = ln(max |rho|) / T.
    const double period = 2.0 * std::numbers::pi / p.omega;
    const double top = std::max(std::abs(rho[0]), std::abs(rho[1]));
    EXPECT_NEAR(r.max_real_part, std::log(top) / period, tol / period) << "omega " << p.omega;
    EXPECT_EQ(r.stable, pick.stable) << "omega " << p.omega;
    EXPECT_EQ(top <= 1.0, pick.stable) << "omega " << p.omega;
  }
}

// Mathieu equation q'' + c q' + (delta + eps cos(omega t)) q = 0 (1 DOF, zero periodic solution):
// its Hill Jacobian D(omega) + [coefficients of eps cos(theta) p], and its monodromy matrix.
constexpr double kMathieuC = 0.05, kMathieuDelta = 1.0, kMathieuEps = 0.8;

Eigen::MatrixXd mathieu_jacobian(int harmonics, double omega) {
  const HarmonicBasis basis(harmonics, 64);  // > 2 (H + 1): the product is projected exactly
  Eigen::MatrixXd J = linear_jacobian(
      Eigen::MatrixXd::Constant(1, 1, 1.0), Eigen::MatrixXd::Constant(1, 1, kMathieuC),
      Eigen::MatrixXd::Constant(1, 1, kMathieuDelta), harmonics, omega);
  Eigen::VectorXd modulation(basis.time_samples());
  for (int j = 0; j < basis.time_samples(); ++j)
    modulation(j) = kMathieuEps * std::cos(2.0 * std::numbers::pi * j / basis.time_samples());
  J += basis.projection() * modulation.asDiagonal() * basis.sampling();
  return J;
}

Eigen::Matrix2d mathieu_monodromy(double omega, int steps) {
  const double h = 2.0 * std::numbers::pi / omega / steps;
  auto rate = [omega](double t, const Eigen::Matrix2d& Phi) {
    Eigen::Matrix2d A;
    A << 0.0, 1.0, -(kMathieuDelta + kMathieuEps * std::cos(omega * t)), -kMathieuC;
    return Eigen::Matrix2d(A * Phi);
  };
  Eigen::Matrix2d Phi = Eigen::Matrix2d::Identity();
  for (int k = 0; k < steps; ++k) {
    const double t = k * h;
    const Eigen::Matrix2d k1 = rate(t, Phi), k2 = rate(t + 0.5 * h, Phi + 0.5 * h * k1);
    const Eigen::Matrix2d k3 = rate(t + 0.5 * h, Phi + 0.5 * h * k2);
    const Eigen::Matrix2d k4 = rate(t + h, Phi + h * k3);
    Phi += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return Phi;
}

// (c) Mathieu: the coefficient's spectrum is one harmonic, so Hill's truncation error falls
// fast (observed: 2e-6 at H = 3, 7e-13 at H = 7); RK4 with 4000 steps per period is exact to
// ~1e-12. Asserted 1e-10 at H = 7. The kinds: two real negative multipliers in the principal
// tongue (omega = 2) must be reported once each (not one of them twice), a real multiplier > 1
// in the second tongue (omega = 0.95, 1), a complex pair inside the unit circle elsewhere.
TEST(HillStability, MathieuTonguesMatchTheMonodromyMatrix) {
  constexpr int H = 7;
  const Eigen::MatrixXd M = Eigen::MatrixXd::Constant(1, 1, 1.0);
  const Eigen::MatrixXd C = Eigen::MatrixXd::Constant(1, 1, kMathieuC);
  const std::vector<std::pair<double, Instability>> cases = {{2.0, Instability::PeriodDoubling},
                                                             {0.95, Instability::Fold},
                                                             {1.0, Instability::Fold},
                                                             {1.5, Instability::None},
                                                             {2.5, Instability::None}};
  for (const auto& [omega, kind] : cases) {
    const FloquetResult r = hill_stability(mathieu_jacobian(H, omega), M, C, H, omega);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    ASSERT_EQ(r.multipliers.size(), 2);
    const Eigen::Vector2cd rho =
        Eigen::EigenSolver<Eigen::Matrix2d>(mathieu_monodromy(omega, 4000)).eigenvalues();
    EXPECT_LE(pair_distance(r.multipliers[0], r.multipliers[1], rho[0], rho[1]), 1e-10)
        << "omega " << omega;
    EXPECT_EQ(r.kind, kind) << "omega " << omega;
    EXPECT_EQ(r.stable, kind == Instability::None) << "omega " << omega;
    EXPECT_NEAR(r.exponents.real().sum(), -kMathieuC, 1e-12) << "omega " << omega;
    if (kind == Instability::PeriodDoubling) {
      EXPECT_LT(rho[0].real(), 0.0);
      EXPECT_LT(rho[1].real(), 0.0);
      EXPECT_NEAR(r.exponents[0].imag(), 0.5 * omega, 1e-10);
      EXPECT_NEAR(r.exponents[1].imag(), 0.5 * omega, 1e-10);
      EXPECT_GT(std::abs(r.multipliers[0] - r.multipliers[1]), 1.0);  // two distinct ones
    }
  }
}

}  // namespace
}  // namespace geardyn::hbm
