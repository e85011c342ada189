#pragma once
// Model -> DrivetrainParts (docs/theory.md §16.9): the assembled linear system (without the gear
// meshes' linear springs) and the model's nonlinear elements, drivers, loads and clutches placed
// on its equations. Gear meshes become tooth-contact elements: the caller passes one element per
// [[gear_meshes]] entry on the coordinates (delta, theta1) — the approach along the line of
// action and gear 1's spin angle; with tooth friction (delta, theta1, theta2, y), MeshRows — or
// null for a mesh without a map, which becomes a contact of the mesh's constant stiffness and
// damping on delta (drive flank; back flank at -backlash when the mesh's contact gives one).
#include <memory>
#include <vector>

#include "geardyn/drivetrain/drivetrain_system.hpp"
#include "geardyn/elements/contact_law.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::drivetrain {

struct BuildOptions {
  /// Per [[gear_meshes]] entry: its element on (delta, theta1), or null (constant stiffness).
  std::vector<std::shared_ptr<const elements::ForceElement>> mesh_elements;
  /// Reference speed for the rolling bearings' cage [rad/s] (the initial spin of the drivers).
  double initial_reference_speed = 0.0;
};

/// The contact law of a model's [contacts.law] / [gear_meshes.contact.law] table; InputError at
/// `source` for bad parameters.
std::shared_ptr<const elements::ContactLaw> make_contact_law(const model::ContactLawSpec& spec,
                                                             const elements::LawSource& source);

/// The model without its gear meshes' linear springs (stiffness and damping 0): the linear part
/// of a drivetrain, to be assembled by the caller (assembly::build_system).
model::Model without_mesh_springs(const model::Model& model);

/// Places every element of the model. Throws InputError (at the element's table) for an end
/// whose DOFs are all constrained on both sides, a driver or load on a spin without equation, a
/// node without mass that only this element holds.
DrivetrainParts build_drivetrain(const model::Model& model, const fe::LinearSystem& system,
                                 const BuildOptions& options);

/// The rigid spin of the whole drivetrain at reference speed `speed`: rz = speed x speed ratio
/// at every node (the initial velocity of a run that starts turning).
Eigen::VectorXd rigid_spin(const fe::LinearSystem& system, double speed);

/// The line-of-action coefficients of gear mesh `index` over the node DOFs (placement row of
/// delta) and gear 1's spin sign: for the placement and for the dynamic transmission error.
struct MeshRows {
  std::vector<int> equations;
  std::vector<double> coefficients;  ///< delta = sum c_k q[e_k]
  int pinion_spin = -1;              ///< gear 1's rz equation
  double pinion_sign = 1.0;          ///< theta1 = sign x q[pinion_spin]
  double base_radius1 = 0.0;
  /// For tooth friction (elements/gear_mesh_contact.hpp): theta2 = wheel_sign x q[wheel_spin]
  /// (the wheel's rotation in its working sense), and y = sum profile_coefficients[k]
  /// q[profile_equations[k]], the wheel centre's displacement relative to the pinion's along
  /// the profile direction t (perpendicular to the line of action in the transverse plane,
  /// where the pinion's contact point moves for theta1_dot > 0).
  int wheel_spin = -1;
  double wheel_sign = 1.0;
  std::vector<int> profile_equations;
  std::vector<double> profile_coefficients;
};
MeshRows mesh_rows(const model::Model& model, const fe::LinearSystem& system, std::size_t index);

}  // namespace geardyn::drivetrain
