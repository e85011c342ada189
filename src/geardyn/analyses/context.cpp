#include "geardyn/analyses/context.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "geardyn/assembly/solid_coupling.hpp"

namespace geardyn::analyses {

Context::Context(const model::Model& model, const model::Analysis& analysis)
    : name_(analysis.name), key_path_("analysis"), where_(analysis.where) {
  for (std::size_t i = 0; i < model.analyses.size(); ++i)
    if (&model.analyses[i] == &analysis || model.analyses[i].name == analysis.name) {
      key_path_ = fmt::format("analyses[{}]", i);
      break;
    }
  if (where_.file.empty()) where_ = SourceLocation{model.source_file, 0, 0};
}

Context::Context(std::string name, std::string key_path, SourceLocation where)
    : name_(std::move(name)), key_path_(std::move(key_path)), where_(std::move(where)) {}

std::string Context::key(std::string_view key) const {
  return fmt::format("{}.{}", key_path_, key);
}

InputError Context::error(std::string_view key, std::string expected, std::string found,
                          std::string hint) const {
  return InputError(where_, this->key(key), std::move(expected), std::move(found), std::move(hint));
}

const fe::LinearSystem& Context::system() const {
  if (system_ == nullptr)
    throw std::logic_error(fmt::format("analysis '{}' needs the rotor's linear system", name_));
  return *system_;
}

const assembly::CoupledSolid* Context::coupled_solid(const std::string& solid_name) const {
  if (coupled_ == nullptr) return nullptr;
  for (const assembly::CoupledSolid& c : *coupled_)
    if (c.name == solid_name) return &c;
  return nullptr;
}

const assembly::SolidComponent& Context::solid(const model::Model& model,
                                               const std::string& solid_name) const {
  if (solids_ != nullptr) {
    auto it = solids_->find(solid_name);
    if (it != solids_->end()) return it->second;
  }
  const std::lock_guard<std::mutex> lock(built_->mutex);
  auto& slot = built_->solids[solid_name];
  if (!slot) {
    const model::Solid* s = model.find_solid(solid_name);
    if (s == nullptr) throw std::logic_error("unresolved solid " + solid_name);
    slot = std::make_unique<assembly::SolidComponent>(assembly::build_solid(model, *s, progress()));
  }
  return *slot;
}

std::vector<const model::Sensor*> select_sensors(const model::Model& model,
                                                 const std::vector<std::string>& names,
                                                 const Context& context) {
  std::vector<const model::Sensor*> sensors;
  if (names.empty()) {
    for (const auto& s : model.sensors) sensors.push_back(&s);
    return sensors;
  }
  for (const auto& sensor_name : names) {
    auto it = std::find_if(model.sensors.begin(), model.sensors.end(),
                           [&](const model::Sensor& s) { return s.name == sensor_name; });
    if (it == model.sensors.end())
      throw context.error("sensors", "the name of a sensor", "'" + sensor_name + "'");
    sensors.push_back(&*it);
  }
  return sensors;
}

}  // namespace geardyn::analyses
