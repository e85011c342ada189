#pragma once
// Reading a model file: TOML text -> ModelDocument (syntax only) -> Model (checked, resolved, SI).
//
//   ModelDocument doc = load_document("model.toml", schema);
//   apply_override(doc, "bearings[0].kxx=2e7");          // `geardyn run --set ...`
//   Model model = build_model(doc);                       // throws InputError on bad input
//
// `schema` is the declaration table (schema.hpp) with the analysis types of the program; the
// analyses module gives the full one (analyses/model_file.hpp: analyses::load_model etc.).
// Every key is declared once (type, unit, default, range, help); build_model reads
// the document through that declaration, so everything is checked before any computation:
// unknown keys (with "did you mean"), types, ranges, required keys, alternatives, references to
// nodes / materials / shafts / sensors / forces / unbalances / analyses, duplicate names, shaft
// speed chains (driven_by), disk geometry, tabulated bearings and the analysis settings.
// Errors are geardyn::InputError with file:line:column, key path, expected and found.
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/model/model.hpp"
#include "geardyn/model/schema.hpp"

namespace toml {
inline namespace v3 {
class table;
class node;
}  // namespace v3
}  // namespace toml

namespace geardyn::model {

/// A parsed model file plus the `--set` / sweep values applied to it.
///
/// Copying is cheap and thread-safe: the parsed file is shared (immutable) and the overrides are
/// a short list, so a sweep copies the document per point and calls set_number on its copy.
/// Overrides are kept beside the file rather than written into it so that every value keeps its
/// source line (toml++ does not copy source positions when a table is copied).
class ModelDocument {
 public:
  /// A value that replaces (or adds) the key `key` of the table at `parent` ("" : root).
  struct Override {
    std::string parent;  ///< canonical key path of the table, e.g. "bearings[0]"
    std::string key;     ///< e.g. "kxx"
    std::string origin;  ///< e.g. "--set bearings[0].kxx=2e7", used as the error location
    std::shared_ptr<const toml::node> value;
  };

  ModelDocument();
  ModelDocument(std::shared_ptr<const toml::table> root, std::string file_name,
                const Section& schema);

  const toml::table& table() const { return *root_; }
  /// The declaration table the document is read with (std::logic_error if none).
  const Section& schema() const;
  const std::string& file_name() const { return file_name_; }
  const std::vector<Override>& overrides() const { return overrides_; }
  /// The override for key `key` of the table at `parent`, or nullptr.
  const Override* find_override(std::string_view parent, std::string_view key) const;
  /// True if some override sets a key at or below the table path `parent`.
  bool has_overrides_below(std::string_view parent) const;
  /// Adds (or replaces) an override; the key path must already be checked (apply_override).
  void add_override(Override override_value);

 private:
  std::shared_ptr<const toml::table> root_;
  std::string file_name_;
  const Section* schema_ = nullptr;  ///< lives as long as the program (a static table)
  std::vector<Override> overrides_;
};

/// Reads and parses a file (TOML syntax only) to be read with `schema`. Throws InputError if it
/// cannot be read or is not valid TOML (with toml++'s line and column).
ModelDocument load_document(const std::string& path, const Section& schema);

/// Parses TOML text; `file_name` is used in error messages.
ModelDocument parse_document(const std::string& text, const std::string& file_name,
                             const Section& schema);

/// Applies "key.path=value" (e.g. "bearings[0].kxx=2e7", "analyses[1].speed_rpm=3000",
/// "shafts[0].theory=euler_bernoulli"). The value is a TOML value ("[1, 2]", "true", "\"x\"");
/// for string keys the quotes may be left out. The key path is checked against the schema and the
/// document (array indices must exist); unknown keys get a "did you mean". The value itself is
/// checked by build_model like any value in the file, with the assignment as its location.
void apply_override(ModelDocument& document, const std::string& assignment);

/// Sets a numeric key (number, integer, or number-or-array key) to `value`, in the key's own unit
/// as written in the file (e.g. rpm for `*_rpm` keys); same path checks as apply_override.
/// Integer keys need an integral value. Used by sweeps.
void set_number(ModelDocument& document, const std::string& key_path, double value);

/// Checks that `key_path` names a key that set_number can set in this document: a number,
/// integer or number-or-array key of an existing table. Throws InputError at `where` otherwise.
void check_number_key(const ModelDocument& document, const std::string& key_path,
                      const SourceLocation& where);

/// The declaration of the key at `key_path` (path checked as by apply_override).
const Field& field_of(const ModelDocument& document, const std::string& key_path,
                      const SourceLocation& where);

/// Reads the document through the schema, resolves references and derived values and validates
/// everything. Throws InputError for the first problem found.
Model build_model(const ModelDocument& document);

/// Shortcuts: parse_document / load_document followed by build_model.
Model parse_model(const std::string& text, const std::string& file_name, const Section& schema);
Model load_model(const std::string& path, const Section& schema);

/// What a check of one object against the rest of the model may use (Variant::check,
/// AnalysisDeclaration::check): the model as read, and the parser's ways of saying what is wrong,
/// located at the key path in the file (or the --set / sweep assignment that gave it).
class ModelCheck {
 public:
  virtual ~ModelCheck() = default;
  virtual const Model& model() const = 0;
  virtual const ModelDocument& document() const = 0;
  /// Throws the InputError at `path`: expected, found, hint.
  [[noreturn]] virtual void fail(const std::string& path, std::string expected, std::string found,
                                 std::string hint = {}) const = 0;
  /// True if the key at `path` is written in the file or set by an override.
  virtual bool given(const std::string& path) const = 0;
  virtual SourceLocation locate(const std::string& path) const = 0;
  /// `name` is one of `known` (the names of section `section`; `what` names one, e.g. "sensor").
  virtual void check_name(const std::string& path, const std::string& name,
                          const std::set<std::string>& known, const char* what,
                          const char* section) const = 0;
  /// check_name for each entry of `names` (path[i]).
  virtual void check_named(const std::string& path, const std::vector<std::string>& names,
                           const std::set<std::string>& known, const char* what,
                           const char* section) const = 0;
  /// `node` is a shaft station or a [[nodes]] name.
  virtual void check_node(const std::string& path, const std::string& node) const = 0;
};

/// The names of the items of a section (their `name` keys).
template <class T>
std::set<std::string> names_of(const std::vector<T>& items) {
  std::set<std::string> out;
  for (const auto& x : items) out.insert(x.name);
  return out;
}

/// "a", "an": the indefinite article and the word ("an analysis", "a sensor").
std::string a_name(const char* what);
/// Items as 'a', 'b', 'c' (for messages).
std::string quoted_list(const std::vector<std::string>& items);

/// Station node name of a shaft: "<shaft>.<k>".
std::string station_name(const std::string& shaft, int station);

}  // namespace geardyn::model
