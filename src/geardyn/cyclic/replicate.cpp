#include "geardyn/cyclic/replicate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <unordered_map>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"

namespace geardyn::cyclic {

namespace {

// True when the component set {c : flags[c]} is mapped onto itself by the rotation R (for both
// the translation and the rotation triple): a component that is in the set must not feed one
// that is not.
bool invariant(const std::array<bool, 6>& flags, const Eigen::Matrix3d& R) {
  for (int t = 0; t < 2; ++t)
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d)
        if (flags[static_cast<std::size_t>(3 * t + d)] !=
                flags[static_cast<std::size_t>(3 * t + c)] &&
            std::abs(R(c, d)) > 1e-12)
          return false;
  return true;
}

// The direction of a spring end in the copy rotated by Rs: R_s n (n the end's axis, Spring),
// kept as "along the component" (zero) when the rotation leaves the axis unchanged (copy 0, a
// component along the axis of symmetry), so those springs stay scalar.
Eigen::Vector3d rotated_direction(const Eigen::Matrix3d& Rs, int component,
                                  const Eigen::Vector3d& direction) {
  const Eigen::Vector3d n = solid::spring_axis(component, direction);
  const Eigen::Vector3d m = Rs * n;
  if ((m - n).norm() <= 1e-14) return direction;
  return m.normalized();
}

long id_stride(long largest) {
  long stride = 10;
  while (stride <= largest) stride *= 10;
  return stride;
}

class PointGrid {
 public:
  explicit PointGrid(double cell) : cell_(cell) {}
  void insert(const Eigen::Vector3d& x, int index) {
    cells_[key(cell_of(x))].push_back({x, index});
  }
  // All stored points within radius (<= cell) of x.
  std::vector<std::pair<int, double>> near(const Eigen::Vector3d& x, double radius) const {
    std::vector<std::pair<int, double>> out;
    const Eigen::Array3i c = cell_of(x);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key(c + Eigen::Array3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const auto& [y, i] : it->second)
            if (const double d = (y - x).norm(); d <= radius) out.emplace_back(i, d);
        }
    return out;
  }

 private:
  Eigen::Array3i cell_of(const Eigen::Vector3d& x) const {
    return (x.array() / cell_).floor().cast<int>();
  }
  static std::uint64_t key(const Eigen::Array3i& c) {
    const auto u = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v)); };
    return (u(c[0]) * 0x9E3779B97F4A7C15ULL) ^ (u(c[1]) * 0xC2B2AE3D27D4EB4FULL) ^
           (u(c[2]) * 0x165667B19E3779F9ULL);
  }
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::pair<Eigen::Vector3d, int>>> cells_;
};

}  // namespace

