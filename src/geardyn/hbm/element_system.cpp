#include "geardyn/hbm/element_system.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geardyn/core/error.hpp"

namespace geardyn::hbm {

void PlacedNonlinearElement::validate(int n_dof) const {
  if (!element) throw InputError({}, name, "an element", "none");
  if (B.rows() != element->size() || B.cols() != n_dof)
    throw InputError(
        {}, name,
        fmt::format("a placement of {} x {} (coordinates x DOFs)", element->size(), n_dof),
        fmt::format("{} x {}", B.rows(), B.cols()));
  if (!B.allFinite()) throw InputError({}, name, "a finite placement", "a non-finite entry");
}

void ElementSystem::validate() const {
  const Eigen::Index n = K.rows();
  auto square = [n](const Eigen::MatrixXd& A, const char* what, bool optional) {
    if (optional && A.size() == 0) return;
    if (A.rows() != n || A.cols() != n)
      throw InputError({}, what, fmt::format("a {} x {} matrix", n, n),
                       fmt::format("{} x {}", A.rows(), A.cols()));
    if (!A.allFinite()) throw InputError({}, what, "finite entries", "a non-finite entry");
  };
  if (n == 0 || K.cols() != n)
    throw InputError({}, "stiffness", "a square matrix of at least one DOF",
                     fmt::format("{} x {}", K.rows(), K.cols()));
  square(M, "mass", false);
  square(C, "damping", false);
  square(K, "stiffness", false);
  square(K_loss, "structural_loss", true);
  for (const auto& e : elements) e.validate(static_cast<int>(n));
  if (excitation.size() > 0) {
    if (excitation_harmonics < 0 || excitation.size() != n * (2 * excitation_harmonics + 1))
      throw InputError({}, "excitation",
                       fmt::format("{} coefficients (n_dof (2 H_f + 1), H_f = {})",
                                   n * (2 * excitation_harmonics + 1), excitation_harmonics),
                       fmt::format("{}", excitation.size()));
    if (!excitation.allFinite())
      throw InputError({}, "excitation", "finite coefficients", "a non-finite entry");
  }
}

Eigen::VectorXd ElementSystem::excitation_at(double theta) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs());
  if (excitation.size() == 0) return f;
  const int s = 2 * excitation_harmonics + 1;
  for (int d = 0; d < dofs(); ++d) {
    const auto c = excitation.segment(d * s, s);
    double v = c[0];
    for (int h = 1; h <= excitation_harmonics; ++h)
      v += c[HarmonicBasis::cos_index(h)] * std::cos(h * theta) +
           c[HarmonicBasis::sin_index(h)] * std::sin(h * theta);
    f[d] = v;
  }
  return f;
}

namespace {

// The excitation's coefficients in the layout of `basis` (harmonics above H dropped).
Eigen::VectorXd excitation_in(const ElementSystem& system, const HarmonicBasis& basis) {
  const int s = basis.size(), n = system.dofs();
  Eigen::VectorXd F = Eigen::VectorXd::Zero(n * s);
  if (system.excitation.size() == 0) return F;
  const int sf = 2 * system.excitation_harmonics + 1;
  const int keep = std::min(s, sf);
  for (int d = 0; d < n; ++d) F.segment(d * s, keep) = system.excitation.segment(d * sf, keep);
  return F;
}

// The DOFs on which B has a non-zero column.
std::vector<int> support(const Eigen::MatrixXd& B) {
  std::vector<int> d;
  for (Eigen::Index j = 0; j < B.cols(); ++j)
    if (B.col(j).cwiseAbs().maxCoeff() > 0.0) d.push_back(static_cast<int>(j));
  return d;
}

// J += B^T Je B in the DOF-major layout, on the DOFs `dofs` of B's support: block (d, g) gets
// sum_{k, l} B(k, d) B(l, g) Je(k, l) (blocks of s x s).
void add_placed(const PlacedNonlinearElement& placed, const std::vector<int>& dofs,
                const Eigen::MatrixXd& Je, int s, Eigen::MatrixXd& J) {
  const int ne = placed.element->size();
  for (int d : dofs)
    for (int g : dofs) {
      Eigen::MatrixXd block = Eigen::MatrixXd::Zero(s, s);
      for (int k = 0; k < ne; ++k)
        for (int l = 0; l < ne; ++l) {
          const double bb = placed.B(k, d) * placed.B(l, g);
          if (bb != 0.0) block += bb * Je.block(k * s, l * s, s, s);
        }
      J.block(d * s, g * s, s, s) += block;
    }
}

}  // namespace

