// The gear analyses run from model files reproduce the gear library's validated numbers and
// closed-form references end to end (model file -> Model -> PairModel -> analysis tables).
//
// Systems:
//   spur pair z1 = 20, z2 = 40, m = 3 mm, alpha = 20 deg, b = 20 mm, T1 = 100 N m
//        r1 = 30 mm  (pinion) ----o---- r2 = 60 mm (wheel), a = 90 mm
//   one-DOF mesh along the line of action (docs/theory.md §13):
//        F_s ---> [ m_e ] ---/\/\/ k(t) ---|  (the other flank)
//                         ----[ c ]--------|
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "geardyn/analyses/correlation.hpp"
#include "geardyn/analyses/gear_pair.hpp"
#include "geardyn/analyses/mesh_force.hpp"
#include "geardyn/analyses/mesh_harmonics.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using namespace test;
constexpr double kPi = std::numbers::pi;
constexpr double kAlpha = 20.0 * kPi / 180.0;

const std::string kHeader = "version = 1\n";

std::string spur_pair(const std::string& extra = {}) {
  return R"([[gear_pairs]]
name = "spur"
teeth1 = 20
teeth2 = 40
module = 0.003
face_width = 0.02
torque = 100
)" + extra;
}

/// Runs analysis `i` of `m` as the registry does (driver, then output) and keeps its result.
Outcome run_entry(const model::Model& m, std::size_t i) {
  return type_of(m.analyses[i]).run(m, m.analyses[i], Context(m, m.analyses[i]));
}

