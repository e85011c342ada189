#pragma once
// Forced response of a cyclic gear (N identical sectors, one tooth per sector) to the engine-order
// harmonics of the tooth force, in the frame rotating with the gear, over a list of speeds
// (docs/theory.md §10, §12; A. Durastante, "Simulation of the Dynamic Response of Aeronautical
// Gears Equipped with Damper Rings", MSc thesis, Politecnico di Torino, 2018, sec. 1.3.3 and 5.2).
//
// Excitation (docs/theory.md §12.3). The gear turns at W [rad/s] in the positive sense about the
// cyclic axis; the mesh is fixed in space. Tooth j (j = 0..N-1, sector j, at angle j alpha, alpha =
// 2 pi / N) reaches the mesh j alpha / W earlier than tooth 0, so its load is tooth 0's load
// advanced by j alpha of rotation. Harmonic k of that load acts on tooth j as the physical force
//   f_j(t) = Re( R(j alpha) F_k e^{i k (W t + j alpha)} )                                   (1)
// at the node R(j alpha) x_e of sector j, where x_e is the excitation node in sector 0 and
// F_k in C^3 the complex amplitude (one-sided, gear::EngineOrderHarmonic / HarmonicComponents
// convention: A_k e^{i phase_k}) in global Cartesian components of sector 0; R rotates the force
// with its tooth, so tangential / radial / axial parts keep their meaning on every tooth.
//
// Sector pattern. e^{i k j alpha} = e^{i j 2 pi m / N} with m = k mod N. Two cases:
//   k = +h (mod N): f_j = e^{+i j phi_h} R(j alpha) f_0, phi_h = 2 pi h / N: exactly the pattern
//       of cyclic::CyclicSector::expand_to_sector for nodal diameter h. The response is
//       u_j = e^{+i j phi_h} R(j alpha) u_0 with u_0 = T_h q, (K_h - w^2 M_h + i w C_h) q =
//       T_h^H f_0, and as a modal sum over the modes of ND h (sector shapes psi_r = T_h phi_r,
//       phi_r^H M_h phi_r = 1):
//         u_0(w) = sum_r psi_r (psi_r^H f_0) / (w_r^2 - w^2 + 2 i zeta_r w_r w),  w = k W.   (2)
//       The pattern has phase k W t + h theta: in the rotating frame it travels against the
//       rotation (a backward wave); in the stationary frame the phase is (k - h) W t + h theta_s,
//       so for k = h it stands still in space (the deflection under the fixed mesh).
//   k = -h (mod N), 0 < h < N/2: f_j = e^{-i j phi_h} R(j alpha) f_0, the complex-conjugate
//       pattern (nodal diameter N - h in expand_to_sector's indexing). Its modes are the
//       conjugates of those of ND h (T_{-h} = conj T_h for real sector matrices), so
//         u_0(w) = sum_r conj(psi_r) (psi_r^T f_0) / (w_r^2 - w^2 + 2 i zeta_r w_r w)       (3)
//       and u_j = e^{-i j phi_h} R(j alpha) u_0. Phase k W t - h theta: a wave travelling with the
//       rotation (forward) in the rotating frame; with the stationary angle theta_s = theta + W t
//       the phase is (k + h) W t - h theta_s, i.e. for k = N - h the mesh frequency N W.
//   h = 0 and h = N/2: both signs give the same (standing) pattern; (2) is used.
// The physical response is Re(u_0 e^{i k W t}) at every sector-0 DOF: amplitude |u_0|, phase
// arg u_0 (cosine phase, same convention as F_k). f_0 holds the loads of sector 0 only; an
// excitation node on an interface is handled by T_h^H (a right-interface node's load is the load
// of the tooth whose node it is). Equations (2)-(3) are exact when all modes of ND h are summed
// and the damping is proportional (e.g. Rayleigh: zeta_r = a / (2 w_r) + b w_r / 2); with fewer
// modes they are the truncated modal superposition (docs/theory.md §12.4).
//
// Resonances: mode r of ND h is met by order k at W_r = w_r / k. Orders exciting ND h:
// k = h, N - h, N + h, 2N - h, ... (gear::nodal_diameter_orders).
//
// Several orders at once (Durastante 2018, sec. 5.2, "mode superposition" of close resonances):
// their responses have different frequencies k W, so they do not add as complex numbers. At each
// speed the result gives, per sensor, the sum of amplitudes sum_k |u_k| (an upper bound of the peak
// of the periodic signal sum_k Re(u_k e^{i k W t}), reached when the phases line up) and the exact
// RMS sqrt(sum_k |u_k|^2 / 2) (distinct frequencies are orthogonal over one revolution), next to
// the per-order curves.
//
// Cost: building a CyclicOrderModel is one pass over the mode shapes; each speed then costs
// O(modes x sensors) complex operations, no assembly or factorisation.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <complex>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/core/progress.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/gear/load_window.hpp"
#include "geardyn/reduce/reduced_component.hpp"
#include "geardyn/response/speed_peaks.hpp"

