// Validation of Craig-Bampton against the full finite-element model it reduces.
//
// Oracle: the eigenvalues of the full model with the same boundary condition. Craig-Bampton is a
// Rayleigh-Ritz method on the subspace spanned by T = [I 0; Psi Phi] (Craig & Bampton, AIAA J. 6
// (1968) 1313-1319), so each reduced eigenvalue is an upper bound of the full one and, with
// nested mode sets, falls monotonically as fixed-interface modes are added.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/reduce/frequency_comparison.hpp"
#include "geardyn/solid/assembly.hpp"
#include "geardyn/solid/structured_mesh.hpp"
#include "reduce/reduce_test_support.hpp"

namespace geardyn::reduce {
namespace {

// Checks the convergence table: errors >= 0 up to round-off (upper bounds) and max_error_pct
// non-increasing down the table (nested Rayleigh-Ritz subspaces). The 1e-9 % slack is round-off
// of the eigenvalues themselves (relative 1e-11).
void expect_monotone(const Table& t) {
  const auto& e = t.column("max_error_pct").numbers;
  for (std::size_t k = 1; k < e.size(); ++k)
    EXPECT_LE(e[k], e[k - 1] + 1e-9) << "row " << k << " of " << t.name;
}

// Shaft of 40 Timoshenko elements (1 m, d = 40 mm, steel), clamped at node 1:
//
//   ||==o==o==o== ... ==o==o   node 1 clamped (masters, then held), node 41 free (masters)
//
// Masters: all 6 DOFs of nodes 1 and 41. The fixed-interface modes are computed by the sparse
// shift-invert Lanczos path (dense_limit lowered below the 234 interior DOFs). Requirement:
// the first 10 natural frequencies (bending pairs, torsion, axial) within 0.5 % of the full
// model with 12 fixed-interface modes.
TEST(CraigBamptonValidation, CantileverBeamFirstTenModes) {
  const auto t = test::beam(40);
  const std::vector<int> root = select_dofs(t.dofs, {1});
  const std::vector<int> masters = select_dofs(t.dofs, {1, 41});
  const auto clamped = test::remove_dofs(t, root);
  const Eigen::VectorXd full =
      test::dense_eigenvalues(Eigen::MatrixXd(clamped.K), Eigen::MatrixXd(clamped.M));

  CraigBamptonOptions o;
  o.n_modes = 40;
  o.dense_limit = 50;
  const ReducedComponent rc = craig_bampton(t.K, t.M, t.dofs, masters, o);
  EXPECT_NE(rc.provenance.solver_report.find("sparse"), std::string::npos)
      << rc.provenance.solver_report;
  const std::vector<int> held{0, 1, 2, 3, 4, 5};  // node 1 is masters[0..5]

  const int kept = 12;
  const Table cmp = compare_frequencies(full, reduced_eigenvalues(truncate(rc, kept), held));
  for (int k = 0; k < 10; ++k) {
    const double e = cmp.column("error_pct").numbers[static_cast<std::size_t>(k)];
    EXPECT_LE(e, 0.5) << "mode " << k + 1 << " at "
                      << cmp.column("full_hz").numbers[static_cast<std::size_t>(k)] << " Hz";
    EXPECT_GE(e, -1e-8) << "mode " << k + 1 << ": Rayleigh-Ritz bound violated";
  }
  const Table conv = convergence_table(rc, full, {4, 6, 8, 12, 20, 40}, 10, held);
  expect_monotone(conv);
  std::printf("beam: n_modes -> max error of first 10 [%%]:");
  for (std::size_t r = 0; r < conv.rows(); ++r)
    std::printf(" %g:%.4g", conv.column("n_modes").numbers[r],
                conv.column("max_error_pct").numbers[r]);
  std::printf("\n");
}

// Solid cantilever: steel bar 0.3 x 0.03 x 0.03 m, 10 x 2 x 2 Hex20 cells (box_mesh), clamped on
// the face x = 0. Masters: the translations of every node on the clamped face ("xmin") and on
// the loaded end face ("xmax"). Reduced model held on the xmin masters; reference: the full
// assembled model with those DOFs removed, solved by the sparse Lanczos solver. Requirement: the
// first 10 frequencies within 0.5 % with 20 fixed-interface modes.
TEST(CraigBamptonValidation, SolidHex20CantileverFirstTenModes) {
  solid::Material steel;
  steel.name = "steel";
  steel.E = 210e9;
  steel.nu = 0.3;
  steel.rho = 7850.0;
  const solid::Mesh mesh =
      solid::box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.3, 0.03, 0.03), 10, 2, 2,
                      solid::ElementType::Hex20, steel);
  const solid::SolidSystem sys = solid::assemble(mesh);
  const std::vector<int> clamp = select_dofs(mesh, sys.dofs, "xmin", kTranslations);
  const std::vector<int> masters =
      merge_dofs({clamp, select_dofs(mesh, sys.dofs, "xmax", kTranslations)});

  test::TestModel model{sys.K, sys.M, sys.dofs};
  const auto clamped = test::remove_dofs(model, clamp);
  eig::SymmetricEigenOptions eo;
  eo.n_modes = 12;
  const auto full = eig::solve_symmetric(clamped.K, clamped.M, eo);
  ASSERT_EQ(full.status, Status::Ok) << full.brief_report();

  CraigBamptonOptions o;
  o.n_modes = 30;
  const ReducedComponent rc = craig_bampton(sys.K, sys.M, sys.dofs, masters, o);
  std::vector<int> held;  // positions of the clamp DOFs among the masters
  for (int k = 0; k < rc.n_masters(); ++k)
    if (std::find(clamp.begin(), clamp.end(), masters[static_cast<std::size_t>(k)]) != clamp.end())
      held.push_back(k);
  ASSERT_EQ(held.size(), clamp.size());

  const Table cmp =
      compare_frequencies(full.eigenvalues, reduced_eigenvalues(truncate(rc, 20), held));
  for (int k = 0; k < 10; ++k) {
    const double e = cmp.column("error_pct").numbers[static_cast<std::size_t>(k)];
    EXPECT_LE(e, 0.5) << "mode " << k + 1;
    EXPECT_GE(e, -1e-6) << "mode " << k + 1 << ": Rayleigh-Ritz bound violated";
  }
  const Table conv = convergence_table(rc, full.eigenvalues, {0, 5, 10, 20, 30}, 10, held);
  expect_monotone(conv);
  std::printf("hex20 (%d DOFs, %d masters): first full %.2f Hz; n_modes -> max error [%%]:",
              static_cast<int>(sys.dofs.size()), rc.n_masters(), cmp.column("full_hz").numbers[0]);
  for (std::size_t r = 0; r < conv.rows(); ++r)
    std::printf(" %g:%.4g", conv.column("n_modes").numbers[r],
                conv.column("max_error_pct").numbers[r]);
  std::printf("\n");
}

}  // namespace
}  // namespace geardyn::reduce
