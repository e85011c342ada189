// The physical harmonic balance of a structure with placed nonlinear elements
// (hbm/element_system.hpp) and the AFT of pointwise laws (hbm/nonlinear_element.hpp):
//   * a Duffing oscillator written as a cubic PointwiseElement placed on the DOF gives the same
//     residual, Jacobian and response curve as the hand-written cubic force of
//     harmonic_balance.hpp (the independent reference of duffing_test.cpp, itself checked against
//     the single-harmonic closed form of Nayfeh & Mook, "Nonlinear Oscillations", Wiley 1979);
//   * the analytic Jacobian and dR/domega against central differences, for an element between two
//     DOFs with a velocity-dependent law and for the hysteretic loss K_loss;
//   * the linear response against the complex receptance (K - w^2 M + i w C + i K_loss)^-1 F.
#include "geardyn/hbm/element_system.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "duffing_problem.hpp"
#include "geardyn/core/error.hpp"

namespace geardyn::hbm {
namespace {

// f = alpha u^3 + c3 u'^3: a cubic spring and, for the derivative checks, a cubic damper.
class CubicLaw final : public PointwiseElement {
 public:
  CubicLaw(double alpha, double c3) : alpha_(alpha), c3_(c3) {}
  int size() const override { return 1; }
  std::string describe() const override { return "cubic"; }
  bool velocity_dependent() const override { return c3_ != 0.0; }
  void pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double /*theta*/,
                 double /*omega*/, ElementStep& out) const override {
    out.force[0] = alpha_ * u[0] * u[0] * u[0] + c3_ * v[0] * v[0] * v[0];
    out.stiffness(0, 0) = 3.0 * alpha_ * u[0] * u[0];
    out.damping(0, 0) = 3.0 * c3_ * v[0] * v[0];
  }

 private:
  double alpha_, c3_;
};

ElementSystem duffing_elements() {
  ElementSystem s;
  s.M = Eigen::MatrixXd::Constant(1, 1, testing::kMass);
  s.C = Eigen::MatrixXd::Constant(1, 1, testing::kDamping);
  s.K = Eigen::MatrixXd::Constant(1, 1, testing::kStiffness);
  s.elements.push_back(
      {std::make_shared<CubicLaw>(testing::kCubic, 0.0), "cubic", Eigen::MatrixXd::Ones(1, 1)});
  s.excitation_harmonics = 1;
  s.excitation = Eigen::Vector3d(0.0, testing::kForce, 0.0);
  return s;
}

TEST(ElementSystem, DuffingEqualsTheHandWrittenCubicForce) {
  const int H = 5;
  const HarmonicBalance reference = testing::duffing_system(H);
  const ElementHarmonicBalance hb(duffing_elements(), reference.basis());
  Eigen::VectorXd X = Eigen::VectorXd::Random(hb.size()) * 0.8;
  Eigen::MatrixXd J1, J2;
  Eigen::VectorXd d1, d2;
  const Eigen::VectorXd R1 = reference.residual(X, 1.3, &J1, &d1);
  const Eigen::VectorXd R2 = hb.residual(X, 1.3, &J2, &d2);
  // Same samples, same transforms: equal to round-off.
  EXPECT_LE((R1 - R2).norm(), 1e-12 * R1.norm());
  EXPECT_LE((J1 - J2).norm(), 1e-12 * J1.norm());
  EXPECT_LE((d1 - d2).norm(), 1e-12 * d1.norm());
  // The whole response curve through both folds.
  // The continuation of duffing_problem.hpp (Omega 0.5 -> 2 through both folds) on both forms.
  ContinuationOptions o;
  o.omega_start = 0.5;
  o.omega_end = 2.0;
  o.step = 0.005;
  o.max_step = 0.005;
  o.tolerance = 1e-12;
  const Eigen::VectorXd X0 = testing::kForce / (testing::kStiffness - 0.25) *
                             Eigen::VectorXd::Unit(hb.size(), HarmonicBasis::cos_index(1));
  const ContinuationResult a = continue_in_frequency(reference, X0, o);
  const ContinuationResult b = continue_in_frequency(hb, X0, o);
  ASSERT_EQ(a.status, Status::Ok) << a.message;
  ASSERT_EQ(b.status, Status::Ok) << b.message;
  ASSERT_EQ(a.points.size(), b.points.size());
  double peak_a = 0.0, peak_b = 0.0;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    peak_a = std::max(peak_a, a.points[i].X.norm());
    peak_b = std::max(peak_b, b.points[i].X.norm());
  }
  EXPECT_NEAR(peak_b, peak_a, 1e-9 * peak_a);
}

