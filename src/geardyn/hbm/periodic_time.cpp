// GCC's -Wnull-dereference false positive inside Eigen's and <complex>'s inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <complex>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/hbm/periodic_time.hpp"

namespace geardyn::hbm {

namespace {

using Complex = std::complex<double>;

void add_problem(std::string& problems, const std::string& p) {
  problems += (problems.empty() ? "" : "; ") + p;
}

double inf_norm(const Eigen::VectorXd& x) { return x.size() > 0 ? x.cwiseAbs().maxCoeff() : 0.0; }

}  // namespace

void TimeMarchOptions::validate() const {
  std::string problems;
  if (steps_per_period < 16)
    add_problem(problems,
                fmt::format("steps_per_period must be >= 16, found {}", steps_per_period));
  if (!std::isfinite(load_factor))
    add_problem(problems, fmt::format("load_factor must be finite, found {}", load_factor));
  if (!(newton_tolerance > 0.0 && newton_tolerance < 1e-3))
    add_problem(problems,
                fmt::format("newton_tolerance must lie in (0, 1e-3), found {}", newton_tolerance));
  if (max_newton_iterations < 1)
    add_problem(problems,
                fmt::format("max_newton_iterations must be >= 1, found {}", max_newton_iterations));
  if (!(closure_tolerance > 0.0 && std::isfinite(closure_tolerance)))
    add_problem(problems, fmt::format("closure_tolerance must be finite and > 0, found {}",
                                      closure_tolerance));
  if (max_periods < 2)
    add_problem(problems, fmt::format("max_periods must be >= 2, found {}", max_periods));
  if (!problems.empty())
    throw InputError({}, "hbm.TimeMarchOptions", "valid time-march options", problems);
}

void MonodromyOptions::validate() const {
  march.validate();
  std::string problems;
  if (!(fd_step > 0.0 && fd_step < 0.1))
    add_problem(problems, fmt::format("fd_step must lie in (0, 0.1), found {}", fd_step));
  if (preliminary_periods < 1)
    add_problem(problems,
                fmt::format("preliminary_periods must be >= 1, found {}", preliminary_periods));
  if (!(stability_tolerance >= 0.0 && std::isfinite(stability_tolerance)))
    add_problem(problems, fmt::format("stability_tolerance must be finite and >= 0, found {}",
                                      stability_tolerance));
  if (!(kind_tolerance > 0.0 && kind_tolerance < 0.25))
    add_problem(problems,
                fmt::format("kind_tolerance must lie in (0, 0.25), found {}", kind_tolerance));
  if (!(neutral_tolerance >= 0.0 && neutral_tolerance < 1e-2))
    add_problem(problems, fmt::format("neutral_tolerance must lie in [0, 1e-2), found {}",
                                      neutral_tolerance));
  if (!problems.empty())
    throw InputError({}, "hbm.MonodromyOptions", "valid monodromy options", problems);
}

// ---------------------------------------------------------------------------------------------
// The integrator.

// Scratch of one period's integration (no allocation per step for systems of fixed size).
struct PeriodicIntegrator::Workspace {
  Eigen::VectorXd g;                  ///< sum_e B_e^T f_e (n_dof)
  Eigen::MatrixXd Kt, Ct;             ///< sum_e B_e^T (df/du, df/dv) B_e
  std::vector<Eigen::VectorXd> next;  ///< the states to commit
  ElementStep step;
  Eigen::VectorXd u, v;  ///< an element's coordinates and rates
  Eigen::VectorXd f_ext, q1, v1, a1, r, dq;
  Eigen::MatrixXd Keff;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
};

PeriodicIntegrator::PeriodicIntegrator(ElementSystem system, double omega, TimeMarchOptions options)
    : system_(std::move(system)), omega_(omega), options_(options) {
  system_.validate();
  options_.validate();
  if (system_.K_loss.size() > 0)
    throw InputError({}, "structural_loss", "no structural loss K_loss in a time analysis",
                     "a non-empty K_loss",
                     "the loss factor i K_loss has no time-domain form; model the damping by C");
  if (!(omega > 0.0 && std::isfinite(omega)))
    throw InputError({}, "omega", "a finite fundamental frequency > 0 rad/s",
                     fmt::format("{}", omega));
  h_ = units::kTwoPi / omega_ / options_.steps_per_period;
  mass_lu_.compute(system_.M);
  const Eigen::FullPivLU<Eigen::MatrixXd> check(system_.M);
  if (!check.isInvertible())
    throw InputError({}, "mass", "an invertible mass matrix",
                     fmt::format("rank {} of {}", check.rank(), system_.dofs()),
                     "condense massless DOFs out of the system first");
}

int PeriodicIntegrator::state_count() const {
  int n = 0;
  for (const auto& e : system_.elements) n += e.element->state_size();
  return n;
}

TimeState PeriodicIntegrator::start_state(const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& v) const {
  const int n = system_.dofs();
  if (q.size() != n || v.size() != n)
    throw InputError({}, "initial_state", fmt::format("q and q' of {} DOFs", n),
                     fmt::format("{} and {}", q.size(), v.size()));
  TimeState z{q, v, {}};
  for (const auto& e : system_.elements)
    z.element_states.push_back(e.element->initial_state(e.B * q));
  return z;
}

void PeriodicIntegrator::element_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                        double theta, const std::vector<Eigen::VectorXd>& states,
                                        Workspace& w, bool tangents) const {
  const int n = system_.dofs();
  w.g.setZero(n);
  if (tangents) {
    w.Kt.setZero(n, n);
    w.Ct.setZero(n, n);
  }
  w.next.resize(system_.elements.size());
  ElementStep& step = w.step;
  for (std::size_t e = 0; e < system_.elements.size(); ++e) {
    const auto& placed = system_.elements[e];
    const int ne = placed.element->size();
    step.force.setZero(ne);
    step.stiffness.setZero(ne, ne);
    step.damping.setZero(ne, ne);
    w.u.noalias() = placed.B * q;
    w.v.noalias() = placed.B * v;
    placed.element->time_force(w.u, w.v, theta, omega_, states[e], step);
    w.g.noalias() += placed.B.transpose() * step.force;
    if (tangents) {
      w.Kt.noalias() += placed.B.transpose() * step.stiffness * placed.B;
      w.Ct.noalias() += placed.B.transpose() * step.damping * placed.B;
    }
    w.next[e] = step.state;
  }
}

