// The model file's nonlinear drivetrain sections (drivetrain_spec.hpp, docs/theory.md §16):
// contacts, bolts, bushings, rolling bearings, drivers, loads, clutches, virtual sensors, and the
// tooth contact of a gear mesh ([gear_meshes.contact]). Only the analysis `drivetrain_transient`
// uses them; the linear analyses ignore them. The checks against the rest of the model (nodes,
// DOFs, gear pairs) are in parse.cpp (Resolver::check_drivetrain).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geardyn/model/schema_builder.hpp"
#include "geardyn/model/schema_sections.hpp"

namespace geardyn::model {
namespace {

using namespace keys;  // NOLINT: the declaration table reads as a table

constexpr Unit kTorque{"N m", 1.0};
constexpr Unit kRadPerSecond{"rad/s", 1.0};
constexpr Unit kDragCoefficient{"N m s^2/rad^2", 1.0};
constexpr Unit kHuntCrossley{"s/m", 1.0};
constexpr Unit kMetrePerSecond{"m/s", 1.0};

const std::vector<std::string> kLawTypes = {"linear", "hertz", "impact", "penalty"};
const std::vector<std::string> kDirections = {"x", "y", "z", "rx", "ry", "rz"};

/// Normalises a vector the schema has already checked to be non-zero.
void normalise(DrivetrainVec3& v) {
  const double norm = std::hypot(v[0], v[1], v[2]);
  for (auto& x : v) x /= norm;
}

std::string vector_text(const std::vector<double>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i)
    out += fmt::format("{}{}", i ? ", " : "", value_text(v[i]));
  return out + "]";
}

/// `key` has as many entries as `other` (both given).
void check_same_length(const TableContext& t, const char* key, const char* other) {
  const auto n = t.at(other).numbers.size();
  const auto m = t.at(key).numbers.size();
  if (m != n)
    t.fail(key, fmt::format("{} value{}, one per '{}' entry", n, n == 1 ? "" : "s", other),
           fmt::format("{} value{}", m, m == 1 ? "" : "s"));
}

// ---------------------------------------------------------------------------------------------
// Contact laws ([contacts.law], [gear_meshes.contact.law])

/// The keys of a contact law; `rotation`: the law may act on a rotation (its units then read
/// rad for m), as a [[contacts]] law can and a gear mesh's cannot.
std::vector<Field> law_fields(bool rotation) {
  auto unit = [rotation](const char* si, const char* angular) {
    return rotation ? fmt::format("{}; {} for a rotation contact", si, angular) : std::string(si);
  };
  return {
      choice("type", kLawTypes,
             "Normal-contact law (docs/theory.md §16.2); selects the keys below. F > 0 pushes "
             "the bodies apart, delta is the penetration beyond the gap.")
          .def("\"impact\"")
          .to_enum(&ContactLawSpec::type, {ContactLawKind::Linear, ContactLawKind::Hertz,
                                           ContactLawKind::Impact, ContactLawKind::Penalty}),
      number("stiffness", kNoUnit,
             "Contact stiffness k of F = k delta^e (linear: e = 1; penalty: e = m1 = "
             "stiffness_exponent).")
          .unit_note(unit("N/m^e", "N m/rad^e"))
          .required()
          .gt(0)
          .to(&ContactLawSpec::stiffness),
      choice("tension", {"allowed", "clipped"},
             "What happens where damping pulls the separating bodies together: \"allowed\" "
             "keeps the negative (tensile) force as the law writes it (ADAMS IMPACT, the "
             "Kelvin-Voigt oscillator), \"clipped\" returns max(F, 0).")
          .def("\"allowed\"")
          .to_enum(&ContactLawSpec::clip_tension, {false, true}),
      // linear
      number("damping", kDampingCoefficient, "Viscous damping c of F = k delta + c d(delta)/dt.")
          .unit_note(unit("N s/m", "N m s/rad"))
          .def("0.0")
          .ge(0)
          .only_in({"linear"})
          .to(&ContactLawSpec::damping),
      // hertz
      number("exponent", kNoUnit,
             "Hertz exponent n of F = k delta^n (1 + chi d(delta)/dt): 1.5 for a point "
             "(ball) contact, 10/9 for a line (roller) contact.")
          .def("1.5")
          .ge(1)
          .only_in({"hertz"})
          .to(&ContactLawSpec::exponent),
      number("damping", kHuntCrossley,
             "Hunt-Crossley damping chi; for a coefficient of restitution e at impact speed v "
             "about chi = 3 (1 - e) / (2 v) (Hunt & Crossley 1975). 0: pure Hertz.")
          .unit_note(unit("s/m", "s/rad"))
          .def("0.0")
          .ge(0)
          .only_in({"hertz"})
          .to(&ContactLawSpec::damping),
      // impact
      number("exponent", kNoUnit,
             "Force exponent e of the ADAMS IMPACT function F = k delta^e + STEP(delta, 0, 0, "
             "d, c_max) d(delta)/dt.")
          .def("1.5")
          .ge(1)
          .only_in({"impact"})
          .to(&ContactLawSpec::exponent),
      number("max_damping", kDampingCoefficient,
             "Maximum damping c_max of the IMPACT function, reached at penetration_depth.")
          .unit_note(unit("N s/m", "N m s/rad"))
          .def("0.0")
          .ge(0)
          .only_in({"impact"})
          .to(&ContactLawSpec::max_damping),
      number("penetration_depth", kNoUnit,
             "Penetration d at which the IMPACT damping reaches max_damping (cubic step from "
             "0 at delta = 0).")
          .unit_note(unit("m", "rad"))
          .required()
          .gt(0)
          .only_in({"impact"})
          .to(&ContactLawSpec::penetration_depth),
      // penalty
      number("damping", kNoUnit,
             "Damping c of the penalty law F = k delta^m1 + c sign(v) |v|^m2 delta^m3, v = "
             "d(delta)/dt.")
          .unit_note("N (s/m)^m2 / m^m3")
          .def("0.0")
          .ge(0)
          .only_in({"penalty"})
          .to(&ContactLawSpec::damping),
      number("stiffness_exponent", kNoUnit, "Exponent m1 of the penalty law's elastic term.")
          .def("1.0")
          .ge(0)
          .only_in({"penalty"})
          .to(&ContactLawSpec::stiffness_exponent),
      number("rate_exponent", kNoUnit, "Exponent m2 of the penetration rate in the damping term.")
          .def("1.0")
          .ge(0)
          .only_in({"penalty"})
          .to(&ContactLawSpec::rate_exponent),
      number("damping_exponent", kNoUnit,
             "Exponent m3 of the penetration in the damping term (0: damping independent of "
             "the penetration).")
          .def("0.0")
          .ge(0)
          .only_in({"penalty"})
          .to(&ContactLawSpec::damping_exponent),
      number("penetration_regularisation", kMetre,
             "Penetration delta_r below which delta^m is replaced by its secant (used when m1 "
             "or m3 < 1, where the tangent is singular at contact).")
          .unit_note(unit("m", "rad"))
          .def("1e-9")
          .gt(0)
          .only_in({"penalty"})
          .to(&ContactLawSpec::penetration_regularisation),
      number("rate_regularisation", kNoUnit,
             "Penetration rate v_r below which |v|^m2 is replaced by its secant (used when m2 < "
             "1).")
          .unit_note(unit("m/s", "rad/s"))
          .def("1e-6")
          .gt(0)
          .only_in({"penalty"})
          .to(&ContactLawSpec::rate_regularisation),
  };
}

std::vector<Variant> law_variants() {
  return {
      variant<ContactLawSpec>("linear", "Kelvin-Voigt spring-damper F = k delta + c d(delta)/dt."),
      variant<ContactLawSpec>("hertz",
                              "Hertz power law with Hunt-Crossley damping F = k delta^n (1 + chi "
                              "d(delta)/dt) (Hunt & Crossley 1975)."),
      variant<ContactLawSpec>("impact",
                              "The MSC ADAMS IMPACT function: F = k delta^e + STEP(delta, 0, 0, "
                              "d, c_max) d(delta)/dt, the damping growing from 0 to c_max over "
                              "the penetration d by a cubic step."),
      variant<ContactLawSpec>("penalty",
                              "Penalty law F = k delta^m1 + c sign(v) |v|^m2 delta^m3 (v = "
                              "d(delta)/dt), regularised where a power below 1 makes its tangent "
                              "singular."),
  };
}

Section contact_law_section() {
  return S("law", SectionKind::Table, "[contacts.law]",
           "The contact's normal-force law (required: at least its `stiffness`, and "
           "`penetration_depth` for the IMPACT law). Keys of another law type are errors.")
      .in_table(&ContactSpec::law)
      .located(&ContactLawSpec::where)
      .fields(law_fields(true))
      .variants("type", law_variants());
}

Section mesh_contact_law_section() {
  return S("law", SectionKind::Table, "[gear_meshes.contact.law]",
           "A contact law for the flanks instead of the force-deflection law of the gear pair's "
           "maps (the same keys as [contacts.law]); with vary_stiffness its stiffness follows "
           "the map's mesh stiffness over the mesh cycle.")
      .in_optional(&MeshContactSpec::law)
      .located(&ContactLawSpec::where)
      .fields(law_fields(false))
      .variants("type", law_variants());
}

}  // namespace

