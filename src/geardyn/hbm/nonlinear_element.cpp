#include "geardyn/hbm/nonlinear_element.hpp"

#include <fmt/format.h>

#include <cmath>
#include <complex>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/signal/fft.hpp"

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

// C_k + i S_k = (1/n) sum_j c_j e^{i k theta_j}, k = 0 .. 2H, from the real FFT of c (which holds
// k <= n / 2; above, X_k = conj(X_{n - k}); n >= 2H + 1 keeps 2H < n).
Eigen::VectorXcd sample_spectrum(const HarmonicBasis& basis,
                                 const Eigen::Ref<const Eigen::VectorXd>& c) {
  const int n = basis.time_samples(), top = 2 * basis.harmonics();
  const Eigen::VectorXcd X = signal::real_fft(c);
  Eigen::VectorXcd z(top + 1);
  for (int k = 0; k <= top; ++k) {
    const std::complex<double> x = 2 * k <= n ? X[k] : std::conj(X[n - k]);
    z[k] = std::conj(x) / static_cast<double>(n);
  }
  return z;
}

}  // namespace

Eigen::MatrixXd projected_diagonal(const HarmonicBasis& basis,
                                   const Eigen::Ref<const Eigen::VectorXd>& c) {
  if (c.size() != basis.time_samples())
    throw InputError({}, "samples", fmt::format("{} time samples", basis.time_samples()),
                     fmt::format("{}", c.size()));
  const int H = basis.harmonics(), s = basis.size();
  const Eigen::VectorXcd z = sample_spectrum(basis, c);
  auto C = [&](int k) { return z[std::abs(k)].real(); };
  auto S = [&](int k) { return k >= 0 ? z[k].imag() : -z[-k].imag(); };
  Eigen::MatrixXd W(s, s);
  W(0, 0) = C(0);
  for (int g = 1; g <= H; ++g) {
    W(0, HarmonicBasis::cos_index(g)) = C(g);
    W(0, HarmonicBasis::sin_index(g)) = S(g);
  }
  for (int h = 1; h <= H; ++h) {
    const int ch = HarmonicBasis::cos_index(h), sh = HarmonicBasis::sin_index(h);
    W(ch, 0) = 2.0 * C(h);
    W(sh, 0) = 2.0 * S(h);
    for (int g = 1; g <= H; ++g) {
      const int cg = HarmonicBasis::cos_index(g), sg = HarmonicBasis::sin_index(g);
      W(ch, cg) = C(h - g) + C(h + g);
      W(ch, sg) = S(h + g) - S(h - g);
      W(sh, cg) = S(h + g) + S(h - g);
      W(sh, sg) = C(h - g) - C(h + g);
    }
  }
  return W;
}

