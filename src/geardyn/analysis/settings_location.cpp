#include "geardyn/analysis/settings_location.hpp"

#include <fmt/format.h>

#include <variant>

namespace geardyn::analysis {

SourceLocation analysis_location(const model::Model& model, const void* settings,
                                 const std::string& fallback_name, std::string& name,
                                 std::string& key) {
  for (std::size_t i = 0; i < model.analyses.size(); ++i) {
    const model::Analysis& a = model.analyses[i];
    const void* p = std::visit([](const auto& s) -> const void* { return &s; }, a.settings);
    if (p == settings) {
      name = a.name;
      key = fmt::format("analyses[{}]", i);
      return a.where;
    }
  }
  key = "analysis";
  name = fallback_name;
  return SourceLocation{model.source_file, 0, 0};
}

}  // namespace geardyn::analysis
