// The FE compliance route against the analytic one (gear/fe_compliance.hpp vs
// gear/tooth_compliance.hpp, docs/theory.md §15.8): single-tooth deflection under a line load at
// five radii of the active profile, the same in a thin (plane-stress) gear, the body's boundary
// (segments with fixed and free cut faces bracket the whole gear), mesh convergence, the pair's
// loaded TE and mesh stiffness by both routes, and the decay length of the face influence line
// (the calibration of the analytic route's coupling_length). About a minute: label slow.
//
// Pair: spur 20 / 40, m = 3 mm, alpha = 20 deg, b = 20 mm, steel; FE of the whole gears (every
// tooth, fixed at the bore r_int = r_f / 2), element size 0.35 m at the loaded tooth, 5 x 15
// grid (the figures of docs/validation.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>

#include "geardyn/gear/fe_compliance.hpp"
#include "geardyn/gear/mesh_stiffness.hpp"
#include "geardyn/gear/slice_compliance.hpp"

namespace {

using namespace geardyn::gear;

GearPairGeometry pair_geometry(double face_width = 20e-3) {
  GearPairSpec s;
  s.teeth_pinion = 20;
  s.teeth_wheel = 40;
  s.module_m = 3e-3;
  s.face_width_m = face_width;
  return gear_pair_geometry(s);
}

FeComplianceOptions options(int teeth, double size, bool fixed_cuts = true) {
  FeComplianceOptions o;
  o.segment_teeth = teeth;
  o.fix_cut_faces = fixed_cuts;
  o.mesh_size = size;
  o.profile_points = 5;
  return o;
}

struct Fixture {
  GearPairGeometry g = pair_geometry();
  ToothCompliance teeth{g};
  FeCompliance fe{teeth, options(0, 0.35)};
};

const Fixture& fixture() {
  static const auto f = std::make_unique<Fixture>();
  return *f;
}

double analytic_tooth(const ToothCompliance& t, double s, bool wheel) {
  const PointCompliance c = t.at(s);
  return wheel ? c.bending_wheel + c.shear_wheel + c.compression_wheel + c.foundation_wheel
               : c.bending_pinion + c.shear_pinion + c.compression_pinion + c.foundation_pinion;
}

// Deflection at mid face per uniform line load over the face.
double fe_line(const ToothInfluence& ti, double s, double b) {
  return ti.at(s, 0.5 * b, s, 0.0, b);
}

std::vector<double> five_points(const GearPairGeometry& g) {
  const double ga = g.path_of_contact_m;
  return {0.0, 0.25 * ga, 0.5 * ga, 0.75 * ga, ga};
}

// Single tooth of each gear under a uniform line load at five points of the active profile
// (root ... tip), FE of the whole gear (the body of Sainsot's formula: a full disc fixed at its
// bore) vs the analytic potential-energy tooth with Sainsot's foundation (D.C.H. Yang, J.Y. Lin
// 1987; Z. Chen, Y. Shao 2011; P. Sainsot, P. Velex, O. Duverger, "Contribution of gear body to
// tooth deflections - a new bidimensional analytical formula", J. Mech. Design 126, 2004).
// Measured (docs/validation.md): FE / analytic = 0.85 ... 0.89 (pinion), 0.85 ... 0.91 (wheel);
// with the mesh error left at 0.35 m (2.6 %, next tests) 0.87 ... 0.93. Not "a few per cent":
// with the same body the analytic sum is the outlier, 7 ... 14 % above the FE at every
// radius, and not from the plane-strain assumption (the thin-gear test below gives the same
// ratios in plane stress) nor from the body's boundary (the bracket test): the tooth part alone
// (the growth from root to tip, where the foundation nearly cancels) agrees within 10 %
// (measured 0.91 pinion, 0.93 wheel), the rest is Sainsot's foundation term, about 1.25 times
// the FE body deflection under the tooth (theory §15.8). Asserted: FE / analytic in
// [0.82, 0.96] at every point (measured band widened by the mesh error and 3 % of mesh-generator
// variation), the root-to-tip growth within 12 %.
TEST(FeComplianceSlow, SingleToothLineLoadAtFiveRadii) {
  const Fixture& f = fixture();
  const double b = f.g.face_width_m;
  for (const bool wheel : {false, true}) {
    const ToothInfluence& ti = wheel ? f.fe.wheel() : f.fe.pinion();
    std::vector<double> fe, an;
    for (double si : five_points(f.g)) {
      fe.push_back(fe_line(ti, si, b));
      an.push_back(analytic_tooth(f.teeth, si, wheel));
      const double r = wheel ? f.teeth.wheel_radius(si) : f.teeth.pinion_radius(si);
      std::printf("%s s = %.3f mm, r = %.3f mm: FE %.4e, analytic %.4e m^2/N, ratio %.3f\n",
                  wheel ? "wheel" : "pinion", si * 1e3, r * 1e3, fe.back(), an.back(),
                  fe.back() / an.back());
      EXPECT_GT(fe.back() / an.back(), 0.82);
      EXPECT_LT(fe.back() / an.back(), 0.96);
    }
    // Root to tip: the pinion's root is at s = 0, the wheel's at s = g_alpha.
    const double growth_fe = std::abs(fe.back() - fe.front());
    const double growth_an = std::abs(an.back() - an.front());
    std::printf("root-to-tip growth: FE %.4e, analytic %.4e, ratio %.3f\n", growth_fe, growth_an,
                growth_fe / growth_an);
    EXPECT_NEAR(growth_fe / growth_an, 1.0, 0.12);
  }
}

// Plane strain or plane stress is not the difference. A gear 1 m wide (3 mm) is in plane
// stress; the analytic route in plane stress (ToothComplianceOptions::plane_strain false) then
// describes the same 2D body. The FE / analytic ratio of the thin pinion matches the 6.7 m wide
// one's (plane strain in the analytic tooth) within 3 % at every radius (measured: differences
// of 0.8 ... 2.0 %): the analytic excess is a 2D one.
TEST(FeComplianceSlow, ThinGearInPlaneStressGivesTheSameRatio) {
  const Fixture& f = fixture();
  const GearPairGeometry thin = pair_geometry(3e-3);
  ToothComplianceOptions ps;
  ps.plane_strain = false;
  const ToothCompliance teeth(thin, ps);
  const ToothInfluence t = fe_tooth_influence(teeth, false, options(0, 0.35));
  for (double si : five_points(f.g)) {
    const double wide =
        fe_line(f.fe.pinion(), si, f.g.face_width_m) / analytic_tooth(f.teeth, si, false);
    const double narrow = fe_line(t, si, thin.face_width_m) / analytic_tooth(teeth, si, false);
    std::printf(
        "s = %.3f mm: FE / analytic b = 6.7 m (plane strain) %.3f, b = 1 m (plane "
        "stress) %.3f\n",
        si * 1e3, wide, narrow);
    EXPECT_NEAR(narrow / wide, 1.0, 0.03);
  }
}

// The body's boundary. A segment of n teeth fixed at its two radial cut faces is stiffer than
// the whole gear, and less so as the cuts move away (its compliance grows with n); with free
// cut faces it is softer (the rim ends are loose) and its compliance falls with n: the two
// bracket the whole gear's compliance at every radius (measured at 0.5 m, pinion root / tip:
// fixed 3, 5, 7 teeth 0.66 / 0.89, 0.79 / 0.93, 0.87 / 0.96 of the whole gear; free 2.54 / 1.52,
// 1.43 / 1.13, 1.18 / 1.05). This is why the whole gear is meshed (theory §15.8).
TEST(FeComplianceSlow, SegmentsWithFixedAndFreeCutsBracketTheWholeGear) {
  const Fixture& f = fixture();
  const double b = f.g.face_width_m;
  const ToothInfluence whole = fe_tooth_influence(f.teeth, false, options(0, 0.5));
  std::vector<ToothInfluence> fixed, free;
  for (int n : {3, 5, 7}) {
    fixed.push_back(fe_tooth_influence(f.teeth, false, options(n, 0.5, true)));
    free.push_back(fe_tooth_influence(f.teeth, false, options(n, 0.5, false)));
  }
  for (double si : five_points(f.g)) {
    const double w = fe_line(whole, si, b);
    std::printf(
        "s = %.3f mm: whole %.4e; fixed 3/5/7 %.3f %.3f %.3f, free 3/5/7 %.3f %.3f %.3f "
        "of it\n",
        si * 1e3, w, fe_line(fixed[0], si, b) / w, fe_line(fixed[1], si, b) / w,
        fe_line(fixed[2], si, b) / w, fe_line(free[0], si, b) / w, fe_line(free[1], si, b) / w,
        fe_line(free[2], si, b) / w);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_LT(fe_line(fixed[k], si, b), w);
      EXPECT_GT(fe_line(free[k], si, b), w);
      if (k == 0) continue;
      EXPECT_GT(fe_line(fixed[k], si, b), fe_line(fixed[k - 1], si, b));
      EXPECT_LT(fe_line(free[k], si, b), fe_line(free[k - 1], si, b));
    }
  }
}

