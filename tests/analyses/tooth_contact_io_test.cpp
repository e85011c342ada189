// Files in and maps out of the loaded tooth contact analysis: an LTCA table exported by another
// tool (ltca_file) feeding the dynamics like the pair's own LTCA (ste_source = "tooth_contact"),
// a topography map (topography_file) against the lead crowning it encodes, and the flank maps of
// the report (line load and contact pressure over face width x roll angle).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/analyses/tooth_contact.hpp"
#include "geardyn/core/error.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using namespace test;

std::string spur(const std::string& torque, const std::string& extra = {}) {
  return spur_pair_20_40(torque, "inertia1 = 0.002\ninertia2 = 0.03\n" + extra);
}

const std::string kTipRelief = R"(
[gear_pairs.flank1]
tip_relief = 8e-6
tip_relief_start_diameter = 0.0625
)";

const std::string kDynamics = R"(
[[analyses]]
name = "force"
type = "mesh_force"
speed_rpm = [1000, 3000, 4500]
)";

const std::string kAnalysis = R"(
[[analyses]]
name = "ltca"
type = "tooth_contact"
)";

Outcome run_entry(const model::Model& m, std::size_t i = 0) {
  return type_of(m.analyses[i]).run(m, m.analyses[i], Context(m, m.analyses[i]));
}

const ToothContactRunResult& result(const Outcome& o) {
  return *static_cast<const ToothContactRunResult*>(o.result.get());
}

// geardyn's own LTCA of `m`'s pair exported as an LTCA table (as another tool would write it):
// the first mesh cycle at each torque, TE and secant stiffness F / (e - e_g), 17 digits.
std::string export_table(const model::Model& m, const std::vector<double>& torques) {
  const auto tc = build_tooth_contact_model(m, 0);
  const double pitch_deg = 360.0 / m.gear_pairs[0].teeth1;
  std::string csv =
      "# geardyn LTCA of the spur pair, exported for the round trip\n"
      "angle_deg, torque_Nm, te_um, stiffness_N_m\n";
  for (double t : torques) {
    const gear::ToothContactResult r = tc->contact->solve(t);
    EXPECT_EQ(r.status, Status::Ok) << r.message;
    for (int p = 0; p < tc->options.positions; ++p) {
      const auto i = static_cast<std::size_t>(p);
      csv += fmt::format("{:.17g}, {}, {:.17g}, {:.17g}\n", r.mesh_fraction[i] * pitch_deg, t,
                         r.te_m[i] * 1e6, r.stiffness_secant_n_per_m[i]);
    }
  }
  return csv;
}

