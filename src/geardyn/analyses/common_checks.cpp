#include "geardyn/analyses/common_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/analyses/cyclic_forced_response.hpp"

namespace geardyn::analyses {

void check_gear_pair_use(const model::Analysis& a, const std::string& path,
                         const model::ModelCheck& check, const GearPairUse& use) {
  const model::Model& m = check.model();
  if (m.gear_pairs.empty())
    check.fail(path + ".type", "an analysis whose gear pair exists in the model",
               fmt::format("\"{}\", but the model has no [[gear_pairs]]", a.type));
  const std::set<std::string> pairs = model::names_of(m.gear_pairs);
  const model::GearPair* gp = nullptr;
  std::size_t index = 0;
  if (!use.pair->empty()) {
    check.check_name(path + ".pair", *use.pair, pairs, "gear pair", "gear_pairs");
    gp = m.find_gear_pair(*use.pair);
    index = static_cast<std::size_t>(gp - m.gear_pairs.data());
  } else if (m.gear_pairs.size() == 1) {
    gp = &m.gear_pairs.front();
  } else if (!use.empty_allowed) {
    check.fail(
        path + ".pair",
        fmt::format("the name of the gear pair analysed (the model has {})",
                    model::quoted_list(std::vector<std::string>(pairs.begin(), pairs.end()))),
        "nothing");
  }
  if (gp != nullptr && use.dynamic) {
    for (const char* key : {"inertia1", "inertia2"}) {
      const double inertia = key[7] == '1' ? gp->inertia1 : gp->inertia2;
      if (std::isnan(inertia))
        check.fail(fmt::format("gear_pairs[{}].{}", index, key),
                   fmt::format("the polar inertia of gear {} [kg m^2] (needed by analysis '{}' "
                               "with model = \"dynamic\")",
                               key[7], a.name),
                   "nothing", "give it, or use model = \"infinite_inertia\"");
    }
  }
  if (gp != nullptr && use.nodal_diameters != nullptr) {
    const int teeth = use.gear == 1 ? gp->teeth1 : gp->teeth2;
    const auto& nds = *use.nodal_diameters;
    for (std::size_t k = 0; k < nds.size(); ++k)
      if (nds[k] > teeth / 2)
        check.fail(fmt::format("{}.nodal_diameters[{}]", path, k),
                   fmt::format("a nodal diameter in 0 .. N / 2 = {} (gear {} has {} teeth)",
                               teeth / 2, use.gear, teeth),
                   std::to_string(nds[k]));
  }
}

const model::Solid& check_solid_use(const std::string& path, const std::string& solid,
                                    const model::ModelCheck& check, bool cyclic,
                                    const std::vector<int>& nodal_diameters) {
  check.check_name(path + ".solid", solid, model::names_of(check.model().solids), "solid",
                   "solids");
  const model::Solid& body = *check.model().find_solid(solid);
  if (!cyclic) return body;
  if (body.sectors < 2)
    check.fail(path + ".solid", "a solid with sectors >= 2 (one sector of a cyclic body)",
               fmt::format("\"{}\" with sectors = {}", solid, body.sectors));
  for (std::size_t k = 0; k < nodal_diameters.size(); ++k)
    if (nodal_diameters[k] > body.sectors / 2)
      check.fail(fmt::format("{}.nodal_diameters[{}]", path, k),
                 fmt::format("a nodal diameter in 0 .. sectors / 2 = {}", body.sectors / 2),
                 std::to_string(nodal_diameters[k]));
  return body;
}

void check_cyclic_forced_response(const model::Analysis& a, const std::string& path,
                                  const model::ModelCheck& check) {
  const auto& c = a.settings_of<CyclicForcedResponseSettings>();
  if (!c.pair.empty()) {
    GearPairUse use;
    use.pair = &c.pair;
    use.dynamic = c.model == MeshForceModel::Dynamic;
    check_gear_pair_use(a, path, check, use);
  }
  const model::Solid& body = check_solid_use(path, c.solid, check, true, c.nodal_diameters);
  const int n = body.sectors;
  for (std::size_t j = 0; j < c.engine_orders.size(); ++j) {
    const int r = c.engine_orders[j] % n;
    const int h = std::min(r, n - r);
    if (!c.nodal_diameters.empty() &&
        std::find(c.nodal_diameters.begin(), c.nodal_diameters.end(), h) == c.nodal_diameters.end())
      check.fail(fmt::format("{}.engine_orders[{}]", path, j),
                 fmt::format("an order k = +-h (mod sectors = {}) of a listed nodal diameter h", n),
                 fmt::format("{} (nodal diameter {})", c.engine_orders[j], h),
                 "add that nodal diameter to nodal_diameters, or drop the order");
  }
  if (!c.pair.empty()) {
    const model::GearPair& gp = *check.model().find_gear_pair(c.pair);
    const int teeth = c.gear == 1 ? gp.teeth1 : gp.teeth2;
    if (teeth != n)
      check.fail(path + ".solid",
                 fmt::format("a cyclic solid with one tooth per sector, sectors = {} (the teeth "
                             "of gear {} of pair '{}'): the tooth force of tooth j acts on "
                             "sector j",
                             teeth, c.gear, c.pair),
                 fmt::format("\"{}\" with sectors = {}", c.solid, n),
                 "mesh one tooth per sector, or give force_amplitude for a load repeated once "
                 "per sector");
    if (body.source == model::SolidSource::GearSector && body.gear_sector.teeth != teeth)
      check.fail(path + ".solid",
                 fmt::format("a gear sector with the {} teeth of gear {} of pair '{}'", teeth,
                             c.gear, c.pair),
                 fmt::format("teeth = {}", body.gear_sector.teeth));
  }
}

void check_master_sets(const Context& context, const std::string& solid_name,
                       const std::vector<std::string>& sets) {
  if (context.solids() == nullptr) return;
  auto it = context.solids()->find(solid_name);
  if (it == context.solids()->end()) return;
  if (!it->second.has_mesh() && !sets.empty())
    throw context.error("master_sets[0]",
                        fmt::format("no master sets (solid '{}' is of type \"{}\" and has no "
                                    "node sets)",
                                    solid_name, it->second.kind()),
                        fmt::format("\"{}\"", sets[0]));
  const solid::Mesh& mesh = it->second.mesh;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    if (mesh.node_sets.count(sets[k])) continue;
    std::string available;
    for (const auto& [set_name, nodes] : mesh.node_sets)
      available += (available.empty() ? "" : ", ") + fmt::format("\"{}\"", set_name);
    throw context.error(fmt::format("master_sets[{}]", k),
                        fmt::format("a node set of solid '{}' ({})", solid_name, available),
                        fmt::format("\"{}\"", sets[k]));
  }
}