Section nonlinear_contact_law_section() {
  return S("law", SectionKind::Table, "[nonlinear_elements.law]",
           "The contact law of a `type = \"contact\"` element (the same keys as "
           "[contacts.law]).")
      .in_table(&NonlinearElementSpec::law)
      .located(&ContactLawSpec::where)
      .only_in({"contact"})
      .fields(law_fields(true))
      .variants("type", law_variants());
}

namespace {

// ---------------------------------------------------------------------------------------------
// [[contacts]]

void finish_contact(ContactSpec& c, const TableContext&) { normalise(c.direction); }

}  // namespace

Section contacts_section() {
  return S("contacts", SectionKind::ArrayOfTables, "[[contacts]]",
           "Drivetrain transient: contacts between two nodes (or a node and ground) along a "
           "global direction, u = (u_node2 - u_node1) . direction: a one-sided end stop, or end "
           "play with a contact on both sides (rattle).")
      .in_array(&Model::contacts)
      .located(&ContactSpec::where)
      .fields({
          name_key("Unique contact name (result columns).").required().to(&ContactSpec::name),
          reference("node1", Ref::Node, "End i of the contact.")
              .note("ground")
              .to(&ContactSpec::node1),
          reference("node2", Ref::Node, "End j of the contact.").required().to(&ContactSpec::node2),
          vector3("direction", kNoUnit, "Contact direction in global axes (normalised).")
              .def("[1.0, 0.0, 0.0]")
              .nonzero()
              .to(&ContactSpec::direction),
          choice("motion", {"translation", "rotation"},
                 "What the contact measures: the relative translation, or the relative rotation "
                 "vector projected on `direction` (a torsional end stop).")
              .def("\"translation\"")
              .to_enum(&ContactSpec::motion, {ContactMotion::Translation, ContactMotion::Rotation}),
          choice("type", {"stop", "end_play"}, "Kind of contact; selects the keys below.")
              .def("\"stop\"")
              .to_enum(&ContactSpec::kind, {ContactKind::Stop, ContactKind::EndPlay}),
          number("gap", kNoUnit,
                 "The stop closes when u > gap (negative: closed and preloaded at u = 0).")
              .unit_note("m; rad for motion = \"rotation\"")
              .def("0.0")
              .only_in({"stop"})
              .to(&ContactSpec::gap),
          number("backlash", kNoUnit,
                 "Half play: the contact closes on one side when u > backlash and on the other "
                 "when u < -backlash.")
              .unit_note("m; rad for motion = \"rotation\"")
              .def("0.0")
              .ge(0)
              .only_in({"end_play"})
              .to(&ContactSpec::backlash),
      })
      .variants("type",
                {
                    variant<ContactSpec>("stop", "One-sided end stop."),
                    variant<ContactSpec>("end_play",
                                         "End play: contacts on both sides of a play (rattle, "
                                         "axial play of a shaft); both sides use the same law."),
                })
      .sections({contact_law_section()})
      .finish<ContactSpec>(finish_contact);
}

