#include "geardyn/gear/dynamic_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <utility>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::gear {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// Floquet multipliers must be this far inside the unit circle for a fixed point of the
// Poincaré map to count as an (asymptotically stable) steady state.
constexpr double kStabilityMargin = 1e-9;
// Region changes allowed within one interval before the step is declared chattering.
constexpr int kMaxEventsPerInterval = 32;
// Longest cycle the solver accepts (intervals); beyond, the mesh frequency is too low for the
// resolution asked for.
constexpr long kMaxIntervalsPerPeriod = 1L << 22;

enum class Region { Contact, Free, Back };

struct State {
  double x = 0.0, v = 0.0;
};

// 2x2 matrix [[a, b], [c, d]].
struct Mat2 {
  double a = 1.0, b = 0.0, c = 0.0, d = 1.0;
  State operator*(const State& s) const { return {a * s.x + b * s.v, c * s.x + d * s.v}; }
  Mat2 operator*(const Mat2& o) const {
    return {a * o.a + b * o.c, a * o.b + b * o.d, c * o.a + d * o.c, c * o.b + d * o.d};
  }
};

// Largest modulus of the eigenvalues of a 2x2 matrix.
double spectral_radius(const Mat2& m) {
  const double tr = m.a + m.d, det = m.a * m.d - m.b * m.c;
  const std::complex<double> disc = std::sqrt(std::complex<double>(0.25 * tr * tr - det));
  return std::max(std::abs(0.5 * tr + disc), std::abs(0.5 * tr - disc));
}

// exp(A t) for A = [[0, 1], [-w2, -2 s]] (x'' + 2 s x' + w2 x = 0), in closed form:
//   exp(A t) = e^{-s t} [ C(t) I + S(t) (A + s I) ],  with d2 = s^2 - w2 and
//   C = cos(w t), S = sin(w t) / w (d2 = -w^2 < 0), C = cosh, S = sinh / d (d2 = d^2 > 0),
// and their series near d2 t^2 = 0 (critical damping) where both forms lose digits.
Mat2 oscillator_transition(double w2, double s, double t) {
  const double d2 = s * s - w2;
  const double z = d2 * t * t;
  double c = 0.0, sn = 0.0;
  if (std::abs(z) < 1e-6) {
    c = 1.0 + 0.5 * z * (1.0 + z / 12.0);
    sn = t * (1.0 + z / 6.0 * (1.0 + z / 20.0));
  } else if (d2 < 0.0) {
    const double w = std::sqrt(-d2);
    c = std::cos(w * t);
    sn = std::sin(w * t) / w;
  } else {
    const double d = std::sqrt(d2);
    c = std::cosh(d * t);
    sn = std::sinh(d * t) / d;
  }
  const double e = std::exp(-s * t);
  return {e * (c + sn * s), e * sn, -e * sn * w2, e * (c - sn * s)};
}

// phi1(z) = (1 - e^{-z}) / z and phi2(z) = (z - 1 + e^{-z}) / z^2, with their series near 0.
double phi1(double z) {
  if (std::abs(z) < 1e-3)
    return 1.0 - z / 2.0 * (1.0 - z / 3.0 * (1.0 - z / 4.0 * (1.0 - z / 5.0)));
  return -std::expm1(-z) / z;
}
double phi2(double z) {
  if (std::abs(z) < 1e-3)
    return 0.5 - z / 6.0 * (1.0 - z / 4.0 * (1.0 - z / 5.0 * (1.0 - z / 6.0)));
  return (z + std::expm1(-z)) / (z * z);
}

