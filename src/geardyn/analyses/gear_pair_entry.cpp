// The `type = "gear_pair"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/gear_pair.hpp"
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

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  GearPairUse use;
  use.pair = &a.settings_of<GearPairSettings>().pair;
  use.empty_allowed = true;
  check_gear_pair_use(a, path, check, use);
}

/// The pair a scalar request reads: `mode` counts the pairs analysed (1 for a single pair).
const PairModel& requested_pair(const GearPairResult& r, const ScalarRequest& q) {
  if (q.mode < 1 || static_cast<std::size_t>(q.mode) > r.pairs.size())
    throw std::runtime_error(
        fmt::format("{}: mode = {} asks for gear pair {}, but the analysis has {} pair{}",
                    q.quantity, q.mode, q.mode, r.pairs.size(), r.pairs.size() == 1 ? "" : "s"));
  return r.pairs[static_cast<std::size_t>(q.mode - 1)];
}

double scalar(const Outcome& o, const ScalarRequest& q, std::string& unit) {
  const PairModel& pm = requested_pair(result_of<GearPairResult>(o), q);
  if (q.quantity == "contact_ratio") {
    unit.clear();
    return pm.geometry.total_contact_ratio;
  }
  if (q.quantity == "mesh_stiffness") {
    unit = std::string("N/m");
    return mean_mesh_stiffness(pm);
  }
  if (q.quantity == "mesh_natural_frequency") {
    unit = std::string("Hz");
    const double fn = mesh_natural_frequency_hz(pm);
    if (std::isnan(fn))
      throw std::runtime_error(fmt::format(
          "mesh_natural_frequency: gear pair '{}' has no inertia1 and inertia2 (the mesh's "
          "equivalent mass needs both)",
          pm.pair->name));
    return fn;
  }
  throw std::runtime_error(fmt::format("gear_pair offers no scalar \'{}\'", q.quantity));
}

std::vector<model::Field> keys() {
  return {
      gear_pair_name_key().to_settings(&GearPairSettings::pair),
  };
}

}  // namespace

AnalysisType gear_pair_analysis() {
  AnalysisType type;
  type.name = "gear_pair";
  type.declare = [] {
    auto d =
        declaration<GearPairSettings>("gear_pair",
                                      "Gear-pair geometry, tooth forces (drive and coast), ISO "
                                      "6336 stiffness and the mesh stiffness / STE over one "
                                      "mesh cycle.");
    d.fields = keys();
    d.check = check;
    return d;
  };
  type.run = runner(run_gear_pair, gear_pair_output);
  type.scalars = {
      {"contact_ratio",
       "",
       "Total contact ratio eps_gamma = eps_alpha + eps_beta of gear pair `mode` (counted among "
       "the pairs analysed; 1 for a single pair).",
       {"mode"}},
      {"mesh_stiffness",
       "N/m",
       "Mean mesh stiffness k_mean = F_s x (mean over the mesh cycle of 1 / (STE - geometric TE)) "
       "of gear pair `mode`.",
       {"mode"}},
      {"mesh_natural_frequency",
       "Hz",
       "Natural frequency of the mesh sqrt(k_mean / m_e) / 2 pi of gear pair `mode` (needs both "
       "inertias).",
       {"mode"}},
  };
  type.scalar = scalar;
  return type;
}

}  // namespace geardyn::analyses
