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

TEST(CyclicSolid, ReplicateMergesInterfacesAndRotatesSprings) {
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

  // A spring on ux acts along the rotated x axis in copy s; one on uz stays scalar.
  solid::Mesh with_spring = sector;
  solid::Spring spring;
  spring.id = 7;
  spring.node1 = 0;
  spring.component1 = 0;
  spring.stiffness = 1e6;
  solid::Spring axial = spring;
  axial.id = 8;
  axial.component1 = 2;
  with_spring.springs = {spring, axial};
  const ReplicatedMesh sprung = replicate(with_spring, N);
  ASSERT_EQ(sprung.mesh.springs.size(), 2u * N);
  for (int s = 0; s < N; ++s) {
    const solid::Spring& x = sprung.mesh.springs[static_cast<std::size_t>(2 * s)];
    const solid::Spring& z = sprung.mesh.springs[static_cast<std::size_t>(2 * s + 1)];
    EXPECT_EQ(x.id, 7 + 10 * s);
    EXPECT_EQ(x.node1, sprung.node_map[static_cast<std::size_t>(s)][0]);
    const double angle = 2.0 * kPi * s / N;
    EXPECT_LT((solid::spring_axis(x.component1, x.direction1) -
               Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0))
                  .norm(),
              1e-14);
    EXPECT_TRUE(z.direction1.isZero(0.0));
    EXPECT_EQ(z.component1, 2);
  }
  EXPECT_TRUE(sprung.mesh.springs[0].direction1.isZero(0.0));  // copy 0 unchanged
}

// Transverse scalar springs on a sector, solved with cyclic symmetry and on the replicated full
// wheel: 7 sectors of hex8 (interfaces not aligned with any axis), grounded springs on ux of an
// interior node, uy of a left-interface node and ux of a right-interface node, and a spring
// between uy of one node and ux of another. In the cyclic model every sector's spring acts along
// that sector's rotated axes (the constraint u_R = e^{i phi} R(alpha) u_L rotates the whole
// sector); replicate() gives each copy the rotated directions, so both are the same discrete
// model and the full wheel's eigenvalues are the union over nodal diameters of the cyclic ones
// (Thomas, "Dynamics of rotationally periodic structures", Int. J. Numer. Meth. Eng. 14 (1979)
// 81-102). Tolerance 1e-8 relative: the gap is the Lanczos tolerance of the sector solves.
TEST(CyclicSolid, TransverseSpringsOnTheSectorMatchTheReplicatedFullWheel) {
  const int N = 7;
  const double alpha = 2.0 * kPi / N;
  solid::Mesh sector = solid::annular_sector_mesh(0.05, 0.15, 0.02, alpha, 2, 3, 1,
                                                  solid::ElementType::Hex8, steel());
  const auto& left = sector.node_sets.at("left");
  const auto& right = sector.node_sets.at("right");
  int interior = -1;
  for (int i = 0; i < sector.num_nodes() && interior < 0; ++i)
    if (std::find(left.begin(), left.end(), i) == left.end() &&
        std::find(right.begin(), right.end(), i) == right.end())
      interior = i;
  ASSERT_GE(interior, 0);
  const auto spring = [](long id, int n1, int c1, int n2, int c2, double k) {
    solid::Spring s;
    s.id = id;
    s.node1 = n1;
    s.component1 = c1;
    s.node2 = n2;
    s.component2 = c2;
    s.stiffness = k;
    return s;
  };
  sector.springs = {spring(1, interior, 0, -1, 0, 4e7), spring(2, left[1], 1, -1, 0, 2e7),
                    spring(3, right[2], 0, -1, 0, 3e7), spring(4, interior, 1, left[0], 0, 5e7)};
  const Comparison c = compare_cyclic_with_full(sector, N, 8);
  EXPECT_GE(c.compared, 30u);
  EXPECT_LT(c.worst_relative, 1e-8);
  EXPECT_LT(c.worst_residual, 1e-10);

  // Control: the same springs without the rotation (every copy on the global ux / uy) are a
  // different structure, whose spectrum the cyclic model does not reproduce.
  const ReplicatedMesh full = replicate(sector, N);
  solid::Mesh unrotated = full.mesh;
  for (auto& s : unrotated.springs) s.direction1 = s.direction2 = Eigen::Vector3d::Zero();
  const Eigen::MatrixXd K1(solid::assemble(full.mesh).K), K0(solid::assemble(unrotated).K);
  EXPECT_GT((K1 - K0).norm(), 1e6);
}

}  // namespace
}  // namespace geardyn::cyclic