// Root of f on [lo, hi] with f(lo) >= 0 > f(hi), by the Illinois variant of regula falsi with a
// bisection safeguard. Returns the last point with f >= 0 (so the state stays in its region).
template <class F>
double bracketed_root(F&& f, double lo, double f_lo, double hi, double f_hi, double tolerance) {
  int side = 0;
  for (int it = 0; it < 200 && hi - lo > tolerance; ++it) {
    double t = hi - f_hi * (hi - lo) / (f_hi - f_lo);
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
    const double ft = f(t);
    if (ft >= 0.0) {
      lo = t;
      f_lo = ft;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = t;
      f_hi = ft;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return lo;
}

// Per-solve data: the intervals of one mesh period at one mesh frequency.
struct Interval {
  double k = 0.0;       // mesh stiffness on the interval [N/m]
  double g = 0.0;       // unloaded TE at the middle of the interval [m]
  double slope = 0.0;   // de_g/dt on the interval [m/s] (damping on the elastic deflection only)
  double t0 = 0.0;      // start of the interval from the cycle start [s]
  std::size_t phi = 0;  // index of the full-interval transition matrix
};

// Gauss-Legendre, 4 points on [-1, 1].
constexpr std::array<double, 4> kGaussNodes = {-0.8611363115940526, -0.3399810435848563,
                                               0.3399810435848563, 0.8611363115940526};
constexpr std::array<double, 4> kGaussWeights = {0.3478548451374539, 0.6521451548625461,
                                                 0.6521451548625461, 0.3478548451374539};

// A piece of the output: a stretch of one interval spent in one region.
struct Piece {
  std::size_t interval = 0;
  Region region = Region::Contact;
  double t0 = 0.0;    // absolute time from the start of the output
  double from = 0.0;  // start of the piece from the start of its interval
  double dt = 0.0;
  State s0;
};

struct CycleRun {
  State end;
  Mat2 monodromy;
  Status status = Status::Ok;
  std::string why;
};

class Solver {
 public:
  Solver(const DynamicMesh& mesh, double mesh_frequency_hz) {
    const DynamicMeshOptions& o = mesh.options();
    m_ = o.equivalent_mass_kg;
    force_ = o.static_force_n;
    c_ = mesh.damping_n_s_m();
    backlash_ = o.backlash_m;
    contact_loss_ = o.contact_loss;
    elastic_ = o.damping_on == MeshDamping::ElasticDeflection;
    period_ = 1.0 / mesh_frequency_hz;
    force_amplitude_ = o.force_amplitude_n;
    force_omega_ = units::kTwoPi * o.force_order * mesh_frequency_hz;
    force_phase_ = o.force_phase_rad;
    const SteCurve& ste = mesh.ste();
    const std::size_t ns = ste.size();
    // Interval count: a multiple of the STE samples (Hold steps fall on interval boundaries),
    // at least min_points_per_period, and short against the shortest natural period.
    const double shortest_natural_period = units::kTwoPi / std::sqrt(mesh.max_stiffness_n_m() / m_);
    double needed = std::max(static_cast<double>(o.min_points_per_period),
                             o.points_per_natural_period * period_ / shortest_natural_period);
    // The external force as finely as the shortest natural period (region changes are located
    // on the assumption of at most one extremum per interval).
    if (o.force_amplitude_n != 0.0)
      needed = std::max(needed, static_cast<double>(o.points_per_natural_period) * o.force_order);
    const double per_sample = std::ceil(needed / static_cast<double>(ns));
    const double count = per_sample * static_cast<double>(ns);
    if (!(count <= static_cast<double>(kMaxIntervalsPerPeriod))) {
      too_fine_ = true;
      count_ = static_cast<std::size_t>(std::min(count, 1e18));
      return;
    }
    const std::size_t sub = static_cast<std::size_t>(per_sample);
    count_ = ns * sub;
    h_ = period_ / static_cast<double>(count_);
    intervals_.resize(count_);
    const auto& e = ste.ste_m();
    const auto& g = ste.geometric_te_m();
    for (std::size_t j = 0; j < ns; ++j) {
      const double d0 = e[j] - g[j];
      const double d1 = e[(j + 1) % ns] - g[(j + 1) % ns];
      for (std::size_t q = 0; q < sub; ++q) {
        Interval& iv = intervals_[j * sub + q];
        if (ste.interpolation() == SteInterpolation::Hold) {
          iv.k = force_ / d0;
          iv.g = g[j];
        } else {
          // Exact mean of F_s / d over the sub-interval where d is linear from da to db.
          const double ua = static_cast<double>(q) / static_cast<double>(sub);
          const double ub = static_cast<double>(q + 1) / static_cast<double>(sub);
          const double da = d0 + ua * (d1 - d0), db = d0 + ub * (d1 - d0);
          const double r = (db - da) / da;
          const double mean_inverse =
              std::abs(r) < 1e-12 ? (1.0 - 0.5 * r) / da : std::log1p(r) / (db - da);
          iv.k = force_ * mean_inverse;
          const double um = 0.5 * (ua + ub);
          iv.g = g[j] + um * (g[(j + 1) % ns] - g[j]);
          // With the damper on the elastic deflection x - e_g, e_g is followed exactly (linear in
          // time) so that e_g' is the curve's own; otherwise its mean over the interval is used.
          if (elastic_) iv.slope = (g[(j + 1) % ns] - g[j]) / (h_ * static_cast<double>(sub));
        }
        iv.t0 = static_cast<double>(j * sub + q) * h_;
      }
    }
    // Undamped resonance of the external force with a stiffness: no periodic solution.
    if (force_amplitude_ != 0.0) {
      for (const Interval& iv : intervals_) {
        if (std::abs(harmonic_denominator(Region::Contact, iv)) <= 1e-12 * iv.k) {
          resonant_ = true;
          break;
        }
      }
    }
    // Full-interval transition matrices, shared by consecutive intervals of equal stiffness.
    for (std::size_t i = 0; i < count_; ++i) {
      if (i > 0 && intervals_[i].k == intervals_[i - 1].k) {
        intervals_[i].phi = intervals_[i - 1].phi;
        continue;
      }
      intervals_[i].phi = phi_.size();
      phi_.push_back(oscillator_transition(intervals_[i].k / m_, 0.5 * c_ / m_, h_));
    }
    scale_x_ = mesh.static_deflection_m();
    scale_v_ = scale_x_ * std::sqrt(mesh.mean_stiffness_n_m() / m_);
    limit_x_ = o.steady_state.divergence_factor * std::max(scale_x_, mesh.max_ste_m());
  }

  bool too_fine() const { return too_fine_; }
  bool resonant() const { return resonant_; }
  std::size_t count() const { return count_; }
  double period() const { return period_; }
  double h() const { return h_; }

  double scaled_change(const State& a, const State& b) const {
    const double dx = (a.x - b.x) / scale_x_, dv = (a.v - b.v) / scale_v_;
    return std::sqrt(dx * dx + dv * dv);
  }

  // Region of the state at the start of interval i; on a boundary the direction of the relative
  // motion decides (with x' = e_g' the acceleration F_s / m_e > 0 points into contact).
  Region classify(const State& s, const Interval& iv) const {
    if (!contact_loss_) return Region::Contact;
    const double delta = s.x - g_at(iv, 0.0), w = s.v - iv.slope;
    if (delta > 0.0 || (delta == 0.0 && w >= 0.0)) return Region::Contact;
    if (std::isfinite(backlash_)) {
      if (delta < -backlash_ || (delta == -backlash_ && w < 0.0)) return Region::Back;
    }
    return Region::Free;
  }

  // Unloaded TE at time tau from the start of the interval (linear in time on it).
  double g_at(const Interval& iv, double tau) const { return iv.g + iv.slope * (tau - 0.5 * h_); }
  // Stiffness acting and the position where its force vanishes.
  double k_eff(Region r, const Interval& iv) const { return r == Region::Free ? 0.0 : iv.k; }
  double x_c(Region r, const Interval& iv, double tau) const {
    return r == Region::Back ? g_at(iv, tau) - backlash_ : g_at(iv, tau);
  }
  // Damping acting in region r: the tooth damper (elastic deflection) acts in contact only.
  double c_of(Region r) const { return elastic_ && r == Region::Free ? 0.0 : c_; }
  // The damper force c (x' - e_g') (elastic deflection; slope = 0 otherwise) or c x'.
  double damper_force(Region r, const Interval& iv, const State& s) const {
    return c_of(r) * (s.v - iv.slope);
  }
  double external_force(double t_cycle) const {
    return force_ + force_amplitude_ * std::cos(force_omega_ * t_cycle + force_phase_);
  }
  double acceleration(Region r, const Interval& iv, const State& s, double tau) const {
    return (external_force(iv.t0 + tau) - damper_force(r, iv, s) - contact_force(r, iv, s, tau)) /
           m_;
  }
  double contact_force(Region r, const Interval& iv, const State& s, double tau) const {
    return k_eff(r, iv) * (s.x - x_c(r, iv, tau));
  }
  // k_eff - m Omega^2 + i c Omega: the harmonic force's particular solution is
  // Re(F_a / denominator exp(i (Omega t + phi))).
  std::complex<double> harmonic_denominator(Region r, const Interval& iv) const {
    return {k_eff(r, iv) - m_ * force_omega_ * force_omega_, c_of(r) * force_omega_};
  }
  // The harmonic particular solution (x, x') at cycle time t_cycle.
  State harmonic_state(Region r, const Interval& iv, double t_cycle) const {
    const std::complex<double> amplitude = force_amplitude_ / harmonic_denominator(r, iv);
    const std::complex<double> rotor =
        amplitude * std::polar(1.0, force_omega_ * t_cycle + force_phase_);
    return {rotor.real(), -force_omega_ * rotor.imag()};
  }

  // Exact state after time t in region r from s0, which holds at time `from` after the start of
  // the interval; the transition matrix in *phi. The solution is the homogeneous one (the
  // transition matrix) around the particular solution of the forcing on the interval: F_s and
  // k e_g with e_g linear in time (x_p = x_c(t) + F_s / k, x_p' = e_g': with e_g' != 0 only for
  // damping on the elastic deflection, c (x_p' - e_g') = 0 holds exactly) and the harmonic force.
  State evaluate(Region r, const Interval& iv, const State& s0, double from, double t, bool full,
                 Mat2* phi = nullptr) const {
    State h0{}, h1{};
    if (force_amplitude_ != 0.0) {
      h0 = harmonic_state(r, iv, iv.t0 + from);
      h1 = harmonic_state(r, iv, iv.t0 + from + t);
    }
    const State q{s0.x - h0.x, s0.v - h0.v};
    if (r == Region::Free) {
      const double beta = c_of(r) / m_, a = force_ / m_;
      const double z = beta * t;
      const double e1 = t * phi1(z);
      const double e0 = std::exp(-z);
      if (phi) *phi = Mat2{1.0, e1, 0.0, e0};
      return {q.x + e1 * q.v + a * t * t * phi2(z) + h1.x, e0 * q.v + a * e1 + h1.v};
    }
    const Mat2 p =
        full && from == 0.0 ? phi_[iv.phi] : oscillator_transition(iv.k / m_, 0.5 * c_ / m_, t);
    if (phi) *phi = p;
    const double shift = force_ / iv.k;
    const State d = p * State{q.x - (x_c(r, iv, from) + shift), q.v - iv.slope};
    return {(x_c(r, iv, from + t) + shift) + d.x + h1.x, iv.slope + d.v + h1.v};
  }

  // Saltation matrix at a change of region with damping on the elastic deflection: the damper
  // force c (x' - e_g') appears (entering contact) or vanishes (leaving it) on the surface
  // x = x_c(t), so the acceleration jumps by Delta a = -/+ c w / m_e with w = x' - e_g' the
  // crossing speed. With the event function x - x_c(t), S = I + (0, Delta a)^T (1, 0) / w
  // = [[1, 0], [-/+ c / m_e, 1]], independent of w. Identity when the damping is unchanged.
  Mat2 saltation(Region from, Region to) const {
    const double jump = c_of(to) - c_of(from);
    return Mat2{1.0, 0.0, -jump / m_, 1.0};
  }

  // One boundary of a region: d(t) = dir (x - e_g(t) - offset) >= 0 inside; crossing leads to
  // `next`.
  struct Boundary {
    double offset;
    double dir;
    Region next;
  };

  int boundaries(Region r, std::array<Boundary, 2>& out) const {
    switch (r) {
      case Region::Contact:
        out[0] = {0.0, 1.0, Region::Free};
        return 1;
      case Region::Free:
        out[0] = {0.0, -1.0, Region::Contact};
        if (std::isfinite(backlash_)) {
          out[1] = {-backlash_, 1.0, Region::Back};
          return 2;
        }
        return 1;
      case Region::Back:
        out[0] = {-backlash_, -1.0, Region::Free};
        return 1;
    }
    return 0;
  }

  // Time (from `done`, within len) at which the state first leaves `region` through boundary b
  // on the interval; infinity when it stays.
  double crossing(Region region, const Interval& iv, const State& s, double done, double len,
                  const State& end, const Boundary& b) const {
    const double tolerance = 1e-14 * h_;
    const double ws = s.v - iv.slope, we = end.v - iv.slope;
    auto surface = [&](double t) { return g_at(iv, done + t) + b.offset; };
    auto distance = [&](double t) {
      return b.dir * (evaluate(region, iv, s, done, t, false).x - surface(t));
    };
    const double d0 = b.dir * (s.x - surface(0.0));
    const double d1 = b.dir * (end.x - surface(len));
    double hi = -1.0, d_hi = 0.0;
    if (d1 < 0.0) {
      hi = len;
      d_hi = d1;
    } else if (b.dir * ws < 0.0 && b.dir * we > 0.0) {
      // d has one interior minimum (an interval is shorter than half a natural period): find it
      // from d' = dir (x' - e_g'), then check whether it dips below the surface.
      auto slope = [&](double t) {
        return -b.dir * (evaluate(region, iv, s, done, t, false).v - iv.slope);
      };
      const double tm = bracketed_root(slope, 0.0, -b.dir * ws, len, -b.dir * we, tolerance);
      const double dm = distance(tm);
      if (dm < 0.0) {
        hi = tm;
        d_hi = dm;
      }
    }
    if (!(hi > 0.0)) return kInf;
    return bracketed_root(distance, 0.0, std::max(d0, 0.0), hi, d_hi, tolerance);
  }

  // Advances the state over the whole interval i (from its start), handling region changes.
  // Appends the pieces to `pieces` when given. Returns false when the region chatters.
  bool advance(std::size_t i, State& s, Mat2& monodromy, double t_start,
               std::vector<Piece>* pieces) const {
    const Interval& iv = intervals_[i];
    Region region = classify(s, iv);
    double done = 0.0;
    for (int events = 0; events <= kMaxEventsPerInterval; ++events) {
      const double len = h_ - done;
      Mat2 phi;
      const State end = evaluate(region, iv, s, done, len, true, &phi);
      double tau = kInf;
      Region next = region;
      double offset = 0.0;
      if (contact_loss_) {
        std::array<Boundary, 2> bs;
        const int nb = boundaries(region, bs);
        for (int q = 0; q < nb; ++q) {
          const Boundary& b = bs[static_cast<std::size_t>(q)];
          const double t = crossing(region, iv, s, done, len, end, b);
          if (t < tau) {
            tau = t;
            next = b.next;
            offset = b.offset;
          }
        }
      }
      if (tau == kInf) {
        if (pieces) pieces->push_back({i, region, t_start + done, done, len, s});
        s = end;
        monodromy = phi * monodromy;
        return true;
      }
      Mat2 phi_tau;
      State at = evaluate(region, iv, s, done, tau, false, &phi_tau);
      if (pieces && tau > 0.0) pieces->push_back({i, region, t_start + done, done, tau, s});
      monodromy = phi_tau * monodromy;
      if (c_of(next) != c_of(region)) monodromy = saltation(region, next) * monodromy;
      // On the boundary exactly (the root is accurate to ~1e-14 of h).
      at.x = g_at(iv, done + tau) + offset;
      s = at;
      region = next;
      done += tau;
    }
    return false;
  }

  CycleRun run_cycle(State s, std::vector<Piece>* pieces, std::vector<State>* grid,
                     double t_offset) const {
    CycleRun run;
    for (std::size_t i = 0; i < count_; ++i) {
      if (grid) grid->push_back(s);
      if (!advance(i, s, run.monodromy, t_offset + static_cast<double>(i) * h_, pieces)) {
        run.status = Status::Failed;
        run.why = fmt::format(
            "the contact state changed more than {} times within one interval at t = {:.6g} s "
            "(chattering at grazing contact); raise min_points_per_period",
            kMaxEventsPerInterval, t_offset + static_cast<double>(i) * h_);
        return run;
      }
      if (!std::isfinite(s.x) || !std::isfinite(s.v) || std::abs(s.x) > limit_x_) {
        run.status = Status::Diverged;
        run.why = fmt::format(
            "|x| = {:.4g} m exceeds {:.4g} m (divergence_factor x the largest "
            "static deflection)",
            std::abs(s.x), limit_x_);
        return run;
      }
    }
    run.end = s;
    return run;
  }

  // Statistics over the recorded pieces: Gauss quadrature for the means, exact extrema.
  void statistics(const std::vector<Piece>& pieces, double span, MeshResponse& r) const {
    double sx = 0.0, sxx = 0.0, sf = 0.0, t_loss = 0.0, t_back = 0.0;
    double xmax = -kInf, xmin = kInf, fmax = -kInf, fmin = kInf;
    const double tolerance = 1e-14 * h_;
    for (const Piece& p : pieces) {
      const Interval& iv = intervals_[p.interval];
      const double ke = k_eff(p.region, iv), cr = c_of(p.region);
      // F_d = k_eff (x - x_c) + c (x' - e_g') at time t after the start of the piece.
      auto force_of = [&](const State& s, double t) {
        return contact_force(p.region, iv, s, p.from + t) + damper_force(p.region, iv, s);
      };
      // F_d' = k_eff (x' - e_g') + c x'' (e_g'' = 0 on an interval).
      auto force_rate = [&](const State& s, double t) {
        return ke * (s.v - iv.slope) + cr * acceleration(p.region, iv, s, p.from + t);
      };
      auto at = [&](double t) { return evaluate(p.region, iv, p.s0, p.from, t, false); };
      const State end = evaluate(p.region, iv, p.s0, p.from, p.dt, p.dt == h_);
      for (std::size_t q = 0; q < kGaussNodes.size(); ++q) {
        const double t = 0.5 * p.dt * (1.0 + kGaussNodes[q]);
        const State s = at(t);
        const double w = 0.5 * p.dt * kGaussWeights[q];
        sx += w * s.x;
        sxx += w * s.x * s.x;
        sf += w * force_of(s, t);
      }
      if (p.region == Region::Free) t_loss += p.dt;
      if (p.region == Region::Back) t_back += p.dt;
      for (const auto& [s, t] : {std::pair{p.s0, 0.0}, std::pair{end, p.dt}}) {
        xmax = std::max(xmax, s.x);
        xmin = std::min(xmin, s.x);
        fmax = std::max(fmax, force_of(s, t));
        fmin = std::min(fmin, force_of(s, t));
      }
      // Interior extrema: at most one of each function per piece (pieces are short).
      if ((p.s0.v > 0.0) != (end.v > 0.0)) {
        const double sign = p.s0.v > 0.0 ? 1.0 : -1.0;
        auto f = [&](double t) { return sign * at(t).v; };
        const double t = bracketed_root(f, 0.0, sign * p.s0.v, p.dt, sign * end.v, tolerance);
        const double x = at(t).x;
        xmax = std::max(xmax, x);
        xmin = std::min(xmin, x);
      }
      const double r0 = force_rate(p.s0, 0.0), r1 = force_rate(end, p.dt);
      if ((r0 > 0.0) != (r1 > 0.0)) {
        const double sign = r0 > 0.0 ? 1.0 : -1.0;
        auto f = [&](double t) { return sign * force_rate(at(t), t); };
        const double t = bracketed_root(f, 0.0, sign * r0, p.dt, sign * r1, tolerance);
        const double fd = force_of(at(t), t);
        fmax = std::max(fmax, fd);
        fmin = std::min(fmin, fd);
      }
    }
    r.dte_mean_m = sx / span;
    r.dte_rms_m = std::sqrt(std::max(0.0, sxx / span - r.dte_mean_m * r.dte_mean_m));
    r.dte_max_m = xmax;
    r.dte_min_m = xmin;
    r.force_mean_n = sf / span;
    r.force_max_n = fmax;
    r.force_min_n = fmin;
    r.dynamic_factor = fmax / force_;
    r.contact_loss_fraction = (t_loss + t_back) / span;
    r.back_contact_fraction = t_back / span;
  }

  // Records `cycles` cycles from s on the grid and the statistics.
  CycleRun output(const State& s, int cycles, MeshResponse& r) const {
    std::vector<Piece> pieces;
    std::vector<State> grid;
    pieces.reserve(count_ * static_cast<std::size_t>(cycles) + 16);
    grid.reserve(count_ * static_cast<std::size_t>(cycles));
    CycleRun total;
    State at = s;
    for (int n = 0; n < cycles; ++n) {
      CycleRun run = run_cycle(at, &pieces, &grid, n * period_);
      if (run.status != Status::Ok) return run;
      total.monodromy = run.monodromy * total.monodromy;
      at = run.end;
    }
    total.end = at;
    r.time_s.resize(grid.size());
    r.dte_m.resize(grid.size());
    r.velocity_m_s.resize(grid.size());
    r.force_n.resize(grid.size());
    r.contact_force_n.resize(grid.size());
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const Interval& iv = intervals_[i % count_];
      const Region region = classify(grid[i], iv);
      r.time_s[i] = static_cast<double>(i) * h_;
      r.dte_m[i] = grid[i].x;
      r.velocity_m_s[i] = grid[i].v;
      r.contact_force_n[i] = contact_force(region, iv, grid[i], 0.0);
      r.force_n[i] = r.contact_force_n[i] + damper_force(region, iv, grid[i]);
    }
    statistics(pieces, cycles * period_, r);
    return total;
  }

 private:
  double m_ = 0.0, force_ = 0.0, c_ = 0.0, backlash_ = kInf;
  bool contact_loss_ = true, elastic_ = false, resonant_ = false;
  double force_amplitude_ = 0.0, force_omega_ = 0.0, force_phase_ = 0.0;
  double period_ = 0.0, h_ = 0.0;
  std::size_t count_ = 0;
  bool too_fine_ = false;
  std::vector<Interval> intervals_;
  std::vector<Mat2> phi_;
  double scale_x_ = 1.0, scale_v_ = 1.0, limit_x_ = kInf;
};

void check_positive(double value, const char* key, const char* expected) {
  if (!(std::isfinite(value) && value > 0.0))
    throw InputError(SourceLocation{}, key, expected, fmt::format("{}", value));
}

}  // namespace