Eigen::VectorXd PeriodicIntegrator::acceleration(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                                 double theta,
                                                 const std::vector<Eigen::VectorXd>& states,
                                                 Workspace& w) const {
  element_forces(q, v, theta, states, w, false);
  w.r = options_.load_factor * system_.excitation_at(theta);
  w.r.noalias() -= system_.C * v;
  w.r.noalias() -= system_.K * q;
  w.r -= w.g;
  return mass_lu_.solve(w.r);
}

bool PeriodicIntegrator::newmark_step(TimeState& z, Eigen::VectorXd& a, int k, Workspace& w) const {
  const double h = h_, theta = units::kTwoPi * (k + 1) / options_.steps_per_period;
  w.f_ext = options_.load_factor * system_.excitation_at(theta);
  const Eigen::VectorXd& q0 = z.q;
  const Eigen::VectorXd& v0 = z.v;
  const double scale_floor =
      std::max({h * inf_norm(v0), h * h * inf_norm(a), std::numeric_limits<double>::min()});
  w.q1 = q0 + h * v0 + 0.5 * h * h * a;  // constant-acceleration predictor
  auto rates = [&]() {                   // Newmark: q1'' and q1' from q1
    w.v1 = (2.0 / h) * (w.q1 - q0) - v0;
    w.a1 = (4.0 / (h * h)) * (w.q1 - q0 - h * v0) - a;
  };
  for (int it = 0; it < options_.max_newton_iterations; ++it) {
    rates();
    element_forces(w.q1, w.v1, theta, z.element_states, w, true);
    w.r = w.g - w.f_ext;
    w.r.noalias() += system_.M * w.a1;
    w.r.noalias() += system_.C * w.v1;
    w.r.noalias() += system_.K * w.q1;
    w.Keff = (4.0 / (h * h)) * system_.M + (2.0 / h) * (system_.C + w.Ct) + system_.K + w.Kt;
    w.lu.compute(w.Keff);
    w.dq = w.lu.solve(w.r);
    if (!w.dq.allFinite()) return false;
    w.q1 -= w.dq;
    if (inf_norm(w.dq) <= options_.newton_tolerance * std::max(inf_norm(w.q1), scale_floor)) {
      rates();
      element_forces(w.q1, w.v1, theta, z.element_states, w, false);
      z.q = w.q1;
      z.v = w.v1;
      a = w.a1;
      std::swap(z.element_states, w.next);
      return true;
    }
  }
  return false;
}

