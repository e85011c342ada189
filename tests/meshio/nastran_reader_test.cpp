// Nastran bulk data reader: field formats, coordinate systems and every supported card, on the
// small hand-written decks in tests/meshio/data (each deck's comments say what it exercises).
// Expected values are derived by hand in the comments next to the assertions.
#include "geardyn/meshio/nastran_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "geardyn/meshio/element_ordering.hpp"

namespace geardyn::meshio {
namespace {

const std::string kData = std::string(GEARDYN_SOURCE_DIR) + "/tests/meshio/data/";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

int index_of(const solid::Mesh& mesh, long id) {
  for (int i = 0; i < mesh.num_nodes(); ++i)
    if (mesh.node_ids[static_cast<std::size_t>(i)] == id) return i;
  ADD_FAILURE() << "no node " << id;
  return -1;
}

void expect_near(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol = 1e-14) {
  EXPECT_LE((a - b).norm(), tol) << "got " << a.transpose() << ", expected " << b.transpose();
}

TEST(NastranReal, AcceptsNastranForms) {
  const std::vector<std::pair<std::string, double>> cases = {
      {"1.5-3", 1.5e-3}, {"2.+5", 2e5},  {"1.E4", 1e4},     {"-.5", -0.5},   {"+1.", 1.0},
      {"1.0D-2", 1e-2},  {"7E4", 7e4},   {"1.5e+3", 1.5e3}, {"100.-2", 1.0}, {"-3.25+1", -32.5},
      {".0", 0.0},       {"0.0-0", 0.0}, {"12.", 12.0}};
  for (const auto& [text, value] : cases) {
    double v = -1;
    EXPECT_TRUE(parse_nastran_real(text, v)) << text;
    EXPECT_DOUBLE_EQ(v, value) << text;
  }
}

TEST(NastranReal, RejectsIntegersAndGarbage) {
  for (const char* text : {"1", "-12", "abc", "1.5-", "1..2", "--1.", "1.5 E3", "E5", ".", "",
                           "1.E999", "nan", "inf", "1.5E", "1.0+-3"}) {
    double v = 0;
    EXPECT_FALSE(parse_nastran_real(text, v)) << text;
  }
}

// formats.bdf: the unit cube (nodes 1..8) written in small, large, free, large free field and
// with tabs; three CHEXAs with the same grids, continued in the three styles.
TEST(NastranReader, AllFieldFormatsGiveTheSameCube) {
  const NastranDeck deck = read_nastran(kData + "formats.bdf");
  const solid::Mesh& mesh = deck.mesh;
  EXPECT_TRUE(deck.unsupported.empty());
  EXPECT_TRUE(deck.warnings.empty());
  ASSERT_EQ(mesh.num_nodes(), 9);
  const std::vector<Eigen::Vector3d> cube = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                             {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(mesh.node_ids[static_cast<std::size_t>(i)], i + 1);
    EXPECT_EQ(mesh.coords[static_cast<std::size_t>(i)], cube[static_cast<std::size_t>(i)])
        << "GRID " << i + 1;
  }
  // GRID 9 (tab-separated): 2.5-3, 2.+5, 1.E4.
  EXPECT_EQ(mesh.coords[8], Eigen::Vector3d(2.5e-3, 2e5, 1e4));
  ASSERT_EQ(mesh.num_elements(), 3);
  for (int e = 0; e < 3; ++e) {
    const solid::Element& el = mesh.elements[static_cast<std::size_t>(e)];
    EXPECT_EQ(el.id, e + 1);
    EXPECT_EQ(el.type, solid::ElementType::Hex8);
    EXPECT_EQ(el.nodes, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7})) << "CHEXA " << e + 1;
    EXPECT_EQ(el.material, 0);
  }
  EXPECT_EQ(mesh.elements[2].where.line, 25);  // CHEXA* 3
  ASSERT_EQ(mesh.materials.size(), 1u);
  EXPECT_EQ(mesh.materials[0].name, "MAT1_1");
  EXPECT_EQ(mesh.materials[0].E, 2e11);
  EXPECT_EQ(mesh.materials[0].nu, 0.3);
  EXPECT_EQ(mesh.materials[0].rho, 7800.0);
  EXPECT_EQ(mesh.element_sets.at("PSOLID_1"), (std::vector<int>{0, 1, 2}));
}

