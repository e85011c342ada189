#include "geardyn/gear/slice_compliance.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace geardyn::gear {

SliceCompliance::SliceCompliance(const ToothCompliance& teeth, double coupling_length_m)
    : HertzianContactCompliance(teeth),
      coupling_length_(coupling_length_m),
      path_(teeth.geometry().path_of_contact_m),
      table_(1025) {
  const std::size_t n = table_.size() - 1;
  for (std::size_t i = 0; i <= n; ++i)
    table_[i] = teeth.at(path_ * static_cast<double>(i) / static_cast<double>(n)).body();
}

double SliceCompliance::body(double s) const {
  const double x = std::clamp(s / path_, 0.0, 1.0) * static_cast<double>(table_.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), table_.size() - 2);
  const double f = x - static_cast<double>(i);
  return (1.0 - f) * table_[i] + f * table_[i + 1];
}

Eigen::MatrixXd SliceCompliance::body_influence(const std::vector<double>& s,
                                                const std::vector<double>& y, double dy) const {
  const auto m = static_cast<Eigen::Index>(s.size());
  const GearPairGeometry& g = teeth_->geometry();
  if (coupling_length_ <= 0.0) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
    for (Eigen::Index i = 0; i < m; ++i) a(i, i) = body(s[static_cast<std::size_t>(i)]);
    return a;
  }
  // Every slice of the tooth over the face: slice k at y_k = (k + 1/2) dy, its contact line
  // position s_k = s_0 - (y_k - y_0) tan(beta_b) (the candidates of one pair lie on one line).
  const int n = std::max(1, static_cast<int>(std::lround(g.face_width_m / dy)));
  const double lag = std::tan(g.base_helix_angle_rad);
  const double s0 = s.front(), y0 = y.front();
  Eigen::VectorXd kw(n);
  for (int k = 0; k < n; ++k) {
    const double yk = (k + 0.5) * dy;
    kw(k) = 1.0 / body(s0 - (yk - y0) * lag);
  }
  const double kc = coupling_length_ * coupling_length_ * kw.mean();
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    k(i, i) += kw(i) * dy;
    if (i + 1 < n) {
      const double c = kc / dy;
      k(i, i) += c;
      k(i + 1, i + 1) += c;
      k(i, i + 1) -= c;
      k(i + 1, i) -= c;
    }
  }
  // Columns of K^{-1} at the candidates, times dy (a line load w over a slice is a force w dy).
  std::vector<int> slot(static_cast<std::size_t>(m));
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, m);
  for (Eigen::Index i = 0; i < m; ++i) {
    const int k_i =
        std::clamp(static_cast<int>(std::floor(y[static_cast<std::size_t>(i)] / dy)), 0, n - 1);
    slot[static_cast<std::size_t>(i)] = k_i;
    rhs(k_i, i) = dy;
  }
  const Eigen::MatrixXd cols = Eigen::LLT<Eigen::MatrixXd>(k).solve(rhs);
  Eigen::MatrixXd a(m, m);
  for (Eigen::Index i = 0; i < m; ++i) a.row(i) = cols.row(slot[static_cast<std::size_t>(i)]);
  return a;
}

double HertzianContactCompliance::hertz_approach(double s, double w) const {
  return teeth_->hertz_approach(s, w);
}
double HertzianContactCompliance::hertz_compliance(double s, double w) const {
  return teeth_->hertz_compliance(s, w);
}
double HertzianContactCompliance::max_pressure(double s, double w) const {
  return w > 0.0 ? teeth_->hertz_max_pressure(s, w) : 0.0;
}

}  // namespace geardyn::gear
