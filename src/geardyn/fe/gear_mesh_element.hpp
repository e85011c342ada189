#pragma once
// Linear gear-mesh element: a spring k (and damper c) along the line of action n through the
// pitch point P, coupling translations, tilts and rotations of the two gear nodes.
//
// Mesh compression (approach of the two tooth surfaces along n, positive when the teeth press
// together), for small motions u_i, theta_i of the gear nodes at x_i in global coordinates:
//   delta = v . q,  v = [n ; (P - x1) x n ; -n ; -(P - x2) x n],  q = [u1; theta1; u2; theta2],
// with n the unit direction of the force gear 1 exerts on gear 2. K = k v v^T, C = c v v^T,
// transformed to the node frames (v_node = T^T v, T = blockdiag(R1, R1, R2, R2)).
//
// Geometry and sign convention (gear 1 drives):
//   e_a  gear 1's axis (node frame e3); for bevel and hypoid gears the axial direction used for
//        the thrust is u_a = +-e_a pointing from the cone apex towards gear 1's node, the apex
//        being the point of gear 1's axis closest to gear 2's axis.
//   e_r  unit vector normal to e_a from gear 1's axis towards gear 2: mesh_direction if given,
//        else the part of x2 - x1 normal to e_a (zero, i.e. coaxial nodes: InputError).
//   e_t  = e_a x e_r: motion of gear 1's pitch point for a positive rotation about e_a.
//   P    = x1 + r_p1 e_r, r_p1 = base_radius1 / cos(alpha_t) with the transverse pressure angle
//        tan(alpha_t) = tan(alpha_n) / cos(beta) (spur: alpha_t = pressure_angle). Gear nodes are
//        expected on the axis in the mid-face plane; for bevel and hypoid gears base_radius1 is
//        r_m cos(alpha_t) with r_m the mean pitch radius, so that P is the mid-face pitch point.
//   sigma = (sign of gear 1's speed ratio, + for 0) x (+1 drive flank, -1 coast flank): the
//        tooth force opposes gear 1's motion, so its tangential part is -sigma e_t.
// Tooth force on gear 1 per unit tangential force (the n above is minus its unit vector):
//   spur:     -sigma e_t - tan(alpha) e_r
//   helical:  -sigma e_t - tan(alpha_n)/cos(beta) e_r + sigma h tan(beta) e_a,
//             h = +1 for a right-hand helix of gear 1 (tooth line advances along +e_a for a
//             positive turn, like a right-hand screw), -1 for left hand.
//   straight / spiral bevel and hypoid (equivalent spur gear at mid face, docs/theory.md §11.2):
//             -sigma e_t + F_a u_a - F_r e_r with s = h sigma (u_a . e_a),
//             F_a = (tan(alpha_n) sin(delta1) + s sin(beta) cos(delta1)) / cos(beta)  (away
//             from the apex when positive), F_r = (tan(alpha_n) cos(delta1) - s sin(beta)
//             sin(delta1)) / cos(beta) (towards gear 1's axis, separating, when positive).
//             Hand as in AGMA 2005 / ISO 23509: right hand when the outer half of the tooth is
//             inclined clockwise for an observer looking at the face of the gear (from the apex
//             side). So s = +1 (upper signs of docs/theory.md (11.3)) is a right-hand gear 1
//             driving counter-clockwise as seen looking from its back towards the apex, or a
//             left-hand one driving clockwise: both push gear 1 away from the apex.
// Torsion of a spur pair: (P - x1) x n . e_a = sigma r_b1, so only-rz motion gives the reduced
// system omega^2 = k (r_b1^2 / J1 + r_b2^2 / J2).
//
// Both base radii are used, and the node positions must agree with them (kConsistencyTolerance):
//   spur, helical (parallel axes): the centre distance a (distance of gear 2's node from gear 1's
//        axis) must be (r_b1 + r_b2) / cos(alpha_t) (external: gear 2's centre beyond P along e_r)
//        or (r_b2 - r_b1) / cos(alpha_t) (internal gear 2: its centre behind gear 1's, reached by
//        a mesh_direction pointing away from gear 2), and gear 2's centre must lie on the line
//        through gear 1's centre along e_r. The line of action is then the common tangent of the
//        two base circles (ISO 21771:2007, Gears - Cylindrical involute gears and gear pairs -
//        Concepts and geometry, a_w = (d_b1 + d_b2) / (2 cos(alpha_wt))): working
//        transverse pressure angle cos(alpha_wt) = (r_b2 +- r_b1) / a, P dividing the centre
//        distance in the ratio r_b1 : r_b2, base helix angle tan(beta_b) = tan(beta) cos(alpha_t)
//        kept (tan(beta_w) = tan(beta_b) / cos(alpha_wt)). The torsional lever arms are then
//        exactly r_b1 cos(beta_b) and r_b2 cos(beta_b): the gear ratio is r_b1 / r_b2, whatever
//        rounding the node coordinates carry, and rigid rotations of the gear train strain nothing.
//   straight / spiral bevel: P must lie at r_p2 = base_radius2 / cos(alpha_t) from gear 2's axis
//        (mean pitch radius of gear 2; both mean pitch points coincide on the pitch cones). Gear
//        2's lever arm is P - x2 with its part normal to gear 2's axis scaled to exactly r_p2.
//   hypoid: the equivalent spiral bevel places P off the true (offset) pitch point, so only gear
//        2's lever arm is scaled to r_p2; no distance is checked.
//   all:  r_b1 / r_b2 must be |speed ratio of gear 2 / speed ratio of gear 1| when both nodes
//        spin, and teeth1 / teeth2 when both are given (one base pitch; not for hypoid gears,
//        whose pinion is enlarged).
#include <string>

