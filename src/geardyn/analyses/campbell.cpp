#include "geardyn/analyses/campbell.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "geardyn/assembly/system_pencil.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/eig/quadratic_eigen.hpp"

namespace geardyn::analyses {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kRpmPerRadS = 60.0 / kTwoPi;
/// Eigenvalues closer than this (relative) count as one repeated eigenvalue when tracking.
constexpr double kRepeatedTolerance = 1e-6;

void add_line(std::vector<EngineOrderLine>& lines, const std::string& label, double order) {
  for (auto& l : lines) {
    if (std::abs(l.order - order) <= 1e-9 * std::max(1.0, order)) {
      l.label += " / " + label;
      return;
    }
  }
  lines.push_back({label, order});
}

std::string format_order(double order) { return fmt::format("{:.6g}", order); }

// Squared norm of the projection of c onto span(Q) relative to ||c||^2, Q orthonormal columns.
double subspace_mac(const Eigen::MatrixXcd& Q, const Eigen::VectorXcd& c) {
  const double nc = c.squaredNorm();
  if (nc == 0.0) return 0.0;
  return (Q.adjoint() * c).squaredNorm() / nc;
}

}  // namespace

std::vector<EngineOrderLine> engine_order_lines(const model::Model& model,
                                                const fe::LinearSystem& system,
                                                const CampbellSettings& settings) {
  std::vector<EngineOrderLine> lines;
  for (double eo : settings.engine_orders) add_line(lines, "EO " + format_order(eo), eo);
  if (settings.shaft_orders) {
    for (const auto& shaft : model.shafts) {
      const double r = std::abs(shaft.speed_ratio);
      if (r > 0.0) add_line(lines, fmt::format("{} 1x ({})", shaft.name, format_order(r)), r);
    }
  }
  if (settings.mesh_orders) {
    for (const auto& mesh : model.gear_meshes) {
      auto order_of = [&](const std::string& gear, int teeth) {
        const int node = system.dofs.find_node(gear);
        if (teeth <= 0 || node < 0) return 0.0;
        return teeth * std::abs(system.dofs.node(node).speed_ratio);
      };
      double order = order_of(mesh.gear1, mesh.teeth1);
      if (order == 0.0) order = order_of(mesh.gear2, mesh.teeth2);
      if (order > 0.0)
        add_line(lines, fmt::format("{} mesh ({})", mesh.name, format_order(order)), order);
    }
  }
  return lines;
}

