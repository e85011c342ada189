// Unit tests of the sparse solid assembly: rigid-body modes and mass of a free body, threads,
// constraints, rigid (RBE2) and averaging (RBE3) elements, point masses (CONM2), springs
// (CELAS), and input errors.
#include "geardyn/solid/assembly.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <numbers>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/solid/structured_mesh.hpp"
#include "solid_test_support.hpp"

namespace geardyn::solid {
namespace {

using test::steel;

Eigen::MatrixXd dense(const Eigen::SparseMatrix<double>& A) { return Eigen::MatrixXd(A); }

// Reduced vector of a rigid-body motion (u = t + theta x x, rotations theta) at the kept DOFs.
Eigen::VectorXd rigid_motion(const SolidSystem& sys, const Eigen::Vector3d& t,
                             const Eigen::Vector3d& theta) {
  Eigen::VectorXd q(sys.num_dofs());
  for (int i = 0; i < sys.num_dofs(); ++i) {
    const DofInfo& d = sys.dofs[static_cast<std::size_t>(i)];
    const Eigen::Vector3d u = t + theta.cross(d.x);
    q[i] = d.component < 3 ? u[d.component] : theta[d.component - 3];
  }
  return q;
}

// Appends a node and returns its index.
int add_node(Mesh& mesh, const Eigen::Vector3d& x) {
  mesh.coords.push_back(x);
  mesh.node_ids.push_back(static_cast<long>(mesh.coords.size()) + 1000);
  return mesh.num_nodes() - 1;
}

// A free hex20 box: six zero eigenvalues (relative 1e-10, see element_test), total mass rho V.
TEST(Assembly, FreeBodyRigidModesAndMass) {
  const Mesh mesh = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.3, 0.1, 0.05), 3, 1, 1,
                             ElementType::Hex20, steel());
  const SolidSystem sys = assemble(mesh);
  EXPECT_EQ(sys.num_dofs(), 3 * mesh.num_nodes());
  EXPECT_TRUE(sys.removed_dofs.empty());
  const Eigen::MatrixXd K = dense(sys.K);
  EXPECT_LT((K - K.transpose()).norm(), 1e-14 * K.norm());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K);
  const double top = eig.eigenvalues()[eig.eigenvalues().size() - 1];
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(eig.eigenvalues()[i]), 1e-10 * top);
  EXPECT_GT(eig.eigenvalues()[6], 1e-8 * top);
  const double V = 0.3 * 0.1 * 0.05;
  EXPECT_NEAR(sys.volume, V, 1e-14);
  const Eigen::VectorXd ex = rigid_motion(sys, Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero());
  EXPECT_NEAR(ex.dot(sys.M * ex), steel().rho * V, 1e-12 * steel().rho * V);
  EXPECT_NEAR(sys.solid_mass, steel().rho * V, 1e-12 * steel().rho * V);
  // DofInfo: external ids and coordinates.
  EXPECT_EQ(sys.dofs[3].node_id, mesh.node_ids[1]);
  EXPECT_EQ(sys.dofs[3].component, 0);
  EXPECT_EQ(sys.dofs[3].x, mesh.coords[1]);
}

// Column-range threading gives bit-identical matrices (same summation order per column).
TEST(Assembly, ThreadCountDoesNotChangeTheResult) {
  const Mesh mesh = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 6, 6, 6,
                             ElementType::Tet10, steel());
  AssemblyOptions one, two;
  two.threads = 2;
  const SolidSystem a = assemble(mesh, one), b = assemble(mesh, two);
  ASSERT_EQ(a.K.nonZeros(), b.K.nonZeros());
  EXPECT_EQ((a.K - b.K).cwiseAbs().sum(), 0.0);
  EXPECT_EQ((a.M - b.M).cwiseAbs().sum(), 0.0);
}

// Fixed face: its DOFs are eliminated, K becomes positive definite, recovery gives zeros there.
TEST(Assembly, ConstraintsAreEliminated) {
  Mesh mesh = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 2, 2, 2, ElementType::Hex8,
                       steel());
  for (int n : nodes_of_set(mesh, "xmin", {})) {
    Constraint c;
    c.node = n;
    c.components = {true, true, true, true, true, true};  // rotations of solid nodes: ignored
    mesh.constraints.push_back(c);
  }
  const SolidSystem sys = assemble(mesh);
  EXPECT_EQ(sys.num_all_dofs(), 81);
  EXPECT_EQ(sys.num_dofs(), 3 * (27 - 9));
  for (int n : mesh.node_sets.at("xmin")) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(sys.node_dof(n, c), -1);
  }
  for (int n : mesh.node_sets.at("xmax")) EXPECT_GE(sys.node_dof(n, 1), 0);
  EXPECT_EQ(sys.node_dof(0, 3), -1);  // no rotation on a solid node
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(sys.K);
  EXPECT_EQ(llt.info(), Eigen::Success);
  const Eigen::VectorXd u_all = sys.recovery * Eigen::VectorXd::Ones(sys.num_dofs());
  for (int n : mesh.node_sets.at("xmin")) EXPECT_EQ(u_all[sys.all_dof(n, 0)], 0.0);
}

