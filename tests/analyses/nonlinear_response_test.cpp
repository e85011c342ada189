// The nonlinear_response analysis through the model file (issue #18):
//  - Duffing oscillator q'' + 2 zeta q' + q + alpha q^3 = F cos(w t) written as a point mass on
//    a spring with a `cubic` element: at H = 1 every converged point satisfies the
//    single-harmonic amplitude-frequency relation
//      [(k - m w^2 + 3/4 alpha a^2)^2 + (c w)^2] a^2 = F^2
//    (Nayfeh & Mook, "Nonlinear Oscillations", Wiley 1979, sec. 4.1) to the Newton tolerance, the
//    curve passes both folds, and the points between them are marked unstable;
//  - the force-level continuation at a fixed frequency ends on the same relation;
//  - the 3-DOF chain with two Jenkins elements, two cubic springs and a unilateral spring of
//    NLvib's example 07 (M. Krack & J. Gross, "Harmonic Balance for Nonlinear Vibration
//    Problems", Springer 2019, and the NLvib toolbox, github.com/maltekrack/NLvib), H = 7, N =
//    1024: the converged points satisfy the balance and the response peaks where NLvib's does;
//  - bad inputs: an element between a node and itself, a `friction_contact` without any normal
//    load, a start the solver cannot converge at.
#include "geardyn/analyses/nonlinear_response.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using test::fresh_dir;
using test::load;
using test::table;

constexpr double kTwoPi = units::kTwoPi;

// m = 1 kg, k = 1 N/m, c = 0.05 N s/m, alpha = 0.1 N/m^3, F = 0.18 N: the Duffing problem of
// tests/hbm/duffing_problem.hpp, here through the model file.
std::string duffing_model(const std::string& analysis) {
  return R"(version = 1
dofs = "axial"
[[nodes]]
name = "p"
position = [0.0, 0.0, 0.0]
[[point_masses]]
node = "p"
mass = 1.0
[[bearings]]
name = "spring"
node = "p"
kzz = 1.0
czz = 0.05
[[forces]]
name = "F"
node = "p"
dof = "uz"
amplitude = 0.18
[[sensors]]
name = "x"
node = "p"
dof = "uz"
[[nonlinear_elements]]
name = "cubic"
type = "cubic"
node2 = "p"
direction = [0.0, 0.0, 1.0]
stiffness = 0.1
[[analyses]]
name = "nl"
type = "nonlinear_response"
forces = ["F"]
)" + analysis;
}

struct Solved {
  Outcome outcome;
  const NonlinearResponseResult& result() const {
    return result_of<NonlinearResponseResult>(outcome);
  }
};

Solved run(const model::Model& m) {
  check_inputs(m, {});
  fe::LinearSystem system = assembly::build_system(m, nullptr);
  Context c(m, m.analyses[0]);
  c.with_system(&system);
  return {run_analysis(m, m.analyses[0], c)};
}

double duffing_relation(double w, double a) {
  const double k = 1.0, m = 1.0, c = 0.05, alpha = 0.1, F = 0.18;
  const double re = k - m * w * w + 0.75 * alpha * a * a;
  return (re * re + c * c * w * w) * a * a - F * F;
}

