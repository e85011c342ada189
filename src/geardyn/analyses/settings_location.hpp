#pragma once
// Where an analysis's settings came from, for error messages of the analyses.
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// The analysis whose settings object is `settings` (found by address in model.analyses): sets
/// `name` and `key` ("analyses[i]", as the parser names it) and returns its source location.
/// Settings not owned by the model (built in code) give `fallback_name`, key "analysis" and the
/// model file without a line.
SourceLocation analysis_location(const model::Model& model, const void* settings,
                                 const std::string& fallback_name, std::string& name,
                                 std::string& key);

/// The sensors an analysis reports: all of the model's when `names` is empty, else those named
/// (in that order). An unknown name is an InputError at `key`.sensors.
std::vector<const model::Sensor*> select_sensors(const model::Model& model,
                                                 const std::vector<std::string>& names,
                                                 const SourceLocation& where,
                                                 const std::string& key);

}  // namespace geardyn::analyses
