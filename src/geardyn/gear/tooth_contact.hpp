#pragma once
// Loaded tooth contact analysis (LTCA) of a cylindrical gear pair by the slice model
// (docs/theory.md §15.3-15.5): at each of many mesh positions the potential contact lines are
// cut into slices along the face width; each slice has an unloaded gap (flank modifications of
// both gears, misalignment, pitch deviations) and the tooth pair a compliance (body influence
// matrix over its slices, plus the nonlinear Hertzian approach of each slice); the contact
// problem under the transmitted force decides which slices touch and what they carry, and the
// rigid approach of the two gears is the loaded transmission error.
//
// Kinematics (spur and helical, external and internal), as in gear/mesh_stiffness.hpp: the
// mesh cycle coordinate u in [0, 1) is the pinion rotation over one transverse base pitch p_bt,
// u = 0 the instant a new tooth pair enters contact at the leading face end (y = 0). Tooth pair j
// (entered j cycles ago) touches at face position y in [0, b] at the transverse path position
//     s_j(u, y) = (u + j) p_bt - y tan(beta_b),   a candidate when 0 <= s <= g_alpha.
// Roll lengths on the base tangents: pinion rho1(s) = rho1_A + s, wheel rho2 = T1T2 - rho1
// (external) or rho1 + T1T2 (internal); contact radius r = sqrt(r_b^2 + rho^2).
//
// Contact problem at one position (unknowns: line loads w_i >= 0 of the candidate slices
// [N/m, along the transverse line of action per unit face width] and the approach delta [m]):
//     sum_k A_ik w_k + h_i(w_i) + g_i - delta  = 0   where w_i > 0 (touching)
//                                              >= 0   where w_i = 0 (open)
//     sum_i w_i dy = F_bt = T1 / r_b1.
// A is block diagonal over tooth pairs (body compliance with coupling between the slices of
// one pair), h_i the Hertzian approach (convex, nonlinear), g_i the unloaded gap. Solved by an
// active-set method with Newton iterations on each set (Conry & Seireg's formulation for the
// linear case: T.F. Conry, A. Seireg, "A mathematical programming technique for the evaluation
// of load distribution and optimal modifications for gear systems", J. Eng. Ind. 1973).
// delta(u) is the loaded TE, min_i g_i the unloaded (geometric) TE; the secant mesh stiffness
// is F_bt / (delta - min g), the tangent stiffness dF/d delta with the contact set frozen.
#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/gear/geometry.hpp"

