#include "geardyn/analyses/model_file.hpp"

#include <set>

#include "geardyn/analyses/registry.hpp"

namespace geardyn::analyses {

const std::vector<model::AnalysisDeclaration>& declarations() {
  static const std::vector<model::AnalysisDeclaration> all = [] {
    std::vector<model::AnalysisDeclaration> out;
    for (const auto& t : registry()) {
      out.push_back(t.declare());
      if (out.back().name != t.name)
        throw std::logic_error("analysis type '" + t.name + "' declares the keys of '" +
                               out.back().name + "'");
    }
    return out;
  }();
  return all;
}

const model::AnalysisDeclaration& declaration_of(const AnalysisType& type) {
  for (const auto& d : declarations())
    if (d.name == type.name) return d;
  throw std::logic_error("analysis type '" + type.name + "' has no declaration");
}

const model::Section& model_schema() {
  static const model::Section schema = model::make_model_schema(declarations());
  return schema;
}

model::ModelDocument load_document(const std::string& path) {
  return model::load_document(path, model_schema());
}

model::ModelDocument parse_document(const std::string& text, const std::string& file_name) {
  return model::parse_document(text, file_name, model_schema());
}

model::Model load_model(const std::string& path) { return model::load_model(path, model_schema()); }

model::Model parse_model(const std::string& text, const std::string& file_name) {
  return model::parse_model(text, file_name, model_schema());
}

std::string schema_markdown() { return model::schema_markdown(model_schema()); }

namespace {

void collect_words(const model::Section& s, std::set<std::string>& out) {
  if (!s.name.empty()) out.insert(s.name);
  for (const auto& f : s.fields) {
    out.insert(f.name);
    for (const auto& c : f.choices) out.insert(c);
  }
  for (const auto& sub : s.sections) collect_words(sub, out);
}

}  // namespace

std::vector<std::string> schema_words() {
  std::set<std::string> words;
  collect_words(model_schema(), words);
  return {words.begin(), words.end()};
}

}  // namespace geardyn::analyses
