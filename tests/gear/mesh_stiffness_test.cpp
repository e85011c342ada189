// ISO 6336-1 Method B tooth stiffness and the time-varying mesh stiffness built on it.
#include "geardyn/gear/mesh_stiffness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace {

using namespace geardyn::gear;
constexpr double kDeg = std::numbers::pi / 180.0;

GearPairSpec spur(int z1, int z2, double m, double b) {
  GearPairSpec s;
  s.teeth_pinion = z1;
  s.teeth_wheel = z2;
  s.module_m = m;
  s.face_width_m = b;
  return s;
}

// Published typical values: ISO 6336-1 (and DIN 3990-1, Niemann/Winter, Maschinenelemente II,
// 21.3) give c' ~ 14 N/(mm·µm) and c_gamma ~ 20 N/(mm·µm) for solid steel spur gears cut by the
// standard 20 deg basic rack without profile shift (the Method C values of ISO 6336-1:1996).
// Pair: 30/60 teeth, m = 4 mm, rack h_fP = 1.25 m (C_B = 0.975), x = 0. ISO Method B gives
// c'_th = 1 / q' = 17.63, c' = 0.8 * 0.975 * 17.63 = 13.75; c_gamma_alpha = c'(0.75 eps + 0.25).
// The typical values are quoted to two digits for "average" tooth counts, so the tolerance is
// 10 % (Method B varies by about +-10 % over z = 20..100).
TEST(MeshStiffness, IsoTypicalValuesForStandardSpurGears) {
  const GearPairGeometry g = gear_pair_geometry(spur(30, 60, 4e-3, 40e-3));
  const IsoStiffness s = iso_mesh_stiffness(g);
  EXPECT_NEAR(s.single_stiffness, 14.0, 1.4);
  EXPECT_NEAR(s.mesh_stiffness_alpha, 20.0, 2.0);
  // Exact factors of Method B for this pair.
  EXPECT_NEAR(s.flexibility_q_prime, 0.04723 + 0.15551 / 30 + 0.25791 / 60, 1e-15);
  EXPECT_NEAR(s.basic_rack_factor, 0.975, 1e-15);
  EXPECT_DOUBLE_EQ(s.blank_factor, 1.0);
  EXPECT_DOUBLE_EQ(s.helix_factor, 1.0);
  EXPECT_DOUBLE_EQ(s.material_factor, 1.0);
  EXPECT_NEAR(s.mesh_stiffness_alpha,
              s.single_stiffness * (0.75 * g.transverse_contact_ratio + 0.25), 1e-12);
  // SI: 1 N/(mm·µm) over b = 40 mm is 40 N/µm = 4e7 N/m.
  EXPECT_NEAR(s.mesh_stiffness_n_per_m, s.mesh_stiffness_alpha * 4e7, 1e-3);
}

// Load correction (ISO 6336-1 Method B): below a line load of 100 N/mm, c' is scaled by
// (F_t K_A / b / 100)^0.25. 20 mm face, F_t = 500 N -> 25 N/mm -> factor 0.25^0.25.
TEST(MeshStiffness, IsoLoadCorrectionAndBlankFactor) {
  const GearPairGeometry g = gear_pair_geometry(spur(20, 40, 3e-3, 20e-3));
  IsoStiffnessOptions o;
  const double full = iso_mesh_stiffness(g, o).single_stiffness;
  o.tangential_force_n = 500.0;
  const IsoStiffness low = iso_mesh_stiffness(g, o);
  EXPECT_NEAR(low.load_factor, std::pow(0.25, 0.25), 1e-15);
  EXPECT_NEAR(low.single_stiffness, full * std::pow(0.25, 0.25), 1e-12);
  o.tangential_force_n = 5000.0;  // 250 N/mm: no correction
  EXPECT_DOUBLE_EQ(iso_mesh_stiffness(g, o).load_factor, 1.0);
  // Webbed blank: b_s/b = 0.5, s_R = 3 m_n: C_R = 1 + ln(0.5) / (5 e^{0.6}) < 1.
  IsoStiffnessOptions w;
  w.web_thickness_m = 10e-3;
  w.rim_thickness_m = 9e-3;
  EXPECT_NEAR(iso_mesh_stiffness(g, w).blank_factor, 1.0 + std::log(0.5) / (5 * std::exp(0.6)),
              1e-15);
  w.web_thickness_m = 2e-3;  // b_s/b = 0.1, outside ISO's range: refused, not clamped
  EXPECT_THROW(iso_mesh_stiffness(g, w), geardyn::InputError);
}

