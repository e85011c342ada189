// nonlinear_response in the condensed form (coordinates = "condensed", nonlinear_condensed.hpp;
// docs/theory.md §19): the balance on the nonlinear elements' relative coordinates through the
// receptance of the kept modes plus the residual flexibility of the others (Petrov & Ewins,
// J. Turbomach. 125 (2003) 364-371; Krack & Gross, "Harmonic Balance for Nonlinear Vibration
// Problems", Springer 2019, sec. 3.4).
//  - a 12-element pinned-pinned steel beam (52 lateral DOFs, mass-proportional damping) with a
//    Jenkins element and a cubic spring: at fixed frequencies across the first bending resonance
//    the condensed form (24 modes) gives the sensor coefficients of the physical form to 1e-7;
//  - without the residual flexibility it equals the modal form with the same modes to the
//    Newton tolerance, whose error against the physical form is much larger;
//  - a 2500-element beam (10^4 DOFs) with 20 elements runs and its points are solutions;
//  - bad inputs: condensed with a speed parameter, with n_modes < 1, with stability =
//    "monodromy".
#include "geardyn/analyses/nonlinear_condensed.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

// A steel shaft (E 211 GPa, rho 7810 kg/m^3, d = 20 mm, L = 1 m) in `divisions` Timoshenko
// elements, lateral DOFs only, on stiff bearings (1e8 N/m) at both ends: nearly pinned-pinned,
// first bending mode pi^2 sqrt(EI / (rho A L^4)) = 257 rad/s (41 Hz) in each plane. Rayleigh
// damping C = alpha M with alpha = 5.1 1/s: zeta_1 = alpha / (2 w_1) = 1 %, proportional. (Not
// stiffness-proportional: beta K damps the modes left out by 2 zeta_r w / w_r = beta w, a
// first-order error the quasi-static residual flexibility does not carry; docs/theory.md §19.)
// 10 N at mid-span along x; `elements` are [[nonlinear_elements]] entries.
std::string beam_model(int divisions, const std::string& elements, const std::string& analysis) {
  // Segments of at most 500 elements (the schema's limit per entry is 1000); nodes shaft.0 to
  // shaft.<divisions> along the whole shaft.
  const int n_segments = divisions > 1000 ? divisions / 500 : 1;
  std::string segments;
  for (int k = 0; k < n_segments; ++k)
    segments += fmt::format(
        "  [[shafts.elements]]\n  length = {}\n  outer_diameter = 0.02\n  divisions = {}\n",
        1.0 / n_segments, divisions / n_segments);
  return fmt::format(R"(version = 1
dofs = "lateral"
[[materials]]
name = "steel"
youngs_modulus = 211e9
shear_modulus = 81.2e9
density = 7810
[[shafts]]
name = "shaft"
material = "steel"
axis = [0, 0, 1]
{5}[[bearings]]
name = "left"
node = "shaft.0"
kxx = 1e8
kyy = 1e8
[[bearings]]
name = "right"
node = "shaft.{0}"
kxx = 1e8
kyy = 1e8
[damping]
rayleigh_alpha = 5.1
[[forces]]
name = "F"
node = "shaft.{1}"
dof = "ux"
amplitude = 10.0
[[sensors]]
name = "mid"
node = "shaft.{1}"
dof = "ux"
[[sensors]]
name = "third"
node = "shaft.{2}"
dof = "ux"
{3}[[analyses]]
name = "nl"
type = "nonlinear_response"
forces = ["F"]
{4})",
                     divisions, divisions / 2, divisions / 3, elements, analysis, segments);
}

std::string element(const std::string& name, const std::string& type, int node,
                    const std::string& law) {
  return fmt::format(
      "[[nonlinear_elements]]\nname = \"{}\"\ntype = \"{}\"\nnode2 = \"shaft.{}\"\n"
      "direction = [1.0, 0.0, 0.0]\n{}\n",
      name, type, node, law);
}

// 12 elements: 52 lateral DOFs, so that the dense physical reference (52 x 7 unknowns at H = 3)
// stays within the test's time budget.
constexpr int kDivisions = 12;

