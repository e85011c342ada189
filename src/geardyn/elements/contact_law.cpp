#include "geardyn/elements/contact_law.hpp"

#include <cmath>

#include "geardyn/elements/parameter_check.hpp"

namespace geardyn::elements {

namespace {

using detail::format_number;

void require_exponent_from_one(const detail::ParameterCheck& c, double x) {
  c.require(std::isfinite(x) && x >= 1.0, "exponent",
            "an exponent >= 1 (3/2 point contact, 10/9 line contact)", x);
}

// Clipping of a tensile force: max(F, 0) with zero tangents where F < 0.
ContactForce apply_tension(ContactForce f, Tension tension) {
  if (tension == Tension::clipped && f.force < 0.0) return ContactForce{};
  return f;
}

// delta^n and its derivative for delta > 0, n >= 1 (n = 1: derivative 1 at delta -> 0).
struct Power {
  double value;
  double derivative;
};

Power power(double x, double n) {
  const double p = std::pow(x, n - 1.0);
  return {p * x, n * p};
}

// Regularised x^m for x >= 0: exact for m >= 1 or x >= x_r, else the secant x_r^(m-1) x.
Power regularised_power(double x, double m, double x_r) {
  if (m >= 1.0 || x >= x_r) return power(x, m);
  const double slope = std::pow(x_r, m - 1.0);
  return {slope * x, slope};
}

std::string tension_note(Tension t) { return t == Tension::clipped ? ", clipped at 0" : ""; }

}  // namespace

double cubic_step(double x, double x0, double h0, double x1, double h1) {
  if (x <= x0) return h0;
  if (x >= x1) return h1;
  const double s = (x - x0) / (x1 - x0);
  return h0 + (h1 - h0) * s * s * (3.0 - 2.0 * s);
}

double cubic_step_derivative(double x, double x0, double h0, double x1, double h1) {
  if (x <= x0 || x >= x1) return 0.0;
  const double s = (x - x0) / (x1 - x0);
  return (h1 - h0) * 6.0 * s * (1.0 - s) / (x1 - x0);
}

// ---- Kelvin-Voigt -------------------------------------------------------------------------

LinearContactLaw::LinearContactLaw(const LinearLawParameters& p, const LawSource& source) : p_(p) {
  const detail::ParameterCheck c(source.location, source.key_path);
  c.positive("stiffness", p.stiffness);
  c.non_negative("damping", p.damping);
}

ContactForce LinearContactLaw::evaluate(double delta, double delta_dot) const {
  if (!(delta > 0.0)) return {};
  return apply_tension({p_.stiffness * delta + p_.damping * delta_dot, p_.stiffness, p_.damping},
                       p_.tension);
}

std::string LinearContactLaw::describe() const {
  return "linear k = " + format_number(p_.stiffness) + " N/m, c = " + format_number(p_.damping) +
         " N s/m" + tension_note(p_.tension);
}

// ---- Hertz / Hunt-Crossley ----------------------------------------------------------------

HertzContactLaw::HertzContactLaw(const HertzLawParameters& p, const LawSource& source) : p_(p) {
  const detail::ParameterCheck c(source.location, source.key_path);
  c.positive("stiffness", p.stiffness);
  require_exponent_from_one(c, p.exponent);
  c.non_negative("damping", p.damping);
}

ContactForce HertzContactLaw::evaluate(double delta, double delta_dot) const {
  if (!(delta > 0.0)) return {};
  const Power d = power(delta, p_.exponent);
  const double factor = 1.0 + p_.damping * delta_dot;
  ContactForce f;
  f.force = p_.stiffness * d.value * factor;
  f.d_penetration = p_.stiffness * d.derivative * factor;
  f.d_rate = p_.stiffness * d.value * p_.damping;
  return apply_tension(f, p_.tension);
}

std::string HertzContactLaw::describe() const {
  return "Hertz k = " + format_number(p_.stiffness) + ", n = " + format_number(p_.exponent) +
         ", Hunt-Crossley chi = " + format_number(p_.damping) + " s/m" + tension_note(p_.tension);
}

// ---- ADAMS IMPACT -------------------------------------------------------------------------

ImpactContactLaw::ImpactContactLaw(const ImpactLawParameters& p, const LawSource& source) : p_(p) {
  const detail::ParameterCheck c(source.location, source.key_path);
  c.positive("stiffness", p.stiffness);
  require_exponent_from_one(c, p.exponent);
  c.non_negative("damping", p.max_damping);
  c.positive("penetration_depth", p.penetration_depth);
}

ContactForce ImpactContactLaw::evaluate(double delta, double delta_dot) const {
  if (!(delta > 0.0)) return {};
  const Power d = power(delta, p_.exponent);
  const double c = cubic_step(delta, 0.0, 0.0, p_.penetration_depth, p_.max_damping);
  const double dc = cubic_step_derivative(delta, 0.0, 0.0, p_.penetration_depth, p_.max_damping);
  ContactForce f;
  f.force = p_.stiffness * d.value + c * delta_dot;
  f.d_penetration = p_.stiffness * d.derivative + dc * delta_dot;
  f.d_rate = c;
  return apply_tension(f, p_.tension);
}

std::string ImpactContactLaw::describe() const {
  return "IMPACT k = " + format_number(p_.stiffness) + ", e = " + format_number(p_.exponent) +
         ", c_max = " + format_number(p_.max_damping) +
         " N s/m, d = " + format_number(p_.penetration_depth) + " m" + tension_note(p_.tension);
}

// ---- penalty law --------------------------------------------------------------------------

PenaltyContactLaw::PenaltyContactLaw(const PenaltyLawParameters& p, const LawSource& source)
    : p_(p) {
  const detail::ParameterCheck c(source.location, source.key_path);
  c.positive("stiffness", p.stiffness);
  c.non_negative("stiffness_exponent", p.stiffness_exponent);
  c.non_negative("damping", p.damping);
  c.non_negative("rate_exponent", p.rate_exponent);
  c.non_negative("damping_exponent", p.damping_exponent);
  c.positive("penetration_regularisation", p.penetration_regularisation);
  c.positive("rate_regularisation", p.rate_regularisation);
}

ContactForce PenaltyContactLaw::evaluate(double delta, double delta_dot) const {
  if (!(delta > 0.0)) return {};
  const Power spring =
      regularised_power(delta, p_.stiffness_exponent, p_.penetration_regularisation);
  const Power shape = regularised_power(delta, p_.damping_exponent, p_.penetration_regularisation);
  // sign(v) |v|^m2 (odd in v); its derivative is even.
  const Power rate =
      regularised_power(std::abs(delta_dot), p_.rate_exponent, p_.rate_regularisation);
  const double signed_rate = delta_dot < 0.0 ? -rate.value : rate.value;
  ContactForce f;
  f.force = p_.stiffness * spring.value + p_.damping * signed_rate * shape.value;
  f.d_penetration = p_.stiffness * spring.derivative + p_.damping * signed_rate * shape.derivative;
  f.d_rate = p_.damping * rate.derivative * shape.value;
  return apply_tension(f, p_.tension);
}

std::string PenaltyContactLaw::describe() const {
  return "penalty k = " + format_number(p_.stiffness) +
         ", m1 = " + format_number(p_.stiffness_exponent) + ", c = " + format_number(p_.damping) +
         ", m2 = " + format_number(p_.rate_exponent) +
         ", m3 = " + format_number(p_.damping_exponent) + tension_note(p_.tension);
}

}  // namespace geardyn::elements
