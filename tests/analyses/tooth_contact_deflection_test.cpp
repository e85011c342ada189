// The mesh misalignment of the loaded tooth contact analysis taken from the static deflection of
// the rotor model ([gear_pairs.contact].deflection_mesh; assembly/static_deflection.hpp,
// docs/theory.md §15.7): a pinion on a simply supported shaft against closed-form beam slopes,
// which face end opens, linearity in the torque, and the located errors.
//
// Pair: spur z1 = 20, z2 = 40, m = 3 mm, alpha = 20 deg, b = 20 mm, T1 = 100 N m. Rotor: the
// pinion node at z = a on a solid steel shaft of length L along global z, simply supported
// ([[constraints]] ux, uy at both ends, uz at z = 0: rigid supports, free tilts); the wheel
// either held rigidly (a node with every DOF constrained: the limit of a stiff shaft) or on an
// identical shaft, centre distance 90 mm along +x.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/analyses/tooth_contact.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using namespace test;

constexpr double kE = 2.1e11, kDiameter = 0.04, kLength = 0.3, kFace = 0.02;
constexpr double kAlpha = 20.0 * units::kPi / 180.0, kBeta = 15.0 * units::kPi / 180.0;
constexpr double kRb1 = 0.030 * 0.9396926207859084;  // spur: r1 cos(alpha)

// Helical 20/40, m_n = 3 mm, beta = 15 deg: transverse pressure angle and reference radii.
double alpha_t() { return std::atan(std::tan(kAlpha) / std::cos(kBeta)); }
double helical_radius(int z) { return z * 0.003 / (2.0 * std::cos(kBeta)); }

struct Rotor {
  double a = 0.1;            // pinion position from the z = 0 support [m]
  double torque = 100.0;     // T1 [N m]
  bool wheel_shaft = false;  // the wheel on an identical shaft (else held rigidly)
  bool helical = false;      // helical 20/40, beta = 15 deg, right hand (else spur)
  bool supported = true;     // the pinion shaft's constraints
  std::string theory = "timoshenko";
  std::string mesh = "m1";     // deflection_mesh
  std::string contact_extra;   // more keys of [gear_pairs.contact]
  std::string analysis_extra;  // keys of the tooth_contact analysis

  double radius(int z) const { return helical ? helical_radius(z) : z * 0.0015; }
  double alpha() const { return helical ? alpha_t() : kAlpha; }
  double centre() const { return radius(20) + radius(40); }

  std::string toml() const {
    std::string s = fmt::format(R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = {}
poisson_ratio = 0.3
density = 7850

[[shafts]]
name = "p"
material = "steel"
speed_ratio = 1.0
theory = "{}"
[[shafts.elements]]
length = {}
outer_diameter = {}
[[shafts.elements]]
length = {}
outer_diameter = {}
)",
                                kE, theory, a, kDiameter, kLength - a, kDiameter);
    if (supported)
      s += R"(
[[constraints]]
node = "p.0"
dofs = ["ux", "uy", "uz"]
[[constraints]]
node = "p.2"
dofs = ["ux", "uy"]
)";
    if (wheel_shaft)
      s += fmt::format(R"(
[[shafts]]
name = "w"
material = "steel"
origin = [{:.17g}, 0.0, 0.0]
speed_ratio = -0.5
theory = "{}"
[[shafts.elements]]
length = {}
outer_diameter = {}
[[shafts.elements]]
length = {}
outer_diameter = {}
[[constraints]]
node = "w.0"
dofs = ["ux", "uy", "uz"]
[[constraints]]
node = "w.2"
dofs = ["ux", "uy"]
)",
                       centre(), theory, a, kDiameter, kLength - a, kDiameter);
    else
      s += fmt::format(R"(
[[nodes]]
name = "wheel"
position = [{:.17g}, 0.0, {}]
[[constraints]]
node = "wheel"
dofs = "all"
)",
                       centre(), a);
    const std::string helix = helical ? "helix_angle_deg = 15\n" : "";
    s += fmt::format(R"(
[[gear_meshes]]
name = "m1"
gear1 = "p.1"
gear2 = "{}"
type = "{}"
base_radius1 = {:.17g}
base_radius2 = {:.17g}
pressure_angle_deg = 20
{}stiffness = 1e9

[[gear_pairs]]
name = "pair"
type = "{}"
{}teeth1 = 20
teeth2 = 40
module = 0.003
face_width = {}
torque = {}

[gear_pairs.contact]
positions = 32
slices = 20
deflection_mesh = "{}"
{}
[[analyses]]
name = "ltca"
type = "tooth_contact"
{}
)",
                     wheel_shaft ? "w.1" : "wheel", helical ? "helical" : "spur",
                     radius(20) * std::cos(alpha()), radius(40) * std::cos(alpha()), helix,
                     helical ? "helical" : "spur", helix, kFace, torque, mesh, contact_extra,
                     analysis_extra);
    return s;
  }
};

