#pragma once
// [[nonlinear_elements]]: the nonlinear force elements of harmonic-balance analyses
// (`nonlinear_response`, docs/theory.md §19) as plain data. They act between two nodes (or a node
// and ground) of any model -- lumped points, rotors, the interface nodes of reduced components --
// on the relative motion u = (motion of node2 - motion of node1) . direction (translation, or the
// rotation vector for motion = "rotation"); plane elements (a 3D friction contact, a squeeze-film
// damper) use two or three directions. The linear analyses ignore them. Included by model.hpp.
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/model/drivetrain_spec.hpp"

namespace geardyn::model {

enum class NonlinearElementKind {
  Jenkins,          ///< spring in series with a Coulomb slider (stiffness, slip_force)
  Coulomb,          ///< regularised Coulomb friction F tanh(v / v_eps)
  FrictionContact,  ///< 2D/3D friction contact with variable normal load and lift-off
  Polynomial,       ///< f = sum c_p u^p
  Cubic,            ///< f = k3 u^3
  Unilateral,       ///< f = k max(u - gap, 0) (+ c u' while closed)
  Contact,          ///< a one-sided contact with a contact law ([nonlinear_elements.law])
  GearMesh,         ///< a [[gear_meshes]] entry's tooth contact: backlash, k(theta), TE
  SqueezeFilm       ///< short-bearing squeeze-film damper in the plane normal to `direction`
};

struct NonlinearElementSpec {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::string name;
  NonlinearElementKind kind = NonlinearElementKind::Jenkins;
  std::string node1;  ///< end i (empty: ground)
  std::string node2;  ///< end j
  /// Direction of u in global axes (normalised); the normal of a friction contact; the axis of
  /// a squeeze-film damper.
  DrivetrainVec3 direction{1.0, 0.0, 0.0};
  bool rotation = false;  ///< motion = "rotation": the rotation vectors' projection
  /// Friction contact: tangential directions (global, normalised; the second one only for a
  /// 3D contact, empty NaN otherwise).
  DrivetrainVec3 tangent{kNaN, kNaN, kNaN};
  DrivetrainVec3 tangent2{kNaN, kNaN, kNaN};

  double stiffness = kNaN;                ///< jenkins, unilateral: k; cubic: k3 [N/m^3]
  double slip_force = kNaN;               ///< jenkins, coulomb: F [N]
  double regularisation_velocity = 1e-4;  ///< coulomb: v_eps
  double gap = 0.0;                       ///< unilateral, contact
  double damping = 0.0;                   ///< unilateral: c while closed; gear mesh: c
  std::vector<double> powers;             ///< polynomial: p (integers >= 1)
  std::vector<double> coefficients;       ///< polynomial: c_p
  // friction_contact
  double normal_stiffness = 0.0;
  double tangential_stiffness = kNaN;
  double friction_coefficient = kNaN;
  double normal_preload = 0.0;
  ContactLawSpec law;  ///< contact
  // gear_mesh
  std::string gear_mesh;   ///< the [[gear_meshes]] entry
  double backlash = kNaN;  ///< total backlash along the line of action [m]; NaN: none
  // squeeze_film
  double radius = kNaN, length = kNaN, clearance = kNaN, viscosity = kNaN;
  bool cavitated = true;  ///< film = "pi" (true) or "full" (false)
  SourceLocation where;
};

}  // namespace geardyn::model
