// Nonlinear modes by the extended periodic motion concept (hbm/nonlinear_modes.hpp; Krack,
// Computers & Structures 154 (2015) 59-71), against closed forms:
//  * Duffing q'' + c q' + q + alpha q^3 = 0, alpha = 0.1: at H = 1 the backbone
//    omega^2 = 1 + 3/4 alpha a^2 (Nayfeh & Mook, "Nonlinear Oscillations", Wiley 1979, §4.1;
//    the first harmonic of cos^3 is 3/4 cos), and the EPMC damping xi = c exactly (C = c M is
//    mass-proportional, so -xi M q' cancels it at every amplitude); at H = 7 the exact period of
//    the undamped oscillator of peak amplitude A (Kovacic & Brennan (eds.), "The Duffing
//    Equation", Wiley 2011, ch. 2): omega = pi sqrt(1 + alpha A^2) / (2 K(m)),
//    m = alpha A^2 / (2 (1 + alpha A^2)), K the complete elliptic integral of the first kind.
//  * a mass on a spring k and a Jenkins element (k_t, F) to ground, H = 1: Griffin's equivalent
//    stiffness and damping of the Jenkins element under u = a cos (hbm/jenkins.hpp): omega^2 =
//    (k + k_eq(a)) / m, W = 4 F (a - F / k_t) = pi a^2 c_eq omega, zeta = c_eq / (2 m omega).
//  * NLvib's example 04 (Krack & Gross, "Harmonic Balance for Nonlinear Vibration Problems",
//    Springer 2019; EXAMPLES/04_twoDOFoscillator_cubicSpring_NM of NLvib 1.3: m = 1, 1, springs
//    1, 1, 1 in a chain, a cubic spring 0.5 q_1^3 on the first DOF, H = 9, first mode): hardening
//    backbone from omega_0 = 1 towards, but below, sqrt(2) (the second DOF on its two springs
//    with the first one held by the stiffening spring), and the small-amplitude slope of the
//    single-mode perturbation omega^2 = 1 + 3/4 * 0.5 phi_1^4 a^2 = 1 + (3/32) a^2.
//  * NLvib's example 05 (2-DOF, regularised dry friction): the stuck and free-sliding limits, the
//    damping peak between them and the energy balance (details at the test).
//  * a linear 2-DOF system with Rayleigh damping and structural loss: its modal frequency and
//    damping ratio at every amplitude; the Jacobian against finite differences; input errors.
#include "geardyn/hbm/nonlinear_modes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/hbm/jenkins.hpp"

namespace geardyn::hbm {
namespace {

constexpr double kAlpha = 0.1;

// f = alpha u^3 on one coordinate.
class CubicSpring final : public PointwiseElement {
 public:
  explicit CubicSpring(double alpha) : alpha_(alpha) {}
  int size() const override { return 1; }
  std::string describe() const override { return "cubic spring"; }
  void pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd&, double, double,
                 ElementStep& out) const override {
    out.force[0] = alpha_ * u[0] * u[0] * u[0];
    out.stiffness(0, 0) = 3.0 * alpha_ * u[0] * u[0];
  }

 private:
  double alpha_;
};

// The Jenkins element of hbm/jenkins.hpp on one coordinate; time state (T, u) of the last step.
class Jenkins final : public NonlinearElement {
 public:
  explicit Jenkins(JenkinsElement e) : e_(e) {}
  int size() const override { return 1; }
  std::string describe() const override { return "jenkins"; }
  void harmonic_force(const HarmonicBasis& basis, const Eigen::VectorXd& w, double,
                      Eigen::VectorXd& f, Eigen::MatrixXd* J, Eigen::VectorXd*) const override {
    const JenkinsResponse r = jenkins_response(e_, basis, w);
    f += r.coefficients;
    if (J != nullptr) *J += r.jacobian;
  }
  ElementLoop loop(const HarmonicBasis& basis, const Eigen::VectorXd& w, double) const override {
    const JenkinsResponse r = jenkins_response(e_, basis, w);
    ElementLoop l;
    l.energy_per_cycle = r.energy_per_cycle;
    l.stick_fraction = r.stick_fraction;
    l.displacement = basis.to_time(w);
    l.force = r.force;
    return l;
  }
  int state_size() const override { return 2; }
  Eigen::VectorXd initial_state(const Eigen::VectorXd& u) const override {
    return Eigen::Vector2d(0.0, u[0]);
  }
  void time_force(const Eigen::VectorXd& u, const Eigen::VectorXd&, double, double,
                  const Eigen::VectorXd& state, ElementStep& out) const override {
    const double trial = state[0] + e_.stiffness * (u[0] - state[1]);
    const bool stick = std::abs(trial) < e_.slip_force;
    const double T = stick ? trial : std::copysign(e_.slip_force, trial);
    out.force = Eigen::VectorXd::Constant(1, T);
    out.stiffness = Eigen::MatrixXd::Constant(1, 1, stick ? e_.stiffness : 0.0);
    out.damping = Eigen::MatrixXd::Zero(1, 1);
    out.state = Eigen::Vector2d(T, u[0]);
  }