std::vector<int> best_assignment(const Eigen::MatrixXd& score) {
  // Hungarian method with potentials (the O(n^2 m) shortest augmenting path form) on the cost
  // -score; rows and columns are 1-based inside, index 0 is the virtual start column.
  const int n = static_cast<int>(score.rows()), m = static_cast<int>(score.cols());
  if (n > m) throw std::invalid_argument("best_assignment: more rows than columns");
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(static_cast<std::size_t>(n + 1), 0.0),
      v(static_cast<std::size_t>(m + 1), 0.0);
  std::vector<int> p(static_cast<std::size_t>(m + 1), 0), way(static_cast<std::size_t>(m + 1), 0);
  auto at = [](auto& vec, int i) -> auto& { return vec[static_cast<std::size_t>(i)]; };
  for (int i = 1; i <= n; ++i) {
    at(p, 0) = i;
    int j0 = 0;
    std::vector<double> minv(static_cast<std::size_t>(m + 1), inf);
    std::vector<char> used(static_cast<std::size_t>(m + 1), 0);
    do {
      at(used, j0) = 1;
      const int i0 = at(p, j0);
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (at(used, j)) continue;
        const double cur = -score(i0 - 1, j - 1) - at(u, i0) - at(v, j);
        if (cur < at(minv, j)) {
          at(minv, j) = cur;
          at(way, j) = j0;
        }
        if (at(minv, j) < delta) {
          delta = at(minv, j);
          j1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (at(used, j)) {
          at(u, at(p, j)) += delta;
          at(v, j) -= delta;
        } else {
          at(minv, j) -= delta;
        }
      }
      j0 = j1;
    } while (at(p, j0) != 0);
    do {
      const int j1 = at(way, j0);
      at(p, j0) = at(p, j1);
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> assignment(static_cast<std::size_t>(n), -1);
  for (int j = 1; j <= m; ++j)
    if (at(p, j) != 0) assignment[static_cast<std::size_t>(at(p, j) - 1)] = j - 1;
  return assignment;
}

CampbellResult run_campbell(const model::Model& model, const fe::LinearSystem& system,
                            const CampbellSettings& settings, Progress& progress) {
  const SourceLocation where{model.source_file, 0, 0};
  if (settings.speeds.empty())
    throw InputError(where, "campbell.speeds", "at least one speed", "an empty list");
  for (std::size_t i = 0; i < settings.speeds.size(); ++i) {
    const double s = settings.speeds[i];
    if (!std::isfinite(s) || s < 0.0)
      throw InputError(where, fmt::format("campbell.speeds[{}]", i), "a finite speed >= 0",
                       fmt::format("{}", s));
    if (i > 0 && !(s > settings.speeds[i - 1]))
      throw InputError(where, fmt::format("campbell.speeds[{}]", i), "strictly increasing speeds",
                       fmt::format("{} after {}", s, settings.speeds[i - 1]));
  }
  if (settings.n_modes < 1)
    throw InputError(where, "campbell.n_modes", "at least 1", fmt::format("{}", settings.n_modes));
  if (!(settings.mac_threshold >= 0.0 && settings.mac_threshold <= 1.0))
    throw InputError(where, "campbell.mac_threshold", "a value in [0, 1]",
                     fmt::format("{}", settings.mac_threshold));
  for (double eo : settings.engine_orders)
    if (!(std::isfinite(eo) && eo > 0.0))
      throw InputError(where, "campbell.engine_orders", "orders > 0", fmt::format("{}", eo));
  if (system.size() == 0)
    throw InputError(where, "model", "at least one unconstrained DOF", "a system without DOFs");

  const auto start = std::chrono::steady_clock::now();
  CampbellResult result;
  result.speeds = settings.speeds;
  result.lines = engine_order_lines(model, system, settings);
  const std::size_t n_speeds = settings.speeds.size();
  const int n_tracks = settings.n_modes;
  // Spare modes give the tracking room when a mode climbs out of the computed window.
  const int n_candidates = settings.n_modes + std::max(2, settings.n_modes / 2);
  result.candidates_per_speed = n_candidates;

  std::vector<Eigen::VectorXcd> reference;        // last assigned shape of each track
  std::vector<std::complex<double>> reference_l;  // and its eigenvalue
  std::vector<bool> has_reference;
  std::vector<bool> reference_fresh;  // the reference is from the previous speed
  std::vector<Mode> previous;         // every elastic mode computed at the previous speed
  Eigen::VectorXd start_vector;
  Status status = Status::Ok;
  std::string first_problem;
  int problem_speeds = 0;
  std::vector<std::string> methods;

  // Rigid-body roots (lambda = 0, e.g. free torsion: a double root per rigid-body motion) have
  // no frequency to track; they are solved for, counted and left out of the tracking, and the
  // request grows by their number so that n_candidates elastic modes remain.
  int rigid_roots = 0;
  progress.start("campbell", n_speeds);
  for (std::size_t i = 0; i < n_speeds; ++i) {
    const double speed = settings.speeds[i];
    const eig::QuadraticPencil pencil = assembly::pencil_at(system, speed);
    const double rigid = rigid_body_limit(system, speed);
    eig::QuadraticEigenOptions qo;
    qo.method = to_eig_method(settings.method);
    qo.start = start_vector;
    eig::QuadraticEigenResult cx;
    int found_rigid = 0;
    for (int attempt = 0; attempt < 2; ++attempt) {
      qo.n_modes = n_candidates + rigid_roots;
      cx = eig::solve_quadratic(pencil, qo);
      result.total_operations += cx.operations;
      found_rigid = 0;
      for (Eigen::Index j = 0; j < cx.eigenvalues.size(); ++j)
        if (std::norm(cx.eigenvalues[j]) <= rigid) ++found_rigid;
      if (found_rigid <= rigid_roots) break;
      rigid_roots = found_rigid;  // one more solve with room for the rigid-body roots
    }
    result.rigid_body_roots = std::max(result.rigid_body_roots, found_rigid);
    const std::string method(eig::to_string(cx.method_used));
    if (std::find(methods.begin(), methods.end(), method) == methods.end())
      methods.push_back(method);
    // The spares are optional: fewer modes only matters below the number of tracks.
    Status s = cx.status;
    if (s == Status::FewerModes && cx.converged - found_rigid >= n_tracks) s = Status::Ok;
    if (s != Status::Ok) {
      ++problem_speeds;
      status = worse(status, s);
      if (first_problem.empty())
        first_problem = fmt::format("at {:.6g} rpm: {}", speed * kRpmPerRadS, cx.message);
    }
    if (cx.method_used == eig::Method::Sparse) start_vector = eig::start_vector(cx);

    std::vector<Mode> candidates;
    for (Eigen::Index j = 0; j < cx.eigenvalues.size(); ++j) {
      if (std::norm(cx.eigenvalues[j]) <= rigid) continue;
      candidates.push_back(describe_mode(system, cx.eigenvalues[j], cx.eigenvectors.col(j),
                                         cx.residuals[j], speed, rigid));
      result.max_residual = std::max(result.max_residual, cx.residuals[j]);
    }

    if (result.tracks.empty()) {
      result.tracks.assign(static_cast<std::size_t>(n_tracks), std::vector<TrackPoint>(n_speeds));
      reference.assign(static_cast<std::size_t>(n_tracks), Eigen::VectorXcd());
      reference_l.assign(static_cast<std::size_t>(n_tracks), {0.0, 0.0});
      has_reference.assign(static_cast<std::size_t>(n_tracks), false);
      reference_fresh.assign(static_cast<std::size_t>(n_tracks), false);
    }
    // Score of every (track, candidate) pair.
    const int n_cand = static_cast<int>(candidates.size());
    Eigen::MatrixXd score = Eigen::MatrixXd::Zero(n_tracks, n_cand);
    const bool first =
        std::none_of(has_reference.begin(), has_reference.end(), [](bool b) { return b; });
    if (!first) {
      for (int t = 0; t < n_tracks; ++t) {
        const auto ut = static_cast<std::size_t>(t);
        if (!has_reference[ut]) continue;
        // A track whose previous eigenvalue is repeated (e.g. the two whirl directions of an
        // isotropic rotor at rest) owns only the subspace of that eigenvalue, since any basis of
        // it is as good as the solver's; score candidates against the whole subspace, spanned by
        // every mode computed at the previous speed with that eigenvalue, tracked or spare.
        std::vector<const Eigen::VectorXcd*> group;
        if (reference_fresh[ut]) {
          for (const Mode& p : previous)
            if (std::abs(p.eigenvalue - reference_l[ut]) <=
                kRepeatedTolerance * std::max(std::abs(reference_l[ut]), 1e-300))
              group.push_back(&p.shape);
        }
        if (group.size() > 1) {
          Eigen::MatrixXcd basis(reference[ut].size(), static_cast<Eigen::Index>(group.size()));
          for (std::size_t g = 0; g < group.size(); ++g)
            basis.col(static_cast<Eigen::Index>(g)) = *group[g];
          const Eigen::HouseholderQR<Eigen::MatrixXcd> qr(basis);
          const Eigen::MatrixXcd Q =
              qr.householderQ() * Eigen::MatrixXcd::Identity(basis.rows(), basis.cols());
          for (int c = 0; c < n_cand; ++c)
            score(t, c) = subspace_mac(Q, candidates[static_cast<std::size_t>(c)].shape);
        } else {
          for (int c = 0; c < n_cand; ++c)
            score(t, c) = mac(reference[ut], candidates[static_cast<std::size_t>(c)].shape);
        }
      }
    }
    // Assignment: at the first speed the lowest modes start the tracks in order of frequency.
    std::vector<int> assigned(static_cast<std::size_t>(n_tracks), -1);
    if (first) {
      for (int t = 0; t < n_tracks && t < n_cand; ++t) assigned[static_cast<std::size_t>(t)] = t;
    } else if (n_cand >= n_tracks) {
      assigned = best_assignment(score);
    } else if (n_cand > 0) {
      const std::vector<int> by_candidate = best_assignment(score.transpose());
      for (int c = 0; c < n_cand; ++c)
        assigned[static_cast<std::size_t>(by_candidate[static_cast<std::size_t>(c)])] = c;
    }
    for (int t = 0; t < n_tracks; ++t) {
      const auto ut = static_cast<std::size_t>(t);
      TrackPoint& pt = result.tracks[ut][i];
      pt.speed = speed;
      const int c = assigned[ut];
      reference_fresh[ut] = c >= 0;
      if (c < 0) {
        pt.ambiguous = true;
        ++result.ambiguous_points;
        continue;
      }
      const Mode& m = candidates[static_cast<std::size_t>(c)];
      pt.eigenvalue = m.eigenvalue;
      pt.frequency_hz = m.frequency_hz;
      pt.damped_frequency_hz = m.damped_frequency_hz;
      pt.damping_ratio = m.damping_ratio;
      pt.whirl = m.whirl;
      pt.kind = m.kind;
      pt.residual = m.residual;
      pt.mac = first || !has_reference[ut] ? 1.0 : score(t, c);
      pt.ambiguous = pt.mac < settings.mac_threshold;
      if (pt.ambiguous) ++result.ambiguous_points;
      reference[ut] = m.shape;
      reference_l[ut] = m.eigenvalue;
      has_reference[ut] = true;
    }
    previous = std::move(candidates);
    progress.update(i + 1);
  }
  progress.finish();

  // Critical speeds: sign changes of g(Omega) = f(Omega) - order Omega / 2pi between speeds,
  // located by linear interpolation. Real roots (no oscillation) and rigid-body modes have no
  // resonance and are skipped.
  for (std::size_t t = 0; t < result.tracks.size(); ++t) {
    const auto& track = result.tracks[t];
    for (const auto& line : result.lines) {
      auto g = [&](const TrackPoint& p) { return p.frequency_hz - line.order * p.speed / kTwoPi; };
      auto oscillates = [](const TrackPoint& p) {
        return std::isfinite(p.frequency_hz) && p.frequency_hz > 0.0 && p.eigenvalue.imag() > 0.0;
      };
      auto record = [&](const TrackPoint& a, const TrackPoint& b, double w) {
        CriticalSpeed cs;
        cs.mode = static_cast<int>(t) + 1;
        cs.order = line.order;
        cs.line = line.label;
        cs.speed = a.speed + w * (b.speed - a.speed);
        cs.frequency_hz = a.frequency_hz + w * (b.frequency_hz - a.frequency_hz);
        cs.damping_ratio = a.damping_ratio + w * (b.damping_ratio - a.damping_ratio);
        cs.whirl = w <= 0.5 ? a.whirl : b.whirl;
        cs.ambiguous = a.ambiguous || b.ambiguous;
        result.critical_speeds.push_back(cs);
      };
      if (!track.empty() && oscillates(track[0]) && track[0].speed > 0.0 && g(track[0]) == 0.0)
        record(track[0], track[0], 0.0);
      for (std::size_t i = 0; i + 1 < track.size(); ++i) {
        const TrackPoint &a = track[i], &b = track[i + 1];
        if (!oscillates(a) || !oscillates(b)) continue;
        const double ga = g(a), gb = g(b);
        if (gb == 0.0)
          record(a, b, 1.0);
        else if (ga * gb < 0.0)
          record(a, b, ga / (ga - gb));
      }
    }
  }
  std::stable_sort(
      result.critical_speeds.begin(), result.critical_speeds.end(),
      [](const CriticalSpeed& a, const CriticalSpeed& b) { return a.speed < b.speed; });

  for (const auto& m : methods) result.method += (result.method.empty() ? "" : ", ") + m;
  result.status = status;
  if (status != Status::Ok)
    result.message = fmt::format("eigen-solve trouble at {} of {} speeds; first {}", problem_speeds,
                                 n_speeds, first_problem);
  result.run_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

// ---------------------------------------------------------------------------------------------
// Output

AnalysisOutput campbell_output(const model::Model& /*model*/, const fe::LinearSystem& /*system*/,
                               const CampbellResult& result, const std::string& analysis_name) {
  AnalysisOutput out;
  out.name = analysis_name;
  out.type = "campbell";
  out.status = result.status;
  out.message = result.message;
  out.run_time_s = result.run_time_s;

  {
    Table t;
    t.name = "campbell";
    t.title = "Tracked complex modes versus speed";
    std::vector<double> rpm, mode, f, fd, zeta, macs, amb, res;
    std::vector<std::string> whirl, kind;
    for (std::size_t i = 0; i < result.speeds.size(); ++i) {
      for (std::size_t k = 0; k < result.tracks.size(); ++k) {
        const TrackPoint& p = result.tracks[k][i];
        rpm.push_back(result.speeds[i] * kRpmPerRadS);
        mode.push_back(static_cast<double>(k + 1));
        f.push_back(p.frequency_hz);
        fd.push_back(p.damped_frequency_hz);
        zeta.push_back(p.damping_ratio);
        whirl.emplace_back(to_string(p.whirl));
        kind.emplace_back(to_string(p.kind));
        macs.push_back(p.mac);
        amb.push_back(p.ambiguous ? 1.0 : 0.0);
        res.push_back(p.residual);
      }
    }
    t.add("speed_rpm", "rpm", rpm);
    t.add("mode", "", mode);
    t.add("frequency_hz", "Hz", f);
    t.add("damping_ratio", "", zeta);
    t.add_text("whirl", whirl);
    t.add("mac", "", macs);
    t.add("ambiguous", "", amb);
    t.add("damped_frequency_hz", "Hz", fd);
    t.add_text("kind", kind);
    t.add("residual", "", res);
    out.tables.push_back(std::move(t));
  }
  {
    Table t;
    t.name = "critical_speeds";
    t.title = "Critical speeds: tracked modes meeting engine-order lines";
    std::vector<double> mode, order, rpm, f, zeta, amb;
    std::vector<std::string> whirl, line;
    for (const auto& c : result.critical_speeds) {
      mode.push_back(c.mode);
      order.push_back(c.order);
      rpm.push_back(c.speed * kRpmPerRadS);
      f.push_back(c.frequency_hz);
      whirl.emplace_back(to_string(c.whirl));
      zeta.push_back(c.damping_ratio);
      line.push_back(c.line);
      amb.push_back(c.ambiguous ? 1.0 : 0.0);
    }
    t.add("mode", "", mode);
    t.add("order", "", order);
    t.add("speed_rpm", "rpm", rpm);
    t.add("frequency_hz", "Hz", f);
    t.add_text("whirl", whirl);
    t.add("damping_ratio", "", zeta);
    t.add_text("line", line);
    t.add("ambiguous", "", amb);
    out.tables.push_back(std::move(t));
  }
  {
    Table t;
    t.name = "engine_orders";
    t.title = "Engine-order lines (orders per revolution of the reference shaft)";
    std::vector<std::string> label;
    std::vector<double> order;
    for (const auto& l : result.lines) {
      label.push_back(l.label);
      order.push_back(l.order);
    }
    t.add_text("line", label);
    t.add("order", "", order);
    out.tables.push_back(std::move(t));
  }

  // Plots.
  const double rpm_min = result.speeds.empty() ? 0.0 : result.speeds.front() * kRpmPerRadS;
  const double rpm_max = result.speeds.empty() ? 0.0 : result.speeds.back() * kRpmPerRadS;
  double f_max = 0.0;
  for (const auto& track : result.tracks)
    for (const auto& p : track)
      if (std::isfinite(p.frequency_hz)) f_max = std::max(f_max, p.frequency_hz);
  Plot campbell;
  campbell.name = "campbell";
  campbell.title = "Campbell diagram";
  campbell.x_label = "speed [rpm]";
  campbell.y_label = "natural frequency |lambda|/2pi [Hz]";
  Plot damping;
  damping.name = "campbell_damping";
  damping.title = "Damping ratio versus speed";
  damping.x_label = "speed [rpm]";
  damping.y_label = "damping ratio [-]";
  for (std::size_t k = 0; k < result.tracks.size(); ++k) {
    const auto& track = result.tracks[k];
    const TrackPoint* last = nullptr;
    for (const auto& p : track)
      if (std::isfinite(p.frequency_hz)) last = &p;
    const std::string name =
        last ? fmt::format("mode {} ({}, {})", k + 1, to_string(last->kind), to_string(last->whirl))
             : fmt::format("mode {}", k + 1);
    Trace tf, tz;
    tf.name = tz.name = name;
    tf.mode = tz.mode = Trace::Mode::LinesMarkers;
    for (std::size_t i = 0; i < track.size(); ++i) {
      const TrackPoint& p = track[i];
      if (!std::isfinite(p.frequency_hz)) continue;
      const double rpm = result.speeds[i] * kRpmPerRadS;
      const std::string hover = fmt::format("{}, MAC {:.3f}{}", to_string(p.whirl), p.mac,
                                            p.ambiguous ? ", ambiguous" : "");
      tf.x.push_back(rpm);
      tf.y.push_back(p.frequency_hz);
      tf.hover.push_back(hover);
      tz.x.push_back(rpm);
      tz.y.push_back(p.damping_ratio);
      tz.hover.push_back(hover);
    }
    campbell.traces.push_back(std::move(tf));
    damping.traces.push_back(std::move(tz));
  }
  // Engine-order lines up to a little above the highest mode, so steep mesh orders do not
  // squash the modes into the bottom of the plot.
  const double y_top = f_max > 0.0 ? 1.2 * f_max : 1.0;
  for (const auto& l : result.lines) {
    Trace tr;
    tr.name = l.label;
    tr.dash = "dash";
    const double rpm_end = std::min(rpm_max, y_top * 60.0 / l.order);
    if (!(rpm_end > rpm_min)) continue;
    tr.x = {rpm_min, rpm_end};
    tr.y = {l.order * rpm_min / 60.0, l.order * rpm_end / 60.0};
    campbell.traces.push_back(std::move(tr));
  }
  if (!result.critical_speeds.empty()) {
    Trace tr;
    tr.name = "critical speeds";
    tr.mode = Trace::Mode::Markers;
    for (const auto& c : result.critical_speeds) {
      tr.x.push_back(c.speed * kRpmPerRadS);
      tr.y.push_back(c.frequency_hz);
      tr.hover.push_back(fmt::format("mode {} x {}: {:.1f} rpm, {}", c.mode, c.line,
                                     c.speed * kRpmPerRadS, to_string(c.whirl)));
    }
    campbell.traces.push_back(std::move(tr));
  }
  out.plots.push_back(std::move(campbell));
  out.plots.push_back(std::move(damping));

  out.notes.push_back(fmt::format(
      "{} speeds, {} tracked modes ({} elastic modes computed per speed{}), method {}; largest "
      "backward error {:.2e}.",
      result.speeds.size(), result.tracks.size(), result.candidates_per_speed,
      result.rigid_body_roots > 0
          ? fmt::format(", plus {} rigid-body roots at 0 Hz that are not tracked",
                        result.rigid_body_roots)
          : std::string(),
      result.method, result.max_residual));
  out.notes.push_back(fmt::format(
      "Modes are tracked by shape (MAC, optimal one-to-one assignment), not by frequency order; "
      "{} of {} points have a MAC below the threshold and are flagged ambiguous (veering, or a "
      "mode leaving the computed window): refine the speed steps there.",
      result.ambiguous_points, result.speeds.size() * result.tracks.size()));
  out.notes.push_back(
      "Critical speeds: linear interpolation of f(Omega) - order Omega / 2pi between speeds; "
      "their accuracy is that of the speed grid. Frequencies are |lambda|/2pi.");
  return out;
}

}  // namespace geardyn::analyses
