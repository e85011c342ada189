#include "geardyn/assembly/solid_component.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "geardyn/assembly/imported_matrices.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/io/sha256.hpp"
#include "geardyn/meshgen/annular_plate.hpp"
#include "geardyn/meshgen/gear_sector.hpp"
#include "geardyn/meshio/gmsh_reader.hpp"
#include "geardyn/meshio/matrix_market.hpp"
#include "geardyn/meshio/nastran_reader.hpp"
#include "geardyn/reduce/reduced_component_io.hpp"

namespace geardyn::assembly {

namespace fs = std::filesystem;

std::vector<solid::DofInfo> SolidComponent::dofs() const {
  return reduced ? reduced->reduced_dofs() : system.dofs;
}

Eigen::SparseMatrix<double> SolidComponent::stiffness() const {
  return reduced ? Eigen::SparseMatrix<double>(reduced->K.sparseView()) : system.K;
}

Eigen::SparseMatrix<double> SolidComponent::mass() const {
  return reduced ? Eigen::SparseMatrix<double>(reduced->M.sparseView()) : system.M;
}

std::string SolidComponent::kind() const {
  return is_reduced() ? "reduced" : external_matrices ? "matrices" : "mesh";
}

solid::Material solid_material(const model::Material& m) {
  solid::Material out;
  out.name = m.name;
  out.E = m.youngs_modulus;
  out.nu = m.youngs_modulus / (2.0 * m.shear_modulus) - 1.0;
  out.rho = m.density;
  out.where = m.where;
  return out;
}

namespace {

std::string key_of(const model::Model& model, const model::Solid& s, const char* key) {
  for (std::size_t i = 0; i < model.solids.size(); ++i)
    if (&model.solids[i] == &s) return fmt::format("solids[{}].{}", i, key);
  return fmt::format("solids.{}", key);
}

fs::path resolve(const model::Model& model, const std::string& file) {
  const fs::path p(file);
  if (p.is_absolute() || model.source_file.empty()) return p;
  return fs::path(model.source_file).parent_path() / p;
}

const model::Material& material_of(const model::Model& model, const std::string& name) {
  const model::Material* m = model.find_material(name);
  if (m == nullptr) throw std::logic_error("solid material not resolved by the parser: " + name);
  return *m;
}

solid::Mesh generate_plate(const model::Model& model, const model::Solid& s, Progress& progress) {
  const auto& spec = s.annular_plate;
  meshgen::AnnularPlateParams p;
  p.inner_radius = spec.inner_radius;
  p.outer_radius = spec.outer_radius;
  p.thickness = spec.thickness;
  p.sector_angle = units::kTwoPi / s.sectors;
  p.element_order = spec.order;
  p.elements_radial = spec.radial_elements;
  if (spec.circumferential_elements > 0) {
    p.elements_circumferential = spec.circumferential_elements;
  } else {
    // About square elements at the outer radius.
    const double radial_size = (spec.outer_radius - spec.inner_radius) / spec.radial_elements;
    p.elements_circumferential = std::max(
        1, static_cast<int>(std::ceil(p.sector_angle * spec.outer_radius / radial_size - 1e-9)));
  }
  p.elements_through_thickness = spec.layers;
  p.material = solid_material(material_of(model, s.material));
  p.key_path = key_of(model, s, "").substr(0, key_of(model, s, "").size() - 1);
  p.where = s.where;
  return meshgen::annular_plate(p, progress);
}

solid::Mesh generate_gear(const model::Model& model, const model::Solid& s, Progress& progress) {
  const auto& g = s.gear_sector;
  meshgen::GearSectorParams p;
  p.num_sectors = s.sectors;
  p.num_teeth = g.teeth;
  p.bore_radius = g.bore_radius;
  p.hub_outer_radius = g.hub_radius;
  p.hub_width = g.hub_width;
  p.hub_offset = g.hub_offset;
  p.web_thickness = g.web_thickness;
  p.web_offset = g.web_offset;
  p.rim_inner_radius = g.rim_inner_radius;
  p.face_width = g.face_width;
  p.tooth.profile = meshgen::ToothProfile::Module;
  p.tooth.module = g.module;
  p.tooth.pressure_angle = g.pressure_angle;
  if (g.groove) {
    meshgen::GrooveParams groove;
    groove.axial_position = g.groove_position;
    groove.width = g.groove_width;
    groove.depth = g.groove_depth;
    groove.ring.width = std::isnan(g.ring_width) ? g.groove_width : g.ring_width;
    groove.ring.axial_position = g.groove_position;
    groove.ring.radial_thickness = g.ring_thickness;
    p.groove = groove;
    p.ring_material = solid_material(material_of(model, s.ring_material));
  }
  p.mesh.global = g.element_size;
  p.mesh.tooth = std::isnan(g.tooth_element_size) ? g.element_size : g.tooth_element_size;
  p.mesh.groove = std::isnan(g.groove_element_size) ? p.mesh.tooth : g.groove_element_size;
  p.mesh.element_order = g.order;
  p.gear_material = solid_material(material_of(model, s.material));
  const std::string base = key_of(model, s, "");
  p.key_path = base.substr(0, base.size() - 1);
  p.where = s.where;
  return meshgen::gear_sector(p, progress);
}

/// Text that identifies generator input, hashed as the component's source.
std::string generator_text(const model::Solid& s) {
  const auto& p = s.annular_plate;
  const auto& g = s.gear_sector;
  if (s.source == model::SolidSource::AnnularPlate)
    return fmt::format("annular_plate {} {} {} {} {} {} {} sectors {}", p.inner_radius,
                       p.outer_radius, p.thickness, p.radial_elements, p.circumferential_elements,
                       p.layers, p.order, s.sectors);
  return fmt::format(
             "gear_sector z {} m {} a {} b {} bore {} hub {} {} {} web {} {} rim {} groove {} {} "
             "{} {} "
             "ring {} {} size {} {} order {} sectors {}",
             g.teeth, g.module, g.pressure_angle, g.face_width, g.bore_radius, g.hub_radius,
             g.hub_width, g.hub_offset, g.web_thickness, g.web_offset, g.rim_inner_radius, g.groove,
             g.groove_position, g.groove_width, g.groove_depth, g.ring_width, g.ring_thickness,
             g.element_size, g.tooth_element_size, g.order, s.sectors) +
         (std::isnan(g.groove_element_size)
              ? std::string()
              : fmt::format(" groove_size {}", g.groove_element_size));
}

}  // namespace

SolidComponent build_solid(const model::Model& model, const model::Solid& s, Progress& progress) {
  SolidComponent c;
  c.name = s.name;
  c.sectors = s.sectors;
  c.interface_tolerance = s.interface_tolerance;

  if (s.source == model::SolidSource::Reduced) {
    const fs::path path = resolve(model, s.reduced);
    if (!fs::exists(path))
      throw InputError(s.where, key_of(model, s, "reduced_file"),
                       "an existing reduced-component file",
                       fmt::format("'{}' (no such file)", path.string()));
    c.reduced = reduce::load_reduced(path.string());
    c.source_sha256 = io::sha256_file(path);
    c.description =
        fmt::format("reduced component {}: {} masters + {} modal coordinates ({}, from {} DOFs)",
                    path.filename().string(), c.reduced->n_masters(), c.reduced->n_modal,
                    c.reduced->provenance.method, c.reduced->n_full());
    return c;
  }

  if (s.source == model::SolidSource::Matrices) {
    const fs::path path_k = resolve(model, s.stiffness_file);
    const fs::path path_m = resolve(model, s.mass_file);
    const fs::path path_map = resolve(model, s.dof_map_file);
    for (const auto& [path, key] :
         {std::pair{path_k, "stiffness_file"}, std::pair{path_m, "mass_file"},
          std::pair{path_map, "dof_map_file"}})
      if (!fs::exists(path))
        throw InputError(s.where, key_of(model, s, key), "an existing file",
                         fmt::format("'{}' (no such file)", path.string()));
    meshio::ExternalMatrices m = meshio::read_matrix_market_component(path_k, path_m, path_map);
    check_imported_matrices(m.K, m.M, s.where, key_of(model, s, "stiffness_file"), path_k.string(),
                            key_of(model, s, "mass_file"), path_m.string());
    c.external_matrices = true;
    c.system.dofs = std::move(m.dofs);
    c.system.K = std::move(m.K);
    c.system.M = std::move(m.M);
    c.source_sha256 = io::sha256_hex(io::sha256_file(path_k) + io::sha256_file(path_m) +
                                     io::sha256_file(path_map));
    int generalised = 0;
    std::set<long> nodes;
    for (const auto& d : c.system.dofs) {
      if (d.component < 0)
        ++generalised;
      else
        nodes.insert(d.node_id);
    }
    c.description = fmt::format(
        "external matrices {} / {}: {} DOFs ({} nodes, {} generalised coordinates), {} and {} "
        "non-zeros{}",
        path_k.filename().string(), path_m.filename().string(), c.system.num_dofs(), nodes.size(),
        generalised, c.system.K.nonZeros(), c.system.M.nonZeros(),
        c.sectors > 1 ? fmt::format(" (one sector of {})", c.sectors) : "");
    return c;
  }

  std::string source;
  switch (s.source) {
    case model::SolidSource::MeshFile: {
      const fs::path path = resolve(model, s.mesh);
      if (!fs::exists(path))
        throw InputError(s.where, key_of(model, s, "file"), "an existing mesh file",
                         fmt::format("'{}' (no such file)", path.string()));
      std::string ext = path.extension().string();
      for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      if (ext == ".msh") {
        meshio::GmshReadOptions options;
        options.default_material = solid_material(material_of(model, s.material));
        c.mesh = meshio::read_gmsh(path, options);
      } else if (ext == ".bdf" || ext == ".dat" || ext == ".nas" || ext == ".blk" ||
                 ext == ".bulk") {
        meshio::NastranOptions options;
        options.unsupported_is_error = s.unsupported_cards_are_errors;
        meshio::NastranDeck deck = meshio::read_nastran(path, options);
        c.mesh = std::move(deck.mesh);
        c.warnings = std::move(deck.warnings);
        for (const auto& u : deck.unsupported)
          c.warnings.push_back(fmt::format("{}:{}: unsupported Nastran entry {} skipped{}", u.file,
                                           u.line, u.name,
                                           u.reason.empty() ? "" : " (" + u.reason + ")"));
      } else {
        throw InputError(s.where, key_of(model, s, "file"),
                         "a Gmsh mesh (.msh) or Nastran bulk data (.bdf, .dat, .nas, .blk)",
                         fmt::format("'{}'", path.filename().string()));
      }
      if (c.mesh.elements.empty() && c.mesh.springs.empty() && c.mesh.point_masses.empty())
        throw InputError(
            s.where, key_of(model, s, "file"),
            "a mesh with at least one element, spring or mass geardyn reads",
            fmt::format("'{}' with {} nodes and none of them{}", path.filename().string(),
                        c.mesh.num_nodes(),
                        c.warnings.empty() ? std::string()
                                           : fmt::format(" ({} entries skipped, the first: {})",
                                                         c.warnings.size(), c.warnings.front())));
      c.source_sha256 = io::sha256_file(path);
      source = path.filename().string();
      break;
    }
    case model::SolidSource::AnnularPlate:
      c.mesh = generate_plate(model, s, progress);
      c.source_sha256 = io::sha256_hex(generator_text(s));
      source = "generated annular plate";
      break;
    case model::SolidSource::GearSector:
      c.mesh = generate_gear(model, s, progress);
      c.source_sha256 = io::sha256_hex(generator_text(s));
      source = "generated gear sector";
      break;
    case model::SolidSource::Reduced:
    case model::SolidSource::Matrices:
      break;
  }

  for (std::size_t k = 0; k < s.fixed_sets.size(); ++k) {
    const SourceLocation where = s.where;
    if (!c.mesh.node_sets.count(s.fixed_sets[k])) {
      std::string available;
      for (const auto& [set_name, set_nodes] : c.mesh.node_sets)
        available += (available.empty() ? "" : ", ") + fmt::format("\"{}\"", set_name);
      throw InputError(where, fmt::format("{}[{}]", key_of(model, s, "fixed_sets"), k),
                       fmt::format("a node set of the mesh ({})", available),
                       fmt::format("\"{}\"", s.fixed_sets[k]));
    }
    const std::vector<int>& nodes = c.mesh.node_sets.at(s.fixed_sets[k]);
    for (int n : nodes) {
      solid::Constraint fix;
      fix.node = n;
      fix.components = {true, true, true, true, true, true};
      fix.where = where;
      c.mesh.constraints.push_back(fix);
    }
  }

  solid::AssemblyOptions options;
  options.threads = 0;
  options.progress = &progress;
  c.system = solid::assemble(c.mesh, options);
  c.description = fmt::format("{}: {} nodes, {} elements, {} DOFs{}", source, c.mesh.num_nodes(),
                              c.mesh.num_elements(), c.system.num_dofs(),
                              c.sectors > 1 ? fmt::format(" (one sector of {})", c.sectors) : "");
  return c;
}

void check_solid_sets(const model::Model& model, const SolidComponents& solids) {
  // Node sets of the joints to the rotor ([[solids.spiders]], solid sensors).
  auto check_set = [&](const std::string& solid_name, const std::string& set,
                       const SourceLocation& where, const std::string& key) {
    auto it = solids.find(solid_name);
    if (it == solids.end()) return;
    if (!it->second.has_mesh())
      throw InputError(where, key,
                       fmt::format("a solid with a mesh (solid '{}' is of type \"{}\" and has "
                                   "no node sets)",
                                   solid_name, it->second.kind()),
                       fmt::format("node set \"{}\"", set));
    const solid::Mesh& mesh = it->second.mesh;
    if (mesh.node_sets.count(set)) return;
    std::string available;
    for (const auto& [set_name, nodes] : mesh.node_sets)
      available += (available.empty() ? "" : ", ") + fmt::format("\"{}\"", set_name);
    throw InputError(where, key,
                     fmt::format("a node set of solid '{}' ({})", solid_name, available),
                     fmt::format("\"{}\"", set));
  };
  for (std::size_t i = 0; i < model.solids.size(); ++i)
    for (std::size_t k = 0; k < model.solids[i].spiders.size(); ++k)
      check_set(model.solids[i].name, model.solids[i].spiders[k].node_set,
                model.solids[i].spiders[k].where,
                fmt::format("solids[{}].spiders[{}].node_set", i, k));
  for (std::size_t j = 0; j < model.sensors.size(); ++j)
    if (!model.sensors[j].solid.empty())
      check_set(model.sensors[j].solid, model.sensors[j].node_set, model.sensors[j].where,
                fmt::format("sensors[{}].node_set", j));
}

SolidComponents build_solids(const model::Model& model, Progress& progress) {
  SolidComponents out;
  for (const auto& s : model.solids) out.emplace(s.name, build_solid(model, s, progress));
  return out;
}

}  // namespace geardyn::assembly
