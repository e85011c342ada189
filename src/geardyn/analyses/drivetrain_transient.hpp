#pragma once
// The drivetrain_transient analysis (docs/theory.md §16): the nonlinear flexible drivetrain in
// the time domain.
//
//   model (shafts, housings and reduced bodies, [[contacts]], [[bolts]], [[bushings]],
//   [[rolling_bearings]], [[gear_meshes]] with their tooth contact, [[drivers]], [[loads]],
//   [[clutches]], [[virtual_sensors]])
//     -> assembled linear part (without the meshes' linear springs) + placed elements
//        (drivetrain::build_drivetrain)
//     -> static equilibrium under load and preloads (drivetrain::solve_static), reported
//     -> linearisation there: the modal table in the ADAMS layout (drivetrain::linearise)
//     -> adaptive integration from the equilibrium (generalised-alpha or SUNDIALS IDA) with
//        output at the fixed sample rate
//     -> channels: virtual sensors (displacement, velocity, acceleration), element forces,
//        mesh force and dynamic transmission error, driver and load speeds and torques;
//        peaks, RMS and spectra.
#include <Eigen/Dense>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/order_analysis.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/drivetrain/linearisation.hpp"
#include "geardyn/drivetrain/modal_frf.hpp"
#include "geardyn/drivetrain/static_equilibrium.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/transient/adaptive.hpp"

