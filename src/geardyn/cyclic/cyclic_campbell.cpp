#include "geardyn/cyclic/cyclic_campbell.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::cyclic {

std::vector<int> engine_orders(int h, int N, int max_order) {
  if (N < 2) throw InputError({}, "cyclic.campbell.n_sectors", "N >= 2", std::to_string(N));
  if (h < 0 || h > N / 2)
    throw InputError({}, "cyclic.campbell.nodal_diameter", fmt::format("0..{}", N / 2),
                     std::to_string(h));
  if (max_order < 1)
    throw InputError({}, "cyclic.campbell.max_engine_order", ">= 1", std::to_string(max_order));
  std::vector<int> out;
  for (int k = 1; k <= max_order; ++k) {
    const int r = k % N;
    if (r == h || r == (N - h) % N) out.push_back(k);
  }
  return out;
}

std::vector<ModeFrequencyLine> frequency_lines(const CyclicModesResult& modes) {
  std::vector<ModeFrequencyLine> out;
  for (const auto& d : modes.diameters)
    for (Eigen::Index j = 0; j < d.frequency_hz.size(); ++j)
      out.push_back({d.nodal_diameter, static_cast<int>(j + 1), {d.frequency_hz[j]}});
  return out;
}

Table cyclic_campbell(const std::vector<ModeFrequencyLine>& lines,
                      const CyclicCampbellOptions& options) {
  const int N = options.n_sectors;
  if (N < 2) throw InputError({}, "cyclic.campbell.n_sectors", "N >= 2", std::to_string(N));
  if (options.max_engine_order < 0)
    throw InputError({}, "cyclic.campbell.max_engine_order", ">= 0 (0: 2 N)",
                     std::to_string(options.max_engine_order));
  const int max_order = options.max_engine_order > 0 ? options.max_engine_order : 2 * N;
  const auto& speeds = options.speeds_rpm;
  for (std::size_t i = 0; i < speeds.size(); ++i)
    if (!std::isfinite(speeds[i]) || speeds[i] < 0.0 || (i > 0 && !(speeds[i] > speeds[i - 1])))
      throw InputError({}, "cyclic.campbell.speeds_rpm", "finite, >= 0 and ascending",
                       fmt::format("{} at position {}", speeds[i], i));

  struct Row {
    int h, mode, k;
    std::string branch;
    double f, rpm;
  };
  std::vector<Row> rows;
  for (std::size_t li = 0; li < lines.size(); ++li) {
    const auto& line = lines[li];
    const std::string where = fmt::format("cyclic.campbell.lines[{}]", li);
    const auto& f = line.frequency_hz;
    if (f.size() != 1 && f.size() != speeds.size())
      throw InputError({}, where + ".frequency_hz",
                       fmt::format("1 value or one per speed ({})", speeds.size()),
                       fmt::format("{} values", f.size()));
    for (double v : f)
      if (!std::isfinite(v) || v < 0.0)
        throw InputError({}, where + ".frequency_hz", "finite frequencies >= 0",
                         fmt::format("{}", v));
    for (int k : engine_orders(line.nodal_diameter, N, max_order)) {
      const std::string branch = (k % N == line.nodal_diameter) ? "h+mN" : "mN-h";
      if (f.size() == 1) {
        if (f[0] > 0.0)
          rows.push_back(
              {line.nodal_diameter, line.mode, k, branch, f[0], units::hz_to_rpm(f[0]) / k});
        continue;
      }
      // g(speed) = f(speed) - k speed / 60; a sign change between two speeds is a crossing.
      for (std::size_t i = 0; i + 1 < speeds.size(); ++i) {
        const double g0 = f[i] - units::rpm_to_hz(k * speeds[i]),
                     g1 = f[i + 1] - units::rpm_to_hz(k * speeds[i + 1]);
        if (g0 == 0.0) {
          rows.push_back({line.nodal_diameter, line.mode, k, branch, f[i], speeds[i]});
        } else if ((g0 > 0.0 && g1 < 0.0) || (g0 < 0.0 && g1 > 0.0)) {
          const double t = g0 / (g0 - g1);
          rows.push_back({line.nodal_diameter, line.mode, k, branch, f[i] + t * (f[i + 1] - f[i]),
                          speeds[i] + t * (speeds[i + 1] - speeds[i])});
        }
      }
      if (f.back() - units::rpm_to_hz(k * speeds.back()) == 0.0)
        rows.push_back({line.nodal_diameter, line.mode, k, branch, f.back(), speeds.back()});
    }
  }
  std::stable_sort(rows.begin(), rows.end(),
                   [](const Row& a, const Row& b) { return a.rpm < b.rpm; });

  Table t;
  t.name = "cyclic_campbell";
  t.title = fmt::format("Resonances with engine orders up to {} (rotating frame, {} sectors)",
                        max_order, N);
  std::vector<double> h, mode, k, fr, rpm;
  std::vector<std::string> branch;
  for (const auto& r : rows) {
    h.push_back(r.h);
    mode.push_back(r.mode);
    k.push_back(r.k);
    branch.push_back(r.branch);
    fr.push_back(r.f);
    rpm.push_back(r.rpm);
  }
  t.add("nodal_diameter", "", h);
  t.add("mode", "", mode);
  t.add("engine_order", "", k);
  t.add_text("branch", branch);
  t.add("frequency_hz", "Hz", fr);
  t.add("resonance_speed_rpm", "rpm", rpm);
  return t;
}

}  // namespace geardyn::cyclic
