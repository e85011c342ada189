// Loaded tooth contact analysis of bevel and hypoid pairs through their virtual cylindrical pair
// at mid face (gear/tooth_contact.hpp, docs/theory.md §15.9): the identity with the virtual
// pair given directly, the ease-off's pattern centre, the first-order shift of the pattern per
// unit mounting error H, V, J, Delta Sigma, and the geometric TE of a profile-crowned pair.
//
// References: ISO 10300-1:2014 (virtual cylindrical gears at mid face, Tredgold); the V-H-J
// convention of H.J. Stadtfeld, "Handbook of Bevel and Hypoid Gears", RIT, 1993; the
// first-order gap of a displaced member, F.L. Litvin, A. Fuentes, "Gear Geometry and Applied
// Theory", 2nd ed., Cambridge University Press, 2004, ch. 9 (the gap along the surface normal
// is -d . n) and V. Simon, "Influence of misalignments on mesh performances of hypoid gears",
// Mech. Mach. Theory 43 (2008) (misalignments as relative displacements of the members).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <numeric>

#include "geardyn/core/error.hpp"
#include "geardyn/gear/slice_compliance.hpp"
#include "geardyn/gear/tooth_compliance.hpp"
#include "geardyn/gear/tooth_contact.hpp"

namespace {

using namespace geardyn;
using namespace geardyn::gear;

constexpr double kDeg = std::numbers::pi / 180.0;

// 36:48 at Sigma = 90 deg: tan(delta1) = 0.75, so the virtual (Tredgold) tooth counts
// z / cos(delta) are the integers 45 and 80 and the virtual pair can be given as a cylindrical
// pair. m_e = 4 mm, b = 30 mm: R_e = 120 mm, R_m = 105 mm, m_m = 3.5 mm.
GearPairSpec bevel_spec(GearType type, double beta_deg) {
  GearPairSpec s;
  s.type = type;
  s.teeth_pinion = 36;
  s.teeth_wheel = 48;
  s.module_m = 4e-3;
  s.face_width_m = 30e-3;
  s.helix_angle_rad = beta_deg * kDeg;
  s.shaft_angle_rad = 0.5 * std::numbers::pi;
  return s;
}

// The LTCA of one pair with the analytic slice compliance built as the analysis builds it.
struct Ltca {
  std::unique_ptr<ToothCompliance> teeth;
  std::unique_ptr<SliceCompliance> slices;
  std::unique_ptr<ToothContact> contact;
  Ltca(const GearPairGeometry& g, const ToothContactOptions& o) {
    const double da = mounting_effect(g, o.mounting).centre_distance_change_m;
    teeth = std::make_unique<ToothCompliance>(virtual_cylindrical_pair(g, da));
    slices = std::make_unique<SliceCompliance>(*teeth, 0.0);
    contact =
        std::make_unique<ToothContact>(g, FlankModification{}, FlankModification{}, *slices, o);
  }
};

// Load-weighted pattern centre over the cycle: eta (face), xi (pinion ease-off coordinate) and
// the wheel's roll length rho2 [m].
struct Centre {
  double eta = 0.0, xi = 0.0, rho2 = 0.0;
};

Centre centre(const ToothContact& tc, const ToothContactResult& r) {
  Centre c;
  double sum = 0.0;
  const double b = tc.geometry().face_width_m, rb2 = tc.geometry().wheel.base_radius_m;
  for (const auto& p : r.distribution) {
    const double w = p.line_load_n_per_m;
    if (w <= 0.0) continue;
    sum += w;
    c.eta += w * (2.0 * p.face_m / b - 1.0);
    c.xi += w * tc.ease_off_xi(p.roll_angle1_rad * tc.base_radius1());
    c.rho2 += w * std::sqrt(p.radius2_m * p.radius2_m - rb2 * rb2);
  }
  c.eta /= sum;
  c.xi /= sum;
  c.rho2 /= sum;
  return c;
}

ToothContactOptions options(int positions, int slices) {
  ToothContactOptions o;
  o.positions = positions;
  o.slices = slices;
  return o;
}

// Zero ease-off and zero mounting errors: the bevel LTCA is the LTCA of the virtual cylindrical
// pair (ISO 10300-1: z_v = z / cos(delta), m_mn, beta_m, b) at the torque that gives the same
// force, T_v = T r_v1 / r_m1 = T / cos(delta1). Same arithmetic: equal to round-off.
TEST(BevelContact, ZeroEaseOffEqualsTheVirtualCylindricalPairGivenDirectly) {
  for (const auto& [type, beta] :
       {std::pair{GearType::StraightBevel, 0.0}, std::pair{GearType::SpiralBevel, 30.0}}) {
    const GearPairGeometry bevel = gear_pair_geometry(bevel_spec(type, beta));
    GearPairSpec v;
    v.type = beta == 0.0 ? GearType::Spur : GearType::Helical;
    v.teeth_pinion = 45;
    v.teeth_wheel = 80;
    v.module_m = bevel.normal_module_m;
    v.helix_angle_rad = beta * kDeg;
    v.face_width_m = 30e-3;
    const GearPairGeometry cyl = gear_pair_geometry(v);
    ASSERT_NEAR(cyl.pinion.base_radius_m, bevel.pinion.base_radius_m, 1e-15);
    ASSERT_NEAR(cyl.centre_distance_m, bevel.centre_distance_m, 1e-15);
    const ToothContactOptions o = options(32, 20);
    const Ltca b(bevel, o), c(cyl, o);
    const double torque = 300.0;
    const double cos_d1 = std::cos(bevel.pinion.pitch_cone_angle_rad);
    ASSERT_NEAR(cos_d1, 0.8, 1e-15);
    const ToothContactResult rb = b.contact->solve(torque), rc = c.contact->solve(torque / cos_d1);
    ASSERT_EQ(rb.status, Status::Ok) << rb.message;
    ASSERT_EQ(rc.status, Status::Ok) << rc.message;
    EXPECT_NEAR(rb.force_n, rc.force_n, 1e-12 * rc.force_n);
    for (std::size_t i = 0; i < rc.te_m.size(); ++i) {
      EXPECT_NEAR(rb.te_m[i], rc.te_m[i], 1e-9 * std::abs(rc.te_m[i]));
      EXPECT_NEAR(rb.stiffness_tangent_n_per_m[i], rc.stiffness_tangent_n_per_m[i],
                  1e-9 * rc.stiffness_tangent_n_per_m[i]);
    }
    EXPECT_NEAR(rb.face_load_factor, rc.face_load_factor, 1e-9);
  }
}

// An ease-off symmetric in eta (no bias, no length slope) with H = V = J = 0: the straight bevel
// pair's contact lines run along the face and the uncoupled slices have one compliance over
// the face, so the face load is symmetric about mid face (to round-off).
TEST(BevelContact, SymmetricEaseOffCentresThePattern) {
  const GearPairGeometry g = gear_pair_geometry(bevel_spec(GearType::StraightBevel, 0.0));
  ToothContactOptions o = options(40, 60);
  o.ease_off.profile_crowning_m = 10e-6;
  o.ease_off.length_crowning_m = 20e-6;
  const Ltca l(g, o);
  const ToothContactResult r = l.contact->solve(100.0);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const auto& f = r.face_load_n_per_m;
  const double peak = *std::max_element(f.begin(), f.end());
  for (std::size_t k = 0; k < f.size(); ++k) EXPECT_NEAR(f[k], f[f.size() - 1 - k], 1e-8 * peak);
  // The ends are unloaded: a pattern, not a full-face contact.
  EXPECT_EQ(f.front(), 0.0);
  EXPECT_NEAR(centre(*l.contact, r).eta, 0.0, 1e-9);
}

// Shift of the pattern centre per unit H, J, V (straight bevel): the cone turns the uniform
// normal approach d . n into the lead slope f = (d . n / cos beta_b) b / R_m (docs/theory.md
// (15.21)); with the ease-off C_b eta^2 + (f / 2) eta the centre moves to eta_c = -f / (4 C_b)
// (15.24). Signs (Gleason convention, +H / +J away from the crossing point): d . n =
// -H sin(delta1) sin(alpha_n), -J sin(delta2) sin(alpha_n), +V cos(alpha_n): pinion or wheel
// out of mesh moves the pattern to the heel (eta > 0), +V to the toe. The centre distance
// change H sin(delta1) + J sin(delta2) moves the pattern on the wheel's flank by Delta a /
// sin(alpha_wt) (the involute: T1T2 = sqrt(a^2 - (r_b1 + r_b2)^2)) and leaves it on the
// pinion's. Tolerance: the contact lines run along the face and the slice compliance is the
// same over it, so the load is symmetric about the gap's minimum along each line; 2 % covers
// the slice discretisation (60 slices), the second-order terms of the mounting errors and, on
// the profile, the loaded window's sampling (40 positions) and its edge at the pinion's start of
// active profile, which the centre distance change moves (1.6 % here, the pinion's centre
// moving by 0.001 in xi; at 100 N m instead of 30 N m the window reaches that edge: 5 %).
TEST(BevelContact, PatternShiftPerUnitHvjFollowsTheFirstOrderFormula) {
  const GearPairGeometry g = gear_pair_geometry(bevel_spec(GearType::StraightBevel, 0.0));
  ToothContactOptions o = options(40, 60);
  o.ease_off.profile_crowning_m = 20e-6;
  o.ease_off.length_crowning_m = 20e-6;
  const double torque = 30.0;
  const Ltca l0(g, o);
  const ToothContactResult r0 = l0.contact->solve(torque);
  ASSERT_EQ(r0.status, Status::Ok) << r0.message;
  const Centre c0 = centre(*l0.contact, r0);
  const double an = g.normal_pressure_angle_rad, d1 = g.pinion.pitch_cone_angle_rad,
               d2 = g.wheel.pitch_cone_angle_rad;
  const double b = g.face_width_m, rm = g.mean_cone_distance_m;
  struct Case {
    double h, v, j, dn, da;
  };
  const double e = 0.3e-3;
  for (const Case& k : {Case{e, 0, 0, -e * std::sin(d1) * std::sin(an), e * std::sin(d1)},
                        Case{0, 0, e, -e * std::sin(d2) * std::sin(an), e * std::sin(d2)},
                        Case{0, e / 3, 0, e / 3 * std::cos(an), 0.0}}) {
    ToothContactOptions om = o;
    om.mounting = {k.h, k.v, k.j, 0.0, true};
    const MountingEffect me = mounting_effect(g, om.mounting);
    EXPECT_NEAR(me.normal_approach_m, k.dn, 1e-15);
    EXPECT_NEAR(me.centre_distance_change_m, k.da, 1e-15);
    const Ltca l(g, om);
    const ToothContactResult r = l.contact->solve(torque);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    const Centre c = centre(*l.contact, r);
    const double f = k.dn * b / rm;  // beta_b = 0
    const double eta_c = -f / (4.0 * o.ease_off.length_crowning_m);
    EXPECT_NEAR(c.eta - c0.eta, eta_c, 0.02 * std::abs(eta_c)) << k.h << " " << k.v << " " << k.j;
    EXPECT_EQ(c.eta > c0.eta, k.dn < 0.0);  // the sign: out of mesh -> heel
    const double drho2 = k.da / std::sin(g.working_pressure_angle_rad);
    EXPECT_NEAR(c.rho2 - c0.rho2, drho2, 0.02 * std::abs(drho2) + 1e-7);
    EXPECT_NEAR(c.xi, c0.xi, 0.01);
  }
}

// With bias the face shift drags the pattern along the profile: the centre solves
// [2 C_a, B; B, 2 C_b] (xi, eta) = -(0, f / 2) (15.24). Straight bevel, H only; the profile
// centre of the load over the cycle is the midpoint of the one-base-pitch window around the
// gap's minimum (the pairs change over where their gaps are equal), so it follows xi_c; 5 %
// covers the elastic sharing near the change-overs, which is not exactly symmetric in xi.
TEST(BevelContact, BiasMovesThePatternDiagonally) {
  const GearPairGeometry g = gear_pair_geometry(bevel_spec(GearType::StraightBevel, 0.0));
  ToothContactOptions o = options(80, 60);
  o.ease_off.profile_crowning_m = 20e-6;
  o.ease_off.length_crowning_m = 20e-6;
  o.ease_off.bias_m = 15e-6;
  const double torque = 30.0;
  const Ltca l0(g, o);
  const ToothContactResult r0 = l0.contact->solve(torque);
  ASSERT_EQ(r0.status, Status::Ok) << r0.message;
  const Centre c0 = centre(*l0.contact, r0);
  EXPECT_NEAR(c0.eta, 0.0, 0.01);
  EXPECT_NEAR(c0.xi, 0.0, 0.01);
  ToothContactOptions om = o;
  om.mounting.h_m = 0.4e-3;
  const Ltca l(g, om);
  const ToothContactResult r = l.contact->solve(torque);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const Centre c = centre(*l.contact, r);
  const auto [xi, eta] = ease_off_centre(o.ease_off, 0.0, 0.5 * l.contact->mounting().lead_slope_m);
  EXPECT_GT(eta, 0.1);
  EXPECT_LT(xi, -0.05);  // B > 0: the heel side of the pattern lies towards the pinion root
  EXPECT_NEAR(c.eta - c0.eta, eta, 0.05 * std::abs(eta));
  EXPECT_NEAR(c.xi - c0.xi, xi, 0.05 * std::abs(xi));
}

// Shaft angle error: a turn about the crossing point (the pitch apex), whose lengthwise gap the
// pinion's rotation absorbs (no lead slope); it separates the pair at the mean point by
// Delta Sigma R_m, which moves the pattern on the wheel's flank by Delta Sigma R_m /
// sin(alpha_wt) (straight bevel, tolerance as for H, V, J).
TEST(BevelContact, ShaftAngleErrorSeparatesThePairAtTheMeanPoint) {
  const GearPairGeometry g = gear_pair_geometry(bevel_spec(GearType::StraightBevel, 0.0));
  ToothContactOptions o = options(40, 60);
  o.ease_off.profile_crowning_m = 20e-6;
  o.ease_off.length_crowning_m = 20e-6;
  const Ltca l0(g, o);
  const ToothContactResult r0 = l0.contact->solve(30.0);
  ToothContactOptions om = o;
  om.mounting.shaft_angle_rad = 0.1 * kDeg;
  const Ltca l(g, om);
  EXPECT_EQ(l.contact->mounting().lead_slope_m, 0.0);
  const ToothContactResult r = l.contact->solve(30.0);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const Centre c0 = centre(*l0.contact, r0), c = centre(*l.contact, r);
  const double drho2 =
      om.mounting.shaft_angle_rad * g.mean_cone_distance_m / std::sin(g.working_pressure_angle_rad);
  EXPECT_NEAR(c.rho2 - c0.rho2, drho2, 0.02 * drho2);
  EXPECT_NEAR(c.eta, c0.eta, 1e-6);
}

// Spiral bevel (beta_m = 30 deg, concave pinion flank loaded): H adds the lengthwise component
// of the normal, d . n = -H (sin(delta1) sin(alpha_n) + cos(delta1) cos(alpha_n) sin(beta_m)),
// and the lead slope is taken along the transverse line of action (/ cos beta_b). The virtual
// pair is helical: its contact lines cross the face diagonally, so the load along a line is no
// longer symmetric about the ease-off minimum and the formula is first order in the pattern
// size too: 5 % (measured 1.3 % for H, 3.4 % for Delta Sigma).
TEST(BevelContact, SpiralBevelPatternShiftPerUnitH) {
  const GearPairGeometry g = gear_pair_geometry(bevel_spec(GearType::SpiralBevel, 30.0));
  ToothContactOptions o = options(40, 60);
  o.ease_off.profile_crowning_m = 20e-6;
  o.ease_off.length_crowning_m = 20e-6;
  const double torque = 30.0;
  const Ltca l0(g, o);
  const ToothContactResult r0 = l0.contact->solve(torque);
  ASSERT_EQ(r0.status, Status::Ok) << r0.message;
  ToothContactOptions om = o;
  om.mounting.h_m = 0.2e-3;
  const double an = g.normal_pressure_angle_rad, d1 = g.pinion.pitch_cone_angle_rad;
  const double dn = -om.mounting.h_m * (std::sin(d1) * std::sin(an) +
                                        std::cos(d1) * std::cos(an) * std::sin(30.0 * kDeg));
  const Ltca l(g, om);
  EXPECT_NEAR(l.contact->mounting().normal_approach_m, dn, 1e-15);
  const ToothContactResult r = l.contact->solve(torque);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const double f = dn / std::cos(g.base_helix_angle_rad) * g.face_width_m / g.mean_cone_distance_m;
  const double eta_c = -f / (4.0 * o.ease_off.length_crowning_m);
  const Centre c0 = centre(*l0.contact, r0), c = centre(*l.contact, r);
  EXPECT_NEAR(c.eta - c0.eta, eta_c, 0.05 * eta_c);
  // Shaft angle error: a profile gradient, -dSigma sin(alpha_wt) (n . e_R) / cos(beta_b), which
  // moves the pinion's pattern centre to xi_c = -(gradient g_alpha / 2) / (2 C_a).
  ToothContactOptions os = o;
  os.mounting.shaft_angle_rad = 0.2 * kDeg;
  const Ltca ls(g, os);
  const ToothContactResult rs = ls.contact->solve(torque);
  ASSERT_EQ(rs.status, Status::Ok) << rs.message;
  const Centre cs = centre(*ls.contact, rs);
  const double half = 0.5 * g.path_of_contact_m;
  const double xi_c =
      -ls.contact->mounting().profile_gradient * half / (2.0 * o.ease_off.profile_crowning_m);
  EXPECT_NEAR(cs.xi - c0.xi, xi_c, 0.05 * std::abs(xi_c));
}

// Profile crowning C_a alone (straight bevel): the geometric TE is the lower envelope of the
// parabolas C_a xi^2 of the tooth pairs, one base pitch apart (Delta xi = 2 p_bt / g_alpha);
// its peak-to-peak is reached where two pairs stand symmetric about the middle:
//     TE_pp = C_a (p_bt / g_alpha)^2     (closed form; e.g. D.R. Houser's "crowning parabola",
// and Harris's map at zero load, S.L. Harris, "Dynamic loads on the teeth of spur gears", 1958).
// Sampling: the envelope has a kink at its peak with slope 4 C_a p_bt / g_alpha^2, so N
// positions miss it by at most TE_pp 2 / N (0.5 % at 400). At light load the loaded TE differs
// from the geometric one by less than the largest elastic approach (the TE minus the gap).
TEST(BevelContact, ProfileCrownedTePeakToPeakIsTheParabolaAtLightLoad) {
  const GearPairGeometry g = gear_pair_geometry(bevel_spec(GearType::StraightBevel, 0.0));
  ToothContactOptions o = options(400, 10);
  o.ease_off.profile_crowning_m = 10e-6;
  const Ltca l(g, o);
  const ToothContactResult r = l.contact->solve(1.0);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const double ratio = g.transverse_base_pitch_m / g.path_of_contact_m;
  const double pp = o.ease_off.profile_crowning_m * ratio * ratio;
  auto span = [](const std::vector<double>& v) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return *hi - *lo;
  };
  EXPECT_NEAR(span(r.unloaded_te_m), pp, 2.0 / 400 * pp);
  double elastic = 0.0;
  for (std::size_t i = 0; i < r.te_m.size(); ++i)
    elastic = std::max(elastic, r.te_m[i] - r.unloaded_te_m[i]);
  EXPECT_LT(elastic, 0.05 * pp);  // light load indeed
  EXPECT_NEAR(span(r.te_m), pp, elastic + 2.0 / 400 * pp);
}