bool has_note(const AnalysisOutput& out, const std::string& text) {
  for (const auto& n : out.notes)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

// Tooth forces: F_t = T / r = 100 N m / 0.030 m = 3333.333333 N and F_r = F_t tan(20 deg)
// (spur formulas, docs/theory.md §11.2); the wheel carries the same tangential force (no losses).
// Contact ratio: eps_alpha = (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - a sin(alpha)) /
// (pi m cos(alpha)) with ra = r + m (docs/theory.md (11.2)). Both to 1e-12 relative: closed forms,
// only rounding differs.
TEST(GearanValidation, GearPairToothForcesAndContactRatioOfASpurPair) {
  const fs::path dir = fresh_dir("gear_pair_spur");
  const model::Model m = load(dir, kHeader + spur_pair() + R"([[analyses]]
name = "pair"
type = "gear_pair"
)");
  check_inputs(m, {});
  const AnalysisOutput out = run_entry(m, 0).output;

  const Table& forces = table(out, "tooth_forces");
  for (const char* load_case : {"drive", "coast"}) {
    for (const char* member : {"pinion", "wheel"}) {
      const std::size_t i = row_where(forces, "load_case", load_case, "member", member);
      EXPECT_NEAR(forces.column("tangential_force_n").numbers[i], 3333.333333, 1e-6)
          << load_case << " " << member;
      EXPECT_NEAR(forces.column("radial_force_n").numbers[i], 3333.333333 * std::tan(kAlpha), 1e-6);
      EXPECT_NEAR(forces.column("axial_force_n").numbers[i], 0.0, 1e-9);
    }
  }
  const double rb1 = 0.030 * std::cos(kAlpha), rb2 = 0.060 * std::cos(kAlpha);
  const double eps = (std::sqrt(0.033 * 0.033 - rb1 * rb1) + std::sqrt(0.063 * 0.063 - rb2 * rb2) -
                      0.090 * std::sin(kAlpha)) /
                     (kPi * 0.003 * std::cos(kAlpha));
  const Table& geometry = table(out, "gear_geometry");
  EXPECT_NEAR(geometry.column("transverse_contact_ratio").numbers[0], eps, 1e-12 * eps);
  std::printf("eps_alpha = %.9f (closed form %.9f)\n",
              geometry.column("transverse_contact_ratio").numbers[0], eps);

  // ISO 6336-1: the mean of the single-pair law over a mesh cycle is c_gamma_alpha b exactly
  // for 1 <= eps_alpha <= 2 (gear/mesh_stiffness.hpp). The curve's mean is that of its 512
  // uniform samples; the spur curve jumps where a pair enters and leaves contact (by 0.75 c' b,
  // twice per cycle), so the sample mean is within 2 x 0.75 c' b / 512 of the integral.
  const Table& iso = table(out, "iso_stiffness");
  const double k_iso = iso.column("mesh_stiffness_n_per_m").numbers[0];
  const double k_curve = iso.column("curve_mean_stiffness_n_per_m").numbers[0];
  const double c_single = iso.column("single_stiffness_n_per_m").numbers[0];
  std::printf("k_mean: curve %.9e, ISO c_gamma_alpha b %.9e\n", k_curve, k_iso);
  EXPECT_NEAR(k_curve, k_iso, 2.0 * 0.75 * c_single / 512.0);
  // The synthetic STE: e = F_s / k with F_s = T / r_b1.
  const Table& ste = table(out, "mesh_stiffness");
  const double fs_n = 100.0 / rb1;
  for (std::size_t j = 0; j < ste.rows(); j += 37)
    EXPECT_NEAR(ste.column("ste_m").numbers[j] * ste.column("stiffness_n_per_m").numbers[j], fs_n,
                1e-9 * fs_n);
  EXPECT_EQ(out.plots.size(), 2u);
}

// Reference case of issue [mesh-excitation] sec. 10 (the library's test
// LinearReferenceCaseMatchesPublishedValues), now through a model file and an STE CSV file:
// m_e = 1 kg, F_s = 1000 N, k = 3.2e8 N/m over the first 0.6 of each mesh cycle and 2.0e8 N/m
// over the rest (e = F_s / k = 3.125 um and 5 um, ten rows held), zeta = 0.05, linear mesh.
//   k_mean = 2.72e8 N/m, f_n = sqrt(k_mean / m_e) / 2 pi = 2624.850565 Hz.
// The pair: r_b1 = 30 mm cos 20 deg; torque = 1000 N x r_b1 gives F_s = 1000 N; inertia1 =
// r_b1^2 kg m^2 with inertia2 = inf gives m_e = inertia1 / r_b1^2 = 1 kg. Gear 1 speed for a
// mesh frequency f_m: n1 = 60 f_m / z1. Published DTE values to 1e-5 relative as in the library
// test (exact propagation; the rest is the 1e-9 steady-state tolerance and rounding of the
// inputs written with 17 digits).
TEST(GearanValidation, MeshForceReproducesTheParkerLinearReferenceThroughAnSteFile) {
  const fs::path dir = fresh_dir("parker_linear");
  std::string csv = "# step STE: double contact 0.6 of the cycle, single contact 0.4\n";
  csv += "angle_deg, ste_um\n";
  for (int j = 0; j < 10; ++j) csv += fmt::format("{}, {}\n", 1.8 * j, j < 6 ? 3.125 : 5.0);
  write_file(dir / "step_ste.csv", csv);
  const double rb1 = 0.030 * std::cos(kAlpha);
  const double fn = std::sqrt(2.72e8) / (2.0 * kPi);
  const double rpm_low = 60.0 * 0.25 * fn / 20.0, rpm_res = 60.0 * fn / 20.0;
  const model::Model m =
      load(dir, kHeader + fmt::format(R"([[gear_pairs]]
name = "parker"
teeth1 = 20
teeth2 = 40
module = 0.003
face_width = 0.02
torque = {:.17g}
inertia1 = {:.17g}
inertia2 = inf
ste_file = "step_ste.csv"
ste_interpolation = "hold"
mesh_damping_ratio = 0.05
[[analyses]]
name = "linear"
type = "mesh_force"
speed_rpm = [{:.17g}, {:.17g}]
direction = "up"
contact_loss = false
[[analyses]]
name = "rigid"
type = "mesh_force"
speed_rpm = [{:.17g}]
direction = "up"
model = "infinite_inertia"
)",
                                      1000.0 * rb1, rb1 * rb1, rpm_low, rpm_res, rpm_low));
  check_inputs(m, {});
  const AnalysisOutput out = run_entry(m, 0).output;
  ASSERT_EQ(out.status, Status::Ok) << out.message;
  const Table& t = table(out, "sweep_up");
  ASSERT_EQ(t.rows(), 2u);
  const auto& mean = t.column("dte_mean_m").numbers;
  const auto& rms = t.column("dte_rms_m").numbers;
  const auto& max = t.column("dte_max_m").numbers;
  std::printf("0.25 f_n: mean %.9e rms %.9e max %.9e; f_n: mean %.9e rms %.9e\n", mean[0], rms[0],
              max[0], mean[1], rms[1]);
  EXPECT_NEAR(mean[0], 3.857469e-6, 3.857469e-6 * 1e-5);
  EXPECT_NEAR(rms[0], 2.138550e-6, 2.138550e-6 * 1e-5);
  EXPECT_NEAR(max[0], 8.046656e-6, 8.046656e-6 * 1e-5);
  EXPECT_NEAR(mean[1], 4.671647e-6, 4.671647e-6 * 1e-5);
  EXPECT_NEAR(rms[1], 1.198939e-5, 1.198939e-5 * 1e-5);
  EXPECT_NEAR(t.column("speed_rpm").numbers[0], rpm_low, 1e-9 * rpm_low);
  // The resonance speed in the notes: 60 f_n / z1 = 7874.551695 rpm.
  EXPECT_TRUE(has_note(out, fmt::format("{:.6g} rpm", rpm_res))) << rpm_res;

  // Infinite inertias: F_d = F_s k(t) / k_mean, so the dynamic factor is k_max / k_mean =
  // 3.2 / 2.72 exactly (up to rounding).
  const AnalysisOutput rigid = run_entry(m, 1).output;
  ASSERT_EQ(rigid.status, Status::Ok) << rigid.message;
  EXPECT_NEAR(table(rigid, "sweep_up").column("dynamic_factor").numbers[0], 3.2 / 2.72, 1e-12);
}