namespace geardyn::response {

/// Harmonic load of one engine order at one node of the tooth of sector 0.
struct ToothLoad {
  long node_id = 0;  ///< external node id (sector DOF list, or a ReducedComponent's full DOFs)
  /// Complex amplitude F_k [N] in global Cartesian components of sector 0, as in eq. (1).
  Eigen::Vector3cd force = Eigen::Vector3cd::Zero();
};

/// F_k = amplitude x direction (direction: real, e.g. tangential + radial/tangential ratio x e_r
/// + axial/tangential ratio x e_a, so that `amplitude` is the tangential harmonic).
ToothLoad tooth_load(long node_id, std::complex<double> amplitude,
                     const Eigen::Vector3d& direction);

/// A response output at one DOF of sector 0 (global Cartesian components 0..5 = ux..rz).
struct CyclicSensor {
  std::string name;
  long node_id = 0;
  int component = 0;
};

/// Modal damping of the modes of every nodal diameter: exactly one of the three forms.
struct ModalDamping {
  double damping_ratio = kNaN;     ///< zeta for every mode
  double q_factor = kNaN;          ///< Q for every mode: zeta = 1 / (2 Q) (docs/theory.md §14)
  Eigen::VectorXd damping_ratios;  ///< zeta per mode of the nodal diameter (index = mode - 1)
  std::vector<std::string> validate() const;
  /// zeta of mode `mode` (0-based). Precondition: validate() is empty; throws InputError when a
  /// per-mode list is too short.
  double ratio(Eigen::Index mode) const;
};

/// How engine order k relates to nodal diameter h (see the file comment).
enum class TravellingWave { Standing, Backward, Forward };
std::string_view to_string(TravellingWave w);

struct OrderRelation {
  bool conjugate = false;                          ///< k = -h (mod N) with 0 < h < N/2: eq. (3)
  TravellingWave wave = TravellingWave::Standing;  ///< in the rotating frame
  std::string rule;  ///< "h", "N-h", "N+h", "2N-h", ... (k = 0 mod N with h = 0: "N", "2N")
};
/// Throws InputError unless N >= 2, 0 <= h <= N/2, k >= 1 and k = +-h (mod N).
OrderRelation relate_order(int n_sectors, int nodal_diameter, int engine_order);

/// The modal data of one (nodal diameter, engine order) reduced to the sensors: evaluating the
/// response is a dense modes x sensors product per speed.
struct CyclicOrderModel {
  int n_sectors = 0;
  int nodal_diameter = 0;
  int engine_order = 0;
  OrderRelation relation;
  Eigen::VectorXd natural_frequency;  ///< w_r [rad/s] (sqrt of max(lambda, 0))
  Eigen::VectorXd damping_ratio;      ///< zeta_r
  Eigen::VectorXcd modal_force;       ///< psi_r^H f_0 (eq. 2) or psi_r^T f_0 (eq. 3) [N m]
  Eigen::MatrixXcd sensor_shapes;     ///< sensors x modes: psi_r (eq. 2) or conj(psi_r) (eq. 3)

