// Interface-mode (Tran) reduction of Craig-Bampton components.
// Source: D.-M. Tran, "Component mode synthesis methods using interface modes. Application to
// structures with cyclic symmetry", Computers & Structures 79 (2001); A. Durastante, "Simulation
// of the Dynamic Response of Aeronautical Gears Equipped with Damper Rings", MSc thesis,
// Politecnico di Torino, 2018, chapter 2.2.3: at least six interface modes so that the rigid-body
// motions survive.
#include "geardyn/reduce/interface_reduction.hpp"

#include <gtest/gtest.h>

#include <complex>
#include <numeric>

#include "geardyn/core/error.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/solid/assembly.hpp"
#include "geardyn/solid/structured_mesh.hpp"
#include "reduce/reduce_test_support.hpp"

namespace geardyn::reduce {
namespace {

std::vector<int> first_n(int n) {
  std::vector<int> v(static_cast<std::size_t>(n));
  std::iota(v.begin(), v.end(), 0);
  return v;
}

// Free-free shaft of 10 elements, masters all DOFs of both end nodes (the "sector interfaces"),
// 8 fixed-interface modes: 20 reduced coordinates with six rigid-body modes.
ReducedComponent free_beam_component() {
  const auto t = test::beam(10);
  CraigBamptonOptions o;
  o.n_modes = 8;
  return craig_bampton(t.K, t.M, t.dofs, select_dofs(t.dofs, {1, 11}), o);
}

// With every interface mode kept, T = [Phi_I 0; 0 I] is square and invertible: the eigenvalues
// are those of the Craig-Bampton pair. Tolerance 1e-10 of the largest eigenvalue (round-off of
// two dense congruences).
TEST(InterfaceReduction, AllInterfaceModesReproduceCraigBampton) {
  const ReducedComponent rc = free_beam_component();
  const auto tran = interface_mode_reduction<double>(rc.K, rc.M, first_n(12), 12);
  EXPECT_EQ(tran.K.rows(), 20);
  const Eigen::VectorXd cb = test::dense_eigenvalues(rc.K, rc.M);
  const Eigen::VectorXd reduced = test::dense_eigenvalues(tran.K, tran.M);
  for (Eigen::Index k = 0; k < cb.size(); ++k)
    EXPECT_NEAR(reduced[k], cb[k], 1e-10 * cb.maxCoeff()) << "mode " << k + 1;
  // Interface modes are M_g-orthonormal: the interface block of the new mass is I.
  EXPECT_LE(
      (tran.M.topLeftCorner(12, 12) - Eigen::MatrixXd::Identity(12, 12)).cwiseAbs().maxCoeff(),
      1e-10);
  // The other coordinates (the modal ones) are kept as they are.
  EXPECT_EQ(tran.other_dofs, (std::vector<int>{12, 13, 14, 15, 16, 17, 18, 19}));
  EXPECT_EQ(tran.transformation.bottomRightCorner(8, 8), Eigen::MatrixXd::Identity(8, 8));
}

// Free-free solid block: 0.1 x 0.04 x 0.04 m steel, 4 x 2 x 2 Hex20 cells. Craig-Bampton on the
// translations of the faces x = 0 and x = 0.1 (the "interfaces", 126 DOFs) with 10 modes, then
// Tran with 6 interface modes: the six lowest Guyan interface modes are the rigid-body motions
// (the interface DOFs alone can carry them, and the constraint modes extend them rigidly), so
// the reduced model keeps six zero eigenvalues. Zero means |lambda| <= 1e-8 lambda_7 (the rigid
// modes of the full CB pair come out at ~1e-12 of it from round-off).
TEST(InterfaceReduction, SixInterfaceModesKeepTheRigidBodyModes) {
  solid::Material steel;
  steel.name = "steel";
  steel.E = 210e9;
  steel.nu = 0.3;
  steel.rho = 7850.0;
  const auto mesh = solid::box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, 0.04, 0.04), 4,
                                    2, 2, solid::ElementType::Hex20, steel);
  const auto sys = solid::assemble(mesh);
  const auto masters = merge_dofs({select_dofs(mesh, sys.dofs, "xmin", kTranslations),
                                   select_dofs(mesh, sys.dofs, "xmax", kTranslations)});
  CraigBamptonOptions o;
  o.n_modes = 10;
  const ReducedComponent rc = craig_bampton(sys.K, sys.M, sys.dofs, masters, o);
  const Eigen::VectorXd cb = test::dense_eigenvalues(rc.K, rc.M);
  ASSERT_LE(std::abs(cb[5]), 1e-8 * cb[6]);  // the CB pair itself is free-free

