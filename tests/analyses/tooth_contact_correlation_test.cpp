// A test rig's TE at the mesh orders (measured_te_file) against the tooth contact analysis: the
// reader (conventions, units, located errors), the point-by-point comparison (a known factor is
// recovered, linear interpolation over torque), and the analysis' table, plot, note and scalars.
//
// References are closed forms: the peak-to-peak value of a sine A sin(k 2 pi u) is 2 A (a
// harmonic's 0-peak amplitude is A, as the DFT bin of gear::mesh_order_amplitudes gives it,
// docs/theory.md §15.3); a pinion angle theta and the TE along the line of action are tied by
// the base radius, e = r_b1 theta, r_b1 = m z1 cos(alpha) / 2 for a spur pair (ISO 21771,
// "Gears - Cylindrical involute gears and gear pairs - Concepts and geometry", 2007).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/analyses/tooth_contact.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/gear/te_rig_csv.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using namespace test;

// A spur pair 20/40, m = 3 mm, alpha = 20 deg, with tip relief (so that the TE harmonics vary
// with the load), and a tooth_contact analysis at `torques`.
std::string spur(const std::string& torques, const std::string& extra = {}) {
  return spur_pair_20_40("100", R"(
[gear_pairs.flank1]
tip_relief = 8e-6
tip_relief_start_diameter = 0.0625

[[analyses]]
name = "ltca"
type = "tooth_contact"
orders = 3
torques = )" + torques + "\n" + extra);
}

Outcome run_entry(const model::Model& m) {
  return type_of(m.analyses[0]).run(m, m.analyses[0], Context(m, m.analyses[0]));
}

const ToothContactRunResult& result(const Outcome& o) {
  return *static_cast<const ToothContactRunResult*>(o.result.get());
}

double scalar(const model::Model& m, const Outcome& o, const std::string& quantity) {
  ScalarRequest q;
  q.quantity = quantity;
  std::string unit;
  return type_of(m.analyses[0]).scalar(o, q, unit);
}

