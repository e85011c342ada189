// The `type = "damper_ring_response"` analysis in the registry: its model-file keys and their
// rules, its checks, how it runs and what it offers to sweeps.
#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/damper_ring_response.hpp"
#include "geardyn/analyses/registry.hpp"
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
  auto& s = a.settings_of<DamperRingResponseSettings>();
  finish_tooth_excitation(s, t);
  if (s.reduction == ReductionMethod::Guyan)
    t.fail("reduction", "\"none\" or \"craig_bampton\" (the receptance sums the sector's modes)",
           "\"guyan\"");
  s.engine_orders = {s.engine_order};
  if (t.has("force_amplitude")) {
    const FieldValue& v = t.at("force_amplitude");
    if (v.is_array && v.count > static_cast<std::size_t>(s.harmonics))
      t.fail("force_amplitude",
             fmt::format("at most {} amplitudes: F_k, F_2k, ... for harmonics 1 .. harmonics",
                         s.harmonics),
             fmt::format("{} amplitudes", v.count), "raise harmonics, or drop amplitudes");
  }
  if (s.time_samples > 0 && s.time_samples < 2 * s.harmonics + 1)
    t.fail("time_samples",
           fmt::format("at least 2 harmonics + 1 = {} samples per period", 2 * s.harmonics + 1),
           std::to_string(s.time_samples));
  const bool sweep = s.sweep != DamperSweep::None;
  if (t.has("performance_values") && !sweep)
    t.fail("performance_values", "a performance_parameter they are values of", "none");
  if (sweep && s.sweep_values.empty())
    t.fail("performance_values", "the values of performance_parameter (at least one)", "none");
  if (sweep && s.sweep != DamperSweep::FrictionCoefficient)
    for (std::size_t i = 0; i < s.sweep_values.size(); ++i)
      if (!(s.sweep_values[i] > 0.0))
        t.fail(fmt::format("performance_values[{}]", i), "factors > 0",
               fmt::format("{}", s.sweep_values[i]));
}

// A damper-ring response is a cyclic forced response whose generated gear sector has its groove
// and ring, on a mesh (the contact pairs are found in it).
void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  check_cyclic_forced_response(a, path, check);
  const auto& d = a.settings_of<DamperRingResponseSettings>();
  const model::Solid& body = *check.model().find_solid(d.solid);
  if (body.source == model::SolidSource::GearSector && !body.gear_sector.groove)
    check.fail(path + ".solid", "a gear sector with groove = true (the damper ring and its groove)",
               fmt::format("\"{}\" without a groove", d.solid));
  if (body.source == model::SolidSource::Reduced || body.source == model::SolidSource::Matrices)
    check.fail(path + ".solid",
               "a mesh solid (generated gear_sector with groove, or a mesh file with the contact "
               "and ring sets): the contact pairs are found in its mesh",
               fmt::format("\"{}\" of type \"{}\"", d.solid,
                           body.source == model::SolidSource::Reduced ? "reduced" : "matrices"));
}

