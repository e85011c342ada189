// The `type = "campbell"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include <algorithm>
#include <cmath>
#include <limits>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/rotor_scalars.hpp"
#include "geardyn/core/units.hpp"
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
  a.settings_of<CampbellSettings>().speeds = speed_range(t);
}

std::vector<model::Field> keys() {
  return {
      speed_list_key().to_settings(&CampbellSettings::speeds),
      speed_start_rpm_key().read_by_finish<model::Analysis>(),
      speed_stop_rpm_key().read_by_finish<model::Analysis>(),
      speed_count_key().read_by_finish<model::Analysis>(),
      n_modes_key().to_settings(&CampbellSettings::n_modes),
      method_key().to_settings_enum(&CampbellSettings::method,
                                    {EigenMethod::Auto, EigenMethod::Dense, EigenMethod::Sparse}),
      numbers("engine_orders", kNoUnit,
              "Excitation orders of the reference speed drawn as lines; critical speeds "
              "are where modes cross them.")
          .def("[1.0]")
          .gt(0)
          .to_settings(&CampbellSettings::engine_orders),
      boolean("shaft_orders", "Add order 1 of every shaft (its speed ratio).")
          .def("true")
          .to_settings(&CampbellSettings::shaft_orders),
      boolean("mesh_orders", "Add the mesh order (teeth x shaft order) of every mesh with teeth.")
          .def("true")
          .to_settings(&CampbellSettings::mesh_orders),
      number("mac_threshold", kNoUnit,
             "Mode tracking between speeds: MAC below this flags an ambiguous step.")
          .def("0.7")
          .ge(0)
          .le(1)
          .to_settings(&CampbellSettings::mac_threshold),
      point_threads_key().to_settings(&CampbellSettings::threads),
  };
}

constexpr double kRpmPerRadS = 60.0 / units::kTwoPi;

double scalar(const Outcome& o, const ScalarRequest& q, std::string& unit) {
  const CampbellResult& r = result_of<CampbellResult>(o);
  if (q.quantity == "natural_frequency") {
    unit = "Hz";
    return nth_mode(r.tracks, q.mode).front().frequency_hz;
  }
  if (q.quantity == "critical_speed") {
    unit = "rpm";
    std::vector<double> speeds;
    for (const auto& c : r.critical_speeds) speeds.push_back(c.speed * kRpmPerRadS);
    std::sort(speeds.begin(), speeds.end());
    const auto row = static_cast<std::size_t>(q.mode - 1);
    // None in range: NaN, not an error.
    return row < speeds.size() ? speeds[row] : std::numeric_limits<double>::quiet_NaN();
  }
  if (q.quantity == "min_damping_ratio") {
    unit.clear();
    double lowest = std::numeric_limits<double>::quiet_NaN();
    for (const auto& p : nth_mode(r.tracks, q.mode))
      if (std::isfinite(p.damping_ratio) && !(p.damping_ratio >= lowest)) lowest = p.damping_ratio;
    return lowest;
  }
  if (q.quantity == "instability_onset_speed") {
    unit = "rpm";
    return instability_onset_speed(r) * kRpmPerRadS;
  }
  unknown_scalar("campbell", q.quantity);
}

}  // namespace

AnalysisType campbell_analysis() {
  AnalysisType type;
  type.name = "campbell";
  type.declare = [] {
    auto d =
        declaration<CampbellSettings>("campbell",
                                      "Eigenvalues versus speed with forward / backward whirl, "
                                      "order lines and critical speeds.");
    d.fields = keys();
    d.choices = {speed_range_choice(true)};
    d.finish = finish;
    d.needs_rotor = true;
    return d;
  };
  type.run = runner(run_campbell, campbell_output);
  type.scalars = {
      {"natural_frequency",
       "Hz",
       "Undamped natural frequency of mode `mode` at the first speed.",
       {"mode"}},
      {"critical_speed",
       "rpm",
       "The `mode`-th lowest critical speed (any tracked mode on any engine-order line; NaN "
       "when fewer are in range).",
       {"mode"}},
      {"min_damping_ratio",
       "",
       "Smallest damping ratio of tracked mode `mode` over the speeds.",
       {"mode"}},
      {"instability_onset_speed",
       "rpm",
       "Lowest speed at which a tracked mode's damping ratio turns negative (NaN: stable "
       "throughout).",
       {}}};
  type.scalar = scalar;
  return type;
}

}  // namespace geardyn::analyses
