// Unit tests of the Craig-Bampton / Guyan reduction on spring-mass chains and a 3-D Timoshenko
// beam (both built in reduce_test_support.hpp).
#include "geardyn/reduce/craig_bampton.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/reduce/frequency_comparison.hpp"
#include "reduce/reduce_test_support.hpp"

namespace geardyn::reduce {
namespace {

using test::beam;
using test::chain;
using test::dense_eigenvalues;

// Keeping every interior mode makes T = [I 0; Psi Phi] square and invertible, so (K_r, M_r) is
// congruent to (K, M) and has exactly the same eigenvalues; only round-off separates them.
// System: free-free chain of 12 unequal masses (one rigid-body mode), masters the two end masses,
// all 10 interior modes kept. Tolerance 1e-10 of the largest eigenvalue: the products in T^T K T
// lose a few digits to the conditioning of Psi and Phi (about 1e-13 observed).
TEST(CraigBampton, AllInteriorModesReproduceTheEigenvaluesExactly) {
  const auto t = chain(12);
  CraigBamptonOptions o;
  o.n_modes = 10;
  const ReducedComponent rc = craig_bampton(t.K, t.M, t.dofs, {0, 11}, o);
  ASSERT_EQ(rc.size(), 12);
  ASSERT_EQ(rc.n_modal, 10);
  EXPECT_EQ(rc.provenance.method, "craig_bampton");
  const Eigen::VectorXd full = dense_eigenvalues(Eigen::MatrixXd(t.K), Eigen::MatrixXd(t.M));
  const Eigen::VectorXd reduced = reduced_eigenvalues(rc);
  ASSERT_EQ(reduced.size(), full.size());
  const double scale = full.maxCoeff();
  for (Eigen::Index k = 0; k < full.size(); ++k)
    EXPECT_NEAR(reduced[k], full[k], 1e-10 * scale) << "mode " << k + 1;

  // The Craig-Bampton structure (docs/theory.md §9): K_r = [K_bb + K_bi Psi, 0; 0, Lambda],
  // M_etaeta = I (mass-normalised fixed-interface modes).
  const Eigen::MatrixXd Kbe = rc.K.topRightCorner(2, 10);
  EXPECT_LE(Kbe.cwiseAbs().maxCoeff(), 1e-10 * scale);
  const Eigen::MatrixXd Mee = rc.M.bottomRightCorner(10, 10);
  EXPECT_LE((Mee - Eigen::MatrixXd::Identity(10, 10)).cwiseAbs().maxCoeff(), 1e-12);
  for (int k = 0; k < 10; ++k) {
    const double omega = 2.0 * 3.141592653589793 * rc.fixed_interface_hz[k];
    EXPECT_NEAR(rc.K(2 + k, 2 + k), omega * omega, 1e-10 * scale);
  }
}

// K_r and M_r are formed blockwise; here they are checked against the plain dense product
// T^T K T with the recovery matrix T (an independent path).
TEST(CraigBampton, BlockwiseProjectionEqualsDenseProduct) {
  const auto t = beam(8);
  CraigBamptonOptions o;
  o.n_modes = 7;
  o.block_size = 5;  // several blocks for 12 masters
  const std::vector<int> masters = select_dofs(t.dofs, {1, 9});
  const ReducedComponent rc = craig_bampton(t.K, t.M, t.dofs, masters, o);
  const Eigen::MatrixXd T = recovery_matrix(rc);
  const Eigen::MatrixXd Kr = T.transpose() * Eigen::MatrixXd(t.K) * T;
  const Eigen::MatrixXd Mr = T.transpose() * Eigen::MatrixXd(t.M) * T;
  EXPECT_LE((Kr - rc.K).norm(), 1e-12 * Kr.norm());
  EXPECT_LE((Mr - rc.M).norm(), 1e-12 * Mr.norm());
  // The master rows of T are the identity (x_b = q_b).
  for (int k = 0; k < rc.n_masters(); ++k) {
    EXPECT_EQ(T(masters[static_cast<std::size_t>(k)], k), 1.0);
    EXPECT_EQ(T.row(masters[static_cast<std::size_t>(k)]).cwiseAbs().sum(), 1.0);
  }
}

// Guyan reduction is exact in statics when every load acts on masters: the interior equations
// K_ii x_i + K_ib x_b = 0 hold exactly for x_i = Psi x_b.
// System: beam of 20 elements clamped at node 1 (its DOFs removed); masters all DOFs of nodes 11
// (midspan) and 21 (tip); load F = (100, -50, 1000) N and moment (0, 20, 5) N m at the tip and a
// lateral 30 N at midspan. Reference: the full sparse solve K x = f. Tolerance 1e-10 relative:
// both sides are direct solves of well-conditioned systems.
TEST(CraigBampton, GuyanIsExactForStaticLoadsOnMasters) {
  const auto clamped = test::remove_dofs(beam(20), {0, 1, 2, 3, 4, 5});
  const std::vector<int> masters = select_dofs(clamped.dofs, {11, 21});
  ASSERT_EQ(masters.size(), 12u);
  const ReducedComponent rc = craig_bampton(clamped.K, clamped.M, clamped.dofs, masters);
  EXPECT_EQ(rc.n_modal, 0);
  EXPECT_EQ(rc.provenance.method, "guyan");

  Eigen::VectorXd f = Eigen::VectorXd::Zero(clamped.K.rows());
  const std::vector<int> tip = select_dofs(clamped.dofs, {21});
  const double tip_load[6] = {100.0, -50.0, 1000.0, 0.0, 20.0, 5.0};
  for (int c = 0; c < 6; ++c) f[tip[static_cast<std::size_t>(c)]] = tip_load[c];
  f[select_dofs(clamped.dofs, {11}, {true, false, false, false, false, false})[0]] = 30.0;

  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> full(clamped.K);
  const Eigen::VectorXd x = full.solve(f);
  Eigen::VectorXd fb(rc.n_masters());
  for (int k = 0; k < rc.n_masters(); ++k) fb[k] = f[masters[static_cast<std::size_t>(k)]];
  const Eigen::VectorXd xb = rc.K.ldlt().solve(fb);
  const Eigen::VectorXd expanded = expand(rc, xb);
  EXPECT_LE((expanded - x).cwiseAbs().maxCoeff(), 1e-10 * x.cwiseAbs().maxCoeff());
}

// A chain of 10 masses cut between masses 7 and 8 (ids), held only at mass 1: masses 8, 9 and 10
// can translate freely along x. The error must name that motion and the nodes.
TEST(CraigBampton, SingularInteriorNamesTheFreeMotion) {
  const auto t = chain(10, 6);
  try {
    craig_bampton(t.K, t.M, t.dofs, {0}, {});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.key_path(), "reduce.craig_bampton.master_dofs");
    EXPECT_NE(what.find("1 free motion"), std::string::npos) << what;
    EXPECT_NE(what.find("translation along x"), std::string::npos) << what;
    EXPECT_NE(what.find("3 node(s) (ids 8, 9, 10)"), std::string::npos) << what;
    EXPECT_NE(what.find("largest at node"), std::string::npos) << what;
  }
}

// Free-free beam whose masters hold every DOF of node 1 except the rotation about the shaft
// axis: the whole shaft can spin about z. Expected: one free motion, rigid rotation about z.
TEST(CraigBampton, FreeTorsionOfABeamIsNamed) {
  const auto t = beam(10);
  const auto masters = select_dofs(t.dofs, {1}, {true, true, true, true, true, false});
  CraigBamptonOptions o;
  o.n_modes = 4;
  try {
    craig_bampton(t.K, t.M, t.dofs, masters, o);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("1 free motion"), std::string::npos) << what;
    EXPECT_NE(what.find("rigid-body rotation about z"), std::string::npos) << what;
    EXPECT_NE(what.find("11 node(s)"), std::string::npos) << what;
  }
}

