#include "geardyn/meshio/element_ordering.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace geardyn::meshio {
namespace {

using solid::ElementType;
using Edge = std::pair<int, int>;

// Gmsh reference manual, "Node ordering" (also written out in solid/mesh.hpp).
constexpr std::array<Edge, 6> kGmshTetEdges{{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}}};
constexpr std::array<Edge, 12> kGmshHexEdges{{{0, 1},
                                              {0, 3},
                                              {0, 4},
                                              {1, 2},
                                              {1, 5},
                                              {2, 3},
                                              {2, 6},
                                              {3, 7},
                                              {4, 5},
                                              {4, 7},
                                              {5, 6},
                                              {6, 7}}};
constexpr std::array<Edge, 9> kGmshWedgeEdges{
    {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 4}, {2, 5}, {3, 4}, {3, 5}, {4, 5}}};

// Nastran Quick Reference Guide, CTETRA / CHEXA / CPENTA (grid numbers 1-based there).
constexpr std::array<Edge, 6> kNastranTetEdges{{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};
constexpr std::array<Edge, 12> kNastranHexEdges{{{0, 1},
                                                 {1, 2},
                                                 {2, 3},
                                                 {3, 0},
                                                 {0, 4},
                                                 {1, 5},
                                                 {2, 6},
                                                 {3, 7},
                                                 {4, 5},
                                                 {5, 6},
                                                 {6, 7},
                                                 {7, 4}}};
constexpr std::array<Edge, 9> kNastranWedgeEdges{
    {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 4}, {2, 5}, {3, 4}, {4, 5}, {5, 3}}};

// Corner permutations that mirror an element (new corner i = old corner perm[i]) while keeping
// the convention's face structure: reverse the winding of the triangle / quadrilateral faces.
constexpr std::array<int, 4> kFlipTet{0, 2, 1, 3};
constexpr std::array<int, 8> kFlipHex{0, 3, 2, 1, 4, 7, 6, 5};
constexpr std::array<int, 6> kFlipWedge{0, 2, 1, 3, 5, 4};

bool same_edge(Edge a, Edge b) {
  return (a.first == b.first && a.second == b.second) ||
         (a.first == b.second && a.second == b.first);
}

// Builds the element in Gmsh order from `source` whose mid-edge nodes follow `source_edges`;
// corner i of the result is corner corner_map[i] of the source, and the node on the result's
// edge (a, b) is the source's node on edge (corner_map[a], corner_map[b]).
std::vector<int> rebuild(ElementType type, const std::vector<int>& source,
                         std::span<const Edge> source_edges, std::span<const int> corner_map) {
  const int corners = num_corner_nodes(type);
  assert(static_cast<int>(source.size()) == solid::num_element_nodes(type));
  std::vector<int> result(source.size());
  for (int i = 0; i < corners; ++i) result[i] = source[corner_map[i]];
  const auto target_edges = gmsh_edges(type);
  for (std::size_t k = 0; k < target_edges.size(); ++k) {
    const Edge wanted{corner_map[target_edges[k].first], corner_map[target_edges[k].second]};
    const auto it = std::find_if(source_edges.begin(), source_edges.end(),
                                 [&](Edge e) { return same_edge(e, wanted); });
    assert(it != source_edges.end());
    result[corners + k] = source[corners + (it - source_edges.begin())];
  }
  return result;
}

std::span<const int> identity_corners(ElementType type) {
  static constexpr std::array<int, 8> kIdentity{0, 1, 2, 3, 4, 5, 6, 7};
  return std::span<const int>(kIdentity.data(), static_cast<std::size_t>(num_corner_nodes(type)));
}

std::span<const int> flip_corners(ElementType type) {
  switch (type) {
    case ElementType::Tet4:
    case ElementType::Tet10:
      return kFlipTet;
    case ElementType::Hex8:
    case ElementType::Hex20:
      return kFlipHex;
    case ElementType::Wedge6:
    case ElementType::Wedge15:
      return kFlipWedge;
  }
  return {};
}

}  // namespace

int num_corner_nodes(ElementType type) {
  switch (type) {
    case ElementType::Tet4:
    case ElementType::Tet10:
      return 4;
    case ElementType::Hex8:
    case ElementType::Hex20:
      return 8;
    case ElementType::Wedge6:
    case ElementType::Wedge15:
      return 6;
  }
  return 0;
}

bool is_quadratic(ElementType type) {
  return type == ElementType::Tet10 || type == ElementType::Hex20 || type == ElementType::Wedge15;
}

std::span<const Edge> gmsh_edges(ElementType type) {
  switch (type) {
    case ElementType::Tet10:
      return kGmshTetEdges;
    case ElementType::Hex20:
      return kGmshHexEdges;
    case ElementType::Wedge15:
      return kGmshWedgeEdges;
    default:
      return {};
  }
}

std::span<const Edge> nastran_edges(ElementType type) {
  switch (type) {
    case ElementType::Tet10:
      return kNastranTetEdges;
    case ElementType::Hex20:
      return kNastranHexEdges;
    case ElementType::Wedge15:
      return kNastranWedgeEdges;
    default:
      return {};
  }
}

std::vector<int> nastran_to_gmsh(ElementType type, const std::vector<int>& nodes) {
  return rebuild(type, nodes, nastran_edges(type), identity_corners(type));
}

double corner_volume_measure(ElementType type, const std::vector<int>& nodes,
                             const std::vector<Eigen::Vector3d>& coords) {
  const auto p = [&](int i) -> const Eigen::Vector3d& { return coords[nodes[i]]; };
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  switch (type) {
    case ElementType::Tet4:
    case ElementType::Tet10:
      J.col(0) = p(1) - p(0);
      J.col(1) = p(2) - p(0);
      J.col(2) = p(3) - p(0);
      break;
    case ElementType::Hex8:
    case ElementType::Hex20:
      // Twice the derivatives of the trilinear map at the centre (reference cube [-1, 1]^3).
      J.col(0) = (p(1) + p(2) + p(5) + p(6) - p(0) - p(3) - p(4) - p(7)) / 4;
      J.col(1) = (p(2) + p(3) + p(6) + p(7) - p(0) - p(1) - p(4) - p(5)) / 4;
      J.col(2) = (p(4) + p(5) + p(6) + p(7) - p(0) - p(1) - p(2) - p(3)) / 4;
      break;
    case ElementType::Wedge6:
    case ElementType::Wedge15:
      // Derivatives at the centroid of the reference prism (unit triangle x [-1, 1]).
      J.col(0) = (p(1) - p(0) + p(4) - p(3)) / 2;
      J.col(1) = (p(2) - p(0) + p(5) - p(3)) / 2;
      J.col(2) = (p(3) + p(4) + p(5) - p(0) - p(1) - p(2)) / 6;
      break;
  }
  return J.determinant();
}

Orientation orient_positive(ElementType type, std::vector<int>& nodes,
                            const std::vector<Eigen::Vector3d>& coords) {
  const int corners = num_corner_nodes(type);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int i = 0; i < corners; ++i) centroid += coords[nodes[i]];
  centroid /= corners;
  double size = 0;
  for (int i = 0; i < corners; ++i) size = std::max(size, (coords[nodes[i]] - centroid).norm());
  const double measure = corner_volume_measure(type, nodes, coords);
  // Written so that NaN coordinates end up as Degenerate.
  if (!(std::abs(measure) > 1e-12 * size * size * size)) return Orientation::Degenerate;
  if (measure > 0) return Orientation::Positive;
  nodes = rebuild(type, nodes, gmsh_edges(type), flip_corners(type));
  return Orientation::Flipped;
}

}  // namespace geardyn::meshio
