#include "geardyn/meshio/gmsh_reader.hpp"

#include <fmt/format.h>
#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <set>
#include <unordered_map>

#include "geardyn/meshgen/gmsh_session.hpp"
#include "geardyn/meshio/element_ordering.hpp"

namespace geardyn::meshio {
namespace {

namespace fs = std::filesystem;
using solid::ElementType;

std::optional<ElementType> element_type_of(int gmsh_type) {
  switch (gmsh_type) {
    case 4:
      return ElementType::Tet4;
    case 11:
      return ElementType::Tet10;
    case 5:
      return ElementType::Hex8;
    case 17:
      return ElementType::Hex20;
    case 6:
      return ElementType::Wedge6;
    case 18:
      return ElementType::Wedge15;
    default:
      return std::nullopt;
  }
}

void check_material(const solid::Material& m, const std::string& key, const std::string& file) {
  const SourceLocation where = m.where.file.empty() ? SourceLocation{file, 0, 0} : m.where;
  if (!(m.E > 0) || !std::isfinite(m.E))
    throw InputError(where, key + ".E", "a Young's modulus > 0 [Pa]", fmt::format("{}", m.E));
  if (!(m.nu > -1.0 && m.nu < 0.5))
    throw InputError(where, key + ".nu", "a Poisson's ratio in (-1, 0.5)", fmt::format("{}", m.nu));
  if (!(m.rho >= 0) || !std::isfinite(m.rho))
    throw InputError(where, key + ".rho", "a density >= 0 [kg/m^3]", fmt::format("{}", m.rho));
}

bool same_material(const solid::Material& a, const solid::Material& b) {
  return a.name == b.name && a.E == b.E && a.nu == b.nu && a.rho == b.rho && a.id == b.id;
}

struct PhysicalGroup {
  int dim = 0;
  int tag = 0;
  std::string name;
  std::vector<int> entities;
};

struct RawElement {
  ElementType type;
  std::size_t tag;
  int entity;
  std::vector<std::size_t> nodes;
};

// Physical groups of every dimension.
std::vector<PhysicalGroup> physical_groups() {
  std::vector<PhysicalGroup> groups;
  {
    gmsh::vectorpair dim_tags;
    gmsh::model::getPhysicalGroups(dim_tags, -1);
    for (const auto& [dim, tag] : dim_tags) {
      PhysicalGroup g;
      g.dim = dim;
      g.tag = tag;
      gmsh::model::getPhysicalName(dim, tag, g.name);
      if (g.name.empty()) g.name = fmt::format("physical_{}_{}", dim, tag);
      gmsh::model::getEntitiesForPhysicalGroup(dim, tag, g.entities);
      groups.push_back(std::move(g));
    }
  }
  return groups;
}

// Every physical volume named in the options exists in the file.
void check_volume_names(const std::vector<PhysicalGroup>& groups, const GmshReadOptions& options,
                        const std::string& file) {
  std::set<std::string> volume_names;
  for (const PhysicalGroup& g : groups)
    if (g.dim == 3) volume_names.insert(g.name);
  for (const auto& [name, material] : options.volume_materials) {
    if (volume_names.count(name) != 0) continue;
    std::string available;
    for (const std::string& n : volume_names) available += (available.empty() ? "" : ", ") + n;
    throw InputError(material.where.file.empty() ? SourceLocation{file, 0, 0} : material.where,
                     "volume_materials", "the name of a physical volume of " + file,
                     "'" + name + "'",
                     available.empty() ? "the file has no physical volumes"
                                       : "available physical volumes: " + available);
  }
}

// Material of each volume entity: the one of the listed physical volumes containing it.
struct EntityMaterials {
  std::unordered_map<int, const solid::Material*> entity_material;
  std::unordered_map<int, std::string> entity_material_group;
};

EntityMaterials entity_materials(const std::vector<PhysicalGroup>& groups,
                                 const GmshReadOptions& options, const std::string& file) {
  EntityMaterials em;
  std::unordered_map<int, const solid::Material*>& entity_material = em.entity_material;
  std::unordered_map<int, std::string>& entity_material_group = em.entity_material_group;
  for (const PhysicalGroup& g : groups) {
    if (g.dim != 3) continue;
    const auto it = options.volume_materials.find(g.name);
    if (it == options.volume_materials.end()) continue;
    for (int entity : g.entities) {
      const auto [e, inserted] = entity_material.emplace(entity, &it->second);
      if (!inserted && !same_material(*e->second, it->second))
        throw InputError(SourceLocation{file, 0, 0}, "volume_materials",
                         "one material per Gmsh volume",
                         fmt::format("volume {} is in physical volumes '{}' and '{}' with "
                                     "different materials",
                                     entity, entity_material_group[entity], g.name));
      entity_material_group.emplace(entity, g.name);
    }
  }
  return em;
}

// Volume elements, entity by entity.
std::vector<RawElement> volume_elements(const std::string& file) {
  std::vector<RawElement> raw;
  {
    gmsh::vectorpair volumes;
    gmsh::model::getEntities(volumes, 3);
    for (const auto& [dim, entity] : volumes) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gmsh::model::mesh::getElements(types, element_tags, node_tags, 3, entity);
      for (std::size_t k = 0; k < types.size(); ++k) {
        const std::optional<ElementType> type = element_type_of(types[k]);
        if (!type) {
          std::string name;
          int element_dim = 0, order = 0, num_nodes = 0, num_primary = 0;
          std::vector<double> local;
          gmsh::model::mesh::getElementProperties(types[k], name, element_dim, order, num_nodes,
                                                  local, num_primary);
          throw InputError(
              SourceLocation{file, 0, 0}, fmt::format("volume {}", entity),
              "volume elements of Gmsh types 4, 11 (tet4, tet10), 5, 17 (hex8, "
              "hex20) or 6, 18 (prism6, prism15)",
              fmt::format("{} elements of type {} ({})", element_tags[k].size(), types[k], name),
              "mesh with Mesh.SecondOrderIncomplete = 1 and without pyramids");
        }
        const std::size_t n = static_cast<std::size_t>(solid::num_element_nodes(*type));
        for (std::size_t e = 0; e < element_tags[k].size(); ++e)
          raw.push_back(
              RawElement{*type, element_tags[k][e], entity,
                         std::vector<std::size_t>(
                             node_tags[k].begin() + static_cast<std::ptrdiff_t>(e * n),
                             node_tags[k].begin() + static_cast<std::ptrdiff_t>((e + 1) * n))});
      }
    }
  }
  if (raw.empty())
    throw InputError(SourceLocation{file, 0, 0}, "elements",
                     "volume elements (tet4/10, hex8/20, prism6/15)", "none",
                     "mesh the volumes (gmsh -3) before saving");
  return raw;
}

// Node sets: all nodes of each group's entities: those classified on them or their boundaries,
// and those of their elements (a file may classify an element's nodes on other entities).
std::map<std::string, std::vector<std::size_t>> node_set_tags(
    const std::vector<PhysicalGroup>& groups) {
  std::map<std::string, std::vector<std::size_t>> set_tags;
  for (const PhysicalGroup& g : groups) {
    std::vector<std::size_t>& tags = set_tags[g.name];
    for (int entity : g.entities) {
      std::vector<std::size_t> t;
      std::vector<double> coords, params;
      gmsh::model::mesh::getNodes(t, coords, params, g.dim, entity, true, false);
      tags.insert(tags.end(), t.begin(), t.end());
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gmsh::model::mesh::getElements(types, element_tags, node_tags, g.dim, entity);
      for (const std::vector<std::size_t>& n : node_tags)
        tags.insert(tags.end(), n.begin(), n.end());
    }
  }
  return set_tags;
}

// Nodes used by volume elements or physical groups, in tag order, and the node sets. Returns the
// index of each node tag.
std::unordered_map<std::size_t, int> add_nodes(
    solid::Mesh& mesh, const std::vector<RawElement>& raw,
    const std::map<std::string, std::vector<std::size_t>>& set_tags, const std::string& file) {
  std::unordered_map<std::size_t, Eigen::Vector3d> coord_of;
  {
    std::vector<std::size_t> tags;
    std::vector<double> coords, params;
    gmsh::model::mesh::getNodes(tags, coords, params, -1, -1, false, false);
    coord_of.reserve(tags.size());
    for (std::size_t i = 0; i < tags.size(); ++i)
      coord_of[tags[i]] = Eigen::Vector3d(coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]);
  }
  std::vector<std::size_t> used;
  for (const RawElement& r : raw) used.insert(used.end(), r.nodes.begin(), r.nodes.end());
  for (const auto& [name, tags] : set_tags) used.insert(used.end(), tags.begin(), tags.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());

