// Nastran reader error reporting: each bad deck must raise InputError naming the file, line,
// column and field of the offending value.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "geardyn/meshio/nastran_reader.hpp"

namespace geardyn::meshio {
namespace {

struct Expected {
  std::string key;
  int line = 0;
  int column = 0;
  std::string found_part{};
};

void expect_error(const std::string& text, const Expected& want, NastranOptions options = {}) {
  try {
    (void)parse_nastran(text, "inline.bdf", options);
    ADD_FAILURE() << "no InputError for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), want.key) << e.what();
    EXPECT_EQ(e.where().file, "inline.bdf");
    EXPECT_EQ(e.where().line, want.line) << e.what();
    if (want.column > 0) {
      EXPECT_EQ(e.where().column, want.column) << e.what();
    }
    if (!want.found_part.empty()) {
      EXPECT_NE(std::string(e.what()).find(want.found_part), std::string::npos) << e.what();
    }
  }
}

const std::string kTetGrids =
    "GRID,1,,0.,0.,0.\n"
    "GRID,2,,1.,0.,0.\n"
    "GRID,3,,0.,1.,0.\n"
    "GRID,4,,0.,0.,1.\n";
const std::string kProperty =
    "PSOLID,1,1\n"
    "MAT1,1,2.1E11,,0.3,7800.\n";

TEST(NastranErrors, MalformedRealWithColumn) {
  // Field 4 occupies columns 25..32; "abc" is right-justified and starts in column 30.
  expect_error("GRID           1       0     abc      0.      0.\n",
               {"GRID field 4 (X1)", 1, 30, "'abc'"});
}

TEST(NastranErrors, IntegerInRealFieldGetsAHint) {
  try {
    (void)parse_nastran("$ comment\nGRID,1,,1,0.,0.\n", "inline.bdf");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "GRID field 4 (X1)");
    EXPECT_EQ(e.where().line, 2);
    EXPECT_EQ(e.where().column, 9);
    EXPECT_NE(e.hint().find("decimal point"), std::string::npos) << e.what();
  }
}

TEST(NastranErrors, MalformedIntegerAndComponents) {
  expect_error("GRID,1.5,,0.,0.,0.\n", {"GRID field 2 (ID)", 1, 6, "'1.5'"});
  expect_error(kTetGrids + "SPC1,1,127,1\n", {"SPC1 field 3 (C)", 5, 8, "'127'"});
  expect_error(kTetGrids + "SPC1,1,113,1\n", {"SPC1 field 3 (C)", 5, 8});
}

TEST(NastranErrors, UnknownGridPropertyMaterialAndSystem) {
  expect_error(
      "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\n" + kProperty + "CTETRA,7,1,1,2,3,4\n",
      {"CTETRA field 7 (G4)", 6, 18, "found 4"});
  expect_error(kTetGrids + kProperty + "CTETRA,7,9,1,2,3,4\n",
               {"CTETRA field 3 (PID)", 7, 10, "found 9"});
  expect_error(kTetGrids + "PSOLID,1,5\nCTETRA,7,1,1,2,3,4\n", {"PSOLID field 3 (MID)", 5, 10});
  expect_error("GRID,1,5,0.,0.,0.\n", {"GRID field 3 (CP)", 1, 8});
  expect_error(kTetGrids + "CONM2,1,4,3,1.\n", {"CONM2 field 4 (CID)", 5, 11});
  expect_error(kTetGrids + "CELAS1,1,3,1,1\n", {"CELAS1 field 3 (PID)", 5, 10});
}

TEST(NastranErrors, DuplicateIds) {
  try {
    (void)parse_nastran("GRID,1,,0.,0.,0.\nGRID           1              1.      0.      0.\n",
                        "inline.bdf");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "GRID field 2 (ID)");
    EXPECT_EQ(e.where().line, 2);
    EXPECT_EQ(e.where().column, 16);
    EXPECT_EQ(e.hint(), "first defined at inline.bdf:1");
  }
  expect_error(kTetGrids + kProperty + "CTETRA,7,1,1,2,3,4\nCONM2,7,1,,1.\n",
               {"CONM2 field 2 (EID)", 8, 7});
}

TEST(NastranErrors, UnsupportedCardBecomesErrorOnRequest) {
  const std::string text = kTetGrids + "CQUAD4,1,1,1,2,3,4\n";
  const NastranDeck deck = parse_nastran(text, "inline.bdf");
  ASSERT_EQ(deck.unsupported.size(), 1u);
  EXPECT_EQ(deck.unsupported[0].name, "CQUAD4");
  EXPECT_EQ(deck.unsupported[0].line, 5);
  NastranOptions options;
  options.unsupported_is_error = true;
  expect_error(text, {"CQUAD4", 5, 1}, options);
}

