// The `type = "reduction"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include <fmt/format.h>

#include <stdexcept>

#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/reduction.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/model/schema_builder.hpp"

namespace geardyn::analyses {
namespace {

using namespace model::keys;  // NOLINT: the declaration table reads as a table
using model::Analysis;
using model::FieldType;
using model::FieldValue;
using model::Ref;
using model::TableContext;

void finish(Analysis& a, const TableContext& t) {
  auto& r = a.settings_of<ReductionSettings>();
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

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  (void)check_solid_use(path, a.settings_of<ReductionSettings>().solid, check, false);
}

double scalar(const Outcome& o, const ScalarRequest& q, std::string& unit) {
  const auto& r = result_of<ReductionResult>(o);
  if (q.quantity == "max_frequency_error") {
    unit = std::string("%");
    return r.max_error_pct;
  }
  if (q.quantity == "reduced_dofs") {
    unit.clear();
    return static_cast<double>(r.reduced->size());
  }
  throw std::runtime_error(fmt::format("reduction offers no scalar \'{}\'", q.quantity));
}

std::vector<model::Field> keys() {
  return {
      n_modes_key().to_settings(&ReductionSettings::compare_modes),
      solid_key().to_settings(&ReductionSettings::solid),
      reduction_key().to_settings_fn<ReductionSettings>(
          [](auto& s, const FieldValue& v) { s.method = reduction_method(v); }),
      reduced_modes_key().to_settings(&ReductionSettings::n_modes),
      number("reduced_f_max_hz", kHertz,
             "Keep every fixed-interface mode up to this frequency instead of a count.")
          .gt(0)
          .note("reduced_modes modes")
          .to_settings(&ReductionSettings::f_max),
      master_sets_key().to_settings(&ReductionSettings::master_sets),
      numbers("convergence", kNoUnit, "Numbers of fixed-interface modes of the convergence table.")
          .ge(0)
          .increasing()
          .note("automatic")
          .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
            auto& r = a.settings_of<ReductionSettings>();
            r.convergence.clear();
            for (double n : v.numbers) r.convergence.push_back(static_cast<int>(n));
          }),
      boolean("save", "Write the reduced component as <analysis>.h5.")
          .def("true")
          .to_settings(&ReductionSettings::save),
  };
}

}  // namespace

AnalysisType reduction_analysis() {
  AnalysisType type;
  type.name = "reduction";
  type.declare = [] {
    auto d =
        declaration<ReductionSettings>("reduction",
                                       "Craig-Bampton or Guyan reduction of a solid: reduced vs "
                                       "full frequencies, convergence, reduced component file.");
    d.fields = keys();
    d.finish = finish;
    d.check = check;
    return d;
  };
  type.check_inputs = [](const model::Model&, const Analysis& a, const InputContext& c) {
    const auto& s = a.settings_of<ReductionSettings>();
    check_master_sets(c, s.solid, s.master_sets);
  };
  type.run = runner(run_reduction, reduction_output);
  type.scalars = {
      {"max_frequency_error",
       "%",
       "Largest relative frequency error 100 |f_reduced - f_full| / f_full over the full-model "
       "modes compared (n_modes).",
       {}},
      {"reduced_dofs",
       "",
       "Number of coordinates of the reduced model (master DOFs + fixed-interface modes).",
       {}},
  };
  type.scalar = scalar;
  return type;
}

}  // namespace geardyn::analyses
