// The LTCA table reader and its interpolation (gear/ltca_table.hpp): exact at the grid nodes,
// multilinear between them (exact for a function linear in each of torque, H, V, J), periodic
// piecewise linear over the angle, open and closed cycles alike, the STE it gives the dynamic
// model (its stiffness F_s / (e - e_g) is the table's), and located errors for bad files.
#include "geardyn/gear/ltca_table.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace geardyn::gear {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kTeeth = 12;                    // one mesh cycle: 30 deg of the pinion
constexpr double kCycleDeg = 360.0 / kTeeth;  // 30

// A TE linear in torque and in H for each angle (with a T*H cross term, still multilinear), so
// that the multilinear interpolation is exact between the nodes: te(u, T, H) [m].
double te_model(double u, double torque, double h) {
  const double shape = 1.0 + 0.2 * std::sin(2 * kPi * u) + 0.05 * std::cos(4 * kPi * u);
  return shape * (2e-6 + 1e-8 * torque + 0.01 * h + 2e-5 * torque * h);
}
double k_model(double u, double torque, double h) {
  return 4e8 * (1.0 + 0.1 * std::cos(2 * kPi * u)) * (1.0 + 1e-3 * torque) * (1.0 - 50.0 * h);
}

// Long format, `angles` open samples over one cycle (or closed: one more, the first again),
// torques x H values, TE in um (or in urad / rb when `angular_rb` > 0) and stiffness in N/m.
std::string table_text(int angles, bool closed, bool stiffness, double angular_rb = 0.0) {
  std::string s = "# synthetic LTCA export, 12-tooth pinion\nangle_deg, torque_Nm, h_mm, ";
  s += angular_rb > 0.0 ? "te_urad" : "te_um";
  s += stiffness ? ", stiffness_N_m\n" : "\n";
  for (double torque : {100.0, 200.0, 400.0})
    for (double h_mm : {-0.1, 0.0, 0.2}) {
      // Rows of one node in reverse angle order: the reader must not depend on the order.
      for (int a = angles - (closed ? 0 : 1); a >= 0; --a) {
        const double u = static_cast<double>(a) / angles;
        const double te = te_model(u, torque, h_mm * 1e-3);
        s += fmt::format("{:.17g}, {}, {}, {:.17g}", 5.0 + u * kCycleDeg, torque, h_mm,
                         angular_rb > 0.0 ? te / angular_rb * 1e6 : te * 1e6);
        if (stiffness) s += fmt::format(", {:.17g}", k_model(u, torque, h_mm * 1e-3));
        s += "\n";
      }
    }
  return s;
}

LtcaTable parse(const std::string& text, double rb = 0.05) {
  LtcaReadOptions o;
  o.teeth = kTeeth;
  o.base_radius_m = rb;
  return LtcaTable::parse(text, "ltca.csv", o);
}

TEST(LtcaTable, ReadsTheGridAndIsExactAtTheNodes) {
  const LtcaTable t = parse(table_text(16, false, true));
  ASSERT_EQ(t.axes()[0], (std::vector<double>{100, 200, 400}));
  ASSERT_EQ(t.axes()[1].size(), 3u);
  EXPECT_DOUBLE_EQ(t.axes()[1][0], -1e-4);
  EXPECT_EQ(t.axes()[2], std::vector<double>{0.0});  // no V column: 0
  EXPECT_EQ(t.axes()[3], std::vector<double>{0.0});
  ASSERT_EQ(t.cycle_fraction().size(), 17u);  // 16 angles, closed by u = 1
  EXPECT_TRUE(t.has_stiffness());
  for (std::size_t it = 0; it < 3; ++it)
    for (std::size_t ih = 0; ih < 3; ++ih)
      for (std::size_t a = 0; a < 16; ++a) {
        const double u = a / 16.0, T = t.axes()[0][it], h = t.axes()[1][ih];
        const LtcaPoint p{T, h, 0.0, 0.0};
        // The CSV holds 17 significant digits: the nodes come back to rounding (1e-15).
        EXPECT_NEAR(t.te_at(p, u), te_model(u, T, h), 1e-15 * te_model(u, T, h));
        EXPECT_NEAR(t.stiffness_at(p, u), k_model(u, T, h), 1e-15 * k_model(u, T, h));
        EXPECT_EQ(t.te_at(p, u), t.te_node({it, ih, 0, 0}, a));
      }
}

