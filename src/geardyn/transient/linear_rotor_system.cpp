#include "geardyn/transient/linear_rotor_system.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geardyn/core/error.hpp"

namespace geardyn::transient {

double SpeedProfile::speed(double t) const {
  if (is_constant() || t <= 0.0) return speed_start;
  if (t >= duration) return speed_end;
  return speed_start + (speed_end - speed_start) * t / duration;
}

double SpeedProfile::acceleration(double t) const {
  if (is_constant() || t < 0.0 || t > duration) return 0.0;
  return (speed_end - speed_start) / duration;
}

double SpeedProfile::angle(double t) const {
  if (is_constant() || t <= 0.0) return speed_start * t;
  const double ramp = std::min(t, duration);
  const double theta =
      speed_start * ramp + 0.5 * (speed_end - speed_start) * ramp * ramp / duration;
  return theta + speed_end * (t - ramp);
}

LinearRotorSystem::LinearRotorSystem(const model::Model& model, const fe::LinearSystem& system,
                                     const SpeedProfile& profile,
                                     const std::vector<std::string>& unbalances)
    : system_(system), profile_(profile) {
  if (!std::isfinite(profile.speed_start) || !std::isfinite(profile.speed_end))
    throw std::invalid_argument("speed profile: speeds must be finite");
  if (!profile.is_constant() && !(profile.duration > 0.0 && std::isfinite(profile.duration)))
    throw std::invalid_argument(
        fmt::format("speed profile: run-up duration must be positive, got {}", profile.duration));

  for (const auto& name : unbalances) {
    const bool known = std::any_of(model.unbalances.begin(), model.unbalances.end(),
                                   [&](const model::Unbalance& u) { return u.name == name; });
    if (!known)
      throw InputError(SourceLocation{model.source_file, 0, 0}, "transient.unbalances",
                       "the name of an unbalance of the model", "'" + name + "'");
  }
  for (const auto& u : model.unbalances) {
    if (!unbalances.empty() &&
        std::find(unbalances.begin(), unbalances.end(), u.name) == unbalances.end())
      continue;
    const int node = system.dofs.find_node(u.node);
    if (node < 0)
      throw InputError(u.where, "unbalances." + u.name + ".node", "a node of the model",
                       "'" + u.node + "'");
    UnbalanceForce f;
    f.name = u.name;
    f.node = node;
    f.equation_e1 = system.dofs.dof(node, model::Component::Ux);
    f.equation_e2 = system.dofs.dof(node, model::Component::Uy);
    f.mass_eccentricity = u.mass_eccentricity;
    f.phase = u.phase;
    f.speed_ratio = system.dofs.node(node).speed_ratio;
    unbalances_.push_back(f);
  }

  has_speed_bearings_ = !system.speed_bearings.empty();
  if (profile_.is_constant()) {
    const double w = profile_.speed_start;
    K_constant_ = system.K + bearing_stiffness(w);
    C_constant_ = system.C + bearing_damping(w) + w * system.G;
    K_constant_.makeCompressed();
    C_constant_.makeCompressed();
  }
}

void LinearRotorSystem::bearing_blocks(double speed, bool stiffness,
                                       std::vector<Eigen::Triplet<double>>& triplets) const {
  for (const auto& b : system_.speed_bearings)
    b.add_tangent(speed, stiffness ? 1.0 : 0.0, stiffness ? 0.0 : 1.0, triplets);
}

SparseMatrix LinearRotorSystem::bearing_stiffness(double speed) const {
  std::vector<Eigen::Triplet<double>> triplets;
  bearing_blocks(speed, true, triplets);
  SparseMatrix K(size(), size());
  K.setFromTriplets(triplets.begin(), triplets.end());
  return K;
}

SparseMatrix LinearRotorSystem::bearing_damping(double speed) const {
  std::vector<Eigen::Triplet<double>> triplets;
  bearing_blocks(speed, false, triplets);
  SparseMatrix C(size(), size());
  C.setFromTriplets(triplets.begin(), triplets.end());
  return C;
}

void LinearRotorSystem::apply_bearings(double speed, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& v, Eigen::VectorXd& r) const {
  for (const auto& b : system_.speed_bearings) b.add_force(speed, q, v, r);
}

void LinearRotorSystem::add_external_force(double t, Eigen::VectorXd& f) const {
  const double w = profile_.speed(t);
  const double w_dot = profile_.acceleration(t);
  const double theta = profile_.angle(t);
  for (const auto& u : unbalances_) {
    const double sense = u.speed_ratio < 0.0 ? -1.0 : 1.0;
    const double psi = u.speed_ratio * theta + sense * u.phase;
    const double rate = u.speed_ratio * w;          // psi'
    const double rate_dot = u.speed_ratio * w_dot;  // psi''
    const double c = std::cos(psi), s = std::sin(psi);
    if (u.equation_e1 >= 0)
      f[u.equation_e1] += u.mass_eccentricity * (rate * rate * c + rate_dot * s);
    if (u.equation_e2 >= 0)
      f[u.equation_e2] += u.mass_eccentricity * (rate * rate * s - rate_dot * c);
  }
}

Eigen::VectorXd LinearRotorSystem::external_force(double t) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(size());
  add_external_force(t, f);
  return f;
}

void LinearRotorSystem::residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                 const Eigen::VectorXd& a, Eigen::VectorXd& r) {
  if (profile_.is_constant()) {
    r.noalias() = system_.M * a;
    r.noalias() += C_constant_ * v;
    r.noalias() += K_constant_ * q;
  } else {
    const double w = profile_.speed(t);
    r.noalias() = system_.M * a;
    r.noalias() += system_.C * v;
    r.noalias() += w * (system_.G * v);
    r.noalias() += system_.K * q;
    if (has_speed_bearings_) apply_bearings(w, q, v, r);
  }
  if (system_.has_modal_damping()) {
    const Eigen::VectorXd modal_velocity = system_.modal_basis.transpose() * v;
    r.noalias() += system_.modal_basis * system_.modal_coefficients.cwiseProduct(modal_velocity);
  }
  force_.setZero(size());
  add_external_force(t, force_);
  r -= force_;
}

void LinearRotorSystem::tangent(double t, const Eigen::VectorXd& /*q*/,
                                const Eigen::VectorXd& /*v*/, double c_m, double c_c, double c_k,
                                SparseMatrix& S) {
  if (profile_.is_constant()) {
    S = c_m * system_.M + c_c * C_constant_ + c_k * K_constant_;
  } else {
    const double w = profile_.speed(t);
    S = c_m * system_.M + c_c * (system_.C + w * system_.G) + c_k * system_.K;
    if (has_speed_bearings_) S += c_c * bearing_damping(w) + c_k * bearing_stiffness(w);
  }
  S.makeCompressed();
}

bool LinearRotorSystem::tangent_low_rank(double /*t*/, const Eigen::VectorXd& /*q*/,
                                         const Eigen::VectorXd& /*v*/, double /*c_m*/, double c_c,
                                         double /*c_k*/, Eigen::MatrixXd& U, Eigen::VectorXd& d) {
  if (!system_.has_modal_damping()) return false;
  U = system_.modal_basis;
  d = c_c * system_.modal_coefficients;
  return true;
}

}  // namespace geardyn::transient
