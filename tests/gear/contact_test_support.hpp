#pragma once
// Simple compliance laws for the loaded tooth contact solver's tests, whose answers are known in
// closed form.
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "geardyn/gear/tooth_contact.hpp"

namespace geardyn::test {

/// Winkler slices: compliance c per unit face width [m^2/N] at every path position, no
/// coupling between slices; Hertz approach h(w) = alpha w^q (alpha = 0: none).
class WinklerCompliance final : public gear::ContactCompliance {
 public:
  explicit WinklerCompliance(double c, double alpha = 0.0, double q = 0.9)
      : c_(c), alpha_(alpha), q_(q) {}
  Eigen::MatrixXd body_influence(const std::vector<double>& s, const std::vector<double>&,
                                 double) const override {
    const auto n = static_cast<Eigen::Index>(s.size());
    return c_ * Eigen::MatrixXd::Identity(n, n);
  }
  double hertz_approach(double, double w) const override { return alpha_ * std::pow(w, q_); }
  double hertz_compliance(double, double w) const override {
    return alpha_ * q_ * std::pow(w, q_ - 1.0);
  }
  double max_pressure(double, double w) const override { return w; }

 private:
  double c_, alpha_, q_;
};

}  // namespace geardyn::test