// Closed-form slope of a simply supported Euler-Bernoulli beam under a point load F at x = a
// (b = L - a) at the load: theta(a) = F a b (b - a) / (3 E I L) (W.C. Young, R.G. Budynas,
// "Roark's Formulas for Stress and Strain", 7th ed., 2002, Table 8.1 case 1e; S. Timoshenko,
// J.M. Gere, "Mechanics of Materials", 1972). Shear (Timoshenko) adds nothing to the section
// rotation there: EI psi' = M as in Euler-Bernoulli, and the shear part of the deflection,
// integral of V / (kappa G A) over the span, is F (b a - a b) / (L kappa G A) = 0, so the
// constant of psi is the same. The load is the tooth force in the transverse plane,
// F = T1 / r_b1 (F_t and F_r = F_t tan(alpha) of gear/tooth_forces.hpp combined), along the
// line of action.
double slope(double a, double torque) {
  const double F = torque / kRb1, b = kLength - a;
  const double I = units::kPi * std::pow(kDiameter, 4) / 64.0;
  return F * a * b * (b - a) / (3.0 * kE * I * kLength);
}

std::shared_ptr<ToothContactModel> contact_model(const Rotor& r, const std::string& dir) {
  return build_tooth_contact_model(load(fresh_dir(dir), r.toml()), 0);
}

Outcome run_entry(const model::Model& m) {
  return type_of(m.analyses[0]).run(m, m.analyses[0], Context(m, m.analyses[0]));
}

// The beam elements (Friedman & Kosmatka's interdependent interpolation, exact solutions of the
// homogeneous Timoshenko / Euler-Bernoulli equations) give the exact nodal displacements and
// rotations for loads at the nodes, so the only error is round-off of a 12-DOF solve: 1e-6
// relative is far above it and far below any modelling error (a missed shear term, a lever
// arm, a wrong face width would be percent).
TEST(ToothContactDeflection, PinionSlopeOnSimplySupportedShaftIsTheBeamFormula) {
  for (const std::string theory : {"timoshenko", "euler_bernoulli"}) {
    Rotor r;
    r.theory = theory;
    const auto tc = contact_model(r, "deflection_slope");
    ASSERT_TRUE(tc->misalignment.deflection.has_value());
    const auto& d = *tc->misalignment.deflection;
    const double theta = slope(r.a, r.torque);
    EXPECT_NEAR(d.slope1_rad, -theta, 1e-6 * theta) << theory;  // gear 1 tilts away
    EXPECT_NEAR(d.slope2_rad, 0.0, 1e-12 * theta) << theory;    // gear 2 held
    EXPECT_NEAR(d.misalignment_m, kFace * theta, 1e-6 * kFace * theta) << theory;
    // The force lies along the transverse line of action (F_r / F_t = tan(alpha) = tan(alpha_wt)
    // at the standard centre distance): no tilt out of the plane of action beyond round-off.
    EXPECT_NEAR(d.out_of_plane_misalignment_m, 0.0, 1e-9 * kFace * theta) << theory;
    EXPECT_DOUBLE_EQ(tc->misalignment_m, d.misalignment_m);
    if (theory == "euler_bernoulli") {
      // Deflection at the load, F a^2 b^2 / (3 E I L) (same tables), along -n_t.
      const double F = r.torque / kRb1, b = kLength - r.a;
      const double I = units::kPi * std::pow(kDiameter, 4) / 64.0;
      const double w = F * r.a * r.a * b * b / (3.0 * kE * I * kLength);
      EXPECT_NEAR(d.displacement1.dot(d.line_of_action), -w, 1e-6 * w);
    }
  }
}