TEST(NastranErrors, Rbe3UmIsUnsupported) {
  const std::string text = kTetGrids + "RBE3,9,,4,123,1.,123,1,2\n,3,UM,1,123\n";
  const NastranDeck deck = parse_nastran(text, "inline.bdf");
  ASSERT_EQ(deck.unsupported.size(), 1u);
  EXPECT_EQ(deck.unsupported[0].name, "RBE3");
  EXPECT_NE(deck.unsupported[0].reason.find("UM"), std::string::npos);
  EXPECT_TRUE(deck.mesh.rigid_elements.empty());
  NastranOptions options;
  options.unsupported_is_error = true;
  expect_error(text, {"RBE3", 5, 1}, options);
}

TEST(NastranErrors, ElementShape) {
  // Some but not all mid-edge grids of a CTETRA.
  expect_error(kTetGrids + kProperty + "CTETRA,7,1,1,2,3,4,1\n", {"CTETRA field 8 (G5)", 7, 20});
  // Four grids in one plane.
  expect_error("GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\nGRID,4,,1.,1.,0.\n" +
                   kProperty + "CTETRA,7,1,1,2,3,4\n",
               {"CTETRA field 4 (G1)", 7, 12, "zero"});
  // A grid twice.
  expect_error(kTetGrids + kProperty + "CTETRA,7,1,1,2,3,1\n", {"CTETRA field 7 (G4)", 7, 18});
}

TEST(NastranErrors, MaterialUnusableForSolids) {
  expect_error(kTetGrids + "PSOLID,1,1\nMAT1,1,2.1E11,,0.5,7800.\nCTETRA,7,1,1,2,3,4\n",
               {"MAT1 field 5 (NU)", 6, 16});
  // Only G: E = NU = 0 by Nastran's rule, not usable for a solid.
  expect_error(kTetGrids + "PSOLID,1,1\nMAT1,1,,8.E10\nCTETRA,7,1,1,2,3,4\n",
               {"MAT1 field 3 (E)", 6, 8});
  expect_error(kTetGrids + "MAT1,1\n", {"MAT1 field 3 (E)", 5});
}

TEST(NastranErrors, LineStructure) {
  expect_error(",1,2\n", {"continuation", 1, 1});
  expect_error("GRID,1,,0.,0.,0.,,,,,7\n", {"free-field line", 1, 22});
  // Field past the last one GRID defines (field 10 = first field of a continuation).
  expect_error("GRID,1,,0.,0.,0.\n,5\n", {"GRID field 10 (extra)", 2, 2});
}

TEST(NastranErrors, CoordinateSystemProblems) {
  expect_error("CORD2R,1,2,0.,0.,0.,0.,0.,1.\n,1.,0.,0.\nCORD2R,2,1,0.,0.,0.,0.,0.,1.\n,1.,0.,0.\n",
               {"CORD2R field 3 (RID)", 1, 10, "cycle"});
  // C on the z axis.
  expect_error("CORD2R,1,0,0.,0.,0.,0.,0.,1.\n,0.,0.,2.\n", {"CORD2R field 4 (A1)", 1, 12});
}

class NastranIncludeErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("geardyn_nastran_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
  }
  std::filesystem::path dir_;
};

TEST_F(NastranIncludeErrors, MissingFile) {
  write("main.bdf", "GRID,1,,0.,0.,0.\nINCLUDE 'nothere.bdf'\n");
  try {
    (void)read_nastran(dir_ / "main.bdf");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "INCLUDE");
    EXPECT_EQ(e.where().line, 2);
    EXPECT_NE(e.found().find("nothere.bdf"), std::string::npos) << e.what();
  }
}

TEST_F(NastranIncludeErrors, Cycle) {
  write("a.bdf", "GRID,1,,0.,0.,0.\nINCLUDE b.bdf\n");
  write("b.bdf", "$ b\n$ b\nINCLUDE 'a.bdf'\n");
  try {
    (void)read_nastran(dir_ / "a.bdf");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "INCLUDE");
    EXPECT_EQ(e.where().line, 3);
    EXPECT_NE(e.where().file.find("b.bdf"), std::string::npos) << e.what();
    EXPECT_NE(e.found().find("includes itself"), std::string::npos) << e.what();
  }
}

TEST_F(NastranIncludeErrors, DisallowedAndUnclosed) {
  write("main.bdf", "INCLUDE 'x.bdf'\n");
  NastranOptions options;
  options.allow_include = false;
  EXPECT_THROW((void)read_nastran(dir_ / "main.bdf", options), InputError);
  write("open.bdf", "INCLUDE 'x\n  y\n");
  EXPECT_THROW((void)read_nastran(dir_ / "open.bdf"), InputError);
  EXPECT_THROW((void)read_nastran(dir_ / "absent.bdf"), InputError);
}

}  // namespace
}  // namespace geardyn::meshio
