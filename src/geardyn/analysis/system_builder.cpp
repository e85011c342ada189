#include "geardyn/analysis/system_builder.hpp"

#include "geardyn/eig/modal_damping.hpp"

namespace geardyn::analysis {

fe::LinearSystem build_system(const model::Model& model) {
  fe::LinearSystem system = fe::assemble(model);
  eig::apply_modal_damping(model, system);
  return system;
}

}  // namespace geardyn::analysis