bool PeriodicIntegrator::rk4_step(TimeState& z, int k, Workspace& w) const {
  const double h = h_, dtheta = units::kTwoPi / options_.steps_per_period;
  const double theta0 = dtheta * k;
  const auto& s0 = z.element_states;
  auto acc = [&](const Eigen::VectorXd& q, const Eigen::VectorXd& v, double theta) {
    return acceleration(q, v, theta, s0, w);
  };
  const Eigen::VectorXd k1q = z.v, k1v = acc(z.q, z.v, theta0);
  const Eigen::VectorXd q2 = z.q + 0.5 * h * k1q, v2 = z.v + 0.5 * h * k1v;
  const Eigen::VectorXd k2v = acc(q2, v2, theta0 + 0.5 * dtheta);
  const Eigen::VectorXd q3 = z.q + 0.5 * h * v2, v3 = z.v + 0.5 * h * k2v;
  const Eigen::VectorXd k3v = acc(q3, v3, theta0 + 0.5 * dtheta);
  const Eigen::VectorXd q4 = z.q + h * v3, v4 = z.v + h * k3v;
  const Eigen::VectorXd k4v = acc(q4, v4, theta0 + dtheta);
  z.q += h / 6.0 * (k1q + 2.0 * v2 + 2.0 * v3 + v4);
  z.v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  if (!z.q.allFinite() || !z.v.allFinite()) return false;
  element_forces(z.q, z.v, theta0 + dtheta, s0, w, false);
  std::swap(z.element_states, w.next);
  return true;
}

Status PeriodicIntegrator::advance_period(TimeState& z, Record* record,
                                          std::string& message) const {
  const int N = options_.steps_per_period, n = system_.dofs();
  if (z.q.size() != n || z.v.size() != n || z.element_states.size() != system_.elements.size())
    throw InputError(
        {}, "time_state",
        fmt::format("q, q' of {} DOFs and {} element states", n, system_.elements.size()),
        fmt::format("{}, {} and {}", z.q.size(), z.v.size(), z.element_states.size()));
  if (record != nullptr) {
    record->q.resize(N + 1, n);
    record->v.resize(N + 1, n);
    record->q.row(0) = z.q.transpose();
    record->v.row(0) = z.v.transpose();
  }
  const bool newmark = options_.scheme == TimeScheme::Newmark;
  Workspace w;
  Eigen::VectorXd a =
      newmark ? acceleration(z.q, z.v, 0.0, z.element_states, w) : Eigen::VectorXd();
  for (int k = 0; k < N; ++k) {
    const bool ok = newmark ? newmark_step(z, a, k, w) : rk4_step(z, k, w);
    if (!ok || !z.q.allFinite() || !z.v.allFinite()) {
      message = fmt::format(
          "time step {} of {} (theta = {:.4g} rad) failed: {}", k + 1, N,
          units::kTwoPi * (k + 1) / N,
          newmark ? fmt::format("Newton did not converge in {} iterations or the state is not "
                                "finite (reduce the step or check the element law)",
                                options_.max_newton_iterations)
                  : std::string("the state is not finite (RK4 unstable: more steps per period, "
                                "or the Newmark scheme for stiff laws)"));
      return Status::Diverged;
    }
    if (record != nullptr) {
      record->q.row(k + 1) = z.q.transpose();
      record->v.row(k + 1) = z.v.transpose();
    }
  }
  return Status::Ok;
}

