// Nastran node sets that constrain nothing: ASET/ASET1, QSET/QSET1, BSET/BSET1, CSET/CSET1 in
// the bulk data and SET in the case control become named node sets ("ASET", ..., "SET_<n>"),
// usable wherever the model file names a node set; only SPC1 (and GRID PS) constrain.
// Deck syntax as in the MSC Nastran Quick Reference Guide (ASET1 "C G1 G2 ... / G1 THRU G2",
// ASET "ID1 C1 ID2 C2 ...", case control "SET n = i1, i2 THRU i3 EXCEPT i4").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/meshio/nastran_reader.hpp"

namespace geardyn::meshio {
namespace {

// A unit cube CHEXA on grids 1..8 plus grids 9, 10, 12 (no 11), case control before the bulk.
const std::string kDeck = R"(SOL 103
CEND
TITLE = node sets
$ A set of grids, with a range, an exception and a continuation line:
SET 5 = 1, 3 THRU 7 EXCEPT 4, 6,
        12
SET 7 = 100 THRU 200
SET 8 = ALL
DISPLACEMENT = 5
BEGIN BULK
GRID,1,,0.,0.,0.
GRID,2,,1.,0.,0.
GRID,3,,1.,1.,0.
GRID,4,,0.,1.,0.
GRID,5,,0.,0.,1.
GRID,6,,1.,0.,1.
GRID,7,,1.,1.,1.
GRID,8,,0.,1.,1.
GRID,9,,2.,0.,0.
GRID,10,,2.,1.,0.
GRID,12,,3.,0.,0.
MAT1,1,2.1+11,,0.3,7850.
PSOLID,1,1
CHEXA,1,1,1,2,3,4,5,6,
+,7,8
$ fixed format (8-column fields): ASET1 C=123456 G1 THRU G2
ASET1   123456  5       THRU    8
$ free format, a THRU range with grid 11 missing (skipped, as Nastran does)
QSET1,123,9,THRU,12
BSET1   123     1       2
BSET    3       123     12      1
CSET,9,456
SPC1,1,123,1,THRU,4
ENDDATA
)";

int id_of(const solid::Mesh& mesh, int index) {
  return static_cast<int>(mesh.node_ids[static_cast<std::size_t>(index)]);
}

std::vector<int> ids(const solid::Mesh& mesh, const std::string& set) {
  std::vector<int> out;
  const auto it = mesh.node_sets.find(set);
  if (it == mesh.node_sets.end()) {
    ADD_FAILURE() << "no node set " << set;
    return out;
  }
  for (int i : it->second) out.push_back(id_of(mesh, i));
  return out;
}

TEST(NastranSets, DofSetEntriesAreNamedNodeSets) {
  const NastranDeck deck = parse_nastran(kDeck, "sets.bdf");
  const solid::Mesh& mesh = deck.mesh;
  EXPECT_EQ(ids(mesh, "ASET"), (std::vector<int>{5, 6, 7, 8}));
  EXPECT_EQ(ids(mesh, "QSET"), (std::vector<int>{9, 10, 12}));
  EXPECT_EQ(ids(mesh, "BSET"), (std::vector<int>{1, 2, 3, 12}));
  EXPECT_EQ(ids(mesh, "CSET"), (std::vector<int>{9}));
  EXPECT_EQ(ids(mesh, "SPC1_1"), (std::vector<int>{1, 2, 3, 4}));
  // Only SPC1 constrains: grids 1..4, 123.
  ASSERT_EQ(mesh.constraints.size(), 4u);
  for (const solid::Constraint& c : mesh.constraints) {
    EXPECT_LE(id_of(mesh, c.node), 4);
    EXPECT_TRUE(c.components[0] && c.components[1] && c.components[2]);
    EXPECT_FALSE(c.components[3] || c.components[4] || c.components[5]);
  }
  for (const auto& u : deck.unsupported) EXPECT_NE(u.name, "ASET1");
}

TEST(NastranSets, CaseControlSetIsANodeSet) {
  const NastranDeck deck = parse_nastran(kDeck, "sets.bdf");
  // 1, 3 THRU 7 EXCEPT 4 6, 12 (continuation line).
  EXPECT_EQ(ids(deck.mesh, "SET_5"), (std::vector<int>{1, 3, 5, 7, 12}));
  // SET 7 names no grid: no set, a warning located at its line (7).
  EXPECT_EQ(deck.mesh.node_sets.count("SET_7"), 0u);
  bool warned = false;
  for (const auto& w : deck.warnings) warned |= w.find("sets.bdf:7: case control SET 7") == 0;
  EXPECT_TRUE(warned);
  // SET 8 = ALL is not a list of ids: listed as unsupported at line 8.
  bool listed = false;
  for (const auto& u : deck.unsupported) listed |= u.name == "SET" && u.line == 8;
  EXPECT_TRUE(listed);
}

TEST(NastranSets, BadEntriesAreLocated) {
  const std::string head = "BEGIN BULK\nGRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\n";
  try {
    (void)parse_nastran(head + "ASET1,127,1,2\n", "bad.bdf");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "ASET1 field 2 (C)");
    EXPECT_EQ(e.where().line, 4);
  }
  try {
    (void)parse_nastran(head + "QSET1   123     1       3\n", "bad.bdf");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "QSET1 field 4 (G)");
    EXPECT_EQ(e.where().column, 25);
    EXPECT_EQ(e.found(), "3");
  }
  try {
    (void)parse_nastran(head + "CSET,1,123,2\n", "bad.bdf");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "CSET field 5 (C)");
  }
}

// Through the model file: a spider joins the solid at the deck's ASET nodes (the top face of
// the cube), which stay free otherwise.
TEST(NastranSets, ModelNamesTheSetOfADeck) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "geardyn_nastran_sets";
  fs::create_directories(dir);
  std::ofstream(dir / "cube.bdf") << kDeck;
  const std::string text = R"(version = 1

[[materials]]
name = "steel"
youngs_modulus = 210e9
poisson_ratio = 0.3
density = 7850

[[nodes]]
name = "hub"
position = [0.5, 0.5, 1.0]

[[solids]]
name = "cube"
type = "mesh"
file = "cube.bdf"
material = "steel"
coupling_modes = 0

[[solids.spiders]]
node_set = "ASET"
node = "hub"
kind = "rigid"
)";
  const model::Model m = analyses::parse_model(text, (dir / "model.toml").string());
  const fe::LinearSystem s = assembly::build_system(m);
  EXPECT_GE(s.dofs.node_index("hub"), 0);
  // A set name the deck does not define is refused, listing the deck's sets.
  std::string other = text;
  other.replace(other.find("\"ASET\""), 6, "\"ASET1\"");
  const model::Model bad = analyses::parse_model(other, (dir / "model.toml").string());
  try {
    (void)assembly::build_system(bad);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ASET"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace geardyn::meshio
