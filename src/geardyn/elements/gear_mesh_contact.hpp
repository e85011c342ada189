#pragma once
// Gear tooth contact of one mesh in the time domain (docs/theory.md §16.6): the angle-varying
// mesh stiffness and unloaded transmission error of a force map (from the loaded tooth contact
// analysis, an LTCA table or an STE file: analyses/mesh_force_map.hpp), backlash with contact on
// both flanks, and a choice of contact law.
//
// Coordinates (n = 2): u = (delta, theta1).
//   * delta [m]: the approach of the teeth along the line of action, positive closing the drive
//     flank (formed by the caller from the node DOFs and the base radii);
//   * theta1 [rad]: the pinion's absolute rotation angle (any size; reduced modulo the map's
//     period). It only indexes the map: the element's force on it is zero, but the force on
//     delta depends on it, so the tangents are 2 x 2 and not symmetric (column 1 = d / d theta1).
//
// Drive flank: penetration p = delta - e_g(theta1), e_g the unloaded TE; force +F(p, p_dot,
// theta1) on delta. Back flank (only with a backlash b): p_b = -(delta - e_g(theta1)) - b, force
// -F(p_b, p_b_dot, theta1): the coast flank is assumed to follow the drive flank's unloaded TE
// shifted by the backlash (its unloaded TE is e_g - b: no tooth-thickness variation) and to have
// the drive flank's force-approach law at the same pinion angle, mirrored. The rates include the
// map's angle dependence: p_dot = delta_dot - e_g'(theta1) theta1_dot.
//
// Laws:
//   * the map's own law (no ContactLaw given): at grid angle i, the piecewise-linear force
//     through (0, 0), (a_1i, F_1), ..., (a_Mi, F_M) in the penetration, a_ji = d_ji - e_gi,
//     extrapolated with the last slope; between grid angles the force is interpolated linearly
//     at equal penetration (so contact starts exactly at p = 0), periodically; plus the mesh
//     viscous damping c p_dot in contact, with the contact laws' Tension;
//   * any ContactLaw on p (and p_b), optionally with its elastic part scaled by
//     s(theta1) = k(theta1) / mean k of the map (vary_stiffness):
//     F = F_law(p, p_dot) + (s - 1) F_law(p, 0), zero where the law clips the force to zero.
//
// Tooth friction (optional, ToothFriction::coefficient > 0; docs/theory.md §16.6): the element
// then has n = 4 coordinates u = (delta, theta1, theta2, y), theta2 the wheel's rotation in its
// working sense and y the displacement of the wheel's centre relative to the pinion's along the
// profile direction t (perpendicular to the line of action in the transverse plane, the
// direction in which the pinion's contact point moves for theta1_dot > 0). A pair in contact at
// distance s from the pitch point along the line of action (s > 0 towards the pinion's tip
// contact, the recess) has the arms rho1 = rho1_p + s and rho2 = rho2_p - s (the flanks' radii of
// curvature) and the sliding velocity v_s = rho1 theta1_dot - rho2 theta2_dot - y_dot
// (= (omega1 + omega2) s at the kinematic speeds). Its friction force mu F_k sigma(v_s) with
// sigma(v) = tanh(v / v_eps) acts against the pinion flank's sliding, so the generalised force is
// mu F_k sigma(v_s) (0, rho1, -rho2, -1) and the dissipated power mu F_k sigma(v_s) v_s.
// Pairs: the contact moves along the path of contact by r_b1 per radian of theta1; a pair enters
// at the start of the active path s_A when theta1 = phase (mod the base pitch angle
// period / mesh_cycles), and the next pair one base pitch behind; the pairs on the path
// [s_A, s_A + g_alpha] share the normal force F equally (F_k = F / n_pairs: the rigid-tooth load
// sharing of the classical tooth loss factor, Ohlendorf 1958). Only the drive flank carries
// friction (a back-flank impact is short and its friction is neglected).
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/elements/contact_law.hpp"
#include "geardyn/elements/force_element.hpp"

