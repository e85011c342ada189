#include "geardyn/analysis/system_builder.hpp"

#include "geardyn/component/solid_coupling.hpp"
#include "geardyn/eig/modal_damping.hpp"

namespace geardyn::analysis {

fe::LinearSystem build_system(const model::Model& model, const component::SolidComponents* solids,
                              Progress& progress) {
  std::vector<fe::Superelement> bodies;
  if (component::has_joined_solids(model)) {
    for (component::CoupledSolid& solid : component::couple_solids(model, solids, progress))
      bodies.push_back(std::move(solid.body));
  }
  fe::LinearSystem system = fe::assemble(model, {}, bodies);
  eig::apply_modal_damping(model, system);
  return system;
}

}  // namespace geardyn::analysis
