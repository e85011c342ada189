#pragma once
// Harmonic balance condensed to the nonlinear coordinates (docs/theory.md §8): the linear structure
// enters only through its receptance at the coordinates where nonlinear forces act (e.g. the
// normal and tangential relative displacements of the contact pairs of a damper ring), so the
// Newton system has n_coordinates (2H + 1) unknowns however large the FE model is.
//
// Harmonic n >= 1 of a coordinate is x(t) = a_n cos(n w t) + b_n sin(n w t) = Re(z_n e^{i n w t})
// with z_n = a_n - i b_n (cosine phase, the convention of the forced-response modules); forces
// likewise. Per harmonic, the linear structure maps the complex amplitudes of the nonlinear
// forces f_n acting on it, together with its own excitation, to displacements:
//   z_n = x_lin,n(n w) - H_n(n w) f_n,
// where f_n is the force the nonlinear elements apply in the residual convention of
// harmonic_balance.hpp (restoring: the structure feels -f). The residual solved is
//   R(X, w) = X - X_lin(w) + H(w) F_nl(X),
// a displacement, judged converged relative to ||X|| + ||X_lin||. Its Jacobian is I + H dF_nl/dX.
// In real form the complex receptance H = H_r + i H_i acts on the (a, b) pair of every
// coordinate as [[H_r, H_i], [-H_i, H_r]].
//
// ModalReceptance gives H_n and x_lin,n as a modal sum plus a frequency-independent residual
// (the static contribution of the modes left out, "residual flexibility"):
//   H(w) = U diag(1 / d_r(w)) V^H + R_res,   d_r(w) = w_r^2 - w^2 + 2 i zeta_r w_r w,
//   x_lin(w) = U diag(1 / d_r(w)) p + r_res,
// U = V = G phi_r for real modes, mass-normalised, and G the map from the model's DOFs to the
// coordinates; for a cyclic sector at nodal diameter h the complex sector modes psi_r (or their
// conjugates for the backward-travelling pattern, see forced/cyclic_forced_response.hpp). The
// harmonic 0 (the mean) may be left without modes and residual: H_0 = 0 holds the mean of every
// coordinate at zero, i.e. at the preloaded static equilibrium (the choice when the structure
// has rigid-body modes at the static nodal diameter, such as a free split ring).
// Sensors: rows S = G_s phi_r and residual rows R_s give any response z_s = S diag(1/d)
// (p - V^H f) + r_s - R_s f from the solved forces (recovery).
//
// Element-local forces (LocalForce) are the fast form: dF_nl/dX is kept as one small block per
// element (per cluster of elements sharing coordinates) and H as its modal sum plus residual, so
// the Newton matrix I + H dF_nl/dX (N = n_coordinates (2H + 1) square, dense) is never formed.
// continue_in_frequency solves with it by GMRES, preconditioned by the exact inverse (Sherman-
// Morrison-Woodbury identity, CondensedPreconditioner) of the same matrix without the residual
// flexibility that couples different elements, built at an earlier Newton point and reused while
// it pays: the only factorisation is of the size of the modal basis. Each Newton iteration then
// costs O(N k + n_coordinates^2 H) (k: twice the modes of all harmonics) instead of O(N^3).
//
// Reference: the receptance ("FRF-based") condensation is the standard one of friction-damping
// codes, e.g. Petrov & Ewins, "Analytical formulation of friction interface elements for
// analysis of nonlinear multi-harmonic vibrations of bladed disks", J. Turbomach. 125 (2003)
// 364-371; Krack & Gross, "Harmonic Balance for Nonlinear Vibration Problems", Springer (2019),
// sec. 3.4.
#include <Eigen/Dense>
#include <complex>
#include <functional>
#include <memory>
#include <vector>

#include "geardyn/hbm/friction_contact.hpp"
#include "geardyn/hbm/harmonic_balance.hpp"

namespace geardyn::hbm {

struct ModalReceptance {
  Eigen::VectorXd natural_frequency;     ///< w_r [rad/s], >= 0
  Eigen::VectorXd damping_ratio;         ///< zeta_r >= 0
  Eigen::MatrixXcd left;                 ///< U: coordinates x modes
  Eigen::MatrixXcd right;                ///< V: coordinates x modes
  Eigen::MatrixXcd residual;             ///< R_res: coordinates x coordinates; empty: none
  Eigen::VectorXcd modal_excitation;     ///< p: modes; empty: no excitation
  Eigen::VectorXcd residual_excitation;  ///< r_res: coordinates; empty: none
  // Sensors (optional).
  Eigen::MatrixXcd sensor_left;                 ///< S: sensors x modes
  Eigen::MatrixXcd sensor_residual;             ///< R_s: sensors x coordinates; empty: none
  Eigen::VectorXcd sensor_residual_excitation;  ///< r_s: sensors; empty: none