// ---------------------------------------------------------------------------------------------
// march_to_periodic.

namespace {

// max |z_a - z_b| over (q, q' / omega), relative to `amplitude`.
double state_distance(const TimeState& a, const TimeState& b, double omega, double amplitude) {
  const double d = std::max(inf_norm(a.q - b.q), inf_norm(a.v - b.v) / omega);
  return d / std::max(amplitude, std::numeric_limits<double>::min());
}

// q at the basis' phases by cubic Hermite interpolation of the period's steps (dq/dtheta =
// q' / omega), and the Fourier coefficients of the steps by the rectangle rule.
void period_output(const PeriodicIntegrator::Record& rec, double omega, const HarmonicBasis& basis,
                   PeriodicMarchResult& out) {
  const auto N = static_cast<int>(rec.q.rows()) - 1;
  const auto n = static_cast<int>(rec.q.cols());
  const int nt = basis.time_samples(), s = basis.size(), H = basis.harmonics();
  const double dtheta = units::kTwoPi / N;
  out.samples.resize(nt, n);
  for (int j = 0; j < nt; ++j) {
    const double x = static_cast<double>(j) * N / nt;
    const int k = std::min(static_cast<int>(std::floor(x)), N - 1);
    const double t = x - k, t2 = t * t, t3 = t2 * t;
    const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2,
                 h11 = t3 - t2;
    out.samples.row(j) = h00 * rec.q.row(k) + h01 * rec.q.row(k + 1) +
                         (dtheta / omega) * (h10 * rec.v.row(k) + h11 * rec.v.row(k + 1));
  }
  out.coefficients.setZero(n * s);
  for (int k = 0; k < N; ++k) {
    const double theta = dtheta * k;
    for (int d = 0; d < n; ++d) {
      const double q = rec.q(k, d);
      out.coefficients[d * s] += q / N;
      for (int h = 1; h <= H; ++h) {
        out.coefficients[d * s + HarmonicBasis::cos_index(h)] += 2.0 * q * std::cos(h * theta) / N;
        out.coefficients[d * s + HarmonicBasis::sin_index(h)] += 2.0 * q * std::sin(h * theta) / N;
      }
    }
  }
}

}  // namespace

PeriodicMarchResult march_to_periodic(const ElementSystem& system, double omega,
                                      const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                                      const HarmonicBasis& basis, const TimeMarchOptions& options) {
  const PeriodicIntegrator integrator(system, omega, options);
  return march_to_periodic(system, omega, integrator.start_state(q0, v0), basis, options);
}

