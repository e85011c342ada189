// A sweep of 100 points, each rebuilding a 100-element rotor from the model document and
// running an unbalance response at 50 speeds, on all cores.
#include <benchmark/benchmark.h>

#include <string>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/sweep.hpp"
#include "geardyn/model/parse.hpp"

namespace {

using namespace geardyn;

const char* kRotor = R"(
version = 1
[[materials]]
name = "steel"
youngs_modulus = 211e9
shear_modulus = 81.2e9
density = 7810
[[shafts]]
name = "s"
material = "steel"
  [[shafts.elements]]
  length = 1.5
  outer_diameter = 0.05
  divisions = 100
[[disks]]
node = "s.33"
mass = 20
polar_inertia = 0.2
diametral_inertia = 0.1
[[disks]]
node = "s.66"
mass = 30
polar_inertia = 0.4
diametral_inertia = 0.2
[[bearings]]
node = "s.0"
kxx = 1e7
kyy = 1e7
kzz = 1e8
ktzz = 1e5
cxx = 500
cyy = 500
[[bearings]]
node = "s.100"
kxx = 1e7
kyy = 1e7
cxx = 500
cyy = 500
[[unbalances]]
node = "s.33"
mass_eccentricity = 1e-4
[[sensors]]
name = "x"
node = "s.33"
dof = "ux"
[[analyses]]
name = "unb"
type = "unbalance"
enabled = false
speed_start_rpm = 100
speed_stop_rpm = 10000
speed_count = 50
[[analyses]]
name = "sweep"
type = "sweep"
parameter = "bearings[0].kxx"
linked_parameters = ["bearings[0].kyy"]
start = 1e6
stop = 1e8
count = 100
spacing = "log"
analysis = "unb"
outputs = [{ quantity = "peak_amplitude", sensor = "x" }]
)";

void BM_Sweep100(benchmark::State& state) {
  const auto doc = analyses::parse_document(kRotor, "bench.toml");
  const model::Model m = model::build_model(doc);
  auto settings = m.analyses[1].settings_of<analyses::SweepSettings>();
  settings.threads = static_cast<int>(state.range(0));
  for (auto _ : state)
    benchmark::DoNotOptimize(analyses::run_sweep(doc, settings, null_progress()));
}
BENCHMARK(BM_Sweep100)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace
