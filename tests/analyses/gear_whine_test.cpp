// The gear_whine analysis (analyses/gear_whine.hpp) on examples/geared_rotor_hcf with a casing
// web (an annular plate) joined at the HPR's front support: the TE per order against the
// analytic harmonics of the STE given, the accelerations against the mesh forced response they
// stand for, the radiated power against an independent expansion of the housing response to its
// surface, and the sweep's delta table.
#include "geardyn/analyses/gear_whine.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "geardyn/acoustics/radiation.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/analyses/sweep.hpp"
#include "geardyn/assembly/solid_coupling.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/reduce/reduced_component.hpp"
#include "support/output_tables.hpp"

namespace geardyn {
namespace {

namespace fs = std::filesystem;
using Complex = std::complex<double>;
using test::table;

constexpr double kSteMean = 20e-6;  // [m]
constexpr double kSteFluctuation = 0.1;
constexpr int kSteRows = 512;

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

const std::string kWeb = R"(
[[solids]]
name = "web"
type = "annular_plate"
material = "steel"
inner_radius = 0.03
outer_radius = 0.12
thickness = 0.004
radial_elements = 3
circumferential_elements = 24
layers = 1
order = 2
coupling_modes = 12
modal_damping_ratio = 0.02
  [[solids.spiders]]
  node_set = "inner"
  node = "support_A"
  kind = "rigid"

[[gear_pairs]]
name = "central"
type = "spiral_bevel"
teeth1 = 40
teeth2 = 36
module = 0.003
face_width = 0.02
helix_angle_deg = 35
hand = "left"
torque = 300
ste_file = "ste.csv"
)";

/// The example model with the web and the pair, and `analyses` appended, parsed in `dir`
/// (where the STE e(theta) = e0 (1 - a cos theta) over a mesh cycle is written).
model::Model whine_model(const fs::path& dir, const std::string& analyses) {
  fs::create_directories(dir);
  std::ofstream ste(dir / "ste.csv");
  ste << "angle_deg, ste_um\n";
  for (int j = 0; j < kSteRows; ++j) {
    const double u = static_cast<double>(j) / kSteRows;
    ste << fmt::format("{:.12g}, {:.12g}\n", 9.0 * u,
                       1e6 * kSteMean * (1.0 - kSteFluctuation * std::cos(units::kTwoPi * u)));
  }
  ste.close();
  const std::string text =
      read_text(fs::path(GEARDYN_SOURCE_DIR) / "examples" / "geared_rotor_hcf" / "model.toml") +
      kWeb + analyses;
  return analyses::parse_model(text, (dir / "model.toml").string());
}

const std::string kWhine = R"(
[[analyses]]
name = "whine"
type = "gear_whine"
pair = "central"
max_mesh_order = 3
speed_start_rpm = 2000
speed_stop_rpm = 30000
speed_count = 57
n_modes = 40
radiating_solid = "web"
radiating_set = "top"
map_speeds_rpm = [9000]
)";

struct WhineRun {
  model::Model model;
  fe::LinearSystem system;
  analyses::GearWhineResult result;
  AnalysisOutput output;
};

const WhineRun& whine_run() {
  static const WhineRun run = [] {
    WhineRun r;
    r.model = whine_model(fs::path(GEARDYN_BINARY_DIR) / "tests" / "whine" / "base", kWhine);
    analyses::check_inputs(r.model, {});
    r.system = assembly::build_system(r.model);
    const model::Analysis& a = r.model.analyses.back();
    const auto& s = a.settings_of<analyses::GearWhineSettings>();
    const analyses::Context context = analyses::Context(r.model, a).with_system(&r.system);
    r.result = analyses::run_gear_whine(r.model, s, context);
    r.output = analyses::gear_whine_output(r.model, s, r.result, context);
    return r;
  }();
  return run;
}

