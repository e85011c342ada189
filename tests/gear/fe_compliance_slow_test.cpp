// The FE compliance route against the analytic one (gear/fe_compliance.hpp vs
// gear/tooth_compliance.hpp, docs/theory.md §15.8): single-tooth deflection under a line load at
// root, pitch and tip of the active profile, mesh convergence, the segment's boundary, the pair's
// loaded TE and mesh stiffness by both routes, and the decay length of the face influence line
// (the calibration of the analytic route's coupling_length). Minutes: label slow.
//
// Pair: spur 20 / 40, m = 3 mm, alpha = 20 deg, b = 20 mm, steel; FE segments of 7 teeth,
// element size 0.35 m at the loaded tooth, 5 x 15 grid (the figures of docs/validation.md).
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

GearPairGeometry pair_geometry() {
  GearPairSpec s;
  s.teeth_pinion = 20;
  s.teeth_wheel = 40;
  s.module_m = 3e-3;
  s.face_width_m = 20e-3;
  return gear_pair_geometry(s);
}

FeComplianceOptions options(int teeth, double size) {
  FeComplianceOptions o;
  o.segment_teeth = teeth;
  o.mesh_size = size;
  o.profile_points = 5;
  return o;
}

struct Fixture {
  GearPairGeometry g = pair_geometry();
  ToothCompliance teeth{g};
  FeCompliance fe{teeth, options(7, 0.35)};
};

const Fixture& fixture() {
  static const auto f = std::make_unique<Fixture>();
  return *f;
}

double analytic_pinion(const ToothCompliance& t, double s) {
  const PointCompliance c = t.at(s);
  return c.bending_pinion + c.shear_pinion + c.compression_pinion + c.foundation_pinion;
}

// Deflection at mid face per uniform line load over the face (plane strain in the middle of a
// face of 6.7 m).
double fe_line(const ToothInfluence& ti, double s, double b) {
  return ti.at(s, 0.5 * b, s, 0.0, b);
}

// Single pinion tooth under a uniform line load at the start of the active profile (near the
// root), mid path (near the pitch point) and the end (tip), FE vs the analytic potential-energy
// tooth with Sainsot's foundation (D.C.H. Yang, J.Y. Lin 1987; Z. Chen, Y. Shao 2011; P.
// Sainsot, P. Velex, O. Duverger, "Contribution of gear body to tooth deflections - a new
// bidimensional analytical formula", J. Mech. Design 126, 2004).
// Measured (docs/validation.md): FE / analytic = 0.75, 0.76, 0.86. Not "a few per cent": the
// segment is fixed at its cut faces 3.5 pitches from the loaded tooth, a stiffer body than
// Sainsot's full disc (3 teeth: 0.58, 0.63, 0.80 -- the FE compliance grows by 4e-12 m^2/N at
// every radius as the cuts move away, see the next test). The tooth itself agrees better: the
// growth of the compliance from root to tip (bending + shear, the foundation part nearly
// cancels) is within 15 % of the analytic one (measured 0.89). The band asserted: FE below the
// analytic (the stiffer segment) and above 0.65 of it; the growth within 15 %.
TEST(FeComplianceSlow, SingleToothLineLoadAtRootPitchAndTip) {
  const Fixture& f = fixture();
  const double b = f.g.face_width_m, ga = f.g.path_of_contact_m;
  const std::vector<double> s = {0.0, 0.5 * ga, ga};
  std::vector<double> fe, an;
  for (double si : s) {
    fe.push_back(fe_line(f.fe.pinion(), si, b));
    an.push_back(analytic_pinion(f.teeth, si));
    std::printf("s = %.3f mm, r = %.3f mm: FE %.4e, analytic %.4e m^2/N, ratio %.3f\n", si * 1e3,
                f.teeth.pinion_radius(si) * 1e3, fe.back(), an.back(), fe.back() / an.back());
    EXPECT_LT(fe.back(), an.back());
    EXPECT_GT(fe.back(), 0.65 * an.back());
  }
  const double growth_fe = fe[2] - fe[0], growth_an = an[2] - an[0];
  std::printf("root-to-tip growth: FE %.4e, analytic %.4e, ratio %.3f\n", growth_fe, growth_an,
              growth_fe / growth_an);
  EXPECT_NEAR(growth_fe / growth_an, 1.0, 0.15);
}

