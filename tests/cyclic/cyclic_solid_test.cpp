// Cyclic symmetry on solid meshes: an annular sector meshed with hex8/hex20 (solid/
// structured_mesh.hpp), assembled (solid/assembly.hpp), solved per nodal diameter, against the
// full 360 deg model built by replicate() from the SAME sector mesh.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/cyclic/replicate.hpp"
#include "geardyn/solid/assembly.hpp"
#include "geardyn/solid/structured_mesh.hpp"

namespace geardyn::cyclic {
namespace {

constexpr double kPi = std::numbers::pi;

solid::Material steel() {
  solid::Material m;
  m.name = "steel";
  m.E = 200e9;
  m.nu = 0.3;
  m.rho = 7850.0;
  return m;
}

double norm1(const Eigen::SparseMatrix<double>& A) {
  double best = 0.0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    double sum = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) sum += std::abs(it.value());
    best = std::max(best, sum);
  }
  return best;
}

struct Comparison {
  double worst_relative = 0;  // cyclic vs full eigenvalues
  double worst_residual = 0;  // expanded cyclic modes in the full model
  std::size_t compared = 0;
};

// Cyclic vs full on one sector mesh (see cyclic_symmetry_test.cpp for the counting argument).
Comparison compare_cyclic_with_full(const solid::Mesh& sector_mesh, int N, int n_modes) {
  const solid::SolidSystem sector = solid::assemble(sector_mesh);
  const ReplicatedMesh full_mesh = replicate(sector_mesh, N);
  const solid::SolidSystem full = solid::assemble(full_mesh.mesh);

  InterfaceOptions io;
  io.n_sectors = N;
  const SectorInterfaces interfaces = find_interfaces(sector.dofs, io);
  EXPECT_LT(interfaces.worst_mismatch, 1e-12);
  const CyclicSector cs(sector.dofs, interfaces);
  CyclicModesOptions options;
  options.eigen.n_modes = n_modes;
  options.eigen.method = eig::Method::Sparse;
  const CyclicModesResult r = solve_cyclic_modes(sector.K, sector.M, cs, options);
  EXPECT_EQ(r.status, Status::Ok) << r.brief_report();

  // Reference: all eigenvalues of the full wheel, dense (Cholesky of M + QR iteration).
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges{Eigen::MatrixXd(full.K),
                                                                      Eigen::MatrixXd(full.M)};
  const Eigen::VectorXd lambda_full = ges.eigenvalues();

  std::vector<double> cyclic;
  double cutoff = std::numeric_limits<double>::infinity();
  for (const auto& d : r.diameters) cutoff = std::min(cutoff, d.eigen.eigenvalues.maxCoeff());
  for (const auto& d : r.diameters)
    for (Eigen::Index j = 0; j < d.eigen.eigenvalues.size(); ++j)
      for (int c = 0; c < d.multiplicity; ++c) cyclic.push_back(d.eigen.eigenvalues[j]);
  std::sort(cyclic.begin(), cyclic.end());
  std::vector<double> below_cyclic, below_full;
  for (double l : cyclic)
    if (l < cutoff * (1.0 - 1e-6)) below_cyclic.push_back(l);
  for (Eigen::Index i = 0; i < lambda_full.size(); ++i)
    if (lambda_full[i] < cutoff * (1.0 - 1e-6)) below_full.push_back(lambda_full[i]);
  Comparison out;
  EXPECT_EQ(below_cyclic.size(), below_full.size());
  out.compared = std::min(below_cyclic.size(), below_full.size());
  for (std::size_t i = 0; i < out.compared; ++i)
    out.worst_relative = std::max(out.worst_relative, std::abs(below_cyclic[i] - below_full[i]) /
                                                          std::max(below_full[i], 1e-3 * cutoff));

  // Expansion to the full wheel through replicate's node map.
  std::unordered_map<long, int> sector_index;
  for (int i = 0; i < sector_mesh.num_nodes(); ++i)
    sector_index[sector_mesh.node_ids[static_cast<std::size_t>(i)]] = i;
  const double nk = norm1(full.K), nm = norm1(full.M);
  const Eigen::SparseMatrix<std::complex<double>> Kc = full.K.cast<std::complex<double>>(),
                                                  Mc = full.M.cast<std::complex<double>>();
  for (const auto& d : r.diameters)
    for (Eigen::Index j = 0; j < d.sector_shapes.cols(); ++j) {
      Eigen::VectorXcd u = Eigen::VectorXcd::Zero(full.num_dofs());
      for (int s = 0; s < N; ++s) {
        const Eigen::VectorXcd us =
            cs.expand_to_sector(d.sector_shapes.col(j), d.nodal_diameter, s);
        for (std::size_t k = 0; k < sector.dofs.size(); ++k) {
          const int node =
              full_mesh.node_map[static_cast<std::size_t>(s)]
                                [static_cast<std::size_t>(sector_index.at(sector.dofs[k].node_id))];
          const int f = full.node_dof(node, sector.dofs[k].component);
          EXPECT_GE(f, 0);
          if (f >= 0) u[f] = us[static_cast<Eigen::Index>(k)];
        }
      }
      const double lambda = d.eigen.eigenvalues[j];
      const Eigen::VectorXcd res = Kc * u - lambda * (Mc * u);
      out.worst_residual =
          std::max(out.worst_residual, res.norm() / ((nk + std::abs(lambda) * nm) * u.norm()));
    }
  return out;
}

