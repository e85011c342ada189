#pragma once
// A six-coordinate bushing (docs/theory.md §16.4), the analogue of the ADAMS BUSHING with
// GFORCE-style nonlinear directions: linear 6 x 6 stiffness K and damping C (symmetric), a
// preload, and per direction an optional force-deflection table that replaces the linear
// diagonal stiffness of that direction.
//
// Coordinates (u = end j - end i in the bushing's frame): u(0..2) translations x, y, z [m],
// u(3..5) small rotations rx, ry, rz [rad]; forces [N] and moments [N m] on them.
//
//   f = f_0 + K' u + g(u) + C v,   K_t = K' + diag(g'(u_i)),   C_t = C,
//
// where K' is K with the diagonal entry of every tabulated direction removed, g_i the table of
// direction i (0 for a linear direction) and f_0 the preload, the internal force at u = 0
// (positive like K u: the bushing pulls end j back towards end i).
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/elements/force_element.hpp"

namespace geardyn::elements {

/// A monotone force-deflection curve through given points.
class ForceDeflectionTable {
 public:
  enum class Interpolation {
    cubic_hermite,  ///< monotone piecewise cubic Hermite (Fritsch & Carlson 1980), C1
    linear,         ///< piecewise linear: C0, the tangent jumps at the nodes (kinks)
  };
  /// deflection strictly increasing, force non-decreasing, at least 2 points, a node at (0, 0).
  /// A violation throws InputError at `where` with key path `key_path + ".deflection"` or
  /// `".force"`.
  ForceDeflectionTable(std::vector<double> deflection, std::vector<double> force,
                       Interpolation interpolation, const std::string& key_path,
                       const SourceLocation& where = {});

  /// Force at deflection x and its derivative dF/dx. Outside the table: linear extrapolation
  /// with the end slope. At a node of the linear table the slope is the right-hand one.
  double value(double x, double* slope = nullptr) const;

  const std::vector<double>& deflection() const { return x_; }
  const std::vector<double>& force() const { return f_; }
  Interpolation interpolation() const { return kind_; }

 private:
  std::vector<double> x_, f_, d_;  // nodes and the Hermite node slopes
  Interpolation kind_;
};

struct BushingParams {
  std::string name;  ///< for messages: "bushing '<name>'"
  Eigen::Matrix<double, 6, 6> stiffness = Eigen::Matrix<double, 6, 6>::Zero();  ///< K
  Eigen::Matrix<double, 6, 6> damping = Eigen::Matrix<double, 6, 6>::Zero();    ///< C
  Eigen::Matrix<double, 6, 1> preload = Eigen::Matrix<double, 6, 1>::Zero();    ///< f_0
  /// Per direction (x, y, z, rx, ry, rz) an optional table replacing K(i, i).
  std::array<std::optional<ForceDeflectionTable>, 6> tables;
};

class Bushing final : public ForceElement {
 public:
  /// Checks the parameters (K and C finite, symmetric, positive semi-definite; preload
  /// finite): a bad one throws InputError at `where` with key path `key_path + ".stiffness"`,
  /// `".damping"` or `".preload"`.
  Bushing(BushingParams params, const std::string& key_path, const SourceLocation& where = {});

  Eigen::Index size() const override { return 6; }
  void evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double t,
                ElementForce& out) const override;
  std::string describe() const override { return "bushing '" + p_.name + "'"; }

  const BushingParams& params() const { return p_; }

  /// Direction names in coordinate order: x, y, z, rx, ry, rz.
  static const std::array<const char*, 6>& direction_names();

 private:
  BushingParams p_;
  Eigen::Matrix<double, 6, 6> linear_;  // K without the diagonal of tabulated directions
};

}  // namespace geardyn::elements
