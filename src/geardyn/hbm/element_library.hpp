#pragma once
// The element library of the `nonlinear_elements` model section (issue #18, docs/theory.md §8):
// concrete NonlinearElements (nonlinear_element.hpp) for harmonic balance (AFT) and for the
// periodic time analyses that check it (monodromy stability, time-marched steady states).
//
//   JenkinsElementHb     spring k in series with a Coulomb slider of limit F (jenkins.hpp),
//                        1 coordinate; hysteretic.
//   FrictionContactHb    node-to-node friction contact with variable normal load and lift-off
//                        (friction_contact.hpp), coordinates [v, u_1, (u_2)]; hysteretic.
//   PolynomialSpring     f = sum_p c_p u^p (the cubic spring is {3: alpha}), 1 coordinate.
//   UnilateralSpringHb   f = k max(u - gap, 0) + c u' while closed, 1 coordinate.
//   TanhCoulomb          f = F tanh(u' / v_eps): regularised Coulomb friction, 1 coordinate.
//   ForceElementAdapter  any autonomous elements::ForceElement (gap contacts with their contact
//                        laws, bushings, bolts, ...) as a pointwise law.
//
// Time-domain state of the hysteretic elements. Both use the slider position s (the "plastic"
// displacement of the return-mapping algorithm, Simo & Hughes, "Computational Inelasticity",
// Springer 1998, ch. 1-2), so that a step needs only the committed state and the current u:
//   predictor  T* = k (u - s),  stick |T*| < F: T = T*, s unchanged, tangent k;
//   slip       T = F T* / |T*|  (radial return), s <- u - T / k, tangent (F / |T*|) k (I - t t^T)
//              with t = T* / |T*| (0 in one direction), plus mu dN/dv t for the contact's normal.
// With s_{j-1} = u_{j-1} - T_{j-1} / k this predictor is T_{j-1} + k (u_j - u_{j-1}), the
// predictor of the AFT marches (jenkins.cpp, friction_contact.cpp): marching time_force over the
// AFT samples from initial_state(mean of u) (the slider at the mean position, where the AFT
// starts its march) reproduces loop() to round-off. The tangential force is k (u - s).
//
// Sampling: the pointwise laws are evaluated by the AFT of PointwiseElement, exact for the
// samples taken. A polynomial of degree p_max has harmonics up to p_max H for H harmonics of u;
// they do not alias onto the kept ones when n_time > (p_max + 1) H, so the AFT of
// PolynomialSpring is then exact (default_time_samples(H, degree())). Laws with kinks (gap,
// friction) converge as O((2 pi / n_time)^2) at their switching instants.
#include <map>
#include <memory>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/elements/force_element.hpp"
#include "geardyn/hbm/friction_contact.hpp"
#include "geardyn/hbm/jenkins.hpp"
#include "geardyn/hbm/nonlinear_element.hpp"

namespace geardyn::hbm {

/// Where an element's parameters came from, for InputError: the model file location and the key
/// path of the element's table (e.g. `nonlinear_elements[2]`); empty: the keys are top level.
/// The keys named are then `<key_path>.stiffness`, `<key_path>.slip_force`, ...
struct ElementSource {
  SourceLocation location;
  std::string key_path;
};

/// A Jenkins element on one coordinate u: stiffness k in series with a slider of limit F.
/// harmonic_force through jenkins_response (exact Jacobian; no dependence on omega). State: the
/// slider position s (T = k (u - s)).
class JenkinsElementHb final : public NonlinearElement {
 public:
  /// Throws InputError for `stiffness` k not finite > 0 or `slip_force` F not finite >= 0.
  JenkinsElementHb(std::string name, JenkinsElement law, const ElementSource& source = {});

  const JenkinsElement& law() const { return law_; }

  int size() const override { return 1; }
  /// "jenkins '<name>'".
  std::string describe() const override;
  void harmonic_force(const HarmonicBasis& basis, const Eigen::VectorXd& w, double omega,
                      Eigen::VectorXd& f, Eigen::MatrixXd* J,
                      Eigen::VectorXd* df_domega) const override;
  /// Stick and slip fractions (open: NaN), energy per cycle (Griffin: 4 F (X - F / k)).
  ElementLoop loop(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                   double omega) const override;
  /// 1: the slider position s [m].
  int state_size() const override { return 1; }
  /// s = u: the spring unloaded at u.
  Eigen::VectorXd initial_state(const Eigen::VectorXd& u) const override;
  /// Return mapping from the committed slider position: tangent k in stick, 0 in slip.
  void time_force(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta, double omega,
                  const Eigen::VectorXd& state, ElementStep& out) const override;

 private:
  std::string name_;
  JenkinsElement law_;
};

/// The friction contact of friction_contact.hpp on the coordinates [v, u_1, (u_2)] (normal
/// approach from the preloaded equilibrium, then the tangential slip): generalized force
/// [N - N_0, T], N = max(N_0 + k_n v, 0). harmonic_force through friction_contact_response with
/// `options`; a loop that does not close within options.max_periods enters with its last period,
/// as friction_contact_force does (only slow 2D slip barely above the limit needs more).
/// State: the tangential slider position s (1 or 2 components; T = k_t (u - s) in stick).
class FrictionContactHb final : public NonlinearElement {
 public:
  /// Throws InputError naming the first invalid field (`tangential_directions`,
  /// `tangential_stiffness`, `normal_stiffness`, `friction_coefficient`, `normal_preload`) or
  /// option (`max_periods`, `closure_tolerance`).
  FrictionContactHb(std::string name, FrictionContact contact, ContactMarchOptions options = {},
                    const ElementSource& source = {});

