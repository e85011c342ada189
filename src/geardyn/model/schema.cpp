// The declaration table of the model file: every key once, with type, unit, default, range,
// help text and where it goes in the Model. parse.cpp reads files through it, schema_markdown()
// documents it. Cross-key rules that a single key cannot express (alternatives, derived values)
// are declared next to the keys as Choices and finish steps.
#include "geardyn/model/schema.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <type_traits>

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
// Declaration helpers

namespace {

constexpr double kPi = std::numbers::pi;
constexpr Unit kNoUnit{"", 1.0};
constexpr Unit kMetre{"m", 1.0};
constexpr Unit kKilogram{"kg", 1.0};
constexpr Unit kPascal{"Pa", 1.0};
constexpr Unit kDensity{"kg/m^3", 1.0};
constexpr Unit kInertia{"kg m^2", 1.0};
constexpr Unit kMassEccentricity{"kg m", 1.0};
constexpr Unit kSecond{"s", 1.0};
constexpr Unit kPerSecond{"1/s", 1.0};
constexpr Unit kStiffness{"N/m", 1.0};
constexpr Unit kStiffnessPerArea{"N/m^3", 1.0};
constexpr Unit kDampingCoefficient{"N s/m", 1.0};
constexpr Unit kTiltStiffness{"N m/rad", 1.0};
constexpr Unit kTiltDamping{"N m s/rad", 1.0};
constexpr Unit kNewton{"N", 1.0};
constexpr Unit kRpm{"rpm", 2.0 * kPi / 60.0};
constexpr Unit kHertz{"Hz", 2.0 * kPi};
constexpr Unit kDegree{"deg", kPi / 180.0};

const std::vector<std::string> kComponentChoices(kComponentNames.begin(), kComponentNames.end());

template <class M>
struct MemberTraits;
template <class C, class V>
struct MemberTraits<V C::*> {
  using Class = C;
  using Value = V;
};

void assign(double& out, const FieldValue& v) { out = v.number; }
void assign(int& out, const FieldValue& v) { out = static_cast<int>(v.integer); }
void assign(bool& out, const FieldValue& v) { out = v.boolean; }
void assign(std::string& out, const FieldValue& v) { out = v.text; }
void assign(std::vector<double>& out, const FieldValue& v) { out = v.numbers; }
void assign(std::vector<std::string>& out, const FieldValue& v) { out = v.strings; }
void assign(Vec3& out, const FieldValue& v) { std::copy_n(v.numbers.begin(), 3, out.begin()); }
void assign(std::optional<Vec3>& out, const FieldValue& v) {
  out.emplace();
  std::copy_n(v.numbers.begin(), 3, out->begin());
}
void assign(Component& out, const FieldValue& v) { out = static_cast<Component>(v.choice); }
void assign(std::vector<Component>& out, const FieldValue& v) {
  out.clear();
  for (int i : v.indices) out.push_back(static_cast<Component>(i));
}

/// Builder of one Field: `F("length", FieldType::Number, "help").unit(kMetre).required().gt(0)`.
class F {
 public:
  F(std::string name, FieldType type, std::string help) {
    f_.name = std::move(name);
    f_.type = type;
    f_.help = std::move(help);
  }
  F& unit(Unit u) {
    f_.unit = u;
    return *this;
  }
  F& unit_note(std::string note) {
    f_.unit_note = std::move(note);
    return *this;
  }
  F& required() {
    f_.required = true;
    return *this;
  }
  F& def(std::string toml_literal) {
    f_.default_value = std::move(toml_literal);
    return *this;
  }
  F& note(std::string text) {
    f_.default_note = std::move(text);
    return *this;
  }
  F& default_from_path() {
    f_.default_from_path = true;
    return *this;
  }
  F& gt(double v) {
    f_.range.min = v;
    f_.range.min_exclusive = true;
    return *this;
  }
  F& ge(double v) {
    f_.range.min = v;
    f_.range.min_exclusive = false;
    return *this;
  }
  F& lt(double v) {
    f_.range.max = v;
    f_.range.max_exclusive = true;
    return *this;
  }
  F& le(double v) {
    f_.range.max = v;
    f_.range.max_exclusive = false;
    return *this;
  }
  F& allow_infinity() {
    f_.allow_infinity = true;
    return *this;
  }
  F& nonzero() {
    f_.nonzero = true;
    return *this;
  }
  F& identifier() {
    f_.identifier = true;
    return *this;
  }
  F& increasing() {
    f_.increasing = true;
    return *this;
  }
  F& unique() {
    f_.unique = true;
    return *this;
  }
  F& min_items(std::size_t n) {
    f_.min_items = n;
    return *this;
  }
  F& sizes(std::vector<int> n) {
    f_.matrix_sizes = std::move(n);
    return *this;
  }
  F& tabulated_by(std::string key) {
    f_.tabulated = true;
    f_.tabulated_by = std::move(key);
    return *this;
  }
  F& choices(std::vector<std::string> c) {
    f_.choices = std::move(c);
    return *this;
  }
  F& ref(Ref r) {
    f_.ref = r;
    return *this;
  }
  F& only_in(std::vector<std::string> variants) {
    f_.only_in = std::move(variants);
    return *this;
  }

  /// Stores the value in `object.*member`.
  template <class M>
  F& to(M member) {
    using T = typename MemberTraits<M>::Class;
    f_.object_type = typeid(T);
    f_.setter = [member](void* object, const FieldValue& v) {
      assign(static_cast<T*>(object)->*member, v);
    };
    return *this;
  }
  /// Maps the chosen string (index into choices) to an enum value.
  template <class T, class E>
  F& to_enum(E T::*member, std::vector<E> values) {
    check_enum_size(values.size());
    f_.object_type = typeid(T);
    f_.setter = [member, values](void* object, const FieldValue& v) {
      static_cast<T*>(object)->*member = values.at(static_cast<std::size_t>(v.choice));
    };
    return *this;
  }
  /// Stores the value in the settings of an Analysis: each member belongs to one settings type,
  /// and the one matching the analysis' type is set.
  template <class... Ms>
  F& to_settings(Ms... members) {
    f_.object_type = typeid(Analysis);
    f_.setter = [members...](void* object, const FieldValue& v) {
      auto& analysis = *static_cast<Analysis*>(object);
      (assign_setting(analysis, members, v), ...);
    };
    return *this;
  }
  template <class S, class E>
  F& to_settings_enum(E S::*member, std::vector<E> values) {
    check_enum_size(values.size());
    f_.object_type = typeid(Analysis);
    f_.setter = [member, values](void* object, const FieldValue& v) {
      if (auto* s = std::get_if<S>(&static_cast<Analysis*>(object)->settings))
        s->*member = values.at(static_cast<std::size_t>(v.choice));
    };
    return *this;
  }
  template <class T>
  F& to_fn(std::function<void(T&, const FieldValue&)> fn) {
    f_.object_type = typeid(T);
    f_.setter = [fn](void* object, const FieldValue& v) { fn(*static_cast<T*>(object), v); };
    return *this;
  }
  /// Read only by the section's finish step (no setter).
  template <class T>
  F& read_by_finish() {
    f_.object_type = typeid(T);
    return *this;
  }

  operator Field() const { return f_; }  // NOLINT: builder converts implicitly

 private:
  template <class M>
  static void assign_setting(Analysis& analysis, M member, const FieldValue& v) {
    using S = typename MemberTraits<M>::Class;
    if (auto* s = settings_as<S>(analysis)) assign(s->*member, v);
  }
  void check_enum_size(std::size_t n) const {
    if (n != f_.choices.size())
      throw std::logic_error(fmt::format("schema: key '{}' maps {} choices to {} enum values",
                                         f_.name, f_.choices.size(), n));
  }
  Field f_;
};

F number(std::string name, Unit unit, std::string help) {
  F f(std::move(name), FieldType::Number, std::move(help));
  f.unit(unit);
  return f;
}
F integer(std::string name, std::string help) {
  return F(std::move(name), FieldType::Integer, std::move(help));
}
F boolean(std::string name, std::string help) {
  return F(std::move(name), FieldType::Boolean, std::move(help));
}
F text(std::string name, std::string help) {
  return F(std::move(name), FieldType::String, std::move(help));
}
F name_key(std::string help) {
  F f("name", FieldType::String, std::move(help));
  f.identifier();
  return f;
}
F reference(std::string name, Ref ref, std::string help) {
  F f(std::move(name), FieldType::String, std::move(help));
  f.ref(ref);
  return f;
}
F choice(std::string name, std::vector<std::string> choices, std::string help) {
  F f(std::move(name), FieldType::Enum, std::move(help));
  f.choices(std::move(choices));
  return f;
}
F numbers(std::string name, Unit unit, std::string help) {
  F f(std::move(name), FieldType::NumberArray, std::move(help));
  f.unit(unit);
  return f;
}
F vector3(std::string name, Unit unit, std::string help) {
  F f(std::move(name), FieldType::Vector3, std::move(help));
  f.unit(unit);
  return f;
}
F names(std::string name, Ref ref, std::string help) {
  F f(std::move(name), FieldType::StringArray, std::move(help));
  f.ref(ref).unique();
  return f;
}
F matrix(std::string name, std::vector<int> sizes, std::string help) {
  F f(std::move(name), FieldType::Matrix, std::move(help));
  f.sizes(std::move(sizes));
  return f;
}

/// Setter into a member of a nested spec of a Solid (annular_plate / gear_sector keys).
template <class Spec, class V>
std::function<void(Solid&, const FieldValue&)> solid_spec(Spec Solid::*spec, V Spec::*member) {
  return [spec, member](Solid& s, const FieldValue& v) { assign(s.*spec.*member, v); };
}

/// Builder of one Section.
class S {
 public:
  S(std::string name, SectionKind kind, std::string title, std::string help) {
    s_.name = std::move(name);
    s_.kind = kind;
    s_.title = std::move(title);
    s_.help = std::move(help);
  }
  /// Array of tables stored in `parent.*member` (a std::vector).
  template <class P, class T>
  S& in_array(std::vector<T> P::*member) {
    s_.object_type = typeid(T);
    s_.child = [member](void* parent) -> void* {
      auto& items = static_cast<P*>(parent)->*member;
      items.emplace_back();
      return &items.back();
    };
    return *this;
  }
  /// Table stored in `parent.*member`.
  template <class P, class T>
  S& in_table(T P::*member) {
    s_.object_type = typeid(T);
    s_.child = [member](void* parent) -> void* { return &(static_cast<P*>(parent)->*member); };
    return *this;
  }
  template <class P, class T>
  S& in_fn(std::function<T*(P&)> fn) {
    s_.object_type = typeid(T);
    s_.child = [fn](void* parent) -> void* { return fn(*static_cast<P*>(parent)); };
    return *this;
  }
  template <class T>
  S& located(SourceLocation T::*member) {
    s_.locate = [member](void* object, const SourceLocation& where) {
      static_cast<T*>(object)->*member = where;
    };
    return *this;
  }
  template <class T>
  S& finish(std::function<void(T&, const TableContext&)> fn) {
    s_.finish = [fn](void* object, const TableContext& t) { fn(*static_cast<T*>(object), t); };
    return *this;
  }
  S& fields(std::vector<Field> f) {
    s_.fields = std::move(f);
    return *this;
  }
  S& choices(std::vector<Choice> c) {
    s_.choices = std::move(c);
    return *this;
  }
  S& sections(std::vector<Section> s) {
    s_.sections = std::move(s);
    return *this;
  }
  S& variants(std::string discriminator, std::vector<Variant> v) {
    s_.discriminator = std::move(discriminator);
    s_.variants = std::move(v);
    return *this;
  }
  S& required() {
    s_.required = true;
    return *this;
  }
  S& min_count(std::size_t n) {
    s_.min_count = n;
    return *this;
  }
  S& only_in(std::vector<std::string> v) {
    s_.only_in = std::move(v);
    return *this;
  }
  operator Section() const { return s_; }  // NOLINT: builder converts implicitly

 private:
  Section s_;
};

template <class T>
Variant variant(std::string name, std::string help,
                std::function<void(T&, const TableContext&)> fn = {}) {
  Variant v;
  v.name = std::move(name);
  v.help = std::move(help);
  if (fn) v.finish = [fn](void* object, const TableContext& t) { fn(*static_cast<T*>(object), t); };
  return v;
}

/// A value for messages; 12 digits hide the rounding of unit conversions back to the file's unit.
std::string value_text(double x) {
  if (std::isinf(x) || std::isnan(x)) return format_number(x);
  return fmt::format("{:.12g}", x);
}

/// n values from a to b, linear or geometric (a, b > 0 for log).
std::vector<double> spaced(double a, double b, int n, bool log) {
  std::vector<double> out(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.0 : static_cast<double>(i) / (n - 1);
    out[static_cast<std::size_t>(i)] =
        log ? std::exp(std::log(a) + t * (std::log(b) - std::log(a))) : a + t * (b - a);
  }
  if (!out.empty()) out.back() = b;  // exact end point whatever the rounding
  return out;
}

// ---------------------------------------------------------------------------------------------
// Cross-key rules (finish steps)

void finish_material(Material& m, const TableContext& t) {
  if (t.has("poisson_ratio")) {
    const double nu = t.at("poisson_ratio").number;
    m.shear_modulus = m.youngs_modulus / (2.0 * (1.0 + nu));
  }
}

void finish_shaft(Shaft& s, const TableContext& t) {
  double norm = std::hypot(s.axis[0], s.axis[1], s.axis[2]);
  for (auto& a : s.axis) a /= norm;
  if (t.has("gear_ratio") && s.gear_ratio == 0.0)
    t.fail("gear_ratio", "a non-zero number (speed of this shaft / speed of driven_by)", "0");
  if (t.has("driven_by") && s.driven_by == s.name)
    t.fail("driven_by", "the name of another shaft",
           fmt::format("\"{}\", the shaft itself", s.driven_by));
}

void finish_element(ShaftElement& e, const TableContext& t) {
  if (e.inner_diameter >= e.outer_diameter)
    t.fail("inner_diameter",
           fmt::format("a number < outer_diameter = {} m", value_text(e.outer_diameter)),
           value_text(e.inner_diameter));
}

void finish_sensor(Sensor& s, const TableContext& t) {
  if (s.solid.empty()) return;
  if (static_cast<int>(s.dof) >= 3)
    t.fail("dof", "ux, uy or uz (a solid sensor measures the mean translation of its node set)",
           fmt::format("\"{}\"", kComponentNames[static_cast<std::size_t>(s.dof)]));
  // '/' is not allowed in solid names, so this cannot be the name of another node.
  s.node = s.solid + "/" + s.node_set;
}

void finish_node(Node& n, const TableContext&) {
  double norm = std::hypot(n.axis[0], n.axis[1], n.axis[2]);
  for (auto& a : n.axis) a /= norm;
}

void finish_gear_mesh(GearMesh& g, const TableContext&) {
  if (g.mesh_direction) {
    auto& d = *g.mesh_direction;
    const double norm = std::hypot(d[0], d[1], d[2]);
    for (auto& x : d) x /= norm;
  }
}

void finish_disk(Disk& d, const TableContext& t) {
  if (t.has("outer_diameter") && d.inner_diameter >= d.outer_diameter)
    t.fail("inner_diameter",
           fmt::format("a number < outer_diameter = {} m", value_text(d.outer_diameter)),
           value_text(d.inner_diameter));
}

struct BearingKey {
  const char* name;
  int row, col;
  bool damping;
  bool diagonal;
};

// Coefficients in the node frame, over (ux, uy, uz, rx, ry, rz): k.. stiffness, c.. damping,
// t = tilting (rx, ry), tzz = torsional (rz).
constexpr BearingKey kBearingKeys[] = {
    {"kxx", 0, 0, false, true},   {"kxy", 0, 1, false, false},  {"kyx", 1, 0, false, false},
    {"kyy", 1, 1, false, true},   {"kzz", 2, 2, false, true},   {"ktxx", 3, 3, false, true},
    {"ktxy", 3, 4, false, false}, {"ktyx", 4, 3, false, false}, {"ktyy", 4, 4, false, true},
    {"ktzz", 5, 5, false, true},  {"cxx", 0, 0, true, true},    {"cxy", 0, 1, true, false},
    {"cyx", 1, 0, true, false},   {"cyy", 1, 1, true, true},    {"czz", 2, 2, true, true},
    {"ctxx", 3, 3, true, true},   {"ctxy", 3, 4, true, false},  {"ctyx", 4, 3, true, false},
    {"ctyy", 4, 4, true, true},   {"ctzz", 5, 5, true, true},
};

/// Writes one coefficient into every tabulated matrix: a number sets all of them, an array of n
/// values makes the table n long (copying the constant entries already set) and sets entry i.
void set_bearing_entry(Bearing& b, const BearingKey& key, const FieldValue& v) {
  auto& table = key.damping ? b.damping : b.stiffness;
  if (table.empty()) table.push_back(Bearing::Matrix6{});
  const std::size_t index = static_cast<std::size_t>(key.row * 6 + key.col);
  if (!v.is_array) {
    for (auto& m : table) m[index] = v.number;
    return;
  }
  if (table.size() == 1 && v.numbers.size() > 1) table.resize(v.numbers.size(), table[0]);
  for (std::size_t i = 0; i < v.numbers.size() && i < table.size(); ++i)
    table[i][index] = v.numbers[i];
}

void set_bearing_matrix(Bearing& b, bool damping, const FieldValue& v) {
  auto& table = damping ? b.damping : b.stiffness;
  table.clear();
  for (std::size_t k = 0; k < v.count; ++k) {
    Bearing::Matrix6 m{};
    std::copy_n(v.numbers.begin() + static_cast<std::ptrdiff_t>(k * 36), 36, m.begin());
    table.push_back(m);
  }
}

void check_matrix_diagonal(const std::vector<double>& a, int n, std::size_t count,
                           const TableContext& t, const char* key, const char* what) {
  for (std::size_t k = 0; k < count; ++k) {
    for (int i = 0; i < n; ++i) {
      const double d = a[k * static_cast<std::size_t>(n * n) + static_cast<std::size_t>(i * n + i)];
      if (d < 0.0)
        t.fail(key, fmt::format("a {} matrix with diagonal entries >= 0", what),
               fmt::format("{} at row {}{}", value_text(d), i + 1,
                           count > 1 ? fmt::format(" of matrix {}", k + 1) : ""));
    }
  }
}

void finish_bearing(Bearing& b, const TableContext& t) {
  bool any = false;
  for (const auto& key : kBearingKeys) any = any || t.has(key.name);
  if (!any && !t.has("stiffness") && !t.has("damping"))
    t.fail("kxx",
           "at least one stiffness or damping coefficient (kxx, ..., cxx, ..., or the "
           "stiffness / damping matrix)",
           "none");
  for (const char* key : {"stiffness", "damping"}) {
    if (t.has(key)) {
      const auto& v = t.at(key);
      check_matrix_diagonal(v.numbers, 6, v.count, t, key, "6x6");
    }
  }
  for (auto* table : {&b.stiffness, &b.damping}) {
    if (table->empty()) table->push_back(Bearing::Matrix6{});
    if (!b.speeds.empty() && table->size() == 1) table->resize(b.speeds.size(), (*table)[0]);
  }
}

void finish_coupling(Coupling& c, const TableContext& t) {
  const int n = c.node2.empty() ? 6 : 12;
  bool any = false;
  for (const char* key : {"stiffness", "damping", "mass"}) {
    if (!t.has(key)) continue;
    any = true;
    const auto& v = t.at(key);
    if (v.rows != n)
      t.fail(key,
             fmt::format("a {0}x{0} matrix ({1})", n,
                         c.node2.empty() ? "6x6 for a coupling to ground, without node2"
                                         : "12x12 for a coupling between node1 and node2"),
             fmt::format("a {0}x{0} matrix", v.rows));
    check_matrix_diagonal(v.numbers, n, 1, t, key, fmt::format("{0}x{0}", n).c_str());
  }
  if (!any) t.fail("stiffness", "at least one of stiffness, damping, mass", "none");
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const double a = c.mass.empty() ? 0.0 : c.mass[static_cast<std::size_t>(i * n + j)];
      const double b = c.mass.empty() ? 0.0 : c.mass[static_cast<std::size_t>(j * n + i)];
      if (std::abs(a - b) > 1e-12 * std::max({std::abs(a), std::abs(b), 1e-300}))
        t.fail("mass", "a symmetric mass matrix",
               fmt::format("mass[{}][{}] = {} but mass[{}][{}] = {}", i, j, value_text(a), j, i,
                           value_text(b)));
    }
  }
}

