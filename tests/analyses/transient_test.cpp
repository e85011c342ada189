// The transient analysis end to end on the Jeffcott rotor, against the closed-form steady
// unbalance response (e.g. Friswell, Penny, Garvey, Lees, Dynamics of Rotating Machines, CUP
// 2010, sec. 3.3; Genta, Dynamics of Rotating Systems, 2005, sec. 3.2):
//
//        k, c                 m x'' + c x' + k x = m_e W^2 cos(W t)
//   ///--/\/\/--( m )         m y'' + c y' + k y = m_e W^2 sin(W t)
//                             |r| = m_e W^2 / sqrt((k - m W^2)^2 + (c W)^2)
//
// m = 10 kg, k = 1e6 N/m (w_n = 316.23 rad/s), zeta = 0.02 (c = 126.49 N s/m), m_e = 1e-4 kg m,
// W = 2 w_n = 632.46 rad/s: |r| = 40 / sqrt(9e12 + 6.4e9) = 1.332860e-5 m, a circular orbit
// whirling forward (with the spin).
#include "geardyn/analyses/transient.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "geardyn/core/error.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/signal/orbit.hpp"
#include "geardyn/signal/window.hpp"
#include "support/transient_rotor_models.hpp"

namespace geardyn::transient {
namespace {

using analyses::TransientOrbit;
using analyses::TransientResult;

constexpr double kPi = std::numbers::pi;
constexpr double kMass = 10.0, kStiffness = 1e6, kZeta = 0.02, kMassEccentricity = 1e-4;
constexpr double kReferenceAmplitude = 1.332860e-5;  // m, closed form above

double omega_n() { return std::sqrt(kStiffness / kMass); }

analyses::TransientSettings jeffcott_settings(analyses::Integrator integrator) {
  // Step: the trapezoidal rule gives the exact steady response at the warped frequency
  // W' = (2/h) tan(W h / 2) ~ W (1 + (W h)^2 / 12) while the force keeps W^2; with
  // |d ln D / d ln W| = 2 m W^2 / (m W^2 - k) = 8/3 at W = 2 w_n the amplitude error is about
  // (8/3) (W h)^2 / 12 = 3.6e-5 for h = 2e-5 s (W h = 0.0126); generalised-alpha's is of the
  // same order. Duration 4 s, steady part the last 2 s: the free response has decayed by
  // exp(-zeta w_n 2 s) = 3e-6. Both errors are far below the 0.5 % tolerance, which leaves room
  // for the 7-digit reference.
  analyses::TransientSettings s;
  s.speed = 2.0 * omega_n();
  s.duration = 4.0;
  s.time_step = 2e-5;
  s.integrator = integrator;
  s.rho_infinity = 0.8;
  s.steady_fraction = 0.5;
  s.output_every = 5;
  return s;
}

TEST(TransientAnalysis, JeffcottSteadyAmplitudeAndForwardCircularOrbit) {
  const model::Model model = testing::jeffcott(kMass, kStiffness, kZeta, kMassEccentricity);
  const fe::LinearSystem system = fe::assemble(model);
  const double W = 2.0 * omega_n();
  const double c = 2 * kZeta * std::sqrt(kStiffness * kMass);
  const double closed_form =
      kMassEccentricity * W * W / std::hypot(kStiffness - kMass * W * W, c * W);
  ASSERT_NEAR(closed_form, kReferenceAmplitude, 1e-11);

  for (auto integrator : {analyses::Integrator::Newmark, analyses::Integrator::GeneralizedAlpha}) {
    const TransientResult r = run_transient(model, jeffcott_settings(integrator),
                                            analyses::Context("transient").with_system(&system));
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    EXPECT_EQ(r.integration.factorizations, 1) << "constant speed: factor once";
    ASSERT_EQ(r.orbits.size(), 1u);
    const TransientOrbit& o = r.orbits[0];
    EXPECT_EQ(o.node, "disk");
    EXPECT_NEAR(o.major / kReferenceAmplitude, 1.0, 5e-3);
    EXPECT_NEAR(o.major / kReferenceAmplitude, 1.0, 2e-4) << "expected accuracy (see above)";
    EXPECT_LT((o.major - o.minor) / o.major, 1e-3) << "circular orbit";
    EXPECT_EQ(o.whirl, signal::Whirl::Forward);
    RecordProperty(integrator == analyses::Integrator::Newmark ? "newmark_major_m"
                                                               : "generalized_alpha_major_m",
                   fmt::format("{:.7e} (reference {:.6e}), minor {:.7e}", o.major,
                               kReferenceAmplitude, o.minor));

    // Spectrum of the steady part: the peak within one bin of W / 2 pi, its amplitude within the
    // Hann scalloping loss below the closed form.
    const int x = 0;
    Eigen::Index peak = 0;
    r.spectrum_amplitude.col(x).maxCoeff(&peak);
    EXPECT_NEAR(r.spectrum_frequency_hz[peak], W / (2 * kPi), r.spectrum_resolution_hz);
    const double a = r.spectrum_amplitude(peak, x);
    EXPECT_LE(a, kReferenceAmplitude * 1.001);
    EXPECT_GE(a, kReferenceAmplitude * (1 - signal::max_scalloping_loss(signal::Window::Hann)));
  }
}

TEST(TransientAnalysis, BackwardSpinGivesBackwardGeometricOrbitButForwardWhirl) {
  // Same rotor spinning the other way (speed ratio -1): the path turns clockwise about e3, which
  // is still forward whirl relative to the spin.
  const model::Model model = testing::jeffcott(kMass, kStiffness, kZeta, kMassEccentricity, -1.0);
  const fe::LinearSystem system = fe::assemble(model);
  analyses::TransientSettings s = jeffcott_settings(analyses::Integrator::Newmark);
  s.time_step = 1e-4;
  const TransientResult r =
      run_transient(model, s, analyses::Context("transient").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.orbits.size(), 1u);
  EXPECT_EQ(r.orbits[0].whirl, signal::Whirl::Forward);
  EXPECT_NEAR(r.orbits[0].major / kReferenceAmplitude, 1.0, 5e-3);
}

TEST(TransientAnalysis, EllipticalOrbitMatchesTheHarmonicSolution) {
  // Flexible rotor on anisotropic bearings at 300 rad/s: the steady orbit of the disk is an
  // ellipse. Reference: the direct harmonic solution X = D(W)^{-1} F (D = K - W^2 M +
  // i W (C + W G)) turned into semi-axes by signal::orbit_from_phasors. Time domain: trapezoidal
  // rule, h = 5e-5 s (W h = 0.015, amplitude error ~1e-4, see rotor_test), 6 s from rest
  // (free response decayed below 2e-8), every step stored: the largest/smallest sampled
  // distances miss the true extremes by at most (W h)^2 / 8 = 3e-5 relative. Tolerance 1e-3.
  using namespace std::complex_literals;
  for (double ratio : {1.0, -1.0}) {
    const model::Model model = testing::flexible_rotor(ratio);
    const fe::LinearSystem system = fe::assemble(model);
    const double W = 300.0;
    const Eigen::VectorXcd F = fe::unbalance_load(model, system, W, 1.0);
    const Eigen::MatrixXcd D =
        Eigen::MatrixXcd(system.K.cast<std::complex<double>>()) -
        W * W * Eigen::MatrixXcd(system.M.cast<std::complex<double>>()) +
        1i * W * Eigen::MatrixXcd((system.C + W * system.G).cast<std::complex<double>>());
    const Eigen::VectorXcd X = D.partialPivLu().solve(F);
    const int node = system.dofs.node_index("s.2");
    const signal::Orbit reference =
        signal::orbit_from_phasors(X[system.dofs.dof(node, model::Component::Ux)],
                                   X[system.dofs.dof(node, model::Component::Uy)]);
    ASSERT_LT(reference.minor, 0.9 * reference.major) << "the test needs an elliptical orbit";

    analyses::TransientSettings s;
    s.speed = W;
    s.duration = 6.0;
    s.time_step = 5e-5;
    s.integrator = analyses::Integrator::Newmark;
    s.steady_fraction = 0.1;
    s.sensors = {"disk_x", "disk_y"};
    const TransientResult r =
        run_transient(model, s, analyses::Context("transient").with_system(&system));
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    ASSERT_EQ(r.orbits.size(), 1u);
    const TransientOrbit& o = r.orbits[0];
    EXPECT_NEAR(o.major / reference.major, 1.0, 1e-3) << "ratio " << ratio;
    EXPECT_NEAR(o.minor / reference.minor, 1.0, 1e-3) << "ratio " << ratio;
    const signal::Whirl expected =
        ratio < 0 ? signal::reversed(reference.whirl) : reference.whirl;  // relative to spin
    EXPECT_EQ(o.whirl, expected) << "ratio " << ratio;
    RecordProperty(
        "ratio" + std::to_string(static_cast<int>(ratio)) + "_orbit",
        fmt::format("major {:.6e} vs {:.6e}, minor {:.6e} vs {:.6e}, {}", o.major, reference.major,
                    o.minor, reference.minor, signal::to_string(o.whirl)));
  }
}

TEST(TransientAnalysis, RunUpTracksTheQuasiStaticResponseAwayFromResonance) {
  // A slow run-up from 0.2 w_n to 0.5 w_n over 30 s (speed changes by 0.3 % of w_n per period
  // of the free vibration): the response follows the steady response at the current speed,
  // |r|(W) = m_e W^2 / |k - m W^2 + i c W|, to within the lag of the transient (~1 %). The
  // gyroscopic-free Jeffcott rotor has a constant tangent, but the run-up is time-varying for
  // the integrator, which must still need only one factorisation here.
  const model::Model model = testing::jeffcott(kMass, kStiffness, kZeta, kMassEccentricity);
  const fe::LinearSystem system = fe::assemble(model);
  analyses::TransientSettings s;
  s.speed = 0.2 * omega_n();
  s.speed_end = 0.5 * omega_n();
  s.duration = 30.0;
  s.time_step = 2e-4;
  s.output_every = 10;
  const TransientResult r =
      run_transient(model, s, analyses::Context("transient").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_EQ(r.integration.factorizations, 1);
  EXPECT_FALSE(r.integration.linear_time_invariant);
  const double c = 2 * kZeta * std::sqrt(kStiffness * kMass);
  for (double t_check : {10.0, 20.0, 29.0}) {
    // Radius over the samples near t_check (the orbit is circular).
    double radius = 0.0;
    double W = 0.0;
    for (std::size_t k = 0; k < r.time.size(); ++k) {
      if (std::abs(r.time[k] - t_check) > 0.05) continue;
      radius = std::max(radius, std::hypot(r.values(static_cast<Eigen::Index>(k), 0),
                                           r.values(static_cast<Eigen::Index>(k), 1)));
      W = r.speed[k];
    }
    const double quasi_static =
        kMassEccentricity * W * W / std::hypot(kStiffness - kMass * W * W, c * W);
    EXPECT_NEAR(radius / quasi_static, 1.0, 0.02) << "t = " << t_check;
  }
}

TEST(TransientAnalysis, OutputHasTablesPlotsAndNotes) {
  const model::Model model = testing::jeffcott(kMass, kStiffness, kZeta, kMassEccentricity);
  const fe::LinearSystem system = fe::assemble(model);
  analyses::TransientSettings s = jeffcott_settings(analyses::Integrator::GeneralizedAlpha);
  // 2 s: the steady part (1-2 s) is steady (the start-up transient has decayed by
  // exp(-zeta w_n 1 s) = 2e-3); over 0.5 s it would not be, and no orbits would be given.
  s.duration = 2.0;
  s.time_step = 1e-4;
  s.output_every = 2;
  const TransientResult r =
      run_transient(model, s, analyses::Context("transient").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok);
  EXPECT_TRUE(r.steadiness.steady) << r.steadiness.non_synchronous;
  const AnalysisOutput out =
      transient_output(model, s, r, analyses::Context("tr").with_system(&system));
  EXPECT_EQ(out.name, "tr");
  EXPECT_EQ(out.type, "transient");
  ASSERT_EQ(out.tables.size(), 3u);
  for (const auto& t : out.tables) EXPECT_NO_THROW(t.validate()) << t.name;
  const Table& history = out.tables[0];
  EXPECT_EQ(history.name, "time_history");
  EXPECT_EQ(history.rows(), 10001u);  // 20000 steps, every 2nd stored, plus t = 0
  EXPECT_TRUE(history.has_column("time_s"));
  EXPECT_TRUE(history.has_column("speed_rpm"));
  EXPECT_TRUE(history.has_column("disk_x_m"));
  EXPECT_NEAR(history.column("speed_rpm").numbers[10], s.speed * 60 / (2 * kPi), 1e-9);
  EXPECT_EQ(out.tables[1].name, "spectrum");
  EXPECT_TRUE(out.tables[1].has_column("frequency_hz"));
  EXPECT_TRUE(out.tables[1].has_column("disk_y_m"));
  EXPECT_EQ(out.tables[2].name, "orbits");
  EXPECT_EQ(out.tables[2].column("node").texts[0], "disk");
  EXPECT_TRUE(out.tables[2].has_column("major_m"));
  EXPECT_TRUE(out.tables[2].has_column("minor_m"));
  bool orbit_plot = false, log_spectrum = false;
  for (const auto& p : out.plots) {
    if (p.name == "orbits") orbit_plot = p.equal_aspect;
    if (p.name == "spectrum") log_spectrum = p.y_log;
    for (const auto& trace : p.traces) EXPECT_LE(trace.x.size(), 4000u) << p.name;
  }
  EXPECT_TRUE(orbit_plot);
  EXPECT_TRUE(log_spectrum);
  EXPECT_FALSE(out.notes.empty());
}

TEST(TransientAnalysis, BadSettingsAreInputErrors) {
  const model::Model model = testing::jeffcott(kMass, kStiffness, kZeta, kMassEccentricity);
  const fe::LinearSystem system = fe::assemble(model);
  auto expect_error = [&](auto change, const std::string& key) {
    analyses::TransientSettings s = jeffcott_settings(analyses::Integrator::Newmark);
    change(s);
    try {
      run_transient(model, s, analyses::Context("transient").with_system(&system));
      ADD_FAILURE() << "no InputError for " << key;
    } catch (const InputError& e) {
      EXPECT_NE(e.key_path().find(key), std::string::npos) << e.what();
    }
  };
  expect_error([](auto& s) { s.duration = 0.0; }, "duration");
  expect_error([](auto& s) { s.time_step = -1.0; }, "time_step");
  expect_error([](auto& s) { s.time_step = 10.0; }, "time_step");
  expect_error([](auto& s) { s.rho_infinity = 1.2; }, "rho_infinity");
  expect_error([](auto& s) { s.steady_fraction = 0.0; }, "steady_fraction");
  expect_error([](auto& s) { s.output_every = 0; }, "output_every");
  expect_error([](auto& s) { s.output_every = 1000000; }, "output_every");
  expect_error([](auto& s) { s.speed = -1.0; }, "speed");
  expect_error([](auto& s) { s.unbalances = {"missing"}; }, "unbalances");
  expect_error([](auto& s) { s.sensors = {"missing"}; }, "sensors");
  expect_error([](auto& s) { s.time_step = 1e-12; }, "time_step");  // 4e12 steps
}

TEST(TransientAnalysis, DivergenceIsReportedNotHidden) {
  // A negative-stiffness support makes the rotor statically unstable; with a step that the
  // trapezoidal rule amplifies by > 1e3 per step, the run must stop as Diverged with the step.
  model::Model model = testing::jeffcott(kMass, -4e8, 0.0, kMassEccentricity);
  model.bearings[0].damping.clear();
  const fe::LinearSystem system = fe::assemble(model);
  analyses::TransientSettings s = jeffcott_settings(analyses::Integrator::Newmark);
  s.time_step = 1.999 * std::sqrt(kMass / 4e8);
  s.duration = 100 * s.time_step;
  const TransientResult r =
      run_transient(model, s, analyses::Context("transient").with_system(&system));
  EXPECT_EQ(r.status, Status::Diverged);
  EXPECT_NE(r.message.find("step"), std::string::npos) << r.message;
  EXPECT_EQ(r.spectrum_frequency_hz.size(), 0);
  EXPECT_TRUE(r.orbits.empty());
  const AnalysisOutput out =
      transient_output(model, s, r, analyses::Context("tr").with_system(&system));
  EXPECT_EQ(out.status, Status::Diverged);
  EXPECT_FALSE(out.message.empty());
}

}  // namespace
}  // namespace geardyn::transient