  Eigen::Index num_modes() const { return natural_frequency.size(); }
  /// Resonance speeds W_r = w_r / k [rad/s].
  Eigen::VectorXd resonance_speeds() const;
  /// u_0 at the sensors for speed W [rad/s] (w = k W).
  Eigen::VectorXcd response(double speed) const;
  /// Rows: speeds; columns: sensors.
  Eigen::MatrixXcd response(const Eigen::VectorXd& speeds) const;
  /// Mode r's term alone at speed W (for checks).
  Eigen::VectorXcd modal_term(Eigen::Index r, double speed) const;
};

/// Builds the model of one (h, k) from the modes of ND h (cyclic::solve_cyclic_modes, or given:
/// `modes.sector_shapes` on sector.dofs(), `modes.eigen.eigenvalues`). `modes_used` > 0 keeps
/// only the lowest that many modes (0: all). `recovery`: the sector is a Craig-Bampton
/// component whose reduced DOFs are sector.dofs(); loads and sensors may then sit on any DOF of
/// recovery->full_dofs (interior values recovered by x = T q, loads projected by T^T).
/// Throws InputError when k is not +-h (mod N), the shapes do not fit the sector, a load or
/// sensor node (component) is not in the sector, a load is non-finite, or the damping is invalid.
CyclicOrderModel make_cyclic_order_model(const cyclic::CyclicSector& sector,
                                         const cyclic::NodalDiameterModes& modes, int engine_order,
                                         const std::vector<ToothLoad>& loads,
                                         const std::vector<CyclicSensor>& sensors,
                                         const ModalDamping& damping, int modes_used = 0,
                                         const reduce::ReducedComponent* recovery = nullptr);

/// Reference solution by direct sparse solves (one complex LU per speed) of the sector problem
///   (K_{+-h} - w^2 M_{+-h} + i w C_{+-h}) q = T_{+-h}^H f_0,  u_0 = T_{+-h} q,  w = k W,
/// with the sign of eq. (2)/(3). K, M, C: real symmetric sector matrices in sector.dofs() order
/// (C may be empty: 0 x 0). Rows: speeds; columns: sensors. Loads and sensors on sector DOFs.
/// Throws InputError as above; NumericalError when a dynamic stiffness is singular.
Eigen::MatrixXcd cyclic_direct_response(const Eigen::SparseMatrix<double>& K,
                                        const Eigen::SparseMatrix<double>& M,
                                        const Eigen::SparseMatrix<double>& C,
                                        const cyclic::CyclicSector& sector, int nodal_diameter,
                                        int engine_order, const std::vector<ToothLoad>& loads,
                                        const std::vector<CyclicSensor>& sensors,
                                        const Eigen::VectorXd& speeds);

/// One excitation: the loads of engine order k, exciting nodal diameter h.
struct CyclicExcitation {
  int nodal_diameter = 0;
  int engine_order = 0;
  std::vector<ToothLoad> loads;
};

/// The excitations of a tooth-force spectrum (gear::harmonic_components) at one node: F_k =
/// tangential e_t + radial e_r + axial e_a (unit vectors of the tooth at the node, sector 0).
std::vector<CyclicExcitation> excitations_from_harmonics(
    const std::vector<gear::HarmonicComponents>& harmonics, long node_id,
    const Eigen::Vector3d& tangential, const Eigen::Vector3d& radial, const Eigen::Vector3d& axial);

/// (h, k) pairs, k <= max_order, such that some mode of ND h (in `modes`) has its resonance
/// speed w_r / k within [speed_min, speed_max]: the combinations worth superposing.
struct OrderPair {
  int nodal_diameter = 0;
  int engine_order = 0;
};
std::vector<OrderPair> resonant_orders(const std::vector<cyclic::NodalDiameterModes>& modes,
                                       int n_sectors, double speed_min, double speed_max,
                                       int max_order);

struct CyclicForcedSettings {
  std::vector<CyclicExcitation> excitations;
  std::vector<CyclicSensor> sensors;
  Eigen::VectorXd speeds;  ///< reference speeds W [rad/s], positive, strictly increasing
  ModalDamping damping;
  int modes_used = 0;  ///< per nodal diameter, the lowest this many modes (0: all given)
  PeakOptions peaks;
};

/// The response of one excitation.
struct OrderResponse {
  int nodal_diameter = 0;
  int engine_order = 0;
  OrderRelation relation;
  Eigen::MatrixXcd displacement;  ///< speeds x sensors, complex amplitude u_0 [m or rad]
};

/// One mode met by one engine order.
struct CyclicResonance {
  int nodal_diameter = 0;
  int engine_order = 0;
  int mode = 0;                 ///< 1-based within the nodal diameter
  double frequency_hz = kNaN;   ///< w_r / 2 pi
  double speed = kNaN;          ///< W_r = w_r / k [rad/s]
  double damping_ratio = kNaN;  ///< zeta_r
  bool in_range = false;        ///< speeds.front() <= W_r <= speeds.back()
  /// |u_0| of this order's full modal sum at W_r, per sensor [m or rad].
  Eigen::VectorXd amplitude;
};

struct CyclicForcedResult {
  Status status = Status::Ok;
  std::string message;
  int n_sectors = 0;
  Eigen::VectorXd speeds;  ///< [rad/s]
  std::vector<CyclicSensor> sensors;
  std::vector<OrderResponse> orders;  ///< one per excitation, in the given order
  Eigen::MatrixXd amplitude_sum;      ///< speeds x sensors: sum over orders of |u| (upper bound)
  Eigen::MatrixXd amplitude_rms;      ///< speeds x sensors: sqrt(sum |u|^2 / 2)
  std::vector<CyclicResonance> resonances;  ///< by excitation, then mode
  /// Peaks of each order's amplitude curve (curve = excitation index) and of amplitude_sum
  /// (curve = -1), by sensor.
  std::vector<SpeedPeak> peaks;
  double seconds = 0;

  /// "cyclic_forced_response": speed_rpm, per order and sensor <sensor>_h<h>_k<k>_amplitude_m
  /// and ..._phase_deg, per sensor <sensor>_sum_amplitude_m and <sensor>_rms_m.
  Table response_table() const;
  /// "cyclic_resonances": nodal_diameter, engine_order, order_rule, wave, mode, frequency_hz,
  /// resonance_speed_rpm, damping_ratio, q_factor, in_range, per sensor <sensor>_amplitude_m.
  Table resonance_table() const;
  /// "cyclic_response_peaks": the peaks in the columns of core/peak_table.hpp over speed [rpm];
  /// curve "ND <h> EO <k>", or "sum" for the superposed sum.
  Table peak_table() const;
};

/// Runs every excitation against the modes of its nodal diameter (`modes` must hold that ND)
/// and superposes them as described above. Throws InputError for invalid settings (k vs h,
/// speeds, missing nodes, damping, a nodal diameter without modes). Progress: excitations.
CyclicForcedResult run_cyclic_forced_response(const cyclic::CyclicSector& sector,
                                              const std::vector<cyclic::NodalDiameterModes>& modes,
                                              const CyclicForcedSettings& settings,
                                              const reduce::ReducedComponent* recovery = nullptr,
                                              Progress& progress = null_progress());

}  // namespace geardyn::response