  Eigen::Index coordinates() const { return left.rows(); }
  Eigen::Index modes() const { return natural_frequency.size(); }
  Eigen::Index sensors() const { return sensor_left.rows(); }

  /// 1 / d_r(w) per mode; with d non-null also d(1/d_r)/dw.
  Eigen::VectorXcd modal_factors(double w, Eigen::VectorXcd* d = nullptr) const;
  /// H(w) (coordinates square); with dH non-null also dH/dw.
  Eigen::MatrixXcd receptance(double w, Eigen::MatrixXcd* dH = nullptr) const;
  /// x_lin(w); with dx non-null also dx_lin/dw.
  Eigen::VectorXcd linear_response(double w, Eigen::VectorXcd* dx = nullptr) const;
  /// Sensor amplitudes for the nonlinear forces f (coordinates) at w.
  Eigen::VectorXcd sensor_response(double w, const Eigen::VectorXcd& f) const;
  /// Throws InputError (key `what`) when the sizes disagree with `coordinates` or a frequency /
  /// damping is negative or not finite.
  void validate(Eigen::Index coordinates, const char* what) const;
};

/// A nonlinear force whose law depends on the excitation frequency as well (e.g. the centrifugal
/// preload of a damper ring, which grows with the square of the speed): like NonlinearForce, plus
/// dF/domega when dF_domega is non-null (sized and zero on entry). J may be null (forces only).
using FrequencyDependentForce =
    std::function<void(const HarmonicBasis& basis, const Eigen::VectorXd& X, double omega,
                       Eigen::VectorXd& F, Eigen::MatrixXd* J, Eigen::VectorXd* dF_domega)>;

/// A nonlinear element acting on a few coordinates: w holds their coefficients coordinate-major
/// (w[j * (2H+1) + c] for the j-th listed coordinate); it writes f (same layout, sized and zero on
/// entry) and, when non-null, J = df/dw (square) and df/domega.
/// The form CondensedHarmonicBalance solves fast: the Jacobian of all elements is kept as their
/// small blocks, never as an N x N matrix (see "Newton linear algebra" below).
struct LocalForce {
  std::vector<int> coordinates;
  std::function<void(const HarmonicBasis& basis, const Eigen::VectorXd& w, double omega,
                     Eigen::VectorXd& f, Eigen::MatrixXd* J, Eigen::VectorXd* df_domega)>
      evaluate;
};

/// `contact` (friction_contact.hpp) on the coordinates [normal, tangential...] (1 +
/// tangential_directions distinct indices >= 0; InputError otherwise, and for an invalid
/// contact), with its exact AFT Jacobian. With preload_per_omega_squared = c != 0 the normal
/// preload follows the frequency, N_0(omega) = contact.normal_preload + c omega^2 (a centrifugal
/// preload; c finite >= 0, and k_n > 0), and df/domega is exact too: N_0 enters the law only
/// through N_0 + k_n v, so f(w; N_0 + delta) = f(w + delta / k_n e; N_0) - delta e, e the unit
/// vector of the mean a_0 of v, hence df/dN_0 = J e / k_n - e (no extra march).
LocalForce local_friction_contact(std::vector<int> coordinates, FrictionContact contact,
                                  double preload_per_omega_squared = 0.0);

/// Work counters and CPU times (of the calling thread) of a CondensedHarmonicBalance and of the
/// continuation that traces it, for benchmarks and profiling. Filled only while attached with
/// CondensedHarmonicBalance::set_statistics; not synchronised: attach it only while one thread
/// uses the system.
struct CondensedStatistics {
  long residual_evaluations = 0;    ///< R(X, omega), with or without the linearization
  long linearizations = 0;          ///< of them, with the element Jacobians and dR/domega
  double element_seconds = 0.0;     ///< nonlinear elements (the AFT: march, transforms, Jacobians)
  double receptance_seconds = 0.0;  ///< modal factors, H f, x_lin and their omega derivatives
  long linear_solves = 0;           ///< Newton and tangent systems solved by the continuation
  long krylov_iterations = 0;       ///< GMRES iterations over all solves
  long preconditioner_builds = 0;   ///< factorised capacitance matrices (size: the modes)
  long dense_factorizations = 0;    ///< LU of an N x N Jacobian (the general path, or fallback)
  double linear_algebra_seconds = 0.0;  ///< all linear solves, builds and factorisations

