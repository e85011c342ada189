#include "geardyn/hbm/nonlinear_element.hpp"

#include <fmt/format.h>

#include <cmath>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::hbm {

Eigen::VectorXd NonlinearElement::initial_state(const Eigen::VectorXd& /*u*/) const {
  return Eigen::VectorXd::Zero(state_size());
}

Eigen::MatrixXd sampling_derivative(const HarmonicBasis& basis) {
  // d/dtheta (a cos h theta + b sin h theta) = h (-a sin h theta + b cos h theta): the columns of
  // the sampling matrix, swapped and scaled.
  const Eigen::MatrixXd& Q = basis.sampling();
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(Q.rows(), Q.cols());
  for (int h = 1; h <= basis.harmonics(); ++h) {
    D.col(HarmonicBasis::cos_index(h)) = -h * Q.col(HarmonicBasis::sin_index(h));
    D.col(HarmonicBasis::sin_index(h)) = h * Q.col(HarmonicBasis::cos_index(h));
  }
  return D;
}

namespace {

int coordinates_of(const HarmonicBasis& basis, const Eigen::VectorXd& w) {
  const int s = basis.size();
  // Contact laws return 0 for a NaN motion: a non-finite input must not pass unnoticed.
  if (!w.allFinite())
    throw NumericalError("harmonic balance",
                         "an element's motion is not finite (the Newton iteration diverged)");
  if (w.size() == 0 || w.size() % s != 0)
    throw InputError({}, "coordinates",
                     fmt::format("a multiple of 2H + 1 = {} Fourier coefficients", s),
                     fmt::format("{}", w.size()));
  return static_cast<int>(w.size() / s);
}

}  // namespace

Eigen::MatrixXd sample_coordinates(const HarmonicBasis& basis, const Eigen::VectorXd& w) {
  const int nc = coordinates_of(basis, w), s = basis.size();
  Eigen::MatrixXd u(basis.time_samples(), nc);
  for (int k = 0; k < nc; ++k) u.col(k) = basis.to_time(w.segment(k * s, s));
  return u;
}

Eigen::MatrixXd sample_velocities(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                                  double omega) {
  const int nc = coordinates_of(basis, w), s = basis.size();
  // The derivative series: harmonic h of (a, b) becomes h (b, -a).
  Eigen::MatrixXd v(basis.time_samples(), nc);
  Eigen::VectorXd d(s);
  for (int k = 0; k < nc; ++k) {
    const auto c = w.segment(k * s, s);
    d.setZero();
    for (int h = 1; h <= basis.harmonics(); ++h) {
      d[HarmonicBasis::cos_index(h)] = h * c[HarmonicBasis::sin_index(h)];
      d[HarmonicBasis::sin_index(h)] = -h * c[HarmonicBasis::cos_index(h)];
    }
    v.col(k) = omega * basis.to_time(d);
  }
  return v;
}

double loop_energy(const Eigen::MatrixXd& u, const Eigen::MatrixXd& f) {
  const Eigen::Index n = u.rows();
  double w = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index next = (j + 1) % n;
    w += 0.5 * (f.row(j) + f.row(next)).dot(u.row(next) - u.row(j));
  }
  return w;
}