// Mesh convergence. A displacement FE model is too stiff and converges from below, for
// quadratic tets as h^2 (to h^3 where the field is smooth) in energy. Whole pinion, element size
// 0.5, 0.35, 0.25 m at the loaded tooth: the line-load compliance grows by 3.0 ... 3.3 % and
// then by 1.2 ... 1.4 % (measured); the ratio of the steps, 2.15 ... 2.65, lies between the h^2
// ratio (0.5^2 - 0.35^2) / (0.35^2 - 0.25^2) = 2.13 and the h^3 one 2.93. Richardson with the
// slower h^2 rate leaves ~1.3 % at 0.25 m and ~2.6 % at 0.35 m (the default). Asserted:
// monotonic growth, each step < 5 %, the ratio of the steps in [1.7, 3.3] (h^2 ... h^3 with
// 20 % for the non-uniform mesh).
TEST(FeComplianceSlow, MeshConvergence) {
  const Fixture& f = fixture();
  const double b = f.g.face_width_m;
  const ToothInfluence coarse = fe_tooth_influence(f.teeth, false, options(0, 0.5));
  const ToothInfluence fine = fe_tooth_influence(f.teeth, false, options(0, 0.25));
  std::printf("pinion DOFs: 0.5 m %d, 0.35 m %d, 0.25 m %d\n", coarse.dofs, f.fe.pinion().dofs,
              fine.dofs);
  for (double si : five_points(f.g)) {
    const double c = fe_line(coarse, si, b), m = fe_line(f.fe.pinion(), si, b);
    const double x = fe_line(fine, si, b);
    const double steps = (m - c) / (x - m);
    std::printf(
        "s = %.3f mm: 0.5 m %.4e, 0.35 m %.4e (+%.2f %%), 0.25 m %.4e (+%.2f %%), ratio "
        "of the steps %.2f\n",
        si * 1e3, c, m, 100.0 * (m / c - 1.0), x, 100.0 * (x / m - 1.0), steps);
    EXPECT_GT(m, c);
    EXPECT_GT(x, m);
    EXPECT_LT(m / c - 1.0, 0.05);
    EXPECT_LT(x / m - 1.0, 0.05);
    EXPECT_GT(steps, 1.7);
    EXPECT_LT(steps, 3.3);
  }
}

