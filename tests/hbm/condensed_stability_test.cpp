// Hill stability of a condensed harmonic balance (hbm/condensed_stability.hpp) against
//  (a) exact exponents: the three-mass chain of condensed_test.cpp with a spring k_t from its
//      last mass to the ground as the "nonlinear" force, every mode kept, no residual. The
//      periodic solution (rest) is that of a linear system, so the Floquet exponents are the
//      eigenvalues mu of its state matrix [0 I; -M^-1 (K + k_t e e^T), -M^-1 C], and the
//      truncated Hill problem with components k = -H..H has exactly mu - i k omega (every family
//      member; Hill's method is exact for a constant Jacobian): the selected representatives
//      are mu (or mu -+ i omega with the mean held), all members with complex shapes.
//      Tolerance 1e-9 absolute on exponents of modulus <= 3 + H omega: rounding of dense
//      eigen-solves of size <= 2 x 3 x 2 x 5;
//  (b) the physical-form Hill method (hbm/stability.hpp, validated against monodromy matrices)
//      on the Duffing oscillator q'' + 0.05 q' + q + 0.1 q^3 = 0.18 cos(Omega t) condensed to its
//      single coordinate (one mode, w = 1, zeta = 0.025: an exact rewriting), along the response
//      curve through both folds: the same verdict at every point (the middle branch unstable
//      by a fold) and the same largest real part. With every mode kept the two are the same
//      Hill matrix in different bases, so the largest real part over all exponents agrees to
//      rounding; the physical method reports it among its selected representatives here
//      (tolerance 1e-9 absolute, exponents of modulus ~ 1).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <complex>
#pragma GCC diagnostic pop

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/hbm/condensed.hpp"
#include "geardyn/hbm/condensed_stability.hpp"
#include "geardyn/hbm/stability.hpp"
#include "hbm/duffing_problem.hpp"

