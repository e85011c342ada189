// Benchmarks of the linear rotor analyses on banded rotor models of growing size.
// Figures and growth exponents are recorded in docs/performance.md.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/stability_check.hpp"
#include "geardyn/analyses/unbalance.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace {

using namespace geardyn;

// A 1.5 m steel shaft refined into n_elements Timoshenko elements (the same rotor at every size,
// so only the discretisation grows), a disk every tenth of its length, isotropic bearings at both
// ends and at mid-span, light Rayleigh damping, one unbalance and two sensors.
model::Model rotor(int n_elements) {
  model::Model m;
  m.title = "benchmark rotor";
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
    k[14] = 1e8;  // axial
    k[35] = 1e5;  // torsional, keeps the rotor from spinning freely in the model
    c[0] = c[7] = 1e3;
    b.stiffness = {k};
    b.damping = {c};
    m.bearings.push_back(b);
  }
  m.damping.rayleigh_beta = 1e-5;
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

void BM_Assemble(benchmark::State& state) {
  const auto m = rotor(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(assembly::build_system(m));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_Assemble)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity();

void BM_Modal(benchmark::State& state) {
  const auto m = rotor(static_cast<int>(state.range(0)));
  const auto system = assembly::build_system(m);
  analyses::ModalSettings settings;
  settings.n_modes = 10;
  settings.speed = units::rpm_to_rad_per_s(3000.0);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        analyses::run_modal(m, settings, analyses::Context("modal").with_system(&system)));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_Modal)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->Complexity();

void BM_Campbell100(benchmark::State& state) {
  const auto m = rotor(static_cast<int>(state.range(0)));
  const auto system = assembly::build_system(m);
  analyses::CampbellSettings settings;
  settings.n_modes = 6;
  for (int i = 0; i < 100; ++i) settings.speeds.push_back(units::rpm_to_rad_per_s(i * 100.0));
  analyses::CampbellResult result;
  for (auto _ : state)
    result =
        analyses::run_campbell(m, settings, analyses::Context("campbell").with_system(&system));
  // The projection basis at the end and the speeds it could not certify (solved in full).
  state.counters["basis"] = result.projection_basis;
  state.counters["fallbacks"] = result.projection_fallbacks;
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_Campbell100)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity()
    ->Iterations(1);

// The same sweep on the full solver (the reference path, method sparse: shift-invert Arnoldi
// per speed), for the projection's speed-up in one binary (issue 19).
void BM_Campbell100Full(benchmark::State& state) {
  const auto m = rotor(static_cast<int>(state.range(0)));
  const auto system = assembly::build_system(m);
  analyses::CampbellSettings settings;
  settings.n_modes = 6;
  settings.method = analyses::EigenMethod::Sparse;
  for (int i = 0; i < 100; ++i) settings.speeds.push_back(units::rpm_to_rad_per_s(i * 100.0));
  for (auto _ : state)
    benchmark::DoNotOptimize(
        analyses::run_campbell(m, settings, analyses::Context("campbell").with_system(&system)));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_Campbell100Full)
    ->Arg(100)
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity()
    ->Iterations(1);

// The bound of the Campbell sweep (docs/performance.md, "Campbell (issue #19)"): the work no
// projection method can skip -- the undamped modes of the basis (one factorisation and the
// Lanczos solves), and per speed one check of every returned mode at full size (M, K, D applied
// to the 2 x 13 real and imaginary parts of the modes and one block solve with the factor).
void BM_Campbell100Bound(benchmark::State& state) {
  const auto m = rotor(static_cast<int>(state.range(0)));
  const auto system = assembly::build_system(m);
  for (auto _ : state) {
    eig::SymmetricEigenOptions so;
    so.n_modes = 15;
    const auto modes = eig::solve_symmetric(system.K, system.M, so);
    linalg::SymmetricFactorization f;
    const double sigma = eig::automatic_shift(system.K, system.M);
    f.compute(Eigen::SparseMatrix<double>(system.K - sigma * system.M));
    const Eigen::MatrixXd X = Eigen::MatrixXd::Ones(system.size(), 26);
    for (int i = 0; i < 100; ++i) {
      const double speed = units::rpm_to_rad_per_s(i * 100.0);
      Eigen::MatrixXd R = system.M * X + system.K * X + speed * (system.G * X);
      benchmark::DoNotOptimize(f.solve(R));
    }
    benchmark::DoNotOptimize(modes);
  }
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_Campbell100Bound)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity()
    ->Iterations(1);

