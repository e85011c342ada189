// GCC's -Wnull-dereference false positive inside Eigen's inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of Eigen.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <utility>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/hbm/nonlinear_modes.hpp"

namespace geardyn::hbm {

namespace {

using Strided = Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<>>;

// The coefficient c (HarmonicBasis layout) of every DOF in DOF-major harmonics X.
Strided coefficient_of_dofs(const Eigen::VectorXd& X, int n_dof, int s, int c) {
  return Strided(X.data() + c, n_dof, Eigen::InnerStride<>(s));
}

// G_1 (n_dof (2H+1) square) with G_1 X the harmonics of -M q' / omega: harmonic h of (a, b)
// gives h M (-b, a). The negative damping -xi M q' thus adds xi omega G_1 X to the residual.
Eigen::MatrixXd velocity_mass(const Eigen::MatrixXd& M, const HarmonicBasis& basis) {
  const int s = basis.size(), n = static_cast<int>(M.rows());
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n * s, n * s);
  for (int d = 0; d < n; ++d)
    for (int e = 0; e < n; ++e) {
      if (M(d, e) == 0.0) continue;
      for (int h = 1; h <= basis.harmonics(); ++h) {
        const int ci = HarmonicBasis::cos_index(h), si = HarmonicBasis::sin_index(h);
        G(d * s + ci, e * s + si) = -h * M(d, e);
        G(d * s + si, e * s + ci) = h * M(d, e);
      }
    }
  return G;
}

// Block (c_row, c_col) of the fundamental over the DOF pairs of the dense Jacobian J at rest.
Eigen::MatrixXd fundamental_block(const Eigen::MatrixXd& J, int n_dof, int s, int c_row,
                                  int c_col) {
  Eigen::MatrixXd B(n_dof, n_dof);
  for (int d = 0; d < n_dof; ++d)
    for (int e = 0; e < n_dof; ++e) B(d, e) = J(d * s + c_row, e * s + c_col);
  return B;
}

// Mode `mode` of the oscillatory (complex) modes of M q'' + C q' + K q = 0, in ascending |lambda|:
// omega_0 = |lambda| and xi = -2 Re lambda (exact for proportional damping), the shape psi (the
// displacement half of the state eigenvector) with psi^H M psi = 1 and its largest entry real
// and positive. Overdamped (real) and rigid-body modes are not counted.
LinearModeStart complex_mode(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C,
                             const Eigen::MatrixXd& K, int mode) {
  const Eigen::Index n = M.rows();
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  // The amplitude condition's gradient 2 M X_1 and the LLT (which reads one triangle) need M
  // symmetric.
  if (llt.info() != Eigen::Success || (M - M.transpose()).norm() > 1e-12 * M.norm())
    throw InputError({}, "mass", "a symmetric positive definite mass matrix",
                     "a non-symmetric matrix or one whose Cholesky factorisation fails");
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = -llt.solve(K);
  A.bottomRightCorner(n, n) = -llt.solve(C);
  const Eigen::EigenSolver<Eigen::MatrixXd> es(A);
  if (es.info() != Eigen::Success)
    throw NumericalError("nonlinear mode",
                         "the eigenvalues of the linearisation at rest did not converge");
  std::vector<Eigen::Index> oscillatory;
  for (Eigen::Index i = 0; i < 2 * n; ++i) {
    const std::complex<double> l = es.eigenvalues()[i];
    if (l.imag() > 1e-12 * std::abs(l)) oscillatory.push_back(i);
  }
  std::sort(oscillatory.begin(), oscillatory.end(), [&es](Eigen::Index i, Eigen::Index j) {
    return std::abs(es.eigenvalues()[i]) < std::abs(es.eigenvalues()[j]);
  });
  if (mode < 0 || mode >= static_cast<int>(oscillatory.size()))
    throw InputError({}, "mode",
                     fmt::format("an oscillatory linear mode index in [0, {}] (K plus the "
                                 "elements' stiffness at rest; rigid-body and overdamped modes "
                                 "are not counted)",
                                 static_cast<int>(oscillatory.size()) - 1),
                     fmt::format("{}", mode));
  const Eigen::Index i = oscillatory[static_cast<std::size_t>(mode)];
  const std::complex<double> lambda = es.eigenvalues()[i];
  LinearModeStart L;
  L.omega = std::abs(lambda);
  L.xi = -2.0 * lambda.real();
  L.damping_ratio = L.xi / (2.0 * L.omega);
  Eigen::VectorXcd psi = es.eigenvectors().col(i).head(n);
  psi /= std::sqrt(std::real(psi.dot(M.cast<std::complex<double>>() * psi)));
  Eigen::Index imax = 0;
  psi.cwiseAbs().maxCoeff(&imax);
  psi *= std::conj(psi[imax]) / std::abs(psi[imax]);
  L.shape = psi;
  return L;
}

// The linear mode `mode` of the linearisation at rest (q = 0) of hb's system. The structural
// loss, frequency-independent, enters as the viscous K_loss / omega at the mode's frequency
// without it (exact for a loss proportional to the mode's stiffness).
LinearModeStart linear_start(const ElementHarmonicBalance& hb, int mode) {
  const ElementSystem& sys = hb.system();
  const int n = sys.dofs(), s = hb.basis().size();
  const int c1 = HarmonicBasis::cos_index(1), s1 = HarmonicBasis::sin_index(1);
  Eigen::MatrixXd J;
  // At omega = 1 the fundamental's cos-cos block is K_lin - M, its cos-sin block C_lin + K_loss.
  hb.residual(Eigen::VectorXd::Zero(hb.size()), 1.0, &J);
  const Eigen::MatrixXd K = fundamental_block(J, n, s, c1, c1) + sys.M;
  Eigen::MatrixXd C = fundamental_block(J, n, s, c1, s1);
  if (sys.K_loss.size() == 0) return complex_mode(sys.M, C, K, mode);
  C -= sys.K_loss;
  const double omega = complex_mode(sys.M, C, K, mode).omega;
  return complex_mode(sys.M, C + sys.K_loss / omega, K, mode);
}

ElementSystem without_excitation(ElementSystem system) {
  if (system.excitation.size() > 0 && system.excitation.cwiseAbs().maxCoeff() > 0.0)
    throw InputError(
        {}, "excitation", "no excitation (a nonlinear mode is a free motion)",
        fmt::format("{} non-zero coefficients", (system.excitation.array() != 0.0).count()));
  return system;
}

HarmonicBasis with_fundamental(HarmonicBasis basis) {
  if (basis.harmonics() < 1)
    throw InputError({}, "harmonics", "H >= 1 (a nonlinear mode oscillates)",
                     fmt::format("{}", basis.harmonics()));
  return basis;
}

}  // namespace

