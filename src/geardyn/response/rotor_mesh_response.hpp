#pragma once
// Forced response of a geared rotor (fe::LinearSystem, docs/theory.md §1) to harmonic gear-mesh
// forces at the gear-mesh orders, over a list of reference speeds (issue [mesh-excitation] section
// 6).
//
// Excitation. Order p of the mesh of gear 1 (teeth z1, spin ratio r1 = speed_ratio of its node)
// is the force pair of complex amplitude F_p [N] along the line of action
// (fe/gear_mesh_element.hpp)
//   f(t) = Re(F_p v e^{i w t}),   w = p z1 |r1| W,
// v the mesh vector of the element (mesh compression delta = v . q): a positive F_p presses the
// teeth together, the force k_m e_p of a transmission-error harmonic e_p. v is a generalised
// force: its translation parts at the two gear nodes are +-n and its rotation parts the moments
// of the force about the nodes ((P - x) x n at the pitch point P).
//
// Response at reference speed W and frequency w (docs/theory.md §5, analyses/harmonic.hpp):
//   D(w, W) q = f,  D = K(W) - w^2 M + i w (C(W) + W G + B diag(c) B^T) + i K_loss.
// Two solvers:
//   ModalReduced: q = Phi eta with Phi the lowest n undamped modes at zero speed, K(0) Phi =
//     M Phi Lambda, Phi^T M Phi = I, computed once (eig::solve_symmetric; a non-symmetric K
//     contributes its symmetric part to the basis only), optionally with one residual vector,
//     the static response (K(0) - sigma M)^{-1} v made M-orthonormal to Phi (static correction
//     of the modes left out). Every matrix is projected once (K(0), C(0), G, K_loss, modal
//     damping; speed-dependent bearings as Phi^T (K(W) - K(0)) Phi per speed), and each speed
//     and order costs one dense n x n complex LU. The projection is a Galerkin approximation:
//     it converges to the direct solution as n grows (tests/forced).
//   Direct: one sparse complex LU (linalg::SparseLU, UMFPACK) of the sparse part of D per speed
//     and order, modal damping added by the Sherman-Morrison-Woodbury identity (r extra solves).
//     The reference for the modal path; cost grows with the model.
// Output per sensor, order and speed: complex amplitude of the physical response Re(u e^{i w t})
// (amplitude |u|, cosine phase arg u), the sum over orders of |u| (upper bound of the peak of the
// multi-order signal), the RMS sqrt(sum |u|^2 / 2), and the resonance peaks of each curve with
// their half-power Q (speed_peaks.hpp) where resolvable.
#include <Eigen/Dense>
#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/core/progress.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/response/speed_peaks.hpp"

namespace geardyn::response {

/// Index of the gear mesh named `name` in model.gear_meshes; InputError listing the names if none.
int find_gear_mesh(const model::Model& model, const std::string& name);

/// v of gear mesh `mesh_index` in the system's equation numbering (constrained DOFs dropped):
/// the load vector of a unit force pair along the line of action. Throws InputError for an
/// unknown gear node and the geometry errors of fe::gear_mesh_geometry.
Eigen::VectorXd mesh_load(const model::Model& model, const fe::LinearSystem& system,
                          int mesh_index);

/// Mesh frequency per unit reference speed, z1 |r1| [rad/s per rad/s]. InputError when teeth1 is
/// not given (0) or gear 1 does not spin (r1 = 0).
double mesh_frequency_per_speed(const model::Model& model, const fe::LinearSystem& system,
                                int mesh_index);

/// A response output: one equation of the system.
struct RotorSensor {
  std::string name;
  int equation = -1;
  bool rotational = false;  ///< rx, ry, rz (rad) rather than ux, uy, uz (m)
};

/// The model's sensors by name (all when `names` is empty). InputError for an unknown name, an
/// unknown node or a constrained DOF.
std::vector<RotorSensor> rotor_sensors(const model::Model& model, const fe::LinearSystem& system,
                                       const std::vector<std::string>& names = {});

/// Frequency response on a modal basis (see the file comment). Keeps a reference to `system`.
class ModalRotorModel {
 public:
  /// `loads`: n x m load vectors; `outputs`: equations read; `n_modes` >= 1 modes at zero speed;
  /// `residual_vectors`: append the static responses to the loads (static correction).
  /// Throws InputError for bad sizes, NumericalError when the eigen-solve finds no mode or the
  /// shifted stiffness for the residual vectors is singular. Fewer modes than asked: status().
  ModalRotorModel(const fe::LinearSystem& system, const Eigen::MatrixXd& loads,
                  const std::vector<int>& outputs, int n_modes, bool residual_vectors = false);

  /// Response at the outputs (outputs x loads) at reference speed W [rad/s], frequency w [rad/s].
  /// Throws NumericalError when the reduced dynamic stiffness is singular.
  Eigen::MatrixXcd response(double speed, double omega) const;