void finish_band(DampingBand& b, const TableContext& t) {
  if (b.f_max <= b.f_min)
    t.fail("f_max_hz",
           fmt::format("a frequency > f_min_hz = {} Hz",
                       value_text(t.at("f_min_hz").number / (2.0 * kPi))),
           fmt::format("{} Hz", value_text(t.at("f_max_hz").number / (2.0 * kPi))));
}

/// Speeds from speed_rpm = [...] or speed_start_rpm / speed_stop_rpm / speed_count.
std::vector<double> speed_range(const TableContext& t) {
  if (t.has("speed_rpm")) return t.at("speed_rpm").numbers;
  const double a = t.at("speed_start_rpm").number, b = t.at("speed_stop_rpm").number;
  if (b <= a)
    t.fail("speed_stop_rpm",
           fmt::format("a speed > speed_start_rpm = {} rpm (the range would be empty)",
                       value_text(a / kRpm.to_si)),
           fmt::format("{} rpm", value_text(b / kRpm.to_si)));
  return spaced(a, b, static_cast<int>(t.at("speed_count").integer), false);
}

void finish_campbell(Analysis& a, const TableContext& t) {
  std::get<CampbellSettings>(a.settings).speeds = speed_range(t);
}

void finish_unbalance(Analysis& a, const TableContext& t) {
  std::get<UnbalanceSettings>(a.settings).speeds = speed_range(t);
}

void finish_harmonic(Analysis& a, const TableContext& t) {
  auto& h = std::get<HarmonicSettings>(a.settings);
  if (h.f_max <= h.f_min)
    t.fail("frequency_stop_hz",
           fmt::format("a frequency > frequency_start_hz = {} Hz (the range would be empty)",
                       value_text(h.f_min / kHertz.to_si)),
           fmt::format("{} Hz", value_text(h.f_max / kHertz.to_si)));
  if (h.spacing == Spacing::Log && h.f_min <= 0.0)
    t.fail("frequency_start_hz", "a frequency > 0 Hz for spacing = \"log\"", "0 Hz");
}

void finish_transient(Analysis& a, const TableContext& t) {
  auto& s = std::get<TransientSettings>(a.settings);
  if (s.time_step >= s.duration)
    t.fail("time_step", fmt::format("a time step < duration = {} s", value_text(s.duration)),
           fmt::format("{} s", value_text(s.time_step)));
}

void finish_sweep(Analysis& a, const TableContext& t) {
  auto& s = std::get<SweepSettings>(a.settings);
  const bool log = s.log_x;
  if (t.has("values")) {
    if (log)
      for (double v : s.values)
        if (v <= 0.0) t.fail("values", "values > 0 for spacing = \"log\"", value_text(v));
    return;
  }
  const double start = t.at("start").number, stop = t.at("stop").number;
  if (start == stop)
    t.fail("stop",
           fmt::format("a value different from start = {} (the range would be empty)",
                       value_text(start)),
           value_text(stop));
  if (log && (start <= 0.0 || stop <= 0.0))
    t.fail(start <= 0.0 ? "start" : "stop", "a value > 0 for spacing = \"log\"",
           value_text(start <= 0.0 ? start : stop));
  s.values = spaced(start, stop, static_cast<int>(t.at("count").integer), log);
}

void finish_cyclic(Analysis& a, const TableContext& t) {
  auto& c = std::get<CyclicModalSettings>(a.settings);
  if (t.has("speed_rpm") || t.has("speed_start_rpm")) c.speeds = speed_range(t);
  if (c.reduction == ReductionMethod::None && c.interface_modes > 0)
    t.fail("interface_modes",
           "0 when reduction = \"none\" (interface modes reduce the "
           "interfaces of a reduced sector)",
           std::to_string(c.interface_modes), "set reduction = \"craig_bampton\" or \"guyan\"");
  if (c.interface_modes > 0 && c.interface_modes < 6)
    t.fail("interface_modes", "0 (off) or at least 6, so rigid-body motion survives",
           std::to_string(c.interface_modes));
}

void finish_reduction(Analysis& a, const TableContext& t) {
  auto& r = std::get<ReductionSettings>(a.settings);
  if (r.master_sets.empty())
    t.fail("master_sets",
           "at least one node set of master nodes (interfaces, connections, contact, excitation "
           "or sensor nodes)",
           "none");
  if (r.method == ReductionMethod::None)
    t.fail("reduction", "\"guyan\" or \"craig_bampton\"", "\"none\"");
  if (r.method == ReductionMethod::Guyan && (t.has("reduced_modes") || t.has("reduced_f_max_hz")))
    t.fail(t.has("reduced_modes") ? "reduced_modes" : "reduced_f_max_hz",
           "no fixed-interface modes for reduction = \"guyan\"", "a mode request",
           "use reduction = \"craig_bampton\" to keep modes");
  if (r.method == ReductionMethod::Guyan) r.n_modes = 0;
  for (int n : r.convergence)
    if (r.method == ReductionMethod::CraigBampton && n > r.n_modes && std::isnan(r.f_max))
      t.fail("convergence", fmt::format("mode counts <= reduced_modes = {}", r.n_modes),
             std::to_string(n));
}

void finish_solid(Solid& s, const TableContext& t) {
  const bool needs_material = s.source == SolidSource::AnnularPlate ||
                              s.source == SolidSource::GearSector ||
                              (s.source == SolidSource::MeshFile && s.mesh.ends_with(".msh"));
  if (needs_material && s.material.empty())
    t.fail("material", "a material name (Gmsh and generated meshes carry no material)", "nothing");
  if (!s.spiders.empty() && s.sectors > 1)
    t.fail("sectors", "1 for a solid joined to the rotor by [[solids.spiders]] (the whole body)",
           std::to_string(s.sectors));
  if (s.source == SolidSource::AnnularPlate) {
    const auto& p = s.annular_plate;
    if (p.outer_radius <= p.inner_radius)
      t.fail("outer_radius",
             fmt::format("a radius > inner_radius = {} m", value_text(p.inner_radius)),
             fmt::format("{} m", value_text(p.outer_radius)));
  }
  if (s.source == SolidSource::GearSector) {
    const auto& g = s.gear_sector;
    if (g.teeth % s.sectors != 0)
      t.fail("sectors", fmt::format("a divisor of teeth = {} (whole teeth per sector)", g.teeth),
             std::to_string(s.sectors));
    if (g.groove) {
      if (s.ring_material.empty())
        t.fail("ring_material", "a material name for the damper ring (groove = true)", "nothing");
      for (const char* key : {"groove_width", "groove_depth", "ring_thickness"})
        if (!t.has(key)) t.fail(key, "a value (groove = true)", "nothing");
    }
    const double root = g.module * (g.teeth / 2.0 - 1.25);
    const double radii[] = {g.bore_radius, g.hub_radius, g.rim_inner_radius, root};
    const char* keys[] = {"bore_radius", "hub_radius", "rim_inner_radius"};
    for (int k = 0; k < 3; ++k)
      if (radii[k] >= radii[k + 1])
        t.fail(keys[k],
               fmt::format("a radius < {} = {} m", k + 1 < 3 ? keys[k + 1] : "root radius",
                           value_text(radii[k + 1])),
               fmt::format("{} m", value_text(radii[k])));
  }
}

void finish_gear_pair(GearPair& g, const TableContext& t) {
  const bool bevel = g.type == GearType::StraightBevel || g.type == GearType::SpiralBevel ||
                     g.type == GearType::Hypoid;
  if (g.internal && bevel)
    t.fail("internal", "false for bevel and hypoid gears (internal gears are spur or helical)",
           "true");
  if (g.internal && g.teeth2 <= g.teeth1)
    t.fail("teeth2",
           fmt::format("more teeth than gear 1 (teeth1 = {}) for an internal gear pair", g.teeth1),
           std::to_string(g.teeth2));
  if (t.has("rim_thickness") != t.has("web_thickness"))
    t.fail(t.has("rim_thickness") ? "web_thickness" : "rim_thickness",
           "rim_thickness and web_thickness together (a gear blank with a web), or neither",
           "only one of them");
  if (!t.has("ste_file") &&
      (t.has("ste_interpolation") || t.has("ste_extrapolation") || t.has("ste_speed_rpm")))
    t.fail(t.has("ste_interpolation")   ? "ste_interpolation"
           : t.has("ste_extrapolation") ? "ste_extrapolation"
                                        : "ste_speed_rpm",
           "an ste_file to apply to (the synthetic STE from ISO 6336 is sampled uniformly)",
           "no ste_file");
}

void finish_mesh_force(Analysis& a, const TableContext& t) {
  auto& s = std::get<MeshForceSettings>(a.settings);
  s.speeds = speed_range(t);
  if (s.speeds.front() <= 0.0)
    t.fail(t.has("speed_rpm") ? "speed_rpm" : "speed_start_rpm",
           "speeds > 0 rpm (the mesh frequency must be positive)", "0 rpm");
  if (s.detail_speeds.size() > 8)
    t.fail("detail_rpm", "at most 8 speeds for time histories",
           fmt::format("{} speeds", s.detail_speeds.size()));
}

void finish_correlation(Analysis& a, const TableContext& t) {
  auto& s = std::get<CorrelationSettings>(a.settings);
  s.reference_is_speed = !t.has("reference_peak_hz");
  const bool reference = t.has("reference_peak_rpm") || t.has("reference_peak_hz");
  for (const char* key : {"reference_amplitude", "reference_q"})
    if (t.has(key) && !reference)
      t.fail(key, "reference_peak_rpm or reference_peak_hz with it (where the reference peak is)",
             "no reference peak position");
}

/// force_amplitude = 1.0 or [a1, a2, ...] (NumberOrArray): the amplitudes in N.
std::vector<double> amplitudes_of(const FieldValue& v) {
  return v.is_array ? v.numbers : std::vector<double>{v.number};
}

/// The keys a cyclic forced response and a damper-ring response share: speeds, the gear pair's
/// keys, the excitation and the sensors.
void finish_tooth_excitation(CyclicForcedResponseSettings& s, const TableContext& t) {
  s.speeds = speed_range(t);
  if (s.speeds.front() <= 0.0)
    t.fail(t.has("speed_rpm") ? "speed_rpm" : "speed_start_rpm",
           "speeds > 0 rpm (the excitation frequency k W must be positive)", "0 rpm");
  const bool pair = t.has("pair");
  for (const char* key :
       {"gear", "model", "contact_loss", "window_shift", "contact_ratio", "harmonics_rpm"})
    if (t.has(key) && !pair)
      t.fail(key, "a `pair` whose tooth force it shapes (or leave it out with force_amplitude)",
             "no pair");
  if (t.has("force_direction") && pair)
    t.fail("force_direction",
           "no force_direction with a gear pair (its tooth forces set the direction)",
           "a direction");
  if (pair && s.model == MeshForceModel::Dynamic && !t.has("harmonics_rpm"))
    t.fail("harmonics_rpm",
           "the speed of gear 1 at which the dynamic mesh force is computed (model = "
           "\"dynamic\")",
           "nothing", "give harmonics_rpm, or use model = \"infinite_inertia\"");
  if (s.sensor_sets.empty() && s.sensor_nodes.empty())
    t.fail("sensor_sets", "at least one sensor point: sensor_sets or sensor_nodes", "neither");
}

void finish_cyclic_forced(Analysis& a, const TableContext& t) {
  auto& s = std::get<CyclicForcedResponseSettings>(a.settings);
  finish_tooth_excitation(s, t);
  if (t.has("force_amplitude")) {
    const FieldValue& v = t.at("force_amplitude");
    if (v.is_array && v.count != s.engine_orders.size())
      t.fail(
          "force_amplitude",
          s.engine_orders.empty()
              ? std::string("a single amplitude for every order (a list needs engine_orders "
                            "with one order per amplitude)")
              : fmt::format("{} amplitudes, one per engine_orders entry", s.engine_orders.size()),
          fmt::format("{} amplitudes", v.count));
  }
  if (t.has("engine_orders") && t.has("orders_per_diameter"))
    t.fail("orders_per_diameter", "no orders_per_diameter when engine_orders lists the orders",
           std::to_string(s.orders_per_diameter));
  for (const char* key : {"measured_sensor", "measured_engine_order", "scale_to_measured"})
    if (t.has(key) && !t.has("measured_file"))
      t.fail(key, "a measured_file to compare with", "no measured_file");
  if (s.measured_engine_order > 0 && !s.engine_orders.empty() &&
      std::find(s.engine_orders.begin(), s.engine_orders.end(), s.measured_engine_order) ==
          s.engine_orders.end())
    t.fail("measured_engine_order", "one of engine_orders (or 0: the superposed sum)",
           std::to_string(s.measured_engine_order));
  if (s.measured_engine_order == 0 && t.has("measured_file") && !s.superpose)
    t.fail("measured_engine_order",
           "the engine order compared with the measurement (the superposed sum needs superpose "
           "= true)",
           "0");
  if (s.reduction == ReductionMethod::Guyan)
    t.fail("reduction", "\"none\" or \"craig_bampton\" (the forced response sums modes)",
           "\"guyan\"");
}