TEST(NonlinearResponse, DuffingSingleHarmonicMatchesTheClosedForm) {
  const auto dir = fresh_dir("nonlinear_duffing_h1");
  const model::Model m = load(dir, duffing_model(R"(frequency_start_hz = 0.0795774715
frequency_stop_hz = 0.3183098862
harmonics = 1
time_samples = 16
tolerance = 1e-12
max_step = 0.02
)"));
  const Solved r = run(m);
  ASSERT_EQ(r.outcome.output.status, Status::Ok) << r.outcome.output.message;
  const auto& res = r.result();
  ASSERT_GT(res.frequency.size(), 50u);
  double peak = 0.0;
  for (std::size_t i = 0; i < res.frequency.size(); ++i) {
    const double a = harmonic_amplitude(res.sensor_coefficients[i].row(0).transpose(), 1);
    peak = std::max(peak, a);
    // AFT of a cubic with 16 > 4H samples is exact: the relation holds to the Newton tolerance
    // (1e-12 of the force), i.e. ~1e-12 F^2 in this squared form; 1e-9 leaves room for the
    // conditioning near the folds.
    EXPECT_NEAR(duffing_relation(res.frequency[i], a), 0.0, 1e-9) << "point " << i;
  }
  // The backbone peak: the largest root of the relation, found where its w-derivative vanishes;
  // for these parameters a_max = F / (c w_peak) with w_peak^2 = 1 + 3/4 alpha a_max^2 (the
  // response meets the backbone at the peak). Solved by fixed point:
  double a_max = 1.0;
  for (int k = 0; k < 100; ++k) a_max = 0.18 / (0.05 * std::sqrt(1.0 + 0.075 * a_max * a_max));
  // The sampled curve's largest amplitude lies below the true peak by at most the curvature
  // times the step squared: max_step 0.02 of the scaled arc gives well under 1 %.
  EXPECT_NEAR(peak, a_max, 1e-2 * a_max);
  // Two folds (jump up and jump down) with the unstable middle branch between them.
  EXPECT_EQ(res.turning_points.size(), 2u);
  const auto unstable = std::count(res.unstable.begin(), res.unstable.end(), 1);
  EXPECT_GT(unstable, 0);
  const Table& t = table(r.outcome.output, "turning_points");
  EXPECT_EQ(t.rows(), 2u);
}

TEST(NonlinearResponse, ForceLevelContinuationEndsOnTheSameCurve) {
  const auto dir = fresh_dir("nonlinear_duffing_level");
  const model::Model m = load(dir, duffing_model(R"(parameter = "force_level"
frequency_hz = 0.2
force_factor_start = 0.0
force_factor_stop = 1.0
harmonics = 1
time_samples = 16
tolerance = 1e-12
)"));
  const Solved r = run(m);
  ASSERT_EQ(r.outcome.output.status, Status::Ok) << r.outcome.output.message;
  const auto& res = r.result();
  ASSERT_FALSE(res.level.empty());
  EXPECT_NEAR(res.level.back(), 1.0, 1e-12);
  const double a = harmonic_amplitude(res.sensor_coefficients.back().row(0).transpose(), 1);
  EXPECT_NEAR(duffing_relation(0.2 * kTwoPi, a), 0.0, 1e-9);
}

// NLvib example 07: masses 1, springs 1 (to ground at both ends and between), dampers 0.02 per
// spring, Jenkins (k 20, mu N 1) to ground at mass 1 and between masses 1 and 2, cubic springs
// (1) at mass 2 and between masses 2 and 3, a unilateral spring (1, gap 0.25) at mass 3; unit
// force at mass 2; Omega 0.5 to 2 rad/s.
std::string nlvib07_model() {
  std::string s = R"(version = 1
dofs = "axial"
)";
  for (int i = 1; i <= 3; ++i)
    s += "[[nodes]]\nname = \"m" + std::to_string(i) + "\"\nposition = [" + std::to_string(i) +
         ".0, 0.0, 0.0]\n[[point_masses]]\nnode = \"m" + std::to_string(i) +
         "\"\nmass = 1.0\n[[sensors]]\nname = \"q" + std::to_string(i) + "\"\nnode = \"m" +
         std::to_string(i) + "\"\ndof = \"uz\"\n";
  s += R"([[bearings]]
node = "m1"
kzz = 1.0
czz = 0.02
[[bearings]]
node = "m2"
node2 = "m1"
kzz = 1.0
czz = 0.02
[[bearings]]
node = "m3"
node2 = "m2"
kzz = 1.0
czz = 0.02
[[bearings]]
node = "m3"
kzz = 1.0
czz = 0.02
[[forces]]
name = "F"
node = "m2"
dof = "uz"
amplitude = 1.0
[[nonlinear_elements]]
name = "fric1"
type = "jenkins"
node2 = "m1"
direction = [0.0, 0.0, 1.0]
stiffness = 20.0
slip_force = 1.0
[[nonlinear_elements]]
name = "fric2"
type = "jenkins"
node1 = "m1"
node2 = "m2"
direction = [0.0, 0.0, 1.0]
stiffness = 20.0
slip_force = 1.0
[[nonlinear_elements]]
name = "cubic1"
type = "cubic"
node2 = "m2"
direction = [0.0, 0.0, 1.0]
stiffness = 1.0
[[nonlinear_elements]]
name = "cubic2"
type = "cubic"
node1 = "m2"
node2 = "m3"
direction = [0.0, 0.0, 1.0]
stiffness = 1.0
[[nonlinear_elements]]
name = "stop"
type = "unilateral"
node2 = "m3"
direction = [0.0, 0.0, 1.0]
stiffness = 1.0
gap = 0.25
[[analyses]]
name = "nl"
type = "nonlinear_response"
forces = ["F"]
frequency_start_hz = 0.0795774715459477
frequency_stop_hz = 0.318309886183791
harmonics = 7
time_samples = 1024
)";
  return s;
}

