// The declaration table of the model file: the machinery (lookups, messages, self-check, the
// markdown reference). The sections themselves are declared in schema_rotor.cpp,
// schema_solids.cpp, schema_gears.cpp and schema_model.cpp, and each analysis type declares its
// own keys (src/geardyn/analyses/*_entry.cpp).
#include "geardyn/model/schema.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geardyn/model/model.hpp"

namespace geardyn::model {

// ---------------------------------------------------------------------------------------------
// TableContext

bool TableContext::has(std::string_view key) const {
  auto it = values.find(key);
  return it != values.end() && it->second.given;
}

const FieldValue& TableContext::at(std::string_view key) const {
  auto it = values.find(key);
  if (it == values.end())
    throw std::logic_error(fmt::format("schema: no value or default for '{}' in {}", key, path));
  return it->second;
}

std::string TableContext::key_path(std::string_view key) const {
  return path.empty() ? std::string(key) : fmt::format("{}.{}", path, key);
}

SourceLocation TableContext::where_of(std::string_view key) const {
  auto it = values.find(key);
  return it != values.end() && it->second.given ? it->second.where : where;
}

void TableContext::fail(std::string_view key, std::string expected, std::string found,
                        std::string hint) const {
  throw InputError(where_of(key), key_path(key), std::move(expected), std::move(found),
                   std::move(hint));
}

// ---------------------------------------------------------------------------------------------
// Section lookups

namespace {

bool allowed_in(const std::vector<std::string>& only_in, std::string_view variant) {
  return only_in.empty() || std::find(only_in.begin(), only_in.end(), variant) != only_in.end();
}

}  // namespace

const Field* Section::find_field(std::string_view key, std::string_view variant) const {
  for (const auto& f : fields)
    if (f.name == key && allowed_in(f.only_in, variant)) return &f;
  return nullptr;
}

const Section* Section::find_section(std::string_view key, std::string_view variant) const {
  for (const auto& s : sections)
    if (s.name == key && allowed_in(s.only_in, variant)) return &s;
  return nullptr;
}

std::vector<std::string> Section::key_names(std::string_view variant) const {
  std::vector<std::string> names;
  for (const auto& f : fields)
    if (allowed_in(f.only_in, variant)) names.push_back(f.name);
  for (const auto& s : sections)
    if (allowed_in(s.only_in, variant)) names.push_back(s.name);
  return names;
}

const Variant* Section::find_variant(std::string_view variant_name) const {
  for (const auto& v : variants)
    if (v.name == variant_name) return &v;
  return nullptr;
}

// ---------------------------------------------------------------------------------------------
// Messages

namespace {

std::string format_number(double x) {
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return fmt::format("{}", x);
}

}  // namespace

std::string describe_range(const Field& f) {
  const Range& r = f.range;
  if (r.min && r.max) {
    if (*r.min == *r.max) return fmt::format("= {}", format_number(*r.min));
    return fmt::format("in {}{}, {}{}", r.min_exclusive ? "(" : "[", format_number(*r.min),
                       format_number(*r.max), r.max_exclusive ? ")" : "]");
  }
  if (r.min) return fmt::format("{} {}", r.min_exclusive ? ">" : ">=", format_number(*r.min));
  if (r.max) return fmt::format("{} {}", r.max_exclusive ? "<" : "<=", format_number(*r.max));
  return {};
}

namespace {

std::string quoted_list(const std::vector<std::string>& items, const char* last_joint) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += i + 1 == items.size() ? last_joint : ", ";
    out += fmt::format("\"{}\"", items[i]);
  }
  return out;
}

const char* ref_noun(Ref ref) {
  switch (ref) {
    case Ref::Node:
      return "node";
    case Ref::Material:
      return "material";
    case Ref::Shaft:
      return "shaft";
    case Ref::Sensor:
      return "sensor";
    case Ref::Force:
      return "force";
    case Ref::Unbalance:
      return "unbalance";
    case Ref::Analysis:
      return "analysis";
    case Ref::KeyPath:
      return "key path";
    case Ref::Solid:
      return "solid";
    case Ref::GearPair:
      return "gear pair";
    case Ref::None:
      break;
  }
  return "";
}

}  // namespace

