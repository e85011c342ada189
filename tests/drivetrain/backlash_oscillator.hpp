#pragma once
// The backlash oscillator of a spur gear pair for the jump-frequency validation of the
// time-domain sweep (backlash_oscillator_test.cpp, backlash_oscillator_slow_test.cpp):
//
//   A. Kahraman, R. Singh, "Non-linear dynamics of a spur gear pair", J. Sound Vib. 142 (1990)
//   49-75: the non-dimensional single-DOF model of a gear pair with backlash 2b,
//     x'' + 2 zeta x' + g(x) = F_m + F_a cos(Omega t),
//     g(x) = x - b (x > b), 0 (|x| <= b), x + b (x < -b)   (unit, time-invariant mesh stiffness),
//   whose frequency response softens where the mean-load contact is lost once per cycle: a
//   jump-up on a sweep up and a jump-down on a sweep down, with a hysteresis band between.
//
// Here:
//   * BacklashOscillator: the model as a transient::SecondOrderSystem with an elements::GapContact
//     (end play b, linear law k = 1, c = 0) and the contact's switches as event functions, for
//     geardyn's integrator under test (transient::integrate_adaptive). Damping: as in the paper,
//     2 zeta x' is a viscous damper acting at all times (their mesh damping is not switched with
//     the contact), so it is a separate dashpot and the contact law is a pure spring; a damping c
//     in the contact law would act only in contact, a different (less damped) model.
//   * Rk4Reference: an independent reference, fixed-step RK4 at constant frequency, N steps per
//     forcing period, every crossing of x = +-b located by bisection on the step length and the
//     step restarted there (RK4's fourth order on each smooth piece); periodic orbits by whole
//     periods until the Poincare map stops moving.
//   * run_sweep: integrate_adaptive with the frequency ramped linearly, peak-to-peak of x per
//     forcing cycle (the amplitude envelope).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/core/progress.hpp"
#include "geardyn/elements/contact_law.hpp"
#include "geardyn/elements/gap_contact.hpp"
#include "geardyn/transient/adaptive_integrator.hpp"

namespace geardyn::transient::backlash {

inline constexpr double kPi = std::numbers::pi;

// Parameters in the hysteresis region: F_m > F_a, so the response is linear (always in contact)
// at small amplitude and loses contact once per cycle near the resonance Omega ~ 1 (the linear
// amplitude F_a / (2 zeta) = 0.2 exceeds the static deflection F_m = 0.1 beyond b).
struct Parameters {
  double zeta = 0.05;
  double b = 1.0;
  double mean_force = 0.1;          // F_m
  double alternating_force = 0.02;  // F_a
};

inline double restoring(const Parameters& p, double x) {
  if (x > p.b) return x - p.b;
  if (x < -p.b) return x + p.b;
  return 0.0;
}

// Unit mass, the dashpot 2 zeta, the backlash as a GapContact to ground (u = x) and the force
// F_m + F_a cos(phi(t)), phi = Omega_0 t + rate t^2 / 2 (instantaneous frequency Omega_0 + rate t).
class BacklashOscillator final : public SecondOrderSystem {
 public:
  BacklashOscillator(const Parameters& p, double omega0, double rate)
      : p_(p),
        omega0_(omega0),
        rate_(rate),
        gap_(elements::GapContact::end_play("mesh", p.b, spring(), spring())) {}

  double phase(double t) const { return omega0_ * t + 0.5 * rate_ * t * t; }
  double frequency(double t) const { return omega0_ + rate_ * t; }

  int size() const override { return 1; }
  void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                const Eigen::VectorXd& a, Eigen::VectorXd& r) override {
    gap_.evaluate(q, v, t, f_);
    r.resize(1);
    r[0] = a[0] + 2.0 * p_.zeta * v[0] + f_.force[0] - p_.mean_force -
           p_.alternating_force * std::cos(phase(t));
  }
  void tangent(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double c_m, double c_c,
               double c_k, SparseMatrix& S) override {
    gap_.evaluate(q, v, t, f_);
    S.resize(1, 1);
    S.setZero();
    S.insert(0, 0) = c_m + c_c * (2.0 * p_.zeta + f_.damping(0, 0)) + c_k * f_.stiffness(0, 0);
  }
  int num_events() const override { return gap_.num_switches(); }
  void event_functions(double t, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                       Eigen::VectorXd& g) const override {
    g.resize(gap_.num_switches());
    gap_.switches(q, t, g.data());
  }
  std::string describe_event(int k) const override {
    return gap_.describe() + " " + gap_.describe_switch(k);
  }

 private:
  static std::shared_ptr<const elements::ContactLaw> spring() {
    return std::make_shared<elements::LinearContactLaw>(elements::LinearLawParameters{1.0, 0.0});
  }