// The pair by both routes, unmodified spur pair at 300 N/mm: the pair compliance is the two
// teeth (FE / analytic 0.84 ... 0.91 above) plus the Hertzian approach, the same analytic term
// in both routes, so the FE route's mean secant mesh stiffness is higher and its TE lower by a
// little less than the single-tooth difference. Measured: mean secant stiffness FE 4.081e8,
// analytic 3.614e8 N/m (1.13; ISO 6336-1 c_gamma_alpha b 3.748e8, between them), mean loaded
// TE 15.7 vs 17.8 um (0.88). Asserted: TE ratio in [0.82, 0.96] and stiffness ratio in
// [1.04, 1.22] (the single-tooth band, its inverse); the TE is larger in single than in double
// contact in the FE route too.
TEST(FeComplianceSlow, LoadedTeAndMeshStiffnessOfBothRoutes) {
  const Fixture& f = fixture();
  const SliceCompliance slices(f.teeth, 0.0);
  ToothContactOptions o;
  o.positions = 32;
  o.slices = 20;
  const ToothContact fe_pair(f.g, {}, {}, f.fe, o);
  const ToothContact an_pair(f.g, {}, {}, slices, o);
  const double torque = 300e3 * f.g.face_width_m * f.g.pinion.base_radius_m;
  const ToothContactResult rf = fe_pair.solve(torque), ra = an_pair.solve(torque);
  ASSERT_EQ(rf.status, geardyn::Status::Ok) << rf.message;
  ASSERT_EQ(ra.status, geardyn::Status::Ok) << ra.message;
  auto mean = [](const std::vector<double>& v) {
    return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  };
  const double kf = mean(rf.stiffness_secant_n_per_m), ka = mean(ra.stiffness_secant_n_per_m);
  const double iso = iso_mesh_stiffness(f.g).mesh_stiffness_n_per_m;
  const auto [fmin, fmax] = std::minmax_element(rf.te_m.begin(), rf.te_m.end());
  const auto [amin, amax] = std::minmax_element(ra.te_m.begin(), ra.te_m.end());
  std::printf("mean mesh stiffness: FE %.4e, analytic %.4e, ISO 6336 c_gamma_alpha b %.4e N/m\n",
              kf, ka, iso);
  std::printf("loaded TE: FE mean %.3f um p-p %.3f um; analytic mean %.3f um p-p %.3f um\n",
              mean(rf.te_m) * 1e6, (*fmax - *fmin) * 1e6, mean(ra.te_m) * 1e6,
              (*amax - *amin) * 1e6);
  EXPECT_GT(kf / ka, 1.04);
  EXPECT_LT(kf / ka, 1.22);
  EXPECT_GT(mean(rf.te_m) / mean(ra.te_m), 0.82);
  EXPECT_LT(mean(rf.te_m) / mean(ra.te_m), 0.96);
  // Single contact (pair 0 alone: share 1) has the larger TE in both routes.
  double single_fe = 0, double_fe = 0;
  int ns = 0, nd = 0;
  for (std::size_t p = 0; p < rf.te_m.size(); ++p) {
    const bool alone = rf.pair_load_share.row(static_cast<Eigen::Index>(p)).maxCoeff() > 0.999;
    (alone ? single_fe : double_fe) += rf.te_m[p];
    (alone ? ns : nd) += 1;
  }
  ASSERT_GT(ns, 0);
  ASSERT_GT(nd, 0);
  EXPECT_GT(single_fe / ns, double_fe / nd);
}