// The InputError of parsing `csv`, or a failure when it parses.
InputError parse_error(const std::string& csv) {
  try {
    (void)gear::parse_te_rig_csv(csv, "rig.csv");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for\n" << csv;
  return InputError({}, "", "", "");
}

// A file written from the computed harmonics times a known factor gives that factor at every
// point: ratio 1.25 and 20 log10 1.25 dB (1e-12: the file holds 17 digits), the mean ratio and
// the least-squares gain 1.25 with no offset (1e-15 m of micrometre amplitudes), the same in the
// scalars offered to sweeps.
TEST(TeCorrelation, AFileWrittenWithAKnownFactorGivesThatFactor) {
  const fs::path dir = fresh_dir("te_correlation_factor");
  const model::Model plain = load(dir, spur("[60, 120, 180]"));
  const Outcome computed = run_entry(plain);
  ASSERT_EQ(computed.output.status, Status::Ok) << computed.output.message;
  const ToothContactRunResult& c = result(computed);
  std::string csv =
      "# written from the computed harmonics x 1.25\ntorque_nm,mesh_order,"
      "amplitude_0_peak_um\n";
  for (std::size_t i = 0; i < c.torques.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k)
      csv += fmt::format("{}, {}, {:.17g}\n", c.torques[i].torque_nm, k + 1,
                         1.25 * c.harmonics_m[i][k] * 1e6);
  write_file(dir / "rig.csv", csv);
  const model::Model m = load(dir, spur("[60, 120, 180]", "measured_te_file = \"rig.csv\"\n"));
  check_inputs(m, {});
  const Outcome o = run_entry(m);
  ASSERT_EQ(o.output.status, Status::Ok) << o.output.message;
  const Table& t = table(o.output, "te_correlation");
  ASSERT_EQ(t.rows(), 9u);
  for (std::size_t i = 0; i < t.rows(); ++i) {
    EXPECT_NEAR(t.column("ratio_measured_to_computed").numbers[i], 1.25, 1e-12) << i;
    EXPECT_NEAR(t.column("difference_db").numbers[i], 20.0 * std::log10(1.25), 1e-10) << i;
    EXPECT_EQ(t.column("compared").numbers[i], 1.0);
    EXPECT_EQ(t.column("match").texts[i], "computed torque");
  }
  const gear::TeComparison& tc = *result(o).te_correlation;
  EXPECT_EQ(tc.compared, 9u);
  EXPECT_NEAR(tc.mean_ratio, 1.25, 1e-12);
  EXPECT_NEAR(tc.fit_gain, 1.25, 1e-9);
  EXPECT_NEAR(tc.fit_offset_m, 0.0, 1e-15);
  EXPECT_NEAR(scalar(m, o, "te_correlation_mean_ratio"), 1.25, 1e-12);
  EXPECT_NEAR(scalar(m, o, "te_correlation_max_difference"), 20.0 * std::log10(1.25), 1e-10);
  EXPECT_THROW((void)scalar(plain, computed, "te_correlation_max_difference"), std::runtime_error);
  // The measured points on the TE-versus-torque plot, one marker trace per order, in urad.
  const double rb1 = c.model->contact->force_radius();
  bool found = false;
  for (const Plot& p : o.output.plots)
    for (const Trace& tr : p.traces)
      if (p.name == "te_vs_torque" && tr.name == "order 2 measured (0-peak)") {
        found = true;
        ASSERT_EQ(tr.x.size(), 3u);
        EXPECT_EQ(tr.mode, Trace::Mode::Markers);
        EXPECT_NEAR(tr.y[1], 1.25 * c.harmonics_m[1][1] / rb1 * 1e6, 1e-9);
      }
  EXPECT_TRUE(found);
  bool noted = false;
  for (const std::string& n : o.output.notes)
    noted = noted || n.find("Mean ratio measured / computed 1.25") != std::string::npos;
  EXPECT_TRUE(noted);
}

// Between two computed torques the computed amplitude is interpolated linearly in torque: exact
// (1e-15 relative) for harmonics that are linear in torque; outside the computed torques and
// above the computed orders a point is kept but not compared, and the summary is over the
// compared points only.
TEST(TeCorrelation, InterpolationOverTorqueIsExactForALinearFunction) {
  const std::vector<double> torques{100.0, 200.0, 400.0};
  auto linear = [](double t, int k) { return (0.2 + 0.003 * t) * 1e-6 / k; };
  std::vector<std::vector<double>> h;
  for (double t : torques) h.push_back({linear(t, 1), linear(t, 2)});
  gear::TeRigFile rig;
  rig.source = "rig.csv";
  rig.amplitude_column = "amplitude_0_peak_m";
  for (const auto& [t, k] : std::vector<std::pair<double, int>>{
           {150.0, 1}, {330.0, 2}, {200.0, 2}, {50.0, 1}, {450.0, 1}, {200.0, 3}})
    rig.points.push_back({t, k, 2.0 * linear(t, k), 0});
  const gear::TeComparison c = gear::compare_te(rig, torques, h, 0.05);
  ASSERT_EQ(c.rows.size(), 6u);
  EXPECT_EQ(c.rows[0].match, gear::TeMatch::Interpolated);
  EXPECT_NEAR(c.rows[0].computed_m, linear(150.0, 1), 1e-15 * linear(150.0, 1));
  EXPECT_EQ(c.rows[1].match, gear::TeMatch::Interpolated);
  EXPECT_NEAR(c.rows[1].computed_m, linear(330.0, 2), 1e-15 * linear(330.0, 2));
  EXPECT_EQ(c.rows[2].match, gear::TeMatch::Computed);
  EXPECT_EQ(c.rows[3].match, gear::TeMatch::OutsideTorques);
  EXPECT_EQ(c.rows[4].match, gear::TeMatch::OutsideTorques);
  EXPECT_EQ(c.rows[5].match, gear::TeMatch::AboveOrders);
  for (std::size_t i = 3; i < 6; ++i) {
    EXPECT_FALSE(c.rows[i].compared());
    EXPECT_TRUE(std::isnan(c.rows[i].ratio));
  }
  EXPECT_EQ(c.compared, 3u);
  EXPECT_NEAR(c.mean_ratio, 2.0, 1e-14);
  EXPECT_NEAR(c.max_abs_db, 20.0 * std::log10(2.0), 1e-12);
  EXPECT_NEAR(c.fit_gain, 2.0, 1e-9);
  // A single computed torque: only that torque compares.
  EXPECT_NEAR(
      gear::interpolate_in_range(std::vector<double>{100.0}, std::vector<double>{3.0}, 100.0), 3.0,
      0.0);
  EXPECT_TRUE(std::isnan(
      gear::interpolate_in_range(std::vector<double>{100.0}, std::vector<double>{3.0}, 101.0)));
}

// Through the analysis: a rig torque between two computed ones reads the linear interpolation of
// the te_harmonics rows at the neighbouring torques (1e-15 relative: the same arithmetic), and
// a rig file with no comparable point is refused before the run at measured_te_file.
TEST(TeCorrelation, TheAnalysisInterpolatesBetweenItsTorques) {
  const fs::path dir = fresh_dir("te_correlation_between");
  write_file(dir / "rig.csv", "torque_nm,mesh_order,amplitude_0_peak_um\n90, 1, 0.5\n");
  const model::Model m = load(dir, spur("[60, 120]", "measured_te_file = \"rig.csv\"\n"));
  check_inputs(m, {});
  const Outcome o = run_entry(m);
  ASSERT_EQ(o.output.status, Status::Ok) << o.output.message;
  const ToothContactRunResult& r = result(o);
  const Table& t = table(o.output, "te_correlation");
  const double expect = 0.5 * (r.harmonics_m[0][0] + r.harmonics_m[1][0]);
  EXPECT_NEAR(t.column("computed_0_peak_m").numbers[0], expect, 1e-15 * expect);
  EXPECT_EQ(t.column("match").texts[0], "interpolated over torque");
  EXPECT_NEAR(t.column("ratio_measured_to_computed").numbers[0], 0.5e-6 / expect, 1e-12);

  write_file(dir / "far.csv", "torque_nm,mesh_order,amplitude_0_peak_um\n500, 1, 0.5\n60, 4, 1\n");
  const model::Model far = load(dir, spur("[60, 120]", "measured_te_file = \"far.csv\"\n"));
  try {
    check_inputs(far, {});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "analyses[0].measured_te_file") << e.what();
    EXPECT_GT(e.where().line, 0);
    EXPECT_NE(e.found().find("none of the 2 points"), std::string::npos) << e.what();
  }
  const model::Model missing = load(dir, spur("[60, 120]", "measured_te_file = \"no.csv\"\n"));
  try {
    check_inputs(missing, {});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "analyses[0].measured_te_file") << e.what();
    EXPECT_NE(e.found().find("does not exist"), std::string::npos) << e.what();
  }
}

