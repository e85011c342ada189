#include "geardyn/study/sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <thread>

#include "geardyn/analysis/system_builder.hpp"
#include "geardyn/model/parse.hpp"
#include "geardyn/study/run_analysis.hpp"

namespace geardyn::study {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const Table* find_table(const AnalysisOutput& output, std::initializer_list<const char*> names) {
  for (const char* name : names)
    for (const auto& t : output.tables)
      if (t.name == name) return &t;
  return nullptr;
}

// The response column of a sensor: "<sensor>_amplitude..." (FRF, unbalance response).
const Column* amplitude_column(const Table& table, const std::string& sensor) {
  const std::string stem = sensor + "_amplitude";
  for (const auto& c : table.columns)
    if (!c.text && c.name.rfind(stem, 0) == 0) return &c;
  return nullptr;
}

// The abscissa of a response table and the factor from rad/s to its unit.
const Column* abscissa(const Table& table, double& per_rad_s) {
  if (table.has_column("speed_rpm")) {
    per_rad_s = 60.0 / (2.0 * std::numbers::pi);
    return &table.column("speed_rpm");
  }
  if (table.has_column("frequency_hz")) {
    per_rad_s = 1.0 / (2.0 * std::numbers::pi);
    return &table.column("frequency_hz");
  }
  return nullptr;
}

// Rows grouped by excitation order (unbalance tables carry an `order` column); a single group
// otherwise. Each group's abscissa is increasing.
std::vector<std::vector<std::size_t>> order_groups(const Table& table) {
  std::vector<std::vector<std::size_t>> groups;
  if (!table.has_column("order")) {
    groups.emplace_back();
    for (std::size_t i = 0; i < table.rows(); ++i) groups.back().push_back(i);
    return groups;
  }
  const auto& order = table.column("order").numbers;
  std::vector<double> seen;
  for (std::size_t i = 0; i < table.rows(); ++i) {
    auto it = std::find(seen.begin(), seen.end(), order[i]);
    if (it == seen.end()) {
      seen.push_back(order[i]);
      groups.emplace_back();
      it = seen.end() - 1;
    }
    groups[static_cast<std::size_t>(it - seen.begin())].push_back(i);
  }
  return groups;
}

}  // namespace

