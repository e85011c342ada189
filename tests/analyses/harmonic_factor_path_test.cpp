// The factor paths of DynamicStiffness (banded LU after RCM vs UMFPACK) and the threaded
// sweeps of the unbalance and harmonic analyses (issue #19): the new paths must reproduce the
// sparse LU's solution, and any thread count must give bit-identical results.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/analyses/unbalance.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"

namespace geardyn::analyses {
namespace {

// A 1.5 m, 50 mm steel shaft in `n_elements` Timoshenko elements, three isotropic damped
// bearings, nine disks, Rayleigh damping (bench/rotor_bench.cpp's rotor, smaller), so D has
// stiffness, mass, damping and gyroscopic terms and the shaft line's banded pattern.
// `modal`: modal damping instead of Rayleigh (the Woodbury path of DynamicStiffness).
model::Model rotor(int n_elements, bool modal = false) {
  model::Model m;
  model::Material steel;
  steel.name = "steel";
  steel.youngs_modulus = 211e9;
  steel.shear_modulus = 81.2e9;
  steel.density = 7810;
  m.materials.push_back(steel);
  model::Shaft s;
  s.name = "s";
  s.material = "steel";
  model::ShaftElement e;
  e.length = 1.5;
  e.outer_diameter = 0.05;
  e.divisions = n_elements;
  s.elements.push_back(e);
  m.shafts.push_back(s);
  for (int k = 1; k < 10; ++k) {
    model::Disk d;
    d.name = "d" + std::to_string(k);
    d.node = "s." + std::to_string(k * n_elements / 10);
    d.mass = 10;
    d.polar_inertia = 0.1;
    d.diametral_inertia = 0.05;
    m.disks.push_back(d);
  }
  for (int station : {0, n_elements / 2, n_elements}) {
    model::Bearing b;
    b.name = "b" + std::to_string(station);
    b.node = "s." + std::to_string(station);
    model::Bearing::Matrix6 k{}, c{};
    k[0] = k[7] = 1e7;
    k[14] = 1e8;
    k[35] = 1e5;
    c[0] = c[7] = 1e3;
    b.stiffness = {k};
    b.damping = {c};
    m.bearings.push_back(b);
  }
  if (modal) {
    m.damping.modal_ratio = 0.02;
    m.damping.modal_modes = 12;
  } else {
    m.damping.rayleigh_beta = 1e-5;
  }
  model::Unbalance u;
  u.name = "u";
  u.node = "s." + std::to_string(n_elements / 4);
  u.mass_eccentricity = 1e-4;
  m.unbalances.push_back(u);
  for (int station : {n_elements / 4, n_elements / 3}) {
    model::Sensor sensor;
    sensor.name = "x" + std::to_string(station);
    sensor.node = "s." + std::to_string(station);
    sensor.dof = model::Component::Ux;
    m.sensors.push_back(sensor);
  }
  return m;
}

// Largest |x_banded - x_sparse| / max |x_sparse| over frequencies from 1 Hz to 2 kHz (through
// the rotor's first resonances) at 3000 rpm.
double banded_vs_sparse(const fe::LinearSystem& system, FactorPath& automatic) {
  const double speed = 3000.0 * 2.0 * M_PI / 60.0;
  DynamicStiffness banded(system, speed, "t", FactorPath::Banded);
  DynamicStiffness sparse(system, speed, "t", FactorPath::Sparse);
  DynamicStiffness chosen(system, speed, "t");
  Eigen::MatrixXcd F = Eigen::MatrixXcd::Zero(system.size(), 2);
  F(system.size() / 4, 0) = 1.0;
  F(system.size() / 3, 1) = std::complex<double>(0.0, 1.0);
  double worst = 0.0;
  for (double hz : {1.0, 17.0, 55.5, 120.0, 333.0, 801.0, 2000.0}) {
    const double w = 2.0 * M_PI * hz;
    banded.factorize(w);
    sparse.factorize(w);
    const Eigen::MatrixXcd xb = banded.solve(F), xs = sparse.solve(F);
    worst = std::max(worst, (xb - xs).cwiseAbs().maxCoeff() / xs.cwiseAbs().maxCoeff());
  }
  chosen.factorize(1.0);
  automatic = chosen.factor_path();
  return worst;
}

TEST(DynamicStiffnessFactorPath, BandedLuReproducesUmfpackOnAShaftLine) {
  // Both are LU factorisations with partial pivoting, backward stable; the solutions differ by
  // the condition number times round-off. Rayleigh and bearing damping keep D well conditioned
  // (cond ~1e6 at most across the range), so 1e-10 leaves a margin of about a hundred.
  const auto system = assembly::build_system(rotor(60));
  FactorPath automatic = FactorPath::Automatic;
  EXPECT_LT(banded_vs_sparse(system, automatic), 1e-10);
  // A shaft line's band is narrow: the automatic choice is the banded LU.
  EXPECT_EQ(automatic, FactorPath::Banded);
}

TEST(DynamicStiffnessFactorPath, BandedLuReproducesUmfpackWithModalDamping) {
  // Same comparison through the Woodbury path (modal damping kept out of the sparse factor);
  // the iterative refinement drives both to a backward error of ~1e-14, so 1e-10 again.
  const auto system = assembly::build_system(rotor(40, true));
  ASSERT_TRUE(system.has_modal_damping());
  FactorPath automatic = FactorPath::Automatic;
  EXPECT_LT(banded_vs_sparse(system, automatic), 1e-10);
}

// D(w) = K(W) - w^2 M + i w (C(W) + W G) + i K_loss as a dense matrix, whole (no blocks): the
// reference for the block solves. Out of line: GCC 12's -Wnull-dereference misfires on Eigen's
// sparse-to-dense conversion when it is inlined into a test body.
[[gnu::noinline]] Eigen::MatrixXcd dense_solve(const fe::LinearSystem& system, double w, double W,
                                               const Eigen::MatrixXcd& F) {
  const Eigen::MatrixXd K = Eigen::MatrixXd(system.K_at(W));
  const Eigen::MatrixXd C = Eigen::MatrixXd(system.C_at(W));
  const Eigen::MatrixXd M = Eigen::MatrixXd(system.M);
  const Eigen::MatrixXd G = Eigen::MatrixXd(system.G);
  const Eigen::MatrixXd L = Eigen::MatrixXd(system.K_loss);
  const std::complex<double> iw(0.0, w);
  const Eigen::MatrixXcd D = (K - w * w * M).cast<std::complex<double>>() +
                             iw * (C + W * G).cast<std::complex<double>>() +
                             std::complex<double>(0.0, 1.0) * L.cast<std::complex<double>>();
  return D.partialPivLu().solve(F);
}

int equation(const fe::LinearSystem& system, const std::string& node, model::Component c) {
  return system.dofs.dof(system.dofs.node_index(node), c);
}

// Unit loads on a lateral, an axial and a torsional DOF (one column each).
Eigen::MatrixXcd three_loads(const fe::LinearSystem& system) {
  Eigen::MatrixXcd F = Eigen::MatrixXcd::Zero(system.size(), 3);
  F(equation(system, "s.15", model::Component::Ux), 0) = 1.0;
  F(equation(system, "s.20", model::Component::Uz), 1) = 1.0;
  F(equation(system, "s.25", model::Component::Rz), 2) = 1.0;
  return F;
}

// Largest |x - x_dense| / max |x_dense| per column over frequencies through the first
// resonances, for `path`.
double block_error(const fe::LinearSystem& system, double speed, FactorPath path) {
  DynamicStiffness D(system, speed, "t", path);
  const Eigen::MatrixXcd F = three_loads(system);
  double worst = 0.0;
  for (double hz : {0.0, 17.0, 120.0, 801.0}) {
    const double w = 2.0 * M_PI * hz;
    D.factorize(w);
    const Eigen::MatrixXcd X = D.solve(F), X_ref = dense_solve(system, w, speed, F);
    for (Eigen::Index j = 0; j < F.cols(); ++j)
      worst = std::max(worst, (X.col(j) - X_ref.col(j)).cwiseAbs().maxCoeff() /
                                  X_ref.col(j).cwiseAbs().maxCoeff());
  }
  return worst;
}

TEST(DynamicStiffnessBlocks, ShaftLineSplitsIntoLateralAxialTorsional) {
  // A straight shaft on isotropic bearings: lateral (ux, uy, rx, ry; the gyroscopic terms join
  // the two planes), axial (uz) and torsional (rz) motions are uncoupled, so D has 3 blocks of
  // 4, 1 and 1 DOFs per node, each with its own band (RCM on a chain: kl = 2 x 4 - 1 at most
  // for the lateral block, 1 for the axial and torsional chains).
  const auto system = assembly::build_system(rotor(60));
  const double speed = 3000.0 * 2.0 * M_PI / 60.0;
  DynamicStiffness D(system, speed, "t", FactorPath::Banded);
  D.factorize(100.0);
  const auto blocks = D.blocks();
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_EQ(blocks[0].size, 4 * 61);
  EXPECT_LE(blocks[0].lower_bandwidth, 7);
  for (std::size_t k = 1; k < 3; ++k) {
    EXPECT_EQ(blocks[k].size, 61);
    EXPECT_EQ(blocks[k].lower_bandwidth, 1);
    EXPECT_EQ(blocks[k].upper_bandwidth, 1);
  }
  // Against the dense LU of the whole D (no blocks): both are backward-stable LUs with
  // partial pivoting, differing by cond(D) x eps; the Rayleigh and bearing damping keep
  // cond(D) around 1e4 at these frequencies (801 Hz lies near a lateral mode), i.e. ~2e-12
  // measured, so 1e-11.
  EXPECT_LT(block_error(system, speed, FactorPath::Banded), 1e-11);
  EXPECT_LT(block_error(system, speed, FactorPath::Sparse), 1e-11);
  EXPECT_LT(block_error(system, speed, FactorPath::Automatic), 1e-11);
}

TEST(DynamicStiffnessBlocks, CrossCoupledSpeedDependentBearingJoinsBlocks) {
  // A bearing whose table couples ux and uz (k_xz = k_zx) at 1000 rad/s only: the pattern holds
  // every entry the bearing takes at any speed, so the lateral and axial blocks are one at
  // every speed, including W = 0 where the coupling is zero (a split made there would be wrong
  // at 1000 rad/s and would change the ordering with the speed the sweep starts at).
  model::Model m = rotor(60);
  model::Bearing& b = m.bearings[1];
  model::Bearing::Matrix6 coupled = b.stiffness[0];
  coupled[2] = coupled[12] = 5e6;
  b.speeds = {0.0, 1000.0};
  b.stiffness = {b.stiffness[0], coupled};
  b.damping = {b.damping[0], b.damping[0]};
  const auto system = assembly::build_system(m);
  ASSERT_FALSE(system.speed_bearings.empty());
  for (double speed : {0.0, 700.0}) {
    DynamicStiffness D(system, speed, "t");
    D.factorize(50.0);
    const auto blocks = D.blocks();
    ASSERT_EQ(blocks.size(), 2u);  // lateral + axial, torsional
    EXPECT_EQ(blocks[0].size, 5 * 61);
  }
  // The coupled solve at 700 rad/s (k_xz = 3.5e6) against the dense LU: 1e-11 as above.
  EXPECT_LT(block_error(system, 700.0, FactorPath::Automatic), 1e-11);
  EXPECT_LT(block_error(system, 700.0, FactorPath::Sparse), 1e-11);
  // One object moved from W = 0 to 700 rad/s gives bit for bit what one built at 700 gives.
  DynamicStiffness moved(system, 0.0, "t"), built(system, 700.0, "t");
  moved.factorize(50.0);
  moved.set_speed(700.0);
  moved.factorize(120.0);
  built.factorize(120.0);
  const Eigen::MatrixXcd F = three_loads(system);
  EXPECT_EQ((moved.solve(F) - built.solve(F)).cwiseAbs().maxCoeff(), 0.0);
}

TEST(DynamicStiffnessBlocks, UnloadedBlocksAreSkippedAndRespondWithZero) {
  const auto system = assembly::build_system(rotor(60));
  const double speed = 3000.0 * 2.0 * M_PI / 60.0;
  Eigen::MatrixXcd F = Eigen::MatrixXcd::Zero(system.size(), 1);
  F(equation(system, "s.15", model::Component::Ux), 0) = 1.0;
  F(equation(system, "s.15", model::Component::Uy), 0) = std::complex<double>(0.0, -1.0);
  DynamicStiffness all(system, speed, "t"), lateral(system, speed, "t");
  lateral.restrict_to(F);
  all.factorize(300.0);
  lateral.factorize(300.0);
  const auto blocks = lateral.blocks();
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_TRUE(blocks[0].factorised);
  EXPECT_FALSE(blocks[1].factorised);
  EXPECT_FALSE(blocks[2].factorised);
  const Eigen::MatrixXcd X = lateral.solve(F), X_all = all.solve(F);
  // The lateral block is factorised from the same values either way: bit-identical; the
  // skipped blocks are exactly 0 (the full solve's zero right-hand side there gives 0 too).
  EXPECT_EQ((X - X_all).cwiseAbs().maxCoeff(), 0.0);
  for (int node : {0, 20, 60}) {
    const std::string name = "s." + std::to_string(node);
    EXPECT_EQ(X(equation(system, name, model::Component::Uz), 0), 0.0);
    EXPECT_EQ(X(equation(system, name, model::Component::Rz), 0), 0.0);
  }
  // The residual uses the whole D (skipped blocks assembled on the fly): round-off of |D||X|.
  const Eigen::MatrixXcd R = lateral.apply(X) - F;
  EXPECT_LT(R.cwiseAbs().maxCoeff(), 1e-12 * (1.0 + all.apply(X).cwiseAbs().maxCoeff()));
  EXPECT_EQ((lateral.apply(X) - all.apply(X)).cwiseAbs().maxCoeff(), 0.0);
  // The pivot ratio is over the factorised block only, so it is at least the whole one.
  EXPECT_GE(lateral.reciprocal_pivot_ratio(), all.reciprocal_pivot_ratio());
  // A load on a skipped block is refused rather than answered with a wrong 0.
  EXPECT_THROW(lateral.solve(three_loads(system)), std::invalid_argument);
  lateral.unrestrict();
  lateral.factorize(300.0);
  EXPECT_EQ((lateral.solve(F) - X_all).cwiseAbs().maxCoeff(), 0.0);
}

TEST(DynamicStiffnessBlocks, SingularUnloadedBlockDoesNotFailTheSolve) {
  // Without axial and torsional bearing springs the rotor is free to translate along and spin
  // about its axis: D(0) is singular on those blocks. A lateral load does not reach them, so
  // the restricted solve succeeds (their response 0 is D's consistent solution there) and
  // equals the static deflection on the bearings; the unrestricted factor reports the rigid
  // body motion as before.
  model::Model m = rotor(40);
  for (model::Bearing& b : m.bearings) b.stiffness[0][14] = b.stiffness[0][35] = 0.0;
  const auto system = assembly::build_system(m);
  Eigen::MatrixXcd F = Eigen::MatrixXcd::Zero(system.size(), 1);
  F(equation(system, "s.10", model::Component::Ux), 0) = 1.0;
  DynamicStiffness whole(system, 0.0, "t"), lateral(system, 0.0, "t");
  lateral.restrict_to(F);
  EXPECT_THROW(whole.factorize(0.0), NumericalError);
  lateral.factorize(0.0);
  const Eigen::MatrixXcd X = lateral.solve(F);
  // Static lateral deflection: K_lat x = F, checked by the residual of the lateral rows
  // (round-off of |K||x|, 1e-12 relative).
  const Eigen::MatrixXcd R = lateral.apply(X) - F;
  EXPECT_LT(R.cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(X(equation(system, "s.10", model::Component::Uz), 0), 0.0);
}

TEST(UnbalanceThreads, AnyThreadCountGivesBitIdenticalResults) {
  // Each speed is solved independently of the others, so threads change nothing, bit for bit.
  const model::Model m = rotor(50);
  const auto system = assembly::build_system(m);
  UnbalanceSettings settings;
  for (int i = 1; i <= 12; ++i) settings.speeds.push_back(i * 80.0);
  settings.threads = 1;
  const UnbalanceResult one = run_unbalance(m, settings, Context("u").with_system(&system));
  settings.threads = 3;
  const UnbalanceResult three = run_unbalance(m, settings, Context("u").with_system(&system));
  EXPECT_EQ(three.threads_used, 3);
  ASSERT_EQ(one.response.size(), three.response.size());
  for (std::size_t o = 0; o < one.response.size(); ++o)
    EXPECT_EQ((one.response[o] - three.response[o]).cwiseAbs().maxCoeff(), 0.0);
  for (std::size_t i = 0; i < settings.speeds.size(); ++i)
    EXPECT_EQ(one.orbits[0][i][0].orbit.major, three.orbits[0][i][0].orbit.major);
}

TEST(UnbalanceThreads, ScaledUnitLoadMatchesTheLoadAtEachSpeed) {
  // The loop solves for the load at unit speed and scales by W^2; the direct solve with
  // fe::unbalance_load at W must agree to round-off (one rounding of W^2: 1e-14 relative).
  const model::Model m = rotor(30);
  const auto system = assembly::build_system(m);
  UnbalanceSettings settings;
  settings.speeds = {120.0, 333.0};
  const UnbalanceResult r = run_unbalance(m, settings, Context("u").with_system(&system));
  DynamicStiffness D(system, settings.speeds[1], "u", FactorPath::Sparse);
  D.factorize(settings.speeds[1]);
  const Eigen::MatrixXcd X =
      D.solve(Eigen::MatrixXcd(fe::unbalance_load(m, system, settings.speeds[1], 1.0)));
  const int eq = r.sensors[0].equation;
  // Relative to the sparse LU: the factor paths differ by cond x eps (see above), 1e-10.
  EXPECT_LT(std::abs(r.response[0](1, 0) - X(eq, 0)) / std::abs(X(eq, 0)), 1e-10);
}

TEST(HarmonicThreads, AnyThreadCountGivesBitIdenticalFrf) {
  // The adaptive grid adds frequencies in batches; each is solved on its own, so the samples,
  // the grid and the peaks are the same for any number of threads.
  const model::Model m = rotor(40);
  const auto system = assembly::build_system(m);
  HarmonicSettings settings;
  settings.f_min = 2.0 * M_PI * 5.0;
  settings.f_max = 2.0 * M_PI * 400.0;
  settings.n_points = 80;
  settings.input_node = "s.10";
  settings.threads = 1;
  const FrfResult one = run_harmonic(m, settings, Context("h").with_system(&system));
  settings.threads = 2;
  const FrfResult two = run_harmonic(m, settings, Context("h").with_system(&system));
  ASSERT_EQ(one.frequencies.size(), two.frequencies.size());
  EXPECT_EQ((one.frequencies - two.frequencies).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((one.displacement - two.displacement).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(one.peaks.size(), two.peaks.size());
}

}  // namespace
}  // namespace geardyn::analyses
