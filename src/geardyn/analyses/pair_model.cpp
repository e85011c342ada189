#include "geardyn/analyses/pair_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/tooth_contact.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/gear/ltca_table.hpp"

namespace geardyn::analyses {

namespace fs = std::filesystem;

namespace {

constexpr double kSteelModulusPa = 206e9;  // ISO 6336-1 E_st: the default material
constexpr int kSyntheticSamples = 512;

// The gear library names the fields of GearPairSpec / IsoStiffnessOptions; the model file uses
// its own key names. Errors are re-thrown with the model's key so the user can find the line.
const std::map<std::string, std::string, std::less<>>& library_to_model_keys() {
  static const std::map<std::string, std::string, std::less<>> keys = {
      {"teeth_pinion", "teeth1"},
      {"teeth_wheel", "teeth2"},
      {"module", "module"},
      {"pressure_angle", "pressure_angle_deg"},
      {"helix_angle", "helix_angle_deg"},
      {"pinion_spiral_angle", "pinion_spiral_angle_deg"},
      {"face_width", "face_width"},
      {"addendum_coefficient", "addendum_coefficient"},
      {"dedendum_coefficient", "dedendum_coefficient"},
      {"profile_shift_pinion", "profile_shift1"},
      {"profile_shift_wheel", "profile_shift2"},
      {"centre_distance", "centre_distance"},
      {"shaft_angle", "shaft_angle_deg"},
      {"outer_cone_distance", "outer_cone_distance"},
      {"mesh", "internal"},
      {"correction_factor", "stiffness_correction"},
      {"application_factor", "application_factor"},
      {"rim_thickness", "rim_thickness"},
      {"web_thickness", "web_thickness"},
      {"youngs_modulus_pinion", "material1"},
      {"youngs_modulus_wheel", "material2"},
      {"pinion_torque", "torque"},
      {"tangential_force", "torque"},
      {"samples", "ste_samples"},
  };
  return keys;
}

[[noreturn]] void rethrow_with_model_keys(const InputError& e, const std::string& key_path,
                                          const SourceLocation& where) {
  std::string key = e.key_path();
  const std::string prefix = key_path + ".";
  if (key.rfind(prefix, 0) == 0) {
    const std::string field = key.substr(prefix.size());
    auto it = library_to_model_keys().find(field);
    if (field.empty())
      key = key_path;  // a property of the whole pair (e.g. its contact ratio)
    else if (it != library_to_model_keys().end())
      key = prefix + it->second;
  }
  // The table's location unless the library knew better (a CSV file's line and column).
  const SourceLocation at = e.where().line > 0 ? e.where() : where;
  throw InputError(at, key, e.expected(), e.found(), e.hint());
}

gear::GearType gear_type(model::GearType t) {
  switch (t) {
    case model::GearType::Spur:
      return gear::GearType::Spur;
    case model::GearType::Helical:
      return gear::GearType::Helical;
    case model::GearType::StraightBevel:
      return gear::GearType::StraightBevel;
    case model::GearType::SpiralBevel:
      return gear::GearType::SpiralBevel;
    case model::GearType::Hypoid:
      return gear::GearType::Hypoid;
  }
  return gear::GearType::Spur;
}

gear::GearPairSpec spec_of(const model::GearPair& p, const std::string& key_path) {
  gear::GearPairSpec s;
  s.name = p.name;
  s.key_path = key_path;
  s.where = p.where;
  s.type = gear_type(p.type);
  s.mesh = p.internal ? gear::MeshType::Internal : gear::MeshType::External;
  s.teeth_pinion = p.teeth1;
  s.teeth_wheel = p.teeth2;
  s.module_m = p.module;
  s.pressure_angle_rad = p.pressure_angle;
  s.helix_angle_rad = p.helix_angle;
  s.pinion_spiral_angle_rad = p.pinion_spiral_angle;
  s.face_width_m = p.face_width;
  s.addendum_coefficient = p.addendum_coefficient;
  s.dedendum_coefficient = p.dedendum_coefficient;
  s.profile_shift_pinion = p.profile_shift1;
  s.profile_shift_wheel = p.profile_shift2;
  s.centre_distance_m = p.centre_distance;
  if (!std::isnan(p.shaft_angle)) s.shaft_angle_rad = p.shaft_angle;
  s.outer_cone_distance_m = p.outer_cone_distance;
  return s;
}

double modulus_of(const model::Model& m, const std::string& material) {
  if (material.empty()) return kSteelModulusPa;
  const model::Material* mat = m.find_material(material);
  if (mat == nullptr) throw std::logic_error("gear-pair material not resolved: " + material);
  return mat->youngs_modulus;
}

}  // namespace

namespace {

// The STE of an imported LTCA table (ltca_file) at the pair's torque and mounting errors. The
// table's own errors keep their file location; a point outside the table is reported at the model
// key that put it there (torque, contact.mounting_h/v/j).
gear::SteCurve ltca_ste(const model::Model& model, const PairModel& pm) {
  const model::GearPair& p = *pm.pair;
  const fs::path path = resolve_model_path(model, p.ltca_file);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw InputError(p.where, pm.key_path + ".ltca_file",
                     "a readable LTCA table CSV file (relative to the model file)",
                     fmt::format("\"{}\" ({} does not exist)", p.ltca_file, path.string()));
  const model::ContactModelSpec& c = p.contact;
  const SourceLocation contact_at = c.where.line > 0 ? c.where : p.where;
  if (c.shaft_angle_error != 0.0)
    throw InputError(contact_at, pm.key_path + ".contact.shaft_angle_error_deg",
                     "0 with an ltca_file (the table has no shaft-angle-error axis)",
                     fmt::format("{} deg", c.shaft_angle_error * 180.0 / units::kPi),
                     "export the table at the shaft angle error, or remove the key");
  gear::LtcaReadOptions read;
  read.teeth = p.teeth1;
  read.base_radius_m = pm.base_radius1_m;
  const gear::LtcaTable table = gear::LtcaTable::read(path, read);
  const gear::LtcaPoint point{p.torque, c.mounting_h, c.mounting_v, c.mounting_j};
  try {
    return table.ste(point, pm.base_radius1_m, p.ste_extrapolation, p.ste_shift,
                     static_cast<std::size_t>(std::max(0, p.ste_samples)),
                     p.ste_interpolation == model::SteInterpolationKind::Hold
                         ? gear::SteInterpolation::Hold
                         : gear::SteInterpolation::Linear);
  } catch (const InputError& e) {
    static const std::map<std::string, std::string, std::less<>> keys = {
        {"torque", "torque"},
        {"h", "contact.mounting_h"},
        {"v", "contact.mounting_v"},
        {"j", "contact.mounting_j"}};
    const auto it = keys.find(e.key_path());
    const bool contact = it != keys.end() && it->first != "torque";
    throw InputError(contact ? contact_at : p.where,
                     pm.key_path + "." + (it != keys.end() ? it->second : std::string("ltca_file")),
                     fmt::format("{} (LTCA table {})", e.expected(), p.ltca_file), e.found(),
                     e.hint().empty()
                         ? "set ste_extrapolation = true to extrapolate, or add that point to the "
                           "table"
                         : e.hint());
  }
}

}  // namespace

fs::path resolve_model_path(const model::Model& model, const std::string& file) {
  const fs::path p(file);
  if (p.is_absolute() || model.source_file.empty()) return p;
  return fs::path(model.source_file).parent_path() / p;
}

std::size_t pair_index(const model::Model& model, const std::string& name) {
  if (name.empty()) {
    if (model.gear_pairs.size() != 1)
      throw std::logic_error("gearan: no pair named and the model has not exactly one");
    return 0;
  }
  for (std::size_t i = 0; i < model.gear_pairs.size(); ++i)
    if (model.gear_pairs[i].name == name) return i;
  throw std::logic_error("gearan: gear pair not resolved by the parser: " + name);
}

std::string PairModel::ste_source_label() const {
  if (ste_from_file) return "file " + pair->ste_file;
  if (ste_from_ltca) return "LTCA table " + pair->ltca_file;
  if (ste_from_contact) return "loaded tooth contact analysis";
  return "synthetic, ISO 6336";
}

double PairModel::equivalent_mass_kg() const {
  for (const auto& [key, inertia] :
       {std::pair{"inertia1", pair->inertia1}, std::pair{"inertia2", pair->inertia2}})
    if (std::isnan(inertia))
      throw InputError(pair->where, fmt::format("{}.{}", key_path, key),
                       "the polar inertia of the gear for the dynamic mesh model", "nothing",
                       "give it, or use model = \"infinite_inertia\"");
  try {
    return gear::equivalent_mass(pair->inertia1, pair->inertia2, base_radius1_m, base_radius2_m);
  } catch (const InputError& e) {
    throw InputError(pair->where, key_path + ".inertia1", e.expected(), e.found(), e.hint());
  }
}

gear::DynamicMeshOptions PairModel::mesh_options(MeshForceModel model, bool contact_loss) const {
  gear::DynamicMeshOptions o;
  o.model = model == MeshForceModel::Dynamic ? gear::MeshModel::Dynamic
                                             : gear::MeshModel::InfiniteInertia;
  if (o.model == gear::MeshModel::Dynamic) o.equivalent_mass_kg = equivalent_mass_kg();
  o.static_force_n = static_force_n;
  o.damping_ratio = pair->mesh_damping_ratio;
  o.contact_loss = contact_loss;
  if (!std::isnan(pair->backlash)) o.backlash_m = pair->backlash;
  return o;
}

PairModel build_pair_model(const model::Model& model, std::size_t index) {
  const model::GearPair& p = model.gear_pairs.at(index);
  PairModel pm;
  pm.pair = &p;
  pm.index = index;
  pm.key_path = fmt::format("gear_pairs[{}]", index);
  try {
    pm.geometry = gear::gear_pair_geometry(spec_of(p, pm.key_path));

    const gear::SpiralHand hand =
        p.hand == model::Hand::Right ? gear::SpiralHand::Right : gear::SpiralHand::Left;
    const gear::Rotation rotation = p.rotation == model::GearRotation::Clockwise
                                        ? gear::Rotation::Clockwise
                                        : gear::Rotation::CounterClockwise;
    pm.drive = {"drive", p.torque, gear::MemberRole::Driving, hand, rotation};
    pm.coast = {"coast", p.torque, gear::MemberRole::Driven, hand, rotation};
    pm.drive_forces = gear::tooth_forces(pm.geometry, pm.drive);
    pm.coast_forces = gear::tooth_forces(pm.geometry, pm.coast);

    gear::IsoStiffnessOptions& iso = pm.iso_options;
    iso.correction_factor = p.stiffness_correction;
    iso.rim_thickness_m = p.rim_thickness;
    iso.web_thickness_m = p.web_thickness;
    iso.application_factor = p.application_factor;
    iso.tangential_force_n = p.load_correction ? pm.drive_forces.pinion.tangential_n
                                               : std::numeric_limits<double>::quiet_NaN();
    iso.youngs_modulus_pinion_pa = modulus_of(model, p.material1);
    iso.youngs_modulus_wheel_pa = modulus_of(model, p.material2);

    gear::MeshStiffnessOptions stiffness_options;
    stiffness_options.iso = iso;
    stiffness_options.samples = p.ste_samples > 0 ? p.ste_samples : kSyntheticSamples;
    pm.stiffness = gear::time_varying_mesh_stiffness(pm.geometry, stiffness_options);
    const gear::SyntheticSte synthetic = gear::synthetic_ste(pm.stiffness, pm.geometry, p.torque);

    // r_b,i = r_m,i cos(alpha_t): the radius synthetic_ste uses for gear 1, and its counterpart.
    const double cos_alpha_t = std::cos(pm.geometry.transverse_pressure_angle_rad);
    pm.base_radius1_m = synthetic.base_radius_m;
    pm.base_radius2_m = pm.geometry.wheel.mean_pitch_radius_m * cos_alpha_t;
    pm.static_force_n = synthetic.static_force_n;

    if (!p.ltca_file.empty()) {
      pm.ste = ltca_ste(model, pm);
      pm.ste_from_ltca = true;
      pm.ste_path = resolve_model_path(model, p.ltca_file);
    } else if (p.ste_file.empty() && p.ste_source == model::SteSourceKind::ToothContact) {
      pm.ste = contact_ste(model, pm);
      pm.ste_from_contact = true;
    } else if (p.ste_file.empty()) {
      pm.ste = gear::SteCurve::from_samples(synthetic.ste_m, gear::SteInterpolation::Linear, {},
                                            p.torque)
                   .shifted(p.ste_shift);
    } else {
      pm.ste_from_file = true;
      pm.ste_path = resolve_model_path(model, p.ste_file);
      std::error_code ec;
      if (!fs::is_regular_file(pm.ste_path, ec))
        throw InputError(
            p.where, pm.key_path + ".ste_file",
            "a readable STE CSV file (relative to the model file)",
            fmt::format("\"{}\" ({} does not exist)", p.ste_file, pm.ste_path.string()));
      gear::SteReadOptions read;
      read.teeth = p.teeth1;
      read.base_radius_m = pm.base_radius1_m;
      read.shift = p.ste_shift;
      read.samples = static_cast<std::size_t>(p.ste_samples);
      if (!std::isnan(p.ste_speed)) read.mesh_period_s = units::kTwoPi / (p.ste_speed * p.teeth1);
      read.interpolation = p.ste_interpolation == model::SteInterpolationKind::Hold
                               ? gear::SteInterpolation::Hold
                               : gear::SteInterpolation::Linear;
      const gear::SteTable table = gear::read_ste_csv(pm.ste_path, read);
      try {
        pm.ste = table.at_torque(p.torque, p.ste_extrapolation);
      } catch (const InputError& e) {
        throw InputError(
            p.where, pm.key_path + ".torque",
            fmt::format("{} (STE file {})", e.expected(), p.ste_file), e.found(),
            e.hint().empty() ? "set ste_extrapolation = true to extrapolate" : e.hint());
      }
    }
  } catch (const InputError& e) {
    rethrow_with_model_keys(e, pm.key_path, p.where);
  }
  return pm;
}

void check_gear_pairs(const model::Model& model) {
  for (std::size_t i = 0; i < model.gear_pairs.size(); ++i) (void)build_pair_model(model, i);
}

}  // namespace geardyn::analyses