TEST(NonlinearResponse, NLvibThreeDofMultipleNonlinearities) {
  const auto dir = fresh_dir("nonlinear_nlvib07");
  const model::Model m = load(dir, nlvib07_model());
  const Solved r = run(m);
  ASSERT_EQ(r.outcome.output.status, Status::Ok) << r.outcome.output.message;
  const auto& res = r.result();
  // Every point converged to the tolerance (relative residual).
  for (double x : res.residual) EXPECT_LE(x, 1e-8);
  EXPECT_NEAR(res.frequency.back(), 2.0, 1e-9);
  // The friction elements dissipate energy, the elastic cubic spring none: its loop encloses no
  // area, up to the second-order error of the trapezoidal loop integral over 1024 samples,
  // O((2 pi / 1024)^2) = 4e-5 of f du before the cancellation over the closed loop; 1e-5 of the
  // friction's energy bounds it.
  double friction = 0.0;
  for (Eigen::Index i = 0; i < res.energy.rows(); ++i)
    friction = std::max(friction, res.energy(i, 0));
  EXPECT_GT(friction, 0.0);
  for (Eigen::Index i = 0; i < res.energy.rows(); ++i)
    EXPECT_NEAR(res.energy(i, 2), 0.0, 1e-5 * friction);
}

TEST(NonlinearResponse, ElementBetweenANodeAndItselfIsALocatedError) {
  const auto dir = fresh_dir("nonlinear_self");
  std::string text = duffing_model("frequency_start_hz = 0.1\nfrequency_stop_hz = 0.2\n");
  text.replace(text.find("node2 = \"p\"\ndirection"), 11, "node1 = \"p\"\nnode2 = \"p\"");
  try {
    (void)load(dir, text);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "nonlinear_elements[0].node2");
    EXPECT_GT(e.where().line, 0);
  }
}

TEST(NonlinearResponse, FrictionContactWithoutNormalLoadIsALocatedError) {
  const auto dir = fresh_dir("nonlinear_no_normal_load");
  std::string text = duffing_model("frequency_start_hz = 0.1\nfrequency_stop_hz = 0.2\n");
  text.replace(text.find("type = \"cubic\""), 14, "type = \"friction_contact\"");
  text.replace(text.find("stiffness = 0.1"), 15,
               "tangent = [1.0, 0.0, 0.0]\ntangential_stiffness = 10.0\nfriction_coefficient = "
               "0.3");
  try {
    (void)load(dir, text);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "nonlinear_elements[0].normal_preload");
  }
}

}  // namespace
}  // namespace geardyn::analyses

namespace geardyn::analyses {
namespace {

// The Duffing oscillator's backbone at H = 1: w^2 = k/m + 3/4 (alpha/m) a^2 (Nayfeh & Mook 1979,
// sec. 4.1), a the first-harmonic amplitude, here through the model file and nonlinear_modes.
TEST(NonlinearModes, DuffingBackboneMatchesTheClosedForm) {
  const auto dir = test::fresh_dir("nonlinear_modes_duffing");
  std::string text = duffing_model("");
  text.replace(text.find("type = \"nonlinear_response\"\nforces = [\"F\"]"),
               std::string("type = \"nonlinear_response\"\nforces = [\"F\"]").size(),
               "type = \"nonlinear_modes\"\namplitude_start = 0.01\namplitude_stop = 4.0\n"
               "harmonics = 1\ntime_samples = 16");
  const model::Model m = test::load(dir, text);
  check_inputs(m, {});
  fe::LinearSystem system = assembly::build_system(m, nullptr);
  Context c(m, m.analyses[0]);
  c.with_system(&system);
  const Outcome out = run_analysis(m, m.analyses[0], c);
  ASSERT_EQ(out.output.status, Status::Ok) << out.output.message;
  const Table& t = test::table(out.output, "backbone");
  const auto& hz = t.column("frequency_hz").numbers;
  const auto& a = t.column("x_h1_m").numbers;
  const auto& zeta = t.column("damping_ratio").numbers;
  ASSERT_GT(hz.size(), 5u);
  EXPECT_GE(a.back(), 4.0 * (1.0 - 1e-9));
  for (std::size_t i = 0; i < hz.size(); ++i) {
    const double w = hz[i] * kTwoPi;
    // Exact at H = 1 with 16 > 4H samples: the Newton tolerance (1e-10) sets the error.
    EXPECT_NEAR(w * w, 1.0 + 0.075 * a[i] * a[i], 1e-8 * (1.0 + a[i] * a[i])) << "point " << i;
    // Mass-proportional damping c = 0.05 m: xi = c / m, zeta = xi / (2 w) (Krack 2015).
    EXPECT_NEAR(zeta[i], 0.05 / (2.0 * w), 1e-8);
  }
}

}  // namespace
}  // namespace geardyn::analyses

