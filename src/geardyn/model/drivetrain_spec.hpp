#pragma once
// The nonlinear drivetrain of the time-domain analysis `drivetrain_transient` as plain data
// (docs/theory.md §16): force elements between nodes (contacts, bolts, bushings, rolling
// bearings), speed and torque drivers, load torques and clutches. Included by model.hpp; SI
// units (m, kg, s, N, rad, rad/s) like the rest of the model. The linear analyses ignore all of
// this: for them the rotor is what [[bearings]], [[couplings]] and [[gear_meshes]] make it.
//
// Ends: `node1` is end i, `node2` end j of an element (u = end j - end i); an empty node1 is
// ground. Directions and frames are global unit vectors (normalised by the parser).
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"

namespace geardyn::model {

using DrivetrainVec3 = std::array<double, 3>;

/// Normal-contact law of a contact side or of a gear mesh's flanks (elements/contact_law.hpp).
enum class ContactLawKind { Linear, Hertz, Impact, Penalty };

struct ContactLawSpec {
  ContactLawKind type = ContactLawKind::Impact;
  double stiffness = std::numeric_limits<double>::quiet_NaN();  ///< k [N/m^e] (required)
  /// Hertz n / IMPACT e (1.5 default); not used by linear and penalty.
  double exponent = 1.5;
  /// linear: c [N s/m]; Hertz: Hunt-Crossley chi [s/m]; penalty: c.
  double damping = 0.0;
  double max_damping = 0.0;                                             ///< IMPACT c_max [N s/m]
  double penetration_depth = std::numeric_limits<double>::quiet_NaN();  ///< IMPACT d [m]
  double stiffness_exponent = 1.0;                                      ///< penalty m1
  double rate_exponent = 1.0;                                           ///< penalty m2
  double damping_exponent = 0.0;                                        ///< penalty m3
  double penetration_regularisation = 1e-9;                             ///< penalty delta_r [m]
  double rate_regularisation = 1e-6;                                    ///< penalty v_r [m/s]
  bool clip_tension = false;  ///< tension = "clipped" (true) or "allowed" (false)
  SourceLocation where;
};

/// [[contacts]]: a contact between two nodes (or a node and ground) along a direction: a
/// one-sided end stop or end play with a contact on both sides (rattle).
enum class ContactKind { Stop, EndPlay };
enum class ContactMotion { Translation, Rotation };

struct ContactSpec {
  std::string name;
  std::string node1;                        ///< end i (empty: ground)
  std::string node2;                        ///< end j
  DrivetrainVec3 direction{1.0, 0.0, 0.0};  ///< global; u = (u_2 - u_1) . direction
  ContactMotion motion =
      ContactMotion::Translation;  ///< rotation: the rotation vectors' projection
  ContactKind kind = ContactKind::Stop;
  double gap = 0.0;       ///< stop: closes when u > gap [m or rad]
  double backlash = 0.0;  ///< end play: closes when |u| > backlash [m or rad]
  ContactLawSpec law;
  SourceLocation where;
};

/// [[bolts]]: a preloaded bolted joint (VDI 2230 joint diagram) between two nodes.
struct BoltSpec {
  std::string name;
  std::string node1;                   ///< end i: the clamped part on the nut side (empty: ground)
  std::string node2;                   ///< end j: the clamped part on the head side
  DrivetrainVec3 axis{0.0, 0.0, 1.0};  ///< bolt axis (global): u_a = (u_2 - u_1) . axis
  double bolt_stiffness = std::numeric_limits<double>::quiet_NaN();   ///< k_S [N/m]
  double clamp_stiffness = std::numeric_limits<double>::quiet_NaN();  ///< k_P [N/m]
  double preload = 0.0;                                               ///< F_V [N]
  double load_introduction = 1.0;                                     ///< n
  double axial_damping = 0.0;                                         ///< [N s/m]
  double shear_stiffness = 0.0;  ///< k_q [N/m] (0: no shear coordinates)
  double shear_damping = 0.0;    ///< [N s/m]
  double activation_time = -std::numeric_limits<double>::infinity();  ///< t_a [s]
  double preload_ramp = 0.0;                                          ///< [s]
  double inactive_stiffness = 0.0;                                    ///< k_0 [N/m]
  SourceLocation where;
};

/// One direction's force-deflection table of a bushing.
struct BushingTableSpec {
  int direction = 0;  ///< 0..5: x, y, z, rx, ry, rz
  std::vector<double> deflection, force;
  bool linear = false;  ///< interpolation "linear" (true) or "cubic" (false)
  SourceLocation where;
};

/// [[bushings]]: 6-coordinate bushing with linear K, C, a preload and per-direction tables.
struct BushingSpec {
  std::string name;
  std::string node1;  ///< end i (empty: ground)
  std::string node2;  ///< end j
  /// Bushing frame: x and z axes (global); y = z x x. Default: the global axes.
  DrivetrainVec3 x_axis{1.0, 0.0, 0.0};
  DrivetrainVec3 z_axis{0.0, 0.0, 1.0};
  std::array<double, 36> stiffness{};  ///< row-major 6 x 6 (or the diagonal keys)
  std::array<double, 36> damping{};
  std::array<double, 6> preload{};
  std::vector<BushingTableSpec> tables;
  SourceLocation where;
};

/// [[rolling_bearings]]: rolling-element bearing between a shaft node (inner ring) and the
/// housing (outer ring: a node or ground). The bearing axis is the shaft node's spin axis.
struct RollingBearingSpec {
  std::string name;
  std::string node;     ///< inner ring: a shaft node (end j)
  std::string housing;  ///< outer ring (end i; empty: ground)
  int elements = 0;
  double stiffness_constant = std::numeric_limits<double>::quiet_NaN();  ///< K_n [N/m^n]
  double exponent = 1.5;
  double radial_clearance = 0.0;
  double axial_clearance = 0.0;
  double contact_angle = 0.0;  ///< [rad]
  double pitch_diameter = std::numeric_limits<double>::quiet_NaN();
  double element_diameter = std::numeric_limits<double>::quiet_NaN();
  double cage_angle = 0.0;  ///< [rad] at t = 0
  double radial_damping = 0.0;
  double axial_damping = 0.0;
  SourceLocation where;
};

/// [[drivers]]: what turns the drivetrain, acting on the rotation about the node's spin axis.
enum class DriverKind { Speed, Motor };

struct DriverSpec {
  std::string name;
  std::string node;
  DriverKind kind = DriverKind::Speed;
  /// speed: prescribed speed over time, piecewise linear (held after the last point); one
  /// point: constant speed.
  std::vector<double> times;   ///< [s], increasing, first >= 0
  std::vector<double> speeds;  ///< [rad/s]
  /// motor: torque over speed, piecewise linear (held outside), and the rotor inertia added to
  /// the node.
  std::vector<double> motor_speeds;   ///< [rad/s], increasing
  std::vector<double> motor_torques;  ///< [N m]
  double inertia = 0.0;               ///< [kg m^2]
  SourceLocation where;
};

/// [[loads]]: a torque on the rotation about a node's spin axis: constant + table (over speed
/// or time) - drag omega |omega|.
enum class LoadTableOver { None, Speed, Time };

struct LoadTorqueSpec {
  std::string name;
  std::string node;
  double torque = 0.0;  ///< [N m], in the node's e3 sense
  LoadTableOver table_over = LoadTableOver::None;
  std::vector<double> table_x;       ///< [rad/s] or [s], increasing
  std::vector<double> table_torque;  ///< [N m]
  double drag = 0.0;                 ///< c_d [N m s^2/rad^2]: adds -c_d omega |omega|
  SourceLocation where;
};

/// [[clutches]]: a slipping clutch between two nodes' spin rotations, or a brake (node1 empty),
/// transmitting at most `max_torque` (regularised Coulomb friction).
struct ClutchSpec {
  std::string name;
  std::string node1;  ///< empty: a brake to ground
  std::string node2;
  double max_torque = std::numeric_limits<double>::quiet_NaN();  ///< [N m]
  double slip_speed = 1e-2;  ///< omega_eps [rad/s]: T = T_max tanh(slip / omega_eps)
  double engage_time = 0.0;  ///< [s]: transmits nothing before
  SourceLocation where;
};

/// Nonlinear tooth contact of a [[gear_meshes]] entry in the drivetrain transient
/// ([gear_meshes.contact]).
struct MeshContactSpec {
  /// [[gear_pairs]] whose TE and force-deflection maps (LTCA or STE file) the mesh uses; empty:
  /// the mesh's constant `stiffness`.
  std::string gear_pair;
  /// Total backlash along the line of action [m]; NaN: no back-flank contact.
  double backlash = std::numeric_limits<double>::quiet_NaN();
  std::optional<ContactLawSpec> law;  ///< absent: the maps' force-deflection law
  /// With an IMPACT / penalty law: scale its stiffness by k(theta) / mean k of the map.
  bool vary_stiffness = true;
  double friction = 0.0;  ///< tooth friction coefficient mu (0: none)
  /// v_eps [m/s] of the friction's smoothed sign tanh(v_s / v_eps) (docs/theory.md §16.6).
  double friction_velocity = 1e-3;
  SourceLocation where;
};

/// [[virtual_sensors]]: displacement, velocity and acceleration of a node in the drivetrain
/// transient, along a component of the node's frame or a global direction.
struct VirtualSensorSpec {
  std::string name;
  std::string node;
  int component = -1;  ///< 0..5 (ux ... rz, node frame), or -1 with `direction`
  std::optional<DrivetrainVec3> direction;  ///< global unit vector
  bool rotation = false;  ///< with `direction`: project the rotation vector, not the translation
  SourceLocation where;
};

}  // namespace geardyn::model
