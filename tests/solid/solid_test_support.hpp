#pragma once
// Shared helpers of the solid tests: material, element types, an independent high-order
// quadrature and a solve with prescribed nodal displacements.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <functional>
#include <vector>

#include "geardyn/solid/assembly.hpp"
#include "geardyn/solid/elements.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::solid::test {

inline Material steel() {
  Material m;
  m.name = "steel";
  m.id = 1;
  m.E = 210e9;
  m.nu = 0.3;
  m.rho = 7850;
  return m;
}

inline std::vector<ElementType> all_types() {
  return {ElementType::Tet4,  ElementType::Tet10,  ElementType::Hex8,
          ElementType::Hex20, ElementType::Wedge6, ElementType::Wedge15};
}

inline double reference_volume(ElementType t) {
  switch (t) {
    case ElementType::Tet4:
    case ElementType::Tet10:
      return 1.0 / 6.0;
    case ElementType::Hex8:
    case ElementType::Hex20:
      return 8.0;
    default:
      return 1.0;
  }
}

/// n-point Gauss-Legendre rule on [0, 1] by Golub & Welsch (1969): nodes are the eigenvalues of
/// the Jacobi matrix of the Legendre polynomials, weights the squared first eigenvector entries.
inline void gauss_01(int n, Eigen::VectorXd& x, Eigen::VectorXd& w) {
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, n);
  for (int k = 1; k < n; ++k) {
    const double b = k / std::sqrt(4.0 * k * k - 1.0);
    T(k, k - 1) = T(k - 1, k) = b;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(T);
  x = (eig.eigenvalues().array() + 1.0) / 2.0;
  w = eig.eigenvectors().row(0).transpose().array().square();  // sums to 1 on [0, 1]
}

/// m_ab = ∫ N_a N_b dV by a collapsed (Duffy) tensor Gauss rule with n points per direction:
/// exact for polynomial integrands of degree <= 2n - 1 - 2 in the collapsed variables.
inline Eigen::MatrixXd shape_mass_reference(ElementType type, const std::vector<Eigen::Vector3d>& x,
                                            int n) {
  Eigen::VectorXd g, w;
  gauss_01(n, g, w);
  const int nn = num_element_nodes(type);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(nn, nn);
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) {
        const double u = g[i], v = g[j], s = g[k];
        double weight = w[i] * w[j] * w[k];
        Eigen::Vector3d xi;
        switch (type) {
          case ElementType::Hex8:
          case ElementType::Hex20:
            xi = Eigen::Vector3d(2 * u - 1, 2 * v - 1, 2 * s - 1);
            weight *= 8;
            break;
          case ElementType::Tet4:
          case ElementType::Tet10:
            xi = Eigen::Vector3d(u, v * (1 - u), s * (1 - u) * (1 - v));
            weight *= (1 - u) * (1 - u) * (1 - v);
            break;
          default:  // wedges: collapsed triangle x line
            xi = Eigen::Vector3d(u, v * (1 - u), 2 * s - 1);
            weight *= (1 - u) * 2;
            break;
        }
        shape_functions(type, xi, N, dN);
        Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
        for (int a = 0; a < nn; ++a) J += x[static_cast<std::size_t>(a)] * dN.row(a);
        m += weight * J.determinant() * N * N.transpose();
      }
    }
  }
  return m;
}

/// Static solution of a system without constraints: the nodes flagged in `prescribed` get
/// u = field(x), the others are solved from K u = 0 (K_ff u_f = -K_fp u_p). Returns the reduced
/// displacement vector.
inline Eigen::VectorXd solve_with_prescribed(
    const SolidSystem& sys, const Mesh& mesh, const std::vector<char>& prescribed,
    const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& field) {
  const int n = sys.num_dofs();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  std::vector<int> free_index(static_cast<std::size_t>(n), -1);
  std::vector<char> is_prescribed(static_cast<std::size_t>(n), 0);
  for (int node = 0; node < mesh.num_nodes(); ++node) {
    if (!prescribed[static_cast<std::size_t>(node)]) continue;
    const Eigen::Vector3d value = field(mesh.coords[static_cast<std::size_t>(node)]);
    for (int c = 0; c < 3; ++c) {
      const int d = sys.node_dof(node, c);
      u[d] = value[c];
      is_prescribed[static_cast<std::size_t>(d)] = 1;
    }
  }
  int nf = 0;
  for (int d = 0; d < n; ++d) {
    if (!is_prescribed[static_cast<std::size_t>(d)]) free_index[static_cast<std::size_t>(d)] = nf++;
  }
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nf);
  for (int col = 0; col < n; ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(sys.K, col); it; ++it) {
      const int fr = free_index[static_cast<std::size_t>(it.row())];
      if (fr < 0) continue;
      const int fc = free_index[static_cast<std::size_t>(col)];
      if (fc >= 0) {
        t.emplace_back(fr, fc, it.value());
      } else {
        rhs[fr] -= it.value() * u[col];
      }
    }
  }
  Eigen::SparseMatrix<double> Kff(nf, nf);
  Kff.setFromTriplets(t.begin(), t.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(Kff);
  const Eigen::VectorXd uf = ldlt.solve(rhs);
  for (int d = 0; d < n; ++d) {
    const int f = free_index[static_cast<std::size_t>(d)];
    if (f >= 0) u[d] = uf[f];
  }
  return u;
}

}  // namespace geardyn::solid::test
