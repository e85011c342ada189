#include "geardyn/analyses/unbalance.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::analyses {
namespace {

using Complex = std::complex<double>;
using units::kPi;
constexpr double kRpmPerRadS = 60.0 / units::kTwoPi;

bool is_rotation(model::Component c) {
  return c == model::Component::Rx || c == model::Component::Ry || c == model::Component::Rz;
}

std::string order_label(double order) { return fmt::format("{:g}x", order); }

std::string yes_no(bool b) { return b ? "yes" : "no"; }

}  // namespace

double UnbalanceResult::phase_lag_deg(std::complex<double> x) {
  double lag = -std::arg(x) * 180.0 / kPi;  // in [-180, 180]
  if (lag < 0.0) lag += 360.0;
  if (lag >= 360.0) lag -= 360.0;
  return lag + 0.0;  // in [0, 360): -0 (from arg = +0) becomes 0
}

namespace {

// The selected unbalances (all when none are named).
std::vector<const model::Unbalance*> select_unbalances(const model::Model& model,
                                                       const UnbalanceSettings& settings,
                                                       const Context& context) {
  if (settings.speeds.empty()) throw context.error("speed_rpm", "at least one speed", "none");
  for (double w : settings.speeds)
    if (!std::isfinite(w) || w <= 0.0)
      throw context.error("speed_rpm",
                          "speeds > 0 (reverse rotation: negative "
                          "speed ratios)",
                          fmt::format("{}", w * kRpmPerRadS));

  std::vector<const model::Unbalance*> unbalances;
  for (const auto& u : model.unbalances)
    if (settings.unbalances.empty() ||
        std::find(settings.unbalances.begin(), settings.unbalances.end(), u.name) !=
            settings.unbalances.end())
      unbalances.push_back(&u);
  for (const auto& u_name : settings.unbalances)
    if (std::none_of(model.unbalances.begin(), model.unbalances.end(),
                     [&](const model::Unbalance& u) { return u.name == u_name; }))
      throw context.error("unbalances", "the name of an unbalance", "'" + u_name + "'");
  if (unbalances.empty())
    throw context.error("unbalances", "at least one unbalance", "none",
                        "add [[unbalances]] to the model");
  return unbalances;
}

// The equation of each sensor (sets result.sensors).
std::vector<int> sensor_equations(const model::Model& model, const fe::DofMap& dofs,
                                  const std::vector<const model::Sensor*>& sensors,
                                  UnbalanceResult& result) {
  std::vector<int> sensor_eq;
  for (const auto* s : sensors) {
    const int node = dofs.find_node(s->node);
    if (node < 0)
      throw InputError(s->where, fmt::format("sensors[{}].node", s - model.sensors.data()),
                       "the name of a node", "'" + s->node + "'");
    const int eq = dofs.dof(node, s->dof);
    if (eq < 0)
      throw InputError(s->where, fmt::format("sensors[{}].dof", s - model.sensors.data()),
                       "an unconstrained DOF",
                       fmt::format("{}.{} (constrained)", s->node,
                                   model::kComponentNames[static_cast<std::size_t>(s->dof)]),
                       "a constrained DOF does not move");
    sensor_eq.push_back(eq);
    result.sensors.push_back({s->name, eq, is_rotation(s->dof)});
  }
  return sensor_eq;
}

// Sensor amplitudes and orbits of speed i, order o from the response X to the unit-speed load
// (times `scale` = W^2).
void record_speed(const fe::DofMap& dofs, const std::vector<int>& sensor_eq,
                  const std::vector<int>& orbit_nodes, const Eigen::Ref<const Eigen::VectorXcd>& X,
                  double scale, std::size_t i, std::size_t o, UnbalanceResult& result) {
  for (std::size_t s = 0; s < sensor_eq.size(); ++s)
    result.response[o](static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(s)) =
        scale * X(sensor_eq[s]);
  for (std::size_t k = 0; k < orbit_nodes.size(); ++k) {
    const int node = orbit_nodes[k];
    const int ex = dofs.dof(node, model::Component::Ux);
    const int ey = dofs.dof(node, model::Component::Uy);
    const Complex x = ex >= 0 ? scale * X(ex) : Complex(0.0);
    const Complex y = ey >= 0 ? scale * X(ey) : Complex(0.0);
    NodeOrbit& no = result.orbits[o][i][k];
    no.orbit = signal::orbit_from_phasors(x, y);
    no.whirl =
        dofs.node(node).speed_ratio < 0.0 ? signal::reversed(no.orbit.whirl) : no.orbit.whirl;
  }
}

// The stability scan over the speeds; Unstable status and message when a speed is unstable.
void check_unbalance_stability(const fe::LinearSystem& system, UnbalanceResult& result) {
  const double top_speed = *std::max_element(result.speeds.begin(), result.speeds.end());
  result.stability = scan_stability(system, result.speeds, result.orders.back() * top_speed,
                                    /*project=*/true, /*certify=*/true);
  if (result.stability.all_stable()) return;
  result.status = worse(result.status, Status::Unstable);
  if (result.message.empty()) result.message = unstable_message(result.stability);
}

}  // namespace