// TE harmonics of e0 (1 - a cos theta): e_1 = a e0 = 2 um (0-peak), 4 um peak-to-peak, the
// higher orders zero; the curve's peak-to-peak 2 a e0 = 4 um (sampled at 512 points: the extreme
// samples lie on the cosine's extremes, exact).
TEST(GearWhine, TransmissionErrorPerOrderInBothConventions) {
  const WhineRun& r = whine_run();
  ASSERT_EQ(r.output.status, Status::Ok) << r.output.message;
  const Table& te = table(r.output, "te_orders");
  EXPECT_NEAR(te.column("te_0peak_um").numbers[0], 2.0, 1e-9);
  EXPECT_NEAR(te.column("te_peak_peak_um").numbers[0], 4.0, 1e-9);
  EXPECT_NEAR(te.column("te_0peak_um").numbers[1], 0.0, 1e-9);
  EXPECT_NEAR(te.column("te_0peak_um").numbers[2], 0.0, 1e-9);
  EXPECT_NEAR(r.result.te_peak_to_peak_m, 2.0 * kSteFluctuation * kSteMean, 1e-15);
}

// a = -w^2 u with w = p z1 |r1| W for every order, speed and sensor (the same solve).
TEST(GearWhine, AccelerationIsMinusOmegaSquaredTimesDisplacement) {
  const WhineRun& r = whine_run();
  const response::RotorForcedResult& f = r.result.response;
  ASSERT_FALSE(f.sensors.empty());
  for (std::size_t h = 0; h < f.harmonics.size(); ++h)
    for (Eigen::Index i = 0; i < f.speeds.size(); ++i) {
      const double w = f.harmonics[h].order * f.mesh_frequency_per_speed * f.speeds[i];
      for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(f.sensors.size()); ++k) {
        const Complex expected = -w * w * f.displacement[h](i, k);
        EXPECT_LE(std::abs(r.result.acceleration[h](i, k) - expected),
                  1e-12 * std::abs(expected) + 1e-300);
      }
    }
  // The table's sum column is the sum of the orders' amplitudes.
  const Table& t = table(r.output, "whine_acceleration");
  const std::string name = f.sensors[0].name;
  const std::string unit = f.sensors[0].rotational ? "rad_s2" : "m_s2";
  const auto& sum = t.column(name + "_sum_" + unit).numbers;
  for (std::size_t i = 0; i < sum.size(); ++i) {
    double s = 0;
    for (int p = 1; p <= 3; ++p)
      s += t.column(fmt::format("{}_p{}_acceleration_{}", name, p, unit)).numbers[i];
    EXPECT_NEAR(sum[i], s, 1e-12 * s);
  }
}

