// Reads a TOML model through the declaration table (schema.cpp), then resolves references and
// derived values (speed chains, disk geometry) and validates what needs the whole model.
//
// Two passes on purpose: the first only knows one table at a time (types, ranges, required keys,
// alternatives, per-table rules); the second knows every name, so references, duplicates and
// cycles are checked there. Both throw InputError at the first problem, pointing at the key.
#include "geardyn/model/parse.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include "geardyn/core/text.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/model/schema.hpp"

namespace geardyn::model {

// ---------------------------------------------------------------------------------------------
// ModelDocument

ModelDocument::ModelDocument() : root_(std::make_shared<toml::table>()), file_name_("<model>") {}

const Section& ModelDocument::schema() const {
  if (schema_ == nullptr) throw std::logic_error("ModelDocument: no declaration table");
  return *schema_;
}

ModelDocument::ModelDocument(std::shared_ptr<const toml::table> root, std::string file_name,
                             const Section& schema)
    : root_(std::move(root)), file_name_(std::move(file_name)), schema_(&schema) {}

const ModelDocument::Override* ModelDocument::find_override(std::string_view parent,
                                                            std::string_view key) const {
  for (const auto& o : overrides_)
    if (o.parent == parent && o.key == key) return &o;
  return nullptr;
}

bool ModelDocument::has_overrides_below(std::string_view parent) const {
  for (const auto& o : overrides_) {
    if (o.parent == parent) return true;
    if (o.parent.size() > parent.size() && o.parent.compare(0, parent.size(), parent) == 0 &&
        (o.parent[parent.size()] == '.' || o.parent[parent.size()] == '['))
      return true;
  }
  return false;
}

void ModelDocument::add_override(Override override_value) {
  for (auto& o : overrides_) {
    if (o.parent == override_value.parent && o.key == override_value.key) {
      o = std::move(override_value);
      return;
    }
  }
  overrides_.push_back(std::move(override_value));
}

std::string station_name(const std::string& shaft, int station) {
  return fmt::format("{}.{}", shaft, station);
}

namespace {

constexpr const char* kSetPrefix = "--set ";
constexpr const char* kSweepPrefix = "sweep value ";

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() && s.compare(0, prefix.size(), prefix) == 0;
}

std::string join_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : fmt::format("{}.{}", parent, key);
}

SourceLocation location_of(const toml::source_region& r, const SourceLocation& fallback) {
  if (!r.path) return fallback;
  if (starts_with(*r.path, kSetPrefix) || starts_with(*r.path, kSweepPrefix))
    return {*r.path, 0, 0};
  return {*r.path, static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)};
}

std::string number_text(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return fmt::format("{}", x);
}

std::string describe_found(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string:
      return fmt::format("the string \"{}\"", shorten(n.as_string()->get()));
    case toml::node_type::integer:
      return fmt::format("the integer {}", n.as_integer()->get());
    case toml::node_type::floating_point:
      return fmt::format("the number {}", number_text(n.as_floating_point()->get()));
    case toml::node_type::boolean:
      return fmt::format("the boolean {}", n.as_boolean()->get() ? "true" : "false");
    case toml::node_type::array: {
      const auto n_items = n.as_array()->size();
      if (n_items == 0) return "an empty array";
      return fmt::format("an array of {} entr{}", n_items, n_items == 1 ? "y" : "ies");
    }
    case toml::node_type::table:
      return "a table";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

}  // namespace

std::string quoted_list(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i)
    out += fmt::format("{}'{}'", i ? ", " : "", items[i]);
  return out;
}

/// "a sensor name", "an analysis name".
std::string a_name(const char* what) {
  const char c = what[0];
  const bool vowel = c == 'a' || c == 'e' || c == 'i' || c == 'o' || c == 'u';
  return fmt::format("{} {} name", vowel ? "an" : "a", what);
}

namespace {

std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates) {
  const std::string best = closest_match(word, candidates);
  return best.empty() ? std::string{} : fmt::format("did you mean '{}'?", best);
}

// ---------------------------------------------------------------------------------------------
// Defaults: every declared default is parsed once, as TOML, and then read like a value in a file.

class Defaults {
 public:
  /// The defaults of the declaration table `root`, parsed on first use (one set per table; the
  /// tables live as long as the program).
  static const Defaults& get(const Section& root) {
    static std::mutex mutex;
    static std::map<const Section*, std::unique_ptr<const Defaults>> cache;
    const std::lock_guard<std::mutex> lock(mutex);
    auto& d = cache[&root];
    if (!d) d.reset(new Defaults(root));
    return *d;
  }
  const toml::node* find(const Field& f) const {
    auto it = nodes_.find(&f);
    return it == nodes_.end() ? nullptr : it->second;
  }

 private:
  explicit Defaults(const Section& root) { collect(root); }
  void collect(const Section& s) {
    for (const auto& f : s.fields) {
      if (f.default_value.empty()) continue;
      auto t = std::make_unique<toml::table>(
          toml::parse("value = " + f.default_value, std::string_view("<schema default>")));
      nodes_[&f] = t->get("value");
      tables_.push_back(std::move(t));
    }
    for (const auto& sub : s.sections) collect(sub);
  }
  std::map<const Field*, const toml::node*> nodes_;
  std::vector<std::unique_ptr<toml::table>> tables_;
};

// ---------------------------------------------------------------------------------------------
// Key paths "a.b[3].c"

struct PathSegment {
  std::string name;
  std::optional<std::size_t> index;
};

std::optional<std::vector<PathSegment>> split_path(std::string_view path) {
  std::vector<PathSegment> out;
  std::size_t i = 0;
  while (i <= path.size()) {
    PathSegment seg;
    while (i < path.size() && path[i] != '.' && path[i] != '[') seg.name += path[i++];
    if (seg.name.empty()) return std::nullopt;
    if (i < path.size() && path[i] == '[') {
      const std::size_t close = path.find(']', i);
      if (close == std::string_view::npos || close == i + 1) return std::nullopt;
      std::size_t index = 0;
      const auto digits = path.substr(i + 1, close - i - 1);
      auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
      if (ec != std::errc() || ptr != digits.data() + digits.size()) return std::nullopt;
      seg.index = index;
      i = close + 1;
    }
    out.push_back(std::move(seg));
    if (i == path.size()) break;
    if (path[i] != '.') return std::nullopt;
    ++i;
    if (i == path.size()) return std::nullopt;
  }
  return out;
}

std::string segment_text(const PathSegment& s) {
  return s.index ? fmt::format("{}[{}]", s.name, *s.index) : s.name;
}

std::string variant_phrase(const Section& s, std::string_view variant) {
  if (variant.empty()) return s.title;
  return fmt::format("{} with {} = \"{}\"", s.title, s.discriminator, variant);
}

/// The variants of `s` in which `key` is allowed (for "belongs to another type" hints).
std::vector<std::string> variants_with_key(const Section& s, std::string_view key) {
  std::vector<std::string> out;
  for (const auto& v : s.variants)
    if (s.find_field(key, v.name) || s.find_section(key, v.name)) out.push_back(v.name);
  return out;
}

[[noreturn]] void unknown_key(const Section& s, std::string_view variant, std::string_view key,
                              const std::string& path, const SourceLocation& where) {
  std::string hint;
  std::string expected = fmt::format("a key of {}", variant_phrase(s, variant));
  const auto others = variants_with_key(s, key);
  if (!variant.empty() && !others.empty()) {
    std::string list;
    for (std::size_t i = 0; i < others.size(); ++i)
      list +=
          fmt::format("{}\"{}\"", i ? (i + 1 == others.size() ? " and " : ", ") : "", others[i]);
    hint = fmt::format("'{}' is a key of {} = {} only", key, s.discriminator, list);
    // A key of another variant (a law parameter of another law type): the keys this one takes.
    expected += fmt::format(": {}", quoted_list(s.key_names(variant)));
  } else {
    hint = did_you_mean(key, s.key_names(variant));
    if (hint.empty()) hint = fmt::format("allowed keys: {}", quoted_list(s.key_names(variant)));
  }
  throw InputError(where, path, expected, fmt::format("the unknown key '{}'", key), hint);
}

/// Reads the variant (discriminator value) of the table at `parent`, through the overrides.
std::string variant_of(const ModelDocument& doc, const Section& s, const toml::table* table,
                       const std::string& parent) {
  if (s.discriminator.empty()) return {};
  const toml::node* n = nullptr;
  if (const auto* o = doc.find_override(parent, s.discriminator))
    n = o->value.get();
  else if (table)
    n = table->get(s.discriminator);
  if (!n) {
    const Field* d = s.find_field(s.discriminator, "");
    if (const toml::node* def = Defaults::get(doc.schema()).find(*d)) n = def;
  }
  if (n && n->is_string() && s.find_variant(n->as_string()->get())) return n->as_string()->get();
  return {};
}

struct ResolvedKey {
  const Field* field = nullptr;
  std::string parent;  ///< canonical path of the table
  std::string key;
};

