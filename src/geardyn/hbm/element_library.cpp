// GCC's -Wnull-dereference false positive inside Eigen's and <complex>'s inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <complex>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "geardyn/core/error.hpp"
#include "geardyn/hbm/element_library.hpp"

namespace geardyn::hbm {
namespace {

std::string key_of(const ElementSource& source, const std::string& key) {
  return source.key_path.empty() ? key : source.key_path + "." + key;
}

void require(bool ok, const ElementSource& source, const char* key, const char* expected,
             double found) {
  if (!ok)
    throw InputError(source.location, key_of(source, key), expected, fmt::format("{}", found));
}

// The coefficients handed to an element's AFT: n (2H + 1) of them, finite.
void check_coefficients(const NonlinearElement& e, const HarmonicBasis& basis,
                        const Eigen::VectorXd& w) {
  const Eigen::Index expected = static_cast<Eigen::Index>(e.size()) * basis.size();
  if (w.size() != expected)
    throw InputError({}, e.describe(), fmt::format("{} Fourier coefficients", expected),
                     fmt::format("{}", w.size()));
  if (!w.allFinite())
    throw NumericalError(e.describe(), "non-finite Fourier coefficients of the motion");
}

// The arguments of a time step: u and v of the element's size, a state of its state size.
void check_step(const NonlinearElement& e, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                const Eigen::VectorXd& state) {
  if (u.size() != e.size() || v.size() != e.size() || state.size() != e.state_size())
    throw InputError(
        {}, e.describe(),
        fmt::format("u and v of size {} and a state of size {}", e.size(), e.state_size()),
        fmt::format("sizes {}, {} and {}", u.size(), v.size(), state.size()));
}

void reset(ElementStep& out, int n) {
  out.force.setZero(n);
  out.stiffness.setZero(n, n);
  out.damping.setZero(n, n);
}

// x^p for an integer p >= 0, by repeated multiplication (exact for the small powers of a
// polynomial spring, and no pow() of a negative base).
double integer_power(double x, int p) {
  double r = 1.0;
  for (int i = 0; i < p; ++i) r *= x;
  return r;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Jenkins

JenkinsElementHb::JenkinsElementHb(std::string name, JenkinsElement law,
                                   const ElementSource& source)
    : name_(std::move(name)), law_(law) {
  require(law_.stiffness > 0.0 && std::isfinite(law_.stiffness), source, "stiffness",
          "a finite stiffness k > 0 N/m", law_.stiffness);
  require(law_.slip_force >= 0.0 && std::isfinite(law_.slip_force), source, "slip_force",
          "a finite slip force F >= 0 N", law_.slip_force);
}

std::string JenkinsElementHb::describe() const { return fmt::format("jenkins '{}'", name_); }

void JenkinsElementHb::harmonic_force(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                                      double /*omega*/, Eigen::VectorXd& f, Eigen::MatrixXd* J,
                                      Eigen::VectorXd* /*df_domega*/) const {
  check_coefficients(*this, basis, w);
  // The force-only march when no Jacobian is asked (a line search's trial).
  const JenkinsResponse r = jenkins_response(law_, basis, w, J != nullptr);
  f += r.coefficients;
  if (J != nullptr) *J += r.jacobian;
  // df/domega = 0: the law is rate-independent.
}

ElementLoop JenkinsElementHb::loop(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                                   double /*omega*/) const {
  check_coefficients(*this, basis, w);
  const JenkinsResponse r = jenkins_response(law_, basis, w, false);
  ElementLoop l;
  l.displacement = sample_coordinates(basis, w);
  l.force = r.force;
  l.stick_fraction = r.stick_fraction;
  l.slip_fraction = 1.0 - r.stick_fraction;
  l.energy_per_cycle = r.energy_per_cycle;
  return l;
}

Eigen::VectorXd JenkinsElementHb::initial_state(const Eigen::VectorXd& u) const {
  return u.head(1);
}

void JenkinsElementHb::time_force(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                  double /*theta*/, double /*omega*/, const Eigen::VectorXd& state,
                                  ElementStep& out) const {
  check_step(*this, u, v, state);
  reset(out, 1);
  const double k = law_.stiffness, F = law_.slip_force;
  const double trial = k * (u[0] - state[0]);
  if (std::abs(trial) < F) {  // stick (jenkins.cpp: slip from |T*| >= F)
    out.force[0] = trial;
    out.stiffness(0, 0) = k;
    out.state = state;
    return;
  }
  const double T = F * (trial >= 0.0 ? 1.0 : -1.0);
  out.force[0] = T;
  out.state = Eigen::VectorXd::Constant(1, u[0] - T / k);
}

// ---------------------------------------------------------------------------------------------
// Friction contact

FrictionContactHb::FrictionContactHb(std::string name, FrictionContact contact,
                                     ContactMarchOptions options, const ElementSource& source)
    : name_(std::move(name)), contact_(contact), options_(options) {
  try {
    validate(contact_);
  } catch (const InputError& e) {  // the same message, at the element's location and key path
    throw InputError(source.location, key_of(source, e.key_path()), e.expected(), e.found(),
                     e.hint());
  }
  if (options_.max_periods < 1)
    throw InputError(source.location, key_of(source, "max_periods"), "at least 1 period",
                     fmt::format("{}", options_.max_periods));
  require(options_.closure_tolerance >= 0.0 && std::isfinite(options_.closure_tolerance), source,
          "closure_tolerance", "a finite relative tolerance >= 0", options_.closure_tolerance);
}

std::string FrictionContactHb::describe() const {
  return fmt::format("friction contact '{}'", name_);
}

void FrictionContactHb::harmonic_force(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                                       double /*omega*/, Eigen::VectorXd& f, Eigen::MatrixXd* J,
                                       Eigen::VectorXd* /*df_domega*/) const {
  check_coefficients(*this, basis, w);
  const ContactResponse r = friction_contact_response(contact_, basis, w, options_);
  f += r.coefficients;
  if (J != nullptr) *J += r.jacobian;
  // df/domega = 0: the law is rate-independent.
}

ElementLoop FrictionContactHb::loop(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                                    double /*omega*/) const {
  check_coefficients(*this, basis, w);
  const ContactResponse r = friction_contact_response(contact_, basis, w, options_);
  ElementLoop l;
  l.displacement = sample_coordinates(basis, w);
  l.force = r.force;
  l.force.col(0).array() -= contact_.normal_preload;  // the generalized force [N - N_0, T]
  l.stick_fraction = r.stick_fraction;
  l.slip_fraction = r.slip_fraction;
  l.open_fraction = r.lift_off_fraction;
  l.energy_per_cycle = r.energy_per_cycle;
  return l;
}

Eigen::VectorXd FrictionContactHb::initial_state(const Eigen::VectorXd& u) const {
  return u.tail(contact_.tangential_directions);
}

void FrictionContactHb::time_force(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                   double /*theta*/, double /*omega*/, const Eigen::VectorXd& state,
                                   ElementStep& out) const {
  check_step(*this, u, v, state);
  const int D = contact_.tangential_directions;
  reset(out, 1 + D);
  const double kt = contact_.tangential_stiffness, kn = contact_.normal_stiffness;
  const double mu = contact_.friction_coefficient, N0 = contact_.normal_preload;
  // Normal law (memoryless), as friction_contact_response samples it.
  const double normal_trial = N0 + kn * u[0];
  const bool touching = normal_trial > 0.0;
  const double N = touching ? normal_trial : 0.0;
  const double normal_slope = touching ? kn : 0.0;
  out.force[0] = N - N0;
  out.stiffness(0, 0) = normal_slope;
  const Eigen::VectorXd ut = u.tail(D);
  if (!touching) {  // lift-off: no tangential force, the slider follows the surface
    out.state = ut;
    return;
  }
  const Eigen::VectorXd trial = kt * (ut - state);
  const double limit = mu * N;
  const double norm = D == 1 ? std::abs(trial[0]) : std::hypot(trial[0], trial[1]);
  if (norm < limit) {  // stick
    out.force.tail(D) = trial;
    out.stiffness.bottomRightCorner(D, D) = kt * Eigen::MatrixXd::Identity(D, D);
    out.state = state;
    return;
  }
  if (limit == 0.0) {  // mu = 0: slips freely without force (and T* may have no direction)
    out.state = ut;
    return;
  }
  // Radial return: T = mu N t, t = T* / |T*|; dT/du_t = (mu N / |T*|) k_t (I - t t^T),
  // dT/dv = mu k_n t.
  const Eigen::VectorXd t = trial / norm;
  const Eigen::VectorXd T = limit * t;
  out.force.tail(D) = T;
  out.stiffness.bottomRightCorner(D, D) =
      (limit / norm) * kt * (Eigen::MatrixXd::Identity(D, D) - t * t.transpose());
  out.stiffness.bottomLeftCorner(D, 1) = mu * normal_slope * t;
  out.state = ut - T / kt;
}

// ---------------------------------------------------------------------------------------------
// Polynomial spring

PolynomialSpring::PolynomialSpring(std::string name, std::map<int, double> coefficients,
                                   const ElementSource& source)
    : name_(std::move(name)), coefficients_(std::move(coefficients)) {
  const std::string key = key_of(source, "coefficients");
  if (coefficients_.empty())
    throw InputError(source.location, key, "at least one (power, coefficient) pair", "none");
  for (const auto& [p, c] : coefficients_) {
    if (p < 1)
      throw InputError(source.location, key, "integer powers >= 1", fmt::format("power {}", p));
    if (!std::isfinite(c))
      throw InputError(source.location, key, "finite coefficients",
                       fmt::format("{} for power {}", c, p));
  }
}

std::string PolynomialSpring::describe() const {
  return fmt::format("polynomial spring '{}'", name_);
}

void PolynomialSpring::pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& /*v*/,
                                 double /*theta*/, double /*omega*/, ElementStep& out) const {
  const double x = u[0];
  double f = 0.0, slope = 0.0;
  for (const auto& [p, c] : coefficients_) {
    const double lower = integer_power(x, p - 1);
    f += c * lower * x;
    slope += p * c * lower;
  }
  out.force[0] = f;
  out.stiffness(0, 0) = slope;
}

// ---------------------------------------------------------------------------------------------
// Unilateral spring

UnilateralSpringHb::UnilateralSpringHb(std::string name, double stiffness, double gap,
                                       double damping, const ElementSource& source)
    : name_(std::move(name)), stiffness_(stiffness), gap_(gap), damping_(damping) {
  require(stiffness_ > 0.0 && std::isfinite(stiffness_), source, "stiffness",
          "a finite contact stiffness > 0 N/m", stiffness_);
  require(std::isfinite(gap_), source, "gap", "a finite gap [m]", gap_);
  require(damping_ >= 0.0 && std::isfinite(damping_), source, "damping",
          "a finite damping >= 0 N s/m", damping_);
}

std::string UnilateralSpringHb::describe() const {
  return fmt::format("unilateral spring '{}'", name_);
}

void UnilateralSpringHb::pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                   double /*theta*/, double /*omega*/, ElementStep& out) const {
  if (!(u[0] > gap_)) return;  // open: no force, zero tangents
  out.force[0] = stiffness_ * (u[0] - gap_) + damping_ * v[0];
  out.stiffness(0, 0) = stiffness_;
  out.damping(0, 0) = damping_;
}

ElementLoop UnilateralSpringHb::loop(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                                     double omega) const {
  ElementLoop l = PointwiseElement::loop(basis, w, omega);
  const Eigen::Index open = (l.displacement.col(0).array() <= gap_).count();
  l.open_fraction = static_cast<double>(open) / static_cast<double>(l.displacement.rows());
  return l;
}

// ---------------------------------------------------------------------------------------------
// Regularised Coulomb friction

TanhCoulomb::TanhCoulomb(std::string name, double slip_force, double regularisation_velocity,
                         const ElementSource& source)
    : name_(std::move(name)),
      slip_force_(slip_force),
      regularisation_velocity_(regularisation_velocity) {
  require(slip_force_ >= 0.0 && std::isfinite(slip_force_), source, "slip_force",
          "a finite slip force F >= 0 N", slip_force_);
  require(regularisation_velocity_ > 0.0 && std::isfinite(regularisation_velocity_), source,
          "regularisation_velocity", "a finite regularisation velocity v_eps > 0 m/s",
          regularisation_velocity_);
}

std::string TanhCoulomb::describe() const { return fmt::format("tanh Coulomb '{}'", name_); }

void TanhCoulomb::pointwise(const Eigen::VectorXd& /*u*/, const Eigen::VectorXd& v,
                            double /*theta*/, double /*omega*/, ElementStep& out) const {
  const double t = std::tanh(v[0] / regularisation_velocity_);
  out.force[0] = slip_force_ * t;
  out.damping(0, 0) = slip_force_ / regularisation_velocity_ * (1.0 - t * t);
}

// ---------------------------------------------------------------------------------------------
// ForceElement adapter

ForceElementAdapter::ForceElementAdapter(std::string name,
                                         std::shared_ptr<const elements::ForceElement> element,
                                         const ElementSource& source)
    : name_(std::move(name)), element_(std::move(element)) {
  if (!element_)
    throw InputError(source.location, key_of(source, "element"), "a force element", "none");
  if (element_->size() < 1)
    throw InputError(source.location, key_of(source, "element"),
                     "an element of at least one coordinate",
                     fmt::format("{} coordinates", element_->size()));
}

std::string ForceElementAdapter::describe() const {
  return fmt::format("force element '{}' ({})", name_, element_->describe());
}

void ForceElementAdapter::pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                    double /*theta*/, double /*omega*/, ElementStep& out) const {
  elements::ElementForce ef;
  // Autonomous elements only: t = 0 (see the header).
  element_->evaluate(u, v, 0.0, ef);
  const Eigen::Index n = element_->size();
  if (ef.force.size() != n || ef.stiffness.rows() != n || ef.stiffness.cols() != n ||
      ef.damping.rows() != n || ef.damping.cols() != n)
    throw NumericalError(describe(),
                         fmt::format("the element returned a force of size {} and "
                                     "tangents of {} x {} and {} x {}, not {}",
                                     ef.force.size(), ef.stiffness.rows(), ef.stiffness.cols(),
                                     ef.damping.rows(), ef.damping.cols(), n));
  out.force = ef.force;
  out.stiffness = ef.stiffness;
  out.damping = ef.damping;
}

}  // namespace geardyn::hbm
