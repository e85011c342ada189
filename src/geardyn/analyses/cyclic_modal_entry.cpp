// The `type = "cyclic_modal"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include <fmt/format.h>

#include <stdexcept>

#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/cyclic_modal.hpp"
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
  auto& c = a.settings_of<CyclicModalSettings>();
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

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  const auto& c = a.settings_of<CyclicModalSettings>();
  (void)check_solid_use(path, c.solid, check, true, c.nodal_diameters);
}

double scalar(const Outcome& o, const ScalarRequest& q, std::string& unit) {
  const auto& r = result_of<CyclicModalResult>(o);
  if (q.quantity != "natural_frequency")
    throw std::runtime_error(fmt::format("cyclic_modal offers no scalar \'{}\'", q.quantity));
  unit = std::string("Hz");
  if (q.mode < 1 || static_cast<std::size_t>(q.mode) > r.frequency_hz.size())
    throw std::runtime_error(
        fmt::format("natural_frequency: mode {} of {} computed over all nodal diameters", q.mode,
                    r.frequency_hz.size()));
  return r.frequency_hz[static_cast<std::size_t>(q.mode - 1)];
}

std::vector<model::Field> keys() {
  return {
      speed_list_key().read_by_finish<model::Analysis>(),
      speed_start_rpm_key().read_by_finish<model::Analysis>(),
      speed_stop_rpm_key().read_by_finish<model::Analysis>(),
      speed_count_key().read_by_finish<model::Analysis>(),
      n_modes_key().to_settings(&CyclicModalSettings::n_modes),
      solid_key().to_settings(&CyclicModalSettings::solid),
      shapes_key().to_settings(&CyclicModalSettings::shapes),
      F("nodal_diameters", FieldType::NumberArray, "Nodal diameters solved.")
          .ge(0)
          .increasing()
          .note("0 .. sectors / 2")
          .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
            auto& c = a.settings_of<CyclicModalSettings>();
            c.nodal_diameters.clear();
            for (double h : v.numbers) c.nodal_diameters.push_back(static_cast<int>(h));
          }),
      reduction_key().to_settings_fn<CyclicModalSettings>([](auto& s, const FieldValue& v) {
        s.reduction = v.given ? reduction_method(v) : ReductionMethod::None;
      }),
      reduced_modes_key().to_settings(&CyclicModalSettings::cb_modes),
      master_sets_key().to_settings(&CyclicModalSettings::master_sets),
      integer("interface_modes",
              "Interface modes per nodal diameter replacing the sector-interface DOFs "
              "(Tran's method; 0: interfaces kept, else >= 6).")
          .def("0")
          .ge(0)
          .le(100000)
          .to_settings(&CyclicModalSettings::interface_modes),
      boolean("compare_full", "Also solve the replicated 360 deg mesh and compare.")
          .def("false")
          .to_settings(&CyclicModalSettings::compare_full),
      integer("max_engine_order",
              "Highest engine order in the Campbell diagram (0: 2 x "
              "sectors).")
          .def("0")
          .ge(0)
          .le(100000)
          .to_settings(&CyclicModalSettings::max_engine_order),
  };
}

}  // namespace

AnalysisType cyclic_modal_analysis() {
  AnalysisType type;
  type.name = "cyclic_modal";
  type.declare = [] {
    auto d =
        declaration<CyclicModalSettings>("cyclic_modal",
                                         "Modes per nodal diameter of a cyclic solid from one "
                                         "sector, optionally reduced, with full-wheel shapes and "
                                         "the rotating-frame Campbell diagram.");
    d.fields = keys();
    d.choices = {speed_range_choice(false)};
    d.finish = finish;
    d.check = check;
    return d;
  };
  type.check_inputs = [](const model::Model&, const Analysis& a, const InputContext& c) {
    const auto& s = a.settings_of<CyclicModalSettings>();
    check_master_sets(c, s.solid, s.master_sets);
  };
  type.run = runner(run_cyclic_modal, cyclic_modal_output);
  type.scalars = {{"natural_frequency",
                   "Hz",
                   "Natural frequency of mode `mode` counted over all nodal diameters solved, in "
                   "ascending order of frequency (a double mode of a nodal diameter counts once).",
                   {"mode"}}};
  type.scalar = scalar;
  return type;
}

}  // namespace geardyn::analyses