ElementHarmonicBalance::ElementHarmonicBalance(ElementSystem system, HarmonicBasis basis)
    : system_(std::move(system)), basis_(std::move(basis)) {
  system_.validate();
  F_ext_ = excitation_in(system_, basis_);
}

Eigen::VectorXd ElementHarmonicBalance::element_coordinates(const Eigen::VectorXd& X, int e) const {
  const int s = basis_.size(), n = system_.dofs();
  const Eigen::MatrixXd& B = system_.elements[static_cast<std::size_t>(e)].B;
  // Xt(d, c) = X[d s + c]: W = B Xt, w[k s + c] = W(k, c).
  const Eigen::Map<const Eigen::MatrixXd> Xs(X.data(), s, n);
  const Eigen::MatrixXd W = B * Xs.transpose();
  Eigen::VectorXd w(W.size());
  Eigen::Map<Eigen::MatrixXd>(w.data(), s, W.rows()) = W.transpose();
  return w;
}

Eigen::VectorXd ElementHarmonicBalance::residual(const Eigen::VectorXd& X, double omega,
                                                 Eigen::MatrixXd* J,
                                                 Eigen::VectorXd* dR_domega) const {
  const int s = basis_.size(), n = system_.dofs(), H = basis_.harmonics();
  if (X.size() != size())
    throw InputError({}, "unknowns", fmt::format("{} coefficients", size()),
                     fmt::format("{}", X.size()));
  const Eigen::MatrixXd& M = system_.M;
  const Eigen::MatrixXd& C = system_.C;
  const Eigen::MatrixXd& K = system_.K;
  const bool loss = system_.K_loss.size() > 0;
  const Eigen::Map<const Eigen::MatrixXd> Xs(X.data(), s, n);
  const Eigen::MatrixXd Xt = Xs.transpose();  // n x s
  Eigen::MatrixXd Rt = K * Xt;
  Eigen::MatrixXd dRt;
  if (dR_domega != nullptr) dRt.setZero(n, s);
  for (int h = 1; h <= H; ++h) {
    const int ci = HarmonicBasis::cos_index(h), si = HarmonicBasis::sin_index(h);
    const double hw = h * omega;
    const Eigen::VectorXd Ma = M * Xt.col(ci), Mb = M * Xt.col(si);
    Eigen::VectorXd Bb = hw * (C * Xt.col(si)), Ba = hw * (C * Xt.col(ci));
    if (dR_domega != nullptr) {
      dRt.col(ci) = -2.0 * h * hw * Ma + Bb / omega;
      dRt.col(si) = -2.0 * h * hw * Mb - Ba / omega;
    }
    if (loss) {
      Bb += system_.K_loss * Xt.col(si);
      Ba += system_.K_loss * Xt.col(ci);
    }
    Rt.col(ci) += -hw * hw * Ma + Bb;
    Rt.col(si) += -hw * hw * Mb - Ba;
  }
  Eigen::VectorXd R(size());
  Eigen::Map<Eigen::MatrixXd>(R.data(), s, n) = Rt.transpose();
  R -= load_factor_ * F_ext_;
  if (dR_domega != nullptr) {
    dR_domega->resize(size());
    Eigen::Map<Eigen::MatrixXd>(dR_domega->data(), s, n) = dRt.transpose();
  }
  if (J != nullptr) {
    J->setZero(size(), size());
    for (int d = 0; d < n; ++d)
      for (int e = 0; e < n; ++e) {
        const double k = K(d, e), m = M(d, e), c = C(d, e);
        const double l = loss ? system_.K_loss(d, e) : 0.0;
        if (k == 0.0 && m == 0.0 && c == 0.0 && l == 0.0) continue;
        (*J)(d * s, e * s) = k;
        for (int h = 1; h <= H; ++h) {
          const int ci = HarmonicBasis::cos_index(h), si = HarmonicBasis::sin_index(h);
          const double hw = h * omega;
          const double a = k - hw * hw * m, b = hw * c + l;
          (*J)(d * s + ci, e * s + ci) = a;
          (*J)(d * s + ci, e * s + si) = b;
          (*J)(d * s + si, e * s + ci) = -b;
          (*J)(d * s + si, e * s + si) = a;
        }
      }
  }
  // The nonlinear elements.
  for (std::size_t e = 0; e < system_.elements.size(); ++e) {
    const auto& placed = system_.elements[e];
    const int ne = placed.element->size();
    const Eigen::VectorXd w = element_coordinates(X, static_cast<int>(e));
    Eigen::VectorXd f = Eigen::VectorXd::Zero(ne * s);
    Eigen::MatrixXd Je;
    Eigen::VectorXd dfw;
    if (J != nullptr) Je.setZero(ne * s, ne * s);
    if (dR_domega != nullptr) dfw.setZero(ne * s);
    placed.element->harmonic_force(basis_, w, omega, f, J != nullptr ? &Je : nullptr,
                                   dR_domega != nullptr ? &dfw : nullptr);
    const std::vector<int> dofs = support(placed.B);
    // R[d s + c] += sum_k B(k, d) f[k s + c]; likewise dR/domega.
    for (int d : dofs)
      for (int k = 0; k < ne; ++k) {
        const double b = placed.B(k, d);
        if (b == 0.0) continue;
        R.segment(d * s, s) += b * f.segment(k * s, s);
        if (dR_domega != nullptr) dR_domega->segment(d * s, s) += b * dfw.segment(k * s, s);
      }
    if (J != nullptr) add_placed(placed, dofs, Je, s, *J);
  }
  return R;
}