UnbalanceResult run_unbalance(const model::Model& model, const UnbalanceSettings& settings,
                              const Context& context) {
  const fe::LinearSystem& system = context.system();
  const fe::DofMap& dofs = system.dofs;
  const std::vector<const model::Unbalance*> unbalances =
      select_unbalances(model, settings, context);

  UnbalanceResult result;
  result.speeds = settings.speeds;
  result.modal_damping = system.has_modal_damping();

  const std::vector<const model::Sensor*> sensors =
      select_sensors(model, settings.sensors, context);
  const std::vector<int> sensor_eq = sensor_equations(model, dofs, sensors, result);

  // Orbit nodes: both lateral sensors present, or carrying unbalance; in node order.
  std::vector<int> orbit_nodes;
  for (int node = 0; node < dofs.num_nodes(); ++node) {
    const std::string& node_name = dofs.node(node).name;
    bool has_x = false, has_y = false, has_unbalance = false;
    for (const auto* s : sensors)
      if (s->node == node_name) {
        has_x = has_x || s->dof == model::Component::Ux;
        has_y = has_y || s->dof == model::Component::Uy;
      }
    for (const auto* u : unbalances) has_unbalance = has_unbalance || u->node == node_name;
    if ((has_x && has_y) || has_unbalance) {
      orbit_nodes.push_back(node);
      result.orbit_nodes.push_back(node_name);
    }
  }

  std::vector<std::string> selected;
  for (const auto* u : unbalances) selected.push_back(u->name);
  result.orders = fe::unbalance_orders(model, system, selected);
  if (result.orders.empty())
    throw context.error("unbalances", "unbalance on a spinning node",
                        "only nodes with speed ratio 0",
                        "set spin_of for the node, or put the "
                        "unbalance on a shaft node");

  const std::size_t n_speeds = result.speeds.size();
  const std::size_t n_orders = result.orders.size();
  const auto n_sensors = static_cast<Eigen::Index>(sensors.size());
  result.response.assign(n_orders,
                         Eigen::MatrixXcd::Zero(static_cast<Eigen::Index>(n_speeds), n_sensors));
  result.orbits.assign(n_orders, std::vector<std::vector<NodeOrbit>>(
                                     n_speeds, std::vector<NodeOrbit>(orbit_nodes.size())));

  // The load is m e (|r| W)^2 times a speed-independent vector: solve for the load at W = 1
  // and scale the response by W^2 (no load assembly inside the loop).
  std::vector<Eigen::MatrixXcd> unit_load(n_orders);
  for (std::size_t o = 0; o < n_orders; ++o)
    unit_load[o] = fe::unbalance_load(model, system, 1.0, result.orders[o], selected);

  const std::string& name = context.name();
  Progress& progress = context.progress();
  // The unbalance loads are lateral: the blocks of D they do not reach (a shaft line's axial
  // and torsional motion, unless a gear mesh or a bearing couples them) are not factorised and
  // respond with exactly 0, and the factorisation forward-substitutes the load as it goes
  // (DynamicStiffness::restrict_to). One order: set once per solver; several: per order.
  std::vector<std::unique_ptr<DynamicStiffness>> solvers;
  std::vector<Eigen::MatrixXcd> responses(1);
  solvers.push_back(std::make_unique<DynamicStiffness>(system, result.speeds.front(), name));
  solvers.back()->restrict_to(unit_load.front());
  auto solve_speed = [&](std::size_t i, unsigned t) {
    DynamicStiffness& D = *solvers[t];
    Eigen::MatrixXcd& X = responses[t];
    const double speed = result.speeds[i];
    D.set_speed(speed);
    for (std::size_t o = 0; o < n_orders; ++o) {
      if (n_orders > 1) D.restrict_to(unit_load[o]);
      D.factorize(result.orders[o] * speed);
      D.solve(unit_load[o], X);
      record_speed(dofs, sensor_eq, orbit_nodes, X.col(0), speed * speed, i, o, result);
    }
  };
  progress.start(fmt::format("{}: {} speeds x {} order(s)", name, n_speeds, n_orders), n_speeds);
  // The first speed on this thread fixes the factor path, which decides whether threads may run.
  solve_speed(0, 0);
  progress.update(1);
  const unsigned threads = sweep_threads(settings.threads, n_speeds - 1,
                                         solvers.front()->factor_path(), result.thread_note);
  for (unsigned t = 1; t < threads; ++t) {
    solvers.push_back(std::make_unique<DynamicStiffness>(system, result.speeds.front(), name));
    solvers.back()->restrict_to(unit_load.front());
  }
  responses.resize(threads);
  result.threads_used = static_cast<int>(threads);
  for_each_point(1, n_speeds, threads, solve_speed,
                 [&](std::size_t done) { progress.update(done + 1); });
  progress.finish();
  check_unbalance_stability(system, result);
  return result;
}

