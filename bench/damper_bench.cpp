// The damper-ring response end to end on a finite-element sector (issue [friction-hbm] sec. 8):
// bench/data/damper_ring_100.toml, the example's gear with its groove and ring meshed at 1 mm
// (105 contact pairs per sector, 3 798 DOFs), 5 harmonics, the speed range of the example.
// The mesh is generated and assembled once, outside the timing (the model file's solid); the
// timing is the analysis: cyclic modes of the 6 nodal diameters the harmonics carry, the residual
// flexibility and excitation at the contacts, the linear references (free and stuck ring), the
// continuation over speed, and the contact states, loops and force truncation at the peak.
// Phases are the analysis' own progress stages, timed in CPU time of the thread.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <map>
#include <string>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/hbm/condensed.hpp"
#include "geardyn/model/parse.hpp"

namespace geardyn {
namespace {

/// CPU seconds of the thread spent in each progress stage, by its name (the damper analysis does
/// not nest its stages).
class StageClock final : public Progress {
 public:
  void start(const std::string& what, std::size_t) override {
    what_ = what;
    started_ = hbm::CondensedStatistics::now();
  }
  void update(std::size_t) override {}
  void finish() override {
    if (!what_.empty()) seconds[what_] += hbm::CondensedStatistics::now() - started_;
    what_.clear();
  }
  std::map<std::string, double> seconds;

 private:
  std::string what_;
  double started_ = 0.0;
};

void BM_DamperRingAnalysis(benchmark::State& state) {
  const model::Model m =
      analyses::load_model(std::string(GEARDYN_SOURCE_DIR) + "/bench/data/damper_ring_100.toml");
  const assembly::SolidComponents solids = assembly::build_solids(m);
  StageClock clock;
  analyses::Context context(m, m.analyses.front());
  context.with_solids(&solids).with_progress(&clock);
  AnalysisOutput out;
  double total = 0.0;
  for (auto _ : state) {
    clock.seconds.clear();
    const double started = hbm::CondensedStatistics::now();
    out = analyses::run_analysis(m, m.analyses.front(), context).output;
    total = hbm::CondensedStatistics::now() - started;
  }
  if (out.status != Status::Ok) {
    state.SkipWithError(out.message.c_str());
    return;
  }
  std::size_t points = 0, pairs = 0;
  double peak = 0.0;
  for (const Table& t : out.tables) {
    if (t.name == "damped_response") points = t.rows();
    if (t.name == "contact_pairs") pairs = t.rows();
    if (t.name == "resonance") peak = t.column("peak_amplitude_m").numbers.front();
  }
  const auto& sec = clock.seconds;
  auto stage = [&](const char* name) {
    const auto it = sec.find(name);
    return it == sec.end() ? 0.0 : it->second;
  };
  const double modes = stage("damper ring: cyclic modes");
  const double flexibility = stage("damper ring: residual flexibility and excitation");
  const double linear = stage("damper ring: linear references");
  const double continuation = stage("damper ring: continuation over speed");
  state.SetLabel(fmt::format("{} pairs, {} points, damped peak {:.6e} m", pairs, points, peak));
  state.counters["cpu_s"] = total;
  state.counters["modes_s"] = modes;
  state.counters["flexibility_s"] = flexibility;
  state.counters["linear_refs_s"] = linear;
  state.counters["continuation_s"] = continuation;
  state.counters["rest_s"] = total - modes - flexibility - linear - continuation;
  state.counters["ms_per_point"] = points ? 1e3 * continuation / static_cast<double>(points) : 0.0;
}
BENCHMARK(BM_DamperRingAnalysis)->Unit(benchmark::kSecond)->Iterations(1)->MeasureProcessCPUTime();

}  // namespace
}  // namespace geardyn
