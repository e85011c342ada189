// GCC's -Wnull-dereference false positive inside Eigen's and <complex>'s inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <complex>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/hbm/jenkins.hpp"
#include "geardyn/hbm/nonlinear_element.hpp"

namespace geardyn::hbm {

namespace {

// sum_j P.col(j) over the samples j of [first, last) of the steady period.
Eigen::VectorXd projected_interval(const Eigen::MatrixXd& P, int first, int last) {
  return P.middleCols(first, last - first).rowwise().sum();
}

// The AFT Jacobian P G from the stick intervals of the steady period. In stick after the last
// clipped (slip) sample a, the incremental gradient telescopes to dT_j/dc = k (Q_j - Q_a); with
// no clipped sample before j in the whole march it is k (Q_j - e_0) (the start T = k (u_0 - a_0));
// in slip it is 0. So P G = k (P diag(stick) Q - sum over the stick runs of the same anchor a of
// (sum_{j in run} P_j) Q_a), P diag(stick) Q by projected_diagonal.
Eigen::MatrixXd stick_jacobian(const HarmonicBasis& basis, double k, const Eigen::VectorXd& stick,
                               const std::vector<int>& anchor) {
  const Eigen::MatrixXd& Q = basis.sampling();
  const Eigen::MatrixXd& P = basis.projection();
  const int n = basis.time_samples(), m = basis.size();
  Eigen::MatrixXd J = projected_diagonal(basis, stick);
  Eigen::RowVectorXd row(m);
  for (int j = 0; j < n;) {
    if (stick[j] == 0.0) {
      ++j;
      continue;
    }
    int last = j + 1;
    while (last < n && stick[last] != 0.0 &&
           anchor[static_cast<std::size_t>(last)] == anchor[static_cast<std::size_t>(j)])
      ++last;
    const int a = anchor[static_cast<std::size_t>(j)];
    if (a < 0)
      row = Eigen::RowVectorXd::Unit(m, 0);
    else
      row = Q.row(a);
    J.noalias() -= projected_interval(P, j, last) * row;
    j = last;
  }
  return k * J;
}

}  // namespace

JenkinsResponse jenkins_response(const JenkinsElement& e, const HarmonicBasis& basis,
                                 const Eigen::Ref<const Eigen::VectorXd>& u_coefficients,
                                 bool with_jacobian) {
  if (!(e.stiffness > 0.0) || !std::isfinite(e.stiffness))
    throw InputError({}, "stiffness", "a finite tangential stiffness > 0 N/m",
                     fmt::format("{}", e.stiffness));
  if (!(e.slip_force >= 0.0) || !std::isfinite(e.slip_force))
    throw InputError({}, "slip_force", "a finite slip force mu N >= 0 N",
                     fmt::format("{}", e.slip_force));
  const int n = basis.time_samples();
  const Eigen::VectorXd u = basis.to_time(u_coefficients);
  const double k = e.stiffness, F = e.slip_force;

  // The force march; `anchor` is the last clipped sample (-1: none yet), whose gradient the
  // stick samples after it inherit (stick_jacobian).
  double T = k * (u[0] - u_coefficients[0]);
  int anchor = -1;
  auto clip = [&](double& force, int sample) {
    if (std::abs(force) >= F) {
      force = F * (force >= 0.0 ? 1.0 : -1.0);
      anchor = sample;
      return false;
    }
    return true;
  };
  clip(T, 0);

  JenkinsResponse r;
  r.force.resize(n);
  Eigen::VectorXd stick(n);
  std::vector<int> anchors(static_cast<std::size_t>(n), -1);
  // Steps s = 1 .. 2n - 1 from sample 0 of the first period; the second period (s >= n) is kept.
  for (int s = 1; s < 2 * n; ++s) {
    const int j = s % n, previous = (s - 1) % n;
    T += k * (u[j] - u[previous]);
    const bool stuck = clip(T, j);
    if (s >= n) {
      r.force[j] = T;
      stick[j] = stuck ? 1.0 : 0.0;
      anchors[static_cast<std::size_t>(j)] = anchor;
    }
  }
  r.coefficients = basis.to_frequency(r.force);
  if (with_jacobian) r.jacobian = stick_jacobian(basis, k, stick, anchors);
  r.stick_fraction = stick.sum() / n;
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