 private:
  JenkinsElement e_;
};

// A system of n_dof DOFs with the given matrices and one element on the coordinate B q.
ElementSystem system_with(Eigen::MatrixXd M, Eigen::MatrixXd C, Eigen::MatrixXd K,
                          std::shared_ptr<const NonlinearElement> element, Eigen::MatrixXd B) {
  ElementSystem s;
  s.M = std::move(M);
  s.C = std::move(C);
  s.K = std::move(K);
  s.elements.push_back({std::move(element), "nl", std::move(B)});
  return s;
}

ElementSystem duffing(double c) {
  const Eigen::MatrixXd one = Eigen::MatrixXd::Constant(1, 1, 1.0);
  return system_with(one, c * one, one, std::make_shared<CubicSpring>(kAlpha), one);
}

// Coefficient c of DOF d in DOF-major harmonics X of basis size s.
double coefficient(const Eigen::VectorXd& X, int s, int d, int c) { return X[d * s + c]; }

// H = 1 Duffing, undamped and lightly damped (zeta_0 = 0.01): the backbone and xi = c.
// Tolerances: Newton stops at ||R|| <= 1e-12 kappa (kappa = 1 here) and its last step is
// quadratic, so omega^2 and xi carry round-off only; the AFT of a cubic is exact with 64 samples
// (> 4H); 1e-11 relative on omega^2 and 1e-12 absolute on xi are asserted.
TEST(NonlinearModes, DuffingSingleHarmonicBackbone) {
  for (const double c : {0.0, 0.02}) {
    const HarmonicBasis basis(1, default_time_samples(1, 3));
    NonlinearModeOptions o;
    o.amplitude_start = 1e-2;
    o.amplitude_end = 4.0;
    o.tolerance = 1e-12;
    const NonlinearModeResult r = nonlinear_mode(duffing(c), basis, o);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    EXPECT_NEAR(r.linear.omega, 1.0, 1e-14);
    EXPECT_NEAR(r.linear.xi, c, 1e-14);
    ASSERT_GT(r.points.size(), 20u);
    EXPECT_GE(r.points.back().amplitude, 4.0);
    for (const auto& p : r.points) {
      const double a = p.amplitude;
      const double w2 = 1.0 + 0.75 * kAlpha * a * a;
      EXPECT_NEAR(p.omega * p.omega, w2, 1e-11 * w2) << "a = " << a;
      EXPECT_NEAR(p.xi, c, 1e-12) << "a = " << a;
      EXPECT_NEAR(p.damping_ratio, c / (2.0 * p.omega), 1e-12);
      // The amplitude and phase conditions: q = a cos(omega t).
      EXPECT_NEAR(coefficient(p.X, 3, 0, HarmonicBasis::cos_index(1)), a, 1e-12 * a);
      EXPECT_NEAR(coefficient(p.X, 3, 0, HarmonicBasis::sin_index(1)), 0.0, 1e-12 * a);
      // W = c int q'^2 dt = pi c omega a^2, what the viscous damper dissipates.
      EXPECT_NEAR(p.energy_per_cycle, std::numbers::pi * c * p.omega * a * a, 1e-11 * a * a);
    }
  }
}

// The period of q'' + q + alpha q^3 = 0 from q(0) = A, q'(0) = 0: with q = A sin(phi) the energy
// integral gives T = 4 int_0^{pi/2} dphi / sqrt(1 + alpha A^2 (1 + sin^2 phi) / 2), whose
// integrand is smooth and periodic, so the midpoint rule converges geometrically; 2000 points
// reach round-off. Checked against the elliptic-integral closed form.
double exact_omega(double A) {
  constexpr int n = 2000;
  double T = 0.0;
  for (int j = 0; j < n; ++j) {
    const double phi = (j + 0.5) * (std::numbers::pi / 2.0) / n;
    const double s = std::sin(phi);
    T += 1.0 / std::sqrt(1.0 + 0.5 * kAlpha * A * A * (1.0 + s * s));
  }
  T *= 4.0 * (std::numbers::pi / 2.0) / n;
  return 2.0 * std::numbers::pi / T;
}

TEST(NonlinearModes, ExactDuffingPeriodByQuadratureMatchesTheEllipticIntegral) {
  for (const double A : {0.1, 1.0, 3.0, 10.0}) {
    const double m = kAlpha * A * A / (2.0 * (1.0 + kAlpha * A * A));
    // std::comp_ellint_1 takes the modulus k, m = k^2.
    const double w = std::numbers::pi * std::sqrt(1.0 + kAlpha * A * A) /
                     (2.0 * std::comp_ellint_1(std::sqrt(m)));
    EXPECT_NEAR(exact_omega(A), w, 1e-13 * w) << "A = " << A;
  }
}

// H = 7: the frequency against the exact one at the peak amplitude A = q(0) = sum_h a_h (the
// phase condition makes q even in t; only odd cosine harmonics are present). The exact motion
// is a Jacobi cn, whose odd harmonics fall off as the nome Q ~ m / 16 + 8 (m / 16)^2 per order
// (Abramowitz & Stegun 16.23.2), so the truncation after the 7th leaves ~Q^4 relative: at the
// last point (A = 4.42, m = 0.33, Q = 0.024) 3.3e-7, the error found there (2.4e-7). The AFT is
// exact (n_time > 4H) and Newton is at round-off, so the spec's 1e-6 holds with margin 4.
TEST(NonlinearModes, DuffingMultiHarmonicMatchesTheExactPeriod) {
  const int H = 7;
  const HarmonicBasis basis(H, default_time_samples(H, 3));
  const int s = basis.size();
  NonlinearModeOptions o;
  o.amplitude_start = 1e-2;
  o.amplitude_end = 4.0;
  o.tolerance = 1e-12;
  const NonlinearModeResult r = nonlinear_mode(duffing(0.0), basis, o);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_GT(r.points.size(), 20u);
  double worst = 0.0;
  for (const auto& p : r.points) {
    double A = 0.0;
    for (int h = 0; h <= H; ++h) {
      const double ah = coefficient(p.X, s, 0, HarmonicBasis::cos_index(h));
      A += ah;
      if (h > 0) {
        EXPECT_NEAR(coefficient(p.X, s, 0, HarmonicBasis::sin_index(h)), 0.0, 1e-12);
      }
      if (h % 2 == 0) {
        EXPECT_NEAR(ah, 0.0, 1e-12) << "even harmonic " << h;
      }
    }
    const double exact = exact_omega(A);
    worst = std::max(worst, std::abs(p.omega - exact) / exact);
    EXPECT_NEAR(p.omega, exact, 1e-6 * exact) << "A = " << A;
    EXPECT_NEAR(p.xi, 0.0, 1e-12);
  }
  RecordProperty("worst_relative_frequency_error", std::to_string(worst));
}

// Mass m = 1 on a spring k = 1 and a Jenkins element k_t = 1, F = 0.1 to ground, H = 1: stuck
// (omega_0^2 = k + k_t = 2, no damping) below a = F / k_t = 0.1, then softening towards
// omega^2 = k and damped. Griffin's forms are the first harmonic of the exact loop under
// u = a cos, so the H = 1 EPMC must reproduce them up to the AFT sampling: the force's kink at
// the stick-slip switch falls between samples, an O((2 pi / n)^2) error of the Fourier integral
// and of the loop's trapezoidal area (hbm/jenkins_test.cpp): 3.8e-5 for n = 1024. Asserted:
// omega^2 to 1e-4 relative, and W and zeta to 1e-4 relative where W is resolved (a >= 2 F / k_t:
// W >= 4 F^2 / k_t; nearer the switch W -> 0 and its relative error grows like 1 / (a - F/k_t)).
constexpr double kSpring = 1.0, kTangential = 1.0, kSlip = 0.1;

struct Griffin {
  double k_eq, c_eq_omega, energy;
};

Griffin griffin(double a) {
  if (a <= kSlip / kTangential) return {kTangential, 0.0, 0.0};
  const double beta = std::acos(1.0 - 2.0 * kSlip / (kTangential * a));
  return {kTangential / std::numbers::pi * (beta - 0.5 * std::sin(2.0 * beta)),
          4.0 * kSlip / (std::numbers::pi * a) * (1.0 - kSlip / (kTangential * a)),
          4.0 * kSlip * (a - kSlip / kTangential)};
}

TEST(NonlinearModes, JenkinsOscillatorMatchesGriffin) {
  const HarmonicBasis basis(1, 1024);
  const Eigen::MatrixXd one = Eigen::MatrixXd::Constant(1, 1, 1.0);
  const ElementSystem sys =
      system_with(one, 0.0 * one, kSpring * one,
                  std::make_shared<Jenkins>(JenkinsElement{kTangential, kSlip}), one);
  NonlinearModeOptions o;
  o.amplitude_start = 1e-3;
  o.amplitude_end = 10.0;
  o.tolerance = 1e-12;
  const NonlinearModeResult r = nonlinear_mode(sys, basis, o);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_NEAR(r.linear.omega, std::sqrt(kSpring + kTangential), 1e-14);
  EXPECT_NEAR(r.linear.xi, 0.0, 1e-14);
  ASSERT_GT(r.points.size(), 30u);
  double zeta_max = 0.0;
  for (const auto& p : r.points) {
    const double a = p.amplitude;
    const Griffin g = griffin(a);
    const double w2 = kSpring + g.k_eq;
    EXPECT_NEAR(p.omega * p.omega, w2, 1e-4 * w2) << "a = " << a;
    zeta_max = std::max(zeta_max, p.damping_ratio);
    if (a < 2.0 * kSlip / kTangential) continue;
    // zeta = c_eq / (2 m omega), c_eq = (c_eq omega) / omega.
    const double zeta = g.c_eq_omega / (2.0 * p.omega * p.omega);
    EXPECT_NEAR(p.damping_ratio, zeta, 1e-4 * zeta) << "a = " << a;
    EXPECT_NEAR(p.energy_per_cycle, g.energy, 1e-4 * g.energy) << "a = " << a;
    ASSERT_EQ(p.element_energy.size(), 1);
    EXPECT_NEAR(p.element_energy[0], g.energy, 1e-4 * g.energy) << "a = " << a;
  }
  // The friction damping peaks at a few F / k_t (about 0.06 here) and vanishes at both ends.
  EXPECT_GT(zeta_max, 0.05);
  EXPECT_LT(r.points.front().damping_ratio, 1e-12);
  EXPECT_LT(r.points.back().damping_ratio, 0.5 * zeta_max);
}

// Linear limit: no element, Rayleigh damping C = 0.01 K and a structural loss K_loss = 0.02 K on
// a 2-DOF system; the second mode. Its shape and frequency omega_1 stay those of the linear mode
// at every amplitude, and the negative damping balances both: xi omega_1 = phi^T (omega_1 C +
// K_loss) phi, i.e. zeta = 0.01 omega_1 / 2 + 0.02 / 2 (the structural loss counts eta / 2).
// Newton at round-off: 1e-12 relative.
TEST(NonlinearModes, LinearSystemKeepsItsModalFrequencyAndDamping) {
  Eigen::MatrixXd M(2, 2), K(2, 2);
  M << 1.0, 0.0, 0.0, 2.0;
  K << 3.0, -1.0, -1.0, 1.0;
  ElementSystem sys;
  sys.M = M;
  sys.K = K;
  sys.C = 0.01 * K;
  sys.K_loss = 0.02 * K;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  const double w1 = std::sqrt(eig.eigenvalues()[1]);
  const double zeta = 0.005 * w1 + 0.01;
  NonlinearModeOptions o;
  o.mode = 1;
  o.amplitude_start = 1e-3;
  o.amplitude_end = 1e3;
  o.tolerance = 1e-12;
  const NonlinearModeResult r = nonlinear_mode(sys, HarmonicBasis(3, 16), o);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_NEAR(r.linear.omega, w1, 1e-12 * w1);
  EXPECT_NEAR(r.linear.damping_ratio, zeta, 1e-12 * zeta);
  ASSERT_GT(r.points.size(), 5u);
  for (const auto& p : r.points) {
    EXPECT_NEAR(p.omega, w1, 1e-12 * w1) << "a = " << p.amplitude;
    EXPECT_NEAR(p.damping_ratio, zeta, 1e-12 * zeta) << "a = " << p.amplitude;
    // W = xi pi omega a^2 for the fundamental alone (the higher harmonics are zero).
    const double a = p.amplitude;
    EXPECT_NEAR(p.energy_per_cycle, 2.0 * zeta * w1 * std::numbers::pi * w1 * a * a,
                1e-11 * zeta * w1 * w1 * a * a);
  }
}

// NLvib example 04, H = 9 (its harmonic order), first mode from a = 1e-2 to 10 (NLvib goes on
// to a = 10^pi, through the internal-resonance loops that begin near log10(energy) = 2.4).
TEST(NonlinearModes, NLvibTwoDofCubicSpringBackboneHardens) {
  const int H = 9;
  const HarmonicBasis basis(H, default_time_samples(H, 3));
  const int s = basis.size();
  Eigen::MatrixXd K(2, 2);
  K << 2.0, -1.0, -1.0, 2.0;
  const ElementSystem sys =
      system_with(Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Zero(2, 2), K,
                  std::make_shared<CubicSpring>(0.5), Eigen::RowVector2d(1.0, 0.0));
  NonlinearModeOptions o;
  o.amplitude_start = 1e-2;
  o.amplitude_end = 10.0;
  o.tolerance = 1e-12;
  const NonlinearModeResult r = nonlinear_mode(sys, basis, o);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_GT(r.points.size(), 20u);
  // The linear mode: omega_0 = 1, phi = (1, 1) / sqrt(2).
  EXPECT_NEAR(r.linear.omega, 1.0, 1e-14);
  EXPECT_NEAR(std::abs(r.linear.shape[0] - std::sqrt(0.5)), 0.0, 1e-14);
  EXPECT_NEAR(std::abs(r.linear.shape[1] - std::sqrt(0.5)), 0.0, 1e-14);
  // Small amplitude: (omega^2 - 1) / a^2 = 3/32 + O(a^2) (the next order of the perturbation
  // is a^2 times a coefficient of order 0.1: 1e-5 at a = 1e-2); 1e-4 of 3/32 is asserted.
  const auto& first = r.points.front();
  EXPECT_NEAR((first.omega * first.omega - 1.0) / (first.amplitude * first.amplitude), 3.0 / 32.0,
              1e-4 * 3.0 / 32.0);
  // Hardening, below sqrt(2), conservative; the first DOF's share of the fundamental shrinks
  // as its spring stiffens.
  double previous_omega = 0.0, previous_ratio = 2.0;
  for (const auto& p : r.points) {
    EXPECT_GT(p.omega, previous_omega) << "a = " << p.amplitude;
    EXPECT_LT(p.omega, std::sqrt(2.0));
    EXPECT_NEAR(p.xi, 0.0, 1e-12);
    const double ratio = coefficient(p.X, s, 0, HarmonicBasis::cos_index(1)) /
                         coefficient(p.X, s, 1, HarmonicBasis::cos_index(1));
    EXPECT_LT(ratio, previous_ratio + 1e-12) << "a = " << p.amplitude;
    previous_omega = p.omega;
    previous_ratio = ratio;
  }
  EXPECT_GT(r.points.back().omega, 1.2);
  RecordProperty("omega_at_a_10", std::to_string(r.points.back().omega));
}

// f = F tanh(u' / eps): NLvib's regularised dry friction ("tanhDryFriction").
class TanhFriction final : public PointwiseElement {
 public:
  TanhFriction(double slip_force, double eps) : F_(slip_force), eps_(eps) {}
  int size() const override { return 1; }
  std::string describe() const override { return "tanh friction"; }
  bool velocity_dependent() const override { return true; }
  void pointwise(const Eigen::VectorXd&, const Eigen::VectorXd& v, double, double,
                 ElementStep& out) const override {
    const double th = std::tanh(v[0] / eps_);
    out.force[0] = F_ * th;
    out.damping(0, 0) = F_ * (1.0 - th * th) / eps_;
  }

