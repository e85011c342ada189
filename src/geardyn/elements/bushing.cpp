#include "geardyn/elements/bushing.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>

#include "geardyn/elements/parameter_check.hpp"

namespace geardyn::elements {

namespace {

using detail::format_number;

// Fritsch & Carlson, "Monotone piecewise cubic interpolation", SIAM J. Numer. Anal. 17 (1980)
// 238-246: node slopes from the averaged secants (0 at a local extremum or a flat segment),
// then scaled per interval onto the circle alpha^2 + beta^2 <= 9, which is sufficient for a
// monotone cubic. Scaling only shrinks slopes, so an interval already treated stays monotone.
std::vector<double> fritsch_carlson_slopes(const std::vector<double>& x,
                                           const std::vector<double>& f) {
  const std::size_t m = x.size();
  std::vector<double> secant(m - 1), d(m);
  for (std::size_t k = 0; k + 1 < m; ++k) secant[k] = (f[k + 1] - f[k]) / (x[k + 1] - x[k]);
  d[0] = secant[0];
  d[m - 1] = secant[m - 2];
  for (std::size_t k = 1; k + 1 < m; ++k)
    d[k] = secant[k - 1] * secant[k] > 0.0 ? 0.5 * (secant[k - 1] + secant[k]) : 0.0;
  for (std::size_t k = 0; k + 1 < m; ++k) {
    if (secant[k] == 0.0) {
      d[k] = d[k + 1] = 0.0;
      continue;
    }
    const double a = d[k] / secant[k], b = d[k + 1] / secant[k];
    const double r2 = a * a + b * b;
    if (r2 > 9.0) {
      const double tau = 3.0 / std::sqrt(r2);
      d[k] = tau * a * secant[k];
      d[k + 1] = tau * b * secant[k];
    }
  }
  return d;
}

void check_matrix(const Eigen::Matrix<double, 6, 6>& m, const Eigen::Matrix<double, 6, 6>& tangent,
                  const SourceLocation& where, const std::string& key, const std::string& what) {
  if (!m.allFinite())
    throw InputError(where, key, "a finite 6 x 6 " + what + " matrix", "a non-finite entry");
  const double scale = m.cwiseAbs().maxCoeff();
  const double asym = (m - m.transpose()).cwiseAbs().maxCoeff();
  if (asym > 1e-12 * scale)
    throw InputError(
        where, key, "a symmetric 6 x 6 " + what + " matrix",
        "|M - M^T| up to " + format_number(asym) + " (largest entry " + format_number(scale) + ")");
  if (scale == 0.0) return;
  const double lowest =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(tangent, Eigen::EigenvaluesOnly)
          .eigenvalues()
          .minCoeff();
  if (lowest < -1e-12 * scale)
    throw InputError(where, key, "a positive semi-definite " + what + " matrix",
                     "an eigenvalue " + format_number(lowest),
                     "a negative " + what + " creates energy");
}

}  // namespace

ForceDeflectionTable::ForceDeflectionTable(std::vector<double> deflection,
                                           std::vector<double> force, Interpolation interpolation,
                                           const std::string& key_path, const SourceLocation& where)
    : x_(std::move(deflection)), f_(std::move(force)), kind_(interpolation) {
  const std::string kx = key_path + ".deflection", kf = key_path + ".force";
  if (x_.size() < 2)
    throw InputError(where, kx, "at least 2 points", std::to_string(x_.size()) + " points");
  if (f_.size() != x_.size())
    throw InputError(where, kf, "as many forces as deflections (" + std::to_string(x_.size()) + ")",
                     std::to_string(f_.size()));
  for (std::size_t k = 0; k < x_.size(); ++k) {
    if (!std::isfinite(x_[k]))
      throw InputError(where, kx, "finite deflections", format_number(x_[k]));
    if (!std::isfinite(f_[k])) throw InputError(where, kf, "finite forces", format_number(f_[k]));
    if (k > 0 && !(x_[k] > x_[k - 1]))
      throw InputError(where, kx, "strictly increasing deflections",
                       format_number(x_[k - 1]) + " then " + format_number(x_[k]));
    if (k > 0 && f_[k] < f_[k - 1])
      throw InputError(where, kf, "a force non-decreasing with the deflection (stiffness >= 0)",
                       format_number(f_[k - 1]) + " then " + format_number(f_[k]));
  }
  const auto zero = std::find(x_.begin(), x_.end(), 0.0);
  if (zero == x_.end() || f_[static_cast<std::size_t>(std::distance(x_.begin(), zero))] != 0.0)
    throw InputError(where, kx, "a point at deflection 0 with force 0", "none",
                     "shift the table and give the force at zero deflection as the preload");
  d_ = fritsch_carlson_slopes(x_, f_);
}

double ForceDeflectionTable::value(double x, double* slope) const {
  const std::size_t m = x_.size();
  auto set_slope = [slope](double s) {
    if (slope) *slope = s;
  };
  const bool hermite = kind_ == Interpolation::cubic_hermite;
  if (x < x_[0]) {
    const double s = hermite ? d_[0] : (f_[1] - f_[0]) / (x_[1] - x_[0]);
    set_slope(s);
    return f_[0] + s * (x - x_[0]);
  }
  if (x >= x_[m - 1]) {
    const double s = hermite ? d_[m - 1] : (f_[m - 1] - f_[m - 2]) / (x_[m - 1] - x_[m - 2]);
    set_slope(s);
    return f_[m - 1] + s * (x - x_[m - 1]);
  }
  // Interval k with x_k <= x < x_{k+1}.
  const std::size_t k = static_cast<std::size_t>(
                            std::distance(x_.begin(), std::upper_bound(x_.begin(), x_.end(), x))) -
                        1;
  const double h = x_[k + 1] - x_[k];
  if (!hermite) {
    const double s = (f_[k + 1] - f_[k]) / h;
    set_slope(s);
    return f_[k] + s * (x - x_[k]);
  }
  const double t = (x - x_[k]) / h, t2 = t * t, t3 = t2 * t;
  const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2,
               h11 = t3 - t2;
  const double g00 = 6 * t2 - 6 * t, g10 = 3 * t2 - 4 * t + 1, g01 = -6 * t2 + 6 * t,
               g11 = 3 * t2 - 2 * t;
  set_slope((g00 * f_[k] + g01 * f_[k + 1]) / h + g10 * d_[k] + g11 * d_[k + 1]);
  return h00 * f_[k] + h * h10 * d_[k] + h01 * f_[k + 1] + h * h11 * d_[k + 1];
}

const std::array<const char*, 6>& Bushing::direction_names() {
  static const std::array<const char*, 6> names = {"x", "y", "z", "rx", "ry", "rz"};
  return names;
}

Bushing::Bushing(BushingParams params, const std::string& key_path, const SourceLocation& where)
    : p_(std::move(params)) {
  linear_ = p_.stiffness;
  Eigen::Matrix<double, 6, 6> tangent0 = p_.stiffness;  // the tangent at u = 0
  for (int i = 0; i < 6; ++i) {
    const auto& table = p_.tables[static_cast<std::size_t>(i)];
    if (!table) continue;
    double slope = 0.0;
    table->value(0.0, &slope);
    linear_(i, i) = 0.0;
    tangent0(i, i) = slope;
  }
  check_matrix(p_.stiffness, tangent0, where, key_path + ".stiffness", "stiffness");
  check_matrix(p_.damping, p_.damping, where, key_path + ".damping", "damping");
  for (int i = 0; i < 6; ++i)
    if (!std::isfinite(p_.preload(i)))
      throw InputError(where, key_path + ".preload", "a finite preload",
                       std::string(direction_names()[static_cast<std::size_t>(i)]) + " = " +
                           format_number(p_.preload(i)));
}

void Bushing::evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double,
                       ElementForce& out) const {
  out.reset(6);
  out.force = p_.preload + linear_ * u + p_.damping * v;
  out.stiffness = linear_;
  out.damping = p_.damping;
  for (int i = 0; i < 6; ++i) {
    const auto& table = p_.tables[static_cast<std::size_t>(i)];
    if (!table) continue;
    double slope = 0.0;
    out.force(i) += table->value(u(i), &slope);
    out.stiffness(i, i) += slope;
  }
}

}  // namespace geardyn::elements