ReplicatedMesh replicate(const solid::Mesh& sector, int n_sectors, double tolerance,
                         const Eigen::Vector3d& axis_in) {
  const std::string key = "cyclic.replicate";
  if (n_sectors < 2) throw InputError({}, key + ".n_sectors", "N >= 2", std::to_string(n_sectors));
  if (!(axis_in.norm() > 0.0) || !axis_in.allFinite())
    throw InputError({}, key + ".axis", "a non-zero finite axis", "a zero or non-finite vector");
  if (!std::isnan(tolerance) && !(tolerance > 0.0 && std::isfinite(tolerance)))
    throw InputError({}, key + ".tolerance", "a positive tolerance [m] or NaN (automatic)",
                     fmt::format("{}", tolerance));
  const Eigen::Vector3d axis = axis_in.normalized();
  const double alpha = units::kTwoPi / n_sectors;
  const Eigen::Matrix3d R1 = rotation(axis, alpha);

  for (const auto& r : sector.rigid_elements)
    if (!invariant(r.components, R1))
      throw InputError(r.where, fmt::format("{}.rigid_elements[id {}]", key, r.id),
                       "component sets unchanged by the sector rotation",
                       "a component set that mixes under rotation about the axis");
  for (const auto& c : sector.constraints)
    if (!invariant(c.components, R1))
      throw InputError(c.where, fmt::format("{}.constraints[node {}]", key, c.node),
                       "constrained component sets unchanged by the sector rotation",
                       "a component set that mixes under rotation about the axis");

  const int n = sector.num_nodes();
  double size = 0.0;
  for (const auto& x : sector.coords) size = std::max(size, x.norm());
  const double tol = std::isnan(tolerance) ? 1e-6 * std::max(size, 1e-300) : tolerance;

  long largest_node = 0, largest_element = 0, largest_mass = 0, largest_rigid = 0,
       largest_spring = 0;
  for (long id : sector.node_ids) largest_node = std::max(largest_node, id);
  for (const auto& e : sector.elements) largest_element = std::max(largest_element, e.id);
  for (const auto& m : sector.point_masses) largest_mass = std::max(largest_mass, m.id);
  for (const auto& r : sector.rigid_elements) largest_rigid = std::max(largest_rigid, r.id);
  for (const auto& sp : sector.springs) largest_spring = std::max(largest_spring, sp.id);
  const long node_stride = id_stride(largest_node), element_stride = id_stride(largest_element),
             mass_stride = id_stride(largest_mass), rigid_stride = id_stride(largest_rigid),
             spring_stride = id_stride(largest_spring);

  ReplicatedMesh out;
  solid::Mesh& full = out.mesh;
  full.source = fmt::format("{} replicated to {} sectors", sector.source, n_sectors);
  full.materials = sector.materials;
  PointGrid grid(tol);
  out.node_map.assign(static_cast<std::size_t>(n_sectors),
                      std::vector<int>(static_cast<std::size_t>(n)));
  for (int s = 0; s < n_sectors; ++s) {
    const Eigen::Matrix3d Rs = rotation(axis, s * alpha);
    auto& map = out.node_map[static_cast<std::size_t>(s)];
    std::vector<std::pair<Eigen::Vector3d, int>> added;
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d x = Rs * sector.coords[static_cast<std::size_t>(i)];
      const auto near = s == 0 ? std::vector<std::pair<int, double>>{} : grid.near(x, tol);
      if (near.size() > 1)
        throw InputError(
            {}, key, "at most one earlier node within the tolerance of each node",
            fmt::format("node {} of copy {} is within {:.3g} m of {} nodes",
                        sector.node_ids[static_cast<std::size_t>(i)], s, tol, near.size()),
            "lower the tolerance or remove duplicate nodes");
      if (near.size() == 1) {
        map[static_cast<std::size_t>(i)] = near.front().first;
        ++out.merged_nodes;
        out.worst_merge_gap = std::max(out.worst_merge_gap, near.front().second);
        continue;
      }
      const int index = full.num_nodes();
      map[static_cast<std::size_t>(i)] = index;
      full.coords.push_back(x);
      full.node_ids.push_back(sector.node_ids[static_cast<std::size_t>(i)] + s * node_stride);
      added.emplace_back(x, index);
    }
    for (const auto& [x, index] : added) grid.insert(x, index);

    const auto remap = [&](int node) { return map[static_cast<std::size_t>(node)]; };
    const int element_base = full.num_elements();
    for (const auto& e : sector.elements) {
      solid::Element c = e;
      c.id = e.id + s * element_stride;
      for (int& v : c.nodes) v = remap(v);
      full.elements.push_back(std::move(c));
    }
    for (const auto& [name, nodes] : sector.node_sets) {
      auto& set = full.node_sets[name];
      for (int v : nodes) set.push_back(remap(v));
    }
    for (const auto& [name, elements] : sector.element_sets) {
      auto& set = full.element_sets[name];
      for (int e : elements) set.push_back(element_base + e);
    }
    for (const auto& m : sector.point_masses) {
      solid::PointMass c = m;
      c.id = m.id + s * mass_stride;
      c.node = remap(m.node);
      c.offset = Rs * m.offset;
      c.inertia = Rs * m.inertia * Rs.transpose();
      full.point_masses.push_back(c);
    }
    for (const auto& sp : sector.springs) {
      solid::Spring c = sp;
      c.id = sp.id + s * spring_stride;
      c.node1 = remap(sp.node1);
      c.direction1 = rotated_direction(Rs, sp.component1, sp.direction1);
      if (sp.node2 >= 0) {
        c.node2 = remap(sp.node2);
        c.direction2 = rotated_direction(Rs, sp.component2, sp.direction2);
      }
      full.springs.push_back(c);
    }
    for (const auto& r : sector.rigid_elements) {
      solid::RigidElement c = r;
      c.id = r.id + s * rigid_stride;
      c.reference = remap(r.reference);
      for (int& v : c.nodes) v = remap(v);
      full.rigid_elements.push_back(std::move(c));
    }
    for (const auto& con : sector.constraints) {
      solid::Constraint c = con;
      c.node = remap(con.node);
      full.constraints.push_back(c);
    }
  }
  // Sets sorted without duplicates (interface nodes are in two copies).
  for (auto& [name, nodes] : full.node_sets) {
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  }
  for (auto& [name, elements] : full.element_sets) std::sort(elements.begin(), elements.end());
  // A constraint on a merged interface node appears twice; keep one per node and component set.
  std::set<std::pair<int, std::array<bool, 6>>> seen;
  std::vector<solid::Constraint> unique_constraints;
  for (const auto& c : full.constraints)
    if (seen.insert({c.node, c.components}).second) unique_constraints.push_back(c);
  full.constraints = std::move(unique_constraints);
  return out;
}

}  // namespace geardyn::cyclic
