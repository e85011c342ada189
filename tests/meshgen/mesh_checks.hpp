#pragma once
// Geometric checks of solid meshes for the generator tests: isoparametric shape functions of the
// element types of solid/mesh.hpp (Gmsh node order), Jacobian determinants, exact element
// volumes, rotations.
//
// Shape functions (standard Lagrange / serendipity, e.g. Zienkiewicz & Taylor, The Finite
// Element Method vol. 1, ch. 6): tet10 with barycentrics L0 = 1 - xi - eta - zeta, L1 = xi,
// L2 = eta, L3 = zeta; hex20 serendipity on [-1,1]^3; wedge15 = quadratic triangle x quadratic
// line serendipity. Mid-edge nodes sit at the reference midpoint of the edges listed in
// solid/mesh.hpp, so an error in that ordering shows up as a wrong volume or a sign change.
// Derivatives are central differences with step 1/4: every shape function is at most quadratic
// in each reference coordinate separately, so the difference is exact up to round-off.
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "geardyn/solid/mesh.hpp"

namespace geardyn::test {

using solid::ElementType;

inline std::vector<std::pair<int, int>> mid_edges(ElementType t) {
  switch (t) {
    case ElementType::Tet10:
      return {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}};
    case ElementType::Hex20:
      return {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
              {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
    case ElementType::Wedge15:
      return {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 4}, {2, 5}, {3, 4}, {3, 5}, {4, 5}};
    default:
      return {};
  }
}

inline std::vector<Eigen::Vector3d> reference_nodes(ElementType t) {
  std::vector<Eigen::Vector3d> corners;
  switch (t) {
    case ElementType::Tet4:
    case ElementType::Tet10:
      corners = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
      break;
    case ElementType::Hex8:
    case ElementType::Hex20:
      corners = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
      break;
    case ElementType::Wedge6:
    case ElementType::Wedge15:
      corners = {{0, 0, -1}, {1, 0, -1}, {0, 1, -1}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
      break;
  }
  for (const auto& [a, b] : mid_edges(t)) corners.push_back(0.5 * (corners[a] + corners[b]));
  return corners;
}

inline Eigen::VectorXd shape(ElementType t, const Eigen::Vector3d& p) {
  const std::vector<Eigen::Vector3d> ref = reference_nodes(t);
  const int n = solid::num_element_nodes(t);
  Eigen::VectorXd N(n);
  const double xi = p.x(), eta = p.y(), zeta = p.z();
  switch (t) {
    case ElementType::Tet4:
    case ElementType::Tet10: {
      const std::array<double, 4> L{1 - xi - eta - zeta, xi, eta, zeta};
      if (t == ElementType::Tet4) {
        for (int i = 0; i < 4; ++i) N(i) = L[i];
        break;
      }
      for (int i = 0; i < 4; ++i) N(i) = L[i] * (2 * L[i] - 1);
      const auto edges = mid_edges(t);
      for (std::size_t k = 0; k < edges.size(); ++k)
        N(4 + static_cast<int>(k)) = 4 * L[edges[k].first] * L[edges[k].second];
      break;
    }
    case ElementType::Hex8:
      for (int i = 0; i < 8; ++i)
        N(i) = 0.125 * (1 + xi * ref[i].x()) * (1 + eta * ref[i].y()) * (1 + zeta * ref[i].z());
      break;
    case ElementType::Hex20:
      for (int i = 0; i < 20; ++i) {
        const Eigen::Vector3d& r = ref[i];
        if (i < 8) {
          N(i) = 0.125 * (1 + xi * r.x()) * (1 + eta * r.y()) * (1 + zeta * r.z()) *
                 (xi * r.x() + eta * r.y() + zeta * r.z() - 2);
        } else if (r.x() == 0) {
          N(i) = 0.25 * (1 - xi * xi) * (1 + eta * r.y()) * (1 + zeta * r.z());
        } else if (r.y() == 0) {
          N(i) = 0.25 * (1 + xi * r.x()) * (1 - eta * eta) * (1 + zeta * r.z());
        } else {
          N(i) = 0.25 * (1 + xi * r.x()) * (1 + eta * r.y()) * (1 - zeta * zeta);
        }
      }
      break;
    case ElementType::Wedge6:
    case ElementType::Wedge15: {
      const std::array<double, 3> L{1 - xi - eta, xi, eta};
      if (t == ElementType::Wedge6) {
        for (int i = 0; i < 6; ++i) N(i) = L[i % 3] * 0.5 * (1 + zeta * ref[i].z());
        break;
      }
      for (int i = 0; i < 6; ++i)
        N(i) = 0.5 * L[i % 3] * (2 * L[i % 3] - 1) * (1 + zeta * ref[i].z()) -
               0.5 * L[i % 3] * (1 - zeta * zeta);
      const auto edges = mid_edges(t);
      for (std::size_t k = 0; k < edges.size(); ++k) {
        const auto [a, b] = edges[k];
        const int i = 6 + static_cast<int>(k);
        if (b == a + 3)
          N(i) = L[a % 3] * (1 - zeta * zeta);
        else
          N(i) = 2 * L[a % 3] * L[b % 3] * (1 + zeta * ref[i].z());
      }
      break;
    }
  }
  return N;
}

inline Eigen::Matrix3d jacobian(const solid::Mesh& mesh, const solid::Element& e,
                                const Eigen::Vector3d& p) {
  constexpr double h = 0.25;
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int d = 0; d < 3; ++d) {
    const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(d);
    const Eigen::VectorXd dN = (shape(e.type, p + step) - shape(e.type, p - step)) / (2 * h);
    for (std::size_t i = 0; i < e.nodes.size(); ++i)
      J.col(d) += dN(static_cast<int>(i)) * mesh.coords[static_cast<std::size_t>(e.nodes[i])];
  }
  return J;
}

struct QuadraturePoint {
  Eigen::Vector3d p;
  double w;
};

/// Gauss rules exact for det J of the quadratic elements: tet via the collapsed (Duffy) map of
/// a 3x3x3 Gauss-Legendre cube rule (exact to degree 5 in the collapsed variable); hex 4x4x4;
/// wedge: a 7-point degree-5 triangle rule (Dunavant) x 4-point Gauss.
inline std::vector<QuadraturePoint> quadrature(ElementType t) {
  const std::array<double, 3> g3{-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const std::array<double, 3> w3{5.0 / 9, 8.0 / 9, 5.0 / 9};
  const double a = std::sqrt(3.0 / 7 - 2.0 / 7 * std::sqrt(1.2));
  const double c = std::sqrt(3.0 / 7 + 2.0 / 7 * std::sqrt(1.2));
  const std::array<double, 4> g4{-c, -a, a, c};
  const std::array<double, 4> w4{(18 - std::sqrt(30.0)) / 36, (18 + std::sqrt(30.0)) / 36,
                                 (18 + std::sqrt(30.0)) / 36, (18 - std::sqrt(30.0)) / 36};
  std::vector<QuadraturePoint> q;
  switch (t) {
    case ElementType::Tet4:
    case ElementType::Tet10:
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          for (int k = 0; k < 3; ++k) {
            const double u = 0.5 * (1 + g3[i]), v = 0.5 * (1 + g3[j]), w = 0.5 * (1 + g3[k]);
            q.push_back({{u, v * (1 - u), w * (1 - u) * (1 - v)},
                         w3[i] * w3[j] * w3[k] / 8 * (1 - u) * (1 - u) * (1 - v)});
          }
      break;
    case ElementType::Hex8:
    case ElementType::Hex20:
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
          for (int k = 0; k < 4; ++k) q.push_back({{g4[i], g4[j], g4[k]}, w4[i] * w4[j] * w4[k]});
      break;
    case ElementType::Wedge6:
    case ElementType::Wedge15: {
      const double a1 = 0.059715871789770, b1 = 0.470142064105115;
      const double a2 = 0.797426985353087, b2 = 0.101286507323456;
      const double wa = 0.225, wb = 0.132394152788506, wc = 0.125939180544827;
      const std::vector<std::array<double, 3>> tri{
          {1.0 / 3, 1.0 / 3, wa}, {a1, b1, wb}, {b1, a1, wb}, {b1, b1, wb},
          {a2, b2, wc},           {b2, a2, wc}, {b2, b2, wc}};
      for (const auto& [x, y, w] : tri)
        for (int k = 0; k < 4; ++k) q.push_back({{x, y, g4[k]}, 0.5 * w * w4[k]});
      break;
    }
  }
  return q;
}

inline double element_volume(const solid::Mesh& mesh, const solid::Element& e) {
  double v = 0;
  for (const QuadraturePoint& q : quadrature(e.type))
    v += q.w * jacobian(mesh, e, q.p).determinant();
  return v;
}

/// Smallest det J over the quadrature points and the nodes, relative to the mean det J
/// (volume / reference volume): > 0 for a valid (non-inverted) element.
inline double min_relative_jacobian(const solid::Mesh& mesh, const solid::Element& e) {
  double reference_volume = 8.0;
  if (e.type == ElementType::Tet4 || e.type == ElementType::Tet10) reference_volume = 1.0 / 6;
  if (e.type == ElementType::Wedge6 || e.type == ElementType::Wedge15) reference_volume = 1.0;
  const double mean = element_volume(mesh, e) / reference_volume;
  double lowest = std::numeric_limits<double>::max();
  for (const QuadraturePoint& q : quadrature(e.type))
    lowest = std::min(lowest, jacobian(mesh, e, q.p).determinant());
  for (const Eigen::Vector3d& p : reference_nodes(e.type))
    lowest = std::min(lowest, jacobian(mesh, e, p).determinant());
  return lowest / std::abs(mean);
}

inline Eigen::Vector3d rotate_z(const Eigen::Vector3d& x, double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()) * x;
}

inline double radius(const Eigen::Vector3d& x) { return std::hypot(x.x(), x.y()); }

}  // namespace geardyn::test
