// The FE compliance route of the loaded tooth contact analysis (gear/fe_compliance.hpp,
// meshgen/involute_segment.hpp, docs/theory.md §15.8): the generated tooth profile against the
// involute and the rack geometry, the segment mesh's volume, the grid interpolation, bad input.
// The FE-vs-analytic comparisons (minutes) are in fe_compliance_slow_test.cpp.
#include "geardyn/gear/fe_compliance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/meshgen/involute_segment.hpp"
#include "geardyn/solid/assembly.hpp"

namespace {

using namespace geardyn;
using namespace geardyn::gear;
constexpr double kPi = std::numbers::pi;

meshgen::InvoluteSegmentParams segment(int z, double x) {
  meshgen::InvoluteSegmentParams p;
  p.teeth = z;
  p.module = 3e-3;
  p.pressure_angle = 20.0 * kPi / 180.0;
  p.profile_shift = x;
  p.tip_radius = 0.5 * p.module * z + (1.0 + x) * p.module;
  p.bore_radius = 0.25 * p.module * z;
  p.face_width = 6e-3;
  p.tooth_size = 0.75e-3;
  p.body_size = 3e-3;
  p.material.E = 206e9;
  p.material.nu = 0.3;
  p.material.rho = 7850.0;
  return p;
}

double inv(double a) { return std::tan(a) - a; }

// The involute part of the generated flank is the involute: half tooth angle
//   psi(r) = (pi/2 + 2 x tan alpha) / z + inv alpha - inv alpha_r,  cos alpha_r = r_b / r
// (ISO 21771:2007, tooth thickness at any diameter; F.L. Litvin, A. Fuentes, "Gear Geometry and
// Applied Theory", 2004, ch. 10). The rack generates it exactly, so the tolerance is round-off of
// the envelope (1e-9 rad). The root: the first point is the root circle r - (h_fP - x) m, the
// end of the rack-tip flat on it lies at pi/z - e m / r with e = pi/4 - h_fP tan(alpha) -
// rho_fP (1 - sin alpha) / cos(alpha) (the flat's half width rolled on the reference circle).
TEST(InvoluteSegment, GeneratedProfileIsTheInvoluteAboveTheFillet) {
  for (const double x : {0.0, 0.3}) {
    const meshgen::InvoluteSegmentParams p = segment(24, x);
    const auto prof = meshgen::tooth_space_profile(p);
    const double r = 0.5 * p.module * p.teeth, alpha = p.pressure_angle;
    const double rb = r * std::cos(alpha);
    EXPECT_NEAR(prof.front().radius, r - (1.25 - x) * p.module, 1e-12);
    EXPECT_NEAR(prof.front().angle, 0.0, 1e-12);
    const double e =
        kPi / 4 - 1.25 * std::tan(alpha) - 0.38 * (1 - std::sin(alpha)) / std::cos(alpha);
    // Point 4 (kFlatPoints) is the first fillet point: the end of the flat.
    EXPECT_NEAR(kPi / p.teeth - prof[4].angle, kPi / p.teeth - e * p.module / r, 1e-12);
    EXPECT_NEAR(prof[4].radius, prof.front().radius, 1e-12);
    int involute_points = 0;
    for (const auto& q : prof) {
      if (q.radius < rb * 1.0001 || q.radius <= prof[15].radius) continue;  // 15: last fillet point
      const double ar = std::acos(rb / q.radius);
      const double psi = (kPi / 2 + 2 * x * std::tan(alpha)) / p.teeth + inv(alpha) - inv(ar);
      EXPECT_NEAR(kPi / p.teeth - q.angle, psi, 1e-9) << q.radius;
      ++involute_points;
    }
    EXPECT_GT(involute_points, 30);
    EXPECT_NEAR(prof.back().radius, p.tip_radius, 1e-12);
  }
}

// Undercut (ISO 21771: no undercut while (h_fP - rho_fP (1 - sin alpha)) - x m <= r sin^2
// alpha; z = 12 at x = 0 violates it) is refused at the profile shift.
TEST(InvoluteSegment, UndercutIsRefused) {
  meshgen::InvoluteSegmentParams p = segment(12, 0.0);
  try {
    meshgen::tooth_space_profile(p);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("profile_shift"), std::string::npos) << e.what();
  }
  p.profile_shift = 0.4;
  p.tip_radius = 0.5 * p.module * 12 + 1.4 * p.module;
  EXPECT_NO_THROW(meshgen::tooth_space_profile(p));
}

