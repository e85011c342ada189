// Gear whine over speed (issue #17, "whine over 500 speeds x 5 orders on a 10^5-DOF reduced
// system in < 30 s"): a two-shaft spur stage (20/40 teeth, the model of
// tests/response/whine_time_domain_test.cpp without its web) whose input-side bearings sit in a
// housing plate of hex8 elements, 0.40 x 0.30 x 0.03 m, 64 x 48 x 10 cells (35 035 nodes,
// 105 105 DOFs less the clamped edges), clamped on its two short edges and joined to the bearing
// seats by rigid spiders. Timed separately:
//   BM_WhineReduction   the housing assembled and Craig-Bampton reduced (assembly::couple_solid,
//                       coupling_modes fixed-interface modes) and the rotor system assembled;
//   BM_WhineModalBasis  the modal basis of the rotor system (response::ModalRotorModel);
//   BM_WhineLoop        run_mesh_forced_response over speeds x orders (ModalReduced; Direct for
//                       comparison), args: speeds, orders, basis modes (0: Direct).
// The reduced housing is built once per coupling_modes and shared by the loop benchmarks.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <tuple>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/assembly/solid_coupling.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/response/rotor_mesh_response.hpp"
#include "geardyn/solid/assembly.hpp"
#include "geardyn/solid/structured_mesh.hpp"

namespace {

using namespace geardyn;
constexpr double kPi = units::kPi;

constexpr const char* kRotor = R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = 210e9
poisson_ratio = 0.3
density = 7850

[[shafts]]
name = "input"
material = "steel"
origin = [0, 0, -0.1]
speed_ratio = 1.0
  [[shafts.elements]]
  length = 0.2
  outer_diameter = 0.03
  divisions = 4

[[shafts]]
name = "output"
material = "steel"
origin = [0.15, 0, -0.1]
driven_by = "input"
gear_ratio = -0.5
  [[shafts.elements]]
  length = 0.2
  outer_diameter = 0.04
  divisions = 4

[[disks]]
name = "pinion"
node = "input.2"
outer_diameter = 0.10
inner_diameter = 0.03
thickness = 0.03
material = "steel"

[[disks]]
name = "wheel"
node = "output.2"
outer_diameter = 0.20
inner_diameter = 0.04
thickness = 0.03
material = "steel"

[[nodes]]
name = "seat_in"
position = [0, 0, -0.1]

[[nodes]]
name = "seat_out"
position = [0.15, 0, -0.1]

[[bearings]]
node = "input.0"
node2 = "seat_in"
kxx = 1e8
kyy = 1e8
kzz = 1e8
cxx = 2000
cyy = 2000
czz = 2000

[[bearings]]
node = "output.0"
node2 = "seat_out"
kxx = 1e8
kyy = 1e8
kzz = 1e8
cxx = 2000
cyy = 2000
czz = 2000

[[bearings]]
node = "input.4"
kxx = 1e8
kyy = 1e8
cxx = 2000
cyy = 2000

[[bearings]]
node = "output.4"
kxx = 1e8
kyy = 1e8
cxx = 2000
cyy = 2000

[[constraints]]
node = "input.0"
dofs = ["rz"]

[[gear_meshes]]
name = "stage"
gear1 = "input.2"
gear2 = "output.2"
type = "spur"
teeth1 = 20
teeth2 = 40
base_radius1 = 0.04698463103929542
base_radius2 = 0.09396926207859084
pressure_angle_deg = 20
stiffness = 2e8

[damping]
rayleigh_alpha = 20.0
rayleigh_beta = 1e-7

[[sensors]]
name = "seat_in_x"
node = "seat_in"
dof = "ux"

[[sensors]]
name = "seat_out_z"
node = "seat_out"
dof = "uz"

[[sensors]]
name = "pinion_y"
node = "input.2"
dof = "uy"
)";

// The housing plate: z from -0.13 to -0.10 (its top face carries the seats), clamped on x = min
// and x = max; the seat sets are the top-face nodes within 20 mm of each seat.
assembly::SolidComponent housing() {
  const solid::Material steel{"steel", 0, 210e9, 0.3, 7850.0, {}};
  assembly::SolidComponent c;
  c.name = "housing";
  c.mesh = solid::box_mesh({-0.12, -0.15, -0.13}, {0.28, 0.15, -0.10}, 64, 48, 10,
                           solid::ElementType::Hex8, steel);
  for (const char* set : {"xmin", "xmax"})
    for (int node : c.mesh.node_sets.at(set)) c.mesh.constraints.push_back({node, {}, {}});
  for (const auto& [name, x, y] : {std::tuple{"seat_in", 0.0, 0.0}, {"seat_out", 0.15, 0.0}}) {
    std::vector<int>& set = c.mesh.node_sets[name];
    for (int node : c.mesh.node_sets.at("zmax")) {
      const Eigen::Vector3d& p = c.mesh.coords[static_cast<std::size_t>(node)];
      if (std::hypot(p.x() - x, p.y() - y) <= 0.02) set.push_back(node);
    }
  }
  c.system = solid::assemble(c.mesh);
  c.description = "generated housing plate";
  return c;
}

struct WhineCase {
  model::Model model;
  fe::LinearSystem system;
  int housing_dofs = 0;
  double seconds_reduction = 0.0;
};