namespace {

// ---------------------------------------------------------------------------------------------
// [[bolts]]

void finish_bolt(BoltSpec& b, const TableContext&) { normalise(b.axis); }

}  // namespace

Section bolts_section() {
  return S("bolts", SectionKind::ArrayOfTables, "[[bolts]]",
           "Drivetrain transient: preloaded bolted joints between two bodies (VDI 2230 joint "
           "diagram): the bolt and the clamped parts as springs in parallel while the joint is "
           "closed, the bolt alone once the external load opens it; optional shear stiffness and "
           "a tightening sequence (activation_time).")
      .in_array(&Model::bolts)
      .located(&BoltSpec::where)
      .fields({
          name_key("Unique bolt name (result columns).").required().to(&BoltSpec::name),
          reference("node1", Ref::Node, "End i: the clamped part on the nut side.")
              .note("ground")
              .to(&BoltSpec::node1),
          reference("node2", Ref::Node, "End j: the clamped part on the head side.")
              .required()
              .to(&BoltSpec::node2),
          vector3("axis", kNoUnit,
                  "Bolt axis in global axes (normalised); the axial opening is u_a = (u_node2 - "
                  "u_node1) . axis.")
              .def("[0.0, 0.0, 1.0]")
              .nonzero()
              .to(&BoltSpec::axis),
          number("bolt_stiffness", kStiffness, "Axial stiffness k_S of the bolt.")
              .required()
              .gt(0)
              .to(&BoltSpec::bolt_stiffness),
          number("clamp_stiffness", kStiffness, "Stiffness k_P of the clamped parts.")
              .required()
              .gt(0)
              .to(&BoltSpec::clamp_stiffness),
          number("preload", kNewton, "Assembly preload F_V.")
              .def("0.0")
              .ge(0)
              .to(&BoltSpec::preload),
          number("load_introduction", kNoUnit,
                 "VDI 2230 load introduction factor n: the axial load acts between planes that "
                 "enclose the fraction n of the clamped parts (1: under the head and the nut).")
              .def("1.0")
              .gt(0)
              .le(1)
              .to(&BoltSpec::load_introduction),
          number("axial_damping", kDampingCoefficient, "Axial damping of the joint.")
              .def("0.0")
              .ge(0)
              .to(&BoltSpec::axial_damping),
          number("shear_stiffness", kStiffness,
                 "Stiffness across the axis (0: the bolt carries no shear).")
              .def("0.0")
              .ge(0)
              .to(&BoltSpec::shear_stiffness),
          number("shear_damping", kDampingCoefficient, "Damping across the axis.")
              .def("0.0")
              .ge(0)
              .to(&BoltSpec::shear_damping),
          number("activation_time", kSecond,
                 "Time at which the bolt is tightened (its place in the tightening sequence); "
                 "before it the joint has inactive_stiffness only.")
              .note("tightened from the start")
              .to(&BoltSpec::activation_time),
          number("preload_ramp", kSecond,
                 "Duration over which the preload rises from 0 after activation_time (0: at "
                 "once).")
              .def("0.0")
              .ge(0)
              .to(&BoltSpec::preload_ramp),
          number("inactive_stiffness", kStiffness,
                 "Axial and shear stiffness before activation (a loosely fitted bolt).")
              .def("0.0")
              .ge(0)
              .to(&BoltSpec::inactive_stiffness),
      })
      .finish<BoltSpec>(finish_bolt);
}