// coords.bdf. System 1: origin (1, 2, 3), axes x1 = ey, y1 = -ex, z1 = ez.
// System 2 (cylindrical, in 1): origin = (1, 2, 3) + z1 = (1, 2, 4); z2 = ez; x2 = x1 = ey;
// y2 = z2 x x2 = -ex. GRID 10 at (r, theta, z) = (2, 90 deg, 0.5) in 2: local Cartesian
// (0, 2, 0.5) -> (1, 2, 4) + 2 y2 + 0.5 z2 = (-1, 2, 4.5).
// System 3 (rectangular, points given in cylindrical 2): A = (1, 90, 0) -> (0, 1, 0) in 2 ->
// (0, 2, 4); B -> (0, 2, 5); C = (2, 90, 0) -> (-1, 2, 4): z3 = ez, x3 = -ex, y3 = -ey.
// GRID 11 at (1, 1, 1) in 3 -> (0, 2, 4) - ex - ey + ez = (-1, 1, 5).
// System 4 (spherical, basic axes): GRID 12 at (R, theta, phi) = (2, 90, 90) -> (0, 2, 0).
TEST(NastranReader, ChainedCoordinateSystems) {
  const NastranDeck deck = read_nastran(kData + "coords.bdf");
  const solid::Mesh& mesh = deck.mesh;
  ASSERT_EQ(mesh.num_nodes(), 4);
  expect_near(mesh.coords[static_cast<std::size_t>(index_of(mesh, 10))], {-1, 2, 4.5});
  expect_near(mesh.coords[static_cast<std::size_t>(index_of(mesh, 11))], {-1, 1, 5});
  expect_near(mesh.coords[static_cast<std::size_t>(index_of(mesh, 12))], {0, 2, 0});
  expect_near(mesh.coords[static_cast<std::size_t>(index_of(mesh, 13))], {1, 4, 4});
}

// GRID 13 has CD = 2 (cylindrical about the vertical line through (1, 2), theta measured from
// x2 = +y); at (1, 4, 4) it is at theta = 0, so its radial axis is +y and its tangential axis -x:
// component 1 alone means global uy, which geardyn cannot express, while 123 is the same set in
// any axes.
TEST(NastranReader, RotatedDisplacementSystemNeedsWholeComponentSets) {
  const std::string base = slurp(kData + "coords.bdf");
  const NastranDeck ok = parse_nastran(base + "SPC1,1,123,13\n", kData + "coords.bdf");
  ASSERT_EQ(ok.mesh.constraints.size(), 1u);
  EXPECT_EQ(ok.mesh.constraints[0].components,
            (std::array<bool, 6>{true, true, true, false, false, false}));
  try {
    (void)parse_nastran(base + "SPC1,1,1,13\n", kData + "coords.bdf");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "SPC1 field 3 (C)");
    EXPECT_EQ(e.where().line, 19);
    EXPECT_NE(e.hint().find("CD = 2"), std::string::npos) << e.what();
  }
}

// A CELAS end on GRID 13 (CD = 2, radial axis +y, tangential -x there) acts along the CD axis
// it names: a spring with a direction (solid::Spring), not refused; an end on a grid with
// global displacement axes (GRID 10) stays a scalar spring on its component.
TEST(NastranReader, SpringOnARotatedDisplacementSystemActsAlongItsAxis) {
  const std::string base = slurp(kData + "coords.bdf");
  const NastranDeck deck = parse_nastran(base + "CELAS2,301,1.+6,13,1\nCELAS2,302,2.+6,13,2,10,3\n",
                                         kData + "coords.bdf");
  ASSERT_EQ(deck.mesh.springs.size(), 2u);
  const solid::Spring& radial = deck.mesh.springs[0];
  EXPECT_EQ(radial.node1, index_of(deck.mesh, 13));
  EXPECT_EQ(radial.node2, -1);
  expect_near(radial.direction1, {0, 1, 0});
  const solid::Spring& tangential = deck.mesh.springs[1];
  expect_near(tangential.direction1, {-1, 0, 0});
  EXPECT_EQ(tangential.node2, index_of(deck.mesh, 10));
  EXPECT_EQ(tangential.component2, 2);
  EXPECT_TRUE(tangential.direction2.isZero(0.0));
}

