#pragma once
// Nonlinear frequency response by harmonic balance (docs/theory.md §19): the model's linear
// structure (any model: lumped points, rotors, joined reduced components) with the
// [[nonlinear_elements]] placed between its DOFs, excited by named harmonic forces at the
// fundamental (plus constant loads), unbalances, a base motion (nonlinear_forcing.hpp) or a gear
// mesh's TE, solved for periodic steady states with H harmonics by the alternating
// frequency-time method and traced by pseudo-arc-length continuation over the excitation
// frequency, the force level or the speed (K(W), C(W), W G and the unbalance force following
// it), passing turning points.
//
// Coordinates: the system's DOFs (n_modes = 0, exact for any damping, gyroscopic terms at the
// reference speed and hysteretic loss), or its n_modes lowest undamped modes at the reference
// speed (M = I, K = diag(w_r^2), C = Phi^T C Phi in full: non-proportional damping couples the
// modes), the nonlinear elements acting on u = B Phi eta. The modal form drops the static
// contribution of the higher modes; the note says how many modes were kept and the highest
// frequency, which should lie well above the highest harmonic H x the highest fundamental.
//
// Stability: from the turning points of the curve (a real multiplier crosses +1 at each fold:
// valid for every element, friction included, but blind to period doubling and Neimark-Sacker),
// by Hill's method on the harmonic-balance Jacobian (stability = "hill": all kinds, but for
// hysteretic elements an approximation; hbm/stability.hpp), or by the monodromy matrix of a time
// march over one period through the elements' actual laws (stability = "monodromy": all kinds,
// valid for stick-slip; 2 (2 n + states) + 1 marched periods per point; hbm/periodic_time.hpp).
#include <Eigen/Dense>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/hbm/nonlinear_element.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

enum class ContinuationParameter { Frequency, ForceLevel, Speed };
/// Direction of a base motion (nonlinear_forcing.hpp): none, a global axis or a rotation about it.
enum class BaseMotion { None, X, Y, Z, Rx, Ry, Rz };
enum class NonlinearStability { Fold, Hill, Monodromy };
/// Coordinates of the balance: the DOFs, the lowest modes, or the elements' relative coordinates
/// with the receptance (modes plus residual flexibility; nonlinear_condensed.hpp). Automatic:
/// physical for n_modes = 0, modal otherwise (resolved when the model file is read).
enum class NonlinearForm { Automatic, Physical, Modal, Condensed };

struct NonlinearResponseSettings : model::SettingsOf<NonlinearResponseSettings> {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double speed = 0.0;                    ///< reference speed [rad/s] (K(W), C(W), W G)
  std::vector<std::string> forces;       ///< [[forces]] at the fundamental
  std::vector<std::string> mean_forces;  ///< [[forces]] applied as constant loads
  ContinuationParameter parameter = ContinuationParameter::Frequency;
  double f_start = kNaN, f_stop = kNaN;        ///< fundamental range [rad/s] (frequency)
  double frequency = kNaN;                     ///< fundamental [rad/s] (force_level)
  double level_start = 0.0, level_stop = 1.0;  ///< force factor range (force_level)
  int harmonics = 7;
  int time_samples = 0;                           ///< 0: automatic (hbm::default_time_samples)
  int n_modes = 0;                                ///< 0: physical DOFs; > 0: that many modes
  NonlinearForm form = NonlinearForm::Automatic;  ///< the `coordinates` key
  std::vector<std::string> sensors;               ///< empty: all
  double step = 0.01;                             ///< first arc-length step (scaled)
  double max_step = 0.05;
  int max_points = 5000;
  double tolerance = 1e-9;
  NonlinearStability stability = NonlinearStability::Fold;
  // Unbalance, base motion and the speed continuation (nonlinear_forcing.hpp).
  std::vector<std::string> unbalances;           ///< [[unbalances]]: m e (rho W)^2
  double speed_start = kNaN, speed_stop = kNaN;  ///< speed range [rad/s] (speed)
  double order = 1.0;                            ///< fundamental = order x speed (speed)
  BaseMotion base_motion = BaseMotion::None;
  double base_acceleration = kNaN;  ///< amplitude [m/s^2 or rad/s^2]
  double base_displacement = kNaN;  ///< amplitude [m or rad]
};

struct NonlinearResponseResult {
  Status status = Status::Ok;
  std::string message;
  ContinuationParameter parameter = ContinuationParameter::Frequency;
  int harmonics = 0, time_samples = 0;
  int coordinates = 0;     ///< unknowns per harmonic coefficient (DOFs or modes)
  bool modal = false;      ///< modal coordinates
  bool condensed = false;  ///< the elements' coordinates (receptance form)
  double highest_mode_hz = std::numeric_limits<double>::quiet_NaN();  ///< modal form
  std::vector<std::string> sensors;
  std::vector<bool> sensor_rotational;
  std::vector<std::string> elements;  ///< element names
  std::vector<std::string> element_kinds;

  // Per continuation point.
  std::vector<double> frequency;  ///< fundamental [rad/s]
  std::vector<double> level;      ///< force factor
  std::vector<double> speed;      ///< reference speed [rad/s]
  std::vector<int> iterations;
  std::vector<double> residual;                      ///< relative residual at convergence
  std::vector<Eigen::MatrixXd> sensor_coefficients;  ///< sensors x (2H+1) per point
  Eigen::MatrixXd energy;                 ///< points x elements: dissipated per cycle [J]
  Eigen::MatrixXd stick, slip, open;      ///< points x elements: regime shares (NaN: none)
  std::vector<char> unstable;             ///< per point
  std::vector<double> max_real_exponent;  ///< Hill: max Re lambda [1/s] (NaN: fold method)
  std::vector<std::string> instability;   ///< Hill: kind per point ("none", "fold", ...)
  std::vector<int> turning_points;        ///< point indices where the parameter turns
  /// Point indices i where the branch-point test function changed sign since the point before
  /// (hbm::ContinuationResult::branch_points): a simple bifurcation of the same period lies
  /// between them. Known for the physical and modal forms (dense Newton algebra), not for the
  /// condensed form (iterative solves).
  std::vector<int> branch_points;

  /// Hysteresis loops of every element at the point of largest response (loop_point).
  int loop_point = -1;
  std::vector<hbm::ElementLoop> loops;
  std::vector<std::string> notes;
};

/// Amplitude of harmonic n >= 1 (or |mean| for n = 0) from coefficients c (HarmonicBasis layout).
double harmonic_amplitude(const Eigen::VectorXd& c, int n);
/// RMS over the period of the series with coefficients c: sqrt(a0^2 + sum (a^2 + b^2) / 2).
double series_rms(const Eigen::VectorXd& c);

/// Builds and traces the response (see the header comment). InputError for bad settings
/// (located by the context); a curve that ends early is Status::NotConverged with where and why.
NonlinearResponseResult run_nonlinear_response(const model::Model& model,
                                               const NonlinearResponseSettings& settings,
                                               const Context& context);

/// Tables "nonlinear_response" (per point: fundamental, force factor, stability, per sensor
/// first-harmonic amplitude, RMS and peak), "harmonics" (per point, sensor and harmonic:
/// amplitude and phase), "element_energy", "turning_points", "hysteresis_loops"; plots of the
/// response curve with unstable parts dashed, the energy per cycle and the loops.
AnalysisOutput nonlinear_response_output(const model::Model& model,
                                         const NonlinearResponseSettings& settings,
                                         const NonlinearResponseResult& result,
                                         const Context& context);

}  // namespace geardyn::analyses