PeriodicMarchResult march_to_periodic(const ElementSystem& system, double omega, TimeState start,
                                      const HarmonicBasis& basis, const TimeMarchOptions& options) {
  const PeriodicIntegrator integrator(system, omega, options);
  if (2 * basis.harmonics() >= options.steps_per_period)
    throw InputError({}, "steps_per_period",
                     fmt::format("more than 2H = {} steps per period", 2 * basis.harmonics()),
                     fmt::format("{}", options.steps_per_period));
  PeriodicMarchResult out;
  PeriodicIntegrator::Record rec;
  TimeState z = std::move(start), previous = z, before_previous;
  double last_closure = std::numeric_limits<double>::quiet_NaN(), period2 = last_closure;
  for (int p = 1; p <= options.max_periods; ++p) {
    out.start = z;
    const Status st = integrator.advance_period(z, &rec, out.message);
    out.periods = p;
    if (st != Status::Ok) {
      out.status = st;
      out.message = fmt::format("period {}: {}", p, out.message);
      return out;
    }
    const double amplitude = rec.q.cwiseAbs().maxCoeff();
    const double closure = state_distance(z, out.start, omega, amplitude);
    out.contraction = std::isfinite(last_closure) && last_closure > 0.0 ? closure / last_closure
                                                                        : out.contraction;
    out.closure_error = closure;
    out.closure_history.push_back(closure);
    last_closure = closure;
    if (p >= 2) period2 = state_distance(z, before_previous, omega, amplitude);
    before_previous = std::move(previous);
    previous = z;
    if (closure <= options.closure_tolerance) {
      period_output(rec, omega, basis, out);
      out.status = Status::Ok;
      return out;
    }
  }
  period_output(rec, omega, basis, out);
  out.status = Status::NotConverged;
  const bool period_two = period2 <= 1e3 * options.closure_tolerance;
  out.message = fmt::format(
      "the response is not periodic at the fundamental after {} periods: closure error {:.3g} "
      "(tolerance {:.3g}), contraction per period {:.4g}; {}",
      options.max_periods, out.closure_error, options.closure_tolerance, out.contraction,
      period_two ? fmt::format("it repeats after two periods (closure {:.3g}): a period-2 "
                               "(subharmonic) response after a period doubling",
                               period2)
                 : std::string("a quasi-periodic or chaotic response, or a transient decaying "
                               "too slowly (contraction near 1)"));
  return out;
}

// ---------------------------------------------------------------------------------------------
// monodromy.

namespace {

// q(theta) and q'(theta) = omega dq/dtheta of the DOF-major series X.
std::pair<Eigen::VectorXd, Eigen::VectorXd> series_state(const Eigen::VectorXd& X, int n_dof, int H,
                                                         double omega, double theta) {
  const int s = 2 * H + 1;
  Eigen::VectorXd q(n_dof), v(n_dof);
  for (int d = 0; d < n_dof; ++d) {
    const auto c = X.segment(d * s, s);
    double x = c[0], dx = 0.0;
    for (int h = 1; h <= H; ++h) {
      const double a = c[HarmonicBasis::cos_index(h)], b = c[HarmonicBasis::sin_index(h)];
      x += a * std::cos(h * theta) + b * std::sin(h * theta);
      dx += h * (b * std::cos(h * theta) - a * std::sin(h * theta));
    }
    q[d] = x;
    v[d] = omega * dx;
  }
  return {q, v};
}

// The start z0 on the HB motion and the amplitudes of each component of z over the period: the
// element states marched along u = B q(theta) (see the header comment).
TimeState hb_start(const PeriodicIntegrator& integrator, const Eigen::VectorXd& X, int H,
                   int periods, Eigen::VectorXd& amplitude) {
  const ElementSystem& sys = integrator.system();
  const int n = sys.dofs(), N = integrator.options().steps_per_period;
  const double omega = integrator.omega();
  auto [q0, v0] = series_state(X, n, H, omega, 0.0);
  TimeState z = integrator.start_state(q0, v0);
  amplitude.setZero(2 * n + integrator.state_count());
  ElementStep step;
  for (int k = 1; k <= periods * N; ++k) {
    const double theta = units::kTwoPi * k / N;
    const auto [q, v] = series_state(X, n, H, omega, theta);
    const bool last = k > (periods - 1) * N;
    if (last) {
      amplitude.head(n) = amplitude.head(n).cwiseMax(q.cwiseAbs());
      amplitude.segment(n, n) = amplitude.segment(n, n).cwiseMax(v.cwiseAbs());
    }
    int offset = 2 * n;
    for (std::size_t e = 0; e < sys.elements.size(); ++e) {
      const auto& placed = sys.elements[e];
      const int ne = placed.element->size(), ns = placed.element->state_size();
      step.force.setZero(ne);
      step.stiffness.setZero(ne, ne);
      step.damping.setZero(ne, ne);
      placed.element->time_force(placed.B * q, placed.B * v, theta, omega, z.element_states[e],
                                 step);
      z.element_states[e] = step.state;
      if (last && ns > 0)
        amplitude.segment(offset, ns) =
            amplitude.segment(offset, ns).cwiseMax(step.state.cwiseAbs());
      offset += ns;
    }
  }
  return z;
}

// The scale of each component: its amplitude; when zero the largest q amplitude (times omega
// for velocities), and 1 for a zero solution.
Eigen::VectorXd component_scales(const Eigen::VectorXd& amplitude, int n, double omega) {
  double q_scale = amplitude.head(n).maxCoeff();
  if (!(q_scale > 0.0)) q_scale = 1.0;
  Eigen::VectorXd s = amplitude;
  for (Eigen::Index j = 0; j < s.size(); ++j)
    if (!(s[j] > 0.0)) s[j] = (j >= n && j < 2 * n) ? omega * q_scale : q_scale;
  return s;
}

Eigen::VectorXd pack(const TimeState& z) {
  Eigen::Index size = z.q.size() + z.v.size();
  for (const auto& s : z.element_states) size += s.size();
  Eigen::VectorXd x(size);
  x << z.q, z.v, Eigen::VectorXd::Zero(size - z.q.size() - z.v.size());
  Eigen::Index offset = z.q.size() + z.v.size();
  for (const auto& s : z.element_states) {
    x.segment(offset, s.size()) = s;
    offset += s.size();
  }
  return x;
}

TimeState unpack(const Eigen::VectorXd& x, const TimeState& like) {
  TimeState z = like;
  const Eigen::Index n = like.q.size();
  z.q = x.head(n);
  z.v = x.segment(n, n);
  Eigen::Index offset = 2 * n;
  for (auto& s : z.element_states) {
    s = x.segment(offset, s.size());
    offset += s.size();
  }
  return z;
}

}  // namespace