// A Jenkins slider (k 1e5 N/m, slip at 50 N: it slips near resonance) at a third of the span and
// a hardening cubic spring (3e8 N/m^3: 10 % of the beam's mid-span stiffness 48 EI / L^3 at
// 5 mm) at two thirds.
std::string two_elements() {
  return element("slider", "jenkins", kDivisions / 3, "stiffness = 1e5\nslip_force = 50.0") +
         element("hardening", "cubic", 2 * kDivisions / 3, "stiffness = 3e8");
}

Outcome run(const model::Model& m) {
  check_inputs(m, {});
  fe::LinearSystem system = assembly::build_system(m, nullptr);
  Context c(m, m.analyses[0]);
  c.with_system(&system);
  return run_analysis(m, m.analyses[0], c);
}

// The sensor coefficients at force factor 1 of a force-level continuation at `hz`, and the
// highest mode kept (NaN: physical form).
struct EndPoint {
  Eigen::MatrixXd coefficients;
  double highest_mode_hz = 0.0;
};

EndPoint end_point(const std::string& name, const std::string& form, double hz) {
  const auto dir = test::fresh_dir(name);
  const model::Model m = test::load(
      dir, beam_model(kDivisions, two_elements(),
                      fmt::format("{}parameter = \"force_level\"\nfrequency_hz = {}\nharmonics = "
                                  "3\ntolerance = 1e-12\nmax_step = 0.2\n",
                                  form, hz)));
  const Outcome o = run(m);
  EXPECT_EQ(o.output.status, Status::Ok) << o.output.message;
  const auto& r = result_of<NonlinearResponseResult>(o);
  EXPECT_NEAR(r.level.back(), 1.0, 1e-12);
  return {r.sensor_coefficients.back(), r.highest_mode_hz};
}

