#include "geardyn/elements/contact_law.hpp"

#include <cmath>
#include <sstream>

namespace geardyn::elements {

namespace {

std::string number(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

std::string key(const LawSource& source, const std::string& name) {
  return source.key_path.empty() ? name : source.key_path + "." + name;
}

// Throws unless `ok`; `expected` says what the key must be.
void require(bool ok, const LawSource& source, const std::string& name, const std::string& expected,
             double found) {
  if (!ok) throw InputError(source.location, key(source, name), expected, number(found));
}

void require_positive(double x, const LawSource& source, const std::string& name) {
  require(std::isfinite(x) && x > 0.0, source, name, "a finite number > 0", x);
}

void require_non_negative(double x, const LawSource& source, const std::string& name) {
  require(std::isfinite(x) && x >= 0.0, source, name, "a finite number >= 0", x);
}

void require_exponent_from_one(double x, const LawSource& source, const std::string& name) {
  require(std::isfinite(x) && x >= 1.0, source, name,
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
  require_positive(p.stiffness, source, "stiffness");
  require_non_negative(p.damping, source, "damping");
}

ContactForce LinearContactLaw::evaluate(double delta, double delta_dot) const {
  if (!(delta > 0.0)) return {};
  return apply_tension({p_.stiffness * delta + p_.damping * delta_dot, p_.stiffness, p_.damping},
                       p_.tension);
}

std::string LinearContactLaw::describe() const {
  return "linear k = " + number(p_.stiffness) + " N/m, c = " + number(p_.damping) + " N s/m" +
         tension_note(p_.tension);
}

// ---- Hertz / Hunt-Crossley ----------------------------------------------------------------

HertzContactLaw::HertzContactLaw(const HertzLawParameters& p, const LawSource& source) : p_(p) {
  require_positive(p.stiffness, source, "stiffness");
  require_exponent_from_one(p.exponent, source, "exponent");
  require_non_negative(p.damping, source, "damping");
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
  return "Hertz k = " + number(p_.stiffness) + ", n = " + number(p_.exponent) +
         ", Hunt-Crossley chi = " + number(p_.damping) + " s/m" + tension_note(p_.tension);
}

// ---- ADAMS IMPACT -------------------------------------------------------------------------

ImpactContactLaw::ImpactContactLaw(const ImpactLawParameters& p, const LawSource& source) : p_(p) {
  require_positive(p.stiffness, source, "stiffness");
  require_exponent_from_one(p.exponent, source, "exponent");
  require_non_negative(p.max_damping, source, "damping");
  require_positive(p.penetration_depth, source, "penetration_depth");
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
  return "IMPACT k = " + number(p_.stiffness) + ", e = " + number(p_.exponent) +
         ", c_max = " + number(p_.max_damping) + " N s/m, d = " + number(p_.penetration_depth) +
         " m" + tension_note(p_.tension);
}

// ---- penalty law --------------------------------------------------------------------------

PenaltyContactLaw::PenaltyContactLaw(const PenaltyLawParameters& p, const LawSource& source)
    : p_(p) {
  require_positive(p.stiffness, source, "stiffness");
  require_non_negative(p.stiffness_exponent, source, "stiffness_exponent");
  require_non_negative(p.damping, source, "damping");
  require_non_negative(p.rate_exponent, source, "rate_exponent");
  require_non_negative(p.damping_exponent, source, "damping_exponent");
  require_positive(p.penetration_regularisation, source, "penetration_regularisation");
  require_positive(p.rate_regularisation, source, "rate_regularisation");
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
  return "penalty k = " + number(p_.stiffness) + ", m1 = " + number(p_.stiffness_exponent) +
         ", c = " + number(p_.damping) + ", m2 = " + number(p_.rate_exponent) +
         ", m3 = " + number(p_.damping_exponent) + tension_note(p_.tension);
}

}  // namespace geardyn::elements