namespace geardyn::gear {

enum class ReliefShape { Linear, Parabolic };

/// A topological flank modification: material removed [m] on a grid of roll angle (pinion or
/// wheel roll angle xi = rho / r_b of that gear) x face position y; bilinear between the grid
/// points, constant beyond its edges.
struct TopographyMap {
  std::vector<double> roll_angle_rad;  ///< increasing, >= 2 points
  std::vector<double> face_m;          ///< increasing, >= 2 points
  Eigen::MatrixXd removed_m;           ///< rows: roll angles, columns: face positions
  bool empty() const { return roll_angle_rad.empty(); }
  double at(double roll_angle, double y) const;
};

/// Flank modifications of one gear's loaded flanks (material removed, normal to the flank along
/// the transverse line of action, ISO 21771 conventions). Face position y from the face end
/// where the pair's contact line enters (y = 0) to y = b.
struct FlankModification {
  double tip_relief_m = 0.0;  ///< C_a at the tip circle
  /// Radius where tip relief starts (NaN: no tip relief). Relief grows from 0 there to C_a at
  /// the tip, (rho - rho_Ca) / (rho_a - rho_Ca) to the power 1 (linear) or 2 (parabolic).
  double tip_relief_start_radius_m = std::numeric_limits<double>::quiet_NaN();
  ReliefShape tip_relief_shape = ReliefShape::Linear;
  double root_relief_m = 0.0;  ///< C_f at the lowest point of contact (start of active profile)
  double root_relief_start_radius_m = std::numeric_limits<double>::quiet_NaN();
  ReliefShape root_relief_shape = ReliefShape::Linear;
  /// Profile crowning C_alpha: parabolic over the active profile, 0 in its middle, C_alpha at
  /// both ends.
  double profile_crowning_m = 0.0;
  /// Lead crowning C_beta: parabolic over the face width, 0 at mid face, C_beta at both ends.
  double lead_crowning_m = 0.0;
  /// Helix slope modification f_Hbeta: removal growing linearly from -f/2 at y = 0 to +f/2 at
  /// y = b (positive: less material, less load towards y = b).
  double lead_slope_m = 0.0;
  double end_relief_m = 0.0;         ///< C_I at both face ends
  double end_relief_length_m = 0.0;  ///< length over which the end relief acts from each end
  ReliefShape end_relief_shape = ReliefShape::Linear;
  TopographyMap topography;  ///< optional, added to the rest
  /// Per-tooth position deviation along the line of action [m], index = tooth number from the
  /// tooth in contact at u = 0 of the first cycle; positive: the flank stands ahead (closer to
  /// the mating flank, contacts early). Empty: none. Size = the gear's tooth count.
  std::vector<double> pitch_deviation_m;
  /// Where the modification was read (errors point there; unset: the pair's location).
  SourceLocation where;
};

/// Compliance of the tooth pairs (the analytic slice model of tooth_compliance.hpp, or an FE
/// influence-coefficient model). Implementations are immutable and thread-safe.
class ContactCompliance {
 public:
  virtual ~ContactCompliance() = default;
  /// Body influence matrix of one tooth pair: A(i, k) = deflection along the line of action at
  /// candidate point i per line load at point k spread over the slice width dy [m^2/N]. The
  /// points are given by their path position s_i and face position y_i (slice centres).
  virtual Eigen::MatrixXd body_influence(const std::vector<double>& s, const std::vector<double>& y,
                                         double dy) const = 0;
  /// Hertzian approach [m] and its derivative [m^2/N] at s under the line load w > 0.
  virtual double hertz_approach(double s, double w) const = 0;
  virtual double hertz_compliance(double s, double w) const = 0;
  /// Peak contact pressure [Pa] at s under the line load w (0 for w <= 0).
  virtual double max_pressure(double s, double w) const = 0;
};

/// Ease-off of a bevel / hypoid pair (docs/theory.md §15.9): the relative flank modification
/// of the pair (material removed from the pinion flank relative to the conjugate of the wheel,
/// along the virtual pair's transverse line of action) over the pinion's normalised roll angle
/// xi in [-1, 1] (root to tip of the nominal active profile) and the normalised face position
/// eta = 2 y / b - 1 in [-1, 1] (toe to heel):
///     E(xi, eta) = C_a xi^2 + C_b eta^2 + B xi eta + F_a xi + F_b eta.
struct EaseOff {
  double profile_crowning_m = 0.0;  ///< C_a (at xi = +-1)
  double length_crowning_m = 0.0;   ///< C_b (at eta = +-1)
  /// B: twist of the flank; B > 0 removes material at (tip, heel) and (root, toe), so the
  /// pattern runs from the pinion's tip at the toe to its root at the heel.
  double bias_m = 0.0;
  double profile_slope_m = 0.0;  ///< F_a: flank (pressure) angle modification, + unloads the tip
  double length_slope_m = 0.0;   ///< F_b: spiral angle modification, + unloads the heel
  double at(double xi, double eta) const {
    return profile_crowning_m * xi * xi + length_crowning_m * eta * eta + bias_m * xi * eta +
           profile_slope_m * xi + length_slope_m * eta;
  }
  bool zero() const {
    return profile_crowning_m == 0.0 && length_crowning_m == 0.0 && bias_m == 0.0 &&
           profile_slope_m == 0.0 && length_slope_m == 0.0;
  }
};

/// Mounting errors of a bevel / hypoid pair (docs/theory.md §15.9; Gleason's V-H-J convention,
/// after H.J. Stadtfeld, "Handbook of Bevel and Hypoid Gears", 1993): H moves the pinion along
/// its axis, J the wheel along its axis, positive away from the crossing point of the axes
/// (out of mesh); V moves the pinion along the common perpendicular of the axes, positive in the
/// direction in which its loaded flank pushes the wheel at the mean point; a positive shaft
/// angle error increases Sigma.
struct MountingErrors {
  double h_m = 0.0, v_m = 0.0, j_m = 0.0;
  double shaft_angle_rad = 0.0;
  /// Which pinion flank carries the load (the concave one pushes the pinion out of mesh, as
  /// gear/tooth_forces.hpp derives from hand and rotation).
  bool pinion_concave_loaded = true;
  bool zero() const { return h_m == 0.0 && v_m == 0.0 && j_m == 0.0 && shaft_angle_rad == 0.0; }
};

/// First-order effect of the mounting errors on the virtual pair (docs/theory.md (15.20)-(15.23)).
struct MountingEffect {
  /// Approach of the pinion's loaded flank towards the wheel's at the mean point, d . n [m].
  double normal_approach_m = 0.0;
  /// Resulting lead slope of the gap along the transverse line of action, heel minus toe [m]:
  /// (d . n / cos beta_b) b / R_m (the cone: a rotation's lever arm grows with R).
  double lead_slope_m = 0.0;
  /// Change of the virtual centre distance (the separation at the mean point) [m].
  double centre_distance_change_m = 0.0;
  /// Gap gradient along the path of contact from the shaft angle error (spiral pairs), d g / d
  /// rho1 [m/m]: the tilt about the common perpendicular turns the flank normal's lengthwise
  /// component into a height-proportional gap.
  double profile_gradient = 0.0;
};

/// Ease-off centre (xi_c, eta_c): the minimum of E(xi, eta) + a xi + c eta (extra linear terms
/// a, c [m] from the mounting errors), i.e. the solution of [2 C_a, B; B, 2 C_b] (xi, eta) =
/// -(F_a + a, F_b + c). Needs 4 C_a C_b > B^2 (a bounded pattern); NaN otherwise.
std::pair<double, double> ease_off_centre(const EaseOff& e, double profile_linear_m = 0.0,
                                          double length_linear_m = 0.0);

/// The mounting errors' first-order effect on the bevel / hypoid pair `bevel`.
MountingEffect mounting_effect(const GearPairGeometry& bevel, const MountingErrors& errors);

/// The virtual cylindrical pair of a bevel / hypoid pair (type spur or helical, the radii of the
/// virtual gears), with its centre distance changed by `centre_distance_change_m` (working
/// pressure angle, path of contact and contact ratio recomputed). Throws InputError (key
/// contact.mounting_h) when the change leaves a contact ratio below 1 or reaches interference.
GearPairGeometry virtual_cylindrical_pair(const GearPairGeometry& bevel,
                                          double centre_distance_change_m = 0.0);

struct ToothContactOptions {
  int positions = 64;  ///< mesh positions per mesh cycle (>= 4)
  int slices = 40;     ///< slices over the face width (>= 1)
  /// Mesh misalignment in the plane of action f_ma [m]: the gap difference along the line of
  /// action between the face ends (y = b minus y = 0; positive opens the gap at y = b).
  double misalignment_in_plane_m = 0.0;
  /// Mesh cycles computed: 1, or the hunting period lcm(z1, z2) when pitch deviations are given
  /// and this is true.
  bool hunting_period = true;
  double tolerance = 1e-10;  ///< relative, on the contact equations (scaled by the approach)
  int max_iterations = 200;  ///< Newton + active-set iterations per position
  EaseOff ease_off;          ///< bevel / hypoid pairs only
  MountingErrors mounting;   ///< bevel / hypoid pairs only
};

/// One loaded contact point of the distribution.
struct ContactPoint {
  int position = 0;              ///< mesh position index (over all cycles)
  int pair = 0;                  ///< tooth pair j (entered j cycles ago)
  double path_m = 0.0;           ///< s
  double face_m = 0.0;           ///< y (slice centre)
  double roll_angle1_rad = 0.0;  ///< pinion roll angle rho1 / r_b1
  double radius1_m = 0.0, radius2_m = 0.0;
  double gap_m = 0.0;  ///< unloaded gap g
  double line_load_n_per_m = 0.0;
  double pressure_pa = 0.0;  ///< peak Hertz pressure
};

/// Result at one torque.
struct ToothContactResult {
  double torque_nm = 0.0;
  double force_n = 0.0;               ///< F_bt = T1 / r_b1 along the transverse line of action
  std::vector<double> mesh_fraction;  ///< u over all computed cycles (cycle k: k + p / P)
  std::vector<double> te_m;           ///< loaded TE delta along the line of action
  std::vector<double> unloaded_te_m;  ///< min gap (geometric TE)
  std::vector<double> stiffness_secant_n_per_m;   ///< F / (delta - min g)
  std::vector<double> stiffness_tangent_n_per_m;  ///< dF / d delta
  std::vector<double> points_in_contact;          ///< loaded slices
  std::vector<double> max_line_load_n_per_m;
  std::vector<double> max_pressure_pa;
  Eigen::MatrixXd pair_load_share;  ///< positions x pairs: share of F carried by pair j
  /// Mean over the computed cycles of the line load summed over pairs at each slice [N/m]
  /// (the face-load distribution) and the face-load factor K_Hbeta = max / mean of it.
  std::vector<double> face_load_n_per_m;
  double face_load_factor = 1.0;
  std::vector<ContactPoint> distribution;  ///< every candidate point of every position
  Status status = Status::Ok;
  std::string message;  ///< why a position failed, or "contact lost" details
};

/// The LTCA problem of one gear pair: geometry, modifications, compliance, options.
class ToothContact {
 public:
  /// A bevel / hypoid pair runs on its virtual cylindrical pair at mid face (docs/theory.md
  /// §15.9) with the ease-off and the mounting errors of the options; the compliance must be
  /// built on virtual_cylindrical_pair(geometry, mounting_effect(...).centre_distance_change_m).
  /// Throws InputError (key path geometry.spec.key_path + ...) for ease-off or mounting errors on
  /// a cylindrical pair, options out of range, pitch deviation vectors of the wrong size, or
  /// modifications that exceed the tooth (a relief start outside the active profile).
  ToothContact(const GearPairGeometry& geometry, FlankModification pinion, FlankModification wheel,
               const ContactCompliance& compliance, ToothContactOptions options = {});

