#include "geardyn/analyses/sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <thread>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/linalg/blas_library.hpp"
#include "geardyn/model/parse.hpp"

namespace geardyn::analyses {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

double extract_scalar(const model::Analysis& analysis, const Outcome& outcome,
                      const SweepOutput& spec, std::string& unit) {
  const AnalysisType& type = type_of(analysis);
  if (!type.scalar)
    throw std::runtime_error(fmt::format("analysis type '{}' offers no scalar outputs", type.name));
  return type.scalar(outcome, spec.request(), unit);
}

SweepResult run_sweep(const model::ModelDocument& document, const SweepSettings& settings,
                      Progress& progress) {
  SweepResult result;
  result.parameter = settings.parameter;
  result.parameter_unit = model::field_of(document, settings.parameter, {}).unit.symbol;
  result.values = settings.values;
  const std::size_t n = settings.values.size();
  const std::size_t n_out = settings.outputs.size();
  result.outputs.assign(n_out, std::vector<double>(n, kNaN));
  result.units.assign(n_out, "");
  result.point_status.assign(n, Status::Ok);
  result.point_message.assign(n, "");
  for (const auto& o : settings.outputs) result.labels.push_back(o.label);

  unsigned threads = settings.threads > 0 ? static_cast<unsigned>(settings.threads)
                                          : std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(n, 1)));
  // Points factorise through SuiteSparse and so call the system BLAS from every thread; a BLAS
  // that shares work buffers between callers corrupts results silently, so it gets one thread.
  const linalg::BlasLibrary& blas = linalg::loaded_blas();
  if (threads > 1 && !linalg::safe_for_concurrent_calls(blas)) {
    result.thread_note = fmt::format(
        "ran on 1 thread instead of {}: the system BLAS ({}) is a sequential OpenBLAS, which is "
        "not safe to call from several threads at once; install the threaded OpenBLAS "
        "(Debian: libopenblas0-pthread, as scripts/install-deps does) to run points in parallel",
        threads, blas.description);
    threads = 1;
  }
  result.threads_used = static_cast<int>(threads);

  std::atomic<std::size_t> next{0}, done{0};
  std::mutex progress_mutex, unit_mutex;
  progress.start(fmt::format("sweep of {}", settings.parameter), n);

  auto worker = [&]() {
    for (std::size_t i = next++; i < n; i = next++) {
      try {
        model::ModelDocument point = document;
        model::set_number(point, settings.parameter, settings.values[i]);
        for (const auto& linked : settings.linked_parameters)
          model::set_number(point, linked, settings.values[i]);
        const model::Model m = model::build_model(point);
        const model::Analysis* a = m.find_analysis(settings.analysis);
        if (a == nullptr)
          throw std::runtime_error("analysis '" + settings.analysis + "' not found");
        // The rotor's system only for a target that uses it (a solid or gear analysis has none).
        fe::LinearSystem system;
        std::vector<assembly::CoupledSolid> coupled;
        const bool needs_rotor = declaration_of(type_of(*a)).needs_rotor;
        if (needs_rotor) system = assembly::build_system(m, nullptr, coupled);
        Context context(m, *a);
        context.with_document(&point);
        if (needs_rotor) context.with_system(&system).with_coupled_solids(&coupled);
        const Outcome outcome = run_analysis(m, *a, context);
        const AnalysisOutput& out = outcome.output;
        // An unstable system still has its numbers (a steady state that is never reached, or
        // modes of which one grows): kept, and the point marked unstable.
        result.point_status[i] = out.status;
        result.point_message[i] = out.message;
        if (out.status == Status::Ok || out.status == Status::Unstable) {
          for (std::size_t j = 0; j < n_out; ++j) {
            std::string unit;
            result.outputs[j][i] = extract_scalar(*a, outcome, settings.outputs[j], unit);
            std::lock_guard<std::mutex> lock(unit_mutex);
            result.units[j] = unit;
          }
        }
      } catch (const InputError&) {
        throw;
      } catch (const std::exception& e) {
        result.point_status[i] = Status::Failed;
        result.point_message[i] = e.what();
      }
      const std::size_t d = ++done;
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress.update(d);
    }
  };

  // Input errors of a point (an override out of range) abort the whole sweep with the message.
  std::exception_ptr input_error;
  std::mutex error_mutex;
  {
    std::vector<std::jthread> pool;
    for (unsigned t = 0; t < threads; ++t)
      pool.emplace_back([&]() {
        try {
          worker();
        } catch (...) {
          std::lock_guard<std::mutex> lock(error_mutex);
          if (!input_error) input_error = std::current_exception();
          next = n;  // stop handing out points
        }
      });
  }
  progress.finish();
  if (input_error) std::rethrow_exception(input_error);

  std::size_t failed = 0, unstable = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (result.point_status[i] == Status::Unstable)
      ++unstable;
    else if (result.point_status[i] != Status::Ok)
      ++failed;
  }
  if (failed == 0 && unstable > 0) {
    result.status = Status::Unstable;
    for (std::size_t i = 0; i < n; ++i)
      if (result.point_status[i] == Status::Unstable) {
        result.message = fmt::format(
            "{} of {} points unstable (values kept, status column); "
            "first at {} = {}: {}",
            unstable, n, settings.parameter, settings.values[i], result.point_message[i]);
        break;
      }
  }
  if (failed > 0) {
    result.status = Status::Failed;
    for (std::size_t i = 0; i < n; ++i)
      if (result.point_status[i] != Status::Ok) {
        result.message =
            fmt::format("{} of {} points failed; first at {} = {}: {}", failed, n,
                        settings.parameter, settings.values[i], result.point_message[i]);
        break;
      }
  }
  return result;
}

