#pragma once
// Builders for the declaration table of the model file (schema.hpp): `number("length", kMetre,
// "help").required().gt(0).to(&ShaftElement::length)` makes one Field, S(...) one Section.
// The model's own sections (schema_*.cpp) and every analysis type's keys
// (src/geardyn/analyses/*_entry.cpp) are written with them.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "geardyn/core/units.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/model/schema.hpp"

namespace geardyn::model::keys {

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
constexpr Unit kRpm{"rpm", units::kRadPerSecondPerRpm};
constexpr Unit kHertz{"Hz", units::kRadPerSecondPerHz};
constexpr Unit kDegree{"deg", units::kRadPerDegree};

inline const std::vector<std::string> kComponentChoices(kComponentNames.begin(),
                                                        kComponentNames.end());

template <class M>
struct MemberTraits;
template <class C, class V>
struct MemberTraits<V C::*> {
  using Class = C;
  using Value = V;
};

inline void assign(double& out, const FieldValue& v) { out = v.number; }
inline void assign(int& out, const FieldValue& v) { out = static_cast<int>(v.integer); }
inline void assign(bool& out, const FieldValue& v) { out = v.boolean; }
inline void assign(std::string& out, const FieldValue& v) { out = v.text; }
inline void assign(std::vector<double>& out, const FieldValue& v) { out = v.numbers; }
inline void assign(std::vector<std::string>& out, const FieldValue& v) { out = v.strings; }
inline void assign(Vec3& out, const FieldValue& v) {
  std::copy_n(v.numbers.begin(), 3, out.begin());
}
inline void assign(std::optional<Vec3>& out, const FieldValue& v) {
  out.emplace();
  std::copy_n(v.numbers.begin(), 3, out->begin());
}
inline void assign(Component& out, const FieldValue& v) { out = static_cast<Component>(v.choice); }
inline void assign(std::vector<Component>& out, const FieldValue& v) {
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
  /// Stores the value in the settings of an Analysis, which must be the member's settings type
  /// (or derived from it).
  template <class M>
  F& to_settings(M member) {
    using S = typename MemberTraits<M>::Class;
    f_.object_type = typeid(Analysis);
    f_.setter = [member](void* object, const FieldValue& v) {
      assign(static_cast<Analysis*>(object)->settings_of<S>().*member, v);
    };
    return *this;
  }
  template <class S, class E>
  F& to_settings_enum(E S::*member, std::vector<E> values) {
    check_enum_size(values.size());
    f_.object_type = typeid(Analysis);
    f_.setter = [member, values](void* object, const FieldValue& v) {
      static_cast<Analysis*>(object)->settings_of<S>().*member =
          values.at(static_cast<std::size_t>(v.choice));
    };
    return *this;
  }
  /// Stores the value through `fn` into the settings of an Analysis, which must be an S.
  template <class S>
  F& to_settings_fn(std::function<void(S&, const FieldValue&)> fn) {
    f_.object_type = typeid(Analysis);
    f_.setter = [fn](void* object, const FieldValue& v) {
      fn(static_cast<Analysis*>(object)->settings_of<S>(), v);
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
  void check_enum_size(std::size_t n) const {
    if (n != f_.choices.size())
      throw std::logic_error(fmt::format("schema: key '{}' maps {} choices to {} enum values",
                                         f_.name, f_.choices.size(), n));
  }
  Field f_;
};

inline F number(std::string name, Unit unit, std::string help) {
  F f(std::move(name), FieldType::Number, std::move(help));
  f.unit(unit);
  return f;
}
inline F integer(std::string name, std::string help) {
  return F(std::move(name), FieldType::Integer, std::move(help));
}
inline F boolean(std::string name, std::string help) {
  return F(std::move(name), FieldType::Boolean, std::move(help));
}
inline F text(std::string name, std::string help) {
  return F(std::move(name), FieldType::String, std::move(help));
}
inline F name_key(std::string help) {
  F f("name", FieldType::String, std::move(help));
  f.identifier();
  return f;
}
inline F reference(std::string name, Ref ref, std::string help) {
  F f(std::move(name), FieldType::String, std::move(help));
  f.ref(ref);
  return f;
}
inline F choice(std::string name, std::vector<std::string> choices, std::string help) {
  F f(std::move(name), FieldType::Enum, std::move(help));
  f.choices(std::move(choices));
  return f;
}
inline F numbers(std::string name, Unit unit, std::string help) {
  F f(std::move(name), FieldType::NumberArray, std::move(help));
  f.unit(unit);
  return f;
}
inline F vector3(std::string name, Unit unit, std::string help) {
  F f(std::move(name), FieldType::Vector3, std::move(help));
  f.unit(unit);
  return f;
}
inline F names(std::string name, Ref ref, std::string help) {
  F f(std::move(name), FieldType::StringArray, std::move(help));
  f.ref(ref).unique();
  return f;
}
inline F matrix(std::string name, std::vector<int> sizes, std::string help) {
  F f(std::move(name), FieldType::Matrix, std::move(help));
  f.sizes(std::move(sizes));
  return f;
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
  /// An optional table: absent, its object is not made (see Section::optional).
  S& optional() {
    s_.optional = true;
    return *this;
  }
  /// Optional table stored in `parent.*member` (a std::optional), made when the table is written.
  template <class P, class T>
  S& in_optional(std::optional<T> P::*member) {
    s_.object_type = typeid(T);
    s_.optional = true;
    s_.child = [member](void* parent) -> void* {
      auto& slot = static_cast<P*>(parent)->*member;
      if (!slot) slot.emplace();
      return &*slot;
    };
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
std::string value_text(double x);

/// n values from a to b, linear or geometric (a, b > 0 for log); the last is exactly b.
std::vector<double> spaced(double a, double b, int n, bool log);

}  // namespace geardyn::model::keys
