#pragma once
// Scalar normal-contact laws F(delta, delta_dot) for end stops, rattle and backlash contacts and
// tooth contact (docs/theory.md §16.2).
//
// Conventions:
//   * delta is the penetration [m] (> 0 in contact), delta_dot = d delta / dt [m/s] (> 0 while
//     the bodies approach). F > 0 pushes the bodies apart (compression).
//   * For delta <= 0 every law gives F = 0 and zero tangents.
//   * The tangents d F / d delta and d F / d delta_dot are analytic and are the derivatives of
//     the force actually returned, including the clipping below.
//   * Tension: where a damping term pulls the bodies together during separation (delta_dot < 0)
//     the sum can be negative. `Tension::allowed` returns it as is (the textbook Kelvin-Voigt
//     oscillator; IMPACT as the MSC ADAMS/Solver reference writes it, while SolidWorks Motion's
//     reference for the same function writes max(0, ...)); `Tension::clipped` returns max(F, 0)
//     with zero tangents where F would be negative.
//   * Bad parameters throw geardyn::InputError at the caller's location and key path, the key
//     being `<key_path>.stiffness`, `.exponent`, `.damping`, `.penetration_depth`, ...
//   * evaluate() is const and keeps no state (thread safe).
#include <string>

#include "geardyn/core/error.hpp"

namespace geardyn::elements {

/// A contact law's force and tangents at one state.
struct ContactForce {
  double force = 0.0;          ///< F [N] (> 0: compression)
  double d_penetration = 0.0;  ///< dF / d delta [N/m]
  double d_rate = 0.0;         ///< dF / d delta_dot [N s/m]
};

/// Whether a law may return a negative (tensile) force during separation.
enum class Tension { allowed, clipped };

/// Where a law's parameters came from, for InputError: the model file location and the key path
/// of the law's table (e.g. `contacts[2].law`); empty means top level.
struct LawSource {
  SourceLocation location;
  std::string key_path;
};

class ContactLaw {
 public:
  virtual ~ContactLaw() = default;
  /// Force and tangents at penetration `delta` [m] and penetration rate `delta_dot` [m/s].
  virtual ContactForce evaluate(double delta, double delta_dot) const = 0;
  /// The law and its parameters, for messages: e.g. "Hertz k = 1e+10, n = 1.5".
  virtual std::string describe() const = 0;
};

/// Kelvin-Voigt spring-damper: F = k delta + c delta_dot.
struct LinearLawParameters {
  double stiffness = 0.0;  ///< k [N/m] > 0
  double damping = 0.0;    ///< c [N s/m] >= 0
  Tension tension = Tension::allowed;
};

class LinearContactLaw final : public ContactLaw {
 public:
  explicit LinearContactLaw(const LinearLawParameters& p, const LawSource& source = {});
  ContactForce evaluate(double delta, double delta_dot) const override;
  std::string describe() const override;

 private:
  LinearLawParameters p_;
};

/// Hertz power law with Hunt-Crossley damping: F = k delta^n (1 + chi delta_dot)
/// (K.H. Hunt, F.R.E. Crossley, "Coefficient of restitution interpreted as damping in
/// vibroimpact", 1975). n = 3/2 point contact, 10/9 line contact; chi = 0 is pure Hertz.
struct HertzLawParameters {
  double stiffness = 0.0;  ///< k [N/m^n] > 0
  double exponent = 1.5;   ///< n >= 1
  double damping = 0.0;    ///< chi [s/m] >= 0 (Hunt-Crossley: chi ~ 3 (1 - e) / (2 v_impact))
  Tension tension = Tension::allowed;
};

class HertzContactLaw final : public ContactLaw {
 public:
  explicit HertzContactLaw(const HertzLawParameters& p, const LawSource& source = {});
  ContactForce evaluate(double delta, double delta_dot) const override;
  std::string describe() const override;

 private:
  HertzLawParameters p_;
};

/// MSC ADAMS' IMPACT function: F = k delta^e + STEP(delta, 0, 0, d, c_max) delta_dot.
struct ImpactLawParameters {
  double stiffness = 0.0;          ///< k [N/m^e] > 0
  double exponent = 1.5;           ///< e >= 1 (ADAMS' softening 0 < e < 1: infinite tangent)
  double max_damping = 0.0;        ///< c_max [N s/m] >= 0
  double penetration_depth = 0.0;  ///< d [m] > 0: full damping reached at delta = d
  Tension tension = Tension::allowed;
};

class ImpactContactLaw final : public ContactLaw {
 public:
  explicit ImpactContactLaw(const ImpactLawParameters& p, const LawSource& source = {});
  ContactForce evaluate(double delta, double delta_dot) const override;
  std::string describe() const override;

 private:
  ImpactLawParameters p_;
};

/// The penalty law of the e-axle NVH study:
/// F = k delta^m1 + c sign(delta_dot) |delta_dot|^m2 delta^m3, exponents >= 0.
/// Its derivatives are singular at delta -> 0 when m1 < 1 or m3 < 1 and at delta_dot -> 0 when
/// m2 < 1. There the law is regularised (the force itself, so the tangents stay its exact
/// derivatives): x^m for 0 < x < x_r is replaced by the secant x_r^(m-1) x, with x_r the
/// penetration regularisation for delta and the rate regularisation for |delta_dot|. Exponents
/// >= 1 need no regularisation and are evaluated exactly.
struct PenaltyLawParameters {
  double stiffness = 0.0;                    ///< k [N/m^m1] > 0
  double stiffness_exponent = 1.0;           ///< m1 >= 0
  double damping = 0.0;                      ///< c [N (s/m)^m2 / m^m3] >= 0
  double rate_exponent = 1.0;                ///< m2 >= 0
  double damping_exponent = 0.0;             ///< m3 >= 0 (on delta)
  double penetration_regularisation = 1e-9;  ///< delta_r [m] > 0 (used when m1 or m3 < 1)
  double rate_regularisation = 1e-6;         ///< v_r [m/s] > 0 (used when m2 < 1)
  Tension tension = Tension::allowed;
};

class PenaltyContactLaw final : public ContactLaw {
 public:
  explicit PenaltyContactLaw(const PenaltyLawParameters& p, const LawSource& source = {});
  ContactForce evaluate(double delta, double delta_dot) const override;
  std::string describe() const override;

 private:
  PenaltyLawParameters p_;
};

/// ADAMS' cubic STEP: h0 for x <= x0, h1 for x >= x1, h0 + (h1 - h0) s^2 (3 - 2 s) between,
/// s = (x - x0) / (x1 - x0); C1 (zero slope at both ends). Requires x1 > x0.
double cubic_step(double x, double x0, double h0, double x1, double h1);
/// d cubic_step / dx.
double cubic_step_derivative(double x, double x0, double h0, double x1, double h1);

}  // namespace geardyn::elements