  std::unordered_map<std::size_t, int> index;
  index.reserve(used.size());
  for (std::size_t tag : used) {
    const auto it = coord_of.find(tag);
    if (it == coord_of.end())
      throw InputError(SourceLocation{file, 0, 0}, "nodes", "every node of the elements defined",
                       fmt::format("node {} is used but not defined", tag));
    index[tag] = static_cast<int>(mesh.coords.size());
    mesh.node_ids.push_back(static_cast<long>(tag));
    mesh.coords.push_back(it->second);
  }
  for (const auto& [name, tags] : set_tags) {
    std::vector<int>& nodes = mesh.node_sets[name];
    for (std::size_t t : tags) nodes.push_back(index.at(t));
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  }
  return index;
}

// Elements in tag order (raw is sorted) with their materials.
void add_elements(solid::Mesh& mesh, std::vector<RawElement>& raw,
                  const std::unordered_map<std::size_t, int>& index, EntityMaterials& em,
                  const GmshReadOptions& options, const std::string& file) {
  std::unordered_map<int, const solid::Material*>& entity_material = em.entity_material;
  std::unordered_map<int, std::string>& entity_material_group = em.entity_material_group;
  std::vector<solid::Material> materials;
  const auto material_index = [&](const solid::Material& m) {
    for (std::size_t i = 0; i < materials.size(); ++i)
      if (same_material(materials[i], m)) return static_cast<int>(i);
    materials.push_back(m);
    return static_cast<int>(materials.size()) - 1;
  };
  std::sort(raw.begin(), raw.end(),
            [](const RawElement& a, const RawElement& b) { return a.tag < b.tag; });
  std::unordered_map<std::size_t, int> element_index;
  bool default_checked = false;
  for (const RawElement& r : raw) {
    solid::Element element;
    element.type = r.type;
    element.id = static_cast<long>(r.tag);
    element.where = SourceLocation{file, 0, 0};
    for (std::size_t t : r.nodes) element.nodes.push_back(index.at(t));
    if (orient_positive(r.type, element.nodes, mesh.coords) == Orientation::Degenerate)
      throw InputError(SourceLocation{file, 0, 0}, fmt::format("element {}", r.tag),
                       "an element with non-zero volume",
                       fmt::format("{} element {} in volume {} with zero corner volume",
                                   solid::to_string(r.type), r.tag, r.entity));
    const auto m = entity_material.find(r.entity);
    if (m != entity_material.end()) {
      solid::Material material = *m->second;
      if (material.name.empty()) material.name = entity_material_group[r.entity];
      check_material(material, "volume_materials." + entity_material_group[r.entity], file);
      element.material = material_index(material);
    } else {
      solid::Material material = options.default_material;
      if (material.name.empty()) material.name = "default";
      if (!default_checked) {
        check_material(material, "default_material", file);
        default_checked = true;
      }
      element.material = material_index(material);
    }
    element_index[r.tag] = mesh.num_elements();
    mesh.elements.push_back(std::move(element));
  }
  mesh.materials = std::move(materials);
}

