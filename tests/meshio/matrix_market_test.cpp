// Matrix Market reader/writer and DOF map: exact round trip, the header variants, and errors
// with file:line:column.
#include "geardyn/meshio/matrix_market.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

namespace geardyn::meshio {
namespace {

namespace fs = std::filesystem;

class MatrixMarketFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("geardyn_mm_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  fs::path dir_;
};

// A random sparse symmetric matrix with values spanning many magnitudes (fixed seed).
Eigen::SparseMatrix<double> random_symmetric(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-12, 12), index(0, n - 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, 10.0 + std::abs(mantissa(rng)));
  for (int k = 0; k < 3 * n; ++k) {
    const int i = index(rng), j = index(rng);
    if (i == j) continue;
    const double v = mantissa(rng) * std::pow(10.0, exponent(rng));
    t.emplace_back(i, j, v);
    t.emplace_back(j, i, v);
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

double max_difference(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  return Eigen::MatrixXd(a - b).cwiseAbs().maxCoeff();
}

TEST_F(MatrixMarketFiles, RoundTripIsExact) {
  const Eigen::SparseMatrix<double> A = random_symmetric(40, 7);
  for (bool symmetric : {true, false}) {
    const fs::path path = dir_ / (symmetric ? "sym.mtx" : "gen.mtx");
    write_matrix_market(path, A, symmetric);
    const MatrixMarketMatrix back = read_matrix_market(path);
    EXPECT_EQ(back.symmetric, symmetric);
    EXPECT_EQ(back.matrix.nonZeros(), A.nonZeros());
    EXPECT_EQ(max_difference(back.matrix, A), 0.0) << "symmetric = " << symmetric;
  }
  // Writing a non-symmetric matrix as symmetric would drop its upper triangle.
  Eigen::SparseMatrix<double> B = A;
  B.coeffRef(0, 1) += 1.0;
  EXPECT_THROW(write_matrix_market(dir_ / "bad.mtx", B, true), std::invalid_argument);
}

TEST(MatrixMarket, ArrayAndCoordinateForms) {
  // [[4, 1, 0], [1, 5, 2], [0, 2, 6]]
  const Eigen::Matrix3d expected{{4, 1, 0}, {1, 5, 2}, {0, 2, 6}};
  const std::string sym_coordinate =
      "%%MatrixMarket matrix coordinate real symmetric\n% comment\n\n3 3 5\n1 1 4\n2 1 1\n2 2 5\n"
      "3 2 2\n3 3 6\n";
  const std::string sym_array =
      "%%MatrixMarket matrix array real symmetric\n3 3\n4\n1\n0\n5\n2\n6\n";
  const std::string general_array =
      "%%MatrixMarket matrix array real general\n3 3\n4\n1\n0\n1\n5\n2\n0\n2\n6\n";
  const std::string integer_general =
      "%%MatrixMarket matrix coordinate integer general\n3 3 7\n1 1 4\n2 1 1\n1 2 1\n2 2 5\n"
      "3 2 2\n2 3 2\n3 3 6\n";
  for (const std::string& text : {sym_coordinate, sym_array, general_array, integer_general}) {
    const MatrixMarketMatrix m = parse_matrix_market(text, "m.mtx");
    EXPECT_EQ(Eigen::Matrix3d(Eigen::MatrixXd(m.matrix)), expected) << text;
  }
}

void expect_mm_error(const std::string& text, const std::string& key, int line, int column) {
  try {
    (void)parse_matrix_market(text, "m.mtx");
    ADD_FAILURE() << "no InputError for\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), key) << e.what();
    EXPECT_EQ(e.where().file, "m.mtx");
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_EQ(e.where().column, column) << e.what();
  }
}

TEST(MatrixMarket, Errors) {
  const std::string h = "%%MatrixMarket matrix coordinate real general\n";
  expect_mm_error("%%MatrixMarket matrix coordinate complex general\n1 1 1\n1 1 1 0\n",
                  "header.field", 1, 34);
  expect_mm_error("%%MatrixMarket matrix coordinate real hermitian\n", "header.symmetry", 1, 39);
  expect_mm_error("3 3 1\n", "header", 1, 1);
  expect_mm_error(h + "3 4 1\n1 1 1.\n", "size.columns", 2, 3);
  expect_mm_error(h + "% c\n3 3 2\n1 1 1.\n4 1 2.\n", "entry.row", 5, 1);
  expect_mm_error(h + "3 3 2\n1 1 1.\n2   0 2.\n", "entry.column", 4, 5);
  expect_mm_error(h + "3 3 2\n1 1 1.\n2 2 nan\n", "entry.value", 4, 5);
  expect_mm_error(h + "3 3 2\n1 1 1.\n2 2 inf\n", "entry.value", 4, 5);
  expect_mm_error(h + "3 3 3\n1 1 1.\n2 2 1.\n", "entry", 4, 0);
  expect_mm_error(h + "3 3 1\n1 1 1.\n2 2 1.\n", "entry", 4, 1);
  expect_mm_error(h + "3 3 2\n1 1 1.\n1 1 1.\n", "entry", 4, 1);
  expect_mm_error("%%MatrixMarket matrix coordinate real symmetric\n3 3 1\n1 2 1.\n", "entry.row",
                  3, 1);
  expect_mm_error(h + "3 3 1\n1 1\n", "entry", 3, 1);
}

TEST_F(MatrixMarketFiles, ComponentWithDofMap) {
  // Two nodes: node 7 with ux, uy, uz; node 9 with rz, and one modal coordinate.
  const std::string dofmap =
      "# external component\nnode_id, component, x, y, z\n7, ux, 0., 0., 1.\n7, 2, 0, 0, 1\n"
      "7, UZ, 0, 0, 1\n9, rz, 1.5, 0, 0\n1, q, 0, 0, 0\n";
  const Eigen::SparseMatrix<double> K = random_symmetric(5, 1), M = random_symmetric(5, 2);
  write_matrix_market(dir_ / "K.mtx", K, true);
  write_matrix_market(dir_ / "M.mtx", M, false);
  const ExternalMatrices ext =
      read_matrix_market_component(dir_ / "K.mtx", dir_ / "M.mtx", write("map.csv", dofmap));
  EXPECT_EQ(max_difference(ext.K, K), 0.0);
  EXPECT_EQ(max_difference(ext.M, M), 0.0);
  ASSERT_EQ(ext.dofs.size(), 5u);
  EXPECT_EQ(ext.dofs[0].node_id, 7);
  EXPECT_EQ(ext.dofs[1].component, 1);
  EXPECT_EQ(ext.dofs[2].component, 2);
  EXPECT_EQ(ext.dofs[3].component, 5);
  EXPECT_EQ(ext.dofs[3].x, Eigen::Vector3d(1.5, 0, 0));
  EXPECT_EQ(ext.dofs[4].component, -1);

  // Size mismatches: M of another size; a DOF map with one row fewer.
  write_matrix_market(dir_ / "M4.mtx", random_symmetric(4, 3), true);
  try {
    (void)read_matrix_market_component(dir_ / "K.mtx", dir_ / "M4.mtx", dir_ / "map.csv");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "size.rows");
    EXPECT_NE(e.where().file.find("M4.mtx"), std::string::npos);
    EXPECT_EQ(e.where().line, 3);
  }
  write("short.csv", "node_id,component,x,y,z\n7,1,0,0,1\n");
  try {
    (void)read_matrix_market_component(dir_ / "K.mtx", dir_ / "M.mtx", dir_ / "short.csv");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "rows");
    EXPECT_NE(e.what(), std::string());
  }
  // A "general" file that is not symmetric.
  Eigen::SparseMatrix<double> N = K;
  N.coeffRef(1, 0) += 1.0;
  write_matrix_market(dir_ / "N.mtx", N, false);
  EXPECT_THROW((void)read_matrix_market_component(dir_ / "N.mtx", dir_ / "M.mtx", dir_ / "map.csv"),
               InputError);
  EXPECT_THROW(
      (void)read_matrix_market_component(dir_ / "none.mtx", dir_ / "M.mtx", dir_ / "map.csv"),
      InputError);
}

void expect_csv_error(const std::string& text, const std::string& key, int line, int column) {
  try {
    (void)parse_dof_map_csv(text, "map.csv");
    ADD_FAILURE() << "no InputError for\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), key) << e.what();
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_EQ(e.where().column, column) << e.what();
  }
}

TEST(DofMap, Errors) {
  const std::string h = "node_id,component,x,y,z\n";
  expect_csv_error("node,component,x,y,z\n", "header", 1, 1);
  expect_csv_error("node_id,component,x,y\n", "header", 1, 1);
  expect_csv_error(h + "1,7,0,0,0\n", "component", 2, 3);
  expect_csv_error(h + "1,ux,0,0,0\n1,1,0,0,0\n", "component", 3, 3);
  expect_csv_error(h + "1,ux,0,0,0\n1,uy,0,1,0\n", "x", 3, 6);
  expect_csv_error(h + "1,ux,0,nan,0\n", "y", 2, 8);
  expect_csv_error(h + "-1,ux,0,0,0\n", "node_id", 2, 1);
  expect_csv_error(h + "1,ux,0,0\n", "row", 2, 1);
  expect_csv_error(h, "row", 1, 0);
  // Columns in another order are fine.
  const auto dofs = parse_dof_map_csv("z,y,x,component,node_id\n3,2,1,rx,5\n", "map.csv");
  ASSERT_EQ(dofs.size(), 1u);
  EXPECT_EQ(dofs[0].x, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(dofs[0].component, 3);
}

// write_dof_map_csv writes what read_dof_map_csv reads: ids, components (q for generalised
// coordinates) and positions come back bit for bit (shortest round-trip form).
TEST_F(MatrixMarketFiles, DofMapRoundTripIsExact) {
  std::vector<solid::DofInfo> dofs;
  for (int c = 0; c < 6; ++c) dofs.push_back({17, c, {0.1, -2.0 / 3.0, 1e-7}});
  dofs.push_back({3, 0, {std::sqrt(2.0), 0.0, -0.25}});
  dofs.push_back({1, -1, Eigen::Vector3d::Zero()});
  dofs.push_back({2, -1, Eigen::Vector3d::Zero()});
  write_dof_map_csv(dir_ / "round.csv", dofs);
  const std::vector<solid::DofInfo> back = read_dof_map_csv(dir_ / "round.csv");
  ASSERT_EQ(back.size(), dofs.size());
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    EXPECT_EQ(back[i].node_id, dofs[i].node_id) << i;
    EXPECT_EQ(back[i].component, dofs[i].component) << i;
    EXPECT_EQ(back[i].x, dofs[i].x) << i;
  }
}

}  // namespace
}  // namespace geardyn::meshio
