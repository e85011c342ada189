// Tests of the parametric gear-sector / damper-ring generator (meshgen/gear_sector.hpp).
//
// The model (units m), one sector of N = 10 of a z = 40, m = 4.5 mm spur gear blank:
//
//   r: 0.020 bore | hub to 0.035 (width 0.040) | web 0.008 thick | rim from 0.070 |
//      groove 0.070..0.074 at z = 9 +- 4 mm | root 0.084375, pitch 0.090, tip 0.0945
//   ring: r 0.069..0.074, z = 9 +- 3 mm, outer face on the groove bottom (contact).
//
// Oracles: geometry (periodicity, coincident contact pairs, node positions) from the
// construction; volume from the closed-form volumes of the idealised geometry; element validity
// from the Jacobian of each element; determinism by generating twice.
#include "geardyn/meshgen/gear_sector.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <set>
#include <tuple>

#include "mesh_checks.hpp"
#include "meshgen/damper_gear.hpp"

namespace geardyn::meshgen {
namespace {

using test::radius;
using test::rotate_z;

using test::damper_gear;

// Generated once: each mesh takes about a second.
const solid::Mesh& quadratic_mesh() {
  static const solid::Mesh mesh = gear_sector(damper_gear(2));
  return mesh;
}

std::set<int> nodes_of_set(const solid::Mesh& mesh, const std::string& element_set) {
  std::set<int> out;
  for (int e : mesh.element_sets.at(element_set))
    out.insert(mesh.elements[static_cast<std::size_t>(e)].nodes.begin(),
               mesh.elements[static_cast<std::size_t>(e)].nodes.end());
  return out;
}

TEST(GearSector, HasAllNodeAndElementSets) {
  const solid::Mesh& mesh = quadratic_mesh();
  for (const char* name : {"left", "right", "bore", "groove_contact", "ring_contact", "ring_left",
                           "ring_right", "excitation", "tooth_tip"}) {
    ASSERT_TRUE(mesh.node_sets.count(name)) << name;
    EXPECT_FALSE(mesh.node_sets.at(name).empty()) << name;
    EXPECT_TRUE(std::is_sorted(mesh.node_sets.at(name).begin(), mesh.node_sets.at(name).end()));
  }
  EXPECT_EQ(mesh.node_sets.at("excitation").size(), 1u);
  ASSERT_EQ(mesh.element_sets.size(), 2u);
  EXPECT_EQ(mesh.element_sets.at("gear").size() + mesh.element_sets.at("ring").size(),
            mesh.elements.size());
  ASSERT_EQ(mesh.materials.size(), 2u);
  EXPECT_EQ(mesh.materials[1].name, "ring steel");
  for (int e : mesh.element_sets.at("ring"))
    EXPECT_EQ(mesh.elements[static_cast<std::size_t>(e)].material, 1);
  for (const solid::Element& e : mesh.elements) EXPECT_EQ(e.type, solid::ElementType::Tet10);
}

// Sector faces: right[i] = R(2 pi / N) left[i]; and the sets are complete: every gear node on
// the plane theta = 0 (resp. 2 pi / N) is in "left" (resp. "right"). Tolerance 1e-9 r_a: the
// generator makes the pairs exact to round-off.
TEST(GearSector, SectorFacesArePeriodic) {
  const solid::Mesh& mesh = quadratic_mesh();
  const double alpha = 2 * std::numbers::pi / 10;
  const double r_a = 0.0945;
  for (const auto& [l, r] : {std::pair{"left", "right"}, std::pair{"ring_left", "ring_right"}}) {
    const std::vector<int>& left = mesh.node_sets.at(l);
    const std::vector<int>& right = mesh.node_sets.at(r);
    ASSERT_EQ(left.size(), right.size());
    double worst = 0;
    for (std::size_t i = 0; i < left.size(); ++i) {
      const Eigen::Vector3d& xl = mesh.coords[static_cast<std::size_t>(left[i])];
      const Eigen::Vector3d& xr = mesh.coords[static_cast<std::size_t>(right[i])];
      worst = std::max(worst, (rotate_z(xl, alpha) - xr).norm());
      EXPECT_NEAR(xl.y(), 0.0, 1e-12 * r_a);
    }
    EXPECT_LT(worst, 1e-9 * r_a) << l;
  }
  const std::set<int> gear = nodes_of_set(mesh, "gear");
  std::size_t on_left = 0, on_right = 0;
  const Eigen::Vector3d normal(-std::sin(alpha), std::cos(alpha), 0);
  for (int n : gear) {
    const Eigen::Vector3d& x = mesh.coords[static_cast<std::size_t>(n)];
    if (std::abs(x.y()) < 1e-9 * r_a && x.x() > 0) ++on_left;
    if (std::abs(normal.dot(x)) < 1e-9 * r_a && x.x() > 0) ++on_right;
  }
  EXPECT_EQ(on_left, mesh.node_sets.at("left").size());
  EXPECT_EQ(on_right, mesh.node_sets.at("right").size());
}

// Contact pairs: same coordinates (1e-12 m), distinct nodes, gear node used only by gear
// elements and ring node only by ring elements; every gear node on the contact face (r = r_c,
// z inside the ring) is paired.
TEST(GearSector, GrooveAndRingContactNodesAreConformingPairs) {
  const solid::Mesh& mesh = quadratic_mesh();
  const std::vector<int>& groove = mesh.node_sets.at("groove_contact");
  const std::vector<int>& ring = mesh.node_sets.at("ring_contact");
  ASSERT_EQ(groove.size(), ring.size());
  const std::set<int> gear_nodes = nodes_of_set(mesh, "gear");
  const std::set<int> ring_nodes = nodes_of_set(mesh, "ring");
  const double r_c = 0.074;
  for (std::size_t i = 0; i < groove.size(); ++i) {
    const Eigen::Vector3d& xg = mesh.coords[static_cast<std::size_t>(groove[i])];
    const Eigen::Vector3d& xr = mesh.coords[static_cast<std::size_t>(ring[i])];
    EXPECT_LT((xg - xr).norm(), 1e-12);
    EXPECT_NE(groove[i], ring[i]);
    EXPECT_TRUE(gear_nodes.count(groove[i]) && !ring_nodes.count(groove[i]));
    EXPECT_TRUE(ring_nodes.count(ring[i]) && !gear_nodes.count(ring[i]));
    EXPECT_NEAR(radius(xg), r_c, 1e-9);
    EXPECT_GE(xg.z(), 0.006 - 1e-12);
    EXPECT_LE(xg.z(), 0.012 + 1e-12);
  }
  std::size_t on_face = 0;
  for (int n : gear_nodes) {
    const Eigen::Vector3d& x = mesh.coords[static_cast<std::size_t>(n)];
    if (std::abs(radius(x) - r_c) < 1e-9 && x.z() > 0.006 - 1e-9 && x.z() < 0.012 + 1e-9) ++on_face;
  }
  EXPECT_EQ(on_face, groove.size());
  // The two bodies share no node at all (the ring is a separate body).
  std::vector<int> shared;
  std::set_intersection(gear_nodes.begin(), gear_nodes.end(), ring_nodes.begin(), ring_nodes.end(),
                        std::back_inserter(shared));
  EXPECT_TRUE(shared.empty());
}

// Set positions: bore nodes at r = 0.020, tooth-tip nodes at r_a = 0.0945, the excitation node
// on the pitch circle r_p = m z / 2 = 0.090 at mid-face z = 0, on the +theta flank of the first
// tooth (angle between the tooth centre pi/z and the next tooth space).
TEST(GearSector, NodeSetsLieWhereTheySay) {
  const solid::Mesh& mesh = quadratic_mesh();
  for (int n : mesh.node_sets.at("bore"))
    EXPECT_NEAR(radius(mesh.coords[static_cast<std::size_t>(n)]), 0.020, 1e-9);
  for (int n : mesh.node_sets.at("tooth_tip"))
    EXPECT_NEAR(radius(mesh.coords[static_cast<std::size_t>(n)]), 0.0945, 1e-9);
  const Eigen::Vector3d& x =
      mesh.coords[static_cast<std::size_t>(mesh.node_sets.at("excitation").front())];
  EXPECT_NEAR(radius(x), 0.090, 1e-12);
  EXPECT_NEAR(x.z(), 0.0, 1e-12);
  const double theta = std::atan2(x.y(), x.x());
  const double s_p = std::numbers::pi * 0.0045 / 2;  // tooth thickness on the pitch circle
  EXPECT_NEAR(theta, std::numbers::pi / 40 + s_p / (2 * 0.090), 2e-3);
}

// No inverted element: det J > 0 at every quadrature point and node of every (curved) tet10.
TEST(GearSector, NoInvertedElements) {
  const solid::Mesh& mesh = quadratic_mesh();
  double worst = 1e300;
  for (const solid::Element& e : mesh.elements)
    worst = std::min(worst, test::min_relative_jacobian(mesh, e));
  EXPECT_GT(worst, 0.0);
}

// Volume of the idealised geometry (annular sectors of hub, web, rim minus groove, plus the
// straight-flank teeth; ring annular sector), analytic_volumes(). The quadratic elements carry
// the arcs as parabolas through 3 points; with arcs of <= 0.2 rad per element edge the
// geometric error is ~1e-6 relative; the 1e-5 tolerance leaves margin.
TEST(GearSector, VolumeMatchesIdealisedGeometry) {
  const solid::Mesh& mesh = quadratic_mesh();
  const SectorVolumes exact = analytic_volumes(damper_gear());
  double gear = 0, ring = 0;
  for (int e : mesh.element_sets.at("gear"))
    gear += test::element_volume(mesh, mesh.elements[static_cast<std::size_t>(e)]);
  for (int e : mesh.element_sets.at("ring"))
    ring += test::element_volume(mesh, mesh.elements[static_cast<std::size_t>(e)]);
  EXPECT_NEAR(gear / exact.gear, 1.0, 1e-5);
  EXPECT_NEAR(ring / exact.ring, 1.0, 1e-5);
  // Cross-check of the formula itself: a hand sum for this model.
  const double pi = std::numbers::pi;
  const double rf = 0.084375, ra = 0.0945,
               sf = pi * 0.0045 / 2 + 2 * 1.25 * 0.0045 * std::tan(pi / 9),
               sa = pi * 0.0045 / 2 - 2 * 0.0045 * std::tan(pi / 9);
  const double bf = sf / (2 * rf), ba = sa / (2 * ra);
  const double tooth = rf * ra * std::sin(bf - ba) + ra * ra * ba - rf * rf * bf;
  const double half = pi / 10;
  const double hand =
      half * ((0.035 * 0.035 - 0.02 * 0.02) * 0.04 + (0.07 * 0.07 - 0.035 * 0.035) * 0.008 +
              (rf * rf - 0.07 * 0.07) * 0.03 - (0.074 * 0.074 - 0.07 * 0.07) * 0.008) +
      4 * tooth * 0.03;
  EXPECT_NEAR(exact.gear / hand, 1.0, 1e-14);
}

// Linear tets: straight edges replace the arcs; element edges of at most ~10 mm on radii
// >= 20 mm give chord sagittas <= 10^2 / (8 * 20) = 0.6 mm on the bore and < 0.2 mm elsewhere,
// adding material at concave faces (bore, rim bore) and removing it at convex ones; 1e-2 of the
// volume bounds that.
TEST(GearSector, LinearMeshIsValidAndCloseInVolume) {
  const solid::Mesh mesh = gear_sector(damper_gear(1));
  const SectorVolumes exact = analytic_volumes(damper_gear(1));
  double gear = 0;
  for (int e : mesh.element_sets.at("gear")) {
    const solid::Element& element = mesh.elements[static_cast<std::size_t>(e)];
    EXPECT_EQ(element.type, solid::ElementType::Tet4);
    const double v = test::element_volume(mesh, element);
    EXPECT_GT(v, 0.0);
    gear += v;
  }
  EXPECT_NEAR(gear / exact.gear, 1.0, 1e-2);
}

// With a coarse blank (8 mm) and a 1 mm strip of rim bore between web and groove, Gmsh's
// Delaunay leaves flat tets whose corners all lie on the bore cylinder; curving their mid-nodes
// turns them inside out. The generator straightens those edges (and says so in Mesh::source);
// the periodic and contact pairs must stay exact and the volume close.
TEST(GearSector, UntanglingKeepsPairsExact) {
  GearSectorParams p = damper_gear(2);
  p.mesh.global = 0.008;
  p.mesh.tooth = 0.004;
  p.mesh.groove = 0.003;
  const solid::Mesh mesh = gear_sector(p);
  EXPECT_NE(mesh.source.find("straightened"), std::string::npos) << mesh.source;
  double worst = 1e300, volume = 0;
  for (int e : mesh.element_sets.at("gear")) {
    const solid::Element& element = mesh.elements[static_cast<std::size_t>(e)];
    worst = std::min(worst, test::min_relative_jacobian(mesh, element));
    volume += test::element_volume(mesh, element);
  }
  EXPECT_GT(worst, 0.0);
  EXPECT_NEAR(volume / analytic_volumes(p).gear, 1.0, 1e-4);
  const double alpha = 2 * std::numbers::pi / 10;
  for (const auto& [a, b, turn] :
       {std::tuple{"left", "right", 1}, std::tuple{"ring_left", "ring_right", 1},
        std::tuple{"groove_contact", "ring_contact", 0}}) {
    const std::vector<int>& first = mesh.node_sets.at(a);
    const std::vector<int>& second = mesh.node_sets.at(b);
    ASSERT_EQ(first.size(), second.size());
    for (std::size_t i = 0; i < first.size(); ++i)
      EXPECT_LT((rotate_z(mesh.coords[static_cast<std::size_t>(first[i])], turn * alpha) -
                 mesh.coords[static_cast<std::size_t>(second[i])])
                    .norm(),
                1e-12)
          << a;
  }
}

TEST(GearSector, SameParametersGiveTheSameMesh) {
  const solid::Mesh again = gear_sector(damper_gear(2));
  const solid::Mesh& mesh = quadratic_mesh();
  ASSERT_EQ(again.num_nodes(), mesh.num_nodes());
  ASSERT_EQ(again.num_elements(), mesh.num_elements());
  for (int i = 0; i < mesh.num_nodes(); ++i)
    ASSERT_EQ(again.coords[static_cast<std::size_t>(i)], mesh.coords[static_cast<std::size_t>(i)]);
  for (int e = 0; e < mesh.num_elements(); ++e)
    ASSERT_EQ(again.elements[static_cast<std::size_t>(e)].nodes,
              mesh.elements[static_cast<std::size_t>(e)].nodes);
  EXPECT_EQ(again.node_sets, mesh.node_sets);
  EXPECT_EQ(again.element_sets, mesh.element_sets);
}

TEST(GearSector, WithoutGrooveThereIsNoRing) {
  GearSectorParams p = damper_gear(1);
  p.groove.reset();
  p.mesh.global = 0.015;
  const solid::Mesh mesh = gear_sector(p);
  EXPECT_EQ(mesh.element_sets.count("ring"), 0u);
  EXPECT_EQ(mesh.node_sets.count("groove_contact"), 0u);
  EXPECT_EQ(mesh.materials.size(), 1u);
  EXPECT_FALSE(mesh.node_sets.at("left").empty());
}

void expect_input_error(const GearSectorParams& p, const std::string& key) {
  try {
    validate(p);
    ADD_FAILURE() << "no InputError for " << key;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), key) << e.what();
  }
}