void check_mesh_excitation(const std::string& path, const model::ModelCheck& check,
                           const std::string& type, const std::string& gear_mesh,
                           const std::string& pair, const std::vector<std::string>& sensors) {
  const model::Model& m = check.model();
  if (m.gear_meshes.empty())
    check.fail(path + ".type", "an analysis whose gear mesh exists in the model",
               fmt::format("\"{}\", but the model has no [[gear_meshes]]", type));
  const model::GearMesh* mesh = &m.gear_meshes.front();
  if (!gear_mesh.empty()) {
    check.check_name(path + ".gear_mesh", gear_mesh, model::names_of(m.gear_meshes), "gear mesh",
                     "gear_meshes");
    for (const auto& gm : m.gear_meshes)
      if (gm.name == gear_mesh) mesh = &gm;
  } else if (m.gear_meshes.size() > 1) {
    check.fail(path + ".gear_mesh", "the name of the gear mesh excited (the model has several)",
               "nothing");
  }
  if (mesh->teeth1 <= 0)
    check.fail(path + ".gear_mesh",
               fmt::format("a gear mesh with teeth1 (mesh '{}' has none, so its mesh frequency "
                           "is unknown)",
                           mesh->name),
               "teeth1 = 0");
  if (!pair.empty()) {
    const model::GearPair& gp = *m.find_gear_pair(pair);
    if (gp.teeth1 != mesh->teeth1 || (mesh->teeth2 > 0 && gp.teeth2 != mesh->teeth2))
      check.fail(path + ".pair",
                 fmt::format("a gear pair with the teeth of gear mesh '{}' ({} / {})", mesh->name,
                             mesh->teeth1, mesh->teeth2),
                 fmt::format("'{}' with {} / {} teeth", gp.name, gp.teeth1, gp.teeth2));
  }
  check.check_named(path + ".sensors", sensors, model::names_of(m.sensors), "sensor", "sensors");
  if (m.sensors.empty())
    check.fail(path + ".type", "an analysis whose response points exist in the model",
               fmt::format("\"{}\", but the model has no [[sensors]]", type));
}

}  // namespace geardyn::analyses
