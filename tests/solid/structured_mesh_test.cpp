// Unit tests of the structured mesh generators: node counts, volumes, node sets, and the exact
// rotational periodicity of the annular sector's left and right faces.
#include "geardyn/solid/structured_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/core/error.hpp"
#include "geardyn/solid/assembly.hpp"
#include "solid_test_support.hpp"

namespace geardyn::solid {
namespace {

using test::all_types;
using test::steel;

// Node count of an nx x ny x nz box: linear types use the (n+1)^3 cell corners; hex20 adds one
// node per cell edge; tet10 and wedge15 use more mid-edge nodes (face / cell diagonals).
TEST(BoxMesh, CountsVolumesAndFaceSets) {
  const int nx = 3, ny = 2, nz = 2;
  const Eigen::Vector3d lo(-0.1, 0.0, 0.2), hi(0.5, 0.2, 0.3);
  const double V = (hi - lo).prod();
  for (ElementType type : all_types()) {
    SCOPED_TRACE(std::string(to_string(type)));
    const Mesh mesh = box_mesh(lo, hi, nx, ny, nz, type, steel());
    const int corners = (nx + 1) * (ny + 1) * (nz + 1);
    const int edges =
        nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
    switch (type) {
      case ElementType::Hex8:
      case ElementType::Tet4:
      case ElementType::Wedge6:
        EXPECT_EQ(mesh.num_nodes(), corners);
        break;
      case ElementType::Hex20:
        EXPECT_EQ(mesh.num_nodes(), corners + edges);
        break;
      case ElementType::Tet10:  // + face diagonals (3 families) + body diagonals
        EXPECT_EQ(mesh.num_nodes(), (2 * nx + 1) * (2 * ny + 1) * (2 * nz + 1));
        break;
      case ElementType::Wedge15:  // + one diagonal per cell face normal to z
        EXPECT_EQ(mesh.num_nodes(), corners + edges + nx * ny * (nz + 1));
        break;
    }
    const int per_cell = type == ElementType::Tet4 || type == ElementType::Tet10       ? 6
                         : type == ElementType::Wedge6 || type == ElementType::Wedge15 ? 2
                                                                                       : 1;
    EXPECT_EQ(mesh.num_elements(), per_cell * nx * ny * nz);
    const SolidSystem sys = assemble(mesh);
    EXPECT_NEAR(sys.volume, V, 1e-14);
    EXPECT_EQ(sys.num_dofs(), 3 * mesh.num_nodes());  // every node used
    for (int n : mesh.node_sets.at("xmin"))
      EXPECT_EQ(mesh.coords[static_cast<std::size_t>(n)].x(), lo.x());
    for (int n : mesh.node_sets.at("zmax"))
      EXPECT_EQ(mesh.coords[static_cast<std::size_t>(n)].z(), hi.z());
    EXPECT_EQ(mesh.node_sets.size(), 6u);
  }
  EXPECT_THROW(box_mesh(lo, hi, 0, 1, 1, ElementType::Hex8, steel()), InputError);
  EXPECT_THROW(box_mesh(hi, lo, 1, 1, 1, ElementType::Hex8, steel()), InputError);
}

// Sector of 30 degrees: right-face nodes are the left-face nodes rotated by the angle, pairwise in
// set order, to rounding (1e-15 relative); all elements valid; inner/outer/top/bottom radii and
// heights exact.
TEST(AnnularSectorMesh, RightFaceIsLeftFaceRotated) {
  const double angle = std::numbers::pi / 6, ri = 0.05, ro = 0.2, t = 0.02;
  for (ElementType type : all_types()) {
    SCOPED_TRACE(std::string(to_string(type)));
    const Mesh mesh = annular_sector_mesh(ri, ro, t, angle, 3, 4, 2, type, steel());
    const auto& left = mesh.node_sets.at("left");
    const auto& right = mesh.node_sets.at("right");
    ASSERT_EQ(left.size(), right.size());
    const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    for (std::size_t k = 0; k < left.size(); ++k) {
      const Eigen::Vector3d xl = mesh.coords[static_cast<std::size_t>(left[k])];
      const Eigen::Vector3d xr = mesh.coords[static_cast<std::size_t>(right[k])];
      EXPECT_LT((R * xl - xr).norm(), 1e-15 * ro);
      EXPECT_EQ(xl.z(), xr.z());
      EXPECT_NEAR(xl.y(), 0.0, 1e-15);
    }
    for (int n : mesh.node_sets.at("inner")) {
      EXPECT_NEAR(mesh.coords[static_cast<std::size_t>(n)].head<2>().norm(), ri, 1e-15);
    }
    for (int n : mesh.node_sets.at("top"))
      EXPECT_EQ(mesh.coords[static_cast<std::size_t>(n)].z(), t / 2);
    const SolidSystem sys = assemble(mesh);  // throws for an invalid element
    EXPECT_GT(sys.volume, 0.0);
  }
}

// Closed annulus: seam merged (no left/right sets, node count without duplicates), every node
// used. Volume: hex8 (straight chords) is the polygonal annulus
//   V = n/2 sin(2 pi / n) (ro^2 - ri^2) t  exactly; hex20 (mid-nodes on the arcs) approaches
// pi (ro^2 - ri^2) t with error O((2 pi / n)^4): < 1e-5 relative for n = 24.
TEST(AnnularSectorMesh, ClosedAnnulusIsMerged) {
  const double ri = 0.05, ro = 0.2, t = 0.02;
  const int nr = 2, nth = 24, nz = 1;
  const Mesh hex8 =
      annular_sector_mesh(ri, ro, t, 2 * std::numbers::pi, nr, nth, nz, ElementType::Hex8, steel());
  EXPECT_EQ(hex8.node_sets.count("left"), 0u);
  EXPECT_EQ(hex8.node_sets.count("right"), 0u);
  EXPECT_EQ(hex8.num_nodes(), (nr + 1) * nth * (nz + 1));
  const SolidSystem s8 = assemble(hex8);
  const double polygon = nth / 2.0 * std::sin(2 * std::numbers::pi / nth) * (ro * ro - ri * ri) * t;
  EXPECT_NEAR(s8.volume, polygon, 1e-14 * polygon);
  const Mesh hex20 = annular_sector_mesh(ri, ro, t, 2 * std::numbers::pi, nr, nth, nz,
                                         ElementType::Hex20, steel());
  const SolidSystem s20 = assemble(hex20);
  const double exact = std::numbers::pi * (ro * ro - ri * ri) * t;
  EXPECT_NEAR(s20.volume, exact, 1e-5 * exact);
  // Free annulus: six rigid-body modes only, checked through rigid translations/rotations.
  Eigen::VectorXd q(s20.num_dofs());
  for (int i = 0; i < s20.num_dofs(); ++i) {
    const DofInfo& d = s20.dofs[static_cast<std::size_t>(i)];
    q[i] = Eigen::Vector3d::UnitZ().cross(d.x)[d.component];
  }
  EXPECT_LT((s20.K * q).norm(), 1e-12 * s20.K.cwiseAbs().sum() / s20.num_dofs() * q.norm());
  EXPECT_THROW(
      annular_sector_mesh(ri, ro, t, 2 * std::numbers::pi, 1, 2, 1, ElementType::Hex8, steel()),
      InputError);
  EXPECT_THROW(annular_sector_mesh(0.0, ro, t, 1.0, 1, 2, 1, ElementType::Hex8, steel()),
               InputError);
}

}  // namespace
}  // namespace geardyn::solid