namespace geardyn::elements {

/// The force map of a mesh over one period of the pinion angle, as plain data.
/// Uniform angle grid theta_i = i period / N, i < N (periodic: sample N is sample 0).
struct MeshForceMap {
  double period_rad = 0.0;  ///< pinion angle period (2 pi / z1, or the hunting period) [rad]
  int mesh_cycles = 1;      ///< mesh cycles in the period (1, or the hunting period's)
  std::vector<double> unloaded_te_m;  ///< e_g(theta_i) [m] along the line of action (size N)
  std::vector<double> forces_n;       ///< F_j > 0, increasing [N] (size M >= 1)
  /// approach_m[j][i] = d_j(theta_i) [m]: the approach at which the mesh carries F_j at angle i
  /// (d_j > e_g, increasing in j).
  std::vector<std::vector<double>> approach_m;
  /// Index j of the force that defines k(theta) = F_j / (d_j - e_g) for the stiffness scaling
  /// and sensors (the pair's static force when among the F_j).
  int reference = 0;
  std::string source;  ///< where the map comes from, for describe()

  /// A linear mesh of constant stiffness k [N/m] and no unloaded TE (one angle).
  static MeshForceMap constant_stiffness(double stiffness_n_per_m, double period_rad);

  int angles() const { return static_cast<int>(unloaded_te_m.size()); }
  double angle(int i) const { return period_rad * i / angles(); }
  /// Secant stiffness F_ref / (d_ref - e_g) at grid angle i [N/m].
  double stiffness_at_node(int i) const;
  /// Arithmetic mean of stiffness_at_node over the grid [N/m].
  double mean_stiffness() const;
};

/// Checks a map; InputError at `source` (key `<key_path>.gear_pair`) naming the first problem:
/// sizes, non-finite values, forces not positive and increasing, approaches not increasing from
/// e_g (the force-approach law must be monotone).
void check_mesh_force_map(const MeshForceMap& map, const LawSource& source = {});

/// Which flank touches.
enum class MeshContactState { drive, separated, back };

/// Tooth friction of a mesh (external spur or helical pair, in the transverse plane).
struct ToothFriction {
  double coefficient = 0.0;  ///< mu (0: no friction, n = 2)
  double velocity = 1e-3;    ///< v_eps [m/s] of sigma(v) = tanh(v / v_eps)
  double base_radius1 = std::numeric_limits<double>::quiet_NaN();  ///< r_b1 [m]
  /// Arms at the pitch point rho_p = r_b tan(alpha_w) of pinion and wheel [m].
  double pitch_arm1 = std::numeric_limits<double>::quiet_NaN();
  double pitch_arm2 = std::numeric_limits<double>::quiet_NaN();
  /// Start of the active path from the pitch point s_A (<= 0) and its length g_alpha [m].
  double path_start = std::numeric_limits<double>::quiet_NaN();
  double path_length = std::numeric_limits<double>::quiet_NaN();
  double phase = 0.0;  ///< theta1 at which a pair enters at s_A [rad]
};

/// Tooth friction of an external involute pair from its base radii r_b1, r_b2, tip radii r_a1,
/// r_a2 and working centre distance a (ISO 21771:2007, sec. 5.4): cos(alpha_w) = (r_b1 + r_b2) /
/// a, rho_p = r_b tan(alpha_w), the recess (pinion tip) part g_a = sqrt(r_a1^2 - r_b1^2) - rho1_p
/// and the approach part g_f = sqrt(r_a2^2 - r_b2^2) - rho2_p: s_A = -g_f, g_alpha = g_f + g_a.
ToothFriction spur_tooth_friction(double coefficient, double velocity, double base_radius1,
                                  double base_radius2, double tip_radius1, double tip_radius2,
                                  double centre_distance);

/// One tooth pair on the path of contact at pinion angle theta1.
struct ToothPairContact {
  double s = 0.0;      ///< position from the pitch point along the line of action [m]
  double share = 0.0;  ///< its part of the normal force (1 / pairs in contact)
};

struct GearMeshContactOptions {
  /// Total backlash b along the line of action [m]; NaN: no back flank.
  double backlash = std::numeric_limits<double>::quiet_NaN();
  /// A contact law on p and p_b; null: the map's force-approach law.
  std::shared_ptr<const ContactLaw> law;
  /// With `law`: scale its elastic part by k(theta1) / mean k.
  bool vary_stiffness = true;
  /// With the map's law: mesh viscous damping c [N s/m] (in contact only) and its tension.
  double damping = 0.0;
  Tension tension = Tension::allowed;
  ToothFriction friction;  ///< coefficient 0: none
};

class GearMeshContact final : public ForceElement {
 public:
  /// Checks the map and options; InputError at `source` (keys `<key_path>.gear_pair`,
  /// `.backlash`, `.damping`).
  GearMeshContact(std::string name, std::shared_ptr<const MeshForceMap> map,
                  GearMeshContactOptions options, const LawSource& source = {});

