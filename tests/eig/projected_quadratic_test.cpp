// The projected quadratic eigen-solver (eig/projected_quadratic.hpp) against the full solvers
// (eig/quadratic_eigen.hpp) on the rotor of Friswell, Penny, Garvey & Lees, "Dynamics of
// Rotating Machines", CUP 2010, Example 5.9.1 (tests/support/rotor_models.hpp): the same modes,
// each checked at full size.
#include "geardyn/eig/projected_quadratic.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/assembly/system_pencil.hpp"
#include "geardyn/core/error.hpp"
#include "support/rotor_models.hpp"

namespace geardyn::eig {
namespace {

constexpr double kRadPerRpm = 2.0 * 3.14159265358979323846 / 60.0;

// Largest relative difference between the elastic roots of `a` and `b` (ascending |lambda|;
// repeated eigenvalues may come in either order, so each is compared with the nearest). Roots
// with |lambda| < 1 rad/s are rigid-body roots: each free rigid-body motion is a defective double
// root at 0, which solvers resolve only to about sqrt(eps) times the frequency scale and return
// two, one or none of (the Campbell analysis counts and extends for them): not compared. The
// lowest min(count) elastic roots of both lists are.
double largest_difference(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b, bool magnitudes) {
  auto elastic = [](const Eigen::VectorXcd& v) {
    std::vector<std::complex<double>> out;
    for (Eigen::Index k = 0; k < v.size(); ++k)
      if (std::abs(v[k]) >= 1.0) out.push_back(v[k]);
    return out;
  };
  const auto ea = elastic(a), eb = elastic(b);
  const std::size_t n = std::min(ea.size(), eb.size());
  EXPECT_GE(n + 3, std::max(ea.size(), eb.size()));  // at most the rigid-root count apart
  double worst = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {  // the last may be paired with an uncomputed one
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < n; ++j)
      nearest = std::min(nearest, (magnitudes ? std::abs(std::abs(ea[k]) - std::abs(eb[j]))
                                              : std::abs(ea[k] - eb[j])) /
                                      std::abs(eb[j]));
    worst = std::max(worst, nearest);
  }
  return worst;
}

// Solves at `speeds` with one ProjectedQuadratic (basis kept between speeds) and with
// solve_quadratic(method), and returns the largest eigenvalue difference; checks every
// projected mode's backward error against the reference solver's limit.
// magnitudes: compare |lambda| only. Also checks that the projected roots of an undamped system
// are imaginary (a conservative gyroscopic system has Re lambda = 0) to 1e-10 |lambda|.
double compare(const fe::LinearSystem& system, const std::vector<double>& speeds, Method method,
               int n_modes, bool magnitudes = false) {
  ProjectedQuadratic projected(assembly::pencil_parts(system));
  double worst = 0.0;
  for (double speed : speeds) {
    const QuadraticPencil pencil = assembly::pencil_at(system, speed);
    const assembly::SpeedIncrements inc = assembly::speed_increments(system, speed);
    QuadraticEigenOptions qo;
    qo.n_modes = n_modes;
    const QuadraticEigenResult p = projected.solve(pencil, speed, inc.dK, inc.dC, qo);
    qo.method = method;
    qo.krylov.tolerance = 1e-13;  // the reference as accurate as Arnoldi gets
    const QuadraticEigenResult r = solve_quadratic(pencil, qo);
    EXPECT_EQ(p.status, Status::Ok) << p.message;
    EXPECT_EQ(r.status, Status::Ok) << r.message;
    if (p.eigenvalues.size() != r.eigenvalues.size()) {
      ADD_FAILURE() << "mode counts differ at " << speed;
      return 1.0;
    }
    // Each projected mode is checked at full size: its backward error is below the limit the
    // reference solver is held to (QuadraticEigenOptions::residual_limit).
    EXPECT_LE(p.max_residual(), qo.residual_limit);
    worst = std::max(worst, largest_difference(p.eigenvalues, r.eigenvalues, magnitudes));
    for (Eigen::Index k = 0; magnitudes && k < p.eigenvalues.size(); ++k) {
      if (std::abs(p.eigenvalues[k]) < 1.0) continue;  // rigid-body roots (largest_difference)
      EXPECT_LE(std::abs(p.eigenvalues[k].real()),
                1e-10 * std::max(std::abs(p.eigenvalues[k]), 1.0));
    }
  }
  return worst;
}

TEST(ProjectedQuadratic, MatchesDenseOnFriswellRotor) {
  // 24 Timoshenko elements (150 DOFs), the 12 lowest roots (4 rigid-body roots of the free axial
  // and torsional motion, 8 lateral / torsional modes) at rest, 2000 and 4000 rpm. The dense
  // solver's backward errors are ~1e-15; the projection's accuracy test (rho <= 1e-6) bounds
  // the frequency error by about rho^2 for this Hermitian-like gyroscopic pencil, so 1e-9 leaves
  // a factor 1e3 for the rigid-body roots, whose |lambda| ~ 1e-12 sits at the reference's floor.
  const auto system = assembly::build_system(test::friswell_591(24));
  const double worst =
      compare(system, {0.0, 2000 * kRadPerRpm, 4000 * kRadPerRpm}, Method::Dense, 12);
  EXPECT_LT(worst, 1e-9);
}

TEST(ProjectedQuadratic, MatchesDenseWithDampedBearings) {
  // The same rotor with 1 kN s/m bearing damping: a non-Hermitian pencil, complex modes with
  // damping ratios up to a few percent. Same tolerance argument, the eigenvalue condition number
  // of lightly damped modes being close to 1.
  auto model = test::friswell_591(24);
  for (auto& b : model.bearings) b.damping = {test::diagonal6(1e3, 1e3, 0, 0, 0, 0)};
  const auto system = assembly::build_system(model);
  const double worst = compare(system, {0.0, 3000 * kRadPerRpm}, Method::Dense, 12);  // damped
  EXPECT_LT(worst, 1e-9);
}

TEST(ProjectedQuadratic, MatchesArnoldiOnALargeRotor) {
  // 1002 elements (6 018 DOFs): shift-invert Arnoldi on the full pencil is the reference. The
  // rotor is undamped, so the exact roots are imaginary; Arnoldi's real parts reach 2e-7 |lambda|
  // here (measured), which is its own error, while the projection's stay below 1e-10 |lambda|
  // (checked in compare). So |lambda| is compared, within 1e-7 relative: Arnoldi's frequency
  // error is of the order of its real parts, 2e-7 |lambda| at most; measured 5.7e-8. (Against
  // the dense solver, where it is affordable, the projection agrees to 1e-11: the tests above
  // and docs/performance.md.)
  const auto system = assembly::build_system(test::friswell_591(1002));
  const double worst =
      compare(system, {1000 * kRadPerRpm, 4000 * kRadPerRpm}, Method::Sparse, 10, true);
  EXPECT_LT(worst, 1e-7);
}

// The number of exact zeros among the roots, and checks that each is a motion K leaves at rest.
int deflated_zeros(const fe::LinearSystem& system, const QuadraticEigenResult& r) {
  int zeros = 0;
  for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) {
    if (r.eigenvalues[k] != std::complex<double>(0.0, 0.0)) continue;
    ++zeros;
    const Eigen::VectorXcd x = r.eigenvectors.col(k);
    // K x = 0 row by row to rounding: relative to the largest stiffness times the motion.
    const double scale = system.K.cwiseAbs().toDense().rowwise().sum().maxCoeff();
    EXPECT_LE((system.K * x).cwiseAbs().maxCoeff(), 1e-12 * scale * x.cwiseAbs().maxCoeff());
  }
  return zeros;
}

