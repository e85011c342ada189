#pragma once
// A hand-made cyclic structure for the cyclic-symmetry tests that does not depend on the solid
// element library: a ring-shaped lattice of point masses joined by springs.
//
//   nodes (i, j, k): radius r_i = r0 + i dr (i < nr), angle theta_j = j beta (beta = alpha / nt,
//   nt columns per sector), height z_k = k dz (k < nz). Node id = 1 + i + nr (k + nz j).
//
//   Each cell between columns j and j + 1 owns springs between all pairs of its corner nodes
//   except the pairs that lie entirely in column j + 1 (those belong to the next cell), so a
//   sector made of cells 0..nt-1 owns every spring of the wheel exactly once; the nodes of column
//   nt form the right interface and carry no mass (their mass belongs to the next sector).
//
//   Truss spring (all pairs):  E = k_t/2 (e . (u_b - u_a))^2, e the unit vector a -> b.
//   Outer top nodes (i = nr-1, k = nz-1) carry rotations as well; between two such nodes also
//     E = k_l/2 |u_b - u_a - theta_m x d|^2 + k_r/2 |theta_b - theta_a|^2,
//     theta_m = (theta_a + theta_b)/2, d = x_b - x_a
//   (zero for rigid motion u = c + w x x, theta = w). Masses: m_i I on translations; rotational
//   inertia J = Q R(theta_j) J0 R(theta_j)^T Q^T on 6-DOF nodes, anisotropic, so a wrong rotation
//   of the rotational DOFs changes the answer.
// Every term is written with global Cartesian vectors, so the whole lattice can be turned by a
// fixed rotation Q (axis = Q e_z) without changing its frequencies.
#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <Eigen/Sparse>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>
#include <vector>

#include "geardyn/solid/mesh.hpp"