 private:
  double F_, eps_;
};

// NLvib example 05 (EXAMPLES/05_twoDOFoscillator_tanhDryFriction_NM of NLvib 1.3): masses 0.02
// and 1, springs 0, 40, 600 in a chain (K = [40 -40; -40 640]), F tanh(q_1' / eps) on the first
// DOF with F = 5, eps = 0.05; H = 21, 1024 samples; first mode, a from 10^-1.5 to 10 (NLvib's
// range). At rest the regularised friction is a damper of F / eps = 100 N s/m on the 0.02 kg
// mass: that DOF is overdamped and the oscillatory mode is the stuck one, omega^2 ~ 640 (the
// damper's compliance 40 / (100 omega) changes the 40 N/m spring by 1.6 % and omega^2 by
// 0.06 %: 1e-3 asserted). With the amplitude the contact slides: the frequency falls towards the
// free-sliding mode of (K, M), omega^2 = (52.8 - sqrt(867.84)) / 0.04 = 583.5 (24.16 rad/s), and
// the damping rises from ~0, peaks and falls again as F becomes small against the spring forces.
// At the slip onset (a ~ F / 40 N/m = 0.13) the frequency first rises by 0.12 % above the stuck
// one (found alike with H = 21 and H = 61, 2048 samples: a property of the regularised law, not
// of the truncation), hence the bound 1.002 omega_stuck.
// Checked: these limits and shapes (what NLvib's figures show), and the energy balance: the
// element's loop energy equals the energy the negative damping feeds, W (both are the
// friction's work; the trapezoidal loop of 1024 samples differs by O((2 pi / 1024)^2) relative
// times the loop's curvature: 1e-3 asserted).
TEST(NonlinearModes, NLvibTwoDofTanhFrictionSoftensAndDamps) {
  const int H = 21;
  const HarmonicBasis basis(H, 1024);
  Eigen::MatrixXd K(2, 2), M = Eigen::MatrixXd::Zero(2, 2);
  K << 40.0, -40.0, -40.0, 640.0;
  M(0, 0) = 0.02;
  M(1, 1) = 1.0;
  const ElementSystem sys =
      system_with(M, Eigen::MatrixXd::Zero(2, 2), K, std::make_shared<TanhFriction>(5.0, 0.05),
                  Eigen::RowVector2d(1.0, 0.0));
  NonlinearModeOptions o;
  o.amplitude_start = std::pow(10.0, -1.5);
  o.amplitude_end = 10.0;
  o.tolerance = 1e-10;
  const NonlinearModeResult r = nonlinear_mode(sys, basis, o);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_GT(r.points.size(), 20u);
  const double stuck = std::sqrt(640.0), free = std::sqrt((52.8 - std::sqrt(867.84)) / 0.04);
  EXPECT_NEAR(r.linear.omega, stuck, 1e-3 * stuck);
  EXPECT_LT(r.linear.damping_ratio, 1e-3);
  double zeta_max = 0.0;
  for (const auto& p : r.points) {
    zeta_max = std::max(zeta_max, p.damping_ratio);
    EXPECT_GT(p.omega, free) << "a = " << p.amplitude;
    EXPECT_LT(p.omega, stuck * (1.0 + 2e-3)) << "a = " << p.amplitude;
    EXPECT_NEAR(p.element_energy[0], p.energy_per_cycle, 1e-3 * p.energy_per_cycle)
        << "a = " << p.amplitude;
  }
  EXPECT_GT(zeta_max, 10.0 * r.points.front().damping_ratio);
  EXPECT_GT(zeta_max, 10.0 * r.points.back().damping_ratio);
  // At a = 10 the friction (5 N) is 1e-3 of the spring forces (~6000 N): 1e-3 of the free mode.
  EXPECT_NEAR(r.points.back().omega, free, 1e-3 * free);
}

// The EPMC Jacobian (dR/dz and dR/dlog10 a) against central differences, on a 2-DOF system
// with non-proportional damping, a cubic spring between the DOFs and H = 3 at a point off the
// solution. Step 1e-6 on z of order one: truncation O(1e-12) times the third derivative, round-
// off 1e-16 / 1e-6 = 1e-10 of the residual's terms; 1e-7 of the largest entry is asserted.
TEST(NonlinearModes, JacobianMatchesFiniteDifferences) {
  Eigen::MatrixXd M(2, 2), C(2, 2), K(2, 2);
  M << 1.0, 0.1, 0.1, 2.0;
  C << 0.03, -0.01, -0.01, 0.02;
  K << 3.0, -1.0, -1.0, 2.0;
  const ElementSystem sys =
      system_with(M, C, K, std::make_shared<CubicSpring>(0.7), Eigen::RowVector2d(1.0, -1.0));
  const HarmonicBasis basis(3, default_time_samples(3, 3));
  const ExtendedPeriodicMotion epmc(sys, basis, 1);
  Eigen::VectorXd z = epmc.linear_guess();
  for (Eigen::Index i = 0; i < z.size(); ++i) z[i] += 0.1 * std::sin(1.7 * static_cast<double>(i));
  const double p = 0.3;
  Eigen::MatrixXd J;
  Eigen::VectorXd dRdp;
  epmc.residual(z, p, &J, &dRdp);
  const double h = 1e-6;
  Eigen::MatrixXd fd(J.rows(), J.cols());
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    Eigen::VectorXd zp = z, zm = z;
    zp[i] += h;
    zm[i] -= h;
    fd.col(i) = (epmc.residual(zp, p) - epmc.residual(zm, p)) / (2.0 * h);
  }
  const Eigen::VectorXd fdp = (epmc.residual(z, p + h) - epmc.residual(z, p - h)) / (2.0 * h);
  EXPECT_LT((J - fd).cwiseAbs().maxCoeff(), 1e-7 * J.cwiseAbs().maxCoeff());
  EXPECT_LT((dRdp - fdp).cwiseAbs().maxCoeff(), 1e-7 * dRdp.cwiseAbs().maxCoeff());
}