namespace {

// Indices of the element states whose row of the scaled Phi is the unit row (neutral).
std::vector<Eigen::Index> neutral_states(const Eigen::MatrixXd& Phi, Eigen::Index first_state,
                                         double tolerance) {
  std::vector<Eigen::Index> out;
  for (Eigen::Index i = first_state; i < Phi.rows(); ++i) {
    Eigen::RowVectorXd row = Phi.row(i);
    row[i] -= 1.0;
    if (row.cwiseAbs().maxCoeff() <= tolerance) out.push_back(i);
  }
  return out;
}

// Multipliers (eigenvalues of Phi without the `excluded` rows and columns) into a FloquetResult.
void floquet_from(const Eigen::MatrixXd& Phi, const std::vector<Eigen::Index>& excluded,
                  double omega, const MonodromyOptions& options, FloquetResult& out) {
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < Phi.rows(); ++i)
    if (std::find(excluded.begin(), excluded.end(), i) == excluded.end()) keep.push_back(i);
  const auto m = static_cast<Eigen::Index>(keep.size());
  Eigen::MatrixXd A(m, m);
  for (Eigen::Index r = 0; r < m; ++r)
    for (Eigen::Index c = 0; c < m; ++c)
      A(r, c) = Phi(keep[static_cast<std::size_t>(r)], keep[static_cast<std::size_t>(c)]);
  const Eigen::EigenSolver<Eigen::MatrixXd> es(A, false);
  if (es.info() != Eigen::Success) {
    out.status = Status::Failed;
    out.message = fmt::format("the eigen-solve of the {0}x{0} monodromy matrix failed", m);
    return;
  }
  Eigen::VectorXcd rho = es.eigenvalues();
  std::vector<Eigen::Index> order(static_cast<std::size_t>(m));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::stable_sort(order.begin(), order.end(), [&rho](Eigen::Index a, Eigen::Index b) {
    if (std::abs(rho[a]) != std::abs(rho[b])) return std::abs(rho[a]) > std::abs(rho[b]);
    return rho[a].imag() > rho[b].imag();
  });
  const double period = units::kTwoPi / omega;
  out.multipliers.resize(m);
  out.exponents.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const Complex r = rho[order[static_cast<std::size_t>(j)]];
    out.multipliers[j] = r;
    out.exponents[j] = r == Complex{0.0, 0.0}
                           ? Complex{-std::numeric_limits<double>::infinity(), 0.0}
                           : std::log(r) / period;
  }
  out.centroids.resize(0);
  out.sorting_gap = std::numeric_limits<double>::quiet_NaN();
  out.max_real_part = m > 0 ? out.exponents[0].real() : -std::numeric_limits<double>::infinity();
  out.stable = m == 0 || std::abs(out.multipliers[0]) <= 1.0 + options.stability_tolerance;
  out.kind = out.stable ? FloquetResult::Instability::None
                        : instability_kind(out.exponents[0], omega, options.kind_tolerance);
  out.status = Status::Ok;
}

}  // namespace