// Conventions against the computed harmonics: a sampled sine A sin(2 pi k u + phi) has the
// 0-peak amplitude A at order k (gear::mesh_order_amplitudes, the te_harmonics convention;
// 1e-15 relative: the DFT of an exactly periodic sample) and peak-to-peak 2A (exact where the
// samples hit the crests); a file of peak-peak amplitudes 2 x computed and one of angles
// computed / r_b1 in urad both give ratio 1 at every point (1e-12), with r_b1 = m z1 cos(alpha)
// / 2 of the spur pair.
TEST(TeCorrelation, ConventionsPeakPeakAndAngleAgreeWithTheComputedHarmonics) {
  const int n = 64, k = 2;
  const double a = 0.7e-6;
  std::vector<double> sine;
  for (int i = 0; i < n; ++i) sine.push_back(a * std::sin(2.0 * units::kPi * k * i / n + 0.25));
  EXPECT_NEAR(gear::mesh_order_amplitudes(sine, 1, 3)[k - 1], a, 1e-15 * a * n);
  std::vector<double> crest;  // samples on the crests: peak-to-peak exactly 2A
  for (int i = 0; i < n; ++i) crest.push_back(a * std::sin(2.0 * units::kPi * k * (i + 4) / n));
  const auto [lo, hi] = std::minmax_element(crest.begin(), crest.end());
  EXPECT_NEAR(*hi - *lo, 2.0 * a, 1e-15 * a * n);
  gear::TeRigFile pp = gear::parse_te_rig_csv(
      fmt::format("torque_nm,mesh_order,amplitude_peak_peak_um\n100,{},{:.17g}\n", k,
                  (*hi - *lo) * 1e6),
      "pp.csv");
  EXPECT_NEAR(pp.zero_peak_m(0, 0.03), a, 1e-15 * a * n);

  const fs::path dir = fresh_dir("te_correlation_conventions");
  const model::Model plain = load(dir, spur("[80, 160]"));
  const Outcome computed = run_entry(plain);
  ASSERT_EQ(computed.output.status, Status::Ok) << computed.output.message;
  const ToothContactRunResult& c = result(computed);
  const double rb1 = 0.5 * 0.003 * 20 * std::cos(20.0 * units::kPi / 180.0);
  EXPECT_NEAR(c.model->contact->force_radius(), rb1, 1e-12 * rb1);
  std::string peak_peak = "torque_nm,mesh_order,amplitude_peak_peak_nm\n";
  std::string angle = "TORQUE_NM,Mesh_Order,amplitude_0_peak_urad\n";
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      const double h = c.harmonics_m[i][j];
      peak_peak += fmt::format("{},{},{:.17g}\n", c.torques[i].torque_nm, j + 1, 2.0 * h * 1e9);
      angle += fmt::format("{},{},{:.17g}\n", c.torques[i].torque_nm, j + 1, h / rb1 * 1e6);
    }
  write_file(dir / "pp.csv", peak_peak);
  write_file(dir / "angle.csv", angle);
  for (const char* file : {"pp.csv", "angle.csv"}) {
    const model::Model m =
        load(dir, spur("[80, 160]", fmt::format("measured_te_file = \"{}\"\n", file)));
    const Outcome o = run_entry(m);
    ASSERT_EQ(o.output.status, Status::Ok) << o.output.message;
    const Table& t = table(o.output, "te_correlation");
    ASSERT_EQ(t.rows(), 6u);
    for (std::size_t i = 0; i < t.rows(); ++i)
      EXPECT_NEAR(t.column("ratio_measured_to_computed").numbers[i], 1.0, 1e-12) << file << i;
  }
}

