// The stability scan of the steady-state analyses (analyses/stability_check) through the
// projected quadratic solver (eig/projected_quadratic, issue 19), and its verdict on undamped
// gyroscopic rotors.
//
// An undamped gyroscopic rotor, M q'' + W G q' + K q = 0 with M, K symmetric positive definite
// and G skew-symmetric, is stable at every speed: its eigenvalues are purely imaginary (the
// energy q'^T M q' + q^T K q is conserved since q'^T G q' = 0). Source: G. Genta, Dynamics of
// Rotating Systems, Springer 2005, sec. 4.4; M. I. Friswell, J. E. T. Penny, S. D. Garvey,
// A. W. Lees, Dynamics of Rotating Machines, Cambridge University Press 2010, sec. 3.5.
// The rotor is the ROSS comparison rotor (bench/ross/README.md) with undamped bearings.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/stability_check.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/assembly/system_pencil.hpp"
#include "geardyn/eig/quadratic_eigen.hpp"
#include "support/rotor_models.hpp"

namespace geardyn::analyses {
namespace {

constexpr double kRadPerRpm = 2.0 * 3.14159265358979323846 / 60.0;

// The ROSS comparison rotor of bench/ross/geardyn_models.py with N elements; bearing damping c
// (0: undamped, the Campbell case of the comparison); `extra`: more bearing keys.
std::string ross_rotor(int n, double c, const std::string& extra = "") {
  std::string text = fmt::format(
      "version = 1\ntitle = \"ROSS comparison rotor\"\n"
      "[[materials]]\nname = \"steel\"\nyoungs_modulus = 211e9\nshear_modulus = 81.2e9\n"
      "density = 7810\n"
      "[[shafts]]\nname = \"shaft\"\nmaterial = \"steel\"\naxis = [0, 0, 1]\n"
      "  [[shafts.elements]]\n  length = 1.5\n  outer_diameter = 0.05\n  divisions = {}\n",
      n);
  const int nodes[2] = {n / 3, 2 * n / 3};
  const double od[2] = {0.28, 0.35};
  for (int d = 0; d < 2; ++d)
    text += fmt::format(
        "[[disks]]\nname = \"disk{}\"\nnode = \"shaft.{}\"\nouter_diameter = {}\n"
        "inner_diameter = 0.05\nthickness = 0.07\nmaterial = \"steel\"\n",
        d, nodes[d], od[d]);
  for (int b = 0; b < 2; ++b)
    text += fmt::format(
        "[[bearings]]\nname = \"b{}\"\nnode = \"shaft.{}\"\nkxx = 1e6\nkyy = 1e6\n"
        "cxx = {}\ncyy = {}\n{}",
        b, b == 0 ? 0 : n, c, c, extra);
  return text;
}

std::vector<double> speeds(int count, double stop_rpm) {
  std::vector<double> w;
  for (int i = 0; i < count; ++i)
    w.push_back(10.0 + (stop_rpm * kRadPerRpm - 10.0) * i / (count - 1));
  return w;
}

TEST(StabilityProjection, UndampedRossRotorIsStableAtEverySpeed) {
  // 48 elements (294 DOFs), 21 speeds to 4000 rpm, the band of an unbalance analysis (1 x the
  // top speed). Before the backward-error rule the double roots at 0 of the free axial and
  // torsional motion, split by round-off into Re(lambda) ~ 0.01-0.04 rad/s (sqrt(eta ||K|| /
  // ||M||)), exceeded 1e-6 x the highest frequency checked and made the rotor "unstable".
  const model::Model m = parse_model(ross_rotor(48, 0.0), "ross_48.toml");
  const fe::LinearSystem system = assembly::build_system(m);
  const std::vector<double> w = speeds(21, 4000.0);
  const StabilityScan scan = scan_stability(system, w, w.back());
  EXPECT_TRUE(scan.all_stable()) << stability_note(scan);
  EXPECT_TRUE(unstable_message(scan).empty());
  // Every speed is solved, by the projection or (where it cannot certify the defective roots at
  // 0 of the free axial and torsional motion) by the full solver; a projection given up after
  // two failures in a row is stated in the note.
  EXPECT_EQ(scan.projected_solves + scan.projection_fallbacks, scan.n_solves);
  if (scan.projection_given_up) {
    EXPECT_NE(stability_note(scan).find("given up"), std::string::npos);
  }
  for (const auto& s : scan.solves) {
    EXPECT_TRUE(s.unstable.empty()) << s.speed;
    // The exact elastic eigenvalues are imaginary: the damping ratios computed are round-off,
    // 1e-7 at most in the scan that exposed the bug (backward error ~1e-14 over a conditioning
    // ~1e7 of the highest modes checked); 1e-6 is the growth tolerance of the verdict.
    EXPECT_LT(std::abs(s.least_damped.damping_ratio), 1e-6) << s.speed;
  }
}

TEST(StabilityProjection, RoundOffGrowthIsNotCertifiedButRealGrowthIs) {
  // The pencil P(lambda) = lambda^2 M + lambda W G + K of the undamped ROSS rotor at 4000 rpm:
  // its computed eigenpairs moved onto the imaginary axis keep the backward error of the solve
  // (not certified growing, whatever the sign of Re(lambda) the solver returned; the rigid
  // roots at 0 come back as +-0.0157 rad/s, the elastic ones with |Re| up to 2e-5 rad/s).
  const model::Model m = parse_model(ross_rotor(48, 0.0), "ross_48.toml");
  const fe::LinearSystem system = assembly::build_system(m);
  const double speed = 4000.0 * kRadPerRpm;
  const eig::QuadraticPencil pencil = assembly::pencil_at(system, speed);
  eig::QuadraticEigenOptions qo;
  qo.n_modes = kMinModes;
  const eig::QuadraticEigenResult r = eig::solve_quadratic(pencil, qo);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  for (Eigen::Index j = 0; j < r.eigenvalues.size(); ++j) {
    const std::complex<double> l = r.eigenvalues[j];
    const Eigen::VectorXcd x = r.eigenvectors.col(j);
    EXPECT_FALSE(certified_growing(pencil, l, x, r.residuals[j])) << l;
  }
}

// Projected and full scans give the same verdicts, mode counts and eigenvalues; the projection
// certified at least one speed.
void expect_same_scans(const fe::LinearSystem& system, const std::vector<double>& w,
                       double band_top) {
  const StabilityScan projected = scan_stability(system, w, band_top, true);
  const StabilityScan full = scan_stability(system, w, band_top, false);
  EXPECT_GT(projected.projected_solves, 0) << stability_note(projected);
  EXPECT_EQ(full.projected_solves, 0);
  ASSERT_EQ(projected.solves.size(), full.solves.size());
  EXPECT_EQ(projected.stable, full.stable);
  for (std::size_t k = 0; k < full.solves.size(); ++k) {
    const StabilityAtSpeed &p = projected.solves[k], &f = full.solves[k];
    EXPECT_EQ(p.stable, f.stable) << f.speed;
    EXPECT_EQ(p.modes_checked, f.modes_checked) << f.speed;
    // Every eigenvalue of the full solve has a projected one within 1e-6 relative. The full
    // (Arnoldi) solver's backward errors reach 1e-10 on these meshes, where ||K|| / ||M|| is far
    // above the frequencies checked: its high modes carry relative errors of a few 1e-7
    // (measured: 2.3e-7 at 5800 rad/s, and damping ratios of -1.6e-8 for modes the projection,
    // certified to a relative correction of 1e-6, gives at -2.6e-13); 1e-6 is four times that.
    for (const std::complex<double> lf : f.eigenvalues) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const std::complex<double> lp : p.eigenvalues)
        nearest = std::min(nearest, std::abs(lp - lf));
      EXPECT_LE(nearest, 1e-6 * std::max(std::abs(lf), 1.0)) << f.speed << " rad/s: " << lf;
    }
    // The least-damped mode where it is not round-off (an unstable or damped mode): to 1e-8.
    if (std::abs(f.least_damped.damping_ratio) > 1e-6) {
      EXPECT_NEAR(p.least_damped.damping_ratio, f.least_damped.damping_ratio, 1e-8) << f.speed;
    }
  }
}