namespace {

// ---------------------------------------------------------------------------------------------
// [[bushings]]

struct BushingKey {
  const char* name;
  int index;  ///< 0..5: x, y, z, rx, ry, rz
  bool damping;
};

// Diagonal coefficients in the bushing frame, named like the direct keys of [[bearings]].
constexpr BushingKey kBushingKeys[] = {
    {"kxx", 0, false},  {"kyy", 1, false},  {"kzz", 2, false}, {"ktxx", 3, false},
    {"ktyy", 4, false}, {"ktzz", 5, false}, {"cxx", 0, true},  {"cyy", 1, true},
    {"czz", 2, true},   {"ctxx", 3, true},  {"ctyy", 4, true}, {"ctzz", 5, true},
};

std::vector<Field> bushing_coefficient_fields() {
  std::vector<Field> out;
  for (const auto& key : kBushingKeys) {
    const bool rotation = key.index >= 3;
    const Unit unit = key.damping ? (rotation ? kTiltDamping : kDampingCoefficient)
                                  : (rotation ? kTiltStiffness : kStiffness);
    const std::string help = fmt::format(
        "{} of the bushing {} {} (diagonal entry; the other entries are 0).",
        key.damping ? "Damping" : "Stiffness", rotation ? "about its" : "along its",
        std::string(kDirections[static_cast<std::size_t>(key.index)]).substr(rotation ? 1 : 0) +
            " axis");
    out.push_back(number(key.name, unit, help)
                      .def("0.0")
                      .ge(0)
                      .to_fn<BushingSpec>([key](BushingSpec& b, const FieldValue& v) {
                        auto& m = key.damping ? b.damping : b.stiffness;
                        m[static_cast<std::size_t>(key.index * 7)] = v.number;
                      }));
  }
  return out;
}

/// A full 6x6 matrix: diagonal >= 0 and symmetric (the element checks it is positive
/// semi-definite when it is built).
void check_bushing_matrix(const TableContext& t, const char* key) {
  if (!t.has(key)) return;
  const auto& a = t.at(key).numbers;
  for (std::size_t i = 0; i < 6; ++i) {
    if (a[i * 7] < 0.0)
      t.fail(key, "a 6x6 matrix with diagonal entries >= 0",
             fmt::format("{} at row {}", value_text(a[i * 7]), i + 1));
    for (std::size_t j = i + 1; j < 6; ++j) {
      const double x = a[i * 6 + j], y = a[j * 6 + i];
      if (std::abs(x - y) > 1e-12 * std::max({std::abs(x), std::abs(y), 1e-300}))
        t.fail(key, "a symmetric 6x6 matrix",
               fmt::format("{}[{}][{}] = {} but {}[{}][{}] = {}", key, i, j, value_text(x), key, j,
                           i, value_text(y)));
    }
  }
}

void finish_bushing(BushingSpec& b, const TableContext& t) {
  normalise(b.x_axis);
  normalise(b.z_axis);
  const double cosine =
      b.x_axis[0] * b.z_axis[0] + b.x_axis[1] * b.z_axis[1] + b.x_axis[2] * b.z_axis[2];
  // 1e-6: axes written with six significant digits are orthogonal to this; the remainder is
  // removed below so that the frame is exactly orthonormal.
  if (std::abs(cosine) > 1e-6)
    t.fail(
        "z_axis", "an axis orthogonal to x_axis (after normalising both)",
        fmt::format("{}, at {} deg to x_axis", vector_text(t.at("z_axis").numbers),
                    value_text(std::acos(std::clamp(cosine, -1.0, 1.0)) / units::kRadPerDegree)));
  for (int i = 0; i < 3; ++i)
    b.z_axis[static_cast<std::size_t>(i)] -= cosine * b.x_axis[static_cast<std::size_t>(i)];
  normalise(b.z_axis);
  check_bushing_matrix(t, "stiffness");
  check_bushing_matrix(t, "damping");
  if (t.has("preload") && t.at("preload").numbers.size() != 6)
    t.fail("preload", "6 values (x, y, z, rx, ry, rz)",
           fmt::format("{} values", t.at("preload").numbers.size()));
  for (std::size_t i = 0; i < b.tables.size(); ++i)
    for (std::size_t k = 0; k < i; ++k)
      if (b.tables[i].direction == b.tables[k].direction)
        throw InputError(
            b.tables[i].where, fmt::format("{}.tables[{}].direction", t.path, i),
            "one table per direction",
            fmt::format("\"{}\" again (tables[{}] has it)",
                        kDirections[static_cast<std::size_t>(b.tables[i].direction)], k));
}

void finish_bushing_table(BushingTableSpec& b, const TableContext& t) {
  check_same_length(t, "force", "deflection");
  for (std::size_t k = 1; k < b.force.size(); ++k)
    if (b.force[k] < b.force[k - 1])
      t.fail("force", "forces non-decreasing with the deflection (a stiffness >= 0)",
             fmt::format("{} then {}", value_text(b.force[k - 1]), value_text(b.force[k])));
  const auto zero = std::find(b.deflection.begin(), b.deflection.end(), 0.0);
  if (zero == b.deflection.end() ||
      b.force[static_cast<std::size_t>(zero - b.deflection.begin())] != 0.0)
    t.fail("deflection", "a point at deflection 0 with force 0",
           zero == b.deflection.end()
               ? fmt::format("{}, without 0", vector_text(b.deflection))
               : fmt::format(
                     "force {} at deflection 0",
                     value_text(b.force[static_cast<std::size_t>(zero - b.deflection.begin())])),
           "shift the table and give the force at zero deflection as the bushing's preload");
}

Section bushing_tables_section() {
  return S("tables", SectionKind::ArrayOfTables, "[[bushings.tables]]",
           "Nonlinear force-deflection curves, one per direction of the bushing frame; each "
           "replaces that direction's diagonal stiffness. Outside the table the end slopes "
           "continue linearly.")
      .in_array(&BushingSpec::tables)
      .located(&BushingTableSpec::where)
      .fields({
          choice("direction", kDirections,
                 "Direction of the bushing frame (rx, ry, rz: a moment over a rotation).")
              .required()
              .to_fn<BushingTableSpec>(
                  [](BushingTableSpec& b, const FieldValue& v) { b.direction = v.choice; }),
          numbers("deflection", kNoUnit,
                  "Deflections, strictly increasing, one of them 0 (with force 0).")
              .unit_note("m; rad for rx, ry, rz")
              .required()
              .increasing()
              .min_items(2)
              .to(&BushingTableSpec::deflection),
          numbers("force", kNoUnit,
                  "Force at each deflection, non-decreasing (0 at deflection 0; the preload is "
                  "given separately).")
              .unit_note("N; N m for rx, ry, rz")
              .required()
              .to(&BushingTableSpec::force),
          choice("interpolation", {"cubic", "linear"},
                 "Between the points: a monotone cubic (Fritsch & Carlson 1980; smooth "
                 "stiffness), or straight lines (the stiffness jumps at the points).")
              .def("\"cubic\"")
              .to_enum(&BushingTableSpec::linear, {false, true}),
      })
      .finish<BushingTableSpec>(finish_bushing_table);
}

}  // namespace