namespace {

// Table "orbits": per order, speed and orbit node.
Table orbits_table(const UnbalanceResult& result, const std::vector<double>& rpm) {
  const std::size_t n_speeds = result.speeds.size();
  const std::size_t n_orders = result.orders.size();
  Table orbits;
  orbits.name = "orbits";
  orbits.title = "Orbits (semi-axes, inclination of the major axis from e1, whirl vs spin)";
  std::vector<double> o_rpm, o_order, o_major, o_minor, o_incl;
  std::vector<std::string> o_node, o_whirl, o_stable;
  for (std::size_t o = 0; o < n_orders; ++o)
    for (std::size_t i = 0; i < n_speeds; ++i)
      for (std::size_t k = 0; k < result.orbit_nodes.size(); ++k) {
        const NodeOrbit& no = result.orbits[o][i][k];
        o_rpm.push_back(rpm[i]);
        o_order.push_back(result.orders[o]);
        o_stable.push_back(yes_no(result.stability.stable[i]));
        o_node.push_back(result.orbit_nodes[k]);
        o_major.push_back(no.orbit.major);
        o_minor.push_back(no.orbit.minor);
        o_incl.push_back(no.orbit.inclination * 180.0 / kPi);
        o_whirl.emplace_back(signal::to_string(no.whirl));
      }
  orbits.add("speed_rpm", "rpm", o_rpm);
  orbits.add("order", "", o_order);
  orbits.add_text("stable", o_stable);
  orbits.add_text("node", o_node);
  orbits.add("major_m", "m", o_major);
  orbits.add("minor_m", "m", o_minor);
  orbits.add("inclination_deg", "deg", o_incl);
  orbits.add_text("whirl", o_whirl);

  return orbits;
}

// Marks the unstable speeds of a plot: a marker on every trace point at an unstable speed (a
// trace of its own, "unstable: not reached") and the range in the title.
void mark_unstable(const UnbalanceResult& result, const std::vector<double>& rpm, Plot& plot) {
  Trace marks;
  marks.name = "unstable (not reached)";
  marks.mode = Trace::Mode::Markers;
  const std::size_t n_traces = plot.traces.size();
  for (std::size_t t = 0; t < n_traces; ++t)
    for (std::size_t i = 0; i < plot.traces[t].x.size(); ++i)
      if (!result.stability.stable[i]) {
        marks.x.push_back(rpm[i]);
        marks.y.push_back(plot.traces[t].y[i]);
        marks.hover.push_back(plot.traces[t].name + ": unstable speed");
      }
  plot.traces.push_back(std::move(marks));
  plot.title += " - UNSTABLE speeds marked";
}

}  // namespace