// Free annular disk r = 0.05..0.15 m, t = 0.02 m, 8 sectors of 45 deg, hex20 (2 x 1 x 1 cells
// per sector): the full wheel has 1000+ DOFs, so the dense reference stays quick. Tolerance
// 1e-8 relative (the brief's); both are the same algebra, the gap is the Lanczos tolerance.
TEST(CyclicSolid, Hex20AnnulusEightSectorsMatchesTheReplicatedFullWheel) {
  const solid::Mesh sector = solid::annular_sector_mesh(0.05, 0.15, 0.02, 2.0 * kPi / 8, 2, 1, 1,
                                                        solid::ElementType::Hex20, steel());
  const Comparison c = compare_cyclic_with_full(sector, 8, 8);
  EXPECT_GE(c.compared, 40u);
  EXPECT_LT(c.worst_relative, 1e-8);
  EXPECT_LT(c.worst_residual, 1e-10);
}

// 7 sectors (51.4 deg: interfaces not aligned with any axis), hex8, with 6-DOF interface nodes:
// a node r on the left plane above the disk carries a point mass with offset and anisotropic
// inertia and is the independent node of a rigid element (RBE2) holding top-face nodes at
// theta = alpha/3; its partner r' = R(alpha) r holds top-face nodes at theta = 2 alpha/3. The
// rotations of r and r' are interface DOFs that R(alpha) must rotate.
TEST(CyclicSolid, Hex8SevenSectorsWithSixDofInterfaceNodes) {
  const int N = 7;
  const double alpha = 2.0 * kPi / N, t = 0.02;
  solid::Mesh sector =
      solid::annular_sector_mesh(0.05, 0.15, t, alpha, 2, 3, 1, solid::ElementType::Hex8, steel());
  long next_id = *std::max_element(sector.node_ids.begin(), sector.node_ids.end()) + 1;
  const Eigen::Vector3d r_left(0.1, 0.0, 0.5 * t + 0.01);
  const Eigen::Matrix3d Ra = rotation(Eigen::Vector3d::UnitZ(), alpha);
  auto add_node = [&](const Eigen::Vector3d& x) {
    sector.coords.push_back(x);
    sector.node_ids.push_back(next_id++);
    return sector.num_nodes() - 1;
  };
  const int left = add_node(r_left), right = add_node(Ra * r_left);
  auto top_nodes_at = [&](double theta) {
    std::vector<int> out;
    for (int i = 0; i < sector.num_nodes(); ++i) {
      const Eigen::Vector3d& x = sector.coords[static_cast<std::size_t>(i)];
      if (std::abs(x.z() - 0.5 * t) < 1e-9 && std::abs(std::atan2(x.y(), x.x()) - theta) < 1e-9)
        out.push_back(i);
    }
    return out;
  };
  solid::RigidElement a, b;
  a.id = 1;
  a.reference = left;
  a.nodes = top_nodes_at(alpha / 3.0);
  b.id = 2;
  b.reference = right;
  b.nodes = top_nodes_at(2.0 * alpha / 3.0);
  ASSERT_EQ(a.nodes.size(), 3u);
  ASSERT_EQ(b.nodes.size(), 3u);
  sector.rigid_elements = {a, b};
  solid::PointMass m;
  m.id = 1;
  m.node = left;
  m.mass = 0.4;
  m.offset = Eigen::Vector3d(0.004, -0.003, 0.006);
  m.inertia = Eigen::Vector3d(2e-4, 5e-4, 9e-4).asDiagonal();
  m.inertia(0, 1) = m.inertia(1, 0) = 1e-4;
  sector.point_masses = {m};

  // the two extra nodes really carry 6 DOFs and pair with each other
  const solid::SolidSystem sys = solid::assemble(sector);
  InterfaceOptions io;
  io.n_sectors = N;
  const SectorInterfaces interfaces = find_interfaces(sys.dofs, io);
  const auto pair =
      std::find_if(interfaces.pairs.begin(), interfaces.pairs.end(), [&](const NodePair& p) {
        return p.left_node_id == sector.node_ids[static_cast<std::size_t>(left)];
      });
  ASSERT_NE(pair, interfaces.pairs.end());
  EXPECT_EQ(pair->right_node_id, sector.node_ids[static_cast<std::size_t>(right)]);
  EXPECT_GE(sys.node_dof(left, 5), 0);
  EXPECT_GE(sys.node_dof(right, 5), 0);

  const Comparison c = compare_cyclic_with_full(sector, N, 8);
  EXPECT_GE(c.compared, 40u);
  EXPECT_LT(c.worst_relative, 1e-8);
  EXPECT_LT(c.worst_residual, 1e-10);
}