TEST(GearSector, BadParametersNameTheKey) {
  {
    auto p = damper_gear();
    p.num_teeth = 41;
    expect_input_error(p, "gear_sector.num_teeth");
  }
  {
    auto p = damper_gear();
    p.num_sectors = 1;
    expect_input_error(p, "gear_sector.num_sectors");
  }
  {
    auto p = damper_gear();
    p.bore_radius = 0.035;
    expect_input_error(p, "gear_sector.bore_radius");
  }
  {
    auto p = damper_gear();
    p.rim_inner_radius = 0.086;
    expect_input_error(p, "gear_sector.rim_inner_radius");
  }
  {
    auto p = damper_gear();
    p.groove->axial_position = 0.013;  // 0.009..0.017 leaves the rim (+-0.015)
    expect_input_error(p, "gear_sector.groove.axial_position");
  }
  {
    auto p = damper_gear();
    p.groove->axial_position = 0.006;  // 0.002..0.010 cuts into the web (+-0.004)
    expect_input_error(p, "gear_sector.groove.axial_position");
  }
  {
    auto p = damper_gear();
    p.groove->depth = 0.015;  // through the rim
    expect_input_error(p, "gear_sector.groove.depth");
  }
  {
    auto p = damper_gear();
    p.groove->ring.width = 0.009;  // wider than the groove
    expect_input_error(p, "gear_sector.groove.ring.width");
  }
  {
    auto p = damper_gear();
    p.groove->ring.radial_thickness = 0.05;  // into the hub
    expect_input_error(p, "gear_sector.groove.ring.radial_thickness");
  }
  {
    auto p = damper_gear();
    p.web_offset = 0.014;  // web outside the hub
    expect_input_error(p, "gear_sector.web_offset");
  }
  {
    auto p = damper_gear();
    p.mesh.element_order = 3;
    expect_input_error(p, "gear_sector.mesh.element_order");
  }
  {
    auto p = damper_gear();
    p.tooth.pressure_angle = 0.7;  // 40 deg: the straight-flank tooth comes to a point
    expect_input_error(p, "gear_sector.tooth.pressure_angle");
  }
  {
    auto p = damper_gear();
    p.tooth.profile = ToothProfile::Explicit;
    p.tooth.root_radius = 0.084;
    p.tooth.tip_radius = 0.094;
    p.tooth.pitch_radius = 0.095;  // outside the tooth
    p.tooth.root_thickness = 0.009;
    p.tooth.tip_thickness = 0.003;
    expect_input_error(p, "gear_sector.tooth.pitch_radius");
  }
  {
    auto p = damper_gear();
    p.ring_material.E = 0;
    expect_input_error(p, "gear_sector.ring_material.E");
  }
  EXPECT_THROW(gear_sector([] {
                 auto p = damper_gear();
                 p.num_teeth = 45;
                 return p;
               }()),
               InputError);
}

}  // namespace
}  // namespace geardyn::meshgen
