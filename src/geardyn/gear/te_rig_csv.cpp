#include "geardyn/gear/te_rig_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <utility>

#include "geardyn/core/text.hpp"
#include "geardyn/gear/ste.hpp"

namespace geardyn::gear {
namespace {

constexpr std::size_t kNone = static_cast<std::size_t>(-1);
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

struct AmplitudeUnit {
  const char* suffix;
  double factor;
  bool angular;
};

constexpr AmplitudeUnit kUnits[] = {{"m", 1.0, false},   {"mm", 1e-3, false}, {"um", 1e-6, false},
                                    {"nm", 1e-9, false}, {"rad", 1.0, true},  {"mrad", 1e-3, true},
                                    {"urad", 1e-6, true}};

constexpr const char* kAmplitudeNames =
    "amplitude_0_peak_<unit> or amplitude_peak_peak_<unit>, <unit> m, mm, um, nm (along the line "
    "of action) or rad, mrad, urad (the pinion's angle)";

// The amplitude column's convention, unit factor and kind; nullopt when `name` is not one.
struct AmplitudeColumn {
  TeConvention convention;
  double factor;
  bool angular;
};
std::optional<AmplitudeColumn> amplitude_column(const std::string& name) {
  for (const auto& [prefix, convention] :
       {std::pair{std::string_view("amplitude_0_peak_"), TeConvention::ZeroPeak},
        std::pair{std::string_view("amplitude_peak_peak_"), TeConvention::PeakPeak}}) {
    if (!name.starts_with(prefix)) continue;
    const std::string_view unit = std::string_view(name).substr(prefix.size());
    for (const AmplitudeUnit& u : kUnits)
      if (unit == u.suffix) return AmplitudeColumn{convention, u.factor, u.angular};
  }
  return std::nullopt;
}

}  // namespace

double TeRigFile::zero_peak_m(std::size_t i, double radius_m) const {
  const double a = points.at(i).amplitude * (angular ? radius_m : 1.0);
  return convention == TeConvention::PeakPeak ? 0.5 * a : a;
}

TeRigFile parse_te_rig_csv(std::string_view text, const std::string& file_name) {
  const NumericCsv csv = parse_numeric_csv(text, file_name, 1);
  TeRigFile f;
  f.source = file_name;
  std::size_t torque = kNone, order = kNone, amplitude = kNone;
  double factor = 1.0;
  for (std::size_t i = 0; i < csv.names.size(); ++i) {
    const std::string n = lower(csv.names[i]);
    std::size_t* slot = nullptr;
    if (n == "torque_nm") {
      slot = &torque;
    } else if (n == "mesh_order") {
      slot = &order;
    } else if (const auto a = amplitude_column(n)) {
      slot = &amplitude;
      f.convention = a->convention;
      f.angular = a->angular;
      factor = a->factor;
      f.amplitude_column = csv.names[i];
    } else {
      throw InputError(csv.at_header(i), csv.names[i],
                       fmt::format("torque_nm, mesh_order and one {}", kAmplitudeNames),
                       fmt::format("'{}'", shorten(csv.names[i], 43)),
                       "the column names carry the quantity, the convention and the unit "
                       "(docs/input-files.md)");
    }
    if (*slot != kNone)
      throw InputError(csv.at_header(i), csv.names[i], "each quantity in one column",
                       fmt::format("a second one (after '{}')", csv.names[*slot]));
    *slot = i;
  }
  const SourceLocation header{csv.file, csv.header_line, 1};
  if (torque == kNone) throw InputError(header, "header", "a torque_nm column", "none");
  if (order == kNone) throw InputError(header, "header", "a mesh_order column", "none");
  if (amplitude == kNone)
    throw InputError(header, "header", fmt::format("an amplitude column: {}", kAmplitudeNames),
                     "none");
  std::map<std::pair<double, int>, int> seen;  // (torque, order) -> line
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const std::vector<double>& row = csv.rows[r];
    if (!(row[torque] > 0.0))
      throw InputError(csv.at(r, torque), csv.names[torque], "a torque > 0 [N m]",
                       fmt::format("{}", row[torque]));
    const double k = row[order];
    if (!(k >= 1.0 && k <= 1e6 && k == std::round(k)))
      throw InputError(csv.at(r, order), csv.names[order], "an integer mesh order >= 1",
                       fmt::format("{}", k));
    if (!(row[amplitude] > 0.0))
      throw InputError(csv.at(r, amplitude), csv.names[amplitude],
                       "an amplitude > 0 (a dB comparison needs it; the phase is not read)",
                       fmt::format("{}", row[amplitude]));
    TeRigPoint p{row[torque], static_cast<int>(k), row[amplitude] * factor, csv.row_lines[r]};
    const auto [it, fresh] = seen.emplace(std::pair{p.torque_nm, p.mesh_order}, p.line);
    if (!fresh)
      throw InputError(csv.at(r, torque), csv.names[torque], "each (torque_nm, mesh_order) once",
                       fmt::format("{} N m, order {}: a repeat of line {}", p.torque_nm,
                                   p.mesh_order, it->second));
    f.points.push_back(p);
  }
  return f;
}