// Mesh convergence and the segment's boundary. A displacement FE model is too stiff and
// converges from below, for quadratic tets as h^2 in energy: from 0.5 m to 0.35 m at the loaded
// tooth the line-load compliance grows by 3.1 ... 3.6 % (measured), from 0.35 m to 0.25 m by
// 1.7 ... 1.8 % (3 teeth, docs/validation.md): the ratio of the changes 1.95 matches the h^2
// ratio (0.5^2 - 0.35^2) / (0.35^2 - 0.25^2) = 2.1, so the error left at 0.35 m is ~3.4 %, at
// the default 0.25 m ~1.7 % (Richardson). Asserted: growth on refinement, below 5 %. Fixed cut
// faces 1.5 pitches from the loaded tooth (3 teeth) instead of 3.5 (7 teeth) stiffen the body:
// the compliance is lower at every radius.
TEST(FeComplianceSlow, MeshConvergenceAndSegmentBoundary) {
  const Fixture& f = fixture();
  const double b = f.g.face_width_m, ga = f.g.path_of_contact_m;
  const ToothInfluence coarse = fe_tooth_influence(f.teeth, false, options(7, 0.5));
  const ToothInfluence three = fe_tooth_influence(f.teeth, false, options(3, 0.5));
  std::printf("pinion DOFs: 0.35 m / 7 teeth %d, 0.5 m / 7 teeth %d, 0.5 m / 3 teeth %d\n",
              f.fe.pinion().dofs, coarse.dofs, three.dofs);
  for (double si : {0.0, 0.5 * ga, ga}) {
    const double fine = fe_line(f.fe.pinion(), si, b), c = fe_line(coarse, si, b);
    const double t3 = fe_line(three, si, b);
    std::printf("s = %.3f mm: 0.35 m %.4e, 0.5 m %.4e (change %.2f %%), 3 teeth %.4e\n", si * 1e3,
                fine, c, 100.0 * (fine - c) / fine, t3);
    EXPECT_GT(fine, c);
    EXPECT_LT(fine / c - 1.0, 0.05);
    EXPECT_LT(t3, c);
  }
}

// The pair by both routes, unmodified spur pair at 300 N/mm: the mean secant mesh stiffness of
// the FE route is higher than the analytic route's by the single-tooth difference above (the
// pair compliance is the sum of two teeth of FE / analytic ~ 0.75 ... 0.86). Measured: mean
// secant stiffness FE 4.487e8, analytic 3.614e8 N/m (1.24; ISO 6336-1 c_gamma_alpha b 3.748e8),
// mean loaded TE 14.2 vs 17.8 um (0.80). Asserted within 30 % (the single-tooth band); the TE
// is larger in single than in double contact in the FE route too.
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
  EXPECT_GT(kf, ka);
  EXPECT_NEAR(kf / ka, 1.0, 0.30);
  EXPECT_NEAR(mean(rf.te_m) / mean(ra.te_m), 1.0, 0.30);
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

// Calibration of the analytic route's slice coupling (docs/theory.md §15.5): the FE deflection
// of the pair (pinion + wheel, centre line) along the face under a load concentrated at mid face
// (one face hat, 2 grid steps wide) at mid path, fitted by exp(-|y - y0| / lambda) (least
// squares on the logarithm) over 1 m <= |y - y0| <= 2.5 m, where the kernel is past the load's
// own width and clear of the face ends. The Pasternak layer's lambda is the fitted one. Measured:
// lambda = 6.41 mm = 2.14 m = 0.95 tooth heights (2.25 m), residual 0.6 % (docs/validation.md);
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