  Parameters p_;
  double omega0_, rate_;
  elements::GapContact gap_;
  elements::ElementForce f_;
};

struct State {
  double x = 0.0, v = 0.0;
};

struct PeriodicOrbit {
  State start;                // state at phase 0 of the forcing
  double peak_to_peak = 0.0;  // max x - min x over the last period
  int periods = 0;            // periods integrated
  bool converged = false;     // the Poincare map moved the state by less than the tolerance
};

class Rk4Reference {
 public:
  explicit Rk4Reference(const Parameters& p, int steps_per_period = 1000)
      : p_(p), n_(steps_per_period) {}

  // The periodic orbit at frequency omega reached from `from` (at phase 0).
  PeriodicOrbit orbit(double omega, State from, double tol = 1e-11, int max_periods = 50000) const {
    PeriodicOrbit out{from, 0.0, 0, false};
    State s = from;
    for (int k = 1; k <= max_periods; ++k) {
      double lo = s.x, hi = s.x;
      const State next = period(omega, s, lo, hi);
      const double change = std::max(std::abs(next.x - s.x), std::abs(next.v - s.v));
      s = next;
      out = {s, hi - lo, k, change < tol};
      if (out.converged) break;
    }
    return out;
  }

  // Continuation in frequency: the orbits at omega_from, omega_from + step, ..., omega_to, each
  // started from the previous one's state (a quasi-static sweep); the last orbit.
  PeriodicOrbit continuation(double omega_from, double omega_to, double step, State from) const {
    const int n = static_cast<int>(std::lround(std::abs(omega_to - omega_from) / step));
    PeriodicOrbit o{from, 0.0, 0, false};
    for (int i = 0; i <= n; ++i) {
      o = orbit(omega_from + (omega_to - omega_from) * i / std::max(n, 1), o.start);
      EXPECT_TRUE(o.converged);
    }
    return o;
  }

 private:
  double accel(double omega, double t, const State& s) const {
    return p_.mean_force + p_.alternating_force * std::cos(omega * t) - 2.0 * p_.zeta * s.v -
           restoring(p_, s.x);
  }
  State rk4(double omega, double t, const State& s, double h) const {
    const double k1x = s.v, k1v = accel(omega, t, s);
    const State s2{s.x + 0.5 * h * k1x, s.v + 0.5 * h * k1v};
    const double k2x = s2.v, k2v = accel(omega, t + 0.5 * h, s2);
    const State s3{s.x + 0.5 * h * k2x, s.v + 0.5 * h * k2v};
    const double k3x = s3.v, k3v = accel(omega, t + 0.5 * h, s3);
    const State s4{s.x + h * k3x, s.v + h * k3v};
    const double k4x = s4.v, k4v = accel(omega, t + h, s4);
    return {s.x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x),
            s.v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v)};
  }
  int piece(double x) const { return x > p_.b ? 1 : (x < -p_.b ? -1 : 0); }

  // One forcing period from phase 0; lo / hi collect the extremes of x (at the step ends and
  // the switches: 1000 steps per period sample a peak to (pi / 1000)^2 / 2 = 5e-6 of it).
  State period(double omega, State s, double& lo, double& hi) const {
    const double h = 2.0 * kPi / omega / n_;
    for (int i = 0; i < n_; ++i) {
      double t = i * h, left = h;
      for (int guard = 0; guard < 8 && left > 0.0; ++guard) {
        const State end = rk4(omega, t, s, left);
        if (piece(end.x) == piece(s.x)) {
          s = end;
          left = 0.0;
          break;
        }
        const int from = piece(s.x);
        double a = 0.0, c = left;  // the first switch lies in (a, c]
        while (c - a > 1e-14 * h) {
          const double m = 0.5 * (a + c);
          (piece(rk4(omega, t, s, m).x) == from ? a : c) = m;
        }
        s = rk4(omega, t, s, c);
        t += c;
        left -= c;
        lo = std::min(lo, s.x);
        hi = std::max(hi, s.x);
      }
      if (left > 0.0) s = rk4(omega, t, s, left);
      lo = std::min(lo, s.x);
      hi = std::max(hi, s.x);
    }
    return s;
  }

  Parameters p_;
  int n_;
};

// A reference jump: bisection between the last frequency on the starting branch and the first
// past it, the branch told by the peak-to-peak against a threshold between the branches.
struct Bracket {
  double on_branch = 0.0, off_branch = 0.0;  // frequencies, |difference| <= resolution
  double pp_on = 0.0, pp_off = 0.0;          // peak-to-peak of the orbits there
  double middle() const { return 0.5 * (on_branch + off_branch); }
};