ExtendedPeriodicMotion::ExtendedPeriodicMotion(ElementSystem system, HarmonicBasis basis, int mode)
    : hb_(without_excitation(std::move(system)), with_fundamental(std::move(basis))) {
  linear_ = linear_start(hb_, mode);
  psi_scale_ = linear_.shape.cwiseAbs().maxCoeff();
  M_real_ = hb_.system().M * linear_.shape.real();
  M_imag_ = hb_.system().M * linear_.shape.imag();
  // ~||K_lin psi||: the force per unit modal amplitude.
  kappa_ = linear_.omega * linear_.omega * std::hypot(M_real_.norm(), M_imag_.norm());
  G1_ = velocity_mass(hb_.system().M, hb_.basis());
}

Eigen::VectorXd ExtendedPeriodicMotion::linear_guess() const {
  const int n = hb_.system().dofs(), s = hb_.basis().size(), N = hb_.size();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(size());
  // q = Re(psi e^{i theta}) = Re psi cos theta - Im psi sin theta.
  for (int d = 0; d < n; ++d) {
    z[d * s + HarmonicBasis::cos_index(1)] = linear_.shape[d].real() / psi_scale_;
    z[d * s + HarmonicBasis::sin_index(1)] = -linear_.shape[d].imag() / psi_scale_;
  }
  z[N] = 1.0;
  z[N + 1] = linear_.xi / linear_.omega;
  return z;
}