/// Checks a key path against the schema and the document: every table must exist (array
/// indices in range), the last segment must be a key allowed in that table.
ResolvedKey resolve_key(const ModelDocument& doc, std::string_view path,
                        const SourceLocation& where) {
  const auto segments = split_path(path);
  if (!segments)
    throw InputError(where, std::string(path),
                     "a key path like shafts[0].elements[2].length or bearings[1].kxx",
                     fmt::format("'{}'", path));
  const Section* section = &doc.schema();
  const toml::table* table = &doc.table();
  std::string parent;
  for (std::size_t i = 0; i + 1 < segments->size(); ++i) {
    const PathSegment& seg = (*segments)[i];
    const std::string variant = variant_of(doc, *section, table, parent);
    const Section* sub = section->find_section(seg.name, variant);
    const std::string here = join_path(parent, segment_text(seg));
    if (!sub) {
      if (section->find_field(seg.name, variant))
        throw InputError(where, here, "a table name before the '.'",
                         fmt::format("'{}', which is a key, not a table", seg.name));
      unknown_key(*section, variant, seg.name, here, where);
    }
    const toml::node* node = table ? table->get(seg.name) : nullptr;
    if (sub->kind == SectionKind::ArrayOfTables) {
      if (!seg.index)
        throw InputError(where, here,
                         fmt::format("an index: {}[0], {}[1], ...", seg.name, seg.name),
                         fmt::format("'{}' without an index", seg.name));
      const toml::array* items = node ? node->as_array() : nullptr;
      const std::size_t n_items = items ? items->size() : 0;
      if (*seg.index >= n_items)
        throw InputError(
            where, here,
            n_items == 0 ? fmt::format("an existing {} table (the model has none)", sub->title)
                         : fmt::format("an index from 0 to {} (the model has {} {} "
                                       "table{})",
                                       n_items - 1, n_items, sub->title, n_items == 1 ? "" : "s"),
            fmt::format("index {}", *seg.index));
      table = (*items)[*seg.index].as_table();
      if (!table)
        throw InputError(where, here, fmt::format("a {} table", sub->title),
                         describe_found((*items)[*seg.index]));
    } else {
      if (seg.index)
        throw InputError(
            where, here,
            fmt::format("'{}' without an index ({} is one table)", seg.name, sub->title),
            fmt::format("'{}'", segment_text(seg)));
      table = node ? node->as_table() : nullptr;
    }
    parent = here;
    section = sub;
  }
  const PathSegment& last = segments->back();
  const std::string variant = variant_of(doc, *section, table, parent);
  const std::string full = join_path(parent, segment_text(last));
  if (last.index)
    throw InputError(where, full,
                     "a key path that ends with a key (set whole arrays: "
                     "key=[1, 2, 3])",
                     fmt::format("'{}'", segment_text(last)));
  const Field* field = section->find_field(last.name, variant);
  if (!field) {
    if (section->find_section(last.name, variant))
      throw InputError(where, full, "a key with a value",
                       fmt::format("'{}', which is a table", last.name));
    unknown_key(*section, variant, last.name, full, where);
  }
  return {field, parent, last.name};
}

// ---------------------------------------------------------------------------------------------
// Reading tables through the schema

struct Entry {
  std::string key;
  const toml::node* node = nullptr;
  SourceLocation key_where;
  SourceLocation value_where;
};

struct ChoiceState;

class Reader {
 public:
  explicit Reader(const ModelDocument& doc) : doc_(doc), file_{doc.file_name(), 0, 0} {}

  const ModelDocument& doc() const { return doc_; }

  SourceLocation loc(const toml::node& n, const SourceLocation& fallback) const {
    return location_of(n.source(), fallback);
  }

  /// Where a key path is written: the override, the value in the file, or the closest
  /// enclosing table that exists.
  SourceLocation locate(const std::string& path) const {
    const auto dot = path.rfind('.');
    const std::string parent = dot == std::string::npos ? std::string{} : path.substr(0, dot);
    const std::string key = dot == std::string::npos ? path : path.substr(dot + 1);
    if (const auto* o = doc_.find_override(parent, key)) return {o->origin, 0, 0};
    std::string p = path;
    while (!p.empty()) {
      auto view = toml::at_path(doc_.table(), p);
      if (view.node()) return loc(*view.node(), file_);
      const auto cut = p.find_last_of(".[");
      if (cut == std::string::npos) break;
      p = p.substr(0, cut);
    }
    return {doc_.file_name(), 1, 1};
  }

  void read_table(const Section& s, const toml::table* table, const std::string& path,
                  const SourceLocation& where, void* object) const;

 private:
  std::vector<Entry> entries(const toml::table* table, const std::string& path) const;
  FieldValue convert(const Field& f, const toml::node& n, const std::string& path,
                     const SourceLocation& where) const;
  double read_number(const Field& f, const toml::node& n, const std::string& path,
                     const SourceLocation& where) const;
  void check_range(const Field& f, double x, const std::string& path,
                   const SourceLocation& where) const;
  void read_matrix(const Field& f, const toml::node& n, const std::string& path,
                   const SourceLocation& where, FieldValue& v) const;
  void read_section(const Section& sub, const Entry* entry, const std::string& path,
                    const SourceLocation& parent_where, void* parent) const;
  std::string read_discriminator(const Section& s, const std::vector<Entry>& all,
                                 const std::string& path, const SourceLocation& where,
                                 TableContext& ctx) const;
  void add_defaults(const Section& s, const std::string& variant,
                    const std::vector<ChoiceState>& states, const std::string& path,
                    const SourceLocation& where, TableContext& ctx) const;

  const ModelDocument& doc_;
  SourceLocation file_;
};

std::vector<Entry> Reader::entries(const toml::table* table, const std::string& path) const {
  std::vector<Entry> out;
  if (table) {
    for (auto&& [k, v] : *table) {
      Entry e;
      e.key = std::string(k.str());
      e.node = &v;
      e.key_where = location_of(k.source(), file_);
      e.value_where = loc(v, e.key_where);
      out.push_back(std::move(e));
    }
    // toml++ keeps keys sorted by name; report problems in the order they are written.
    std::stable_sort(out.begin(), out.end(), [](const Entry& a, const Entry& b) {
      return std::tie(a.key_where.line, a.key_where.column) <
             std::tie(b.key_where.line, b.key_where.column);
    });
  }
  for (const auto& o : doc_.overrides()) {
    if (o.parent != path) continue;
    const SourceLocation origin{o.origin, 0, 0};
    auto it = std::find_if(out.begin(), out.end(), [&](const Entry& e) { return e.key == o.key; });
    if (it == out.end()) it = out.insert(out.end(), Entry{o.key, nullptr, origin, origin});
    it->node = o.value.get();
    it->key_where = origin;
    it->value_where = origin;
  }
  return out;
}

void Reader::check_range(const Field& f, double x, const std::string& path,
                         const SourceLocation& where) const {
  bool ok = !std::isnan(x) && (f.allow_infinity || !std::isinf(x));
  const Range& r = f.range;
  if (ok && r.min) ok = r.min_exclusive ? x > *r.min : x >= *r.min;
  if (ok && r.max) ok = r.max_exclusive ? x < *r.max : x <= *r.max;
  if (!ok) {
    std::string expected = f.type == FieldType::Integer ? "an integer"
                           : f.allow_infinity           ? "a number"
                                                        : "a finite number";
    const std::string range = describe_range(f);
    if (!range.empty()) expected += " " + range;
    if (f.unit.symbol[0] != '\0') expected += fmt::format(" [{}]", f.unit.symbol);
    throw InputError(where, path, expected, number_text(x));
  }
}

double Reader::read_number(const Field& f, const toml::node& n, const std::string& path,
                           const SourceLocation& where) const {
  if (const auto* i = n.as_integer()) {
    const double x = static_cast<double>(i->get());
    check_range(f, x, path, where);
    return x;
  }
  if (const auto* d = n.as_floating_point()) {
    check_range(f, d->get(), path, where);
    return d->get();
  }
  throw InputError(where, path, describe_type(f), describe_found(n));
}

void Reader::read_matrix(const Field& f, const toml::node& n, const std::string& path,
                         const SourceLocation& where, FieldValue& v) const {
  const toml::array* outer = n.as_array();
  if (!outer || outer->empty()) throw InputError(where, path, describe_type(f), describe_found(n));
  // A table of matrices when the first entry is itself an array of arrays.
  const toml::array* first = (*outer)[0].as_array();
  const bool table = first && !first->empty() && (*first)[0].is_array();
  if (table && !f.tabulated)
    throw InputError(where, path, describe_type(f), "an array of matrices");
  std::vector<const toml::array*> matrices;
  if (table) {
    for (std::size_t k = 0; k < outer->size(); ++k) {
      const toml::array* m = (*outer)[k].as_array();
      if (!m)
        throw InputError(loc((*outer)[k], where), fmt::format("{}[{}]", path, k),
                         "a matrix (an array of rows)", describe_found((*outer)[k]));
      matrices.push_back(m);
    }
  } else {
    matrices.push_back(outer);
  }
  const int n_rows = static_cast<int>(table ? first->size() : outer->size());
  if (std::find(f.matrix_sizes.begin(), f.matrix_sizes.end(), n_rows) == f.matrix_sizes.end())
    throw InputError(where, path, describe_type(f),
                     fmt::format("{} row{}", n_rows, n_rows == 1 ? "" : "s"));
  for (std::size_t k = 0; k < matrices.size(); ++k) {
    const toml::array& m = *matrices[k];
    const std::string mpath = table ? fmt::format("{}[{}]", path, k) : path;
    if (static_cast<int>(m.size()) != n_rows)
      throw InputError(where, mpath, fmt::format("{0} rows, like the first matrix", n_rows),
                       fmt::format("{} rows", m.size()));
    for (std::size_t i = 0; i < m.size(); ++i) {
      const std::string rpath = fmt::format("{}[{}]", mpath, i);
      const toml::array* row = m[i].as_array();
      const SourceLocation rwhere = loc(m[i], where);
      if (!row || static_cast<int>(row->size()) != n_rows)
        throw InputError(rwhere, rpath, fmt::format("a row of {} numbers", n_rows),
                         describe_found(m[i]));
      for (std::size_t j = 0; j < row->size(); ++j)
        v.numbers.push_back(
            read_number(f, (*row)[j], fmt::format("{}[{}]", rpath, j), loc((*row)[j], rwhere)));
    }
  }
  v.rows = n_rows;
  v.count = matrices.size();
  v.is_array = table;
}

