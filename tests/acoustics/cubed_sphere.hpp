#pragma once
// A spherical shell r_inner <= r <= r_outer meshed as a cubed sphere (test geometry for the
// pulsating sphere): the six faces of a cube, each with n x n cells by the equiangular map
// (x = tan(pi/4 t), t in [-1, 1] on each face), projected to the sphere, one layer of hex8 or
// hex20 elements through the thickness (hex20 mid-edge nodes on the sphere / at the mid radius).
// Node set "outer": every node on r = r_outer.
#include <array>
#include <cmath>
#include <map>
#include <numbers>

#include "geardyn/solid/mesh.hpp"

namespace geardyn::acoustics::testing {

inline solid::Mesh cubed_sphere_shell(double r_inner, double r_outer, int n,
                                      solid::ElementType type) {
  solid::Mesh mesh;
  mesh.source = "cubed-sphere shell";
  mesh.materials.push_back({"steel", 1, 2.1e11, 0.3, 7850, {}});
  // (i, j, k on the cube surface in half cells, 0..2n; layer 0 inner, 1 middle, 2 outer) -> node
  std::map<std::array<int, 4>, int> index;
  auto node = [&](std::array<int, 3> g, int layer) {
    const std::array<int, 4> key{g[0], g[1], g[2], layer};
    const auto found = index.find(key);
    if (found != index.end()) return found->second;
    Eigen::Vector3d x;
    for (int a = 0; a < 3; ++a)
      x[a] = std::tan(std::numbers::pi / 4 * (-1.0 + static_cast<double>(g[a]) / n));
    const double r = r_inner + (r_outer - r_inner) * layer / 2.0;
    const int id = mesh.num_nodes();
    mesh.coords.push_back(x.normalized() * r);
    mesh.node_ids.push_back(id + 1);
    if (layer == 2) mesh.node_sets["outer"].push_back(id);
    index.emplace(key, id);
    return id;
  };
  // Gmsh hex corners in reference coordinates, and the hex20 mid-edge corner pairs.
  const int corner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                            {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  const int edge[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                           {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
  const bool quadratic = type == solid::ElementType::Hex20;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
      for (int u = 0; u < n; ++u)
        for (int v = 0; v < n; ++v) {
          const int b = (axis + 1) % 3, c = (axis + 2) % 3;
          auto at = [&](int xi, int eta, int zeta) {  // reference point -> mesh node
            std::array<int, 3> g{};
            g[axis] = side * 2 * n;
            g[b] = 2 * u + 1 + xi;
            g[c] = 2 * v + 1 + eta;
            return node(g, 1 + zeta);
          };
          solid::Element e;
          e.type = type;
          e.id = mesh.num_elements() + 1;
          for (const auto& p : corner) e.nodes.push_back(at(p[0], p[1], p[2]));
          if (quadratic)
            for (const auto& k : edge)
              e.nodes.push_back(at((corner[k[0]][0] + corner[k[1]][0]) / 2,
                                   (corner[k[0]][1] + corner[k[1]][1]) / 2,
                                   (corner[k[0]][2] + corner[k[1]][2]) / 2));
          mesh.elements.push_back(e);
        }
  return mesh;
}

}  // namespace geardyn::acoustics::testing
