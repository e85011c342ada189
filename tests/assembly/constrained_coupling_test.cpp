// A solid joined by averaging (RBE3) spiders and a sensor set is reduced with the constraints
// kept as constraints (couple_solid, reduce::craig_bampton with InterfaceConstraints); the
// references are plain Craig-Bampton in coordinates that satisfy the constraints: a dense,
// well-conditioned parametrisation built here, and the pivot elimination x = S z of
// spider_system; both span the same subspace (docs/theory.md §9). The coupled rotor systems
// built from the bodies must have the same natural frequencies.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/assembly/solid_coupling.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "spider_test_support.hpp"

namespace geardyn {
namespace {

using test::spider_rotor;

// An annular plate (as in spider_test_support.hpp, coarser) joined by `inner` (to s.2) and
// `outer` (to s.3), with a sensor on its top face; `modes` ends the kept modes at a gap.
std::string two_spider_plate(const std::string& inner_kind, const std::string& outer_kind,
                             int modes) {
  return fmt::format(R"(
[[solids]]
name = "disk"
type = "annular_plate"
material = "steel"
inner_radius = 0.02
outer_radius = 0.15
thickness = 0.01
radial_elements = 2
circumferential_elements = 16
layers = 1
order = 2
coupling_modes = {}
  [[solids.spiders]]
  node_set = "inner"
  node = "s.2"
  kind = "{}"
  [[solids.spiders]]
  node_set = "outer"
  node = "s.3"
  kind = "{}"

[[sensors]]
name = "face_z"
solid = "disk"
node_set = "top"
dof = "uz"
)",
                     modes, inner_kind, outer_kind);
}

// The lowest n natural frequencies [Hz] of the rotor system with `body` joined.
Eigen::VectorXd coupled_frequencies(const model::Model& m, const fe::Superelement& body, int n) {
  const fe::LinearSystem s = fe::assemble(m, {}, {body});
  eig::SymmetricEigenOptions o;
  o.n_modes = n;
  const auto r = eig::solve_symmetric(s.K, s.M, o);
  EXPECT_EQ(r.status, Status::Ok) << r.brief_report();
  return r.eigenvalues.cwiseMax(0.0).cwiseSqrt() / (2.0 * std::numbers::pi);
}

// The dense reference: the solid in coordinates z = [w; q_b] with x_i = Z w + A_i^+ (u - A_m x_m)
// and x_m = the rigid masters, Z an orthonormal basis of {A_i x = 0} (Householder QR of A_i^T),
// A_i^+ = A_i^T (A_i A_i^T)^-1. S is well conditioned (orthonormal Z, the pseudo-inverse of a
// few rows), unlike the pivot elimination of spider_system, and maps z one to one onto
// {A x = u}; plain Craig-Bampton on the dense (S^T K S, S^T M S) then gives the reduction.
reduce::ReducedComponent dense_reference(const assembly::SpiderSystem& ss, int n_modes) {
  const Eigen::SparseMatrix<double>& A = ss.constraints.A;
  const auto n = static_cast<int>(A.cols()), r = static_cast<int>(A.rows());
  const std::vector<int>& masters = ss.constrained_masters;
  std::vector<int> master_of(static_cast<std::size_t>(n), -1), interior;
  for (std::size_t k = 0; k < masters.size(); ++k)
    if (masters[k] < n) master_of[static_cast<std::size_t>(masters[k])] = static_cast<int>(k);
  for (int j = 0; j < n; ++j)
    if (master_of[static_cast<std::size_t>(j)] < 0) interior.push_back(j);
  const auto ni = static_cast<int>(interior.size()), nw = ni - r;
  const auto nz = nw + static_cast<int>(masters.size());
  const Eigen::MatrixXd Ad(A);
  Eigen::MatrixXd Ai(r, ni);
  for (int c = 0; c < ni; ++c) Ai.col(c) = Ad.col(interior[static_cast<std::size_t>(c)]);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Ai.transpose());
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(ni, ni);
  const Eigen::MatrixXd pinv = Ai.transpose() * (Ai * Ai.transpose()).inverse();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, nz);
  Eigen::MatrixXd Si(ni, nz);
  Si.leftCols(nw) = Q.rightCols(nw);
  solid::DofInfo modal;
  modal.node_id = 0;
  modal.component = -1;
  modal.x = Eigen::Vector3d::Zero();
  std::vector<solid::DofInfo> zdofs(static_cast<std::size_t>(nz), modal);
  std::vector<int> zmasters;
  for (std::size_t k = 0; k < masters.size(); ++k) {
    const int col = nw + static_cast<int>(k), g = masters[k];
    zmasters.push_back(col);
    if (g >= n) {
      Si.col(col) = pinv.col(g - n);
      zdofs[static_cast<std::size_t>(col)] = ss.constraints.dofs[static_cast<std::size_t>(g - n)];
    } else {
      Si.col(col) = -pinv * Ad.col(g);
      S(g, col) = 1.0;
      zdofs[static_cast<std::size_t>(col)] = ss.system.dofs[static_cast<std::size_t>(g)];
    }
  }
  for (int c = 0; c < ni; ++c) S.row(interior[static_cast<std::size_t>(c)]) = Si.row(c);
  auto project = [&](const Eigen::SparseMatrix<double>& X) {
    const Eigen::MatrixXd XS = X * S;
    Eigen::MatrixXd Xz = S.transpose() * XS;
    Xz = 0.5 * (Xz + Xz.transpose()).eval();
    return Eigen::SparseMatrix<double>(Xz.sparseView());
  };
  reduce::CraigBamptonOptions o;
  o.n_modes = n_modes;
  return reduce::craig_bampton(project(ss.system.K), project(ss.system.M), zdofs, zmasters, o);
}

