// The scalar outputs of the gear analyses (gear_pair, mesh_force, mesh_harmonics, correlation):
// each read from the typed result, checked against that result, against the table the analysis
// prints, and against a closed form where one is cheap.
//
// Pair: spur z1 = 20, z2 = 40, m = 3 mm, alpha = 20 deg, b = 20 mm, T1 = 100 N m (as in
// gear_analyses_test.cpp).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "geardyn/analyses/correlation.hpp"
#include "geardyn/analyses/gear_pair.hpp"
#include "geardyn/analyses/mesh_force.hpp"
#include "geardyn/analyses/mesh_harmonics.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/core/units.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using namespace test;
constexpr double kPi = units::kPi;
constexpr double kAlpha = 20.0 * kPi / 180.0;

const std::string kPair = R"(version = 1
[[gear_pairs]]
name = "spur"
teeth1 = 20
teeth2 = 40
module = 0.003
face_width = 0.02
torque = 100
)";

Outcome run_entry(const model::Model& m, std::size_t i) {
  return type_of(m.analyses[i]).run(m, m.analyses[i], Context(m, m.analyses[i]));
}

double scalar(const model::Model& m, const Outcome& o, std::size_t i, const std::string& quantity,
              int mode = 1) {
  ScalarRequest q;
  q.quantity = quantity;
  q.mode = mode;
  std::string unit;
  return type_of(m.analyses[i]).scalar(o, q, unit);
}

std::string unit_of(const model::Model& m, const Outcome& o, std::size_t i,
                    const std::string& quantity, int mode = 1) {
  ScalarRequest q;
  q.quantity = quantity;
  q.mode = mode;
  std::string unit;
  (void)type_of(m.analyses[i]).scalar(o, q, unit);
  return unit;
}

// contact_ratio: for a spur pair eps_gamma = eps_alpha = (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 -
// rb2^2) - a sin(alpha)) / (pi m cos(alpha)) (closed form, rounding only: 1e-12).
// mesh_stiffness: F_s times the time mean of 1 / (e - e_g), e - e_g linear between the samples
// of the printed STE table. The segment mean ln(d1 / d0) / (d1 - d0) loses about eps / |r|,
// r = d1 / d0 - 1, so below |r| = 1e-6 its series 1 - r / 2 + r^2 / 3 (truncation r^3 / 4) is
// used: at most ~2e-10 relative per segment, 1e-9.
// mesh_natural_frequency:
// sqrt(k_mean / m_e) / 2 pi with m_e = J1 J2 / (J1 rb2^2 + J2 rb1^2) (closed form: 1e-12).
TEST(GearScalars, GearPairContactRatioStiffnessAndMeshFrequency) {
  const fs::path dir = fresh_dir("scalars_gear_pair");
  const model::Model m = load(dir, kPair + R"(inertia1 = 0.01
inertia2 = 0.04
[[analyses]]
name = "pair"
type = "gear_pair"
)");
  const Outcome o = run_entry(m, 0);
  const auto& r = result_of<GearPairResult>(o);
  ASSERT_EQ(r.pairs.size(), 1u);
  const PairModel& pm = r.pairs[0];

  const double cr = scalar(m, o, 0, "contact_ratio");
  EXPECT_EQ(cr, pm.geometry.total_contact_ratio);
  const double rb1 = 0.030 * std::cos(kAlpha), rb2 = 0.060 * std::cos(kAlpha);
  const double eps = (std::sqrt(0.033 * 0.033 - rb1 * rb1) + std::sqrt(0.063 * 0.063 - rb2 * rb2) -
                      0.090 * std::sin(kAlpha)) /
                     (kPi * 0.003 * std::cos(kAlpha));
  EXPECT_NEAR(cr, eps, 1e-12 * eps);

  const double k = scalar(m, o, 0, "mesh_stiffness");
  EXPECT_EQ(unit_of(m, o, 0, "mesh_stiffness"), "N/m");
  EXPECT_EQ(k, mean_mesh_stiffness(pm));
  // The time mean of k = F_s / d over the cycle, d = STE - geometric TE linear between the
  // printed samples: mean of 1 / d over a segment = ln(d1 / d0) / (d1 - d0).
  const Table& ste = table(o.output, "mesh_stiffness");
  const auto& e = ste.column("ste_m").numbers;
  const auto& eg = ste.column("geometric_te_m").numbers;
  double sum = 0.0;
  for (std::size_t j = 0; j < e.size(); ++j) {
    const double d0 = e[j] - eg[j], d1 = e[(j + 1) % e.size()] - eg[(j + 1) % e.size()];
    const double x = (d1 - d0) / d0;
    sum += std::abs(x) < 1e-6 ? (1.0 - x / 2.0 + x * x / 3.0) / d0 : std::log(d1 / d0) / (d1 - d0);
  }
  const double k_table = pm.static_force_n * sum / static_cast<double>(e.size());
  EXPECT_NEAR(k, k_table, 1e-9 * k);

  const double fn = scalar(m, o, 0, "mesh_natural_frequency");
  const double me =
      0.01 * 0.04 /
      (0.01 * pm.base_radius2_m * pm.base_radius2_m + 0.04 * pm.base_radius1_m * pm.base_radius1_m);
  EXPECT_NEAR(fn, std::sqrt(k / me) / (2.0 * kPi), 1e-12 * fn);

  EXPECT_THROW(scalar(m, o, 0, "contact_ratio", 2), std::runtime_error);  // one pair only
}