std::shared_ptr<WhineCase> whine_case(int coupling_modes) {
  static std::map<int, std::shared_ptr<WhineCase>> cache;
  if (auto it = cache.find(coupling_modes); it != cache.end()) return it->second;
  auto c = std::make_shared<WhineCase>();
  c->model = analyses::parse_model(kRotor, "whine_bench.toml");
  model::Solid s;
  s.name = "housing";
  s.mesh = "generated";
  s.coupling_modes = coupling_modes;
  s.spiders = {{"seat_in", "seat_in", model::SpiderKind::Rigid, {}},
               {"seat_out", "seat_out", model::SpiderKind::Rigid, {}}};
  c->model.solids.push_back(s);
  const auto start = std::chrono::steady_clock::now();
  assembly::SolidComponents built;
  built.emplace("housing", housing());
  c->housing_dofs = built.at("housing").system.num_dofs();
  const std::vector<assembly::CoupledSolid> coupled = assembly::couple_solids(c->model, &built);
  c->system = fe::assemble(c->model, {}, {coupled.front().body});
  c->seconds_reduction =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  cache[coupling_modes] = c;
  return c;
}

response::RotorForcedSettings settings(const WhineCase& c, int speeds, int orders, int modes) {
  response::RotorForcedSettings s;
  s.gear_mesh = "stage";
  for (int p = 1; p <= orders; ++p) s.harmonics.push_back({p, {100.0 / p, 0.0}});
  s.sensors = response::rotor_sensors(c.model, c.system);
  // 300 .. 6000 rpm: mesh order 1 from 100 Hz to 2 kHz.
  s.speeds = Eigen::VectorXd::LinSpaced(speeds, 2 * kPi * 300 / 60.0, 2 * kPi * 6000 / 60.0);
  s.method =
      modes > 0 ? response::RotorForcedMethod::ModalReduced : response::RotorForcedMethod::Direct;
  s.n_modes = std::max(modes, 1);
  return s;
}

// Arg: coupling_modes of the housing.
void BM_WhineReduction(benchmark::State& state) {
  std::shared_ptr<WhineCase> c;
  for (auto _ : state) c = whine_case(static_cast<int>(state.range(0)));
  state.counters["housing_dofs"] = c->housing_dofs;
  state.counters["system_dofs"] = c->system.size();
  state.counters["reduction_s"] = c->seconds_reduction;
}
BENCHMARK(BM_WhineReduction)->Arg(30)->Arg(150)->Iterations(1)->Unit(benchmark::kSecond);

// Args: coupling_modes, basis modes.
void BM_WhineModalBasis(benchmark::State& state) {
  const auto c = whine_case(static_cast<int>(state.range(0)));
  const response::RotorForcedSettings s = settings(*c, 1, 1, static_cast<int>(state.range(1)));
  const Eigen::MatrixXd load =
      response::mesh_load(c->model, c->system, response::find_gear_mesh(c->model, "stage"));
  std::vector<int> outputs;
  for (const auto& sensor : s.sensors) outputs.push_back(sensor.equation);
  int basis = 0;
  for (auto _ : state) {
    const response::ModalRotorModel modal(c->system, load, outputs, s.n_modes, true);
    basis = modal.basis_size();
  }
  state.counters["basis"] = basis;
}
BENCHMARK(BM_WhineModalBasis)
    ->Args({30, 50})
    ->Args({150, 100})
    ->Args({150, 200})
    ->Unit(benchmark::kMillisecond);

// The loop alone (basis or symbolic analysis outside it): per speed one setup (at), per order
// one solve, as run_mesh_forced_response does. Args: coupling_modes, speeds, orders, basis
// modes (0: Direct). Counter run_s: the whole run_mesh_forced_response (basis, loop, peaks).
void BM_WhineLoop(benchmark::State& state) {
  const auto c = whine_case(static_cast<int>(state.range(0)));
  const response::RotorForcedSettings s =
      settings(*c, static_cast<int>(state.range(1)), static_cast<int>(state.range(2)),
               static_cast<int>(state.range(3)));
  const Eigen::MatrixXd load =
      response::mesh_load(c->model, c->system, response::find_gear_mesh(c->model, "stage"));
  const double per_speed = response::mesh_frequency_per_speed(c->model, c->system, 0);
  std::vector<int> outputs;
  for (const auto& sensor : s.sensors) outputs.push_back(sensor.equation);
  std::unique_ptr<response::ModalRotorModel> modal;
  std::unique_ptr<response::DirectRotorSolver> direct;
  if (state.range(3) > 0)
    modal = std::make_unique<response::ModalRotorModel>(c->system, load, outputs, s.n_modes,
                                                        s.residual_vectors);
  else
    direct = std::make_unique<response::DirectRotorSolver>(c->system, load, outputs);
  double sum = 0.0;
  const auto solve_all = [&](const auto& point) {
    for (const auto& h : s.harmonics)
      sum += std::abs(point.response(h.order * per_speed * point.speed())(0, 0));
  };
  for (auto _ : state) {
    for (Eigen::Index i = 0; i < s.speeds.size(); ++i) {
      if (modal)
        solve_all(modal->at(s.speeds[i]));
      else
        solve_all(direct->at(s.speeds[i]));
    }
    benchmark::DoNotOptimize(sum);
  }
  const response::RotorForcedResult r = response::run_mesh_forced_response(c->model, c->system, s);
  state.counters["run_s"] = r.seconds;
  state.counters["system_dofs"] = c->system.size();
  state.counters["basis"] = modal ? modal->basis_size() : 0;
  state.counters["solves"] = static_cast<double>(state.range(1) * state.range(2));
}
BENCHMARK(BM_WhineLoop)
    ->Args({30, 500, 5, 50})
    ->Args({30, 250, 5, 50})
    ->Args({30, 500, 1, 50})
    ->Args({150, 500, 5, 100})
    ->Args({150, 500, 5, 200})
    ->Args({30, 500, 5, 0})
    ->Args({150, 500, 5, 0})
    ->Unit(benchmark::kMillisecond);

}  // namespace
