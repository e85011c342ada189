#include "geardyn/analyses/settings_location.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace geardyn::analyses {

SourceLocation analysis_location(const model::Model& model, const void* settings,
                                 const std::string& fallback_name, std::string& name,
                                 std::string& key) {
  for (std::size_t i = 0; i < model.analyses.size(); ++i) {
    const model::Analysis& a = model.analyses[i];
    if (dynamic_cast<const void*>(a.settings.get()) == settings) {
      name = a.name;
      key = fmt::format("analyses[{}]", i);
      return a.where;
    }
  }
  key = "analysis";
  name = fallback_name;
  return SourceLocation{model.source_file, 0, 0};
}

std::vector<const model::Sensor*> select_sensors(const model::Model& model,
                                                 const std::vector<std::string>& names,
                                                 const SourceLocation& where,
                                                 const std::string& key) {
  std::vector<const model::Sensor*> sensors;
  if (names.empty()) {
    for (const auto& s : model.sensors) sensors.push_back(&s);
    return sensors;
  }
  for (const auto& sensor_name : names) {
    auto it = std::find_if(model.sensors.begin(), model.sensors.end(),
                           [&](const model::Sensor& s) { return s.name == sensor_name; });
    if (it == model.sensors.end())
      throw InputError(where, key + ".sensors", "the name of a sensor", "'" + sensor_name + "'");
    sensors.push_back(&*it);
  }
  return sensors;
}

}  // namespace geardyn::analyses