void finish_damper_ring(Analysis& a, const TableContext& t) {
  auto& s = std::get<DamperRingResponseSettings>(a.settings);
  finish_tooth_excitation(s, t);
  if (s.reduction == ReductionMethod::Guyan)
    t.fail("reduction", "\"none\" or \"craig_bampton\" (the receptance sums the sector's modes)",
           "\"guyan\"");
  s.engine_orders = {s.engine_order};
  if (t.has("force_amplitude")) {
    const FieldValue& v = t.at("force_amplitude");
    if (v.is_array && v.count > static_cast<std::size_t>(s.harmonics))
      t.fail("force_amplitude",
             fmt::format("at most {} amplitudes: F_k, F_2k, ... for harmonics 1 .. harmonics",
                         s.harmonics),
             fmt::format("{} amplitudes", v.count), "raise harmonics, or drop amplitudes");
  }
  if (s.time_samples > 0 && s.time_samples < 2 * s.harmonics + 1)
    t.fail("time_samples",
           fmt::format("at least 2 harmonics + 1 = {} samples per period", 2 * s.harmonics + 1),
           std::to_string(s.time_samples));
  const bool sweep = s.sweep != DamperSweep::None;
  if (t.has("performance_values") && !sweep)
    t.fail("performance_values", "a performance_parameter they are values of", "none");
  if (sweep && s.sweep_values.empty())
    t.fail("performance_values", "the values of performance_parameter (at least one)", "none");
  if (sweep && s.sweep != DamperSweep::FrictionCoefficient)
    for (std::size_t i = 0; i < s.sweep_values.size(); ++i)
      if (!(s.sweep_values[i] > 0.0))
        t.fail(fmt::format("performance_values[{}]", i), "factors > 0",
               fmt::format("{}", s.sweep_values[i]));
}

void finish_gear_forced(Analysis& a, const TableContext& t) {
  auto& s = std::get<GearForcedResponseSettings>(a.settings);
  s.speeds = speed_range(t);
  for (const char* key : {"measured_sensor", "measured_mesh_order", "scale_to_measured"})
    if (t.has(key) && !t.has("measured_file"))
      t.fail(key, "a measured_file to compare with", "no measured_file");
  if (s.speeds.front() <= 0.0)
    t.fail(t.has("speed_rpm") ? "speed_rpm" : "speed_start_rpm",
           "speeds > 0 rpm (the mesh frequency must be positive)", "0 rpm");
  if (t.has("force_amplitude") && t.at("force_amplitude").is_array) {
    const std::size_t n = t.at("force_amplitude").count;
    if (!t.has("max_mesh_order"))
      s.max_mesh_order = static_cast<int>(n);
    else if (n != static_cast<std::size_t>(s.max_mesh_order))
      t.fail("force_amplitude",
             fmt::format("{} amplitudes, one per mesh order 1 .. max_mesh_order", s.max_mesh_order),
             fmt::format("{} amplitudes", n));
  }
  if (s.measured_mesh_order > s.max_mesh_order)
    t.fail("measured_mesh_order",
           fmt::format("a mesh order 1 .. max_mesh_order = {} (or 0: the sum)", s.max_mesh_order),
           std::to_string(s.measured_mesh_order));
}

void finish_output(SweepOutput& o, const TableContext& t) {
  if (t.has("label")) return;
  static const char* const kNames[] = {"natural_frequency", "critical_speed", "peak_amplitude",
                                       "peak_location", "amplitude_at"};
  const char* stem = kNames[static_cast<int>(o.quantity)];
  if (o.quantity == SweepOutput::Quantity::NaturalFrequency ||
      o.quantity == SweepOutput::Quantity::CriticalSpeed)
    o.label = fmt::format("{}_{}", stem, o.mode);
  else
    o.label = fmt::format("{}_{}", stem, o.sensor);
}

// ---------------------------------------------------------------------------------------------
// The table

const std::vector<std::string> kAnalysisTypes(kAnalysisTypeNames.begin(), kAnalysisTypeNames.end());

void set_analysis_type(Analysis& a, const FieldValue& v) {
  constexpr AnalysisType kTypes[] = {AnalysisType::Modal,
                                     AnalysisType::Campbell,
                                     AnalysisType::Harmonic,
                                     AnalysisType::Unbalance,
                                     AnalysisType::Transient,
                                     AnalysisType::Sweep,
                                     AnalysisType::SolidModal,
                                     AnalysisType::CyclicModal,
                                     AnalysisType::Reduction,
                                     AnalysisType::GearPair,
                                     AnalysisType::MeshForce,
                                     AnalysisType::MeshHarmonics,
                                     AnalysisType::Correlation,
                                     AnalysisType::CyclicForcedResponse,
                                     AnalysisType::GearForcedResponse,
                                     AnalysisType::DamperRingResponse};
  a.type = kTypes[v.choice];
  switch (a.type) {
    case AnalysisType::Modal:
      a.settings = ModalSettings{};
      break;
    case AnalysisType::Campbell:
      a.settings = CampbellSettings{};
      break;
    case AnalysisType::Harmonic:
      a.settings = HarmonicSettings{};
      break;
    case AnalysisType::Unbalance:
      a.settings = UnbalanceSettings{};
      break;
    case AnalysisType::Transient:
      a.settings = TransientSettings{};
      break;
    case AnalysisType::Sweep:
      a.settings = SweepSettings{};
      break;
    case AnalysisType::SolidModal:
      a.settings = SolidModalSettings{};
      break;
    case AnalysisType::CyclicModal:
      a.settings = CyclicModalSettings{};
      break;
    case AnalysisType::Reduction:
      a.settings = ReductionSettings{};
      break;
    case AnalysisType::GearPair:
      a.settings = GearPairSettings{};
      break;
    case AnalysisType::MeshForce:
      a.settings = MeshForceSettings{};
      break;
    case AnalysisType::MeshHarmonics:
      a.settings = MeshHarmonicsSettings{};
      break;
    case AnalysisType::Correlation:
      a.settings = CorrelationSettings{};
      break;
    case AnalysisType::CyclicForcedResponse:
      a.settings = CyclicForcedResponseSettings{};
      break;
    case AnalysisType::GearForcedResponse:
      a.settings = GearForcedResponseSettings{};
      break;
    case AnalysisType::DamperRingResponse:
      a.settings = DamperRingResponseSettings{};
      break;
  }
}

std::vector<Field> bearing_coefficient_fields() {
  std::vector<Field> out;
  for (const auto& key : kBearingKeys) {
    const bool tilt = key.row >= 3;
    Unit unit = key.damping ? (tilt ? kTiltDamping : kDampingCoefficient)
                            : (tilt ? kTiltStiffness : kStiffness);
    const char* axis_names[] = {"x", "y", "z", "rx", "ry", "rz"};
    std::string help = fmt::format("{} {} coefficient: {} at {} from motion in {}{}.",
                                   key.diagonal ? "Direct" : "Cross-coupled",
                                   key.damping ? "damping" : "stiffness", tilt ? "moment" : "force",
                                   axis_names[key.row], axis_names[key.col],
                                   key.row == 5 ? " (torsional)"
                                   : tilt       ? " (tilting)"
                                                : "");
    F f(key.name, FieldType::NumberOrArray, help);
    f.unit(unit)
        .def("0.0")
        .tabulated_by("speed_rpm")
        .to_fn<Bearing>([key](Bearing& b, const FieldValue& v) { set_bearing_entry(b, key, v); });
    if (key.diagonal) f.ge(0.0);
    out.push_back(f);
  }
  return out;
}