// The same mesh with contact loss near the resonance, swept both ways: the teeth separate
// (contact_loss > 0) and the analysis says so; and without damping at the principal parametric
// resonance f_m = 2 f_n the linear model grows without bound: with that speed alone the
// analysis fails and names it; among speeds that have a steady state it is reported per speed.
TEST(GearanValidation, MeshForceReportsContactLossAndFailsVisiblyWithoutSteadyState) {
  const fs::path dir = fresh_dir("parker_contact_loss");
  std::string csv = "angle_deg, ste_um\n";
  for (int j = 0; j < 10; ++j) csv += fmt::format("{}, {}\n", 1.8 * j, j < 6 ? 3.125 : 5.0);
  write_file(dir / "step_ste.csv", csv);
  const double rb1 = 0.030 * std::cos(kAlpha);
  const double rpm_res = 60.0 * std::sqrt(2.72e8) / (2.0 * kPi) / 20.0;
  const std::string pair = fmt::format(R"([[gear_pairs]]
name = "parker"
teeth1 = 20
teeth2 = 40
module = 0.003
face_width = 0.02
torque = {:.17g}
inertia1 = {:.17g}
inertia2 = inf
ste_file = "step_ste.csv"
ste_interpolation = "hold"
)",
                                       1000.0 * rb1, rb1 * rb1);
  const model::Model m = load(dir, kHeader + pair +
                                       fmt::format(R"(mesh_damping_ratio = 0.03
[[analyses]]
name = "loss"
type = "mesh_force"
speed_start_rpm = {:.17g}
speed_stop_rpm = {:.17g}
speed_count = 9
detail_rpm = [{:.17g}]
)",
                                                   0.8 * rpm_res, 1.2 * rpm_res, rpm_res));
  const AnalysisOutput out = run_entry(m, 0).output;
  ASSERT_EQ(out.status, Status::Ok) << out.message;
  double loss = 0.0;
  for (const char* name : {"sweep_up", "sweep_down"})
    for (double x : table(out, name).column("contact_loss").numbers) loss = std::max(loss, x);
  EXPECT_GT(loss, 0.0);
  EXPECT_TRUE(has_note(out, "CONTACT LOSS"));
  EXPECT_EQ(out.plots.size(), 5u);  // dynamic factor, DTE RMS, contact loss, detail F and DTE
  // Every steady state found is a stable orbit (largest Floquet multiplier below 1: it is the
  // attractor the continuation converged to), and the DTE extremes bracket its mean.
  for (const char* name : {"sweep_up", "sweep_down"}) {
    const Table& t = table(out, name);
    for (std::size_t i = 0; i < t.rows(); ++i) {
      EXPECT_LT(t.column("floquet_multiplier").numbers[i], 1.0) << name << " row " << i;
      EXPECT_LE(t.column("dte_min_m").numbers[i], t.column("dte_mean_m").numbers[i]);
      EXPECT_LE(t.column("dte_mean_m").numbers[i], t.column("dte_max_m").numbers[i]);
      EXPECT_LE(t.column("force_min_n").numbers[i], t.column("force_max_n").numbers[i]);
    }
  }
  // The detail table is named by the exact speed and carries it.
  const Table& detail = table(out, fmt::format("detail_{:.10g}rpm", rpm_res));
  EXPECT_NEAR(detail.column("speed_rpm").numbers.front(), rpm_res, 1e-9 * rpm_res);

  const model::Model undamped = load(dir, kHeader + pair +
                                              fmt::format(R"(mesh_damping_ratio = 0.0
[[analyses]]
name = "unstable"
type = "mesh_force"
speed_rpm = [{:.17g}]
direction = "up"
contact_loss = false
)",
                                                          2.0 * rpm_res));
  const AnalysisOutput bad = run_entry(undamped, 0).output;
  EXPECT_NE(bad.status, Status::Ok);
  EXPECT_NE(bad.message.find(fmt::format("{:.6g} rpm", 2.0 * rpm_res)), std::string::npos)
      << bad.message;
  EXPECT_NE(bad.message.find("mesh_damping_ratio"), std::string::npos) << bad.message;

  // One speed without a steady state among others that have one is a finding, not a failed
  // analysis: status ok, the speed named in a note and in the table's status column.
  const model::Model light = load(dir, kHeader + pair +
                                           fmt::format(R"(mesh_damping_ratio = 0.002
[[analyses]]
name = "partly"
type = "mesh_force"
speed_rpm = [{:.17g}, {:.17g}]
direction = "up"
contact_loss = false
)",
                                                       0.3 * rpm_res, 2.0 * rpm_res));
  const AnalysisOutput partly = run_entry(light, 0).output;
  const Table& t = table(partly, "sweep_up");
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.column("status").texts[0], "ok");
  EXPECT_NE(t.column("status").texts[1], "ok");
  EXPECT_FALSE(t.column("message").texts[1].empty());
  EXPECT_EQ(partly.status, Status::Ok) << partly.message;
  EXPECT_TRUE(has_note(partly, "NO STEADY STATE"));
  EXPECT_TRUE(has_note(partly, fmt::format("{:.6g} rpm", 2.0 * rpm_res)));
}