TEST(LtcaTable, IsMultilinearBetweenTorquesAndMountingErrors) {
  const LtcaTable t = parse(table_text(16, false, false));
  // te_model is linear in T and in H: the multilinear interpolation reproduces it exactly at
  // any (T, H) inside the grid, at the angle nodes (rounding only: 1e-13).
  for (double T : {100.0, 137.5, 250.0, 399.0})
    for (double h : {-1e-4, -3e-5, 0.0, 1.234e-4, 2e-4})
      for (int a : {0, 5, 11}) {
        const double u = a / 16.0;
        EXPECT_NEAR(t.te_at({T, h, 0, 0}, u), te_model(u, T, h), 1e-13 * te_model(u, T, h))
            << T << " " << h << " " << a;
      }
  // Between two angle nodes: linear in the angle (the mean of the two nodes at mid-way).
  const LtcaPoint p{150.0, 5e-5, 0, 0};
  const double mid = 0.5 * (t.te_at(p, 3 / 16.0) + t.te_at(p, 4 / 16.0));
  EXPECT_NEAR(t.te_at(p, 3.5 / 16.0), mid, 1e-15 * mid);
}

TEST(LtcaTable, IsPeriodicInTheAngleAndOpenEqualsClosed) {
  const LtcaTable open = parse(table_text(16, false, true));
  const LtcaTable closed = parse(table_text(16, true, true));
  EXPECT_EQ(closed.cycle_fraction().size(), 17u);  // the closing row is the knot u = 1
  const LtcaPoint p{300.0, 1e-4, 0, 0};
  for (double u : {0.0, 0.1, 0.47, 0.97, 0.99}) {
    const double e = open.te_at(p, u);
    EXPECT_NEAR(open.te_at(p, u + 1.0), e, 1e-15 * e);
    EXPECT_NEAR(open.te_at(p, u - 3.0), e, 1e-15 * e);
    EXPECT_NEAR(closed.te_at(p, u), e, 1e-15 * e);
    EXPECT_NEAR(closed.stiffness_at(p, u), open.stiffness_at(p, u), 1e-7);
  }
  // The last interval wraps: between the last angle (15/16) and the next cycle's first.
  const double wrap = 0.5 * (open.te_at(p, 15 / 16.0) + open.te_at(p, 0.0));
  EXPECT_NEAR(open.te_at(p, 15.5 / 16.0), wrap, 1e-15 * wrap);
}

TEST(LtcaTable, OutsideTheTableIsAnErrorUnlessExtrapolated) {
  const LtcaTable t = parse(table_text(8, false, false));
  auto key_of = [&](const LtcaPoint& p) {
    try {
      (void)t.te_at(p, 0.0);
    } catch (const InputError& e) {
      return e.key_path();
    }
    return std::string("none");
  };
  EXPECT_EQ(key_of({450.0, 0, 0, 0}), "torque");
  EXPECT_EQ(key_of({200.0, 3e-4, 0, 0}), "h");
  EXPECT_EQ(key_of({200.0, 0, 1e-5, 0}), "v");  // no V column: only V = 0 is in the table
  EXPECT_EQ(key_of({200.0, 0, 0, 0}), "none");
  // Extrapolated: linear from the two end nodes (exact for te_model), V held.
  EXPECT_NEAR(t.te_at({500.0, 3e-4, 1e-5, 0}, 0.25, true), te_model(0.25, 500.0, 3e-4), 1e-18);
}

TEST(LtcaTable, SteStiffnessIsTheTablesStiffness) {
  const double rb = 0.05;
  const LtcaTable t = parse(table_text(16, false, true), rb);
  const LtcaPoint p{250.0, 5e-5, 0, 0};
  const SteCurve c = t.ste(p, rb, false, 0.0, 64);
  ASSERT_EQ(c.size(), 64u);
  ASSERT_TRUE(c.has_geometric_te());
  const double force = p.torque_nm / rb;
  for (std::size_t j = 0; j < 64; ++j) {
    const double u = j / 64.0;
    EXPECT_NEAR(c.ste_m()[j], t.te_at(p, u), 1e-18);
    // k = F_s / (e - e_g) is the interpolated stiffness (rounding of e - e_g: 1e-9 relative).
    const double k = force / (c.ste_m()[j] - c.geometric_te_m()[j]);
    EXPECT_NEAR(k, t.stiffness_at(p, u), 1e-9 * k);
  }
  // Without a stiffness column the TE is all elastic: e_g = 0.
  const SteCurve plain = parse(table_text(16, false, false), rb).ste(p, rb);
  EXPECT_FALSE(plain.has_geometric_te());
  EXPECT_EQ(plain.size(), 16u);
  // The shift moves sample 0 along the cycle.
  const SteCurve shifted = t.ste(p, rb, false, 0.25, 64);
  EXPECT_NEAR(shifted.ste_m()[0], c.ste_m()[16], 1e-18);
}

TEST(LtcaTable, AngularTeIsScaledByTheBaseRadius) {
  const double rb = 0.04;
  const LtcaTable lin = parse(table_text(8, false, false));
  const LtcaTable ang = parse(table_text(8, false, false, rb), rb);
  const LtcaPoint p{200.0, 0.0, 0, 0};
  for (double u : {0.0, 0.3, 0.8})
    EXPECT_NEAR(ang.te_at(p, u), lin.te_at(p, u), 1e-15 * lin.te_at(p, u));
}

