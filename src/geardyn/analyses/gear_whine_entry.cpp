// The `type = "gear_whine"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/forced_helpers.hpp"
#include "geardyn/analyses/gear_whine.hpp"
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

constexpr model::Unit kSpeedOfSound{"m/s", 1.0};
constexpr model::Unit kAcceleration{"m/s^2", 1.0};

void finish(Analysis& a, const TableContext& t) {
  auto& s = a.settings_of<GearWhineSettings>();
  s.speeds = positive_speed_range(t, "the mesh frequency must be positive");
  for (const char* key : {"radiating_set", "radiation_efficiency", "radiator_radius", "distance",
                          "directivity", "map_speeds_rpm", "air_density", "speed_of_sound"})
    if (t.has(key) && !t.has("radiating_solid"))
      t.fail(key, "a radiating_solid whose surface radiates", "no radiating_solid");
}

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  const auto& g = a.settings_of<GearWhineSettings>();
  GearPairUse use;
  use.pair = &g.pair;
  check_gear_pair_use(a, path, check, use);
  check_mesh_excitation(path, check, "gear_whine", g.gear_mesh, g.pair, g.sensors);
}

std::vector<model::Field> radiation_keys() {
  return {
      reference("radiating_solid", Ref::Solid,
                "The housing whose surface radiates: a [[solids]] entry with a mesh joined to "
                "the rotor by spiders. Its ERP, sound power and sound pressure level are "
                "computed.")
          .note("no radiation")
          .to_settings(&GearWhineSettings::radiating_solid),
      text("radiating_set",
           "Node set of the radiating solid's mesh: the exterior element faces whose nodes all "
           "lie in it radiate.")
          .note("the whole exterior surface")
          .to_settings(&GearWhineSettings::radiating_set),
      number("radiation_efficiency", kNoUnit,
             "Radiation efficiency sigma applied to the ERP (1: the ERP upper bound).")
          .def("1.0")
          .gt(0)
          .le(10)
          .to_settings(&GearWhineSettings::radiation_efficiency),
      number("air_density", kDensity, "Density of the air.")
          .def("1.2041")
          .gt(0)
          .to_settings(&GearWhineSettings::air_density),
      number("speed_of_sound", kSpeedOfSound, "Speed of sound in the air.")
          .def("343.4")
          .gt(0)
          .to_settings(&GearWhineSettings::speed_of_sound),
      number("radiator_radius", kMetre,
             "Radius R of the 0-order spherical radiator (corner frequency c / (2 pi R)).")
          .note("the radius of a sphere with the surface's area")
          .gt(0)
          .to_settings(&GearWhineSettings::radiator_radius),
      number("distance", kMetre, "Distance of the sound pressure level from the source.")
          .def("1.0")
          .gt(0)
          .to_settings(&GearWhineSettings::distance),
      number("directivity", kNoUnit,
             "Directivity factor Q of the sound pressure level (1 free field, 2 over a "
             "reflecting plane).")
          .def("1.0")
          .gt(0)
          .to_settings(&GearWhineSettings::directivity),
      numbers("map_speeds_rpm", kRpm,
              "Speeds of the per-face ERP maps (VTU and report), the nearest computed speed.")
          .note("the speed of the largest ERP")
          .ge(0)
          .to_settings(&GearWhineSettings::map_speeds),
  };
}

