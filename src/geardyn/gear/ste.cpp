#include "geardyn/gear/ste.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <utility>

#include "geardyn/core/text.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::gear {
namespace {

constexpr std::size_t kNpos = static_cast<std::size_t>(-1);

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

// Whole-string parse of a finite double; from_chars rejects leading '+', so allow it by hand.
bool parse_double(std::string_view s, double& value) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const char* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

// A cell or column name quoted in a message: at most 43 bytes, control and non-ASCII bytes
// shown as '?'.
std::string quoted_cell(std::string_view s) {
  std::string out = shorten(s, 43);
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  return "'" + out + "'";
}

// --- units ---------------------------------------------------------------------------------

struct ValueUnit {
  double factor = 1.0;  // to rad or m
  bool angular = false;
};

bool value_unit(std::string_view name, ValueUnit& unit) {
  const std::string u = lower(name);
  if (u == "rad")
    unit = {1.0, true};
  else if (u == "mrad")
    unit = {1e-3, true};
  else if (u == "urad")
    unit = {1e-6, true};
  else if (u == "deg")
    unit = {units::kPi / 180.0, true};
  else if (u == "arcsec")
    unit = {units::kPi / (180.0 * 3600.0), true};
  else if (u == "m")
    unit = {1.0, false};
  else if (u == "mm")
    unit = {1e-3, false};
  else if (u == "um")
    unit = {1e-6, false};
  else if (u == "nm")
    unit = {1e-9, false};
  else
    return false;
  return true;
}

constexpr const char* kValueUnits = "rad, mrad, urad, deg, arcsec, m, mm, um or nm";

enum class Abscissa { AngleRad, AngleDeg, TimeS, TimeMs };

// A value column of the header: the STE at one torque, or the unloaded TE.
struct ValueColumn {
  std::size_t index = 0;
  ValueUnit unit;
  double torque_nm = SteCurve::kNaN;
};

// "200Nm", "1.5kNm" -> N m.
bool parse_torque_label(std::string_view label, double& torque_nm) {
  const std::string l = lower(label);
  double scale = 0.0;
  std::string_view number;
  if (l.size() > 3 && l.ends_with("knm")) {
    scale = 1e3;
    number = std::string_view(label).substr(0, label.size() - 3);
  } else if (l.size() > 2 && l.ends_with("nm")) {
    scale = 1.0;
    number = std::string_view(label).substr(0, label.size() - 2);
  } else {
    return false;
  }
  double t = 0.0;
  if (!parse_double(number, t) || t < 0.0) return false;
  torque_nm = t * scale;
  return true;
}

// One cycle of data: abscissa as cycle fraction in [0, 1], values in metres.
struct CycleData {
  std::vector<double> u;
  std::vector<double> ste;
  std::vector<double> geometric;  // empty when none
  double torque_nm = SteCurve::kNaN;
};

double interpolate_knots(const std::vector<double>& u, const std::vector<double>& y, double x,
                         SteInterpolation interpolation) {
  // u increasing from 0 to 1 inclusive (the last knot closes the cycle). A point on a knot up to
  // the rounding of the abscissa (10.8 deg / 18 deg = 0.6000000000000001 against the grid point
  // 6 / 10) belongs to that knot: otherwise Hold would return the previous row's value.
  constexpr double kKnotTolerance = 1e-9;  // of a mesh cycle
  const auto it = std::upper_bound(u.begin(), u.end(), x + kKnotTolerance);
  std::size_t j = it == u.begin() ? 0 : static_cast<std::size_t>(it - u.begin()) - 1;
  if (j >= u.size() - 1) j = u.size() - 2;
  if (interpolation == SteInterpolation::Hold) return y[j];
  const double t = (x - u[j]) / (u[j + 1] - u[j]);
  return y[j] + t * (y[j + 1] - y[j]);
}

}  // namespace

// --- NumericCsv ------------------------------------------------------------------------------

SourceLocation NumericCsv::at(std::size_t row, std::size_t column) const {
  return SourceLocation{file, row_lines.at(row), cell_columns.at(row).at(column)};
}

SourceLocation NumericCsv::at_header(std::size_t column) const {
  return SourceLocation{file, header_line, name_columns.at(column)};
}