// The meshed segment's volume equals the section area (polygon of the generated profile points
// with the exact tip and bore arcs) times the face width: checks the CAD section, the splines
// and the extrusion. Tolerance 3e-3: the straight-edged tets cut chords on the curved faces, and
// on the concave bore (R = 18 mm, body size h = 3 mm) each chord adds (2/3) h s, sagitta s =
// h^2 / (8 R) = 0.0625 mm, i.e. 0.125 mm^2 per chord, ~5 chords on the 14 mm arc: 0.6 mm^2 of
// the 323 mm^2 section (0.2 %; measured +0.14 %, the convex tip arcs take a little back).
TEST(InvoluteSegment, MeshVolumeEqualsTheSectionArea) {
  const meshgen::InvoluteSegmentParams p = segment(24, 0.0);
  const solid::Mesh mesh = meshgen::involute_segment(p);
  solid::AssemblyOptions ao;
  ao.mass = false;
  const solid::SolidSystem sys = solid::assemble(mesh, ao);
  const double area = meshgen::segment_section_area(p);
  EXPECT_NEAR(sys.volume / (area * p.face_width), 1.0, 6e-3);
  EXPECT_GT(sys.volume, area * p.face_width);  // the concave chords add material
  // The section by hand: 3 teeth on a 45 deg sector of the annulus [bore, r_f] plus three teeth
  // of area ~ (mean thickness ~ pi m / 2) x 2.25 m: within 5 % of the polygon.
  const double rf = 36e-3 - 3.75e-3;
  const double hand = kPi / 8 * (rf * rf - 18e-3 * 18e-3) + 3 * (kPi * 3e-3 / 2) * 2.25 * 3e-3;
  EXPECT_NEAR(area / hand, 1.0, 0.05);
  EXPECT_FALSE(mesh.node_sets.at("bore").empty());
  EXPECT_FALSE(mesh.node_sets.at("cut").empty());
}

// The whole gear (segment_teeth = z): one closed toothed outline around the bore, no cut faces.
// Every tooth is there: each of the z tip arcs carries mesh nodes. Its volume equals the section
// area times the face width as for the segment, with more chord error: ~38 bore chords of
// h = 3 mm add 0.125 mm^2 each (0.2 % of the 2590 mm^2 section) and the concave root fillets
// (rho = 1.14 mm) of the 23 teeth outside the refined box are chorded by 3 mm elements too
// (measured +0.43 % in all; tolerance 6e-3); the section is the annulus [bore, r_f] plus z teeth
// (5 % by hand as above).
TEST(InvoluteSegment, WholeGearHasNoCutFacesAndItsVolume) {
  meshgen::InvoluteSegmentParams p = segment(24, 0.0);
  p.segment_teeth = 24;
  const solid::Mesh mesh = meshgen::involute_segment(p);
  solid::AssemblyOptions ao;
  ao.mass = false;
  const solid::SolidSystem sys = solid::assemble(mesh, ao);
  const double area = meshgen::segment_section_area(p);
  EXPECT_NEAR(sys.volume / (area * p.face_width), 1.0, 6e-3);
  EXPECT_GT(sys.volume, area * p.face_width);  // the concave chords add material
  const double rf = 36e-3 - 3.75e-3;
  const double hand = kPi * (rf * rf - 18e-3 * 18e-3) + 24 * (kPi * 3e-3 / 2) * 2.25 * 3e-3;
  EXPECT_NEAR(area / hand, 1.0, 0.05);
  EXPECT_FALSE(mesh.node_sets.at("bore").empty());
  EXPECT_TRUE(mesh.node_sets.at("cut").empty());
  // Nodes on the tip circle, per tooth (tooth j centred at 2 pi j / z; the one on +x, j = 0).
  std::vector<int> tip_nodes(24, 0);
  for (const auto& x : mesh.coords) {
    if (std::abs(std::hypot(x.x(), x.y()) - p.tip_radius) > 1e-9) continue;
    const double t = std::atan2(x.y(), x.x()) / (2.0 * kPi / 24);
    const long j = std::lround(t);
    if (std::abs(t - static_cast<double>(j)) < 0.25)
      ++tip_nodes[static_cast<std::size_t>((j + 24) % 24)];
  }
  for (int j = 0; j < 24; ++j) EXPECT_GT(tip_nodes[static_cast<std::size_t>(j)], 0) << j;
}