TEST(ProjectedQuadratic, DeflatesFreeRigidBodyMotionsExactly) {
  // Friswell 5.9.1 has no axial or torsional support: two free rigid-body motions, each a
  // defective double root at 0. The projection deflates them (header comment) and returns four
  // exact zeros, and the elastic roots still match the dense solver (the comparison above, 1e-9).
  const auto system = assembly::build_system(test::friswell_591(24));
  ProjectedQuadratic projected(assembly::pencil_parts(system));
  QuadraticEigenOptions qo;
  qo.n_modes = 12;
  for (double rpm : {0.0, 4000.0}) {
    const double speed = rpm * kRadPerRpm;
    const assembly::SpeedIncrements inc = assembly::speed_increments(system, speed);
    const QuadraticEigenResult r =
        projected.solve(assembly::pencil_at(system, speed), speed, inc.dK, inc.dC, qo);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    EXPECT_EQ(deflated_zeros(system, r), 4) << rpm;
    // Undamped and gyroscopic: the projected pencil is solved in its Hermitian form, whose
    // roots are imaginary by construction (a conservative system neither grows nor decays). At
    // rest the two whirls of each mode are a double root, which inverse iteration cannot
    // separate: there the Schur vectors of the general form are used (real parts ~1e-12).
    for (Eigen::Index k = 0; rpm > 0.0 && k < r.eigenvalues.size(); ++k)
      EXPECT_EQ(r.eigenvalues[k].real(), 0.0) << k;
  }
  // A torsional damper at one bearing: the free torsion is no longer at rest under C (its root
  // is -c / J_total, real), so only the axial motion is deflated.
  auto model = test::friswell_591(24);
  model.bearings[0].damping = {test::diagonal6(0, 0, 0, 0, 0, 1.0)};
  const auto damped = assembly::build_system(model);
  ProjectedQuadratic projected_damped(assembly::pencil_parts(damped));
  const QuadraticEigenResult r =
      projected_damped.solve(assembly::pencil_at(damped, 0.0), 0.0, {}, {}, qo);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_EQ(deflated_zeros(damped, r), 2);
  qo.method = Method::Dense;
  const QuadraticEigenResult ref = solve_quadratic(assembly::pencil_at(damped, 0.0), qo);
  EXPECT_LT(largest_difference(r.eigenvalues, ref.eigenvalues, false), 1e-9);
}

