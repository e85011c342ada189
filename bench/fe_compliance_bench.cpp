// Benchmark of the FE compliance route of the loaded tooth contact analysis
// (gear/fe_compliance.hpp): the influence coefficients of one tooth pair (both gears: mesh of
// the whole gear, assembly, Cholesky, load cases), and one mesh cycle of the contact analysis
// with them.
// Figures are recorded in docs/performance.md ("Loaded tooth contact").
//
//   spur 20/40 teeth, m = 3 mm, alpha = 20 deg, b = 20 mm, steel, T1 = 169 N m (300 N/mm);
//   FE of the whole gears (the default fe_teeth = 0), element size 0.35 m (0.25 m: the finer
//   case) at the loaded tooth, 3 m elsewhere, 9 profile x 15 face points per gear.
#include <benchmark/benchmark.h>

#include "geardyn/gear/fe_compliance.hpp"
#include "geardyn/gear/tooth_contact.hpp"

namespace {

using namespace geardyn;

gear::GearPairGeometry spur() {
  gear::GearPairSpec s;
  s.teeth_pinion = 20;
  s.teeth_wheel = 40;
  s.module_m = 3e-3;
  s.face_width_m = 20e-3;
  return gear::gear_pair_geometry(s);
}

gear::FeComplianceOptions options(double size) {
  gear::FeComplianceOptions o;
  o.mesh_size = size;
  o.segment_teeth = 0;
  o.profile_points = 9;
  return o;
}

// Arg: element size at the loaded tooth in 1/100 modules. Counters: DOFs of both gears.
void BM_FeInfluenceCoefficients(benchmark::State& state) {
  const gear::GearPairGeometry g = spur();
  const gear::ToothCompliance teeth(g);
  const double size = static_cast<double>(state.range(0)) / 100.0;
  for (auto _ : state) {
    const gear::FeCompliance fe(teeth, options(size));
    state.counters["dofs"] = fe.pinion().dofs + fe.wheel().dofs;
    state.counters["mesh_factor_s"] = fe.pinion().mesh_seconds + fe.wheel().mesh_seconds;
    state.counters["load_cases_s"] = fe.pinion().solve_seconds + fe.wheel().solve_seconds;
  }
}
BENCHMARK(BM_FeInfluenceCoefficients)->Arg(35)->Arg(25)->Unit(benchmark::kSecond)->Iterations(1);

// One mesh cycle, 64 positions x 40 slices, with the FE compliance (built once, outside).
void BM_FeToothContactCycle(benchmark::State& state) {
  const gear::GearPairGeometry g = spur();
  const gear::ToothCompliance teeth(g);
  const gear::FeCompliance fe(teeth, options(0.35));
  gear::ToothContactOptions o;
  o.positions = 64;
  o.slices = 40;
  const gear::ToothContact tc(g, {}, {}, fe, o);
  const double torque = 300e3 * g.face_width_m * g.pinion.base_radius_m;
  for (auto _ : state) {
    const gear::ToothContactResult r = tc.solve(torque);
    if (r.status != Status::Ok) state.SkipWithError(r.message.c_str());
    benchmark::DoNotOptimize(r.te_m.data());
  }
}
BENCHMARK(BM_FeToothContactCycle)->Unit(benchmark::kMillisecond);

}  // namespace