FieldValue Reader::convert(const Field& f, const toml::node& n, const std::string& path,
                           const SourceLocation& where) const {
  FieldValue v;
  v.given = true;
  v.where = where;
  v.path = path;
  auto wrong_type = [&]() { return InputError(where, path, describe_type(f), describe_found(n)); };
  auto element = [&](const toml::array& a, std::size_t i) {
    return std::pair{fmt::format("{}[{}]", path, i), loc(a[i], where)};
  };
  switch (f.type) {
    case FieldType::Number:
      v.number = read_number(f, n, path, where) * f.unit.to_si;
      break;
    case FieldType::Integer: {
      if (const auto* d = n.as_floating_point()) {
        throw InputError(
            where, path, describe_type(f), describe_found(n),
            d->get() == std::floor(d->get()) ? "write it without a decimal point" : "");
      }
      if (!n.is_integer()) throw wrong_type();
      check_range(f, static_cast<double>(n.as_integer()->get()), path, where);
      v.integer = n.as_integer()->get();
      v.number = static_cast<double>(v.integer);
      break;
    }
    case FieldType::Boolean:
      if (!n.is_boolean()) throw wrong_type();
      v.boolean = n.as_boolean()->get();
      break;
    case FieldType::String: {
      if (!n.is_string()) throw wrong_type();
      v.text = n.as_string()->get();
      if ((f.identifier || f.ref != Ref::None) && v.text.empty())
        throw InputError(where, path, describe_type(f), "an empty string");
      if (f.identifier) {
        for (char c : v.text) {
          const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
          if (!ok)
            throw InputError(where, path, describe_type(f), describe_found(n),
                             fmt::format("the character '{}' is not allowed in names", c));
        }
      }
      break;
    }
    case FieldType::Enum: {
      if (!n.is_string()) throw wrong_type();
      v.text = n.as_string()->get();
      auto it = std::find(f.choices.begin(), f.choices.end(), v.text);
      if (it == f.choices.end())
        throw InputError(where, path, describe_type(f), describe_found(n),
                         did_you_mean(v.text, f.choices));
      v.choice = static_cast<int>(it - f.choices.begin());
      break;
    }
    case FieldType::NumberOrArray:
    case FieldType::NumberArray: {
      if (f.type == FieldType::NumberOrArray && n.is_number()) {
        v.number = read_number(f, n, path, where) * f.unit.to_si;
        v.count = 1;
        break;
      }
      const toml::array* a = n.as_array();
      if (!a) throw wrong_type();
      if (a->size() < std::max<std::size_t>(f.min_items, f.type == FieldType::NumberOrArray))
        throw InputError(where, path,
                         fmt::format("at least {} value{}", std::max<std::size_t>(f.min_items, 1),
                                     std::max<std::size_t>(f.min_items, 1) == 1 ? "" : "s"),
                         describe_found(n));
      for (std::size_t i = 0; i < a->size(); ++i) {
        auto [epath, ewhere] = element(*a, i);
        const double x = read_number(f, (*a)[i], epath, ewhere);
        if (f.increasing && !v.numbers.empty() && x * f.unit.to_si <= v.numbers.back())
          throw InputError(ewhere, epath,
                           fmt::format("a value > the previous one, {} (values must increase)",
                                       number_text(v.numbers.back() / f.unit.to_si)),
                           number_text(x));
        v.numbers.push_back(x * f.unit.to_si);
      }
      v.is_array = true;
      v.count = v.numbers.size();
      break;
    }
    case FieldType::Vector3: {
      const toml::array* a = n.as_array();
      if (!a || a->size() != 3) throw wrong_type();
      for (std::size_t i = 0; i < 3; ++i) {
        auto [epath, ewhere] = element(*a, i);
        v.numbers.push_back(read_number(f, (*a)[i], epath, ewhere) * f.unit.to_si);
      }
      if (f.nonzero && v.numbers[0] == 0.0 && v.numbers[1] == 0.0 && v.numbers[2] == 0.0)
        throw InputError(where, path, describe_type(f), "[0, 0, 0]");
      break;
    }
    case FieldType::StringArray:
    case FieldType::DofList: {
      if (f.type == FieldType::DofList && n.is_string()) {
        if (n.as_string()->get() != "all") throw wrong_type();
        for (int i = 0; i < static_cast<int>(f.choices.size()); ++i) v.indices.push_back(i);
        break;
      }
      const toml::array* a = n.as_array();
      if (!a) throw wrong_type();
      const std::size_t min_items = f.type == FieldType::DofList ? 1 : f.min_items;
      if (a->size() < min_items)
        throw InputError(where, path,
                         fmt::format("at least {} name{}", min_items, min_items == 1 ? "" : "s"),
                         describe_found(n));
      for (std::size_t i = 0; i < a->size(); ++i) {
        auto [epath, ewhere] = element(*a, i);
        const toml::node& e = (*a)[i];
        if (!e.is_string() || e.as_string()->get().empty())
          throw InputError(ewhere, epath, "a non-empty string", describe_found(e));
        const std::string s = e.as_string()->get();
        if (!f.choices.empty()) {
          auto it = std::find(f.choices.begin(), f.choices.end(), s);
          if (it == f.choices.end())
            throw InputError(ewhere, epath, describe_type(f), describe_found(e),
                             did_you_mean(s, f.choices));
          v.indices.push_back(static_cast<int>(it - f.choices.begin()));
        }
        if ((f.unique || f.type == FieldType::DofList) &&
            std::find(v.strings.begin(), v.strings.end(), s) != v.strings.end())
          throw InputError(ewhere, epath, "each name once", fmt::format("\"{}\" again", s));
        v.strings.push_back(s);
      }
      break;
    }
    case FieldType::Matrix:
      read_matrix(f, n, path, where, v);
      for (auto& x : v.numbers) x *= f.unit.to_si;
      break;
  }
  return v;
}

/// Which keys of a Choice are in play: the alternatives given, or none.
struct ChoiceState {
  const Choice* choice;
  std::vector<std::size_t> given;  ///< indices of alternatives with at least one key given
};

bool in_alternative(const std::vector<std::string>& alt, std::string_view key) {
  return std::find(alt.begin(), alt.end(), key) != alt.end();
}

std::string alternatives_phrase(const Choice& c) {
  std::string out;
  for (std::size_t i = 0; i < c.alternatives.size(); ++i) {
    if (i) out += " or ";
    std::string keys;
    for (std::size_t j = 0; j < c.alternatives[i].size(); ++j)
      keys += fmt::format("{}{}", j ? ", " : "", c.alternatives[i][j]);
    out += c.alternatives[i].size() == 1 ? keys : "(" + keys + ")";
  }
  return out;
}

// The alternatives of s in play for the variant, with the one given (at most one each).
std::vector<ChoiceState> choice_states(const Section& s, const std::string& variant,
                                       const TableContext& ctx, const std::string& path,
                                       const SourceLocation& where) {
  std::vector<ChoiceState> states;
  for (const auto& c : s.choices) {
    if (!c.only_in.empty() &&
        std::find(c.only_in.begin(), c.only_in.end(), variant) == c.only_in.end())
      continue;
    ChoiceState st{&c, {}};
    std::vector<std::string> first_given;
    for (std::size_t i = 0; i < c.alternatives.size(); ++i) {
      for (const auto& key : c.alternatives[i]) {
        if (ctx.has(key)) {
          st.given.push_back(i);
          first_given.push_back(key);
          break;
        }
      }
    }
    if (st.given.size() > 1)
      throw InputError(ctx.where_of(first_given[1]), join_path(path, first_given[1]),
                       fmt::format("only one of {}", alternatives_phrase(c)),
                       fmt::format("both '{}' and '{}'", first_given[0], first_given[1]));
    if (st.given.empty() && c.required)
      throw InputError(where, path.empty() ? s.title : path,
                       fmt::format("one of {} in this {} table", alternatives_phrase(c),
                                   variant_phrase(s, variant)),
                       "none of them");
    states.push_back(std::move(st));
  }
  return states;
}

// Arrays tabulated against another key (bearing coefficients against speed_rpm): as many values
// as that key has.
void check_tabulated(const Section& s, const std::string& variant, const TableContext& ctx) {
  for (const auto& [key, v] : ctx.values) {
    const Field* f = s.find_field(key, variant);
    if (!f || f->tabulated_by.empty() || !v.is_array) continue;
    if (!ctx.has(f->tabulated_by))
      throw InputError(v.where, v.path,
                       fmt::format("a single value, since there is no '{}' to tabulate against",
                                   f->tabulated_by),
                       fmt::format("{} value{}", v.count, v.count == 1 ? "" : "s"),
                       fmt::format("give '{}' = [...] with one speed per value", f->tabulated_by));
    const std::size_t n = ctx.at(f->tabulated_by).count;
    if (v.count != n)
      throw InputError(
          v.where, v.path,
          fmt::format("{} value{}, one per '{}' entry", n, n == 1 ? "" : "s", f->tabulated_by),
          fmt::format("{} value{}", v.count, v.count == 1 ? "" : "s"));
  }
}

// The discriminator decides which keys are allowed, so it is read first. Returns the variant
// ("" when s has no discriminator).
std::string Reader::read_discriminator(const Section& s, const std::vector<Entry>& all,
                                       const std::string& path, const SourceLocation& where,
                                       TableContext& ctx) const {
  std::string variant;
  if (!s.discriminator.empty()) {
    const Field& d = *s.find_field(s.discriminator, "");
    const std::string dpath = join_path(path, d.name);
    auto it = std::find_if(all.begin(), all.end(), [&](const Entry& e) { return e.key == d.name; });
    if (it != all.end()) {
      ctx.values[d.name] = convert(d, *it->node, dpath, it->value_where);
    } else if (const toml::node* def = Defaults::get(doc_.schema()).find(d)) {
      ctx.values[d.name] = convert(d, *def, dpath, where);
      ctx.values[d.name].given = false;
    } else {
      throw InputError(where, dpath, fmt::format("the key '{}' ({})", d.name, describe_type(d)),
                       fmt::format("a {} table without it", s.title));
    }
    variant = ctx.values[d.name].text;
  }
  return variant;
}

