#include "geardyn/analyses/tooth_contact_correlation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "geardyn/analyses/gear_helpers.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/core/error.hpp"

namespace geardyn::analyses {

gear::TeRigFile read_measured_te(const model::Model& model, const std::string& file,
                                 const Context& context) {
  const std::filesystem::path path = resolve_model_path(model, file);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw context.error("measured_te_file",
                        "a readable TE rig CSV file (relative to the model file)",
                        fmt::format("\"{}\" ({} does not exist)", file, path.string()));
  return gear::read_te_rig_csv(path);
}

namespace {

// InputError at measured_te_file when none of the rig's points can be compared.
void require_compared(const gear::TeComparison& c, const std::vector<double>& torques_nm,
                      int orders, const Context& context) {
  if (c.compared > 0) return;
  throw context.error(
      "measured_te_file",
      fmt::format("at least one measured point within the computed torques ({:.6g} ... {:.6g} "
                  "N m) at a mesh order <= orders = {}",
                  torques_nm.front(), torques_nm.back(), orders),
      fmt::format("none of the {} points of '{}'", c.rig.points.size(), c.rig.source),
      "add the rig's torques to torques or raise orders");
}

}  // namespace

void check_measured_te(const model::Model& model, const ToothContactSettings& settings,
                       const std::vector<double>& torques_nm, const Context& context) {
  if (settings.measured_te_file.empty()) return;
  const gear::TeRigFile rig = read_measured_te(model, settings.measured_te_file, context);
  // Unit amplitudes stand for the computed ones: only which points can be compared matters here.
  const std::vector<std::vector<double>> unit(
      torques_nm.size(), std::vector<double>(static_cast<std::size_t>(settings.orders), 1.0));
  require_compared(gear::compare_te(rig, torques_nm, unit, 1.0), torques_nm, settings.orders,
                   context);
}

std::optional<gear::TeComparison> correlate_measured_te(const model::Model& model,
                                                        const ToothContactSettings& settings,
                                                        const ToothContactRunResult& r,
                                                        const Context& context) {
  if (settings.measured_te_file.empty()) return std::nullopt;
  const gear::TeRigFile rig = read_measured_te(model, settings.measured_te_file, context);
  std::vector<double> torques;
  for (const auto& t : r.torques) torques.push_back(t.torque_nm);
  gear::TeComparison c =
      gear::compare_te(rig, torques, r.harmonics_m, r.model->contact->force_radius());
  require_compared(c, torques, settings.orders, context);
  return c;
}

Table te_correlation_table(const gear::TeComparison& c) {
  Table t;
  t.name = "te_correlation";
  t.title = fmt::format(
      "Measured ('{}', column {}) versus computed TE harmonics, 0-peak along the line of action; "
      "ratio = measured / computed, difference_db = 20 log10(ratio); computed interpolated "
      "linearly in torque between the computed torques",
      std::filesystem::path(c.rig.source).filename().string(), c.rig.amplitude_column);
  std::vector<double> torque, order, line, meas, comp, meas_rad, comp_rad, ratio, db, compared;
  std::vector<std::string> match;
  for (const auto& r : c.rows) {
    torque.push_back(r.torque_nm);
    order.push_back(r.mesh_order);
    line.push_back(r.line);
    meas.push_back(r.measured_m);
    comp.push_back(r.computed_m);
    meas_rad.push_back(r.measured_m / c.radius_m);
    comp_rad.push_back(r.computed_m / c.radius_m);
    ratio.push_back(r.ratio);
    db.push_back(r.difference_db);
    compared.push_back(r.compared() ? 1.0 : 0.0);
    match.emplace_back(gear::to_string(r.match));
  }
  t.add("torque_nm", "N m", torque);
  t.add("mesh_order", "", order);
  t.add("file_line", "", line);
  t.add("measured_0_peak_m", "m", meas);
  t.add("computed_0_peak_m", "m", comp);
  t.add("measured_0_peak_rad", "rad", meas_rad);
  t.add("computed_0_peak_rad", "rad", comp_rad);
  t.add("ratio_measured_to_computed", "", ratio);
  t.add("difference_db", "dB", db);
  t.add("compared", "", compared);
  t.add_text("match", match);
  return t;
}

void add_measured_te_traces(Plot& te_vs_torque, const gear::TeComparison& c) {
  std::map<int, std::pair<std::vector<double>, std::vector<double>>> per_order;
  for (const auto& r : c.rows) {
    auto& [x, y] = per_order[r.mesh_order];
    x.push_back(r.torque_nm);
    y.push_back(r.measured_m / c.radius_m * 1e6);
  }
  for (auto& [order, xy] : per_order) {
    // Sorted by torque, so that the hover reads along the axis.
    std::vector<std::size_t> idx(xy.first.size());
    for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
    std::sort(idx.begin(), idx.end(),
              [&](std::size_t a, std::size_t b) { return xy.first[a] < xy.first[b]; });
    std::vector<double> x, y;
    for (std::size_t i : idx) {
      x.push_back(xy.first[i]);
      y.push_back(xy.second[i]);
    }
    te_vs_torque.traces.push_back(line(fmt::format("order {} measured (0-peak)", order),
                                       std::move(x), std::move(y), Trace::Mode::Markers));
  }
}

std::string te_correlation_note(const std::string& analysis, const gear::TeComparison& c) {
  std::size_t interpolated = 0, outside = 0, above = 0;
  for (const auto& r : c.rows) {
    interpolated += r.match == gear::TeMatch::Interpolated;
    outside += r.match == gear::TeMatch::OutsideTorques;
    above += r.match == gear::TeMatch::AboveOrders;
  }
  const std::string file = std::filesystem::path(c.rig.source).filename().string();
  std::string text = fmt::format(
      "'{}': measured TE '{}' ({}, read as 0-peak along the line of action{}): {} of {} points "
      "compared ({} interpolated in torque",
      analysis, file, c.rig.amplitude_column,
      c.rig.angular ? fmt::format(", angle x r = {:.6g} m", c.radius_m) : std::string(), c.compared,
      c.rows.size(), interpolated);
  if (outside > 0) text += fmt::format("; {} outside the computed torques", outside);
  if (above > 0) text += fmt::format("; {} above the computed orders", above);
  const gear::TeComparisonRow& worst = c.rows[c.max_db_row];
  text += fmt::format(
      "). Mean ratio measured / computed {:.4g}; largest difference {:+.3g} dB at {:.6g} N m, "
      "order {} ({:.4g} against {:.4g} um).",
      c.mean_ratio, worst.difference_db, worst.torque_nm, worst.mesh_order, worst.measured_m * 1e6,
      worst.computed_m * 1e6);
  if (!std::isnan(c.fit_gain))
    text += fmt::format(
        " Least-squares line measured = {:.4g} x computed {:+.4g} um (a gain error and an "
        "additive floor told apart).",
        c.fit_gain, c.fit_offset_m * 1e6);
  text +=
      " How far to trust it: a point's ratio and dB are sensitive where the computed harmonic "
      "is small (near a minimum of the TE-versus-torque map or an order that nearly cancels), "
      "where a rig's noise floor or a small shift of the minimum in torque gives large ratios; "
      "judge the agreement on the larger harmonics and on the fit. The computed TE is "
      "quasi-static (a rig's TE at speed includes the dynamic response), and a bevel or hypoid "
      "pair's is that of its virtual cylindrical pair (docs/theory.md §15.9).";
  return text;
}

}  // namespace geardyn::analyses