double equivalent_mass(double inertia1_kgm2, double inertia2_kgm2, double base_radius1_m,
                       double base_radius2_m) {
  const auto check = [](double v, const char* key) {
    if (!(v > 0.0) || std::isnan(v))
      throw InputError(SourceLocation{}, key, "a value > 0 (inertia may be infinite)",
                       fmt::format("{}", v));
  };
  check(inertia1_kgm2, "gear_pair.inertia1_kgm2");
  check(inertia2_kgm2, "gear_pair.inertia2_kgm2");
  check_positive(base_radius1_m, "gear_pair.base_radius1_m", "a base radius > 0 m");
  check_positive(base_radius2_m, "gear_pair.base_radius2_m", "a base radius > 0 m");
  if (std::isinf(inertia1_kgm2) && std::isinf(inertia2_kgm2))
    throw InputError(SourceLocation{}, "gear_pair.inertia1_kgm2",
                     "at least one finite inertia (two infinite inertias: use the infinite-inertia "
                     "model)",
                     "both infinite");
  if (std::isinf(inertia1_kgm2)) return inertia2_kgm2 / (base_radius2_m * base_radius2_m);
  if (std::isinf(inertia2_kgm2)) return inertia1_kgm2 / (base_radius1_m * base_radius1_m);
  return inertia1_kgm2 * inertia2_kgm2 /
         (inertia1_kgm2 * base_radius2_m * base_radius2_m +
          inertia2_kgm2 * base_radius1_m * base_radius1_m);
}