TEST(ProjectedQuadratic, RestoredBasisRepeatsTheSolveBitForBit) {
  // A sweep split into chunks (threads over speeds) starts every chunk from one kept basis: the
  // solve at a speed after restore_basis() must be the same, bit for bit, as the solve of that
  // speed straight after keep_basis(), whatever was solved (and enriched) in between.
  const auto system = assembly::build_system(test::friswell_591(24));
  ProjectedQuadratic projected(assembly::pencil_parts(system));
  QuadraticEigenOptions qo;
  qo.n_modes = 12;
  auto solve = [&](double rpm) {
    const double speed = rpm * kRadPerRpm;
    const assembly::SpeedIncrements inc = assembly::speed_increments(system, speed);
    return projected.solve(assembly::pencil_at(system, speed), speed, inc.dK, inc.dC, qo);
  };
  solve(0.0);
  projected.keep_basis();
  const Eigen::Index kept = projected.basis_size();
  const QuadraticEigenResult first = solve(3000.0);
  solve(8000.0);
  solve(20000.0);  // far above: the gyroscopic terms need more directions
  EXPECT_GT(projected.basis_size(), kept);
  projected.restore_basis();
  EXPECT_EQ(projected.basis_size(), kept);
  const QuadraticEigenResult again = solve(3000.0);
  ASSERT_EQ(first.status, Status::Ok) << first.message;
  ASSERT_EQ(again.eigenvalues.size(), first.eigenvalues.size());
  for (Eigen::Index k = 0; k < first.eigenvalues.size(); ++k)
    EXPECT_EQ(again.eigenvalues[k], first.eigenvalues[k]) << k;  // exact: the same computation
}

TEST(ProjectedQuadratic, InvalidOptionsThrowInputError) {
  const auto system = assembly::build_system(test::friswell_591(6));
  ProjectedQuadraticOptions bad;
  bad.tolerance = 0.0;
  EXPECT_THROW(ProjectedQuadratic(assembly::pencil_parts(system), bad), InputError);
  SpeedPencilParts empty;
  EXPECT_THROW(ProjectedQuadratic{empty}, InputError);
}

}  // namespace
}  // namespace geardyn::eig
