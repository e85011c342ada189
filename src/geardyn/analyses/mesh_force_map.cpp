#include "geardyn/analyses/mesh_force_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>

#include "geardyn/analyses/tooth_contact.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/gear/ltca_table.hpp"
#include "geardyn/gear/ste.hpp"

namespace geardyn::analyses {

namespace {

// The key of the pair that selects its STE source.
std::string source_key(const PairModel& pm) {
  if (pm.ste_from_ltca) return pm.key_path + ".ltca_file";
  if (pm.ste_from_file) return pm.key_path + ".ste_file";
  return pm.key_path + ".ste_source";
}

// Samples of a periodic series moved by `shift` samples: out[i] = v(i + shift), linear.
std::vector<double> periodic_shift(const std::vector<double>& v, double shift) {
  const auto n = static_cast<double>(v.size());
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    double x = std::fmod(static_cast<double>(i) + shift, n);
    if (x < 0.0) x += n;
    const auto k = static_cast<std::size_t>(std::floor(x));
    const double w = x - static_cast<double>(k);
    out[i] = (1.0 - w) * v[k % v.size()] + w * v[(k + 1) % v.size()];
  }
  return out;
}

// The map of STE curves at known forces: e_g from the first (lowest) curve's unloaded TE.
elements::MeshForceMap from_curves(const std::vector<gear::SteCurve>& curves,
                                   const std::vector<double>& forces, double period) {
  elements::MeshForceMap m;
  m.period_rad = period;
  m.unloaded_te_m = curves.front().geometric_te_m();
  m.forces_n = forces;
  for (const auto& c : curves) m.approach_m.push_back(c.ste_m());
  return m;
}

// The LTCA at the torque factors, over all computed cycles (the hunting period with pitch
// deviations), shifted by ste_shift of a mesh cycle.
elements::MeshForceMap ltca_map(const model::Model& model, const PairModel& pm,
                                const MeshForceMapOptions& options) {
  const model::GearPair& p = *pm.pair;
  const auto tc = build_tooth_contact_model(model, pm);
  elements::MeshForceMap m;
  m.mesh_cycles = tc->contact->cycles();
  m.period_rad = units::kTwoPi * m.mesh_cycles / p.teeth1;
  const double shift = p.ste_shift * tc->options.positions;
  for (double factor : options.torque_factors) {
    const double torque = factor * p.torque;
    const gear::ToothContactResult r = tc->contact->solve(torque);
    if (r.status != Status::Ok)
      throw InputError(
          p.where, pm.key_path + ".ste_source",
          "a tooth contact analysis that converges at the force map's torques",
          fmt::format("at T1 = {:.6g} N m ({:.3g} x torque): {}", torque, factor, r.message),
          "check the flank modifications and the misalignment, or use \"iso\"");
    if (m.unloaded_te_m.empty()) m.unloaded_te_m = periodic_shift(r.unloaded_te_m, shift);
    m.forces_n.push_back(torque / pm.base_radius1_m);
    m.approach_m.push_back(periodic_shift(r.te_m, shift));
  }
  m.source = fmt::format("LTCA of '{}' at {} torques", p.name, options.torque_factors.size());
  return m;
}

// The imported LTCA table at its torques and the pair's mounting errors.
elements::MeshForceMap ltca_table_map(const PairModel& pm) {
  const model::GearPair& p = *pm.pair;
  gear::LtcaReadOptions read;
  read.teeth = p.teeth1;
  read.base_radius_m = pm.base_radius1_m;
  const gear::LtcaTable table = gear::LtcaTable::read(pm.ste_path, read);
  const model::ContactModelSpec& c = p.contact;
  std::vector<gear::SteCurve> curves;
  std::vector<double> forces;
  for (double torque : table.axes()[0]) {
    if (!(torque > 0.0)) continue;  // the unloaded row carries no force
    const gear::LtcaPoint point{torque, c.mounting_h, c.mounting_v, c.mounting_j};
    curves.push_back(table.ste(point, pm.base_radius1_m, p.ste_extrapolation, p.ste_shift,
                               static_cast<std::size_t>(std::max(0, p.ste_samples))));
    forces.push_back(torque / pm.base_radius1_m);
  }
  if (curves.empty())
    throw InputError(p.where, pm.key_path + ".ltca_file", "an LTCA table with a torque > 0",
                     "only zero torque");
  elements::MeshForceMap m = from_curves(curves, forces, units::kTwoPi / p.teeth1);
  m.source = fmt::format("LTCA table {} at {} torques", p.ltca_file, forces.size());
  return m;
}

// The STE file at its torques; a single curve (or one without torque) is the pair's STE at
// its force: a linear mesh.
elements::MeshForceMap ste_file_map(const PairModel& pm) {
  const model::GearPair& p = *pm.pair;
  gear::SteReadOptions read;
  read.teeth = p.teeth1;
  read.base_radius_m = pm.base_radius1_m;
  read.shift = p.ste_shift;
  read.samples = static_cast<std::size_t>(std::max(0, p.ste_samples));
  if (!std::isnan(p.ste_speed)) read.mesh_period_s = units::kTwoPi / (p.ste_speed * p.teeth1);
  const gear::SteTable table = gear::read_ste_csv(pm.ste_path, read);
  const double period = units::kTwoPi / p.teeth1;
  elements::MeshForceMap m;
  if (table.curves.size() == 1 || std::isnan(table.curves.front().torque_nm())) {
    m = from_curves({*pm.ste}, {pm.static_force_n}, period);
  } else {
    std::vector<double> forces;
    for (const auto& c : table.curves) forces.push_back(c.torque_nm() / pm.base_radius1_m);
    m = from_curves(table.curves, forces, period);
  }
  m.source = fmt::format("STE file {} at {} torque{}", p.ste_file, m.forces_n.size(),
                         m.forces_n.size() == 1 ? "" : "s");
  return m;
}

// The force of the map closest to the pair's static force: the reference of k(theta).
int reference_index(const std::vector<double>& forces, double static_force) {
  int best = 0;
  for (std::size_t j = 1; j < forces.size(); ++j)
    if (std::abs(forces[j] - static_force) <
        std::abs(forces[static_cast<std::size_t>(best)] - static_force))
      best = static_cast<int>(j);
  return best;
}

}  // namespace

