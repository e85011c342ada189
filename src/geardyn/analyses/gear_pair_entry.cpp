// The `type = "gear_pair"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/gear_pair.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/scalar_tables.hpp"
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
  type.run = [](const model::Model& m, const Analysis& a, const Context& c) {
    return Outcome{run_gear_pair(m, a.settings_of<GearPairSettings>(), a.name, c.progress()),
                   nullptr};
  };
  return type;
}

}  // namespace geardyn::analyses
