#include "geardyn/acoustics/surface.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace geardyn::acoustics {

double Surface::area() const {
  double sum = 0;
  for (const SurfaceFace& f : faces) sum += f.area;
  return sum;
}

namespace {

using solid::ElementType;

struct QuadraturePoint {
  double xi, eta, weight;
};

// 7-point degree-5 rule on the reference triangle (0,0) (1,0) (0,1), weights summing to 1/2
// (Dunavant 1985).
const std::vector<QuadraturePoint>& triangle_rule() {
  static const std::vector<QuadraturePoint> rule = [] {
    const double s = std::sqrt(15.0);
    const double a1 = (6 - s) / 21, b1 = (9 + 2 * s) / 21, w1 = (155 - s) / 2400;
    const double a2 = (6 + s) / 21, b2 = (9 - 2 * s) / 21, w2 = (155 + s) / 2400;
    return std::vector<QuadraturePoint>{{1.0 / 3, 1.0 / 3, 9.0 / 80},
                                        {a1, a1, w1},
                                        {b1, a1, w1},
                                        {a1, b1, w1},
                                        {a2, a2, w2},
                                        {b2, a2, w2},
                                        {a2, b2, w2}};
  }();
  return rule;
}

// 3 x 3 Gauss-Legendre on [-1, 1]^2.
const std::vector<QuadraturePoint>& quad_rule() {
  static const std::vector<QuadraturePoint> rule = [] {
    const double g = std::sqrt(0.6);
    const std::array<double, 3> x{-g, 0.0, g}, w{5.0 / 9, 8.0 / 9, 5.0 / 9};
    std::vector<QuadraturePoint> r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.push_back({x[i], x[j], w[i] * w[j]});
    return r;
  }();
  return rule;
}

bool is_triangle(int n) { return n == 3 || n == 6; }

// Shape functions of a face with n = 3, 6 (triangle) or 4, 8 (quad) nodes in VTK order, and their
// derivatives with respect to the reference coordinates (xi, eta).
void face_shape(int n, double x, double y, double* N, double* dx, double* dy) {
  if (n == 3) {
    N[0] = 1 - x - y, N[1] = x, N[2] = y;
    dx[0] = -1, dx[1] = 1, dx[2] = 0;
    dy[0] = -1, dy[1] = 0, dy[2] = 1;
  } else if (n == 6) {
    const double L[3] = {1 - x - y, x, y}, Lx[3] = {-1, 1, 0}, Ly[3] = {-1, 0, 1};
    for (int i = 0; i < 3; ++i) {
      N[i] = L[i] * (2 * L[i] - 1);
      dx[i] = (4 * L[i] - 1) * Lx[i];
      dy[i] = (4 * L[i] - 1) * Ly[i];
      const int j = (i + 1) % 3;
      N[3 + i] = 4 * L[i] * L[j];
      dx[3 + i] = 4 * (Lx[i] * L[j] + L[i] * Lx[j]);
      dy[3 + i] = 4 * (Ly[i] * L[j] + L[i] * Ly[j]);
    }
  } else {
    static constexpr double s[4] = {-1, 1, 1, -1}, t[4] = {-1, -1, 1, 1};
    for (int i = 0; i < 4; ++i) {
      const double a = 1 + s[i] * x, b = 1 + t[i] * y;
      if (n == 4) {
        N[i] = a * b / 4, dx[i] = s[i] * b / 4, dy[i] = t[i] * a / 4;
      } else {
        N[i] = a * b * (s[i] * x + t[i] * y - 1) / 4;
        dx[i] = s[i] * b * (2 * s[i] * x + t[i] * y) / 4;
        dy[i] = t[i] * a * (s[i] * x + 2 * t[i] * y) / 4;
      }
    }
    if (n == 8) {
      N[4] = (1 - x * x) * (1 - y) / 2, dx[4] = -x * (1 - y), dy[4] = -(1 - x * x) / 2;
      N[5] = (1 + x) * (1 - y * y) / 2, dx[5] = (1 - y * y) / 2, dy[5] = -(1 + x) * y;
      N[6] = (1 - x * x) * (1 + y) / 2, dx[6] = -x * (1 + y), dy[6] = (1 - x * x) / 2;
      N[7] = (1 - x) * (1 - y * y) / 2, dx[7] = -(1 - y * y) / 2, dy[7] = -(1 - x) * y;
    }
  }
}

struct FaceGeometry {
  double area = 0;
  Eigen::Vector3d normal_integral = Eigen::Vector3d::Zero();  // int n dA
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();           // int x dA
  std::vector<double> weight;                                 // lumped area per node
  std::vector<Eigen::Vector3d> weighted_normal;               // int w_i n dA per node
};

FaceGeometry face_geometry(const std::vector<Eigen::Vector3d>& x) {
  const int n = static_cast<int>(x.size());
  const bool quadratic = n == 6 || n == 8;
  FaceGeometry g;
  std::vector<double> row(static_cast<std::size_t>(n), 0.0), square(row);
  std::vector<Eigen::Vector3d> row_n(static_cast<std::size_t>(n), Eigen::Vector3d::Zero()),
      square_n(row_n);
  double N[8], dx[8], dy[8];
  for (const QuadraturePoint& p : is_triangle(n) ? triangle_rule() : quad_rule()) {
    face_shape(n, p.xi, p.eta, N, dx, dy);
    Eigen::Vector3d point = Eigen::Vector3d::Zero(), tx = point, ty = point;
    for (int i = 0; i < n; ++i) {
      point += N[i] * x[static_cast<std::size_t>(i)];
      tx += dx[i] * x[static_cast<std::size_t>(i)];
      ty += dy[i] * x[static_cast<std::size_t>(i)];
    }
    const Eigen::Vector3d dA = tx.cross(ty) * p.weight;  // n dA
    const double da = dA.norm();
    g.area += da;
    g.normal_integral += dA;
    g.moment += point * da;
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      row[k] += N[i] * da, row_n[k] += N[i] * dA;
      square[k] += N[i] * N[i] * da, square_n[k] += N[i] * N[i] * dA;
    }
  }
  if (!quadratic) {
    g.weight = std::move(row);
    g.weighted_normal = std::move(row_n);
  } else {  // diagonal scaling (Hinton, Rock and Zienkiewicz 1976)
    double total = 0;
    for (double v : square) total += v;
    const double scale = total > 0 ? g.area / total : 0.0;
    for (std::size_t k = 0; k < square.size(); ++k) {
      g.weight.push_back(square[k] * scale);
      g.weighted_normal.push_back(square_n[k] * scale);
    }
  }
  return g;
}