// The load distribution of a misaligned pair (spur 20 / 40 at 300 N/mm, f_ma = 20 um in the
// plane of action) by the FE route and by the analytic route with and without the slice
// coupling at the FE-calibrated default of 2.5 m (analyses::kCouplingLengthPerModule, the decay
// length of the next test). A tooth is a plate, not a bed of independent springs: the FE
// concentrates the load towards the closing face end far more than uncoupled slices do (ISO
// 6336-1's linear distribution). Measured (model files, 64 x 40; here 32 x 20): K_Hbeta FE
// 2.12, coupled analytic 2.37, uncoupled 1.57. Asserted: the coupled analytic route within 15 %
// of the FE (the stiffness difference of the previous test, ~13 %, enters K_Hbeta as its square
// root, plus the Pasternak layer's free-end idealisation); the uncoupled one more than 20 %
// below it: the calibrated coupling is the better model of the FE.
TEST(FeComplianceSlow, MisalignedPairLoadConcentrationNeedsTheSliceCoupling) {
  const Fixture& f = fixture();
  const double m_n = f.g.normal_module_m;
  const SliceCompliance coupled(f.teeth, 2.5 * m_n), uncoupled(f.teeth, 0.0);
  ToothContactOptions o;
  o.positions = 32;
  o.slices = 20;
  o.misalignment_in_plane_m = 20e-6;
  const double torque = 300e3 * f.g.face_width_m * f.g.pinion.base_radius_m;
  const ToothContactResult rf = ToothContact(f.g, {}, {}, f.fe, o).solve(torque);
  const ToothContactResult rc = ToothContact(f.g, {}, {}, coupled, o).solve(torque);
  const ToothContactResult ru = ToothContact(f.g, {}, {}, uncoupled, o).solve(torque);
  ASSERT_EQ(rf.status, geardyn::Status::Ok) << rf.message;
  ASSERT_EQ(rc.status, geardyn::Status::Ok) << rc.message;
  ASSERT_EQ(ru.status, geardyn::Status::Ok) << ru.message;
  std::printf("K_Hbeta at f_ma = 20 um: FE %.3f, analytic coupled (2.5 m) %.3f, uncoupled %.3f\n",
              rf.face_load_factor, rc.face_load_factor, ru.face_load_factor);
  EXPECT_NEAR(rc.face_load_factor / rf.face_load_factor, 1.0, 0.15);
  EXPECT_LT(ru.face_load_factor / rf.face_load_factor, 0.8);
}

