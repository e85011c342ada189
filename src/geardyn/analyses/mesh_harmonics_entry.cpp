// The `type = "mesh_harmonics"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include <fmt/format.h>

#include <stdexcept>

#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/mesh_harmonics.hpp"
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
  const auto& h = a.settings_of<MeshHarmonicsSettings>();
  GearPairUse use;
  use.pair = &h.pair;
  use.dynamic = h.model == MeshForceModel::Dynamic;
  use.gear = h.gear;
  use.nodal_diameters = &h.nodal_diameters;
  check_gear_pair_use(a, path, check, use);
}

double scalar(const Outcome& o, const ScalarRequest& q, std::string& unit) {
  const auto& r = result_of<MeshHarmonicsResult>(o);
  if (q.quantity == "harmonic_amplitude") {
    unit = std::string("N");
    if (q.mode < 1 || q.mode > r.max_order)
      throw std::runtime_error(fmt::format(
          "harmonic_amplitude: engine order mode = {} is outside the order spectrum 1 .. {} "
          "(max_order)",
          q.mode, r.max_order));
    return r.order_amplitude_n[static_cast<std::size_t>(q.mode)];
  }
  if (q.quantity == "dynamic_factor") {
    unit.clear();
    return r.revolution.mesh.dynamic_factor;
  }
  throw std::runtime_error(fmt::format("mesh_harmonics offers no scalar \'{}\'", q.quantity));
}

std::vector<model::Field> keys() {
  return {
      gear_pair_name_key().to_settings(&MeshHarmonicsSettings::pair),
      mesh_model_key().to_settings_enum(&MeshHarmonicsSettings::model,
                                        {MeshForceModel::Dynamic, MeshForceModel::InfiniteInertia}),
      contact_loss_key().to_settings(&MeshHarmonicsSettings::contact_loss),
      number("speed_rpm", kRpm, "Speed of gear 1.")
          .required()
          .gt(0)
          .to_settings(&MeshHarmonicsSettings::speed),
      gear_key().to_settings(&MeshHarmonicsSettings::gear),
      window_shift_key().to_settings(&MeshHarmonicsSettings::window_shift),
      contact_ratio_key().to_settings(&MeshHarmonicsSettings::contact_ratio),
      nodal_diameters_key().to_settings_fn<MeshHarmonicsSettings>(
          [](auto& s, const FieldValue& v) { s.nodal_diameters = integers_of(v); }),
      orders_per_diameter_key().to_settings(&MeshHarmonicsSettings::orders_per_diameter),
      integer("max_order", "Highest order of the order-spectrum table (0: 2 N).")
          .def("0")
          .ge(0)
          .le(100000)
          .to_settings(&MeshHarmonicsSettings::max_order),
  };
}

}  // namespace

AnalysisType mesh_harmonics_analysis() {
  AnalysisType type;
  type.name = "mesh_harmonics";
  type.declare = [] {
    auto d =
        declaration<MeshHarmonicsSettings>("mesh_harmonics",
                                           "Engine-order harmonics of the tooth force of one gear "
                                           "at one speed: tooth-load window, order spectrum, "
                                           "harmonics per nodal diameter in 3D components.");
    d.fields = keys();
    d.check = check;
    return d;
  };
  type.check_inputs = [](const model::Model& m, const Analysis& a, const InputContext& c) {
    check_mesh_harmonics_inputs(m, a.settings_of<MeshHarmonicsSettings>(), c);
  };
  type.run = runner(run_mesh_harmonics, mesh_harmonics_output);
  type.scalars = {
      {"harmonic_amplitude",
       "N",
       "Tangential amplitude (one-sided) of engine order `mode` (the harmonic number, per "
       "revolution of the loaded gear) of the tooth force, as in the order spectrum.",
       {"mode"}},
      {"dynamic_factor",
       "",
       "Dynamic factor F_max / F_s of the mesh force, the largest over the speeds computed.",
       {}},
  };
  type.scalar = scalar;
  return type;
}

}  // namespace geardyn::analyses
