// GCC's -Wnull-dereference false positive inside Eigen's and <complex>'s inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <complex>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <cmath>

#include "geardyn/core/error.hpp"
#include "geardyn/hbm/jenkins.hpp"

namespace geardyn::hbm {

JenkinsResponse jenkins_response(const JenkinsElement& e, const HarmonicBasis& basis,
                                 const Eigen::Ref<const Eigen::VectorXd>& u_coefficients) {
  if (!(e.stiffness > 0.0) || !std::isfinite(e.stiffness))
    throw InputError({}, "stiffness", "a finite tangential stiffness > 0 N/m",
                     fmt::format("{}", e.stiffness));
  if (!(e.slip_force >= 0.0) || !std::isfinite(e.slip_force))
    throw InputError({}, "slip_force", "a finite slip force mu N >= 0 N",
                     fmt::format("{}", e.slip_force));
  const int n = basis.time_samples();
  const int m = basis.size();
  const Eigen::VectorXd u = basis.to_time(u_coefficients);
  const Eigen::MatrixXd& Q = basis.sampling();  // d u_j / d coefficients = Q.row(j)
  const double k = e.stiffness, F = e.slip_force;

  // State: force T and its gradient g = dT / d coefficients.
  double T = k * (u[0] - u_coefficients[0]);
  // d a_0 / d coefficients = e_0.
  Eigen::RowVectorXd g = k * (Q.row(0) - Eigen::RowVectorXd::Unit(m, 0));
  auto clip = [&](double& force, Eigen::RowVectorXd& gradient) {
    if (std::abs(force) >= F) {
      force = F * (force >= 0.0 ? 1.0 : -1.0);
      gradient.setZero();
      return false;
    }
    return true;
  };
  clip(T, g);

  JenkinsResponse r;
  r.force.resize(n);
  Eigen::MatrixXd G(n, m);  // per sample of the second period: dT_j / d coefficients
  int stuck = 0;
  // Steps s = 1 .. 2n - 1 from sample 0 of the first period; the second period (s >= n) is kept.
  for (int s = 1; s < 2 * n; ++s) {
    const int j = s % n, previous = (s - 1) % n;
    T += k * (u[j] - u[previous]);
    g += k * (Q.row(j) - Q.row(previous));
    const bool stick = clip(T, g);
    if (s >= n) {
      r.force[j] = T;
      G.row(j) = g;
      stuck += stick ? 1 : 0;
    }
  }
  r.coefficients = basis.to_frequency(r.force);
  r.jacobian = basis.projection() * G;
  r.stick_fraction = static_cast<double>(stuck) / n;
  // Closed-loop integral of T du by the trapezoidal rule over the periodic samples.
  double w = 0.0;
  for (int j = 0; j < n; ++j) {
    const int next = (j + 1) % n;
    w += 0.5 * (r.force[j] + r.force[next]) * (u[next] - u[j]);
  }
  r.energy_per_cycle = w;
  return r;
}

}  // namespace geardyn::hbm
