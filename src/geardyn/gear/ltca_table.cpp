#include "geardyn/gear/ltca_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "geardyn/core/text.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::gear {
namespace {

constexpr std::size_t kNone = static_cast<std::size_t>(-1);
constexpr const char* kLengthUnits = "m, mm or um";
constexpr const char* kTeUnits = "m, mm, um, nm, rad, mrad, urad, deg or arcsec";

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

std::optional<double> length_unit(std::string_view u) {
  if (u == "m") return 1.0;
  if (u == "mm") return 1e-3;
  if (u == "um") return 1e-6;
  return std::nullopt;
}

// TE units: the factor to metres or radians, and whether angular.
std::optional<std::pair<double, bool>> te_unit(std::string_view u) {
  if (const auto f = length_unit(u)) return std::pair{*f, false};
  if (u == "nm") return std::pair{1e-9, false};
  if (u == "rad") return std::pair{1.0, true};
  if (u == "mrad") return std::pair{1e-3, true};
  if (u == "urad") return std::pair{1e-6, true};
  if (u == "deg") return std::pair{units::kPi / 180.0, true};
  if (u == "arcsec") return std::pair{units::kPi / (180.0 * 3600.0), true};
  return std::nullopt;
}

// The columns of the header: index into the row and the factor to SI.
struct Columns {
  std::size_t angle = kNone, torque = kNone, te = kNone, stiffness = kNone;
  std::array<std::size_t, 4> axis{kNone, kNone, kNone, kNone};  // torque, h, v, j
  std::array<double, 4> axis_factor{1.0, 1.0, 1.0, 1.0};
  double angle_period = 0.0;  // one mesh cycle in the angle's unit
  double te_factor = 1.0, stiffness_factor = 1.0;
  bool te_angular = false;
};

void claim(const NumericCsv& csv, std::size_t i, std::size_t& slot, const char* what) {
  if (slot != kNone)
    throw InputError(csv.at_header(i), csv.names[i], fmt::format("one {} column", what),
                     fmt::format("a second one (after '{}')", csv.names[slot]));
  slot = i;
}

Columns parse_header(const NumericCsv& csv, const LtcaReadOptions& options) {
  Columns c;
  for (std::size_t i = 0; i < csv.names.size(); ++i) {
    const std::string n = lower(csv.names[i]);
    if (n == "angle_deg" || n == "angle_rad") {
      claim(csv, i, c.angle, "angle");
      c.angle_period = (n == "angle_deg" ? 360.0 : units::kTwoPi) / options.teeth;
    } else if (n == "torque_nm" || n == "torque_knm") {
      claim(csv, i, c.axis[0], "torque");
      c.axis_factor[0] = n == "torque_knm" ? 1e3 : 1.0;
    } else if (n.size() > 2 && (n[0] == 'h' || n[0] == 'v' || n[0] == 'j') && n[1] == '_') {
      const std::size_t a = n[0] == 'h' ? 1 : n[0] == 'v' ? 2 : 3;
      const auto f = length_unit(std::string_view(n).substr(2));
      if (!f)
        throw InputError(csv.at_header(i), csv.names[i],
                         fmt::format("{}_<unit>, unit {}", n[0], kLengthUnits),
                         fmt::format("'{}'", shorten(csv.names[i], 43)));
      claim(csv, i, c.axis[a], "mounting error");
      c.axis_factor[a] = *f;
    } else if (n.starts_with("te_")) {
      const auto u = te_unit(std::string_view(n).substr(3));
      if (!u)
        throw InputError(csv.at_header(i), csv.names[i],
                         fmt::format("te_<unit>, unit {}", kTeUnits),
                         fmt::format("'{}'", shorten(csv.names[i], 43)));
      claim(csv, i, c.te, "te");
      c.te_factor = u->first;
      c.te_angular = u->second;
    } else if (n == "stiffness_n_per_m" || n == "stiffness_n_m" || n == "stiffness_n_per_um" ||
               n == "stiffness_n_um") {
      claim(csv, i, c.stiffness, "stiffness");
      c.stiffness_factor = n.ends_with("um") ? 1e6 : 1.0;
    } else {
      throw InputError(csv.at_header(i), csv.names[i],
                       "angle_deg or angle_rad, torque_nm or torque_knm, h_<u>, v_<u>, j_<u>, "
                       "te_<u>, stiffness_n_per_m",
                       fmt::format("'{}'", shorten(csv.names[i], 43)),
                       "the column names carry the quantity and its unit (docs/input-files.md)");
    }
  }
  const SourceLocation header{csv.file, csv.header_line, 1};
  if (c.angle == kNone)
    throw InputError(header, "header", "an angle_deg or angle_rad column (pinion rotation)",
                     "none");
  if (c.axis[0] == kNone)
    throw InputError(header, "header", "a torque_nm or torque_knm column", "none");
  if (c.te == kNone) throw InputError(header, "header", "a te_<unit> column", "none");
  if (c.te_angular && !(options.base_radius_m > 0.0))
    throw InputError(csv.at_header(c.te), csv.names[c.te],
                     "the base radius of gear 1 for an angular TE", "none",
                     "angular TE times the base radius is the TE along the line of action");
  return c;
}

// Sorted distinct values of column `col` (times `factor`).
std::vector<double> distinct(const NumericCsv& csv, std::size_t col, double factor) {
  std::vector<double> v;
  if (col == kNone) return {0.0};
  for (const auto& row : csv.rows) v.push_back(row[col] * factor);
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

std::size_t position(const std::vector<double>& axis, double value) {
  return static_cast<std::size_t>(std::lower_bound(axis.begin(), axis.end(), value) - axis.begin());
}

std::string node_text(const std::array<std::vector<double>, 4>& axes,
                      const std::array<std::size_t, 4>& node) {
  return fmt::format("torque {} N m, h {} m, v {} m, j {} m", axes[0][node[0]], axes[1][node[1]],
                     axes[2][node[2]], axes[3][node[3]]);
}

// Linear bracket of x in the increasing `axis` (size >= 2): interval and weight of its upper end
// (outside: the end interval, weight < 0 or > 1).
std::pair<std::size_t, double> bracket(const std::vector<double>& axis, double x) {
  std::size_t i = position(axis, x);
  i = std::clamp<std::size_t>(i, 1, axis.size() - 1) - 1;
  return {i, (x - axis[i]) / (axis[i + 1] - axis[i])};
}

}  // namespace

LtcaTable LtcaTable::parse(std::string_view text, const std::string& file_name,
                           const LtcaReadOptions& options) {
  if (options.teeth < 1)
    throw InputError(SourceLocation{file_name, 0, 0}, "teeth", "the pinion's tooth count >= 1",
                     fmt::format("{}", options.teeth));
  const NumericCsv csv = parse_numeric_csv(text, file_name, 3);
  const Columns c = parse_header(csv, options);
  LtcaTable t;
  t.source_ = file_name;
  t.has_stiffness_ = c.stiffness != kNone;
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const auto& row = csv.rows[r];
    if (row[c.axis[0]] < 0.0)
      throw InputError(csv.at(r, c.axis[0]), csv.names[c.axis[0]], "a torque >= 0",
                       fmt::format("{}", row[c.axis[0]]));
    if (t.has_stiffness_ && !(row[c.stiffness] > 0.0))
      throw InputError(csv.at(r, c.stiffness), csv.names[c.stiffness], "a mesh stiffness > 0",
                       fmt::format("{}", row[c.stiffness]));
    if (!t.has_stiffness_ && !(row[c.te] > 0.0))
      throw InputError(csv.at(r, c.te), csv.names[c.te],
                       "a positive loaded TE (without a stiffness column the whole TE is "
                       "elastic, k = F / e)",
                       fmt::format("{}", row[c.te]),
                       "give the TE as the deflection along the line of action, positive, or add "
                       "a stiffness_n_per_m column");
  }
  for (std::size_t a = 0; a < 4; ++a) t.axes_[a] = distinct(csv, c.axis[a], c.axis_factor[a]);
  const std::vector<double> angles = distinct(csv, c.angle, 1.0);
  const SourceLocation header{csv.file, csv.header_line, 1};
  if (angles.size() < 3)
    throw InputError(csv.at_header(c.angle), csv.names[c.angle],
                     "at least 3 distinct angles over the mesh cycle",
                     fmt::format("{}", angles.size()));