// Round trip: the table written from geardyn's LTCA at 80, 120 and 160 N m, read back at the
// pair's 120 N m (a node: no interpolation error), gives the STE of ste_source = "tooth_contact"
// sample by sample — the TE to the CSV's 17 digits (1e-18 m of a micrometre TE), the stiffness
// F_s / (e - e_g) to 1e-9 (e_g = e - F_s / k loses the digits of e that e - e_g does not hold:
// e / (e - e_g) ~ 1e2 here, so 1e-16 x 1e2 x a margin) — and so the same dynamics: every number
// of mesh_force agrees to 1e-7 relative (the solver's own tolerance is far below; the inputs
// differ by 1e-9).
TEST(LtcaTableImport, RoundTripOfGeardynsOwnLtcaGivesTheSameDynamics) {
  const fs::path dir = fresh_dir("ltca_import_round_trip");
  const model::Model own =
      load(dir, spur("120", "ste_source = \"tooth_contact\"\n" + kTipRelief) + kDynamics);
  write_file(dir / "ltca.csv", export_table(own, {80.0, 120.0, 160.0}));
  const model::Model imported =
      load(dir, spur("120", "ltca_file = \"ltca.csv\"\n" + kTipRelief) + kDynamics);
  check_inputs(imported, {});
  const PairModel a = build_pair_model(own, 0), b = build_pair_model(imported, 0);
  ASSERT_TRUE(b.ste_from_ltca);
  EXPECT_EQ(b.ste_source_label(), "LTCA table ltca.csv");
  ASSERT_EQ(a.ste->size(), b.ste->size());
  for (std::size_t j = 0; j < a.ste->size(); ++j) {
    EXPECT_NEAR(b.ste->ste_m()[j], a.ste->ste_m()[j], 1e-18) << j;
    const double ka = a.static_force_n / (a.ste->ste_m()[j] - a.ste->geometric_te_m()[j]);
    const double kb = b.static_force_n / (b.ste->ste_m()[j] - b.ste->geometric_te_m()[j]);
    EXPECT_NEAR(kb, ka, 1e-9 * ka) << j;
  }
  const Outcome fa = run_entry(own), fb = run_entry(imported);
  ASSERT_EQ(fa.output.status, Status::Ok) << fa.output.message;
  ASSERT_EQ(fb.output.status, Status::Ok) << fb.output.message;
  ASSERT_EQ(fa.output.tables.size(), fb.output.tables.size());
  std::size_t compared = 0;
  for (std::size_t t = 0; t < fa.output.tables.size(); ++t) {
    const Table &ta = fa.output.tables[t], &tb = fb.output.tables[t];
    ASSERT_EQ(ta.name, tb.name);
    ASSERT_EQ(ta.rows(), tb.rows()) << ta.name;
    for (const Column& ca : ta.columns) {
      if (ca.text) continue;  // the STE source's label differs
      const Column& cb = tb.column(ca.name);
      double scale = 0.0;
      for (double v : ca.numbers) scale = std::max(scale, std::abs(v));
      for (std::size_t i = 0; i < ca.numbers.size(); ++i, ++compared)
        EXPECT_NEAR(cb.numbers[i], ca.numbers[i], 1e-7 * scale) << ta.name << "." << ca.name;
    }
  }
  EXPECT_GT(compared, 50u);
}

// Between the torques of the table the STE is the linear interpolation of the two neighbouring
// curves (sample by sample), and outside it an error at the pair's torque unless
// ste_extrapolation = true.
TEST(LtcaTableImport, InterpolatesBetweenTorquesAndRejectsTorquesOutside) {
  const fs::path dir = fresh_dir("ltca_import_between");
  const model::Model own = load(dir, spur("120", kTipRelief));
  write_file(dir / "ltca.csv", export_table(own, {80.0, 160.0}));
  const auto tc = build_tooth_contact_model(own, 0);
  const gear::ToothContactResult r80 = tc->contact->solve(80.0), r160 = tc->contact->solve(160.0);
  const PairModel b =
      build_pair_model(load(dir, spur("100", "ltca_file = \"ltca.csv\"\n" + kTipRelief)), 0);
  for (std::size_t j = 0; j < b.ste->size(); ++j)
    EXPECT_NEAR(b.ste->ste_m()[j], 0.75 * r80.te_m[j] + 0.25 * r160.te_m[j], 1e-18) << j;
  try {
    (void)build_pair_model(load(dir, spur("200", "ltca_file = \"ltca.csv\"\n")), 0);
    ADD_FAILURE() << "no error for a torque outside the table";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "gear_pairs[0].torque");
    EXPECT_NE(std::string(e.what()).find("[80, 160] N m"), std::string::npos) << e.what();
    EXPECT_NE(e.hint().find("ste_extrapolation"), std::string::npos);
  }
  const PairModel x = build_pair_model(
      load(dir, spur("200", "ltca_file = \"ltca.csv\"\nste_extrapolation = true\n")), 0);
  EXPECT_TRUE(x.ste_from_ltca);
}

