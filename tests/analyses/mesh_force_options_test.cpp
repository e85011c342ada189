// The mesh_force keys damping_on, force_amplitude_n, force_order and force_phase_deg through a
// model file (docs/theory.md §13): the closed-form response to the external force end to end,
// the damping model named in the notes, and bad values reported at their keys.
//
//   one-DOF mesh along the line of action, constant stiffness k (flat STE):
//        F_s + F_a cos(r 2 pi f_m t + phi) ---> [ m_e ] ---/\/\/ k ---|  (the other flank)
//                                                       ----[ c ]----|
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "geardyn/analyses/mesh_force.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using namespace test;
constexpr double kPi = std::numbers::pi;
constexpr double kAlpha = 20.0 * kPi / 180.0;

Outcome run_entry(const model::Model& m, std::size_t i) {
  return type_of(m.analyses[i]).run(m, m.analyses[i], Context(m, m.analyses[i]));
}

bool has_note(const AnalysisOutput& out, const std::string& text) {
  for (const auto& n : out.notes)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

// A pair with F_s = 1000 N (torque = 1000 N x r_b1), m_e = 1 kg (inertia1 = r_b1^2, inertia2 =
// inf) and a flat elastic part of the STE, 4 um: k = F_s / 4 um = 2.5e8 N/m,
// f_n = sqrt(k / m_e) / 2 pi. With `with_te` an unloaded TE e_g = 0.5 um cos(2 pi u) on `rows`
// rows per mesh cycle (18 deg of gear 1); `interpolation` is the pair's ste_interpolation.
std::string pair_model(const fs::path& dir, const std::string& interpolation, bool with_te,
                       int rows = 8, double zeta = 0.04) {
  std::string csv = with_te ? "angle_deg, ste_um, geometric_te_um\n" : "angle_deg, ste_um\n";
  for (int j = 0; j < rows; ++j) {
    const double g = with_te ? 0.5 * std::cos(2.0 * kPi * j / rows) : 0.0;
    const double angle = 18.0 * j / rows;
    csv += with_te ? fmt::format("{:.17g}, {:.17g}, {:.17g}\n", angle, 4.0 + g, g)
                   : fmt::format("{:.17g}, 4\n", angle);
  }
  write_file(dir / "flat_ste.csv", csv);
  const double rb1 = 0.030 * std::cos(kAlpha);
  return fmt::format(R"(version = 1
[[gear_pairs]]
name = "flat"
teeth1 = 20
teeth2 = 40
module = 0.003
face_width = 0.02
torque = {:.17g}
inertia1 = {:.17g}
inertia2 = inf
ste_file = "flat_ste.csv"
ste_interpolation = "{}"
mesh_damping_ratio = {}
)",
                     1000.0 * rb1, rb1 * rb1, interpolation, zeta);
}

// The external force alone on a constant stiffness: the DTE fluctuation is the harmonic
// X = F_a / (k - m W^2 + i c W), W = r 2 pi f_m, so its RMS is |X| / sqrt(2) and the dynamic
// force F_d = k x + c x' = F_s + Re((k + i c W) X e^{i(W t + phi)}) peaks at F_s + |k + i c W| |X|
// (Den Hartog, "Mechanical Vibrations", 1956, ch. 2). Both to 1e-7 relative: the solver is exact
// for this input (closed-form particular solution), the RMS is a 4-point Gauss quadrature of a
// sinusoid over >= 128 pieces per period (error ~1e-12) and the steady state is converged to
// 1e-9 of the static deflection (4 um, about 10 |X| here).
TEST(MeshForceOptions, ExternalForceGivesTheClosedFormResponse) {
  const fs::path dir = fresh_dir("mesh_force_external_force");
  const double k = 2.5e8, m = 1.0, fa = 100.0, zeta = 0.04;
  const double c = 2.0 * zeta * std::sqrt(k * m);
  const double fn = std::sqrt(k / m) / (2.0 * kPi);
  const double rpm = 60.0 * 0.45 * fn / 20.0;  // f_m = 0.45 f_n, the force at 0.9 f_n
  for (const char* damping : {"dte", "elastic_deflection"}) {
    const model::Model model =
        load(dir, pair_model(dir, "hold", false) + fmt::format(R"(
[[analyses]]
name = "forced"
type = "mesh_force"
speed_rpm = [{:.17g}]
direction = "up"
damping_on = "{}"
force_amplitude_n = {}
force_order = 2
force_phase_deg = 40
)",
                                                               rpm, damping, fa));
    check_inputs(model, {});
    const AnalysisOutput out = run_entry(model, 0).output;
    ASSERT_EQ(out.status, Status::Ok) << out.message;
    const Table& t = table(out, "sweep_up");
    const double w = 2.0 * 2.0 * kPi * 0.45 * fn;
    const double x = fa / std::hypot(k - m * w * w, c * w);
    EXPECT_NEAR(t.column("dte_rms_m").numbers[0], x / std::sqrt(2.0), 1e-7 * x) << damping;
    const double peak = 1000.0 + std::hypot(k, c * w) * x;
    EXPECT_NEAR(t.column("force_max_n").numbers[0], peak, 1e-7 * peak) << damping;
    EXPECT_TRUE(has_note(out, "External harmonic force")) << damping;
    EXPECT_TRUE(has_note(out, std::string(damping) == "dte"
                                  ? "damping_on = \"dte\""
                                  : "damping_on = \"elastic_deflection\""))
        << damping;
  }
}