  /// Solves every mesh position under the pinion torque T1 > 0.
  ToothContactResult solve(double pinion_torque_nm) const;

  /// Unloaded gap of pair j's slice at path s and face y in cycle `cycle` [m].
  double gap(double s, double y, int pair, int cycle) const;
  int cycles() const { return cycles_; }
  const GearPairGeometry& geometry() const { return geometry_; }
  const ToothContactOptions& options() const { return options_; }
  double pinion_roll_length(double s) const { return rho1_a_ + s; }
  double wheel_roll_length(double s) const;
  double base_radius1() const { return geometry_.pinion.base_radius_m; }
  /// Radius that turns the pinion torque into the force along the transverse line of action,
  /// F_bt = T1 / radius (and a TE length into the pinion's angle): r_b1, or r_m1 cos(alpha_t)
  /// of the real pinion for a bevel / hypoid pair.
  double force_radius() const { return force_radius_; }
  bool bevel() const { return bevel_; }
  const MountingEffect& mounting() const { return mounting_; }
  /// The ease-off coordinate xi of the pinion roll length rho1 (over the nominal active profile:
  /// for a bevel / hypoid pair the one without mounting errors).
  double ease_off_xi(double rho1) const {
    return (2.0 * rho1 - nominal_rho1_low_ - nominal_rho1_high_) /
           (nominal_rho1_high_ - nominal_rho1_low_);
  }