namespace geardyn::hbm {
namespace {

using cd = std::complex<double>;

// Modal receptances of a chain with proportional damping C = beta K (zeta_r = beta w_r / 2),
// every mode, at coordinate `dof`; harmonic 1 excited by `force` on DOF 0.
std::vector<ModalReceptance> receptances(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K,
                                         double beta, int dof, double force, int harmonics) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  const Eigen::VectorXd w = eig.eigenvalues().cwiseSqrt();
  const Eigen::MatrixXd phi = eig.eigenvectors();  // mass-normalised
  std::vector<ModalReceptance> out;
  for (int n = 0; n <= harmonics; ++n) {
    ModalReceptance r;
    r.natural_frequency = w;
    r.damping_ratio = 0.5 * beta * w;
    r.left = phi.row(dof).cast<cd>();
    r.right = r.left;
    if (n == 1) r.modal_excitation = force * phi.row(0).transpose().cast<cd>();
    out.push_back(r);
  }
  return out;
}

// A linear spring k between coordinate `dof` and the ground, as a nonlinear force.
NonlinearForce linear_spring(int dof, double k) {
  return [dof, k](const HarmonicBasis& basis, const Eigen::VectorXd& X, Eigen::VectorXd& F,
                  Eigen::MatrixXd& J) {
    const int s = basis.size();
    F.segment(dof * s, s) += k * X.segment(dof * s, s);
    J.block(dof * s, dof * s, s, s).diagonal().array() += k;
  };
}

// Nearest distance from `value` to an entry of `set`.
double nearest(const Eigen::VectorXcd& set, cd value) {
  double best = 1e300;
  for (Eigen::Index e = 0; e < set.size(); ++e) best = std::min(best, std::abs(set[e] - value));
  return best;
}

TEST(CondensedHillStability, SpringCoupledChainHasTheStateMatrixEigenvalues) {
  Eigen::MatrixXd M = Eigen::Vector3d(1.0, 1.0, 0.5).asDiagonal(), K(3, 3);
  K << 2.0, -1.0, 0.0, -1.0, 3.0, -2.0, 0.0, -2.0, 2.0;
  const double beta = 0.004, kt = 0.8;
  const int H = 2;
  const HarmonicBasis basis(H, 32);
  Eigen::MatrixXd Ks = K;
  Ks(2, 2) += kt;
  Eigen::MatrixXd state = Eigen::MatrixXd::Zero(6, 6);
  state.topRightCorner(3, 3).setIdentity();
  state.bottomLeftCorner(3, 3) = -M.inverse() * Ks;
  state.bottomRightCorner(3, 3) = -M.inverse() * (beta * K);
  const Eigen::VectorXcd mu = Eigen::EigenSolver<Eigen::MatrixXd>(state).eigenvalues();

  // Real modes, the same for every harmonic: one representative per family, the central one.
  const CondensedHarmonicBalance hb(1, basis, receptances(M, K, beta, 2, 0.02, H),
                                    {linear_spring(0, kt)});
  EXPECT_EQ(condensed_hill_size(hb), 2 * H + 1);
  for (double omega : {0.37, 1.3}) {
    const FloquetResult r = condensed_hill_stability(hb, Eigen::VectorXd::Zero(hb.size()), omega);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    ASSERT_EQ(r.exponents.size(), 6);
    for (Eigen::Index j = 0; j < mu.size(); ++j)
      EXPECT_LT(nearest(r.exponents, mu[j]), 1e-9) << "mu " << mu[j] << ", omega " << omega;
    EXPECT_TRUE(r.stable);
    EXPECT_NEAR(r.max_real_part, mu.real().maxCoeff(), 1e-9);
  }

  // Complex shapes on harmonics 1.. (each mode times e^{0.7 i}: the same receptance; the mean
  // keeps real shapes, as a cyclic sector's nodal diameter 0 does): no families are assumed,
  // every component's exponents are returned, mu - i k omega for every k.
  std::vector<ModalReceptance> rotated = receptances(M, K, beta, 2, 0.02, H);
  for (std::size_t n = 1; n < rotated.size(); ++n) {
    rotated[n].left *= std::polar(1.0, 0.7);
    rotated[n].right = rotated[n].left;
  }
  const CondensedHarmonicBalance hc(1, basis, rotated, {linear_spring(0, kt)});
  const double omega = 0.37;
  const FloquetResult rc = condensed_hill_stability(hc, Eigen::VectorXd::Zero(hc.size()), omega);
  ASSERT_EQ(rc.status, Status::Ok) << rc.message;
  ASSERT_EQ(rc.exponents.size(), 6 * (2 * H + 1));
  for (int k = -H; k <= H; ++k)
    for (Eigen::Index j = 0; j < mu.size(); ++j)
      EXPECT_LT(nearest(rc.exponents, mu[j] - cd(0.0, k * omega)), 1e-9)
          << "mu " << mu[j] << ", k " << k;
  EXPECT_NEAR(rc.max_real_part, mu.real().maxCoeff(), 1e-9);

  // The mean held at zero (harmonic 0 without receptance): the representatives are the
  // members of components +-1, mu -+ i omega.
  std::vector<ModalReceptance> held = receptances(M, K, beta, 2, 0.02, H);
  held[0] = ModalReceptance{};
  held[0].left.resize(1, 0);
  held[0].right.resize(1, 0);
  const CondensedHarmonicBalance hb0(1, basis, held, {linear_spring(0, kt)});
  EXPECT_EQ(condensed_hill_size(hb0), 2 * H);
  const FloquetResult r0 = condensed_hill_stability(hb0, Eigen::VectorXd::Zero(hb0.size()), omega);
  ASSERT_EQ(r0.exponents.size(), 6);
  for (Eigen::Index j = 0; j < mu.size(); ++j)
    EXPECT_LT(std::min(nearest(r0.exponents, mu[j] - cd(0.0, omega)),
                       nearest(r0.exponents, mu[j] + cd(0.0, omega))),
              1e-9)
        << "mu " << mu[j];
  EXPECT_NEAR(r0.max_real_part, mu.real().maxCoeff(), 1e-9);

  EXPECT_THROW(condensed_hill_stability(hb, Eigen::VectorXd::Zero(3), omega), InputError);
  EXPECT_THROW(condensed_hill_stability(hb, Eigen::VectorXd::Zero(hb.size()), 0.0), InputError);
}

// (c) A friction element: the chain with its Jenkins element (k_t = 0.8, slip force 0.01) from
// stick through gross slip at resonance, condensed with every mode (an exact rewriting): the
// physical-form exponents (largest real part to 1e-9, the same verdict) at every point.
TEST(CondensedHillStability, JenkinsChainAgreesWithThePhysicalForm) {
  Eigen::MatrixXd M = Eigen::Vector3d(1.0, 1.0, 0.5).asDiagonal(), K(3, 3);
  K << 2.0, -1.0, 0.0, -1.0, 3.0, -2.0, 0.0, -2.0, 2.0;
  const double beta = 0.004;
  const int H = 3;
  const HarmonicBasis basis(H, 64);
  const JenkinsElement element{0.8, 0.01};
  const Eigen::VectorXd F =
      0.02 * Eigen::VectorXd::Unit(3 * basis.size(), HarmonicBasis::cos_index(1));
  const HarmonicBalance physical(M, beta * K, K, basis, {jenkins_force(2, -1, element)}, F);
  const CondensedHarmonicBalance condensed(1, basis, receptances(M, K, beta, 2, 0.02, H),
                                           {jenkins_force(0, -1, element)});
  ContinuationOptions o;
  o.omega_start = 0.3;
  o.omega_end = 0.9;
  o.step = 0.01;
  o.max_step = 0.02;
  o.tolerance = 1e-12;
  o.x_scale = 1.0;
  o.omega_scale = 0.6;
  const ContinuationResult curve =
      continue_in_frequency(physical, Eigen::VectorXd::Zero(physical.size()), o);
  ASSERT_EQ(curve.status, Status::Ok) << curve.message;
  double largest_slip = 0.0;
  for (const ContinuationPoint& p : curve.points) {
    Eigen::MatrixXd J;
    physical.residual(p.X, p.omega, &J);
    const FloquetResult ref = hill_stability(J, M, beta * K, H, p.omega);
    const Eigen::VectorXd Xc = p.X.segment(2 * basis.size(), basis.size());
    ASSERT_LT(condensed.residual(Xc, p.omega).norm(), 1e-10) << "omega " << p.omega;
    const FloquetResult r = condensed_hill_stability(condensed, Xc, p.omega);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    EXPECT_NEAR(r.max_real_part, ref.max_real_part, 1e-9) << "omega " << p.omega;
    EXPECT_EQ(r.stable, ref.stable) << "omega " << p.omega;
    largest_slip = std::max(largest_slip, Xc.norm());
  }
  EXPECT_GT(largest_slip, 5.0 * element.slip_force / element.stiffness);  // into gross slip
}

void check_duffing(int harmonics) {
  using namespace testing;
  const HarmonicBalance physical = duffing_system(harmonics);
  std::vector<ModalReceptance> rec;
  for (int n = 0; n <= harmonics; ++n) {
    ModalReceptance r;
    r.natural_frequency = Eigen::VectorXd::Constant(1, std::sqrt(kStiffness / kMass));
    r.damping_ratio =
        Eigen::VectorXd::Constant(1, kDamping / (2.0 * std::sqrt(kStiffness * kMass)));
    r.left = Eigen::MatrixXcd::Constant(1, 1, 1.0 / std::sqrt(kMass));
    r.right = r.left;
    if (n == 1) r.modal_excitation = Eigen::VectorXcd::Constant(1, kForce / std::sqrt(kMass));
    rec.push_back(r);
  }
  const CondensedHarmonicBalance condensed(1, physical.basis(), rec, {cubic_spring(0, kCubic)});
  const ContinuationResult curve = duffing_continuation(physical);
  ASSERT_EQ(curve.status, Status::Ok) << curve.message;
  const auto [upper_fold, lower_fold] = fold_points(curve);
  ASSERT_GT(lower_fold, upper_fold);
  const Eigen::MatrixXd Mm = Eigen::MatrixXd::Constant(1, 1, kMass);
  const Eigen::MatrixXd Cm = Eigen::MatrixXd::Constant(1, 1, kDamping);
  int unstable = 0;
  for (int i = 0; i < static_cast<int>(curve.points.size()); ++i) {
    const ContinuationPoint& p = curve.points[static_cast<std::size_t>(i)];
    // The same solution solves the condensed balance (an exact rewriting).
    ASSERT_LT(condensed.residual(p.X, p.omega).norm(), 1e-10) << "omega " << p.omega;
    Eigen::MatrixXd J;
    physical.residual(p.X, p.omega, &J);
    const FloquetResult ref = hill_stability(J, Mm, Cm, harmonics, p.omega);
    const FloquetResult r = condensed_hill_stability(condensed, p.X, p.omega);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    EXPECT_NEAR(r.max_real_part, ref.max_real_part, 1e-9) << "omega " << p.omega;
    if (i == upper_fold || i == lower_fold) continue;
    EXPECT_EQ(r.stable, ref.stable) << "omega " << p.omega;
    EXPECT_EQ(r.kind, ref.kind) << "omega " << p.omega;
    unstable += r.stable ? 0 : 1;
  }
  EXPECT_GT(unstable, 10);  // the middle branch
}

TEST(CondensedHillStability, DuffingSingleHarmonicAgreesWithThePhysicalForm) { check_duffing(1); }
TEST(CondensedHillStability, DuffingThreeHarmonicsAgreesWithThePhysicalForm) { check_duffing(3); }

}  // namespace
}  // namespace geardyn::hbm
