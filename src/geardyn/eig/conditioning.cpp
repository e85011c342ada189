#include "geardyn/eig/conditioning.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace geardyn::eig {

std::string scaling_diagnosis_of_diagonals(const Eigen::VectorXd& k, const Eigen::VectorXd& m) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  double k_lo = std::numeric_limits<double>::infinity(), k_hi = 0.0;
  for (Eigen::Index i = 0; i < k.size(); ++i) {
    if (k[i] > 0.0) {
      k_lo = std::min(k_lo, k[i]);
      k_hi = std::max(k_hi, k[i]);
    }
    if (!(k[i] > 0.0) || !(m[i] > 0.0)) continue;
    const double r = k[i] / m[i];
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  constexpr double kSpread = 1e14;  // ~1e7 in frequency: beyond any physical model
  if (hi > 0.0 && !std::isfinite(hi))
    return "the mass of some DOFs is vanishingly small against their stiffness (K_ii / M_ii "
           "overflows double precision): look for a density or mass far below physical values";
  if (hi > 0.0 && hi / lo > kSpread)
    return fmt::format(
        "the model's stiffness and mass values differ by {:.1e} across its DOFs (K_ii / M_ii "
        "from {:.3g} to {:.3g} 1/s^2), more than double precision can resolve: look for a "
        "stiffness far above the rest (a 'rigid' spring: use a constraint or a coupling with a "
        "physical value instead) or a density or mass far below it",
        hi / lo, lo, hi);
  if (k_hi > 0.0 && k_hi / k_lo > 1e16)
    return fmt::format(
        "the model's stiffness values span {:.1e} (diagonal from {:.3g} to {:.3g}), more than "
        "double precision can resolve: look for a stiffness far above the rest (a 'rigid' "
        "spring: use a constraint instead)",
        k_hi / k_lo, k_lo, k_hi);
  return "";
}

}  // namespace geardyn::eig