// The reduced body of `rc` in place of `body`'s matrices.
fe::Superelement body_of(const fe::Superelement& like, const reduce::ReducedComponent& rc) {
  fe::Superelement body = like;
  body.K = 0.5 * (rc.K + rc.K.transpose());
  body.M = 0.5 * (rc.M + rc.M.transpose());
  body.n_generalized = rc.n_modal;
  return body;
}

// Tolerances: coupled frequencies 1e-8 relative against the dense reference (the task's
// requirement; each fixed-interface solve converges to 1e-10 and the rest is round-off); the
// rigid mass matrix 1e-10 of its largest entry (the same sums in another order). The old
// elimination path (spider_system, then plain Craig-Bampton on S^T K S) agrees to 1e-6 only:
// its pivots carry the averaging weights' inverse (about the set size), which multiplies the
// condition number of S^T K S (observed: 5e-9 and 2e-8 from the reference, the constrained
// path 2e-10 and 7e-11; with more modes its pairs of equal frequencies, which the axisymmetric
// plate has, split by up to 5e-8 while the constrained path keeps them equal to 1e-13).
void expect_same_reduction(const std::string& inner_kind, const std::string& outer_kind,
                           int modes) {
  SCOPED_TRACE(inner_kind + " / " + outer_kind);
  const model::Model m = analyses::parse_model(
      spider_rotor(two_spider_plate(inner_kind, outer_kind, modes)), "c.toml");
  const model::Solid& solid = m.solids[0];
  const assembly::SolidComponent built = assembly::build_solid(m, solid);
  const int n_modes = solid.coupling_modes;

  const assembly::CoupledSolid kept = assembly::couple_solid(m, solid, built);
  const assembly::SpiderSystem ss = assembly::spider_system(m, solid, built);
  std::printf("%s/%s: %ld solid DOFs, nnz(K) %ld, eliminated S^T K S %ld\n", inner_kind.c_str(),
              outer_kind.c_str(), static_cast<long>(ss.system.K.rows()),
              static_cast<long>(ss.system.K.nonZeros()), static_cast<long>(ss.K.nonZeros()));
  const reduce::ReducedComponent one_more = dense_reference(ss, n_modes + 1);
  const reduce::ReducedComponent reference = reduce::truncate(one_more, n_modes);
  // The kept modes must end at a gap: a cut through a pair of equal frequencies keeps an
  // arbitrary combination of the pair, and two solvers may keep different ones (a real
  // non-uniqueness of the truncated reduction, not an error of either).
  const Eigen::VectorXd& hz = one_more.fixed_interface_hz;
  ASSERT_GT(hz[n_modes], (1.0 + 1e-6) * hz[n_modes - 1]) << "fixed-interface: " << hz.transpose();
  reduce::CraigBamptonOptions o;
  o.n_modes = n_modes;
  const reduce::ReducedComponent old = reduce::craig_bampton(ss.K, ss.M, ss.dofs, ss.masters, o);

  ASSERT_EQ(kept.reduced.size(), reference.size());
  for (int k = 0; k < n_modes; ++k)
    EXPECT_NEAR(kept.reduced.fixed_interface_hz[k], reference.fixed_interface_hz[k],
                1e-8 * reference.fixed_interface_hz[k])
        << "fixed-interface mode " << k + 1;
  const double j_scale = ss.rigid_mass.cwiseAbs().maxCoeff();
  EXPECT_LE((kept.rigid_mass - ss.rigid_mass).cwiseAbs().maxCoeff(), 1e-10 * j_scale);

  const Eigen::VectorXd a = coupled_frequencies(m, kept.body, 30);
  const Eigen::VectorXd b = coupled_frequencies(m, body_of(kept.body, reference), 30);
  const Eigen::VectorXd c = coupled_frequencies(m, body_of(kept.body, old), 30);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(c.size(), b.size());
  double worst = 0.0, worst_old = 0.0;
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    EXPECT_NEAR(a[k], b[k], 1e-8 * b[k]) << "coupled mode " << k + 1;
    EXPECT_NEAR(c[k], b[k], 1e-6 * b[k]) << "coupled mode " << k + 1 << " (elimination path)";
    worst = std::max(worst, std::abs(a[k] - b[k]) / b[k]);
    worst_old = std::max(worst_old, std::abs(c[k] - b[k]) / b[k]);
  }
  std::printf(
      "coupled: %ld modes up to %.6g Hz; largest relative difference from the dense "
      "reference %.2e (constrained), %.2e (elimination)\n",
      static_cast<long>(a.size()), b.maxCoeff(), worst, worst_old);
}

TEST(ConstrainedCoupling, AveragingSpidersAndSensorEqualTheEliminatedReduction) {
  expect_same_reduction("averaging", "averaging", 17);
}

TEST(ConstrainedCoupling, RigidAndAveragingSpidersEqualTheEliminatedReduction) {
  expect_same_reduction("rigid", "averaging", 16);
}

}  // namespace
}  // namespace geardyn
