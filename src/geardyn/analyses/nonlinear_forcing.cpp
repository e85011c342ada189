// GCC's -Wnull-dereference false positive inside Eigen's inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of Eigen.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geardyn/analyses/nonlinear_forcing.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/fe/dof_map.hpp"

namespace geardyn::analyses {
namespace {

constexpr double kRpmPerRadS = 60.0 / units::kTwoPi;

// Coefficients F (n_eq x columns, HarmonicBasis layout per equation) on the coordinates
// (basis^T F) in the unknowns' layout of a balance with s coefficients per coordinate; columns
// beyond s are dropped, as the fixed excitation's are (a balance of H = 0 has no fundamental).
Eigen::VectorXd in_unknowns(const Eigen::MatrixXd& F, const Eigen::MatrixXd& basis, int s) {
  const Eigen::MatrixXd Fq = basis.transpose() * F;
  const auto keep = std::min<Eigen::Index>(Fq.cols(), s);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(Fq.rows() * s);
  for (Eigen::Index d = 0; d < Fq.rows(); ++d) out.segment(d * s, keep) = Fq.row(d).head(keep);
  return out;
}

// Adds the complex amplitude F (f = Re(F e^{i n w t})) on harmonic n of the columns of `to`.
void add_harmonic(const Eigen::VectorXcd& F, int n, Eigen::MatrixXd& to) {
  to.col(hbm::HarmonicBasis::cos_index(n)) += F.real();
  to.col(hbm::HarmonicBasis::sin_index(n)) -= F.imag();
}

std::string ratios_text(const std::vector<double>& orders) {
  std::string s;
  for (double o : orders) s += (s.empty() ? "" : ", ") + fmt::format("{:g}", o);
  return s;
}

void add_unbalance(const model::Model& model, const fe::LinearSystem& system,
                   const NonlinearResponseSettings& s, int harmonics, const Context& context,
                   NonlinearForcing& f) {
  if (s.unbalances.empty()) return;
  for (const auto& name : s.unbalances)
    if (std::none_of(model.unbalances.begin(), model.unbalances.end(),
                     [&](const model::Unbalance& u) { return u.name == name; }))
      throw context.error("unbalances", "the name of an unbalance", "'" + name + "'");
  const std::vector<double> orders = fe::unbalance_orders(model, system, s.unbalances);
  if (orders.empty())
    throw context.error("unbalances", "unbalance on a spinning node",
                        "only nodes with speed ratio 0",
                        "set spin_of for the node, or put the unbalance on a shaft node");
  if (s.parameter == ContinuationParameter::Speed) {
    for (double rho : orders) {
      const double k = rho / s.order;
      const long n = std::lround(k);
      if (std::abs(k - static_cast<double>(n)) > 1e-9 * k || n < 1 || n > harmonics)
        throw context.error(
            "order",
            fmt::format("an order r with rho / r a harmonic 1 .. {} for the unbalance on a "
                        "node of speed ratio rho = {:g}",
                        harmonics, rho),
            fmt::format("{:g}", s.order), "order = rho puts the unbalance on the fundamental");
      // Per W^2: fe::unbalance_load at W = 1.
      add_harmonic(fe::unbalance_load(model, system, 1.0, rho, s.unbalances), static_cast<int>(n),
                   f.per_speed2);
    }
    return;
  }
  if (orders.size() > 1)
    throw context.error("unbalances",
                        "unbalances on nodes of one |speed ratio| (a force at the fundamental)",
                        "ratios " + ratios_text(orders),
                        "use parameter = \"speed\", where each ratio acts on its harmonic");
  if (!(s.speed > 0.0))
    throw context.error("speed_rpm",
                        "a reference speed > 0: the unbalance force m e (rho W)^2 is taken at it",
                        fmt::format("{:g} rpm", s.speed * kRpmPerRadS));
  add_harmonic(fe::unbalance_load(model, system, s.speed, orders[0], s.unbalances), 1, f.fixed);
}

const char* direction_name(BaseMotion b) {
  switch (b) {
    case BaseMotion::X:
      return "x";
    case BaseMotion::Y:
      return "y";
    case BaseMotion::Z:
      return "z";
    case BaseMotion::Rx:
      return "rx";
    case BaseMotion::Ry:
      return "ry";
    case BaseMotion::Rz:
      return "rz";
    case BaseMotion::None:
      break;
  }
  return "none";
}

// The rigid-body influence vector of a base motion: the whole model's first six candidates of
// fe::rigid_body_candidates are, per global axis a, the translation along a then the rotation
// about a through the centroid of the nodes.
Eigen::VectorXd influence_vector(const fe::LinearSystem& system, BaseMotion b) {
  const int index = static_cast<int>(b) - static_cast<int>(BaseMotion::X);  // 0 .. 5
  const bool rotation = index >= 3;
  const int axis = index % 3;
  const Eigen::MatrixXd rigid = fe::rigid_body_candidates(system.dofs);
  return rigid.col(2 * axis + (rotation ? 1 : 0));
}

void add_base_motion(const fe::LinearSystem& system, const NonlinearResponseSettings& s,
                     const Context& context, NonlinearForcing& f) {
  if (s.base_motion == BaseMotion::None) return;
  const Eigen::VectorXd r = influence_vector(system, s.base_motion);
  if (r.size() == 0 || r.cwiseAbs().maxCoeff() == 0.0)
    throw context.error("base_motion", "a direction along which the model has free DOFs",
                        fmt::format("\"{}\"", direction_name(s.base_motion)),
                        "the model's `dofs` leave out every DOF of that direction");
  const Eigen::VectorXd Mr = system.M * r;
  if (std::isfinite(s.base_acceleration)) {
    f.fixed.col(1) -= s.base_acceleration * Mr;  // f_eff = -M r a_g
  } else if (s.parameter == ContinuationParameter::ForceLevel) {
    f.fixed.col(1) += s.frequency * s.frequency * s.base_displacement * Mr;  // a_g = -w^2 D
  } else {
    f.per_fundamental2.col(1) += s.base_displacement * Mr;
  }
}

}  // namespace

NonlinearForcing nonlinear_forcing(const model::Model& model, const fe::LinearSystem& system,
                                   const NonlinearResponseSettings& settings, int harmonics,
                                   const Context& context) {
  const int n = system.size();
  NonlinearForcing f;
  f.fixed = Eigen::MatrixXd::Zero(n, 3);
  f.per_fundamental2 = Eigen::MatrixXd::Zero(n, 3);
  f.per_speed2 = Eigen::MatrixXd::Zero(n, 2 * harmonics + 1);
  add_unbalance(model, system, settings, harmonics, context, f);
  add_base_motion(system, settings, context, f);
  return f;
}

ForcedBalance::ForcedBalance(const fe::LinearSystem& system,
                             const NonlinearCoordinates& coordinates,
                             const hbm::ElementHarmonicBalance& reference,
                             const NonlinearForcing& forcing,
                             const NonlinearResponseSettings& settings)
    : system_(system),
      c_(coordinates),
      reference_(reference),
      by_speed_(settings.parameter == ContinuationParameter::Speed),
      speed_(settings.speed),
      order_(settings.order) {
  const int s = reference.basis().size();
  Fd_ = in_unknowns(forcing.per_fundamental2, c_.basis, s);
  Fu_ = in_unknowns(forcing.per_speed2, c_.basis, s);
  if (c_.modal && system.has_modal_damping()) {
    const Eigen::MatrixXd BtPhi = system.modal_basis.transpose() * c_.basis;
    modal_damping_ = BtPhi.transpose() * system.modal_coefficients.asDiagonal() * BtPhi;
  }
}

hbm::ElementHarmonicBalance ForcedBalance::balance_at(double p) const {
  hbm::ElementSystem sys = reference_.system();
  const double W = speed(p), w = fundamental(p);
  if (by_speed_) {
    const Eigen::MatrixXd& Phi = c_.basis;
    if (!system_.speed_bearings.empty())
      sys.K = c_.modal ? Eigen::MatrixXd(Phi.transpose() * (system_.K_at(W) * Phi))
                       : Eigen::MatrixXd(system_.K_at(W));
    if (c_.modal) {
      const fe::SparseMatrix CW = system_.C_at(W) + W * system_.G;
      sys.C = Phi.transpose() * (CW * Phi);
      if (modal_damping_.size() > 0) sys.C += modal_damping_;
    } else {
      sys.C = system_.damping_dense(W);
    }
  }
  sys.excitation = reference_.external_force() + (w * w) * Fd_ + (W * W) * Fu_;
  sys.excitation_harmonics = reference_.basis().harmonics();
  return hbm::ElementHarmonicBalance(std::move(sys), reference_.basis());
}

Eigen::VectorXd ForcedBalance::structure_speed_derivative(const Eigen::VectorXd& X, double W,
                                                          double w) const {
  const int s = reference_.basis().size(), n = reference_.system().dofs();
  const Eigen::Map<const Eigen::MatrixXd> Xs(X.data(), s, n);
  const Eigen::MatrixXd Q = c_.basis * Xs.transpose();  // n_eq x s
  // d/dW [K(W) q + (C(W) + W G) v] on the coordinates.
  auto dforce = [&](const Eigen::VectorXd& q, const Eigen::VectorXd& v) -> Eigen::VectorXd {
    Eigen::VectorXd out = system_.G * v;
    for (const auto& b : system_.speed_bearings) b.add_speed_derivative(W, q, v, 1.0, out);
    return c_.basis.transpose() * out;
  };
  Eigen::MatrixXd dRt(n, s);
  dRt.col(0) = dforce(Q.col(0), Eigen::VectorXd::Zero(Q.rows()));
  for (int h = 1; h <= reference_.basis().harmonics(); ++h) {
    const int ci = hbm::HarmonicBasis::cos_index(h), si = hbm::HarmonicBasis::sin_index(h);
    const double hw = h * w;
    // The balance's rows: cos: K a + n w C b; sin: K b - n w C a.
    dRt.col(ci) = dforce(Q.col(ci), hw * Q.col(si));
    dRt.col(si) = dforce(Q.col(si), -hw * Q.col(ci));
  }
  Eigen::VectorXd dR(X.size());
  Eigen::Map<Eigen::MatrixXd>(dR.data(), s, n) = dRt.transpose();
  return dR;
}

Eigen::VectorXd ForcedBalance::residual(const Eigen::VectorXd& X, double p, Eigen::MatrixXd* J,
                                        Eigen::VectorXd* dR_dp) const {
  if (!moves()) return reference_.residual(X, p, J, dR_dp);
  const double W = speed(p), w = fundamental(p);
  Eigen::VectorXd dR_dw;
  const Eigen::VectorXd R = balance_at(p).residual(X, w, J, dR_dp != nullptr ? &dR_dw : nullptr);
  if (dR_dp == nullptr) return R;
  if (!by_speed_) {
    *dR_dp = dR_dw - 2.0 * w * Fd_;
    return R;
  }
  *dR_dp =
      order_ * dR_dw + structure_speed_derivative(X, W, w) - 2.0 * W * Fu_ - 2.0 * order_ * w * Fd_;
  return R;
}

double ForcedBalance::residual_scale(const Eigen::VectorXd& X, double p) const {
  if (!moves()) return reference_.residual_scale(X, p);
  return balance_at(p).residual_scale(X, fundamental(p));
}

Eigen::VectorXd ForcedBalance::linear_response(double p) const {
  if (!moves()) return reference_.linear_response(p);
  return balance_at(p).linear_response(fundamental(p));
}

}  // namespace geardyn::analyses