  // The grid: every node (torque, h, v, j) once at every angle.
  const std::size_t na = angles.size();
  std::size_t nodes = 1;
  for (const auto& axis : t.axes_) nodes *= axis.size();
  std::vector<std::size_t> row_of(nodes * na, kNone);
  auto node_of = [&](std::size_t r) {
    std::array<std::size_t, 4> node{};
    for (std::size_t a = 0; a < 4; ++a)
      node[a] =
          c.axis[a] == kNone ? 0 : position(t.axes_[a], csv.rows[r][c.axis[a]] * c.axis_factor[a]);
    return node;
  };
  auto flat = [&](const std::array<std::size_t, 4>& node) {
    return ((node[0] * t.axes_[1].size() + node[1]) * t.axes_[2].size() + node[2]) *
               t.axes_[3].size() +
           node[3];
  };
  std::vector<std::size_t> first_row(nodes, kNone);
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const auto node = node_of(r);
    const std::size_t k = flat(node) * na + position(angles, csv.rows[r][c.angle]);
    if (row_of[k] != kNone)
      throw InputError(csv.at(r, c.angle), csv.names[c.angle],
                       "each angle once per torque and mounting state (a regular grid)",
                       fmt::format("a repeat of line {} ({}, angle {})", csv.row_lines[row_of[k]],
                                   node_text(t.axes_, node), csv.rows[r][c.angle]));
    row_of[k] = r;
    if (first_row[flat(node)] == kNone) first_row[flat(node)] = r;
  }
  const std::array<std::size_t, 4> sizes{t.axes_[0].size(), t.axes_[1].size(), t.axes_[2].size(),
                                         t.axes_[3].size()};
  std::array<std::size_t, 4> node{};
  for (std::size_t n = 0; n < nodes; ++n) {
    std::size_t rest = n;
    for (std::size_t a = 4; a-- > 0;) {
      node[a] = rest % sizes[a];
      rest /= sizes[a];
    }
    if (first_row[n] == kNone)
      throw InputError(header, "rows",
                       fmt::format("a regular grid: every combination of the {} torques, {} h, {} "
                                   "v and {} j values, at each of the {} angles",
                                   sizes[0], sizes[1], sizes[2], sizes[3], na),
                       fmt::format("no rows at {}", node_text(t.axes_, node)));
    for (std::size_t ia = 0; ia < na; ++ia)
      if (row_of[n * na + ia] == kNone)
        throw InputError(
            csv.at(first_row[n], c.angle), csv.names[c.angle],
            fmt::format("a row at each of the {} angles of the grid", na),
            fmt::format("no row at angle {} for {}", angles[ia], node_text(t.axes_, node)));
  }

  // The angles span one mesh cycle, closed or open (as the STE reader).
  const double span = (angles.back() - angles.front()) / c.angle_period;
  const double closed_error = std::abs(span - 1.0);
  const double open_error =
      std::abs(span * static_cast<double>(na) / static_cast<double>(na - 1) - 1.0);
  if (std::min(closed_error, open_error) > options.period_tolerance)
    throw InputError(
        csv.at(row_of[na - 1], c.angle), csv.names[c.angle],
        fmt::format("angles spanning one mesh cycle of gear 1 ({} in the angle unit "
                    "for {} teeth), or one cycle minus one spacing, within {:.3g} %",
                    c.angle_period, options.teeth, 100.0 * options.period_tolerance),
        fmt::format("a span of {} ({:.6g} cycles)", angles.back() - angles.front(), span),
        "check the pinion's tooth count and the angle unit");
  const bool closed = closed_error <= open_error;
  const double scale =
      closed ? 1.0 / span : static_cast<double>(na - 1) / (span * static_cast<double>(na));
  t.angles_ = closed ? na - 1 : na;
  for (std::size_t ia = 0; ia < t.angles_; ++ia)
    t.u_.push_back((angles[ia] - angles.front()) / c.angle_period * scale);
  t.u_.push_back(1.0);
  const std::size_t knots = t.angles_ + 1;
  t.te_m_.resize(nodes * knots);
  if (t.has_stiffness_) t.stiffness_.resize(nodes * knots);
  const double te_scale = c.te_factor * (c.te_angular ? options.base_radius_m : 1.0);
  for (std::size_t n = 0; n < nodes; ++n)
    for (std::size_t k = 0; k < knots; ++k) {
      // The closing knot is the last row (closed) or the first angle again (open).
      const std::size_t r = row_of[n * na + (k < t.angles_ ? k : (closed ? na - 1 : 0))];
      t.te_m_[n * knots + k] = csv.rows[r][c.te] * te_scale;
      if (t.has_stiffness_)
        t.stiffness_[n * knots + k] = csv.rows[r][c.stiffness] * c.stiffness_factor;
    }
  return t;
}

