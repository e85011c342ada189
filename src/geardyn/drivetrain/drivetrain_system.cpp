#include "geardyn/drivetrain/drivetrain_system.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace geardyn::drivetrain {
namespace {

void check_equation(int e, int n, const std::string& what) {
  if (e < 0 || e >= n)
    throw std::invalid_argument(
        fmt::format("DrivetrainSystem: {} has equation {} of {}", what, e, n));
}

}  // namespace

DrivetrainSystem::DrivetrainSystem(DrivetrainParts parts) : p_(std::move(parts)) {
  const int n = static_cast<int>(p_.M.rows());
  if (p_.M.cols() != n || p_.K.rows() != n || p_.K.cols() != n || p_.C.rows() != n ||
      p_.C.cols() != n)
    throw std::invalid_argument("DrivetrainSystem: M, C, K must be square of one size");
  if (p_.G.size() == 0) p_.G.resize(n, n);
  if (p_.modal_basis.size() > 0 &&
      (p_.modal_basis.rows() != n || p_.modal_basis.cols() != p_.modal_coefficients.size()))
    throw std::invalid_argument("DrivetrainSystem: modal basis size");
  held_row_.assign(static_cast<std::size_t>(n), 0);
  held_static_row_.assign(static_cast<std::size_t>(n), 0);
  // Motors' rotor inertia on their spins.
  for (const Motor& m : p_.motors) {
    check_equation(m.equation, n, "motor '" + m.name + "'");
    p_.M.coeffRef(m.equation, m.equation) += m.inertia;
  }
  p_.M.makeCompressed();
  for (const SpeedDriver& d : p_.speed_drivers) {
    check_equation(d.equation, n, "driver '" + d.name + "'");
    held_.push_back(d.equation);
    held_row_[static_cast<std::size_t>(d.equation)] = 1;
  }
  held_static_ = held_;
  for (const Motor& m : p_.motors) held_static_.push_back(m.equation);
  for (int e : held_static_) held_static_row_[static_cast<std::size_t>(e)] = 1;
  for (const LoadTorque& l : p_.loads) check_equation(l.equation, n, "load '" + l.name + "'");
  for (const SpinUnbalance& u : p_.unbalances)
    check_equation(u.spin, n, "unbalance '" + u.name + "'");
  if (p_.speed_equation >= 0) check_equation(p_.speed_equation, n, "reference speed");
  if (!p_.speed_bearings.empty() && p_.speed_equation < 0)
    throw std::invalid_argument(
        "DrivetrainSystem: speed-dependent bearings without a reference speed equation");
  for (const fe::SpeedDependentBearing& b : p_.speed_bearings)
    for (int e : b.equations)
      if (e >= 0) check_equation(e, n, "speed-dependent bearing");
  for (std::size_t k = 0; k < p_.elements.size(); ++k) {
    const PlacedElement& e = p_.elements[k];
    for (int eq : e.equations) check_equation(eq, n, e.element->describe());
    if (e.B.rows() != e.element->size() ||
        e.B.cols() != static_cast<Eigen::Index>(e.equations.size()))
      throw std::invalid_argument("DrivetrainSystem: placement size of " + e.element->describe());
    for (int s = 0; s < e.element->num_switches(); ++s)
      event_owner_.emplace_back(static_cast<int>(k), s);
  }
  num_events_ = static_cast<int>(event_owner_.size());
  held_mass_.resize(static_cast<std::size_t>(n), 0.0);
  for (int e : held_static_) {
    const double m = p_.M.coeff(e, e);
    held_mass_[static_cast<std::size_t>(e)] = m > 0.0 ? m : 1.0;
  }
}

double DrivetrainSystem::reference_speed(const Eigen::VectorXd& v) const {
  return p_.speed_equation >= 0 ? v[p_.speed_equation] / p_.speed_ratio : 0.0;
}

void DrivetrainSystem::add_linear(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                  const Eigen::VectorXd& a, Eigen::VectorXd& r) const {
  r.noalias() += p_.M * a;
  r.noalias() += p_.C * v;
  r.noalias() += p_.K * q;
  const double omega = reference_speed(v);
  if (omega != 0.0) r.noalias() += omega * (p_.G * v);
  for (const fe::SpeedDependentBearing& b : p_.speed_bearings) b.add_force(omega, q, v, r);
  if (p_.modal_coefficients.size() > 0)
    r.noalias() +=
        p_.modal_basis * (p_.modal_coefficients.asDiagonal() * (p_.modal_basis.transpose() * v));
}

void DrivetrainSystem::add_elements(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                    Eigen::VectorXd& r) const {
  Eigen::VectorXd u, w;
  elements::ElementForce f;
  for (const PlacedElement& e : p_.elements) {
    e.gather(q, u);
    e.gather(v, w);
    e.element->evaluate(u, w, t, f);
    e.scatter(f.force, 1.0, r);
  }
}