TEST(LtcaTable, SingleTorqueExtrapolatesAsALinearMesh) {
  const std::string text =
      "angle_deg, torque_knm, te_m, stiffness_n_per_um\n"
      "0, 0.1, 3e-6, 400\n10, 0.1, 3.5e-6, 380\n20, 0.1, 3.2e-6, 390\n";
  LtcaReadOptions o;
  o.teeth = 12;  // open: three samples 10 deg apart over the 30 deg cycle
  const LtcaTable t = LtcaTable::parse(text, "one.csv", o);
  EXPECT_EQ(t.axes()[0], std::vector<double>{100.0});
  EXPECT_THROW((void)t.ste({200.0, 0, 0, 0}, 0.05), InputError);
  const SteCurve c = t.ste({200.0, 0, 0, 0}, 0.05, true);
  // e = e_0 + (F - F_0) / k and k unchanged: F / (e - e_g) = k = 400 N/um at sample 0.
  EXPECT_NEAR(c.ste_m()[0], 3e-6 + (200.0 - 100.0) / 0.05 / 400e6, 1e-18);
  EXPECT_NEAR(200.0 / 0.05 / (c.ste_m()[0] - c.geometric_te_m()[0]), 400e6, 1e-3);
}

// Bad files: each error names the file, line, column, the column, what was expected, found.
TEST(LtcaTable, BadFilesAreLocated) {
  auto error = [](const std::string& text) -> std::string {
    try {
      (void)parse(text);
    } catch (const InputError& e) {
      return fmt::format("{}:{} {} | {} | {} | {}", e.where().line, e.where().column, e.key_path(),
                         e.expected(), e.found(), e.where().file);
    }
    return "no error";
  };
  const std::string head = "angle_deg, torque_nm, te_um\n";
  // A missing combination: torque 200 has no row at 20 deg.
  std::string grid = head;
  for (double T : {100.0, 200.0})
    for (double a : {0.0, 10.0, 20.0})
      if (!(T == 200.0 && a == 20.0)) grid += fmt::format("{}, {}, 3.0\n", a, T);
  EXPECT_NE(error(grid).find("5:1 angle_deg"), std::string::npos) << error(grid);
  EXPECT_NE(error(grid).find("no row at angle 20 for torque 200"), std::string::npos);
  EXPECT_NE(error(grid).find("ltca.csv"), std::string::npos);
  // A repeated row.
  const std::string repeated = head + "0, 100, 3\n10, 100, 3\n20, 100, 3\n10, 100, 4\n";
  EXPECT_NE(error(repeated).find("5:1 angle_deg"), std::string::npos) << error(repeated);
  EXPECT_NE(error(repeated).find("a repeat of line 3"), std::string::npos);
  // An unknown column, a bad unit, a missing TE, a second angle column.
  EXPECT_NE(
      error("angle_deg, torque_nm, te_um, load\n0,1,1,1\n1,1,1,1\n2,1,1,1\n").find("1:30 load"),
      std::string::npos);
  EXPECT_NE(error("angle_deg, torque_nm, h_in, te_um\n0,1,0,1\n1,1,0,1\n2,1,0,1\n").find("h_in"),
            std::string::npos);
  EXPECT_NE(error("angle_deg, torque_nm\n0,1\n1,1\n2,1\n").find("te_<unit> column"),
            std::string::npos);
  EXPECT_NE(error("angle_deg, angle_rad, torque_nm, te_um\n0,0,1,1\n1,1,1,1\n2,2,1,1\n")
                .find("one angle column"),
            std::string::npos);
  // A non-positive TE without a stiffness, a zero stiffness, a negative torque, a bad number.
  EXPECT_NE(error(head + "0, 100, 3\n10, 100, -1\n20, 100, 3\n").find("3:10 te_um"),
            std::string::npos);
  EXPECT_NE(
      error("angle_deg, torque_nm, te_um, stiffness_n_per_m\n0,1,1,1e8\n10,1,1,0\n20,1,1,1e8\n")
          .find("3:8 stiffness_n_per_m"),
      std::string::npos);
  EXPECT_NE(error(head + "0, -100, 3\n10, -100, 3\n20, -100, 3\n").find("2:4 torque_nm"),
            std::string::npos);
  EXPECT_NE(error(head + "0, 100, 3\n10, 100, x\n20, 100, 3\n").find("3:10 te_um"),
            std::string::npos);
  // Angles that are not one mesh cycle of the 12-tooth pinion (30 deg).
  EXPECT_NE(error(head + "0, 100, 3\n10, 100, 3\n45, 100, 3\n").find("one mesh cycle"),
            std::string::npos);
}

}  // namespace
}  // namespace geardyn::gear