Eigen::VectorXd ExtendedPeriodicMotion::harmonics(const Eigen::VectorXd& z, double p) const {
  return std::pow(10.0, p) * psi_scale_ * z.head(hb_.size());
}

double ExtendedPeriodicMotion::omega(const Eigen::VectorXd& z) const {
  return linear_.omega * z[hb_.size()];
}

double ExtendedPeriodicMotion::xi(const Eigen::VectorXd& z) const {
  return linear_.omega * z[hb_.size() + 1];
}

Eigen::VectorXd ExtendedPeriodicMotion::residual(const Eigen::VectorXd& z, double p,
                                                 Eigen::MatrixXd* J, Eigen::VectorXd* dR_dp) const {
  const int N = hb_.size(), s = hb_.basis().size(), n = hb_.system().dofs();
  const int c1 = HarmonicBasis::cos_index(1), s1 = HarmonicBasis::sin_index(1);
  if (z.size() != size())
    throw InputError({}, "unknowns", fmt::format("{} values", size()), fmt::format("{}", z.size()));
  const double a = std::pow(10.0, p), w0 = linear_.omega;
  const Eigen::VectorXd Psi = psi_scale_ * z.head(N);
  const double w = omega(z), x = xi(z);
  const bool linearize = J != nullptr || dR_dp != nullptr;
  Eigen::MatrixXd JX;
  Eigen::VectorXd dRw;
  const Eigen::VectorXd Rhb =
      hb_.residual(a * Psi, w, linearize ? &JX : nullptr, J != nullptr ? &dRw : nullptr) / a;
  const Eigen::VectorXd g = G1_ * Psi;  // harmonics of -M q' / omega per unit xi, scaled
  const Eigen::MatrixXd& M = hb_.system().M;
  const Strided Pc = coefficient_of_dofs(Psi, n, s, c1), Ps = coefficient_of_dofs(Psi, n, s, s1);

  Eigen::VectorXd R(size());
  R.head(N) = Rhb + x * w * g;
  R[N] = kappa_ * (Pc.dot(M * Pc) + Ps.dot(M * Ps) - 1.0);
  R[N + 1] = kappa_ * (M_real_.dot(Ps) + M_imag_.dot(Pc));
  if (dR_dp != nullptr) {
    // d/dp of F(a Psi) / a at fixed Psi is ln 10 (J_F Psi - F / a); the linear terms cancel.
    dR_dp->setZero(size());
    dR_dp->head(N) = std::log(10.0) * (JX * Psi - Rhb);
  }
  if (J != nullptr) {
    J->setZero(size(), size());
    J->topLeftCorner(N, N) = psi_scale_ * (JX + x * w * G1_);
    J->col(N).head(N) = w0 * (dRw / a + x * g);
    J->col(N + 1).head(N) = w0 * w * g;
    const Eigen::VectorXd MPc = M * Pc, MPs = M * Ps;
    for (int d = 0; d < n; ++d) {
      (*J)(N, d * s + c1) = kappa_ * psi_scale_ * 2.0 * MPc[d];
      (*J)(N, d * s + s1) = kappa_ * psi_scale_ * 2.0 * MPs[d];
      (*J)(N + 1, d * s + c1) = kappa_ * psi_scale_ * M_imag_[d];
      (*J)(N + 1, d * s + s1) = kappa_ * psi_scale_ * M_real_[d];
    }
  }
  return R;
}

double ExtendedPeriodicMotion::residual_scale(const Eigen::VectorXd& z, double p) const {
  const double a = std::pow(10.0, p);
  return std::max(kappa_, hb_.residual_scale(harmonics(z, p), omega(z)) / a);
}