Eigen::MatrixXd projected_diagonal_derivative(const HarmonicBasis& basis,
                                              const Eigen::Ref<const Eigen::VectorXd>& c) {
  const Eigen::MatrixXd W = projected_diagonal(basis, c);
  // Q' = Q with the columns of harmonic h swapped and scaled (sampling_derivative).
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(W.rows(), W.cols());
  for (int h = 1; h <= basis.harmonics(); ++h) {
    D.col(HarmonicBasis::cos_index(h)) = -h * W.col(HarmonicBasis::sin_index(h));
    D.col(HarmonicBasis::sin_index(h)) = h * W.col(HarmonicBasis::cos_index(h));
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

namespace {

// The pointwise law over the samples of one period: the force (n x nc) and, as asked, per sample
// j the entries (i, k) of df_i/du_k and df_i/dv_k (column-major: i + k nc) and df/domega at
// fixed u, v. One u, v and ElementStep are reused over the samples: no allocation per sample.
struct LawSamples {
  Eigen::MatrixXd u, v, force, dfdu, dfdv, direct;
};

LawSamples sample_law(const PointwiseElement& e, const HarmonicBasis& basis,
                      const Eigen::VectorXd& w, double omega, bool slopes, bool rates,
                      bool direct) {
  const int nc = e.size(), s = basis.size(), n = basis.time_samples();
  if (w.size() != nc * s)
    throw InputError({}, e.describe(), fmt::format("{} Fourier coefficients", nc * s),
                     fmt::format("{}", w.size()));
  LawSamples r;
  r.u = sample_coordinates(basis, w);
  r.v = e.velocity_dependent() ? sample_velocities(basis, w, omega) : Eigen::MatrixXd::Zero(n, nc);
  r.force.resize(n, nc);
  if (slopes) r.dfdu.resize(n, nc * nc);
  if (rates) r.dfdv.resize(n, nc * nc);
  if (direct) r.direct.setZero(n, nc);
  ElementStep step;
  Eigen::VectorXd uj(nc), vj(nc), d(nc);
  for (int j = 0; j < n; ++j) {
    step.force.setZero(nc);
    step.stiffness.setZero(nc, nc);
    step.damping.setZero(nc, nc);
    uj = r.u.row(j).transpose();
    vj = r.v.row(j).transpose();
    const double theta = units::kTwoPi * j / n;
    e.pointwise(uj, vj, theta, omega, step);
    if (direct) {
      d.setZero();
      e.pointwise_omega_derivative(uj, vj, theta, omega, d);
      r.direct.row(j) = d.transpose();
    }
    if (!step.force.allFinite())
      throw NumericalError(e.describe(), fmt::format("the force is not finite at phase {:.4g} rad "
                                                     "of the period (a non-finite motion?)",
                                                     theta));
    r.force.row(j) = step.force.transpose();
    if (slopes) r.dfdu.row(j) = step.stiffness.reshaped().transpose();
    if (rates) r.dfdv.row(j) = step.damping.reshaped().transpose();
  }
  return r;
}

}  // namespace

void PointwiseElement::harmonic_force(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                                      double omega, Eigen::VectorXd& f, Eigen::MatrixXd* J,
                                      Eigen::VectorXd* df_domega) const {
  const int nc = size(), s = basis.size(), n = basis.time_samples();
  const bool rate = velocity_dependent();
  const LawSamples l =
      sample_law(*this, basis, w, omega, J != nullptr,
                 rate && (J != nullptr || df_domega != nullptr), df_domega != nullptr);
  for (int i = 0; i < nc; ++i) f.segment(i * s, s) += basis.to_frequency(l.force.col(i));
  if (J != nullptr) {
    for (int i = 0; i < nc; ++i)
      for (int k = 0; k < nc; ++k) {
        // Column-major reshape: entry (i, k) of an nc x nc matrix is at i + k nc;
        // J = P diag(df/du) Q + omega P diag(df/dv) Q'.
        const Eigen::Index ik = i + k * nc;
        if (!l.dfdu.col(ik).isZero(0.0))
          J->block(i * s, k * s, s, s) += projected_diagonal(basis, l.dfdu.col(ik));
        if (rate && !l.dfdv.col(ik).isZero(0.0))
          J->block(i * s, k * s, s, s) +=
              omega * projected_diagonal_derivative(basis, l.dfdv.col(ik));
      }
  }
  if (df_domega != nullptr && rate) {
    // v = omega Q' w: df/domega = P diag(df/dv) (v / omega).
    Eigen::VectorXd g(n);
    for (int i = 0; i < nc; ++i) {
      g.setZero();
      for (int k = 0; k < nc; ++k) g += l.dfdv.col(i + k * nc).cwiseProduct(l.v.col(k));
      df_domega->segment(i * s, s) += basis.to_frequency(g) / omega;
    }
  }
  if (df_domega != nullptr)
    for (int i = 0; i < nc; ++i)
      df_domega->segment(i * s, s) += basis.to_frequency(l.direct.col(i));
}

void PointwiseElement::harmonic_velocity_jacobian(const HarmonicBasis& basis,
                                                  const Eigen::VectorXd& w, double omega,
                                                  Eigen::MatrixXd& Jv) const {
  if (!velocity_dependent()) return;
  const int nc = size(), s = basis.size();
  const LawSamples l = sample_law(*this, basis, w, omega, false, true, false);
  for (int i = 0; i < nc; ++i)
    for (int k = 0; k < nc; ++k)
      if (!l.dfdv.col(i + k * nc).isZero(0.0))
        Jv.block(i * s, k * s, s, s) += projected_diagonal(basis, l.dfdv.col(i + k * nc));
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