  /// CPU time of the calling thread [s], the clock of these statistics.
  static double now();
};

class CondensedJacobian;
class CondensedPreconditioner;

class CondensedHarmonicBalance final : public HarmonicSystem {
 public:
  /// `harmonics[n]`, n = 0..H, is the receptance of harmonic n (basis.harmonics() = H); a
  /// harmonic-0 entry with no modes and no residual holds the mean at zero. `forces` act on the
  /// coordinates 0..coordinates-1 in the unknowns' layout of harmonic_balance.hpp.
  CondensedHarmonicBalance(int coordinates, HarmonicBasis basis,
                           std::vector<ModalReceptance> harmonics,
                           std::vector<NonlinearForce> forces);
  /// The same with forces that depend on the frequency too.
  CondensedHarmonicBalance(int coordinates, HarmonicBasis basis,
                           std::vector<ModalReceptance> harmonics,
                           std::vector<FrequencyDependentForce> forces);
  /// The same with element-local forces (coordinates in 0..coordinates-1, distinct within an
  /// element, evaluate set; InputError otherwise): the fast form. Elements may share
  /// coordinates; those that do are grouped into one cluster of the block-diagonal Jacobian.
  CondensedHarmonicBalance(int coordinates, HarmonicBasis basis,
                           std::vector<ModalReceptance> harmonics, std::vector<LocalForce> forces);

  int coordinates() const { return n_c_; }
  int size() const override { return n_c_ * basis_.size(); }
  const HarmonicBasis& basis() const { return basis_; }
  const std::vector<ModalReceptance>& harmonics() const { return harmonics_; }

  Eigen::VectorXd residual(const Eigen::VectorXd& X, double omega, Eigen::MatrixXd* J = nullptr,
                           Eigen::VectorXd* dR_domega = nullptr) const override;
  /// ||X|| + ||X_lin(omega)|| (or 1e-30 when both vanish).
  double residual_scale(const Eigen::VectorXd& X, double omega) const override;

  /// X_lin(omega): the response of the coordinates without nonlinear forces.
  Eigen::VectorXd linear_response(double omega) const;
  /// F_nl(X) at omega (Fourier coefficients of the nonlinear forces, the unknowns' layout).
  Eigen::VectorXd nonlinear_forces(const Eigen::VectorXd& X, double omega) const;
  /// Complex amplitudes of harmonic n >= 1 (or the mean, n = 0) of coordinate block `v`
  /// (size(), the unknowns' layout): z_n = a_n - i b_n per coordinate.
  Eigen::VectorXcd complex_harmonic(const Eigen::VectorXd& v, int n) const;
  /// Sensor amplitudes of harmonic n >= 0 at the solution X (recovery).
  Eigen::VectorXcd sensor_response(const Eigen::VectorXd& X, double omega, int n) const;
  /// dF_nl/dX at (X, omega), dense N x N in the unknowns' layout (both forms; for stability
  /// analysis, condensed_stability.hpp).
  Eigen::MatrixXd nonlinear_jacobian(const Eigen::VectorXd& X, double omega) const;

  // ---- Newton linear algebra of the LocalForce form ---------------------------------------
  // J = I + H(omega) J_nl, with J_nl block diagonal (one block per cluster of elements that share
  // coordinates) and H block diagonal per harmonic (a modal sum plus the residual). The
  // continuation (continue_in_frequency) uses these for systems built from LocalForce instead of
  // the dense Jacobian of residual(): J applied from its parts, solved by GMRES preconditioned
  // with CondensedPreconditioner.

  /// True when built from LocalForce: linearize() and the classes below are available.
  bool has_local_forces() const { return structure_ != nullptr; }
  /// R, dR/domega and the element Jacobians at (X, omega). Throws std::logic_error without
  /// local forces, InputError for a wrong size of X.
  CondensedJacobian linearize(const Eigen::VectorXd& X, double omega) const;

  /// Attaches (or with nullptr detaches) counters that this system, and the continuation
  /// tracing it, add to; borrowed, must outlive the attachment.
  void set_statistics(CondensedStatistics* statistics) { statistics_ = statistics; }
  CondensedStatistics* statistics() const { return statistics_; }

  struct Structure;  // clusters and the real form of the modal sums (condensed.cpp)