// Calibration of the analytic route's slice coupling (docs/theory.md §15.5): the FE deflection
// of the pair (pinion + wheel, centre line) along the face under a load concentrated at mid face
// (one face hat, 2 grid steps wide) at mid path, fitted by exp(-|y - y0| / lambda) (least
// squares on the logarithm) over 1 m <= |y - y0| <= 2.5 m, where the kernel is past the load's
// own width and clear of the face ends. The Pasternak layer's lambda is the fitted one. Measured
// (whole gears): lambda = 7.54 mm = 2.51 m = 1.12 tooth heights (2.25 m), residual 0.7 %
// (docs/validation.md; the segments fixed at their cuts gave 2.14 m: a stiffer body);
// asserted: a decay length of the order of the tooth height (0.5 ... 1.5 of it, the range of
// plate-strip decay lengths for a cantilever of that height) and an exponential fit within 5 %.
TEST(FeComplianceSlow, FaceDecayLengthCalibratesCouplingLength) {
  const Fixture& f = fixture();
  const double m = f.g.normal_module_m, ga = f.g.path_of_contact_m;
  const ToothInfluence& p = f.fe.pinion();
  const ToothInfluence& w = f.fe.wheel();
  const std::size_t nf = p.face.size(), mid = nf / 2;
  const double y0 = p.face[mid];
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  std::vector<std::pair<double, double>> pts;
  for (int k = 0; k <= 200; ++k) {
    const double y = p.face.front() + (p.face.back() - p.face.front()) * k / 200.0;
    const double d = std::abs(y - y0);
    if (d < 1.0 * m || d > 2.5 * m) continue;
    const double u = p.at(0.5 * ga, y, 0.5 * ga, p.face[mid - 1], p.face[mid + 1]) +
                     w.at(0.5 * ga, y, 0.5 * ga, w.face[mid - 1], w.face[mid + 1]);
    ASSERT_GT(u, 0.0);
    pts.emplace_back(d, std::log(u));
    sx += d;
    sy += std::log(u);
    sxx += d * d;
    sxy += d * std::log(u);
    ++n;
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double icpt = (sy - slope * sx) / n;
  const double lambda = -1.0 / slope;
  double worst = 0.0;
  for (const auto& [d, lu] : pts)
    worst = std::max(worst, std::abs(std::exp(lu - icpt - slope * d) - 1.0));
  std::printf(
      "face decay length lambda = %.3f mm = %.3f m = %.3f tooth heights; fit residual %.3f\n",
      lambda * 1e3, lambda / m, lambda / (2.25 * m), worst);
  EXPECT_GT(lambda, 0.5 * 2.25 * m);
  EXPECT_LT(lambda, 1.5 * 2.25 * m);
  EXPECT_LT(worst, 0.05);
}

}  // namespace