std::size_t NumericCsv::find(std::string_view name) const {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return i;
  return kNpos;
}

NumericCsv parse_numeric_csv(std::string_view text, const std::string& file_name,
                             std::size_t min_rows) {
  NumericCsv csv;
  csv.file = file_name;
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  int line_number = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    const std::string_view content = trim(line);
    if (content.empty() || content.front() == '#') {
      if (end == text.size()) break;
      continue;
    }
    // Split on commas, remembering where each field starts (1-based character column).
    std::vector<std::string_view> fields;
    std::vector<int> columns;
    std::size_t field_start = 0;
    for (std::size_t i = 0; i <= line.size(); ++i) {
      if (i == line.size() || line[i] == ',') {
        const std::string_view raw = line.substr(field_start, i - field_start);
        const std::string_view field = trim(raw);
        const std::size_t lead =
            field.empty() ? 0 : static_cast<std::size_t>(field.data() - raw.data());
        fields.push_back(field);
        columns.push_back(static_cast<int>(field_start + lead + 1));
        field_start = i + 1;
      }
    }
    if (csv.names.empty()) {
      csv.header_line = line_number;
      for (std::size_t i = 0; i < fields.size(); ++i) {
        const SourceLocation where{file_name, line_number, columns[i]};
        if (fields[i].empty())
          throw InputError(where, fmt::format("header[{}]", i + 1), "a column name with its unit",
                           "an empty name");
        const std::string name(fields[i]);
        if (std::find(csv.names.begin(), csv.names.end(), name) != csv.names.end())
          throw InputError(where, name, "each column name once",
                           "a repeated name " + quoted_cell(name));
        csv.names.push_back(name);
        csv.name_columns.push_back(columns[i]);
      }
    } else {
      if (fields.size() != csv.names.size())
        throw InputError(
            SourceLocation{file_name, line_number, 1}, fmt::format("row {}", line_number),
            fmt::format("{} comma-separated values (one per header column)", csv.names.size()),
            fmt::format("{} values", fields.size()));
      std::vector<double> row(fields.size());
      for (std::size_t i = 0; i < fields.size(); ++i)
        if (!parse_double(fields[i], row[i]))
          throw InputError(SourceLocation{file_name, line_number, columns[i]}, csv.names[i],
                           "a finite number",
                           fields[i].empty() ? "an empty cell" : quoted_cell(fields[i]));
      csv.rows.push_back(std::move(row));
      csv.row_lines.push_back(line_number);
      csv.cell_columns.push_back(std::move(columns));
    }
    if (end == text.size()) break;
  }
  if (csv.names.empty())
    throw InputError(SourceLocation{file_name, 0, 0}, "header", "a header line naming the columns",
                     "no data");
  if (csv.rows.size() < min_rows)
    throw InputError(
        SourceLocation{file_name, csv.rows.empty() ? csv.header_line : csv.row_lines.back(), 0},
        "rows", fmt::format("at least {} data rows", min_rows),
        fmt::format("{} rows", csv.rows.size()));
  return csv;
}

// --- SteCurve --------------------------------------------------------------------------------