Section bushings_section() {
  std::vector<Field> fields = {
      name_key("Unique bushing name (result columns).").required().to(&BushingSpec::name),
      reference("node1", Ref::Node, "End i of the bushing.").note("ground").to(&BushingSpec::node1),
      reference("node2", Ref::Node, "End j of the bushing.").required().to(&BushingSpec::node2),
      vector3("x_axis", kNoUnit, "x axis of the bushing frame in global axes (normalised).")
          .def("[1.0, 0.0, 0.0]")
          .nonzero()
          .to(&BushingSpec::x_axis),
      vector3("z_axis", kNoUnit,
              "z axis of the bushing frame in global axes (normalised; orthogonal to x_axis); "
              "y = z x x.")
          .def("[0.0, 0.0, 1.0]")
          .nonzero()
          .to(&BushingSpec::z_axis),
  };
  for (auto& f : bushing_coefficient_fields()) fields.push_back(std::move(f));
  fields.push_back(matrix("stiffness", {6},
                          "Full 6x6 stiffness matrix over (x, y, z, rx, ry, rz) of the bushing "
                          "frame (symmetric, positive semi-definite), instead of the k.. keys.")
                       .unit_note("N/m, N/rad, N, N m/rad by block")
                       .to_fn<BushingSpec>([](BushingSpec& b, const FieldValue& v) {
                         std::copy_n(v.numbers.begin(), 36, b.stiffness.begin());
                       }));
  fields.push_back(matrix("damping", {6},
                          "Full 6x6 damping matrix (symmetric, positive semi-definite), instead "
                          "of the c.. keys.")
                       .unit_note("N s/m, N s/rad, N s, N m s/rad by block")
                       .to_fn<BushingSpec>([](BushingSpec& b, const FieldValue& v) {
                         std::copy_n(v.numbers.begin(), 36, b.damping.begin());
                       }));
  fields.push_back(numbers("preload", kNoUnit,
                           "Force and moment at zero deflection, over (x, y, z, rx, ry, rz) of "
                           "the bushing frame (6 values).")
                       .unit_note("N for x, y, z; N m for rx, ry, rz")
                       .note("zero")
                       .to_fn<BushingSpec>([](BushingSpec& b, const FieldValue& v) {
                         std::copy_n(v.numbers.begin(), std::min<std::size_t>(6, v.numbers.size()),
                                     b.preload.begin());
                       }));
  std::vector<std::string> stiffness_keys, damping_keys;
  for (const auto& key : kBushingKeys)
    (key.damping ? damping_keys : stiffness_keys).push_back(key.name);
  return S("bushings", SectionKind::ArrayOfTables, "[[bushings]]",
           "Drivetrain transient: 6-coordinate bushings (an elastic damping part, a rubber "
           "mount) between two nodes or a node and ground: linear stiffness and damping in the "
           "bushing frame, a preload, and nonlinear force-deflection tables per direction.")
      .in_array(&Model::bushings)
      .located(&BushingSpec::where)
      .fields(fields)
      .choices(
          {{{stiffness_keys, {"stiffness"}}, false, {}}, {{damping_keys, {"damping"}}, false, {}}})
      .sections({bushing_tables_section()})
      .finish<BushingSpec>(finish_bushing);
}

