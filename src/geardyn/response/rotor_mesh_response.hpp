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
//     damping). Per speed (ModalRotorModel::at) the speed-dependent part is set up once,
//     K_r(W) = K_r(0) + Phi^T (K(W) - K(0)) Phi and C_r(W) + W G_r, and reused for every order;
//     each order then costs one dense n x n complex LU. The projection is a Galerkin
//     approximation: it converges to the direct solution as n grows (tests/response).
//   Direct: one sparse complex LU (UMFPACK) of the sparse part of D per speed and order, modal
//     damping added by the Sherman-Morrison-Woodbury identity (r extra solves). The sparsity
//     pattern of D is the same for every speed and frequency (the union of those of K, M, C, G,
//     K_loss and the speed-dependent bearing blocks), so the symbolic analysis (fill-reducing
//     ordering) is done once for the whole run and each (speed, order) is a numeric
//     factorisation only; the values of K(W), C(W) + W G are set up once per speed
//     (DirectRotorSolver::at). The reference for the modal path; cost grows with the model.
// Both give the full equation vector q on request (full_response), e.g. to expand a housing's
// surface velocities from the rotor system's response.
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

  /// The reduced model at one reference speed W [rad/s]: K_r(W) and C_r(W) + W G_r assembled
  /// once, reused for every frequency (mesh order) asked of it. Keeps a reference to the model.
  class SpeedPoint {
   public:
    double speed() const { return speed_; }
    /// Response at the outputs (outputs x loads) at frequency w [rad/s]. Throws NumericalError
    /// when the reduced dynamic stiffness is singular.
    Eigen::MatrixXcd response(double omega) const;
    /// Reduced coordinates eta (basis_size x loads), q = basis() eta.
    Eigen::MatrixXcd coordinates(double omega) const;
    /// Full equation vector q = Phi eta (system size x loads).
    Eigen::MatrixXcd full_response(double omega) const;

   private:
    friend class ModalRotorModel;
    SpeedPoint(const ModalRotorModel& model, double speed);
    const ModalRotorModel* model_;
    double speed_;
    Eigen::MatrixXd K_, C_;  // K_r(W), C_r(W) + W G_r
  };

  SpeedPoint at(double speed) const { return SpeedPoint(*this, speed); }

  /// Response at the outputs (outputs x loads) at reference speed W [rad/s], frequency w [rad/s]
  /// (= at(W).response(w): for several frequencies at one speed, use at()).
  /// Throws NumericalError when the reduced dynamic stiffness is singular.
  Eigen::MatrixXcd response(double speed, double omega) const { return at(speed).response(omega); }
  /// Full equation vector q (system size x loads) at (W, w).
  Eigen::MatrixXcd full_response(double speed, double omega) const {
    return at(speed).full_response(omega);
  }
  /// The basis Phi (system size x basis_size), M-orthonormal.
  const Eigen::MatrixXd& basis() const { return Phi_; }

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
/// The symbolic analysis of the sparse LU is shared by all calls (the first factorisation does
/// it): the solver is not safe to use from several threads at once.
class DirectRotorSolver {
 public:
  DirectRotorSolver(const fe::LinearSystem& system, const Eigen::MatrixXd& loads,
                    const std::vector<int>& outputs);
  ~DirectRotorSolver();
  DirectRotorSolver(const DirectRotorSolver&) = delete;
  DirectRotorSolver& operator=(const DirectRotorSolver&) = delete;

  /// The values of K(W) and C(W) + W G on the solver's pattern at one reference speed W
  /// [rad/s], reused for every frequency. Keeps a reference to the solver.
  class SpeedPoint {
   public:
    double speed() const { return speed_; }
    /// Response at the outputs (outputs x loads) at frequency w [rad/s]. Throws NumericalError
    /// when the dynamic stiffness is singular.
    Eigen::MatrixXcd response(double omega) const;
    /// Full equation vector q (system size x loads).
    Eigen::MatrixXcd full_response(double omega) const;

   private:
    friend class DirectRotorSolver;
    SpeedPoint(const DirectRotorSolver& solver, double speed);
    const DirectRotorSolver* solver_;
    double speed_;
    Eigen::VectorXd k_, c_;  // values of K(W), C(W) + W G on the pattern
  };

  SpeedPoint at(double speed) const { return SpeedPoint(*this, speed); }
  /// = at(W).response(w). Throws NumericalError when the dynamic stiffness is singular.
  Eigen::MatrixXcd response(double speed, double omega) const { return at(speed).response(omega); }
  /// = at(W).full_response(w).
  Eigen::MatrixXcd full_response(double speed, double omega) const {
    return at(speed).full_response(omega);
  }
  /// Symbolic analyses done so far (1 after the first solve: shared by all speeds and orders).
  int symbolic_analyses() const;
  /// Numeric factorisations done so far (one per speed and frequency solved).
  int numeric_factorizations() const;

 private:
  struct Factorization;
  Eigen::MatrixXcd solve(const SpeedPoint& point, double omega) const;

  const fe::LinearSystem& system_;
  Eigen::MatrixXcd loads_;
  std::vector<int> outputs_;
  std::unique_ptr<Factorization> lu_;  // pattern, per-matrix values on it, UMFPACK LU
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
  /// Keep the response coordinates of every speed and order (RotorForcedResult::coordinates):
  /// the full equation vector q is then available by RotorForcedResult::full_response. Memory:
  /// speeds x orders x basis_size (ModalReduced) or x system size (Direct) complex numbers.
  bool keep_coordinates = false;
  PeakOptions peaks;
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
  Eigen::MatrixXd amplitude_sum;               ///< speeds x sensors: sum over orders of |u|
  Eigen::MatrixXd amplitude_rms;               ///< speeds x sensors: sqrt(sum |u|^2 / 2)
  std::vector<SpeedPeak> peaks;   ///< curve = harmonic index, -1 for the sum; by sensor
  int basis_size = 0;             ///< ModalReduced: modes (+ residual vectors) used
  double highest_mode_hz = kNaN;  ///< ModalReduced: highest basis mode [Hz]
  double seconds = 0;
  /// keep_coordinates only: per harmonic, coordinates x speeds, the response to F_p (amplitude
  /// included): the reduced coordinates eta (ModalReduced, q = basis eta) or q itself (Direct).
  std::vector<Eigen::MatrixXcd> coordinates;
  Eigen::MatrixXd basis;  ///< keep_coordinates and ModalReduced: Phi (system size x basis_size)

  /// Full equation vector q [m, rad] of harmonic `harmonic` at speed index `speed`: the complex
  /// amplitude of Re(q e^{i w t}). std::logic_error unless run with keep_coordinates;
  /// std::out_of_range for bad indices.
  Eigen::VectorXcd full_response(std::size_t harmonic, Eigen::Index speed) const;

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
