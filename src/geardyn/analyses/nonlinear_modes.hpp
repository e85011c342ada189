#pragma once
// Nonlinear modes (docs/theory.md §19.8): backbone curves -- frequency, damping ratio and energy
// dissipated per cycle against amplitude -- of the model's linear structure with its
// [[nonlinear_elements]], by the extended periodic motion concept (hbm/nonlinear_modes.hpp;
// Krack 2015): the free periodic motion of the system with an artificial negative
// mass-proportional damping xi that feeds what the damping and the elements dissipate, traced by
// continuation in the modal amplitude from the linear mode. Coordinates as nonlinear_response
// (physical DOFs, or the lowest n_modes modes).
#include <Eigen/Dense>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

struct NonlinearModesSettings : model::SettingsOf<NonlinearModesSettings> {
  double speed = 0.0;             ///< reference speed [rad/s]
  int mode = 1;                   ///< 1-based index of the linear mode the curve starts from
  double amplitude_start = 1e-4;  ///< modal amplitude a [sqrt(kg) m]
  double amplitude_stop = std::numeric_limits<double>::quiet_NaN();
  int harmonics = 7;
  int time_samples = 0;  ///< 0: automatic
  int n_modes = 0;       ///< 0: physical DOFs
  std::vector<std::string> sensors;
  double max_step = 0.1;
  int max_points = 2000;
  double tolerance = 1e-10;
};

struct NonlinearModesResult {
  Status status = Status::Ok;
  std::string message;
  int harmonics = 0, time_samples = 0, coordinates = 0;
  bool modal = false;
  double linear_frequency = 0.0;  ///< [rad/s] of the mode at rest (elements linearised)
  double linear_damping_ratio = 0.0;
  std::vector<std::string> sensors, elements;
  std::vector<bool> sensor_rotational;
  std::vector<double> amplitude;                     ///< modal amplitude a [sqrt(kg) m]
  std::vector<double> frequency;                     ///< [rad/s]
  std::vector<double> damping_ratio;                 ///< xi / (2 omega)
  std::vector<double> energy;                        ///< dissipated per cycle [J]
  std::vector<Eigen::MatrixXd> sensor_coefficients;  ///< sensors x (2H+1) per point
  Eigen::MatrixXd element_energy;                    ///< points x elements [J]
};

NonlinearModesResult run_nonlinear_modes(const model::Model& model,
                                         const NonlinearModesSettings& settings,
                                         const Context& context);

/// Table "backbone" (per point: modal amplitude, frequency, damping ratio, energy per cycle, per
/// sensor first-harmonic amplitude and RMS, per element energy) and plots of frequency and
/// damping ratio against the first-harmonic amplitude of the first sensor.
AnalysisOutput nonlinear_modes_output(const model::Model& model,
                                      const NonlinearModesSettings& settings,
                                      const NonlinearModesResult& result, const Context& context);

}  // namespace geardyn::analyses
