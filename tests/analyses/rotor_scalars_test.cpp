// The scalar outputs (sweep quantities) of the rotor analyses: modal, campbell, harmonic,
// unbalance and transient. Each scalar is read through the registry from the typed result and
// checked (a) against the same number in the typed result, (b) for the quantities that were read
// back from the output tables before, bit for bit against that table reader (so sweeps give the
// values they gave), and (c) against the closed form of the Jeffcott rotor where one is cheap.
//
// Jeffcott rotor (tests/analyses/harmonic_test_support.hpp): a point mass m on an isotropic
// support k with viscous damping c, spinning with the reference speed.
//   w_n = sqrt(k / m), zeta = c / (2 sqrt(k m)), complex modes lambda = -zeta w_n +- i w_d,
//   so |lambda| / 2pi = w_n / 2pi and the damping ratio is zeta exactly; the logarithmic
//   decrement is 2 pi zeta / sqrt(1 - zeta^2). Unbalance m e: |x(W)| = m e W^2 / |k - m W^2 +
//   i c W|, largest near W = w_n / sqrt(1 - 2 zeta^2). Receptance |H(w)| = 1 / |k - m w^2 + i c
//   w|, largest 1 / (2 k zeta sqrt(1 - zeta^2)) at w_n sqrt(1 - 2 zeta^2).
// Source: M. I. Friswell, J. E. T. Penny, S. D. Garvey, A. W. Lees, Dynamics of Rotating
// Machines, Cambridge University Press 2010, sec. 3.6; the SDOF FRF in any vibration text.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "analyses/table_scalars.hpp"
#include "geardyn/analyses/campbell.hpp"
#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/transient.hpp"
#include "geardyn/analyses/unbalance.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "harmonic_test_support.hpp"

namespace geardyn::analyses {
namespace {

using namespace geardyn::harmonic_test;

constexpr double kMass = 10.0, kStiffness = 1e6, kZeta = 0.02, kMe = 1e-4;
const double kWn = std::sqrt(kStiffness / kMass);  // 316.2 rad/s, 50.33 Hz

double damping() { return 2.0 * kZeta * std::sqrt(kStiffness * kMass); }

// The Jeffcott model with one analysis of type `type` and settings `settings`, and what
// running it through its registry entry gives.
struct Run {
  model::Model model;
  fe::LinearSystem system;
  Outcome outcome;
  const AnalysisType* type = nullptr;

