// Unit tests of the solid element kernels: symmetry, rigid-body null space, mass, quadrature
// exactness against an independent high-order rule, patch test, degenerate elements.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/solid/assembly.hpp"
#include "geardyn/solid/elements.hpp"
#include "geardyn/solid/structured_mesh.hpp"
#include "solid_test_support.hpp"

namespace geardyn::solid {
namespace {

using test::all_types;
using test::steel;

// Nodes of an element: reference nodes mapped by x = x0 + A xi (affine), then, if `perturb` > 0,
// each corner moved by a random vector of size up to perturb * (element size) and each mid-edge
// node by a fifth of that (non-affine, curved edges, still valid).
std::vector<Eigen::Vector3d> element_nodes(ElementType type, double perturb, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d A;
  A << 0.11, 0.02, -0.01, 0.015, 0.09, 0.02, -0.02, 0.01, 0.13;  // det > 0, well conditioned
  const Eigen::Vector3d x0(0.3, -0.2, 0.1);
  const Eigen::MatrixXd r = reference_nodes(type);
  std::vector<Eigen::Vector3d> x;
  for (Eigen::Index i = 0; i < r.rows(); ++i) {
    Eigen::Vector3d p = x0 + A * r.row(i).transpose();
    const double amount = i < num_corner_nodes(type) ? perturb : 0.2 * perturb;
    if (perturb > 0) p += amount * 0.1 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    x.push_back(p);
  }
  return x;
}

// The six rigid-body motions at the nodes (3 translations, 3 small rotations about the origin).
Eigen::MatrixXd rigid_modes(const std::vector<Eigen::Vector3d>& x) {
  const auto n = static_cast<Eigen::Index>(x.size());
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3 * n, 6);
  for (Eigen::Index a = 0; a < n; ++a) {
    const Eigen::Vector3d& p = x[static_cast<std::size_t>(a)];
    R.block<3, 3>(3 * a, 0).setIdentity();
    for (int k = 0; k < 3; ++k) {
      R.block<3, 1>(3 * a, 3 + k) = Eigen::Vector3d::Unit(k).cross(p);
    }
  }
  return R;
}

class ElementTypeTest : public ::testing::TestWithParam<ElementType> {};

// K and M symmetric; K has exactly six (numerically) zero eigenvalues whose eigenspace contains
// the rigid-body motions, on an affine and on a non-affinely distorted element.
//   "Zero": lambda < 1e-10 lambda_max. K is assembled from O(n) Gauss-point contributions, each
//   with relative rounding ~1e-16, so a true zero comes out at ~1e-14 lambda_max; the seventh
//   eigenvalue of these elements is > 1e-4 lambda_max (checked), so the gap is > 6 decades.
TEST_P(ElementTypeTest, StiffnessHasExactlySixRigidBodyModes) {
  const ElementType type = GetParam();
  for (double perturb : {0.0, 0.15}) {
    SCOPED_TRACE(std::string(to_string(type)) + (perturb > 0 ? " distorted" : " affine"));
    const auto x = element_nodes(type, perturb, 7);
    const ElementMatrices em = element_matrices(type, x, steel());
    EXPECT_LT((em.K - em.K.transpose()).norm(), 1e-14 * em.K.norm());
    EXPECT_LT((em.M - em.M.transpose()).norm(), 1e-14 * em.M.norm());
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(em.K);
    const Eigen::VectorXd lam = eig.eigenvalues();
    const double top = lam[lam.size() - 1];  // ascending
    for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(lam[i]), 1e-10 * top) << "eigenvalue " << i;
    EXPECT_GT(lam[6], 1e-4 * top);
    const Eigen::MatrixXd R = rigid_modes(x);
    EXPECT_LT((em.K * R).norm(), 1e-12 * top * R.norm());
    // Mass matrix positive definite (consistent mass of a valid element).
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> meig(em.M);
    EXPECT_GT(meig.eigenvalues().minCoeff(), 0.0);
  }
}

// Total mass: translating the element rigidly in x, 1_x^T M 1_x = rho V, with V = det(A) V_ref
// for the affine element (exact).
TEST_P(ElementTypeTest, TotalMassIsRhoTimesVolume) {
  const ElementType type = GetParam();
  const auto x = element_nodes(type, 0.0, 1);
  const ElementMatrices em = element_matrices(type, x, steel());
  Eigen::Matrix3d A;
  A << 0.11, 0.02, -0.01, 0.015, 0.09, 0.02, -0.02, 0.01, 0.13;
  const double V = A.determinant() * test::reference_volume(type);
  EXPECT_NEAR(em.volume, V, 1e-14 * V);
  for (int d = 0; d < 3; ++d) {
    Eigen::VectorXd one = Eigen::VectorXd::Zero(em.M.rows());
    for (Eigen::Index a = 0; a < one.size() / 3; ++a) one[3 * a + d] = 1.0;
    EXPECT_NEAR(one.dot(em.M * one), steel().rho * V, 1e-13 * steel().rho * V);
  }
}

