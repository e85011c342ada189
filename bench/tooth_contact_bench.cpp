// Benchmark of the loaded tooth contact analysis (gear/tooth_contact.hpp with the analytic slice
// compliance, gear/slice_compliance.hpp): one mesh cycle of a helical pair at P positions x N
// slices, and a torque map of 10 torques. Figures are recorded in docs/performance.md ("Loaded
// tooth contact").
//
//   helical 23/47 teeth, m_n = 2.5 mm, beta = 20 deg, b = 30 mm, T1 = 250 N m, steel;
//   tip relief 8 um (linear) and lead crowning 5 um on the pinion, f_ma = 8 um;
//   coupling_length 0 (Winkler) or 3 mm (Pasternak coupling).
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "geardyn/gear/slice_compliance.hpp"
#include "geardyn/gear/tooth_compliance.hpp"
#include "geardyn/gear/tooth_contact.hpp"

namespace {

using namespace geardyn;

gear::GearPairGeometry helical() {
  gear::GearPairSpec s;
  s.type = gear::GearType::Helical;
  s.teeth_pinion = 23;
  s.teeth_wheel = 47;
  s.module_m = 2.5e-3;
  s.helix_angle_rad = 20.0 * std::acos(-1.0) / 180.0;
  s.face_width_m = 30e-3;
  return gear::gear_pair_geometry(s);
}

struct Problem {
  gear::GearPairGeometry g = helical();
  gear::ToothCompliance teeth{g};
  gear::SliceCompliance compliance;
  gear::FlankModification pinion;
  Problem(double coupling) : compliance(teeth, coupling) {
    pinion.tip_relief_m = 8e-6;
    pinion.tip_relief_start_radius_m = g.pinion.pitch_radius_m + 0.5 * g.normal_module_m;
    pinion.lead_crowning_m = 5e-6;
  }
  gear::ToothContact contact(int positions, int slices) const {
    gear::ToothContactOptions o;
    o.positions = positions;
    o.slices = slices;
    o.misalignment_in_plane_m = 8e-6;
    return gear::ToothContact(g, pinion, {}, compliance, o);
  }
};

// Args: positions, slices, coupling (0: none, 1: 3 mm).
void BM_ToothContactCycle(benchmark::State& state) {
  const Problem p(state.range(2) != 0 ? 3e-3 : 0.0);
  const gear::ToothContact tc =
      p.contact(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  for (auto _ : state) {
    const gear::ToothContactResult r = tc.solve(250.0);
    if (r.status != Status::Ok) state.SkipWithError(r.message.c_str());
    benchmark::DoNotOptimize(r.te_m.data());
  }
}
BENCHMARK(BM_ToothContactCycle)
    ->Args({64, 40, 0})
    ->Args({64, 40, 1})
    ->Args({32, 40, 0})
    ->Args({128, 40, 0})
    ->Args({64, 20, 0})
    ->Args({64, 80, 0})
    ->Unit(benchmark::kMillisecond);

// A TE-vs-torque map: 10 torques from 25 to 500 N m, 64 positions x 40 slices.
void BM_ToothContactTorqueMap(benchmark::State& state) {
  const Problem p(0.0);
  const gear::ToothContact tc = p.contact(64, 40);
  for (auto _ : state)
    for (int i = 1; i <= 10; ++i) {
      const gear::ToothContactResult r = tc.solve(50.0 * i);
      if (r.status != Status::Ok) state.SkipWithError(r.message.c_str());
    }
}
BENCHMARK(BM_ToothContactTorqueMap)->Unit(benchmark::kMillisecond);

}  // namespace
