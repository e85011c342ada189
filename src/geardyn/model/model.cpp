#include "geardyn/model/model.hpp"

namespace geardyn::model {

std::array<bool, 6> dof_set_components(DofSet set) {
  const bool lateral = set == DofSet::All || set == DofSet::Lateral ||
                       set == DofSet::LateralAxial || set == DofSet::LateralTorsional;
  const bool axial = set == DofSet::All || set == DofSet::Axial || set == DofSet::LateralAxial ||
                     set == DofSet::AxialTorsional;
  const bool torsional = set == DofSet::All || set == DofSet::Torsional ||
                         set == DofSet::LateralTorsional || set == DofSet::AxialTorsional;
  return {lateral, lateral, axial, lateral, lateral, torsional};
}

const Material* Model::find_material(const std::string& name) const {
  for (const auto& m : materials)
    if (m.name == name) return &m;
  return nullptr;
}

const Analysis* Model::find_analysis(const std::string& name) const {
  for (const auto& a : analyses)
    if (a.name == name) return &a;
  return nullptr;
}

const Solid* Model::find_solid(const std::string& name) const {
  for (const auto& s : solids)
    if (s.name == name) return &s;
  return nullptr;
}

const GearPair* Model::find_gear_pair(const std::string& name) const {
  for (const auto& p : gear_pairs)
    if (p.name == name) return &p;
  return nullptr;
}

}  // namespace geardyn::model