// The element's mass rule is exact for undistorted elements: compare m_ab = ∫ N_a N_b dV with an
// independent rule far above the needed degree (collapsed Gauss-Legendre, see support header).
// Both integrate a polynomial exactly, so they agree to rounding (1e-13 relative).
TEST_P(ElementTypeTest, MassRuleIsExactForAffineElements) {
  const ElementType type = GetParam();
  const auto x = element_nodes(type, 0.0, 3);
  const Eigen::MatrixXd m = element_shape_mass(type, x);
  const Eigen::MatrixXd ref = test::shape_mass_reference(type, x, 7);
  EXPECT_LT((m - ref).cwiseAbs().maxCoeff(), 1e-13 * ref.cwiseAbs().maxCoeff())
      << "element\n"
      << m << "\nreference\n"
      << ref;
}

// Shape functions: Kronecker property at the nodes, partition of unity, derivatives against
// central finite differences (step 1e-6: truncation ~1e-12, rounding ~1e-10).
TEST_P(ElementTypeTest, ShapeFunctionsInterpolateAndDifferentiate) {
  const ElementType type = GetParam();
  const Eigen::MatrixXd r = reference_nodes(type);
  Eigen::VectorXd N, Np, Nm;
  Eigen::MatrixXd dN, dtmp;
  for (Eigen::Index i = 0; i < r.rows(); ++i) {
    shape_functions(type, r.row(i).transpose(), N, dN);
    for (Eigen::Index a = 0; a < r.rows(); ++a) EXPECT_NEAR(N[a], a == i ? 1.0 : 0.0, 1e-14);
  }
  const Eigen::Vector3d xi(0.21, 0.17,
                           type == ElementType::Tet4 || type == ElementType::Tet10 ? 0.31 : -0.43);
  shape_functions(type, xi, N, dN);
  EXPECT_NEAR(N.sum(), 1.0, 1e-14);
  const double h = 1e-6;
  for (int d = 0; d < 3; ++d) {
    shape_functions(type, xi + h * Eigen::Vector3d::Unit(d), Np, dtmp);
    shape_functions(type, xi - h * Eigen::Vector3d::Unit(d), Nm, dtmp);
    EXPECT_LT(((Np - Nm) / (2 * h) - dN.col(d)).cwiseAbs().maxCoeff(), 1e-8);
  }
}

// Patch test (Irons; MacNeal & Harder, "A proposed standard set of problems to test finite
// element accuracy", Finite Elem. Anal. Des. 1 (1985) 3-20): a 3x3x3-cell box of the element type
// with every interior corner node moved randomly by up to 15 % of the cell size and the mid-edge
// nodes kept at the middle of their (now skewed, straight) edges. The boundary nodes get
// u = u0 + G x (G general: stretch, shear and rotation) and the interior nodes are solved for
// from K. The isoparametric elements contain the linear field and their stiffness rules are
// exact for straight-edged elements, so the interior nodes reproduce the field and the strain is
// the constant sym(G) everywhere. Tolerance 1e-10 relative: the solve's error is about
// cond(K_ii) eps, and cond(K_ii) < 1e5 for this patch.
TEST_P(ElementTypeTest, DistortedPatchReproducesLinearField) {
  const ElementType type = GetParam();
  Mesh mesh =
      box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.0, 1.2, 0.8), 3, 3, 3, type, steel());
  std::vector<char> boundary(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (const auto& [name, nodes] : mesh.node_sets) {
    for (int n : nodes) boundary[static_cast<std::size_t>(n)] = 1;
  }
  std::vector<char> corner(static_cast<std::size_t>(mesh.num_nodes()), 0);
  const int nc = num_corner_nodes(type);
  for (const Element& e : mesh.elements) {
    for (int k = 0; k < nc; ++k)
      corner[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(k)])] = 1;
  }
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = 0.8 / 3;
  int moved = 0;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    if (boundary[static_cast<std::size_t>(n)] || !corner[static_cast<std::size_t>(n)]) continue;
    mesh.coords[static_cast<std::size_t>(n)] += 0.15 * h * Eigen::Vector3d(u(rng), u(rng), u(rng));
    ++moved;
  }
  const auto edges = element_edges(type);
  for (const Element& e : mesh.elements) {
    for (std::size_t k = 0; k < edges.size(); ++k) {
      const auto& ed = edges[k];
      mesh.coords[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(nc) + k])] =
          0.5 * (mesh.coords[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(ed[0])])] +
                 mesh.coords[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(ed[1])])]);
    }
  }
  ASSERT_GT(moved, 0);
  const SolidSystem sys = assemble(mesh);
  ASSERT_EQ(sys.num_dofs(), 3 * mesh.num_nodes());
  Eigen::Matrix3d G;
  G << 1.0e-3, 2.0e-4, -3.0e-4, -1.0e-4, -5.0e-4, 4.0e-4, 3.0e-4, 1.0e-4, 8.0e-4;
  const Eigen::Vector3d u0(1e-3, -2e-3, 5e-4);
  auto field = [&](const Eigen::Vector3d& p) { return Eigen::Vector3d(u0 + G * p); };
  const Eigen::VectorXd solution = test::solve_with_prescribed(sys, mesh, boundary, field);
  double err = 0;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const Eigen::Vector3d exact = field(mesh.coords[static_cast<std::size_t>(n)]);
    for (int c = 0; c < 3; ++c) {
      err = std::max(err, std::abs(solution[sys.node_dof(n, c)] - exact[c]));
    }
  }
  EXPECT_LT(err, 1e-10 * G.norm()) << to_string(type);
  // Constant strain sym(G) at points inside every element.
  const Eigen::Matrix3d eps_exact = 0.5 * (G + G.transpose());
  double strain_err = 0;
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (const Element& e : mesh.elements) {
    const Eigen::Vector3d xi =
        type == ElementType::Hex8 || type == ElementType::Hex20
            ? Eigen::Vector3d(0.3, -0.5, 0.7)
            : Eigen::Vector3d(0.2, 0.3,
                              type == ElementType::Tet4 || type == ElementType::Tet10 ? 0.1 : -0.6);
    shape_functions(type, xi, N, dN);
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero(), grad = Eigen::Matrix3d::Zero();
    for (std::size_t a = 0; a < e.nodes.size(); ++a) {
      J += mesh.coords[static_cast<std::size_t>(e.nodes[a])] * dN.row(static_cast<Eigen::Index>(a));
    }
    const Eigen::MatrixXd g = dN * J.inverse();
    for (std::size_t a = 0; a < e.nodes.size(); ++a) {
      Eigen::Vector3d ua;
      for (int c = 0; c < 3; ++c) ua[c] = solution[sys.node_dof(e.nodes[a], c)];
      grad += ua * g.row(static_cast<Eigen::Index>(a));
    }
    strain_err = std::max(strain_err, (0.5 * (grad + grad.transpose()) - eps_exact).norm());
  }
  EXPECT_LT(strain_err, 1e-9 * eps_exact.norm());
}

