// Validation of the stability check of the steady-state analyses (analyses/stability_check).
//
// Jeffcott rotor with cross-coupled stiffness: a point mass m on an isotropic support k with
// viscous damping c and cross-coupled stiffness kxy = q, kyx = -q. In z = x + i y,
//   m z'' + c z' + (k - i q) z = 0,
// and the conjugate equation for conj(z), so the eigenvalues are the roots of
//   m s^2 + c s + k -+ i q = 0,   s = (-c +- sqrt(c^2 - 4 m (k -+ i q))) / (2 m).
// A root crosses the imaginary axis (s = i W) when W^2 = k / m and c W = q: the rotor is
// unstable exactly when q > c w_n, w_n = sqrt(k / m).
// Source: M. I. Friswell, J. E. T. Penny, S. D. Garvey, A. W. Lees, Dynamics of Rotating
// Machines, Cambridge University Press 2010, sec. 3.8 (instability from cross-coupled bearing
// stiffness); G. Genta, Dynamics of Rotating Systems, Springer 2005, sec. 4.6.
#include "geardyn/analyses/stability_check.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/unbalance.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/eig/quadratic_eigen.hpp"
#include "harmonic_test_support.hpp"
#include "support/rotor_models.hpp"

namespace geardyn::analyses {
namespace {

using namespace geardyn::harmonic_test;
namespace fs = std::filesystem;

const Column* find_column(const Table& t, const std::string& name) {
  for (const auto& c : t.columns)
    if (c.name == name) return &c;
  return nullptr;
}

constexpr double kMass = 10.0, kStiffness = 1e6, kZeta = 0.02, kMe = 1e-4;
double damping() { return 2.0 * kZeta * std::sqrt(kStiffness * kMass); }
double natural() { return std::sqrt(kStiffness / kMass); }
double threshold() { return damping() * natural(); }  // q at the onset, 2.529822e4 N/m

model::Model cross_coupled(double q) {
  model::Model m = jeffcott(kMass, kStiffness, kStiffness, damping(), kMe);
  m.bearings[0].stiffness[0][1] = q;   // kxy: force at x from motion in y
  m.bearings[0].stiffness[0][6] = -q;  // kyx
  return m;
}

// The two roots with Im > 0 of m s^2 + c s + k -+ i q = 0 (one per equation).
std::vector<Complex> closed_form_roots(double q) {
  std::vector<Complex> roots;
  for (double sign : {1.0, -1.0}) {
    const Complex root =
        std::sqrt(Complex(damping() * damping()) - 4.0 * kMass * Complex(kStiffness, -sign * q));
    for (const Complex r :
         {(-damping() + root) / (2.0 * kMass), (-damping() - root) / (2.0 * kMass)})
      if (r.imag() > 0.0) roots.push_back(r);
  }
  std::sort(roots.begin(), roots.end(), [](Complex a, Complex b) { return a.real() < b.real(); });
  return roots;
}

TEST(StabilityCheck, JeffcottEigenvaluesMatchTheClosedForm) {
  const double q = 1.3 * threshold();
  const model::Model m = cross_coupled(q);
  const fe::LinearSystem s = fe::assemble(m);
  const StabilityAtSpeed v = check_stability(s, 100.0, natural());
  ASSERT_EQ(v.modes_checked, 2);  // the 2-DOF system has two modes (one per whirl direction)
  const std::vector<Complex> ref = closed_form_roots(q);
  ASSERT_EQ(ref.size(), 2u);
  // The growing root: s = i W + g with g > 0; its damping ratio from the closed form.
  ASSERT_EQ(v.unstable.size(), 1u);
  const Complex l = v.unstable[0].eigenvalue;
  // A dense 4x4 state-space eigen-solve: round-off only (backward error ~1e-16, the roots are
  // simple and well separated, condition < 1e2): 1e-10 relative leaves margin.
  EXPECT_LE(std::abs(l - ref[1]), 1e-10 * std::abs(ref[1]));
  EXPECT_NEAR(v.unstable[0].damping_ratio, -ref[1].real() / std::abs(ref[1]), 1e-10);
  EXPECT_LT(v.unstable[0].damping_ratio, 0.0);
  EXPECT_NEAR(v.least_damped.damping_ratio, v.unstable[0].damping_ratio, 1e-15);
}

TEST(StabilityCheck, VerdictOnBothSidesOfTheAnalyticThreshold) {
  // 1 % either side of q = c w_n: the growth rate there is about +-0.01 c / (2 m) = 1e-3 of
  // w_n (the root moves by q / (2 m w_n) per unit q), far above the verdict tolerance 1e-6 w_n.
  for (double factor : {0.0, 0.5, 0.99, 1.01, 2.0}) {
    const fe::LinearSystem s = fe::assemble(cross_coupled(factor * threshold()));
    const StabilityAtSpeed v = check_stability(s, 300.0, natural());
    EXPECT_EQ(v.stable, factor < 1.0) << "q / (c w_n) = " << factor;
    EXPECT_EQ(v.solver_status, Status::Ok);
    const double zeta_ref = -closed_form_roots(factor * threshold())[1].real() /
                            std::abs(closed_form_roots(factor * threshold())[1]);
    EXPECT_NEAR(v.least_damped.damping_ratio, zeta_ref, 1e-10) << factor;
  }
}

UnbalanceSettings speed_list(std::vector<double> speeds) {
  UnbalanceSettings s;
  s.speeds = std::move(speeds);
  return s;
}

TEST(StabilityCheck, UnbalanceOfAnUnstableRotorIsUnstableWithModeFrequencyAndSpeed) {
  const double q = 1.5 * threshold();
  const model::Model m = cross_coupled(q);
  const fe::LinearSystem s = fe::assemble(m);
  const UnbalanceResult r =
      run_unbalance(m, speed_list({100.0, 200.0, 400.0}), Context("unbalance").with_system(&s));
  EXPECT_EQ(r.status, Status::Unstable);
  EXPECT_NE(r.message.find("mode 1"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("Hz"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("damping ratio -"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("954.93 to 3819.72 rpm"), std::string::npos) << r.message;
  const AnalysisOutput out = unbalance_output(m, speed_list({100.0, 200.0, 400.0}), r,
                                              Context("unbalance").with_system(&s));
  EXPECT_EQ(out.status, Status::Unstable);
  const Column* stable = find_column(out.tables[0], "stable");
  ASSERT_NE(stable, nullptr);
  for (const auto& v : stable->texts) EXPECT_EQ(v, "no");
  EXPECT_NE(out.plots[0].traces.back().name.find("unstable"), std::string::npos);
  EXPECT_EQ(out.plots[0].traces.back().x.size(), 2u * 3u);  // two sensors x three speeds
  EXPECT_NE(find_column(out.tables[1], "stable"), nullptr);

  // Below the threshold: ok, every speed stable.
  const model::Model m2 = cross_coupled(0.8 * threshold());
  const fe::LinearSystem s2 = fe::assemble(m2);
  const UnbalanceResult r2 =
      run_unbalance(m2, speed_list({100.0, 200.0, 400.0}), Context("unbalance").with_system(&s2));
  EXPECT_EQ(r2.status, Status::Ok) << r2.message;
  EXPECT_TRUE(r2.stability.all_stable());
}

TEST(StabilityCheck, OnsetSpeedOfASpeedDependentCrossCouplingIsRootRefined) {
  // kxy = -kyx = q(W), linear from 0.5 q* at W = 0 to 1.5 q* at W = 1000 rad/s (q* = c w_n):
  // the onset is exactly W* = 500 rad/s. 101 speeds: more than the sampled 41, so the list
  // verdicts around the onset come from the bisection on the list and the onset from the
  // bisection on the speed (to 1e-4 relative).
  model::Model m = cross_coupled(0.0);
  model::Bearing& b = m.bearings[0];
  b.speeds = {0.0, 1000.0};
  b.stiffness = {b.stiffness[0], b.stiffness[0]};
  b.damping = {b.damping[0], b.damping[0]};
  b.stiffness[0][1] = 0.5 * threshold();
  b.stiffness[0][6] = -0.5 * threshold();
  b.stiffness[1][1] = 1.5 * threshold();
  b.stiffness[1][6] = -1.5 * threshold();
  const fe::LinearSystem s = fe::assemble(m);
  std::vector<double> W;
  for (int k = 0; k <= 100; ++k) W.push_back(10.0 + 9.7 * k);
  std::reverse(W.begin(), W.end());  // any order
  const StabilityScan scan = scan_stability(s, W, natural());
  EXPECT_TRUE(scan.subsampled);
  EXPECT_LT(scan.n_solves, 70);
  for (std::size_t i = 0; i < W.size(); ++i) EXPECT_EQ(scan.stable[i], W[i] < 500.0) << W[i];
  ASSERT_EQ(scan.changes.size(), 1u);
  EXPECT_FALSE(scan.changes[0].stable_above);
  // Bisection to 1e-4 relative of the bracket's upper end; the verdicts themselves are exact.
  EXPECT_NEAR(scan.changes[0].speed, 500.0, 1e-4 * 505.0);
}

TEST(StabilityCheck, HarmonicOfAnUnstableRotorIsUnstableAndMarksTheMode) {
  const model::Model m = cross_coupled(1.5 * threshold());
  const fe::LinearSystem s = fe::assemble(m);
  HarmonicSettings hs;
  hs.speed = 100.0;
  hs.f_min = 0.2 * natural();
  hs.f_max = 3.0 * natural();
  hs.n_points = 100;
  hs.input_node = "disk";
  hs.input_dof = model::Component::Ux;
  const FrfResult r = run_harmonic(m, hs, Context("frf").with_system(&s));
  EXPECT_EQ(r.status, Status::Unstable) << r.message;
  EXPECT_NE(r.message.find("damping ratio -"), std::string::npos) << r.message;
  const AnalysisOutput out = harmonic_output(m, hs, r, Context("frf").with_system(&s));
  const Trace& line = out.plots[0].traces.back();
  EXPECT_NE(line.name.find("UNSTABLE mode"), std::string::npos) << line.name;
  EXPECT_EQ(line.dash, "dash");
  EXPECT_NEAR(line.x[0], std::abs(closed_form_roots(1.5 * threshold())[1]) / (2 * std::numbers::pi),
              1e-9);

  const model::Model m2 = cross_coupled(0.5 * threshold());
  const fe::LinearSystem s2 = fe::assemble(m2);
  EXPECT_EQ(run_harmonic(m2, hs, Context("frf").with_system(&s2)).status, Status::Ok);
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The demo rotor (examples/geared_rotor_hcf): stable as given; with kxy = -kyx = 5e6 N/m on
// its two rotor bearings (the case of the robustness issue: damping ratios down to -0.064)
// both steady-state analyses say unstable.
TEST(StabilityCheck, DemoRotorIsStableWithoutAndUnstableWithCrossCoupling) {
  const fs::path file =
      fs::path(GEARDYN_SOURCE_DIR) / "examples" / "geared_rotor_hcf" / "model.toml";
  const std::string text = read_text(file);
  for (int coupled = 0; coupled < 2; ++coupled) {
    model::Model m = parse_model(text, file.string());
    if (coupled == 1)
      for (int b : {0, 1}) {
        m.bearings[static_cast<std::size_t>(b)].stiffness[0][1] = 5e6;
        m.bearings[static_cast<std::size_t>(b)].stiffness[0][6] = -5e6;
      }
    const fe::LinearSystem system = assembly::build_system(m);
    for (const auto& a : m.analyses) {
      const Context context = Context(m, a).with_system(&system);
      if (a.name == "unbalance") {
        const UnbalanceResult r = run_unbalance(m, a.settings_of<UnbalanceSettings>(), context);
        EXPECT_EQ(r.status, coupled == 1 ? Status::Unstable : Status::Ok) << r.message;
        EXPECT_EQ(r.stability.all_stable(), coupled == 0);
        EXPECT_LE(r.stability.n_solves, kMaxSampledSpeeds + 40);
      } else if (a.name == "frf_driving_gear") {
        const FrfResult r = run_harmonic(m, a.settings_of<HarmonicSettings>(), context);
        EXPECT_EQ(r.status, coupled == 1 ? Status::Unstable : Status::Ok) << r.message;
        if (coupled == 0) {
          // Every mode up to twice frequency_stop checked.
          EXPECT_GE(r.stability.solves[0].covered, 2.0 * a.settings_of<HarmonicSettings>().f_max);
          EXPECT_GT(r.stability.solves[0].least_damped.damping_ratio, 0.0);
        }
      }
    }
  }
}

// The energy certificate (stability_check.hpp): where it holds, the eigenvalue scan it replaces
// finds every mode decaying or neutral; it refuses each of the terms that can destabilise a
// rotor, and the scan then decides as before. Reference: the energy theorem of the header
// (Meirovitch 1970, ch. 6) and, for the cases it refuses, the eigenvalues of the closed form
// above.
double certificate_tau(double band_top) { return kGrowthTolerance * kBandMargin * band_top; }

TEST(StabilityCheck, EnergyCertificateHoldsWhereTheEigenScanFindsNoGrowth) {
  const std::vector<double> speeds = {0.0, 150.0, 300.0, 450.0};
  // A damped Jeffcott rotor and the Friswell 5.9.1 rotor (free axial and torsional motion,
  // undamped: neutral modes and defective roots at 0) with a disk's gyroscopic terms.
  for (const fe::LinearSystem& s :
       {fe::assemble(cross_coupled(0.0)), assembly::build_system(test::friswell_591(12))}) {
    EXPECT_EQ(energy_certificate(s, certificate_tau(450.0)), "");
    const StabilityScan certified = scan_stability(s, speeds, 450.0, true, true);
    EXPECT_TRUE(certified.certified);
    EXPECT_TRUE(certified.all_stable());
    EXPECT_EQ(certified.n_solves, 0);
    const StabilityScan scanned = scan_stability(s, speeds, 450.0, false, false);
    EXPECT_FALSE(scanned.certified);
    EXPECT_TRUE(scanned.all_stable());
    EXPECT_EQ(scanned.n_solves, 4);
  }
}

TEST(StabilityCheck, EnergyCertificateRefusesEveryDestabilisingTerm) {
  const double tau = certificate_tau(400.0);
  const std::vector<double> speeds = {100.0, 200.0, 400.0};
  auto refused = [&](const fe::LinearSystem& s, const std::string& why, bool stable) {
    const std::string reason = energy_certificate(s, tau);
    EXPECT_NE(reason.find(why), std::string::npos) << reason;
    const StabilityScan scan = scan_stability(s, speeds, 400.0, true, true);
    EXPECT_FALSE(scan.certified);
    EXPECT_EQ(scan.all_stable(), stable) << why;
    EXPECT_NE(stability_note(scan).find("does not apply: " + reason), std::string::npos);
  };
  // Cross-coupled stiffness, below the threshold q* = c w_n (stable) and above it (unstable).
  refused(fe::assemble(cross_coupled(0.8 * threshold())), "not symmetric", true);
  refused(fe::assemble(cross_coupled(1.5 * threshold())), "not symmetric", false);
  // Negative stiffness: k - 2k in x, a static divergence (real root sqrt(k / m) = 316 1/s).
  fe::LinearSystem soft = fe::assemble(cross_coupled(0.0));
  const int ux = soft.dofs.dof(0, model::Component::Ux);
  soft.K.coeffRef(ux, ux) -= 2.0 * kStiffness;
  refused(soft, "negative stiffness", false);
  // Negative damping: -c in x, growth rate c / (2 m) = 12.6 1/s, far above tau.
  fe::LinearSystem pumped = fe::assemble(cross_coupled(0.0));
  pumped.C.coeffRef(ux, ux) = -damping();
  refused(pumped, "negative damping", false);
  // Damping below -tau M by a hair is refused; above it, certified (the bound is tau itself).
  fe::LinearSystem hair = fe::assemble(cross_coupled(0.0));
  hair.C.coeffRef(ux, ux) = -0.5 * tau * kMass;
  EXPECT_EQ(energy_certificate(hair, tau), "");
  hair.C.coeffRef(ux, ux) = -2.0 * tau * kMass;
  EXPECT_NE(energy_certificate(hair, tau), "");
}

TEST(StabilityCheck, UnbalanceNotesTheCertificateAndSkipsTheSolves) {
  const model::Model m = cross_coupled(0.0);
  const fe::LinearSystem s = fe::assemble(m);
  const UnbalanceResult r =
      run_unbalance(m, speed_list({100.0, 200.0, 400.0}), Context("unbalance").with_system(&s));
  EXPECT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_TRUE(r.stability.certified);
  EXPECT_EQ(r.stability.n_solves, 0);
  const AnalysisOutput out = unbalance_output(m, speed_list({100.0, 200.0, 400.0}), r,
                                              Context("unbalance").with_system(&s));
  bool noted = false;
  for (const auto& note : out.notes)
    noted = noted || note.find("by the energy certificate") != std::string::npos;
  EXPECT_TRUE(noted);
  const Column* stable = find_column(out.tables[0], "stable");
  ASSERT_NE(stable, nullptr);
  for (const auto& v : stable->texts) EXPECT_EQ(v, "yes");
}

}  // namespace
}  // namespace geardyn::analyses