std::string describe_type(const Field& f) {
  std::string range = describe_range(f);
  std::string unit = f.unit.symbol[0] != '\0' ? fmt::format(" [{}]", f.unit.symbol) : "";
  if (!f.unit_note.empty()) unit = fmt::format(" [{}]", f.unit_note);
  auto with_range = [&](std::string what) {
    return range.empty() ? what + unit : fmt::format("{} {}{}", what, range, unit);
  };
  switch (f.type) {
    case FieldType::Number:
      return with_range("a number");
    case FieldType::Integer:
      return with_range("an integer");
    case FieldType::Boolean:
      return "a boolean (true or false)";
    case FieldType::String:
      if (f.ref != Ref::None) return fmt::format("a {} name (a string)", ref_noun(f.ref));
      if (f.identifier) return "a name (a string of letters, digits, '_' and '-')";
      return "a string";
    case FieldType::Enum:
      return fmt::format("one of {}", quoted_list(f.choices, " or "));
    case FieldType::NumberOrArray:
      return fmt::format("a number{} or an array of them, one per `{}` entry{}",
                         range.empty() ? "" : " " + range, f.tabulated_by, unit);
    case FieldType::NumberArray:
      return fmt::format("an array of {}numbers{}{}", f.increasing ? "increasing " : "",
                         range.empty() ? "" : ", each " + range, unit);
    case FieldType::Vector3:
      return fmt::format("an array of 3 numbers [x, y, z]{}{}", f.nonzero ? ", not all zero" : "",
                         unit);
    case FieldType::StringArray:
      if (!f.choices.empty())
        return fmt::format("an array of strings from {}", quoted_list(f.choices, ", "));
      if (f.ref != Ref::None) return fmt::format("an array of {} names", ref_noun(f.ref));
      return "an array of strings";
    case FieldType::Matrix: {
      std::string sizes;
      for (std::size_t i = 0; i < f.matrix_sizes.size(); ++i)
        sizes += fmt::format("{}{}x{}", i == 0 ? "" : " or ", f.matrix_sizes[i], f.matrix_sizes[i]);
      return fmt::format("a {} matrix as an array of rows{}{}", sizes,
                         f.tabulated ? fmt::format(" (or an array of such matrices, one per `{}` "
                                                   "entry)",
                                                   f.tabulated_by)
                                     : "",
                         unit);
    }
    case FieldType::DofList:
      return fmt::format("\"all\" or an array of DOF names from {}", quoted_list(f.choices, ", "));
  }
  return "a value";
}

// ---------------------------------------------------------------------------------------------
// Edit distance (optimal string alignment, i.e. Damerau-Levenshtein with adjacent swaps).