// Engine-order harmonics of a constant mesh force (constant STE, infinite inertias): the tooth
// force is F_t w(phi), so its harmonics are the window's closed-form Fourier coefficients
// (docs/theory.md §12, gear/load_window.hpp):
//   A_k = 2 F_t |W_k|,  W_k = (1/N) e^{-i k CR p / 2} sinc(k p / 2) sinc(k L / 2),
//   p = 2 pi / N, L = (CR - 1) p,
// zero at k = N (order of h = 0), and radial = F_t tan(alpha) per tangential (spur).
// F_t = T / r1 = 3333.333 N, N = 20, CR = 1.6 (given). The window is sampled at 128 points per
// pitch; a trapezoid's DFT differs from its Fourier series by aliasing, bounded below from
// |W_j| <= 4 / (N p L j^2); the k = N amplitude is zero to rounding (1e-9 F_t).
TEST(GearanValidation, MeshHarmonicsOfAConstantMeshForceAreTheWindowCoefficients) {
  const fs::path dir = fresh_dir("harmonics_window");
  write_file(dir / "flat_ste.csv", "angle_deg, ste_um\n0, 4\n4.5, 4\n9, 4\n13.5, 4\n");
  const model::Model m = load(dir, kHeader + spur_pair(R"(ste_file = "flat_ste.csv"
[[analyses]]
name = "h"
type = "mesh_harmonics"
speed_rpm = 1000
model = "infinite_inertia"
contact_ratio = 1.6
nodal_diameters = [0, 1, 7]
)"));
  check_inputs(m, {});
  const AnalysisOutput out = run_entry(m, 0).output;
  ASSERT_EQ(out.status, Status::Ok) << out.message;
  const double ft = 100.0 / 0.030;
  const int n_teeth = 20;
  const double cr = 1.6, p = 2.0 * kPi / n_teeth, l = (cr - 1.0) * p;
  auto sinc = [](double x) { return std::sin(x) / x; };
  auto window_coefficient = [&](int k) {
    return std::polar(1.0 / n_teeth, -k * cr * p / 2.0) * sinc(k * p / 2.0) * sinc(k * l / 2.0);
  };
  const Table& h = table(out, "harmonics");
  ASSERT_EQ(h.rows(), 6u);
  for (std::size_t i = 0; i < h.rows(); ++i) {
    const int nd = static_cast<int>(h.column("nodal_diameter").numbers[i]);
    const int k = static_cast<int>(h.column("engine_order").numbers[i]);
    const double amplitude = h.column("tangential_n").numbers[i];
    const std::complex<double> w = window_coefficient(k);
    std::printf("h = %d k = %2d (%s): A = %.9g N, closed form %.9g N, phase %.6f deg\n", nd, k,
                h.column("branch").texts[i].c_str(), amplitude, 2.0 * ft * std::abs(w),
                h.column("phase_deg").numbers[i]);
    if (k % n_teeth == 0) {
      EXPECT_LT(amplitude, 1e-9 * ft) << "k = " << k;
      continue;
    }
    // Aliasing bound of the sampled window: |W_j| <= 4 / (N p L j^2), summed over the aliases
    // k + m n, m != 0 (n = 2560 samples per revolution).
    double alias = 0.0;
    for (int mm = -50; mm <= 50; ++mm)
      if (mm != 0) alias += 4.0 / (n_teeth * p * l * std::pow(k + mm * 2560.0, 2));
    const double bound = 2.0 * ft * alias;
    EXPECT_NEAR(amplitude, 2.0 * ft * std::abs(w), bound) << "k = " << k;
    const double dphase =
        std::remainder(h.column("phase_deg").numbers[i] - std::arg(w) * 180 / kPi, 360.0);
    EXPECT_NEAR(dphase, 0.0, bound / amplitude * 180 / kPi) << "k = " << k;
    EXPECT_NEAR(h.column("radial_n").numbers[i], amplitude * std::tan(kAlpha), 1e-9 * ft);
    EXPECT_NEAR(h.column("axial_n").numbers[i], 0.0, 1e-9 * ft);
    EXPECT_NEAR(h.column("amplitude_n").numbers[i], amplitude / std::cos(kAlpha), 1e-9 * ft);
  }
  // h = 1: orders 1 ("h") and 19 ("N-h"); h = 7: orders 7 and 13.
  EXPECT_EQ(h.column("branch").texts[2], "h");
  EXPECT_EQ(h.column("branch").texts[3], "N-h");
  EXPECT_DOUBLE_EQ(h.column("engine_order").numbers[3], 19.0);
  // The windows of all teeth sum to one: the mean tooth load is F_t / N (order 0).
  const Table& spectrum = table(out, "order_spectrum");
  EXPECT_NEAR(spectrum.column("amplitude_n").numbers[0], ft / n_teeth, 1e-9 * ft);
  EXPECT_EQ(spectrum.rows(), 41u);  // orders 0 .. 2 N
  EXPECT_EQ(table(out, "tooth_load").rows(), 20u * 128u);
}

// Half-power Q of a measured single-DOF resonance |H| = 1 / sqrt((1 - r^2)^2 + (2 zeta r)^2),
// f_n = 100 Hz, zeta = 0.01, sampled every 0.02 Hz. Exact values (Ewins, Modal Testing, 2.2):
// peak at r = sqrt(1 - 2 zeta^2), half-power points r^2 = 1 - 2 zeta^2 -+ 2 zeta sqrt(1 - zeta^2),
// Q = r_peak / (r2 - r1). Linear interpolation of the crossings and the parabolic peak leave
// O(h^2 / bandwidth^2) ~ 1e-4 relative with 100 samples in the 2 Hz band: tolerance 1e-3.
TEST(GearanValidation, CorrelationFindsTheMeasuredPeakAndItsHalfPowerQ) {
  const fs::path dir = fresh_dir("correlation");
  const double fn = 100.0, zeta = 0.01;
  std::string csv = "# synthetic single-DOF response\nfrequency_hz, amplitude_um\n";
  for (int i = 0; i <= 5000; ++i) {
    const double f = 50.0 + 0.02 * i, r = f / fn;
    const double a = 1.0 / std::sqrt(std::pow(1.0 - r * r, 2) + std::pow(2.0 * zeta * r, 2));
    csv += fmt::format("{:.10g}, {:.12g}\n", f, a);
  }
  write_file(dir / "measured.csv", csv);
  const model::Model m = load(dir, kHeader + spur_pair() + R"([[analyses]]
name = "c"
type = "correlation"
measured_file = "measured.csv"
reference_peak_hz = 101
reference_amplitude = 1e-4
reference_q = 40
)");
  check_inputs(m, {});
  const AnalysisOutput out = run_entry(m, 0).output;
  const Table& peaks = table(out, "peaks");
  ASSERT_EQ(peaks.rows(), 1u);
  const double r_peak = std::sqrt(1.0 - 2.0 * zeta * zeta);
  const double r1 = std::sqrt(1.0 - 2.0 * zeta * zeta - 2.0 * zeta * std::sqrt(1.0 - zeta * zeta));
  const double r2 = std::sqrt(1.0 - 2.0 * zeta * zeta + 2.0 * zeta * std::sqrt(1.0 - zeta * zeta));
  const double q = r_peak / (r2 - r1);
  const double a_peak = 1e-6 / (2.0 * zeta * std::sqrt(1.0 - zeta * zeta));  // um -> m
  std::printf("peak %.6f Hz (%.6f), Q %.5f (%.5f), amplitude %.6e m (%.6e)\n",
              peaks.column("frequency_hz").numbers[0], fn * r_peak,
              peaks.column("q_factor").numbers[0], q, peaks.column("amplitude").numbers[0], a_peak);
  EXPECT_NEAR(peaks.column("frequency_hz").numbers[0], fn * r_peak, 1e-3);
  EXPECT_NEAR(peaks.column("q_factor").numbers[0], q, 1e-3 * q);
  EXPECT_NEAR(peaks.column("amplitude").numbers[0], a_peak, 1e-4 * a_peak);
  // The comparison with the reference: mismatch = (reference - measured) / measured.
  const Table& c = table(out, "comparison");
  EXPECT_NEAR(c.column("x_mismatch_pct").numbers[0], 100.0 * (101.0 - fn * r_peak) / (fn * r_peak),
              1e-3);
  EXPECT_NEAR(c.column("q_mismatch_pct").numbers[0], 100.0 * (40.0 - q) / q, 0.1);
  EXPECT_NEAR(c.column("amplitude_mismatch_pct").numbers[0], 100.0 * (1e-4 - a_peak) / a_peak, 0.1);
}

}  // namespace
}  // namespace geardyn::analyses
