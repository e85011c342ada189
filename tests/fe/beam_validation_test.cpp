// Validation of the shaft element against closed-form beam theory: natural frequencies of
// Euler-Bernoulli and Timoshenko beams (free-free, pinned-pinned, cantilever), the observed
// convergence order under mesh refinement, and static cantilever deflection.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <functional>
#include <numbers>

#include "fe_test_support.hpp"
#include "geardyn/fe/linear_system.hpp"

namespace geardyn::fe {
namespace {

using model::Component;
constexpr double kPi = std::numbers::pi;

// Steel, solid round bar.
constexpr double kE = 2.1e11, kG = 8.1e10, kRho = 7800.0;

enum class Support { FreeFree, PinnedPinned, Cantilever };

// Planar bending model in the e1-e3 plane:
//
//    x ^        n equal elements, only (ux, ry) free at each node
//      |  o----o----o----o----o   pinned: ux = 0 at both ends
//      +-----------------------> z   cantilever: ux = ry = 0 at z = 0
model::Model planar_beam(Support support, model::BeamTheory theory, bool rotary_inertia,
                         double length, double diameter, int n, double kappa = model::kNaN) {
  model::Model m;
  m.materials.push_back(test::material("steel", kE, kG, kRho));
  model::Shaft s = test::uniform_shaft("b", "steel", length, diameter, n);
  s.theory = theory;
  s.rotary_inertia = rotary_inertia;
  s.shear_coefficient = kappa;
  m.shafts.push_back(s);
  for (int k = 0; k <= n; ++k) {
    m.constraints.push_back(test::constrain(
        "b." + std::to_string(k), {Component::Uy, Component::Uz, Component::Rx, Component::Rz}));
  }
  const std::string last = "b." + std::to_string(n);
  if (support == Support::PinnedPinned) {
    m.constraints.push_back(test::constrain("b.0", {Component::Ux}));
    m.constraints.push_back(test::constrain(last, {Component::Ux}));
  } else if (support == Support::Cantilever) {
    m.constraints.push_back(test::constrain("b.0", {Component::Ux, Component::Ry}));
  }
  return m;
}

double area(double d) { return kPi * d * d / 4; }
double second_moment(double d) { return kPi * std::pow(d, 4) / 64; }

// Roots of cos(x) cosh(x) = c (c = 1: free-free, c = -1: clamped-free), written as
// cos(x) - c / cosh(x) = 0 for conditioning; the k-th root lies within 1 of (k + 1/2) pi.
double beam_root(double c, int k) {
  auto f = [c](double x) { return std::cos(x) - c / std::cosh(x); };
  double lo = (k + 0.5) * kPi - 1.0, hi = (k + 0.5) * kPi + 1.0;
  double flo = f(lo);
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
    const double mid = 0.5 * (lo + hi), fm = f(mid);
    if ((fm < 0) == (flo < 0)) {
      lo = mid;
      flo = fm;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

// Euler-Bernoulli: omega = (beta L)^2 / L^2 sqrt(E I / (rho A)).
double euler_bernoulli_frequency(double beta_L, double length, double d) {
  return beta_L * beta_L / (length * length) * std::sqrt(kE * second_moment(d) / (kRho * area(d)));
}

// Timoshenko simply supported beam, mode n (Timoshenko 1921; e.g. Han, Benaroya & Wei,
// J. Sound Vib. 225 (1999) 935-988, eq. for the hinged-hinged case): with k = n pi / L,
//   EI k^4 - rho A w^2 - rho I (1 + E / (kappa G)) k^2 w^2 + rho^2 I / (kappa G) w^4 = 0,
// lower root.
double timoshenko_pinned_frequency(int n, double length, double d, double kappa) {
  const double k = n * kPi / length, A = area(d), I = second_moment(d);
  const double a = kRho * kRho * I / (kappa * kG);
  const double b = kRho * A + kRho * I * k * k * (1 + kE / (kappa * kG));
  const double c = kE * I * std::pow(k, 4);
  return std::sqrt((b - std::sqrt(b * b - 4 * a * c)) / (2 * a));
}

Eigen::VectorXd elastic_frequencies(const model::Model& m, int skip) {
  const Eigen::VectorXd w = test::undamped_frequencies(assemble(m));
  return w.tail(w.size() - skip);
}

TEST(BeamValidation, EulerBernoulliClosedFormsAllSupports) {
  // Tolerance: the relative frequency error of cubic elements with consistent mass is about
  // (beta h)^4 / 2880 (observed), 2e-6 for mode 3 of the free-free beam with 40 elements;
  // 1e-5 leaves margin while any modelling error (a wrong mass or stiffness term) is far larger.
  const double L = 1.2, d = 0.04;
  const int n = 40;
  // Reference roots, with the textbook values as a sanity check of the root finder.
  EXPECT_NEAR(beam_root(1.0, 1), 4.7300, 1e-4);
  EXPECT_NEAR(beam_root(-1.0, 0), 1.8751, 1e-4);
  struct Case {
    Support support;
    int rigid;
    std::function<double(int)> beta_L;
  };
  const std::vector<Case> cases = {
      {Support::FreeFree, 2, [](int i) { return beam_root(1.0, i + 1); }},
      {Support::PinnedPinned, 0, [](int i) { return (i + 1) * kPi; }},
      {Support::Cantilever, 0, [](int i) { return beam_root(-1.0, i); }},
  };
  for (const Case& c : cases) {
    const model::Model m =
        planar_beam(c.support, model::BeamTheory::EulerBernoulli, false, L, d, n);
    const Eigen::VectorXd w = test::undamped_frequencies(assemble(m));
    for (int i = 0; i < c.rigid; ++i) EXPECT_LT(w(i), 1e-4 * w(c.rigid));
    for (int i = 0; i < 3; ++i) {
      const double exact = euler_bernoulli_frequency(c.beta_L(i), L, d);
      EXPECT_LT(test::relative_error(w(c.rigid + i), exact), 1e-5)
          << "support " << static_cast<int>(c.support) << " mode " << i + 1 << ": "
          << w(c.rigid + i) << " vs " << exact;
    }
  }
}

// Observed convergence order of the frequencies under uniform refinement h -> h/2:
// p = log2(e_h / e_{h/2}). Hermite cubic elements with consistent mass converge as h^4
// (Strang & Fix, An Analysis of the Finite Element Method, ch. 6: eigenvalue error
// O(h^{2(k+1-m)}) with k = 3, m = 2).
TEST(BeamValidation, EulerBernoulliConvergenceOrderIsFour) {
  const double L = 1.0, d = 0.05;
  std::vector<Eigen::VectorXd> errors;
  for (int n : {4, 8, 16}) {
    const Eigen::VectorXd w = elastic_frequencies(
        planar_beam(Support::PinnedPinned, model::BeamTheory::EulerBernoulli, false, L, d, n), 0);
    Eigen::VectorXd e(3);
    for (int i = 0; i < 3; ++i)
      e(i) = test::relative_error(w(i), euler_bernoulli_frequency((i + 1) * kPi, L, d));
    errors.push_back(e);
  }
  for (int i = 0; i < 3; ++i) {
    const double order = std::log2(errors[1](i) / errors[2](i));
    RecordProperty("eb_order_mode" + std::to_string(i + 1), std::to_string(order));
    // Asymptotic range reached from n = 8 on; +-0.15 allows the pre-asymptotic tail of mode 3.
    EXPECT_NEAR(order, 4.0, 0.15) << "mode " << i + 1 << " errors " << errors[1](i) << " -> "
                                  << errors[2](i);
  }
}

// Timoshenko beam, pinned-pinned, against the closed form with shear and rotary inertia.
// Observed convergence order: 2, not 4. The two-node interdependent-interpolation element has a
// piecewise-constant shear strain w' - theta, while the exact mode's shear strain varies like
// cos(k z); the shear-energy error is O(h^2) and so is the frequency error (Rayleigh-Ritz), with
// a coefficient that vanishes with Phi (the Euler-Bernoulli limit recovers order 4 above).
// The limit is checked by Richardson extrapolation with the observed order.
TEST(BeamValidation, TimoshenkoPinnedPinnedWithShearAndRotaryInertia) {
  // A stubby shaft, L / d = 5, so shear and rotary inertia lower mode 3 by tens of percent.
  const double L = 0.5, d = 0.1, kappa = 0.9;
  std::vector<Eigen::VectorXd> frequencies;
  for (int n : {16, 32, 64}) {
    frequencies.push_back(elastic_frequencies(
        planar_beam(Support::PinnedPinned, model::BeamTheory::Timoshenko, true, L, d, n, kappa),
        0));
  }
  // The shear correction matters: the Euler-Bernoulli value is far off for mode 3.
  EXPECT_GT(test::relative_error(euler_bernoulli_frequency(3 * kPi, L, d),
                                 timoshenko_pinned_frequency(3, L, d, kappa)),
            0.2);
  for (int i = 0; i < 3; ++i) {
    const double exact = timoshenko_pinned_frequency(i + 1, L, d, kappa);
    const double e16 = test::relative_error(frequencies[0](i), exact);
    const double e32 = test::relative_error(frequencies[1](i), exact);
    const double e64 = test::relative_error(frequencies[2](i), exact);
    const double order = std::log2(e32 / e64);
    RecordProperty("timoshenko_order_mode" + std::to_string(i + 1), std::to_string(order));
    EXPECT_NEAR(order, 2.0, 0.05) << "mode " << i + 1 << " errors " << e16 << ", " << e32 << ", "
                                  << e64;
    // Upper bound from the Rayleigh-Ritz principle: the FE frequencies lie above the exact ones.
    EXPECT_GT(frequencies[2](i), exact);
    // Richardson extrapolation with order 2 removes the leading error term; the remainder is
    // O(h^4) ~ e64^2 scale, far below the tolerance 1e-6 that any modelling error would exceed.
    const double extrapolated = frequencies[2](i) + (frequencies[2](i) - frequencies[1](i)) / 3.0;
    EXPECT_LT(test::relative_error(extrapolated, exact), 1e-6)
        << "mode " << i + 1 << ": " << extrapolated << " vs " << exact;
  }
}

// Static tip load on a cantilever in 3D (all six DOFs per node, root clamped):
//
//   |=====o=====o=====o   <- P (ux and uy), torque T (rz), axial force N (uz)
//   clamp
// Timoshenko: delta = P L^3 / (3 E I) + P L / (kappa G A); twist T L / (G J); stretch N L / (E A).
// The interdependent-interpolation element is exact for end loads (its shape functions solve
// the homogeneous beam equations), so the tolerance is round-off: 1e-10 relative.
TEST(BeamValidation, CantileverStaticTipDeflectionIsExact) {
  const double L = 0.6, d = 0.08, kappa = 0.85, P = 1e4, T = 300, N = 5e4;
  for (const auto theory : {model::BeamTheory::Timoshenko, model::BeamTheory::EulerBernoulli}) {
    for (int n : {1, 3, 7}) {
      model::Model m;
      m.materials.push_back(test::material("steel", kE, kG, kRho));
      model::Shaft s = test::uniform_shaft("b", "steel", L, d, n);
      s.theory = theory;
      s.shear_coefficient = kappa;
      s.axis = {0.2, 0.3, 0.9};  // oblique: exercises the node frames as well
      m.shafts.push_back(s);
      m.constraints.push_back(
          test::constrain("b.0", {Component::Ux, Component::Uy, Component::Uz, Component::Rx,
                                  Component::Ry, Component::Rz}));
      const LinearSystem sys = assemble(m);
      const int tip = n;
      const Eigen::VectorXd f =
          P * sys.unit_load(tip, Component::Ux) + P * sys.unit_load(tip, Component::Uy) +
          T * sys.unit_load(tip, Component::Rz) + N * sys.unit_load(tip, Component::Uz);
      Eigen::SimplicialLDLT<SparseMatrix> ldlt(sys.K);
      ASSERT_EQ(ldlt.info(), Eigen::Success);
      const Eigen::VectorXd u = ldlt.solve(f);
      const double A = area(d), I = second_moment(d), J = 2 * I;
      const double shear = theory == model::BeamTheory::Timoshenko ? P * L / (kappa * kG * A) : 0.0;
      const double bending = P * L * L * L / (3 * kE * I) + shear;
      auto at = [&](Component c) { return u(sys.dofs.dof(tip, c)); };
      EXPECT_LT(test::relative_error(at(Component::Ux), bending), 1e-10) << "n = " << n;
      EXPECT_LT(test::relative_error(at(Component::Uy), bending), 1e-10) << "n = " << n;
      EXPECT_LT(test::relative_error(at(Component::Rz), T * L / (kG * J)), 1e-10);
      EXPECT_LT(test::relative_error(at(Component::Uz), N * L / (kE * A)), 1e-10);
      // Tip slopes P L^2 / (2 E I): ry = +dux/dz, rx = -duy/dz.
      EXPECT_LT(test::relative_error(at(Component::Ry), P * L * L / (2 * kE * I)), 1e-10);
      EXPECT_LT(test::relative_error(at(Component::Rx), -P * L * L / (2 * kE * I)), 1e-10);
    }
  }
}

}  // namespace
}  // namespace geardyn::fe