double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& reference) {
  return (a - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

constexpr double kFrequencies[] = {35.0, 41.0, 47.0, 60.0};

TEST(NonlinearCondensed, EqualsThePhysicalFormAtFixedFrequencies) {
  for (double hz : kFrequencies) {
    const EndPoint condensed =
        end_point("condensed_condensed", "coordinates = \"condensed\"\nn_modes = 24\n", hz);
    const EndPoint physical = end_point("condensed_physical", "", hz);
    const double error = relative_difference(condensed.coefficients, physical.coefficients);
    std::cout << "condensed vs physical at " << hz << " Hz: " << error << "\n";
    // The residual flexibility makes the static part exact; each mode left out errs by the
    // relative (n w / w_r)^2 of its quasi-static term (its damping alpha / w_r^2 far smaller).
    // 24 modes keep 12 per plane, the highest at 5835 Hz (w_13: 6354 Hz); the quasi-static share
    // of the modes left out is ~1.2e-4 of the response (the modal form's error, next test), so
    // the error is below 1.2e-4 x (3 x 60 Hz / 5835 Hz)^2 = 1.1e-7 for the third harmonic and
    // 1.2e-4 x (60 / 5835)^2 = 1.3e-8 for the fundamental, which dominates (the third harmonic
    // is 3e-5 of the amplitude): 1e-7.
    EXPECT_LT(error, 1e-7) << hz << " Hz";
  }
}

// The problem run_nonlinear_response hands to the condensed form, built here to switch the
// residual flexibility off.
NonlinearResponseResult condensed_without_residual(const model::Model& m) {
  check_inputs(m, {});
  const fe::LinearSystem system = assembly::build_system(m, nullptr);
  Context c(m, m.analyses[0]);
  c.with_system(&system);
  const auto& s = m.analyses[0].settings_of<NonlinearResponseSettings>();
  const auto elements = build_nonlinear_elements(m, system, c);
  const NonlinearCoordinates modes = nonlinear_coordinates(system, s.speed, s.n_modes, c);
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(system.size(), 3);
  const int mid = system.dofs.node_index(fmt::format("shaft.{}", kDivisions / 2));
  F.col(1) = 10.0 * system.unit_load(mid, model::Component::Ux);
  const SensorRows sensors = nonlinear_sensor_rows(m, system, s.sensors, c);
  CondensedFormOptions o;
  o.residual_flexibility = false;
  return run_nonlinear_condensed({system, elements, modes, F, sensors}, s, c, o);
}

TEST(NonlinearCondensed, WithoutResidualFlexibilityItIsTheModalForm) {
  const double hz = 47.0;
  const std::string level =
      "parameter = \"force_level\"\nfrequency_hz = 47.0\nharmonics = 3\n"
      "tolerance = 1e-12\nmax_step = 0.2\n";
  const auto dir = test::fresh_dir("condensed_no_residual");
  const model::Model m = test::load(
      dir, beam_model(kDivisions, two_elements(),
                      fmt::format("coordinates = \"condensed\"\nn_modes = 24\n{}", level)));
  const NonlinearResponseResult bare = condensed_without_residual(m);
  ASSERT_EQ(bare.status, Status::Ok) << bare.message;
  const EndPoint modal =
      end_point("condensed_modal", "coordinates = \"modal\"\nn_modes = 24\n", hz);
  const EndPoint physical = end_point("condensed_physical_2", "", hz);
  const EndPoint condensed =
      end_point("condensed_full", "coordinates = \"condensed\"\nn_modes = 24\n", hz);
  const double same = relative_difference(bare.sensor_coefficients.back(), modal.coefficients);
  const double modal_error = relative_difference(modal.coefficients, physical.coefficients);
  const double condensed_error = relative_difference(condensed.coefficients, physical.coefficients);
  std::cout << "bare condensed vs modal " << same << ", modal vs physical " << modal_error
            << ", condensed vs physical " << condensed_error << "\n";
  // The same equations (the modal sum of the kept modes, proportional damping diagonal in them)
  // in other unknowns: equal to the Newton tolerance 1e-12 amplified by the conditioning of the
  // slipping Jenkins element's tangent; 1e-9.
  EXPECT_LT(same, 1e-9);
  // The modal form's error is the quasi-static share of the modes left out; the residual
  // flexibility removes it up to their dynamic part, the relative (n w / w_r)^2 with w_r above
  // the highest mode kept and n <= H = 3: the bound below (measured 2.4e-9 against 1.1e-4).
  const double dynamic = std::pow(3.0 * hz / condensed.highest_mode_hz, 2);
  EXPECT_LT(condensed_error, modal_error * dynamic);
  EXPECT_GT(modal_error, 1e3 * condensed_error);
}

// 2500 elements, 10004 lateral DOFs, 20 nonlinear elements (Jenkins and cubic alternating along
// the span), 20 modes: the condensed balance has 20 x 7 unknowns.
TEST(NonlinearCondensed, TenThousandDofsRun) {
  std::string elements;
  for (int k = 0; k < 20; ++k) {
    const int node = 100 + 115 * k;
    elements += k % 2 == 0 ? element(fmt::format("s{}", k), "jenkins", node,
                                     "stiffness = 1e4\nslip_force = 20.0")
                           : element(fmt::format("c{}", k), "cubic", node, "stiffness = 1e7");
  }
  const auto dir = test::fresh_dir("condensed_large");
  const model::Model m = test::load(
      dir, beam_model(2500, elements,
                      "coordinates = \"condensed\"\nn_modes = 20\nfrequency_start_hz = 35.0\n"
                      "frequency_stop_hz = 50.0\nharmonics = 3\n"));
  const Outcome o = run(m);
  ASSERT_EQ(o.output.status, Status::Ok) << o.output.message;
  const auto& r = result_of<NonlinearResponseResult>(o);
  EXPECT_TRUE(r.condensed);
  EXPECT_EQ(r.coordinates, 20);
  EXPECT_NEAR(r.frequency.back(), 50.0 * units::kTwoPi, 1e-9);
  ASSERT_GT(r.frequency.size(), 5u);
  // Every point converged (relative residual within the default Newton tolerance 1e-9).
  for (double x : r.residual) EXPECT_LE(x, 1e-9);
  // The notes say what the condensed form did.
  const auto& notes = o.output.notes;
  EXPECT_TRUE(std::any_of(notes.begin(), notes.end(), [](const std::string& n) {
    return n.find("Condensed form: the balance on the 20 relative coordinates") !=
           std::string::npos;
  }));
}

// stability = "hill" in the condensed form: the condensed Hill method (hbm/condensed_stability.hpp)
// gives a verdict at every point of the 12-element beam's curve below the resonance, where the
// response is the stable low branch.
TEST(NonlinearCondensed, HillStabilityRuns) {
  const auto dir = test::fresh_dir("condensed_hill");
  const model::Model m = test::load(
      dir, beam_model(kDivisions, two_elements(),
                      "coordinates = \"condensed\"\nn_modes = 8\nfrequency_start_hz = 30.0\n"
                      "frequency_stop_hz = 36.0\nharmonics = 3\nstability = \"hill\"\n"));
  const Outcome o = run(m);
  ASSERT_EQ(o.output.status, Status::Ok) << o.output.message;
  const auto& r = result_of<NonlinearResponseResult>(o);
  ASSERT_GT(r.frequency.size(), 2u);
  for (std::size_t i = 0; i < r.frequency.size(); ++i) {
    EXPECT_TRUE(std::isfinite(r.max_real_exponent[i])) << "point " << i;
    EXPECT_NE(r.instability[i], "failed") << "point " << i;
    // Below the first resonance, with no fold, every point is stable (Re lambda < 0).
    EXPECT_EQ(r.unstable[i], 0) << "point " << i << ": " << r.max_real_exponent[i];
  }
  EXPECT_TRUE(r.turning_points.empty());
}

TEST(NonlinearCondensed, NModesBelowOneIsALocatedError) {
  const auto dir = test::fresh_dir("condensed_no_modes");
  try {
    (void)test::load(dir, beam_model(kDivisions, two_elements(),
                                     "coordinates = \"condensed\"\nfrequency_start_hz = 35.0\n"
                                     "frequency_stop_hz = 50.0\n"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "analyses[0].n_modes");
    EXPECT_GT(e.where().line, 0);
  }
}

TEST(NonlinearCondensed, MonodromyIsALocatedError) {
  const auto dir = test::fresh_dir("condensed_monodromy");
  const model::Model m = test::load(
      dir, beam_model(kDivisions, two_elements(),
                      "coordinates = \"condensed\"\nn_modes = 20\nstability = \"monodromy\"\n"
                      "frequency_start_hz = 35.0\nfrequency_stop_hz = 50.0\n"));
  try {
    (void)run(m);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "analyses[0].stability");
  }
}

// parameter = "speed" is refused when the model file is read: the receptance is built once at
// the reference speed.
TEST(NonlinearCondensed, SpeedContinuationIsALocatedError) {
  const auto dir = test::fresh_dir("condensed_speed");
  try {
    (void)test::load(dir, beam_model(kDivisions, two_elements(),
                                     "coordinates = \"condensed\"\nn_modes = 20\nparameter = "
                                     "\"speed\"\nspeed_start_rpm = 100.0\nspeed_stop_rpm = "
                                     "200.0\n"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "analyses[0].parameter");
    EXPECT_GT(e.where().line, 0);
  }
}

}  // namespace
}  // namespace geardyn::analyses

namespace geardyn::analyses {
namespace {

// A free-free axial chain of 5 unit masses and unit springs (one rigid-body mode, K singular)
// with a Jenkins element between masses 2 and 4 and a unit force at mass 1: with 3 modes kept
// the residual flexibility must be the static term of the 2 modes left out,
// B (phi_4 phi_4^T / w_4^2 + phi_5 phi_5^T / w_5^2) B^T, from a dense eigen-decomposition of
// the 5 x 5 problem (the reference), and the mean (harmonic 0) must leave out the rigid-body mode
// (inertia relief).
TEST(NonlinearCondensed, FreeChainResidualFlexibilityIsTheModesLeftOut) {
  std::string text = "version = 1\ndofs = \"axial\"\n";
  for (int i = 1; i <= 5; ++i)
    text += fmt::format(
        "[[nodes]]\nname = \"m{0}\"\nposition = [{0}.0, 0.0, 0.0]\n[[point_masses]]\nnode = "
        "\"m{0}\"\nmass = 1.0\n[[sensors]]\nname = \"q{0}\"\nnode = \"m{0}\"\ndof = \"uz\"\n",
        i);
  for (int i = 1; i < 5; ++i)
    text += fmt::format("[[bearings]]\nnode = \"m{}\"\nnode2 = \"m{}\"\nkzz = 1.0\nczz = 0.01\n",
                        i + 1, i);
  text += R"([[forces]]
name = "F"
node = "m1"
dof = "uz"
amplitude = 1.0
[[nonlinear_elements]]
name = "slider"
type = "jenkins"
node1 = "m2"
node2 = "m4"
direction = [0.0, 0.0, 1.0]
stiffness = 1.0
slip_force = 0.1
[[analyses]]
name = "nl"
type = "nonlinear_response"
forces = ["F"]
coordinates = "condensed"
n_modes = 3
frequency_start_hz = 0.1
frequency_stop_hz = 0.2
harmonics = 2
)";
  const auto dir = test::fresh_dir("condensed_free_chain");
  const model::Model m = test::load(dir, text);
  check_inputs(m, {});
  const fe::LinearSystem system = assembly::build_system(m, nullptr);
  Context c(m, m.analyses[0]);
  c.with_system(&system);
  const auto& s = m.analyses[0].settings_of<NonlinearResponseSettings>();
  const auto elements = build_nonlinear_elements(m, system, c);
  const NonlinearCoordinates modes = nonlinear_coordinates(system, s.speed, s.n_modes, c);
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(system.size(), 3);
  F.col(1) = system.unit_load(system.dofs.node_index("m1"), model::Component::Uz);
  const SensorRows sensors = nonlinear_sensor_rows(m, system, s.sensors, c);
  std::vector<std::string> notes;
  const auto h = condensed_receptances({system, elements, modes, F, sensors}, s, {}, c, notes);

  const Eigen::MatrixXd K(system.K), M(system.M);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  const Eigen::MatrixXd& Phi = eig.eigenvectors();  // mass-normalised, ascending
  const Eigen::MatrixXd& B = elements[0].B;
  Eigen::MatrixXd reference = Eigen::MatrixXd::Zero(1, 1);
  for (int r = 3; r < 5; ++r)
    reference += (B * Phi.col(r)) * (B * Phi.col(r)).transpose() / eig.eigenvalues()[r];
  ASSERT_EQ(h.size(), 3u);
  // Round-off of a 5 x 5 eigen-decomposition and of the fixed point (settled to 1e-12): 1e-10.
  EXPECT_NEAR(h[1].residual(0, 0).real(), reference(0, 0), 1e-10 * reference(0, 0));
  EXPECT_NEAR(h[1].residual(0, 0).imag(), 0.0, 1e-14);
  // Inertia relief: the mean has the 2 elastic modes kept, harmonics >= 1 all 3.
  EXPECT_EQ(h[0].modes(), 2);
  EXPECT_EQ(h[1].modes(), 3);
  // The residual excitation: the same static term applied to the force at mass 1.
  const Eigen::VectorXd f1 = F.col(1);
  double r_f = 0.0;
  for (int r = 3; r < 5; ++r)
    r_f += (B * Phi.col(r))(0) * Phi.col(r).dot(f1) / eig.eigenvalues()[r];
  EXPECT_NEAR(h[1].residual_excitation[0].real(), r_f, 1e-10 * std::abs(reference(0, 0)));
  // And the whole curve runs through the rigid-body mode.
  const Outcome o = run(m);
  EXPECT_EQ(o.output.status, Status::Ok) << o.output.message;
}

}  // namespace
}  // namespace geardyn::analyses