// Element sets of physical volumes.
void add_element_sets(solid::Mesh& mesh, const std::vector<RawElement>& raw,
                      const std::vector<PhysicalGroup>& groups) {
  std::unordered_map<int, std::vector<int>> elements_of_entity;
  for (std::size_t i = 0; i < raw.size(); ++i)
    elements_of_entity[raw[i].entity].push_back(static_cast<int>(i));
  for (const PhysicalGroup& g : groups) {
    if (g.dim != 3) continue;
    std::vector<int>& set = mesh.element_sets[g.name];
    for (int entity : g.entities) {
      const auto it = elements_of_entity.find(entity);
      if (it != elements_of_entity.end())
        set.insert(set.end(), it->second.begin(), it->second.end());
    }
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }
}

solid::Mesh extract(const std::string& file, const GmshReadOptions& options) {
  const std::vector<PhysicalGroup> groups = physical_groups();
  check_volume_names(groups, options, file);
  EntityMaterials em = entity_materials(groups, options, file);
  std::vector<RawElement> raw = volume_elements(file);
  const std::map<std::string, std::vector<std::size_t>> set_tags = node_set_tags(groups);
  solid::Mesh mesh;
  mesh.source = file;
  const std::unordered_map<std::size_t, int> index = add_nodes(mesh, raw, set_tags, file);
  add_elements(mesh, raw, index, em, options, file);
  add_element_sets(mesh, raw, groups);
  return mesh;
}

}  // namespace

solid::Mesh read_gmsh(const fs::path& path, const GmshReadOptions& options) {
  const std::string file = path.string();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw InputError(SourceLocation{file, 0, 0}, "file", "an existing Gmsh mesh file",
                     "'" + file + "' does not exist or is not a file");
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe)
      throw InputError(SourceLocation{file, 0, 0}, "file", "a readable file",
                       "'" + file + "' cannot be opened");
  }
  meshgen::GmshSession session("geardyn_read_gmsh");
  // Gmsh reports errors by throwing std::string (General.AbortOnError = 2, set by initialize);
  // after such an error it refuses further calls until finalised, which the session does.
  try {
    gmsh::open(file);
    return extract(file, options);
  } catch (const std::string& message) {
    throw InputError(SourceLocation{file, 0, 0}, "file", "a mesh file Gmsh can read",
                     "Gmsh: " + message);
  }
}

}  // namespace geardyn::meshio