void DrivetrainSystem::add_loads(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                 const Eigen::VectorXd& a, Eigen::VectorXd& r) const {
  for (const LoadTorque& l : p_.loads) r[l.equation] -= l.value(t, v[l.equation], nullptr);
  for (const Motor& m : p_.motors) r[m.equation] -= m.torque.value(v[m.equation]);
  for (const SpinUnbalance& u : p_.unbalances) {
    const double psi = q[u.spin] + u.phase, w = v[u.spin], al = a[u.spin];
    const double c = std::cos(psi), s = std::sin(psi), me = u.mass_eccentricity;
    if (u.e1 >= 0) r[u.e1] -= me * (w * w * c + al * s);
    if (u.e2 >= 0) r[u.e2] -= me * (w * w * s - al * c);
  }
}

void DrivetrainSystem::free_residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                     const Eigen::VectorXd& a, Eigen::VectorXd& r) const {
  r.setZero(size());
  add_linear(q, v, a, r);
  add_elements(t, q, v, r);
  add_loads(t, q, v, a, r);
}

void DrivetrainSystem::residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                const Eigen::VectorXd& a, Eigen::VectorXd& r) {
  free_residual(static_ ? static_time_ : t, q, v, a, r);
  const double ws = p_.servo_frequency;
  if (static_) {
    for (const SpeedDriver& d : p_.speed_drivers) {
      const int e = d.equation;
      r[e] = held_mass_[static_cast<std::size_t>(e)] * ws * ws * (q[e] - d.angle(static_time_));
    }
    for (const Motor& m : p_.motors)
      r[m.equation] = held_mass_[static_cast<std::size_t>(m.equation)] * ws * ws * q[m.equation];
    return;
  }
  for (std::size_t k = 0; k < p_.speed_drivers.size(); ++k) {
    const SpeedDriver& d = p_.speed_drivers[k];
    const int e = d.equation;
    const double err = q[e] - d.angle(t), err_v = v[e] - d.velocity(t),
                 err_a = a[e] - d.acceleration(t);
    r[e] = held_mass_[static_cast<std::size_t>(e)] * (err_a + 2.0 * ws * err_v + ws * ws * err);
  }
}

