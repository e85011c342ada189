#include "geardyn/solid/elements.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>

#include "geardyn/solid/element_kernel.hpp"

namespace geardyn::solid {
namespace {

// Reference coordinates of the corners, then mid-edge nodes as midpoints of the edges listed in
// mesh.hpp (Gmsh order).
struct EdgeList {
  int count;
  std::array<std::array<int, 2>, 12> edges;
};

constexpr EdgeList kTet10Edges{6, {{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}}}};
constexpr EdgeList kHex20Edges{12,
                               {{{0, 1},
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
                                 {6, 7}}}};
constexpr EdgeList kWedge15Edges{
    9, {{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 4}, {2, 5}, {3, 4}, {3, 5}, {4, 5}}}};

Eigen::MatrixXd corners(ElementType type) {
  switch (type) {
    case ElementType::Tet4:
    case ElementType::Tet10: {
      Eigen::MatrixXd c(4, 3);
      c << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
      return c;
    }
    case ElementType::Hex8:
    case ElementType::Hex20: {
      Eigen::MatrixXd c(8, 3);
      c << -1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1;
      return c;
    }
    case ElementType::Wedge6:
    case ElementType::Wedge15: {
      Eigen::MatrixXd c(6, 3);
      c << 0, 0, -1, 1, 0, -1, 0, 1, -1, 0, 0, 1, 1, 0, 1, 0, 1, 1;
      return c;
    }
  }
  return {};
}

const EdgeList* edges_of(ElementType type) {
  switch (type) {
    case ElementType::Tet10:
      return &kTet10Edges;
    case ElementType::Hex20:
      return &kHex20Edges;
    case ElementType::Wedge15:
      return &kWedge15Edges;
    default:
      return nullptr;
  }
}

std::string material_key(const Material& m) {
  if (!m.name.empty()) return fmt::format("materials[{}]", m.name);
  return fmt::format("materials[id {}]", m.id);
}

}  // namespace

std::vector<std::array<int, 2>> element_edges(ElementType type) {
  const EdgeList* e = edges_of(type);
  if (e == nullptr) return {};
  return {e->edges.begin(), e->edges.begin() + e->count};
}

int num_corner_nodes(ElementType type) { return static_cast<int>(corners(type).rows()); }

Eigen::MatrixXd reference_nodes(ElementType type) {
  Eigen::MatrixXd c = corners(type);
  const EdgeList* e = edges_of(type);
  if (e == nullptr) return c;
  Eigen::MatrixXd r(c.rows() + e->count, 3);
  r.topRows(c.rows()) = c;
  for (int k = 0; k < e->count; ++k) {
    r.row(c.rows() + k) = 0.5 * (c.row(e->edges[static_cast<std::size_t>(k)][0]) +
                                 c.row(e->edges[static_cast<std::size_t>(k)][1]));
  }
  return r;
}

