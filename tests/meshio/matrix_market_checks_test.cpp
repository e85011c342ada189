// Imported stiffness and mass matrices are checked before use: symmetry, a positive mass
// diagonal and a non-negative stiffness diagonal, each refused at the line of the entry with the
// DOF it acts on. The issue's case: a mass matrix with -1 on the diagonal was accepted and gave
// wrong frequencies silently.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/meshio/matrix_market.hpp"

namespace geardyn::meshio {
namespace {

namespace fs = std::filesystem;

// Three masses on a chain of springs, fixed at one end (k = 1e6 N/m, m = 2 kg): positive
// definite K and M, the DOFs are ux of nodes 1..3.
const std::string kStiffness = R"(%%MatrixMarket matrix coordinate real symmetric
% three springs in a chain
3 3 5
1 1 2e6
2 1 -1e6
2 2 2e6
3 2 -1e6
3 3 1e6
)";
const std::string kMass = R"(%%MatrixMarket matrix coordinate real symmetric
3 3 3
1 1 2
2 2 2
3 3 2
)";
const std::string kDofs = "node_id,component,x,y,z\n1,ux,0,0,0\n2,ux,1,0,0\n3,ux,2,0,0\n";

class ImportedMatrixChecks : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("geardyn_mmchecks_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_);
    write("dofs.csv", kDofs);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  InputError error(const std::string& k, const std::string& m) {
    write("K.mtx", k);
    write("M.mtx", m);
    try {
      (void)read_matrix_market_component(dir_ / "K.mtx", dir_ / "M.mtx", dir_ / "dofs.csv");
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no InputError";
    return InputError({}, "", "", "");
  }
  fs::path dir_;
};

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST_F(ImportedMatrixChecks, ValidMatricesAreAccepted) {
  write("K.mtx", kStiffness);
  write("M.mtx", kMass);
  const ExternalMatrices m =
      read_matrix_market_component(dir_ / "K.mtx", dir_ / "M.mtx", dir_ / "dofs.csv");
  EXPECT_EQ(m.M.coeff(1, 1), 2.0);
  EXPECT_EQ(m.K.coeff(0, 1), -1e6);
}

// The issue's case: -1 on the mass diagonal, refused at its line (4) naming the DOF.
TEST_F(ImportedMatrixChecks, NegativeMassDiagonalIsRefusedAtItsLine) {
  const InputError e = error(kStiffness, replace(kMass, "2 2 2", "2 2 -1"));
  EXPECT_EQ(e.key_path(), "M");
  EXPECT_NE(e.where().file.find("M.mtx"), std::string::npos);
  EXPECT_EQ(e.where().line, 4);
  EXPECT_EQ(e.where().column, 1);
  EXPECT_EQ(e.found(), "M(2, 2) = -1 on node 2 ux");
  EXPECT_NE(e.expected().find("positive diagonal"), std::string::npos);
}

// A zero mass diagonal, absent from the file: located at the size line, "(no entry)".
TEST_F(ImportedMatrixChecks, MissingMassDiagonalIsRefused) {
  const InputError e = error(kStiffness,
                             "%%MatrixMarket matrix coordinate real symmetric\n"
                             "3 3 2\n1 1 2\n2 2 2\n");
  EXPECT_EQ(e.key_path(), "M");
  EXPECT_EQ(e.where().line, 2);
  EXPECT_EQ(e.found(), "M(3, 3) = 0 (no entry) on node 3 ux");
  // An explicit zero is located at its own line.
  const InputError zero = error(kStiffness, replace(kMass, "3 3 2", "3 3 0"));
  EXPECT_EQ(zero.where().line, 5);
  EXPECT_EQ(zero.found(), "M(3, 3) = 0 on node 3 ux");
}

TEST_F(ImportedMatrixChecks, NegativeStiffnessDiagonalIsRefused) {
  const InputError e = error(replace(kStiffness, "3 3 1e6", "3 3 -1e6"), kMass);
  EXPECT_EQ(e.key_path(), "K");
  EXPECT_NE(e.where().file.find("K.mtx"), std::string::npos);
  EXPECT_EQ(e.where().line, 8);
  EXPECT_EQ(e.found(), "K(3, 3) = -1000000 on node 3 ux");
  // A zero stiffness diagonal (a DOF with no stiffness: a mechanism) is allowed: semi-definite.
  write("K0.mtx",
        replace(replace(replace(kStiffness, "3 3 5", "3 3 3"), "3 2 -1e6\n", ""), "3 3 1e6\n", ""));
  write("M.mtx", kMass);
  EXPECT_NO_THROW(
      (void)read_matrix_market_component(dir_ / "K0.mtx", dir_ / "M.mtx", dir_ / "dofs.csv"));
}

// Array format: the diagonal entry is located at its token.
TEST_F(ImportedMatrixChecks, ArrayFormatDiagonalIsLocated) {
  const InputError e = error(kStiffness,
                             "%%MatrixMarket matrix array real symmetric\n3 3\n"
                             "2\n0\n0\n2\n0 -3\n");
  EXPECT_EQ(e.key_path(), "M");
  EXPECT_EQ(e.where().line, 7);
  EXPECT_EQ(e.where().column, 3);
  EXPECT_EQ(e.found(), "M(3, 3) = -3 on node 3 ux");
}

// Symmetry of a "general" file: |A_ij - A_ji| <= 1e-10 max|A| (round-off of an exporting code
// is 1e-16 .. 1e-13 relative). 1e-12 of max|A| passes, 1e-8 is refused with both entries.
TEST_F(ImportedMatrixChecks, AsymmetryBeyondRoundOffIsRefused) {
  const std::string general =
      "%%MatrixMarket matrix coordinate real general\n3 3 7\n"
      "1 1 2e6\n2 1 -1e6\n1 2 {}\n2 2 2e6\n3 2 -1e6\n2 3 -1e6\n3 3 1e6\n";
  auto with = [&](const std::string& v) { return replace(general, "{}", v); };
  write("K.mtx", with("-1000000.000002"));  // 2e-6 / 2e6 = 1e-12 of max|K|
  write("M.mtx", kMass);
  EXPECT_NO_THROW(
      (void)read_matrix_market_component(dir_ / "K.mtx", dir_ / "M.mtx", dir_ / "dofs.csv"));
  const InputError e = error(with("-1000020"), kMass);  // 1e-5 of max|K|
  EXPECT_EQ(e.key_path(), "K");
  EXPECT_NE(e.found().find("A(2, 1) = -1000000 but A(1, 2) = -1000020"), std::string::npos)
      << e.found();
}

}  // namespace
}  // namespace geardyn::meshio
