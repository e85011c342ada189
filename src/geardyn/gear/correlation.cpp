#include "geardyn/gear/correlation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "geardyn/core/error.hpp"
#include "geardyn/core/text.hpp"
#include "geardyn/gear/ste.hpp"
#include "geardyn/signal/half_power.hpp"

namespace geardyn::gear {
namespace {

constexpr std::size_t kNpos = static_cast<std::size_t>(-1);

struct AmplitudeUnit {
  const char* suffix;
  double factor;
  const char* si;
};

constexpr AmplitudeUnit kAmplitudeUnits[] = {
    {"m", 1.0, "m"},           {"mm", 1e-3, "m"},           {"um", 1e-6, "m"},
    {"nm", 1e-9, "m"},         {"m_s", 1.0, "m/s"},         {"mm_s", 1e-3, "m/s"},
    {"m_s2", 1.0, "m/s^2"},    {"g", 9.80665, "m/s^2"},     {"n", 1.0, "N"},
    {"strain", 1.0, "strain"}, {"ustrain", 1e-6, "strain"}, {"pa", 1.0, "Pa"},
    {"mpa", 1e6, "Pa"}};

std::string unit_suffix(const std::string& si) {
  if (si == "m/s") return "m_s";
  if (si == "m/s^2") return "m_s2";
  if (si == "N") return "n";
  if (si == "Pa") return "pa";
  return si;
}

void check_curve(std::span<const double> x, std::span<const double> a, const char* what) {
  if (x.size() != a.size())
    throw InputError(SourceLocation{}, what, "as many amplitudes as abscissa values",
                     fmt::format("{} and {}", x.size(), a.size()));
  if (x.size() < 3)
    throw InputError(SourceLocation{}, what, "at least 3 points", fmt::format("{}", x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(a[i]) || a[i] < 0.0)
      throw InputError(SourceLocation{}, fmt::format("{}[{}]", what, i),
                       "finite abscissa and amplitude >= 0", fmt::format("({}, {})", x[i], a[i]));
    if (i > 0 && !(x[i] > x[i - 1]))
      throw InputError(SourceLocation{}, fmt::format("{}[{}]", what, i),
                       "a strictly increasing abscissa",
                       fmt::format("{} after {}", x[i], x[i - 1]));
  }
}

PeakEstimate from_half_power(std::span<const double> x, std::span<const double> a,
                             std::size_t index) {
  const signal::HalfPower hp = signal::half_power(x, a, index);
  PeakEstimate p;
  p.index = index;
  p.x = hp.frequency;
  p.amplitude = hp.amplitude;
  p.x1 = hp.f1;
  p.x2 = hp.f2;
  p.q_factor = hp.q_factor;
  p.damping_ratio = hp.has_bandwidth() ? hp.damping_ratio() : PeakEstimate::kNaN;
  p.points_in_band = hp.points_in_band;
  return p;
}

// 20 log10 of the amplitude with a floor, so zeros do not give -inf.
std::vector<double> to_db(std::span<const double> a) {
  double peak = 0.0;
  for (double v : a) peak = std::max(peak, v);
  const double floor = peak > 0.0 ? peak * 1e-12 : 1e-300;
  std::vector<double> db(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) db[i] = 20.0 * std::log10(std::max(a[i], floor));
  return db;
}

double relative(double computed, double measured) { return (computed - measured) / measured; }

}  // namespace

MeasuredResponse parse_measured_response_csv(std::string_view text, const std::string& file_name) {
  const NumericCsv csv = parse_numeric_csv(text, file_name, 5);
  MeasuredResponse r;
  r.source = file_name;
  std::size_t ix = kNpos, ia = kNpos, ip = kNpos;
  double factor = 1.0;
  for (std::size_t i = 0; i < csv.names.size(); ++i) {
    const std::string& name = csv.names[i];
    if (name == "speed_rpm" || name == "frequency_hz") {
      if (ix != kNpos)
        throw InputError(csv.at_header(i), name, "one abscissa column (speed_rpm or frequency_hz)",
                         "a second one");
      ix = i;
      r.abscissa = name == "speed_rpm" ? ResponseAbscissa::SpeedRpm : ResponseAbscissa::FrequencyHz;
    } else if (name.starts_with("amplitude_")) {
      if (ia != kNpos)
        throw InputError(csv.at_header(i), name, "one amplitude column", "a second one");
      const std::string unit = name.substr(10);
      const auto* u = std::find_if(std::begin(kAmplitudeUnits), std::end(kAmplitudeUnits),
                                   [&](const AmplitudeUnit& au) { return unit == au.suffix; });
      if (u == std::end(kAmplitudeUnits))
        throw InputError(csv.at_header(i), name,
                         "amplitude_<unit> with unit m, mm, um, nm, m_s, mm_s, m_s2, g, n, strain, "
                         "ustrain, pa or mpa",
                         "'" + unit + "'");
      ia = i;
      factor = u->factor;
      r.amplitude_unit = u->si;
    } else if (name == "phase_deg") {
      ip = i;
    } else {
      throw InputError(csv.at_header(i), name,
                       "speed_rpm or frequency_hz, amplitude_<unit>, phase_deg", "'" + name + "'",
                       "the column names carry the quantity and its unit");
    }
  }
  if (ix == kNpos)
    throw InputError(csv.at_header(0), "header", "a speed_rpm or frequency_hz column", "none");
  if (ia == kNpos)
    throw InputError(csv.at_header(0), "header", "an amplitude_<unit> column", "none");
  for (std::size_t row = 0; row < csv.rows.size(); ++row) {
    const double x = csv.rows[row][ix], a = csv.rows[row][ia];
    if (x < 0.0)
      throw InputError(csv.at(row, ix), csv.names[ix], "a speed or frequency >= 0",
                       fmt::format("{}", x));
    if (row > 0 && !(x > r.x.back()))
      throw InputError(csv.at(row, ix), csv.names[ix], "a strictly increasing abscissa",
                       fmt::format("{} after {}", x, r.x.back()));
    if (a < 0.0)
      throw InputError(csv.at(row, ia), csv.names[ia], "an amplitude >= 0 (phase in phase_deg)",
                       fmt::format("{}", a));
    r.x.push_back(x);
    r.amplitude.push_back(a * factor);
    if (ip != kNpos) r.phase_deg.push_back(csv.rows[row][ip]);
  }
  return r;
}

MeasuredResponse read_measured_response_csv(const std::filesystem::path& path) {
  const std::optional<std::string> text = try_read_file(path);
  if (!text)
    throw InputError(SourceLocation{path.string(), 0, 0}, "measured_response",
                     "a readable CSV file", "a file that cannot be opened");
  return parse_measured_response_csv(*text, path.string());
}

PeakEstimate estimate_peak(std::span<const double> x, std::span<const double> amplitude,
                           double near) {
  check_curve(x, amplitude, "response");
  std::size_t best = kNpos;
  if (std::isnan(near)) {
    for (std::size_t i = 1; i + 1 < x.size(); ++i)
      if (amplitude[i] >= amplitude[i - 1] && amplitude[i] >= amplitude[i + 1] &&
          (best == kNpos || amplitude[i] > amplitude[best]))
        best = i;
  } else {
    for (const signal::PeakIndex& p : signal::find_peaks(amplitude, 0.0))
      if (best == kNpos || std::abs(x[p.index] - near) < std::abs(x[best] - near)) best = p.index;
  }
  if (best == kNpos || amplitude[best] <= 0.0)
    throw InputError(SourceLocation{}, "response", "a resonance peak inside the data range",
                     "no interior maximum", "extend the sweep across the resonance");
  return from_half_power(x, amplitude, best);
}

std::vector<PeakComparison> compare_peaks(std::span<const double> measured_x,
                                          std::span<const double> measured_amplitude,
                                          std::span<const double> computed_x,
                                          std::span<const double> computed_amplitude,
                                          const CorrelationOptions& options) {
  check_curve(measured_x, measured_amplitude, "measured");
  check_curve(computed_x, computed_amplitude, "computed");
  if (!(options.min_prominence_db >= 0.0) || options.max_peaks == 0)
    throw InputError(SourceLocation{}, "correlation", "min_prominence_db >= 0 and max_peaks >= 1",
                     fmt::format("{} dB, {} peaks", options.min_prominence_db, options.max_peaks));
  std::vector<signal::PeakIndex> peaks =
      signal::find_peaks(to_db(measured_amplitude), options.min_prominence_db);
  std::sort(peaks.begin(), peaks.end(), [](const signal::PeakIndex& a, const signal::PeakIndex& b) {
    return a.prominence > b.prominence;
  });
  if (peaks.size() > options.max_peaks) peaks.resize(options.max_peaks);
  std::sort(peaks.begin(), peaks.end(), [](const signal::PeakIndex& a, const signal::PeakIndex& b) {
    return a.index < b.index;
  });
  const std::vector<signal::PeakIndex> computed_peaks = signal::find_peaks(computed_amplitude, 0.0);
  std::vector<PeakComparison> out;
  for (const signal::PeakIndex& p : peaks) {
    PeakComparison c;
    c.measured = from_half_power(measured_x, measured_amplitude, p.index);
    std::size_t best = kNpos;
    for (const signal::PeakIndex& q : computed_peaks)
      if (best == kNpos ||
          std::abs(computed_x[q.index] - c.measured.x) < std::abs(computed_x[best] - c.measured.x))
        best = q.index;
    if (best != kNpos) {
      c.computed = from_half_power(computed_x, computed_amplitude, best);
      c.x_mismatch = relative(c.computed.x, c.measured.x);
      c.amplitude_mismatch = relative(c.computed.amplitude, c.measured.amplitude);
      c.q_mismatch = relative(c.computed.q_factor, c.measured.q_factor);
    }
    out.push_back(c);
  }
  return out;
}

Table correlation_table(const std::vector<PeakComparison>& peaks, ResponseAbscissa abscissa,
                        const std::string& amplitude_unit, std::string name) {
  Table t;
  t.name = std::move(name);
  t.title = "Measured versus computed resonance peaks";
  const bool rpm = abscissa == ResponseAbscissa::SpeedRpm;
  const std::string xs = rpm ? "speed_rpm" : "frequency_hz";
  const std::string xu = rpm ? "rpm" : "Hz";
  const std::string as = "amplitude_" + unit_suffix(amplitude_unit);
  auto column = [&](const std::string& n, const std::string& unit, auto field) {
    std::vector<double> v;
    for (const PeakComparison& p : peaks) v.push_back(field(p));
    t.add(n, unit, std::move(v));
  };
  std::vector<double> index;
  for (std::size_t i = 0; i < peaks.size(); ++i) index.push_back(static_cast<double>(i + 1));
  t.add("peak", "", std::move(index));
  column("measured_" + xs, xu, [](const PeakComparison& p) { return p.measured.x; });
  column("computed_" + xs, xu, [](const PeakComparison& p) { return p.computed.x; });
  column("x_mismatch_pct", "%", [](const PeakComparison& p) { return 100.0 * p.x_mismatch; });
  column("measured_" + as, amplitude_unit,
         [](const PeakComparison& p) { return p.measured.amplitude; });
  column("computed_" + as, amplitude_unit,
         [](const PeakComparison& p) { return p.computed.amplitude; });
  column("amplitude_mismatch_pct", "%",
         [](const PeakComparison& p) { return 100.0 * p.amplitude_mismatch; });
  column("measured_q", "", [](const PeakComparison& p) { return p.measured.q_factor; });
  column("computed_q", "", [](const PeakComparison& p) { return p.computed.q_factor; });
  column("q_mismatch_pct", "%", [](const PeakComparison& p) { return 100.0 * p.q_mismatch; });
  return t;
}

ForceScaling scale_force_to_peak(const PeakComparison& peak, double force_used_n) {
  if (!(std::isfinite(force_used_n) && force_used_n > 0.0))
    throw InputError(SourceLocation{}, "force_used_n",
                     "the harmonic force of the computation, > 0 N",
                     fmt::format("{}", force_used_n));
  if (!(peak.measured.amplitude > 0.0) || !(peak.computed.amplitude > 0.0))
    throw InputError(SourceLocation{}, "peak", "a measured and a computed peak amplitude > 0",
                     fmt::format("{} and {}", peak.measured.amplitude, peak.computed.amplitude));
  ForceScaling s;
  s.scale = peak.measured.amplitude / peak.computed.amplitude;
  s.implied_force_n = s.scale * force_used_n;
  return s;
}

}  // namespace geardyn::gear
