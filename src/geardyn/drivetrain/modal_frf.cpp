#include "geardyn/drivetrain/modal_frf.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::drivetrain {
namespace {

using Complex = std::complex<double>;

/// Roots with |Im lambda| below this fraction of |lambda| are real (overdamped): no conjugate.
constexpr double kRealRoot = 1e-12;

Complex dot(const EquationCombination& c, const Eigen::VectorXcd& x) {
  Complex s = 0.0;
  for (std::size_t k = 0; k < c.equations.size(); ++k) s += c.coefficients[k] * x[c.equations[k]];
  return s;
}

/// The combination over the free equations (held ones dropped).
Eigen::VectorXd on_free(const Linearisation& lin, const EquationCombination& c, int n) {
  std::vector<int> position(static_cast<std::size_t>(n), -1);
  for (std::size_t i = 0; i < lin.free.size(); ++i)
    position[static_cast<std::size_t>(lin.free[i])] = static_cast<int>(i);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(lin.free.size()));
  for (std::size_t k = 0; k < c.equations.size(); ++k) {
    const int p = position[static_cast<std::size_t>(c.equations[k])];
    if (p >= 0) v[p] += c.coefficients[k];
  }
  return v;
}

int system_size(const Linearisation& lin) {
  int n = lin.equations;
  for (int e : lin.free) n = std::max(n, e + 1);
  return n;
}

void static_check(const Linearisation& lin, const EquationCombination& load,
                  const std::vector<EquationCombination>& outputs, ModalFrf& out) {
  if (lin.rigid_body_modes > 0 || lin.free.empty() || outputs.empty()) return;
  linalg::SparseLU<double> lu;
  if (lu.compute(lin.K) != Status::Ok) return;
  const int n = system_size(lin);
  const Eigen::VectorXd xf = lu.solve(on_free(lin, load, n));
  Eigen::VectorXcd x = Eigen::VectorXcd::Zero(n);
  for (std::size_t i = 0; i < lin.free.size(); ++i)
    x[lin.free[i]] = xf[static_cast<Eigen::Index>(i)];
  const auto n_out = static_cast<Eigen::Index>(outputs.size());
  out.static_exact.resize(n_out);
  for (Eigen::Index j = 0; j < n_out; ++j)
    out.static_exact[j] = dot(outputs[static_cast<std::size_t>(j)], x).real();
  const double ref = out.static_exact.cwiseAbs().maxCoeff();
  if (!(ref > 0.0) || !std::isfinite(ref)) return;
  out.static_checked = true;
  out.static_truncation =
      (out.static_modal - out.static_exact.cast<Complex>()).cwiseAbs().maxCoeff() / ref;
}

}  // namespace