  const auto tran = interface_mode_reduction<double>(rc.K, rc.M, first_n(rc.n_masters()), 6);
  EXPECT_EQ(tran.K.rows(), 16);
  const Eigen::VectorXd lambda = test::dense_eigenvalues(tran.K, tran.M);
  for (int k = 0; k < 6; ++k)
    EXPECT_LE(std::abs(lambda[k]), 1e-8 * cb[6]) << "rigid mode " << k + 1;
  EXPECT_GT(lambda[6], 0.5 * cb[6]);  // and the first elastic mode is elastic
  // The interface eigenproblem has exactly six zero eigenvalues.
  EXPECT_LE(std::abs(tran.interface_eigenvalues[5]), 1e-8 * tran.interface_eigenvalues[6]);

  EXPECT_THROW(interface_mode_reduction<double>(rc.K, rc.M, first_n(rc.n_masters()), 5),
               InputError);
}

// The Hermitian case: (D^H K D, D^H M D) with D = diag(e^{i theta_k}) is unitarily congruent to
// (K, M), and the interface problem maps the same way, so the complex reduction must give the
// real one's eigenvalues (a transpose where an adjoint belongs would break this).
TEST(InterfaceReduction, ComplexHermitianPairMatchesTheRealOne) {
  const ReducedComponent rc = free_beam_component();
  const Eigen::Index m = rc.size();
  Eigen::VectorXcd d(m);
  for (Eigen::Index k = 0; k < m; ++k) d[k] = std::polar(1.0, 0.3 * k + 0.1 * k * k);
  const Eigen::MatrixXcd D = d.asDiagonal();
  const Eigen::MatrixXcd Kc = D.adjoint() * rc.K.cast<std::complex<double>>() * D;
  const Eigen::MatrixXcd Mc = D.adjoint() * rc.M.cast<std::complex<double>>() * D;
  for (int n_modes : {6, 12}) {
    const auto real = interface_mode_reduction<double>(rc.K, rc.M, first_n(12), n_modes);
    const auto cplx = interface_mode_reduction<std::complex<double>>(Kc, Mc, first_n(12), n_modes);
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXcd> s(cplx.K, cplx.M,
                                                                       Eigen::EigenvaluesOnly);
    const Eigen::VectorXd expected = test::dense_eigenvalues(real.K, real.M);
    for (Eigen::Index k = 0; k < expected.size(); ++k)
      EXPECT_NEAR(s.eigenvalues()[k], expected[k], 1e-10 * expected.maxCoeff())
          << n_modes << " interface modes, mode " << k + 1;
    EXPECT_LE((cplx.K - cplx.K.adjoint()).norm(), 1e-14 * cplx.K.norm());
  }
}

// If the interface does not hold the other coordinates (here: the modal coordinates are taken as
// the "interface", leaving the free-free physical masters outside), K_OO is singular.
TEST(InterfaceReduction, FreeOtherCoordinatesAreRejected) {
  const ReducedComponent rc = free_beam_component();
  std::vector<int> modal(8);
  std::iota(modal.begin(), modal.end(), 12);
  EXPECT_THROW(interface_mode_reduction<double>(rc.K, rc.M, modal, 6), InputError);
  EXPECT_THROW(interface_mode_reduction<double>(rc.K, rc.M, first_n(12), 13), InputError);
  EXPECT_THROW(interface_mode_reduction<double>(rc.K, rc.M, {0, 0, 1, 2, 3, 4, 5}, 6), InputError);
}

}  // namespace
}  // namespace geardyn::reduce