TEST(GearScalars, GearPairWithoutInertiasHasNoMeshFrequency) {
  const fs::path dir = fresh_dir("scalars_gear_pair_no_inertia");
  const model::Model m = load(dir, kPair + R"([[analyses]]
name = "pair"
type = "gear_pair"
)");
  const Outcome o = run_entry(m, 0);
  EXPECT_THROW(scalar(m, o, 0, "mesh_natural_frequency"), std::runtime_error);
}

// Infinite inertias on a step STE held between samples (6 samples of 3.125 um, 4 of 5 um, as in
// gear_analyses_test.cpp): F_d(t) = F_s k(t) / k_mean, so the dynamic factor is k_max / k_mean
// = (1 / 3.125) / ((6 / 3.125 + 4 / 5) / 10) = 3.2 / 2.72 at every speed (rounding: 1e-12) and
// the peak mesh force is F_s times it; both equal the largest entry of the printed sweep table
// exactly. No dynamics: no mesh resonance (NaN). The dynamic model's resonance speed is
// 60 f_n / z1 with f_n the gear_pair analysis's mesh natural frequency (same formula: 1e-12).
TEST(GearScalars, MeshForceDynamicFactorPeakForceAndResonanceSpeed) {
  const fs::path dir = fresh_dir("scalars_mesh_force");
  std::string csv = "angle_deg, ste_um\n";
  for (int j = 0; j < 10; ++j) csv += fmt::format("{}, {}\n", 1.8 * j, j < 6 ? 3.125 : 5.0);
  write_file(dir / "step_ste.csv", csv);
  const model::Model m = load(dir, kPair + R"(inertia1 = 0.01
inertia2 = 0.04
mesh_damping_ratio = 0.05
ste_file = "step_ste.csv"
ste_interpolation = "hold"
[[analyses]]
name = "rigid"
type = "mesh_force"
speed_rpm = [500, 1000, 1500]
model = "infinite_inertia"
[[analyses]]
name = "dynamic"
type = "mesh_force"
speed_rpm = [1000, 2000]
direction = "up"
[[analyses]]
name = "pair"
type = "gear_pair"
)");
  const Outcome o = run_entry(m, 0);
  ASSERT_EQ(o.output.status, Status::Ok) << o.output.message;
  const auto& r = result_of<MeshForceResult>(o);
  const double df = scalar(m, o, 0, "dynamic_factor");
  double table_df = 0.0, table_force = 0.0;
  for (const char* name : {"sweep_up", "sweep_down"}) {
    const Table& t = table(o.output, name);
    for (double x : t.column("dynamic_factor").numbers) table_df = std::max(table_df, x);
    for (double x : t.column("force_max_n").numbers) table_force = std::max(table_force, x);
  }
  EXPECT_EQ(df, table_df);
  EXPECT_NEAR(df, 3.2 / 2.72, 1e-12);
  const double force = scalar(m, o, 0, "peak_mesh_force");
  EXPECT_EQ(unit_of(m, o, 0, "peak_mesh_force"), "N");
  EXPECT_EQ(force, table_force);
  EXPECT_NEAR(force, 3.2 / 2.72 * r.pair.static_force_n, 1e-12 * force);
  EXPECT_TRUE(std::isnan(scalar(m, o, 0, "mesh_resonance_speed")));

  const Outcome d = run_entry(m, 1);
  ASSERT_EQ(d.output.status, Status::Ok) << d.output.message;
  const double rpm = scalar(m, d, 1, "mesh_resonance_speed");
  EXPECT_EQ(unit_of(m, d, 1, "mesh_resonance_speed"), "rpm");
  const Outcome pair = run_entry(m, 2);
  const double fn = scalar(m, pair, 2, "mesh_natural_frequency");
  EXPECT_NEAR(rpm, 60.0 * fn / 20.0, 1e-12 * rpm);
  EXPECT_GT(scalar(m, d, 1, "dynamic_factor"), 1.0);
}

