#include "geardyn/elements/rolling_bearing.hpp"

#include <fmt/format.h>

#include <cassert>
#include <cmath>
#include <utility>

#include "geardyn/core/units.hpp"
#include "geardyn/elements/parameter_check.hpp"

namespace geardyn::elements {

namespace {

void check(const RollingBearingParams& p, const std::string& key_path,
           const SourceLocation& where) {
  const detail::ParameterCheck c(where, key_path);
  if (p.elements < 1)
    c.fail("elements", "a number of balls or rollers >= 1", static_cast<double>(p.elements));
  c.positive("stiffness_constant", p.stiffness_constant,
             "the load-deflection constant K_n of one element in N/m^n (Q = K_n delta^n)");
  if (!(std::isfinite(p.exponent) && p.exponent >= 1.0 && p.exponent <= 2.0))
    c.fail("exponent", "a load-deflection exponent in [1, 2]", p.exponent,
           "3/2 for balls (point contact), 10/9 for rollers (line contact)");
  c.finite("radial_clearance", p.radial_clearance);
  c.finite("axial_clearance", p.axial_clearance);
  if (!(std::isfinite(p.contact_angle) && std::abs(p.contact_angle) <= 0.5 * units::kPi))
    c.fail("contact_angle", "a contact angle in [-pi/2, pi/2] rad", p.contact_angle);
  c.positive("pitch_diameter", p.pitch_diameter);
  c.positive("element_diameter", p.element_diameter);
  if (p.element_diameter >= p.pitch_diameter)
    c.fail("element_diameter",
           fmt::format("a ball or roller diameter < pitch_diameter = {:.6g} m", p.pitch_diameter),
           p.element_diameter);
  c.finite("cage_angle", p.cage_angle);
  c.finite("cage_speed", p.cage_speed);
  c.non_negative("radial_damping", p.radial_damping);
  c.non_negative("axial_damping", p.axial_damping);
}

}  // namespace

double BearingKinematics::gamma() const {
  return element_diameter * std::cos(contact_angle) / pitch_diameter;
}

double BearingKinematics::cage(double inner, double outer) const {
  const double g = gamma();
  return 0.5 * (inner * (1.0 - g) + outer * (1.0 + g));
}

double BearingKinematics::ball_pass_outer(double inner, double outer) const {
  return elements * std::abs(cage(inner, outer) - outer);
}

double BearingKinematics::ball_pass_inner(double inner, double outer) const {
  return elements * std::abs(inner - cage(inner, outer));
}

double BearingKinematics::ball_spin(double inner, double outer) const {
  const double g = gamma();
  return pitch_diameter / (2.0 * element_diameter) * (1.0 - g * g) * std::abs(inner - outer);
}

RollingBearing::RollingBearing(RollingBearingParams params, const std::string& key_path,
                               SourceLocation where)
    : p_(std::move(params)) {
  check(p_, key_path, where);
  // The axial play projects on the contact line with |sin(alpha)|: a bearing carrying thrust in
  // -z (alpha < 0) closes its axial play just like one carrying it in +z.
  gap_ = 0.5 * (p_.radial_clearance * std::cos(p_.contact_angle) +
                p_.axial_clearance * std::abs(std::sin(p_.contact_angle)));
  kappa_ = 0.5 * (1.0 - kinematics().gamma());
}

double RollingBearing::cage_angle(const Eigen::VectorXd& u, double t) const {
  return p_.spin_angle ? cage_angle(t) + kappa_ * u(3) : cage_angle(t);
}

double RollingBearing::deflection(const Eigen::VectorXd& u, double t, int k) const {
  const double psi = cage_angle(u, t) + 2.0 * units::kPi * k / p_.elements;
  const double ca = std::cos(p_.contact_angle), sa = std::sin(p_.contact_angle);
  return ca * (u(0) * std::cos(psi) + u(1) * std::sin(psi)) + sa * u(2) - gap_;
}

void RollingBearing::evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double t,
                              ElementForce& out) const {
  const Eigen::Index n_u = size();
  assert(u.size() == n_u && v.size() == n_u);
  out.reset(n_u);
  const double psi0 = cage_angle(u, t);
  const double ca = std::cos(p_.contact_angle), sa = std::sin(p_.contact_angle);
  const double kn = p_.stiffness_constant, n = p_.exponent;
  for (int k = 0; k < p_.elements; ++k) {
    const double psi = psi0 + 2.0 * units::kPi * k / p_.elements;
    const Eigen::Vector3d e(ca * std::cos(psi), ca * std::sin(psi), sa);
    const double delta = e.dot(u.head<3>()) - gap_;
    if (delta <= 0.0) continue;  // not in contact: no load, no stiffness
    const double pow_nm1 = std::pow(delta, n - 1.0);
    const double q = kn * pow_nm1 * delta, dq = n * kn * pow_nm1;
    out.force.head<3>() += q * e;                                   // Q_k e_k, Q_k = K_n delta^n
    out.stiffness.topLeftCorner<3, 3>() += dq * e * e.transpose();  // dQ_k/d delta e_k e_k^T
    if (p_.spin_angle) {  // d (Q_k e_k) / d theta = kappa d (Q_k e_k) / d psi
      const Eigen::Vector3d de(-ca * std::sin(psi), ca * std::cos(psi), 0.0);
      out.stiffness.block<3, 1>(0, 3) += kappa_ * (dq * de.dot(u.head<3>()) * e + q * de);
    }
  }
  out.damping(0, 0) = p_.radial_damping;
  out.damping(1, 1) = p_.radial_damping;
  out.damping(2, 2) = p_.axial_damping;
  out.force.head<3>() += out.damping.topLeftCorner<3, 3>() * v.head<3>();
}

std::string RollingBearing::describe() const {
  return fmt::format("rolling bearing '{}' (Z = {}, n = {:.4g}{})", p_.name, p_.elements,
                     p_.exponent, p_.spin_angle ? ", cage driven by the spin angle" : "");
}

BearingKinematics RollingBearing::kinematics() const {
  return {p_.elements, p_.pitch_diameter, p_.element_diameter, p_.contact_angle};
}

}  // namespace geardyn::elements