Section make_schema() {
  const std::vector<std::string> kGearTypes = {"spur", "helical", "straight_bevel", "spiral_bevel",
                                               "hypoid"};
  const std::vector<std::string> kHelical = {"helical", "spiral_bevel", "hypoid"};
  const std::vector<std::string> kBevel = {"straight_bevel", "spiral_bevel", "hypoid"};

  Section materials =
      S("materials", SectionKind::ArrayOfTables, "[[materials]]",
        "Isotropic linear-elastic materials, referred to by name from shafts, shaft elements "
        "and disks.")
          .in_array(&Model::materials)
          .located(&Material::where)
          .fields({
              name_key("Unique material name.").required().to(&Material::name),
              number("youngs_modulus", kPascal, "Young's modulus E.")
                  .required()
                  .gt(0)
                  .to(&Material::youngs_modulus),
              number("shear_modulus", kPascal, "Shear modulus G.")
                  .required()
                  .gt(0)
                  .to(&Material::shear_modulus),
              number("poisson_ratio", kNoUnit, "Poisson's ratio nu; gives G = E / (2 (1 + nu)).")
                  .required()
                  .gt(-1.0)
                  .le(0.5)
                  .read_by_finish<Material>(),
              number("density", kDensity, "Mass density rho.")
                  .required()
                  .gt(0)
                  .to(&Material::density),
          })
          .choices({{{{"shear_modulus"}, {"poisson_ratio"}}, true, {}}})
          .finish<Material>(finish_material);

  Section elements =
      S("elements", SectionKind::ArrayOfTables, "[[shafts.elements]]",
        "Sections of the shaft from its origin along its axis, in order. Each is cut into "
        "`divisions` equal beam elements; the stations between them are the shaft's nodes.")
          .in_array(&Shaft::elements)
          .located(&ShaftElement::where)
          .required()
          .min_count(1)
          .fields({
              number("length", kMetre, "Length of the section.")
                  .required()
                  .gt(0)
                  .to(&ShaftElement::length),
              number("outer_diameter", kMetre, "Outer diameter.")
                  .required()
                  .gt(0)
                  .to(&ShaftElement::outer_diameter),
              number("inner_diameter", kMetre,
                     "Bore diameter (0: solid); must be < "
                     "outer_diameter.")
                  .def("0.0")
                  .ge(0)
                  .to(&ShaftElement::inner_diameter),
              reference("material", Ref::Material, "Material of this section.")
                  .note("the shaft's material")
                  .to(&ShaftElement::material),
              number("loss_factor", kNoUnit,
                     "Structural (hysteretic) loss factor eta of this section: stiffness "
                     "K (1 + i eta) in frequency-domain analyses.")
                  .def("0.0")
                  .ge(0)
                  .to(&ShaftElement::loss_factor),
              integer("divisions", "Number of equal beam elements made from this section.")
                  .def("1")
                  .ge(1)
                  .le(1000)
                  .to(&ShaftElement::divisions),
          })
          .finish<ShaftElement>(finish_element);

  Section shafts =
      S("shafts", SectionKind::ArrayOfTables, "[[shafts]]",
        "Straight shafts of beam elements. Node k of shaft `s` is named \"s.k\" (k = 0 at the "
        "origin, counted after `divisions` are expanded). Each shaft spins at speed_ratio times "
        "the reference speed of the analysis.")
          .in_array(&Model::shafts)
          .located(&Shaft::where)
          .fields({
              name_key("Unique shaft name; its nodes are `\"<name>.<k>\"`.")
                  .required()
                  .to(&Shaft::name),
              reference("material", Ref::Material, "Material of the shaft's elements.")
                  .required()
                  .to(&Shaft::material),
              vector3("origin", kMetre, "Position of node 0.")
                  .def("[0.0, 0.0, 0.0]")
                  .to(&Shaft::origin),
              vector3("axis", kNoUnit, "Direction of the shaft (normalised); the spin axis.")
                  .def("[0.0, 0.0, 1.0]")
                  .nonzero()
                  .to(&Shaft::axis),
              number("speed_ratio", kNoUnit,
                     "Spin speed / reference speed (negative: opposite sense about `axis`).")
                  .def("1.0")
                  .to(&Shaft::speed_ratio),
              reference("driven_by", Ref::Shaft,
                        "Shaft this one is driven from through a gear pair; its speed_ratio is "
                        "gear_ratio x the speed_ratio of that shaft.")
                  .required()
                  .to(&Shaft::driven_by),
              number("gear_ratio", kNoUnit,
                     "Speed of this shaft / speed of `driven_by` (non-zero; negative for the "
                     "opposite sense).")
                  .required()
                  .to(&Shaft::gear_ratio),
              number("shear_coefficient", kNoUnit, "Timoshenko shear coefficient kappa.")
                  .gt(0)
                  .le(1.0)
                  .note("Cowper's (1966) value for each element's (hollow) circle")
                  .to(&Shaft::shear_coefficient),
              choice("theory", {"timoshenko", "euler_bernoulli"},
                     "Beam theory: Timoshenko (shear deformation) or Euler-Bernoulli.")
                  .def("\"timoshenko\"")
                  .to_enum(&Shaft::theory, {BeamTheory::Timoshenko, BeamTheory::EulerBernoulli}),
              boolean("rotary_inertia", "Include the rotary inertia of the cross-sections.")
                  .def("true")
                  .to(&Shaft::rotary_inertia),
              boolean("gyroscopic", "Include gyroscopic moments of the spinning shaft.")
                  .def("true")
                  .to(&Shaft::gyroscopic),
          })
          .choices({{{{"speed_ratio"}, {"driven_by", "gear_ratio"}}, false, {}}})
          .sections({elements})
          .finish<Shaft>(finish_shaft);

  Section nodes =
      S("nodes", SectionKind::ArrayOfTables, "[[nodes]]",
        "Nodes that are not on a shaft (a gear on a flexible web, a housing point).")
          .in_array(&Model::nodes)
          .located(&Node::where)
          .fields({
              name_key("Unique node name (must differ from every shaft station name).")
                  .required()
                  .to(&Node::name),
              vector3("position", kMetre, "Position of the node.").required().to(&Node::position),
              vector3("axis", kNoUnit, "Spin axis of the node frame (normalised).")
                  .def("[0.0, 0.0, 1.0]")
                  .nonzero()
                  .to(&Node::axis),
              reference("spin_of", Ref::Shaft, "Shaft whose speed this node spins with.")
                  .note("not spinning")
                  .to(&Node::spin_of),
          })
          .finish<Node>(finish_node);

  Section disks =
      S("disks", SectionKind::ArrayOfTables, "[[disks]]",
        "Rigid disks (gears, impellers) at a node: give mass and inertias, or the geometry of a "
        "uniform annular disk, from which m = rho pi (ro^2 - ri^2) h, Ip = m (ro^2 + ri^2) / 2, "
        "Id = m (3 (ro^2 + ri^2) + h^2) / 12.")
          .in_array(&Model::disks)
          .located(&Disk::where)
          .fields({
              name_key("Name of the disk.").default_from_path().to(&Disk::name),
              reference("node", Ref::Node, "Node carrying the disk.").required().to(&Disk::node),
              number("mass", kKilogram, "Mass m.").required().gt(0).to(&Disk::mass),
              number("polar_inertia", kInertia, "Polar moment of inertia Ip about the spin axis.")
                  .required()
                  .ge(0)
                  .to(&Disk::polar_inertia),
              number("diametral_inertia", kInertia, "Moment of inertia Id about a diameter.")
                  .required()
                  .ge(0)
                  .to(&Disk::diametral_inertia),
              number("outer_diameter", kMetre, "Outer diameter 2 ro.")
                  .required()
                  .gt(0)
                  .to(&Disk::outer_diameter),
              number("inner_diameter", kMetre, "Bore diameter 2 ri (< outer_diameter).")
                  .def("0.0")
                  .ge(0)
                  .to(&Disk::inner_diameter),
              number("thickness", kMetre, "Axial thickness h.")
                  .required()
                  .gt(0)
                  .to(&Disk::thickness),
              reference("material", Ref::Material, "Material (its density is used).")
                  .required()
                  .to(&Disk::material),
          })
          .choices({{{{"mass", "polar_inertia", "diametral_inertia"},
                      {"outer_diameter", "inner_diameter", "thickness", "material"}},
                     true,
                     {}}})
          .finish<Disk>(finish_disk);

  Section point_masses =
      S("point_masses", SectionKind::ArrayOfTables, "[[point_masses]]",
        "Point masses (translational inertia only) at a node.")
          .in_array(&Model::point_masses)
          .located(&PointMass::where)
          .fields({
              name_key("Name of the mass.").default_from_path().to(&PointMass::name),
              reference("node", Ref::Node, "Node carrying the mass.")
                  .required()
                  .to(&PointMass::node),
              number("mass", kKilogram, "Mass.").required().gt(0).to(&PointMass::mass),
          });

  std::vector<Field> bearing_fields = {
      name_key("Name of the bearing.").default_from_path().to(&Bearing::name),
      reference("node", Ref::Node, "Node of the bearing (its frame is the bearing's frame).")
          .required()
          .to(&Bearing::node),
      reference("node2", Ref::Node,
                "Second node: the bearing acts on the relative motion node - node2.")
          .note("ground")
          .to(&Bearing::node2),
      numbers("speed_rpm", kRpm,
              "Reference speeds of a tabulated bearing: coefficients given as arrays have one "
              "value per speed, interpolated linearly and held constant outside.")
          .ge(0)
          .increasing()
          .min_items(1)
          .note("constant coefficients")
          .to(&Bearing::speeds),
  };
  for (auto& f : bearing_coefficient_fields()) bearing_fields.push_back(std::move(f));
  {
    F stiffness = matrix("stiffness", {6},
                         "Full 6x6 stiffness matrix over (ux, uy, uz, rx, ry, "
                         "rz) in the node frame, instead of the k.. keys.");
    stiffness.tabulated_by("speed_rpm")
        .unit_note("N/m, N/rad, N, N m/rad by block")
        .to_fn<Bearing>([](Bearing& b, const FieldValue& v) { set_bearing_matrix(b, false, v); });
    F damping = matrix("damping", {6}, "Full 6x6 damping matrix, instead of the c.. keys.");
    damping.tabulated_by("speed_rpm")
        .unit_note("N s/m, N s/rad, N s, N m s/rad by block")
        .to_fn<Bearing>([](Bearing& b, const FieldValue& v) { set_bearing_matrix(b, true, v); });
    bearing_fields.push_back(stiffness);
    bearing_fields.push_back(damping);
  }
  std::vector<std::string> stiffness_keys, damping_keys;
  for (const auto& key : kBearingKeys)
    (key.damping ? damping_keys : stiffness_keys).push_back(key.name);

  Section bearings =
      S("bearings", SectionKind::ArrayOfTables, "[[bearings]]",
        "Bearings and bushings: linear stiffness and damping between a node and ground, or "
        "between two nodes, in the node's frame. Each coefficient is a number, or an array "
        "with one value per `speed_rpm` entry.")
          .in_array(&Model::bearings)
          .located(&Bearing::where)
          .fields(bearing_fields)
          .choices({{{stiffness_keys, {"stiffness"}}, false, {}},
                    {{damping_keys, {"damping"}}, false, {}}})
          .finish<Bearing>(finish_bearing);

  Section couplings =
      S("couplings", SectionKind::ArrayOfTables, "[[couplings]]",
        "General linear elements: full stiffness, damping and mass matrices in global "
        "coordinates, 12x12 over (node1 DOFs, node2 DOFs), or 6x6 to ground without node2. "
        "DOF order per node: ux, uy, uz, rx, ry, rz.")
          .in_array(&Model::couplings)
          .located(&Coupling::where)
          .fields({
              name_key("Name of the coupling.").default_from_path().to(&Coupling::name),
              reference("node1", Ref::Node, "First node.").required().to(&Coupling::node1),
              reference("node2", Ref::Node, "Second node.")
                  .note("ground (6x6 matrices)")
                  .to(&Coupling::node2),
              matrix("stiffness", {6, 12}, "Stiffness matrix (diagonal >= 0).")
                  .unit_note("N/m, N/rad, N, N m/rad by block")
                  .note("zero")
                  .to(&Coupling::stiffness),
              matrix("damping", {6, 12}, "Damping matrix (diagonal >= 0).")
                  .unit_note("N s/m, N s/rad, N s, N m s/rad by block")
                  .note("zero")
                  .to(&Coupling::damping),
              matrix("mass", {6, 12}, "Mass matrix (symmetric, diagonal >= 0).")
                  .unit_note("kg, kg m, kg m^2 by block")
                  .note("zero")
                  .to(&Coupling::mass),
          })
          .finish<Coupling>(finish_coupling);

  Section gear_meshes =
      S("gear_meshes", SectionKind::ArrayOfTables, "[[gear_meshes]]",
        "Linear gear-mesh couplings: a spring-damper along the line of action between the "
        "nodes of two gears (gear1 drives). Bevel and hypoid pairs are treated as the "
        "equivalent spur pair at mid face.")
          .in_array(&Model::gear_meshes)
          .located(&GearMesh::where)
          .fields({
              name_key("Name of the mesh.").default_from_path().to(&GearMesh::name),
              reference("gear1", Ref::Node, "Node of the driving gear.")
                  .required()
                  .to(&GearMesh::gear1),
              reference("gear2", Ref::Node, "Node of the driven gear.")
                  .required()
                  .to(&GearMesh::gear2),
              choice("type", kGearTypes, "Gear type; selects the keys below.")
                  .def("\"spur\"")
                  .to_enum(&GearMesh::type,
                           {GearType::Spur, GearType::Helical, GearType::StraightBevel,
                            GearType::SpiralBevel, GearType::Hypoid}),
              integer("teeth1", "Number of teeth of gear1 (for mesh orders).")
                  .ge(1)
                  .le(100000)
                  .note("unknown (no mesh orders)")
                  .to(&GearMesh::teeth1),
              integer("teeth2", "Number of teeth of gear2.")
                  .ge(1)
                  .le(100000)
                  .note("unknown (no mesh orders)")
                  .to(&GearMesh::teeth2),
              number("base_radius1", kMetre,
                     "Base radius of gear1 (equivalent spur gear for "
                     "bevels).")
                  .required()
                  .gt(0)
                  .to(&GearMesh::base_radius1),
              number("base_radius2", kMetre, "Base radius of gear2.")
                  .required()
                  .gt(0)
                  .to(&GearMesh::base_radius2),
              number("pressure_angle_deg", kDegree,
                     "Pressure angle: transverse for spur, normal for helical and bevel gears.")
                  .def("20.0")
                  .gt(0)
                  .lt(60)
                  .to(&GearMesh::pressure_angle),
              number("helix_angle_deg", kDegree, "Helix angle, or mean spiral angle of bevels.")
                  .required()
                  .gt(0)
                  .lt(90)
                  .only_in(kHelical)
                  .to(&GearMesh::helix_angle),
              number("pitch_cone_angle1_deg", kDegree, "Pitch cone angle of gear1.")
                  .required()
                  .gt(0)
                  .lt(90)
                  .only_in(kBevel)
                  .to(&GearMesh::pitch_cone_angle1),
              number("pitch_cone_angle2_deg", kDegree, "Pitch cone angle of gear2.")
                  .required()
                  .gt(0)
                  .lt(90)
                  .only_in(kBevel)
                  .to(&GearMesh::pitch_cone_angle2),
              choice("hand", {"right", "left"}, "Hand of gear1's helix or spiral.")
                  .def("\"right\"")
                  .only_in(kHelical)
                  .to_enum(&GearMesh::hand, {Hand::Right, Hand::Left}),
              choice("flank", {"drive", "coast"}, "Loaded flank.")
                  .def("\"drive\"")
                  .to_enum(&GearMesh::flank, {Flank::Drive, Flank::Coast}),
              number("stiffness", kStiffness,
                     "Mesh stiffness along the line of action (0: gears not coupled, e.g. a "
                     "variant without the mesh).")
                  .required()
                  .ge(0)
                  .to(&GearMesh::stiffness),
              number("damping", kDampingCoefficient, "Mesh damping along the line of action.")
                  .def("0.0")
                  .ge(0)
                  .to(&GearMesh::damping),
              vector3("mesh_direction", kNoUnit,
                      "Direction from gear1's centre towards the pitch point.")
                  .nonzero()
                  .note("from gear1's node towards gear2's node")
                  .to(&GearMesh::mesh_direction),
          })
          .variants("type",
                    {
                        variant<GearMesh>("spur", "Spur gears: no helix, no cone angles."),
                        variant<GearMesh>("helical", "Parallel-axis helical gears."),
                        variant<GearMesh>("straight_bevel", "Straight bevel gears."),
                        variant<GearMesh>("spiral_bevel", "Spiral bevel gears."),
                        variant<GearMesh>("hypoid",
                                          "Hypoid gears (equivalent spiral bevel at mid face)."),
                    })
          .finish<GearMesh>(finish_gear_mesh);

  Section constraints =
      S("constraints", SectionKind::ArrayOfTables, "[[constraints]]",
        "Fixed DOFs (in the node's frame), removed from the equations.")
          .in_array(&Model::constraints)
          .located(&Constraint::where)
          .fields({
              reference("node", Ref::Node, "Constrained node.").required().to(&Constraint::node),
              F("dofs", FieldType::DofList, "Fixed DOFs.")
                  .required()
                  .choices(kComponentChoices)
                  .to(&Constraint::dofs),
          });

  Section unbalances =
      S("unbalances", SectionKind::ArrayOfTables, "[[unbalances]]",
        "Rotating unbalances: force m e (r Omega)^2 turning with the node's spin.")
          .in_array(&Model::unbalances)
          .located(&Unbalance::where)
          .fields({
              name_key("Name of the unbalance.").default_from_path().to(&Unbalance::name),
              reference("node", Ref::Node, "Node of the unbalance (spinning).")
                  .required()
                  .to(&Unbalance::node),
              number("mass_eccentricity", kMassEccentricity, "Unbalance m e.")
                  .required()
                  .gt(0)
                  .to(&Unbalance::mass_eccentricity),
              number("phase_deg", kDegree, "Angular position at t = 0, from the node's e1 axis.")
                  .def("0.0")
                  .to(&Unbalance::phase),
          });

  Section forces =
      S("forces", SectionKind::ArrayOfTables, "[[forces]]",
        "Harmonic forces and moments at a node, along a DOF of the node frame.")
          .in_array(&Model::forces)
          .located(&HarmonicForce::where)
          .fields({
              name_key("Name of the force.").default_from_path().to(&HarmonicForce::name),
              reference("node", Ref::Node, "Node loaded.").required().to(&HarmonicForce::node),
              choice("dof", kComponentChoices, "Direction (rx, ry, rz: a moment).")
                  .required()
                  .to(&HarmonicForce::dof),
              number("amplitude", kNewton, "Amplitude.")
                  .unit_note("N, or N m for rx, ry, rz")
                  .required()
                  .ge(0)
                  .to(&HarmonicForce::amplitude),
              number("phase_deg", kDegree, "Phase.").def("0.0").to(&HarmonicForce::phase),
          });

  Section sensors =
      S("sensors", SectionKind::ArrayOfTables, "[[sensors]]",
        "Response outputs: a DOF of a node, in the node's frame; or the mean translation of a "
        "node set of a solid joined to the rotor ([[solids.spiders]]), in global axes. A solid "
        "sensor's node set becomes a physical (master) point of the solid's reduction, node "
        "\"<solid>/<node_set>\" of the system.")
          .in_array(&Model::sensors)
          .located(&Sensor::where)
          .fields({
              name_key("Unique sensor name (used in result columns).").required().to(&Sensor::name),
              reference("node", Ref::Node, "Node measured.").required().to(&Sensor::node),
              reference("solid", Ref::Solid,
                        "Solid measured (joined to the rotor by [[solids.spiders]]).")
                  .required()
                  .to(&Sensor::solid),
              text("node_set",
                   "Node set of the solid's mesh whose mean translation (sum u_i / n) is measured.")
                  .required()
                  .to(&Sensor::node_set),
              choice("dof", kComponentChoices,
                     "DOF measured (a solid sensor: ux, uy or uz in global axes).")
                  .required()
                  .to(&Sensor::dof),
          })
          .choices({{{{"node"}, {"solid", "node_set"}}, true, {}}})
          .finish<Sensor>(finish_sensor);

  Section bands = S("bands", SectionKind::ArrayOfTables, "[[damping.bands]]",
                    "Modal damping ratio for the modes whose undamped frequency lies in [f_min_hz, "
                    "f_max_hz); bands must not overlap.")
                      .in_array(&Damping::bands)
                      .fields({
                          number("f_min_hz", kHertz, "Lower band edge.")
                              .required()
                              .ge(0)
                              .to(&DampingBand::f_min),
                          number("f_max_hz", kHertz, "Upper band edge (may be inf).")
                              .required()
                              .gt(0)
                              .allow_infinity()
                              .to(&DampingBand::f_max),
                          number("ratio", kNoUnit, "Modal damping ratio zeta in the band.")
                              .required()
                              .ge(0)
                              .to(&DampingBand::ratio),
                      })
                      .finish<DampingBand>(finish_band);

  Section damping =
      S("damping", SectionKind::Table, "[damping]",
        "Global damping: Rayleigh C = alpha M + beta K, structural loss factor, and modal "
        "damping ratios (per mode, per band, or one for all modes).")
          .in_table(&Model::damping)
          .fields({
              number("rayleigh_alpha", kPerSecond, "Mass-proportional coefficient alpha.")
                  .def("0.0")
                  .ge(0)
                  .to(&Damping::rayleigh_alpha),
              number("rayleigh_beta", kSecond, "Stiffness-proportional coefficient beta.")
                  .def("0.0")
                  .ge(0)
                  .to(&Damping::rayleigh_beta),
              number("loss_factor", kNoUnit,
                     "Structural loss factor eta of the whole model, K (1 + i eta) in the "
                     "frequency domain.")
                  .def("0.0")
                  .ge(0)
                  .to(&Damping::loss_factor),
              number("modal_ratio", kNoUnit,
                     "Damping ratio of every mode not covered by modal_ratios or bands.")
                  .def("0.0")
                  .ge(0)
                  .to(&Damping::modal_ratio),
              numbers("modal_ratios", kNoUnit,
                      "Damping ratios of the first modes, in order of undamped frequency.")
                  .ge(0)
                  .note("modal_ratio and bands apply")
                  .to(&Damping::modal_ratios),
          })
          .sections({bands});

  // --- solids ---
  const std::vector<std::string> kPlate = {"annular_plate"};
  const std::vector<std::string> kGear = {"gear_sector"};
  auto plate = [](auto member) { return solid_spec(&Solid::annular_plate, member); };
  auto gear = [](auto member) { return solid_spec(&Solid::gear_sector, member); };
  Section spiders =
      S("spiders", SectionKind::ArrayOfTables, "[[solids.spiders]]",
        "Joints of the solid to rotor nodes through node sets of its mesh (RBE2 / RBE3-like). "
        "Each adds a reference point at the rotor node's position, whose 6 DOFs (global axes, "
        "rotated into the node frame) become the rotor node's.")
          .in_array(&Solid::spiders)
          .located(&Spider::where)
          .only_in({"mesh", "annular_plate", "gear_sector"})
          .fields({
              text("node_set", "Node set of the solid's mesh that is joined.")
                  .required()
                  .to(&Spider::node_set),
              reference("node", Ref::Node,
                        "Rotor node joined: \"<shaft>.<k>\" or a [[nodes]] name.")
                  .required()
                  .to(&Spider::node),
              choice("kind", {"rigid", "averaging"},
                     "rigid (RBE2): the set moves with the node as a rigid body; averaging (RBE3): "
                     "the node follows the least-squares rigid fit of the set's translations, "
                     "which keep their own flexibility.")
                  .def("\"rigid\"")
                  .to_enum(&Spider::kind, {SpiderKind::Rigid, SpiderKind::Averaging}),
          });

  Section solids =
      S("solids", SectionKind::ArrayOfTables, "[[solids]]",
        "Solid (3D finite-element) components: a mesh file, a generated annular plate or "
        "gear-blank sector, a reduced component saved by an earlier run, or stiffness and mass "
        "matrices exported by another FE code (Matrix Market) with their DOF map. With "
        "sectors > 1 "
        "the mesh is one sector of a cyclic body about the z axis. Mesh coordinates are in the "
        "global frame of the rotor model (generated plates and gears lie about the global z "
        "axis, mid-plane z = 0). A solid with [[solids.spiders]] is part of the rotor system: "
        "it is Craig-Bampton reduced onto its spider points (6 DOFs each, joined to the rotor "
        "node's 6 DOFs) and its sensor points, plus `coupling_modes` fixed-interface modes, "
        "which become generalised coordinates of the system. Its gyroscopic effect is that of "
        "its rigid-body polar inertia about the spin axis of its spider nodes, when they all "
        "spin at one speed; the gyroscopic coupling of its elastic modes is not included.")
          .in_array(&Model::solids)
          .located(&Solid::where)
          .fields({
              name_key("Unique solid name.").required().to(&Solid::name),
              choice("type", {"mesh", "annular_plate", "gear_sector", "reduced", "matrices"},
                     "Where the solid comes from; selects the keys below.")
                  .required()
                  .to_enum(&Solid::source,
                           {SolidSource::MeshFile, SolidSource::AnnularPlate,
                            SolidSource::GearSector, SolidSource::Reduced, SolidSource::Matrices}),
              text("file",
                   "Mesh file (Gmsh .msh v4, or Nastran bulk data .bdf/.dat/.nas/.blk), "
                   "relative to the model file.")
                  .required()
                  .only_in({"mesh"})
                  .to(&Solid::mesh),
              text("reduced_file",
                   "Reduced component (.h5) written by a `reduction` analysis, relative to the "
                   "model file.")
                  .required()
                  .only_in({"reduced"})
                  .to(&Solid::reduced),
              text("stiffness_file",
                   "Stiffness matrix K in Matrix Market format (coordinate or array, real, "
                   "general or symmetric), relative to the model file.")
                  .required()
                  .only_in({"matrices"})
                  .to(&Solid::stiffness_file),
              text("mass_file", "Mass matrix M in Matrix Market format, the same size as K.")
                  .required()
                  .only_in({"matrices"})
                  .to(&Solid::mass_file),
              text("dof_map_file",
                   "DOF map CSV of K and M, one row per matrix row: node_id, component (1-6, "
                   "ux..rz, or q for a generalised coordinate), x, y, z [m] "
                   "(docs/reduced-component-format.md).")
                  .required()
                  .only_in({"matrices"})
                  .to(&Solid::dof_map_file),
              reference("material", Ref::Material,
                        "Material of the solid (Nastran decks carry their own MAT1).")
                  .note("required except for Nastran meshes and reduced components")
                  .only_in({"mesh", "annular_plate", "gear_sector"})
                  .to(&Solid::material),
              integer("sectors", "Number of identical sectors of the body (1: the whole body).")
                  .def("1")
                  .ge(1)
                  .le(10000)
                  .to(&Solid::sectors),
              number("interface_tolerance", kMetre,
                     "Largest distance between a right-interface node and the rotated "
                     "left-interface node it is paired with.")
                  .def("1e-6")
                  .gt(0)
                  .to(&Solid::interface_tolerance),
              F("fixed_sets", FieldType::StringArray, "Node sets whose translations are fixed.")
                  .def("[]")
                  .only_in({"mesh", "annular_plate", "gear_sector"})
                  .to(&Solid::fixed_sets),
              integer("coupling_modes",
                      "Fixed-interface modes (spider and sensor points held) kept when the solid "
                      "is joined to the rotor by [[solids.spiders]]; 0: Guyan (static) coupling.")
                  .def("20")
                  .ge(0)
                  .le(10000)
                  .only_in({"mesh", "annular_plate", "gear_sector"})
                  .to(&Solid::coupling_modes),
              choice("unsupported_cards", {"warn", "error"},
                     "Nastran cards geardyn does not read: listed as warnings, or an error.")
                  .def("\"warn\"")
                  .only_in({"mesh"})
                  .to_fn<Solid>([](Solid& s, const FieldValue& v) {
                    s.unsupported_cards_are_errors = v.choice == 1;
                  }),
              // annular plate
              number("inner_radius", kMetre, "Inner radius b.")
                  .required()
                  .gt(0)
                  .only_in(kPlate)
                  .to_fn<Solid>(plate(&AnnularPlateSpec::inner_radius)),
              number("outer_radius", kMetre, "Outer radius a (> inner_radius).")
                  .required()
                  .gt(0)
                  .only_in(kPlate)
                  .to_fn<Solid>(plate(&AnnularPlateSpec::outer_radius)),
              number("thickness", kMetre, "Plate thickness h.")
                  .required()
                  .gt(0)
                  .only_in(kPlate)
                  .to_fn<Solid>(plate(&AnnularPlateSpec::thickness)),
              integer("radial_elements", "Elements across the radius.")
                  .def("8")
                  .ge(1)
                  .le(1000)
                  .only_in(kPlate)
                  .to_fn<Solid>(plate(&AnnularPlateSpec::radial_elements)),
              integer("circumferential_elements",
                      "Elements around the circumference of the mesh (the sector, or the whole "
                      "plate).")
                  .ge(0)
                  .le(100000)
                  .note("about square elements at the outer radius")
                  .only_in(kPlate)
                  .to_fn<Solid>(plate(&AnnularPlateSpec::circumferential_elements)),
              integer("layers", "Elements through the thickness.")
                  .def("2")
                  .ge(1)
                  .le(100)
                  .only_in(kPlate)
                  .to_fn<Solid>(plate(&AnnularPlateSpec::layers)),
              integer("order", "Element order: 1 linear, 2 quadratic.")
                  .def("2")
                  .ge(1)
                  .le(2)
                  .only_in({"annular_plate", "gear_sector"})
                  .to_fn<Solid>([](Solid& s, const FieldValue& v) {
                    s.annular_plate.order = static_cast<int>(v.integer);
                    s.gear_sector.order = static_cast<int>(v.integer);
                  }),
              // gear sector
              integer("teeth", "Number of teeth of the whole gear.")
                  .required()
                  .ge(3)
                  .le(10000)
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::teeth)),
              number("module", kMetre, "Transverse module m (pitch radius m z / 2).")
                  .required()
                  .gt(0)
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::module)),
              number("pressure_angle_deg", kDegree, "Pressure angle of the simplified tooth.")
                  .def("20.0")
                  .gt(0)
                  .lt(45)
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::pressure_angle)),
              number("face_width", kMetre, "Face width of the rim and teeth.")
                  .required()
                  .gt(0)
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::face_width)),
              number("bore_radius", kMetre, "Bore radius.")
                  .required()
                  .gt(0)
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::bore_radius)),
              number("hub_radius", kMetre, "Outer radius of the hub.")
                  .required()
                  .gt(0)
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::hub_radius)),
              number("hub_width", kMetre, "Axial width of the hub.")
                  .required()
                  .gt(0)
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::hub_width)),
              number("hub_offset", kMetre, "Axial position of the hub centre from mid-face.")
                  .def("0.0")
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::hub_offset)),
              number("web_offset", kMetre, "Axial position of the web centre from mid-face.")
                  .def("0.0")
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::web_offset)),
              number("web_thickness", kMetre, "Axial thickness of the web.")
                  .required()
                  .gt(0)
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::web_thickness)),
              number("rim_inner_radius", kMetre, "Inner radius of the rim.")
                  .required()
                  .gt(0)
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::rim_inner_radius)),
              boolean("groove", "Damper-ring groove under the rim, with its split ring.")
                  .def("false")
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::groove)),
              number("groove_position", kMetre,
                     "Axial position of the groove centre from mid-face.")
                  .def("0.0")
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::groove_position)),
              number("groove_width", kMetre, "Axial width of the groove (and the ring).")
                  .gt(0)
                  .note("required when groove = true")
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::groove_width)),
              number("groove_depth", kMetre, "Radial depth of the groove into the rim.")
                  .gt(0)
                  .note("required when groove = true")
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::groove_depth)),
              number("ring_width", kMetre, "Axial width of the ring (<= groove_width).")
                  .gt(0)
                  .note("groove_width")
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::ring_width)),
              number("ring_thickness", kMetre, "Radial thickness of the ring.")
                  .gt(0)
                  .note("required when groove = true")
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::ring_thickness)),
              reference("ring_material", Ref::Material, "Material of the damper ring.")
                  .note("required when groove = true")
                  .only_in(kGear)
                  .to(&Solid::ring_material),
              number("element_size", kMetre, "Target element size.")
                  .required()
                  .gt(0)
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::element_size)),
              number("tooth_element_size", kMetre, "Target element size at the teeth and groove.")
                  .gt(0)
                  .note("element_size")
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::tooth_element_size)),
              number("groove_element_size", kMetre,
                     "Target element size at the groove and the ring (sets how many contact "
                     "pairs the ring has).")
                  .gt(0)
                  .note("tooth_element_size")
                  .only_in(kGear)
                  .to_fn<Solid>(gear(&GearSectorSpec::groove_element_size)),
          })
          .variants("type",
                    {variant<Solid>("mesh", "A mesh file: Gmsh .msh (v4) or Nastran bulk data."),
                     variant<Solid>("annular_plate",
                                    "A generated annular plate (or one sector of it) about z."),
                     variant<Solid>("gear_sector",
                                    "A generated gear-blank sector with simplified teeth and an "
                                    "optional damper-ring groove and ring."),
                     variant<Solid>("reduced", "A reduced component file (.h5)."),
                     variant<Solid>("matrices",
                                    "Stiffness and mass matrices exported by another FE code "
                                    "(e.g. an ANSYS or Nastran superelement) with a DOF map.")})
          .sections({spiders})
          .finish<Solid>(finish_solid);

  // --- gear pairs (mesh excitation) ---
  constexpr Unit kTorque{"N m", 1.0};
  const std::vector<std::string> kCylindrical = {"spur", "helical"};
  const std::vector<std::string> kSpiral = {"spiral_bevel", "hypoid"};
  Section gear_pairs =
      S("gear_pairs", SectionKind::ArrayOfTables, "[[gear_pairs]]",
        "Gear pairs of the mesh-excitation chain (DESIGN 4.4-4.5): geometry and contact ratio "
        "(ISO 21771; bevel and hypoid gears as virtual cylindrical gears at mid face), tooth "
        "forces, ISO 6336-1 mesh stiffness, the static transmission error (STE) from a file or "
        "synthetic from the stiffness, the dynamic mesh force and the engine-order harmonics "
        "(analyses gear_pair, mesh_force, mesh_harmonics). Gear 1 is the pinion; `torque` acts "
        "on it. The geometry is checked (interference, contact ratio >= 1, backlash) before any "
        "analysis runs.")
          .in_array(&Model::gear_pairs)
          .located(&GearPair::where)
          .fields({
              name_key("Unique gear-pair name.").required().to(&GearPair::name),
              choice("type", kGearTypes, "Gear type; selects the keys below.")
                  .def("\"spur\"")
                  .to_enum(&GearPair::type,
                           {GearType::Spur, GearType::Helical, GearType::StraightBevel,
                            GearType::SpiralBevel, GearType::Hypoid}),
              boolean("internal", "Gear 2 is an internal gear (ring gear).")
                  .def("false")
                  .only_in(kCylindrical)
                  .to(&GearPair::internal),
              integer("teeth1", "Number of teeth z1 of gear 1 (pinion).")
                  .required()
                  .ge(3)
                  .le(100000)
                  .to(&GearPair::teeth1),
              integer("teeth2", "Number of teeth z2 of gear 2 (internal gear: its tooth count).")
                  .required()
                  .ge(3)
                  .le(100000)
                  .to(&GearPair::teeth2),
              number("module", kMetre,
                     "Normal module m_n (spur, helical); outer transverse module m_e at the heel "
                     "(bevel; hypoid: the wheel's).")
                  .required()
                  .gt(0)
                  .to(&GearPair::module),
              number("pressure_angle_deg", kDegree, "Normal pressure angle of the basic rack.")
                  .def("20.0")
                  .gt(0)
                  .lt(45)
                  .to(&GearPair::pressure_angle),
              number("helix_angle_deg", kDegree,
                     "Helix angle (helical), mean spiral angle (spiral bevel), the wheel's mean "
                     "spiral angle (hypoid).")
                  .required()
                  .gt(0)
                  .lt(90)
                  .only_in(kHelical)
                  .to(&GearPair::helix_angle),
              number("pinion_spiral_angle_deg", kDegree,
                     "Hypoid: the pinion's mean spiral angle (> the wheel's helix_angle_deg).")
                  .required()
                  .gt(0)
                  .lt(90)
                  .only_in({"hypoid"})
                  .to(&GearPair::pinion_spiral_angle),
              choice("hand", {"right", "left"}, "Hand of gear 1's helix or spiral.")
                  .def("\"right\"")
                  .only_in(kHelical)
                  .to_enum(&GearPair::hand, {Hand::Right, Hand::Left}),
              choice("rotation", {"cw", "ccw"},
                     "Direction of rotation of gear 1, seen from its back (cone base) towards "
                     "the apex; with `hand` it sets which flank is loaded and the sign of the "
                     "axial force.")
                  .def("\"cw\"")
                  .only_in(kSpiral)
                  .to_enum(&GearPair::rotation,
                           {GearRotation::Clockwise, GearRotation::CounterClockwise}),
              number("face_width", kMetre, "Face width b.")
                  .required()
                  .gt(0)
                  .to(&GearPair::face_width),
              number("profile_shift1", kNoUnit, "Profile shift coefficient x1 of gear 1.")
                  .def("0.0")
                  .ge(-2.0)
                  .le(2.0)
                  .to(&GearPair::profile_shift1),
              number("profile_shift2", kNoUnit,
                     "Profile shift coefficient x2 of gear 2 (ISO 21771 sign for internal "
                     "gears; bevel gears need x2 = -x1).")
                  .def("0.0")
                  .ge(-2.0)
                  .le(2.0)
                  .to(&GearPair::profile_shift2),
              number("addendum_coefficient", kNoUnit, "Addendum of the basic rack h_aP / m_n.")
                  .def("1.0")
                  .gt(0)
                  .le(2.0)
                  .to(&GearPair::addendum_coefficient),
              number("dedendum_coefficient", kNoUnit, "Dedendum of the basic rack h_fP / m_n.")
                  .def("1.25")
                  .gt(0)
                  .le(2.5)
                  .to(&GearPair::dedendum_coefficient),
              number("centre_distance", kMetre,
                     "Working centre distance (must leave backlash >= 0 for the profile shifts).")
                  .gt(0)
                  .note("the zero-backlash value for x1 + x2")
                  .only_in(kCylindrical)
                  .to(&GearPair::centre_distance),
              number("shaft_angle_deg", kDegree, "Shaft angle Sigma.")
                  .def("90.0")
                  .gt(0)
                  .lt(180)
                  .only_in(kBevel)
                  .to(&GearPair::shaft_angle),
              number("outer_cone_distance", kMetre,
                     "Outer cone distance R_e (checked against m_e z1 / (2 sin delta1)).")
                  .gt(0)
                  .note("from module, teeth and shaft angle")
                  .only_in(kBevel)
                  .to(&GearPair::outer_cone_distance),
              number("torque", kTorque, "Torque on gear 1 (drive side).")
                  .required()
                  .gt(0)
                  .to(&GearPair::torque),
              number("inertia1", kInertia,
                     "Polar moment of inertia of gear 1 (with what turns rigidly with it); "
                     "may be inf.")
                  .gt(0)
                  .allow_infinity()
                  .note("needed by mesh_force / mesh_harmonics with model = \"dynamic\"")
                  .to(&GearPair::inertia1),
              number("inertia2", kInertia, "Polar moment of inertia of gear 2; may be inf.")
                  .gt(0)
                  .allow_infinity()
                  .note("needed by mesh_force / mesh_harmonics with model = \"dynamic\"")
                  .to(&GearPair::inertia2),
              reference("material1", Ref::Material,
                        "Material of gear 1 (its Young's modulus enters the ISO 6336 stiffness).")
                  .note("steel, E = 206 GPa")
                  .to(&GearPair::material1),
              reference("material2", Ref::Material, "Material of gear 2.")
                  .note("steel, E = 206 GPa")
                  .to(&GearPair::material2),
              number("stiffness_correction", kNoUnit,
                     "ISO 6336-1 correction factor C_M (measured / theoretical stiffness).")
                  .def("0.8")
                  .gt(0)
                  .le(2.0)
                  .to(&GearPair::stiffness_correction),
              number("application_factor", kNoUnit,
                     "ISO 6336-1 application factor K_A in the light-load correction.")
                  .def("1.0")
                  .ge(1.0)
                  .le(10.0)
                  .to(&GearPair::application_factor),
              boolean("load_correction",
                      "Apply ISO 6336-1's stiffness reduction for line loads F_t K_A / b below "
                      "100 N/mm.")
                  .def("true")
                  .to(&GearPair::load_correction),
              number("rim_thickness", kMetre,
                     "Rim thickness s_R of a gear blank with a web (ISO 6336-1 C_R; give "
                     "web_thickness too).")
                  .gt(0)
                  .note("solid disc, C_R = 1")
                  .to(&GearPair::rim_thickness),
              number("web_thickness", kMetre, "Web thickness b_s of a gear blank with a web.")
                  .gt(0)
                  .note("solid disc, C_R = 1")
                  .to(&GearPair::web_thickness),
              text("ste_file",
                   "Static transmission error over one mesh cycle, CSV relative to the model "
                   "file (format in gear/ste.hpp: an angle_deg or angle_rad column of gear 1's "
                   "rotation, or a time_s or time_ms column (with ste_speed_rpm), over one mesh "
                   "cycle, ste_<unit> or ste_<unit>@<torque>Nm columns; "
                   "angular STE is scaled by gear 1's base radius); the first row is the tooth "
                   "entering contact.")
                  .note("synthetic STE e = F_s / k from the ISO 6336 mesh stiffness")
                  .to(&GearPair::ste_file),
              choice("ste_interpolation", {"linear", "hold"},
                     "How the STE file is read between its rows: periodic linear, or each row "
                     "held to the next (contact steps).")
                  .def("\"linear\"")
                  .to_enum(&GearPair::ste_interpolation,
                           {SteInterpolationKind::Linear, SteInterpolationKind::Hold}),
              boolean("ste_extrapolation",
                      "Allow a torque outside the file's torques (linear extrapolation).")
                  .def("false")
                  .to(&GearPair::ste_extrapolation),
              number("ste_shift", kNoUnit,
                     "Moves the start of the STE cycle (the tooth entering contact) by this "
                     "fraction of a mesh cycle.")
                  .def("0.0")
                  .ge(0)
                  .lt(1)
                  .to(&GearPair::ste_shift),
              number("ste_speed_rpm", kRpm,
                     "Speed of gear 1 while an STE file with a time abscissa (time_s, time_ms) "
                     "was recorded: one mesh period is 60 / (speed teeth1) s.")
                  .gt(0)
                  .note("required with a time abscissa")
                  .to(&GearPair::ste_speed),
              integer("ste_samples", "Samples of the STE per mesh cycle.")
                  .ge(16)
                  .le(100000)
                  .note("512 for the synthetic STE; the file's rows per cycle")
                  .to(&GearPair::ste_samples),
              number("mesh_damping_ratio", kNoUnit,
                     "Damping ratio zeta of the mesh: c = 2 zeta sqrt(k_mean m_e).")
                  .def("0.08")
                  .ge(0)
                  .le(1.0)
                  .to(&GearPair::mesh_damping_ratio),
              number("backlash", kMetre,
                     "Backlash along the line of action: back-side contact when the DTE falls "
                     "below -backlash.")
                  .gt(0)
                  .note("no back-side contact")
                  .to(&GearPair::backlash),
          })
          .variants("type",
                    {
                        variant<GearPair>("spur", "Spur gears (external or internal)."),
                        variant<GearPair>("helical", "Helical gears (external or internal)."),
                        variant<GearPair>("straight_bevel",
                                          "Straight bevel gears (virtual spur gears at mid "
                                          "face)."),
                        variant<GearPair>("spiral_bevel", "Spiral bevel gears."),
                        variant<GearPair>("hypoid",
                                          "Hypoid gears (approximation: the offset is neglected "
                                          "in the cone geometry; pinion enlargement from the "
                                          "spiral angles)."),
                    })
          .finish<GearPair>(finish_gear_pair);

  // --- analyses ---
  const std::vector<std::string> kSpeedRange = {"campbell",
                                                "unbalance",
                                                "cyclic_modal",
                                                "mesh_force",
                                                "cyclic_forced_response",
                                                "gear_forced_response",
                                                "damper_ring_response"};
  const std::vector<std::string> kSolidAnalyses = {
      "solid_modal", "cyclic_modal", "reduction", "cyclic_forced_response", "damper_ring_response"};
  const std::vector<std::string> kForcedAnalyses = {"cyclic_forced_response",
                                                    "gear_forced_response", "damper_ring_response"};
  // Keys of the tooth-force excitation, sensors and damping shared by the cyclic forced
  // responses (a damper-ring response is one).
  const std::vector<std::string> kCyclicForced = {"cyclic_forced_response", "damper_ring_response"};
  const std::vector<std::string> kGearAnalyses = {"gear_pair", "mesh_force", "mesh_harmonics"};
  Section outputs =
      S("outputs", SectionKind::ArrayOfTables, "[[analyses.outputs]]",
        "Scalar results tabulated per sweep point.")
          .in_fn<Analysis, SweepOutput>([](Analysis& a) {
            auto& outs = std::get<SweepSettings>(a.settings).outputs;
            outs.emplace_back();
            return &outs.back();
          })
          .only_in({"sweep"})
          .required()
          .min_count(1)
          .fields({
              choice("quantity",
                     {"natural_frequency", "critical_speed", "peak_amplitude", "peak_location",
                      "amplitude_at"},
                     "What to tabulate; selects the keys below.")
                  .required()
                  .to_enum(
                      &SweepOutput::quantity,
                      {SweepOutput::Quantity::NaturalFrequency,
                       SweepOutput::Quantity::CriticalSpeed, SweepOutput::Quantity::PeakAmplitude,
                       SweepOutput::Quantity::PeakLocation, SweepOutput::Quantity::AmplitudeAt}),
              integer("mode", "Mode number (1-based, in order of frequency).")
                  .def("1")
                  .ge(1)
                  .le(10000)
                  .only_in({"natural_frequency", "critical_speed"})
                  .to(&SweepOutput::mode),
              reference("sensor", Ref::Sensor, "Sensor whose response is used.")
                  .required()
                  .only_in({"peak_amplitude", "peak_location", "amplitude_at"})
                  .to(&SweepOutput::sensor),
              number("at_rpm", kRpm, "Speed at which to read the amplitude (unbalance target).")
                  .required()
                  .ge(0)
                  .only_in({"amplitude_at"})
                  .to(&SweepOutput::at),
              number("at_hz", kHertz,
                     "Frequency at which to read the amplitude (harmonic "
                     "target).")
                  .required()
                  .ge(0)
                  .only_in({"amplitude_at"})
                  .to(&SweepOutput::at),
              text("label", "Column name stem in the results table.")
                  .identifier()
                  .note("quantity and mode or sensor, e.g. `natural_frequency_1`")
                  .to(&SweepOutput::label),
          })
          .choices({{{{"at_rpm"}, {"at_hz"}}, true, {"amplitude_at"}}})
          .variants(
              "quantity",
              {variant<SweepOutput>("natural_frequency",
                                    "Undamped natural frequency of mode `mode` [Hz] "
                                    "(modal or campbell target; campbell: at its first "
                                    "speed)."),
               variant<SweepOutput>("critical_speed",
                                    "Critical speed of mode `mode` on engine order 1 "
                                    "[rpm] (campbell target)."),
               variant<SweepOutput>("peak_amplitude",
                                    "Largest response amplitude at `sensor` (harmonic or "
                                    "unbalance target)."),
               variant<SweepOutput>("peak_location", "Frequency [Hz] or speed [rpm] of that peak."),
               variant<SweepOutput>("amplitude_at",
                                    "Amplitude at `sensor` at one speed (at_rpm, unbalance "
                                    "target) or frequency (at_hz, harmonic target).")})
          .finish<SweepOutput>(finish_output);

  Section analyses =
      S("analyses", SectionKind::ArrayOfTables, "[[analyses]]",
        "Analyses run on the model, in order. `type` selects which further keys are allowed; "
        "keys of another type are errors.")
          .in_array(&Model::analyses)
          .located(&Analysis::where)
          .fields({
              name_key("Unique analysis name (results folder, sweep target).")
                  .required()
                  .to(&Analysis::name),
              choice("type", kAnalysisTypes, "Kind of analysis; selects the keys below.")
                  .required()
                  .to_fn<Analysis>(set_analysis_type),
              boolean("enabled", "Run it (false: only as the target of a sweep).")
                  .def("true")
                  .to(&Analysis::enabled),
              F("set", FieldType::StringArray,
                "Model changes for this analysis only, as \"key.path=value\" like `--set`, "
                "e.g. [\"gear_meshes[0].stiffness=0\"] for a variant without the mesh.")
                  .def("[]")
                  .to(&Analysis::overrides),
              // reference speed (single)
              number("speed_rpm", kRpm,
                     "Reference speed (transient: constant speed, or run-up start speed).")
                  .def("0.0")
                  .ge(0)
                  .only_in({"modal", "harmonic", "transient"})
                  .to_settings(&ModalSettings::speed, &HarmonicSettings::speed,
                               &TransientSettings::speed),
              // speed range
              numbers("speed_rpm", kRpm, "Reference speeds, increasing.")
                  .required()
                  .ge(0)
                  .increasing()
                  .min_items(1)
                  .only_in(kSpeedRange)
                  .to_settings(&CampbellSettings::speeds, &UnbalanceSettings::speeds,
                               &MeshForceSettings::speeds),
              number("speed_start_rpm", kRpm, "First speed of an evenly spaced range.")
                  .required()
                  .ge(0)
                  .only_in(kSpeedRange)
                  .read_by_finish<Analysis>(),
              number("speed_stop_rpm", kRpm, "Last speed of the range (> speed_start_rpm).")
                  .required()
                  .ge(0)
                  .only_in(kSpeedRange)
                  .read_by_finish<Analysis>(),
              integer("speed_count", "Number of speeds in the range.")
                  .def("51")
                  .ge(2)
                  .le(100000)
                  .only_in(kSpeedRange)
                  .read_by_finish<Analysis>(),
              // modal, campbell
              integer("n_modes",
                      "Number of modes computed (cyclic_modal, cyclic_forced_response: per nodal "
                      "diameter; reduction: full-model modes compared with the reduced ones; "
                      "gear_forced_response: modes of the modal basis).")
                  .def("10")
                  .ge(1)
                  .le(10000)
                  .only_in({"modal", "campbell", "solid_modal", "cyclic_modal", "reduction",
                            "cyclic_forced_response", "gear_forced_response",
                            "damper_ring_response"})
                  .to_settings(&ModalSettings::n_modes, &CampbellSettings::n_modes,
                               &SolidModalSettings::n_modes, &CyclicModalSettings::n_modes,
                               &ReductionSettings::compare_modes,
                               &CyclicForcedResponseSettings::n_modes,
                               &GearForcedResponseSettings::n_modes),
              // solids
              reference("solid", Ref::Solid, "The [[solids]] component analysed.")
                  .required()
                  .only_in(kSolidAnalyses)
                  .to_settings(&SolidModalSettings::solid, &CyclicModalSettings::solid,
                               &ReductionSettings::solid, &CyclicForcedResponseSettings::solid),
              number("f_max_hz", kHertz, "Every mode up to this frequency (n_modes is ignored).")
                  .gt(0)
                  .note("n_modes modes")
                  .only_in({"solid_modal"})
                  .to_settings(&SolidModalSettings::f_max),
              boolean("full_wheel", "Cyclic solid: replicate the sector to the whole wheel first.")
                  .def("false")
                  .only_in({"solid_modal"})
                  .to_settings(&SolidModalSettings::full_wheel),
              integer("shapes",
                      "Mode shapes written as VTU and Gmsh views (per nodal diameter "
                      "for cyclic_modal; 0: none).")
                  .def("6")
                  .ge(0)
                  .le(1000)
                  .only_in({"solid_modal", "cyclic_modal"})
                  .to_settings(&SolidModalSettings::shapes, &CyclicModalSettings::shapes),
              F("nodal_diameters", FieldType::NumberArray, "Nodal diameters solved.")
                  .ge(0)
                  .increasing()
                  .note("0 .. sectors / 2")
                  .only_in({"cyclic_modal"})
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    auto& c = std::get<CyclicModalSettings>(a.settings);
                    c.nodal_diameters.clear();
                    for (double h : v.numbers) c.nodal_diameters.push_back(static_cast<int>(h));
                  }),
              choice("reduction", {"none", "guyan", "craig_bampton"},
                     "Sector reduction before the cyclic solve (cyclic_modal), or the method of "
                     "a reduction analysis.")
                  .def("\"craig_bampton\"")
                  .note("cyclic_modal, cyclic_forced_response, damper_ring_response: \"none\"")
                  .only_in({"cyclic_modal", "reduction", "cyclic_forced_response",
                            "damper_ring_response"})
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    constexpr ReductionMethod kMethods[] = {ReductionMethod::None,
                                                            ReductionMethod::Guyan,
                                                            ReductionMethod::CraigBampton};
                    if (auto* c = std::get_if<CyclicModalSettings>(&a.settings))
                      c->reduction = v.given ? kMethods[v.choice] : ReductionMethod::None;
                    if (auto* c = settings_as<CyclicForcedResponseSettings>(a))
                      c->reduction = v.given ? kMethods[v.choice] : ReductionMethod::None;
                    if (auto* r = std::get_if<ReductionSettings>(&a.settings))
                      r->method = kMethods[v.choice];
                  }),
              integer("reduced_modes", "Fixed-interface (Craig-Bampton) modes kept.")
                  .def("40")
                  .ge(0)
                  .le(100000)
                  .only_in({"cyclic_modal", "reduction", "cyclic_forced_response",
                            "damper_ring_response"})
                  .to_settings(&CyclicModalSettings::cb_modes, &ReductionSettings::n_modes,
                               &CyclicForcedResponseSettings::cb_modes),
              number("reduced_f_max_hz", kHertz,
                     "Keep every fixed-interface mode up to this frequency instead of a count.")
                  .gt(0)
                  .note("reduced_modes modes")
                  .only_in({"reduction"})
                  .to_settings(&ReductionSettings::f_max),
              F("master_sets", FieldType::StringArray,
                "Node sets kept as physical masters (contact, excitation, sensor, connection "
                "nodes); cyclic_modal adds the sector interfaces itself, "
                "cyclic_forced_response the interfaces, the excitation and the sensor nodes, "
                "damper_ring_response also the contact pairs.")
                  .def("[]")
                  .only_in({"cyclic_modal", "reduction", "cyclic_forced_response",
                            "damper_ring_response"})
                  .to_settings(&CyclicModalSettings::master_sets, &ReductionSettings::master_sets,
                               &CyclicForcedResponseSettings::master_sets),
              integer("interface_modes",
                      "Interface modes per nodal diameter replacing the sector-interface DOFs "
                      "(Tran's method; 0: interfaces kept, else >= 6).")
                  .def("0")
                  .ge(0)
                  .le(100000)
                  .only_in({"cyclic_modal"})
                  .to_settings(&CyclicModalSettings::interface_modes),
              boolean("compare_full", "Also solve the replicated 360 deg mesh and compare.")
                  .def("false")
                  .only_in({"cyclic_modal"})
                  .to_settings(&CyclicModalSettings::compare_full),
              integer("max_engine_order",
                      "Highest engine order in the Campbell diagram (0: 2 x "
                      "sectors).")
                  .def("0")
                  .ge(0)
                  .le(100000)
                  .only_in({"cyclic_modal"})
                  .to_settings(&CyclicModalSettings::max_engine_order),
              numbers("convergence", kNoUnit,
                      "Numbers of fixed-interface modes of the convergence table.")
                  .ge(0)
                  .increasing()
                  .note("automatic")
                  .only_in({"reduction"})
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    auto& r = std::get<ReductionSettings>(a.settings);
                    r.convergence.clear();
                    for (double n : v.numbers) r.convergence.push_back(static_cast<int>(n));
                  }),
              boolean("save", "Write the reduced component as <analysis>.h5.")
                  .def("true")
                  .only_in({"reduction"})
                  .to_settings(&ReductionSettings::save),
              boolean("complex_modes", "Also compute the damped gyroscopic (complex) modes.")
                  .def("true")
                  .only_in({"modal"})
                  .to_settings(&ModalSettings::complex_modes),
              choice("method", {"auto", "dense", "sparse"},
                     "Eigen solver: dense for small models, sparse shift-invert Lanczos / "
                     "Arnoldi for large ones, auto chooses by size.")
                  .def("\"auto\"")
                  .only_in({"modal", "campbell"})
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    constexpr EigenMethod kMethods[] = {EigenMethod::Auto, EigenMethod::Dense,
                                                        EigenMethod::Sparse};
                    const EigenMethod m = kMethods[v.choice];
                    if (auto* s = std::get_if<ModalSettings>(&a.settings)) s->method = m;
                    if (auto* s = std::get_if<CampbellSettings>(&a.settings)) s->method = m;
                  }),
              number("shift_hz", kHertz, "Shift of the sparse solver: the modes nearest to it.")
                  .def("0.0")
                  .ge(0)
                  .only_in({"modal"})
                  .to_settings(&ModalSettings::shift),
              numbers("engine_orders", kNoUnit,
                      "Excitation orders of the reference speed drawn as lines; critical speeds "
                      "are where modes cross them.")
                  .def("[1.0]")
                  .gt(0)
                  .only_in({"campbell"})
                  .to_settings(&CampbellSettings::engine_orders),
              boolean("shaft_orders", "Add order 1 of every shaft (its speed ratio).")
                  .def("true")
                  .only_in({"campbell"})
                  .to_settings(&CampbellSettings::shaft_orders),
              boolean("mesh_orders",
                      "Add the mesh order (teeth x shaft order) of every mesh with teeth.")
                  .def("true")
                  .only_in({"campbell"})
                  .to_settings(&CampbellSettings::mesh_orders),
              number("mac_threshold", kNoUnit,
                     "Mode tracking between speeds: MAC below this flags an ambiguous step.")
                  .def("0.7")
                  .ge(0)
                  .le(1)
                  .only_in({"campbell"})
                  .to_settings(&CampbellSettings::mac_threshold),
              // harmonic
              number("frequency_start_hz", kHertz, "First frequency.")
                  .required()
                  .ge(0)
                  .only_in({"harmonic"})
                  .to_settings(&HarmonicSettings::f_min),
              number("frequency_stop_hz", kHertz, "Last frequency (> frequency_start_hz).")
                  .required()
                  .gt(0)
                  .only_in({"harmonic"})
                  .to_settings(&HarmonicSettings::f_max),
              integer("frequency_count", "Number of frequencies (before adaptive refinement).")
                  .def("200")
                  .ge(2)
                  .le(1000000)
                  .only_in({"harmonic"})
                  .to_settings(&HarmonicSettings::n_points),
              choice("spacing", {"linear", "log"},
                     "Spacing of the frequencies (harmonic) or sweep values (sweep; log also "
                     "draws a log axis).")
                  .def("\"linear\"")
                  .only_in({"harmonic", "sweep"})
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    if (auto* h = std::get_if<HarmonicSettings>(&a.settings))
                      h->spacing = v.choice == 1 ? Spacing::Log : Spacing::Linear;
                    if (auto* s = std::get_if<SweepSettings>(&a.settings)) s->log_x = v.choice == 1;
                  }),
              boolean("adaptive", "Refine the frequency grid around peaks.")
                  .def("true")
                  .only_in({"harmonic"})
                  .to_settings(&HarmonicSettings::adaptive),
              reference("input_node", Ref::Node, "Node of the unit-force input of an FRF.")
                  .required()
                  .only_in({"harmonic"})
                  .to_settings(&HarmonicSettings::input_node),
              choice("input_dof", kComponentChoices, "DOF of the unit-force input.")
                  .def("\"ux\"")
                  .only_in({"harmonic"})
                  .to_settings(&HarmonicSettings::input_dof),
              names("forces", Ref::Force, "Named [[forces]] applied together (forced response).")
                  .min_items(1)
                  .only_in({"harmonic"})
                  .to_settings(&HarmonicSettings::forces),
              choice("quantity", {"receptance", "mobility", "accelerance"},
                     "Response quantity: displacement, velocity or acceleration per force.")
                  .def("\"receptance\"")
                  .only_in({"harmonic"})
                  .to_settings_enum(&HarmonicSettings::quantity,
                                    {ResponseQuantity::Receptance, ResponseQuantity::Mobility,
                                     ResponseQuantity::Accelerance}),
              // unbalance, transient
              names("unbalances", Ref::Unbalance, "Unbalances applied.")
                  .note("all unbalances")
                  .only_in({"unbalance", "transient"})
                  .to_settings(&UnbalanceSettings::unbalances, &TransientSettings::unbalances),
              names("sensors", Ref::Sensor, "Sensors reported.")
                  .note("all sensors")
                  .only_in({"harmonic", "unbalance", "transient", "gear_forced_response"})
                  .to_settings(&HarmonicSettings::sensors, &UnbalanceSettings::sensors,
                               &TransientSettings::sensors, &GearForcedResponseSettings::sensors),
              // transient
              number("speed_end_rpm", kRpm, "End speed of a linear run-up over `duration`.")
                  .ge(0)
                  .note("constant speed")
                  .only_in({"transient"})
                  .to_settings(&TransientSettings::speed_end),
              number("duration", kSecond, "Simulated time.")
                  .required()
                  .gt(0)
                  .only_in({"transient"})
                  .to_settings(&TransientSettings::duration),
              number("time_step", kSecond, "Time step (< duration).")
                  .required()
                  .gt(0)
                  .only_in({"transient"})
                  .to_settings(&TransientSettings::time_step),
              choice("integrator", {"newmark", "generalized_alpha"},
                     "Time integrator: Newmark average acceleration, or generalised-alpha with "
                     "numerical damping set by rho_infinity.")
                  .def("\"generalized_alpha\"")
                  .only_in({"transient"})
                  .to_settings_enum(&TransientSettings::integrator,
                                    {Integrator::Newmark, Integrator::GeneralizedAlpha}),
              number("rho_infinity", kNoUnit,
                     "Spectral radius at infinite frequency "
                     "(generalised-alpha; 1: no numerical damping).")
                  .def("0.9")
                  .ge(0)
                  .le(1)
                  .only_in({"transient"})
                  .to_settings(&TransientSettings::rho_infinity),
              number("steady_fraction", kNoUnit,
                     "Last fraction of the record used for spectra and orbits.")
                  .def("0.5")
                  .gt(0)
                  .le(1)
                  .only_in({"transient"})
                  .to_settings(&TransientSettings::steady_fraction),
              integer("output_every", "Store every n-th time step.")
                  .def("1")
                  .ge(1)
                  .le(1000000)
                  .only_in({"transient"})
                  .to_settings(&TransientSettings::output_every),
              // sweep
              F("parameter", FieldType::String,
                "Key path of the numeric key varied, e.g. \"bearings[0].kxx\" or "
                "\"analyses[1].speed_rpm\" (values in that key's unit).")
                  .ref(Ref::KeyPath)
                  .required()
                  .only_in({"sweep"})
                  .to_settings(&SweepSettings::parameter),
              F("linked_parameters", FieldType::StringArray,
                "Further key paths set to the same value at each point, e.g. "
                "[\"bearings[0].kyy\"] with parameter = \"bearings[0].kxx\" for an isotropic "
                "bearing.")
                  .def("[]")
                  .only_in({"sweep"})
                  .to_settings(&SweepSettings::linked_parameters),
              numbers("values", kNoUnit, "Values of the parameter.")
                  .unit_note("unit of the key")
                  .min_items(1)
                  .only_in({"sweep"})
                  .to_settings(&SweepSettings::values),
              number("start", kNoUnit, "First value of an evenly spaced range.")
                  .unit_note("unit of the key")
                  .required()
                  .only_in({"sweep"})
                  .read_by_finish<Analysis>(),
              number("stop", kNoUnit, "Last value of the range.")
                  .unit_note("unit of the key")
                  .required()
                  .only_in({"sweep"})
                  .read_by_finish<Analysis>(),
              integer("count", "Number of values in the range.")
                  .required()
                  .ge(2)
                  .le(100000)
                  .only_in({"sweep"})
                  .read_by_finish<Analysis>(),
              reference("analysis", Ref::Analysis,
                        "Name of the analysis run at each point (not "
                        "a sweep).")
                  .required()
                  .only_in({"sweep"})
                  .to_settings(&SweepSettings::analysis),
              integer("threads", "Worker threads (0: all cores).")
                  .def("0")
                  .ge(0)
                  .le(4096)
                  .only_in({"sweep"})
                  .to_settings(&SweepSettings::threads),
              // gear pairs: gear_pair, mesh_force, mesh_harmonics
              reference("pair", Ref::GearPair, "The [[gear_pairs]] entry analysed.")
                  .note("gear_pair: every pair; otherwise the model's only pair")
                  .only_in(kGearAnalyses)
                  .to_settings(&GearPairSettings::pair, &MeshForceSettings::pair,
                               &MeshHarmonicsSettings::pair),
              choice("direction", {"up", "down", "both"},
                     "Sweep direction; each speed starts from the previous steady state, so "
                     "\"both\" shows the jump and hysteresis of contact loss.")
                  .def("\"both\"")
                  .only_in({"mesh_force"})
                  .to_settings_enum(
                      &MeshForceSettings::direction,
                      {SweepDirectionKind::Up, SweepDirectionKind::Down, SweepDirectionKind::Both}),
              choice("model", {"dynamic", "infinite_inertia"},
                     "Mesh model: the dynamic one-DOF model along the line of action, or the "
                     "algebraic limit of infinite inertias F_d = F_s k(t) / k_mean.")
                  .def("\"dynamic\"")
                  .only_in({"mesh_force", "mesh_harmonics", "cyclic_forced_response",
                            "damper_ring_response"})
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    const MeshForceModel m =
                        v.choice == 0 ? MeshForceModel::Dynamic : MeshForceModel::InfiniteInertia;
                    if (auto* s = std::get_if<MeshForceSettings>(&a.settings)) s->model = m;
                    if (auto* s = std::get_if<MeshHarmonicsSettings>(&a.settings)) s->model = m;
                    if (auto* s = settings_as<CyclicForcedResponseSettings>(a)) s->model = m;
                  }),
              boolean("contact_loss",
                      "Teeth separate when the dynamic transmission error falls to zero (false: "
                      "the linear time-periodic mesh law for every deflection).")
                  .def("true")
                  .only_in({"mesh_force", "mesh_harmonics", "cyclic_forced_response",
                            "damper_ring_response"})
                  .to_settings(&MeshForceSettings::contact_loss,
                               &MeshHarmonicsSettings::contact_loss,
                               &CyclicForcedResponseSettings::contact_loss),
              numbers("detail_rpm", kRpm,
                      "Speeds of gear 1 at which time histories over one period are written "
                      "(at most 8; computed on their own from the static state).")
                  .gt(0)
                  .def("[]")
                  .only_in({"mesh_force"})
                  .to_settings(&MeshForceSettings::detail_speeds),
              number("speed_rpm", kRpm, "Speed of gear 1.")
                  .required()
                  .gt(0)
                  .only_in({"mesh_harmonics"})
                  .to_settings(&MeshHarmonicsSettings::speed),
              integer("gear", "The gear whose tooth load is analysed: 1 or 2 (N = its teeth).")
                  .def("1")
                  .ge(1)
                  .le(2)
                  .only_in({"mesh_harmonics", "cyclic_forced_response", "damper_ring_response"})
                  .to_settings(&MeshHarmonicsSettings::gear, &CyclicForcedResponseSettings::gear),
              number("window_shift", kNoUnit,
                     "Shift of the tooth-load window against the STE cycle start (the tooth "
                     "entering contact), in tooth pitches of that gear.")
                  .def("0.0")
                  .ge(-3.0)
                  .le(3.0)
                  .only_in({"mesh_harmonics", "cyclic_forced_response", "damper_ring_response"})
                  .to_settings(&MeshHarmonicsSettings::window_shift,
                               &CyclicForcedResponseSettings::window_shift),
              number("contact_ratio", kNoUnit,
                     "Contact ratio of the tooth-load window (the tooth carries load for this "
                     "many pitches).")
                  .ge(1.0)
                  .le(3.0)
                  .note("the pair's total contact ratio eps_gamma")
                  .only_in({"mesh_harmonics", "cyclic_forced_response", "damper_ring_response"})
                  .to_settings(&MeshHarmonicsSettings::contact_ratio,
                               &CyclicForcedResponseSettings::contact_ratio),
              F("nodal_diameters", FieldType::NumberArray,
                "Nodal diameters h whose engine orders k = h, N - h, ... are tabulated.")
                  .ge(0)
                  .increasing()
                  .note("0 .. N / 2")
                  .only_in({"mesh_harmonics", "cyclic_forced_response"})
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    std::vector<int> nds;
                    for (double h : v.numbers) nds.push_back(static_cast<int>(h));
                    if (auto* s = std::get_if<MeshHarmonicsSettings>(&a.settings))
                      s->nodal_diameters = nds;
                    if (auto* s = settings_as<CyclicForcedResponseSettings>(a))
                      s->nodal_diameters = nds;
                  }),
              integer("orders_per_diameter",
                      "Engine orders per nodal diameter: 2 gives k = h and k = N - h, more add "
                      "N + h, 2 N - h, ...")
                  .def("2")
                  .ge(1)
                  .le(20)
                  .only_in({"mesh_harmonics", "cyclic_forced_response"})
                  .to_settings(&MeshHarmonicsSettings::orders_per_diameter,
                               &CyclicForcedResponseSettings::orders_per_diameter),
              integer("max_order", "Highest order of the order-spectrum table (0: 2 N).")
                  .def("0")
                  .ge(0)
                  .le(100000)
                  .only_in({"mesh_harmonics"})
                  .to_settings(&MeshHarmonicsSettings::max_order),
              // correlation
              text("measured_file",
                   "Measured response CSV relative to the model file (format in "
                   "gear/correlation.hpp: speed_rpm or frequency_hz, amplitude_<unit>, optional "
                   "phase_deg).")
                  .required()
                  .only_in({"correlation"})
                  .to_settings(&CorrelationSettings::measured_file),
              number("min_prominence_db", kNoUnit,
                     "Measured peaks at least this prominent [dB] are reported.")
                  .def("6.0")
                  .ge(0)
                  .only_in({"correlation", "cyclic_forced_response", "gear_forced_response"})
                  .to_settings(&CorrelationSettings::min_prominence_db,
                               &CyclicForcedResponseSettings::min_prominence_db,
                               &GearForcedResponseSettings::min_prominence_db),
              integer("max_peaks", "At most this many peaks (the most prominent).")
                  .def("8")
                  .ge(1)
                  .le(1000)
                  .only_in({"correlation"})
                  .to_settings(&CorrelationSettings::max_peaks),
              number("reference_peak_rpm", kRpm,
                     "Position of a reference (e.g. computed) peak, for a measured file over "
                     "speed; the nearest measured peak is compared with it.")
                  .gt(0)
                  .note("no comparison")
                  .only_in({"correlation"})
                  .to_settings(&CorrelationSettings::reference_peak),
              number("reference_peak_hz", kHertz,
                     "Position of a reference peak, for a measured file over frequency.")
                  .gt(0)
                  .note("no comparison")
                  .only_in({"correlation"})
                  .to_settings(&CorrelationSettings::reference_peak),
              number("reference_amplitude", kNoUnit,
                     "Amplitude of the reference peak, in the SI unit of the measured amplitude "
                     "(m, m/s, m/s^2, N, strain or Pa).")
                  .unit_note("SI unit of the measured amplitude")
                  .gt(0)
                  .note("no amplitude comparison")
                  .only_in({"correlation"})
                  .to_settings(&CorrelationSettings::reference_amplitude),
              number("reference_q", kNoUnit, "Quality factor Q of the reference peak.")
                  .gt(0)
                  .note("no Q comparison")
                  .only_in({"correlation"})
                  .to_settings(&CorrelationSettings::reference_q),
              // forced responses: cyclic_forced_response, gear_forced_response
              reference("pair", Ref::GearPair,
                        "The [[gear_pairs]] entry whose tooth force (cyclic_forced_response: "
                        "computed as mesh_harmonics does) or mesh force (gear_forced_response: "
                        "the blocked force F_s k(t) / k_mean at the mesh orders) excites the "
                        "structure.")
                  .note("force_amplitude")
                  .only_in(kForcedAnalyses)
                  .to_settings(&CyclicForcedResponseSettings::pair,
                               &GearForcedResponseSettings::pair),
              F("force_amplitude", FieldType::NumberOrArray,
                "Harmonic force amplitude [N] without a gear pair: one value for every order, "
                "or one per entry of engine_orders (cyclic_forced_response) or per mesh order "
                "1 .. max_mesh_order (gear_forced_response), or F_k, F_2k, ... on harmonics "
                "1, 2, ... (damper_ring_response).")
                  .unit(kNewton)
                  .gt(0)
                  .only_in(kForcedAnalyses)
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    if (auto* s = settings_as<CyclicForcedResponseSettings>(a))
                      s->force_amplitude = amplitudes_of(v);
                    if (auto* s = std::get_if<GearForcedResponseSettings>(&a.settings))
                      s->force_amplitude = amplitudes_of(v);
                  }),
              number("harmonics_rpm", kRpm,
                     "Speed of gear 1 at which the dynamic mesh force, and so the tooth-force "
                     "harmonics, are computed (model = \"dynamic\"); the harmonics are then used "
                     "at every speed of the range.")
                  .gt(0)
                  .note("required with model = \"dynamic\"")
                  .only_in(kCyclicForced)
                  .to_settings(&CyclicForcedResponseSettings::harmonics_speed),
              vector3("force_direction", kNoUnit,
                      "Direction of an explicit force_amplitude in global components of the "
                      "sector (the rotating frame), normalised.")
                  .nonzero()
                  .note("tangential, -e_theta at each excitation node")
                  .only_in(kCyclicForced)
                  .to_settings(&CyclicForcedResponseSettings::force_direction),
              choice("cone_apex", {"minus_z", "plus_z"},
                     "Side of the pitch-cone apex along the solid's z axis: the axial tooth "
                     "force (positive away from the apex, gear/tooth_forces.hpp) points the "
                     "other way.")
                  .def("\"minus_z\"")
                  .only_in(kCyclicForced)
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    settings_as<CyclicForcedResponseSettings>(a)->apex_below = v.choice == 0;
                  }),
              F("engine_orders", FieldType::NumberArray,
                "Engine orders k excited (each k = +-h mod sectors for a listed nodal "
                "diameter h).")
                  .ge(1)
                  .increasing()
                  .note("orders_per_diameter orders per nodal diameter: h, N - h, ...")
                  .only_in({"cyclic_forced_response"})
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    auto& s = *settings_as<CyclicForcedResponseSettings>(a);
                    s.engine_orders.clear();
                    for (double k : v.numbers) s.engine_orders.push_back(static_cast<int>(k));
                  }),
              text("excitation_set",
                   "Node set of the sector carrying the tooth load (the load is shared equally "
                   "by its nodes).")
                  .def("\"excitation\"")
                  .only_in(kCyclicForced)
                  .to_settings(&CyclicForcedResponseSettings::excitation_set),
              F("sensor_sets", FieldType::StringArray,
                "Node sets of the sector whose response is reported: one point per set, its "
                "node nearest to the set's centroid.")
                  .def("[]")
                  .unique()
                  .only_in(kCyclicForced)
                  .to_settings(&CyclicForcedResponseSettings::sensor_sets),
              F("sensor_nodes", FieldType::NumberArray,
                "Node ids of the sector mesh whose response is reported.")
                  .def("[]")
                  .ge(0)
                  .only_in(kCyclicForced)
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    auto& s = *settings_as<CyclicForcedResponseSettings>(a);
                    s.sensor_nodes.clear();
                    for (double n : v.numbers) s.sensor_nodes.push_back(static_cast<int>(n));
                  }),
              F("sensor_components", FieldType::DofList,
                "Components reported at each sensor point, in the global axes of the sector "
                "(which turn with the gear: the rotating frame).")
                  .def("[\"ux\", \"uy\", \"uz\"]")
                  .choices(kComponentChoices)
                  .only_in(kCyclicForced)
                  .to_settings(&CyclicForcedResponseSettings::sensor_components),
              number("damping_ratio", kNoUnit, "Modal damping ratio zeta of every mode.")
                  .gt(0)
                  .lt(1)
                  .only_in(kCyclicForced)
                  .to_settings(&CyclicForcedResponseSettings::damping_ratio),
              number("q_factor", kNoUnit, "Quality factor Q = 1 / (2 zeta) of every mode.")
                  .gt(0.5)
                  .only_in(kCyclicForced)
                  .to_settings(&CyclicForcedResponseSettings::q_factor),
              boolean("superpose",
                      "Also report the superposition of all orders per sensor: the sum of "
                      "amplitudes (upper bound of the peak) and the RMS.")
                  .def("true")
                  .only_in({"cyclic_forced_response"})
                  .to_settings(&CyclicForcedResponseSettings::superpose),
              text("measured_file",
                   "Measured response over speed (CSV, gear/correlation.hpp, displacement "
                   "amplitude) overlaid on the computed one and compared peak by peak.")
                  .note("no comparison")
                  .only_in({"cyclic_forced_response", "gear_forced_response"})
                  .to_settings(&CyclicForcedResponseSettings::measured_file,
                               &GearForcedResponseSettings::measured_file),
              text("measured_sensor",
                   "Computed curve compared with the measurement: its sensor name (in a cyclic "
                   "sector <set or node<id>>_<component>).")
                  .note("the first sensor")
                  .only_in({"cyclic_forced_response", "gear_forced_response"})
                  .to_settings(&CyclicForcedResponseSettings::measured_sensor,
                               &GearForcedResponseSettings::measured_sensor),
              integer("measured_engine_order",
                      "Engine order of the computed curve compared with the measurement (0: the "
                      "superposed sum of amplitudes).")
                  .def("0")
                  .ge(0)
                  .le(100000)
                  .only_in({"cyclic_forced_response"})
                  .to_settings(&CyclicForcedResponseSettings::measured_engine_order),
              boolean("scale_to_measured",
                      "Scale the harmonic force so that the computed peak matches the measured "
                      "one, and report the implied force.")
                  .def("false")
                  .only_in({"cyclic_forced_response", "gear_forced_response"})
                  .to_settings(&CyclicForcedResponseSettings::scale_to_measured,
                               &GearForcedResponseSettings::scale_to_measured),
              integer("measured_mesh_order",
                      "Mesh order of the computed curve compared with the measurement (0: the "
                      "sum of the amplitudes of all mesh orders).")
                  .def("0")
                  .ge(0)
                  .le(100000)
                  .only_in({"gear_forced_response"})
                  .to_settings(&GearForcedResponseSettings::measured_mesh_order),
              text("gear_mesh", "The [[gear_meshes]] entry of the rotor that is excited.")
                  .note("the model's only gear mesh")
                  .only_in({"gear_forced_response"})
                  .to_settings(&GearForcedResponseSettings::gear_mesh),
              integer("max_mesh_order", "Mesh orders 1 .. this are excited.")
                  .def("3")
                  .ge(1)
                  .le(100)
                  .only_in({"gear_forced_response"})
                  .to_settings(&GearForcedResponseSettings::max_mesh_order),
              boolean("residual_vectors",
                      "Add the static response to the mesh load to the modal basis (static "
                      "correction of the modes left out).")
                  .def("true")
                  .only_in({"gear_forced_response"})
                  .to_settings(&GearForcedResponseSettings::residual_vectors),
              // damper_ring_response
              integer("engine_order",
                      "Engine order k of the tooth force exciting the gear; it excites nodal "
                      "diameter h = +-k mod sectors, and harmonic n of the response carries "
                      "engine order n k.")
                  .required()
                  .ge(1)
                  .le(100000)
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::engine_order),
              text("gear_contact_set",
                   "Node set of the gear's contact face in the groove (its i-th node coincides "
                   "with the i-th of ring_contact_set).")
                  .def("\"groove_contact\"")
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::gear_contact_set),
              text("ring_contact_set", "Node set of the ring's contact face.")
                  .def("\"ring_contact\"")
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::ring_contact_set),
              text("ring_element_set",
                   "Element set of the ring (its mass and centre-of-mass radius give the "
                   "centrifugal preload).")
                  .def("\"ring\"")
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::ring_element_set),
              choice("contact", {"2d", "3d"},
                     "Contact model per node pair: \"2d\" normal + one slip direction "
                     "(inclined by ring_inclination_deg from the circumferential one), \"3d\" "
                     "normal + circumferential and axial slip.")
                  .def("\"2d\"")
                  .only_in({"damper_ring_response"})
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    std::get<DamperRingResponseSettings>(a.settings).contact_directions =
                        v.choice + 1;
                  }),
              number("ring_inclination_deg", kDegree,
                     "Inclination psi of the 2d contact's slip direction from the "
                     "circumferential direction towards the axis.")
                  .def("0.0")
                  .ge(-90.0)
                  .le(90.0)
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::ring_inclination),
              number("normal_stiffness", kStiffness, "Normal contact stiffness k_n per node pair.")
                  .ge(0)
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::normal_stiffness),
              number("contact_stiffness", kStiffnessPerArea,
                     "Normal contact stiffness per contact area: k_n = this x the contact face "
                     "area of a sector / the pairs per sector.")
                  .ge(0)
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::contact_stiffness),
              number("tangential_stiffness", kStiffness,
                     "Tangential (stick) contact stiffness k_t per node pair.")
                  .gt(0)
                  .note("Mindlin: k_t = 4 G* / E* k_n, 2 (1 - nu) / (2 - nu) k_n for equal "
                        "materials")
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::tangential_stiffness),
              number("friction_coefficient", kNoUnit, "Coulomb friction coefficient mu.")
                  .required()
                  .ge(0)
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::friction_coefficient),
              integer("harmonics",
                      "Harmonics H balanced (1: the fundamental; more resolve the contact "
                      "forces' higher harmonics and engine orders n k).")
                  .def("1")
                  .ge(1)
                  .le(50)
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::harmonics),
              integer("time_samples",
                      "Time samples per period of the alternating frequency-time evaluation.")
                  .ge(3)
                  .le(65536)
                  .note("(8 + 1) H + 1 rounded up to a power of two, at least 64")
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::time_samples),
              F("hysteresis_pairs", FieldType::NumberArray,
                "Contact pairs (0-based, in the order of the contact sets) whose hysteresis "
                "loops at the resonance are reported.")
                  .ge(0)
                  .unique()
                  .note("three pairs spread over the contact face")
                  .only_in({"damper_ring_response"})
                  .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
                    auto& s = std::get<DamperRingResponseSettings>(a.settings);
                    s.hysteresis_pairs.clear();
                    for (double n : v.numbers) s.hysteresis_pairs.push_back(static_cast<int>(n));
                  }),
              number("max_step", kNoUnit,
                     "Largest continuation step, relative to the speed range and the linear "
                     "response amplitude.")
                  .def("0.02")
                  .gt(0)
                  .le(0.5)
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::max_step),
              choice("performance_parameter",
                     {"ring_mass", "friction_coefficient", "contact_stiffness"},
                     "Damper performance curve: the response is traced again for each of "
                     "performance_values of this parameter (ring_mass, contact_stiffness: "
                     "factors on the ring's density and on k_n and k_t; friction_coefficient: "
                     "values of mu), giving resonance speed, peak and Q against it.")
                  .note("no performance curve")
                  .only_in({"damper_ring_response"})
                  .to_settings_enum(&DamperRingResponseSettings::sweep,
                                    {DamperSweep::RingMass, DamperSweep::FrictionCoefficient,
                                     DamperSweep::ContactStiffness}),
              numbers("performance_values", kNoUnit, "Values of performance_parameter, increasing.")
                  .ge(0)
                  .increasing()
                  .min_items(1)
                  .only_in({"damper_ring_response"})
                  .to_settings(&DamperRingResponseSettings::sweep_values),
          })
          .choices({{{{"speed_rpm"}, {"speed_start_rpm", "speed_stop_rpm", "speed_count"}},
                     true,
                     {"campbell", "unbalance", "mesh_force", "cyclic_forced_response",
                      "gear_forced_response", "damper_ring_response"}},
                    {{{"pair"}, {"force_amplitude"}}, true, kForcedAnalyses},
                    {{{"damping_ratio"}, {"q_factor"}}, true, kCyclicForced},
                    {{{"normal_stiffness"}, {"contact_stiffness"}}, true, {"damper_ring_response"}},
                    {{{"speed_rpm"}, {"speed_start_rpm", "speed_stop_rpm", "speed_count"}},
                     false,
                     {"cyclic_modal"}},
                    {{{"input_node", "input_dof"}, {"forces"}}, true, {"harmonic"}},
                    {{{"values"}, {"start", "stop", "count"}}, true, {"sweep"}},
                    {{{"reference_peak_rpm"}, {"reference_peak_hz"}}, false, {"correlation"}}})
          .sections({outputs})
          .variants("type",
                    {variant<Analysis>("modal",
                                       "Natural frequencies and mode shapes at one speed "
                                       "(undamped, and complex modes with damping and "
                                       "gyroscopic terms)."),
                     variant<Analysis>("campbell",
                                       "Eigenvalues versus speed with forward / backward whirl, "
                                       "order lines and critical speeds.",
                                       finish_campbell),
                     variant<Analysis>("harmonic",
                                       "Frequency response at one speed: an FRF from a unit "
                                       "force, or the response to named forces.",
                                       finish_harmonic),
                     variant<Analysis>("unbalance", "Steady unbalance response versus speed.",
                                       finish_unbalance),
                     variant<Analysis>("transient",
                                       "Time integration at constant speed or in a linear "
                                       "run-up.",
                                       finish_transient),
                     variant<Analysis>("sweep",
                                       "Runs another analysis for each value of one parameter "
                                       "and tabulates scalar outputs.",
                                       finish_sweep),
                     variant<Analysis>("solid_modal",
                                       "Natural frequencies and mode shapes of a solid "
                                       "component (sparse shift-invert Lanczos)."),
                     variant<Analysis>("cyclic_modal",
                                       "Modes per nodal diameter of a cyclic solid from one "
                                       "sector, optionally reduced, with full-wheel shapes and "
                                       "the rotating-frame Campbell diagram.",
                                       finish_cyclic),
                     variant<Analysis>("reduction",
                                       "Craig-Bampton or Guyan reduction of a solid: reduced vs "
                                       "full frequencies, convergence, reduced component file.",
                                       finish_reduction),
                     variant<Analysis>("gear_pair",
                                       "Gear-pair geometry, tooth forces (drive and coast), ISO "
                                       "6336 stiffness and the mesh stiffness / STE over one "
                                       "mesh cycle."),
                     variant<Analysis>("mesh_force",
                                       "Dynamic mesh force over a speed range of gear 1: "
                                       "dynamic factor, DTE and contact loss versus speed, the "
                                       "mesh resonance, time histories.",
                                       finish_mesh_force),
                     variant<Analysis>("mesh_harmonics",
                                       "Engine-order harmonics of the tooth force of one gear "
                                       "at one speed: tooth-load window, order spectrum, "
                                       "harmonics per nodal diameter in 3D components."),
                     variant<Analysis>("correlation",
                                       "Resonance peaks and Q (half-power) of a measured "
                                       "response, optionally compared with a reference peak.",
                                       finish_correlation),
                     variant<Analysis>("cyclic_forced_response",
                                       "Forced response of a cyclic solid (a gear) to the "
                                       "engine-order harmonics of its tooth force over speed, "
                                       "per nodal diameter and engine order (modal sum), the "
                                       "resonance table, the superposition of the orders, and "
                                       "the comparison with a measured response.",
                                       finish_cyclic_forced),
                     variant<Analysis>("gear_forced_response",
                                       "Forced response of the rotor to the mesh-order "
                                       "harmonics of one gear mesh over speed (modal basis), "
                                       "with the resonance peaks and their Q.",
                                       finish_gear_forced),
                     variant<Analysis>("damper_ring_response",
                                       "Friction-damped response over speed of a cyclic gear "
                                       "with a damper ring in a groove (harmonic balance on the "
                                       "ring's contacts): damped, free and stuck responses, Q "
                                       "and resonance shift, energy, stick / slip / lift-off, "
                                       "hysteresis loops, optional performance curve.",
                                       finish_damper_ring)});

  Section root =
      S("", SectionKind::Root, "top level", "Keys at the top of the file, before any table.")
          .fields({
              integer("version", "Model-file format version; this geardyn reads version 1.")
                  .required()
                  .ge(1)
                  .le(1)
                  .to(&Model::version),
              text("title", "Title shown in reports.").def("\"\"").to(&Model::title),
          })
          .sections({materials, shafts, nodes, disks, point_masses, bearings, couplings,
                     gear_meshes, constraints, unbalances, forces, sensors, damping, solids,
                     gear_pairs, analyses});
  root.object_type = typeid(Model);  // the root has no parent to append it to
  return root;
}

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
  if (!s.discriminator.empty()) {
    const Field* d = s.find_field(s.discriminator, "");
    if (!d || d->type != FieldType::Enum || d->choices.size() != s.variants.size())
      throw std::logic_error(
          fmt::format("schema: discriminator of {} does not list its variants", s.title));
  }
  for (const auto& sub : s.sections) check_section(sub);
}

}  // namespace

const Section& model_schema() {
  static const Section schema = [] {
    Section s = make_schema();
    check_section(s);
    return s;
  }();
  return schema;
}

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

std::string schema_markdown() {
  const Section& root = model_schema();
  std::string out;
  out += "# geardyn model-file reference\n\n";
  out +=
      "<!-- Generated from the declaration table in src/geardyn/model/schema.cpp by "
      "schema_markdown() (`geardyn schema`). Do not edit: regenerate with "
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
