#pragma once
// Reading model files with every registered analysis type: the declaration table of the model
// module (model/schema.hpp) completed with the registry's analysis types, and the model
// module's reading functions bound to it.
//
//   model::ModelDocument doc = analyses::load_document("model.toml");
//   model::apply_override(doc, "bearings[0].kxx=2e7");
//   model::Model m = model::build_model(doc);
#include <string>
#include <vector>

#include "geardyn/analyses/registry.hpp"
#include "geardyn/model/parse.hpp"
#include "geardyn/model/schema.hpp"

namespace geardyn::analyses {

/// The declarations of the registry's analysis types (built once, in registry order).
const std::vector<model::AnalysisDeclaration>& declarations();
/// The declaration of `type` (its keys, checks and whether it needs the rotor).
const model::AnalysisDeclaration& declaration_of(const AnalysisType& type);

/// The model file's declaration table with every analysis type of the registry (built once,
/// self-checked).
const model::Section& model_schema();

model::ModelDocument load_document(const std::string& path);
model::ModelDocument parse_document(const std::string& text, const std::string& file_name);
model::Model load_model(const std::string& path);
model::Model parse_model(const std::string& text, const std::string& file_name);

/// docs/model-reference.md: every key of the model file (`geardyn schema`).
std::string schema_markdown();

/// Every word a model file can contain as a key or a choice (for the fuzzers' dictionaries).
std::vector<std::string> schema_words();

}  // namespace geardyn::analyses