LtcaTable LtcaTable::read(const std::filesystem::path& path, const LtcaReadOptions& options) {
  const std::optional<std::string> text = try_read_file(path);
  if (!text)
    throw InputError(SourceLocation{path.string(), 0, 0}, "ltca_file", "a readable CSV file",
                     "a file that cannot be opened");
  return parse(*text, path.string(), options);
}

std::size_t LtcaTable::index(const std::array<std::size_t, 4>& node, std::size_t a) const {
  const std::size_t n =
      ((node[0] * axes_[1].size() + node[1]) * axes_[2].size() + node[2]) * axes_[3].size() +
      node[3];
  return n * (angles_ + 1) + a;
}

double LtcaTable::te_node(const std::array<std::size_t, 4>& node, std::size_t a) const {
  return te_m_.at(index(node, a));
}

double LtcaTable::stiffness_node(const std::array<std::size_t, 4>& node, std::size_t a) const {
  return has_stiffness_ ? stiffness_.at(index(node, a)) : std::numeric_limits<double>::quiet_NaN();
}

LtcaTable::Weights LtcaTable::weights(const LtcaPoint& point, bool extrapolate) const {
  const std::array<double, 4> x{point.torque_nm, point.h_m, point.v_m, point.j_m};
  const std::array<const char*, 4> unit{"N m", "m", "m", "m"};
  Weights w;
  for (std::size_t a = 0; a < 4; ++a) {
    const std::vector<double>& axis = axes_[a];
    if (!std::isfinite(x[a]))
      throw InputError(SourceLocation{source_, 0, 0}, kAxisNames[a], "a finite value",
                       fmt::format("{}", x[a]));
    const bool outside =
        axis.size() == 1 ? x[a] != axis[0] : x[a] < axis.front() || x[a] > axis.back();
    if (outside && !extrapolate)
      throw InputError(
          SourceLocation{source_, 0, 0}, kAxisNames[a],
          axis.size() == 1
              ? fmt::format("the table's only {} value, {} {}", kAxisNames[a], axis[0], unit[a])
              : fmt::format("a {} within the table, [{}, {}] {}", kAxisNames[a], axis.front(),
                            axis.back(), unit[a]),
          fmt::format("{} {}", x[a], unit[a]));
    if (axis.size() == 1) continue;  // held (lo = hi = 0)
    const auto [i, f] = bracket(axis, x[a]);
    w.lo[a] = i;
    w.hi[a] = i + 1;
    w.w[a] = f;
  }
  return w;
}

