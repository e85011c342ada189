#pragma once
// The model's [[nonlinear_elements]] as harmonic-balance elements placed on a linear system
// (docs/theory.md §19): each entry's law (hbm/element_library.hpp, hbm/gear_mesh_element.hpp,
// hbm/squeeze_film_element.hpp) and its placement u = B q over the system's equations, built from
// the node frames of the DofMap (drivetrain/placement.hpp) -- one row per coordinate of the
// element: its direction (translation or rotation vector); a friction contact's normal then its
// tangents; a squeeze-film damper's two in-plane axes; a gear mesh's line of action
// (drivetrain::mesh_rows).
#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/fe/linear_system.hpp"
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

/// The model without the linear springs of the [[gear_meshes]] that a gear_mesh element
/// replaces (their stiffness and damping move into the nonlinear element).
model::Model without_replaced_mesh_springs(const model::Model& model);

}  // namespace geardyn::analyses
