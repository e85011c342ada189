// The `type = "sweep"` analysis in the registry: its keys, the [[analyses.outputs]] it tabulates
// (any scalar output of the other analysis types), its checks and how it runs.
#include <set>

#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/sweep.hpp"
#include "geardyn/model/schema_builder.hpp"

namespace geardyn::analyses {
namespace {

using namespace model::keys;  // NOLINT: the declaration table reads as a table
using model::Analysis;
using model::FieldType;
using model::FieldValue;
using model::Ref;
using model::TableContext;

/// reference_value, when given, is one of the swept values (the deltas are taken against it).
void check_reference(const SweepSettings& s, const TableContext& t) {
  if (!t.has("reference_value")) return;
  for (double v : s.values)
    if (std::abs(v - s.reference_value) <= 1e-9 * std::max(1.0, std::abs(v))) return;
  std::string values;
  for (double v : s.values) values += (values.empty() ? "" : ", ") + value_text(v);
  t.fail("reference_value", fmt::format("one of the swept values ({})", values),
         value_text(s.reference_value));
}

void finish(Analysis& a, const TableContext& t) {
  auto& s = a.settings_of<SweepSettings>();
  const bool log = s.log_x;
  if (t.has("values")) {
    if (log)
      for (double v : s.values)
        if (v <= 0.0) t.fail("values", "values > 0 for spacing = \"log\"", value_text(v));
    check_reference(s, t);
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
  check_reference(s, t);
}

/// Every scalar name offered by a registered type, in registry order, once.
std::vector<std::string> scalar_names() {
  std::vector<std::string> names;
  for (const auto& t : registry())
    for (const auto& s : t.scalars)
      if (std::find(names.begin(), names.end(), s.name) == names.end()) names.push_back(s.name);
  return names;
}

/// The scalar names whose outputs read `parameter` ("mode", "sensor", "at_rpm", "at_hz").
std::vector<std::string> scalars_reading(const std::string& parameter) {
  std::vector<std::string> names;
  for (const auto& t : registry())
    for (const auto& s : t.scalars)
      if (std::find(s.parameters.begin(), s.parameters.end(), parameter) != s.parameters.end() &&
          std::find(names.begin(), names.end(), s.name) == names.end())
        names.push_back(s.name);
  return names;
}

/// The meaning of a scalar with the types that offer it, for the reference.
std::string scalar_help(const std::string& name) {
  std::string meaning, types;
  for (const auto& t : registry())
    for (const auto& s : t.scalars)
      if (s.name == name) {
        if (meaning.empty())
          meaning = s.meaning + (s.unit.empty() ? std::string() : " [" + s.unit + "]");
        types += (types.empty() ? "" : ", ") + t.name;
      }
  return fmt::format("{} (target: {}).", meaning.substr(0, meaning.size()), types);
}

/// True when some type's scalar `quantity` reads `parameter`.
bool reads(const std::string& quantity, const std::string& parameter) {
  const std::vector<std::string> names = scalars_reading(parameter);
  return std::find(names.begin(), names.end(), quantity) != names.end();
}

/// The default column label: the quantity with the sensor and/or the mode it reads
/// (natural_frequency_2, peak_amplitude_bearing_x, contact_ratio).
void finish_output(SweepOutput& o, const TableContext& t) {
  o.at_speed = t.has("at_rpm");
  if (t.has("label")) return;
  const bool sensor = (reads(o.quantity, "sensor") && t.has("sensor")) ||
                      (reads(o.quantity, "channel") && t.has("channel"));
  // With a sensor, the mode (peak number) shows only when given.
  const bool mode = reads(o.quantity, "mode") && (!sensor || t.has("mode"));
  if (sensor && mode)
    o.label = fmt::format("{}_{}_{}", o.quantity, o.sensor, o.mode);
  else if (sensor)
    o.label = fmt::format("{}_{}", o.quantity, o.sensor);
  else if (mode)
    o.label = fmt::format("{}_{}", o.quantity, o.mode);
  else
    o.label = o.quantity;
}

model::Section outputs_section() {
  const std::vector<std::string> quantities = scalar_names();
  std::vector<model::Variant> variants;
  for (const auto& q : quantities) variants.push_back(variant<SweepOutput>(q, scalar_help(q)));
  return S("outputs", model::SectionKind::ArrayOfTables, "[[analyses.outputs]]",
           "Scalar results tabulated per sweep point.")
      .in_fn<Analysis, SweepOutput>([](Analysis& a) {
        auto& outs = a.settings_of<SweepSettings>().outputs;
        outs.emplace_back();
        return &outs.back();
      })
      .required()
      .min_count(1)
      .fields({
          choice("quantity", quantities, "What to tabulate; selects the keys below.")
              .required()
              .to(&SweepOutput::quantity),
          integer("mode", "Mode number (1-based, in order of frequency).")
              .def("1")
              .ge(1)
              .le(10000)
              .only_in(scalars_reading("mode"))
              .to(&SweepOutput::mode),
          reference("sensor", Ref::Sensor, "Sensor whose response is used.")
              .required()
              .only_in(scalars_reading("sensor"))
              .to(&SweepOutput::sensor),
          text("channel",
               "Time-history channel whose response is used: a column name of the target's "
               "time_history table (drivetrain_transient), e.g. \"B1_bolt_force_n\".")
              .required()
              .only_in(scalars_reading("channel"))
              .to(&SweepOutput::sensor),
          number("at_rpm", kRpm, "Speed at which to read the amplitude (unbalance target).")
              .required()
              .ge(0)
              .only_in(scalars_reading("at_rpm"))
              .to(&SweepOutput::at),
          number("at_hz", kHertz,
                 "Frequency at which to read the amplitude (harmonic "
                 "target).")
              .required()
              .ge(0)
              .only_in(scalars_reading("at_hz"))
              .to(&SweepOutput::at),
          text("label", "Column name stem in the results table.")
              .identifier()
              .note("quantity with its sensor and/or mode, e.g. `natural_frequency_1`")
              .to(&SweepOutput::label),
      })
      .choices({{{{"at_rpm"}, {"at_hz"}}, true, {"amplitude_at"}}})
      .variants("quantity", variants)
      .finish<SweepOutput>(finish_output);
}

/// "a modal or campbell": the types that offer `quantity` (with `at` read as a speed or not).
std::string types_offering(const std::string& quantity, bool amplitude_at, bool at_rpm) {
  std::vector<std::string> names;
  for (const auto& t : registry())
    for (const auto& s : t.scalars) {
      if (s.name != quantity) continue;
      const bool reads_rpm =
          std::find(s.parameters.begin(), s.parameters.end(), "at_rpm") != s.parameters.end();
      if (!amplitude_at || reads_rpm == at_rpm) names.push_back(t.name);
    }
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? " or " : "") + names[i];
  if (names.empty()) return "another";
  const bool vowel = std::string("aeiou").find(names.front()[0]) != std::string::npos;
  return fmt::format("{} {}{}", vowel ? "an" : "a", out,
                     amplitude_at ? (at_rpm ? " (at_rpm)" : " (at_hz)") : "");
}

bool offers(const std::string& type, const SweepOutput& o) {
  const AnalysisType* t = find_analysis_type(type);
  if (t == nullptr) return false;
  for (const auto& s : t->scalars) {
    if (s.name != o.quantity) continue;
    if (o.quantity != "amplitude_at") return true;
    const bool reads_rpm =
        std::find(s.parameters.begin(), s.parameters.end(), "at_rpm") != s.parameters.end();
    if (reads_rpm == o.at_speed) return true;
  }
  return false;
}

// The target analysis exists and is not a sweep, the parameters are numeric keys outside the
// sweep, integer keys get integers, each output is one the target offers, labels are unique.
void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  const auto& s = a.settings_of<SweepSettings>();
  const model::Model& m = check.model();
  check.check_name(path + ".analysis", s.analysis, model::names_of(m.analyses), "analysis",
                   "analyses");
  const Analysis* target = m.find_analysis(s.analysis);
  if (target == &a)
    check.fail(path + ".analysis", "the name of another analysis", "this sweep's own name");
  if (target->type == "sweep")
    check.fail(path + ".analysis", "an analysis that is not a sweep",
               fmt::format("\"{}\", a sweep", s.analysis));
  if (s.parameter.rfind(path + ".", 0) == 0)
    check.fail(path + ".parameter", "a key outside this sweep",
               fmt::format("\"{}\", a key of the sweep itself", s.parameter));
  model::check_number_key(check.document(), s.parameter, check.locate(path + ".parameter"));
  for (const auto& linked : s.linked_parameters)
    model::check_number_key(check.document(), linked, check.locate(path + ".linked_parameters"));
  // Integer keys take integral values only.
  if (model::field_of(check.document(), s.parameter, check.locate(path + ".parameter")).type ==
      FieldType::Integer)
    for (std::size_t k = 0; k < s.values.size(); ++k)
      if (s.values[k] != std::floor(s.values[k]))
        check.fail(path + (check.given(path + ".values") ? ".values" : ".start"),
                   fmt::format("integers, since {} is an integer key", s.parameter),
                   fmt::format("{}", s.values[k]));
  std::set<std::string> labels;
  for (std::size_t k = 0; k < s.outputs.size(); ++k) {
    const SweepOutput& o = s.outputs[k];
    const std::string opath = fmt::format("{}.outputs[{}]", path, k);
    // A `channel` names a column of the target's record, known only when it runs (the
    // scalar reports an unknown one); a `sensor` is a [[sensors]] entry.
    if (!o.sensor.empty() && !check.given(opath + ".channel"))
      check.check_name(opath + ".sensor", o.sensor, model::names_of(m.sensors), "sensor",
                       "sensors");
    if (!offers(target->type, o))
      check.fail(opath + ".quantity",
                 fmt::format("an output of {} analysis",
                             types_offering(o.quantity, o.quantity == "amplitude_at", o.at_speed)),
                 fmt::format("\"{}\" for analysis '{}' of type \"{}\"", o.quantity, s.analysis,
                             target->type));
    if (!labels.insert(o.label).second)
      check.fail(opath + ".label", "a label not used by another output of this sweep",
                 fmt::format("\"{}\" again", o.label), "give the outputs different `label`s");
  }
}

std::vector<model::Field> keys() {
  return {
      spacing_key().to_settings_fn<SweepSettings>(
          [](auto& s, const FieldValue& v) { s.log_x = v.choice == 1; }),
      F("parameter", FieldType::String,
        "Key path of the numeric key varied, e.g. \"bearings[0].kxx\" or "
        "\"analyses[1].speed_rpm\" (values in that key's unit).")
          .ref(Ref::KeyPath)
          .required()
          .to_settings(&SweepSettings::parameter),
      F("linked_parameters", FieldType::StringArray,
        "Further key paths set to the same value at each point, e.g. "
        "[\"bearings[0].kyy\"] with parameter = \"bearings[0].kxx\" for an isotropic "
        "bearing.")
          .def("[]")
          .to_settings(&SweepSettings::linked_parameters),
      numbers("values", kNoUnit, "Values of the parameter.")
          .unit_note("unit of the key")
          .min_items(1)
          .to_settings(&SweepSettings::values),
      number("start", kNoUnit, "First value of an evenly spaced range.")
          .unit_note("unit of the key")
          .required()
          .read_by_finish<Analysis>(),
      number("stop", kNoUnit, "Last value of the range.")
          .unit_note("unit of the key")
          .required()
          .read_by_finish<Analysis>(),
      integer("count", "Number of values in the range.")
          .required()
          .ge(2)
          .le(100000)
          .read_by_finish<Analysis>(),
      reference("analysis", Ref::Analysis,
                "Name of the analysis run at each point (not "
                "a sweep).")
          .required()
          .to_settings(&SweepSettings::analysis),
      number("reference_value", kNoUnit,
             "The swept value the others are compared with (a model variant's baseline): the "
             "table sweep_deltas gives each output's difference from its value there (for "
             "levels in dB: the level difference, as in an SPL delta table).")
          .unit_note("unit of the key")
          .note("no delta table")
          .to_settings(&SweepSettings::reference_value),
      integer("threads",
              "Worker threads (0: all cores); 1 when the system BLAS is a sequential OpenBLAS, "
              "which is not safe to call from several threads (the notes say so).")
          .def("0")
          .ge(0)
          .le(4096)
          .to_settings(&SweepSettings::threads),
  };
}

}  // namespace

AnalysisType sweep_analysis() {
  AnalysisType type;
  type.name = "sweep";
  type.declare = [] {
    auto d = declaration<SweepSettings>("sweep",
                                        "Runs another analysis for each value of one parameter "
                                        "and tabulates scalar outputs.");
    d.fields = keys();
    d.choices = {{{{"values"}, {"start", "stop", "count"}}, true, {}}};
    d.sections = {outputs_section()};
    d.finish = finish;
    d.check = check;
    return d;
  };
  type.run = runner(run_sweep, sweep_output);
  return type;
}

}  // namespace geardyn::analyses