TEST(CraigBampton, UnconnectedDofIsNamed) {
  auto t = chain(5, 3);  // mass 5 (id 5) hangs on nothing
  try {
    craig_bampton(t.K, t.M, t.dofs, {0}, {});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("node 5 ux"), std::string::npos) << e.what();
  }
}

// Cut-off mode keeps exactly the fixed-interface modes below f_max. Reference: the dense
// eigenvalues of (K_ii, M_ii) of a 30-mass chain held at mass 1.
TEST(CraigBampton, FrequencyCutOffKeepsTheModesBelowIt) {
  const auto t = chain(30);
  const auto interior = test::remove_dofs(t, {0});
  const Eigen::VectorXd lambda =
      dense_eigenvalues(Eigen::MatrixXd(interior.K), Eigen::MatrixXd(interior.M));
  const double f_max = 0.5 * (frequency_hz(lambda[6]) + frequency_hz(lambda[7]));
  CraigBamptonOptions o;
  o.frequency_max_hz = f_max;
  const ReducedComponent rc = craig_bampton(t.K, t.M, t.dofs, {0}, o);
  ASSERT_EQ(rc.n_modal, 7);
  for (int k = 0; k < 7; ++k)
    EXPECT_NEAR(rc.fixed_interface_hz[k], frequency_hz(lambda[k]), 1e-9 * frequency_hz(lambda[k]));
}