double mesh_frequency_hz(double speed_rpm, int teeth) {
  if (teeth < 1)
    throw InputError(SourceLocation{}, "teeth", "a tooth count >= 1", fmt::format("{}", teeth));
  if (!std::isfinite(speed_rpm) || speed_rpm < 0.0)
    throw InputError(SourceLocation{}, "speed_rpm", "a finite speed >= 0 rpm",
                     fmt::format("{}", speed_rpm));
  return units::rpm_to_hz(speed_rpm) * teeth;
}

void DynamicMeshOptions::validate() const {
  if (model == MeshModel::Dynamic)
    check_positive(equivalent_mass_kg, "dynamic_mesh.equivalent_mass_kg", "a mass > 0 kg");
  check_positive(static_force_n, "dynamic_mesh.static_force_n",
                 "a static mesh force F_s = T / r_b > 0 N");
  if (!(std::isfinite(damping_ratio) && damping_ratio >= 0.0))
    throw InputError(SourceLocation{}, "dynamic_mesh.damping_ratio", "a damping ratio >= 0",
                     fmt::format("{}", damping_ratio));
  if (!(backlash_m > 0.0))
    throw InputError(SourceLocation{}, "dynamic_mesh.backlash_m",
                     "a backlash > 0 m (infinity: none)", fmt::format("{}", backlash_m));
  if (std::isfinite(backlash_m) && !contact_loss)
    throw InputError(SourceLocation{}, "dynamic_mesh.backlash_m",
                     "no backlash with the linear model (contact_loss = false)",
                     fmt::format("{} m", backlash_m));
  if (min_points_per_period < 4 || min_points_per_period > (1 << 20))
    throw InputError(SourceLocation{}, "dynamic_mesh.min_points_per_period",
                     "an integer in [4, 2^20]", fmt::format("{}", min_points_per_period));
  if (points_per_natural_period < 8 || points_per_natural_period > 4096)
    throw InputError(SourceLocation{}, "dynamic_mesh.points_per_natural_period",
                     "an integer in [8, 4096] (an interval must stay below half a natural period)",
                     fmt::format("{}", points_per_natural_period));
  if (!(std::isfinite(force_amplitude_n) && force_amplitude_n >= 0.0))
    throw InputError(SourceLocation{}, "dynamic_mesh.force_amplitude_n",
                     "a finite force amplitude >= 0 N", fmt::format("{}", force_amplitude_n));
  if (force_order < 1 || force_order > 1000)
    throw InputError(SourceLocation{}, "dynamic_mesh.force_order",
                     "an integer harmonic of the mesh frequency in [1, 1000]",
                     fmt::format("{}", force_order));
  if (!std::isfinite(force_phase_rad))
    throw InputError(SourceLocation{}, "dynamic_mesh.force_phase_rad", "a finite phase",
                     fmt::format("{}", force_phase_rad));
  const SteadyStateOptions& s = steady_state;
  if (!(s.tolerance > 0.0 && s.tolerance < 1.0))
    throw InputError(SourceLocation{}, "dynamic_mesh.steady_state.tolerance", "a value in (0, 1)",
                     fmt::format("{}", s.tolerance));
  if (s.max_cycles < 1)
    throw InputError(SourceLocation{}, "dynamic_mesh.steady_state.max_cycles", "an integer >= 1",
                     fmt::format("{}", s.max_cycles));
  if (s.max_period < 1 || s.max_period > 64)
    throw InputError(SourceLocation{}, "dynamic_mesh.steady_state.max_period",
                     "an integer in [1, 64]", fmt::format("{}", s.max_period));
  if (!(s.divergence_factor > 1.0))
    throw InputError(SourceLocation{}, "dynamic_mesh.steady_state.divergence_factor",
                     "a factor > 1", fmt::format("{}", s.divergence_factor));
}