namespace geardyn::analyses {
namespace {

// A mass held only by a unilateral spring that acts for u > gap, pushed the other way by a
// constant load: no periodic state exists (the mean has nothing to balance the load), so Newton
// cannot start. The run reports it (status failed, where and what helps); nothing is hidden.
TEST(NonlinearResponse, AStartTheSolverCannotConvergeIsReported) {
  const auto dir = test::fresh_dir("nonlinear_cannot_start");
  std::string text =
      duffing_model("mean_forces = [\"P\"]\nfrequency_start_hz = 0.1\nfrequency_stop_hz = 0.2\n");
  text.replace(text.find("[[sensors]]"), 11,
               "[[forces]]\nname = \"P\"\nnode = \"p\"\ndof = \"uz\"\namplitude = 0.5\n"
               "phase_deg = 180.0\n[[sensors]]");
  text.replace(text.find("kzz = 1.0\nczz = 0.05"), 20, "czz = 0.05");
  text.replace(text.find("type = \"cubic\""), 14, "type = \"unilateral\"");
  text.replace(text.find("stiffness = 0.1"), 15, "stiffness = 1.0\ngap = 0.5");
  const model::Model m = test::load(dir, text);
  check_inputs(m, {});
  fe::LinearSystem system = assembly::build_system(m, nullptr);
  Context c(m, m.analyses[0]);
  c.with_system(&system);
  const Outcome out = run_analysis(m, m.analyses[0], c);
  EXPECT_EQ(out.output.status, Status::Failed);
  EXPECT_NE(out.output.message.find("could not start"), std::string::npos) << out.output.message;
}

// A Duffing oscillator with a tanh-regularised Coulomb damper in parallel: a velocity-dependent
// element. Hill's method takes its velocity Jacobian in the first-order term (hbm/stability.hpp),
// so its verdicts must agree with the monodromy matrix of a time march through the same laws
// (Seydel, "Practical Bifurcation and Stability Analysis", 2010, ch. 7: both give the Floquet
// multipliers of the same periodic solution). The two may differ only at the one or two points
// next to each fold, where the critical multiplier is within the truncation (H = 5) and the
// march's frequency error ((w h)^2 / 12 at 1024 steps) of the unit circle.
TEST(NonlinearResponse, HillWithAVelocityDependentElementAgreesWithTheMonodromy) {
  auto with_coulomb = [](const std::string& stability) {
    std::string text = duffing_model(R"(frequency_start_hz = 0.0795774715
frequency_stop_hz = 0.3183098862
harmonics = 5
time_samples = 64
max_step = 0.03
stability = ")" + stability + "\"\n");
    text.replace(text.find("[[analyses]]"), 12,
                 "[[nonlinear_elements]]\nname = \"damper\"\ntype = \"coulomb\"\nnode2 = \"p\"\n"
                 "direction = [0.0, 0.0, 1.0]\nslip_force = 0.01\nregularisation_velocity = 0.05\n"
                 "[[analyses]]");
    return text;
  };
  const model::Model hill_model = load(fresh_dir("nonlinear_hill_coulomb"), with_coulomb("hill"));
  const model::Model mono_model =
      load(fresh_dir("nonlinear_monodromy_coulomb"), with_coulomb("monodromy"));
  const Solved hill = run(hill_model), mono = run(mono_model);
  ASSERT_EQ(hill.outcome.output.status, Status::Ok) << hill.outcome.output.message;
  ASSERT_EQ(mono.outcome.output.status, Status::Ok) << mono.outcome.output.message;
  const auto &h = hill.result(), &m = mono.result();
  ASSERT_EQ(h.frequency.size(), m.frequency.size());
  ASSERT_EQ(h.turning_points.size(), 2u);  // the hardening curve still folds twice
  int unstable = 0, differ = 0;
  for (std::size_t i = 0; i < h.frequency.size(); ++i) {
    unstable += h.unstable[i] ? 1 : 0;
    if (h.unstable[i] != m.unstable[i]) ++differ;
  }
  EXPECT_GT(unstable, 3);  // the middle branch is found unstable
  EXPECT_LE(differ, 4);    // at most two points next to each fold (see above)
}

// Two identical Duffing oscillators (tests above) joined by a linear spring k_c, forced in phase:
// the symmetric motion x1 = x2 is the single Duffing's, and the antisymmetric perturbation
// d = x1 - x2 sees the single oscillator's linearisation with k + 2 k_c. Where that block is
// singular on the symmetric curve away from its folds, an antisymmetric family branches off: a
// symmetry-breaking pitchfork (Vakakis et al., "Normal Modes and Localization in Nonlinear
// Systems", Wiley 1996). At H = 1 the block is the 2 x 2 Jacobian of the averaged equations,
//   [k' - w^2 + 3/4 alpha (A^2 + 2 a^2), c w + 3/2 alpha a b; -c w + 3/2 alpha a b,
//    k' - w^2 + 3/4 alpha (A^2 + 2 b^2)],  x1 = a cos wt + b sin wt,  A^2 = a^2 + b^2,
// whose determinant must change sign exactly between each reported branch point and the point
// before it, and nowhere else on the curve (the test function of the continuation is the sign of
// the full bordered determinant, whose symmetric block keeps its sign through the folds).
TEST(NonlinearResponse, SymmetryBreakingBranchPointsOfCoupledDuffings) {
  std::string text = R"(version = 1
dofs = "axial"
[[nodes]]
name = "p1"
position = [0.0, 0.0, 0.0]
[[nodes]]
name = "p2"
position = [1.0, 0.0, 0.0]
[[point_masses]]
node = "p1"
mass = 1.0
[[point_masses]]
node = "p2"
mass = 1.0
[[bearings]]
name = "s1"
node = "p1"
kzz = 1.0
czz = 0.05
[[bearings]]
name = "s2"
node = "p2"
kzz = 1.0
czz = 0.05
[[forces]]
name = "F1"
node = "p1"
dof = "uz"
amplitude = 0.18
[[forces]]
name = "F2"
node = "p2"
dof = "uz"
amplitude = 0.18
[[sensors]]
name = "x1"
node = "p1"
dof = "uz"
[[sensors]]
name = "x2"
node = "p2"
dof = "uz"
[[nonlinear_elements]]
name = "cubic1"
type = "cubic"
node2 = "p1"
direction = [0.0, 0.0, 1.0]
stiffness = 0.1
[[nonlinear_elements]]
name = "cubic2"
type = "cubic"
node2 = "p2"
direction = [0.0, 0.0, 1.0]
stiffness = 0.1
[[nonlinear_elements]]
name = "coupling"
type = "polynomial"
node1 = "p1"
node2 = "p2"
direction = [0.0, 0.0, 1.0]
powers = [1]
coefficients = [0.02]
[[analyses]]
name = "nl"
type = "nonlinear_response"
forces = ["F1", "F2"]
frequency_start_hz = 0.0795774715
frequency_stop_hz = 0.3183098862
harmonics = 1
time_samples = 16
tolerance = 1e-12
max_step = 0.02
)";
  const model::Model m = load(fresh_dir("nonlinear_coupled_duffing"), text);
  const Solved run_result = run(m);
  ASSERT_EQ(run_result.outcome.output.status, Status::Ok) << run_result.outcome.output.message;
  const auto& r = run_result.result();
  const double k = 1.0 + 2.0 * 0.02, c = 0.05, alpha = 0.1;
  auto antisymmetric_det = [&](std::size_t i) {
    const Eigen::MatrixXd& x = r.sensor_coefficients[i];  // row 0: x1
    const double a = x(0, hbm::HarmonicBasis::cos_index(1));
    const double b = x(0, hbm::HarmonicBasis::sin_index(1));
    const double w = r.frequency[i], A2 = a * a + b * b;
    const double d11 = k - w * w + 0.75 * alpha * (A2 + 2.0 * a * a);
    const double d22 = k - w * w + 0.75 * alpha * (A2 + 2.0 * b * b);
    const double s = 1.5 * alpha * a * b;
    return d11 * d22 - (s * s - c * c * w * w);
  };
  std::vector<int> expected;
  for (std::size_t i = 1; i < r.frequency.size(); ++i) {
    // The motion stays symmetric (the continuation follows the symmetric family).
    EXPECT_NEAR((r.sensor_coefficients[i].row(0) - r.sensor_coefficients[i].row(1)).norm(), 0.0,
                1e-9);
    if ((antisymmetric_det(i) > 0.0) != (antisymmetric_det(i - 1) > 0.0))
      expected.push_back(static_cast<int>(i));
  }
  ASSERT_FALSE(expected.empty()) << "k_c chosen so that the symmetric curve has branch points";
  EXPECT_EQ(r.branch_points, expected);
  EXPECT_EQ(r.turning_points.size(), 2u);
  // The branch_points table lists them.
  const Table& branches = table(run_result.outcome.output, "branch_points");
  EXPECT_EQ(branches.rows(), expected.size());
}

}  // namespace
}  // namespace geardyn::analyses
