// Unit tests of the harmonic analysis: grid, quantities, adaptive refinement, name resolution,
// input errors, output tables.
#include "geardyn/analyses/harmonic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "geardyn/core/error.hpp"
#include "harmonic_test_support.hpp"

namespace geardyn::analyses {
namespace {

using namespace geardyn::harmonic_test;
constexpr double kPi = std::numbers::pi;

TEST(FrequencyResponse, SdofQuantitiesOnAFixedGrid) {
  // m x'' + c x' + k x = f: H = 1 / (k - w^2 m + i w c); mobility i w H; accelerance -w^2 H.
  const double m = 2.0, k = 8e4, c = 12.0;
  const fe::LinearSystem s = sdof(m, k, c);
  const Eigen::VectorXcd load = Eigen::VectorXcd::Ones(1);
  for (auto q : {analyses::ResponseQuantity::Receptance, analyses::ResponseQuantity::Mobility,
                 analyses::ResponseQuantity::Accelerance}) {
    auto settings = grid(0.0, 600.0, 61, false);
    settings.quantity = q;
    const FrfResult r = frequency_response(s, load, {0}, settings, Context("harmonic"));
    ASSERT_EQ(r.frequencies.size(), 61);
    EXPECT_EQ(r.frequencies[0], 0.0);
    EXPECT_EQ(r.frequencies[60], 600.0);
    const Eigen::MatrixXcd y = r.response();
    for (Eigen::Index i = 0; i < r.frequencies.size(); ++i) {
      const double w = r.frequencies[i];
      const Complex H = 1.0 / Complex(k - w * w * m, w * c);
      const Complex ref = q == analyses::ResponseQuantity::Receptance ? H
                          : q == analyses::ResponseQuantity::Mobility ? Complex(0, w) * H
                                                                      : -w * w * H;
      // A 1x1 LU is one complex division: round-off only.
      EXPECT_LE(std::abs(y(i, 0) - ref), 1e-14 * std::abs(ref) + 1e-300) << w;
    }
  }
}

TEST(FrequencyResponse, AdaptiveGridMeetsItsCriteria) {
  const double m = 1.0, k = 1e6, zeta = 0.005;
  const double wn = std::sqrt(k / m);
  const fe::LinearSystem s = sdof(m, k, 2.0 * zeta * std::sqrt(k * m));
  const FrfResult r = frequency_response(s, Eigen::VectorXcd::Ones(1), {0},
                                         grid(10.0, 3000.0, 40, true), Context("harmonic"));
  EXPECT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_TRUE(r.grid.converged);
  EXPECT_GT(r.grid.final_points, r.grid.initial_points);
  ASSERT_EQ(r.peaks.size(), 1u);
  const FrfPeak& p = r.peaks[0];
  EXPECT_TRUE(p.resolved);
  EXPECT_GE(p.points_in_band, 5);
  EXPECT_LE(p.location_error, 1e-3);
  EXPECT_NEAR(p.frequency / wn, 1.0, 1e-3);
  // Grid strictly increasing, every sample equal to the exact receptance.
  for (Eigen::Index i = 1; i < r.frequencies.size(); ++i)
    ASSERT_GT(r.frequencies[i], r.frequencies[i - 1]);
}

TEST(FrequencyResponse, PointLimitLeavesTheGridNotConverged) {
  // zeta = 1e-4 needs ~45 extra samples; allow only 5 beyond the initial grid.
  const double k = 1e6, m = 1.0;
  const fe::LinearSystem s = sdof(m, k, 2.0 * 1e-4 * std::sqrt(k * m));
  AdaptiveGridOptions options;
  options.max_points = 45;
  const FrfResult r = frequency_response(s, Eigen::VectorXcd::Ones(1), {0},
                                         grid(0.0, 3000.0, 40, true), Context("harmonic"), options);
  EXPECT_EQ(r.status, Status::NotConverged);
  EXPECT_FALSE(r.grid.converged);
  EXPECT_NE(r.message.find("max_points = 45"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("sensor eq0"), std::string::npos) << r.message;
  EXPECT_LE(r.grid.final_points, 45);
}

TEST(FrequencyResponse, ManyMorePeaksThanModesIsANumericalFaultNotLightDamping) {
  // A lightly damped SDOF with too small a point budget: one unresolved peak, one mode in the
  // range: the advice is damping. The same result with 12 unresolved maxima on one sensor (a
  // mode gives one per sensor, so at most 2 x 1 + 2 are explained with margin): not smooth.
  const double k = 1e6, m = 1.0;
  const fe::LinearSystem s = sdof(m, k, 2.0 * 1e-4 * std::sqrt(k * m));
  AdaptiveGridOptions options;
  options.max_points = 45;
  FrfResult r = frequency_response(s, Eigen::VectorXcd::Ones(1), {0}, grid(0.0, 3000.0, 40, true),
                                   Context("harmonic"), options);
  ASSERT_EQ(r.status, Status::NotConverged);
  diagnose_unresolved_peaks(r, 1);
  EXPECT_NE(r.message.find("add damping"), std::string::npos) << r.message;
  FrfPeak noise = r.peaks.front();
  noise.resolved = false;
  noise.q_factor = 50.0;
  r.peaks.assign(12, noise);
  diagnose_unresolved_peaks(r, 1);
  EXPECT_EQ(r.status, Status::NotConverged);
  EXPECT_NE(r.message.find("not smooth"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("12 unresolved peaks"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("only 1 mode(s)"), std::string::npos) << r.message;
  EXPECT_EQ(r.message.find("add damping"), std::string::npos) << r.message;
}

TEST(FrfResult, UnitsOfRotationsAndMoments) {
  FrfResult r;
  r.sensors = {{"a", 0, true}, {"b", 1, false}};
  r.input_rotational = true;
  r.quantity = analyses::ResponseQuantity::Mobility;
  EXPECT_EQ(r.amplitude_unit(0), "rad/s/(N m)");
  EXPECT_EQ(r.amplitude_unit(1), "m/s/(N m)");
  r.forced = true;
  r.quantity = analyses::ResponseQuantity::Accelerance;
  EXPECT_EQ(r.amplitude_unit(0), "rad/s^2");
}

TEST(FrequencyResponse, RejectsBadGrids) {
  const fe::LinearSystem s = sdof(1.0, 1.0, 0.1);
  const Eigen::VectorXcd f = Eigen::VectorXcd::Ones(1);
  EXPECT_THROW(frequency_response(s, f, {0}, grid(5.0, 5.0, 10, false), Context("harmonic")),
               InputError);
  EXPECT_THROW(frequency_response(s, f, {0}, grid(-1.0, 5.0, 10, false), Context("harmonic")),
               InputError);
  EXPECT_THROW(frequency_response(s, f, {0}, grid(0.0, 5.0, 1, false), Context("harmonic")),
               InputError);
  auto log_grid = grid(0.0, 5.0, 10, false);
  log_grid.spacing = analyses::Spacing::Log;
  EXPECT_THROW(frequency_response(s, f, {0}, log_grid, Context("harmonic")), InputError);
  log_grid.f_min = 0.5;
  const FrfResult r = frequency_response(s, f, {0}, log_grid, Context("harmonic"));
  EXPECT_NEAR(r.frequencies[1] / r.frequencies[0], std::pow(10.0, 1.0 / 9.0), 1e-12);
}

// Jeffcott-type model with 2 free DOFs (ux, uy) assembled by fe.
model::Model two_dof_model() {
  model::Model m = jeffcott(10.0, 1e6, 2e6, 50.0, 1e-4);
  model::HarmonicForce f;
  f.name = "fx";
  f.node = "disk";
  f.dof = model::Component::Ux;
  f.amplitude = 3.0;
  f.phase = 0.5;
  m.forces.push_back(f);
  model::Analysis a;
  a.name = "frf";
  a.type = "harmonic";
  analyses::HarmonicSettings hs = grid(0.0, 1000.0, 101, false);
  hs.input_node = "disk";
  hs.input_dof = model::Component::Ux;
  a.settings =
      std::unique_ptr<model::AnalysisSettings>(std::make_unique<analyses::HarmonicSettings>(hs));
  m.analyses.push_back(a);
  return m;
}

TEST(RunHarmonic, AnyFrequencyCountTheSchemaAllowsRuns) {
  // frequency_count is allowed up to 1e6; a grid above the adaptive budget's default (20 000
  // samples) once threw "invalid AdaptiveGridOptions" and aborted the program. Fixed and
  // adaptive grids of 25 000 points against the closed-form receptance of the Jeffcott rotor.
  model::Model m = two_dof_model();
  const fe::LinearSystem s = fe::assemble(m);
  for (bool adaptive : {false, true}) {
    analyses::HarmonicSettings hs = m.analyses[0].settings_of<analyses::HarmonicSettings>();
    hs.n_points = 25000;
    hs.adaptive = adaptive;
    const FrfResult frf = run_harmonic(m, hs, Context("harmonic").with_system(&s));
    ASSERT_GE(frf.frequencies.size(), 25000) << "adaptive = " << adaptive;
    const Eigen::Index i = frf.frequencies.size() / 3;
    const double w = frf.frequencies[i];
    const Complex H = 1.0 / Complex(1e6 - w * w * 10.0, 50.0 * w);
    EXPECT_LE(std::abs(frf.displacement(i, 0) - H), 1e-13 * std::abs(H));
  }
}

TEST(RunHarmonic, FrfAndForcedResponseByName) {
  model::Model m = two_dof_model();
  const fe::LinearSystem s = fe::assemble(m);
  const auto& hs = m.analyses[0].settings_of<analyses::HarmonicSettings>();
  const FrfResult frf = run_harmonic(m, hs, Context("harmonic").with_system(&s));
  ASSERT_EQ(frf.sensors.size(), 2u);
  EXPECT_EQ(frf.sensors[0].name, "dx");
  EXPECT_EQ(frf.sensors[1].equation, s.dofs.dof(0, model::Component::Uy));
  EXPECT_EQ(frf.input, "disk.ux");
  EXPECT_FALSE(frf.forced);
  EXPECT_EQ(frf.amplitude_unit(0), "m/N");
  for (Eigen::Index i = 0; i < frf.frequencies.size(); ++i) {
    const double w = frf.frequencies[i];
    const Complex H = 1.0 / Complex(1e6 - w * w * 10.0, 50.0 * w);
    EXPECT_LE(std::abs(frf.displacement(i, 0) - H), 1e-13 * std::abs(H));
    EXPECT_EQ(std::abs(frf.displacement(i, 1)), 0.0);  // x and y are uncoupled
  }

  analyses::HarmonicSettings forced = hs;
  forced.input_node.clear();
  forced.forces = {"fx"};
  forced.quantity = analyses::ResponseQuantity::Mobility;
  const FrfResult r = run_harmonic(m, forced, Context("harmonic").with_system(&s));
  EXPECT_TRUE(r.forced);
  EXPECT_EQ(r.amplitude_unit(0), "m/s");
  const Eigen::MatrixXcd v = r.response();
  for (Eigen::Index i = 0; i < r.frequencies.size(); ++i) {
    const double w = r.frequencies[i];
    const Complex ref =
        Complex(0, w) * std::polar(3.0, 0.5) / Complex(1e6 - w * w * 10.0, 50.0 * w);
    EXPECT_LE(std::abs(v(i, 0) - ref), 1e-13 * std::abs(ref) + 1e-300);
  }
}

TEST(RunHarmonic, OutputTablesAndPlots) {
  model::Model m = two_dof_model();
  const fe::LinearSystem s = fe::assemble(m);
  auto hs = m.analyses[0].settings_of<analyses::HarmonicSettings>();
  hs.adaptive = true;
  hs.sensors = {"dx"};
  hs.quantity = analyses::ResponseQuantity::Accelerance;
  const FrfResult r = run_harmonic(m, hs, Context("harmonic").with_system(&s));
  const AnalysisOutput out = harmonic_output(m, hs, r, Context("frf").with_system(&s));
  EXPECT_EQ(out.type, "harmonic");
  ASSERT_EQ(out.tables.size(), 2u);
  const Table& frf = out.tables[0];
  EXPECT_EQ(frf.name, "frf");
  EXPECT_NO_THROW(frf.validate());
  EXPECT_TRUE(frf.has_column("frequency_hz"));
  ASSERT_TRUE(frf.has_column("dx_amplitude_m_per_s2_per_N"));
  EXPECT_EQ(frf.column("dx_amplitude_m_per_s2_per_N").unit, "m/s^2/N");
  EXPECT_TRUE(frf.has_column("dx_phase_deg"));
  const Table& peaks = out.tables[1];
  EXPECT_EQ(peaks.name, "peaks");
  EXPECT_NO_THROW(peaks.validate());
  ASSERT_EQ(peaks.rows(), 1u);  // the x mode at sqrt(1e5) rad/s
  const double zeta = 50.0 / (2.0 * std::sqrt(1e6 * 10.0));
  EXPECT_NEAR(peaks.column("frequency_hz").numbers[0], std::sqrt(1e5) / (2 * kPi), 0.01);
  EXPECT_NEAR(peaks.column("damping_ratio").numbers[0], zeta, 0.02 * zeta);
  ASSERT_EQ(out.plots.size(), 2u);
  EXPECT_TRUE(out.plots[0].y_log);
  EXPECT_FALSE(out.notes.empty());
}

TEST(RunHarmonic, InputErrorsNameTheKey) {
  model::Model m = two_dof_model();
  const fe::LinearSystem s = fe::assemble(m);
  auto& hs = m.analyses[0].settings_of<analyses::HarmonicSettings>();
  hs.sensors = {"nope"};
  const Context context = Context(m, m.analyses[0]).with_system(&s);
  try {
    run_harmonic(m, hs, context);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "analyses[0].sensors");
  }
  hs.sensors.clear();
  hs.forces = {"fx"};  // both input_node and forces
  EXPECT_THROW(run_harmonic(m, hs, context), InputError);
  hs.forces.clear();
  hs.input_dof = model::Component::Uz;  // constrained
  EXPECT_THROW(run_harmonic(m, hs, context), InputError);
  hs.input_dof = model::Component::Ux;
  hs.input_node = "nowhere";
  EXPECT_THROW(run_harmonic(m, hs, context), InputError);
}

TEST(RunHarmonic, UnconstrainedRotorFailsWithAHelpfulMessage) {
  // A free-free steel shaft without bearings: rigid-body modes make D(0) = K singular.
  model::Model m;
  model::Material steel;
  steel.name = "steel";
  steel.youngs_modulus = 2.1e11;
  steel.shear_modulus = 8.1e10;
  steel.density = 7850.0;
  m.materials.push_back(steel);
  model::Shaft shaft;
  shaft.name = "s";
  shaft.material = "steel";
  model::ShaftElement e;
  e.length = 1.0;
  e.outer_diameter = 0.05;
  e.divisions = 10;
  shaft.elements.push_back(e);
  m.shafts.push_back(shaft);
  model::Sensor sensor;
  sensor.name = "tip";
  sensor.node = "s.10";
  sensor.dof = model::Component::Ux;
  m.sensors.push_back(sensor);
  const fe::LinearSystem s = fe::assemble(m);
  analyses::HarmonicSettings hs = grid(0.0, 2000.0, 50, false);
  hs.input_node = "s.0";
  try {
    run_harmonic(m, hs, Context("harmonic").with_system(&s));
    FAIL() << "expected NumericalError";
  } catch (const NumericalError& err) {
    const std::string what = err.what();
    EXPECT_NE(what.find("f = 0 Hz"), std::string::npos) << what;
    EXPECT_NE(what.find("model has rigid-body motion: add bearings or constraints"),
              std::string::npos)
        << what;
  }
  // Above zero frequency the free-free rotor has a regular D(w).
  hs.f_min = 1.0;
  EXPECT_NO_THROW(run_harmonic(m, hs, Context("harmonic").with_system(&s)));
}

}  // namespace
}  // namespace geardyn::analyses