// A constant mesh force (flat STE, infinite inertias): the dynamic factor is 1 (rounding:
// 1e-12). The amplitude of engine order k is the order-spectrum entry of order k exactly, and
// equals the tangential amplitude of the same order in the harmonics table, computed by another
// path (harmonic_components): 1e-9 F_t, as in gear_analyses_test.cpp.
TEST(GearScalars, MeshHarmonicsAmplitudeOfAnOrderAndDynamicFactor) {
  const fs::path dir = fresh_dir("scalars_mesh_harmonics");
  write_file(dir / "flat_ste.csv", "angle_deg, ste_um\n0, 4\n4.5, 4\n9, 4\n13.5, 4\n");
  const model::Model m = load(dir, kPair + R"(ste_file = "flat_ste.csv"
[[analyses]]
name = "h"
type = "mesh_harmonics"
speed_rpm = 1000
model = "infinite_inertia"
contact_ratio = 1.6
nodal_diameters = [0, 1, 7]
)");
  const Outcome o = run_entry(m, 0);
  const auto& r = result_of<MeshHarmonicsResult>(o);
  EXPECT_NEAR(scalar(m, o, 0, "dynamic_factor"), 1.0, 1e-12);
  const Table& spectrum = table(o.output, "order_spectrum");
  const Table& h = table(o.output, "harmonics");
  const double ft = 100.0 / 0.030;
  for (int k : {1, 7, 13, 19}) {
    const double a = scalar(m, o, 0, "harmonic_amplitude", k);
    EXPECT_EQ(a, r.order_amplitude_n[static_cast<std::size_t>(k)]);
    EXPECT_EQ(a, spectrum.column("amplitude_n").numbers[static_cast<std::size_t>(k)]);
    for (std::size_t i = 0; i < h.rows(); ++i) {
      if (h.column("engine_order").numbers[i] == k) {
        EXPECT_NEAR(a, h.column("tangential_n").numbers[i], 1e-9 * ft) << "order " << k;
      }
    }
  }
  EXPECT_EQ(unit_of(m, o, 0, "harmonic_amplitude", 1), "N");
  EXPECT_THROW(scalar(m, o, 0, "harmonic_amplitude", 0), std::runtime_error);
  EXPECT_THROW(scalar(m, o, 0, "harmonic_amplitude", 41), std::runtime_error);  // max_order 2 N
}

// Half-power Q of a measured single-DOF resonance (f_n = 100 Hz, zeta = 0.01, 0.02 Hz steps):
// the exact peak, Q and amplitude (Ewins, Modal Testing, 2.2) to the tolerances of
// gear_analyses_test.cpp (interpolation error ~1e-4 relative); each scalar equals the typed
// result and the printed peak table exactly.
TEST(GearScalars, CorrelationPeakLocationAmplitudeAndQ) {
  const fs::path dir = fresh_dir("scalars_correlation");
  const double fn = 100.0, zeta = 0.01;
  std::string csv = "frequency_hz, amplitude_um\n";
  for (int i = 0; i <= 5000; ++i) {
    const double f = 50.0 + 0.02 * i, r = f / fn;
    const double a = 1.0 / std::sqrt(std::pow(1.0 - r * r, 2) + std::pow(2.0 * zeta * r, 2));
    csv += fmt::format("{:.10g}, {:.12g}\n", f, a);
  }
  write_file(dir / "measured.csv", csv);
  const model::Model m = load(dir, kPair + R"([[analyses]]
name = "c"
type = "correlation"
measured_file = "measured.csv"
)");
  const Outcome o = run_entry(m, 0);
  const auto& r = result_of<CorrelationResult>(o);
  ASSERT_EQ(r.peaks.size(), 1u);
  const Table& peaks = table(o.output, "peaks");
  const double r_peak = std::sqrt(1.0 - 2.0 * zeta * zeta);
  const double r1 = std::sqrt(1.0 - 2.0 * zeta * zeta - 2.0 * zeta * std::sqrt(1.0 - zeta * zeta));
  const double r2 = std::sqrt(1.0 - 2.0 * zeta * zeta + 2.0 * zeta * std::sqrt(1.0 - zeta * zeta));
  const double q = r_peak / (r2 - r1);
  const double a_peak = 1e-6 / (2.0 * zeta * std::sqrt(1.0 - zeta * zeta));

  const double x = scalar(m, o, 0, "measured_peak_location");
  EXPECT_EQ(unit_of(m, o, 0, "measured_peak_location"), "Hz");
  EXPECT_EQ(x, r.peaks[0].x);
  EXPECT_EQ(x, peaks.column("frequency_hz").numbers[0]);
  EXPECT_NEAR(x, fn * r_peak, 1e-3);
  const double qf = scalar(m, o, 0, "measured_peak_q");
  EXPECT_EQ(qf, peaks.column("q_factor").numbers[0]);
  EXPECT_NEAR(qf, q, 1e-3 * q);
  EXPECT_NEAR(peaks.column("damping_ratio").numbers[0], 0.5 / q, 1e-3 * 0.5 / q);
  const double a = scalar(m, o, 0, "measured_peak_amplitude");
  EXPECT_EQ(unit_of(m, o, 0, "measured_peak_amplitude"), "m");
  EXPECT_EQ(a, peaks.column("amplitude").numbers[0]);
  EXPECT_NEAR(a, a_peak, 1e-4 * a_peak);
  EXPECT_THROW(scalar(m, o, 0, "measured_peak_location", 2), std::runtime_error);
}

}  // namespace
}  // namespace geardyn::analyses