// Both gears on identical simply supported shafts: each tilts by theta(a) away from the other
// (equal and opposite tooth forces), so the slopes add: f_ma = 2 b theta(a) (superposition of
// the same Roark / Timoshenko case), within the same 1e-6.
TEST(ToothContactDeflection, BothShaftsFlexibleAddTheirSlopes) {
  Rotor r;
  r.wheel_shaft = true;
  const auto tc = contact_model(r, "deflection_two_shafts");
  const auto& d = *tc->misalignment.deflection;
  const double theta = slope(r.a, r.torque);
  EXPECT_NEAR(d.slope1_rad, -theta, 1e-6 * theta);
  EXPECT_NEAR(d.slope2_rad, theta, 1e-6 * theta);
  EXPECT_NEAR(d.misalignment_m, 2.0 * kFace * theta, 2e-6 * kFace * theta);
}

// Which face end opens: the pinion shaft bends most near mid-span, so the pinion's flank moves
// away from the wheel more at its face end towards mid-span. With the pinion nearer the z = 0
// support that is the +z end (y = b for a spur pair: y runs along +e3 of gear 1), f_ma > 0, and
// the load concentrates at y = 0; with the pinion nearer the other support the other way round.
// The face-load table of the contact analysis shows it (line load at the first slice against
// the last: no tolerance needed, the sign is the claim).
TEST(ToothContactDeflection, FaceEndTowardsMidSpanOpens) {
  for (const double a : {0.1, 0.2}) {
    Rotor r;
    r.a = a;
    const fs::path dir = fresh_dir("deflection_sign");
    const model::Model m = load(dir, r.toml());
    check_inputs(m, {});
    const Outcome o = run_entry(m);
    ASSERT_EQ(o.output.status, Status::Ok) << o.output.message;
    const auto& res = *static_cast<const ToothContactRunResult*>(o.result.get());
    const double f = res.model->misalignment.deflection->misalignment_m;
    const auto& w = res.torques.front().face_load_n_per_m;
    if (a < 0.5 * kLength) {
      EXPECT_GT(f, 0.0);
      EXPECT_GT(w.front(), w.back());
    } else {
      EXPECT_LT(f, 0.0);
      EXPECT_LT(w.front(), w.back());
    }
    EXPECT_GT(res.torques.front().face_load_factor, 1.05);  // a real concentration
    // The summary states the misalignment used and its deflection part; the note where from.
    const Table& s = table(o.output, "summary");
    EXPECT_DOUBLE_EQ(s.column("misalignment_m").numbers.front(), f);
    EXPECT_DOUBLE_EQ(s.column("misalignment_deflection_m").numbers.front(), f);
    bool noted = false;
    for (const auto& note : o.output.notes)
      noted = noted || note.find("static deflection of the rotor") != std::string::npos;
    EXPECT_TRUE(noted);
  }
}