// The time-varying curve of a spur pair: zones and mean.
//   double contact for u in [0, eps - 1), single contact for u in [eps - 1, 1)
//   (u = 0: a new pair enters while the previous one is still in contact).
// Oracle 1: the fraction of double-contact samples equals eps_alpha - 1 to one sample (1/n).
// Oracle 2: the mean over a cycle equals ISO's c_gamma_alpha b (by construction of the single-pair
// law, see mesh_stiffness.hpp); sampling a curve with two jumps of 0.75 c' b per cycle at n points
// changes the mean by at most 2 * 0.75 / n of c' b: tolerance 2/n relative.
TEST(MeshStiffness, SpurCurveZonesAndMeanMatchIso) {
  const GearPairGeometry g = gear_pair_geometry(spur(20, 40, 3e-3, 20e-3));
  MeshStiffnessOptions o;
  o.samples = 2000;
  const MeshStiffnessCurve c = time_varying_mesh_stiffness(g, o);
  const double eps = g.transverse_contact_ratio;
  int doubles = 0;
  for (int j = 0; j < o.samples; ++j) {
    const double u = c.mesh_fraction[j];
    const double pairs = c.pairs_in_contact[j];
    EXPECT_EQ(pairs, u < eps - 1 ? 2.0 : 1.0) << "u = " << u;
    doubles += pairs == 2.0 ? 1 : 0;
  }
  EXPECT_NEAR(static_cast<double>(doubles) / o.samples, eps - 1.0, 1.0 / o.samples);
  EXPECT_NEAR(c.double_zone_length_m, (eps - 1.0) * g.transverse_base_pitch_m, 1e-15);
  EXPECT_NEAR(c.mean_stiffness_n_per_m, c.iso.mesh_stiffness_n_per_m,
              2.0 / o.samples * c.iso.mesh_stiffness_n_per_m);
  // Single contact zone: exactly one pair at its full stiffness c' b.
  const int mid = static_cast<int>((0.5 * (eps - 1.0) + 0.5) * o.samples);
  EXPECT_NEAR(c.stiffness_n_per_m[mid], c.iso.single_stiffness_n_per_m,
              1e-12 * c.iso.single_stiffness_n_per_m);
  // Double contact zone: two pairs sharing, 1.75 c' b.
  EXPECT_NEAR(c.stiffness_n_per_m[0], 1.75 * c.iso.single_stiffness_n_per_m,
              1e-12 * c.iso.single_stiffness_n_per_m);
  EXPECT_NEAR(c.pinion_angle_rad[1], 2 * std::numbers::pi / 20 / o.samples, 1e-15);
}

// Helical pair (beta = 20 deg, b = 40 mm, eps_beta ~ 1.3): the contact lines sweep the face, so
// the curve is continuous and far smoother than the spur one, its mean still equals
// c_gamma_alpha b, and the face-width-weighted number of pairs in contact averages eps_alpha
// (every point of the face is in contact over the path g_alpha = eps_alpha p_bt). The helical curve
// has no jumps, so the sampled mean converges like 1/n^2: tolerance 1e-6.
TEST(MeshStiffness, HelicalCurveMeanAndTotalContactRatio) {
  GearPairSpec s = spur(23, 57, 3e-3, 40e-3);
  s.type = GearType::Helical;
  s.helix_angle_rad = 20 * kDeg;
  const GearPairGeometry g = gear_pair_geometry(s);
  MeshStiffnessOptions o;
  o.samples = 1024;
  const MeshStiffnessCurve c = time_varying_mesh_stiffness(g, o);
  EXPECT_NEAR(c.mean_stiffness_n_per_m / c.iso.mesh_stiffness_n_per_m, 1.0, 1e-6);
  double mean_pairs = 0.0, max_jump = 0.0;
  for (int j = 0; j < o.samples; ++j) {
    mean_pairs += c.pairs_in_contact[j] / o.samples;
    const double next = c.stiffness_n_per_m[(j + 1) % o.samples];
    max_jump = std::max(max_jump, std::abs(next - c.stiffness_n_per_m[j]));
  }
  EXPECT_NEAR(mean_pairs, g.transverse_contact_ratio, 1e-6);
  EXPECT_LT(max_jump, 0.01 * c.mean_stiffness_n_per_m);
  // Peak-to-peak well below a spur pair's 0.75 c' b / c_gamma_alpha b ~ 50 %; here about 17 %,
  // set by the varying total length of the contact lines (eps_beta = 1.45 is not an integer).
  EXPECT_LT(c.max_stiffness_n_per_m - c.min_stiffness_n_per_m, 0.25 * c.mean_stiffness_n_per_m);
}