namespace {

/// Column name with its unit as a suffix ("value_N_m", "natural_frequency_1_Hz").
std::string with_unit(const std::string& name, const std::string& unit) {
  std::string suffix = unit.empty() ? "" : "_" + unit;
  for (auto& ch : suffix)
    if (ch == '/' || ch == ' ' || ch == '^' || ch == '*') ch = '_';
  return name + suffix;
}

}  // namespace

Table delta_table(const SweepResult& result, const SweepSettings& settings) {
  std::size_t ref = 0;
  for (std::size_t i = 0; i < result.values.size(); ++i)
    if (std::abs(result.values[i] - settings.reference_value) <
        std::abs(result.values[ref] - settings.reference_value))
      ref = i;
  Table t;
  t.name = "sweep_deltas";
  t.title = fmt::format(
      "Each output minus its value at {} = {} (the reference variant); "
      "levels in dB: the level difference",
      settings.parameter, result.values[ref]);
  t.add(with_unit("value", result.parameter_unit), result.parameter_unit, result.values);
  for (std::size_t j = 0; j < result.outputs.size(); ++j) {
    const double base = result.outputs[j][ref];
    std::vector<double> delta, change;
    for (double v : result.outputs[j]) {
      delta.push_back(v - base);
      change.push_back(base != 0.0 ? 100.0 * (v - base) / std::abs(base) : NAN);
    }
    t.add(with_unit(result.labels[j] + "_delta", result.units[j]), result.units[j], delta);
    if (result.units[j] != "dB") t.add(result.labels[j] + "_change_pct", "%", change);
  }
  return t;
}

AnalysisOutput sweep_output(const SweepResult& result, const SweepSettings& settings,
                            const std::string& analysis_name) {
  AnalysisOutput out;
  out.name = analysis_name;
  out.type = "sweep";
  out.status = result.status;
  out.message = result.message;

  Table table;
  table.name = "sweep";
  table.title = fmt::format("Sweep of {} (analysis '{}')", settings.parameter, settings.analysis);
  table.add(with_unit("value", result.parameter_unit), result.parameter_unit, result.values);
  for (std::size_t j = 0; j < result.outputs.size(); ++j)
    table.add(with_unit(result.labels[j], result.units[j]), result.units[j], result.outputs[j]);
  std::vector<std::string> status;
  for (auto s : result.point_status) status.emplace_back(to_string(s));
  table.add_text("status", status);
  out.tables.push_back(std::move(table));
  if (!std::isnan(settings.reference_value)) out.tables.push_back(delta_table(result, settings));

  for (std::size_t j = 0; j < result.outputs.size(); ++j) {
    Plot plot;
    plot.name = "sweep_" + result.labels[j];
    plot.title = fmt::format("{} versus {}", result.labels[j], settings.parameter);
    plot.x_label = result.parameter_unit.empty()
                       ? settings.parameter
                       : fmt::format("{} [{}]", settings.parameter, result.parameter_unit);
    plot.y_label = result.units[j].empty()
                       ? result.labels[j]
                       : fmt::format("{} [{}]", result.labels[j], result.units[j]);
    plot.x_log = settings.log_x;
    // Amplitudes spanning decades read best on a log axis.
    double lo = INFINITY, hi = 0.0;
    for (double v : result.outputs[j])
      if (v > 0.0 && std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    plot.y_log = hi > 0.0 && hi / lo > 100.0;
    Trace trace;
    trace.name = result.labels[j];
    trace.x = result.values;
    trace.y = result.outputs[j];
    trace.mode = Trace::Mode::LinesMarkers;
    plot.traces.push_back(std::move(trace));
    out.plots.push_back(std::move(plot));
  }
  out.notes.push_back(
      fmt::format("{} points on {} threads; each point rebuilds the model from "
                  "the file with the new value, so results equal a serial run.",
                  result.values.size(), result.threads_used));
  if (!result.thread_note.empty()) out.notes.push_back(result.thread_note);
  return out;
}

SweepResult run_sweep(const model::Model& /*model*/, const SweepSettings& settings,
                      const Context& context) {
  if (context.document() == nullptr)
    throw NumericalError(context.name(), "a sweep needs the model document to rebuild points");
  return run_sweep(*context.document(), settings, context.progress());
}

AnalysisOutput sweep_output(const model::Model& /*model*/, const SweepSettings& settings,
                            const SweepResult& result, const Context& context) {
  return sweep_output(result, settings, context.name());
}

}  // namespace geardyn::analyses