// Local corner numbers of each face of an element type (solid/mesh.hpp, Gmsh ordering).
const std::vector<std::vector<int>>& face_corners(ElementType type) {
  static const std::vector<std::vector<int>> tet{{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {0, 2, 3}};
  static const std::vector<std::vector<int>> hex{{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  static const std::vector<std::vector<int>> wedge{
      {0, 1, 2}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
  switch (type) {
    case ElementType::Tet4:
    case ElementType::Tet10:
      return tet;
    case ElementType::Hex8:
    case ElementType::Hex20:
      return hex;
    case ElementType::Wedge6:
    case ElementType::Wedge15:
      return wedge;
  }
  return tet;
}

// Mid-edge nodes of the quadratic types: edge (a, b) -> local node (solid/mesh.hpp).
int mid_edge_node(ElementType type, int a, int b) {
  using Edge = std::array<int, 3>;  // corner, corner, mid-edge node
  static const std::vector<Edge> tet10{{0, 1, 4}, {1, 2, 5}, {2, 0, 6},
                                       {0, 3, 7}, {2, 3, 8}, {1, 3, 9}};
  static const std::vector<Edge> hex20{{0, 1, 8},  {0, 3, 9},  {0, 4, 10}, {1, 2, 11},
                                       {1, 5, 12}, {2, 3, 13}, {2, 6, 14}, {3, 7, 15},
                                       {4, 5, 16}, {4, 7, 17}, {5, 6, 18}, {6, 7, 19}};
  static const std::vector<Edge> wedge15{{0, 1, 6},  {0, 2, 7},  {0, 3, 8},  {1, 2, 9}, {1, 4, 10},
                                         {2, 5, 11}, {3, 4, 12}, {3, 5, 13}, {4, 5, 14}};
  const std::vector<Edge>& edges = type == ElementType::Tet10   ? tet10
                                   : type == ElementType::Hex20 ? hex20
                                                                : wedge15;
  for (const Edge& e : edges)
    if ((e[0] == a && e[1] == b) || (e[0] == b && e[1] == a)) return e[2];
  return -1;
}

bool is_quadratic(ElementType type) {
  return type == ElementType::Tet10 || type == ElementType::Hex20 || type == ElementType::Wedge15;
}

// The mesh node indices of face `f` of element `e`: corners in the given cyclic order, then the
// mid-edge nodes of consecutive corner pairs.
std::vector<int> face_nodes(const solid::Element& e, const std::vector<int>& corners) {
  std::vector<int> nodes;
  for (int c : corners) nodes.push_back(e.nodes[static_cast<std::size_t>(c)]);
  if (is_quadratic(e.type)) {
    const std::size_t k = corners.size();
    for (std::size_t i = 0; i < k; ++i)
      nodes.push_back(e.nodes[static_cast<std::size_t>(
          mid_edge_node(e.type, corners[i], corners[(i + 1) % k]))]);
  }
  return nodes;
}

struct FaceRef {
  std::array<int, 4> key;  // sorted corner nodes, padded with INT_MAX
  int element;
  int face;
};

std::vector<FaceRef> exterior_faces(const solid::Mesh& mesh) {
  std::vector<FaceRef> refs;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const solid::Element& element = mesh.elements[static_cast<std::size_t>(e)];
    if (static_cast<int>(element.nodes.size()) != solid::num_element_nodes(element.type))
      throw std::invalid_argument(fmt::format("mesh element {} (id {}): {} nodes for a {}", e,
                                              element.id, element.nodes.size(),
                                              solid::to_string(element.type)));
    const auto& faces = face_corners(element.type);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      constexpr int pad = std::numeric_limits<int>::max();
      FaceRef r{{pad, pad, pad, pad}, e, static_cast<int>(f)};
      for (std::size_t i = 0; i < faces[f].size(); ++i)
        r.key[i] = element.nodes[static_cast<std::size_t>(faces[f][i])];
      std::sort(r.key.begin(), r.key.end());
      refs.push_back(r);
    }
  }
  std::sort(refs.begin(), refs.end(), [](const FaceRef& a, const FaceRef& b) {
    return a.key != b.key ? a.key < b.key : a.element < b.element;
  });
  std::vector<FaceRef> exterior;
  for (std::size_t i = 0; i < refs.size();) {
    std::size_t j = i + 1;
    while (j < refs.size() && refs[j].key == refs[i].key) ++j;
    if (j == i + 1) exterior.push_back(refs[i]);
    i = j;
  }
  return exterior;
}

std::vector<Eigen::Vector3d> coordinates(const solid::Mesh& mesh, const std::vector<int>& nodes) {
  std::vector<Eigen::Vector3d> x;
  for (int n : nodes) x.push_back(mesh.coords[static_cast<std::size_t>(n)]);
  return x;
}

// An outward-oriented face of the surface, its nodes still mesh indices.
SurfaceFace oriented_face(const solid::Mesh& mesh, const FaceRef& ref) {
  const solid::Element& element = mesh.elements[static_cast<std::size_t>(ref.element)];
  std::vector<int> corners = face_corners(element.type)[static_cast<std::size_t>(ref.face)];
  std::vector<int> nodes = face_nodes(element, corners);
  FaceGeometry g = face_geometry(coordinates(mesh, nodes));
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  const int n_corners = element.type == ElementType::Tet4 || element.type == ElementType::Tet10 ? 4
                        : element.type == ElementType::Hex8 || element.type == ElementType::Hex20
                            ? 8
                            : 6;
  for (int c = 0; c < n_corners; ++c)
    centre += mesh.coords[static_cast<std::size_t>(element.nodes[static_cast<std::size_t>(c)])];
  centre /= n_corners;
  const Eigen::Vector3d centroid = g.area > 0 ? Eigen::Vector3d(g.moment / g.area) : centre;
  if (g.normal_integral.dot(centroid - centre) < 0) {  // reverse the corner cycle
    std::reverse(corners.begin() + 1, corners.end());
    nodes = face_nodes(element, corners);
    g = face_geometry(coordinates(mesh, nodes));
  }
  SurfaceFace face;
  face.nodes = std::move(nodes);
  face.element = ref.element;
  face.area = g.area;
  const double norm = g.normal_integral.norm();
  face.normal = norm > 0 ? Eigen::Vector3d(g.normal_integral / norm) : Eigen::Vector3d::Zero();
  face.centroid = centroid;
  face.node_weight = std::move(g.weight);
  return face;
}

}  // namespace

Surface exterior_surface(const solid::Mesh& mesh, const std::vector<int>& node_set) {
  const std::vector<FaceRef> exterior = exterior_faces(mesh);
  if (exterior.empty())
    throw std::invalid_argument(
        fmt::format("the mesh ({} elements) has no exterior face", mesh.num_elements()));
  std::vector<char> in_set(static_cast<std::size_t>(mesh.num_nodes()), node_set.empty() ? 1 : 0);
  for (int n : node_set) {
    if (n < 0 || n >= mesh.num_nodes())
      throw std::invalid_argument(
          fmt::format("node set: node index {} outside the mesh's {} nodes", n, mesh.num_nodes()));
    in_set[static_cast<std::size_t>(n)] = 1;
  }
  std::vector<char> on_exterior(in_set.size(), 0);
  Surface s;
  std::vector<int> surface_index(in_set.size(), -1);
  for (const FaceRef& ref : exterior) {
    const solid::Element& element = mesh.elements[static_cast<std::size_t>(ref.element)];
    const std::vector<int> nodes =
        face_nodes(element, face_corners(element.type)[static_cast<std::size_t>(ref.face)]);
    bool all = true;
    for (int n : nodes) {
      on_exterior[static_cast<std::size_t>(n)] = 1;
      all = all && in_set[static_cast<std::size_t>(n)] != 0;
    }
    if (!all) continue;
    s.faces.push_back(oriented_face(mesh, ref));
    for (int n : nodes) surface_index[static_cast<std::size_t>(n)] = 0;
  }
  if (s.faces.empty()) {
    std::size_t set_size = 0, set_on_exterior = 0;
    for (std::size_t n = 0; n < in_set.size(); ++n) {
      set_size += static_cast<std::size_t>(in_set[n]);
      set_on_exterior += static_cast<std::size_t>(in_set[n] && on_exterior[n]);
    }
    throw std::invalid_argument(fmt::format(
        "the node set has {} nodes, {} of them on the exterior surface of the mesh ({}): no "
        "exterior face has all its nodes in the set (it must cover whole element faces of the "
        "outer surface, mid-side nodes included)",
        set_size, set_on_exterior,
        set_on_exterior == 0 ? "none lies on the exterior" : "too few lie on the exterior"));
  }
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (surface_index[static_cast<std::size_t>(n)] == 0) {
      surface_index[static_cast<std::size_t>(n)] = static_cast<int>(s.nodes.size());
      s.nodes.push_back(n);
    }
  const int count = s.num_nodes();
  s.node_area = Eigen::VectorXd::Zero(count);
  s.node_normal = Eigen::Matrix3Xd::Zero(3, count);
  for (SurfaceFace& face : s.faces) {
    const FaceGeometry g = face_geometry(coordinates(mesh, face.nodes));
    for (std::size_t k = 0; k < face.nodes.size(); ++k) {
      const int i = surface_index[static_cast<std::size_t>(face.nodes[k])];
      face.nodes[k] = i;
      s.node_area[i] += g.weight[k];
      s.node_normal.col(i) += g.weighted_normal[k];
    }
  }
  for (int i = 0; i < count; ++i) {
    const double norm = s.node_normal.col(i).norm();
    if (norm > 0) s.node_normal.col(i) /= norm;
  }
  return s;
}

std::vector<int> surface_dof_rows(const solid::Mesh& mesh, const Surface& s,
                                  const std::vector<solid::DofInfo>& dofs) {
  std::unordered_map<long, std::array<int, 3>> rows;
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const solid::DofInfo& d = dofs[k];
    if (d.component < 0 || d.component > 2) continue;
    auto [it, inserted] = rows.try_emplace(d.node_id, std::array<int, 3>{-1, -1, -1});
    it->second[static_cast<std::size_t>(d.component)] = static_cast<int>(k);
  }
  std::vector<int> out;
  out.reserve(3 * s.nodes.size());
  for (int node : s.nodes) {
    const long id = mesh.node_ids.empty() ? node : mesh.node_ids[static_cast<std::size_t>(node)];
    const auto found = rows.find(id);
    for (int c = 0; c < 3; ++c) {
      const int row = found == rows.end() ? -1 : found->second[static_cast<std::size_t>(c)];
      if (row < 0)
        throw std::invalid_argument(fmt::format(
            "surface node {} (mesh node index {}) has no {} among the {} DOFs given (constrained "
            "or not part of the component?)",
            id, node,
            c == 0   ? "ux"
            : c == 1 ? "uy"
                     : "uz",
            dofs.size()));
      out.push_back(row);
    }
  }
  return out;
}

}  // namespace geardyn::acoustics