TEST(LtcaTableImport, BadKeysAreLocated) {
  const fs::path dir = fresh_dir("ltca_import_bad");
  write_file(dir / "ltca.csv",
             "angle_deg, torque_nm, h_um, te_um\n0, 100, 0, 3\n6, 100, 0, 3.2\n12, 100, 0, 3.1\n"
             "0, 100, 50, 3.5\n6, 100, 50, 3.6\n12, 100, 50, 3.4\n");
  auto fails = [&](const std::string& extra, const std::string& key) {
    try {
      const model::Model m = load(dir, spur("100", extra));
      check_inputs(m, {});
      ADD_FAILURE() << "no error for " << key;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key_path(), key) << e.what();
      EXPECT_GT(e.where().line, 0) << e.what();
    }
  };
  fails("ltca_file = \"ltca.csv\"\nste_file = \"ste.csv\"\n", "gear_pairs[0].ltca_file");
  fails("ltca_file = \"ltca.csv\"\nste_source = \"tooth_contact\"\n", "gear_pairs[0].ste_source");
  fails("ltca_file = \"missing.csv\"\n", "gear_pairs[0].ltca_file");
  fails("ltca_file = \"ltca.csv\"\n[gear_pairs.contact]\nmounting_h = 60e-6\n",
        "gear_pairs[0].contact.mounting_h");
  fails("ltca_file = \"ltca.csv\"\n[gear_pairs.contact]\nmounting_v = 1e-6\n",
        "gear_pairs[0].contact.mounting_v");
  fails("ltca_file = \"ltca.csv\"\n[gear_pairs.contact]\nshaft_angle_error_deg = 0.01\n",
        "gear_pairs[0].contact.shaft_angle_error_deg");
  // Within the table's H: interpolated (the midpoint of the two H rows).
  const PairModel pm = build_pair_model(
      load(dir, spur("100",
                     "ltca_file = \"ltca.csv\"\n[gear_pairs.contact]\nmounting_h = "
                     "25e-6\n")),
      0);
  EXPECT_NEAR(pm.ste->ste_m()[0], 3.25e-6, 1e-18);
}

// A topography equal to a lead crowning C_beta (z = 2y/b - 1, removal C_beta z^2) gives the
// crowning's LTCA. The slice model samples the gap at the slice centres only, so a map with its
// face points there reproduces the crowning exactly (rounding: 1e-15 m). A coarser map (11 face
// points, spacing h = b/10) differs from the parabola by at most C_beta (h/b)^2 = 1e-7 m between
// its points (the linear-interpolation error f'' h^2 / 8 with f'' = 8 C_beta / b^2); a gap
// perturbation bounded by eps moves the approach, the loaded TE, by at most eps (the contact
// problem is monotone in the gaps), so the TE agrees within 1e-7 m.
TEST(TopographyFile, EqualsTheLeadCrowningItEncodes) {
  const fs::path dir = fresh_dir("ltca_topography");
  const double crowning = 10e-6, b = 0.02;
  const int slices = 40;
  auto write_map = [&](const std::string& name, const std::vector<double>& faces) {
    std::string csv = "roll_angle_deg, face_mm, removed_um\n";
    for (double roll : {0.0, 60.0})
      for (double y : faces) {
        const double z = 2.0 * y / b - 1.0;
        csv += fmt::format("{}, {:.17g}, {:.17g}\n", roll, y * 1e3, crowning * z * z * 1e6);
      }
    write_file(dir / name, csv);
  };
  std::vector<double> centres, coarse;
  for (int k = 0; k < slices; ++k) centres.push_back((k + 0.5) * b / slices);
  for (int k = 0; k <= 10; ++k) coarse.push_back(k * b / 10);
  write_map("centres.csv", centres);
  write_map("coarse.csv", coarse);
  auto te = [&](const std::string& flank1) {
    const model::Model m = load(dir, spur("150", "[gear_pairs.flank1]\n" + flank1) + kAnalysis);
    const Outcome o = run_entry(m);
    EXPECT_EQ(o.output.status, Status::Ok) << o.output.message;
    return result(o).torques.front();
  };
  const auto ref = te(fmt::format("lead_crowning = {}\n", crowning));
  const auto exact = te("topography_file = \"centres.csv\"\n");
  const auto approx = te("topography_file = \"coarse.csv\"\n");
  ASSERT_EQ(ref.te_m.size(), exact.te_m.size());
  double largest = 0.0;
  for (std::size_t p = 0; p < ref.te_m.size(); ++p) {
    EXPECT_NEAR(exact.te_m[p], ref.te_m[p], 1e-15) << p;
    EXPECT_NEAR(approx.te_m[p], ref.te_m[p], 1e-7) << p;
    largest = std::max(largest, std::abs(approx.te_m[p] - ref.te_m[p]));
  }
  EXPECT_GT(largest, 0.0);  // the coarse map is not the parabola
  EXPECT_NEAR(exact.face_load_factor, ref.face_load_factor, 1e-9);
}