TEST(CyclicSolid, ReplicateMergesInterfacesAndRejectsTransverseSprings) {
  const int N = 6;
  const solid::Mesh sector = solid::annular_sector_mesh(0.05, 0.15, 0.02, 2.0 * kPi / N, 2, 2, 1,
                                                        solid::ElementType::Hex8, steel());
  const ReplicatedMesh full = replicate(sector, N);
  const solid::Mesh closed = solid::annular_sector_mesh(0.05, 0.15, 0.02, 2.0 * kPi, 2, 2 * N, 1,
                                                        solid::ElementType::Hex8, steel());
  EXPECT_EQ(full.mesh.num_nodes(), closed.num_nodes());
  EXPECT_EQ(full.mesh.num_elements(), N * sector.num_elements());
  EXPECT_EQ(full.merged_nodes, N * static_cast<int>(sector.node_sets.at("left").size()));
  EXPECT_LT(full.worst_merge_gap, 1e-12);
  EXPECT_EQ(full.mesh.node_sets.at("inner").size(), closed.node_sets.at("inner").size());
  // copy s's right face is copy s+1's left face
  const auto& left = sector.node_sets.at("left");
  const auto& right = sector.node_sets.at("right");
  for (std::size_t k = 0; k < left.size(); ++k)
    for (int s = 0; s < N; ++s)
      EXPECT_EQ(
          full.node_map[static_cast<std::size_t>(s)][static_cast<std::size_t>(right[k])],
          full.node_map[static_cast<std::size_t>((s + 1) % N)][static_cast<std::size_t>(left[k])]);

  solid::Mesh with_spring = sector;
  solid::Spring spring;
  spring.node1 = 0;
  spring.component1 = 0;  // ux: points elsewhere in each copy
  spring.stiffness = 1e6;
  with_spring.springs = {spring};
  EXPECT_THROW(replicate(with_spring, N), InputError);
  with_spring.springs[0].component1 = 2;  // uz: along the axis, invariant
  EXPECT_NO_THROW(replicate(with_spring, N));
}

}  // namespace
}  // namespace geardyn::cyclic
