#pragma once
// Small models for the reduction tests: spring-mass chains and a 3-D Timoshenko beam built from
// fe::timoshenko_beam, each with its DofInfo.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <vector>

#include "geardyn/fe/timoshenko_beam.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::reduce::test {

struct TestModel {
  Eigen::SparseMatrix<double> K, M;
  std::vector<solid::DofInfo> dofs;
};

/// Free-free chain of n masses along x, node ids 1..n at x = k, one DOF (ux) each:
///   (m_0)--k_0--(m_1)--k_1-- ... --(m_{n-1})
/// masses m_i = 1 + 0.1 i [kg], springs k_i = 1000 (1 + 0.05 i) [N/m] (unequal, so that no two
/// eigenvalues coincide). A spring with k_i = 0 (`cut` = i) disconnects the chain there.
inline TestModel chain(int n, int cut = -1) {
  TestModel t;
  std::vector<Eigen::Triplet<double>> tk, tm;
  for (int i = 0; i < n; ++i) tm.emplace_back(i, i, 1.0 + 0.1 * i);
  for (int i = 0; i + 1 < n; ++i) {
    if (i == cut) continue;
    const double k = 1000.0 * (1.0 + 0.05 * i);
    tk.emplace_back(i, i, k);
    tk.emplace_back(i + 1, i + 1, k);
    tk.emplace_back(i, i + 1, -k);
    tk.emplace_back(i + 1, i, -k);
  }
  t.K.resize(n, n);
  t.M.resize(n, n);
  t.K.setFromTriplets(tk.begin(), tk.end());
  t.M.setFromTriplets(tm.begin(), tm.end());
  for (int i = 0; i < n; ++i) t.dofs.push_back({i + 1, 0, Eigen::Vector3d(i, 0, 0)});
  return t;
}

/// Free-free steel shaft along z: length 1 m, solid diameter 40 mm, `n` Timoshenko elements,
/// nodes 1..n+1 at z = L k / n with 6 DOFs each (ux uy uz rx ry rz). E = 211 GPa, G = 81.2 GPa,
/// rho = 7810 kg/m^3 (the steel of Friswell et al. 2010, ch. 5). It has six rigid-body modes.
inline TestModel beam(int n, double length = 1.0, double diameter = 0.04) {
  fe::BeamProperties p;
  p.length = length / n;
  p.outer_diameter = diameter;
  p.youngs_modulus = 211e9;
  p.shear_modulus = 81.2e9;
  p.density = 7810.0;
  p.gyroscopic = false;
  const fe::BeamMatrices e = fe::timoshenko_beam(p);
  TestModel t;
  const int nd = 6 * (n + 1);
  std::vector<Eigen::Triplet<double>> tk, tm;
  for (int el = 0; el < n; ++el)
    for (int r = 0; r < 12; ++r)
      for (int c = 0; c < 12; ++c) {
        if (e.stiffness(r, c) != 0.0) tk.emplace_back(6 * el + r, 6 * el + c, e.stiffness(r, c));
        if (e.mass(r, c) != 0.0) tm.emplace_back(6 * el + r, 6 * el + c, e.mass(r, c));
      }
  t.K.resize(nd, nd);
  t.M.resize(nd, nd);
  t.K.setFromTriplets(tk.begin(), tk.end());
  t.M.setFromTriplets(tm.begin(), tm.end());
  for (int node = 0; node <= n; ++node)
    for (int c = 0; c < 6; ++c)
      t.dofs.push_back({node + 1, c, Eigen::Vector3d(0, 0, length * node / n)});
  return t;
}

/// The model with the DOFs `fixed` removed (a clamp): rows and columns deleted.
inline TestModel remove_dofs(const TestModel& t, const std::vector<int>& fixed) {
  const auto n = static_cast<int>(t.dofs.size());
  std::vector<int> map(static_cast<std::size_t>(n), -1);
  TestModel out;
  for (int j = 0; j < n; ++j)
    if (std::find(fixed.begin(), fixed.end(), j) == fixed.end()) {
      map[static_cast<std::size_t>(j)] = static_cast<int>(out.dofs.size());
      out.dofs.push_back(t.dofs[static_cast<std::size_t>(j)]);
    }
  auto cut = [&](const Eigen::SparseMatrix<double>& A) {
    std::vector<Eigen::Triplet<double>> tr;
    for (int c = 0; c < A.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
        const int r = map[static_cast<std::size_t>(it.row())],
                  cc = map[static_cast<std::size_t>(c)];
        if (r >= 0 && cc >= 0) tr.emplace_back(r, cc, it.value());
      }
    Eigen::SparseMatrix<double> B(static_cast<Eigen::Index>(out.dofs.size()),
                                  static_cast<Eigen::Index>(out.dofs.size()));
    B.setFromTriplets(tr.begin(), tr.end());
    return B;
  };
  out.K = cut(t.K);
  out.M = cut(t.M);
  return out;
}

/// All eigenvalues of a small pair, dense, ascending.
inline Eigen::VectorXd dense_eigenvalues(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> s(K, M, Eigen::EigenvaluesOnly);
  return s.eigenvalues();
}

}  // namespace geardyn::reduce::test