void PointwiseElement::harmonic_force(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                                      double omega, Eigen::VectorXd& f, Eigen::MatrixXd* J,
                                      Eigen::VectorXd* df_domega) const {
  const int nc = size(), s = basis.size(), n = basis.time_samples();
  if (w.size() != nc * s)
    throw InputError({}, describe(), fmt::format("{} Fourier coefficients", nc * s),
                     fmt::format("{}", w.size()));
  const Eigen::MatrixXd u = sample_coordinates(basis, w);
  const bool rate = velocity_dependent();
  const Eigen::MatrixXd v =
      rate ? sample_velocities(basis, w, omega) : Eigen::MatrixXd::Zero(n, nc);
  const Eigen::MatrixXd& Q = basis.sampling();
  const Eigen::MatrixXd& P = basis.projection();
  const Eigen::MatrixXd Qd =
      (J != nullptr && rate) ? sampling_derivative(basis) : Eigen::MatrixXd();
  Eigen::MatrixXd force(n, nc);
  // Per sample j, the entries (i, k) of df_i/du_k and df_i/dv_k (column-major: i + k nc).
  Eigen::MatrixXd dfdu, dfdv;
  if (J != nullptr) dfdu.resize(n, nc * nc);
  if (J != nullptr || df_domega != nullptr) dfdv.resize(n, nc * nc);
  Eigen::MatrixXd direct;  // df/domega at fixed u, v per sample (n x nc)
  if (df_domega != nullptr) direct.setZero(n, nc);
  ElementStep step;
  Eigen::VectorXd d(nc);
  for (int j = 0; j < n; ++j) {
    step.force.setZero(nc);
    step.stiffness.setZero(nc, nc);
    step.damping.setZero(nc, nc);
    const double theta = units::kTwoPi * j / n;
    pointwise(u.row(j).transpose(), v.row(j).transpose(), theta, omega, step);
    if (df_domega != nullptr) {
      d.setZero();
      pointwise_omega_derivative(u.row(j).transpose(), v.row(j).transpose(), theta, omega, d);
      direct.row(j) = d.transpose();
    }
    if (!step.force.allFinite())
      throw NumericalError(describe(), fmt::format("the force is not finite at phase {:.4g} rad "
                                                   "of the period (a non-finite motion?)",
                                                   theta));
    force.row(j) = step.force.transpose();
    if (dfdu.size() > 0) dfdu.row(j) = step.stiffness.reshaped().transpose();
    if (dfdv.size() > 0) dfdv.row(j) = step.damping.reshaped().transpose();
  }
  for (int i = 0; i < nc; ++i) f.segment(i * s, s) += P * force.col(i);
  if (J != nullptr) {
    for (int i = 0; i < nc; ++i)
      for (int k = 0; k < nc; ++k) {
        // Column-major reshape: entry (i, k) of an nc x nc matrix is at i + k nc.
        const Eigen::Index ik = i + k * nc;
        Eigen::MatrixXd block = P * dfdu.col(ik).asDiagonal() * Q;
        if (rate) block += omega * (P * dfdv.col(ik).asDiagonal() * Qd);
        J->block(i * s, k * s, s, s) += block;
      }
  }
  if (df_domega != nullptr && rate) {
    // v = omega Q' w: df/domega = P diag(df/dv) (v / omega).
    for (int i = 0; i < nc; ++i) {
      Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
      for (int k = 0; k < nc; ++k) g += dfdv.col(i + k * nc).cwiseProduct(v.col(k));
      df_domega->segment(i * s, s) += P * g / omega;
    }
  }
  if (df_domega != nullptr)
    for (int i = 0; i < nc; ++i) df_domega->segment(i * s, s) += P * direct.col(i);
}

ElementLoop PointwiseElement::loop(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                                   double omega) const {
  const int nc = size(), n = basis.time_samples();
  ElementLoop r;
  r.displacement = sample_coordinates(basis, w);
  const Eigen::MatrixXd v =
      velocity_dependent() ? sample_velocities(basis, w, omega) : Eigen::MatrixXd::Zero(n, nc);
  r.force.resize(n, nc);
  ElementStep step;
  for (int j = 0; j < n; ++j) {
    step.force.setZero(nc);
    step.stiffness.setZero(nc, nc);
    step.damping.setZero(nc, nc);
    pointwise(r.displacement.row(j).transpose(), v.row(j).transpose(), units::kTwoPi * j / n, omega,
              step);
    r.force.row(j) = step.force.transpose();
  }
  r.energy_per_cycle = loop_energy(r.displacement, r.force);
  return r;
}

void PointwiseElement::time_force(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta,
                                  double omega, const Eigen::VectorXd& /*state*/,
                                  ElementStep& out) const {
  const int nc = size();
  out.force.setZero(nc);
  out.stiffness.setZero(nc, nc);
  out.damping.setZero(nc, nc);
  pointwise(u, v, theta, omega, out);
  out.state.resize(0);
}

}  // namespace geardyn::hbm
