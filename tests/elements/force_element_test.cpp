// The force-element interface's tangent check (elements/force_element.hpp) on an element whose
// tangents are known exactly: a 2-coordinate cubic spring with linear viscous coupling.
#include "geardyn/elements/force_element.hpp"

#include <gtest/gtest.h>

namespace {

using namespace geardyn::elements;

// f = K u + a u.^3 + C v: stiffness K + diag(3 a u^2), damping C.
class CubicSpring final : public ForceElement {
 public:
  explicit CubicSpring(bool wrong_tangent = false) : wrong_(wrong_tangent) {}
  Eigen::Index size() const override { return 2; }
  void evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double,
                ElementForce& out) const override {
    Eigen::Matrix2d k, c;
    k << 2e6, -5e5, -5e5, 1e6;
    c << 30.0, 5.0, 5.0, 10.0;
    const double a = 4e12;
    out.reset(2);
    out.force = k * u + c * v + a * u.array().cube().matrix();
    out.stiffness = k;
    out.stiffness.diagonal() += (3.0 * a * u.array().square()).matrix();
    if (wrong_) out.stiffness(0, 1) *= 1.01;
    out.damping = c;
  }
  std::string describe() const override { return "cubic spring"; }

 private:
  bool wrong_;
};

// Central differences of a cubic are exact up to h^2 a u (the third derivative term): with
// h = 1e-7 m on u ~ 1e-3 m the truncation is ~1e-14 relative and round-off ~1e-9; 1e-7 bounds
// both. A 1 % error in one entry must show (relative to the largest entry, 2e6 + 3 a u^2).
TEST(ForceElement, TangentCheckAcceptsExactAndFlagsWrongTangents) {
  Eigen::VectorXd u(2), v(2);
  u << 1e-3, -2e-3;
  v << 0.1, -0.3;
  const TangentCheck ok = check_tangents(CubicSpring(), u, v, 0.0, 1e-7, 1e-4);
  EXPECT_LT(ok.stiffness_error, 1e-7);
  EXPECT_LT(ok.damping_error, 1e-7);
  const TangentCheck bad = check_tangents(CubicSpring(true), u, v, 0.0, 1e-7, 1e-4);
  EXPECT_GT(bad.stiffness_error, 1e-4);
  EXPECT_LT(bad.damping_error, 1e-7);
}

}  // namespace