namespace {

NonlinearModePoint make_point(const ExtendedPeriodicMotion& epmc, const ContinuationPoint& cp) {
  const ElementHarmonicBalance& hb = epmc.harmonic_balance();
  const HarmonicBasis& basis = hb.basis();
  const Eigen::MatrixXd& M = hb.system().M;
  const int n = hb.system().dofs(), s = basis.size();
  NonlinearModePoint p;
  p.amplitude = std::pow(10.0, cp.omega);
  p.omega = epmc.omega(cp.X);
  p.xi = epmc.xi(cp.X);
  p.damping_ratio = p.xi / (2.0 * p.omega);
  p.X = epmc.harmonics(cp.X, cp.omega);
  double kinetic = 0.0;  // sum h^2 (X_ch^T M X_ch + X_sh^T M X_sh)
  for (int h = 1; h <= basis.harmonics(); ++h) {
    const Strided Xc = coefficient_of_dofs(p.X, n, s, HarmonicBasis::cos_index(h));
    const Strided Xs = coefficient_of_dofs(p.X, n, s, HarmonicBasis::sin_index(h));
    kinetic += h * h * (Xc.dot(M * Xc) + Xs.dot(M * Xs));
  }
  p.energy_per_cycle = p.xi * units::kPi * p.omega * kinetic;
  const auto& elements = hb.system().elements;
  p.element_energy.resize(static_cast<Eigen::Index>(elements.size()));
  for (std::size_t e = 0; e < elements.size(); ++e)
    p.element_energy[static_cast<Eigen::Index>(e)] =
        elements[e]
            .element->loop(basis, hb.element_coordinates(p.X, static_cast<int>(e)), p.omega)
            .energy_per_cycle;
  p.iterations = cp.iterations;
  p.residual = cp.residual;
  return p;
}

void validate(const NonlinearModeOptions& o) {
  const bool positive = o.amplitude_start > 0.0 && o.amplitude_end > 0.0 &&
                        std::isfinite(o.amplitude_start) && std::isfinite(o.amplitude_end);
  if (!positive || o.amplitude_start == o.amplitude_end)
    throw InputError({}, "amplitude_start, amplitude_end",
                     "two different finite modal amplitudes > 0",
                     fmt::format("{} and {}", o.amplitude_start, o.amplitude_end));
  if (!(o.tolerance > 0.0) || o.max_iterations < 1 || o.max_points < 1)
    throw InputError({}, "tolerance, max_iterations, max_points", "> 0, >= 1 and >= 1",
                     fmt::format("{}, {} and {}", o.tolerance, o.max_iterations, o.max_points));
}

}  // namespace

NonlinearModeResult nonlinear_mode(const ElementSystem& system, const HarmonicBasis& basis,
                                   const NonlinearModeOptions& options) {
  validate(options);
  const ExtendedPeriodicMotion epmc(system, basis, options.mode);
  ContinuationOptions co;
  co.omega_start = std::log10(options.amplitude_start);
  co.omega_end = std::log10(options.amplitude_end);
  co.x_scale = 1.0;      // z is of order one by construction
  co.omega_scale = 1.0;  // one decade of amplitude
  co.step = options.step;
  co.min_step = options.min_step;
  co.max_step = options.max_step;
  co.max_points = options.max_points;
  co.tolerance = options.tolerance;
  co.max_iterations = options.max_iterations;
  const ContinuationResult c = continue_in_frequency(epmc, epmc.linear_guess(), co);

  NonlinearModeResult r;
  r.linear = epmc.linear_mode();
  r.status = c.status;
  r.points.reserve(c.points.size());
  for (const ContinuationPoint& cp : c.points) r.points.push_back(make_point(epmc, cp));
  if (c.status != Status::Ok) {
    const std::string last =
        r.points.empty()
            ? std::string("no point converged")
            : fmt::format("the last converged point is a = {:.6g}, omega = {:.6g} rad/s",
                          r.points.back().amplitude, r.points.back().omega);
    r.message = fmt::format(
        "nonlinear mode {} ended before the modal amplitude {:.6g}: {} (continuation in "
        "log10 a, the 'frequency' of the note): {}",
        options.mode, options.amplitude_end, last, c.message);
  }
  return r;
}

}  // namespace geardyn::hbm