TEST(NonlinearModes, BadInputThrows) {
  const HarmonicBasis basis(1, 64);
  NonlinearModeOptions o;
  o.mode = 1;  // a single DOF has mode 0 only
  EXPECT_THROW(nonlinear_mode(duffing(0.0), basis, o), InputError);
  o.mode = 0;
  o.amplitude_start = 0.0;
  EXPECT_THROW(nonlinear_mode(duffing(0.0), basis, o), InputError);
  o.amplitude_start = 1e-3;
  ElementSystem forced = duffing(0.0);
  forced.excitation = Eigen::Vector3d(0.0, 1.0, 0.0);
  EXPECT_THROW(nonlinear_mode(forced, basis, o), InputError);
  EXPECT_THROW(nonlinear_mode(duffing(0.0), HarmonicBasis(0, 8), o), InputError);
  Eigen::MatrixXd K(2, 2), M(2, 2);
  K << 2.0, -1.0, -1.0, 2.0;
  M << 1.0, 0.2, 0.0, 1.0;  // not symmetric
  EXPECT_THROW(nonlinear_mode(system_with(M, 0.0 * K, K, std::make_shared<CubicSpring>(1.0),
                                          Eigen::RowVector2d(1.0, 0.0)),
                              basis, o),
               InputError);
}

// A corrector that cannot converge (one Newton iteration to a tolerance below round-off) is
// reported with its status and the amplitude reached, never hidden.
TEST(NonlinearModes, FailedCorrectorIsReported) {
  const HarmonicBasis basis(3, default_time_samples(3, 3));
  NonlinearModeOptions o;
  o.amplitude_start = 1.0;
  o.amplitude_end = 2.0;
  o.tolerance = 1e-30;
  o.max_iterations = 1;
  const NonlinearModeResult r = nonlinear_mode(duffing(0.0), basis, o);
  EXPECT_EQ(r.status, Status::NotConverged);
  EXPECT_TRUE(r.points.empty());
  EXPECT_NE(r.message.find("nonlinear mode 0"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace geardyn::hbm