namespace {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[n][m];
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

std::string closest_match(std::string_view word, const std::vector<std::string>& candidates) {
  if (word.empty() || word.size() > 200) return {};
  const std::string w = lower(word);
  // A key written without its unit suffix ("phase" for "phase_deg", "speed" for "speed_rpm").
  for (const auto& c : candidates) {
    const std::string lc = lower(c);
    for (const char* suffix : {"_rpm", "_hz", "_deg"})
      if (lc == w + suffix) return c;
  }
  std::string best;
  std::size_t best_distance = 0;
  for (const auto& c : candidates) {
    const std::size_t dist = edit_distance(w, lower(c));
    if (best.empty() || dist < best_distance) {
      best = c;
      best_distance = dist;
    }
  }
  // Close enough: about a third of the letters wrong, at least one, at most three.
  const std::size_t limit = std::clamp<std::size_t>(w.size() / 3, 1, 3);
  return !best.empty() && best_distance <= limit ? best : std::string{};
}

// ---------------------------------------------------------------------------------------------
// Self-check

namespace {

// Schema self-check: every setter writes into the object type of its section, defaults are
// declared only where they can apply, and each variant-restricted key names known variants.
void check_section(const Section& s) {
  for (const auto& f : s.fields) {
    if (f.object_type != s.object_type)
      throw std::logic_error(
          fmt::format("schema: key '{}' of {} writes into another type", f.name, s.title));
    if (f.required && !f.default_value.empty())
      throw std::logic_error(fmt::format("schema: required key '{}' has a default", f.name));
    for (const auto& v : f.only_in)
      if (!s.find_variant(v))
        throw std::logic_error(
            fmt::format("schema: key '{}' names unknown variant '{}'", f.name, v));
  }
  // A key is declared once for each variant (keys of different variants may share a name).
  for (std::size_t i = 0; i < s.fields.size(); ++i)
    for (std::size_t j = i + 1; j < s.fields.size(); ++j) {
      const Field& a = s.fields[i];
      const Field& b = s.fields[j];
      if (a.name != b.name) continue;
      const bool overlap = a.only_in.empty() || b.only_in.empty() ||
                           std::any_of(a.only_in.begin(), a.only_in.end(),
                                       [&](const auto& v) { return allowed_in(b.only_in, v); });
      if (overlap)
        throw std::logic_error(
            fmt::format("schema: key '{}' of {} is declared twice", a.name, s.title));
    }
  if (!s.discriminator.empty()) {
    const Field* d = s.find_field(s.discriminator, "");
    bool listed =
        d != nullptr && d->type == FieldType::Enum && d->choices.size() == s.variants.size();
    for (std::size_t i = 0; listed && i < s.variants.size(); ++i)
      listed = d->choices[i] == s.variants[i].name;
    if (!listed)
      throw std::logic_error(
          fmt::format("schema: discriminator of {} does not list its variants", s.title));
  }
  for (const auto& sub : s.sections) check_section(sub);
}

}  // namespace

void check_schema(const Section& root) { check_section(root); }

// ---------------------------------------------------------------------------------------------
// Markdown

namespace {

std::string cell(std::string s) {
  std::string out;
  for (char c : s) {
    if (c == '|')
      out += "\\|";
    else if (c == '\n')
      out += ' ';
    else
      out += c;
  }
  return out;
}

std::string doc_type(const Field& f) {
  switch (f.type) {
    case FieldType::Number:
      return "number";
    case FieldType::Integer:
      return "integer";
    case FieldType::Boolean:
      return "boolean";
    case FieldType::String:
      if (f.ref == Ref::KeyPath) return "key path";
      if (f.ref != Ref::None) return fmt::format("{} name", ref_noun(f.ref));
      return f.identifier ? "name" : "string";
    case FieldType::Enum: {
      std::string out;
      for (std::size_t i = 0; i < f.choices.size(); ++i)
        out += fmt::format("{}`\"{}\"`", i ? " | " : "", f.choices[i]);
      return out;
    }
    case FieldType::NumberOrArray:
      return fmt::format("number, or array per `{}`", f.tabulated_by);
    case FieldType::NumberArray:
      return f.increasing ? "array of numbers (increasing)" : "array of numbers";
    case FieldType::Vector3:
      return "[x, y, z]";
    case FieldType::StringArray:
      if (f.ref != Ref::None) return fmt::format("array of {} names", ref_noun(f.ref));
      return "array of strings";
    case FieldType::Matrix: {
      std::string sizes;
      for (std::size_t i = 0; i < f.matrix_sizes.size(); ++i)
        sizes += fmt::format("{}{}x{}", i ? " or " : "", f.matrix_sizes[i], f.matrix_sizes[i]);
      return fmt::format(
          "{} matrix (array of rows){}", sizes,
          f.tabulated ? fmt::format(", or array of them per `{}`", f.tabulated_by) : "");
    }
    case FieldType::DofList:
      return "`\"all\"` or array of `\"ux\"` ... `\"rz\"`";
  }
  return "";
}

std::string doc_default(const Field& f, const Section& s) {
  if (f.required) {
    for (const auto& c : s.choices)
      for (const auto& alt : c.alternatives)
        if (std::find(alt.begin(), alt.end(), f.name) != alt.end() && c.alternatives.size() > 1)
          return "required (in its alternative)";
    return "**required**";
  }
  if (!f.default_value.empty()) return fmt::format("`{}`", f.default_value);
  if (f.default_from_path) return fmt::format("the table's key path, e.g. `\"{}[0]\"`", s.name);
  if (!f.default_note.empty()) return fmt::format("none: {}", f.default_note);
  return "none";
}

void field_table(std::string& out, const Section& s, const std::vector<const Field*>& fields) {
  out += "| key | type | unit | default | allowed | description |\n";
  out += "|---|---|---|---|---|---|\n";
  for (const Field* f : fields) {
    std::string unit = f->unit_note.empty() ? f->unit.symbol : f->unit_note;
    std::string allowed = describe_range(*f);
    if (f->nonzero) allowed = "not all zero";
    if (f->identifier) allowed = "letters, digits, `_`, `-`";
    if (f->min_items > 0)
      allowed += fmt::format("{}at least {} entr{}", allowed.empty() ? "" : "; ", f->min_items,
                             f->min_items == 1 ? "y" : "ies");
    if (f->allow_infinity) allowed += "; `inf` allowed";
    out += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", f->name, cell(doc_type(*f)),
                       cell(unit), cell(doc_default(*f, s)), cell(allowed), cell(f->help));
  }
  out += "\n";
}

std::string alternatives_text(const Choice& c) {
  std::string out;
  for (std::size_t i = 0; i < c.alternatives.size(); ++i) {
    if (i > 0) out += " or ";
    out += "(";
    for (std::size_t j = 0; j < c.alternatives[i].size(); ++j)
      out += fmt::format("{}`{}`", j ? ", " : "", c.alternatives[i][j]);
    out += ")";
  }
  return out;
}

void choices_text(std::string& out, const Section& s, std::string_view variant) {
  for (const auto& c : s.choices) {
    if (variant.empty() ? !c.only_in.empty() : !allowed_in(c.only_in, variant) || c.only_in.empty())
      continue;
    out += fmt::format("{} of {}.\n\n", c.required ? "Give exactly one" : "Give at most one",
                       alternatives_text(c));
  }
}

void section_markdown(std::string& out, const Section& s, int level) {
  const std::string hashes(static_cast<std::size_t>(level), '#');
  out += fmt::format("{} {}\n\n{}\n\n", hashes, s.title, s.help);
  if (!s.only_in.empty()) {
    out += "Only in:";
    for (const auto& v : s.only_in) out += fmt::format(" `{} = \"{}\"`", "type", v);
    out += ".\n\n";
  }
  if (s.kind == SectionKind::Table && s.optional) out += "Optional table.\n\n";
  if (s.kind == SectionKind::ArrayOfTables && s.min_count > 0)
    out += fmt::format("At least {} entr{} {}.\n\n", s.min_count, s.min_count == 1 ? "y" : "ies",
                       s.required ? "required" : "when present");
  std::vector<const Field*> common;
  for (const auto& f : s.fields)
    if (f.only_in.empty()) common.push_back(&f);
  field_table(out, s, common);
  choices_text(out, s, "");
  for (const auto& v : s.variants) {
    out += fmt::format("{}# {} = \"{}\"\n\n{}\n\n", hashes, s.discriminator, v.name, v.help);
    std::vector<const Field*> own;
    for (const auto& f : s.fields)
      if (!f.only_in.empty() && allowed_in(f.only_in, v.name)) own.push_back(&f);
    if (own.empty())
      out += "No further keys.\n\n";
    else
      field_table(out, s, own);
    choices_text(out, s, v.name);
  }
  for (const auto& sub : s.sections) section_markdown(out, sub, level + 1);
}

}  // namespace