Eigen::MatrixXd ElementHarmonicBalance::velocity_jacobian(const Eigen::VectorXd& X,
                                                          double omega) const {
  const int s = basis_.size();
  if (X.size() != size())
    throw InputError({}, "unknowns", fmt::format("{} coefficients", size()),
                     fmt::format("{}", X.size()));
  Eigen::MatrixXd Jv = Eigen::MatrixXd::Zero(size(), size());
  for (std::size_t e = 0; e < system_.elements.size(); ++e) {
    const auto& placed = system_.elements[e];
    const int ne = placed.element->size();
    Eigen::MatrixXd Je = Eigen::MatrixXd::Zero(ne * s, ne * s);
    placed.element->harmonic_velocity_jacobian(basis_, element_coordinates(X, static_cast<int>(e)),
                                               omega, Je);
    if (!Je.isZero(0.0)) add_placed(placed, support(placed.B), Je, s, Jv);
  }
  return Jv;
}

double ElementHarmonicBalance::residual_scale(const Eigen::VectorXd& X, double omega) const {
  const int s = basis_.size(), n = system_.dofs();
  const Eigen::Map<const Eigen::MatrixXd> Xs(X.data(), s, n);
  const Eigen::MatrixXd Xt = Xs.transpose();
  const double stiffness_force = (system_.K * Xt).norm();
  // A structure held by its elements alone (K = 0: a gear pair held by its mesh) is judged
  // against its inertia forces (n w)^2 M X_n, which the elements' forces balance; no AFT here,
  // this runs at every Newton check.
  double inertia = 0.0;
  for (int h = 1; h <= basis_.harmonics(); ++h) {
    const double hw2 = (h * omega) * (h * omega);
    inertia += hw2 * hw2 *
               ((system_.M * Xt.col(HarmonicBasis::cos_index(h))).squaredNorm() +
                (system_.M * Xt.col(HarmonicBasis::sin_index(h))).squaredNorm());
  }
  const double inertia_force = std::sqrt(inertia);
  return std::max({std::abs(load_factor_) * F_ext_.norm(), stiffness_force, inertia_force,
                   std::numeric_limits<double>::min()});
}

Eigen::VectorXd ElementHarmonicBalance::linear_response(double omega) const {
  ElementSystem linear = system_;
  linear.elements.clear();
  const ElementHarmonicBalance hb(std::move(linear), basis_);
  Eigen::MatrixXd J;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(size());
  hb.residual(zero, omega, &J);  // J = D(omega): the system is linear
  return J.partialPivLu().solve(load_factor_ * F_ext_);
}

}  // namespace geardyn::hbm