double LtcaTable::blend(const std::vector<double>& values, const Weights& w, double u) const {
  u -= std::floor(u);
  const auto it = std::upper_bound(u_.begin(), u_.end(), u);
  std::size_t k = it == u_.begin() ? 0 : static_cast<std::size_t>(it - u_.begin()) - 1;
  k = std::min(k, u_.size() - 2);
  const double t = (u - u_[k]) / (u_[k + 1] - u_[k]);
  double sum = 0.0;
  for (unsigned corner = 0; corner < 16; ++corner) {
    std::array<std::size_t, 4> node{};
    double weight = 1.0;
    bool skip = false;
    for (std::size_t a = 0; a < 4 && !skip; ++a) {
      const bool upper = (corner >> a) & 1U;
      if (upper && w.hi[a] == w.lo[a]) skip = true;  // a one-value axis has one corner
      node[a] = upper ? w.hi[a] : w.lo[a];
      weight *= w.hi[a] == w.lo[a] ? 1.0 : (upper ? w.w[a] : 1.0 - w.w[a]);
    }
    if (skip) continue;
    const std::size_t i = index(node, k);
    sum += weight * ((1.0 - t) * values[i] + t * values[i + 1]);
  }
  return sum;
}

double LtcaTable::te_at(const LtcaPoint& point, double u, bool extrapolate) const {
  return blend(te_m_, weights(point, extrapolate), u);
}