// cards.bdf (+ INCLUDEs sub/"grids in sub.bdf" and sub/more.bdf): every supported card.
TEST(NastranReader, CardsDeckWithIncludes) {
  const NastranDeck deck = read_nastran(kData + "cards.bdf");
  const solid::Mesh& mesh = deck.mesh;

  // Unsupported entries with their lines (the case control before BEGIN BULK is not read).
  ASSERT_EQ(deck.unsupported.size(), 3u);
  EXPECT_EQ(deck.unsupported[0].name, "PARAM");
  EXPECT_EQ(deck.unsupported[0].line, 6);
  EXPECT_EQ(deck.unsupported[1].name, "CQUAD4");
  EXPECT_EQ(deck.unsupported[1].line, 33);
  EXPECT_EQ(deck.unsupported[2].name, "EIGRL");
  EXPECT_EQ(deck.unsupported[2].line, 34);
  EXPECT_NE(deck.unsupported[1].file.find("cards.bdf"), std::string::npos);
  // PELAS 6 has GE = 0.01.
  ASSERT_EQ(deck.warnings.size(), 1u);
  EXPECT_NE(deck.warnings[0].find("cards.bdf:22: PELAS GE"), std::string::npos) << deck.warnings[0];

  // Grids 1..8, 20 from sub/"grids in sub.bdf", 21 from sub/more.bdf.
  ASSERT_EQ(mesh.num_nodes(), 10);
  EXPECT_EQ(mesh.node_ids, (std::vector<long>{1, 2, 3, 4, 5, 6, 7, 8, 20, 21}));
  const int n20 = 8, n21 = 9;
  EXPECT_EQ(mesh.coords[static_cast<std::size_t>(n21)], Eigen::Vector3d(3, 0, 0));
  ASSERT_EQ(mesh.num_elements(), 1);

  // MAT1 with G = 8e10 and NU = 0.25 only: E = 2 (1 + 0.25) 8e10 = 2e11.
  ASSERT_EQ(mesh.materials.size(), 1u);
  EXPECT_DOUBLE_EQ(mesh.materials[0].E, 2e11);
  EXPECT_EQ(mesh.materials[0].nu, 0.25);

  // CONM2 101: CID 0, offset (0.1, 0, 0), inertia with Nastran's minus signs on I21 I31 I32.
  ASSERT_EQ(mesh.point_masses.size(), 3u);
  const solid::PointMass& m1 = mesh.point_masses[0];
  EXPECT_EQ(m1.id, 101);
  EXPECT_EQ(m1.node, n20);
  EXPECT_EQ(m1.mass, 2.0);
  EXPECT_EQ(m1.offset, Eigen::Vector3d(0.1, 0, 0));
  Eigen::Matrix3d J;
  J << 1, -0.1, -0.2, -0.1, 2, -0.3, -0.2, -0.3, 3;
  EXPECT_EQ(m1.inertia, J);
  // CONM2 102: CID -1, CG at (0.5, 0.5, 2.5), GRID 20 at (0.5, 0.5, 2): offset (0, 0, 0.5).
  EXPECT_EQ(mesh.point_masses[1].offset, Eigen::Vector3d(0, 0, 0.5));
  // CONM2 103: CID 1 (x1 = ey, y1 = -ex): offset x1 = (0, 1, 0); diag(1, 2, 3) in axes 1 is
  // diag(2, 1, 3) in global axes.
  const solid::PointMass& m3 = mesh.point_masses[2];
  EXPECT_EQ(m3.node, n21);
  expect_near(m3.offset, {0, 1, 0});
  EXPECT_LE((m3.inertia - Eigen::Vector3d(2, 1, 3).asDiagonal().toDenseMatrix()).norm(), 1e-14);

  // CELAS1 201 with PELAS 5 (k = 1e6) between ux of 20 and ux of 21; CELAS2 202 grounded rz.
  ASSERT_EQ(mesh.springs.size(), 2u);
  EXPECT_EQ(mesh.springs[0].stiffness, 1e6);
  EXPECT_EQ(mesh.springs[0].node1, n20);
  EXPECT_EQ(mesh.springs[0].component1, 0);
  EXPECT_EQ(mesh.springs[0].node2, n21);
  EXPECT_EQ(mesh.springs[0].component2, 0);
  EXPECT_EQ(mesh.springs[1].stiffness, 3000.0);
  EXPECT_EQ(mesh.springs[1].node1, n21);
  EXPECT_EQ(mesh.springs[1].component1, 5);
  EXPECT_EQ(mesh.springs[1].node2, -1);

  // RBE2 301: GN 20, all components, GM 5..8. RBE3 302: REFGRID 21, REFC 123, weights 1 on
  // grids 1, 2 and 2 on grids 3, 4.
  ASSERT_EQ(mesh.rigid_elements.size(), 2u);
  const solid::RigidElement& rbe2 = mesh.rigid_elements[0];
  EXPECT_EQ(rbe2.kind, solid::RigidElement::Kind::Rigid);
  EXPECT_EQ(rbe2.reference, n20);
  EXPECT_EQ(rbe2.nodes, (std::vector<int>{4, 5, 6, 7}));
  EXPECT_EQ(rbe2.components, (std::array<bool, 6>{true, true, true, true, true, true}));
  const solid::RigidElement& rbe3 = mesh.rigid_elements[1];
  EXPECT_EQ(rbe3.kind, solid::RigidElement::Kind::Averaging);
  EXPECT_EQ(rbe3.reference, n21);
  EXPECT_EQ(rbe3.nodes, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(rbe3.weights, (std::vector<double>{1, 1, 2, 2}));
  EXPECT_EQ(rbe3.components, (std::array<bool, 6>{true, true, true, false, false, false}));
  EXPECT_EQ(rbe3.where.line, 27);

  // SPC1: set 1 = grids 1 THRU 4 (123) and 20 (456); set 2 = grids 5, 6 (3).
  EXPECT_EQ(mesh.node_sets.at("SPC1_1"), (std::vector<int>{0, 1, 2, 3, n20}));
  EXPECT_EQ(mesh.node_sets.at("SPC1_2"), (std::vector<int>{4, 5}));
  ASSERT_EQ(mesh.constraints.size(), 7u);
  for (const solid::Constraint& c : mesh.constraints) {
    std::array<bool, 6> expected{false, false, true, false, false, false};  // set 2: nodes 5, 6
    if (c.node <= 3) expected = {true, true, true, false, false, false};
    if (c.node == n20) expected = {false, false, false, true, true, true};
    EXPECT_EQ(c.components, expected) << "node " << c.node;
  }
}

TEST(NastranReader, SpcSetSelection) {
  NastranOptions options;
  options.spc_set = 2;
  const NastranDeck deck = read_nastran(kData + "cards.bdf", options);
  ASSERT_EQ(deck.mesh.constraints.size(), 2u);
  EXPECT_EQ(deck.mesh.constraints[0].node, 4);
  EXPECT_EQ(deck.mesh.constraints[1].node, 5);
  EXPECT_EQ(deck.mesh.node_sets.at("SPC1_1").size(), 5u);  // sets are listed regardless

  options.spc_set = 7;
  try {
    (void)read_nastran(kData + "cards.bdf", options);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "NastranOptions.spc_set");
    EXPECT_NE(e.expected().find("sets: 1, 2"), std::string::npos) << e.what();
  }
}