void DrivetrainSystem::tangent(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                               double c_m, double c_c, double c_k, SparseMatrix& S) {
  const double time = static_ ? static_time_ : t;
  const double omega = reference_speed(v);
  S = c_m * p_.M + c_c * p_.C + c_k * p_.K;
  if (omega != 0.0 && c_c != 0.0) S += (c_c * omega) * p_.G;
  std::vector<Eigen::Triplet<double>> trip;
  // d (Omega(v) G v) / d v_ref = G v / speed_ratio: one column.
  if (p_.speed_equation >= 0 && c_c != 0.0 && p_.G.nonZeros() > 0) {
    const Eigen::VectorXd gv = p_.G * v;
    for (Eigen::Index i = 0; i < gv.size(); ++i)
      if (gv[i] != 0.0)
        trip.emplace_back(static_cast<int>(i), p_.speed_equation, c_c * gv[i] / p_.speed_ratio);
  }
  // Speed-dependent bearings: K_b(Omega), C_b(Omega), and d(K_b q + C_b v) / d Omega times
  // d Omega / d v_ref = 1 / speed_ratio on the reference speed's column.
  if (!p_.speed_bearings.empty()) {
    Eigen::VectorXd column = Eigen::VectorXd::Zero(size());
    for (const fe::SpeedDependentBearing& b : p_.speed_bearings) {
      b.add_tangent(omega, c_k, c_c, trip);
      if (c_c != 0.0) b.add_speed_derivative(omega, q, v, c_c / p_.speed_ratio, column);
    }
    for (Eigen::Index i = 0; i < column.size(); ++i)
      if (column[i] != 0.0) trip.emplace_back(static_cast<int>(i), p_.speed_equation, column[i]);
  }
  Eigen::VectorXd u, w;
  elements::ElementForce f;
  for (const PlacedElement& e : p_.elements) {
    e.gather(q, u);
    e.gather(v, w);
    e.element->evaluate(u, w, time, f);
    const Eigen::MatrixXd block = e.project(c_k * f.stiffness + c_c * f.damping);
    for (std::size_t i = 0; i < e.equations.size(); ++i)
      for (std::size_t j = 0; j < e.equations.size(); ++j) {
        const double x = block(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
        if (x != 0.0) trip.emplace_back(e.equations[i], e.equations[j], x);
      }
  }
  for (const SpinUnbalance& ub : p_.unbalances) {
    // d(-f_unbalance) / d(theta, theta', theta'') on the spin column. The tangent has no a,
    // so the angle derivative of the theta'' term is left out: modified Newton, which costs
    // iterations during an angular acceleration, never accuracy (the residual is exact).
    const double psi = q[ub.spin] + ub.phase, ws = v[ub.spin];
    const double c = std::cos(psi), s = std::sin(psi), me = ub.mass_eccentricity;
    if (ub.e1 >= 0)
      trip.emplace_back(ub.e1, ub.spin,
                        -me * (c_k * (-ws * ws * s) + c_c * 2.0 * ws * c + c_m * s));
    if (ub.e2 >= 0)
      trip.emplace_back(ub.e2, ub.spin, -me * (c_k * (ws * ws * c) + c_c * 2.0 * ws * s - c_m * c));
  }
  if (c_c != 0.0) {
    for (const LoadTorque& l : p_.loads) {
      double d = 0.0;
      l.value(time, v[l.equation], &d);
      if (d != 0.0) trip.emplace_back(l.equation, l.equation, -c_c * d);
    }
    for (const Motor& m : p_.motors) {
      double d = 0.0;
      m.torque.value(v[m.equation], &d);
      if (d != 0.0) trip.emplace_back(m.equation, m.equation, -c_c * d);
    }
  }
  if (!trip.empty()) {
    SparseMatrix extra(S.rows(), S.cols());
    extra.setFromTriplets(trip.begin(), trip.end());
    S += extra;
  }
  // Servo rows replace the held equations' rows.
  const std::vector<char>& held = static_ ? held_static_row_ : held_row_;
  S.prune([&](const Eigen::Index& row, const Eigen::Index&, const double&) {
    return held[static_cast<std::size_t>(row)] == 0;
  });
  const double ws = p_.servo_frequency;
  std::vector<Eigen::Triplet<double>> diag;
  for (int e : held_equations()) {
    const double m = held_mass_[static_cast<std::size_t>(e)];
    const double value = static_ ? m * ws * ws * c_k : m * (c_m + 2.0 * ws * c_c + ws * ws * c_k);
    diag.emplace_back(e, e, value);
  }
  SparseMatrix D(S.rows(), S.cols());
  D.setFromTriplets(diag.begin(), diag.end());
  S += D;
}

bool DrivetrainSystem::tangent_low_rank(double, const Eigen::VectorXd&, const Eigen::VectorXd&,
                                        double, double c_c, double, Eigen::MatrixXd& U,
                                        Eigen::VectorXd& d) {
  if (p_.modal_coefficients.size() == 0 || c_c == 0.0) return false;
  U = p_.modal_basis;
  // The servo rows carry no modal damping; dropping the held rows (and so, by symmetry, their
  // columns) from the tangent only slows Newton on the coupling, never changes the solution.
  for (int e : held_equations()) U.row(e).setZero();
  d = c_c * p_.modal_coefficients;
  return true;
}

Eigen::VectorXd DrivetrainSystem::element_force(std::size_t k, double t, const Eigen::VectorXd& q,
                                                const Eigen::VectorXd& v) const {
  const PlacedElement& e = p_.elements.at(k);
  Eigen::VectorXd u, w;
  e.gather(q, u);
  e.gather(v, w);
  elements::ElementForce f;
  e.element->evaluate(u, w, t, f);
  return f.force;
}

void DrivetrainSystem::event_functions(double t, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                                       Eigen::VectorXd& g) const {
  g.resize(num_events_);
  Eigen::VectorXd u;
  int k = 0;
  for (const PlacedElement& e : p_.elements) {
    const int ns = e.element->num_switches();
    if (ns == 0) continue;
    e.gather(q, u);
    e.element->switches(u, t, g.data() + k);
    k += ns;
  }
}

std::string DrivetrainSystem::describe_event(int k) const {
  const auto [element, sw] = event_owner_.at(static_cast<std::size_t>(k));
  const PlacedElement& e = p_.elements[static_cast<std::size_t>(element)];
  return fmt::format("{} '{}' {}", e.kind, e.name, e.element->describe_switch(sw));
}

std::string DrivetrainSystem::describe_state(double t, const Eigen::VectorXd& q,
                                             const Eigen::VectorXd& v) const {
  std::string worst;
  double largest = -1.0;
  for (std::size_t k = 0; k < p_.elements.size(); ++k) {
    const Eigen::VectorXd f = element_force(k, t, q, v);
    const std::string what = p_.elements[k].element->describe();
    if (!f.allFinite()) return fmt::format("{} has a non-finite force at t = {:.9g} s", what, t);
    const double m = f.size() > 0 ? f.cwiseAbs().maxCoeff() : 0.0;
    if (m > largest) {
      largest = m;
      worst = what;
    }
  }
  std::string out = fmt::format("reference speed {:.6g} rad/s", reference_speed(v));
  if (!worst.empty()) out += fmt::format("; largest element force: {} ({:.6g})", worst, largest);
  if (!q.allFinite() || !v.allFinite()) out += "; the state is not finite";
  return out;
}

}  // namespace geardyn::drivetrain
