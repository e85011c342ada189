// Hill's method with velocity-dependent elements (hbm/stability.hpp: the term Jv = dF_nl/dV of
// the first-order part D1; ElementHarmonicBalance::velocity_jacobian), against
//  (a) a linear viscous damper f = c_e u' written as a velocity-dependent PointwiseElement on a
//      2-DOF chain: the system is linear, so its Floquet exponents are the eigenvalues of
//      M q'' + (C + c_e B^T B) q' + K q = 0 (Hill's exponents of a linear system are its
//      eigenvalues, whatever omega: stability.hpp);
//  (b) a tanh-Coulomb (regularised friction) oscillator q'' + c q' + q + F tanh(q' / v_eps) =
//      P cos(omega t): the Floquet multipliers of the monodromy matrix of the time march
//      (hbm/periodic_time.hpp, RK4) at points of the harmonic-balance curve.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <complex>
#pragma GCC diagnostic pop

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/hbm/element_library.hpp"
#include "geardyn/hbm/element_system.hpp"
#include "geardyn/hbm/harmonic_balance.hpp"
#include "geardyn/hbm/periodic_time.hpp"
#include "geardyn/hbm/stability.hpp"

namespace geardyn::hbm {
namespace {

// f = c u' on one coordinate: a linear viscous damper as a pointwise law.
class ViscousDamper final : public PointwiseElement {
 public:
  explicit ViscousDamper(double c) : c_(c) {}
  int size() const override { return 1; }
  std::string describe() const override { return "viscous damper"; }
  void pointwise(const Eigen::VectorXd& /*u*/, const Eigen::VectorXd& v, double /*theta*/,
                 double /*omega*/, ElementStep& out) const override {
    out.force[0] = c_ * v[0];
    out.damping(0, 0) = c_;
  }
  bool velocity_dependent() const override { return true; }