namespace geardyn::analyses {

enum class DrivetrainIntegrator { GeneralizedAlpha, Ida };
/// What the FRF table gives per unit load: receptance, mobility (i w x) or accelerance (-w^2 x).
enum class FrfQuantity { Displacement, Velocity, Acceleration };

struct DrivetrainTransientSettings : model::SettingsOf<DrivetrainTransientSettings> {
  double duration = model::kNaN;  ///< [s]
  /// 2 pi x the output samples per second [rad/s] (the key sample_rate_hz, converted like every
  /// _hz key); sample_rate() gives it in Hz.
  double sample_angular_rate = model::kNaN;
  double sample_rate() const { return sample_angular_rate / (2.0 * 3.14159265358979323846); }
  DrivetrainIntegrator integrator = DrivetrainIntegrator::GeneralizedAlpha;
  double relative_tolerance = 1e-4;
  double absolute_tolerance = 1e-9;  ///< [m, rad]
  double max_step = model::kNaN;     ///< [s] (NaN: 1 / sample_rate)
  double rho_infinity = 0.8;
  bool static_start = true;          ///< start from the static equilibrium (else from q = 0)
  int modes = 20;                    ///< linearised modes tabulated (0: no linearisation)
  std::vector<std::string> sensors;  ///< virtual sensors recorded (empty: all)
  double spectrum_start = 0.0;       ///< spectra over [spectrum_start, duration] [s]
  /// FRF by modal superposition at the operating point (docs/theory.md §16.14): the load is a
  /// [[virtual_sensors]] entry (a unit force or moment at its node along its DOF / direction) or
  /// a [[gear_meshes]] entry (a unit pair of opposite forces along its line of action). Empty:
  /// no FRF.
  std::string frf_excitation;
  std::vector<double> frf_band;  ///< [w_min, w_max] [rad/s] (key frf_band_hz); empty: default
  int frf_points = 400;
  int frf_modes = 0;                  ///< modes in the sum (0: all `modes`)
  bool frf_static_correction = true;  ///< add the truncated modes' static part
  FrfQuantity frf_quantity = FrfQuantity::Displacement;
  /// Order analysis of the record (as the analysis order_analysis, docs/theory.md §14): the
  /// channels analysed (columns of time_history; empty: none) against the angle channel
  /// `order_reference` (e.g. a mesh's "<mesh>_pinion_angle_rad"), from the sample after which
  /// that angle keeps increasing. order_options.orders are of that shaft.
  std::vector<std::string> order_channels;
  std::string order_reference;
  OrderAnalysisOptions order_options;
};

/// One recorded quantity.
struct DrivetrainChannel {
  std::string name;   ///< column name with its unit suffix, e.g. "hub_x_acc_m_per_s2"
  std::string unit;   ///< "m/s^2"
  std::string group;  ///< for plots: "displacement", "velocity", "acceleration", "force",
                      ///< "torque", "speed", "dte"
};

/// Where a mesh's order analysis reads its record: gear 1's spin angle and the DTE channel.
struct DrivetrainMeshOrders {
  std::string mesh;
  int teeth1 = 0;
  std::size_t angle_channel = 0, dte_channel = 0;
};

struct DrivetrainTransientResult {
  Status status = Status::Ok;
  std::string message;
  drivetrain::StaticResult equilibrium;
  std::vector<std::string> held_names;  ///< drivers / motors held in the static solution
  drivetrain::Linearisation linearisation;
  bool linearised = false;
  /// The linearised mode shapes at the virtual sensors (modes x sensors; each mode scaled to 1
  /// at its largest sensor).
  std::vector<std::string> shape_sensors;
  Eigen::MatrixXcd shape_at_sensors;
  std::vector<DrivetrainChannel> channels;
  std::vector<DrivetrainMeshOrders> mesh_orders;  ///< meshes with teeth1 and a spinning gear 1
  std::vector<double> time;
  Eigen::MatrixXd values;  ///< samples x channels (rows filled up to time.size())
  transient::AdaptiveSummary integration;
  /// Per event function of the system: its description and the fraction of samples it was
  /// positive (closed / in contact).
  std::vector<std::string> switch_names;
  std::vector<double> closed_fraction;
  /// The modal FRF (settings.frf_excitation given): one output per recorded virtual sensor
  /// (frf_outputs, frf_output_units "m" or "rad"), the load's unit ("N" or "N m"); a direct
  /// solve as a check at the lowest kept mode in the band, the band's middle and its top
  /// (frf_check_hz, frf_check_deviation: the largest |modal - direct| / max_j |direct| there).
  bool has_frf = false;
  drivetrain::ModalFrf frf;
  std::vector<std::string> frf_outputs, frf_output_units;
  std::string frf_load_unit;
  std::vector<double> frf_check_hz, frf_check_deviation;
  /// Orbits: pairs of displacement channels of two sensors on the same node along different
  /// directions (first against second).
  std::vector<std::pair<std::size_t, std::size_t>> orbits;
  std::vector<std::string> static_rows_element, static_rows_quantity, static_rows_unit;
  std::vector<double> static_rows_value;
  double run_time_s = 0.0;
};

/// A problem of the FRF keys (frf_*) against the model: the key (relative to the analysis),
/// what was expected and what was found; nullopt when they are fine or no FRF is asked for.
struct SettingsProblem {
  std::string key, expected, found, hint;
};
std::optional<SettingsProblem> frf_settings_problem(const model::Model& model,
                                                    const DrivetrainTransientSettings& settings);

/// Validates the settings against the model (InputError at the analysis keys), builds the
/// drivetrain, solves the static equilibrium, linearises and integrates. A numerical failure
/// (static equilibrium not found, a step that cannot converge) comes back as a non-Ok status
/// with the samples up to the failure and a message naming the time and the element.
DrivetrainTransientResult run_drivetrain_transient(const model::Model& model,
                                                   const DrivetrainTransientSettings& settings,
                                                   const Context& context);

/// Tables "static_equilibrium", "eigen" (mode, undamped_natural_frequency_hz, damping_ratio,
/// real_hz, imaginary_hz), "mode_shapes" (at the virtual sensors), "time_history" (or the file
/// time_history.h5 for long records), "summary" (peak and RMS per channel), "spectrum",
/// "orders_<mesh>" (the DTE amplitude at mesh orders 1-3 over gear 1's speed, by a least-squares
/// fit in gear 1's angle over successive windows of the record),
/// "contacts" (closed fraction per switch), "integration" and, with frf_excitation, "frf"
/// (magnitude and phase per sensor over the band); plots of the time histories by group, the
/// orbits of sensor pairs, the spectra and the FRF; notes on the integration and trust.
AnalysisOutput drivetrain_transient_output(const model::Model& model,
                                           const DrivetrainTransientSettings& settings,
                                           const DrivetrainTransientResult& result,
                                           const Context& context);

}  // namespace geardyn::analyses
