#pragma once
// A preloaded bolted joint as a force element (docs/theory.md §16.3): the joint diagram of
// VDI 2230 Part 1 (2015) along the bolt axis, with clamped-part separation and a slack bolt, an
// activation time with an optional preload ramp (the tightening sequence), linear axial damping
// and linear shear stiffness and damping (the joint sticks: no slip in this element).
//
// Coordinates (u = end j - end i, in the joint's frame): u(0) = u_a, the axial opening of the
// joint, positive when the flanges separate along the bolt axis, measured from the assembled
// (preloaded) geometry; with `shear` also u(1), u(2), the two shear displacements across the
// axis. With a load introduction factor n = 1 u_a is the separation of the bolt head and nut
// bearing faces; with n < 1 it is the separation of the two load introduction planes inside the
// clamped parts (VDI 2230 Part 1 (2015), the load introduction factor).
#include <Eigen/Core>
#include <limits>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/elements/force_element.hpp"

namespace geardyn::elements {

struct BoltedJointParams {
  std::string name;                ///< for messages: "bolt '<name>'"
  double bolt_stiffness = 0.0;     ///< k_S = 1 / delta_S, bolt [N/m] (> 0)
  double clamp_stiffness = 0.0;    ///< k_P = 1 / delta_P, clamped parts [N/m] (> 0)
  double preload = 0.0;            ///< F_V, assembly preload [N] (>= 0)
  double load_introduction = 1.0;  ///< n, load introduction factor, 0 < n <= 1
  double axial_damping = 0.0;      ///< c_a [N s/m] (>= 0), on u_a while active
  bool shear = false;              ///< two shear coordinates u(1), u(2) (size 3) or none (size 1)
  double shear_stiffness = 0.0;    ///< k_q [N/m] (>= 0; > 0 when shear), sticking joint
  double shear_damping = 0.0;      ///< c_q [N s/m] (>= 0)
  /// t_a [s]: before it the bolt is not there; -inf (default) = active from the start.
  double activation_time = -std::numeric_limits<double>::infinity();
  double preload_ramp = 0.0;        ///< duration [s] of a linear preload ramp from t_a (>= 0)
  double inactive_stiffness = 0.0;  ///< k_0 [N/m] on every coordinate before t_a (>= 0)
};

/// Where a bolt's axial law is at one state.
enum class BoltState {
  inactive,  ///< before the activation time: the bolt is not there
  closed,    ///< bolt in tension and clamped parts in contact (the joint diagram's working range)
  open,      ///< clamped parts separated: the bolt alone carries the load
  slack,     ///< compressed so far that the bolt force would be negative: the clamped parts alone
};

/// The bolt and clamp forces of a state (for sensors and tables).
struct BoltForces {
  double bolt_force = 0.0;   ///< F_S, bolt tension [N] (>= 0)
  double clamp_force = 0.0;  ///< F_K, compression of the clamped parts' interface [N] (>= 0)
  double preload = 0.0;      ///< the preload in effect at this time [N] (ramped)
  BoltState state = BoltState::inactive;
};

class BoltedJoint final : public ForceElement {
 public:
  /// Checks the parameters: a bad one throws InputError at `where` with the key path
  /// `key_path + "." + <parameter name>` (e.g. "bolts[3].preload").
  BoltedJoint(BoltedJointParams params, const std::string& key_path,
              const SourceLocation& where = {});

  Eigen::Index size() const override { return p_.shear ? 3 : 1; }
  void evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double t,
                ElementForce& out) const override;
  std::string describe() const override { return "bolt '" + p_.name + "'"; }
  /// Two switches: the clamp force F_K (> 0: clamped parts in contact) and the bolt branch
  /// tension (> 0: the bolt is not slack), both with the preload in effect at t.
  int num_switches() const override { return 2; }
  void switches(const Eigen::VectorXd& u, double t, double* g) const override;
  std::string describe_switch(int k) const override;

  /// Bolt force, clamp force and state at axial opening `u_a` [m] and time `t` [s].
  BoltForces forces(double u_a, double t) const;
  /// Preload in effect at time t: 0 before t_a, F_V (t - t_a) / t_r during the ramp, F_V after.
  double preload_at(double t) const;
  /// True from the activation time on.
  bool active(double t) const { return t >= p_.activation_time; }

  /// Load factor Phi_n = n k_S / (k_S + k_P) of VDI 2230.
  double load_factor() const;
  /// Axial load F_A at which the clamped parts separate, F_V / (1 - Phi_n), at full preload.
  double opening_load() const;
  /// Stiffness of the bolt branch (bolt in series with the clamped parts outside the load
  /// introduction planes), k_1 = 1 / (delta_S + (1 - n) delta_P); k_S when n = 1.
  double bolt_branch_stiffness() const { return k1_; }
  /// Stiffness of the clamped parts between the load introduction planes, k_2 = 1 / (n delta_P).
  double clamp_branch_stiffness() const { return k2_; }

  const BoltedJointParams& params() const { return p_; }

 private:
  BoltedJointParams p_;
  double k1_ = 0.0, k2_ = 0.0;
};

}  // namespace geardyn::elements