// With an integer overlap ratio the inclined contact lines cover the path of contact uniformly
// at every instant (each path position is crossed by exactly eps_beta lines per base pitch), so
// the mesh stiffness is constant and equals c_gamma_alpha b (the integral of the single-pair law
// over one base pitch, times eps_beta, is the same at every instant). Face width chosen for
// eps_beta = 2 exactly; rounding only: 1e-12.
TEST(MeshStiffness, HelicalIntegerOverlapRatioGivesConstantStiffness) {
  GearPairSpec s = spur(23, 57, 3e-3, 0.0);
  s.type = GearType::Helical;
  s.helix_angle_rad = 20 * kDeg;
  s.face_width_m = 2.0 * std::numbers::pi * 3e-3 / std::sin(s.helix_angle_rad);
  const GearPairGeometry g = gear_pair_geometry(s);
  ASSERT_NEAR(g.overlap_ratio, 2.0, 1e-14);
  const MeshStiffnessCurve c = time_varying_mesh_stiffness(g, {});
  for (double k : c.stiffness_n_per_m)
    EXPECT_NEAR(k, c.iso.mesh_stiffness_n_per_m, 1e-12 * c.iso.mesh_stiffness_n_per_m);
}

// Synthetic STE: e(u) k(u) = F_s with F_s = T1 / r_b1, sample 0 (double contact, stiffest) has
// the smallest STE. docs/theory.md (11.5) inverted.
TEST(MeshStiffness, SyntheticSteInvertsTheStiffness) {
  const GearPairGeometry g = gear_pair_geometry(spur(20, 40, 3e-3, 20e-3));
  const MeshStiffnessCurve c = time_varying_mesh_stiffness(g, {});
  const SyntheticSte e = synthetic_ste(c, g, 100.0);
  EXPECT_NEAR(e.base_radius_m, g.pinion.base_radius_m, 1e-16);
  EXPECT_NEAR(e.static_force_n, 100.0 / (30e-3 * std::cos(20 * kDeg)), 1e-9);
  for (std::size_t j = 0; j < e.ste_m.size(); ++j) {
    EXPECT_NEAR(e.ste_m[j] * c.stiffness_n_per_m[j], e.static_force_n, 1e-9 * e.static_force_n);
    EXPECT_NEAR(e.ste_rad[j] * e.base_radius_m, e.ste_m[j], 1e-20);
  }
  EXPECT_EQ(*std::min_element(e.ste_m.begin(), e.ste_m.end()), e.ste_m.front());
  // Order of magnitude: 3.6 kN on a ~3e8 N/m mesh is about 10 µm.
  EXPECT_GT(e.mean_ste_m, 5e-6);
  EXPECT_LT(e.mean_ste_m, 20e-6);
  const geardyn::Table t = mesh_stiffness_table(c, &e);
  t.validate();
  EXPECT_EQ(t.rows(), c.stiffness_n_per_m.size());
  EXPECT_TRUE(t.has_column("ste_m"));
  EXPECT_THROW(synthetic_ste(c, g, -1.0), geardyn::InputError);
  MeshStiffnessOptions few;
  few.samples = 8;
  EXPECT_THROW(time_varying_mesh_stiffness(g, few), geardyn::InputError);
}

}  // namespace