double extract_scalar(const AnalysisOutput& output, const model::SweepOutput& spec,
                      std::string& unit) {
  using Q = model::SweepOutput::Quantity;
  switch (spec.quantity) {
    case Q::NaturalFrequency: {
      const Table* t = find_table(output, {"modes", "undamped_modes"});
      if (t == nullptr)
        throw std::runtime_error("analysis has no modes table (use a modal analysis)");
      unit = "Hz";
      const auto& f = t->column("frequency_hz").numbers;
      const auto row = static_cast<std::size_t>(spec.mode - 1);
      if (row >= f.size())
        throw std::runtime_error(fmt::format("mode {} requested, {} found", spec.mode, f.size()));
      return f[row];
    }
    case Q::CriticalSpeed: {
      const Table* t = find_table(output, {"critical_speeds"});
      if (t == nullptr)
        throw std::runtime_error("analysis has no critical_speeds table (use a campbell analysis)");
      unit = "rpm";
      std::vector<double> speeds = t->column("speed_rpm").numbers;
      std::sort(speeds.begin(), speeds.end());
      const auto row = static_cast<std::size_t>(spec.mode - 1);
      return row < speeds.size() ? speeds[row] : kNaN;  // none in range: NaN, not an error
    }
    case Q::PeakAmplitude:
    case Q::PeakLocation:
    case Q::AmplitudeAt: {
      const Table* t = find_table(output, {"frf", "response"});
      if (t == nullptr)
        throw std::runtime_error("analysis has no response table (use harmonic or unbalance)");
      const Column* amp = amplitude_column(*t, spec.sensor);
      if (amp == nullptr)
        throw std::runtime_error(fmt::format("no amplitude column for sensor '{}'", spec.sensor));
      double per_rad_s = 1.0;
      const Column* x = abscissa(*t, per_rad_s);
      if (x == nullptr) throw std::runtime_error("response table has no speed or frequency column");
      if (spec.quantity == Q::PeakAmplitude || spec.quantity == Q::PeakLocation) {
        std::size_t best = 0;
        for (std::size_t i = 1; i < amp->numbers.size(); ++i)
          if (amp->numbers[i] > amp->numbers[best]) best = i;
        if (amp->numbers.empty()) return kNaN;
        unit = spec.quantity == Q::PeakAmplitude ? amp->unit : x->unit;
        return spec.quantity == Q::PeakAmplitude ? amp->numbers[best] : x->numbers[best];
      }
      // AmplitudeAt: linear interpolation per order group, the largest over groups.
      unit = amp->unit;
      const double at = spec.at * per_rad_s;
      double result = kNaN;
      for (const auto& rows : order_groups(*t)) {
        for (std::size_t k = 0; k < rows.size(); ++k) {
          const double xk = x->numbers[rows[k]];
          double value = kNaN;
          if (std::abs(xk - at) <= 1e-9 * std::max(1.0, std::abs(at))) {
            value = amp->numbers[rows[k]];
          } else if (k + 1 < rows.size()) {
            const double x1 = x->numbers[rows[k + 1]];
            if ((xk - at) * (x1 - at) < 0.0) {
              const double s = (at - xk) / (x1 - xk);
              value = (1.0 - s) * amp->numbers[rows[k]] + s * amp->numbers[rows[k + 1]];
            }
          }
          if (!std::isnan(value) && (std::isnan(result) || value > result)) result = value;
        }
      }
      if (std::isnan(result))
        throw std::runtime_error(fmt::format("{} {} is outside the analysis range", at, x->unit));
      return result;
    }
  }
  return kNaN;
}

SweepResult run_sweep(const model::ModelDocument& document, const model::SweepSettings& settings,
                      Progress& progress) {
  SweepResult result;
  result.parameter = settings.parameter;
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
        const fe::LinearSystem system = analysis::build_system(m);
        RunContext context;
        context.document = &point;
        const AnalysisOutput out = run_analysis(m, system, *a, context);
        if (out.status != Status::Ok) {
          result.point_status[i] = out.status;
          result.point_message[i] = out.message;
        } else {
          for (std::size_t j = 0; j < n_out; ++j) {
            std::string unit;
            result.outputs[j][i] = extract_scalar(out, settings.outputs[j], unit);
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

  std::size_t failed = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (result.point_status[i] != Status::Ok) ++failed;
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

AnalysisOutput sweep_output(const SweepResult& result, const model::SweepSettings& settings,
                            const std::string& analysis_name) {
  AnalysisOutput out;
  out.name = analysis_name;
  out.type = "sweep";
  out.status = result.status;
  out.message = result.message;

  Table table;
  table.name = "sweep";
  table.title = fmt::format("Sweep of {} (analysis '{}')", settings.parameter, settings.analysis);
  table.add("value", "", result.values);
  for (std::size_t j = 0; j < result.outputs.size(); ++j) {
    const std::string unit = result.units[j];
    std::string suffix = unit.empty() ? "" : "_" + unit;
    for (auto& ch : suffix)
      if (ch == '/') ch = '_';
    table.add(result.labels[j] + suffix, unit, result.outputs[j]);
  }
  std::vector<std::string> status;
  for (auto s : result.point_status) status.emplace_back(to_string(s));
  table.add_text("status", status);
  out.tables.push_back(std::move(table));

  for (std::size_t j = 0; j < result.outputs.size(); ++j) {
    Plot plot;
    plot.name = "sweep_" + result.labels[j];
    plot.title = fmt::format("{} versus {}", result.labels[j], settings.parameter);
    plot.x_label = settings.parameter;
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
  return out;
}

}  // namespace geardyn::study