  int basis_size() const { return static_cast<int>(Phi_.cols()); }
  int modes() const { return modes_; }
  /// Highest natural frequency of the basis modes [rad/s].
  double highest_mode() const { return highest_; }
  Status status() const { return status_; }
  const std::string& message() const { return message_; }

 private:
  const fe::LinearSystem& system_;
  Eigen::MatrixXd Phi_;                     // basis, n x nb, M-orthonormal
  Eigen::MatrixXd Kr_, Cr_, Gr_, Lr_, Mr_;  // projected K(0), C(0) + modal, G, K_loss, M
  Eigen::MatrixXd Fr_;                      // Phi^T loads
  Eigen::MatrixXd Sr_;                      // outputs x nb: rows of Phi
  int modes_ = 0;
  double highest_ = 0.0;
  Status status_ = Status::Ok;
  std::string message_;
};

/// The same by direct sparse solves (see the file comment). Keeps a reference to `system`.
class DirectRotorSolver {
 public:
  DirectRotorSolver(const fe::LinearSystem& system, const Eigen::MatrixXd& loads,
                    const std::vector<int>& outputs);
  /// Throws NumericalError when the dynamic stiffness is singular.
  Eigen::MatrixXcd response(double speed, double omega) const;

 private:
  const fe::LinearSystem& system_;
  Eigen::MatrixXcd loads_;
  std::vector<int> outputs_;
};

/// One mesh-order harmonic of the mesh force.
struct MeshOrderForce {
  int order = 1;                        ///< multiple p >= 1 of the mesh frequency
  std::complex<double> amplitude{1.0};  ///< F_p [N] along the line of action (see file comment)
};

enum class RotorForcedMethod { ModalReduced, Direct };

struct RotorForcedSettings {
  std::string gear_mesh;                  ///< name in model.gear_meshes
  std::vector<MeshOrderForce> harmonics;  ///< distinct orders
  std::vector<RotorSensor> sensors;
  Eigen::VectorXd speeds;  ///< reference speeds W [rad/s], positive, strictly increasing
  RotorForcedMethod method = RotorForcedMethod::ModalReduced;
  int n_modes = 30;              ///< ModalReduced: modes at zero speed in the basis
  bool residual_vectors = true;  ///< ModalReduced: add the static correction (file comment)
  PeakOptions peaks;
  /// Further equations whose response is kept (RotorForcedResult::extra), e.g. the coordinates
  /// of a joined housing for its surface velocities; no peaks or tables.
  std::vector<int> extra_outputs;
  std::vector<std::string> validate() const;
};

struct RotorForcedResult {
  Status status = Status::Ok;
  std::string message;
  RotorForcedMethod method = RotorForcedMethod::ModalReduced;
  std::string gear_mesh;
  double mesh_frequency_per_speed = kNaN;  ///< z1 |r1|
  Eigen::VectorXd speeds;                  ///< [rad/s]
  std::vector<MeshOrderForce> harmonics;
  std::vector<RotorSensor> sensors;
  std::vector<Eigen::MatrixXcd> displacement;  ///< per harmonic: speeds x sensors [m or rad]
  std::vector<Eigen::MatrixXcd> extra;         ///< per harmonic: speeds x settings.extra_outputs
  Eigen::MatrixXd amplitude_sum;               ///< speeds x sensors: sum over orders of |u|
  Eigen::MatrixXd amplitude_rms;               ///< speeds x sensors: sqrt(sum |u|^2 / 2)
  std::vector<SpeedPeak> peaks;   ///< curve = harmonic index, -1 for the sum; by sensor
  int basis_size = 0;             ///< ModalReduced: modes (+ residual vectors) used
  double highest_mode_hz = kNaN;  ///< ModalReduced: highest basis mode [Hz]
  double seconds = 0;

  /// "mesh_forced_response": speed_rpm, per order p and sensor <sensor>_p<p>_amplitude_<unit>
  /// and _phase_deg, <sensor>_sum_amplitude_<unit>, <sensor>_rms_<unit>.
  Table response_table() const;
  /// "mesh_resonances": the peaks in the columns of core/peak_table.hpp over speed [rpm]; curve
  /// "order <p>", or "sum" for the sum over orders (the excitation frequency at a peak is
  /// p mesh_frequency_per_speed speed).
  Table resonance_table() const;
  std::string brief_report() const;
};

/// Runs the mesh-order forced response over speed. Throws InputError for invalid settings
/// (unknown mesh, no teeth1, bad speeds, repeated or non-positive orders, no sensors),
/// NumericalError for singular solves. Progress: speeds.
RotorForcedResult run_mesh_forced_response(const model::Model& model,
                                           const fe::LinearSystem& system,
                                           const RotorForcedSettings& settings,
                                           Progress& progress = null_progress());

}  // namespace geardyn::response