SteCurve SteCurve::from_samples(std::vector<double> ste_m, SteInterpolation interpolation,
                                std::vector<double> geometric_te_m, double torque_nm) {
  const SourceLocation nowhere{};
  if (ste_m.size() < 2)
    throw InputError(nowhere, "ste", "at least 2 samples over one mesh period",
                     fmt::format("{} samples", ste_m.size()));
  const bool has_geometric = !geometric_te_m.empty();
  if (has_geometric && geometric_te_m.size() != ste_m.size())
    throw InputError(nowhere, "geometric_te", fmt::format("{} samples (as the STE)", ste_m.size()),
                     fmt::format("{} samples", geometric_te_m.size()));
  if (!has_geometric) geometric_te_m.assign(ste_m.size(), 0.0);
  if (!(std::isnan(torque_nm) || (std::isfinite(torque_nm) && torque_nm >= 0.0)))
    throw InputError(nowhere, "torque", "a torque >= 0 N m or none", fmt::format("{}", torque_nm));
  for (std::size_t j = 0; j < ste_m.size(); ++j) {
    if (!std::isfinite(ste_m[j]) || !std::isfinite(geometric_te_m[j]))
      throw InputError(nowhere, fmt::format("ste[{}]", j), "a finite length in metres",
                       fmt::format("{} (geometric {})", ste_m[j], geometric_te_m[j]));
    const double elastic = ste_m[j] - geometric_te_m[j];
    if (!(elastic > 0.0))
      throw InputError(
          nowhere, fmt::format("ste[{}]", j),
          "an elastic STE e - e_g > 0 (mesh stiffness F_s / (e - e_g) positive and finite)",
          fmt::format("e = {} m, e_g = {} m", ste_m[j], geometric_te_m[j]),
          "the STE is the loaded deflection along the line of action, positive");
  }
  SteCurve curve;
  curve.ste_m_ = std::move(ste_m);
  curve.geometric_m_ = std::move(geometric_te_m);
  curve.has_geometric_ = has_geometric;
  curve.interpolation_ = interpolation;
  curve.torque_nm_ = torque_nm;
  return curve;
}

double SteCurve::evaluate(const std::vector<double>& v, double u) const {
  const std::size_t n = v.size();
  u -= std::floor(u);
  const double pos = u * static_cast<double>(n);
  std::size_t j = static_cast<std::size_t>(pos);
  if (j >= n) j = n - 1;
  if (interpolation_ == SteInterpolation::Hold) return v[j];
  const double t = pos - static_cast<double>(j);
  return v[j] + t * (v[(j + 1) % n] - v[j]);
}

double SteCurve::mean_elastic_m() const {
  // Both interpolations have the sample mean as their cycle mean (periodic trapezoid = mean).
  double sum = 0.0;
  for (std::size_t j = 0; j < size(); ++j) sum += ste_m_[j] - geometric_m_[j];
  return sum / static_cast<double>(size());
}

double SteCurve::mean_inverse_elastic_per_m() const {
  const std::size_t n = size();
  double sum = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double d0 = ste_m_[j] - geometric_m_[j];
    if (interpolation_ == SteInterpolation::Hold) {
      sum += 1.0 / d0;
      continue;
    }
    const double d1 = ste_m_[(j + 1) % n] - geometric_m_[(j + 1) % n];
    // mean of 1 / (d0 + (d1 - d0) t) over t in [0, 1] = ln(d1 / d0) / (d1 - d0); log1p keeps it
    // accurate when d1 ~ d0.
    const double r = (d1 - d0) / d0;
    sum += std::abs(r) < 1e-12 ? 1.0 / d0 * (1.0 - 0.5 * r) : std::log1p(r) / (d1 - d0);
  }
  return sum / static_cast<double>(n);
}

SteCurve SteCurve::shifted(double shift, std::size_t samples) const {
  if (!std::isfinite(shift))
    throw InputError(SourceLocation{}, "shift", "a finite fraction of the mesh cycle",
                     fmt::format("{}", shift));
  if (samples == 0) samples = size();
  if (samples < 2)
    throw InputError(SourceLocation{}, "samples", "at least 2 samples", fmt::format("{}", samples));
  std::vector<double> e(samples), g(samples);
  for (std::size_t j = 0; j < samples; ++j) {
    const double u = static_cast<double>(j) / static_cast<double>(samples) + shift;
    e[j] = ste_at(u);
    g[j] = geometric_at(u);
  }
  return from_samples(std::move(e), interpolation_,
                      has_geometric_ ? std::move(g) : std::vector<double>{}, torque_nm_);
}

// --- SteTable --------------------------------------------------------------------------------