  Eigen::Index size() const override { return has_friction() ? 4 : 2; }
  void evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double t,
                ElementForce& out) const override;
  std::string describe() const override;
  /// Switches: the drive-flank penetration p and, with backlash, the back flank's p_b (> 0: in
  /// contact).
  int num_switches() const override { return has_backlash() ? 2 : 1; }
  void switches(const Eigen::VectorXd& u, double t, double* g) const override;
  std::string describe_switch(int k) const override;

  const MeshForceMap& map() const { return *map_; }
  const GearMeshContactOptions& options() const { return options_; }
  bool has_backlash() const;
  bool has_friction() const { return options_.friction.coefficient > 0.0; }
  /// The tooth pairs on the path of contact at pinion angle theta1 (friction only; empty
  /// without friction).
  std::vector<ToothPairContact> pairs(double theta1) const;

  /// e_g(theta1) and its derivative (periodic linear interpolation) [m], [m/rad].
  double unloaded_te(double theta1) const;
  /// k(theta1) / mean k (periodic linear interpolation of the nodes' ratio).
  double stiffness_ratio(double theta1) const;
  /// Drive-flank penetration p = delta - e_g(theta1) [m] (event function: contact at p = 0).
  double penetration(const Eigen::VectorXd& u) const;
  /// Back-flank penetration p_b = -(delta - e_g(theta1)) - b [m]; -infinity without backlash.
  double back_penetration(const Eigen::VectorXd& u) const;
  MeshContactState state(const Eigen::VectorXd& u) const;
  /// The force on delta at zero rates (the elastic tooth force for sensors) [N].
  double static_force(const Eigen::VectorXd& u) const;

 private:
  struct Grid {
    int i0 = 0, i1 = 0;  ///< bracketing grid angles
    double w = 0.0;      ///< weight of i1
    double inv_h = 0.0;  ///< 1 / grid spacing [1/rad]
  };
  struct FlankForce {
    double force = 0.0, d_p = 0.0, d_rate = 0.0, d_theta = 0.0;  ///< at fixed p
  };
  Grid locate(double theta1) const;
  /// The map's elastic law at grid angle i and penetration p > 0: force and dF/dp.
  void node_law(int i, double p, double& force, double& slope) const;
  FlankForce flank(const Grid& g, double p, double p_dot) const;
  /// Adds the drive flank's tooth friction for the normal force out.force(0) (with its tangents
  /// in row 0) to rows 1..3.
  void add_friction(const Eigen::VectorXd& u, const Eigen::VectorXd& v, ElementForce& out) const;

  std::string name_;
  std::shared_ptr<const MeshForceMap> map_;
  GearMeshContactOptions options_;
  std::vector<double> ratio_;  ///< k_i / mean k
};

}  // namespace geardyn::elements
