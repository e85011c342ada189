// nonlinear_response against NLvib's example 08, "beam_tanhDryFriction" (issue #18): a steel
// cantilever (Euler-Bernoulli, 8 equal elements, clamped at x = 0) with a regularised dry-friction
// element f = mu N tanh(u' / eps) to ground at the third node from the clamp and a harmonic force
// at its tip, written in the model file and solved by the nonlinear_response analysis.
//
// Reference: the NLvib toolbox (M. Krack & J. Gross, "Harmonic Balance for Nonlinear Vibration
// Problems", Springer 2019; github.com/maltekrack/NLvib, commit 69598c5e, 2024-02-22), script
// EXAMPLES/08_beam_tanhDryFriction/beam_tanhDryFriction_simple.m run unchanged in GNU Octave
// 7.3.0 (only SRC/solve_and_continue.m's optimset(@fsolve) written optimset('fsolve') for
// Octave), with the frequency Omega, the tip and friction-node RMS and the norm of HB_residual of
// every point recorded after the run. Its settings: H = 7, N = 128 samples per period, Omega =
// 370 -> 110 rad/s in fixed steps of 5 (sequential continuation), fsolve's default tolerances.
//
// The model (beam.mat of the example, identical to its "advanced" variant's
// FE_EulerBernoulliBeam('clamped-free', 9 nodes): relative difference of K and M 3e-18 and 3e-17):
// length 2 m, section 0.1 m (bending) x 0.3 m, E = 185 GPa, rho = 7830 kg/m^3; stiffness-
// proportional damping D = beta K with beta = 2 * 0.01 / omega_stick,1 (1 % at the first mode with
// the contact stuck, omega_stick,1 = 248.97 rad/s); friction at node 4 of 9 (x = 0.75 m, "beam.3"
// here) in the bending direction, mu N = 1.5 N, eps = 6e-7 m/s; force 0.2 cos(Omega t) N at the
// tip. Only E I and rho A enter an Euler-Bernoulli beam without rotary inertia, so geardyn's
// circular shaft (d = 0.1 m) gets a material with E' = E I_rect / I_circ and rho' = rho A_rect /
// A_circ; the out-of-plane DOFs (uy, rx) are constrained, which leaves NLvib's 16 DOFs.
//
// Comparison: at every NLvib point whose residual is at its solver's tolerance (||R|| < 1e-5 of
// ||F_ex||: 8 of its 54 points), geardyn's solution at exactly that Omega (a continuation that
// ends there) against NLvib's tip and friction-node RMS; the resonance peak against NLvib's
// largest point. Same H and N, so both solve the same algebraic system: the difference is NLvib's
// solver residual (see the tolerances).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <utility>

#include "geardyn/analyses/nonlinear_response.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/units.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

std::string num(double x) {
  std::ostringstream s;
  s << std::setprecision(17) << x;
  return s.str();
}

// NLvib's beam.mat: D = beta K, beta = 2e-2 / omega_stick,1 (printed by Octave to 16 digits).
constexpr double kBeta = 8.032992955386351e-05;

// The example's beam through the model file, nonlinear_response from `first` to `last` [rad/s]
// (H = 7, N = 128 as NLvib), sensors "tip" (row 0) and "fric" (row 1).
std::string beam_model(double first, double last, double max_step) {
  const double E = 185e9, rho = 7830.0, height = 0.1, thickness = 0.3, d = 0.1;
  const double I_rect = thickness * height * height * height / 12.0, A_rect = thickness * height;
  const double I_circ = units::kPi * d * d * d * d / 64.0, A_circ = units::kPi * d * d / 4.0;
  std::string s = "version = 1\ndofs = \"lateral\"\n[[materials]]\nname = \"steel\"\n";
  s += "youngs_modulus = " + num(E * I_rect / I_circ) + "\npoisson_ratio = 0.3\n";
  s += "density = " + num(rho * A_rect / A_circ) + "\n";
  s += R"([[shafts]]
name = "beam"
material = "steel"
theory = "euler_bernoulli"
rotary_inertia = false
gyroscopic = false
[[shafts.elements]]
length = 2.0
outer_diameter = 0.1
divisions = 8
[[constraints]]
node = "beam.0"
dofs = "all"
)";
  for (int k = 1; k <= 8; ++k)
    s += "[[constraints]]\nnode = \"beam." + std::to_string(k) + "\"\ndofs = [\"uy\", \"rx\"]\n";
  s += "[damping]\nrayleigh_beta = " + num(kBeta) + "\n";
  s += R"([[forces]]
