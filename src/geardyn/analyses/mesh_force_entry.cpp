// The `type = "mesh_force"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/mesh_force.hpp"
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
  auto& s = a.settings_of<MeshForceSettings>();
  s.speeds = positive_speed_range(t, "the mesh frequency must be positive");
  if (s.force_amplitude > 0.0 && s.model == MeshForceModel::InfiniteInertia)
    t.fail("force_amplitude_n",
           "0 with model = \"infinite_inertia\" (the external force needs the dynamic model)",
           fmt::format("{} N", s.force_amplitude));
  if (s.detail_speeds.size() > 8)
    t.fail("detail_rpm", "at most 8 speeds for time histories",
           fmt::format("{} speeds", s.detail_speeds.size()));
}

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  const auto& f = a.settings_of<MeshForceSettings>();
  GearPairUse use;
  use.pair = &f.pair;
  use.dynamic = f.model == MeshForceModel::Dynamic;
  check_gear_pair_use(a, path, check, use);
}

/// The largest value of `field` over the converged points of both sweeps (runtime_error: none).
double largest(const MeshForceResult& r, const std::string& quantity,
               double (*field)(const gear::MeshSweepPoint&)) {
  double best = -std::numeric_limits<double>::infinity();
  for (const auto* points : {&r.sweep.up, &r.sweep.down})
    for (const gear::MeshSweepPoint& q : *points)
      if (q.status == Status::Ok) best = std::max(best, field(q));
  if (!std::isfinite(best))
    throw std::runtime_error(
        fmt::format("{}: no speed of the sweep reached a periodic steady state", quantity));
  return best;
}

double scalar(const Outcome& o, const ScalarRequest& q, std::string& unit) {
  const auto& r = result_of<MeshForceResult>(o);
  if (q.quantity == "dynamic_factor") {
    unit.clear();
    return largest(r, q.quantity, [](const gear::MeshSweepPoint& p) { return p.dynamic_factor; });
  }
  if (q.quantity == "peak_mesh_force") {
    unit = std::string("N");
    return largest(r, q.quantity, [](const gear::MeshSweepPoint& p) { return p.force_max_n; });
  }
  if (q.quantity == "mesh_resonance_speed") {
    unit = std::string(
        "rpm");  // the speed of gear 1 at which the mesh frequency meets f_n (NaN: no dynamics)
    return 60.0 * r.natural_frequency_hz / r.pair.pair->teeth1;
  }
  throw std::runtime_error(fmt::format("mesh_force offers no scalar \'{}\'", q.quantity));
}

std::vector<model::Field> keys() {
  return {
      speed_list_key().to_settings(&MeshForceSettings::speeds),
      speed_start_rpm_key().read_by_finish<model::Analysis>(),
      speed_stop_rpm_key().read_by_finish<model::Analysis>(),
      speed_count_key().read_by_finish<model::Analysis>(),
      gear_pair_name_key().to_settings(&MeshForceSettings::pair),
      choice("direction", {"up", "down", "both"},
             "Sweep direction; each speed starts from the previous steady state, so "
             "\"both\" shows the jump and hysteresis of contact loss.")
          .def("\"both\"")
          .to_settings_enum(
              &MeshForceSettings::direction,
              {SweepDirectionKind::Up, SweepDirectionKind::Down, SweepDirectionKind::Both}),
      mesh_model_key().to_settings_enum(&MeshForceSettings::model,
                                        {MeshForceModel::Dynamic, MeshForceModel::InfiniteInertia}),
      contact_loss_key().to_settings(&MeshForceSettings::contact_loss),
      numbers("detail_rpm", kRpm,
              "Speeds of gear 1 at which time histories over one period are written "
              "(at most 8; computed on their own from the static state).")
          .gt(0)
          .def("[]")
          .to_settings(&MeshForceSettings::detail_speeds),
      choice("damping_on", {"dte", "elastic_deflection"},
             "What the mesh damper c = 2 zeta sqrt(k_mean m_e) acts on: \"dte\", c x' on the "
             "dynamic transmission error, in and out of contact; \"elastic_deflection\", "
             "c (x' - e_g') on the elastic deflection of the teeth x - e_g (e_g the unloaded TE "
             "of the STE) as in the models of Kahraman & Singh (1990) and Ozguven & Houser "
             "(1988), here acting in contact only (no damping while the teeth are apart, where "
             "those models keep it). The two agree "
             "while the teeth stay in contact and e_g is constant (the synthetic STE).")
          .def("\"dte\"")
          .to_settings_enum(&MeshForceSettings::damping_on,
                            {MeshDampingKind::Dte, MeshDampingKind::ElasticDeflection}),
      number("force_amplitude_n", kNewton,
             "Amplitude F_a of an external harmonic force on the mesh coordinate, added to the "
             "static force: F(t) = F_s + F_a cos(2 pi force_order f_m t + force_phase_deg), t = 0 "
             "when a tooth pair enters contact (dynamic model only; 0: none).")
          .ge(0)
          .def("0")
          .to_settings(&MeshForceSettings::force_amplitude),
      integer("force_order",
              "Frequency of the external force in orders of the mesh frequency (1: f_m). Whole "
              "orders only: with a fractional order the force, and the response, would not repeat "
              "over a mesh period, so the steady state periodic in the mesh period that the "
              "analysis computes would not exist.")
          .ge(1)
          .le(1000)
          .def("1")
          .to_settings(&MeshForceSettings::force_order),
      number("force_phase_deg", kDegree,
             "Phase of the external force at the start of a mesh cycle (see force_amplitude_n).")
          .def("0")
          .to_settings(&MeshForceSettings::force_phase),
  };
}

}  // namespace

AnalysisType mesh_force_analysis() {
  AnalysisType type;
  type.name = "mesh_force";
  type.declare = [] {
    auto d =
        declaration<MeshForceSettings>("mesh_force",
                                       "Dynamic mesh force over a speed range of gear 1: "
                                       "dynamic factor, DTE and contact loss versus speed, the "
                                       "mesh resonance, time histories.");
    d.fields = keys();
    d.choices = {speed_range_choice(true)};
    d.finish = finish;
    d.check = check;
    return d;
  };
  type.check_inputs = [](const model::Model& m, const Analysis& a, const InputContext& c) {
    check_mesh_force_inputs(m, a.settings_of<MeshForceSettings>(), c);
  };
  type.run = runner(run_mesh_force, mesh_force_output);
  type.scalars = {
      {"dynamic_factor",
       "",
       "Dynamic factor F_max / F_s of the mesh force, the largest over the speeds computed.",
       {}},
      {"peak_mesh_force",
       "N",
       "Largest dynamic mesh force F_max over the speeds computed (both sweep directions).",
       {}},
      {"mesh_resonance_speed",
       "rpm",
       "Speed of gear 1 at which the mesh frequency meets the mesh natural frequency "
       "sqrt(k_mean / m_e) / 2 pi (NaN for model = \"infinite_inertia\").",
       {}},
  };
  type.scalar = scalar;
  return type;
}

}  // namespace geardyn::analyses