// The ERP per speed and order against an independent route: the housing's body coordinates
// q_b = B u, the Craig-Bampton expansion z = T q_b of reduce::expand, the solid's recovery of
// every node, the normal velocity i w n . u per surface node and acoustics::erp (the
// quadratic form of the analysis is algebraically the same sum: round-off, 1e-9).
TEST(GearWhine, RadiatedPowerEqualsExplicitExpansionToTheSurface) {
  const WhineRun& r = whine_run();
  ASSERT_TRUE(r.result.has_radiation);
  const analyses::WhineRadiation& w = r.result.radiation;
  const model::Solid& spec = r.model.solids.front();
  const assembly::SolidComponent built = assembly::build_solid(r.model, spec);
  const assembly::CoupledSolid coupled = assembly::couple_solid(r.model, spec, built);
  const Eigen::SparseMatrix<double> B = fe::body_coordinates(r.system, coupled.body);
  const response::RotorForcedResult& f = r.result.response;
  const acoustics::Air air;
  for (Eigen::Index i : {Eigen::Index{5}, Eigen::Index{30}}) {
    for (std::size_t h = 0; h < f.harmonics.size(); ++h) {
      const double omega = f.harmonics[h].order * f.mesh_frequency_per_speed * f.speeds[i];
      const Eigen::VectorXcd u = f.full_response(h, i);
      const Eigen::VectorXcd qb = B.cast<Complex>() * u;
      const Eigen::MatrixXd z_re = reduce::expand(coupled.reduced, qb.real());
      const Eigen::MatrixXd z_im = reduce::expand(coupled.reduced, qb.imag());
      const Eigen::SparseMatrix<double>& rec = coupled.solid_dofs.recovery;
      const Eigen::VectorXd x_re = z_re.col(0).head(rec.cols()),
                            x_im = z_im.col(0).head(rec.cols());
      const Eigen::VectorXd all_re = rec * x_re, all_im = rec * x_im;
      Eigen::VectorXcd vn(static_cast<Eigen::Index>(w.surface.nodes.size()));
      for (std::size_t k = 0; k < w.surface.nodes.size(); ++k) {
        Eigen::Vector3cd d;
        for (int c = 0; c < 3; ++c) {
          const int a = coupled.solid_dofs.all_dof(w.surface.nodes[k], c);
          d[c] = Complex(all_re[a], all_im[a]);
        }
        vn[static_cast<Eigen::Index>(k)] =
            Complex(0.0, omega) *
            w.surface.node_normal.col(static_cast<Eigen::Index>(k)).cast<Complex>().dot(d);
      }
      const double expected = acoustics::erp(w.surface, vn, air);
      EXPECT_NEAR(w.erp_w(i, static_cast<Eigen::Index>(h)), expected, 1e-9 * expected)
          << "speed " << i << " order " << f.harmonics[h].order;
    }
  }
  // The plate's top face: pi (a^2 - b^2) within the polygon error of 24 curved sectors
  // (quadratic faces: the arc is interpolated, error ~ (pi/24)^4 / ...; 1e-4).
  const double area = units::kPi * (0.12 * 0.12 - 0.03 * 0.03);
  EXPECT_NEAR(w.area_m2, area, 1e-4 * area);
  // Orders add in power; levels re 1e-12 W.
  for (Eigen::Index i = 0; i < w.erp_total_w.size(); ++i) {
    EXPECT_NEAR(w.erp_total_w[i], w.erp_w.row(i).sum(), 1e-12 * w.erp_total_w[i]);
    EXPECT_NEAR(r.result.sound_power_level_db()[i], 10.0 * std::log10(w.erp_total_w[i] / 1e-12),
                1e-9);
  }
  // The per-face map at 9000 rpm sums to the total ERP there.
  ASSERT_EQ(w.face_erp_w.size(), 1U);
  Eigen::Index at = 0;
  (f.speeds.array() - 9000.0 * units::kRadPerSecondPerRpm).abs().minCoeff(&at);
  EXPECT_NEAR(w.face_erp_w[0].sum(), w.erp_total_w[at], 1e-9 * w.erp_total_w[at]);
  EXPECT_FALSE(r.output.files.empty());
}

// A sweep over the radiation efficiency sigma with reference_value = 1: ERP scales with sigma,
// so the sound power level moves by exactly 10 lg sigma (-6.02 and -3.01 dB), the delta table's
// values (round-off of the logarithms, 1e-9 dB).
TEST(GearWhine, SweepDeltaTableAgainstTheReferenceVariant) {
  const fs::path dir = fs::path(GEARDYN_BINARY_DIR) / "tests" / "whine" / "sweep";
  (void)whine_model(dir, "");  // writes the STE file
  const std::string text =
      read_text(fs::path(GEARDYN_SOURCE_DIR) / "examples" / "geared_rotor_hcf" / "model.toml") +
      kWeb + kWhine + R"(
[[analyses]]
name = "sigma_sweep"
type = "sweep"
parameter = "analyses[11].radiation_efficiency"
values = [0.25, 0.5, 1.0]
reference_value = 1.0
analysis = "whine"
threads = 1
  [[analyses.outputs]]
  quantity = "sound_power_level_at"
  at_rpm = 9000
)";
  const auto doc = analyses::parse_document(text, (dir / "model.toml").string());
  const model::Model m = model::build_model(doc);
  ASSERT_EQ(m.analyses[11].name, "whine");
  const auto& settings = m.analyses[12].settings_of<analyses::SweepSettings>();
  const analyses::SweepResult r = analyses::run_sweep(doc, settings, null_progress());
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_EQ(r.units[0], "dB");
  const Table t = analyses::delta_table(r, settings);
  const auto& delta = t.column("sound_power_level_at_delta_dB").numbers;
  EXPECT_NEAR(delta[0], 10.0 * std::log10(0.25), 1e-9);
  EXPECT_NEAR(delta[1], 10.0 * std::log10(0.5), 1e-9);
  EXPECT_NEAR(delta[2], 0.0, 1e-12);
}

}  // namespace
}  // namespace geardyn