elements::MeshForceMap mesh_force_map(const model::Model& model, const PairModel& pm,
                                      const MeshForceMapOptions& options) {
  const model::GearPair& p = *pm.pair;
  const std::string key = source_key(pm);
  elements::MeshForceMap m;
  try {
    if (pm.ste_from_contact) {
      for (std::size_t j = 0; j < options.torque_factors.size(); ++j)
        if (!(options.torque_factors[j] > (j == 0 ? 0.0 : options.torque_factors[j - 1])))
          throw std::logic_error("mesh_force_map: torque factors not positive and increasing");
      m = ltca_map(model, pm, options);
    } else if (pm.ste_from_ltca) {
      m = ltca_table_map(pm);
    } else if (pm.ste_from_file) {
      m = ste_file_map(pm);
    } else {
      m = from_curves({*pm.ste}, {pm.static_force_n}, units::kTwoPi / p.teeth1);
      m.source = "synthetic ISO 6336 STE";
    }
    m.reference = reference_index(m.forces_n, pm.static_force_n);
    elements::check_mesh_force_map(m, {p.where, pm.key_path});
  } catch (const InputError& e) {
    const SourceLocation at = e.where().line > 0 ? e.where() : p.where;
    throw InputError(at, key, e.expected(), e.found(), e.hint());
  }
  return m;
}

elements::MeshForceMap mesh_force_map(const model::Model& model, std::size_t mesh_index,
                                      const MeshForceMapOptions& options) {
  const model::GearMesh& g = model.gear_meshes.at(mesh_index);
  const std::string key = fmt::format("gear_meshes[{}]", mesh_index);
  if (g.contact && !g.contact->gear_pair.empty()) {
    const PairModel pm = build_pair_model(model, pair_index(model, g.contact->gear_pair));
    return mesh_force_map(model, pm, options);
  }
  if (!(std::isfinite(g.stiffness) && g.stiffness > 0.0))
    throw InputError(g.where, key + ".stiffness",
                     "a mesh stiffness > 0 [N/m] for the tooth contact (or contact.gear_pair)",
                     std::isnan(g.stiffness) ? "nothing" : fmt::format("{:.6g}", g.stiffness),
                     "give stiffness, or name a [[gear_pairs]] entry in [gear_meshes.contact]");
  return elements::MeshForceMap::constant_stiffness(
      g.stiffness, g.teeth1 > 0 ? units::kTwoPi / g.teeth1 : units::kTwoPi);
}

}  // namespace geardyn::analyses