#include "geardyn/fe/dof_map.hpp"
#include "geardyn/fe/element_types.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::fe {

struct GearMeshGeometry {
  Eigen::Vector3d pitch_point;           ///< P [m], global
  Eigen::Vector3d radial;                ///< e_r
  Eigen::Vector3d tangential;            ///< e_t
  Eigen::Vector3d axial;                 ///< e_a (spur, helical) or u_a (bevel, hypoid)
  Eigen::Vector3d line_of_action;        ///< n: unit direction of the force on gear 2
  Eigen::Vector3d lever2;                ///< lever arm of the mesh force about gear 2's node [m]
  double pitch_radius1 = 0;              ///< r_p1 [m]
  double transverse_pressure_angle = 0;  ///< alpha_t [rad] (spur, helical: working alpha_wt)
  double sigma = 1;                      ///< rotation sense x flank, see above
  /// Tooth force on gear 1 per unit tangential force, along -sigma e_t, `axial` and -e_r:
  /// (1, F_a, F_r). The unnormalised force is -sigma e_t + F_a axial - F_r e_r.
  double tangential_force = 1, axial_force = 0, radial_force = 0;
};

/// Relative tolerance of the check of node positions against the base radii: coordinates and
/// radii written to 4 significant digits carry up to 5e-4 relative rounding, twice that is 1e-3,
/// and 0.1 % of a centre distance is well above a manufacturing tolerance (DIN 3964, 1980,
/// centre distance allowances: tens of micrometres on hundreds of millimetres): a larger mismatch
/// is a modelling error that would otherwise change the gear ratio.
inline constexpr double kConsistencyTolerance = 1e-3;

/// Geometry of `mesh` between the gear nodes (global positions and frames from the DofMap).
/// `key` is the key path used in InputError messages (e.g. "gear_meshes[0]").
/// Throws InputError for coaxial nodes, a mesh_direction along the axis, non-positive base
/// radius, a pressure angle outside (0, pi/2), |helix angle| >= pi/2, bevel axes that are parallel
/// or a gear node at the cone apex, and node positions inconsistent with the base radii (above).
GearMeshGeometry gear_mesh_geometry(const model::GearMesh& mesh, const NodeInfo& gear1,
                                    const NodeInfo& gear2, const std::string& key);

/// v in the node frames (see top of file): mesh compression delta = v . q_node.
Vector12d gear_mesh_vector(const GearMeshGeometry& geometry, const NodeInfo& gear1,
                           const NodeInfo& gear2);

}  // namespace geardyn::fe
