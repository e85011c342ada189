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
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/hbm/friction_contact.hpp"

namespace geardyn::hbm {
namespace {

void require(bool ok, const char* key, const char* expected, double found) {
  if (!ok) throw InputError({}, key, expected, fmt::format("{}", found));
}

void validate(const ContactMarchOptions& o) {
  if (o.max_periods < 1)
    throw InputError({}, "max_periods", "at least 1 period", std::to_string(o.max_periods));
  require(o.closure_tolerance >= 0.0 && std::isfinite(o.closure_tolerance), "closure_tolerance",
          "a finite relative tolerance >= 0", o.closure_tolerance);
}

void validate_unilateral(double stiffness, double gap) {
  require(stiffness > 0.0 && std::isfinite(stiffness), "stiffness",
          "a finite contact stiffness > 0 N/m", stiffness);
  require(std::isfinite(gap), "gap", "a finite gap [m]", gap);
}

// The tangential force and its gradient with respect to the coefficients of w, carried from
// sample to sample. Buffers are sized once: the march runs n_time steps per period.
class TangentialMarch {
 public:
  TangentialMarch(const FrictionContact& c, const HarmonicBasis& basis, const Eigen::VectorXd& N,
                  const Eigen::VectorXd& normal_slope, const Eigen::MatrixXd& u)
      : D_(c.tangential_directions),
        m_(basis.size()),
        kt_(c.tangential_stiffness),
        mu_(c.friction_coefficient),
        Q_(basis.sampling()),
        N_(N),
        normal_slope_(normal_slope),
        u_(u),
        T_(D_),
        T_trial_(D_),
        t_(D_),
        g_(D_, (1 + D_) * m_),
        g_trial_(D_, (1 + D_) * m_),
        t_g_((1 + D_) * m_) {}

  // Sample 0 of the first period: stuck about the mean position u_mean, T* = k_t (u_0 - u_mean),
  // then the return map like any predictor.
  ContactState start(const Eigen::VectorXd& u_mean) {
    T_trial_ = kt_ * (u_.row(0).transpose() - u_mean);
    g_trial_.setZero();
    for (int d = 0; d < D_; ++d) {
      // d u_mean / d w is the unit vector of that direction's a_0.
      g_trial_.block(d, (1 + d) * m_, 1, m_) = kt_ * Q_.row(0);
      g_trial_(d, (1 + d) * m_) -= kt_;
    }
    return return_map(0);
  }

  // From sample `previous` to sample j.
  ContactState step(int j, int previous) {
    T_trial_ = T_ + kt_ * (u_.row(j) - u_.row(previous)).transpose();
    g_trial_ = g_;
    for (int d = 0; d < D_; ++d)
      g_trial_.block(d, (1 + d) * m_, 1, m_) += kt_ * (Q_.row(j) - Q_.row(previous));
    return return_map(j);
  }

  const Eigen::VectorXd& force() const { return T_; }
  const Eigen::MatrixXd& gradient() const { return g_; }

 private:
  ContactState return_map(int j) {
    if (!(N_[j] > 0.0)) {
      T_.setZero();
      g_.setZero();
      return ContactState::LiftOff;
    }
    const double limit = mu_ * N_[j];
    // hypot, not sqrt(x^2 + y^2): no underflow for tiny forces; in 1D |T*| exactly, so the
    // element reproduces jenkins.cpp to the last bit.
    const double norm = D_ == 1 ? std::abs(T_trial_[0]) : std::hypot(T_trial_[0], T_trial_[1]);
    if (norm < limit) {
      T_ = T_trial_;
      g_ = g_trial_;
      return ContactState::Stick;
    }
    if (limit == 0.0) {  // mu = 0: slips freely, no force (and T* may be 0: no direction)
      T_.setZero();
      g_.setZero();
      return ContactState::Slip;
    }
    // Radial return onto the circle |T| = mu N: T = mu N t with t = T* / |T*|, whose derivative
    // is mu dN t + mu N dt and dt = (I - t t^T) dT* / |T*|. In 1D the projector vanishes and
    // only the load's variation remains.
    t_ = T_trial_ / norm;
    T_ = limit * t_;
    t_g_.noalias() = t_.transpose() * g_trial_;
    g_ = g_trial_;
    g_.noalias() -= t_ * t_g_;
    g_ *= limit / norm;
    if (normal_slope_[j] != 0.0)
      g_.leftCols(m_).noalias() += (mu_ * normal_slope_[j]) * t_ * Q_.row(j);
    return ContactState::Slip;
  }