namespace {

// ---------------------------------------------------------------------------------------------
// [[rolling_bearings]]

void finish_rolling_bearing(RollingBearingSpec& b, const TableContext& t) {
  if (b.element_diameter >= b.pitch_diameter)
    t.fail("element_diameter",
           fmt::format("a ball or roller diameter < pitch_diameter = {} m",
                       value_text(b.pitch_diameter)),
           value_text(b.element_diameter));
}

}  // namespace

Section rolling_bearings_section() {
  return S("rolling_bearings", SectionKind::ArrayOfTables, "[[rolling_bearings]]",
           "Drivetrain transient: rolling-element bearings as contacts. Each ball or roller "
           "carries Q = K_n delta^n while compressed beyond the clearance, at its current "
           "angular position (the cage turns with the shaft), so the stiffness varies at the "
           "ball-pass frequency. The bearing axis is the spin axis of `node`.")
      .in_array(&Model::rolling_bearings)
      .located(&RollingBearingSpec::where)
      .fields({
          name_key("Unique bearing name (result columns).")
              .required()
              .to(&RollingBearingSpec::name),
          reference("node", Ref::Node,
                    "Inner ring: a node with a spin axis (a shaft station, or a [[nodes]] entry "
                    "with spin_of).")
              .required()
              .to(&RollingBearingSpec::node),
          reference("housing", Ref::Node, "Outer ring: a housing node.")
              .note("ground")
              .to(&RollingBearingSpec::housing),
          integer("elements", "Number of balls or rollers.")
              .required()
              .ge(1)
              .le(1000)
              .to(&RollingBearingSpec::elements),
          number("stiffness_constant", kNoUnit,
                 "Load-deflection constant K_n of one rolling element (inner and outer contact "
                 "in series): Q = K_n delta^n.")
              .unit_note("N/m^n")
              .required()
              .gt(0)
              .to(&RollingBearingSpec::stiffness_constant),
          number("exponent", kNoUnit,
                 "Load-deflection exponent n: 1.5 for ball (point) contact, 10/9 for roller "
                 "(line) contact.")
              .def("1.5")
              .ge(1)
              .le(2)
              .to(&RollingBearingSpec::exponent),
          number("radial_clearance", kMetre,
                 "Diametral clearance: total radial play of the inner ring (negative: "
                 "interference, a preloaded bearing).")
              .def("0.0")
              .to(&RollingBearingSpec::radial_clearance),
          number("axial_clearance", kMetre, "Total axial play (negative: axial preload).")
              .def("0.0")
              .to(&RollingBearingSpec::axial_clearance),
          number("contact_angle_deg", kDegree,
                 "Nominal contact angle (0: radial bearing; taper-roller and angular-contact "
                 "bearings: the cone or contact angle).")
              .def("0.0")
              .ge(-90)
              .le(90)
              .to(&RollingBearingSpec::contact_angle),
          number("pitch_diameter", kMetre, "Pitch diameter of the element set.")
              .required()
              .gt(0)
              .to(&RollingBearingSpec::pitch_diameter),
          number("element_diameter", kMetre,
                 "Ball or roller diameter (< pitch_diameter); sets the cage speed.")
              .required()
              .gt(0)
              .to(&RollingBearingSpec::element_diameter),
          number("cage_angle_deg", kDegree,
                 "Angular position of the first element at t = 0, from the node frame's e1 axis.")
              .def("0.0")
              .to(&RollingBearingSpec::cage_angle),
          number("radial_damping", kDampingCoefficient, "Radial damping of the bearing.")
              .def("0.0")
              .ge(0)
              .to(&RollingBearingSpec::radial_damping),
          number("axial_damping", kDampingCoefficient, "Axial damping of the bearing.")
              .def("0.0")
              .ge(0)
              .to(&RollingBearingSpec::axial_damping),
      })
      .finish<RollingBearingSpec>(finish_rolling_bearing);
}