// A two-DOF chain with a cubic spring-damper between the DOFs and a hysteretic loss.
ElementHarmonicBalance two_dof(int H) {
  ElementSystem s;
  s.M = Eigen::Matrix2d{{1.0, 0.0}, {0.0, 2.0}};
  s.C = Eigen::Matrix2d{{0.03, -0.01}, {-0.01, 0.02}};
  s.K = Eigen::Matrix2d{{2.0, -1.0}, {-1.0, 1.5}};
  s.K_loss = 0.02 * s.K;
  Eigen::MatrixXd B(1, 2);
  B << -1.0, 1.0;
  s.elements.push_back({std::make_shared<CubicLaw>(0.7, 0.05), "cubic", B});
  s.excitation_harmonics = 1;
  s.excitation = Eigen::VectorXd::Zero(6);
  s.excitation[1] = 0.3;   // a_1 of DOF 0
  s.excitation[5] = -0.1;  // b_1 of DOF 1
  return ElementHarmonicBalance(s, HarmonicBasis(H, default_time_samples(H, 3)));
}

TEST(ElementSystem, JacobianAndFrequencyDerivativeMatchCentralDifferences) {
  const ElementHarmonicBalance hb = two_dof(3);
  const Eigen::VectorXd X = Eigen::VectorXd::Random(hb.size()) * 0.5;
  const double omega = 0.9;
  Eigen::MatrixXd J;
  Eigen::VectorXd dR;
  const Eigen::VectorXd R = hb.residual(X, omega, &J, &dR);
  // Central differences of a smooth (polynomial) residual: truncation O(h^2 |R'''|) ~ 1e-10
  // and round-off O(eps |R| / h) ~ 1e-10 at h = 1e-5.
  const double h = 1e-5;
  for (int k = 0; k < hb.size(); ++k) {
    Eigen::VectorXd Xp = X, Xm = X;
    Xp[k] += h;
    Xm[k] -= h;
    const Eigen::VectorXd fd = (hb.residual(Xp, omega) - hb.residual(Xm, omega)) / (2.0 * h);
    EXPECT_LE((fd - J.col(k)).norm(), 1e-7 * (1.0 + J.col(k).norm())) << "column " << k;
  }
  const Eigen::VectorXd fdw = (hb.residual(X, omega + h) - hb.residual(X, omega - h)) / (2.0 * h);
  EXPECT_LE((fdw - dR).norm(), 1e-7 * (1.0 + dR.norm()));
  EXPECT_GT(R.norm(), 0.0);
}

TEST(ElementSystem, LinearResponseIsTheComplexReceptance) {
  const ElementHarmonicBalance hb = two_dof(2);
  const double w = 1.1;
  const ElementSystem& s = hb.system();
  using C = std::complex<double>;
  const Eigen::MatrixXcd D = s.K.cast<C>() - w * w * s.M.cast<C>() + C(0.0, w) * s.C.cast<C>() +
                             C(0.0, 1.0) * s.K_loss.cast<C>();
  // Forces a_1 - i b_1 per DOF: DOF 0: 0.3, DOF 1: +0.1 i.
  const Eigen::Vector2cd F(C(0.3, 0.0), C(0.0, 0.1));
  const Eigen::Vector2cd z = D.partialPivLu().solve(F);
  const Eigen::VectorXd X = hb.linear_response(w);
  const int n = hb.basis().size();
  for (int d = 0; d < 2; ++d) {
    // z = a_1 - i b_1 (harmonic_balance.hpp's cosine phase).
    EXPECT_NEAR(X[d * n + HarmonicBasis::cos_index(1)], z[d].real(), 1e-13);
    EXPECT_NEAR(X[d * n + HarmonicBasis::sin_index(1)], -z[d].imag(), 1e-13);
    EXPECT_NEAR(X[d * n + HarmonicBasis::cos_index(2)], 0.0, 1e-15);
  }
}

TEST(ElementSystem, RejectsAMisplacedElement) {
  ElementSystem s = duffing_elements();
  s.elements[0].B = Eigen::MatrixXd::Ones(1, 2);  // two DOFs on a one-DOF system
  EXPECT_THROW(ElementHarmonicBalance(s, HarmonicBasis(1, 16)), InputError);
}

}  // namespace
}  // namespace geardyn::hbm