// With a varying unloaded TE e_g = e_hat cos(2 pi u) the two damping options differ by the
// damper force c e_g' (k constant: e - e_g = 4 um): the linear steady state is
// X / e_hat = (k + s i c w) / (k - m w^2 + i c w) for s = 0 (dte) and 1 (elastic deflection)
// (Kahraman & Singh, "Non-linear dynamics of a spur gear pair", 1990, the linear limit), so the
// RMS of the DTE differs by the factor |k + i c w| / k = sqrt(1 + (2 zeta w / w_n)^2) = 1.5620
// at w = 3 w_n, zeta = 0.2. Checked to 1e-3: the 64-row STE is linearly interpolated and its
// first harmonic, sinc^2(1 / 64), cancels in the ratio; the dte option takes e_g's mean over
// each of the 128 intervals, a further factor sinc(1 / 128) = 1 - 1e-4; the aliased harmonics
// 63 and 65 carry a relative weight (1 / 64)^2 = 2.4e-4 at most.
TEST(MeshForceOptions, ElasticDeflectionDampingAddsTheDamperForceOfTheUnloadedTe) {
  const fs::path dir = fresh_dir("mesh_force_elastic_damping");
  const double k = 2.5e8, zeta = 0.2;
  const double fn = std::sqrt(k) / (2.0 * kPi);
  const double rpm = 60.0 * 3.0 * fn / 20.0;
  double rms[2] = {0.0, 0.0};
  int q = 0;
  for (const char* damping : {"dte", "elastic_deflection"}) {
    const model::Model model =
        load(dir, pair_model(dir, "linear", true, 64, zeta) + fmt::format(R"(
[[analyses]]
name = "te"
type = "mesh_force"
speed_rpm = [{:.17g}]
direction = "up"
contact_loss = false
damping_on = "{}"
)",
                                                                          rpm, damping));
    const AnalysisOutput out = run_entry(model, 0).output;
    ASSERT_EQ(out.status, Status::Ok) << out.message;
    rms[q++] = table(out, "sweep_up").column("dte_rms_m").numbers[0];
  }
  const double expected = std::sqrt(1.0 + 36.0 * zeta * zeta);
  std::printf(
      "DTE RMS at 3 f_n: dte %.6e m, elastic deflection %.6e m, ratio %.6f (closed form "
      "%.6f)\n",
      rms[0], rms[1], rms[1] / rms[0], expected);
  EXPECT_NEAR(rms[1] / rms[0], expected, 1e-3 * expected);
}

struct BadCase {
  std::string analysis_keys;  // under [[analyses]] name = "bad", type = "mesh_force"
  std::string interpolation;
  bool with_te;
  std::string key;       // InputError::key_path() ends with this
  std::string expected;  // part of InputError::expected()
};

TEST(MeshForceOptions, BadValuesAreInputErrorsAtTheirKeys) {
  const fs::path dir = fresh_dir("mesh_force_bad_options");
  const std::vector<BadCase> cases = {
      {"damping_on = \"teeth\"", "hold", false, "damping_on", "\"dte\""},
      {"force_amplitude_n = -5", "hold", false, "force_amplitude_n", ">= 0"},
      {"force_order = 1.5", "hold", false, "force_order", "an integer"},
      {"force_order = 0", "hold", false, "force_order", "an integer"},
      {"force_amplitude_n = 10\nmodel = \"infinite_inertia\"", "hold", false, "force_amplitude_n",
       "infinite_inertia"},
      {"damping_on = \"elastic_deflection\"", "hold", true, "damping_on", "continuous"},
  };
  for (const BadCase& bad : cases) {
    std::optional<InputError> error;
    try {
      const model::Model model = load(dir, pair_model(dir, bad.interpolation, bad.with_te) + R"(
[[analyses]]
name = "bad"
type = "mesh_force"
speed_rpm = [1000]
)" + bad.analysis_keys + "\n");
      check_inputs(model, {});
      run_entry(model, 0);
    } catch (const InputError& e) {
      error = e;
    }
    ASSERT_TRUE(error.has_value()) << bad.analysis_keys;
    EXPECT_NE(error->key_path().find(bad.key), std::string::npos)
        << bad.analysis_keys << ": " << error->what();
    EXPECT_NE(error->expected().find(bad.expected), std::string::npos)
        << bad.analysis_keys << ": " << error->what();
    std::printf("%s\n  -> %s\n", bad.analysis_keys.c_str(), error->what());
  }
}

}  // namespace
}  // namespace geardyn::analyses