double LtcaTable::stiffness_at(const LtcaPoint& point, double u, bool extrapolate) const {
  if (!has_stiffness_) return std::numeric_limits<double>::quiet_NaN();
  return blend(stiffness_, weights(point, extrapolate), u);
}

SteCurve LtcaTable::ste(const LtcaPoint& point, double base_radius_m, bool extrapolate,
                        double shift, std::size_t samples, SteInterpolation interpolation) const {
  const SourceLocation where{source_, 0, 0};
  if (!(point.torque_nm > 0.0))
    throw InputError(where, "torque", "a pinion torque > 0 N m (the STE is the loaded TE)",
                     fmt::format("{} N m", point.torque_nm));
  if (!(base_radius_m > 0.0))
    throw InputError(where, "base_radius", "a base radius > 0 m", fmt::format("{}", base_radius_m));
  const Weights w = weights(point, extrapolate);
  // One torque in the table, extrapolated: a linear mesh, the elastic part scales with the force.
  const double t0 = axes_[0][0];
  const bool scale_single = axes_[0].size() == 1 && point.torque_nm != t0;
  if (scale_single && !(t0 > 0.0))
    throw InputError(where, "torque", "a table torque > 0 to scale from", fmt::format("{}", t0));
  const double force = point.torque_nm / base_radius_m, force0 = t0 / base_radius_m;
  const std::size_t n = samples != 0 ? samples : angles_;
  std::vector<double> e(n), g;
  if (has_stiffness_) g.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double u = static_cast<double>(j) / static_cast<double>(n) + shift;
    double te = blend(te_m_, w, u);
    if (has_stiffness_) {
      const double k = blend(stiffness_, w, u);
      if (!(k > 0.0))
        throw InputError(where, "stiffness",
                         "an interpolated mesh stiffness > 0 at the pair's torque and mounting",
                         fmt::format("{} N/m at cycle fraction {:.4g}", k, u),
                         "the point lies too far outside the table to extrapolate");
      if (scale_single) te += (force - force0) / k;
      g[j] = te - force / k;
    } else if (scale_single) {
      te *= point.torque_nm / t0;
    }
    if (!(te - (has_stiffness_ ? g[j] : 0.0) > 0.0))
      throw InputError(where, "te", "an interpolated loaded TE > 0 (the elastic deflection)",
                       fmt::format("{} m at cycle fraction {:.4g}", te, u),
                       "the point lies too far outside the table to extrapolate");
    e[j] = te;
  }
  return SteCurve::from_samples(std::move(e), interpolation, std::move(g), point.torque_nm);
}

}  // namespace geardyn::gear
