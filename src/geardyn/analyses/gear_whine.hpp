#pragma once
// gear_whine: how loud a gearbox whines over speed. The transmission error of a gear pair at
// each mesh order excites the rotor system with its flexible (reduced) housing; the analysis
// gives the acceleration at virtual accelerometers per mesh order over speed and their sum, and,
// for a radiating housing, the equivalent radiated power of its surface, the sound power of a
// 0-order spherical radiator and the sound pressure level at a distance (issue [nvh-acoustics]
// items 2 and 3; docs/theory.md §14, §18).
//
// Chain (one linear model, frequency domain):
//   TE of the pair (STE file, LTCA table or the loaded tooth contact analysis) -> the blocked
//   mesh force of mesh order p, F_p = k_mean e_p to first order (analyses/tooth_force.hpp)
//   -> the forced response over speed, the mesh order p at w = p z1 |r1| W
//      (response/rotor_mesh_response.hpp, modal basis with static correction)
//   -> acceleration a = -w^2 u at the sensors
//   -> the housing's reduced coordinates q_b = B u (fe::body_coordinates) -> the surface
//      translations by the Craig-Bampton recovery -> normal velocities v_n = i w n . u
//   -> ERP = 1/2 rho c sigma sum_i A_i |v_n,i|^2 per order (acoustics/), summed over orders
//      (different frequencies: powers add) -> L_W = 10 lg(P / 1e-12 W)
//   -> the 0-order radiator of the mean normal velocity and L_p at a distance.
// Bad input throws InputError located by the context (check_gear_whine_inputs runs before any
// analysis); a numerical failure throws NumericalError naming the analysis.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/acoustics/radiation.hpp"
#include "geardyn/analyses/context.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/response/rotor_mesh_response.hpp"

namespace geardyn::analyses {

struct GearWhineSettings : model::SettingsOf<GearWhineSettings> {
  std::string gear_mesh;             ///< [[gear_meshes]] name (empty: the only one)
  std::string pair;                  ///< [[gear_pairs]] entry whose TE excites the mesh
  int max_mesh_order = 3;            ///< orders 1 .. this
  std::vector<std::string> sensors;  ///< virtual accelerometers (empty: all sensors)
  std::vector<double> speeds;        ///< reference speeds [rad/s]
  int n_modes = 30;
  bool residual_vectors = true;
  // Radiation (radiating_solid empty: none).
  std::string radiating_solid;  ///< a [[solids]] entry joined to the rotor (spiders)
  std::string radiating_set;    ///< node set of its mesh (empty: its whole exterior)
  double radiation_efficiency = 1.0;
  double air_density = 1.2041;           ///< [kg/m^3]
  double speed_of_sound = 343.4;         ///< [m/s]
  double radiator_radius = model::kNaN;  ///< [m] (NaN: the radius of a sphere of equal area)
  double distance = 1.0;                 ///< [m] for the sound pressure level
  double directivity = 1.0;              ///< Q
  std::vector<double> map_speeds;        ///< [rad/s] speeds of the per-face ERP maps
  double acceleration_reference = 1e-6;  ///< [m/s^2] 0 dB of acceleration levels (ISO 1683)
};

/// The radiated power of the housing per speed (rows) and mesh order (columns) [W].
struct WhineRadiation {
  std::string solid;
  std::string surface_set;
  acoustics::Surface surface;  ///< the radiating faces (mesh node indices)
  double area_m2 = 0;
  int surface_nodes = 0;
  int surface_faces = 0;
  double radiator_radius_m = 0;
  Eigen::MatrixXd erp_w;             ///< speeds x orders
  Eigen::MatrixXd radiator_w;        ///< speeds x orders (0-order radiator)
  Eigen::MatrixXd mean_velocity_ms;  ///< speeds x orders: v~ with S v~^2 = sum A |v_n|^2
  Eigen::VectorXd erp_total_w, radiator_total_w;  ///< sums over orders
  /// Per map speed: per face ERP summed over orders [W], with the face areas.
  std::vector<double> map_speeds;
  std::vector<Eigen::VectorXd> face_erp_w;
};

struct GearWhineResult {
  response::RotorForcedResult response;        ///< displacements per order at the sensors
  std::vector<Eigen::MatrixXcd> acceleration;  ///< per order: speeds x sensors [m/s^2 or rad/s^2]
  Eigen::MatrixXd acceleration_sum;            ///< speeds x sensors: sum over orders of |a|
  Eigen::MatrixXd acceleration_rms;            ///< speeds x sensors: sqrt(sum |a|^2 / 2)
  std::vector<response::SpeedPeak> acceleration_peaks;  ///< curve: order index, -1 the sum
  // The excitation.
  double static_force_n = 0;
  std::string ste_source;
  double te_peak_to_peak_m = 0;        ///< of the STE curve over one mesh cycle
  std::vector<double> te_amplitude_m;  ///< per order: 0-peak amplitude e_p
  std::vector<double> te_phase_rad;
  bool has_radiation = false;
  WhineRadiation radiation;

  std::size_t sensor_index(const std::string& name) const;
  /// Sound power level [dB re 1e-12 W] of the ERP summed over orders at each speed.
  Eigen::VectorXd sound_power_level_db() const;
  /// Sound pressure level [dB re 2e-5 Pa] at the distance from the ERP sound power.
  Eigen::VectorXd sound_pressure_level_db(const GearWhineSettings& s) const;
};

GearWhineResult run_gear_whine(const model::Model& model, const GearWhineSettings& settings,
                               const Context& context);

AnalysisOutput gear_whine_output(const model::Model& model, const GearWhineSettings& settings,
                                 const GearWhineResult& result, const Context& context);

/// What the parser cannot check: the pair's STE resolves max_mesh_order; the radiating solid is
/// joined to the rotor and has a mesh; its set exists and lies on the exterior. InputError
/// located by `context`.
void check_gear_whine_inputs(const model::Model& model, const GearWhineSettings& settings,
                             const Context& context);

}  // namespace geardyn::analyses