 private:
  friend class CondensedJacobian;
  friend class CondensedPreconditioner;
  // F, and with J non-null the cluster Jacobians, with dF non-null dF/domega (LocalForce form).
  void evaluate_local(const Eigen::VectorXd& X, double omega, Eigen::VectorXd& F,
                      std::vector<Eigen::MatrixXd>* J, Eigen::VectorXd* dF) const;
  // R = X - X_lin + H F from the forces F, dR/domega from dF when asked (both forms).
  Eigen::VectorXd receptance_residual(const Eigen::VectorXd& X, double omega,
                                      const Eigen::VectorXd& F, const Eigen::VectorXd* dF,
                                      Eigen::VectorXd* dR_domega) const;

  int n_c_;
  HarmonicBasis basis_;
  std::vector<ModalReceptance> harmonics_;
  std::vector<FrequencyDependentForce> forces_;
  std::vector<LocalForce> local_forces_;
  std::shared_ptr<const Structure> structure_;  // set for the LocalForce form
  CondensedStatistics* statistics_ = nullptr;
};

/// The exact Jacobian J = dR/dX of a CondensedHarmonicBalance (LocalForce form) at one point,
/// kept as its parts: cluster blocks of dF_nl/dX and the receptance at omega. Applying it costs
/// O(n_coordinates (modes + n_coordinates) H) (the residual flexibility is the quadratic
/// term), against O(N^2) for a dense J. Keeps a reference to the system: must not outlive it.
class CondensedJacobian {
 public:
  const Eigen::VectorXd& residual() const { return R_; }                  ///< R(X, omega)
  const Eigen::VectorXd& omega_derivative() const { return dR_domega_; }  ///< dR/domega
  double omega() const { return omega_; }
  /// J v.
  Eigen::VectorXd apply(const Eigen::VectorXd& v) const;
  /// J as a dense N x N matrix, assembled from the cluster blocks (O(N n_c) work per cluster
  /// column block, no N x N nonlinear Jacobian).
  Eigen::MatrixXd dense() const;
  /// dF_nl/dX on the unknowns of cluster k (coordinate-major over the cluster's coordinates).
  const Eigen::MatrixXd& cluster_jacobian(int k) const {
    return blocks_[static_cast<std::size_t>(k)];
  }

 private:
  friend class CondensedHarmonicBalance;
  friend class CondensedPreconditioner;
  explicit CondensedJacobian(const CondensedHarmonicBalance& system) : system_(&system) {}
  const CondensedHarmonicBalance* system_;
  double omega_ = 0.0;
  Eigen::VectorXd R_, dR_domega_;
  std::vector<Eigen::MatrixXd> blocks_;
  std::vector<Eigen::VectorXcd> factors_;  // modal factors 1 / d_r(n omega) per harmonic
};

/// An approximate inverse M^{-1} of a CondensedJacobian J = I + (U D V^T + R_res) J_nl (real
/// form of the receptance; U D V^T the modal sums of all harmonics, k columns in all):
///   M = I + R_b J_nl + U D V^T J_nl,
/// R_b the part of the residual flexibility inside the clusters. By the Sherman-Morrison-
/// Woodbury identity, with B = J_nl (I + R_b J_nl)^{-1} (cluster by cluster),
///   M^{-1} = (I - R_b B) (I - U (I + D V^T B U)^{-1} D V^T B),
/// so building costs cluster solves plus one k x k LU (k = sum over harmonics of 2 x modes),
/// and applying it O(N k). M = J exactly when the residual flexibility does not couple
/// clusters (none, or cluster-local); otherwise J - M = (R_res - R_b) J_nl, and a Krylov
/// method corrects the difference. Keeps a reference to the system.
class CondensedPreconditioner {
 public:
  /// Built at the element Jacobians and frequency of `J`. Status::Singular when a cluster or
  /// the capacitance matrix cannot be factorised (not finite).
  CondensedPreconditioner(const CondensedHarmonicBalance& system, const CondensedJacobian& J);
  Status status() const { return status_; }
  /// True when M = J (no residual flexibility between clusters).
  bool exact() const { return exact_; }
  /// Number of capacitance columns k.
  int capacity() const { return static_cast<int>(capacitance_.rows()); }
  /// Floating-point operations of building it over those of one application of J and of
  /// M^{-1}: the Krylov iterations a rebuild must save to pay for itself.
  double rebuild_cost() const { return rebuild_cost_; }
  /// M^{-1} r.
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const;

 private:
  const CondensedHarmonicBalance* system_;
  Status status_ = Status::Ok;
  bool exact_ = true;
  std::vector<Eigen::MatrixXd> B_;  // J_nl (I + R_b J_nl)^{-1}, per cluster
  Eigen::MatrixXd capacitance_;     // I + D V^T B U
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  std::vector<Eigen::VectorXcd> factors_;  // D per harmonic
  double rebuild_cost_ = 0.0;
};

}  // namespace geardyn::hbm