name = "F"
node = "beam.8"
dof = "ux"
amplitude = 0.2
[[sensors]]
name = "tip"
node = "beam.8"
dof = "ux"
[[sensors]]
name = "fric"
node = "beam.3"
dof = "ux"
[[nonlinear_elements]]
name = "dry"
type = "coulomb"
node2 = "beam.3"
direction = [1.0, 0.0, 0.0]
slip_force = 1.5
regularisation_velocity = 6e-7
[[analyses]]
name = "nl"
type = "nonlinear_response"
forces = ["F"]
harmonics = 7
time_samples = 128
tolerance = 1e-11
)";
  s += "frequency_start_hz = " + num(first / units::kTwoPi) + "\n";
  s += "frequency_stop_hz = " + num(last / units::kTwoPi) + "\n";
  s += "step = " + num(std::min(max_step, 0.01)) + "\nmax_step = " + num(max_step) + "\n";
  return s;
}

Outcome solve(const std::string& name, double first, double last, double max_step) {
  const model::Model m = test::load(test::fresh_dir(name), beam_model(first, last, max_step));
  check_inputs(m, {});
  fe::LinearSystem system = assembly::build_system(m, nullptr);
  Context c(m, m.analyses[0]);
  c.with_system(&system);
  return run_analysis(m, m.analyses[0], c);
}

double rms(const NonlinearResponseResult& r, std::size_t point, int sensor) {
  return series_rms(r.sensor_coefficients[point].row(sensor).transpose());
}

// NLvib's points with ||R|| / ||F_ex|| < 1e-5 (F_ex = 0.2 N): Omega [rad/s], tip RMS [m],
// friction-node RMS [m] (sqrt(sum of squared coefficients) / sqrt(2), as the example computes),
// ||R|| / ||F_ex||.
struct NlvibPoint {
  double omega, tip, fric, residual;
};
constexpr NlvibPoint kConverged[] = {
    {370.0, 2.185585428e-08, 7.04405259e-10, 8.99e-6},
    {365.0, 2.296998668e-08, 7.480669721e-10, 1.41e-6},
    {360.0, 2.417753803e-08, 7.969165825e-10, 2.29e-6},
    {355.0, 2.548922241e-08, 8.519426371e-10, 3.81e-6},
    {350.0, 2.69169546e-08, 9.14411196e-10, 6.51e-6},
    {175.0, 5.788234827e-08, 4.050096905e-09, 6.71e-6},
    {150.0, 4.659821716e-08, 2.742600429e-09, 8.76e-6},
    {145.0, 4.506048373e-08, 2.664788482e-09, 2.19e-6},
};
// NLvib's largest tip response on its 5 rad/s grid (its residual 1.34e-3 of ||F_ex||).
constexpr NlvibPoint kNlvibPeak = {195.0, 6.715326435e-08, 7.936369297e-09, 1.34e-3};

// The vertex (x, y) of the parabola through three points (x0 < x1 < x2): the peak of a sampled
// resonance curve, the same estimator for both codes.
std::pair<double, double> parabola_vertex(double x0, double y0, double x1, double y1, double x2,
                                          double y2) {
  // Newton form y = y0 + d01 (x - x0) + a (x - x0)(x - x1); its derivative vanishes at x.
  const double d01 = (y1 - y0) / (x1 - x0), d12 = (y2 - y1) / (x2 - x1);
  const double a = (d12 - d01) / (x2 - x0);
  const double x = 0.5 * (x0 + x1) - d01 / (2.0 * a);
  return {x, y0 + d01 * (x - x0) + a * (x - x0) * (x - x1)};
}