// Bad files: each refused at its line and column, naming the column, what was expected and what
// was found.
TEST(TeCorrelation, BadFilesAreRefusedAtTheirLineAndColumn) {
  const std::string head = "# rig\ntorque_nm,mesh_order,amplitude_0_peak_um\n";
  struct Case {
    std::string csv;
    int line, column;
    std::string key, found;
  };
  const std::vector<Case> cases{
      {"torque_nm,amplitude_0_peak_um\n100,1\n", 1, 1, "header", "none"},
      {"torque_nm,mesh_order\n100,1\n", 1, 1, "header", "none"},
      {"torque_nm,mesh_order,amplitude_um\n100,1,2\n", 1, 22, "amplitude_um", "'amplitude_um'"},
      {"torque_nm,mesh_order,amplitude_0_peak_um,amplitude_peak_peak_um\n100,1,2,4\n", 1, 42,
       "amplitude_peak_peak_um", "a second one (after 'amplitude_0_peak_um')"},
      {head + "100,1,0.5\n100,x,0.5\n", 4, 5, "", "x"},
      {head + "100,1,-0.5\n", 3, 7, "amplitude_0_peak_um", "-0.5"},
      {head + "100,1,0\n", 3, 7, "amplitude_0_peak_um", "0"},
      {head + "100,1,0.5\n200,1,0.5\n100, 1, 0.6\n", 5, 1, "torque_nm",
       "100 N m, order 1: a repeat of line 3"},
      {head + "100,1.5,0.5\n", 3, 5, "mesh_order", "1.5"},
      {head + "100,0,0.5\n", 3, 5, "mesh_order", "0"},
      {head + "-100,1,0.5\n", 3, 1, "torque_nm", "-100"},
  };
  for (const Case& c : cases) {
    const InputError e = parse_error(c.csv);
    EXPECT_EQ(e.where().file, "rig.csv") << c.csv;
    EXPECT_EQ(e.where().line, c.line) << c.csv << e.what();
    EXPECT_EQ(e.where().column, c.column) << c.csv << e.what();
    if (!c.key.empty()) {
      EXPECT_EQ(e.key_path(), c.key) << e.what();
    }
    EXPECT_NE(e.found().find(c.found), std::string::npos) << c.csv << e.what();
    EXPECT_FALSE(e.expected().empty());
  }
}

}  // namespace
}  // namespace geardyn::analyses