// Required keys and defaults of the keys not given.
void Reader::add_defaults(const Section& s, const std::string& variant,
                          const std::vector<ChoiceState>& states, const std::string& path,
                          const SourceLocation& where, TableContext& ctx) const {
  // A key in an alternative is required only when its alternative is used, and takes its
  // default only when no other alternative is used.
  auto alternative_status = [&](std::string_view key) -> int {  // 1 used, -1 other used, 0 n/a
    for (const auto& st : states)
      for (std::size_t i = 0; i < st.choice->alternatives.size(); ++i)
        if (in_alternative(st.choice->alternatives[i], key)) {
          if (st.given.empty()) return 0;
          return st.given[0] == i ? 1 : -1;
        }
    return 0;
  };
  auto in_any_alternative = [&](std::string_view key) {
    for (const auto& st : states)
      for (const auto& alt : st.choice->alternatives)
        if (in_alternative(alt, key)) return true;
    return false;
  };

  for (const auto& f : s.fields) {
    if (!f.only_in.empty() &&
        std::find(f.only_in.begin(), f.only_in.end(), variant) == f.only_in.end())
      continue;
    if (ctx.values.count(f.name)) continue;
    const int status = alternative_status(f.name);
    if (f.required && (!in_any_alternative(f.name) || status == 1)) {
      std::string found = fmt::format("a {} table without it", variant_phrase(s, variant));
      if (status == 1) {
        for (const auto& st : states)
          for (const auto& key : st.choice->alternatives[st.given.empty() ? 0 : st.given[0]])
            if (ctx.has(key) && in_alternative(st.choice->alternatives[st.given[0]], f.name)) {
              found = fmt::format("'{}' without '{}'", key, f.name);
              break;
            }
      }
      throw InputError(where, join_path(path, f.name),
                       fmt::format("the key '{}' ({})", f.name, describe_type(f)), found);
    }
    if (status == -1) continue;
    if (f.default_from_path) {
      FieldValue v;
      v.where = where;
      v.path = join_path(path, f.name);
      v.text = path;
      ctx.values[f.name] = std::move(v);
    } else if (const toml::node* def = Defaults::get(doc_.schema()).find(f)) {
      FieldValue v = convert(f, *def, join_path(path, f.name), where);
      v.given = false;
      ctx.values[f.name] = std::move(v);
    }
  }
}

void Reader::read_table(const Section& s, const toml::table* table, const std::string& path,
                        const SourceLocation& where, void* object) const {
  const std::vector<Entry> all = entries(table, path);
  TableContext ctx;
  ctx.path = path;
  ctx.section = s.title;
  ctx.where = where;

  const std::string variant = read_discriminator(s, all, path, where, ctx);

  std::vector<std::pair<const Section*, const Entry*>> subsections;
  for (const Entry& e : all) {
    if (e.key == s.discriminator) continue;
    const std::string kpath = join_path(path, e.key);
    if (const Field* f = s.find_field(e.key, variant)) {
      ctx.values[e.key] = convert(*f, *e.node, kpath, e.value_where);
    } else if (const Section* sub = s.find_section(e.key, variant)) {
      subsections.emplace_back(sub, &e);
    } else {
      unknown_key(s, variant, e.key, kpath, e.key_where);
    }
  }

  const std::vector<ChoiceState> states = choice_states(s, variant, ctx, path, where);
  add_defaults(s, variant, states, path, where, ctx);

  check_tabulated(s, variant, ctx);

  // Store: the discriminator first (it prepares variant settings), then in declaration order.
  if (!s.discriminator.empty()) {
    const Field& d = *s.find_field(s.discriminator, "");
    if (d.setter) d.setter(object, ctx.at(d.name));
  }
  for (const auto& f : s.fields) {
    if (f.name == s.discriminator || !f.setter) continue;
    if (!f.only_in.empty() &&
        std::find(f.only_in.begin(), f.only_in.end(), variant) == f.only_in.end())
      continue;
    auto it = ctx.values.find(f.name);
    if (it != ctx.values.end()) f.setter(object, it->second);
  }
  if (s.locate) s.locate(object, where);

  for (const auto& sub : s.sections) {
    if (!sub.only_in.empty() &&
        std::find(sub.only_in.begin(), sub.only_in.end(), variant) == sub.only_in.end())
      continue;
    const Entry* entry = nullptr;
    for (const auto& [sec, e] : subsections)
      if (sec == &sub) entry = e;
    read_section(sub, entry, join_path(path, sub.name), where, object);
  }

  if (!variant.empty()) {
    const Variant* v = s.find_variant(variant);
    if (v && v->finish) v->finish(object, ctx);
  }
  if (s.finish) s.finish(object, ctx);
}

void Reader::read_section(const Section& sub, const Entry* entry, const std::string& path,
                          const SourceLocation& parent_where, void* parent) const {
  if (sub.kind == SectionKind::Table) {
    const toml::table* t = nullptr;
    SourceLocation where = parent_where;
    if (entry) {
      t = entry->node->as_table();
      if (!t)
        throw InputError(entry->value_where, path, fmt::format("a table ({})", sub.title),
                         describe_found(*entry->node));
      where = entry->value_where;
    }
    // An optional table that is neither written nor given by an override makes no object.
    if (!entry && sub.optional && !doc_.has_overrides_below(path)) return;
    // Read even when absent, so that the declared defaults are what the model gets.
    read_table(sub, t, path, where, sub.child(parent));
    return;
  }
  if (!entry) {
    if (sub.required)
      throw InputError(parent_where, path,
                       fmt::format("at least {} {} table{}", sub.min_count, sub.title,
                                   sub.min_count == 1 ? "" : "s"),
                       "none");
    return;
  }
  const toml::array* items = entry->node->as_array();
  if (!items)
    throw InputError(entry->value_where, path,
                     fmt::format("an array of tables ({} headers)", sub.title),
                     describe_found(*entry->node));
  if (items->size() < sub.min_count)
    throw InputError(entry->value_where, path,
                     fmt::format("at least {} {} table{}", sub.min_count, sub.title,
                                 sub.min_count == 1 ? "" : "s"),
                     describe_found(*entry->node));
  for (std::size_t i = 0; i < items->size(); ++i) {
    const std::string ipath = fmt::format("{}[{}]", path, i);
    const toml::node& item = (*items)[i];
    const SourceLocation iwhere = loc(item, entry->value_where);
    const toml::table* t = item.as_table();
    if (!t)
      throw InputError(iwhere, ipath, fmt::format("a table ({})", sub.title), describe_found(item));
    read_table(sub, t, ipath, iwhere, sub.child(parent));
  }
}

// ---------------------------------------------------------------------------------------------
// Resolution and whole-model checks

struct NodeInfo {
  int shaft = -1;
  Vec3 position{};
};

class Resolver final : public ModelCheck {
 public:
  Resolver(Model& model, const Reader& reader) : m_(model), r_(reader) {}

  void run();

  // ModelCheck
  const Model& model() const override { return m_; }
  const ModelDocument& document() const override { return r_.doc(); }
  [[noreturn]] void fail(const std::string& path, std::string expected, std::string found,
                         std::string hint = {}) const override {
    throw InputError(r_.locate(path), path, std::move(expected), std::move(found), std::move(hint));
  }
  bool given(const std::string& path) const override;
  SourceLocation locate(const std::string& path) const override { return r_.locate(path); }
  void check_named(const std::string& path, const std::vector<std::string>& names,
                   const std::set<std::string>& known, const char* what,
                   const char* section) const override;
  void check_name(const std::string& path, const std::string& name,
                  const std::set<std::string>& known, const char* what,
                  const char* section) const override;
  void check_node(const std::string& path, const std::string& name) const override {
    (void)node_info(path, name);
  }

 private:
  template <class T>
  void check_unique(const std::vector<T>& items, const char* section) const;
  void build_nodes();
  NodeInfo node_info(const std::string& path, const std::string& name) const;
  void check_material(const std::string& path, const std::string& name) const;
  /// A material whose density must be > 0 (a disk from geometry, a solid): its whole mass
  /// comes from it.
  void check_massive(const std::string& path, const std::string& name, const char* what) const;
  void resolve_speeds();
  void resolve_disks();
  void check_connections();
  void check_damping();
  void check_analyses();
  // The nonlinear drivetrain (drivetrain_spec.hpp): its nodes, DOFs and gear pairs.
  void check_drivetrain();
  void check_nonlinear_elements() const;
  void check_element_ends(const std::string& path, const std::string& node1,
                          const std::string& node2, const char* key1, const char* key2) const;
  void check_bolt_bodies() const;
  void check_rz_free(const std::string& path, const std::string& node, const char* what) const;
  void check_drivers_and_loads() const;
  void check_analysis_overrides(const std::string& base, const Analysis& analysis) const;

  Model& m_;
  const Reader& r_;
  std::map<std::string, NodeInfo> nodes_;  ///< free nodes by name
  std::map<std::string, int> shaft_index_;
  std::vector<int> shaft_stations_;
};

template <class T>
void Resolver::check_unique(const std::vector<T>& items, const char* section) const {
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < items.size(); ++i) {
    auto [it, inserted] = seen.emplace(items[i].name, i);
    if (!inserted) {
      const SourceLocation first = r_.locate(fmt::format("{}[{}]", section, it->second));
      fail(fmt::format("{}[{}].name", section, i),
           fmt::format("a name not used by another of [[{}]]", section),
           fmt::format("\"{}\", already the name of {}[{}]", items[i].name, section, it->second),
           first.line > 0 ? fmt::format("first defined at {}:{}", first.file, first.line) : "");
    }
  }
}

void Resolver::build_nodes() {
  for (std::size_t i = 0; i < m_.shafts.size(); ++i) {
    int stations = 1;
    for (const auto& e : m_.shafts[i].elements) stations += e.divisions;
    shaft_index_[m_.shafts[i].name] = static_cast<int>(i);
    shaft_stations_.push_back(stations);
  }
  for (const auto& n : m_.nodes) nodes_[n.name] = NodeInfo{-1, n.position};
  // A model of record analyses only (order analysis of a measurement) needs no structure.
  const bool records_only =
      !m_.analyses.empty() &&
      std::all_of(m_.analyses.begin(), m_.analyses.end(),
                  [](const Analysis& a) { return a.type == "order_analysis"; });
  if (m_.shafts.empty() && m_.nodes.empty() && m_.solids.empty() && m_.gear_pairs.empty() &&
      !records_only)
    throw InputError({r_.doc().file_name(), 1, 1}, "shafts",
                     "a model with at least one [[shafts]], [[nodes]], [[solids]] or "
                     "[[gear_pairs]] table",
                     "no nodes, no solids and no gear pairs");
}