ModalFrf modal_frf(const Linearisation& lin, const EquationCombination& load,
                   const std::vector<EquationCombination>& outputs,
                   const std::vector<double>& frequency_hz, int n_modes, bool static_correction) {
  ModalFrf out;
  out.frequency_hz = frequency_hz;
  const auto n_out = static_cast<Eigen::Index>(outputs.size());
  const auto n_f = static_cast<Eigen::Index>(frequency_hz.size());
  out.receptance.setZero(n_f, n_out);
  out.static_modal.setZero(n_out);
  if (lin.modes.empty()) {
    out.status = Status::Failed;
    out.message = fmt::format("modal FRF: the linearisation has no modes ({})", lin.message);
    return out;
  }
  if (!lin.has_left) {
    out.status = Status::Failed;
    out.message = fmt::format(
        "modal FRF: {} of the {} linearised modes have no left eigenvector (the transposed "
        "pencil's solve did not return their eigenvalues)",
        lin.unmatched_left, lin.modes.size());
    return out;
  }
  const std::size_t kept = n_modes > 0
                               ? std::min(lin.modes.size(), static_cast<std::size_t>(n_modes))
                               : lin.modes.size();
  // Per mode: the participation (y_k^T f) and the outputs' components c_j^T x_k.
  for (std::size_t k = 0; k < kept; ++k) {
    const LinearMode& m = lin.modes[k];
    const Complex l = m.eigenvalue;
    const Complex participation = dot(load, m.left);
    const bool real_root = std::abs(l.imag()) <= kRealRoot * std::abs(l);
    for (Eigen::Index j = 0; j < n_out; ++j) {
      const Complex a = dot(outputs[static_cast<std::size_t>(j)], m.shape) * participation;
      auto term = [&](Complex s) {
        Complex h = a / (s - l);
        if (!real_root) h += std::conj(a) / (s - std::conj(l));
        return h;
      };
      for (Eigen::Index i = 0; i < n_f; ++i)
        out.receptance(i, j) +=
            term(Complex(0.0, 2.0 * M_PI * frequency_hz[static_cast<std::size_t>(i)]));
      out.static_modal[j] += term(0.0);
    }
    ++out.modes_used;
    out.highest_mode_hz = std::max(out.highest_mode_hz, m.natural_frequency_hz);
  }
  static_check(lin, load, outputs, out);
  if (static_correction && out.static_checked) {
    const Eigen::RowVectorXcd residual =
        (out.static_exact.cast<Complex>() - out.static_modal).transpose();
    out.receptance.rowwise() += residual;
    out.static_corrected = true;
  }
  return out;
}

Eigen::MatrixXcd direct_frf(const Linearisation& lin, const EquationCombination& load,
                            const std::vector<EquationCombination>& outputs,
                            const std::vector<double>& frequency_hz) {
  const auto n_out = static_cast<Eigen::Index>(outputs.size());
  const auto n_f = static_cast<Eigen::Index>(frequency_hz.size());
  Eigen::MatrixXcd H(n_f, n_out);
  const int n = system_size(lin);
  const Eigen::VectorXcd f = on_free(lin, load, n).cast<Complex>();
  const Eigen::SparseMatrix<Complex> K = lin.K.cast<Complex>(), M = lin.M.cast<Complex>(),
                                     C = lin.C.cast<Complex>();
  const Eigen::MatrixXcd U = lin.low_rank_basis.cast<Complex>();
  const bool low_rank = lin.low_rank_coefficients.size() > 0;
  for (Eigen::Index i = 0; i < n_f; ++i) {
    const double w = 2.0 * M_PI * frequency_hz[static_cast<std::size_t>(i)];
    const Complex s(0.0, w);
    Eigen::SparseMatrix<Complex> A = K + (s * s) * M + s * C;
    linalg::SparseLU<Complex> lu;
    if (lu.compute(A) != Status::Ok) {
      H.row(i).setConstant(Complex(std::numeric_limits<double>::quiet_NaN(), 0.0));
      continue;
    }
    Eigen::VectorXcd xf = lu.solve(f);
    if (low_rank) {
      // (A + U W U^T)^-1 f = z0 - Z a,  (I + W U^T Z) a = W U^T z0,  W = s diag(c).
      const Eigen::MatrixXcd Z = lu.solve(Eigen::MatrixXcd(U));
      const Eigen::VectorXcd Wd = s * lin.low_rank_coefficients.cast<Complex>();
      Eigen::MatrixXcd S = Wd.asDiagonal() * (U.transpose() * Z);
      S.diagonal().array() += 1.0;
      const Eigen::VectorXcd a = S.partialPivLu().solve(Wd.asDiagonal() * (U.transpose() * xf));
      xf -= Z * a;
    }
    Eigen::VectorXcd x = Eigen::VectorXcd::Zero(n);
    for (std::size_t k = 0; k < lin.free.size(); ++k)
      x[lin.free[k]] = xf[static_cast<Eigen::Index>(k)];
    for (Eigen::Index j = 0; j < n_out; ++j) H(i, j) = dot(outputs[static_cast<std::size_t>(j)], x);
  }
  return H;
}

}  // namespace geardyn::drivetrain