  const FrictionContact& contact() const { return contact_; }

  /// 1 + tangential directions.
  int size() const override { return 1 + contact_.tangential_directions; }
  /// "friction contact '<name>'".
  std::string describe() const override;
  void harmonic_force(const HarmonicBasis& basis, const Eigen::VectorXd& w, double omega,
                      Eigen::VectorXd& f, Eigen::MatrixXd* J,
                      Eigen::VectorXd* df_domega) const override;
  /// Stick, slip and lift-off (open) fractions; force samples [N - N_0, T]; the energy of the
  /// tangential force (the normal force is elastic).
  ElementLoop loop(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                   double omega) const override;
  /// Tangential directions: the slider position s [m].
  int state_size() const override { return contact_.tangential_directions; }
  /// s = the tangential part of u: stuck and unloaded there.
  Eigen::VectorXd initial_state(const Eigen::VectorXd& u) const override;
  /// Normal law, then the radial return of the tangential force from the committed s; at
  /// lift-off T = 0 and s follows u.
  void time_force(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta, double omega,
                  const Eigen::VectorXd& state, ElementStep& out) const override;

 private:
  std::string name_;
  FrictionContact contact_;
  ContactMarchOptions options_;
};

/// f = sum_p c_p u^p on one coordinate (powers p >= 1). The AFT is exact when
/// n_time > (degree() + 1) H (default_time_samples(H, degree())).
class PolynomialSpring final : public PointwiseElement {
 public:
  /// `coefficients`: power -> c_p, at least one, powers >= 1, finite c_p; InputError otherwise.
  PolynomialSpring(std::string name, std::map<int, double> coefficients,
                   const ElementSource& source = {});

  /// The largest power p_max.
  int degree() const { return coefficients_.rbegin()->first; }
  const std::map<int, double>& coefficients() const { return coefficients_; }

  int size() const override { return 1; }
  /// "polynomial spring '<name>'".
  std::string describe() const override;
  void pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta, double omega,
                 ElementStep& out) const override;

 private:
  std::string name_;
  std::map<int, double> coefficients_;
};

/// f = k max(u - gap, 0) + c u' while closed (u > gap), on one coordinate: a contact that closes
/// at u = gap (gap < 0: preloaded by k |gap| at u = 0). The slope at u == gap is that of the open
/// side (0), as unilateral_spring_response takes it. The damping term may pull (tension) while
/// the closed contact opens: the Kelvin-Voigt law as written.
class UnilateralSpringHb final : public PointwiseElement {
 public:
  /// Throws InputError for `stiffness` not finite > 0, `gap` not finite or `damping` not
  /// finite >= 0.
  UnilateralSpringHb(std::string name, double stiffness, double gap, double damping = 0.0,
                     const ElementSource& source = {});

  int size() const override { return 1; }
  /// "unilateral spring '<name>'".
  std::string describe() const override;
  void pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta, double omega,
                 ElementStep& out) const override;
  bool velocity_dependent() const override { return damping_ > 0.0; }
  /// PointwiseElement's loop with the open fraction (share of the samples with u <= gap).
  ElementLoop loop(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                   double omega) const override;

 private:
  std::string name_;
  double stiffness_, gap_, damping_;
};

/// Regularised Coulomb friction f = F tanh(u' / v_eps) on one coordinate: velocity-dependent
/// (df/domega != 0). It tends to the rigid-plastic slider (Jenkins with k -> infinity) as
/// v_eps -> 0. The NLvib examples of Krack & Gross ("Harmonic Balance for Nonlinear Vibration
/// Problems", Springer 2019) use it for a friction-damped 2-DOF oscillator after Laxalde &
/// Thouverez (J. Sound Vib. 322 (2009) 1009-1025), to be compared with the Jenkins element.
class TanhCoulomb final : public PointwiseElement {
 public:
  /// Throws InputError for `slip_force` not finite >= 0 or `regularisation_velocity` not
  /// finite > 0.
  TanhCoulomb(std::string name, double slip_force, double regularisation_velocity,
              const ElementSource& source = {});

  int size() const override { return 1; }
  /// "tanh Coulomb '<name>'".
  std::string describe() const override;
  void pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta, double omega,
                 ElementStep& out) const override;
  bool velocity_dependent() const override { return true; }

 private:
  std::string name_;
  double slip_force_, regularisation_velocity_;
};

/// An elements::ForceElement as a pointwise law: f(u, v) = element.evaluate(u, v, t = 0).
/// Only autonomous (time-independent) force elements are accepted: the phase theta = omega t of
/// a periodic solution is not the element's time t (a bolt's activation schedule is in absolute
/// time), so t = 0 is passed always and an element with a schedule would be evaluated frozen at
/// t = 0. The adapter cannot tell from the interface whether the element damps, so it is treated
/// as velocity-dependent (velocities are sampled; df/domega is exact, zero for elastic laws).
class ForceElementAdapter final : public PointwiseElement {
 public:
  /// Throws InputError (`element`) for a null element or one of size < 1.
  ForceElementAdapter(std::string name, std::shared_ptr<const elements::ForceElement> element,
                      const ElementSource& source = {});

  const elements::ForceElement& element() const { return *element_; }

  int size() const override { return static_cast<int>(element_->size()); }
  /// "force element '<name>' (<the element's describe()>)".
  std::string describe() const override;
  void pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta, double omega,
                 ElementStep& out) const override;
  bool velocity_dependent() const override { return true; }

 private:
  std::string name_;
  std::shared_ptr<const elements::ForceElement> element_;
};

}  // namespace geardyn::hbm