SteCurve SteTable::at_torque(double torque_nm, bool allow_extrapolation) const {
  const SourceLocation where{source, 0, 0};
  if (curves.empty()) throw InputError(where, "ste", "at least one STE curve", "none");
  if (!std::isfinite(torque_nm) || torque_nm < 0.0)
    throw InputError(where, "torque", "a finite torque >= 0 N m", fmt::format("{}", torque_nm));
  if (curves.size() == 1) {
    const double t0 = curves[0].torque_nm();
    if (std::isnan(t0) || t0 == torque_nm) return curves[0];
    if (!allow_extrapolation)
      throw InputError(where, "torque", fmt::format("the torque of the only STE curve, {} N m", t0),
                       fmt::format("{} N m", torque_nm),
                       "give STE curves at several torques, or allow extrapolation");
    // One curve and extrapolation: scale the elastic part with the torque (linear mesh).
    const double s = torque_nm / t0;
    std::vector<double> e(curves[0].size());
    for (std::size_t j = 0; j < e.size(); ++j)
      e[j] = curves[0].geometric_te_m()[j] +
             s * (curves[0].ste_m()[j] - curves[0].geometric_te_m()[j]);
    return SteCurve::from_samples(
        std::move(e), curves[0].interpolation(),
        curves[0].has_geometric_te() ? curves[0].geometric_te_m() : std::vector<double>{},
        torque_nm);
  }
  for (std::size_t i = 1; i < curves.size(); ++i)
    if (!(curves[i].torque_nm() > curves[i - 1].torque_nm()))
      throw InputError(
          where, "torque", "STE curves at strictly increasing, known torques",
          fmt::format("{} N m after {} N m", curves[i].torque_nm(), curves[i - 1].torque_nm()));
  const double lo = curves.front().torque_nm(), hi = curves.back().torque_nm();
  if ((torque_nm < lo || torque_nm > hi) && !allow_extrapolation)
    throw InputError(where, "torque",
                     fmt::format("a torque within the STE data, [{}, {}] N m", lo, hi),
                     fmt::format("{} N m", torque_nm),
                     "add an STE curve at that torque, or allow extrapolation");
  std::size_t i = 1;
  while (i + 1 < curves.size() && torque_nm > curves[i].torque_nm()) ++i;
  const SteCurve& a = curves[i - 1];
  const SteCurve& b = curves[i];
  if (torque_nm == a.torque_nm()) return a;
  if (torque_nm == b.torque_nm()) return b;
  const std::size_t n = std::max(a.size(), b.size());
  const SteCurve ra = a.size() == n ? a : a.resampled(n);
  const SteCurve rb = b.size() == n ? b : b.resampled(n);
  const double w = (torque_nm - a.torque_nm()) / (b.torque_nm() - a.torque_nm());
  std::vector<double> e(n), g(n);
  for (std::size_t j = 0; j < n; ++j) {
    e[j] = (1.0 - w) * ra.ste_m()[j] + w * rb.ste_m()[j];
    g[j] = (1.0 - w) * ra.geometric_te_m()[j] + w * rb.geometric_te_m()[j];
    if (!(e[j] - g[j] > 0.0))
      throw InputError(where, fmt::format("ste@{}Nm[{}]", torque_nm, j),
                       "an interpolated elastic STE e - e_g > 0", fmt::format("{} m", e[j] - g[j]),
                       "the torque lies too far outside the data to extrapolate");
  }
  const bool geometric = a.has_geometric_te() || b.has_geometric_te();
  return SteCurve::from_samples(std::move(e), a.interpolation(),
                                geometric ? std::move(g) : std::vector<double>{}, torque_nm);
}

// --- reading ---------------------------------------------------------------------------------

void SteReadOptions::validate() const {
  const SourceLocation nowhere{};
  if (teeth < 0)
    throw InputError(nowhere, "ste_options.teeth", "a tooth count >= 1 (0: not given)",
                     fmt::format("{}", teeth));
  if (!(std::isnan(mesh_period_s) || (std::isfinite(mesh_period_s) && mesh_period_s > 0.0)))
    throw InputError(nowhere, "ste_options.mesh_period_s", "a period > 0 s (NaN: not given)",
                     fmt::format("{}", mesh_period_s));
  if (!(std::isnan(base_radius_m) || (std::isfinite(base_radius_m) && base_radius_m > 0.0)))
    throw InputError(nowhere, "ste_options.base_radius_m", "a radius > 0 m (NaN: not given)",
                     fmt::format("{}", base_radius_m));
  if (!(period_tolerance >= 0.0 && period_tolerance < 0.5))
    throw InputError(nowhere, "ste_options.period_tolerance", "a relative tolerance in [0, 0.5)",
                     fmt::format("{}", period_tolerance));
  if (!(shift >= 0.0 && shift < 1.0))
    throw InputError(nowhere, "ste_options.shift", "a fraction of the mesh cycle in [0, 1)",
                     fmt::format("{}", shift));
  if (samples == 1)
    throw InputError(nowhere, "ste_options.samples", "0 (as read) or at least 2", "1");
}