namespace geardyn::test {

struct RingLattice {
  int n_sectors = 7;
  int nt = 2, nr = 2, nz = 2;
  double r0 = 0.2, dr = 0.05, dz = 0.04;
  double k_truss = 1e7, k_link = 5e6, k_rot = 2e4;
  double mass = 0.3;
  Eigen::Matrix3d J0 = Eigen::Vector3d(1e-3, 2e-3, 4e-3).asDiagonal();
  Eigen::Matrix3d Q = Eigen::Matrix3d::Identity();  ///< base rotation of the whole lattice
};

struct LatticeSystem {
  std::vector<solid::DofInfo> dofs;
  Eigen::SparseMatrix<double> K, M;
  std::map<long, std::array<int, 6>> node_dof;  ///< node id -> DOF index per component (-1)
};

inline bool has_rotations(const RingLattice& p, int i, int k) {
  return i == p.nr - 1 && k == p.nz - 1;
}

inline long lattice_node_id(const RingLattice& p, int i, int j, int k) {
  return 1 + i + p.nr * (k + p.nz * static_cast<long>(j));
}

inline Eigen::Vector3d lattice_position(const RingLattice& p, int i, int j, int k) {
  const double beta = 2.0 * std::numbers::pi / p.n_sectors / p.nt;
  const double r = p.r0 + i * p.dr;
  return p.Q * Eigen::Vector3d(r * std::cos(j * beta), r * std::sin(j * beta), k * p.dz);
}

/// Sector (full = false: columns 0..nt, node ids as above) or full wheel (full = true: columns
/// 0..N nt - 1, column N nt identified with column 0).
inline LatticeSystem build_lattice(const RingLattice& p, bool full) {
  const int columns = full ? p.n_sectors * p.nt : p.nt + 1;
  const int cells = full ? p.n_sectors * p.nt : p.nt;
  LatticeSystem s;
  auto column_of = [&](int j) { return full ? j % columns : j; };
  for (int j = 0; j < columns; ++j)
    for (int k = 0; k < p.nz; ++k)
      for (int i = 0; i < p.nr; ++i) {
        std::array<int, 6> idx;
        idx.fill(-1);
        const int ncomp = has_rotations(p, i, k) ? 6 : 3;
        for (int c = 0; c < ncomp; ++c) {
          idx[static_cast<std::size_t>(c)] = static_cast<int>(s.dofs.size());
          s.dofs.push_back({lattice_node_id(p, i, j, k), c, lattice_position(p, i, j, k)});
        }
        s.node_dof[lattice_node_id(p, i, j, k)] = idx;
      }
  const int n = static_cast<int>(s.dofs.size());
  std::vector<Eigen::Triplet<double>> tk, tm;
  auto add_block = [](std::vector<Eigen::Triplet<double>>& t, const std::vector<int>& rows,
                      const Eigen::MatrixXd& B) {
    for (std::size_t a = 0; a < rows.size(); ++a)
      for (std::size_t b = 0; b < rows.size(); ++b)
        if (B(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) != 0.0)
          t.emplace_back(rows[a], rows[b],
                         B(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)));
  };
  auto skew = [](const Eigen::Vector3d& v) {
    Eigen::Matrix3d S;
    S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return S;
  };
  for (int c = 0; c < cells; ++c) {
    std::vector<std::tuple<int, int, int>> corners;  // (i, column, k), column c or c + 1
    for (int dj = 0; dj < 2; ++dj)
      for (int k = 0; k < p.nz; ++k)
        for (int i = 0; i < p.nr; ++i) corners.emplace_back(i, c + dj, k);
    for (std::size_t a = 0; a < corners.size(); ++a)
      for (std::size_t b = a + 1; b < corners.size(); ++b) {
        const auto [ia, ja, ka] = corners[a];
        const auto [ib, jb, kb] = corners[b];
        if (ja == c + 1 && jb == c + 1) continue;  // owned by the next cell
        const Eigen::Vector3d xa = lattice_position(p, ia, ja, ka),
                              xb = lattice_position(p, ib, jb, kb);
        const auto& da = s.node_dof.at(lattice_node_id(p, ia, column_of(ja), ka));
        const auto& db = s.node_dof.at(lattice_node_id(p, ib, column_of(jb), kb));
        const Eigen::Vector3d d = xb - xa, e = d.normalized();
        // truss: B = [-e^T, e^T] on (u_a, u_b)
        Eigen::MatrixXd Bt(1, 6);
        Bt << -e.transpose(), e.transpose();
        add_block(tk, {da[0], da[1], da[2], db[0], db[1], db[2]}, p.k_truss * Bt.transpose() * Bt);
        if (has_rotations(p, ia, ka) && has_rotations(p, ib, kb)) {
          // g = u_b - u_a - theta_m x d = u_b - u_a + S(d) (theta_a + theta_b)/2
          Eigen::MatrixXd G(3, 12);
          G << -Eigen::Matrix3d::Identity(), 0.5 * skew(d), Eigen::Matrix3d::Identity(),
              0.5 * skew(d);
          Eigen::MatrixXd Gr(3, 12);
          Gr << Eigen::Matrix3d::Zero(), -Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Zero(),
              Eigen::Matrix3d::Identity();
          const Eigen::MatrixXd Kl = p.k_link * G.transpose() * G + p.k_rot * Gr.transpose() * Gr;
          add_block(
              tk,
              {da[0], da[1], da[2], da[3], da[4], da[5], db[0], db[1], db[2], db[3], db[4], db[5]},
              Kl);
        }
      }
  }
  const double beta = 2.0 * std::numbers::pi / p.n_sectors / p.nt;
  const int mass_columns = full ? columns : p.nt;  // the sector's right column has no mass
  for (int j = 0; j < mass_columns; ++j)
    for (int k = 0; k < p.nz; ++k)
      for (int i = 0; i < p.nr; ++i) {
        const auto& d = s.node_dof.at(lattice_node_id(p, i, j, k));
        const double m = p.mass * (1.0 + 0.5 * i);
        for (int c = 0; c < 3; ++c)
          tm.emplace_back(d[static_cast<std::size_t>(c)], d[static_cast<std::size_t>(c)], m);
        if (has_rotations(p, i, k)) {
          const Eigen::Matrix3d Rj =
              Eigen::AngleAxisd(j * beta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
          const Eigen::Matrix3d J = p.Q * Rj * p.J0 * Rj.transpose() * p.Q.transpose();
          add_block(tm, {d[3], d[4], d[5]}, J);
        }
      }
  s.K.resize(n, n);
  s.M.resize(n, n);
  s.K.setFromTriplets(tk.begin(), tk.end());
  s.M.setFromTriplets(tm.begin(), tm.end());
  return s;
}

}  // namespace geardyn::test
