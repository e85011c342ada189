// Benchmarks of the solid components: assembly rate of quadratic solid meshes, the lowest modes
// of a ~3e5-DOF gear sector (real shift-invert Lanczos, and the complex Hermitian solver for one
// nodal diameter of the cyclic wheel), and a Craig-Bampton reduction of a sector onto its
// left/right interfaces. Figures are recorded in docs/performance.md ("Solid components").
//
// The solver cases run one iteration each (they take seconds to minutes); the meshes are
// generated and assembled once, outside the timed region. Times are wall clock (UseRealTime) and
// the CPU column is the whole process (MeasureProcessCPUTime), since CHOLMOD and BLAS may use
// threads.
#include <benchmark/benchmark.h>

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "bench_sector.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"
#include "geardyn/meshgen/gear_sector.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/solid/assembly.hpp"
#include "geardyn/solid/structured_mesh.hpp"

namespace {

using namespace geardyn;

const solid::Material kSteel{"steel", 1, 210e9, 0.3, 7850, {}};

// ---------------------------------------------------------------------------------------------
// (a) Assembly rate: a unit box of n^3 cells, tet10 (6 tets per cell) or hex20.

void BM_AssembleBox(benchmark::State& state) {
  const auto type = state.range(0) == 0 ? solid::ElementType::Tet10 : solid::ElementType::Hex20;
  const int n = static_cast<int>(state.range(1));
  const solid::Mesh mesh =
      solid::box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), n, n, n, type, kSteel);
  solid::AssemblyOptions options;
  options.threads = static_cast<int>(state.range(2));
  int dofs = 0;
  for (auto _ : state) {
    const solid::SolidSystem system = solid::assemble(mesh, options);
    dofs = system.num_dofs();
    benchmark::DoNotOptimize(system.K.nonZeros());
  }
  state.SetLabel(type == solid::ElementType::Tet10 ? "tet10" : "hex20");
  state.counters["dofs"] = dofs;
  state.counters["elements"] = static_cast<double>(mesh.elements.size());
  state.counters["dofs_per_s"] =
      benchmark::Counter(dofs, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["elements_per_s"] = benchmark::Counter(
      static_cast<double>(mesh.elements.size()), benchmark::Counter::kIsIterationInvariantRate);
}
// tet10: n = 11, 16, 23 -> 3.3e4, 9.9e4, 2.9e5 DOFs; hex20: n = 14, 20, 29 -> 3.8e4, 1.1e5,
// 3.2e5 DOFs. The largest of each also on 2 threads.
BENCHMARK(BM_AssembleBox)
    ->Args({0, 11, 1})
    ->Args({0, 16, 1})
    ->Args({0, 23, 1})
    ->Args({0, 23, 2})
    ->Args({1, 14, 1})
    ->Args({1, 20, 1})
    ->Args({1, 29, 1})
    ->Args({1, 29, 2})
    ->ArgNames({"hex20", "n", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime();

// ---------------------------------------------------------------------------------------------

// Mesh sizes [m] (global, tooth): 0 "coarse" (2.7e4 DOFs), 1 "fine" (2.7e5 DOFs, the sector
// of bench/export_matrices.cpp and of the scipy comparison).
struct SectorModel {
  solid::Mesh mesh;
  solid::SolidSystem system;
};

const SectorModel& sector(int size_index) {
  static std::map<int, SectorModel> cache;
  static const std::pair<double, double> kSizes[] = {
      {bench::kCoarseSizes[0], bench::kCoarseSizes[1]},  // 0 coarse
      {bench::kFineSizes[0], bench::kFineSizes[1]},      // 1 fine
  };
  auto it = cache.find(size_index);
  if (it == cache.end()) {
    const auto [global, tooth] = kSizes[size_index];
    SectorModel model;
    model.mesh = meshgen::gear_sector(bench::sector_params(global, tooth));
    model.system = solid::assemble(model.mesh);
    it = cache.emplace(size_index, std::move(model)).first;
  }
  return it->second;
}

void set_sector_counters(benchmark::State& state, const SectorModel& model) {
  state.counters["nodes"] = static_cast<double>(model.mesh.coords.size());
  state.counters["dofs"] = model.system.num_dofs();
}

// ---------------------------------------------------------------------------------------------
// (b) The 30 lowest modes of the sector (6 rigid-body modes + 24 elastic). Second argument: the
// Lanczos block size of the default block engine, 0 for the Spectra engine (single vector).

void BM_SectorModes30(benchmark::State& state) {
  const SectorModel& model = sector(static_cast<int>(state.range(0)));
  eig::SymmetricEigenOptions options;
  options.n_modes = 30;
  options.method = eig::Method::Sparse;
  if (state.range(1) == 0)
    options.engine = eig::KrylovEngine::Spectra;
  else
    options.block_size = static_cast<int>(state.range(1));
  eig::SymmetricEigenResult r;
  for (auto _ : state) r = eig::solve_symmetric(model.system.K, model.system.M, options);
  if (r.status != Status::Ok) state.SkipWithError(r.brief_report().c_str());
  set_sector_counters(state, model);
  state.counters["solves"] = r.operations;
  state.counters["max_residual"] = r.max_residual();
  if (r.eigenvalues.size() == 30) {
    state.counters["f7_hz"] = units::rad_per_s_to_hz(std::sqrt(r.eigenvalues[6]));
    state.counters["f30_hz"] = units::rad_per_s_to_hz(std::sqrt(r.eigenvalues[29]));
  }
}
BENCHMARK(BM_SectorModes30)
    ->ArgsProduct({{0, 1}, {0, 1, 2, 4, 8}})
    ->ArgNames({"size", "block"})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Iterations(1);

// The parts of that solve: the supernodal Cholesky factorisation of K - sigma M (once per solve),
// and one block solve with it for 1, 4 or 16 right-hand sides (the operator application of the
// Lanczos engines). Second argument: right-hand sides, 0 for the factorisation alone.
void BM_SectorShiftedFactorAndSolve(benchmark::State& state) {
  const SectorModel& model = sector(static_cast<int>(state.range(0)));
  const Eigen::SparseMatrix<double> A =
      model.system.K - eig::automatic_shift(model.system.K, model.system.M) * model.system.M;
  const Eigen::Index rhs = state.range(1);
  linalg::SymmetricFactorization factor;
  if (rhs > 0 && factor.compute(A) != Status::Ok) state.SkipWithError(factor.message().c_str());
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), std::max<Eigen::Index>(rhs, 1));
  Eigen::MatrixXd X;
  for (auto _ : state) {
    if (rhs == 0) {
      if (factor.compute(A) != Status::Ok) state.SkipWithError(factor.message().c_str());
    } else {
      X = factor.solve(B);
      benchmark::DoNotOptimize(X.data());
    }
  }
  set_sector_counters(state, model);
  if (rhs > 0) state.counters["rhs"] = static_cast<double>(rhs);
}
BENCHMARK(BM_SectorShiftedFactorAndSolve)
    ->ArgsProduct({{0, 1}, {0, 1, 4, 16}})
    ->ArgNames({"size", "rhs"})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Iterations(1);

