#include "geardyn/solid/structured_mesh.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "geardyn/core/units.hpp"
#include "geardyn/solid/elements.hpp"

namespace geardyn::solid {
namespace {

using Lattice = std::array<int, 3>;

// A structured block of n[0] x n[1] x n[2] hexahedral cells in the parameter cube [0,1]^3,
// mapped to space by `map`. Nodes live on the lattice of half cells (2 n + 1 points per
// direction) so that quadratic elements find their mid-edge nodes; only lattice points used by
// an element become nodes, numbered in lattice order (i fastest, then j, then k). If
// `periodic_j`, lattice j wraps around (closed ring).
struct Block {
  std::array<int, 3> n{};
  bool periodic_j = false;
  std::function<Eigen::Vector3d(double, double, double)> map;

  int size(int d) const {
    return d == 1 && periodic_j ? 2 * n[1] : 2 * n[static_cast<std::size_t>(d)] + 1;
  }
  Lattice wrap(Lattice p) const {
    if (periodic_j) p[1] %= 2 * n[1];
    return p;
  }
  long index(const Lattice& p) const {
    return (static_cast<long>(p[2]) * size(1) + p[1]) * size(0) + p[0];
  }
};

// Corners of the cell's sub-elements in lattice offsets (0 or 1 per axis, times 2 later).
std::vector<std::vector<Lattice>> cell_split(ElementType type) {
  const std::array<Lattice, 8> c{
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  switch (type) {
    case ElementType::Hex8:
    case ElementType::Hex20:
      return {{c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]}};
    case ElementType::Wedge6:
    case ElementType::Wedge15:
      // bottom quad split along its diagonal 0-2, extruded along the third axis
      return {{c[0], c[1], c[2], c[4], c[5], c[6]}, {c[0], c[2], c[3], c[4], c[6], c[7]}};
    case ElementType::Tet4:
    case ElementType::Tet10: {
      // Kuhn (Freudenthal) subdivision: the 6 monotone edge paths from corner (0,0,0) to
      // (1,1,1), one per axis order; identical in every cell, hence conforming.
      std::vector<std::vector<Lattice>> tets;
      const std::array<std::array<int, 3>, 6> orders{
          {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
      for (const auto& o : orders) {
        Lattice p{0, 0, 0};
        std::vector<Lattice> t{p};
        for (int k = 0; k < 3; ++k) {
          p[static_cast<std::size_t>(o[static_cast<std::size_t>(k)])] = 1;
          t.push_back(p);
        }
        // orientation: positive volume in the parameter space (the maps preserve orientation)
        Eigen::Matrix3d J;
        for (int k = 0; k < 3; ++k) {
          for (int d = 0; d < 3; ++d) {
            J(d, k) = t[static_cast<std::size_t>(k) + 1][static_cast<std::size_t>(d)] -
                      t[0][static_cast<std::size_t>(d)];
          }
        }
        if (J.determinant() < 0) std::swap(t[1], t[2]);
        tets.push_back(t);
      }
      return tets;
    }
  }
  return {};
}

Mesh build(const Block& block, ElementType type, const Material& material, std::string source) {
  const auto split = cell_split(type);
  const auto edges = element_edges(type);
  const long n_lattice = static_cast<long>(block.size(0)) * block.size(1) * block.size(2);
  std::vector<int> node_of(static_cast<std::size_t>(n_lattice), -1);
  std::vector<std::vector<long>> element_lattice;
  element_lattice.reserve(static_cast<std::size_t>(block.n[0] * block.n[1] * block.n[2]) *
                          split.size());
  for (int k = 0; k < block.n[2]; ++k) {
    for (int j = 0; j < block.n[1]; ++j) {
      for (int i = 0; i < block.n[0]; ++i) {
        for (const auto& sub : split) {
          std::vector<Lattice> pts;
          for (const Lattice& c : sub)
            pts.push_back({2 * (i + c[0]), 2 * (j + c[1]), 2 * (k + c[2])});
          for (const auto& e : edges) {
            const Lattice& a = pts[static_cast<std::size_t>(e[0])];
            const Lattice& b = pts[static_cast<std::size_t>(e[1])];
            pts.push_back({(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2});
          }
          std::vector<long> ids;
          for (const Lattice& p : pts) {
            const long id = block.index(block.wrap(p));
            node_of[static_cast<std::size_t>(id)] = 0;
            ids.push_back(id);
          }
          element_lattice.push_back(std::move(ids));
        }
      }
    }
  }
  Mesh mesh;
  mesh.source = std::move(source);
  mesh.materials = {material};
  const std::array<std::string, 6> face_names = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  for (int k = 0; k < block.size(2); ++k) {
    for (int j = 0; j < block.size(1); ++j) {
      for (int i = 0; i < block.size(0); ++i) {
        const long id = block.index({i, j, k});
        if (node_of[static_cast<std::size_t>(id)] < 0) continue;
        const int node = mesh.num_nodes();
        node_of[static_cast<std::size_t>(id)] = node;
        const double u = 0.5 * i / block.n[0], v = 0.5 * j / block.n[1], w = 0.5 * k / block.n[2];
        mesh.coords.push_back(block.map(u, v, w));
        mesh.node_ids.push_back(node + 1);
        const std::array<int, 3> p{i, j, k};
        for (int d = 0; d < 3; ++d) {
          const auto sd = static_cast<std::size_t>(d);
          if (p[sd] == 0 && !(d == 1 && block.periodic_j)) {
            mesh.node_sets[face_names[2 * sd]].push_back(node);
          }
          if (p[sd] == 2 * block.n[sd] && !(d == 1 && block.periodic_j)) {
            mesh.node_sets[face_names[2 * sd + 1]].push_back(node);
          }
        }
      }
    }
  }
  mesh.elements.reserve(element_lattice.size());
  for (const auto& ids : element_lattice) {
    Element e;
    e.type = type;
    e.id = mesh.num_elements() + 1;
    e.material = 0;
    for (long id : ids) e.nodes.push_back(node_of[static_cast<std::size_t>(id)]);
    mesh.elements.push_back(std::move(e));
  }
  return mesh;
}

void check_count(int n, const char* key) {
  if (n < 1) throw InputError({}, key, "a cell count >= 1", fmt::format("{}", n));
}

void rename(Mesh& mesh, const std::string& from, const std::string& to) {
  auto it = mesh.node_sets.find(from);
  if (it == mesh.node_sets.end()) return;
  auto nodes = std::move(it->second);
  mesh.node_sets.erase(it);
  mesh.node_sets[to] = std::move(nodes);
}

}  // namespace

Mesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int nx, int ny, int nz,
              ElementType type, const Material& material) {
  check_count(nx, "box.nx");
  check_count(ny, "box.ny");
  check_count(nz, "box.nz");
  if (!lo.allFinite() || !hi.allFinite() || !((hi - lo).minCoeff() > 0)) {
    throw InputError({}, "box.hi", "hi > lo in every direction",
                     fmt::format("lo = ({}, {}, {}), hi = ({}, {}, {})", lo.x(), lo.y(), lo.z(),
                                 hi.x(), hi.y(), hi.z()));
  }
  Block block;
  block.n = {nx, ny, nz};
  const Eigen::Vector3d size = hi - lo;
  block.map = [lo, size](double u, double v, double w) {
    return Eigen::Vector3d(lo.x() + size.x() * u, lo.y() + size.y() * v, lo.z() + size.z() * w);
  };
  return build(block, type, material,
               fmt::format("box_mesh {}x{}x{} {}", nx, ny, nz, to_string(type)));
}

Mesh annular_sector_mesh(double r_inner, double r_outer, double thickness, double angle_rad,
                         int n_radial, int n_theta, int n_thick, ElementType type,
                         const Material& material) {
  check_count(n_radial, "sector.n_radial");
  check_count(n_theta, "sector.n_theta");
  check_count(n_thick, "sector.n_thick");
  if (!(r_inner > 0) || !std::isfinite(r_inner)) {
    throw InputError({}, "sector.r_inner", "an inner radius > 0 (no degenerate cells at the axis)",
                     fmt::format("{}", r_inner));
  }
  if (!(r_outer > r_inner) || !std::isfinite(r_outer)) {
    throw InputError({}, "sector.r_outer", fmt::format("an outer radius > r_inner = {}", r_inner),
                     fmt::format("{}", r_outer));
  }
  if (!(thickness > 0) || !std::isfinite(thickness)) {
    throw InputError({}, "sector.thickness", "a thickness > 0", fmt::format("{}", thickness));
  }
  if (!(angle_rad > 0) || angle_rad > units::kTwoPi * (1 + 1e-12)) {
    throw InputError({}, "sector.angle", "an angle in (0, 2 pi] rad", fmt::format("{}", angle_rad));
  }
  const bool closed = angle_rad >= units::kTwoPi * (1 - 1e-12);
  if (closed && n_theta < 3) {
    throw InputError({}, "sector.n_theta", "at least 3 cells around a closed annulus",
                     fmt::format("{}", n_theta));
  }
  Block block;
  block.n = {n_radial, n_theta, n_thick};
  block.periodic_j = closed;
  const double angle = closed ? units::kTwoPi : angle_rad;
  block.map = [=](double u, double v, double w) {
    const double r = r_inner + (r_outer - r_inner) * u;
    const double theta = angle * v;
    return Eigen::Vector3d(r * std::cos(theta), r * std::sin(theta), thickness * (w - 0.5));
  };
  Mesh mesh = build(
      block, type, material,
      fmt::format("annular_sector_mesh r {}..{} t {} angle {} ({}x{}x{} {})", r_inner, r_outer,
                  thickness, angle_rad, n_radial, n_theta, n_thick, to_string(type)));
  rename(mesh, "xmin", "inner");
  rename(mesh, "xmax", "outer");
  rename(mesh, "ymin", "left");
  rename(mesh, "ymax", "right");
  rename(mesh, "zmin", "bottom");
  rename(mesh, "zmax", "top");
  if (!closed) {
    // Exact periodicity: right = R(angle) left, with the same floating-point r and z.
    const auto& left = mesh.node_sets["left"];
    const auto& right = mesh.node_sets["right"];
    const double c = std::cos(angle), s = std::sin(angle);
    for (std::size_t k = 0; k < left.size(); ++k) {
      const Eigen::Vector3d& xl = mesh.coords[static_cast<std::size_t>(left[k])];
      mesh.coords[static_cast<std::size_t>(right[k])] =
          Eigen::Vector3d(c * xl.x() - s * xl.y(), s * xl.x() + c * xl.y(), xl.z());
    }
  }
  return mesh;
}

}  // namespace geardyn::solid