TEST(NastranReader, UnsupportedIsErrorOption) {
  NastranOptions options;
  options.unsupported_is_error = true;
  try {
    (void)read_nastran(kData + "cards.bdf", options);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "PARAM");
    EXPECT_EQ(e.where().line, 6);
    EXPECT_NE(std::string(e.what()).find("cards.bdf:6:1"), std::string::npos) << e.what();
  }
}

// Quadratic elements of pair_deck.bdf (connectivity typed in Nastran order by make_pair.py, some
// elements mirrored): after reading, every mid-edge node sits at the midpoint of the corners of
// its edge in Gmsh's edge table, and every element has a positive corner volume.
TEST(NastranReader, QuadraticNodeOrderAndOrientation) {
  const NastranDeck deck = read_nastran(kData + "pair_deck.bdf");
  const solid::Mesh& mesh = deck.mesh;
  ASSERT_EQ(mesh.num_elements(), 6);
  int quadratic = 0;
  for (const solid::Element& e : mesh.elements) {
    EXPECT_GT(corner_volume_measure(e.type, e.nodes, mesh.coords), 0) << "element " << e.id;
    const auto edges = gmsh_edges(e.type);
    const int corners = num_corner_nodes(e.type);
    for (std::size_t k = 0; k < edges.size(); ++k) {
      const Eigen::Vector3d a =
          mesh.coords[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(edges[k].first)])];
      const Eigen::Vector3d b =
          mesh.coords[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(edges[k].second)])];
      const Eigen::Vector3d m =
          mesh.coords[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(corners) + k])];
      EXPECT_LE((m - 0.5 * (a + b)).norm(), 1e-12) << "element " << e.id << " edge " << k;
    }
    quadratic += edges.empty() ? 0 : 1;
  }
  EXPECT_EQ(quadratic, 3);
  // SPC1 1 123 1 THRU 4 101 102 104 / 106: the bottom face of the hex20.
  EXPECT_EQ(mesh.node_sets.at("SPC1_1").size(), 8u);
}

}  // namespace
}  // namespace geardyn::meshio