MonodromyResult monodromy(const ElementSystem& system, double omega, const Eigen::VectorXd& X,
                          const HarmonicBasis& basis, const MonodromyOptions& options) {
  options.validate();
  const PeriodicIntegrator integrator(system, omega, options.march);
  const int n = system.dofs(), H = basis.harmonics();
  if (X.size() != n * basis.size() || !X.allFinite())
    throw InputError(
        {}, "hbm.monodromy.X",
        fmt::format("{} finite Fourier coefficients (n_dof (2H + 1))", n * basis.size()),
        fmt::format("{} coefficients{}", X.size(), X.allFinite() ? "" : ", non-finite"));
  MonodromyResult out;
  Eigen::VectorXd amplitude;
  const TimeState z0 = hb_start(integrator, X, H, options.preliminary_periods, amplitude);
  out.scales = component_scales(amplitude, n, omega);
  const Eigen::VectorXd x0 = pack(z0);
  const Eigen::Index size = x0.size();
  std::string message;
  // The flow map over one period in the scaled coordinates; false on a failed integration.
  auto flow = [&](const Eigen::VectorXd& x, Eigen::VectorXd& xT) {
    TimeState z = unpack(x, z0);
    if (integrator.advance_period(z, nullptr, message) != Status::Ok) return false;
    xT = pack(z).cwiseQuotient(out.scales);
    return true;
  };
  Eigen::VectorXd plus, minus;
  if (!flow(x0, plus)) {
    out.floquet.status = Status::Diverged;
    out.floquet.message = "the period from the HB solution: " + message;
    return out;
  }
  out.closure_error = (plus - x0.cwiseQuotient(out.scales)).cwiseAbs().maxCoeff();
  out.monodromy.resize(size, size);
  for (Eigen::Index j = 0; j < size; ++j) {
    const double d = options.fd_step * out.scales[j];
    if (!flow(x0 + d * Eigen::VectorXd::Unit(size, j), plus) ||
        !flow(x0 - d * Eigen::VectorXd::Unit(size, j), minus)) {
      out.floquet.status = Status::Diverged;
      out.floquet.message = fmt::format("the period perturbed in component {}: {}", j, message);
      return out;
    }
    out.monodromy.col(j) = (plus - minus) / (2.0 * options.fd_step);
  }
  if (!out.monodromy.allFinite()) {
    out.floquet.status = Status::Failed;
    out.floquet.message = "the monodromy matrix has non-finite entries";
    return out;
  }
  const std::vector<Eigen::Index> neutral =
      neutral_states(out.monodromy, 2 * n, options.neutral_tolerance);
  out.neutral_states = static_cast<int>(neutral.size());
  floquet_from(out.monodromy, neutral, omega, options, out.floquet);
  return out;
}

FloquetResult monodromy_stability(const ElementSystem& system, double omega,
                                  const Eigen::VectorXd& X, const HarmonicBasis& basis,
                                  const MonodromyOptions& options) {
  return monodromy(system, omega, X, basis, options).floquet;
}

}  // namespace geardyn::hbm