void BM_Frf10k(benchmark::State& state) {
  const auto m = rotor(static_cast<int>(state.range(0)));
  const auto system = assembly::build_system(m);
  analyses::HarmonicSettings settings;
  settings.f_min = units::hz_to_rad_per_s(1.0);
  settings.f_max = units::hz_to_rad_per_s(2000.0);
  settings.n_points = 10000;
  settings.adaptive = false;
  settings.input_node = "s." + std::to_string(state.range(0) / 4);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        analyses::run_harmonic(m, settings, analyses::Context("harmonic").with_system(&system)));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_Frf10k)
    ->Arg(100)
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity()
    ->Iterations(1);

void BM_Unbalance1k(benchmark::State& state) {
  const auto m = rotor(static_cast<int>(state.range(0)));
  const auto system = assembly::build_system(m);
  analyses::UnbalanceSettings settings;
  for (int i = 1; i <= 1000; ++i) settings.speeds.push_back(units::rpm_to_rad_per_s(i * 10.0));
  for (auto _ : state)
    benchmark::DoNotOptimize(
        analyses::run_unbalance(m, settings, analyses::Context("unbalance").with_system(&system)));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_Unbalance1k)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity()
    ->Iterations(1);

// The unbalance sweep's direct solves alone (what run_unbalance does besides the stability
// scan): 1000 speeds, one factorisation of D(W; W) and one solve each, on the factor path
// range(1) (0: automatic = banded for this rotor, 2: UMFPACK, today's sparse path). With the
// banded path this is the bound of docs/performance.md: the unavoidable work of the method.
// As in run_unbalance, only the blocks of D the (lateral) load reaches are factorised.
void BM_UnbalanceSolves(benchmark::State& state) {
  const auto m = rotor(static_cast<int>(state.range(0)));
  const auto system = assembly::build_system(m);
  const auto path = static_cast<analyses::FactorPath>(state.range(1));
  const Eigen::MatrixXcd F = fe::unbalance_load(m, system, 1.0, 1.0);
  Eigen::MatrixXcd X;
  for (auto _ : state) {
    analyses::DynamicStiffness D(system, 1.0, "unbalance", path);
    D.restrict_to(F);
    for (int i = 1; i <= 1000; ++i) {
      const double speed = units::rpm_to_rad_per_s(i * 10.0);
      D.set_speed(speed);
      D.factorize(speed);
      D.solve(F, X);
      benchmark::DoNotOptimize(X.data());
    }
    // The blocks of D, the factorised ones and the widest band among them.
    int factorised = 0, factorised_size = 0, kl = 0, ku = 0;
    for (const auto& b : D.blocks()) {
      if (!b.factorised) continue;
      ++factorised;
      factorised_size += b.size;
      kl = std::max(kl, b.lower_bandwidth);
      ku = std::max(ku, b.upper_bandwidth);
    }
    state.counters["blocks"] = static_cast<double>(D.blocks().size());
    state.counters["factorised"] = factorised;
    state.counters["factorised_dofs"] = factorised_size;
    state.counters["kl"] = kl;
    state.counters["ku"] = ku;
  }
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_UnbalanceSolves)
    ->ArgsProduct({{100, 1000, 10000}, {0, 2}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// The eigenvalue stability scan (analyses/stability_check.cpp) without the energy certificate:
// measured apart so that the direct solves and the scan can be reported separately.
void BM_UnbalanceScan(benchmark::State& state) {
  const auto m = rotor(static_cast<int>(state.range(0)));
  const auto system = assembly::build_system(m);
  std::vector<double> speeds;
  for (int i = 1; i <= 1000; ++i) speeds.push_back(units::rpm_to_rad_per_s(i * 10.0));
  for (auto _ : state)
    benchmark::DoNotOptimize(analyses::scan_stability(system, speeds, speeds.back()));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_UnbalanceScan)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// BM_Campbell100 on `threads` worker threads (issue 19; the results are bit-identical for any
// count): wall-clock time and the CPU time of the whole process (all threads).
void BM_Campbell100Threads(benchmark::State& state) {
  const auto m = rotor(static_cast<int>(state.range(0)));
  const auto system = assembly::build_system(m);
  analyses::CampbellSettings settings;
  settings.n_modes = 6;
  settings.threads = static_cast<int>(state.range(1));
  for (int i = 0; i < 100; ++i) settings.speeds.push_back(units::rpm_to_rad_per_s(i * 100.0));
  analyses::CampbellResult r;
  for (auto _ : state)
    r = analyses::run_campbell(m, settings, analyses::Context("campbell").with_system(&system));
  state.counters["operations"] = r.total_operations;
  state.counters["basis"] = r.projection_basis;
  state.counters["threads_used"] = r.threads_used;
}
BENCHMARK(BM_Campbell100Threads)
    ->ArgsProduct({{100, 1000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