TEST(NonlinearNlvibBeam, ConvergedPointsMatchNlvib) {
  for (const NlvibPoint& p : kConverged) {
    SCOPED_TRACE("Omega = " + num(p.omega));
    // A short continuation that lands exactly on NLvib's Omega.
    const Outcome out = solve("nlvib_beam_point", 0.97 * p.omega, p.omega, 0.05);
    ASSERT_EQ(out.output.status, Status::Ok) << out.output.message;
    const auto& r = result_of<NonlinearResponseResult>(out);
    const std::size_t last = r.frequency.size() - 1;
    ASSERT_NEAR(r.frequency[last], p.omega, 1e-9 * p.omega);
    // Both codes solve the same equations (same H, N, law); geardyn's to 1e-11, NLvib's to its
    // residual ||R|| / ||F_ex|| = p.residual. The error of a solution is J^-1 R, and J^-1 maps
    // F_ex to the response, so the relative amplitude error is of the order of the relative
    // residual: that is the tolerance. Measured (Octave 7.3.0 run above): tip 1e-8 to 2e-7
    // (0.01-0.03 of the residual), friction node 3e-7 to 4e-6 (0.2-0.6 of it: its response is
    // 20-70 times smaller than the tip's, so the same absolute error, ~1e-14 m, weighs more).
    EXPECT_NEAR(rms(r, last, 0), p.tip, p.residual * p.tip);
    EXPECT_NEAR(rms(r, last, 1), p.fric, p.residual * p.fric);
  }
}

TEST(NonlinearNlvibBeam, ResonancePeakMatchesNlvib) {
  // At NLvib's largest point, its residual (1.34e-3 of ||F_ex||) bounds the difference as above
  // (measured 5e-5 at the tip, 4e-5 at the friction node).
  const Outcome at = solve("nlvib_beam_peak", 0.97 * kNlvibPeak.omega, kNlvibPeak.omega, 0.05);
  ASSERT_EQ(at.output.status, Status::Ok) << at.output.message;
  const auto& rp = result_of<NonlinearResponseResult>(at);
  const std::size_t last = rp.frequency.size() - 1;
  ASSERT_NEAR(rp.frequency[last], kNlvibPeak.omega, 1e-9 * kNlvibPeak.omega);
  EXPECT_NEAR(rms(rp, last, 0), kNlvibPeak.tip, kNlvibPeak.residual * kNlvibPeak.tip);
  EXPECT_NEAR(rms(rp, last, 1), kNlvibPeak.fric, kNlvibPeak.residual * kNlvibPeak.fric);

  // The resonance itself: the parabola through NLvib's points at 190, 195, 200 rad/s (tip RMS
  // 6.688402977e-08, 6.715326435e-08, 6.667737602e-08; residuals 6.0e-4, 1.3e-3, 1.1e-3) peaks
  // at 194.31 rad/s with 6.71604e-08 m; the same parabola through geardyn's largest point and
  // its neighbours on the traced curve.
  const auto nlvib =
      parabola_vertex(190.0, 6.688402977e-08, 195.0, kNlvibPeak.tip, 200.0, 6.667737602e-08);
  const Outcome out = solve("nlvib_beam_curve", 100.0, 375.0, 0.01);
  ASSERT_EQ(out.output.status, Status::Ok) << out.output.message;
  const auto& r = result_of<NonlinearResponseResult>(out);
  // No fold on this curve (the friction element only damps): one branch, increasing Omega.
  EXPECT_TRUE(r.turning_points.empty());
  std::size_t peak = 1;
  for (std::size_t i = 1; i + 1 < r.frequency.size(); ++i)
    if (rms(r, i, 0) > rms(r, peak, 0)) peak = i;
  const auto ours = parabola_vertex(r.frequency[peak - 1], rms(r, peak - 1, 0), r.frequency[peak],
                                    rms(r, peak, 0), r.frequency[peak + 1], rms(r, peak + 1, 0));
  // The two parabolas are sampled 5 rad/s (NLvib's step) and about 2.5 rad/s apart: their cubic
  // error moves the vertex by a fraction of a step on a resonance some 60 rad/s wide (measured
  // 193.89 vs 194.31 rad/s); 1 rad/s. The peak values: NLvib's points err by up to their
  // residual, 1.3e-3 (measured difference 2.6e-4).
  EXPECT_NEAR(ours.first, nlvib.first, 1.0);
  EXPECT_NEAR(ours.second, nlvib.second, 1.3e-3 * nlvib.second);
}

}  // namespace
}  // namespace geardyn::analyses