namespace {

struct Header {
  Abscissa abscissa = Abscissa::AngleRad;
  std::vector<ValueColumn> ste;  // wide layout: one per torque
  bool has_geometric = false;
  ValueColumn geometric;
  bool long_layout = false;
  std::size_t torque_index = 0;
  double torque_scale = 1.0;
};

Header parse_header(const NumericCsv& csv) {
  Header h;
  const std::string first = lower(csv.names[0]);
  if (first == "angle_rad")
    h.abscissa = Abscissa::AngleRad;
  else if (first == "angle_deg")
    h.abscissa = Abscissa::AngleDeg;
  else if (first == "time_s")
    h.abscissa = Abscissa::TimeS;
  else if (first == "time_ms")
    h.abscissa = Abscissa::TimeMs;
  else
    throw InputError(csv.at_header(0), "header[1]",
                     "angle_rad, angle_deg, time_s or time_ms as the first column",
                     quoted_cell(csv.names[0]),
                     "the first column is the position in the mesh cycle");
  bool plain_ste = false;
  for (std::size_t i = 1; i < csv.names.size(); ++i) {
    const std::string& name = csv.names[i];
    const std::string l = lower(name);
    if (l == "torque_nm" || l == "torque_knm") {
      if (h.long_layout)
        throw InputError(csv.at_header(i), name, "one torque column", "a second one");
      h.long_layout = true;
      h.torque_index = i;
      h.torque_scale = l == "torque_knm" ? 1e3 : 1.0;
      continue;
    }
    if (l.starts_with("geometric_te_")) {
      ValueColumn c;
      c.index = i;
      if (!value_unit(std::string_view(name).substr(13), c.unit))
        throw InputError(csv.at_header(i), name,
                         fmt::format("geometric_te_<unit>, unit {}", kValueUnits),
                         quoted_cell(name));
      if (h.has_geometric)
        throw InputError(csv.at_header(i), name, "one geometric_te column", "a second one");
      h.has_geometric = true;
      h.geometric = c;
      continue;
    }
    if (l.starts_with("ste_")) {
      ValueColumn c;
      c.index = i;
      const std::string_view rest = std::string_view(name).substr(4);
      const std::size_t at = rest.find('@');
      if (!value_unit(rest.substr(0, at), c.unit))
        throw InputError(csv.at_header(i), name,
                         fmt::format("ste_<unit>[@<torque>Nm], unit {}", kValueUnits),
                         quoted_cell(name));
      if (at != std::string_view::npos) {
        if (!parse_torque_label(rest.substr(at + 1), c.torque_nm))
          throw InputError(csv.at_header(i), name,
                           "a torque label such as @200Nm or @1.5kNm (>= 0)",
                           quoted_cell(rest.substr(at + 1)));
        for (const ValueColumn& other : h.ste)
          if (other.torque_nm == c.torque_nm)
            throw InputError(csv.at_header(i), name, "each torque once",
                             fmt::format("a second column at {} N m", c.torque_nm));
      } else {
        plain_ste = true;
      }
      h.ste.push_back(c);
      continue;
    }
    throw InputError(csv.at_header(i), name,
                     "ste_<unit>[@<torque>Nm], geometric_te_<unit>, torque_nm or torque_knm",
                     quoted_cell(name), "the column names carry the quantity and its unit");
  }
  if (h.ste.empty())
    throw InputError(csv.at_header(0), "header", "at least one ste_<unit> column", "none");
  if (plain_ste && h.ste.size() > 1)
    throw InputError(csv.at_header(h.ste[1].index), csv.names[h.ste[1].index],
                     "either one ste_<unit> column or one ste_<unit>@<torque>Nm column per torque",
                     "a column without torque among several STE columns");
  if (h.long_layout && (h.ste.size() != 1 || !plain_ste))
    throw InputError(csv.at_header(h.torque_index), csv.names[h.torque_index],
                     "with a torque column, exactly one ste_<unit> column without @torque",
                     fmt::format("{} STE columns", h.ste.size()));
  return h;
}

double to_length(const ValueUnit& unit, double value, double base_radius_m) {
  return unit.angular ? value * unit.factor * base_radius_m : value * unit.factor;
}

// Rows [begin, end) of the csv as one cycle (abscissa to cycle fractions, values to metres).
std::vector<CycleData> read_cycle(const NumericCsv& csv, const Header& h, std::size_t begin,
                                  std::size_t end, const SteReadOptions& options) {
  const std::size_t n = end - begin;
  if (n < 3)
    throw InputError(csv.at(begin, 0), csv.names[0], "at least 3 rows per mesh cycle",
                     fmt::format("{} rows", n));
  double period = 0.0;
  switch (h.abscissa) {
    case Abscissa::AngleRad:
    case Abscissa::AngleDeg:
      if (options.teeth < 1)
        throw InputError(csv.at_header(0), csv.names[0],
                         "the tooth count (SteReadOptions::teeth) with an angle abscissa", "none",
                         "one mesh period is 2 pi / teeth");
      period = (h.abscissa == Abscissa::AngleRad ? units::kTwoPi : 360.0) / options.teeth;
      break;
    case Abscissa::TimeS:
    case Abscissa::TimeMs:
      if (std::isnan(options.mesh_period_s))
        throw InputError(csv.at_header(0), csv.names[0],
                         "the mesh period (SteReadOptions::mesh_period_s) with a time abscissa",
                         "none",
                         "one mesh period is 60 / (speed_rpm teeth) s; in a model file give the "
                         "gear pair's ste_speed_rpm, the speed of gear 1 while the STE was "
                         "recorded");
      period = options.mesh_period_s * (h.abscissa == Abscissa::TimeMs ? 1e3 : 1.0);
      break;
  }
  const double a0 = csv.rows[begin][0];
  for (std::size_t r = begin + 1; r < end; ++r)
    if (!(csv.rows[r][0] > csv.rows[r - 1][0]))
      throw InputError(csv.at(r, 0), csv.names[0], "a strictly increasing abscissa",
                       fmt::format("{} after {}", csv.rows[r][0], csv.rows[r - 1][0]));
  const double span = (csv.rows[end - 1][0] - a0) / period;
  const double closed_error = std::abs(span - 1.0);
  const double open_error =
      std::abs(span * static_cast<double>(n) / static_cast<double>(n - 1) - 1.0);
  if (std::min(closed_error, open_error) > options.period_tolerance)
    throw InputError(csv.at(end - 1, 0), csv.names[0],
                     fmt::format("rows spanning one mesh period ({} in the abscissa unit), or one "
                                 "period minus one spacing, within {:.3g} %",
                                 period, 100.0 * options.period_tolerance),
                     fmt::format("a span of {} ({:.6g} periods)", csv.rows[end - 1][0] - a0, span),
                     "check the tooth count and the angle unit; give exactly one mesh cycle");
  const bool closed = closed_error <= open_error;
  // Rescale so the cycle is exactly [0, 1]: the tolerance only absorbs rounding in the data.
  const double scale =
      closed ? 1.0 / span : static_cast<double>(n - 1) / (span * static_cast<double>(n));

  std::vector<CycleData> cycles(h.long_layout ? 1 : h.ste.size());
  for (std::size_t c = 0; c < cycles.size(); ++c) {
    CycleData& d = cycles[c];
    const ValueColumn& col = h.ste[c];
    d.torque_nm = h.long_layout ? csv.rows[begin][h.torque_index] * h.torque_scale : col.torque_nm;
    for (std::size_t r = begin; r < end; ++r) {
      d.u.push_back((csv.rows[r][0] - a0) / period * scale);
      const bool angular = col.unit.angular || (h.has_geometric && h.geometric.unit.angular);
      if (angular && std::isnan(options.base_radius_m))
        throw InputError(csv.at_header(col.unit.angular ? col.index : h.geometric.index),
                         csv.names[col.unit.angular ? col.index : h.geometric.index],
                         "the base radius (SteReadOptions::base_radius_m) for an angular STE",
                         "none",
                         "angular STE times the base radius is the STE along the line of action");
      const double e = to_length(col.unit, csv.rows[r][col.index], options.base_radius_m);
      const double g = h.has_geometric ? to_length(h.geometric.unit, csv.rows[r][h.geometric.index],
                                                   options.base_radius_m)
                                       : 0.0;
      if (!std::isfinite(e) || !std::isfinite(g) || !(e - g > 0.0))
        throw InputError(
            csv.at(r, col.index), csv.names[col.index],
            h.has_geometric ? "an STE larger than the geometric TE (e - e_g > 0)"
                            : "a positive STE",
            fmt::format("{} (as length e = {} m, e_g = {} m)", csv.rows[r][col.index], e, g),
            "k = F_s / (e - e_g) must be positive and finite");
      d.ste.push_back(e);
      if (h.has_geometric) d.geometric.push_back(g);
    }
    if (!closed) {  // the open form wraps: the cycle's end is its first sample again
      d.u.push_back(1.0);
      d.ste.push_back(d.ste.front());
      if (h.has_geometric) d.geometric.push_back(d.geometric.front());
    }
    d.u.back() = 1.0;
  }
  return cycles;
}

SteCurve to_curve(const CycleData& d, const SteReadOptions& options) {
  const std::size_t n = options.samples != 0 ? options.samples : d.u.size() - 1;
  std::vector<double> e(n), g;
  if (!d.geometric.empty()) g.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    double u = static_cast<double>(j) / static_cast<double>(n) + options.shift;
    u -= std::floor(u);
    e[j] = interpolate_knots(d.u, d.ste, u, options.interpolation);
    if (!g.empty()) g[j] = interpolate_knots(d.u, d.geometric, u, options.interpolation);
  }
  return SteCurve::from_samples(std::move(e), options.interpolation, std::move(g), d.torque_nm);
}

}  // namespace