 private:
  double c_;
};

// The eigenvalues of M q'' + C q' + K q = 0, by decreasing real part then imaginary part.
std::vector<std::complex<double>> linear_eigenvalues(const Eigen::MatrixXd& M,
                                                     const Eigen::MatrixXd& C,
                                                     const Eigen::MatrixXd& K) {
  const Eigen::Index n = M.rows();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = -M.partialPivLu().solve(K);
  A.bottomRightCorner(n, n) = -M.partialPivLu().solve(C);
  const Eigen::VectorXcd e = Eigen::EigenSolver<Eigen::MatrixXd>(A).eigenvalues();
  std::vector<std::complex<double>> out(e.data(), e.data() + e.size());
  std::sort(out.begin(), out.end(), [](std::complex<double> a, std::complex<double> b) {
    return a.real() != b.real() ? a.real() > b.real() : a.imag() > b.imag();
  });
  return out;
}

TEST(VelocityHill, ViscousDamperElementGivesTheLinearEigenvalues) {
  ElementSystem s;
  s.M = Eigen::Vector2d(1.0, 2.0).asDiagonal();
  s.K.resize(2, 2);
  s.K << 3.0, -1.0, -1.0, 1.0;
  s.C = 0.01 * s.K;
  const double damper = 0.3;
  Eigen::MatrixXd B(1, 2);
  B << 1.0, -1.0;
  s.elements.push_back({std::make_shared<ViscousDamper>(damper), "damper", B});
  s.excitation_harmonics = 1;
  s.excitation = Eigen::VectorXd::Zero(2 * 3);
  s.excitation[HarmonicBasis::cos_index(1)] = 1.0;
  const HarmonicBasis basis(5, 64);
  const ElementHarmonicBalance hb(s, basis);
  const double omega = 0.7;
  // Any motion: the element is linear, so J and Jv do not depend on it.
  Eigen::VectorXd X = Eigen::VectorXd::LinSpaced(hb.size(), -0.3, 0.5);
  const std::vector<std::complex<double>> exact =
      linear_eigenvalues(s.M, s.C + damper * B.transpose() * B, s.K);
  const FloquetResult hill = hill_stability(hb, X, omega);
  ASSERT_EQ(hill.status, Status::Ok) << hill.message;
  ASSERT_EQ(hill.exponents.size(), 4);
  // Both are eigenvalues of 4 x 4 (exact) and 44 x 44 (Hill) dense problems with entries of
  // order 1 and eigenvalues of order 1: rounding leaves ~1e-14; 1e-8 is the brief's bound.
  for (int j = 0; j < 4; ++j)
    EXPECT_LT(std::abs(hill.exponents[j] - exact[static_cast<std::size_t>(j)]), 1e-8)
        << "exponent " << j << ": " << hill.exponents[j] << " vs "
        << exact[static_cast<std::size_t>(j)];
  EXPECT_TRUE(hill.stable);
  // Without Jv the damper's damping is missing: the exponents are those of C alone (the
  // linearization J holds the damper's omega-coupling, not its lambda term); they differ by
  // the damper's share, far above the 1e-8.
  Eigen::MatrixXd J;
  hb.residual(X, omega, &J);
  const FloquetResult without = hill_stability(J, s.M, s.C, basis.harmonics(), omega);
  ASSERT_EQ(without.status, Status::Ok);
  EXPECT_GT(std::abs(without.max_real_part - hill.max_real_part), 1e-3);
  // Jv of the wrong size is refused.
  EXPECT_THROW(
      (void)hill_stability(J, Eigen::MatrixXd::Zero(3, 3), s.M, s.C, basis.harmonics(), omega),
      InputError);
}

// The velocity Jacobian of a pointwise law against central differences of its force
// coefficients in the velocity's coefficients (f depends on v alone here, so moving the velocity
// coefficients is moving w through v = omega Q' w; done directly on the sampled law).
TEST(VelocityHill, VelocityJacobianOfTanhCoulombIsTheAftOfDfDv) {
  const HarmonicBasis basis(3, 128);
  const TanhCoulomb law("friction", 0.4, 0.2);
  const Eigen::VectorXd w = Eigen::Matrix<double, 7, 1>{{0.05, 0.6, -0.2, 0.1, 0.05, -0.03, 0.02}};
  const double omega = 1.3;
  Eigen::MatrixXd Jv = Eigen::MatrixXd::Zero(basis.size(), basis.size());
  law.harmonic_velocity_jacobian(basis, w, omega, Jv);
  // The reference: P diag(df/dv) Q by the matrices, df/dv = (F / v_eps) (1 - tanh^2).
  const Eigen::VectorXd v = sample_velocities(basis, w, omega).col(0);
  const Eigen::VectorXd slope = (0.4 / 0.2) * (1.0 - (v / 0.2).array().tanh().square()).matrix();
  const Eigen::MatrixXd reference = basis.projection() * slope.asDiagonal() * basis.sampling();
  // The FFT-based product against the dense one: rounding of sums of 128 terms of order 2,
  // ~1e-15 each; 1e-12 asserted.
  EXPECT_LT((Jv - reference).cwiseAbs().maxCoeff(), 1e-12);
  // A law without velocity dependence adds nothing.
  const PolynomialSpring spring("cubic", {{3, 1.0}});
  Eigen::MatrixXd none = Eigen::MatrixXd::Zero(basis.size(), basis.size());
  spring.harmonic_velocity_jacobian(basis, w, omega, none);
  EXPECT_TRUE(none.isZero(0.0));
}

TEST(VelocityHill, TanhCoulombOscillatorAgreesWithMonodromy) {
  ElementSystem s;
  s.M = Eigen::MatrixXd::Identity(1, 1);
  s.K = Eigen::MatrixXd::Identity(1, 1);
  s.C = 0.02 * Eigen::MatrixXd::Identity(1, 1);
  s.elements.push_back({std::make_shared<TanhCoulomb>("friction", 0.1, 0.1), "friction",
                        Eigen::MatrixXd::Ones(1, 1)});
  s.excitation_harmonics = 1;
  s.excitation = Eigen::VectorXd::Zero(3);
  s.excitation[HarmonicBasis::cos_index(1)] = 0.5;
  const HarmonicBasis basis(9, 256);
  const ElementHarmonicBalance hb(s, basis);
  ContinuationOptions o;
  o.omega_start = 0.6;
  o.omega_end = 1.4;
  o.x_scale = 1.0;
  o.omega_scale = 1.0;
  o.max_step = 0.05;
  o.step = 0.02;
  const ContinuationResult curve = continue_in_frequency(hb, hb.linear_response(0.6), o);
  ASSERT_EQ(curve.status, Status::Ok) << curve.message;
  for (const double target : {0.7, 1.0, 1.25}) {
    const auto& p = *std::min_element(
        curve.points.begin(), curve.points.end(), [target](const auto& a, const auto& b) {
          return std::abs(a.omega - target) < std::abs(b.omega - target);
        });
    SCOPED_TRACE("Omega " + std::to_string(p.omega));
    const FloquetResult hill = hill_stability(hb, p.X, p.omega);
    ASSERT_EQ(hill.status, Status::Ok) << hill.message;
    MonodromyOptions mo;
    mo.march.scheme = TimeScheme::RungeKutta4;
    const FloquetResult m = monodromy_stability(s, p.omega, p.X, basis, mo);
    ASSERT_EQ(m.status, Status::Ok) << m.message;
    EXPECT_EQ(hill.stable, m.stable);
    EXPECT_EQ(hill.kind, m.kind);
    // The largest multiplier's modulus: Hill at H = 9 on 256 samples of the tanh law against
    // RK4 at 1024 steps per period from the same HB motion, which is not exactly periodic in the
    // ODE (truncation of the tanh's harmonics). Measured differences 3.6e-5, 1.8e-6 and 7.6e-5
    // at the three points; 5e-4 asserted. Without Jv Hill misses the friction's damping: its
    // |rho| is 0.91 and 0.95 at Omega = 0.69 and 1.25 against 0.58 and 0.82 (hundreds of times
    // the tolerance off).
    EXPECT_NEAR(std::abs(hill.multipliers[0]), std::abs(m.multipliers[0]), 5e-4);
    Eigen::MatrixXd J;
    hb.residual(p.X, p.omega, &J);
    const FloquetResult without = hill_stability(J, s.M, s.C, basis.harmonics(), p.omega);
    ASSERT_EQ(without.status, Status::Ok);
    // At resonance the velocity saturates the tanh over most of the period (df/dv ~ 0 there).
    if (std::abs(p.omega - 1.0) > 0.1) {
      EXPECT_GT(std::abs(std::abs(without.multipliers[0]) - std::abs(m.multipliers[0])), 0.05);
    }
  }
}

}  // namespace
}  // namespace geardyn::hbm