// ToothInfluence::at: a load slice is projected on the face hats by its integral of each hat
// over the hat's own integral, so a uniform line load over the whole face is the sum of the
// hats exactly (here: unit response per hat -> face.size()), and half the face gives the hats'
// share of it; receivers and path positions interpolate linearly.
TEST(FeCompliance, GridInterpolationReproducesUniformLoads) {
  ToothInfluence t;
  t.path = {0.0, 1.0, 2.0};
  t.face = {0.0, 0.5, 1.0, 1.5, 2.0};
  const auto n = static_cast<Eigen::Index>(t.path.size() * t.face.size());
  t.influence = Eigen::MatrixXd::Ones(n, n);
  EXPECT_NEAR(t.at(0.3, 0.7, 1.6, 0.0, 2.0), 5.0, 1e-12);
  // Half the face [0, 1]: hats 0 (all), 1 (all), 2 (half): 1 + 1 + 0.5.
  EXPECT_NEAR(t.at(0.3, 0.7, 1.6, 0.0, 1.0), 2.5, 1e-12);
  // Linear in the receiver path position: influence = receiver p index.
  for (Eigen::Index i = 0; i < n; ++i) t.influence.row(i).setConstant(static_cast<double>(i / 5));
  EXPECT_NEAR(t.at(1.25, 0.7, 0.5, 0.0, 2.0), 5.0 * 1.25, 1e-12);
}

GearPairSpec spur(int z1, int z2) {
  GearPairSpec s;
  s.teeth_pinion = z1;
  s.teeth_wheel = z2;
  s.module_m = 3e-3;
  s.face_width_m = 20e-3;
  s.key_path = "gear_pairs[0]";
  return s;
}

void expect_key(const std::function<void()>& f, const std::string& key) {
  try {
    f();
    FAIL() << "expected InputError at " << key;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

TEST(FeCompliance, BadInputNamesTheKey) {
  GearPairSpec h = spur(20, 40);
  h.type = GearType::Helical;
  h.helix_angle_rad = 0.3;
  const GearPairGeometry gh = gear_pair_geometry(h);
  const ToothCompliance th(gh);
  expect_key([&] { FeCompliance fe(th, {}); }, "gear_pairs[0].contact.compliance");
  const GearPairGeometry g = gear_pair_geometry(spur(20, 40));
  const ToothCompliance t(g);
  FeComplianceOptions o;
  o.segment_teeth = 4;
  expect_key([&] { FeCompliance fe(t, o); }, "gear_pairs[0].contact.fe_teeth");
  o.segment_teeth = -1;
  expect_key([&] { FeCompliance fe(t, o); }, "gear_pairs[0].contact.fe_teeth");
  o = {};
  o.mesh_size = 2.0;
  expect_key([&] { FeCompliance fe(t, o); }, "gear_pairs[0].contact.fe_mesh_size");
  o = {};
  o.profile_points = 2;
  expect_key([&] { FeCompliance fe(t, o); }, "gear_pairs[0].contact.fe_profile_points");
}

}  // namespace