SteTable parse_ste_csv(std::string_view text, const std::string& file_name,
                       const SteReadOptions& options) {
  options.validate();
  const NumericCsv csv = parse_numeric_csv(text, file_name, 3);
  const Header h = parse_header(csv);
  SteTable table;
  table.source = file_name;
  std::vector<CycleData> cycles;
  if (!h.long_layout) {
    cycles = read_cycle(csv, h, 0, csv.rows.size(), options);
  } else {
    std::vector<double> seen;
    std::size_t begin = 0;
    while (begin < csv.rows.size()) {
      const double torque = csv.rows[begin][h.torque_index];
      if (torque < 0.0)
        throw InputError(csv.at(begin, h.torque_index), csv.names[h.torque_index], "a torque >= 0",
                         fmt::format("{}", torque));
      if (std::find(seen.begin(), seen.end(), torque) != seen.end())
        throw InputError(csv.at(begin, h.torque_index), csv.names[h.torque_index],
                         "the rows of one torque in one contiguous block",
                         fmt::format("torque {} again after another torque", torque));
      seen.push_back(torque);
      std::size_t end = begin + 1;
      while (end < csv.rows.size() && csv.rows[end][h.torque_index] == torque) ++end;
      std::vector<CycleData> block = read_cycle(csv, h, begin, end, options);
      cycles.push_back(std::move(block.front()));
      begin = end;
    }
  }
  std::sort(cycles.begin(), cycles.end(),
            [](const CycleData& a, const CycleData& b) { return a.torque_nm < b.torque_nm; });
  std::size_t common = options.samples;
  if (common == 0)
    for (const CycleData& d : cycles) common = std::max(common, d.u.size() - 1);
  SteReadOptions resample = options;
  resample.samples = common;
  for (const CycleData& d : cycles) table.curves.push_back(to_curve(d, resample));
  return table;
}

SteTable read_ste_csv(const std::filesystem::path& path, const SteReadOptions& options) {
  const std::optional<std::string> text = try_read_file(path);
  if (!text)
    throw InputError(SourceLocation{path.string(), 0, 0}, "ste_file", "a readable CSV file",
                     "a file that cannot be opened");
  return parse_ste_csv(*text, path.string(), options);
}

}  // namespace geardyn::gear
