#include "geardyn/meshio/gmsh_view_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <limits>
#include <map>

#include "geardyn/core/error.hpp"

namespace geardyn::meshio {

int gmsh_element_type(solid::ElementType type) {
  switch (type) {
    case solid::ElementType::Tet4:
      return 4;
    case solid::ElementType::Tet10:
      return 11;
    case solid::ElementType::Hex8:
      return 5;
    case solid::ElementType::Hex20:
      return 17;
    case solid::ElementType::Wedge6:
      return 6;
    case solid::ElementType::Wedge15:
      return 18;
  }
  return 0;
}

namespace {

std::string quoted_name(std::string name) {
  // A Gmsh string tag is delimited by double quotes and cannot contain them.
  std::replace(name.begin(), name.end(), '"', '\'');
  std::replace(name.begin(), name.end(), '\n', ' ');
  return "\"" + name + "\"";
}

}  // namespace

void write_gmsh_views(const std::filesystem::path& path, const solid::Mesh& mesh,
                      const std::vector<Field>& fields, double time) {
  check_fields(mesh, fields);
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const int c = fields[i].num_components;
    if (c != 1 && c != 3 && c != 9)
      throw InputError({}, fmt::format("fields[{}].num_components", i),
                       "1, 3 or 9 (a Gmsh scalar, vector or tensor view)", fmt::format("{}", c),
                       "field '" + fields[i].name + "'");
  }

  // One volume entity per (material, element type): Gmsh's API assumes a single element type
  // per family (tetrahedra, hexahedra, prisms) in an entity, so tet4 and tet10 of one material
  // must not share one. The entities of a material form its physical group.
  std::map<std::pair<int, int>, std::vector<int>> blocks;  // (material, gmsh type) -> elements
  for (int e = 0; e < mesh.num_elements(); ++e)
    blocks[{mesh.elements[static_cast<std::size_t>(e)].material,
            gmsh_element_type(mesh.elements[static_cast<std::size_t>(e)].type)}]
        .push_back(e);
  std::map<int, std::string> materials;
  for (const auto& [key, elements] : blocks) {
    const int material = key.first;
    const bool named = material >= 0 && material < static_cast<int>(mesh.materials.size()) &&
                       !mesh.materials[static_cast<std::size_t>(material)].name.empty();
    materials[material] = named ? mesh.materials[static_cast<std::size_t>(material)].name
                                : fmt::format("material_{}", material);
  }
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d hi = -lo;
  for (const Eigen::Vector3d& x : mesh.coords) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  if (mesh.coords.empty()) lo = hi = Eigen::Vector3d::Zero();

  fmt::memory_buffer b;
  auto out = std::back_inserter(b);
  fmt::format_to(out, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
  fmt::format_to(out, "$PhysicalNames\n{}\n", materials.size());
  for (const auto& [material, name] : materials)
    fmt::format_to(out, "3 {} {}\n", material + 1, quoted_name(name));
  fmt::format_to(out, "$EndPhysicalNames\n");
  fmt::format_to(out, "$Entities\n0 0 0 {}\n", blocks.size());
  int entity = 0;
  for (const auto& [key, elements] : blocks)
    fmt::format_to(out, "{} {} {} {} {} {} {} 1 {} 0\n", ++entity, lo.x(), lo.y(), lo.z(), hi.x(),
                   hi.y(), hi.z(), key.first + 1);
  fmt::format_to(out, "$EndEntities\n");

  // All nodes in one block attached to the first volume entity.
  const int n = mesh.num_nodes();
  fmt::format_to(out, "$Nodes\n{} {} {} {}\n", n > 0 ? 1 : 0, n, n > 0 ? 1 : 0, n);
  if (n > 0) {
    fmt::format_to(out, "3 1 0 {}\n", n);
    for (int i = 0; i < n; ++i) fmt::format_to(out, "{}\n", i + 1);
    for (const Eigen::Vector3d& x : mesh.coords)
      fmt::format_to(out, "{} {} {}\n", x.x(), x.y(), x.z());
  }
  fmt::format_to(out, "$EndNodes\n");

  const int m = mesh.num_elements();
  fmt::format_to(out, "$Elements\n{} {} {} {}\n", blocks.size(), m, m > 0 ? 1 : 0, m);
  entity = 0;
  for (const auto& [key, elements] : blocks) {
    fmt::format_to(out, "3 {} {} {}\n", ++entity, key.second, elements.size());
    for (int e : elements) {
      fmt::format_to(out, "{}", e + 1);
      for (int node : mesh.elements[static_cast<std::size_t>(e)].nodes)
        fmt::format_to(out, " {}", node + 1);
      fmt::format_to(out, "\n");
    }
  }
  fmt::format_to(out, "$EndElements\n");

  for (const Field& f : fields) {
    fmt::format_to(out, "$NodeData\n1\n{}\n1\n{}\n3\n0\n{}\n{}\n", quoted_name(f.name), time,
                   f.num_components, n);
    const std::size_t c = static_cast<std::size_t>(f.num_components);
    for (int i = 0; i < n; ++i) {
      fmt::format_to(out, "{}", i + 1);
      for (std::size_t k = 0; k < c; ++k)
        fmt::format_to(out, " {}", f.values[static_cast<std::size_t>(i) * c + k]);
      fmt::format_to(out, "\n");
    }
    fmt::format_to(out, "$EndNodeData\n");
  }
  write_file_atomically(path, fmt::to_string(b));
}

}  // namespace geardyn::meshio