TEST(TopographyFile, BadFilesAreLocated) {
  const fs::path dir = fresh_dir("ltca_topography_bad");
  write_file(dir / "gap.csv",
             "roll_angle_deg, face_mm, removed_um\n0, 0, 1\n0, 20, 1\n60, 0, 1\n60, 10, 1\n");
  try {
    (void)build_tooth_contact_model(
        load(dir, spur("100", "[gear_pairs.flank2]\ntopography_file = \"gap.csv\"\n")), 0);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(e.where().file.find("gap.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no row at roll_angle_deg = 0, face_mm = 10"),
              std::string::npos)
        << e.what();
  }
  try {
    (void)build_tooth_contact_model(
        load(dir, spur("100", "[gear_pairs.flank2]\ntopography_file = \"none.csv\"\n")), 0);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "gear_pairs[0].flank2.topography_file") << e.what();
    EXPECT_GT(e.where().line, 0);
  }
}

// The contact pattern of an aligned, unmodified spur pair: in single-tooth contact (the middle of
// the path, between g_alpha - p_bt and p_bt) one tooth pair carries the whole F_bt = T1 / r_b1,
// evenly over the face (no misalignment, no crowning): w = F_bt / b at every slice, by
// equilibrium (the contact problem's force balance, 1e-9 relative). The pressure map there is
// the Hertzian peak pressure of that line load: uniform over the face too.
TEST(FlankMaps, SingleContactCarriesTheWholeForceEvenlyOverTheFace) {
  const model::Model m = load(fresh_dir("ltca_maps"), spur("180") + kAnalysis);
  const Outcome o = run_entry(m);
  ASSERT_EQ(o.output.status, Status::Ok) << o.output.message;
  const auto& r = result(o);
  const auto& g = r.model->contact->geometry();
  const Plot* load = nullptr;
  const Plot* pressure = nullptr;
  for (const Plot& p : o.output.plots) {
    if (p.name == "line_load_map") load = &p;
    if (p.name == "pressure_map") pressure = &p;
  }
  ASSERT_NE(load, nullptr);
  ASSERT_NE(pressure, nullptr);
  const Trace& t = load->traces.at(0);
  ASSERT_TRUE(t.is_heatmap());
  EXPECT_EQ(t.z_label, "line load [N/mm]");
  ASSERT_EQ(t.x.size(), 40u);  // the slices
  ASSERT_EQ(t.z.size(), t.y.size());
  const double w = r.torques.front().force_n / g.face_width_m * 1e-3;  // N/mm
  const double rb1 = r.model->contact->base_radius1();
  std::size_t single = 0;
  for (std::size_t i = 0; i < t.y.size(); ++i) {
    const double s = t.y[i] / (180.0 / M_PI) * rb1 - r.model->contact->pinion_roll_length(0.0);
    ASSERT_EQ(t.z[i].size(), t.x.size());
    // Strictly inside single contact by one sampling step (the map is linear between samples).
    const double step = g.transverse_base_pitch_m / r.model->options.positions;
    if (s > g.path_of_contact_m - g.transverse_base_pitch_m + step &&
        s < g.transverse_base_pitch_m - step) {
      ++single;
      for (std::size_t k = 0; k < t.x.size(); ++k) {
        EXPECT_NEAR(t.z[i][k], w, 1e-9 * w) << i << " " << k;
        EXPECT_NEAR(pressure->traces[0].z[i][k], pressure->traces[0].z[i][0],
                    1e-9 * pressure->traces[0].z[i][0]);
      }
    }
    for (double v : t.z[i]) EXPECT_FALSE(v > 1.0001 * w) << "more than the whole force";
  }
  EXPECT_GT(single, 3u);
}

}  // namespace
}  // namespace geardyn::analyses