TeRigFile read_te_rig_csv(const std::filesystem::path& path) {
  const std::optional<std::string> text = try_read_file(path);
  if (!text)
    throw InputError(SourceLocation{path.string(), 0, 0}, "measured_te_file", "a readable CSV file",
                     "a file that cannot be opened");
  return parse_te_rig_csv(*text, path.string());
}

const char* to_string(TeMatch m) {
  switch (m) {
    case TeMatch::Computed:
      return "computed torque";
    case TeMatch::Interpolated:
      return "interpolated over torque";
    case TeMatch::OutsideTorques:
      return "not compared: torque outside the computed torques";
    case TeMatch::AboveOrders:
      return "not compared: order above the computed orders";
  }
  return "";
}

double interpolate_in_range(std::span<const double> x, std::span<const double> y, double xq,
                            double rel_tol) {
  if (x.empty() || x.size() != y.size()) return kNaN;
  const double tol = rel_tol * std::max(x.back() - x.front(), std::abs(x.back()));
  if (xq < x.front() - tol || xq > x.back() + tol) return kNaN;
  if (xq <= x.front()) return y.front();
  if (xq >= x.back()) return y.back();
  const auto hi = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), xq) - x.begin());
  const std::size_t lo = hi - 1;
  const double f = (xq - x[lo]) / (x[hi] - x[lo]);
  return y[lo] + f * (y[hi] - y[lo]);
}

namespace {

// Fills the summary of `c` over its compared rows.
void summarise(TeComparison& c) {
  double sum_ratio = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  c.compared = 0;
  c.max_abs_db = 0.0;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    const TeComparisonRow& r = c.rows[i];
    if (!r.compared()) continue;
    ++c.compared;
    sum_ratio += r.ratio;
    if (std::abs(r.difference_db) >= c.max_abs_db) {
      c.max_abs_db = std::abs(r.difference_db);
      c.max_db_row = i;
    }
    sx += r.computed_m;
    sy += r.measured_m;
    sxx += r.computed_m * r.computed_m;
    sxy += r.computed_m * r.measured_m;
  }
  const auto n = static_cast<double>(c.compared);
  c.mean_ratio = c.compared > 0 ? sum_ratio / n : kNaN;
  if (c.compared == 0) c.max_abs_db = kNaN;
  const double det = n * sxx - sx * sx;
  if (c.compared >= 2 && det > 1e-12 * n * sxx) {
    c.fit_gain = (n * sxy - sx * sy) / det;
    c.fit_offset_m = (sy - c.fit_gain * sx) / n;
  } else {
    c.fit_gain = c.fit_offset_m = kNaN;
  }
}

}  // namespace

TeComparison compare_te(const TeRigFile& rig, std::span<const double> torques_nm,
                        const std::vector<std::vector<double>>& harmonics_m, double radius_m) {
  TeComparison c;
  c.rig = rig;
  c.radius_m = radius_m;
  const std::size_t orders = harmonics_m.empty() ? 0 : harmonics_m.front().size();
  for (std::size_t i = 0; i < rig.points.size(); ++i) {
    const TeRigPoint& p = rig.points[i];
    TeComparisonRow r;
    r.torque_nm = p.torque_nm;
    r.mesh_order = p.mesh_order;
    r.line = p.line;
    r.measured_m = rig.zero_peak_m(i, radius_m);
    r.computed_m = r.ratio = r.difference_db = kNaN;
    if (static_cast<std::size_t>(p.mesh_order) > orders) {
      r.match = TeMatch::AboveOrders;
    } else {
      std::vector<double> a;
      for (const auto& h : harmonics_m) a.push_back(h[static_cast<std::size_t>(p.mesh_order - 1)]);
      r.computed_m = interpolate_in_range(torques_nm, a, p.torque_nm);
      const bool at = std::any_of(torques_nm.begin(), torques_nm.end(), [&](double t) {
        return std::abs(t - p.torque_nm) <= 1e-9 * std::abs(t);
      });
      r.match = std::isnan(r.computed_m) ? TeMatch::OutsideTorques
                : at                     ? TeMatch::Computed
                                         : TeMatch::Interpolated;
      if (r.compared()) {
        r.ratio = r.measured_m / r.computed_m;
        r.difference_db = 20.0 * std::log10(r.ratio);
      }
    }
    c.rows.push_back(r);
  }
  summarise(c);
  return c;
}

}  // namespace geardyn::gear