 private:
  void setup_bevel(const GearPairGeometry& given);
  double bevel_gap(double rho1, double y) const;
  double flank_removal(const FlankModification& m, double rho, double rho_low, double rho_high,
                       double base_radius, double y) const;

  GearPairGeometry geometry_;
  FlankModification pinion_, wheel_;
  const ContactCompliance* compliance_;
  ToothContactOptions options_;
  double rho1_a_ = 0.0, t1t2_ = 0.0;
  double rho1_low_ = 0.0, rho1_high_ = 0.0, rho2_low_ = 0.0, rho2_high_ = 0.0;
  bool internal_ = false;
  int cycles_ = 1;
  double force_radius_ = 0.0;
  bool bevel_ = false;
  MountingEffect mounting_;
  double nominal_rho1_low_ = 0.0, nominal_rho1_high_ = 1.0;
};

/// Centre of the contact pattern: the load-weighted mean over all computed positions of the
/// pinion's profile coordinate xi = ToothContact::ease_off_xi(rho1) (-1 at the start of its
/// nominal active profile, +1 at its tip) and of the face coordinate eta = 2 y / b - 1 (-1 at
/// y = 0, the toe of a bevel pair). NaN when nothing is loaded.
std::pair<double, double> pattern_centre(const ToothContact& contact,
                                         const ToothContactResult& result);

/// TE harmonics at mesh orders 1..n of a series sampled uniformly over `cycles` mesh cycles:
/// amplitude (0-peak) of order k = the DFT bin k * cycles.
std::vector<double> mesh_order_amplitudes(const std::vector<double>& series, int cycles,
                                          int orders);

}  // namespace geardyn::gear
