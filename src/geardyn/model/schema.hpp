#pragma once
// The one declaration of every key of a model file (deal.II-style parameter declaration).
//
// Each key is declared once with its type, unit, default or "required", allowed range, help
// text and a setter into the plain-data Model (model.hpp): the model's sections in
// schema_rotor.cpp, schema_solids.cpp, schema_gears.cpp and schema_model.cpp, and each analysis
// type's keys in its AnalysisDeclaration (given by the analysis registry,
// src/geardyn/analyses/registry.hpp). That table drives
//   - parsing and validation (parse.cpp walks the TOML document with it),
//   - `--set key.path=value` overrides and sweep parameters (key paths are checked against it),
//   - the markdown reference (schema_markdown(), docs/model-reference.md).
//
// Units: values are written in the unit the table declares for the key, and converted to SI
// when they are stored in the Model. Only keys whose name says so use other units:
// `*_rpm` (to rad/s), `*_hz` (to rad/s), `*_deg` (to rad).
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <typeindex>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::model {

enum class FieldType {
  Number,         ///< float or integer, stored as double (SI)
  Integer,        ///< integer
  Boolean,        ///< true / false
  String,         ///< free text, or a name / reference (see Field::ref, Field::identifier)
  Enum,           ///< one string of Field::choices
  NumberOrArray,  ///< a number, or an array of numbers tabulated against Field::tabulated_by
  NumberArray,    ///< array of numbers
  Vector3,        ///< array of exactly 3 numbers
  StringArray,    ///< array of strings (names, or Field::choices when given)
  Matrix,         ///< square matrix as an array of rows; size in Field::matrix_sizes
  DofList,        ///< "all" or an array of DOF names ("ux", "uy", "uz", "rx", "ry", "rz")
};

/// What a string (or each string of an array) names; checked after the whole file is read.
enum class Ref {
  None,
  Node,
  Material,
  Shaft,
  Sensor,
  Force,
  Unbalance,
  Analysis,
  KeyPath,
  Solid,
  GearPair
};

/// A unit as written in the file and the factor that converts it to SI.
struct Unit {
  const char* symbol = "";  ///< empty: dimensionless
  double to_si = 1.0;
};

/// Allowed interval of a number (of each element for arrays), in the unit of the key.
struct Range {
  std::optional<double> min, max;
  bool min_exclusive = false;
  bool max_exclusive = false;
};

/// A value read from the file (or a default), checked and converted to SI.
struct FieldValue {
  bool given = false;                ///< false: the declared default
  SourceLocation where;              ///< where the value is written (the table for defaults)
  std::string path;                  ///< key path, e.g. "shafts[0].elements[2].length"
  double number = 0.0;               ///< Number, NumberOrArray given as a number
  long long integer = 0;             ///< Integer
  bool boolean = false;              ///< Boolean
  std::string text;                  ///< String, Enum
  int choice = -1;                   ///< Enum: index into Field::choices
  std::vector<double> numbers;       ///< NumberArray, Vector3, NumberOrArray as array, Matrix
                                     ///< (row-major, matrices one after the other when tabulated)
  std::vector<std::string> strings;  ///< StringArray
  std::vector<int> indices;          ///< DofList: Component indices
  bool is_array = false;  ///< NumberOrArray given as array; Matrix given as a table of them
  int rows = 0;           ///< Matrix: size n of the n x n matrix
  std::size_t count = 0;  ///< NumberOrArray / Matrix tabulated: number of entries
};

/// The values of one table, for the cross-key checks of Section::finish / Variant::finish.
struct TableContext {
  std::string path;      ///< key path of the table, e.g. "shafts[1]" ("" for the root)
  std::string section;   ///< e.g. "[[shafts]]"
  SourceLocation where;  ///< where the table starts
  std::map<std::string, FieldValue, std::less<>> values;  ///< given keys and defaults

  bool has(std::string_view key) const;              ///< given in the file (not a default)
  const FieldValue& at(std::string_view key) const;  ///< given or default; throws if neither
  std::string key_path(std::string_view key) const;
  SourceLocation where_of(std::string_view key) const;  ///< the value, or the table if absent
  [[noreturn]] void fail(std::string_view key, std::string expected, std::string found,
                         std::string hint = {}) const;
};

using Setter = std::function<void(void* object, const FieldValue& value)>;
using Finisher = std::function<void(void* object, const TableContext& table)>;

struct Field {
  std::string name;
  FieldType type = FieldType::Number;
  Unit unit;                       ///< unit of the value as written
  std::string unit_note;           ///< docs: unit text when it depends on something else
  bool required = false;           ///< required (inside its Choice alternative, if any)
  std::string default_value;       ///< TOML literal in the key's unit; empty: no default
  std::string default_note;        ///< docs: meaning of "absent" when there is no default
  bool default_from_path = false;  ///< default: the table's key path (names of unnamed objects)
  Range range;
  bool allow_infinity = false;       ///< +-inf accepted (NaN never is)
  bool nonzero = false;              ///< Vector3: must not be the zero vector
  bool identifier = false;           ///< String: a name of letters, digits, '_' and '-'
  bool increasing = false;           ///< arrays: strictly increasing
  bool unique = false;               ///< StringArray: no repeated entries
  std::size_t min_items = 0;         ///< arrays: minimum number of entries
  std::vector<int> matrix_sizes;     ///< Matrix: allowed n
  bool tabulated = false;            ///< Matrix: an array of matrices is accepted
  std::string tabulated_by;          ///< arrays must have as many entries as this key has
  std::vector<std::string> choices;  ///< Enum, StringArray, DofList: allowed strings
  Ref ref = Ref::None;
  std::vector<std::string> only_in;  ///< variants of the section where this key is allowed
                                     ///< (empty: all)
  std::string help;
  std::type_index object_type = typeid(void);  ///< type the setter writes into
  Setter setter;                               ///< empty: read by the section's finish step
};

/// Keys that are alternatives: at most one alternative may be given (exactly one if required).
/// An alternative counts as given when any of its keys is; then its required keys must be there.
struct Choice {
  std::vector<std::vector<std::string>> alternatives;
  bool required = false;
  std::vector<std::string> only_in;  ///< variants where this choice applies (empty: all)
};

/// A value of the section's discriminator key (e.g. analyses' `type`) selecting extra keys.
class ModelCheck;

/// Checks of one object against the rest of the model after the whole file is read (references
/// to other sections, sizes that depend on them): `path` is the object's key path.
using Checker = std::function<void(const void* object, const std::string& path, const ModelCheck&)>;

struct Variant {
  std::string name;
  std::string help;
  Finisher finish;  ///< cross-key checks and derived values for this variant
  Checker check;    ///< checks against the rest of the model (may be empty)
};

enum class SectionKind { Root, Table, ArrayOfTables };

struct Section {
  std::string name;   ///< key in the parent table ("" for the root)
  std::string title;  ///< docs: "[[shafts.elements]]"
  SectionKind kind = SectionKind::ArrayOfTables;
  std::string help;
  bool required = false;
  /// Table: absent means no object (the parent's std::optional stays empty, `child` is not
  /// called); otherwise an absent table is read with its defaults.
  bool optional = false;
  std::size_t min_count = 0;  ///< ArrayOfTables: minimum entries when present
  std::vector<Field> fields;
  std::vector<Choice> choices;
  std::vector<Section> sections;
  std::string discriminator;  ///< Enum field selecting a Variant ("" : none)
  std::vector<Variant> variants;
  std::vector<std::string> only_in;  ///< parent variants where this sub-table is allowed
  std::type_index object_type = typeid(void);
  std::function<void*(void* parent)> child;  ///< appends (array) or returns (table) the object
  std::function<void(void* object, const SourceLocation&)> locate;  ///< sets its `where`
  Finisher finish;  ///< cross-key checks after all keys are set

  const Field* find_field(std::string_view key, std::string_view variant) const;
  const Section* find_section(std::string_view key, std::string_view variant) const;
  /// Every key name allowed in this table for `variant` (fields and sub-tables).
  std::vector<std::string> key_names(std::string_view variant) const;
  const Variant* find_variant(std::string_view name) const;
};

/// One analysis type as the model file sees it: its `type` name, help, settings object, keys,
/// cross-key rules and checks. The analysis registry makes one per type.
struct AnalysisDeclaration {
  std::string name;  ///< `type = "..."`
  std::string help;
  std::function<std::unique_ptr<AnalysisSettings>()> make_settings;
  std::vector<Field> fields;      ///< its keys (setters into Analysis, see keys::F::to_settings)
  std::vector<Choice> choices;    ///< alternatives among its keys
  std::vector<Section> sections;  ///< its sub-tables
  std::function<void(Analysis&, const TableContext&)> finish;  ///< cross-key rules, derived values
  std::function<void(const Analysis&, const std::string& path, const ModelCheck&)> check;
  bool needs_rotor = false;  ///< needs [[shafts]] or [[nodes]]
};

/// The root of the declaration table (keys `version`, `title` and the sections) with these
/// analysis types, self-checked: a declaration error (a key declared twice, a setter into the
/// wrong object, ...) is a std::logic_error.
Section make_model_schema(const std::vector<AnalysisDeclaration>& analyses);

/// Throws std::logic_error when the declaration table contradicts itself.
void check_schema(const Section& root);

/// The model-file reference as markdown: every section and key with type, unit, default,
/// range and help (this is docs/model-reference.md).
std::string schema_markdown(const Section& root);

/// Text used in messages and docs.
std::string describe_type(const Field& field);   ///< "a number > 0 [m]"-style expectation
std::string describe_range(const Field& field);  ///< "> 0", "in [0, 1]", "" for none

/// The closest candidate by edit distance (Damerau-Levenshtein), or "" if none is close;
/// a candidate that is `word` plus a unit suffix (`phase` -> `phase_deg`) counts as close.
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace geardyn::model