// Spiral bevel and hypoid pairs run (helical virtual pairs); the hypoid's force radius is the
// enlarged pinion's r_m1 cos(alpha_t).
TEST(BevelContact, SpiralBevelAndHypoidRun) {
  GearPairSpec s = bevel_spec(GearType::Hypoid, 30.0);
  s.pinion_spiral_angle_rad = 45.0 * kDeg;
  const GearPairGeometry g = gear_pair_geometry(s);
  ToothContactOptions o = options(24, 20);
  o.ease_off.profile_crowning_m = 10e-6;
  o.ease_off.length_crowning_m = 20e-6;
  o.mounting.h_m = 0.1e-3;
  const Ltca l(g, o);
  EXPECT_NEAR(l.contact->force_radius(),
              g.pinion.mean_pitch_radius_m * std::cos(g.transverse_pressure_angle_rad), 1e-15);
  const ToothContactResult r = l.contact->solve(200.0);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_NEAR(r.force_n, 200.0 / l.contact->force_radius(), 1e-9);
}

TEST(BevelContact, BadInputsAreLocated) {
  GearPairSpec cs;
  cs.teeth_pinion = 20;
  cs.teeth_wheel = 40;
  cs.module_m = 3e-3;
  cs.face_width_m = 20e-3;
  const GearPairGeometry cyl = gear_pair_geometry(cs);
  const ToothCompliance teeth(cyl);
  const SliceCompliance slices(teeth, 0.0);
  ToothContactOptions o;
  o.ease_off.profile_crowning_m = 5e-6;
  EXPECT_THROW(ToothContact(cyl, {}, {}, slices, o), InputError);
  o = {};
  o.mounting.h_m = 1e-4;
  EXPECT_THROW(ToothContact(cyl, {}, {}, slices, o), InputError);
  // A centre distance change that pulls the virtual pair out of mesh.
  const GearPairGeometry bevel = gear_pair_geometry(bevel_spec(GearType::StraightBevel, 0.0));
  EXPECT_THROW(virtual_cylindrical_pair(bevel, 3e-3), InputError);
  EXPECT_THROW(virtual_cylindrical_pair(bevel, -20e-3), InputError);
}

}  // namespace