NodeInfo Resolver::node_info(const std::string& path, const std::string& name) const {
  NodeInfo station;
  const auto dot = name.rfind('.');
  if (dot != std::string::npos) {
    const std::string shaft = name.substr(0, dot);
    const std::string k_text = name.substr(dot + 1);
    auto it = shaft_index_.find(shaft);
    if (it == shaft_index_.end()) {
      std::vector<std::string> shafts;
      for (const auto& [n, i] : shaft_index_) shafts.push_back(n);
      fail(path, "a node: \"<shaft>.<k>\" of an existing shaft, or a [[nodes]] name",
           fmt::format("\"{}\", but there is no shaft '{}'", name, shaft),
           did_you_mean(shaft, shafts));
    }
    const int n_stations = shaft_stations_[static_cast<std::size_t>(it->second)];
    int k = -1;
    auto [ptr, ec] = std::from_chars(k_text.data(), k_text.data() + k_text.size(), k);
    if (ec != std::errc() || ptr != k_text.data() + k_text.size() || k < 0 || k >= n_stations)
      fail(path,
           fmt::format("a station of shaft '{}': \"{}.0\" to \"{}.{}\"", shaft, shaft, shaft,
                       n_stations - 1),
           fmt::format("\"{}\"", name));
    const Shaft& s = m_.shafts[static_cast<std::size_t>(it->second)];
    double z = 0.0;
    int station_index = 0;
    for (const auto& e : s.elements) {
      for (int d = 0; d < e.divisions && station_index < k; ++d, ++station_index)
        z += e.length / e.divisions;
    }
    station.shaft = it->second;
    for (int c = 0; c < 3; ++c)
      station.position[static_cast<std::size_t>(c)] =
          s.origin[static_cast<std::size_t>(c)] + z * s.axis[static_cast<std::size_t>(c)];
    return station;
  }
  auto it = nodes_.find(name);
  if (it == nodes_.end()) {
    std::vector<std::string> candidates;
    for (const auto& [n, info] : nodes_) candidates.push_back(n);
    for (const auto& [n, i] : shaft_index_) candidates.push_back(n + ".0");
    std::string hint = did_you_mean(name, candidates);
    if (hint.empty() && shaft_index_.count(name))
      hint = fmt::format("shaft nodes are named \"{}.<k>\", e.g. \"{}.0\"", name, name);
    fail(path, "a node: \"<shaft>.<k>\" of an existing shaft, or a [[nodes]] name",
         fmt::format("\"{}\"", name), hint);
  }
  return it->second;
}

void Resolver::check_material(const std::string& path, const std::string& name) const {
  if (m_.find_material(name)) return;
  std::vector<std::string> names;
  for (const auto& mat : m_.materials) names.push_back(mat.name);
  fail(path,
       m_.materials.empty() ? "a material name, but there is no [[materials]] table"
                            : fmt::format("a material name ({})", quoted_list(names)),
       fmt::format("\"{}\"", name), did_you_mean(name, names));
}

void Resolver::check_massive(const std::string& path, const std::string& name,
                             const char* what) const {
  const Material* m = m_.find_material(name);
  if (m == nullptr || m->density > 0.0) return;
  fail(path, fmt::format("a material with a density > 0 ({} takes its whole mass from it)", what),
       fmt::format("\"{}\" with density = {} kg/m^3", name, m->density),
       fmt::format("give the material \"{}\" its density, or use another material here (a "
                   "density of 0 is meant for massless shafts)",
                   name));
}

void Resolver::check_name(const std::string& path, const std::string& name,
                          const std::set<std::string>& known, const char* what,
                          const char* section) const {
  if (known.count(name)) return;
  std::vector<std::string> candidates(known.begin(), known.end());
  fail(path,
       known.empty() ? fmt::format("{}, but there is no [[{}]] table", a_name(what), section)
                     : fmt::format("{} ({})", a_name(what), quoted_list(candidates)),
       fmt::format("\"{}\"", name), did_you_mean(name, candidates));
}

void Resolver::check_named(const std::string& path, const std::vector<std::string>& names,
                           const std::set<std::string>& known, const char* what,
                           const char* section) const {
  for (std::size_t i = 0; i < names.size(); ++i)
    check_name(fmt::format("{}[{}]", path, i), names[i], known, what, section);
}

bool Resolver::given(const std::string& path) const {
  const auto dot = path.rfind('.');
  if (dot != std::string::npos && r_.doc().find_override(path.substr(0, dot), path.substr(dot + 1)))
    return true;
  return static_cast<bool>(toml::at_path(r_.doc().table(), path));
}

void Resolver::resolve_speeds() {
  // speed_ratio of a shaft driven through gears = gear_ratio x speed_ratio of its driver.
  std::vector<int> state(m_.shafts.size(), 0);  // 0 todo, 1 on the current chain, 2 done
  for (std::size_t start = 0; start < m_.shafts.size(); ++start) {
    std::vector<std::size_t> chain;
    std::size_t i = start;
    while (state[i] == 0 && !m_.shafts[i].driven_by.empty()) {
      state[i] = 1;
      chain.push_back(i);
      const std::string path = fmt::format("shafts[{}].driven_by", i);
      auto it = shaft_index_.find(m_.shafts[i].driven_by);
      if (it == shaft_index_.end()) {
        std::vector<std::string> names;
        for (const auto& [n, k] : shaft_index_) names.push_back(n);
        fail(path, fmt::format("a shaft name ({})", quoted_list(names)),
             fmt::format("\"{}\"", m_.shafts[i].driven_by),
             did_you_mean(m_.shafts[i].driven_by, names));
      }
      const auto next = static_cast<std::size_t>(it->second);
      if (state[next] == 1) {
        std::string cycle;
        auto from = std::find(chain.begin(), chain.end(), next);
        for (auto c = from; c != chain.end(); ++c) cycle += m_.shafts[*c].name + " -> ";
        cycle += m_.shafts[next].name;
        fail(path, "a chain of driven_by that ends at a shaft with a speed_ratio",
             fmt::format("the cycle {}", cycle));
      }
      i = next;
    }
    for (auto c = chain.rbegin(); c != chain.rend(); ++c) {
      Shaft& s = m_.shafts[*c];
      s.speed_ratio = s.gear_ratio *
                      m_.shafts[static_cast<std::size_t>(shaft_index_.at(s.driven_by))].speed_ratio;
      state[*c] = 2;
    }
    state[start] = 2;
  }
  for (std::size_t i = 0; i < m_.nodes.size(); ++i) {
    Node& n = m_.nodes[i];
    if (n.spin_of.empty()) continue;
    auto it = shaft_index_.find(n.spin_of);
    if (it == shaft_index_.end()) {
      std::vector<std::string> names;
      for (const auto& [name, k] : shaft_index_) names.push_back(name);
      fail(fmt::format("nodes[{}].spin_of", i),
           names.empty() ? std::string("a shaft name, but there is no [[shafts]] table")
                         : fmt::format("a shaft name ({})", quoted_list(names)),
           fmt::format("\"{}\"", n.spin_of), did_you_mean(n.spin_of, names));
    }
    n.speed_ratio = m_.shafts[static_cast<std::size_t>(it->second)].speed_ratio;
  }
}

void Resolver::resolve_disks() {
  for (std::size_t i = 0; i < m_.disks.size(); ++i) {
    Disk& d = m_.disks[i];
    check_node(fmt::format("disks[{}].node", i), d.node);
    if (std::isnan(d.outer_diameter)) continue;
    check_material(fmt::format("disks[{}].material", i), d.material);
    check_massive(fmt::format("disks[{}].material", i), d.material, "a disk given by its geometry");
    // Uniform annular disk: m = rho pi (ro^2 - ri^2) h, Ip = m (ro^2 + ri^2) / 2,
    // Id = m (3 (ro^2 + ri^2) + h^2) / 12 (about a diameter through the centre of mass).
    const double rho = m_.find_material(d.material)->density;
    const double ro = d.outer_diameter / 2.0, ri = d.inner_diameter / 2.0, h = d.thickness;
    d.mass = rho * units::kPi * (ro * ro - ri * ri) * h;
    d.polar_inertia = d.mass * (ro * ro + ri * ri) / 2.0;
    d.diametral_inertia = d.mass * (3.0 * (ro * ro + ri * ri) + h * h) / 12.0;
  }
}