// Rigid spider (RBE2) from a node at the centre of the x = 1 face to all face nodes: the face
// nodes are eliminated; rotating the independent node rotates the face rigidly:
//   u_d = u_r + theta x (x_d - x_r)  (exact). A rigid motion of the whole body stays force-free.
TEST(Assembly, RigidSpiderMovesFaceRigidly) {
  Mesh mesh = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 2, 2, 2, ElementType::Hex8,
                       steel());
  const int r = add_node(mesh, Eigen::Vector3d(1.0, 0.5, 0.5));
  RigidElement rbe2;
  rbe2.id = 7;
  rbe2.reference = r;
  rbe2.nodes = mesh.node_sets.at("xmax");
  mesh.rigid_elements.push_back(rbe2);
  const SolidSystem sys = assemble(mesh);
  EXPECT_EQ(sys.node_dofs[static_cast<std::size_t>(r)], 6);
  EXPECT_EQ(sys.num_dofs(), 3 * (27 - 9) + 6);
  for (int n : rbe2.nodes) EXPECT_EQ(sys.node_dof(n, 0), -1);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(sys.num_dofs());
  const Eigen::Vector3d ur(1e-3, 2e-3, -1e-3), theta(0.01, -0.02, 0.03);
  for (int c = 0; c < 3; ++c) {
    q[sys.node_dof(r, c)] = ur[c];
    q[sys.node_dof(r, 3 + c)] = theta[c];
  }
  const Eigen::VectorXd u = sys.recovery * q;
  for (int n : rbe2.nodes) {
    const Eigen::Vector3d expected = ur + theta.cross(mesh.coords[static_cast<std::size_t>(n)] -
                                                      mesh.coords[static_cast<std::size_t>(r)]);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(u[sys.all_dof(n, c)], expected[c], 1e-16);
  }
  // Rigid motions of the whole assembly remain in the null space of K (relative 1e-12).
  const Eigen::VectorXd rb =
      rigid_motion(sys, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.3, -0.2, 0.1));
  const Eigen::VectorXd f = sys.K * rb;
  EXPECT_LT(f.norm(), 1e-12 * dense(sys.K).norm() * rb.norm());
}