TEST(CraigBampton, BadInputIsRejected) {
  const auto t = chain(6);
  CraigBamptonOptions o;
  o.n_modes = 5;  // only 4 interior DOFs
  EXPECT_THROW(craig_bampton(t.K, t.M, t.dofs, {0, 5}, o), InputError);
  o.n_modes = 2;
  o.frequency_max_hz = 10.0;
  EXPECT_THROW(craig_bampton(t.K, t.M, t.dofs, {0, 5}, o), InputError);
  EXPECT_THROW(craig_bampton(t.K, t.M, t.dofs, {0, 0}, {}), InputError);
  EXPECT_THROW(craig_bampton(t.K, t.M, t.dofs, {6}, {}), InputError);
  Eigen::SparseMatrix<double> K = t.K;
  K.coeffRef(0, 1) += 1.0;  // not symmetric
  EXPECT_THROW(craig_bampton(K, t.M, t.dofs, {0}, {}), InputError);
}

TEST(SelectDofs, ByNodeIdAndComponents) {
  const auto t = beam(4);
  const auto all = select_dofs(t.dofs, {2});
  EXPECT_EQ(all, (std::vector<int>{6, 7, 8, 9, 10, 11}));
  const auto trans = select_dofs(t.dofs, {5, 1}, kTranslations);
  EXPECT_EQ(trans, (std::vector<int>{0, 1, 2, 24, 25, 26}));
  EXPECT_THROW(select_dofs(t.dofs, {42}), InputError);
  EXPECT_EQ(merge_dofs({{3, 1}, {1, 2}}), (std::vector<int>{1, 2, 3}));

  solid::Mesh mesh;
  mesh.node_ids = {1, 2, 3, 4, 5};
  mesh.coords.resize(5, Eigen::Vector3d::Zero());
  mesh.node_sets["tip"] = {4};
  EXPECT_EQ(select_dofs(mesh, t.dofs, "tip", kTranslations), (std::vector<int>{24, 25, 26}));
  try {
    select_dofs(mesh, t.dofs, "root");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(e.hint().find("tip"), std::string::npos);
  }
}

TEST(FrequencyComparison, TableColumnsAndErrors) {
  Eigen::VectorXd full(3), reduced(3);
  const double w = 2.0 * 3.141592653589793;
  full << 0.0, std::pow(w * 10.0, 2), std::pow(w * 20.0, 2);
  reduced << 1e-12, std::pow(w * 10.1, 2), std::pow(w * 20.0, 2);
  const Table t = compare_frequencies(full, reduced);
  t.validate();
  EXPECT_EQ(t.rows(), 3u);
  EXPECT_DOUBLE_EQ(t.column("mode").numbers[2], 3.0);
  EXPECT_NEAR(t.column("full_hz").numbers[1], 10.0, 1e-12);
  EXPECT_NEAR(t.column("reduced_hz").numbers[1], 10.1, 1e-12);
  EXPECT_NEAR(t.column("error_pct").numbers[1], 1.0, 1e-9);
  EXPECT_NEAR(t.column("error_pct").numbers[2], 0.0, 1e-12);
  EXPECT_LT(std::abs(t.column("error_pct").numbers[0]), 1.0);  // rigid body against the floor
}

}  // namespace
}  // namespace geardyn::reduce
