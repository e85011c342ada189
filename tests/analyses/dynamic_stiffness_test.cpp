// Unit tests of DynamicStiffness: the sparse LU solve of D(w), the Woodbury treatment of modal
// damping against a dense solve with the full C_modal, singularity detection.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>

#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/core/error.hpp"
#include "harmonic_test_support.hpp"

namespace geardyn::analyses {
namespace {

using namespace geardyn::harmonic_test;

// A 6-DOF grounded chain with a skew gyroscopic coupling between DOF pairs, viscous damping on
// one spring, hysteretic damping on another and modal damping on its lowest four modes:
// every term of D(w) is present and D is complex non-symmetric.
struct Fixture {
  fe::LinearSystem system;
  Eigen::MatrixXd M, K, C, G, K_loss, C_modal;
  double speed = 150.0;

  Fixture() {
    const int n = 6;
    M = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0).asDiagonal();
    K = chain_stiffness(n, 4e4);
    C = Eigen::MatrixXd::Zero(n, n);
    C(2, 2) = 3.0;
    G = Eigen::MatrixXd::Zero(n, n);
    G(0, 1) = 0.02;
    G(1, 0) = -0.02;
    G(3, 4) = 0.05;
    G(4, 3) = -0.05;
    K_loss = Eigen::MatrixXd::Zero(n, n);
    K_loss(5, 5) = 0.01 * 4e4;
    system.M = sparse(M);
    system.K = sparse(K);
    system.C = sparse(C);
    system.G = sparse(G);
    system.K_loss = sparse(K_loss);
    // Mass-normalised undamped modes: Phi^T M Phi = I, B = M Phi, c_r = 2 zeta_r omega_r.
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
    const int r = 4;
    const Eigen::MatrixXd Phi = eig.eigenvectors().leftCols(r);
    system.modal_basis = M * Phi;
    system.modal_coefficients.resize(r);
    const double zeta[] = {0.01, 0.02, 0.0, 0.05};  // a zero ratio is allowed
    for (int i = 0; i < r; ++i)
      system.modal_coefficients[i] = 2.0 * zeta[i] * std::sqrt(eig.eigenvalues()[i]);
    C_modal = system.modal_basis * system.modal_coefficients.asDiagonal() *
              system.modal_basis.transpose();
  }

  Eigen::MatrixXcd dense(double w) const {
    const Complex i(0.0, 1.0);
    return (K - w * w * M).cast<Complex>() + i * w * (C + speed * G + C_modal).cast<Complex>() +
           i * K_loss.cast<Complex>();
  }
};

TEST(DynamicStiffness, WoodburyModalDampingEqualsDenseSolve) {
  Fixture fx;
  DynamicStiffness D(fx.system, fx.speed, "test");
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(fx.K, fx.M);
  std::vector<double> omegas = {0.0, 5.0, 60.0, 333.3};
  // At the undamped natural frequencies the sparse part is nearly singular; the low-rank term
  // restores a regular D and the Woodbury result must still match.
  for (int k = 0; k < 3; ++k) omegas.push_back(std::sqrt(eig.eigenvalues()[k]) * (1.0 + 1e-9));
  Eigen::MatrixXcd F = Eigen::MatrixXcd::Zero(6, 2);
  F(0, 0) = 1.0;
  F(5, 1) = Complex(0.3, -2.0);
  for (double w : omegas) {
    D.factorize(w);
    const Eigen::MatrixXcd x = D.solve(F);
    const Eigen::MatrixXcd ref = fx.dense(w).fullPivLu().solve(F);
    // Both are backward-stable solves of a system with condition number < 1e7 here
    // (modal damping 1 % at resonance): agreement to 1e-9 relative leaves a margin of 1e2
    // over eps * cond.
    EXPECT_LT((x - ref).norm(), 1e-9 * ref.norm()) << "w = " << w;
    // Residual of the defining equation through the operator.
    EXPECT_LT((D.apply(x) - F).norm(), 1e-12 * (F.norm() + fx.dense(w).norm() * x.norm()))
        << "w = " << w;
  }
}

TEST(DynamicStiffness, SpeedChangesGyroscopicTerm) {
  Fixture fx;
  DynamicStiffness D(fx.system, 0.0, "test");
  D.set_speed(fx.speed);
  D.factorize(40.0);
  Eigen::MatrixXcd F = Eigen::MatrixXcd::Ones(6, 1);
  const Eigen::MatrixXcd ref = fx.dense(40.0).fullPivLu().solve(F);
  EXPECT_LT((D.solve(F) - ref).norm(), 1e-10 * ref.norm());
}

TEST(DynamicStiffness, RigidBodyAtZeroFrequencyIsNamed) {
  // Free-free chain of 5 masses: K has a rigid-body null space, D(0) = K is singular.
  const Eigen::MatrixXd K = chain_stiffness(5, 1e5, false);
  fe::LinearSystem s;
  s.M = sparse(Eigen::MatrixXd::Identity(5, 5));
  s.K = sparse(K);
  DynamicStiffness D(s, 0.0, "frf");
  try {
    D.factorize(0.0);
    FAIL() << "expected NumericalError";
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("analysis 'frf'"), std::string::npos) << what;
    EXPECT_NE(what.find("f = 0 Hz"), std::string::npos) << what;
    EXPECT_NE(what.find("rigid-body motion: add bearings or constraints"), std::string::npos)
        << what;
  }
  EXPECT_NO_THROW(D.factorize(1.0));  // the mass term makes D regular above 0
}

TEST(DynamicStiffness, UndampedResonanceIsSingular) {
  // k - w^2 m = 0 exactly for k = 4, m = 1, w = 2, no damping at all.
  fe::LinearSystem s = sdof(1.0, 4.0, 0.0);
  DynamicStiffness D(s, 0.0, "frf");
  try {
    D.factorize(2.0);
    FAIL() << "expected NumericalError";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("natural frequency"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace geardyn::analyses