  double scalar(const ScalarRequest& q, std::string& unit) const {
    return type->scalar(outcome, q, unit);
  }
};

template <class S>
std::unique_ptr<Run> run(const std::string& type, const S& settings) {
  auto r = std::make_unique<Run>();
  r->model = jeffcott(kMass, kStiffness, kStiffness, damping(), kMe);
  model::Analysis a;
  a.name = type + "_run";
  a.type = type;
  a.settings = std::unique_ptr<model::AnalysisSettings>(std::make_unique<S>(settings));
  r->model.analyses.push_back(std::move(a));
  r->system = fe::assemble(r->model);
  r->type = find_analysis_type(type);
  const model::Analysis& analysis = r->model.analyses.back();
  r->outcome =
      r->type->run(r->model, analysis, Context(r->model, analysis).with_system(&r->system));
  return r;
}

ScalarRequest request(std::string quantity, int mode = 1, std::string sensor = {}) {
  ScalarRequest q;
  q.quantity = std::move(quantity);
  q.mode = mode;
  q.sensor = std::move(sensor);
  return q;
}

// The old reader of the output tables, for the quantities it served: the same value, bit for
// bit, and the same unit.
void expect_same_as_tables(const Run& r, const ScalarRequest& q) {
  std::string unit, table_unit;
  const double value = r.scalar(q, unit);
  const double from_tables = scalar_from_tables(r.outcome, q, table_unit);
  if (std::isnan(from_tables))
    EXPECT_TRUE(std::isnan(value)) << q.quantity;
  else
    EXPECT_EQ(value, from_tables) << q.quantity << " " << q.sensor;
  EXPECT_EQ(unit, table_unit) << q.quantity;
}

TEST(RotorScalars, ModalNaturalFrequencyDampingAndLogDecrement) {
  ModalSettings s;
  s.n_modes = 2;
  const auto r = run("modal", s);
  const ModalResult& result = result_of<ModalResult>(r->outcome);
  ASSERT_EQ(result.complex.size(), 2u);
  std::string unit;
  for (int mode = 1; mode <= 2; ++mode) {
    const Mode& m = result.complex[static_cast<std::size_t>(mode - 1)];
    expect_same_as_tables(*r, request("natural_frequency", mode));
    EXPECT_EQ(r->scalar(request("natural_frequency", mode), unit), m.frequency_hz);
    EXPECT_EQ(unit, "Hz");
    // The eigen-solve is accurate to round-off: 1e-10 relative.
    EXPECT_NEAR(m.frequency_hz, kWn / units::kTwoPi, 1e-10 * kWn);
    EXPECT_EQ(r->scalar(request("damping_ratio", mode), unit), m.damping_ratio);
    EXPECT_EQ(unit, "");
    EXPECT_NEAR(m.damping_ratio, kZeta, 1e-10);
    const double delta = r->scalar(request("log_decrement", mode), unit);
    EXPECT_NEAR(delta, units::kTwoPi * kZeta / std::sqrt(1.0 - kZeta * kZeta), 1e-9);
  }
  EXPECT_THROW(r->scalar(request("natural_frequency", 3), unit), std::runtime_error);
  EXPECT_TRUE(std::isnan(log_decrement(1.0)));  // critically damped: no oscillation
}

TEST(RotorScalars, CampbellCriticalSpeedFrequencyAndStability) {
  // No gyroscopic terms (a point mass): f = w_n / 2pi at every speed, so the 1x line meets
  // both whirl modes exactly at W = w_n and the linear interpolation of the crossing is exact
  // (to round-off, 1e-9 relative).
  CampbellSettings s;
  s.speeds = {0.5 * kWn, 0.8 * kWn, 1.1 * kWn, 1.5 * kWn};
  s.n_modes = 2;
  s.shaft_orders = false;
  s.mesh_orders = false;
  const auto r = run("campbell", s);
  const CampbellResult& result = result_of<CampbellResult>(r->outcome);
  ASSERT_EQ(result.status, Status::Ok) << result.message;
  ASSERT_EQ(result.critical_speeds.size(), 2u);
  std::string unit;
  const double rpm_n = kWn * 60.0 / units::kTwoPi;
  for (int mode = 1; mode <= 2; ++mode) {
    expect_same_as_tables(*r, request("critical_speed", mode));
    const double cs = r->scalar(request("critical_speed", mode), unit);
    EXPECT_EQ(unit, "rpm");
    EXPECT_NEAR(cs, rpm_n, 1e-9 * rpm_n);
    const double f = r->scalar(request("natural_frequency", mode), unit);
    EXPECT_EQ(f, result.tracks[static_cast<std::size_t>(mode - 1)][0].frequency_hz);
    EXPECT_NEAR(f, kWn / units::kTwoPi, 1e-10 * kWn);
    const double zeta = r->scalar(request("min_damping_ratio", mode), unit);
    EXPECT_NEAR(zeta, kZeta, 1e-10);
  }
  // Only two crossings in range: the third is NaN, not an error.
  EXPECT_TRUE(std::isnan(r->scalar(request("critical_speed", 3), unit)));
  EXPECT_THROW(r->scalar(request("natural_frequency", 3), unit), std::runtime_error);
  // Damped throughout.
  EXPECT_TRUE(std::isnan(r->scalar(request("instability_onset_speed"), unit)));
  EXPECT_EQ(unit, "rpm");
}

TEST(RotorScalars, InstabilityOnsetIsTheLowestOnset) {
  // The onsets are located by run_campbell (root of the damping ratio between grid speeds,
  // tested against the closed form of a cross-coupled Jeffcott rotor in
  // rotor_stability_test.cpp); the scalar is the lowest of them, NaN when there is none.
  CampbellResult r;
  EXPECT_TRUE(std::isnan(instability_onset_speed(r)));
  r.onsets.resize(2);
  r.onsets[0].speed = 250.0;
  r.onsets[1].speed = 150.0;
  EXPECT_EQ(instability_onset_speed(r), 150.0);
}

TEST(RotorScalars, HarmonicPeakLocationAmplitudeAndDamping) {
  HarmonicSettings s = grid(0.2 * kWn, 2.0 * kWn, 60, true);
  s.input_node = "disk";
  s.input_dof = model::Component::Ux;
  const auto r = run("harmonic", s);
  const FrfResult& result = result_of<FrfResult>(r->outcome);
  ASSERT_EQ(result.status, Status::Ok) << result.message;
  for (const char* q : {"peak_amplitude", "peak_location"}) {
    expect_same_as_tables(*r, request(q, 1, "dx"));
    expect_same_as_tables(*r, request(q, 1, "dy"));
  }
  ScalarRequest at = request("amplitude_at", 1, "dx");
  at.at_speed = false;
  for (double w : {0.2 * kWn, 0.73 * kWn, kWn, 1.9 * kWn}) {
    at.at = w;
    expect_same_as_tables(*r, at);
  }
  std::string unit;
  // The adaptive grid brackets the peak to 1e-3 of its half-power band (2 zeta w_n): the
  // sampled maximum is within 1e-3 x 2 zeta of the peak frequency and, the curve being flat
  // there to second order, within ~1e-5 of its height; 1e-4 relative for both.
  const double w_peak = kWn * std::sqrt(1.0 - 2.0 * kZeta * kZeta);
  const double peak = 1.0 / (2.0 * kStiffness * kZeta * std::sqrt(1.0 - kZeta * kZeta));
  EXPECT_NEAR(r->scalar(request("peak_amplitude", 1, "dx"), unit), peak, 1e-4 * peak);
  EXPECT_EQ(unit, "m/N");
  EXPECT_NEAR(r->scalar(request("peak_location", 1, "dx"), unit), w_peak / units::kTwoPi,
              1e-4 * w_peak / units::kTwoPi);
  EXPECT_EQ(unit, "Hz");
  at.at = 0.73 * kWn;  // between samples: linear interpolation, within 1 % on this grid
  const double h = 1.0 / std::abs(Complex(kStiffness - kMass * at.at * at.at, damping() * at.at));
  EXPECT_NEAR(r->scalar(at, unit), h, 1e-2 * h);
  // Half-power estimate 1/(2Q) of zeta: exact to O(zeta^2) for an isolated mode, plus the
  // interpolation of the -3 dB crossings; 2 % as in the harmonic tests.
  const double z = r->scalar(request("peak_damping_ratio", 1, "dx"), unit);
  EXPECT_NEAR(z, kZeta, 0.02 * kZeta);
  double table_zeta = std::numeric_limits<double>::quiet_NaN();
  for (const auto& t : r->outcome.output.tables)
    if (t.name == "peaks") table_zeta = t.column("damping_ratio").numbers.at(0);
  EXPECT_EQ(z, table_zeta);  // what the peak table prints
  EXPECT_THROW(r->scalar(request("peak_amplitude", 1, "nope"), unit), std::runtime_error);
  at.at = 3.0 * kWn;
  EXPECT_THROW(r->scalar(at, unit), std::runtime_error);  // outside the range
}

TEST(RotorScalars, UnbalancePeakAndAmplitudeAtASpeed) {
  UnbalanceSettings s;
  for (int i = 0; i <= 40; ++i) s.speeds.push_back(kWn * (0.5 + 0.025 * i));
  const auto r = run("unbalance", s);
  for (const char* q : {"peak_amplitude", "peak_location"})
    for (const char* sensor : {"dx", "dy"}) expect_same_as_tables(*r, request(q, 1, sensor));
  ScalarRequest at = request("amplitude_at", 1, "dx");
  at.at_speed = true;
  std::string unit;
  for (double w : {0.5 * kWn, 0.81 * kWn, kWn, 1.5 * kWn}) {
    at.at = w;
    expect_same_as_tables(*r, at);
  }
  // At a listed speed: the closed form to round-off (1e-12 relative).
  at.at = kWn;
  const double x =
      kMe * kWn * kWn / std::abs(Complex(kStiffness - kMass * kWn * kWn, damping() * kWn));
  EXPECT_NEAR(r->scalar(at, unit), x, 1e-12 * x);
  EXPECT_EQ(unit, "m");
  // The largest listed amplitude is the sample nearest the peak (W = w_n here).
  EXPECT_NEAR(r->scalar(request("peak_location", 1, "dx"), unit), kWn * 60.0 / units::kTwoPi,
              1e-9 * kWn);
  EXPECT_EQ(unit, "rpm");
}

TEST(RotorScalars, TransientPeakRmsAndSpeedOfThePeak) {
  // Constant speed 2 w_n from rest: the start-up transient decays (zeta w_n t >> 1 by the
  // steady part) and the steady part is the circular forward orbit of radius |x(2 w_n)|, so
  // its RMS is |x| / sqrt(2) per axis. The steady part spans several periods: the RMS of a
  // sampled sinusoid over a non-integer number of periods is within ~1 / (2 pi N) of it; the
  // integrator's amplitude error is (w h)^2 / 12 ~ 1e-4; 2 % covers both.
  TransientSettings s;
  s.speed = 2.0 * kWn;
  s.duration = 1.5;
  s.time_step = 2e-4;
  s.steady_fraction = 0.3;
  s.integrator = Integrator::Newmark;
  const auto r = run("transient", s);
  const TransientResult& result = result_of<TransientResult>(r->outcome);
  ASSERT_EQ(result.status, Status::Ok) << result.message;
  std::string unit;
  const double x = kMe * 4.0 * kWn * kWn /
                   std::abs(Complex(kStiffness - kMass * 4.0 * kWn * kWn, damping() * 2.0 * kWn));
  const double rms = r->scalar(request("rms_response", 1, "dx"), unit);
  EXPECT_EQ(unit, "m");
  EXPECT_NEAR(rms, x / std::sqrt(2.0), 0.02 * x);
  // Against the record itself: the largest |x| and the RMS of the steady part.
  const Eigen::VectorXd col = result.values.col(0);
  EXPECT_EQ(r->scalar(request("max_response", 1, "dx"), unit), col.cwiseAbs().maxCoeff());
  const Eigen::Index n = col.size() - result.steady_first;
  EXPECT_DOUBLE_EQ(rms, std::sqrt(col.tail(n).squaredNorm() / static_cast<double>(n)));
  // The start-up overshoot is at least the steady amplitude.
  EXPECT_GE(r->scalar(request("max_response", 1, "dx"), unit), 0.98 * x);
  // Constant speed: the speed of the peak is that speed.
  EXPECT_NEAR(r->scalar(request("max_response_speed", 1, "dx"), unit),
              2.0 * kWn * 60.0 / units::kTwoPi, 1e-9 * kWn);
  EXPECT_EQ(unit, "rpm");
  EXPECT_THROW(r->scalar(request("rms_response", 1, "nope"), unit), std::runtime_error);
}

}  // namespace
}  // namespace geardyn::analyses