// Axial and torsional restraint at both bearings: every root elastic. (With free axial and
// torsional motion the double roots at 0 are defective, their Ritz vectors converge too slowly
// for the projection to certify them, and the scan gives it up: see the first test.)
const std::string kRestrained = "kzz = 1e6\nktzz = 1e3\n";

TEST(StabilityProjection, ProjectedAndFullScansAgreeOn6006Dofs) {
  // The ROSS rotor of the unbalance comparison (c = 100 N s/m) at 1000 elements, 6006 DOFs;
  // 3 speeds to keep the test short (the full solver costs ~1 s per speed here). Stable.
  const model::Model m = parse_model(ross_rotor(1000, 100.0, kRestrained), "ross_1000.toml");
  const fe::LinearSystem system = assembly::build_system(m);
  ASSERT_EQ(system.size(), 6006);
  const std::vector<double> w = speeds(3, 4000.0);
  expect_same_scans(system, w, w.back());
  EXPECT_TRUE(scan_stability(system, w, w.back()).all_stable());
}

TEST(StabilityProjection, ProjectedScanFindsCrossCoupledInstability) {
  // 48 elements, bearings c = 500 N s/m with kxy = -kyx = 2e5 N/m: the forward whirl of the
  // first mode is destabilised (Friswell et al. 2010, sec. 3.8; damping ratio about -0.03);
  // both scans must say so at the same speeds with the same least-damped mode.
  const model::Model m = parse_model(ross_rotor(48, 500.0, kRestrained + "kxy = 2e5\nkyx = -2e5\n"),
                                     "ross_48_kxy.toml");
  const fe::LinearSystem system = assembly::build_system(m);
  const std::vector<double> w = speeds(5, 4000.0);
  expect_same_scans(system, w, w.back());
  const StabilityScan scan = scan_stability(system, w, w.back());
  EXPECT_FALSE(scan.all_stable());
  EXPECT_NE(unstable_message(scan).find("damping ratio -"), std::string::npos);
}

}  // namespace
}  // namespace geardyn::analyses
