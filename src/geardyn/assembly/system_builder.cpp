#include "geardyn/assembly/system_builder.hpp"

#include "geardyn/assembly/modal_damping.hpp"
#include "geardyn/assembly/solid_coupling.hpp"

namespace geardyn::assembly {

fe::LinearSystem build_system(const model::Model& model, const assembly::SolidComponents* solids,
                              Progress& progress) {
  std::vector<fe::Superelement> bodies;
  if (assembly::has_joined_solids(model)) {
    for (assembly::CoupledSolid& solid : assembly::couple_solids(model, solids, progress))
      bodies.push_back(std::move(solid.body));
  }
  fe::LinearSystem system = fe::assemble(model, {}, bodies);
  assembly::apply_modal_damping(model, system);
  return system;
}

}  // namespace geardyn::assembly
