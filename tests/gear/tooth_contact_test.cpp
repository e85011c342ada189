// The contact solver of the loaded tooth contact analysis (gear/tooth_contact.hpp) with simple
// compliance laws whose answers are known in closed form: a Winkler foundation (each slice a
// spring, no coupling) and an optional power-law approach. These check the kinematics (which
// slices of which pairs are candidates), the gaps of the modifications, the unilateral contact
// and the equilibrium; the physical compliance is tested in tooth_compliance_test.cpp.
#include "geardyn/gear/tooth_contact.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "contact_test_support.hpp"
#include "geardyn/core/error.hpp"

namespace {

using namespace geardyn;
using namespace geardyn::gear;

using geardyn::test::WinklerCompliance;

GearPairGeometry spur_pair(int z1 = 20, int z2 = 40, double b = 20e-3) {
  GearPairSpec s;
  s.teeth_pinion = z1;
  s.teeth_wheel = z2;
  s.module_m = 3e-3;
  s.face_width_m = b;
  return gear_pair_geometry(s);
}

GearPairGeometry helical_pair() {
  GearPairSpec s;
  s.type = GearType::Helical;
  s.teeth_pinion = 23;
  s.teeth_wheel = 47;
  s.module_m = 2.5e-3;
  s.helix_angle_rad = 20.0 * std::numbers::pi / 180.0;
  s.face_width_m = 30e-3;
  return gear_pair_geometry(s);
}

constexpr double kC = 1.0 / 1.4e10;  // 14 N/(mm um) per unit face width: ISO's typical c'
constexpr double kTorque = 200.0;

// Spur, unmodified, Winkler: in single contact one pair carries F, delta = F c / b; in double
// contact two pairs share it equally, delta = F c / (2 b). The fraction of positions in
// double contact is eps_alpha - 1 (to one position).
TEST(ToothContact, UnmodifiedSpurPairWinklerSharesTheLoadExactly) {
  const GearPairGeometry g = spur_pair();
  const WinklerCompliance c(kC);
  ToothContactOptions o;
  o.positions = 200;
  o.slices = 10;
  const ToothContact tc(g, {}, {}, c, o);
  const ToothContactResult r = tc.solve(kTorque);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const double f = kTorque / g.pinion.base_radius_m, b = g.face_width_m;
  EXPECT_DOUBLE_EQ(r.force_n, f);
  int doubles = 0;
  for (std::size_t p = 0; p < r.te_m.size(); ++p) {
    const int pairs = static_cast<int>(std::lround(r.points_in_contact[p])) / o.slices;
    ASSERT_TRUE(pairs == 1 || pairs == 2) << p;
    EXPECT_NEAR(r.te_m[p], f * kC / (pairs * b), 1e-12 * f * kC / b) << p;
    EXPECT_NEAR(r.stiffness_secant_n_per_m[p], pairs * b / kC, 1e-9 * b / kC);
    EXPECT_NEAR(r.stiffness_tangent_n_per_m[p], pairs * b / kC, 1e-9 * b / kC);
    EXPECT_DOUBLE_EQ(r.unloaded_te_m[p], 0.0);
    const double share0 = r.pair_load_share(static_cast<Eigen::Index>(p), 0);
    EXPECT_NEAR(share0, pairs == 2 ? 0.5 : (share0 > 0.5 ? 1.0 : 0.0), 1e-12);
    EXPECT_NEAR(r.pair_load_share.row(static_cast<Eigen::Index>(p)).sum(), 1.0, 1e-12);
    doubles += pairs == 2;
  }
  EXPECT_NEAR(doubles / 200.0, g.transverse_contact_ratio - 1.0, 1.0 / 200.0);
  EXPECT_NEAR(r.face_load_factor, 1.0, 1e-12);
}

// Power-law approach: in single contact c w + alpha w^q = delta with w = F / b.
TEST(ToothContact, NonlinearApproachIsSolvedToTheTolerance) {
  const GearPairGeometry g = spur_pair();
  const double alpha = 2e-9;
  const WinklerCompliance c(kC, alpha, 0.85);
  ToothContactOptions o;
  o.positions = 16;
  o.slices = 8;
  const ToothContactResult r = ToothContact(g, {}, {}, c, o).solve(kTorque);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const double w = r.force_n / g.face_width_m;
  const double single = kC * w + alpha * std::pow(w, 0.85);
  // Position 12 lies in the single-contact zone (u = 0.75; eps_alpha ~ 1.56).
  EXPECT_NEAR(r.te_m[12], single, 1e-9 * single);
  // Tangent stiffness: d delta / dF = (c + alpha q w^(q-1)) / b.
  EXPECT_NEAR(r.stiffness_tangent_n_per_m[12],
              g.face_width_m / (kC + alpha * 0.85 * std::pow(w, -0.15)), 1e-6 * 1.4e10 * 0.02);
}

// Lead crowning C on the pinion, Winkler k = 1/c, one pair: gap g(y) = C z^2, z = 2y/b - 1.
// Full contact (delta >= C): F = k b (delta - mean z^2 C); with N mid-point slices the mean of
// z_k^2 is (N^2 - 1) / (3 N^2) exactly. Partial contact (light load or heavy crowning): the
// continuous solution, by integrating k (delta - C z^2) over |z| < sqrt(delta / C),
// F = (2/3) k b delta^(3/2) / C^(1/2); 400 slices resolve it to the discretisation error of
// the contact edge, O(1/N): 0.5 %.
TEST(ToothContact, LeadCrowningOnAWinklerFoundationMatchesTheClosedForms) {
  const GearPairGeometry g = spur_pair();
  const double b = g.face_width_m;
  const WinklerCompliance c(kC);
  ToothContactOptions o;
  o.positions = 8;
  o.slices = 40;
  FlankModification crowned;
  crowned.lead_crowning_m = 2e-6;
  const ToothContact light(g, crowned, {}, c, o);
  const double n = o.slices;
  // Position 6 (u = 0.75) is in single contact.
  const ToothContactResult r = light.solve(2000.0);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const double f = r.force_n;
  const double full = f * kC / b + 2e-6 * (n * n - 1) / (3 * n * n);
  ASSERT_GE(full, 2e-6);  // the load closes the crowning at the face ends: full contact
  EXPECT_NEAR(r.te_m[6], full, 1e-12 * full);
  // Symmetric modification and no misalignment: symmetric face-load distribution.
  for (int k = 0; k < o.slices; ++k)
    EXPECT_NEAR(r.face_load_n_per_m[static_cast<std::size_t>(k)],
                r.face_load_n_per_m[static_cast<std::size_t>(o.slices - 1 - k)],
                1e-9 * r.face_load_n_per_m[static_cast<std::size_t>(o.slices / 2)]);

  o.slices = 400;
  crowned.lead_crowning_m = 40e-6;
  const ToothContactResult p = ToothContact(g, crowned, {}, c, o).solve(200.0);
  ASSERT_EQ(p.status, Status::Ok) << p.message;
  const double delta = std::pow(1.5 * p.force_n * kC / b * std::sqrt(40e-6), 2.0 / 3.0);
  ASSERT_LT(delta, 40e-6);  // partial contact
  EXPECT_NEAR(p.te_m[6], delta, 5e-3 * delta);
  EXPECT_LT(p.points_in_contact[6], 400);
}

// Misalignment on a linear foundation: ISO 6336-1:2019 6.4 (Method C, eq. 41-42) derives
// K_Hbeta = 1 + F_beta_y c_gamma_beta / (2 F_m / b) for contact over the full face width from a
// linear load distribution on a foundation of stiffness c_gamma_beta. With Winkler slices that
// is exact once c_gamma_beta is the mean effective mesh stiffness per unit face width over the
// cycle (the mean tangent stiffness / b: the secant one also contains the misalignment gap).
// Contact stays full width at every position (checked), so the only difference is round-off.
TEST(ToothContact, MisalignedSpurPairFaceLoadFactorEqualsIsoForALinearFoundation) {
  const GearPairGeometry g = spur_pair();
  const WinklerCompliance c(kC);
  ToothContactOptions o;
  o.positions = 100;
  o.slices = 50;
  o.misalignment_in_plane_m = 5e-6;
  const ToothContactResult r = ToothContact(g, {}, {}, c, o).solve(kTorque);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  for (std::size_t p = 0; p < r.te_m.size(); ++p)
    ASSERT_EQ(std::lround(r.points_in_contact[p]) % o.slices, 0) << "partial contact at " << p;
  const double b = g.face_width_m, fm_b = r.force_n / b;
  const double cgb =
      std::accumulate(r.stiffness_tangent_n_per_m.begin(), r.stiffness_tangent_n_per_m.end(), 0.0) /
      static_cast<double>(r.te_m.size()) / b;
  // Linear distribution sampled at slice centres: max is at y = b - dy/2, i.e. the ISO value
  // with F_beta_y reduced by (1 - 1/N).
  const double iso = 1.0 + 5e-6 * (1.0 - 1.0 / o.slices) * cgb / (2.0 * fm_b);
  EXPECT_NEAR(r.face_load_factor, iso, 1e-9);
  EXPECT_GT(r.face_load_factor, 1.1);
  // The load is higher at y = 0 (the gap opens towards y = b).
  EXPECT_GT(r.face_load_n_per_m.front(), r.face_load_n_per_m.back());
}

// Stiff-tooth limit: with a negligible compliance the loaded TE is the geometric TE of the
// modifications, min over the candidate points of the gap. c = 1e-16 m^2/N (7e5 times stiffer
// than steel teeth) leaves an elastic approach of c F / b ~ 6e-11 m next to gaps of micrometres.
TEST(ToothContact, StiffTeethGiveTheGeometricTransmissionErrorOfTheModifications) {
  const GearPairGeometry g = spur_pair();
  const WinklerCompliance c(1e-16);
  FlankModification tip;
  tip.tip_relief_m = 10e-6;
  tip.tip_relief_start_radius_m = g.pinion.pitch_radius_m + 0.6 * g.normal_module_m;
  tip.profile_crowning_m = 2e-6;
  FlankModification wheel_tip = tip;
  wheel_tip.tip_relief_start_radius_m = g.wheel.pitch_radius_m + 0.6 * g.normal_module_m;
  ToothContactOptions o;
  o.positions = 64;
  o.slices = 4;
  const ToothContactResult r = ToothContact(g, tip, wheel_tip, c, o).solve(kTorque);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  double range = 0.0;
  for (std::size_t p = 0; p < r.te_m.size(); ++p) {
    EXPECT_NEAR(r.te_m[p], r.unloaded_te_m[p], 1e-10) << p;
    range = std::max(range, r.unloaded_te_m[p]);
  }
  EXPECT_GT(range, 1e-6);  // the relief shows in the TE
}

// A pitch deviation e on one pinion tooth: in single contact that tooth's pair needs e less
// approach, delta = F c / b - e; the TE repeats with the hunting period lcm(z1, z2).
TEST(ToothContact, PitchDeviationShiftsTheTeOverTheHuntingPeriod) {
  const GearPairGeometry g = spur_pair(20, 30);
  const WinklerCompliance c(kC);
  FlankModification pitch;
  pitch.pitch_deviation_m.assign(20, 0.0);
  pitch.pitch_deviation_m[3] = 1e-6;
  ToothContactOptions o;
  o.positions = 16;
  o.slices = 2;
  const ToothContact tc(g, pitch, {}, c, o);
  EXPECT_EQ(tc.cycles(), 60);
  const ToothContactResult r = tc.solve(kTorque);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const double single = r.force_n * kC / g.face_width_m;
  // Cycle 3 (tooth 3 enters at u = 0 and is alone at u = 0.8): position 3 * 16 + 13.
  EXPECT_NEAR(r.te_m[3 * 16 + 13], single - 1e-6, 1e-12);
  EXPECT_NEAR(r.te_m[2 * 16 + 13], single, 1e-12);
  EXPECT_NEAR(r.te_m[23 * 16 + 13], single - 1e-6, 1e-12);  // the same tooth, one turn later
  // Double contact where the deviation exceeds the elastic approach: the proud tooth carries all.
  pitch.pitch_deviation_m[3] = 50e-6;
  const ToothContactResult big = ToothContact(g, pitch, {}, c, o).solve(kTorque);
  ASSERT_EQ(big.status, Status::Ok) << big.message;
  EXPECT_NEAR(big.pair_load_share(3 * 16 + 1, 0), 1.0, 1e-12);
  EXPECT_NEAR(big.pair_load_share(3 * 16 + 1, 1), 0.0, 1e-12);
}

// Helical pair: contact lines inclined by beta_b; the candidate count per position follows the
// total contact ratio, and with Winkler slices every loaded slice carries the same line load.
TEST(ToothContact, HelicalContactLinesFollowTheTotalContactRatio) {
  const GearPairGeometry g = helical_pair();
  const WinklerCompliance c(kC);
  ToothContactOptions o;
  o.positions = 64;
  o.slices = 60;
  const ToothContactResult r = ToothContact(g, {}, {}, c, o).solve(kTorque);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const double mean_points =
      std::accumulate(r.points_in_contact.begin(), r.points_in_contact.end(), 0.0) /
      static_cast<double>(r.points_in_contact.size());
  // Mean contact length / b = eps_gamma... in slices: eps_alpha slices per face slice.
  EXPECT_NEAR(mean_points / o.slices, g.transverse_contact_ratio, 0.05);
  for (std::size_t p = 0; p < r.te_m.size(); ++p) {
    const double w = r.force_n / (r.points_in_contact[p] * g.face_width_m / o.slices);
    EXPECT_NEAR(r.max_line_load_n_per_m[p], w, 1e-9 * w);
  }
  EXPECT_NEAR(r.face_load_factor, 1.0, 0.05);
}

TEST(ToothContact, BadInputsAreLocated) {
  const GearPairGeometry g = spur_pair();
  const WinklerCompliance c(kC);
  FlankModification m;
  m.tip_relief_m = 5e-6;
  m.tip_relief_start_radius_m = 0.5 * g.pinion.base_radius_m;
  EXPECT_THROW(ToothContact(g, m, {}, c), InputError);
  m = {};
  m.tip_relief_m = 5e-3;  // larger than the tooth
  m.tip_relief_start_radius_m = g.pinion.pitch_radius_m;
  EXPECT_THROW(ToothContact(g, m, {}, c), InputError);
  m = {};
  m.pitch_deviation_m.assign(7, 0.0);
  EXPECT_THROW(ToothContact(g, m, {}, c), InputError);
  ToothContactOptions o;
  o.slices = 0;
  EXPECT_THROW(ToothContact(g, {}, {}, c, o), InputError);
  EXPECT_THROW(ToothContact(g, {}, {}, c).solve(-1.0), InputError);
}

TEST(ToothContact, MeshOrderAmplitudesOfASampledCosine) {
  std::vector<double> v(3 * 32);
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = 1.0 + 0.5 * std::cos(2 * std::numbers::pi * 2 * i / 32.0 + 0.3);
  const auto a = mesh_order_amplitudes(v, 3, 4);
  EXPECT_NEAR(a[0], 0.0, 1e-14);
  EXPECT_NEAR(a[1], 0.5, 1e-14);
  EXPECT_NEAR(a[2], 0.0, 1e-14);
}

}  // namespace