void Resolver::check_connections() {
  for (std::size_t i = 0; i < m_.point_masses.size(); ++i)
    check_node(fmt::format("point_masses[{}].node", i), m_.point_masses[i].node);
  for (std::size_t i = 0; i < m_.bearings.size(); ++i) {
    const Bearing& b = m_.bearings[i];
    check_node(fmt::format("bearings[{}].node", i), b.node);
    if (b.node2.empty()) continue;
    check_node(fmt::format("bearings[{}].node2", i), b.node2);
    if (b.node2 == b.node)
      fail(fmt::format("bearings[{}].node2", i), "a node other than `node`",
           fmt::format("\"{}\" again", b.node2), "leave node2 out for a bearing to ground");
  }
  for (std::size_t i = 0; i < m_.couplings.size(); ++i) {
    const Coupling& c = m_.couplings[i];
    check_node(fmt::format("couplings[{}].node1", i), c.node1);
    if (c.node2.empty()) continue;
    check_node(fmt::format("couplings[{}].node2", i), c.node2);
    if (c.node2 == c.node1)
      fail(fmt::format("couplings[{}].node2", i), "a node other than `node1`",
           fmt::format("\"{}\" again", c.node2));
  }
  for (std::size_t i = 0; i < m_.gear_meshes.size(); ++i) {
    const GearMesh& g = m_.gear_meshes[i];
    const Vec3 p1 = node_info(fmt::format("gear_meshes[{}].gear1", i), g.gear1).position;
    const Vec3 p2 = node_info(fmt::format("gear_meshes[{}].gear2", i), g.gear2).position;
    if (g.gear2 == g.gear1)
      fail(fmt::format("gear_meshes[{}].gear2", i), "a node other than gear1",
           fmt::format("\"{}\" again", g.gear2));
    if (!g.mesh_direction && p1 == p2)
      fail(fmt::format("gear_meshes[{}].gear2", i),
           "a gear node away from gear1's node, so that the mesh direction is defined",
           fmt::format("\"{}\" at the same position as \"{}\"", g.gear2, g.gear1),
           "give mesh_direction = [x, y, z]");
  }
  for (std::size_t i = 0; i < m_.constraints.size(); ++i)
    check_node(fmt::format("constraints[{}].node", i), m_.constraints[i].node);
  for (std::size_t i = 0; i < m_.unbalances.size(); ++i) {
    const Unbalance& u = m_.unbalances[i];
    const std::string path = fmt::format("unbalances[{}].node", i);
    const NodeInfo info = node_info(path, u.node);
    const double ratio = info.shaft >= 0
                             ? m_.shafts[static_cast<std::size_t>(info.shaft)].speed_ratio
                             : std::find_if(m_.nodes.begin(), m_.nodes.end(), [&](const Node& n) {
                                 return n.name == u.node;
                               })->speed_ratio;
    if (ratio == 0.0)
      fail(path, "a spinning node (a shaft station, or a node with spin_of)",
           fmt::format("\"{}\", which does not spin (speed ratio 0)", u.node));
  }
  for (std::size_t i = 0; i < m_.forces.size(); ++i)
    check_node(fmt::format("forces[{}].node", i), m_.forces[i].node);
  std::set<std::string> joined_solids;
  for (const Solid& s : m_.solids)
    if (!s.spiders.empty()) joined_solids.insert(s.name);
  for (std::size_t i = 0; i < m_.sensors.size(); ++i) {
    const Sensor& sensor = m_.sensors[i];
    if (sensor.solid.empty()) {
      check_node(fmt::format("sensors[{}].node", i), sensor.node);
    } else if (m_.find_solid(sensor.solid) == nullptr) {
      std::set<std::string> solids;
      for (const Solid& s : m_.solids) solids.insert(s.name);
      check_name(fmt::format("sensors[{}].solid", i), sensor.solid, solids, "solid", "solids");
    } else if (!joined_solids.count(sensor.solid)) {
      fail(fmt::format("sensors[{}].solid", i),
           joined_solids.empty()
               ? std::string("a solid joined to the rotor by [[solids.spiders]], but no solid is")
               : fmt::format("a solid joined to the rotor by [[solids.spiders]] ({})",
                             quoted_list({joined_solids.begin(), joined_solids.end()})),
           fmt::format("\"{}\", which has no spiders", sensor.solid),
           "a solid without spiders is not part of the rotor system; add [[solids.spiders]]");
    }
  }
}

void Resolver::check_damping() {
  std::vector<std::size_t> order(m_.damping.bands.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return m_.damping.bands[a].f_min < m_.damping.bands[b].f_min;
  });
  for (std::size_t k = 1; k < order.size(); ++k) {
    const DampingBand& lo = m_.damping.bands[order[k - 1]];
    const DampingBand& hi = m_.damping.bands[order[k]];
    if (hi.f_min < lo.f_max)
      fail(fmt::format("damping.bands[{}].f_min_hz", order[k]),
           fmt::format("a band that does not overlap damping.bands[{}] (which ends at {} Hz)",
                       order[k - 1], number_text(lo.f_max * (1.0 / units::kTwoPi))),
           fmt::format("{} Hz", number_text(hi.f_min * (1.0 / units::kTwoPi))));
  }
}

// ---------------------------------------------------------------------------------------------
// The nonlinear drivetrain

// An element between end i (`key1`, empty: ground) and end j (`key2`): both nodes exist and
// differ. End j is a required key, so an element with both ends on ground cannot be written.
void Resolver::check_element_ends(const std::string& path, const std::string& node1,
                                  const std::string& node2, const char* key1,
                                  const char* key2) const {
  if (!node1.empty()) check_node(fmt::format("{}.{}", path, key1), node1);
  check_node(fmt::format("{}.{}", path, key2), node2);
  if (node1 == node2)
    fail(fmt::format("{}.{}", path, key2), fmt::format("a node other than `{}`", key1),
         fmt::format("\"{}\" again", node2),
         fmt::format("leave {} out for an element to ground", key1));
}

// A bolt clamps two bodies: each node it joins must belong to one (a shaft station, a node with
// mass, a node joined to a solid), or the bolt acts on a massless point that nothing else holds.
void Resolver::check_bolt_bodies() const {
  std::set<std::string> on_body;
  for (const Disk& d : m_.disks) on_body.insert(d.node);
  for (const PointMass& p : m_.point_masses) on_body.insert(p.node);
  for (const Solid& solid : m_.solids)
    for (const Spider& spider : solid.spiders) on_body.insert(spider.node);
  for (const Coupling& c : m_.couplings) {
    if (c.mass.empty()) continue;
    on_body.insert(c.node1);
    if (!c.node2.empty()) on_body.insert(c.node2);
  }
  for (std::size_t i = 0; i < m_.bolts.size(); ++i) {
    const BoltSpec& b = m_.bolts[i];
    for (const auto& [key, node] : {std::pair{"node1", &b.node1}, std::pair{"node2", &b.node2}}) {
      if (node->empty() || on_body.count(*node) ||
          node_info(fmt::format("bolts[{}].{}", i, key), *node).shaft >= 0)
        continue;
      fail(fmt::format("bolts[{}].{}", i, key),
           "a node on a body: a shaft station, a [[nodes]] node with a disk or point mass, or "
           "a node joined to a solid by [[solids.spiders]]",
           fmt::format("\"{}\", a node without mass that no body holds", *node),
           fmt::format("a bolt joins two bodies: join \"{}\" to its part with [[solids.spiders]], "
                       "or give it a [[disks]] or [[point_masses]] entry",
                       *node));
    }
  }
}

// A driver, load or clutch acts on the rotation about the node's spin axis (rz of the node
// frame): it must be a DOF, kept by the node's DOF set and not fixed by [[constraints]].
void Resolver::check_rz_free(const std::string& path, const std::string& node,
                             const char* what) const {
  const NodeInfo info = node_info(path, node);
  const Shaft* shaft = info.shaft >= 0 ? &m_.shafts[static_cast<std::size_t>(info.shaft)] : nullptr;
  const DofSet set = shaft != nullptr && shaft->dofs ? *shaft->dofs : m_.dofs;
  if (!dof_set_components(set)[5])
    fail(path, fmt::format("a node whose rotation about its spin axis (rz) is a DOF, for {}", what),
         fmt::format("\"{}\", whose DOFs are \"{}\" (no torsion)", node,
                     kDofSetNames[static_cast<std::size_t>(set)]),
         shaft != nullptr && shaft->dofs
             ? fmt::format("set the `dofs` of shaft \"{}\" to a set with torsion, e.g. \"all\"",
                           shaft->name)
             : std::string("set the model's `dofs` to a set with torsion, e.g. \"all\""));
  for (std::size_t k = 0; k < m_.constraints.size(); ++k) {
    const Constraint& c = m_.constraints[k];
    if (c.node == node && std::find(c.dofs.begin(), c.dofs.end(), Component::Rz) != c.dofs.end())
      fail(path,
           fmt::format("a node whose rz is free (not fixed by [[constraints]]), for {}", what),
           fmt::format("\"{}\", whose rz constraints[{}] fixes: {} on a constrained DOF", node, k,
                       what),
           fmt::format("remove \"rz\" from constraints[{}].dofs, or drive another node", k));
  }
}

void Resolver::check_drivers_and_loads() const {
  std::map<std::string, std::size_t> driven;
  for (std::size_t i = 0; i < m_.drivers.size(); ++i) {
    const DriverSpec& d = m_.drivers[i];
    const std::string path = fmt::format("drivers[{}].node", i);
    check_rz_free(path, d.node, "a driver");
    auto [it, inserted] = driven.emplace(d.node, i);
    if (!inserted)
      fail(path, "a node that no other driver drives",
           fmt::format("\"{}\", already driven by drivers[{}] (\"{}\")", d.node, it->second,
                       m_.drivers[it->second].name),
           "one node takes one driver; combine them into one speed table or motor curve");
  }
  for (std::size_t i = 0; i < m_.loads.size(); ++i)
    check_rz_free(fmt::format("loads[{}].node", i), m_.loads[i].node, "a load torque");
  for (std::size_t i = 0; i < m_.clutches.size(); ++i) {
    const ClutchSpec& c = m_.clutches[i];
    const std::string path = fmt::format("clutches[{}]", i);
    check_element_ends(path, c.node1, c.node2, "node1", "node2");
    if (!c.node1.empty()) check_rz_free(path + ".node1", c.node1, "a clutch");
    check_rz_free(path + ".node2", c.node2, c.node1.empty() ? "a brake" : "a clutch");
  }
}

void Resolver::check_drivetrain() {
  check_unique(m_.contacts, "contacts");
  check_unique(m_.bolts, "bolts");
  check_unique(m_.bushings, "bushings");
  check_unique(m_.rolling_bearings, "rolling_bearings");
  check_unique(m_.drivers, "drivers");
  check_unique(m_.loads, "loads");
  check_unique(m_.clutches, "clutches");
  check_unique(m_.virtual_sensors, "virtual_sensors");
  for (std::size_t i = 0; i < m_.contacts.size(); ++i)
    check_element_ends(fmt::format("contacts[{}]", i), m_.contacts[i].node1, m_.contacts[i].node2,
                       "node1", "node2");
  for (std::size_t i = 0; i < m_.bolts.size(); ++i)
    check_element_ends(fmt::format("bolts[{}]", i), m_.bolts[i].node1, m_.bolts[i].node2, "node1",
                       "node2");
  check_bolt_bodies();
  for (std::size_t i = 0; i < m_.bushings.size(); ++i)
    check_element_ends(fmt::format("bushings[{}]", i), m_.bushings[i].node1, m_.bushings[i].node2,
                       "node1", "node2");
  for (std::size_t i = 0; i < m_.rolling_bearings.size(); ++i) {
    const RollingBearingSpec& b = m_.rolling_bearings[i];
    const std::string path = fmt::format("rolling_bearings[{}]", i);
    check_element_ends(path, b.housing, b.node, "housing", "node");
    const bool spins = node_info(path + ".node", b.node).shaft >= 0 ||
                       std::any_of(m_.nodes.begin(), m_.nodes.end(), [&](const Node& n) {
                         return n.name == b.node && !n.spin_of.empty();
                       });
    if (!spins)
      fail(path + ".node",
           "a node with a spin axis: a shaft station, or a [[nodes]] entry with spin_of",
           fmt::format("\"{}\", a [[nodes]] entry that does not spin", b.node),
           "the inner ring sits on a shaft: give the node's spin_of, or use a shaft station");
  }
  check_drivers_and_loads();
  for (std::size_t i = 0; i < m_.virtual_sensors.size(); ++i)
    check_node(fmt::format("virtual_sensors[{}].node", i), m_.virtual_sensors[i].node);
  const std::set<std::string> pairs = names_of(m_.gear_pairs);
  for (std::size_t i = 0; i < m_.gear_meshes.size(); ++i) {
    const GearMesh& g = m_.gear_meshes[i];
    if (g.contact && !g.contact->gear_pair.empty())
      check_name(fmt::format("gear_meshes[{}].contact.gear_pair", i), g.contact->gear_pair, pairs,
                 "gear pair", "gear_pairs");
  }
}