// `a` on the branch (its orbit starts at `on`), `b` past the jump.
inline Bracket bisect_jump(const Rk4Reference& ref, double a, double b, State on, double threshold,
                           bool branch_below_threshold, double resolution) {
  const auto on_branch = [&](const PeriodicOrbit& o) {
    return branch_below_threshold ? o.peak_to_peak < threshold : o.peak_to_peak > threshold;
  };
  const PeriodicOrbit oa = ref.orbit(a, on), ob = ref.orbit(b, oa.start);
  EXPECT_TRUE(on_branch(oa) && !on_branch(ob)) << "no jump between " << a << " and " << b;
  Bracket out{a, b, oa.peak_to_peak, ob.peak_to_peak};
  State state_on = oa.start;
  while (std::abs(out.off_branch - out.on_branch) > resolution) {
    const double m = out.middle();
    const PeriodicOrbit o = ref.orbit(m, state_on);
    EXPECT_TRUE(o.converged) << "reference orbit at Omega = " << m;
    if (on_branch(o)) {
      out.on_branch = m;
      out.pp_on = o.peak_to_peak;
      state_on = o.start;
    } else {
      out.off_branch = m;
      out.pp_off = o.peak_to_peak;
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// The time-domain sweep with the integrator under test.

struct Cycle {
  double omega;         // instantaneous frequency at the middle of the forcing cycle
  double peak_to_peak;  // max x - min x over the cycle
};

struct Sweep {
  std::vector<Cycle> cycles;
  AdaptiveSummary summary;
  double seconds = 0.0;

  // The first cycle whose peak-to-peak crosses `threshold` upward (up) or downward, i.e. after a
  // cycle on the other side (a sweep down from above the resonance starts below the threshold
  // and rises above it before it jumps down): its frequency; NaN when none.
  double jump(double threshold, bool up) const {
    bool armed = false;
    for (const Cycle& c : cycles) {
      const bool past = up ? c.peak_to_peak > threshold : c.peak_to_peak < threshold;
      if (past && armed) return c.omega;
      armed = armed || !past;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }
  // The cycle nearest to frequency omega.
  const Cycle& at(double omega) const {
    return *std::min_element(cycles.begin(), cycles.end(), [&](const Cycle& a, const Cycle& b) {
      return std::abs(a.omega - omega) < std::abs(b.omega - omega);
    });
  }
};

// Error control for the sweeps. The jump frequencies are sensitive to the integrator's error
// near the folds (there the stable orbit and the saddle between the branches are close): with
// an absolute tolerance of 1e-6 the jump-up came 1.7e-4 early; at rtol 1e-7 / atol 1e-8 the
// jumps move by 3e-5 when both are divided by 10.
struct SweepTolerance {
  double relative = 1e-7;
  double absolute = 1e-8;
};

// integrate_adaptive from `start` (the periodic state at phase 0 and omega0) with the frequency
// ramped from omega0 to omega1 at `rate` (signed) [1 / time unit^2].
inline Sweep run_sweep(const Parameters& p, double omega0, double omega1, double rate, State start,
                       SweepTolerance tol = {}) {
  BacklashOscillator system(p, omega0, rate);
  AdaptiveOptions o;
  o.end_time = (omega1 - omega0) / rate;
  o.sample_rate = 40.0;  // > 250 samples per forcing cycle: peaks to (pi / 250)^2 / 2 = 8e-5
  o.max_step = 0.5;      // larger than the error control allows: the samples do not limit h
  o.relative_tolerance = tol.relative;
  o.absolute_tolerance = tol.absolute;
  o.event_tolerance = 1e-9;
  Eigen::VectorXd q = Eigen::VectorXd::Constant(1, start.x);
  Eigen::VectorXd v = Eigen::VectorXd::Constant(1, start.v);
  Sweep out;
  long long cycle = 0;
  double lo = start.x, hi = start.x, t_begin = 0.0;
  const auto clock = std::chrono::steady_clock::now();
  out.summary = integrate_adaptive(
      system, o, q, v,
      [&](long long, double t, const Eigen::VectorXd& x, const Eigen::VectorXd&,
          const Eigen::VectorXd&) {
        const auto k = static_cast<long long>(std::floor(system.phase(t) / (2.0 * kPi)));
        if (k != cycle) {
          out.cycles.push_back({system.frequency(0.5 * (t_begin + t)), hi - lo});
          cycle = k;
          lo = hi = x[0];
          t_begin = t;
        }
        lo = std::min(lo, x[0]);
        hi = std::max(hi, x[0]);
      },
      null_progress());
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
  EXPECT_EQ(out.summary.status, Status::Ok) << out.summary.message;
  return out;
}

// Thresholds between the branches for the jump detection (peak-to-peak): the lower branch ends
// at 0.21 (jump-up) and 0.11 (jump-down), the upper branch at 0.37 and 0.47 there.
inline constexpr double kJumpThreshold = 0.28;

}  // namespace geardyn::transient::backlash
