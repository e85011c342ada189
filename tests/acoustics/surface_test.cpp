// Exterior surfaces of solid meshes (acoustics/surface.hpp): a unit cube of every element type has
// area 6 (its faces are flat, so every quadrature is exact up to round-off: tolerance 1e-12),
// outward face and node normals, lumped areas that are positive and sum to the area; node sets
// select faces, and a set that is not on the exterior is an error naming its sizes.
#include "geardyn/acoustics/surface.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "acoustics/cubed_sphere.hpp"
#include "geardyn/acoustics/radiation.hpp"
#include "geardyn/solid/structured_mesh.hpp"

namespace geardyn::acoustics {
namespace {

using solid::ElementType;

const solid::Material kSteel{"steel", 1, 2.1e11, 0.3, 7850, {}};

solid::Mesh unit_cube(ElementType type, int n = 2) {
  return solid::box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), n, n, n, type, kSteel);
}

class UnitCube : public ::testing::TestWithParam<ElementType> {};

TEST_P(UnitCube, AreaSixOutwardNormalsAndLumpedAreasSumToTheArea) {
  const solid::Mesh mesh = unit_cube(GetParam());
  const Surface s = exterior_surface(mesh);
  const Eigen::Vector3d centre(0.5, 0.5, 0.5);
  EXPECT_NEAR(s.area(), 6.0, 1e-12);
  EXPECT_NEAR(s.node_area.sum(), 6.0, 1e-12);
  // Faces per side: 2 x 2 cells; tets split each cell face into 2 triangles, wedges (extruded
  // along z) have triangles on the z faces.
  const std::size_t per_side = 4;
  const std::size_t expected_faces =
      GetParam() == ElementType::Tet4 || GetParam() == ElementType::Tet10       ? 12 * per_side
      : GetParam() == ElementType::Wedge6 || GetParam() == ElementType::Wedge15 ? 8 * per_side
                                                                                : 6 * per_side;
  EXPECT_EQ(s.faces.size(), expected_faces);
  for (const SurfaceFace& f : s.faces) {
    // Each face lies on a side of the cube: its normal is that side's outward axis.
    const Eigen::Vector3d d = f.centroid - centre;
    int axis = 0;
    d.cwiseAbs().maxCoeff(&axis);
    EXPECT_NEAR(std::abs(d[axis]), 0.5, 1e-12);
    EXPECT_NEAR(f.normal[axis], d[axis] > 0 ? 1.0 : -1.0, 1e-12);
    double weights = 0;
    for (double w : f.node_weight) weights += w;
    EXPECT_NEAR(weights, f.area, 1e-14);
    // Counter-clockwise seen from outside: the first corners' cross product points outward.
    const auto& x = [&](int k) {
      return mesh.coords[static_cast<std::size_t>(
          s.nodes[static_cast<std::size_t>(f.nodes[static_cast<std::size_t>(k)])])];
    };
    EXPECT_GT((x(1) - x(0)).cross(x(2) - x(0)).dot(f.normal), 0.0);
  }
  for (int i = 0; i < s.num_nodes(); ++i) {
    EXPECT_GT(s.node_area[i], 0.0) << "node " << s.nodes[static_cast<std::size_t>(i)];
    EXPECT_NEAR(s.node_normal.col(i).norm(), 1.0, 1e-12);
    const Eigen::Vector3d& x =
        mesh.coords[static_cast<std::size_t>(s.nodes[static_cast<std::size_t>(i)])];
    EXPECT_GT(s.node_normal.col(i).dot(x - centre), 0.0);
  }
  // A node in the middle of the +z side has the normal +z; no interior node is on the surface.
  for (int i = 0; i < s.num_nodes(); ++i) {
    const Eigen::Vector3d& x =
        mesh.coords[static_cast<std::size_t>(s.nodes[static_cast<std::size_t>(i)])];
    EXPECT_TRUE((x.array() < 1e-12).any() || (x.array() > 1 - 1e-12).any());
    if ((x - Eigen::Vector3d(0.5, 0.5, 1.0)).norm() < 1e-12) {
      EXPECT_NEAR(s.node_normal(2, i), 1.0, 1e-12);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllElementTypes, UnitCube,
                         ::testing::Values(ElementType::Hex8, ElementType::Tet4, ElementType::Hex20,
                                           ElementType::Tet10, ElementType::Wedge6,
                                           ElementType::Wedge15),
                         [](const auto& p) { return std::string(solid::to_string(p.param)); });

TEST(ExteriorSurface, FlatQuadraticFacesLumpByDiagonalScaling) {
  // One flat 8-node quad of area 1 ([0,1]^2): the row sums int N_i dA are -1/12 at the corners
  // and 1/3 at the mid-sides (Zienkiewicz, Taylor and Zhu, "The Finite Element Method: Its Basis
  // and Fundamentals", 2005, serendipity element); diagonal scaling (Hinton, Rock and Zienkiewicz
  // 1976) gives int N_i^2 dA = 1/30 (corner) and 8/45 (mid-side), scaled to sum 1: 3/76, 16/76.
  const solid::Mesh mesh = unit_cube(ElementType::Hex20, 1);
  const Surface s = exterior_surface(mesh, mesh.node_sets.at("zmax"));
  ASSERT_EQ(s.faces.size(), 1u);
  const SurfaceFace& f = s.faces.front();
  for (std::size_t k = 0; k < 8; ++k)
    EXPECT_NEAR(f.node_weight[k], k < 4 ? 3.0 / 76 : 16.0 / 76, 1e-14) << k;
}

TEST(ExteriorSurface, NodeSetSelectsTheFacesItCovers) {
  const solid::Mesh mesh = unit_cube(ElementType::Hex20, 3);
  const Surface top = exterior_surface(mesh, mesh.node_sets.at("zmax"));
  EXPECT_EQ(top.faces.size(), 9u);
  EXPECT_NEAR(top.area(), 1.0, 1e-12);
  EXPECT_EQ(top.nodes, mesh.node_sets.at("zmax"));  // 7 x 7 grid minus the 4 x 4 cell centres
  for (const SurfaceFace& f : top.faces) EXPECT_NEAR(f.normal.z(), 1.0, 1e-12);
}

TEST(ExteriorSurface, NodeSetNotOnTheExteriorIsAnError) {
  const solid::Mesh mesh = unit_cube(ElementType::Hex8, 4);
  std::vector<int> inside;  // the nodes of the plane z = 0.5, all but its rim inside the cube
  for (int i = 0; i < mesh.num_nodes(); ++i)
    if (std::abs(mesh.coords[static_cast<std::size_t>(i)].z() - 0.5) < 1e-12 &&
        mesh.coords[static_cast<std::size_t>(i)].x() > 0.1 &&
        mesh.coords[static_cast<std::size_t>(i)].x() < 0.9 &&
        mesh.coords[static_cast<std::size_t>(i)].y() > 0.1 &&
        mesh.coords[static_cast<std::size_t>(i)].y() < 0.9)
      inside.push_back(i);
  ASSERT_EQ(inside.size(), 9u);
  try {
    exterior_surface(mesh, inside);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("9 nodes, 0 of them on the exterior"), std::string::npos) << message;
    EXPECT_NE(message.find("none lies on the exterior"), std::string::npos) << message;
  }
  // A single edge of the cube is on the exterior but covers no face.
  std::vector<int> edge;
  for (int i = 0; i < mesh.num_nodes(); ++i)
    if (mesh.coords[static_cast<std::size_t>(i)].head<2>().norm() < 1e-12) edge.push_back(i);
  try {
    exterior_surface(mesh, edge);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("5 nodes, 5 of them on the exterior"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(exterior_surface(mesh, {mesh.num_nodes()}), std::invalid_argument);
}

TEST(ExteriorSurface, ShellHasTwoSpheresAndCurvedQuadraticFaces) {
  // The cubed-sphere shell has an outer and an inner sphere (radius 0.9 r). The hex20 faces are
  // curved: their area converges to 4 pi r^2 at fourth order, the flat hex8 faces' at second
  // (measured relative errors at 6 and 12 cells per cube face: hex8 1.5e-2 -> 3.7e-3, hex20
  // 1.5e-4 -> 9.7e-6); asserted: the ratios > 3.5 and > 12, and the outer node normals within
  // 8 degrees of radial (cos > 0.99).
  const double r = 0.15;
  for (auto [type, ratio] : {std::pair{ElementType::Hex8, 3.5}, {ElementType::Hex20, 12.0}}) {
    double previous = 0;
    for (const int n : {6, 12}) {
      const solid::Mesh mesh = testing::cubed_sphere_shell(0.9 * r, r, n, type);
      const Surface all = exterior_surface(mesh);
      const std::size_t per_sphere = 6u * static_cast<std::size_t>(n * n);
      EXPECT_EQ(all.faces.size(), 2 * per_sphere);
      const Surface outer = exterior_surface(mesh, mesh.node_sets.at("outer"));
      EXPECT_EQ(outer.faces.size(), per_sphere);
      const double exact = 4 * std::numbers::pi * r * r;
      const double error = std::abs(outer.area() / exact - 1);
      // The inner sphere is the outer one scaled by 0.9: the same relative error.
      EXPECT_NEAR(all.area() / (exact * 1.81) - 1, outer.area() / exact - 1, 1e-12);
      if (n == 12) {
        EXPECT_GT(previous / error, ratio) << solid::to_string(type);
      }
      previous = error;
      for (int i = 0; i < outer.num_nodes(); ++i) {
        const Eigen::Vector3d radial =
            mesh.coords[static_cast<std::size_t>(outer.nodes[static_cast<std::size_t>(i)])]
                .normalized();
        EXPECT_GT(outer.node_normal.col(i).dot(radial), 0.99);
      }
    }
  }
}

TEST(ExteriorSurface, DofRowsOfTheSurfaceNodes) {
  // DOFs listed node-major in reverse node order with a rotation in between: the rows must be
  // found by node id and component, not by position.
  const solid::Mesh mesh = unit_cube(ElementType::Hex8, 1);
  std::vector<solid::DofInfo> dofs;
  for (int n = mesh.num_nodes() - 1; n >= 0; --n)
    for (int c : {3, 2, 1, 0})
      dofs.push_back({mesh.node_ids[static_cast<std::size_t>(n)], c,
                      mesh.coords[static_cast<std::size_t>(n)]});
  const Surface s = exterior_surface(mesh, mesh.node_sets.at("xmax"));
  const std::vector<int> rows = surface_dof_rows(mesh, s, dofs);
  ASSERT_EQ(rows.size(), 3u * s.nodes.size());
  for (std::size_t i = 0; i < s.nodes.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const solid::DofInfo& d =
          dofs[static_cast<std::size_t>(rows[3 * i + static_cast<std::size_t>(c)])];
      EXPECT_EQ(d.node_id, mesh.node_ids[static_cast<std::size_t>(s.nodes[i])]);
      EXPECT_EQ(d.component, c);
    }
  dofs.erase(dofs.begin() + 2);  // node 8's uy (listed 3, 2, 1, 0): constrained away
  try {
    surface_dof_rows(mesh, s, dofs);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("surface node 8 (mesh node index 7) has no uy"),
              std::string::npos)
        << e.what();
  }
}

TEST(ErpOperator, PowerEqualsErpOfTheExpandedVelocities) {
  // W = R_n^T diag(A) R_n is an exact rewriting of the sum: agreement to round-off (1e-12).
  const solid::Mesh mesh = unit_cube(ElementType::Hex20, 2);
  const Surface s = exterior_surface(mesh);
  std::mt19937 rng(17);
  std::normal_distribution<double> normal;
  const int m = 7;
  Eigen::MatrixXd R(3 * s.num_nodes(), m);
  for (Eigen::Index i = 0; i < R.size(); ++i) R.data()[i] = normal(rng);
  Eigen::VectorXcd q(m);
  for (int k = 0; k < m; ++k) q[k] = {normal(rng), normal(rng)};
  const ErpOperator op(s, R);
  const Air air;
  const double omega = 2 * std::numbers::pi * 850;
  const Eigen::VectorXcd u = R.cast<std::complex<double>>() * q;
  const Eigen::VectorXcd vn = normal_velocity(s, u, omega);
  const double direct = erp(s, vn, air, 0.7);
  EXPECT_NEAR(op.power(q, omega, air, 0.7), direct, 1e-12 * direct);
  EXPECT_NEAR((op.normal_velocity(q, omega) - vn).norm(), 0.0, 1e-12 * vn.norm());
  EXPECT_NEAR(face_erp(s, vn, air, 0.7).sum(), direct, 1e-12 * direct);
  const double v = op.mean_normal_velocity(q, omega);
  EXPECT_NEAR(0.5 * air.impedance() * 0.7 * op.area() * v * v, direct, 1e-12 * direct);
  EXPECT_NEAR(op.area(), 6.0, 1e-12);
  EXPECT_THROW(op.power(Eigen::VectorXcd::Zero(m + 1), omega, air), std::invalid_argument);
  EXPECT_THROW(ErpOperator(s, R.topRows(R.rows() - 3)), std::invalid_argument);
  EXPECT_THROW(erp(s, vn.head(3), air), std::invalid_argument);
}

}  // namespace
}  // namespace geardyn::acoustics
