#include "geardyn/elements/bolted_joint.hpp"

#include <cmath>
#include <utility>

#include "geardyn/elements/parameter_check.hpp"

namespace geardyn::elements {

namespace {

bool finite_positive(double x) { return std::isfinite(x) && x > 0.0; }
bool finite_nonnegative(double x) { return std::isfinite(x) && x >= 0.0; }

}  // namespace

BoltedJoint::BoltedJoint(BoltedJointParams params, const std::string& key_path,
                         const SourceLocation& where)
    : p_(std::move(params)) {
  const detail::ParameterCheck c(where, key_path);
  c.require(finite_positive(p_.bolt_stiffness), "bolt_stiffness", "a bolt stiffness k_S > 0 [N/m]",
            p_.bolt_stiffness);
  c.require(finite_positive(p_.clamp_stiffness), "clamp_stiffness",
            "a clamped-part stiffness k_P > 0 [N/m]", p_.clamp_stiffness);
  c.require(finite_nonnegative(p_.preload), "preload", "a preload F_V >= 0 [N]", p_.preload);
  c.require(std::isfinite(p_.load_introduction) && p_.load_introduction > 0.0 &&
                p_.load_introduction <= 1.0,
            "load_introduction", "a load introduction factor 0 < n <= 1", p_.load_introduction,
            "n = 1 introduces the load under the head and the nut");
  c.require(finite_nonnegative(p_.axial_damping), "axial_damping", "an axial damping >= 0 [N s/m]",
            p_.axial_damping);
  c.require(finite_nonnegative(p_.shear_stiffness), "shear_stiffness",
            "a shear stiffness >= 0 [N/m]", p_.shear_stiffness);
  c.require(!p_.shear || p_.shear_stiffness > 0.0, "shear_stiffness",
            "a shear stiffness > 0 [N/m] when the bolt has shear coordinates", p_.shear_stiffness,
            "or model the bolt without shear coordinates");
  c.require(finite_nonnegative(p_.shear_damping), "shear_damping", "a shear damping >= 0 [N s/m]",
            p_.shear_damping);
  c.require(!std::isnan(p_.activation_time) &&
                p_.activation_time < std::numeric_limits<double>::infinity(),
            "activation_time", "an activation time [s] (or none: active from the start)",
            p_.activation_time);
  c.require(finite_nonnegative(p_.preload_ramp), "preload_ramp", "a preload ramp duration >= 0 [s]",
            p_.preload_ramp);
  c.require(finite_nonnegative(p_.inactive_stiffness), "inactive_stiffness",
            "a stiffness before activation >= 0 [N/m]", p_.inactive_stiffness);
  // VDI 2230 Part 1 (2015), load introduction factor n: the clamped parts' compliance delta_P
  // splits into n delta_P between the load introduction planes and (1 - n) delta_P in series with
  // the bolt.
  const double delta_s = 1.0 / p_.bolt_stiffness, delta_p = 1.0 / p_.clamp_stiffness;
  const double n = p_.load_introduction;
  k1_ = 1.0 / (delta_s + (1.0 - n) * delta_p);
  k2_ = 1.0 / (n * delta_p);
}

double BoltedJoint::load_factor() const {
  // k_1 / (k_1 + k_2) = n delta_P / (delta_S + delta_P) = n k_S / (k_S + k_P).
  return p_.load_introduction * p_.bolt_stiffness / (p_.bolt_stiffness + p_.clamp_stiffness);
}

double BoltedJoint::opening_load() const { return p_.preload / (1.0 - load_factor()); }

double BoltedJoint::preload_at(double t) const {
  if (!active(t)) return 0.0;
  if (p_.preload_ramp > 0.0 && t < p_.activation_time + p_.preload_ramp)
    return p_.preload * (t - p_.activation_time) / p_.preload_ramp;
  return p_.preload;
}

BoltForces BoltedJoint::forces(double u_a, double t) const {
  BoltForces b;
  if (!active(t)) return b;
  b.preload = preload_at(t);
  const double bolt = b.preload + k1_ * u_a;   // bolt branch tension, both in contact
  const double clamp = b.preload - k2_ * u_a;  // interface compression, both in contact
  if (clamp <= 0.0 && u_a >= 0.0) {
    b.state = BoltState::open;
    b.bolt_force = bolt;
  } else if (bolt <= 0.0) {
    b.state = BoltState::slack;
    b.clamp_force = clamp;
  } else {
    b.state = BoltState::closed;
    b.bolt_force = bolt;
    b.clamp_force = clamp;
  }
  return b;
}

void BoltedJoint::evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double t,
                           ElementForce& out) const {
  const Eigen::Index n = size();
  out.reset(n);
  if (!active(t)) {
    // The bolt is not there; k_0 (default 0) only keeps a body hung on untightened bolts
    // connected for the static solution and the implicit step.
    out.force = p_.inactive_stiffness * u;
    out.stiffness.diagonal().setConstant(p_.inactive_stiffness);
    return;
  }
  const BoltForces b = forces(u(0), t);
  // Internal force on the opening = bolt tension - clamp compression (0 at u_a = 0: the
  // preload is self-equilibrated inside the joint).
  out.force(0) = b.bolt_force - b.clamp_force + p_.axial_damping * v(0);
  switch (b.state) {
    case BoltState::closed:
      out.stiffness(0, 0) = k1_ + k2_;
      break;
    case BoltState::open:
      out.stiffness(0, 0) = k1_;
      break;
    case BoltState::slack:
      out.stiffness(0, 0) = k2_;
      break;
    case BoltState::inactive:
      break;
  }
  out.damping(0, 0) = p_.axial_damping;
  for (Eigen::Index q = 1; q < n; ++q) {
    out.force(q) = p_.shear_stiffness * u(q) + p_.shear_damping * v(q);
    out.stiffness(q, q) = p_.shear_stiffness;
    out.damping(q, q) = p_.shear_damping;
  }
}

void BoltedJoint::switches(const Eigen::VectorXd& u, double t, double* g) const {
  const double preload = active(t) ? preload_at(t) : 0.0;
  g[0] = preload - k2_ * u(0);
  g[1] = preload + k1_ * u(0);
}

std::string BoltedJoint::describe_switch(int k) const {
  return k == 0 ? "joint opening" : "bolt slack";
}

}  // namespace geardyn::elements
