#pragma once
// Static deflection of the rotor model under the tooth forces of one of its gear meshes, and the
// mesh misalignment the gear nodes' tilts cause (docs/theory.md §15.7): the "f_sh" component of
// ISO 6336-1's initial equivalent misalignment, taken from the shafts and bearings of the model
// as a system deflection does.
//
// The static problem K q = f (K at zero speed, K_at(0): speed-dependent bearings at their first
// tabulated speed) is solved with
//   * the mesh spring of the linked gear mesh removed: the tooth force is the load, applied at
//     the two gear nodes (so the mesh's own compliance, the tooth deflection, is the contact
//     analysis's business and is not counted twice); other gear meshes keep their springs;
//   * the torsional DOFs (rz) of every node held: torsion of a beam element is uncoupled from
//     bending, axial motion and tilts, so holding it changes no tilt and removes the spin
//     rigid-body modes of the shafts (the input and output torques that balance the tooth force
//     about the gear axes are reacted where rz is held). The twist of the pinion body over the
//     face width (ISO 6336-1's torsional part of f_sh) is not represented by one gear node.
//
// Tooth force on gear 1 (magnitudes from the pair at its torque, directions from the gear
// mesh geometry, fe/gear_mesh_element.hpp): F1 = -sigma F_t e_t - F_r e_r + s_a F_a e_a with
// s_a the sign of the mesh's own axial force (sigma h for helical, 0 for spur), applied at the
// mid-face pitch point P: force F1 and moment (P - x1) x F1 at gear 1's node, -F1 and
// lever2 x (-F1) at gear 2's node.
//
// Misalignment (the gap difference along the transverse line of action n_t between the face
// ends, y = b minus y = 0, as gear/tooth_contact.hpp): a gear node tilted by theta moves the
// point of its flank line at face position y by theta x (y yhat), so with the slope of gear i in
// the plane of action s_i = (theta_i x yhat) . n_t, f_ma = b (s_2 - s_1); the out-of-plane part,
// along q = yhat x n_t (normal to the plane of action), is b (o_2 - o_1) with o_i = (theta_i x
// yhat) . q. Translations of the gear nodes move the whole contact line alike and give no
// misalignment (the change of centre distance they cause is second order for the gap).
// Face coordinate: the slice model's y runs from the face end where a tooth pair enters contact;
// for a helical mesh that is the end at +sigma h e_a of gear 1's axis (the base helix of a
// right-hand gear (h = +1) turning in its driving sense (sigma) stands ahead at +e_a), so
// yhat = -sigma h e_a; for a spur mesh (no entering end) yhat = +e_a: y = 0 at the face end on
// the -e3 side of gear 1's node frame.
#include <Eigen/Dense>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::assembly {

/// Tooth force components on gear 1 [N], magnitudes (gear/tooth_forces.hpp: tangential, radial
/// separating, axial).
struct MeshToothLoad {
  double tangential_n = 0.0;
  double radial_n = 0.0;
  double axial_n = 0.0;
};

struct MeshDeflection {
  std::string mesh;                                         ///< the [[gear_meshes]] name
  std::string gear1, gear2;                                 ///< its gear nodes
  Eigen::Vector3d displacement1 = Eigen::Vector3d::Zero();  ///< gear 1's node, global [m]
  Eigen::Vector3d displacement2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d tilt1 = Eigen::Vector3d::Zero();  ///< rotation vector, global [rad]
  Eigen::Vector3d tilt2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d face_direction = Eigen::Vector3d::UnitZ();  ///< yhat (see top of file)
  Eigen::Vector3d line_of_action = Eigen::Vector3d::UnitX();  ///< n_t (transverse, unit)
  Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitY();    ///< q = yhat x n_t
  double slope1_rad = 0.0, slope2_rad = 0.0;                  ///< s_1, s_2: in the plane of action
  double out_of_plane_slope1_rad = 0.0, out_of_plane_slope2_rad = 0.0;  ///< o_1, o_2
  double misalignment_m = 0.0;                                          ///< f_ma = b (s_2 - s_1)
  double out_of_plane_misalignment_m = 0.0;                             ///< b (o_2 - o_1)
};

/// The static deflection of `model`'s rotor under `load` on gear mesh `mesh_name` and the
/// misalignment over the face width `face_width_m` (see top of file). Errors are InputError at
/// `where`, key `key` (the model key that asked for it): no gear mesh of that name, a bevel or
/// hypoid mesh, a rotor free to move without the mesh spring (the motion named: which shaft or
/// free nodes, along or about which global axis), or a singular stiffness otherwise.
MeshDeflection mesh_static_deflection(const model::Model& model, const std::string& mesh_name,
                                      const MeshToothLoad& load, double face_width_m,
                                      const SourceLocation& where, const std::string& key);

}  // namespace geardyn::assembly