DynamicMesh::DynamicMesh(SteCurve ste, DynamicMeshOptions options)
    : ste_(std::move(ste)), options_(std::move(options)) {
  options_.validate();
  k_mean_ = options_.static_force_n * ste_.mean_inverse_elastic_per_m();
  double d_min = kInf;
  for (std::size_t j = 0; j < ste_.size(); ++j) {
    d_min = std::min(d_min, ste_.ste_m()[j] - ste_.geometric_te_m()[j]);
    e_max_ = std::max(e_max_, std::abs(ste_.ste_m()[j]));
  }
  k_max_ = options_.static_force_n / d_min;
  if (options_.model == MeshModel::Dynamic &&
      options_.damping_on == MeshDamping::ElasticDeflection &&
      ste_.interpolation() == SteInterpolation::Hold) {
    const auto& g = ste_.geometric_te_m();
    if (std::any_of(g.begin(), g.end(), [&](double v) { return v != g.front(); }))
      throw InputError(SourceLocation{}, "dynamic_mesh.damping_on",
                       "a continuous unloaded TE e_g for damping on the elastic deflection (its "
                       "damper force c (x' - e_g') would be an impulse at every step of a held "
                       "curve): a linear interpolation of the STE, or damping on the DTE",
                       "a step (hold) curve with a varying unloaded TE");
  }
  if (options_.model == MeshModel::Dynamic)
    damping_ = 2.0 * options_.damping_ratio * std::sqrt(k_mean_ * options_.equivalent_mass_kg);
}

