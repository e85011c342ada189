// Backlash oscillator of a spur gear pair (A. Kahraman, R. Singh, "Non-linear dynamics of a spur
// gear pair", J. Sound Vib. 142 (1990) 49-75), the long runs (label `slow`; the short default
// check is backlash_oscillator_test.cpp, which explains the tolerances):
//   * full sweeps up 0.6 -> 1.05 and down 1.05 -> 0.6 at r = 1e-6 with integrate_adaptive: the
//     amplitude envelope on both branches against the RK4 reference's continuation every 0.025;
//   * the jumps at three rates r = 1e-6, 5e-7, 2.5e-7 with ten times tighter tolerances (rtol
//     1e-8, atol 1e-9): the lag shrinks by 2^(-2/3) per halving twice (R. Haberman, "Slowly
//     varying jump and transition phenomena associated with algebraic bifurcation problems",
//     SIAM J. Appl. Math. 37 (1979) 69-106), and the rate-extrapolated jump meets the reference.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "backlash_oscillator.hpp"

namespace geardyn::transient::backlash {
namespace {

// Peak-to-peak of the sweep every 0.025 of Omega vs the reference's continuation in the same
// direction, except within `skip` of a jump (the sweep's transient between the branches).
// 2e-3 as in backlash_oscillator_test.cpp.
void check_branch(const Sweep& sweep, const Rk4Reference& ref, double from, double to, State s,
                  double skip_lo, double skip_hi, const char* name) {
  const double step = from < to ? 0.025 : -0.025;
  const int n = static_cast<int>(std::lround((to - from) / step));
  double previous = from;
  double worst = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double omega = from + i * step;
    const PeriodicOrbit o = ref.continuation(previous, omega, 0.005, s);
    s = o.start;
    previous = omega;
    if (omega > skip_lo && omega < skip_hi) continue;
    const Cycle& c = sweep.at(omega);
    const double rel = c.peak_to_peak / o.peak_to_peak - 1.0;
    worst = std::max(worst, std::abs(rel));
    EXPECT_NEAR(rel, 0.0, 2e-3) << name << " at " << omega;
  }
  fmt::print("{}: largest amplitude deviation {:.2e} ({} frequencies)\n", name, worst, n + 1);
}

TEST(BacklashOscillatorSlow, FullSweepsFollowBothBranches) {
  const Parameters p;
  const Rk4Reference ref(p);
  const double rate = 1e-6;
  const State lower_060 = ref.orbit(0.6, {p.b + p.mean_force, 0.0}).start;
  const State upper_105 = ref.continuation(0.6, 1.05, 0.01, lower_060).start;
  const Sweep up = run_sweep(p, 0.6, 1.05, rate, lower_060);
  const Sweep down = run_sweep(p, 1.05, 0.6, -rate, upper_105);
  fmt::print("up: {} ({:.1f} s)\ndown: {} ({:.1f} s)\n", up.summary.brief_report(), up.seconds,
             down.summary.brief_report(), down.seconds);
  const double jump_up = up.jump(kJumpThreshold, true);
  const double jump_down = down.jump(kJumpThreshold, false);
  fmt::print("full sweeps at r = {:g}: jump-up {:.6f}, jump-down {:.6f}\n", rate, jump_up,
             jump_down);
  // The same jumps as the narrow sweeps of the default test at the same rate (started 0.03 and
  // 0.018 before the jumps, on the reference's orbits): once the start's transient has decayed
  // the sweep does not remember where it began. 2e-5: 2.5 forcing cycles at r = 1e-6.
  const State lower_088 = ref.continuation(0.6, 0.88, 0.02, lower_060).start;
  const State upper_0815 = ref.continuation(1.05, 0.815, 0.005, upper_105).start;
  const double narrow_up = run_sweep(p, 0.88, 0.93, rate, lower_088).jump(kJumpThreshold, true);
  const double narrow_down =
      run_sweep(p, 0.815, 0.785, -rate, upper_0815).jump(kJumpThreshold, false);
  fmt::print("narrow sweeps: jump-up {:.6f}, jump-down {:.6f}\n", narrow_up, narrow_down);
  EXPECT_NEAR(jump_up, narrow_up, 2e-5);
  EXPECT_NEAR(jump_down, narrow_down, 2e-5);
  check_branch(up, ref, 0.6, 1.05, lower_060, 0.9, 0.92, "sweep up");
  check_branch(down, ref, 1.05, 0.6, upper_105, 0.785, 0.8, "sweep down");
}

TEST(BacklashOscillatorSlow, JumpLagConvergesWithRate) {
  const Parameters p;
  const Rk4Reference ref(p);
  const double resolution = 1e-5;
  const SweepTolerance tight{1e-8, 1e-9};
  const State lower_088 = ref.continuation(0.6, 0.88, 0.02, {p.b + p.mean_force, 0.0}).start;
  const State lower_090 = ref.continuation(0.88, 0.90, 0.01, lower_088).start;
  const Bracket up = bisect_jump(ref, 0.90, 0.91, lower_090, kJumpThreshold, true, resolution);
  const State upper_0815 =
      ref.continuation(0.90, 0.815, 0.005, ref.continuation(0.90, 1.0, 0.01, lower_090).start)
          .start;
  const State upper_080 = ref.continuation(0.815, 0.80, 0.005, upper_0815).start;
  const Bracket down = bisect_jump(ref, 0.80, 0.79, upper_080, kJumpThreshold, false, resolution);

  const double ratio = std::pow(2.0, -2.0 / 3.0);
  for (const bool going_up : {true, false}) {
    const Bracket& b = going_up ? up : down;
    const double sign = going_up ? 1.0 : -1.0;
    double lag[3], omega[3];
    for (int i = 0; i < 3; ++i) {
      const double r = 1e-6 / (1 << i);
      const Sweep s = going_up ? run_sweep(p, 0.88, 0.93, r, lower_088, tight)
                               : run_sweep(p, 0.815, 0.785, -r, upper_0815, tight);
      omega[i] = s.jump(kJumpThreshold, going_up);
      lag[i] = sign * (omega[i] - b.middle());
      fmt::print("{} r = {:.3g}: {:.6f} (lag {:.2e}; {:.1f} s, {} steps)\n",
                 going_up ? "jump-up" : "jump-down", r, omega[i], lag[i], s.seconds,
                 s.summary.steps);
    }
    // Two halvings, each by 2^(-2/3) = 0.63 ([0.5, 0.75] as in the default test).
    for (int i = 1; i < 3; ++i) {
      EXPECT_GT(lag[i], 0.0);
      EXPECT_GT(lag[i] / lag[i - 1], 0.5);
      EXPECT_LT(lag[i] / lag[i - 1], 0.75);
    }
    const double extrapolated = omega[2] - (omega[1] - omega[2]) / (1.0 / ratio - 1.0);
    fmt::print("  reference {:.6f}; extrapolated {:.6f} ({:+.1e})\n", b.middle(), extrapolated,
               extrapolated - b.middle());
    // At the tight tolerances the integrator's share is < 1e-5 (3e-5 at rtol 1e-7); the rest is
    // the extrapolation's O(r) residual.
    EXPECT_NEAR(extrapolated, b.middle(), 5e-5 + resolution);
  }
}

}  // namespace
}  // namespace geardyn::transient::backlash
