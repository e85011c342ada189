// Tests of the structured annular-plate generator (meshgen/annular_plate.hpp).
//
//        theta = alpha (right)
//          /
//         /______    r = a (outer)
//  r = b  |       )        thickness h (z = -h/2 .. h/2), axis z
//  (inner)|_______)  theta = 0 (left)
//
// Oracles: volume pi (a^2 - b^2) h alpha / (2 pi) for curved quadratic elements; the exact
// volume of the inscribed polygonal annulus for linear elements; node counts of the structured
// grid; periodic left/right pairs; element validity (det J > 0).
#include "geardyn/meshgen/annular_plate.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "mesh_checks.hpp"

namespace geardyn::meshgen {
namespace {

constexpr double kPi = std::numbers::pi;

AnnularPlateParams plate(double angle, int order, PlateElementShape shape) {
  AnnularPlateParams p;
  p.inner_radius = 0.05;
  p.outer_radius = 0.15;
  p.thickness = 0.005;  // h / a = 1 / 30
  p.sector_angle = angle;
  p.element_order = order;
  p.shape = shape;
  p.elements_radial = 4;
  p.elements_circumferential = 6;
  p.elements_through_thickness = 2;
  p.material = {"steel", 1, 210e9, 0.3, 7850, {}};
  return p;
}

double total_volume(const solid::Mesh& mesh, double* worst_jacobian) {
  double v = 0;
  *worst_jacobian = 1e300;
  for (const solid::Element& e : mesh.elements) {
    v += test::element_volume(mesh, e);
    *worst_jacobian = std::min(*worst_jacobian, test::min_relative_jacobian(mesh, e));
  }
  return v;
}

void expect_periodic(const solid::Mesh& mesh, double angle) {
  const std::vector<int>& left = mesh.node_sets.at("left");
  const std::vector<int>& right = mesh.node_sets.at("right");
  ASSERT_EQ(left.size(), right.size());
  ASSERT_FALSE(left.empty());
  for (std::size_t i = 0; i < left.size(); ++i)
    EXPECT_LT((test::rotate_z(mesh.coords[static_cast<std::size_t>(left[i])], angle) -
               mesh.coords[static_cast<std::size_t>(right[i])])
                  .norm(),
              1e-9 * 0.15);
}

// Hex20 sector of 45 degrees, 4 x 6 x 2 elements: arcs of 7.5 degrees carried by parabolas,
// relative area error ~ (7.5 deg in rad)^4 / 180 ~ 1e-6; tolerance 1e-5.
TEST(AnnularPlate, QuadraticHexSectorVolumeAndPeriodicity) {
  const double angle = 2 * kPi / 8;
  const solid::Mesh mesh = annular_plate(plate(angle, 2, PlateElementShape::Hex));
  ASSERT_EQ(mesh.num_elements(), 4 * 6 * 2);
  for (const solid::Element& e : mesh.elements) EXPECT_EQ(e.type, solid::ElementType::Hex20);
  // Serendipity grid: corner grid (5 x 7 x 3) plus mid-edge nodes.
  const int corners = 5 * 7 * 3;
  const int edges = (4 * 7 + 5 * 6) * 3 + 5 * 7 * 2;
  EXPECT_EQ(mesh.num_nodes(), corners + edges);
  double worst = 0;
  const double v = total_volume(mesh, &worst);
  EXPECT_GT(worst, 0.0);
  EXPECT_NEAR(v / (kPi * (0.15 * 0.15 - 0.05 * 0.05) * 0.005 / 8), 1.0, 1e-5);
  expect_periodic(mesh, angle);
  for (int n : mesh.node_sets.at("inner"))
    EXPECT_NEAR(test::radius(mesh.coords[static_cast<std::size_t>(n)]), 0.05, 1e-12);
  for (int n : mesh.node_sets.at("outer"))
    EXPECT_NEAR(test::radius(mesh.coords[static_cast<std::size_t>(n)]), 0.15, 1e-12);
  // 3 node rows of 13 (corner levels) + 2 rows of 7 (mid-thickness; no face-centre nodes).
  EXPECT_EQ(mesh.node_sets.at("inner").size(), 13u * 3u + 7u * 2u);
  for (int n : mesh.node_sets.at("top"))
    EXPECT_NEAR(mesh.coords[static_cast<std::size_t>(n)].z(), 0.0025, 1e-15);
}

TEST(AnnularPlate, QuadraticWedgeSectorVolume) {
  const double angle = 2 * kPi / 8;
  const solid::Mesh mesh = annular_plate(plate(angle, 2, PlateElementShape::Wedge));
  EXPECT_EQ(mesh.num_elements(), 2 * 4 * 6 * 2);
  for (const solid::Element& e : mesh.elements) EXPECT_EQ(e.type, solid::ElementType::Wedge15);
  double worst = 0;
  const double v = total_volume(mesh, &worst);
  EXPECT_GT(worst, 0.0);
  EXPECT_NEAR(v / (kPi * (0.15 * 0.15 - 0.05 * 0.05) * 0.005 / 8), 1.0, 1e-5);
  expect_periodic(mesh, angle);
}

// Full plate with linear hexes: the mesh is exactly the polygonal annulus with n = 24 sides,
// area (n/2) sin(2 pi / n) (a^2 - b^2); agreement to round-off.
TEST(AnnularPlate, LinearFullPlateIsThePolygonalAnnulus) {
  AnnularPlateParams p = plate(2 * kPi, 1, PlateElementShape::Hex);
  p.elements_circumferential = 24;
  const solid::Mesh mesh = annular_plate(p);
  EXPECT_EQ(mesh.num_nodes(), 5 * 24 * 3);  // closed ring: no duplicate seam nodes
  EXPECT_EQ(mesh.node_sets.count("left"), 0u);
  double worst = 0;
  const double v = total_volume(mesh, &worst);
  EXPECT_GT(worst, 0.0);
  const double polygon = 12 * std::sin(2 * kPi / 24) * (0.15 * 0.15 - 0.05 * 0.05) * 0.005;
  EXPECT_NEAR(v / polygon, 1.0, 1e-12);
}

TEST(AnnularPlate, MeshSizeSetsTheDivisions) {
  AnnularPlateParams p = plate(kPi / 2, 1, PlateElementShape::Hex);
  p.elements_radial = 0;
  p.elements_circumferential = 0;
  p.mesh_size = 0.02;
  const solid::Mesh mesh = annular_plate(p);
  // n_r = ceil(0.1 / 0.02) = 5, n_theta = ceil(pi/2 * 0.15 / 0.02) = 12.
  EXPECT_EQ(mesh.num_elements(), 5 * 12 * 2);
}

// Solid disc (inner_radius = 0), linear hexes, n_theta = 24 (n_q = 6 per quarter), n_r = 4:
// the mesh is exactly the inscribed 24-gon of radius a (the centre square and the ring's inner
// edges are straight), area 12 sin(2 pi / 24) a^2; in-plane nodes (n_q + 1)^2 + 4 n_q n_r, each
// once (the centre is meshed once), elements (n_q^2 + 4 n_q n_r) per layer, none degenerate.
TEST(AnnularPlate, LinearSolidDiscIsThePolygonWithoutDuplicateNodes) {
  AnnularPlateParams p = plate(2 * kPi, 1, PlateElementShape::Hex);
  p.inner_radius = 0.0;
  p.elements_circumferential = 22;  // rounded up to 24, a multiple of 4
  const solid::Mesh mesh = annular_plate(p);
  EXPECT_EQ(mesh.num_nodes(), (7 * 7 + 4 * 6 * 4) * 3);
  EXPECT_EQ(mesh.num_elements(), (6 * 6 + 4 * 6 * 4) * 2);
  EXPECT_EQ(mesh.node_sets.count("inner"), 0u);
  EXPECT_EQ(mesh.node_sets.at("outer").size(), 24u * 3);
  for (int i = 0; i < mesh.num_nodes(); ++i)
    for (int j = 0; j < i; ++j)
      ASSERT_GT(
          (mesh.coords[static_cast<std::size_t>(i)] - mesh.coords[static_cast<std::size_t>(j)])
              .norm(),
          1e-6)
          << "nodes " << i << " and " << j << " coincide";
  double worst = 0;
  const double v = total_volume(mesh, &worst);
  // No element is collapsed: the smallest det J of any element is at least 1/10 of its largest
  // (the O-grid's worst element is the ring's, at a square corner).
  EXPECT_GT(worst, 0.1);
  const double polygon = 12 * std::sin(2 * kPi / 24) * 0.15 * 0.15 * 0.005;
  EXPECT_NEAR(v / polygon, 1.0, 1e-12);
}

// Quadratic solid discs, hex20 and wedge15, n_theta = 48 (arcs of 7.5 degrees carried by
// parabolas: relative area error ~ 1e-6, tolerance 1e-5): volume pi a^2 h.
TEST(AnnularPlate, QuadraticSolidDiscVolume) {
  for (const PlateElementShape shape : {PlateElementShape::Hex, PlateElementShape::Wedge}) {
    AnnularPlateParams p = plate(2 * kPi, 2, shape);
    p.inner_radius = 0.0;
    p.elements_circumferential = 48;
    const solid::Mesh mesh = annular_plate(p);
    double worst = 0;
    const double v = total_volume(mesh, &worst);
    EXPECT_GT(worst, 0.1);
    EXPECT_NEAR(v / (kPi * 0.15 * 0.15 * 0.005), 1.0, 1e-5);
    for (int n : mesh.node_sets.at("outer"))
      EXPECT_NEAR(test::radius(mesh.coords[static_cast<std::size_t>(n)]), 0.15, 1e-12);
  }
}

TEST(AnnularPlate, BadParametersNameTheKey) {
  auto expect_key = [](const AnnularPlateParams& p, const std::string& key) {
    try {
      validate(p);
      ADD_FAILURE() << "no InputError for " << key;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key_path(), key) << e.what();
    }
  };
  auto p = plate(kPi, 2, PlateElementShape::Hex);
  p.outer_radius = 0.04;
  expect_key(p, "annular_plate.outer_radius");
  p = plate(kPi, 2, PlateElementShape::Hex);
  p.sector_angle = 7;
  expect_key(p, "annular_plate.sector_angle");
  p = plate(kPi, 2, PlateElementShape::Hex);
  p.elements_through_thickness = 0;
  expect_key(p, "annular_plate.elements_through_thickness");
  p = plate(kPi, 2, PlateElementShape::Hex);
  p.elements_circumferential = 1;  // 180 degrees need two 90-degree patches
  expect_key(p, "annular_plate.elements_circumferential");
  p = plate(kPi, 2, PlateElementShape::Hex);
  p.elements_radial = 0;
  p.mesh_size = 0;
  expect_key(p, "annular_plate.mesh_size");
  p = plate(kPi, 2, PlateElementShape::Hex);
  p.thickness = -1;
  expect_key(p, "annular_plate.thickness");
  p = plate(2 * kPi, 2, PlateElementShape::Hex);
  p.inner_radius = -0.01;
  expect_key(p, "annular_plate.inner_radius");
  p = plate(kPi / 4, 2, PlateElementShape::Hex);
  p.inner_radius = 0.0;  // a sector of a disc: its apex would lie on the axis
  expect_key(p, "annular_plate.inner_radius");
  p.sector_angle = 2 * kPi;  // the whole disc is fine
  EXPECT_NO_THROW(validate(p));
}

}  // namespace
}  // namespace geardyn::meshgen
