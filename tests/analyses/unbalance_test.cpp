// Unit tests of the unbalance analysis: input checks, orbit nodes, whirl sense relative to the
// spin, phase-lag convention, output tables.
#include "geardyn/analyses/unbalance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "geardyn/core/error.hpp"
#include "harmonic_test_support.hpp"

namespace geardyn::analyses {
namespace {

using namespace geardyn::harmonic_test;

analyses::UnbalanceSettings speeds(std::vector<double> w) {
  analyses::UnbalanceSettings s;
  s.speeds = std::move(w);
  return s;
}

TEST(PhaseLag, ConventionIsMinusArgInZeroTo360) {
  EXPECT_DOUBLE_EQ(UnbalanceResult::phase_lag_deg(Complex(1.0, 0.0)), 0.0);
  EXPECT_NEAR(UnbalanceResult::phase_lag_deg(Complex(0.0, -1.0)), 90.0, 1e-12);
  EXPECT_NEAR(UnbalanceResult::phase_lag_deg(Complex(-1.0, 1e-9)), 180.0, 1e-6);
  EXPECT_NEAR(UnbalanceResult::phase_lag_deg(Complex(0.0, 1.0)), 270.0, 1e-12);
}

TEST(RunUnbalance, NegativeSpinReportsWhirlRelativeToSpin) {
  model::Model m = jeffcott(10.0, 1e6, 1e6, 100.0, 1e-4);
  m.nodes[0].speed_ratio = -1.0;  // spins about -e3
  const fe::LinearSystem s = fe::assemble(m);
  const UnbalanceResult r =
      run_unbalance(m, speeds({100.0, 500.0}), Context("unbalance").with_system(&s));
  ASSERT_EQ(r.orders.size(), 1u);
  EXPECT_EQ(r.orders[0], 1.0);
  ASSERT_EQ(r.orbit_nodes.size(), 1u);
  for (std::size_t i = 0; i < 2; ++i) {
    const NodeOrbit& o = r.orbits[0][i][0];
    // The isotropic rotor whirls with its spin: clockwise about e3 when seen geometrically.
    EXPECT_EQ(o.orbit.whirl, signal::Whirl::Backward);
    EXPECT_EQ(o.whirl, signal::Whirl::Forward);
    EXPECT_NEAR(o.orbit.minor / o.orbit.major, 1.0, 1e-12);
  }
}

TEST(RunUnbalance, TablesAndColumns) {
  model::Model m = jeffcott(10.0, 1e6, 1e6, 100.0, 1e-4);
  const fe::LinearSystem s = fe::assemble(m);
  const UnbalanceResult r =
      run_unbalance(m, speeds({100.0, 200.0, 300.0}), Context("unbalance").with_system(&s));
  const AnalysisOutput out =
      unbalance_output(m, UnbalanceSettings{}, r, Context("unb").with_system(&s));
  ASSERT_EQ(out.tables.size(), 2u);
  const Table& resp = out.tables[0];
  EXPECT_EQ(resp.name, "response");
  EXPECT_NO_THROW(resp.validate());
  EXPECT_EQ(resp.rows(), 3u);
  EXPECT_NEAR(resp.column("speed_rpm").numbers[1], 200.0 * 60.0 / (2.0 * std::numbers::pi), 1e-9);
  EXPECT_TRUE(resp.has_column("order"));
  EXPECT_EQ(resp.column("dx_amplitude_m").unit, "m");
  EXPECT_TRUE(resp.has_column("dy_phase_deg"));
  const Table& orbits = out.tables[1];
  EXPECT_EQ(orbits.name, "orbits");
  EXPECT_NO_THROW(orbits.validate());
  EXPECT_EQ(orbits.rows(), 3u);
  for (const char* c : {"speed_rpm", "node", "major_m", "minor_m", "inclination_deg", "whirl"})
    EXPECT_TRUE(orbits.has_column(c)) << c;
  EXPECT_EQ(orbits.column("whirl").texts[0], "forward");
  ASSERT_EQ(out.plots.size(), 2u);
  EXPECT_TRUE(out.plots[0].y_log);
  // uy of a forward circular whirl lags ux by 90 deg.
  const double lag_x = resp.column("dx_phase_deg").numbers[2];
  const double lag_y = resp.column("dy_phase_deg").numbers[2];
  EXPECT_NEAR(std::remainder(lag_y - lag_x - 90.0, 360.0), 0.0, 1e-9);
}

TEST(RunUnbalance, UndampedRotorAtItsCriticalSpeedIsReportedSingular) {
  // No damping at all and W = sqrt(k/m): k - m W^2 cancels to round-off in both rows, which
  // leaves UMFPACK's row-scaled pivot ratio at 1; the row-cancellation check must catch it.
  model::Model m = jeffcott(10.0, 1e6, 1e6, 0.0, 1e-4);
  const fe::LinearSystem s = fe::assemble(m);
  try {
    run_unbalance(m, speeds({std::sqrt(1e6 / 10.0)}), Context("unbalance").with_system(&s));
    FAIL() << "expected NumericalError";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("natural frequency"), std::string::npos) << e.what();
  }
}

TEST(RunUnbalance, InputErrors) {
  model::Model m = jeffcott(10.0, 1e6, 1e6, 100.0, 1e-4);
  const fe::LinearSystem s = fe::assemble(m);
  EXPECT_THROW(run_unbalance(m, speeds({}), Context("unbalance").with_system(&s)), InputError);
  EXPECT_THROW(run_unbalance(m, speeds({0.0}), Context("unbalance").with_system(&s)), InputError);
  auto bad = speeds({100.0});
  bad.unbalances = {"u9"};
  EXPECT_THROW(run_unbalance(m, bad, Context("unbalance").with_system(&s)), InputError);
  bad.unbalances.clear();
  bad.sensors = {"nope"};
  EXPECT_THROW(run_unbalance(m, bad, Context("unbalance").with_system(&s)), InputError);
  model::Model none = m;
  none.unbalances.clear();
  EXPECT_THROW(run_unbalance(none, speeds({100.0}), Context("unbalance").with_system(&s)),
               InputError);
}

TEST(UnbalancePhase, LagIsInZeroTo360WithoutNegativeZero) {
  // Documented range [0, 360): a response in phase with the mark is 0, not -0 (printed "-0").
  const double in_phase = UnbalanceResult::phase_lag_deg({1.0, 0.0});
  EXPECT_EQ(in_phase, 0.0);
  EXPECT_FALSE(std::signbit(in_phase));
  EXPECT_DOUBLE_EQ(UnbalanceResult::phase_lag_deg({0.0, -1.0}), 90.0);  // lags a quarter turn
  EXPECT_DOUBLE_EQ(UnbalanceResult::phase_lag_deg({0.0, 1.0}), 270.0);
}
}  // namespace
}  // namespace geardyn::analyses
