// The factor paths of DynamicStiffness (banded LU after RCM vs UMFPACK) and the threaded
// sweeps of the unbalance and harmonic analyses (issue #19): the new paths must reproduce the
// sparse LU's solution, and any thread count must give bit-identical results.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/analyses/unbalance.hpp"
#include "geardyn/assembly/system_builder.hpp"

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