std::string schema_markdown(const Section& root) {
  std::string out;
  out += "# geardyn model-file reference\n\n";
  out +=
      "<!-- Generated from the declaration table (src/geardyn/model/schema_*.cpp and the "
      "analysis types of src/geardyn/analyses/registry.cpp) by schema_markdown() (`geardyn "
      "schema`). Do not edit: regenerate with "
      "`GEARDYN_UPDATE_DOCS=1 build/tests/model/test_model "
      "--gtest_filter=ModelReference.*`. -->\n\n";
  out +=
      "A model is a TOML file. Every key below is checked: unknown keys, wrong types, values "
      "out of range, missing required keys, references to things that do not exist and "
      "duplicate names are errors that name the file, line, column and key path.\n\n"
      "Conventions:\n\n"
      "- **Units** are SI (m, kg, s, N, Pa, rad/s) except in keys whose name says otherwise: "
      "`*_rpm` (rev/min), `*_hz` (Hz) and `*_deg` (degrees); they are converted to rad/s and rad "
      "when read.\n"
      "- **Names** (`name` keys) contain letters, digits, `_` and `-`, and are unique within "
      "their section. Nodes are shaft stations `\"<shaft>.<k>\"` or the names of `[[nodes]]`.\n"
      "- **DOFs** of a node are `ux`, `uy`, `uz` (translations) and `rx`, `ry`, `rz` "
      "(rotations) in the node's frame; for a shaft along z that is the global frame.\n"
      "- **Key paths** (`--set`, sweep `parameter`) are written like "
      "`shafts[0].elements[2].length`, `bearings[1].kxx`, `damping.rayleigh_beta`; the value "
      "is in the unit of the key.\n"
      "- **Alternatives**: where a table says \"give exactly one of (a) or (b, c)\", the keys "
      "of one group may be given and the others not; keys marked \"required (in its "
      "alternative)\" are needed when their group is used.\n\n";
  out += "## Top level\n\n" + root.help + "\n\n";
  std::vector<const Field*> top;
  for (const auto& f : root.fields) top.push_back(&f);
  field_table(out, root, top);
  for (const auto& s : root.sections) section_markdown(out, s, 2);
  while (out.size() >= 2 && out[out.size() - 1] == '\n' && out[out.size() - 2] == '\n')
    out.pop_back();
  return out;
}

}  // namespace geardyn::model