INSTANTIATE_TEST_SUITE_P(AllTypes, ElementTypeTest, ::testing::ValuesIn(all_types()),
                         [](const auto& param_info) {
                           return std::string(to_string(param_info.param));
                         });

// An inverted tet (two corners swapped) and a hex20 with a mid-edge node pulled through the
// element are rejected with the element id and its source location.
TEST(ElementErrors, InvertedElementNamesItsId) {
  auto x = element_nodes(ElementType::Tet4, 0.0, 1);
  std::swap(x[1], x[2]);
  try {
    element_matrices(ElementType::Tet4, x, steel(), 1234, SourceLocation{"model.bdf", 77, 1});
    FAIL() << "no InputError for an inverted tet";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "elements[id 1234]");
    EXPECT_NE(std::string(e.what()).find("model.bdf:77"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("inverted"), std::string::npos) << e.what();
  }
  EXPECT_LT(element_min_jacobian(ElementType::Tet4, x), 0.0);

  auto y = element_nodes(ElementType::Hex20, 0.0, 1);
  y[8] = y[2] + 0.5 * (y[2] - y[8]);  // mid-edge node of edge (0,1) far beyond corner 2
  EXPECT_THROW(element_matrices(ElementType::Hex20, y, steel(), 55), InputError);

  // A flat (zero-volume) tet: degenerate.
  std::vector<Eigen::Vector3d> flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  EXPECT_THROW(element_matrices(ElementType::Tet4, flat, steel(), 9), InputError);

  // Through the mesh: the error names the element of the mesh.
  Mesh mesh = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 2, 1, 1, ElementType::Hex8,
                       steel());
  mesh.elements[1].id = 4321;
  mesh.elements[1].where = SourceLocation{"wheel.msh", 12, 0};
  std::swap(mesh.elements[1].nodes[0], mesh.elements[1].nodes[4]);
  try {
    assemble(mesh);
    FAIL() << "no InputError for an inverted hex in a mesh";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "elements[id 4321]");
    EXPECT_EQ(e.where().file, "wheel.msh");
  }
}

TEST(ElementErrors, BadMaterialAndNodeCount) {
  Material m = steel();
  m.nu = 0.5;
  const auto x = element_nodes(ElementType::Hex8, 0.0, 1);
  EXPECT_THROW(element_matrices(ElementType::Hex8, x, m), InputError);
  std::vector<Eigen::Vector3d> short_list(x.begin(), x.begin() + 5);
  EXPECT_THROW(element_matrices(ElementType::Hex8, short_list, steel()), InputError);
}

// A distorted element stays accepted and its quality ratio reflects the distortion.
TEST(ElementQualityTest, RatioIsOneForAffineAndBelowForDistorted) {
  for (ElementType type : all_types()) {
    EXPECT_NEAR(element_min_jacobian(type, element_nodes(type, 0.0, 2)), 1.0, 1e-12)
        << to_string(type);
    const double q = element_min_jacobian(type, element_nodes(type, 0.15, 2));
    EXPECT_GT(q, kMinJacobianRatio) << to_string(type);
    if (type != ElementType::Tet4) {  // a tet4 is always affine
      EXPECT_LT(q, 1.0 - 1e-3) << to_string(type);
    }
  }
}

}  // namespace
}  // namespace geardyn::solid
