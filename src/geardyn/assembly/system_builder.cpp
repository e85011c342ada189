#include "geardyn/assembly/system_builder.hpp"

#include "geardyn/assembly/modal_damping.hpp"
#include "geardyn/assembly/solid_coupling.hpp"

namespace geardyn::assembly {

fe::LinearSystem build_system(const model::Model& model, const assembly::SolidComponents* solids,
                              std::vector<CoupledSolid>& coupled, Progress& progress) {
  coupled.clear();
  std::vector<fe::Superelement> bodies;
  if (assembly::has_joined_solids(model)) {
    coupled = assembly::couple_solids(model, solids, progress);
    for (const assembly::CoupledSolid& solid : coupled) bodies.push_back(solid.body);
  }
  fe::LinearSystem system = fe::assemble(model, {}, bodies);
  assembly::apply_modal_damping(model, system);
  return system;
}

fe::LinearSystem build_system(const model::Model& model, const assembly::SolidComponents* solids,
                              Progress& progress) {
  std::vector<CoupledSolid> coupled;
  return build_system(model, solids, coupled, progress);
}

}  // namespace geardyn::assembly