double DynamicMesh::natural_frequency_hz() const {
  return std::sqrt(k_mean_ / options_.equivalent_mass_kg) / units::kTwoPi;
}

MeshState DynamicMesh::static_state() const {
  const double d0 = ste_.ste_m()[0] - ste_.geometric_te_m()[0];
  return {ste_.geometric_te_m()[0] + d0, 0.0};
}

namespace {

// The infinite-inertia (quasi-static) response: F_d = F_s k(t) / k_mean with x = F_s / k_mean,
// the gears turning at constant speed.
void quasi_static_response(const SteCurve& ste, const DynamicMeshOptions& options, double x,
                           double period, MeshResponse& r) {
  // F_d = F_s k(t) / k_mean with x = F_s / k_mean: the gears turn at constant speed.
  const std::size_t ns = ste.size();
  const std::size_t sub = static_cast<std::size_t>(
      std::ceil(static_cast<double>(options.min_points_per_period) / static_cast<double>(ns)));
  const std::size_t n = ns * sub;
  r.points_per_period = static_cast<int>(n);
  r.period_cycles = 1;
  r.force_max_n = -kInf;
  r.force_min_n = kInf;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = static_cast<double>(i) / static_cast<double>(n);
    const double k = options.static_force_n / (ste.ste_at(u) - ste.geometric_at(u));
    r.time_s.push_back(u * period);
    r.dte_m.push_back(x);
    r.velocity_m_s.push_back(0.0);
    r.contact_force_n.push_back(k * x);
    r.force_n.push_back(k * x);
  }
  // Extrema of k(t) lie at the samples for both interpolations.
  for (std::size_t j = 0; j < ns; ++j) {
    const double k = options.static_force_n / (ste.ste_m()[j] - ste.geometric_te_m()[j]);
    r.force_max_n = std::max(r.force_max_n, k * x);
    r.force_min_n = std::min(r.force_min_n, k * x);
  }
  r.dte_mean_m = r.dte_max_m = r.dte_min_m = x;
  r.dte_rms_m = 0.0;
  r.force_mean_n = options.static_force_n;  // k_mean x by definition of k_mean
  r.dynamic_factor = r.force_max_n / options.static_force_n;
  r.contact_loss_fraction = 0.0;
  r.back_contact_fraction = 0.0;
  r.start_state = {x, 0.0};
  r.status = Status::Ok;
}

// The search for a stable periodic steady state: cycles from the start state, with Newton steps
// on the Poincaré map now and then.
struct OrbitSearch {
  int period_cycles = 0;  // 0: none found
  State orbit_start;
  double rejected_multiplier = kNaN;
  std::string failure;
  Status failure_status = Status::Ok;
  int cycle = 0;
};

OrbitSearch search_periodic_orbit(const Solver& solver, const SteadyStateOptions& ss, State s,
                                  MeshResponse& r) {
  OrbitSearch o;
  std::vector<State> history{s};  // Poincaré points, newest last
  int next_newton = 1, newton_gap = 4;
  while (o.cycle < ss.max_cycles && o.period_cycles == 0) {
    const CycleRun run = solver.run_cycle(s, nullptr, nullptr, 0.0);
    ++o.cycle;
    if (run.status != Status::Ok) {
      o.failure_status = run.status;
      o.failure = run.why;
      break;
    }
    r.poincare_change = solver.scaled_change(run.end, s);
    history.push_back(run.end);
    if (r.poincare_change < ss.tolerance) {
      o.period_cycles = 1;
      o.orbit_start = run.end;
      break;
    }
    for (int p = 2; p <= ss.max_period && static_cast<std::size_t>(p) < history.size(); ++p) {
      if (solver.scaled_change(history.back(),
                               history[history.size() - 1 - static_cast<std::size_t>(p)]) <
          ss.tolerance) {
        o.period_cycles = p;
        o.orbit_start = run.end;
        break;
      }
    }
    if (o.period_cycles > 0) break;
    if (history.size() > static_cast<std::size_t>(ss.max_period) + 2)
      history.erase(history.begin());

    if (ss.newton && o.cycle >= next_newton) {
      // Newton on G(y) = P(y) - y with G' = M - I, from the newest Poincaré point.
      State y = run.end;
      for (int it = 0; it < 12 && o.cycle < ss.max_cycles; ++it) {
        const CycleRun ny = solver.run_cycle(y, nullptr, nullptr, 0.0);
        ++o.cycle;
        ++r.newton_iterations;
        if (ny.status != Status::Ok) break;
        const double change = solver.scaled_change(ny.end, y);
        if (change < ss.tolerance) {
          const double rho = spectral_radius(ny.monodromy);
          if (rho < 1.0 - kStabilityMargin) {
            o.period_cycles = 1;
            o.orbit_start = y;
            r.poincare_change = change;
          } else {
            o.rejected_multiplier = rho;
          }
          break;
        }
        const Mat2& m = ny.monodromy;
        const double a = 1.0 - m.a, b = -m.b, c = -m.c, d = 1.0 - m.d;
        const double det = a * d - b * c;
        if (!(std::abs(det) > 1e-14)) break;
        const double gx = ny.end.x - y.x, gv = ny.end.v - y.v;
        y = State{y.x + (d * gx - b * gv) / det, y.v + (-c * gx + a * gv) / det};
        if (!std::isfinite(y.x) || !std::isfinite(y.v)) break;
      }
      if (o.period_cycles > 0) break;
      next_newton = o.cycle + newton_gap;
      newton_gap = std::min(2 * newton_gap, 256);
    }
    s = run.end;
  }
  return o;
}

