#pragma once
// A SecondOrderSystem from constant matrices and a force function, for integrator tests:
//   M a + C v + K q = f(t)   (+ optionally a low-rank damping U diag(c) U^T v).
#include <functional>

#include "geardyn/transient/second_order_system.hpp"

namespace geardyn::transient::testing {

class MatrixSystem : public SecondOrderSystem {
 public:
  using Force = std::function<Eigen::VectorXd(double)>;
  MatrixSystem(Eigen::MatrixXd M, Eigen::MatrixXd C, Eigen::MatrixXd K, Force f = {})
      : M_(M.sparseView()), C_(C.sparseView()), K_(K.sparseView()), f_(std::move(f)) {}

  void set_low_rank_damping(Eigen::MatrixXd U, Eigen::VectorXd c) {
    U_ = std::move(U);
    c_ = std::move(c);
  }

  int size() const override { return static_cast<int>(M_.rows()); }
  void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                const Eigen::VectorXd& a, Eigen::VectorXd& r) override {
    ++residual_calls;
    r = M_ * a + C_ * v + K_ * q;
    if (U_.cols() > 0) r += U_ * c_.cwiseProduct(U_.transpose() * v);
    if (f_) r -= f_(t);
  }
  void tangent(double, const Eigen::VectorXd&, const Eigen::VectorXd&, double c_m, double c_c,
               double c_k, SparseMatrix& S) override {
    ++tangent_calls;
    S = tangent_scale * (c_m * M_ + c_c * C_ + c_k * K_);
  }
  bool tangent_low_rank(double, const Eigen::VectorXd&, const Eigen::VectorXd&, double, double c_c,
                        double, Eigen::MatrixXd& U, Eigen::VectorXd& d) override {
    if (U_.cols() == 0) return false;
    U = U_;
    d = c_c * c_;
    return true;
  }
  bool is_linear_time_invariant() const override { return lti; }

  double energy(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
    return 0.5 * v.dot(M_ * v) + 0.5 * q.dot(K_ * q);
  }

  bool lti = true;
  double tangent_scale = 1.0;  ///< != 1 gives a deliberately wrong tangent (modified Newton test)
  int residual_calls = 0;
  int tangent_calls = 0;

 private:
  SparseMatrix M_, C_, K_;
  Force f_;
  Eigen::MatrixXd U_;
  Eigen::VectorXd c_;
};

}  // namespace geardyn::transient::testing