namespace {

// ---------------------------------------------------------------------------------------------
// [[drivers]], [[loads]], [[clutches]]

void finish_speed_driver(DriverSpec&, const TableContext& t) {
  check_same_length(t, "speed_rpm", "time");
}

void finish_motor_driver(DriverSpec&, const TableContext& t) {
  check_same_length(t, "motor_torque", "motor_speed_rpm");
}

void finish_load(LoadTorqueSpec& l, const TableContext& t) {
  const char* over = t.has("speed_rpm") ? "speed_rpm" : t.has("time") ? "time" : nullptr;
  if (over == nullptr) {
    if (t.has("table_torque"))
      t.fail("table_torque",
             "a table with its abscissa: speed_rpm = [...] (over the node's speed) or time = "
             "[...]",
             "table_torque without speed_rpm or time");
    return;
  }
  if (!t.has("table_torque"))
    t.fail("table_torque",
           fmt::format("the torques of the table over '{}' (table_torque = [...])", over),
           fmt::format("'{}' without 'table_torque'", over));
  check_same_length(t, "table_torque", over);
  l.table_over = t.has("speed_rpm") ? LoadTableOver::Speed : LoadTableOver::Time;
  l.table_x = t.at(over).numbers;
}

}  // namespace

Section drivers_section() {
  return S("drivers", SectionKind::ArrayOfTables, "[[drivers]]",
           "Drivetrain transient: what turns the drivetrain, acting on the rotation of a node "
           "about its spin axis (its rz): a prescribed speed over time, or a motor's torque-speed "
           "curve with its rotor inertia. At most one driver per node, on a free rz (not "
           "constrained, and kept by the shaft's `dofs`).")
      .in_array(&Model::drivers)
      .located(&DriverSpec::where)
      .fields({
          name_key("Unique driver name (result columns).").required().to(&DriverSpec::name),
          reference("node", Ref::Node, "Node driven (about its spin axis).")
              .required()
              .to(&DriverSpec::node),
          choice("type", {"speed", "motor"}, "Kind of driver; selects the keys below.")
              .required()
              .to_enum(&DriverSpec::kind, {DriverKind::Speed, DriverKind::Motor}),
          numbers("time", kSecond,
                  "Times of the speed table, increasing from >= 0; the speed is linear between "
                  "them and held after the last (one point: a constant speed; a step: two close "
                  "times).")
              .required()
              .ge(0)
              .increasing()
              .min_items(1)
              .only_in({"speed"})
              .to(&DriverSpec::times),
          numbers("speed_rpm", kRpm, "Prescribed speed at each time (sense about the node's e3).")
              .required()
              .min_items(1)
              .only_in({"speed"})
              .to(&DriverSpec::speeds),
          numbers("motor_speed_rpm", kRpm,
                  "Speeds of the motor's torque-speed curve, increasing; the torque is linear "
                  "between them and held outside.")
              .required()
              .increasing()
              .min_items(1)
              .only_in({"motor"})
              .to(&DriverSpec::motor_speeds),
          numbers("motor_torque", kTorque, "Motor torque at each speed (about the node's e3).")
              .required()
              .min_items(1)
              .only_in({"motor"})
              .to(&DriverSpec::motor_torques),
          number("inertia", kInertia, "Rotor inertia of the motor, added to the node.")
              .def("0.0")
              .ge(0)
              .only_in({"motor"})
              .to(&DriverSpec::inertia),
      })
      .variants("type", {
                            variant<DriverSpec>("speed",
                                                "Prescribed speed over time: the node's rotation "
                                                "follows it whatever torque that takes.",
                                                finish_speed_driver),
                            variant<DriverSpec>("motor",
                                                "A motor: torque from its torque-speed curve at "
                                                "the node's current speed.",
                                                finish_motor_driver),
                        });
}

Section loads_section() {
  return S("loads", SectionKind::ArrayOfTables, "[[loads]]",
           "Drivetrain transient: load torques about a node's spin axis (on its rz): T = torque "
           "+ table(speed or time) - drag omega |omega|.")
      .in_array(&Model::loads)
      .located(&LoadTorqueSpec::where)
      .fields({
          name_key("Unique load name (result columns).").required().to(&LoadTorqueSpec::name),
          reference("node", Ref::Node, "Node loaded (about its spin axis).")
              .required()
              .to(&LoadTorqueSpec::node),
          number("torque", kTorque,
                 "Constant torque in the sense of the node's e3 (a braking load on a shaft "
                 "turning positively is negative).")
              .def("0.0")
              .to(&LoadTorqueSpec::torque),
          numbers("speed_rpm", kRpm,
                  "Abscissa of a table over the node's speed, increasing (torque held outside).")
              .increasing()
              .min_items(1)
              .note("no table over speed")
              .read_by_finish<LoadTorqueSpec>(),
          numbers("time", kSecond, "Abscissa of a table over time, increasing.")
              .increasing()
              .min_items(1)
              .note("no table over time")
              .read_by_finish<LoadTorqueSpec>(),
          numbers("table_torque", kTorque,
                  "Torque at each entry of speed_rpm or time, added to `torque`.")
              .note("no table")
              .to(&LoadTorqueSpec::table_torque),
          number("drag", kDragCoefficient,
                 "Drag coefficient c_d: adds -c_d omega |omega| (fan, churning losses).")
              .def("0.0")
              .ge(0)
              .to(&LoadTorqueSpec::drag),
      })
      .choices({{{{"speed_rpm"}, {"time"}}, false, {}}})
      .finish<LoadTorqueSpec>(finish_load);
}