  int D_, m_;
  double kt_, mu_;
  const Eigen::MatrixXd& Q_;
  const Eigen::VectorXd& N_;
  const Eigen::VectorXd& normal_slope_;
  const Eigen::MatrixXd& u_;
  Eigen::VectorXd T_, T_trial_, t_;
  Eigen::MatrixXd g_, g_trial_;
  Eigen::RowVectorXd t_g_;
};

}  // namespace

void validate(const FrictionContact& c) {
  if (c.tangential_directions != 1 && c.tangential_directions != 2)
    throw InputError({}, "tangential_directions", "1 (2D contact) or 2 (3D contact)",
                     std::to_string(c.tangential_directions));
  require(c.tangential_stiffness > 0.0 && std::isfinite(c.tangential_stiffness),
          "tangential_stiffness", "a finite tangential stiffness k_t > 0 N/m",
          c.tangential_stiffness);
  require(c.normal_stiffness >= 0.0 && std::isfinite(c.normal_stiffness), "normal_stiffness",
          "a finite normal stiffness k_n >= 0 N/m", c.normal_stiffness);
  require(c.friction_coefficient >= 0.0 && std::isfinite(c.friction_coefficient),
          "friction_coefficient", "a finite friction coefficient mu >= 0", c.friction_coefficient);
  require(c.normal_preload >= 0.0 && std::isfinite(c.normal_preload), "normal_preload",
          "a finite normal preload N_0 >= 0 N", c.normal_preload);
}

ContactResponse friction_contact_response(const FrictionContact& contact,
                                          const HarmonicBasis& basis,
                                          const Eigen::Ref<const Eigen::VectorXd>& w,
                                          const ContactMarchOptions& options) {
  validate(contact);
  validate(options);
  const int D = contact.tangential_directions;
  const int m = basis.size(), n = basis.time_samples(), size = (1 + D) * m;
  if (w.size() != size)
    throw InputError({}, "w",
                     fmt::format("{} coefficients ((1 + tangential_directions) (2H + 1))", size),
                     std::to_string(w.size()));
  const double kt = contact.tangential_stiffness, kn = contact.normal_stiffness;
  const double mu = contact.friction_coefficient, N0 = contact.normal_preload;

  // The normal force has no memory: sample it once, with its slope dN_j / dv_j.
  const Eigen::VectorXd v = basis.to_time(w.head(m));
  Eigen::VectorXd N(n), normal_slope(n);
  for (int j = 0; j < n; ++j) {
    const double trial = N0 + kn * v[j];
    N[j] = trial > 0.0 ? trial : 0.0;
    normal_slope[j] = trial > 0.0 ? kn : 0.0;
  }
  Eigen::MatrixXd u(n, D);
  Eigen::VectorXd u_mean(D);
  for (int d = 0; d < D; ++d) {
    u.col(d) = basis.to_time(w.segment((1 + d) * m, m));
    u_mean[d] = w[(1 + d) * m];
  }
  // Closure scales: the largest friction force and the largest elastic force about the mean
  // (not about 0: a large static offset must not loosen the test), and the largest gradient.
  const double force_scale =
      std::max({mu * N.maxCoeff(), kt * (u.rowwise() - u_mean.transpose()).cwiseAbs().maxCoeff(),
                std::numeric_limits<double>::min()});
  const double gradient_scale = std::max(kt, mu * kn);

  ContactResponse r;
  Eigen::MatrixXd T(n, D);
  std::vector<Eigen::MatrixXd> G(static_cast<std::size_t>(D), Eigen::MatrixXd(n, size));
  r.state.resize(static_cast<std::size_t>(n));
  TangentialMarch march(contact, basis, N, normal_slope, u);
  ContactState state = march.start(u_mean);
  Eigen::VectorXd T_start = march.force();
  Eigen::MatrixXd g_start = march.gradient();
  auto record = [&](int j, ContactState s) {
    T.row(j) = march.force().transpose();
    for (int d = 0; d < D; ++d) G[static_cast<std::size_t>(d)].row(j) = march.gradient().row(d);
    r.state[static_cast<std::size_t>(j)] = s;
  };
  for (int p = 0; p < options.max_periods; ++p) {
    record(0, state);
    for (int j = 1; j < n; ++j) record(j, march.step(j, j - 1));
    state = march.step(0, n - 1);  // the start of the next period
    r.periods_marched = p + 1;
    r.closure_error = std::max((march.force() - T_start).cwiseAbs().maxCoeff() / force_scale,
                               (march.gradient() - g_start).cwiseAbs().maxCoeff() / gradient_scale);
    if (r.closure_error <= options.closure_tolerance) {
      r.loop_closed = true;
      break;
    }
    T_start = march.force();
    g_start = march.gradient();
  }

  const Eigen::MatrixXd& P = basis.projection();
  r.coefficients.resize(size);
  r.coefficients.head(m) = basis.to_frequency(N.array() - N0);
  r.jacobian = Eigen::MatrixXd::Zero(size, size);
  r.jacobian.topLeftCorner(m, m) = P * normal_slope.asDiagonal() * basis.sampling();
  for (int d = 0; d < D; ++d) {
    r.coefficients.segment((1 + d) * m, m) = basis.to_frequency(T.col(d));
    r.jacobian.middleRows((1 + d) * m, m) = P * G[static_cast<std::size_t>(d)];
  }
  r.force.resize(n, 1 + D);
  r.force.col(0) = N;
  r.force.rightCols(D) = T;

  int stuck = 0, slipping = 0, lifted = 0;
  for (ContactState s : r.state) {
    stuck += s == ContactState::Stick ? 1 : 0;
    slipping += s == ContactState::Slip ? 1 : 0;
    lifted += s == ContactState::LiftOff ? 1 : 0;
  }
  r.stick_fraction = static_cast<double>(stuck) / n;
  r.slip_fraction = static_cast<double>(slipping) / n;
  r.lift_off_fraction = static_cast<double>(lifted) / n;
  // Closed-loop integral of T . du by the trapezoidal rule over the periodic samples.
  double energy = 0.0;
  for (int j = 0; j < n; ++j) {
    const int next = (j + 1) % n;
    energy += 0.5 * (T.row(j) + T.row(next)).dot(u.row(next) - u.row(j));
  }
  r.energy_per_cycle = energy;
  return r;
}

UnilateralResponse unilateral_spring_response(double stiffness, double gap,
                                              const HarmonicBasis& basis,
                                              const Eigen::Ref<const Eigen::VectorXd>& q) {
  validate_unilateral(stiffness, gap);
  const int n = basis.time_samples();
  if (q.size() != basis.size())
    throw InputError({}, "q", fmt::format("{} coefficients (2H + 1)", basis.size()),
                     std::to_string(q.size()));
  const Eigen::VectorXd samples = basis.to_time(q);
  UnilateralResponse r;
  r.force.resize(n);
  Eigen::VectorXd slope(n);
  int closed = 0;
  for (int j = 0; j < n; ++j) {
    const bool touching = samples[j] > gap;
    r.force[j] = touching ? stiffness * (samples[j] - gap) : 0.0;
    slope[j] = touching ? stiffness : 0.0;
    closed += touching ? 1 : 0;
  }
  r.coefficients = basis.to_frequency(r.force);
  r.jacobian = basis.projection() * slope.asDiagonal() * basis.sampling();
  r.contact_fraction = static_cast<double>(closed) / n;
  return r;
}

NonlinearForce friction_contact_force(std::vector<int> coordinates, FrictionContact contact) {
  validate(contact);
  const std::size_t count = static_cast<std::size_t>(1 + contact.tangential_directions);
  if (coordinates.size() != count)
    throw InputError({}, "coordinates",
                     fmt::format("{} DOF indices (normal, then {} tangential)", count, count - 1),
                     fmt::format("{} indices", coordinates.size()));
  for (std::size_t i = 0; i < count; ++i) {
    if (coordinates[i] < 0)
      throw InputError({}, fmt::format("coordinates[{}]", i), "a DOF index >= 0",
                       std::to_string(coordinates[i]));
    for (std::size_t k = 0; k < i; ++k)
      if (coordinates[k] == coordinates[i])
        throw InputError({}, fmt::format("coordinates[{}]", i),
                         "a DOF distinct from the other coordinates",
                         fmt::format("{} (also coordinates[{}])", coordinates[i], k));
  }
  return [coordinates = std::move(coordinates), contact](const HarmonicBasis& b,
                                                         const Eigen::VectorXd& X,
                                                         Eigen::VectorXd& F, Eigen::MatrixXd& J) {
    const int s = b.size();
    const int c = static_cast<int>(coordinates.size());
    const int highest = *std::max_element(coordinates.begin(), coordinates.end());
    if (X.size() < (highest + 1) * s)
      throw InputError({}, "coordinates",
                       fmt::format("DOF indices below {}, the DOFs of the unknowns", X.size() / s),
                       std::to_string(highest));
    Eigen::VectorXd w(c * s);
    for (int i = 0; i < c; ++i)
      w.segment(i * s, s) = X.segment(coordinates[static_cast<std::size_t>(i)] * s, s);
    const ContactResponse r = friction_contact_response(contact, b, w);
    for (int i = 0; i < c; ++i) {
      const int row = coordinates[static_cast<std::size_t>(i)] * s;
      F.segment(row, s) += r.coefficients.segment(i * s, s);
      for (int k = 0; k < c; ++k)
        J.block(row, coordinates[static_cast<std::size_t>(k)] * s, s, s) +=
            r.jacobian.block(i * s, k * s, s, s);
    }
  };
}

NonlinearForce unilateral_spring(int dof, double stiffness, double gap) {
  if (dof < 0) throw InputError({}, "dof", "a DOF index >= 0", std::to_string(dof));
  validate_unilateral(stiffness, gap);
  return [dof, stiffness, gap](const HarmonicBasis& b, const Eigen::VectorXd& X, Eigen::VectorXd& F,
                               Eigen::MatrixXd& J) {
    const int s = b.size();
    if (X.size() < (dof + 1) * s)
      throw InputError({}, "dof",
                       fmt::format("a DOF index below {}, the DOFs of the unknowns", X.size() / s),
                       std::to_string(dof));
    const UnilateralResponse r =
        unilateral_spring_response(stiffness, gap, b, X.segment(dof * s, s));
    F.segment(dof * s, s) += r.coefficients;
    J.block(dof * s, dof * s, s, s) += r.jacobian;
  };
}

}  // namespace geardyn::hbm