// [[nonlinear_elements]]: ends, the gear mesh a mesh element uses, the friction contact's
// directions (normal and tangents mutually orthogonal).
void Resolver::check_nonlinear_elements() const {
  check_unique(m_.nonlinear_elements, "nonlinear_elements");
  std::set<std::string> meshes;
  for (const GearMesh& g : m_.gear_meshes) meshes.insert(g.name);
  for (std::size_t i = 0; i < m_.nonlinear_elements.size(); ++i) {
    const NonlinearElementSpec& e = m_.nonlinear_elements[i];
    const std::string path = fmt::format("nonlinear_elements[{}]", i);
    if (e.kind == NonlinearElementKind::GearMesh) {
      check_name(path + ".gear_mesh", e.gear_mesh, meshes, "gear mesh", "gear_meshes");
      continue;
    }
    check_element_ends(path, e.node1, e.node2, "node1", "node2");
  }
}

// An analysis's `set` entries are checked like --set, and the variant model they make is built
// and validated here, so a bad value is reported before any computation. The variant's own
// analyses are not checked again (that would recurse).
void Resolver::check_analysis_overrides(const std::string& base, const Analysis& analysis) const {
  static thread_local int depth = 0;
  if (analysis.overrides.empty() || depth > 0) return;
  ModelDocument variant = r_.doc();
  for (std::size_t k = 0; k < analysis.overrides.size(); ++k) {
    const std::string path = fmt::format("{}.set[{}]", base, k);
    try {
      apply_override(variant, analysis.overrides[k]);
    } catch (const InputError& e) {
      fail(path, e.expected(), e.found(), e.hint());
    }
  }
  ++depth;
  try {
    (void)build_model(variant);
  } catch (const InputError& e) {
    --depth;
    fail(base + ".set",
         fmt::format("changes giving a valid model ({}: expected {})", e.key_path(), e.expected()),
         e.found(), e.hint());
  }
  --depth;
}

// Every analysis's type's own checks (Variant::check: the references of its keys into the rest
// of the model) first, then the `set` variants build. In that order a problem of the model
// itself is reported at its own key; a variant then fails only for what its `set` changed.
void Resolver::check_analyses() {
  const Section* section = r_.doc().schema().find_section("analyses", "");
  for (std::size_t i = 0; i < m_.analyses.size(); ++i) {
    const Analysis& a = m_.analyses[i];
    const Variant* v = section != nullptr ? section->find_variant(a.type) : nullptr;
    if (v != nullptr && v->check) v->check(&a, fmt::format("analyses[{}]", i), *this);
  }
  for (std::size_t i = 0; i < m_.analyses.size(); ++i)
    check_analysis_overrides(fmt::format("analyses[{}]", i), m_.analyses[i]);
}

void Resolver::run() {
  check_unique(m_.materials, "materials");
  check_unique(m_.shafts, "shafts");
  check_unique(m_.nodes, "nodes");
  build_nodes();
  for (std::size_t i = 0; i < m_.shafts.size(); ++i) {
    const Shaft& s = m_.shafts[i];
    check_material(fmt::format("shafts[{}].material", i), s.material);
    for (std::size_t k = 0; k < s.elements.size(); ++k)
      if (!s.elements[k].material.empty())
        check_material(fmt::format("shafts[{}].elements[{}].material", i, k),
                       s.elements[k].material);
  }
  resolve_speeds();
  check_unique(m_.disks, "disks");
  check_unique(m_.point_masses, "point_masses");
  check_unique(m_.bearings, "bearings");
  check_unique(m_.couplings, "couplings");
  check_unique(m_.gear_meshes, "gear_meshes");
  check_unique(m_.unbalances, "unbalances");
  check_unique(m_.forces, "forces");
  check_unique(m_.sensors, "sensors");
  check_unique(m_.analyses, "analyses");
  check_unique(m_.solids, "solids");
  check_unique(m_.gear_pairs, "gear_pairs");
  for (std::size_t i = 0; i < m_.gear_pairs.size(); ++i) {
    const GearPair& g = m_.gear_pairs[i];
    if (!g.material1.empty())
      check_material(fmt::format("gear_pairs[{}].material1", i), g.material1);
    if (!g.material2.empty())
      check_material(fmt::format("gear_pairs[{}].material2", i), g.material2);
  }
  for (std::size_t i = 0; i < m_.solids.size(); ++i) {
    const Solid& s = m_.solids[i];
    if (!s.material.empty()) {
      check_material(fmt::format("solids[{}].material", i), s.material);
      check_massive(fmt::format("solids[{}].material", i), s.material, "a solid");
    }
    if (!s.ring_material.empty()) {
      check_material(fmt::format("solids[{}].ring_material", i), s.ring_material);
      check_massive(fmt::format("solids[{}].ring_material", i), s.ring_material, "a damper ring");
    }
    for (std::size_t k = 0; k < s.spiders.size(); ++k)
      check_node(fmt::format("solids[{}].spiders[{}].node", i, k), s.spiders[k].node);
  }
  resolve_disks();
  check_connections();
  check_drivetrain();
  check_nonlinear_elements();
  check_damping();
  check_analyses();
}

// ---------------------------------------------------------------------------------------------
// Pre-check of the raw text.
//
// toml++ 3.3 (Debian 12) reaches __builtin_unreachable in is_non_ascii_horizontal_whitespace()
// for some non-ASCII code points where it looks for whitespace (toml++ issues #190 and #295,
// found again by fuzz/model_fuzz): undefined behaviour on input a user can type. TOML allows
// non-ASCII characters only inside strings and comments, so this scan rejects them elsewhere
// (toml++ would reject them too, but only after the undefined behaviour), and rejects the one
// in-string case: the first character of a line continued with a backslash in a """ string.

struct Utf8 {
  char32_t code_point = 0;
  std::size_t length = 0;  ///< 0: not valid UTF-8
};

