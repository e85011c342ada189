// Cyclic forced response of a Craig-Bampton-reduced gear sector over 1000 speeds: the per-speed
// modal sum of response/cyclic_forced_response (setup: mesh, reduction and modes, done once outside
// the timed loop). Sector: annular steel disk r = 0.05 .. 0.15 m, t = 0.02 m, N = 24, hex8 with
// 4 x 4 x 2 cells, clamped at the inner radius; masters = both interfaces + the tooth node + a
// sensor node, 20 fixed-interface modes; 30 modes of nodal diameter 3, engine order 21 = N - h.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include "geardyn/core/units.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/response/cyclic_forced_response.hpp"
#include "geardyn/solid/assembly.hpp"
#include "geardyn/solid/structured_mesh.hpp"

namespace {

using namespace geardyn;
constexpr double kPi = units::kPi;
constexpr int kSectors = 24;

struct ReducedSectorCase {
  reduce::ReducedComponent rc;
  std::unique_ptr<cyclic::CyclicSector> sector;
  cyclic::NodalDiameterModes modes;
  std::vector<response::ToothLoad> loads;
  std::vector<response::CyclicSensor> sensors;
  Eigen::VectorXd speeds;

  ReducedSectorCase() {
    solid::Material steel{"steel", 0, 200e9, 0.3, 7850.0, {}};
    solid::Mesh mesh = solid::annular_sector_mesh(0.05, 0.15, 0.02, 2 * kPi / kSectors, 4, 4, 2,
                                                  solid::ElementType::Hex8, steel);
    for (int node : mesh.node_sets.at("inner")) mesh.constraints.push_back({node, {}, {}});
    for (auto& c : mesh.constraints) c.components = {true, true, true, false, false, false};
    const solid::SolidSystem sys = solid::assemble(mesh);
    auto nearest = [&](const Eigen::Vector3d& x) {
      int best = 0;
      for (int i = 1; i < mesh.num_nodes(); ++i)
        if ((mesh.coords[static_cast<std::size_t>(i)] - x).norm() <
            (mesh.coords[static_cast<std::size_t>(best)] - x).norm())
          best = i;
      return best;
    };
    const double half = kPi / kSectors;
    const int tooth = nearest({0.15 * std::cos(half), 0.15 * std::sin(half), 0.01});
    const int probe = nearest({0.10 * std::cos(half), 0.10 * std::sin(half), -0.01});
    // Masters: the interface nodes (less the clamped ones, which have no DOF) and the tooth and
    // sensor nodes.
    std::vector<long> ids = {mesh.node_ids[static_cast<std::size_t>(tooth)],
                             mesh.node_ids[static_cast<std::size_t>(probe)]};
    const auto& inner = mesh.node_sets.at("inner");
    for (const char* set : {"left", "right"})
      for (int node : mesh.node_sets.at(set))
        if (!std::binary_search(inner.begin(), inner.end(), node))
          ids.push_back(mesh.node_ids[static_cast<std::size_t>(node)]);
    const std::vector<int> masters = reduce::select_dofs(sys.dofs, ids);
    reduce::CraigBamptonOptions cb;
    cb.n_modes = 20;
    rc = reduce::craig_bampton(sys.K, sys.M, sys.dofs, masters, cb);
    const std::vector<solid::DofInfo> dofs = rc.reduced_dofs();
    cyclic::InterfaceOptions io;
    io.n_sectors = kSectors;
    sector = std::make_unique<cyclic::CyclicSector>(dofs, cyclic::find_interfaces(dofs, io));
    cyclic::CyclicModesOptions mo;
    mo.nodal_diameters = {3};
    mo.eigen.n_modes = 30;
    const Eigen::SparseMatrix<double> K = rc.K.sparseView(), M = rc.M.sparseView();
    modes = cyclic::solve_cyclic_modes(K, M, *sector, mo).diameters.at(0);
    const long tooth_id = mesh.node_ids[static_cast<std::size_t>(tooth)];
    const long probe_id = mesh.node_ids[static_cast<std::size_t>(probe)];
    loads = {response::tooth_load(tooth_id, {100.0, 20.0},
                                  Eigen::Vector3d(-std::sin(half), std::cos(half), 0.2))};
    sensors = {{"probe_uz", probe_id, 2}, {"tooth_uz", tooth_id, 2}, {"tooth_ux", tooth_id, 0}};
    const double w1 = std::sqrt(modes.eigen.eigenvalues[0]);
    speeds = Eigen::VectorXd::LinSpaced(1000, 0.5 * w1 / 21, 3.0 * w1 / 21);
  }
};

const ReducedSectorCase& the_case() {
  static const ReducedSectorCase c;
  return c;
}

// Per-speed cost only: the (h, k) model is built once, then 1000 speeds are evaluated.
void BM_CyclicOrderResponse1000Speeds(benchmark::State& state) {
  const ReducedSectorCase& c = the_case();
  response::ModalDamping damping;
  damping.q_factor = 100.0;
  const response::CyclicOrderModel model = response::make_cyclic_order_model(
      *c.sector, c.modes, 21, c.loads, c.sensors, damping, 0, &c.rc);
  for (auto _ : state) {
    Eigen::MatrixXcd u = model.response(c.speeds);
    benchmark::DoNotOptimize(u.data());
  }
  state.counters["modes"] = static_cast<double>(model.num_modes());
  state.counters["speeds"] = static_cast<double>(c.speeds.size());
  state.counters["reduced_dofs"] = static_cast<double>(c.rc.size());
  state.counters["full_sector_dofs"] = static_cast<double>(c.rc.n_full());
}
BENCHMARK(BM_CyclicOrderResponse1000Speeds)->Unit(benchmark::kMillisecond);

// The whole analysis call: model build, 1000 speeds, resonance table and half-power peaks.
void BM_RunCyclicForcedResponse1000Speeds(benchmark::State& state) {
  const ReducedSectorCase& c = the_case();
  response::CyclicForcedSettings settings;
  settings.excitations = {{3, 21, c.loads}};
  settings.sensors = c.sensors;
  settings.speeds = c.speeds;
  settings.damping.q_factor = 100.0;
  for (auto _ : state) {
    response::CyclicForcedResult r =
        response::run_cyclic_forced_response(*c.sector, {c.modes}, settings, &c.rc);
    benchmark::DoNotOptimize(r.amplitude_sum.data());
  }
}
BENCHMARK(BM_RunCyclicForcedResponse1000Speeds)->Unit(benchmark::kMillisecond);

}  // namespace