// The same sector as one of N = 10 of the full wheel, nodal diameter h = 1 (complex Hermitian
// K_1, M_1 on the sector minus its right interface): 30 lowest modes.
void BM_SectorCyclicModes30(benchmark::State& state) {
  const SectorModel& model = sector(static_cast<int>(state.range(0)));
  cyclic::InterfaceOptions io;
  io.n_sectors = 10;
  const cyclic::CyclicSector cs(model.system.dofs, cyclic::find_interfaces(model.system.dofs, io));
  cyclic::CyclicModesOptions options;
  options.nodal_diameters = {1};
  options.eigen.n_modes = 30;
  options.eigen.method = eig::Method::Sparse;
  cyclic::CyclicModesResult r;
  for (auto _ : state) r = cyclic::solve_cyclic_modes(model.system.K, model.system.M, cs, options);
  if (r.status != Status::Ok) state.SkipWithError(r.brief_report().c_str());
  set_sector_counters(state, model);
  state.counters["reduced_dofs"] = static_cast<double>(cs.num_reduced_dofs());
  if (!r.diameters.empty() && r.diameters[0].frequency_hz.size() > 0) {
    state.counters["f1_hz"] = r.diameters[0].frequency_hz[0];
    state.counters["max_residual"] = r.diameters[0].eigen.residuals.maxCoeff();
  }
}
BENCHMARK(BM_SectorCyclicModes30)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("size")
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Iterations(1);

// ---------------------------------------------------------------------------------------------
// (c) Craig-Bampton: all DOFs of the left and right sector faces as masters, 40 fixed-interface
// modes.

void BM_SectorCraigBampton40(benchmark::State& state) {
  const SectorModel& model = sector(static_cast<int>(state.range(0)));
  const std::vector<int> masters =
      reduce::merge_dofs({reduce::select_dofs(model.mesh, model.system.dofs, "left"),
                          reduce::select_dofs(model.mesh, model.system.dofs, "right")});
  reduce::CraigBamptonOptions options;
  options.n_modes = 40;
  int size = 0;
  double f1 = 0;
  for (auto _ : state) {
    const reduce::ReducedComponent rc =
        reduce::craig_bampton(model.system.K, model.system.M, model.system.dofs, masters, options);
    size = rc.size();
    f1 = rc.fixed_interface_hz.size() > 0 ? rc.fixed_interface_hz[0] : 0.0;
  }
  set_sector_counters(state, model);
  state.counters["masters"] = static_cast<double>(masters.size());
  state.counters["reduced_size"] = size;
  state.counters["f1_fixed_hz"] = f1;
}
// Only the coarse sector: with every face DOF a master, Psi is dense n_interior x n_masters and
// the products T^T K T, T^T M T cost O(n_interior (n_masters + n_modes)^2).
BENCHMARK(BM_SectorCraigBampton40)
    ->Arg(0)
    ->ArgName("size")
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Iterations(1);

}  // namespace