// RBE3 (averaging) with the 9 nodes of the x = 1 face (2 x 2 cells) as independent nodes, equal
// weights, reference node in front of the face centre. Loads on the reference node reach the
// independent nodes through T^T (virtual work):
//   (a) axial force F e_x: each node carries F/9 (symmetric set, the moment arm is along x);
//   (b) transverse force at the offset reference: the resultant is F and the moment about the
//       reference is zero;
//   (c) a moment M: zero resultant, moment M.
// The reference node adds no stiffness: K equals that of the mesh without the RBE3.
TEST(Assembly, AveragingElementDistributesLoads) {
  Mesh mesh = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 2, 2, 2, ElementType::Hex8,
                       steel());
  const SolidSystem plain = assemble(mesh);
  const int r = add_node(mesh, Eigen::Vector3d(1.3, 0.5, 0.5));
  RigidElement rbe3;
  rbe3.kind = RigidElement::Kind::Averaging;
  rbe3.id = 8;
  rbe3.reference = r;
  rbe3.nodes = mesh.node_sets.at("xmax");
  mesh.rigid_elements.push_back(rbe3);
  const SolidSystem sys = assemble(mesh);
  ASSERT_EQ(sys.num_dofs(), plain.num_dofs());  // all 6 reference DOFs are dependent
  EXPECT_LT((dense(sys.K) - dense(plain.K)).norm(), 1e-15 * dense(plain.K).norm());
  const Eigen::Vector3d xr = mesh.coords[static_cast<std::size_t>(r)];
  auto distribute = [&](const Eigen::Vector3d& force, const Eigen::Vector3d& moment) {
    Eigen::VectorXd f_all = Eigen::VectorXd::Zero(sys.num_all_dofs());
    for (int c = 0; c < 3; ++c) {
      f_all[sys.all_dof(r, c)] = force[c];
      f_all[sys.all_dof(r, 3 + c)] = moment[c];
    }
    return Eigen::VectorXd(sys.recovery.transpose() * f_all);
  };
  const double F = 1000;
  {
    const Eigen::VectorXd f = distribute(Eigen::Vector3d(F, 0, 0), Eigen::Vector3d::Zero());
    for (int n : rbe3.nodes) {
      EXPECT_NEAR(f[sys.node_dof(n, 0)], F / 9, 1e-12 * F);
      EXPECT_NEAR(f[sys.node_dof(n, 1)], 0.0, 1e-12 * F);
      EXPECT_NEAR(f[sys.node_dof(n, 2)], 0.0, 1e-12 * F);
    }
  }
  auto resultant = [&](const Eigen::VectorXd& f, Eigen::Vector3d& force, Eigen::Vector3d& moment) {
    force.setZero();
    moment.setZero();
    for (int n : rbe3.nodes) {
      const Eigen::Vector3d fi(f[sys.node_dof(n, 0)], f[sys.node_dof(n, 1)], f[sys.node_dof(n, 2)]);
      force += fi;
      moment += (mesh.coords[static_cast<std::size_t>(n)] - xr).cross(fi);
    }
  };
  Eigen::Vector3d force, moment;
  resultant(distribute(Eigen::Vector3d(0, F, 0), Eigen::Vector3d::Zero()), force, moment);
  EXPECT_LT((force - Eigen::Vector3d(0, F, 0)).norm(), 1e-12 * F);
  EXPECT_LT(moment.norm(), 1e-12 * F);
  const Eigen::Vector3d M(100, -50, 30);
  resultant(distribute(Eigen::Vector3d::Zero(), M), force, moment);
  EXPECT_LT(force.norm(), 1e-12 * M.norm());
  EXPECT_LT((moment - M).norm(), 1e-12 * M.norm());
}

// Chain RBE3 -> RBE2: a remote node rigidly attached to an RBE3 reference node follows a rigid
// motion of the body exactly (both elements reproduce rigid motions).
TEST(Assembly, RigidElementChainFollowsRigidMotion) {
  Mesh mesh = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1, 1, 1,
                       ElementType::Hex20, steel());
  const int r = add_node(mesh, Eigen::Vector3d(1.0, 0.4, 0.6));
  const int p = add_node(mesh, Eigen::Vector3d(2.0, -1.0, 0.3));
  RigidElement rbe3;
  rbe3.kind = RigidElement::Kind::Averaging;
  rbe3.reference = r;
  rbe3.nodes = mesh.node_sets.at("xmax");
  rbe3.weights.assign(rbe3.nodes.size(), 1.0);
  for (std::size_t i = 0; i < rbe3.weights.size(); i += 2) rbe3.weights[i] = 2.5;
  RigidElement rbe2;
  rbe2.reference = r;
  rbe2.nodes = {p};
  // RBE3 makes r dependent; RBE2 makes p dependent on r.
  mesh.rigid_elements = {rbe2, rbe3};
  const SolidSystem sys = assemble(mesh);
  const Eigen::Vector3d t(1e-3, -2e-3, 3e-3), theta(0.02, 0.01, -0.03);
  const Eigen::VectorXd u = sys.recovery * rigid_motion(sys, t, theta);
  for (int node : {r, p}) {
    const Eigen::Vector3d expected = t + theta.cross(mesh.coords[static_cast<std::size_t>(node)]);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(u[sys.all_dof(node, c)], expected[c], 1e-15) << node << " " << c;
      EXPECT_NEAR(u[sys.all_dof(node, 3 + c)], theta[c], 1e-15);
    }
  }
}