// Status and message when no periodic steady state was found.
void report_no_orbit(const OrbitSearch& o, const SteadyStateOptions& ss, double mesh_frequency_hz,
                     MeshResponse& r) {
  r.status = o.failure_status != Status::Ok ? o.failure_status : Status::NotConverged;
  if (o.failure_status == Status::Diverged) {
    r.message = fmt::format(
        "the response grows without bound at f_m = {:.6g} Hz after {} mesh "
        "cycles: {}",
        mesh_frequency_hz, o.cycle, o.failure);
    if (!std::isnan(o.rejected_multiplier))
      r.message += fmt::format(
          "; the periodic solution is unstable (largest Floquet multiplier "
          "|mu| = {:.6g}: parametric instability)",
          o.rejected_multiplier);
    r.message += "; add damping or leave this speed range";
  } else if (o.failure_status != Status::Ok) {
    r.message = fmt::format("f_m = {:.6g} Hz: {}", mesh_frequency_hz, o.failure);
  } else {
    r.message = fmt::format(
        "no periodic steady state (period <= {} mesh cycles) after {} mesh cycles at f_m = "
        "{:.6g} Hz; last Poincaré change {:.3g} (tolerance {:.3g})",
        ss.max_period, o.cycle, mesh_frequency_hz, r.poincare_change, ss.tolerance);
    if (!std::isnan(o.rejected_multiplier))
      r.message += fmt::format(
          "; a periodic solution exists but is not asymptotically stable "
          "(largest Floquet multiplier |mu| = {:.6g})",
          o.rejected_multiplier);
    r.message +=
        "; the response may be quasi-periodic or chaotic (contact loss) or too lightly "
        "damped: raise max_cycles, max_period or the damping ratio";
  }
}

}  // namespace

MeshResponse DynamicMesh::solve(double mesh_frequency_hz, const MeshState* initial) const {
  if (!(std::isfinite(mesh_frequency_hz) && mesh_frequency_hz > 0.0))
    throw InputError(SourceLocation{}, "mesh_frequency_hz", "a mesh frequency > 0 Hz",
                     fmt::format("{}", mesh_frequency_hz));
  MeshResponse r;
  r.mesh_frequency_hz = mesh_frequency_hz;
  const double period = 1.0 / mesh_frequency_hz;

  if (options_.model == MeshModel::InfiniteInertia) {
    quasi_static_response(ste_, options_, static_deflection_m(), period, r);
    return r;
  }

  const Solver solver(*this, mesh_frequency_hz);
  if (solver.too_fine()) {
    r.status = Status::Failed;
    r.message = fmt::format(
        "mesh frequency {:.6g} Hz is too low against the natural frequency {:.6g} Hz: one mesh "
        "period would need {} intervals; use the quasi-static limit (infinite-inertia model) there",
        mesh_frequency_hz, natural_frequency_hz(), solver.count());
    return r;
  }
  r.points_per_period = static_cast<int>(solver.count());
  if (solver.resonant()) {
    r.status = Status::Failed;
    r.message = fmt::format(
        "the external force (order {}, {:.6g} Hz) meets an undamped natural frequency of the "
        "mesh at f_m = {:.6g} Hz: no periodic steady state; add mesh damping or change the "
        "force order",
        options_.force_order, options_.force_order * mesh_frequency_hz, mesh_frequency_hz);
    return r;
  }
  const SteadyStateOptions& ss = options_.steady_state;
  State s = initial ? State{initial->x_m, initial->v_m_s} : State{static_state().x_m, 0.0};
  if (!std::isfinite(s.x) || !std::isfinite(s.v)) s = State{static_state().x_m, 0.0};

  const OrbitSearch o = search_periodic_orbit(solver, ss, s, r);
  const int period_cycles = o.period_cycles;
  const State orbit_start = o.orbit_start;
  r.transient_cycles = o.cycle;

  if (period_cycles == 0) {
    report_no_orbit(o, ss, mesh_frequency_hz, r);
    return r;
  }

  r.period_cycles = period_cycles;
  r.start_state = {orbit_start.x, orbit_start.v};
  const CycleRun out = solver.output(orbit_start, period_cycles, r);
  if (out.status != Status::Ok) {
    r.status = out.status;
    r.message = fmt::format("f_m = {:.6g} Hz, while recording the steady state: {}",
                            mesh_frequency_hz, out.why);
    return r;
  }
  r.floquet_multiplier = spectral_radius(out.monodromy);
  if (!(r.floquet_multiplier < 1.0 - kStabilityMargin)) {
    r.status = Status::NotConverged;
    r.message = fmt::format(
        "f_m = {:.6g} Hz: the periodic solution found is not asymptotically stable (largest "
        "Floquet multiplier |mu| = {:.9g}); without damping transients never decay",
        mesh_frequency_hz, r.floquet_multiplier);
    return r;
  }
  r.status = Status::Ok;
  if (period_cycles > 1)
    r.message = fmt::format("period-{} subharmonic steady state ({} mesh cycles per period)",
                            period_cycles, period_cycles);
  return r;
}

