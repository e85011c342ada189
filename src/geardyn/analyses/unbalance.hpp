#pragma once
// Steady-state unbalance response (docs/theory.md §5). An unbalance m e at a node spinning at r W
// (r: the node's speed ratio, W the reference speed) is a force of magnitude m e (r W)^2 turning
// with the shaft, at frequency |r| W. For every speed W and every order r (distinct |speed
// ratio| of the nodes carrying unbalance), solve
//   D(|r| W; W) X = F_unb(r, W),  D(w; W) = K(W) - w^2 M + i w (C(W) + W G) + i K_loss + i w
//   C_modal
// with the speed-dependent bearing coefficients and the gyroscopic matrix at W.
// Phase convention: x(t) = Re(X e^{i w t}); the reported phase is the LAG of the response behind
// the shaft's reference mark, lag = -arg X in [0, 360) deg, where the reference mark is the
// direction (e1 of the node frame at t = 0) of an unbalance with phase 0. For a single unbalance
// of phase 0 this is the phase lag of the ux response behind the ux force (the classical Jeffcott
// phase, 0 below and 180 deg far above the critical speed); a uy probe reads 90 deg more lag in
// forward whirl, as a keyphasor-referenced probe at 90 deg does.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/analyses/stability_check.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/signal/orbit.hpp"

namespace geardyn::analyses {

struct UnbalanceSettings : model::SettingsOf<UnbalanceSettings> {
  std::vector<double> speeds;           ///< [rad/s]
  std::vector<std::string> unbalances;  ///< empty: all
  std::vector<std::string> sensors;     ///< empty: all
  /// Worker threads over speeds (library setting; <= 0: all cores). Each speed is solved
  /// independently, so results are bit-identical for any count.
  int threads = 1;
};

/// Orbit of one node at one speed and order.
struct NodeOrbit {
  signal::Orbit orbit;  ///< geometry in the node's e1-e2 plane [m], geometric sense about e3
  signal::Whirl whirl = signal::Whirl::Straight;  ///< sense relative to the node's spin (a node
                                                  ///< that does not spin: relative to +e3)
};

struct UnbalanceResult {
  Status status = Status::Ok;
  std::string message;
  std::vector<double> speeds;  ///< reference speeds [rad/s]
  std::vector<double> orders;  ///< excitation orders (|speed ratio|), ascending
  std::vector<ResponseSensor> sensors;
  /// response[o](i, s): complex amplitude of sensor s at speeds[i] for orders[o] [m or rad].
  std::vector<Eigen::MatrixXcd> response;
  std::vector<std::string> orbit_nodes;  ///< nodes with an orbit
  /// orbits[o][i][k]: node orbit_nodes[k] at speeds[i] for orders[o].
  std::vector<std::vector<std::vector<NodeOrbit>>> orbits;
  bool modal_damping = false;
  /// Stability of the system at the speeds (analyses/stability_check.hpp); any unstable speed
  /// makes the status Unstable.
  StabilityScan stability;
  int threads_used = 1;
  std::string thread_note;  ///< why fewer threads ran than asked for (empty when none)

  /// Phase lag [deg] in [0, 360) of a complex amplitude (see the header comment).
  static double phase_lag_deg(std::complex<double> x);
};

/// Runs the unbalance response on the context's linear system. Orbits are given for every node that
/// has both a ux and a uy sensor among the selected sensors and for every node carrying a selected
/// unbalance. Sensors are optional (empty list and no model sensors: orbits only). Throws
/// InputError for unknown names, constrained sensor DOFs, no unbalance (on a spinning node) or a
/// speed <= 0; NumericalError (naming speed and frequency) when D is singular.
UnbalanceResult run_unbalance(const model::Model& model, const UnbalanceSettings& settings,
                              const Context& context);

/// Tables "response" (speed_rpm, order, stable, per sensor <sensor>_amplitude_m|rad and
/// <sensor>_phase_deg) and "orbits" (speed_rpm, order, stable, node, major_m, minor_m,
/// inclination_deg, whirl); plots of amplitude (log) and phase lag versus speed, unstable speeds
/// marked.
AnalysisOutput unbalance_output(const model::Model& model, const UnbalanceSettings& settings,
                                const UnbalanceResult& result, const Context& context);

}  // namespace geardyn::analyses