// The static problem is linear: twice the torque, twice the deflection misalignment, both
// from the kernel (pair torque doubled) and along the analysis's torque list; the given
// misalignment adds unchanged. Round-off only: 1e-9 relative.
TEST(ToothContactDeflection, MisalignmentIsLinearInTheTorqueAndAddsToTheGivenOne) {
  Rotor r;
  const double f1 = contact_model(r, "deflection_linear")->misalignment.deflection->misalignment_m;
  r.torque = 200.0;
  const double f2 = contact_model(r, "deflection_linear")->misalignment.deflection->misalignment_m;
  EXPECT_NEAR(f2, 2.0 * f1, 1e-9 * f1);

  Rotor given;
  given.contact_extra = "misalignment = 5e-6\n";
  given.analysis_extra = "torques = [100, 200]\n";
  const model::Model m = load(fresh_dir("deflection_given"), given.toml());
  const Outcome o = run_entry(m);
  ASSERT_EQ(o.output.status, Status::Ok) << o.output.message;
  const Table& s = table(o.output, "summary");
  const auto& used = s.column("misalignment_m").numbers;
  const auto& defl = s.column("misalignment_deflection_m").numbers;
  ASSERT_EQ(used.size(), 2u);
  EXPECT_NEAR(defl[0], f1, 1e-9 * f1);
  EXPECT_NEAR(defl[1], 2.0 * f1, 1e-9 * f1);
  EXPECT_NEAR(used[0], 5e-6 + f1, 1e-9 * f1);
  EXPECT_NEAR(used[1], 5e-6 + 2.0 * f1, 1e-9 * f1);
  // The contact analysis at 200 N m saw the larger misalignment: a larger face-load factor
  // than the same pair with the 100 N m misalignment would show is not asserted here (load
  // also grows); the load concentration grows with it.
  const auto& res = *static_cast<const ToothContactRunResult*>(o.result.get());
  EXPECT_GT(res.torques[1].face_load_factor, 1.0);
}

// Helical pinion at mid-span (Euler-Bernoulli): the transverse force gives no slope there
// (theta(L/2) = 0 above), the axial force F_a = F_t tan(beta) at the pitch radius r1 is a
// moment M = F_a r1 = T1 tan(beta) about e_t, and a simply supported span under a couple M at
// mid-span turns there by M L / (12 E I) (Roark, Table 8.1, concentrated intermediate moment;
// by integration of EI w'' = -M x / L over the half span with w = 0 at both ends). The axis
// tilts in the plane of the axes (along e_r over the face), which the line of action sees with
// sin(alpha_wt) and the normal of the plane of action with cos(alpha_wt). Exact nodal values
// again: 1e-6 relative. (Timoshenko would add M / (kappa G A L) to the section rotation: the
// shear of a couple-loaded span does not vanish, so the test uses Euler-Bernoulli.)
TEST(ToothContactDeflection, HelicalAxialForceTiltsThePinionByItsMoment) {
  Rotor r;
  r.helical = true;
  r.a = 0.5 * kLength;
  r.theory = "euler_bernoulli";
  const auto tc = contact_model(r, "deflection_helical");
  const auto& d = *tc->misalignment.deflection;
  const double I = units::kPi * std::pow(kDiameter, 4) / 64.0;
  const double theta = r.torque * std::tan(kBeta) * kLength / (12.0 * kE * I);
  const double in = kFace * theta * std::sin(alpha_t()), out = kFace * theta * std::cos(alpha_t());
  EXPECT_NEAR(std::abs(d.misalignment_m), in, 1e-6 * in);
  EXPECT_NEAR(std::abs(d.out_of_plane_misalignment_m), out, 1e-6 * out);
  // The contact analysis runs with it (the misalignment of the slice model is the in-plane part).
  EXPECT_DOUBLE_EQ(tc->misalignment_m, d.misalignment_m);
}

std::string error_of(const Rotor& r) {
  try {
    const model::Model m = load(fresh_dir("deflection_bad"), r.toml());
    check_inputs(m, {});
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// Bad input is located at the key: a mesh the rotor does not have, and a pinion shaft without
// supports (singular without the mesh spring), which names the free motion and the keys to add.
TEST(ToothContactDeflection, BadLinksAreLocated) {
  Rotor unknown;
  unknown.mesh = "nope";
  const std::string e1 = error_of(unknown);
  EXPECT_NE(e1.find("gear_pairs[0].contact.deflection_mesh"), std::string::npos) << e1;
  EXPECT_NE(e1.find("\"m1\""), std::string::npos) << e1;

  Rotor free;
  free.supported = false;
  const std::string e2 = error_of(free);
  EXPECT_NE(e2.find("gear_pairs[0].contact.deflection_mesh"), std::string::npos) << e2;
  EXPECT_NE(e2.find("shaft 'p'"), std::string::npos) << e2;
  EXPECT_NE(e2.find("[[constraints]]"), std::string::npos) << e2;
  EXPECT_NE(e2.find("model.toml"), std::string::npos) << e2;
}

}  // namespace
}  // namespace geardyn::analyses