std::vector<model::Field> keys() {
  std::vector<model::Field> k = {
      speed_list_key().read_by_finish<model::Analysis>(),
      speed_start_rpm_key().read_by_finish<model::Analysis>(),
      speed_stop_rpm_key().read_by_finish<model::Analysis>(),
      speed_count_key().read_by_finish<model::Analysis>(),
      n_modes_key().to_settings(&GearWhineSettings::n_modes),
      sensors_key().to_settings(&GearWhineSettings::sensors),
      reference("pair", Ref::GearPair,
                "The [[gear_pairs]] entry whose transmission error excites the mesh (STE file, "
                "LTCA table or its loaded tooth contact analysis): the blocked mesh force "
                "k_mean e_p at each mesh order p.")
          .required()
          .to_settings(&GearWhineSettings::pair),
      excited_gear_mesh_key().to_settings(&GearWhineSettings::gear_mesh),
      max_mesh_order_key().to_settings(&GearWhineSettings::max_mesh_order),
      residual_vectors_key().to_settings(&GearWhineSettings::residual_vectors),
      number("acceleration_reference", kAcceleration,
             "0 dB of the acceleration levels (ISO 1683: 1e-6 m/s^2).")
          .def("1e-6")
          .gt(0)
          .to_settings(&GearWhineSettings::acceleration_reference),
  };
  for (model::Field& f : radiation_keys()) k.push_back(std::move(f));
  return k;
}

double curve_at(const GearWhineResult& r, const Eigen::VectorXd& curve, const ScalarRequest& q) {
  const Eigen::VectorXd& w = r.response.speeds;
  return value_at(std::vector<double>(w.data(), w.data() + w.size()),
                  std::vector<double>(curve.data(), curve.data() + curve.size()), q.at,
                  60.0 / units::kTwoPi, "rpm");
}

double whine_scalar(const Outcome& o, const ScalarRequest& q, std::string& unit) {
  const auto& r = result_of<GearWhineResult>(o);
  if (q.quantity == "acceleration_at" || q.quantity == "peak_acceleration") {
    const std::size_t k = r.sensor_index(q.sensor);
    const Eigen::VectorXd a = r.acceleration_rms.col(static_cast<Eigen::Index>(k));
    unit = r.response.sensors[k].rotational ? "rad/s^2" : "m/s^2";
    if (q.quantity == "peak_acceleration") return a.maxCoeff();
    return curve_at(r, a, q);
  }
  if (!r.has_radiation)
    throw std::runtime_error("the analysis has no radiating_solid (no sound power)");
  unit = "dB";
  if (q.quantity == "sound_power_level_at") return curve_at(r, r.sound_power_level_db(), q);
  if (q.quantity == "peak_sound_power_level") return r.sound_power_level_db().maxCoeff();
  throw std::logic_error("gear_whine: unknown scalar " + q.quantity);
}

}  // namespace

AnalysisType gear_whine_analysis() {
  AnalysisType type;
  type.name = "gear_whine";
  type.declare = [] {
    auto d = declaration<GearWhineSettings>(
        "gear_whine",
        "Gear whine over speed: the transmission error of a gear pair at each mesh order "
        "excites the rotor with its reduced housing; acceleration at the sensors per order "
        "and summed, and the housing's radiated power (ERP, 0-order radiator) and sound "
        "pressure level.");
    d.fields = keys();
    d.choices = {speed_range_choice(true)};
    d.finish = finish;
    d.check = check;
    d.needs_rotor = true;
    return d;
  };
  type.check_inputs = [](const model::Model& m, const Analysis& a, const InputContext& c) {
    check_gear_whine_inputs(m, a.settings_of<GearWhineSettings>(), c);
  };
  type.run = runner(run_gear_whine, gear_whine_output);
  type.scalars = {
      {"acceleration_at",
       "",
       "RMS acceleration over the mesh orders at `sensor` at speed `at_rpm` (linear "
       "interpolation).",
       {"sensor", "at_rpm"}},
      {"peak_acceleration", "", "Largest RMS acceleration over speed at `sensor`.", {"sensor"}},
      {"sound_power_level_at",
       "dB",
       "Sound power level of the ERP summed over orders at speed `at_rpm` [dB re 1e-12 W].",
       {"at_rpm"}},
      {"peak_sound_power_level", "dB", "Largest sound power level over speed.", {}}};
  type.scalar = whine_scalar;
  return type;
}

}  // namespace geardyn::analyses