MeshState DynamicMesh::poincare_map(double mesh_frequency_hz, const MeshState& start,
                                    std::array<double, 4>* monodromy) const {
  if (!(std::isfinite(mesh_frequency_hz) && mesh_frequency_hz > 0.0))
    throw InputError(SourceLocation{}, "mesh_frequency_hz", "a mesh frequency > 0 Hz",
                     fmt::format("{}", mesh_frequency_hz));
  if (options_.model != MeshModel::Dynamic)
    throw InputError(SourceLocation{}, "dynamic_mesh.model", "the dynamic model for a Poincaré map",
                     "the infinite-inertia model");
  const Solver solver(*this, mesh_frequency_hz);
  if (solver.too_fine())
    throw NumericalError("dynamic mesh", fmt::format("mesh frequency {:.6g} Hz: {} intervals per "
                                                     "period are too many",
                                                     mesh_frequency_hz, solver.count()));
  const CycleRun run = solver.run_cycle(State{start.x_m, start.v_m_s}, nullptr, nullptr, 0.0);
  if (run.status != Status::Ok) throw NumericalError("dynamic mesh", run.why);
  if (monodromy) *monodromy = {run.monodromy.a, run.monodromy.b, run.monodromy.c, run.monodromy.d};
  return {run.end.x, run.end.v};
}

// --- sweep -----------------------------------------------------------------------------------

Table MeshSweepResult::table(const std::vector<MeshSweepPoint>& points, std::string name,
                             std::string title) {
  Table t;
  t.name = std::move(name);
  t.title = std::move(title);
  auto column = [&](const char* n, const char* unit, auto field) {
    std::vector<double> v;
    v.reserve(points.size());
    for (const MeshSweepPoint& p : points) v.push_back(field(p));
    t.add(n, unit, std::move(v));
  };
  column("mesh_frequency_hz", "Hz", [](const MeshSweepPoint& p) { return p.mesh_frequency_hz; });
  column("speed_rpm", "rpm", [](const MeshSweepPoint& p) { return p.speed_rpm; });
  column("dte_mean_m", "m", [](const MeshSweepPoint& p) { return p.dte_mean_m; });
  column("dte_rms_m", "m", [](const MeshSweepPoint& p) { return p.dte_rms_m; });
  column("dte_min_m", "m", [](const MeshSweepPoint& p) { return p.dte_min_m; });
  column("dte_max_m", "m", [](const MeshSweepPoint& p) { return p.dte_max_m; });
  column("force_min_n", "N", [](const MeshSweepPoint& p) { return p.force_min_n; });
  column("force_max_n", "N", [](const MeshSweepPoint& p) { return p.force_max_n; });
  column("dynamic_factor", "", [](const MeshSweepPoint& p) { return p.dynamic_factor; });
  column("contact_loss", "", [](const MeshSweepPoint& p) { return p.contact_loss_fraction; });
  column("floquet_multiplier", "", [](const MeshSweepPoint& p) { return p.floquet_multiplier; });
  column("period_cycles", "",
         [](const MeshSweepPoint& p) { return static_cast<double>(p.period_cycles); });
  column("cycles", "", [](const MeshSweepPoint& p) { return static_cast<double>(p.cycles); });
  std::vector<std::string> status;
  std::vector<std::string> message;
  for (const MeshSweepPoint& p : points) {
    status.emplace_back(to_string(p.status));
    message.push_back(p.message);
  }
  t.add_text("status", std::move(status));
  t.add_text("message", std::move(message));
  return t;
}

MeshSweepResult sweep_mesh_frequency(const DynamicMesh& mesh, const MeshSweepOptions& options,
                                     Progress& progress) {
  const auto& f = options.mesh_frequencies_hz;
  if (f.empty())
    throw InputError(SourceLocation{}, "sweep.mesh_frequencies_hz", "at least one mesh frequency",
                     "none");
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!(std::isfinite(f[i]) && f[i] > 0.0))
      throw InputError(SourceLocation{}, fmt::format("sweep.mesh_frequencies_hz[{}]", i),
                       "a mesh frequency > 0 Hz", fmt::format("{}", f[i]));
    if (i > 0 && !(f[i] > f[i - 1]))
      throw InputError(SourceLocation{}, fmt::format("sweep.mesh_frequencies_hz[{}]", i),
                       "strictly increasing mesh frequencies",
                       fmt::format("{} after {}", f[i], f[i - 1]));
  }
  if (options.teeth < 0)
    throw InputError(SourceLocation{}, "sweep.teeth", "a tooth count >= 1 (0: no speed column)",
                     fmt::format("{}", options.teeth));
  MeshSweepResult result;
  const bool up = options.direction != SweepDirection::Down;
  const bool down = options.direction != SweepDirection::Up;
  progress.start("mesh frequency sweep", (up ? f.size() : 0) + (down ? f.size() : 0));
  std::size_t done = 0;
  int not_ok = 0;
  auto run = [&](bool increasing, std::vector<MeshSweepPoint>& points,
                 std::vector<MeshResponse>& keep) {
    MeshState previous{};
    bool have_previous = false;
    for (std::size_t q = 0; q < f.size(); ++q) {
      const std::size_t i = increasing ? q : f.size() - 1 - q;
      MeshResponse r = mesh.solve(f[i], have_previous ? &previous : nullptr);
      // Continue from this steady state; after a failure restart from the static equilibrium.
      have_previous = r.status == Status::Ok;
      previous = r.start_state;
      MeshSweepPoint p;
      p.mesh_frequency_hz = f[i];
      p.speed_rpm = options.teeth > 0 ? units::hz_to_rpm(f[i]) / options.teeth : kNaN;
      p.dte_mean_m = r.dte_mean_m;
      p.dte_rms_m = r.dte_rms_m;
      p.dte_min_m = r.dte_min_m;
      p.dte_max_m = r.dte_max_m;
      p.force_min_n = r.force_min_n;
      p.force_max_n = r.force_max_n;
      p.dynamic_factor = r.dynamic_factor;
      p.contact_loss_fraction = r.contact_loss_fraction;
      p.floquet_multiplier = r.floquet_multiplier;
      p.period_cycles = r.period_cycles;
      p.cycles = r.transient_cycles;
      p.status = r.status;
      if (r.status != Status::Ok) p.message = r.message;
      if (r.status != Status::Ok) {
        ++not_ok;
        result.status = worse(result.status, r.status);
        if (result.message.empty()) result.message = r.message;
      }
      points.push_back(p);
      if (options.keep_responses) keep.push_back(std::move(r));
      progress.update(++done);
    }
  };
  if (up) run(true, result.up, result.up_responses);
  if (down) run(false, result.down, result.down_responses);
  progress.finish();
  if (not_ok > 0)
    result.message = fmt::format("{} of {} points not ok; first: {}", not_ok, done, result.message);
  return result;
}

}  // namespace geardyn::gear
