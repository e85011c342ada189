// The drivetrain transient of issue #16 (Performance), both adaptive integrators side by side:
// bench/data/drivetrain_housing.toml, a run-up 0 -> 3000 rpm of two shafts joined by two spur
// pairs with backlash, on four ball bearings whose outer rings sit on a Craig-Bampton reduced
// housing (an annular plate, `coupling_modes` fixed-interface modes) held by eight preloaded
// bolts, recorded at 20 kHz. The housing is generated and reduced once per mode count, outside
// the timing; the timing is run_drivetrain_transient (assembly of the reduced system, static
// equilibrium, integration, channels).
//
//   BM_DrivetrainRunup/<integrator>/<housing modes>/<simulated ms>/<-log10 rtol>
//     integrator 0: generalized_alpha, 1: ida. Counters: steps, rejected_error,
//     rejected_newton, newton_iterations, factorizations, residual_evaluations, wall_s (the
//     whole analysis), integration_s and integration_cpu_s (the integration stage alone, wall and
//     thread CPU), setup_cpu_s (the rest: the Craig-Bampton reduction of the housing, which
//     couple_solids redoes on every run, assembly, static equilibrium), dte_peak_m (largest
//     |DTE| of pair_a along the line of action), dte_rms_m.
//   BM_DrivetrainAccuracy/<integrator>/<-log10 rtol>: the same run (200 modes, 20 ms) and the
//     error of its DTE peak and of its DTE record against a tight-tolerance reference
//     (generalised-alpha at rtol 1e-7), so that the two integrators are compared at equal
//     accuracy (IDA's errors against it, as rtol falls, show whether the reference favours
//     generalised-alpha).
// Iterations are fixed at 1 (a run is seconds to minutes); timings live here, never in tests.
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <time.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <string>

#include "geardyn/analyses/drivetrain_transient.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/progress.hpp"