void shape_functions(ElementType type, const Eigen::Vector3d& xi, Eigen::VectorXd& N,
                     Eigen::MatrixXd& dN) {
  const int n = num_element_nodes(type);
  N.setZero(n);
  dN.setZero(n, 3);
  const double x = xi[0], y = xi[1], z = xi[2];
  switch (type) {
    case ElementType::Tet4: {
      N << 1 - x - y - z, x, y, z;
      dN << -1, -1, -1, 1, 0, 0, 0, 1, 0, 0, 0, 1;
      return;
    }
    case ElementType::Tet10: {
      // Barycentric L0..L3 with dL/dxi; corners L(2L-1), edges 4 La Lb (Zienkiewicz vol. 1 §6.5).
      const std::array<double, 4> L{1 - x - y - z, x, y, z};
      const std::array<Eigen::RowVector3d, 4> dL{
          Eigen::RowVector3d(-1, -1, -1), Eigen::RowVector3d(1, 0, 0), Eigen::RowVector3d(0, 1, 0),
          Eigen::RowVector3d(0, 0, 1)};
      for (int i = 0; i < 4; ++i) {
        const auto s = static_cast<std::size_t>(i);
        N[i] = L[s] * (2 * L[s] - 1);
        dN.row(i) = (4 * L[s] - 1) * dL[s];
      }
      for (int k = 0; k < 6; ++k) {
        const auto a = static_cast<std::size_t>(kTet10Edges.edges[static_cast<std::size_t>(k)][0]);
        const auto b = static_cast<std::size_t>(kTet10Edges.edges[static_cast<std::size_t>(k)][1]);
        N[4 + k] = 4 * L[a] * L[b];
        dN.row(4 + k) = 4 * (L[a] * dL[b] + L[b] * dL[a]);
      }
      return;
    }
    case ElementType::Hex8: {
      const Eigen::MatrixXd c = corners(type);
      for (int i = 0; i < 8; ++i) {
        const double a = 1 + c(i, 0) * x, b = 1 + c(i, 1) * y, d = 1 + c(i, 2) * z;
        N[i] = a * b * d / 8;
        dN(i, 0) = c(i, 0) * b * d / 8;
        dN(i, 1) = a * c(i, 1) * d / 8;
        dN(i, 2) = a * b * c(i, 2) / 8;
      }
      return;
    }
    case ElementType::Hex20: {
      // 20-node serendipity (Zienkiewicz vol. 1 §6.3): corners
      // (1+x xi)(1+y yi)(1+z zi)(x xi + y yi + z zi - 2)/8, mid-edge nodes with xi_i = 0:
      // (1-x^2)(1+y yi)(1+z zi)/4 (and permutations).
      const Eigen::MatrixXd r = reference_nodes(type);
      for (int i = 0; i < 20; ++i) {
        const double xi_i = r(i, 0), yi = r(i, 1), zi = r(i, 2);
        if (i < 8) {
          const double a = 1 + xi_i * x, b = 1 + yi * y, d = 1 + zi * z;
          const double s = xi_i * x + yi * y + zi * z - 2;
          N[i] = a * b * d * s / 8;
          dN(i, 0) = xi_i * b * d * (s + a) / 8;
          dN(i, 1) = yi * a * d * (s + b) / 8;
          dN(i, 2) = zi * a * b * (s + d) / 8;
        } else if (xi_i == 0) {
          const double b = 1 + yi * y, d = 1 + zi * z;
          N[i] = (1 - x * x) * b * d / 4;
          dN(i, 0) = -2 * x * b * d / 4;
          dN(i, 1) = (1 - x * x) * yi * d / 4;
          dN(i, 2) = (1 - x * x) * b * zi / 4;
        } else if (yi == 0) {
          const double a = 1 + xi_i * x, d = 1 + zi * z;
          N[i] = a * (1 - y * y) * d / 4;
          dN(i, 0) = xi_i * (1 - y * y) * d / 4;
          dN(i, 1) = -2 * y * a * d / 4;
          dN(i, 2) = a * (1 - y * y) * zi / 4;
        } else {
          const double a = 1 + xi_i * x, b = 1 + yi * y;
          N[i] = a * b * (1 - z * z) / 4;
          dN(i, 0) = xi_i * b * (1 - z * z) / 4;
          dN(i, 1) = a * yi * (1 - z * z) / 4;
          dN(i, 2) = -2 * z * a * b / 4;
        }
      }
      return;
    }
    case ElementType::Wedge6: {
      const std::array<double, 3> L{1 - x - y, x, y};
      const std::array<Eigen::RowVector2d, 3> dL{
          Eigen::RowVector2d(-1, -1), Eigen::RowVector2d(1, 0), Eigen::RowVector2d(0, 1)};
      for (int i = 0; i < 3; ++i) {
        const auto s = static_cast<std::size_t>(i);
        for (int top = 0; top < 2; ++top) {
          const double sz = top ? 1.0 : -1.0;
          const int k = i + 3 * top;
          N[k] = L[s] * (1 + sz * z) / 2;
          dN.block<1, 2>(k, 0) = dL[s] * (1 + sz * z) / 2;
          dN(k, 2) = L[s] * sz / 2;
        }
      }
      return;
    }
    case ElementType::Wedge15: {
      // 15-node serendipity wedge: corner i on face zeta = s (s = -1, 1):
      //   L_i (2 L_i - 1)(1 + s zeta)/2 - L_i (1 - zeta^2)/2,
      // triangle-edge nodes 2 La Lb (1 + s zeta), vertical-edge nodes L_i (1 - zeta^2).
      const std::array<double, 3> L{1 - x - y, x, y};
      const std::array<Eigen::RowVector2d, 3> dL{
          Eigen::RowVector2d(-1, -1), Eigen::RowVector2d(1, 0), Eigen::RowVector2d(0, 1)};
      auto tri = [](int corner) { return corner % 3; };
      auto side = [](int corner) { return corner < 3 ? -1.0 : 1.0; };
      for (int k = 0; k < 6; ++k) {
        const auto i = static_cast<std::size_t>(tri(k));
        const double s = side(k);
        const double q = L[i] * (2 * L[i] - 1);
        const Eigen::RowVector2d dq = (4 * L[i] - 1) * dL[i];
        N[k] = q * (1 + s * z) / 2 - L[i] * (1 - z * z) / 2;
        dN.block<1, 2>(k, 0) = dq * (1 + s * z) / 2 - dL[i] * (1 - z * z) / 2;
        dN(k, 2) = q * s / 2 + L[i] * z;
      }
      for (int e = 0; e < 9; ++e) {
        const int a = kWedge15Edges.edges[static_cast<std::size_t>(e)][0];
        const int b = kWedge15Edges.edges[static_cast<std::size_t>(e)][1];
        const int k = 6 + e;
        const auto ia = static_cast<std::size_t>(tri(a)), ib = static_cast<std::size_t>(tri(b));
        if (ia == ib) {  // vertical edge
          N[k] = L[ia] * (1 - z * z);
          dN.block<1, 2>(k, 0) = dL[ia] * (1 - z * z);
          dN(k, 2) = -2 * z * L[ia];
        } else {
          const double s = side(a);
          N[k] = 2 * L[ia] * L[ib] * (1 + s * z);
          dN.block<1, 2>(k, 0) = 2 * (L[ia] * dL[ib] + L[ib] * dL[ia]) * (1 + s * z);
          dN(k, 2) = 2 * L[ia] * L[ib] * s;
        }
      }
      return;
    }
  }
}

