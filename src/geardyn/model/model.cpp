#include "geardyn/model/model.hpp"

namespace geardyn::model {

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
