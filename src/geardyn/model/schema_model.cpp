// The root of the model file's declaration table: `version`, `title`, the model's sections and
// [[analyses]], whose `type` selects one of the analysis types given by the caller (the analysis
// registry, src/geardyn/analyses/registry.hpp) and with it the keys that type declares.
#include <fmt/format.h>

#include <stdexcept>

#include "geardyn/model/parse.hpp"
#include "geardyn/model/schema_builder.hpp"
#include "geardyn/model/schema_sections.hpp"

namespace geardyn::model {
namespace {

using namespace keys;  // NOLINT: the declaration table reads as a table

/// The keys every analysis has; `type` lists the declared types and makes their settings.
std::vector<Field> common_analysis_fields(const std::vector<AnalysisDeclaration>& analyses) {
  std::vector<std::string> names;
  std::vector<std::function<std::unique_ptr<AnalysisSettings>()>> makers;
  for (const auto& a : analyses) {
    names.push_back(a.name);
    makers.push_back(a.make_settings);
  }
  return {
      name_key("Unique analysis name (results folder, sweep target).")
          .required()
          .to(&Analysis::name),
      choice("type", names, "Kind of analysis; selects the keys below.")
          .required()
          .to_fn<Analysis>([names, makers](Analysis& a, const FieldValue& v) {
            const auto k = static_cast<std::size_t>(v.choice);
            a.type = names.at(k);
            a.settings = makers.at(k)();
          }),
      boolean("enabled", "Run it (false: only as the target of a sweep).")
          .def("true")
          .to(&Analysis::enabled),
      F("set", FieldType::StringArray,
        "Model changes for this analysis only, as \"key.path=value\" like `--set`, "
        "e.g. [\"gear_meshes[0].stiffness=0\"] for a variant without the mesh.")
          .def("[]")
          .to(&Analysis::overrides),
  };
}

/// The analysis types that need no rotor, for the message when a model without one asks for one
/// that does.
std::string rotorless_types(const std::vector<AnalysisDeclaration>& analyses) {
  std::string out;
  for (const auto& a : analyses)
    if (!a.needs_rotor) out += fmt::format("{}{}", out.empty() ? "" : ", ", a.name);
  return out;
}

/// The type's own checks, after the generic one: a rotor analysis needs [[shafts]] or [[nodes]].
Checker variant_check(const AnalysisDeclaration& a, const std::string& rotorless) {
  return [a, rotorless](const void* object, const std::string& path, const ModelCheck& check) {
    const Analysis& analysis = *static_cast<const Analysis*>(object);
    if (a.needs_rotor && check.model().shafts.empty() && check.model().nodes.empty())
      check.fail(path + ".type",
                 fmt::format("an analysis that needs no rotor ({}), since the model has no "
                             "[[shafts]] or [[nodes]]",
                             rotorless),
                 fmt::format("\"{}\"", a.name));
    if (a.check) a.check(analysis, path, check);
  };
}

/// [[analyses]]: the common keys, then each type's own keys, choices and sub-tables, restricted
/// to that type.
Section analyses_section(const std::vector<AnalysisDeclaration>& analyses) {
  Section s = S("analyses", SectionKind::ArrayOfTables, "[[analyses]]",
                "Analyses run on the model, in order. `type` selects which further keys are "
                "allowed; keys of another type are errors.")
                  .in_array(&Model::analyses)
                  .located(&Analysis::where)
                  .fields(common_analysis_fields(analyses));
  s.discriminator = "type";
  const std::string rotorless = rotorless_types(analyses);
  for (const auto& a : analyses) {
    for (Field f : a.fields) {
      if (!f.only_in.empty())
        throw std::logic_error(
            fmt::format("schema: key '{}' of analysis type '{}' restricts "
                        "itself to other types",
                        f.name, a.name));
      f.only_in = {a.name};
      s.fields.push_back(std::move(f));
    }
    for (Choice c : a.choices) {
      c.only_in = {a.name};
      s.choices.push_back(std::move(c));
    }
    for (Section sub : a.sections) {
      sub.only_in = {a.name};
      s.sections.push_back(std::move(sub));
    }
    Variant v;
    v.name = a.name;
    v.help = a.help;
    if (a.finish) {
      auto fn = a.finish;
      v.finish = [fn](void* object, const TableContext& t) {
        fn(*static_cast<Analysis*>(object), t);
      };
    }
    v.check = variant_check(a, rotorless);
    s.variants.push_back(std::move(v));
  }
  return s;
}

}  // namespace

Section make_model_schema(const std::vector<AnalysisDeclaration>& analyses) {
  Section root =
      S("", SectionKind::Root, "top level", "Keys at the top of the file, before any table.")
          .fields({
              integer("version", "Model-file format version; this geardyn reads version 1.")
                  .required()
                  .ge(1)
                  .le(1)
                  .to(&Model::version),
              text("title", "Title shown in reports.").def("\"\"").to(&Model::title),
              dof_set_key("The DOFs of every node: \"all\" (six per node), or a subset for a "
                          "torsion-only, lateral-only or axial model; a shaft's own `dofs` "
                          "overrides it for that shaft's nodes.")
                  .def("\"all\"")
                  .to_fn<Model>([](Model& m, const FieldValue& v) {
                    m.dofs = static_cast<DofSet>(v.choice);
                  }),
          })
          .sections({materials_section(),
                     shafts_section(),
                     nodes_section(),
                     disks_section(),
                     point_masses_section(),
                     bearings_section(),
                     couplings_section(),
                     gear_meshes_section(),
                     constraints_section(),
                     unbalances_section(),
                     forces_section(),
                     sensors_section(),
                     damping_section(),
                     solids_section(),
                     gear_pairs_section(),
                     contacts_section(),
                     bolts_section(),
                     bushings_section(),
                     rolling_bearings_section(),
                     drivers_section(),
                     loads_section(),
                     clutches_section(),
                     virtual_sensors_section(),
                     nonlinear_elements_section(),
                     analyses_section(analyses)});
  root.object_type = typeid(Model);  // the root has no parent to append it to
  check_schema(root);
  return root;
}

}  // namespace geardyn::model