Eigen::Matrix<double, 6, 6> elasticity_matrix(double E, double nu) {
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu = E / (2 * (1 + nu));
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
  D.topLeftCorner<3, 3>().setConstant(lambda);
  D.topLeftCorner<3, 3>().diagonal().array() += 2 * mu;
  D.bottomRightCorner<3, 3>().diagonal().setConstant(mu);
  return D;
}

void check_material(const Material& m) {
  const auto bad = [&](const char* field, const char* expected, double value) {
    throw InputError(m.where, fmt::format("{}.{}", material_key(m), field), expected,
                     fmt::format("{}", value));
  };
  if (!std::isfinite(m.E) || m.E <= 0) bad("E", "a Young's modulus > 0", m.E);
  if (!std::isfinite(m.nu) || m.nu <= -1 || m.nu >= 0.5) {
    bad("nu", "a Poisson's ratio in (-1, 0.5)", m.nu);
  }
  if (!std::isfinite(m.rho) || m.rho < 0) bad("rho", "a density >= 0", m.rho);
}

ElementQuality element_quality(ElementType type, const std::vector<Eigen::Vector3d>& x) {
  const ElementKernel& kernel = element_kernel(type);
  kernel.check_node_count(static_cast<int>(x.size()), 0, {});
  return kernel.quality(x.data());
}

double element_min_jacobian(ElementType type, const std::vector<Eigen::Vector3d>& x) {
  return element_quality(type, x).min_ratio;
}

ElementMatrices element_matrices(ElementType type, const std::vector<Eigen::Vector3d>& x,
                                 const Material& material, long element_id,
                                 const SourceLocation& where) {
  check_material(material);
  const ElementKernel& kernel = element_kernel(type);
  kernel.check_node_count(static_cast<int>(x.size()), element_id, where);
  ElementMatrices out;
  Eigen::MatrixXd m;
  out.volume = kernel.compute(x.data(), material.E, material.nu, element_id, where, out.K, &m);
  const int n = kernel.nodes();
  out.M.setZero(3 * n, 3 * n);
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      const double v = material.rho * m(a, b);
      for (int i = 0; i < 3; ++i) out.M(3 * a + i, 3 * b + i) = v;
    }
  }
  return out;
}

ElementMatrices element_matrices(const Mesh& mesh, int index) {
  if (index < 0 || index >= mesh.num_elements()) {
    throw InputError({}, "elements",
                     fmt::format("an element index in [0, {})", mesh.num_elements()),
                     fmt::format("{}", index));
  }
  const Element& e = mesh.elements[static_cast<std::size_t>(index)];
  const std::string key = fmt::format("elements[id {}]", e.id);
  if (e.material < 0 || e.material >= static_cast<int>(mesh.materials.size())) {
    throw InputError(e.where, key + ".material",
                     fmt::format("a material index in [0, {})", mesh.materials.size()),
                     fmt::format("{}", e.material));
  }
  std::vector<Eigen::Vector3d> x;
  x.reserve(e.nodes.size());
  for (int node : e.nodes) {
    if (node < 0 || node >= mesh.num_nodes()) {
      throw InputError(e.where, key + ".nodes",
                       fmt::format("node indices in [0, {})", mesh.num_nodes()),
                       fmt::format("{}", node));
    }
    x.push_back(mesh.coords[static_cast<std::size_t>(node)]);
  }
  return element_matrices(e.type, x, mesh.materials[static_cast<std::size_t>(e.material)], e.id,
                          e.where);
}

Eigen::MatrixXd element_shape_mass(ElementType type, const std::vector<Eigen::Vector3d>& x,
                                   long element_id, const SourceLocation& where) {
  const ElementKernel& kernel = element_kernel(type);
  kernel.check_node_count(static_cast<int>(x.size()), element_id, where);
  Eigen::MatrixXd K, m;
  kernel.compute(x.data(), 1.0, 0.0, element_id, where, K, &m);
  return m;
}

}  // namespace geardyn::solid