Utf8 decode_utf8(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b0 = byte(i);
  std::size_t n = 0;
  char32_t cp = 0;
  if (b0 < 0x80) return {b0, 1};
  if ((b0 & 0xE0) == 0xC0) {
    n = 2;
    cp = b0 & 0x1F;
  } else if ((b0 & 0xF0) == 0xE0) {
    n = 3;
    cp = b0 & 0x0F;
  } else if ((b0 & 0xF8) == 0xF0) {
    n = 4;
    cp = b0 & 0x07;
  } else {
    return {};
  }
  if (i + n > s.size()) return {};
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return {};
    cp = (cp << 6) | (byte(i + k) & 0x3F);
  }
  constexpr char32_t kMinForLength[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < kMinForLength[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return {};
  return {cp, n};
}

// The scan of check_text: a small state machine over the characters, tracking line and column.
class TextCheck {
 public:
  TextCheck(std::string_view text, const std::string& file_name)
      : text_(text), file_name_(file_name) {}

  void run() {
    for (std::size_t i = 0; i < text_.size();) {
      const char c = text_[i];
      const Utf8 u = decode_utf8(text_, i);
      if (u.length == 0)
        fail("valid UTF-8 text", fmt::format("the byte 0x{:02X}",
                                             static_cast<unsigned>(static_cast<unsigned char>(c))));
      std::size_t advance = u.length;
      check_code_point(u);
      const State was = state_;
      if (state_ == State::Normal)
        step_normal(i, c, advance);
      else
        step_inside(i, c, advance);
      if (state_ == State::Normal) {
        if (c == '\n') key_side_ = brackets_.empty() || brackets_.back() == '{';
        if (was == State::Comment)
          before_ = '\n';
        else if (was != State::Normal)
          before_ = '"';  // a string ended
        else if (c != ' ' && c != '\t' && c != '\r')
          before_ = c;
      }
      move_position(i, advance);
      i += advance;
    }
  }

 private:
  enum class State { Normal, Comment, Basic, Literal, MultiBasic, MultiLiteral };

  [[noreturn]] void fail(std::string expected, std::string found) const {
    throw InputError({file_name_, line_, column_}, "(syntax)", std::move(expected),
                     std::move(found));
  }

  bool starts(std::size_t i, std::string_view what) const {
    return text_.compare(i, what.size(), what) == 0;
  }

  // TOML escapes are ASCII (\n, \t, \", \\, \uXXXX, ... or a line-ending backslash). toml++
  // 3.3 classifies the character after a backslash with a whitespace table that has undefined
  // behaviour for some non-ASCII code points (e.g. U+FEFD), so those are refused here first.
  void escape_must_be_ascii(std::size_t backslash, std::size_t k) {
    if (k >= text_.size() || static_cast<unsigned char>(text_[k]) < 0x80) return;
    const Utf8 next = decode_utf8(text_, k);
    column_ += static_cast<int>(k - backslash);  // the characters in between are ASCII
    fail(
        "an escape sequence after the backslash (\\b \\t \\n \\f \\r \\\" \\\\ \\uXXXX "
        "\\UXXXXXXXX, or a line-ending backslash)",
        next.length == 0
            ? std::string("invalid UTF-8")
            : fmt::format("the character U+{:04X}", static_cast<unsigned>(next.code_point)));
  }

  // Non-ASCII characters: only inside strings and comments, and not first on a continued line.
  void check_code_point(const Utf8& u) const {
    if (u.code_point < 0x80) return;
    if (state_ == State::Normal)
      fail("valid TOML: non-ASCII characters only inside strings and comments",
           fmt::format("the character U+{:04X}", static_cast<unsigned>(u.code_point)));
    if (state_ == State::MultiBasic && continued_line_)
      fail(
          "an ASCII character first on a line continued with a backslash (a limitation of "
          "the TOML reader)",
          fmt::format("the character U+{:04X}", static_cast<unsigned>(u.code_point)));
  }

  // Outside strings and comments.
  void step_normal(std::size_t i, char c, std::size_t& advance) {
    if (c == '#') {
      state_ = State::Comment;
    } else if (c == '\\') {
      // Never valid outside a string; toml++ 3.3 classifies the character after it with the
      // table that has undefined behaviour for some non-ASCII code points (found by fuzzing).
      fail("valid TOML: a backslash only inside a \"...\" string",
           "a backslash outside any string");
    } else if ((c == '"' || c == '\'') &&
               (std::string_view("=[,{.\n").find(before_) == std::string_view::npos ||
                (before_ == '.' && !key_side_))) {
      // TOML starts a string only there (after '.' only in a dotted key); toml++ 3.3 would
      // scan a quote after a bare value (x = 0x"..." or x = 0."...") as part of that value,
      // classifying its characters with the table that has undefined behaviour for some
      // non-ASCII code points (found by fuzzing).
      fail("valid TOML: a string only after '=', ',', '[', '{', a key's '.' or first on a line",
           fmt::format("a quote after '{}'", before_));
    } else if (c == '=') {
      key_side_ = false;
    } else if (c == '[' || c == '{') {
      brackets_.push_back(c);
      if (c == '{') key_side_ = true;
    } else if ((c == ']' || c == '}') && !brackets_.empty()) {
      brackets_.pop_back();
    } else if (c == ',' && !brackets_.empty() && brackets_.back() == '{') {
      key_side_ = true;
    } else if (starts(i, "\"\"\"")) {
      state_ = State::MultiBasic;
      advance = 3;
    } else if (starts(i, "'''")) {
      state_ = State::MultiLiteral;
      advance = 3;
    } else if (c == '"') {
      state_ = State::Basic;
    } else if (c == '\'') {
      state_ = State::Literal;
    }
  }

  // Inside a comment or a string.
  void step_inside(std::size_t i, char c, std::size_t& advance) {
    switch (state_) {
      case State::Normal:
        break;
      case State::Comment:
        if (c == '\n') state_ = State::Normal;
        break;
      case State::Basic:
        if (c == '\\' && i + 1 < text_.size() && text_[i + 1] != '\n') {
          escape_must_be_ascii(i, i + 1);
          advance = 2;
        } else if (c == '"' || c == '\n')
          state_ = State::Normal;
        break;
      case State::Literal:
        if (c == '\'' || c == '\n') state_ = State::Normal;
        break;
      case State::MultiBasic:
        if (c == '\\') {
          std::size_t k = i + 1;
          while (k < text_.size() && (text_[k] == ' ' || text_[k] == '\t' || text_[k] == '\r')) ++k;
          escape_must_be_ascii(i, k);
          if (k < text_.size() && text_[k] == '\n')
            continued_line_ = true;
          else if (k < text_.size() && static_cast<unsigned char>(text_[k]) < 0x80)
            advance = 2;
        } else if (starts(i, "\"\"\"")) {
          state_ = State::Normal;
          continued_line_ = false;
          advance = 3;
        } else if (c != ' ' && c != '\t' && c != '\r' && c != '\n') {
          continued_line_ = false;
        }
        break;
      case State::MultiLiteral:
        if (starts(i, "'''")) {
          state_ = State::Normal;
          advance = 3;
        }
        break;
    }
  }

  void move_position(std::size_t i, std::size_t advance) {
    for (std::size_t k = 0; k < advance && i + k < text_.size(); ++k) {
      if (text_[i + k] == '\n') {
        ++line_;
        column_ = 1;
      } else if ((static_cast<unsigned char>(text_[i + k]) & 0xC0) != 0x80) {
        ++column_;
      }
    }
  }

  std::string_view text_;
  const std::string& file_name_;
  State state_ = State::Normal;
  int line_ = 1, column_ = 1;
  bool continued_line_ = false;  // inside """: after a line-ending backslash, before content
  char before_ = '\n';           // outside strings and comments: the last non-blank character
  // Outside strings: the open brackets, and whether a key (not a value) is expected; a dotted
  // key may continue with a quoted part (a."b"), a value may not (x = 0."b").
  std::string brackets_;
  bool key_side_ = true;
};

void check_text(std::string_view text, const std::string& file_name) {
  TextCheck(text, file_name).run();
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Public API

ModelDocument parse_document(const std::string& file_text, const std::string& file_name,
                             const Section& schema) {
  // A UTF-8 byte-order mark (editors on Windows write one) is not part of the text.
  const std::string_view bom = "\xEF\xBB\xBF";
  const std::string text = std::string_view(file_text).substr(0, bom.size()) == bom
                               ? file_text.substr(bom.size())
                               : file_text;
  check_text(text, file_name);
  try {
    auto table = std::make_shared<toml::table>(toml::parse(text, file_name));
    return ModelDocument(std::move(table), file_name, schema);
  } catch (const toml::parse_error& e) {
    const auto& r = e.source();
    throw InputError({file_name, static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)},
                     "(syntax)", "valid TOML", std::string(e.description()));
  }
}

ModelDocument load_document(const std::string& path, const Section& schema) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status))
    throw InputError({path, 0, 0}, "(file)", "a model file (TOML)", "a directory",
                     "give the model file inside it, e.g. " +
                         (std::filesystem::path(path) / "model.toml").string());
  const std::optional<std::string> text = try_read_file(path);
  if (!text)
    throw InputError(
        {path, 0, 0}, "(file)", "a readable model file",
        std::filesystem::exists(status) ? "a file that cannot be read" : "no such file");
  return parse_document(*text, path, schema);
}

void apply_override(ModelDocument& document, const std::string& assignment) {
  const std::string origin = kSetPrefix + assignment;
  const SourceLocation where{origin, 0, 0};
  const auto eq = assignment.find('=');
  auto trim = [](std::string s) {
    const auto b = s.find_first_not_of(" \t");
    const auto e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string{} : s.substr(b, e - b + 1);
  };
  if (eq == std::string::npos)
    throw InputError(where, assignment, "key.path=value, e.g. bearings[0].kxx=2e7",
                     fmt::format("'{}' without '='", assignment));
  const std::string path = trim(assignment.substr(0, eq));
  const std::string value = trim(assignment.substr(eq + 1));
  const ResolvedKey key = resolve_key(document, path, where);
  if (value.empty()) throw InputError(where, path, describe_type(*key.field), "no value after '='");
  std::shared_ptr<toml::table> holder;
  std::string problem;
  try {
    check_text(value, origin);
    holder = std::make_shared<toml::table>(toml::parse("value = " + value, origin));
  } catch (const toml::parse_error& e) {
    problem = std::string(e.description());
  } catch (const InputError& e) {
    problem = fmt::format("expected {}, found {}", e.expected(), e.found());
  }
  if (!holder) {
    const bool text_key =
        key.field->type == FieldType::String || key.field->type == FieldType::Enum;
    if (!text_key || value.find_first_of("\"'[]{}") != std::string::npos)
      throw InputError(where, path, fmt::format("a TOML value: {}", describe_type(*key.field)),
                       fmt::format("'{}' ({})", value, problem));
    // Quotes are optional for string keys: --set shafts[0].theory=euler_bernoulli
    holder = std::make_shared<toml::table>();
    holder->insert("value", value);
  }
  document.add_override({key.parent, key.key, origin,
                         std::shared_ptr<const toml::node>(holder, holder->get("value"))});
}

void check_number_key(const ModelDocument& document, const std::string& key_path,
                      const SourceLocation& where) {
  const ResolvedKey key = resolve_key(document, key_path, where);
  const FieldType t = key.field->type;
  if (t != FieldType::Number && t != FieldType::Integer && t != FieldType::NumberOrArray)
    throw InputError(where, key_path, "the path of a number or integer key",
                     fmt::format("'{}', which is {}", key.key, describe_type(*key.field)));
}

const Field& field_of(const ModelDocument& document, const std::string& key_path,
                      const SourceLocation& where) {
  return *resolve_key(document, key_path, where).field;
}

void set_number(ModelDocument& document, const std::string& key_path, double value) {
  const std::string origin = fmt::format("{}{} = {}", kSweepPrefix, key_path, number_text(value));
  const SourceLocation where{origin, 0, 0};
  check_number_key(document, key_path, where);
  const ResolvedKey key = resolve_key(document, key_path, where);
  if (std::isnan(value)) throw InputError(where, key_path, describe_type(*key.field), "nan");
  auto holder = std::make_shared<toml::table>();
  if (key.field->type == FieldType::Integer) {
    if (value != std::floor(value) || std::abs(value) > 9.0e15)
      throw InputError(where, key_path, describe_type(*key.field), number_text(value));
    holder->insert("value", static_cast<int64_t>(value));
  } else {
    holder->insert("value", value);
  }
  document.add_override({key.parent, key.key, origin,
                         std::shared_ptr<const toml::node>(holder, holder->get("value"))});
}

Model build_model(const ModelDocument& document) {
  Model model;
  model.source_file = document.file_name();
  Reader reader(document);
  reader.read_table(document.schema(), &document.table(), "", {document.file_name(), 1, 1}, &model);
  Resolver(model, reader).run();
  return model;
}

Model parse_model(const std::string& text, const std::string& file_name, const Section& schema) {
  return build_model(parse_document(text, file_name, schema));
}

Model load_model(const std::string& path, const Section& schema) {
  return build_model(load_document(path, schema));
}

}  // namespace geardyn::model
