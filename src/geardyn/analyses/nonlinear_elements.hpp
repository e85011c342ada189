#pragma once
// The model's [[nonlinear_elements]] as harmonic-balance elements placed on a linear system
// (docs/theory.md §19): each entry's law (hbm/element_library.hpp, hbm/gear_mesh_element.hpp,
// hbm/squeeze_film_element.hpp) and its placement u = B q over the system's equations, built from
// the node frames of the DofMap (drivetrain/placement.hpp) -- one row per coordinate of the
// element: its direction (translation or rotation vector); a friction contact's normal then its
// tangents; a squeeze-film damper's two in-plane axes; a gear mesh's line of action
// (drivetrain::mesh_rows).
#include <Eigen/Dense>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/hbm/element_system.hpp"
#include "geardyn/hbm/nonlinear_element.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

struct BuiltNonlinearElement {
  std::string name;
  std::string kind;  ///< the model file's `type`
  std::shared_ptr<const hbm::NonlinearElement> element;
  Eigen::MatrixXd B;  ///< element->size() x system.size()
  /// Gear mesh elements: the mesh cycles per pinion revolution (teeth1): the balance's
  /// fundamental is then the mesh frequency. 0 for other elements.
  int mesh_teeth = 0;
};

/// Every entry of model.nonlinear_elements, in order. InputError located at the entry for a bad
/// parameter of its law, an end whose DOFs are all constrained on both sides (the element would
/// act on nothing), or a gear mesh without stiffness.
std::vector<BuiltNonlinearElement> build_nonlinear_elements(const model::Model& model,
                                                            const fe::LinearSystem& system,
                                                            const Context& context);

/// The linear structure on the coordinates of the balance: the system's DOFs (n_modes = 0; dense,
/// InputError at `n_modes` beyond 600 DOFs) or its n_modes lowest undamped modes at `speed`
/// (M = I, K = diag(w_r^2), C = Phi^T (C(W) + W G + modal damping) Phi in full, K_loss projected;
/// NumericalError when the eigen-solve fails).
struct NonlinearCoordinates {
  Eigen::MatrixXd M, C, K, K_loss;
  Eigen::MatrixXd basis;  ///< n_eq x n_coordinates (the identity for the physical form)
  bool modal = false;
  double highest_mode = std::numeric_limits<double>::quiet_NaN();  ///< [rad/s]
};
NonlinearCoordinates nonlinear_coordinates(const fe::LinearSystem& system, double speed,
                                           int n_modes, const Context& context);

/// The structure on `c` with the elements placed on it (B_e basis) and the excitation F
/// (n_eq x 3: the coefficients a_0, a_1, b_1 per equation; empty: none).
hbm::ElementSystem placed_element_system(const NonlinearCoordinates& c,
                                         const std::vector<BuiltNonlinearElement>& elements,
                                         const Eigen::MatrixXd& F);

/// Rows of the model's sensors named in `names` (empty: all) over the equations; InputError
/// (key `sensors`) for a solid sensor or one on a constrained DOF.
struct SensorRows {
  std::vector<std::string> names;
  std::vector<bool> rotational;
  Eigen::MatrixXd rows;  ///< sensors x n_eq
};
SensorRows nonlinear_sensor_rows(const model::Model& model, const fe::LinearSystem& system,
                                 const std::vector<std::string>& names, const Context& context);

/// The linear structure the nonlinear analyses balance: the context's system, or, when gear_mesh
/// elements replace their meshes' linear springs, the system built without them (into `own`).
const fe::LinearSystem& nonlinear_structure(const model::Model& model, const Context& context,
                                            fe::LinearSystem& own);

/// The model without the linear springs of the [[gear_meshes]] that a gear_mesh element
/// replaces (their stiffness and damping move into the nonlinear element).
model::Model without_replaced_mesh_springs(const model::Model& model);

}  // namespace geardyn::analyses