// CONM2 with offset e and inertia J about its CG on a free node: kinetic energy
// T = 1/2 m |v + omega x e|^2 + 1/2 omega^T J omega  must equal 1/2 q^T M q, q = (v, omega);
// equivalently the rotational block is J + m (|e|^2 I - e e^T) (parallel-axis theorem).
TEST(Assembly, PointMassWithOffsetFollowsParallelAxisTheorem) {
  Mesh mesh;
  add_node(mesh, Eigen::Vector3d(0.1, 0.2, 0.3));
  PointMass pm;
  pm.node = 0;
  pm.mass = 12.0;
  pm.offset = Eigen::Vector3d(0.05, -0.02, 0.1);
  pm.inertia << 0.5, 0.01, -0.02, 0.01, 0.7, 0.03, -0.02, 0.03, 0.9;
  mesh.point_masses.push_back(pm);
  const SolidSystem sys = assemble(mesh);
  ASSERT_EQ(sys.num_dofs(), 6);
  const Eigen::MatrixXd M = dense(sys.M);
  const Eigen::Vector3d& e = pm.offset;
  const Eigen::Matrix3d parallel_axis =
      pm.inertia + pm.mass * (e.squaredNorm() * Eigen::Matrix3d::Identity() - e * e.transpose());
  EXPECT_LT((M.bottomRightCorner<3, 3>() - parallel_axis).norm(), 1e-14 * parallel_axis.norm());
  std::srand(3);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Matrix<double, 6, 1> q = Eigen::Matrix<double, 6, 1>::Random();
    const Eigen::Vector3d v = q.head<3>(), w = q.tail<3>();
    const double T = 0.5 * pm.mass * (v + w.cross(e)).squaredNorm() + 0.5 * w.dot(pm.inertia * w);
    EXPECT_NEAR(0.5 * q.dot(M * q), T, 1e-13 * T);
  }
  // A plain point mass on a solid node keeps 3 DOFs and adds m to the translational mass.
  Mesh box = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1, 1, 1, ElementType::Hex8,
                      steel());
  PointMass plain;
  plain.node = 3;
  plain.mass = 5.0;
  box.point_masses.push_back(plain);
  const SolidSystem s2 = assemble(box);
  EXPECT_EQ(s2.num_dofs(), 24);
  const Eigen::VectorXd ex = rigid_motion(s2, Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero());
  EXPECT_NEAR(ex.dot(s2.M * ex), steel().rho + 5.0, 1e-9);
}

// Springs: k between u_x of two free nodes and a grounded torsional spring on r_y of the first.
// The DOFs nothing touches are removed; the remaining 3 x 3 stiffness is exact.
TEST(Assembly, SpringsAndUnconnectedDofs) {
  Mesh mesh;
  add_node(mesh, Eigen::Vector3d(0, 0, 0));
  add_node(mesh, Eigen::Vector3d(1, 0, 0));
  Spring s1;
  s1.node1 = 0;
  s1.component1 = 0;
  s1.node2 = 1;
  s1.component2 = 0;
  s1.stiffness = 3e6;
  Spring s2;
  s2.node1 = 0;
  s2.component1 = 4;
  s2.stiffness = 5e4;
  mesh.springs = {s1, s2};
  AssemblyOptions options;
  options.mass = false;
  const SolidSystem sys = assemble(mesh, options);
  ASSERT_EQ(sys.num_dofs(), 3);
  EXPECT_EQ(sys.removed_dofs.size(), 9u);
  Eigen::Matrix3d expected;
  expected << 3e6, 0, -3e6, 0, 5e4, 0, -3e6, 0, 3e6;
  EXPECT_EQ((dense(sys.K) - expected).norm(), 0.0);
  EXPECT_EQ(sys.node_dof(0, 4), 1);
  EXPECT_EQ(sys.node_dof(1, 1), -1);
  EXPECT_EQ(sys.M.rows(), 0);
  options.remove_unconnected_dofs = false;
  EXPECT_EQ(assemble(mesh, options).num_dofs(), 12);
}