namespace geardyn {
namespace {

using analyses::DrivetrainIntegrator;
using analyses::DrivetrainTransientResult;
using analyses::DrivetrainTransientSettings;

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// CPU seconds of this thread (the analysis runs on one thread; on a shared machine the wall
/// time is inflated by the other processes, the CPU time much less).
double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Wall and CPU seconds of the integration stage (the analysis' progress stage of that name).
class IntegrationClock final : public Progress {
 public:
  void start(const std::string& what, std::size_t) override {
    if (what.find("time integration") == std::string::npos) return;
    started_ = now_s();
    started_cpu_ = thread_cpu_s();
  }
  void update(std::size_t) override {}
  void finish() override {
    if (started_ > 0.0) {
      seconds += now_s() - started_;
      cpu_seconds += thread_cpu_s() - started_cpu_;
    }
    started_ = 0.0;
  }
  double seconds = 0.0;
  double cpu_seconds = 0.0;

 private:
  double started_ = 0.0, started_cpu_ = 0.0;
};

/// The benchmark model with `modes` housing modes, and its reduced housing (built once).
struct Case {
  model::Model model;
  assembly::SolidComponents solids;
};

const Case& case_with_modes(int modes) {
  static std::map<int, std::unique_ptr<Case>> cases;
  auto& c = cases[modes];
  if (!c) {
    c = std::make_unique<Case>();
    c->model = analyses::load_model(std::string(GEARDYN_SOURCE_DIR) +
                                    "/bench/data/drivetrain_housing.toml");
    c->model.solids.front().coupling_modes = modes;
    c->solids = assembly::build_solids(c->model);
  }
  return *c;
}

struct Run {
  DrivetrainTransientResult result;
  double wall_s = 0.0;
  double integration_s = 0.0;
  double integration_cpu_s = 0.0;
  double cpu_s = 0.0;   ///< the whole analysis, CPU of this thread
  Eigen::VectorXd dte;  ///< pair_a DTE along the line of action [m], per sample
};

Run run(int modes, DrivetrainIntegrator integrator, double duration, double rtol) {
  const Case& c = case_with_modes(modes);
  DrivetrainTransientSettings s =
      c.model.analyses.front().settings_of<DrivetrainTransientSettings>();
  s.integrator = integrator;
  s.duration = duration;
  s.relative_tolerance = rtol;
  s.modes = 0;  // no linearisation: the run-up only
  IntegrationClock clock;
  analyses::Context context(c.model, c.model.analyses.front());
  context.with_solids(&c.solids).with_progress(&clock);
  Run r;
  const double started = now_s(), started_cpu = thread_cpu_s();
  r.result = analyses::run_drivetrain_transient(c.model, s, context);
  r.wall_s = now_s() - started;
  r.cpu_s = thread_cpu_s() - started_cpu;
  r.integration_s = clock.seconds;
  r.integration_cpu_s = clock.cpu_seconds;
  for (std::size_t k = 0; k < r.result.channels.size(); ++k)
    if (r.result.channels[k].name == "pair_a_dte_m")
      r.dte = r.result.values.col(static_cast<Eigen::Index>(k));
  return r;
}

double peak(const Eigen::VectorXd& x) { return x.size() ? x.cwiseAbs().maxCoeff() : 0.0; }
double rms(const Eigen::VectorXd& x) {
  return x.size() ? std::sqrt(x.squaredNorm() / static_cast<double>(x.size())) : 0.0;
}

void report(benchmark::State& state, const Run& r) {
  const transient::AdaptiveSummary& i = r.result.integration;
  state.counters["steps"] = static_cast<double>(i.steps);
  state.counters["rejected_error"] = static_cast<double>(i.rejected_error);
  state.counters["rejected_newton"] = static_cast<double>(i.rejected_newton);
  state.counters["newton_iterations"] = static_cast<double>(i.newton_iterations);
  state.counters["factorizations"] = static_cast<double>(i.factorizations);
  state.counters["residual_evaluations"] = static_cast<double>(i.residual_evaluations);
  state.counters["wall_s"] = r.wall_s;
  state.counters["integration_s"] = r.integration_s;
  state.counters["integration_cpu_s"] = r.integration_cpu_s;
  state.counters["setup_cpu_s"] = r.cpu_s - r.integration_cpu_s;  // reduction, assembly, statics
  state.counters["dte_peak_m"] = peak(r.dte);
  state.counters["dte_rms_m"] = rms(r.dte);
  state.SetLabel(fmt::format("{} ({}), {} samples, min step {:.3g} s", i.integrator, i.solver,
                             i.samples, i.min_step_taken));
}

DrivetrainIntegrator integrator_of(std::int64_t arg) {
  return arg == 0 ? DrivetrainIntegrator::GeneralizedAlpha : DrivetrainIntegrator::Ida;
}

void BM_DrivetrainRunup(benchmark::State& state) {
  const auto integrator = integrator_of(state.range(0));
  const int modes = static_cast<int>(state.range(1));
  const double duration = 1e-3 * static_cast<double>(state.range(2));
  const double rtol = std::pow(10.0, -static_cast<double>(state.range(3)));
  case_with_modes(modes);  // reduction outside the timing
  Run r;
  for (auto _ : state) r = run(modes, integrator, duration, rtol);
  if (r.result.status != Status::Ok) {
    state.SkipWithError(r.result.message.c_str());
    return;
  }
  report(state, r);
}

// Side by side at the size (200 housing modes), the growth with housing modes (50 ...
// 400) and with simulated time (the full 1 s run is ~minutes per integrator on this machine:
// docs/performance.md "Drivetrain transient" gives the figures).
void runup_args(benchmark::internal::Benchmark* b) {
  for (const int integrator : {0, 1}) {
    for (const int modes : {50, 100, 200, 400}) b->Args({integrator, modes, 20, 4});
    for (const int ms : {50, 100, 250, 500, 1000}) b->Args({integrator, 200, ms, 4});
  }
}
BENCHMARK(BM_DrivetrainRunup)
    ->Apply(runup_args)
    ->ArgNames({"integrator", "modes", "ms", "rtol_exp"})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

void BM_DrivetrainAccuracy(benchmark::State& state) {
  constexpr int kModes = 200;
  constexpr double kDuration = 0.02;
  static const Run reference = run(kModes, DrivetrainIntegrator::GeneralizedAlpha, kDuration, 1e-7);
  const auto integrator = integrator_of(state.range(0));
  const double rtol = std::pow(10.0, -static_cast<double>(state.range(1)));
  Run r;
  for (auto _ : state) r = run(kModes, integrator, kDuration, rtol);
  if (r.result.status != Status::Ok || reference.result.status != Status::Ok) {
    state.SkipWithError(r.result.status != Status::Ok ? r.result.message.c_str()
                                                      : reference.result.message.c_str());
    return;
  }
  report(state, r);
  state.counters["dte_peak_error_m"] = std::abs(peak(r.dte) - peak(reference.dte));
  // Same sample times (the fixed output rate): the largest sample-wise DTE difference.
  const Eigen::Index n = std::min(r.dte.size(), reference.dte.size());
  state.counters["dte_max_error_m"] =
      n ? (r.dte.head(n) - reference.dte.head(n)).cwiseAbs().maxCoeff() : 0.0;
}
BENCHMARK(BM_DrivetrainAccuracy)
    ->ArgsProduct({{0, 1}, {3, 4, 5}})
    ->ArgNames({"integrator", "rtol_exp"})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace geardyn