Section clutches_section() {
  return S("clutches", SectionKind::ArrayOfTables, "[[clutches]]",
           "Drivetrain transient: slipping clutches between the spin rotations of two nodes, or "
           "brakes (without node1): a torque limit T = max_torque tanh(slip / slip_speed) "
           "(regularised Coulomb friction).")
      .in_array(&Model::clutches)
      .located(&ClutchSpec::where)
      .fields({
          name_key("Unique clutch name (result columns).").required().to(&ClutchSpec::name),
          reference("node1", Ref::Node, "Input side.")
              .note("ground (a brake)")
              .to(&ClutchSpec::node1),
          reference("node2", Ref::Node, "Output side.").required().to(&ClutchSpec::node2),
          number("max_torque", kTorque, "Largest torque transmitted (the slipping torque).")
              .required()
              .gt(0)
              .to(&ClutchSpec::max_torque),
          number("slip_speed", kRadPerSecond,
                 "Slip speed at which the torque reaches tanh(1) = 76 % of max_torque (smaller: "
                 "closer to dry friction, stiffer to integrate).")
              .def("0.01")
              .gt(0)
              .to(&ClutchSpec::slip_speed),
          number("engage_time", kSecond, "Time before which the clutch transmits nothing.")
              .def("0.0")
              .ge(0)
              .to(&ClutchSpec::engage_time),
      });
}

namespace {

void finish_virtual_sensor(VirtualSensorSpec& s, const TableContext&) {
  if (s.direction) normalise(*s.direction);
}

}  // namespace

Section virtual_sensors_section() {
  return S("virtual_sensors", SectionKind::ArrayOfTables, "[[virtual_sensors]]",
           "Drivetrain transient: displacement, velocity and acceleration of a node, along a "
           "DOF of the node frame or a global direction (e.g. the normal of a housing face: a "
           "virtual accelerometer).")
      .in_array(&Model::virtual_sensors)
      .located(&VirtualSensorSpec::where)
      .fields({
          name_key("Unique sensor name (result columns).").required().to(&VirtualSensorSpec::name),
          reference("node", Ref::Node, "Node measured.").required().to(&VirtualSensorSpec::node),
          choice("dof", kComponentChoices, "DOF measured, in the node's frame.")
              .required()
              .to_fn<VirtualSensorSpec>(
                  [](VirtualSensorSpec& s, const FieldValue& v) { s.component = v.choice; }),
          vector3("direction", kNoUnit, "Global direction measured (normalised).")
              .required()
              .nonzero()
              .to(&VirtualSensorSpec::direction),
          boolean("rotation",
                  "With `direction`: measure the rotation vector's component (rad) instead of "
                  "the translation's (m).")
              .def("false")
              .to(&VirtualSensorSpec::rotation),
      })
      .choices({{{{"dof"}, {"direction", "rotation"}}, true, {}}})
      .finish<VirtualSensorSpec>(finish_virtual_sensor);
}

Section mesh_contact_section() {
  return S("contact", SectionKind::Table, "[gear_meshes.contact]",
           "Drivetrain transient: the mesh's tooth contact (absent: the constant `stiffness` "
           "along the line of action, no back flank, a linear law). The analyses in the "
           "frequency domain ignore it.")
      .in_optional(&GearMesh::contact)
      .located(&MeshContactSpec::where)
      .fields({
          reference("gear_pair", Ref::GearPair,
                    "Gear pair whose maps (transmission error and mesh stiffness over the pinion "
                    "angle and the torque, from the tooth contact analysis or an STE / LTCA "
                    "file) the mesh uses.")
              .note("the mesh's constant `stiffness`")
              .to(&MeshContactSpec::gear_pair),
          number("backlash", kMetre,
                 "Total backlash along the line of action: the teeth separate and the back "
                 "flanks strike once the relative motion exceeds it.")
              .ge(0)
              .note("no back-flank contact")
              .to(&MeshContactSpec::backlash),
          boolean("vary_stiffness",
                  "With a [gear_meshes.contact.law]: scale its stiffness by k(theta) / mean k "
                  "of the map, so the mesh stiffness varies over the mesh cycle.")
              .def("true")
              .to(&MeshContactSpec::vary_stiffness),
          number("friction", kNoUnit,
                 "Tooth friction coefficient mu (0: none): the force mu F_n along the profile, "
                 "against the sliding, which reverses at the pitch point; its moments about "
                 "both shafts follow the contact's position on the path of contact, taken from "
                 "the mesh's [[gear_pairs]] geometry (docs/theory.md §16.6). Needs gear_pair "
                 "naming an external spur or helical pair (tooth pairs share the load "
                 "equally).")
              .def("0.0")
              .ge(0)
              .le(1)
              .to(&MeshContactSpec::friction),
          number("friction_velocity", kMetrePerSecond,
                 "Sliding speed v_eps of the friction's smoothed sign tanh(v_s / v_eps): "
                 "smaller is closer to dry friction at the pitch point and stiffer to "
                 "integrate.")
              .def("1e-3")
              .gt(0)
              .to(&MeshContactSpec::friction_velocity),
      })
      .sections({mesh_contact_law_section()});
}

}  // namespace geardyn::model
