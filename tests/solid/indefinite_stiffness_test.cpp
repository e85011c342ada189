// The solid eigen-solve refuses an indefinite stiffness with a clear message instead of
// reporting its negative eigenvalue as a 0 Hz mode.
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <string>

#include "geardyn/analyses/solid_helpers.hpp"
#include "geardyn/core/error.hpp"

namespace geardyn::analyses {
namespace {

Eigen::SparseMatrix<double> diagonal(const Eigen::VectorXd& d) {
  Eigen::SparseMatrix<double> A(d.size(), d.size());
  for (Eigen::Index i = 0; i < d.size(); ++i) A.insert(i, i) = d(i);
  A.makeCompressed();
  return A;
}

// K = diag(4e6, -1e6, 9e6), M = I: eigenvalues omega^2 = -1e6, 4e6, 9e6 (exact for a diagonal
// pencil). The negative one is far below the round-off level 1e-8 max K_ii / M_ii = 0.09.
TEST(SolidEigenSolve, IndefiniteStiffnessIsNamed) {
  const Eigen::SparseMatrix<double> K = diagonal(Eigen::Vector3d(4e6, -1e6, 9e6));
  const Eigen::SparseMatrix<double> M = diagonal(Eigen::Vector3d(1, 1, 1));
  try {
    (void)solve_modes(K, M, 3, eig::kNaN, "modes");
    FAIL() << "no NumericalError";
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("not positive semi-definite"), std::string::npos) << what;
    EXPECT_NE(what.find("omega^2 = -1e+06"), std::string::npos) << what;
  }
}

// A free body (rigid-body mode, omega^2 = 0 up to round-off) is not refused: K of a free
// two-mass chain, k = 1e6, m = 1: omega^2 = 0 and 2e6.
TEST(SolidEigenSolve, RigidBodyModesAreAccepted) {
  Eigen::SparseMatrix<double> K(2, 2);
  K.insert(0, 0) = 1e6;
  K.insert(0, 1) = -1e6;
  K.insert(1, 0) = -1e6;
  K.insert(1, 1) = 1e6;
  K.makeCompressed();
  const eig::SymmetricEigenResult r =
      solve_modes(K, diagonal(Eigen::Vector2d(1, 1)), 2, eig::kNaN, "modes");
  ASSERT_EQ(r.eigenvalues.size(), 2);
  // Round-off of a 2x2 solve: 1e-9 of the scale 2e6.
  EXPECT_NEAR(r.eigenvalues[0], 0.0, 1e-9 * 2e6);
  EXPECT_NEAR(r.eigenvalues[1], 2e6, 1e-9 * 2e6);
}

}  // namespace
}  // namespace geardyn::analyses