std::vector<model::Field> keys() {
  std::vector<model::Field> fields = cyclic_sector_response_keys();
  std::vector<model::Field> own = {
      integer("engine_order",
              "Engine order k of the tooth force exciting the gear; it excites nodal "
              "diameter h = +-k mod sectors, and harmonic n of the response carries "
              "engine order n k.")
          .required()
          .ge(1)
          .le(100000)
          .to_settings(&DamperRingResponseSettings::engine_order),
      text("gear_contact_set",
           "Node set of the gear's contact face in the groove (its i-th node coincides "
           "with the i-th of ring_contact_set).")
          .def("\"groove_contact\"")
          .to_settings(&DamperRingResponseSettings::gear_contact_set),
      text("ring_contact_set", "Node set of the ring's contact face.")
          .def("\"ring_contact\"")
          .to_settings(&DamperRingResponseSettings::ring_contact_set),
      text("ring_element_set",
           "Element set of the ring (its mass and centre-of-mass radius give the "
           "centrifugal preload).")
          .def("\"ring\"")
          .to_settings(&DamperRingResponseSettings::ring_element_set),
      choice("contact", {"2d", "3d"},
             "Contact model per node pair: \"2d\" normal + one slip direction "
             "(inclined by ring_inclination_deg from the circumferential one), \"3d\" "
             "normal + circumferential and axial slip.")
          .def("\"2d\"")
          .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
            a.settings_of<DamperRingResponseSettings>().contact_directions = v.choice + 1;
          }),
      number("ring_inclination_deg", kDegree,
             "Inclination psi of the 2d contact's slip direction from the "
             "circumferential direction towards the axis.")
          .def("0.0")
          .ge(-90.0)
          .le(90.0)
          .to_settings(&DamperRingResponseSettings::ring_inclination),
      number("normal_stiffness", kStiffness, "Normal contact stiffness k_n per node pair.")
          .ge(0)
          .to_settings(&DamperRingResponseSettings::normal_stiffness),
      number("contact_stiffness", kStiffnessPerArea,
             "Normal contact stiffness per contact area: k_n = this x the contact face "
             "area of a sector / the pairs per sector.")
          .ge(0)
          .to_settings(&DamperRingResponseSettings::contact_stiffness),
      number("tangential_stiffness", kStiffness,
             "Tangential (stick) contact stiffness k_t per node pair.")
          .gt(0)
          .note("Mindlin: k_t = 4 G* / E* k_n, 2 (1 - nu) / (2 - nu) k_n for equal "
                "materials")
          .to_settings(&DamperRingResponseSettings::tangential_stiffness),
      number("friction_coefficient", kNoUnit, "Coulomb friction coefficient mu.")
          .required()
          .ge(0)
          .to_settings(&DamperRingResponseSettings::friction_coefficient),
      integer("harmonics",
              "Harmonics H balanced (1: the fundamental; more resolve the contact "
              "forces' higher harmonics and engine orders n k).")
          .def("1")
          .ge(1)
          .le(50)
          .to_settings(&DamperRingResponseSettings::harmonics),
      integer("time_samples",
              "Time samples per period of the alternating frequency-time evaluation.")
          .ge(3)
          .le(65536)
          .note("(8 + 1) H + 1 rounded up to a power of two, at least 64")
          .to_settings(&DamperRingResponseSettings::time_samples),
      F("hysteresis_pairs", FieldType::NumberArray,
        "Contact pairs (0-based, in the order of the contact sets) whose hysteresis "
        "loops at the resonance are reported.")
          .ge(0)
          .unique()
          .note("three pairs spread over the contact face")
          .to_fn<Analysis>([](Analysis& a, const FieldValue& v) {
            auto& s = a.settings_of<DamperRingResponseSettings>();
            s.hysteresis_pairs.clear();
            for (double n : v.numbers) s.hysteresis_pairs.push_back(static_cast<int>(n));
          }),
      number("max_step", kNoUnit,
             "Largest continuation step, relative to the speed range and the linear "
             "response amplitude.")
          .def("0.02")
          .gt(0)
          .le(0.5)
          .to_settings(&DamperRingResponseSettings::max_step),
      choice("performance_parameter", {"ring_mass", "friction_coefficient", "contact_stiffness"},
             "Damper performance curve: the response is traced again for each of "
             "performance_values of this parameter (ring_mass, contact_stiffness: "
             "factors on the ring's density and on k_n and k_t; friction_coefficient: "
             "values of mu), giving resonance speed, peak and Q against it.")
          .note("no performance curve")
          .to_settings_enum(&DamperRingResponseSettings::sweep,
                            {DamperSweep::RingMass, DamperSweep::FrictionCoefficient,
                             DamperSweep::ContactStiffness}),
      numbers("performance_values", kNoUnit, "Values of performance_parameter, increasing.")
          .ge(0)
          .increasing()
          .min_items(1)
          .to_settings(&DamperRingResponseSettings::sweep_values),
  };
  fields.insert(fields.end(), own.begin(), own.end());
  return fields;
}

}  // namespace

AnalysisType damper_ring_response_analysis() {
  AnalysisType type;
  type.name = "damper_ring_response";
  type.declare = [] {
    auto d = declaration<DamperRingResponseSettings>(
        "damper_ring_response",
        "Friction-damped response over speed of a cyclic gear "
        "with a damper ring in a groove (harmonic balance on the "
        "ring's contacts): damped, free and stuck responses, Q "
        "and resonance shift, energy, stick / slip / lift-off, "
        "hysteresis loops, optional performance curve.");
    d.fields = keys();
    d.choices = {speed_range_choice(true),
                 {{{"pair"}, {"force_amplitude"}}, true, {}},
                 {{{"damping_ratio"}, {"q_factor"}}, true, {}},
                 {{{"normal_stiffness"}, {"contact_stiffness"}}, true, {}}};
    d.finish = finish;
    d.check = check;
    return d;
  };
  type.check_inputs = [](const model::Model& m, const Analysis& a, const InputContext& c) {
    const auto& s = a.settings_of<DamperRingResponseSettings>();
    check_cyclic_forced_response_inputs(m, s, c);
    if (c.solids() == nullptr) return;
    const auto it = c.solids()->find(s.solid);
    if (it != c.solids()->end()) check_damper_ring_response(it->second, s, c);
  };
  type.run = runner(run_damper_ring_response, damper_ring_response_output);
  type.scalars = {
      {"peak_amplitude",
       "m",
       "Friction-damped peak amplitude (harmonic 1) at `sensor` over the speed range.",
       {"sensor"}},
      {"peak_location", "rpm", "Speed of that peak.", {"sensor"}},
      {"amplitude_vs_free",
       "",
       "Friction-damped peak amplitude at `sensor` over the peak of the gear without ring (< 1: "
       "the ring reduces it).",
       {"sensor"}}};
  type.scalar = [](const Outcome& o, const ScalarRequest& q, std::string& unit) -> double {
    const auto& r = result_of<DamperRingResponseResult>(o);
    const std::size_t k = r.sensor_index(q.sensor);
    const response::SpeedPeak& damped = r.damped_peaks.at(k);
    if (q.quantity == "peak_amplitude") {
      unit = std::string("m");
      return damped.amplitude;
    }
    if (q.quantity == "peak_location") {
      unit = std::string("rpm");
      return units::rad_per_s_to_rpm(damped.speed);
    }
    if (q.quantity == "amplitude_vs_free") {
      unit.clear();
      return damped.amplitude / r.free_peaks.at(k).amplitude;
    }
    throw std::logic_error(fmt::format("damper_ring_response offers no scalar {}", q.quantity));
  };
  return type;
}

}  // namespace geardyn::analyses
