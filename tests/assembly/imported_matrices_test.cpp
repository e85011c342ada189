// Definiteness of imported K and M beyond their diagonals (sparse Cholesky factorisations), and
// the check wired into a [[solids]] type = "matrices" component.
#include "geardyn/assembly/imported_matrices.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <filesystem>
#include <fstream>
#include <string>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/error.hpp"

namespace geardyn::assembly {
namespace {

namespace fs = std::filesystem;

Eigen::SparseMatrix<double> sparse(const Eigen::MatrixXd& A) { return A.sparseView(); }

InputError check_error(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M) {
  try {
    check_imported_matrices(sparse(K), sparse(M), SourceLocation{"model.toml", 12, 1},
                            "solids[0].stiffness_file", "K.mtx", "solids[0].mass_file", "M.mtx");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError({}, "", "", "");
}

// M = [[1, 2], [2, 1]]: positive diagonal, eigenvalues 3 and -1 (trace 2, determinant -3):
// indefinite, which only the factorisation sees.
TEST(ImportedMatrices, IndefiniteMassWithPositiveDiagonalIsRefused) {
  Eigen::MatrixXd M(2, 2), K(2, 2);
  M << 1, 2, 2, 1;
  K << 2, -1, -1, 2;
  const InputError e = check_error(K, M);
  EXPECT_EQ(e.key_path(), "solids[0].mass_file");
  EXPECT_EQ(e.where().line, 12);
  EXPECT_NE(e.found().find("'M.mtx': M is not positive definite"), std::string::npos) << e.found();
}

// K = [[1, -3], [-3, 1]] with M = I: eigenvalues 4 and -2, positive diagonal. The shift is
// s = 1e-8 max K_ii / M_ii = 1e-8, far below 2: refused.
TEST(ImportedMatrices, IndefiniteStiffnessWithPositiveDiagonalIsRefused) {
  Eigen::MatrixXd K(2, 2);
  K << 1, -3, -3, 1;
  const InputError e = check_error(K, Eigen::MatrixXd::Identity(2, 2));
  EXPECT_EQ(e.key_path(), "solids[0].stiffness_file");
  EXPECT_NE(e.found().find("'K.mtx': K has a negative eigenvalue"), std::string::npos) << e.found();
}

// A free-free chain of three masses on two springs is positive semi-definite (one rigid-body
// mode, K [1 1 1]^T = 0 exactly): accepted, as is a positive definite clamped chain.
TEST(ImportedMatrices, SemiDefiniteAndDefiniteStiffnessAreAccepted) {
  const double k = 3e7;
  Eigen::MatrixXd free(3, 3), clamped(3, 3);
  free << k, -k, 0, -k, 2 * k, -k, 0, -k, k;
  clamped << 2 * k, -k, 0, -k, 2 * k, -k, 0, -k, k;
  const Eigen::MatrixXd M = Eigen::Vector3d(0.5, 2.0, 1.0).asDiagonal();
  EXPECT_NO_THROW(check_imported_matrices(sparse(free), sparse(M), {}, "k", "K", "m", "M"));
  EXPECT_NO_THROW(check_imported_matrices(sparse(clamped), sparse(M), {}, "k", "K", "m", "M"));
  // The smallest negative eigenvalue the check sees: K = diag(1, -eps) is refused once eps
  // exceeds the shift 1e-8 (here 1e-6), not at round-off size (1e-12).
  Eigen::MatrixXd tiny = Eigen::MatrixXd::Identity(2, 2);
  tiny(1, 1) = -1e-12;
  EXPECT_NO_THROW(check_imported_matrices(sparse(tiny), sparse(Eigen::MatrixXd::Identity(2, 2)), {},
                                          "k", "K", "m", "M"));
  tiny(1, 1) = -1e-6;
  EXPECT_THROW(check_imported_matrices(sparse(tiny), sparse(Eigen::MatrixXd::Identity(2, 2)), {},
                                       "k", "K", "m", "M"),
               InputError);
}

// Through the model: a "matrices" solid whose mass is indefinite off the diagonal is refused at
// the solid's table and its mass_file key.
TEST(ImportedMatrices, MatricesSolidIsChecked) {
  const fs::path dir = fs::temp_directory_path() / "geardyn_imported_matrices_solid";
  fs::create_directories(dir);
  std::ofstream(dir / "K.mtx") << "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n"
                                  "1 1 2e6\n2 1 -1e6\n2 2 1e6\n";
  std::ofstream(dir / "M.mtx") << "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n"
                                  "1 1 1\n2 1 3\n2 2 1\n";
  std::ofstream(dir / "dofs.csv") << "node_id,component,x,y,z\n1,ux,0,0,0\n2,ux,1,0,0\n";
  const std::string text = R"(version = 1

[[solids]]
name = "block"
type = "matrices"
stiffness_file = "K.mtx"
mass_file = "M.mtx"
dof_map_file = "dofs.csv"
)";
  const model::Model m = analyses::parse_model(text, (dir / "model.toml").string());
  try {
    (void)build_solid(m, m.solids.front());
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "solids[0].mass_file");
    EXPECT_EQ(e.where().line, 3);
    EXPECT_NE(e.found().find("M.mtx"), std::string::npos);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace geardyn::assembly