// Springs with directions: between node 0 along n1 = (3, 4, 0) / 5 and node 1 along
// n2 = (0, 3, 4) / 5, k = 25e4 N/m, and a grounded torsional spring on node 1 about
// m = (1, 2, 2) / 3, k = 9e3 N m/rad. By hand, the stretch d = n1 . u0 - n2 . u1 gives
// K = k [n1 n1^T, -n1 n2^T; -n2 n1^T, n2 n2^T] on (u0, u1) and 9e3 m m^T on theta1; with
// k / 25 = 1e4 and 9e3 / 9 = 1e3 every entry is an integer multiple.
TEST(Assembly, DirectionalSpringsMatchTheHandComputedStiffness) {
  Mesh mesh;
  add_node(mesh, Eigen::Vector3d(0, 0, 0));
  add_node(mesh, Eigen::Vector3d(1, 0, 0));
  Spring s1;
  s1.node1 = 0;
  s1.component1 = 0;
  s1.direction1 = Eigen::Vector3d(3, 4, 0) / 5.0;
  s1.node2 = 1;
  s1.component2 = 2;
  s1.direction2 = Eigen::Vector3d(0, 3, 4) / 5.0;
  s1.stiffness = 25e4;
  Spring s2;
  s2.node1 = 1;
  s2.component1 = 3;
  s2.direction1 = Eigen::Vector3d(1, 2, 2) / 3.0;
  s2.stiffness = 9e3;
  mesh.springs = {s1, s2};
  AssemblyOptions options;
  options.mass = false;
  options.remove_unconnected_dofs = false;
  const SolidSystem sys = assemble(mesh, options);
  ASSERT_EQ(sys.num_dofs(), 12);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(12, 12);
  // node 0 translations (rows 0..2), node 1 translations (6..8), node 1 rotations (9..11)
  expected.block(0, 0, 3, 3) << 9, 12, 0, 12, 16, 0, 0, 0, 0;
  expected.block(0, 6, 3, 3) << 0, -9, -12, 0, -12, -16, 0, 0, 0;
  expected.block(6, 0, 3, 3) = expected.block(0, 6, 3, 3).transpose();
  expected.block(6, 6, 3, 3) << 0, 0, 0, 0, 9, 12, 0, 12, 16;
  expected *= 1e4;
  expected.block(9, 9, 3, 3) << 1, 2, 2, 2, 4, 4, 2, 4, 4;
  expected.block(9, 9, 3, 3) *= 1e3;
  EXPECT_LT((dense(sys.K) - expected).norm(), 1e-9);

  // Component springs are the special case n = e_x / e_y / e_z.
  Mesh scalar = mesh;
  scalar.springs[0].direction1 = Eigen::Vector3d::UnitY();
  scalar.springs[0].direction2.setZero();
  scalar.springs[0].component1 = 0;
  Mesh component = scalar;
  component.springs[0].direction1.setZero();
  component.springs[0].component1 = 1;
  EXPECT_EQ((dense(assemble(scalar, options).K) - dense(assemble(component, options).K)).norm(),
            0.0);

  // A direction that is not a unit vector is refused, naming the spring and the end.
  Mesh bad = mesh;
  bad.springs[0].direction2 = Eigen::Vector3d(0, 3, 4);
  bad.springs[0].where = SourceLocation{"deck.bdf", 12, 1};
  try {
    assemble(bad, options);
    FAIL();
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("deck.bdf:12"), std::string::npos) << what;
    EXPECT_NE(what.find("direction2"), std::string::npos) << what;
  }
}

TEST(AssemblyErrors, MissingNodeSetListsAvailableOnes) {
  const Mesh mesh = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1, 1, 1,
                             ElementType::Hex8, steel());
  try {
    nodes_of_set(mesh, "hub", SourceLocation{"model.toml", 5, 3});
    FAIL();
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("model.toml:5:3"), std::string::npos) << what;
    EXPECT_NE(what.find("'xmin'"), std::string::npos) << what;
    EXPECT_NE(what.find("'hub'"), std::string::npos) << what;
  }
  EXPECT_EQ(nodes_of_set(mesh, "xmin", {}).size(), 4u);
}

TEST(AssemblyErrors, ConflictingRigidElementsAndConstraints) {
  Mesh base = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1, 1, 1, ElementType::Hex8,
                       steel());
  const int r = add_node(base, Eigen::Vector3d(1.5, 0.5, 0.5));
  RigidElement rbe2;
  rbe2.id = 11;
  rbe2.reference = r;
  rbe2.nodes = base.node_sets.at("xmax");
  {
    Mesh mesh = base;
    mesh.rigid_elements = {rbe2, rbe2};
    mesh.rigid_elements[1].id = 12;
    EXPECT_THROW(assemble(mesh), InputError);
  }
  {
    Mesh mesh = base;
    mesh.rigid_elements = {rbe2};
    Constraint c;
    c.node = rbe2.nodes[0];
    mesh.constraints.push_back(c);
    EXPECT_THROW(assemble(mesh), InputError);
  }
  {
    // RBE3 on collinear nodes asked for rotations: rotation about the line undetermined.
    Mesh mesh = base;
    RigidElement rbe3;
    rbe3.kind = RigidElement::Kind::Averaging;
    rbe3.reference = r;
    rbe3.nodes = {1, 2};  // one edge of the x = 1 face
    mesh.rigid_elements = {rbe3};
    EXPECT_THROW(assemble(mesh), InputError);
  }
  {
    Mesh mesh = base;
    mesh.elements[0].nodes[3] = 99;
    EXPECT_THROW(assemble(mesh), InputError);
  }
}

}  // namespace
}  // namespace geardyn::solid