AnalysisOutput unbalance_output(const model::Model& /*model*/,
                                const UnbalanceSettings& /*settings*/,
                                const UnbalanceResult& result, const Context& context) {
  AnalysisOutput out;
  out.name = context.name();
  out.type = "unbalance";
  out.status = result.status;
  out.message = result.message;

  const std::size_t n_speeds = result.speeds.size();
  const std::size_t n_orders = result.orders.size();
  const std::size_t n_sensors = result.sensors.size();
  const bool many_orders = n_orders > 1;

  std::vector<double> rpm(n_speeds);
  for (std::size_t i = 0; i < n_speeds; ++i) rpm[i] = result.speeds[i] * kRpmPerRadS;

  Table response;
  response.name = "response";
  response.title = "Unbalance response per speed and order (phase: lag behind the reference mark)";
  std::vector<double> col_rpm, col_order;
  std::vector<std::string> col_stable;
  for (std::size_t o = 0; o < n_orders; ++o)
    for (std::size_t i = 0; i < n_speeds; ++i) {
      col_rpm.push_back(rpm[i]);
      col_order.push_back(result.orders[o]);
      col_stable.push_back(yes_no(result.stability.stable[i]));
    }
  response.add("speed_rpm", "rpm", col_rpm);
  response.add("order", "", col_order);
  response.add_text("stable", col_stable);

  Plot amp_plot;
  amp_plot.name = "amplitude";
  amp_plot.title = "Unbalance response amplitude";
  amp_plot.x_label = "speed [rpm]";
  amp_plot.y_log = true;
  Plot phase_plot;
  phase_plot.name = "phase";
  phase_plot.title = "Unbalance response phase lag";
  phase_plot.x_label = "speed [rpm]";
  phase_plot.y_label = "phase lag [deg]";
  bool any_rotation = false, any_translation = false;

  for (std::size_t s = 0; s < n_sensors; ++s) {
    const bool rot = result.sensors[s].rotational;
    (rot ? any_rotation : any_translation) = true;
    const std::string unit = rot ? "rad" : "m";
    std::vector<double> amp, lag;
    for (std::size_t o = 0; o < n_orders; ++o) {
      Trace a, p;
      a.name = p.name = many_orders ? fmt::format("{} ({})", result.sensors[s].name,
                                                  order_label(result.orders[o]))
                                    : result.sensors[s].name;
      a.x = p.x = rpm;
      for (std::size_t i = 0; i < n_speeds; ++i) {
        const Complex z =
            result.response[o](static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(s));
        amp.push_back(std::abs(z));
        lag.push_back(UnbalanceResult::phase_lag_deg(z));
        a.y.push_back(amp.back());
        p.y.push_back(lag.back());
      }
      amp_plot.traces.push_back(std::move(a));
      phase_plot.traces.push_back(std::move(p));
    }
    response.add(result.sensors[s].name + "_amplitude_" + unit, unit, amp);
    response.add(result.sensors[s].name + "_phase_deg", "deg", lag);
  }
  amp_plot.y_label = any_rotation && any_translation ? "amplitude [m, rad]"
                     : any_rotation                  ? "amplitude [rad]"
                                                     : "amplitude [m]";

  if (!result.stability.all_stable()) {
    mark_unstable(result, rpm, amp_plot);
    mark_unstable(result, rpm, phase_plot);
  }
  out.tables.push_back(std::move(response));
  out.tables.push_back(orbits_table(result, rpm));
  out.plots.push_back(std::move(amp_plot));
  out.plots.push_back(std::move(phase_plot));

  std::string orders;
  for (double r : result.orders) orders += (orders.empty() ? "" : ", ") + order_label(r);
  out.notes.push_back(fmt::format(
      "{} speed(s) from {:.6g} to {:.6g} rpm; unbalance orders {} (response at order x speed). "
      "Each point solves D(w; W) X = F_unb directly with K, C of speed-dependent bearings and "
      "the gyroscopic matrix at the speed W{}.",
      n_speeds, rpm.empty() ? 0.0 : rpm.front(), rpm.empty() ? 0.0 : rpm.back(), orders,
      result.modal_damping ? ", modal damping by the Woodbury identity" : ""));
  out.notes.push_back(
      "Phase = lag of the response behind the reference mark (direction of a phase-0 unbalance "
      "along e1 at t = 0), -arg(X) in [0, 360) deg with x = Re(X e^(iwt)): for one unbalance it is "
      "the lag of ux behind the ux force; uy reads 90 deg more in forward whirl.");
  out.notes.push_back(stability_note(result.stability));
  if (!result.thread_note.empty()) out.notes.push_back(result.thread_note);
  out.notes.push_back(
      "Peaks between listed speeds are not resolved: the speed list is the grid (use a harmonic "
      "analysis or a finer list near critical speeds). Whirl is relative to the node's spin "
      "(for non-spinning nodes: relative to +e3).");
  return out;
}

}  // namespace geardyn::analyses
