#pragma once
// The assembled linear model of a rotor-bearing system (docs/theory.md §1):
//   M q'' + (C(Omega) + Omega G) q' + K(Omega) q = f(t),   frequency domain adds i K_s (hysteretic)
// Omega is the reference speed [rad/s]; each shaft spins at speed_ratio x Omega, and G already
// carries the speed ratios. All matrices are sparse, symmetric except G (skew) and
// cross-coupled bearing terms, in the DofMap's numbering (constrained DOFs removed).
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "geardyn/fe/dof_map.hpp"
#include "geardyn/fe/superelement.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::fe {

using SparseMatrix = Eigen::SparseMatrix<double>;
using ComplexSparseMatrix = Eigen::SparseMatrix<std::complex<double>>;

/// A bearing whose coefficients depend on speed; its contribution is added by K_at / C_at
/// (linear interpolation in the reference speed, held constant outside the table).
/// Matrices are over (node 1 DOFs, node 2 DOFs) in the node frames.
struct SpeedDependentBearing {
  std::vector<double> speeds;                                     ///< [rad/s], increasing
  std::vector<Eigen::Matrix<double, 12, 12>> stiffness, damping;  ///< in equation space
  std::array<int, 12> equations{};                                ///< -1 for constrained or ground

  /// r += K_b(speed) q_b + C_b(speed) v_b over the bearing's equations (block by block: cheaper
  /// than assembling sparse matrices per call).
  void add_force(double speed, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                 Eigen::VectorXd& r) const;
  /// Triplets of c_k K_b(speed) + c_c C_b(speed) (entries that are zero left out).
  void add_tangent(double speed, double c_k, double c_c,
                   std::vector<Eigen::Triplet<double>>& out) const;
  /// out += scale d/d speed (K_b(speed) q_b + C_b(speed) v_b), over all equations.
  void add_speed_derivative(double speed, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                            double scale, Eigen::VectorXd& out) const;
};

struct LinearSystem {
  DofMap dofs;
  SparseMatrix M;       ///< mass
  SparseMatrix K;       ///< stiffness without speed-dependent bearings
  SparseMatrix C;       ///< viscous damping (bearings, couplings, meshes, Rayleigh) without
                        ///< speed-dependent bearings and without gyroscopic terms;
                        ///< Rayleigh alpha M + beta K uses this K (speed-independent part)
  SparseMatrix G;       ///< gyroscopic matrix per unit reference speed (skew-symmetric)
  SparseMatrix K_loss;  ///< hysteretic part: frequency-domain stiffness K + i K_loss, with
                        ///< K_loss = sum_e eta_e K_e (shaft elements' loss_factor)
                        ///<        + Damping::loss_factor x K
  std::vector<SpeedDependentBearing> speed_bearings;

  /// Modal damping (docs/theory.md §4) as a low-rank term C_modal = B diag(c) B^T with B = M Phi
  /// from mass-normalised undamped modes at zero speed and c_r = 2 zeta_r omega_r. Empty if none.
  Eigen::MatrixXd modal_basis;
  Eigen::VectorXd modal_coefficients;

  int size() const { return dofs.num_dofs(); }
  /// K + speed-dependent bearing stiffness at reference speed `speed`.
  SparseMatrix K_at(double speed) const;
  /// C + speed-dependent bearing damping at `speed` (without Omega G and modal damping).
  SparseMatrix C_at(double speed) const;
  bool has_modal_damping() const { return modal_coefficients.size() > 0; }
  /// Dense C_at(speed) + speed G + modal damping: for small (dense) solvers and checks.
  Eigen::MatrixXd damping_dense(double speed) const;

  /// Unit load vector for a force/moment at `node` along component `c` of the node frame.
  /// Throws InputError when that DOF is constrained.
  Eigen::VectorXd unit_load(int node, model::Component c) const;
};

/// Complex amplitude of a rotating unbalance force, f(t) = Re(F exp(i |r| Omega t)), with r the
/// node's speed ratio: m e (r Omega)^2 in the node's e1-e2 plane, turning in the spin sense.
/// Only unbalances whose node has |speed_ratio| == `order` (within 1e-12) are included, so the
/// result is one frequency component. `selected` empty: all unbalances.
Eigen::VectorXcd unbalance_load(const model::Model& model, const LinearSystem& system, double speed,
                                double order, const std::vector<std::string>& selected = {});

/// Distinct |speed ratios| of the nodes that carry the selected unbalances (the orders at which
/// unbalance excites the system), ascending.
std::vector<double> unbalance_orders(const model::Model& model, const LinearSystem& system,
                                     const std::vector<std::string>& selected = {});

struct AssemblyOptions {
  /// Modes used for modal damping (0: max(20, 2 x modes with a ratio given)); ignored when the
  /// model has no modal damping.
  int modal_damping_modes = 0;
};

/// Builds DOF map and matrices from a validated model, with the bodies `superelements` joined
/// to it (fe/superelement.hpp): their new nodes and generalised coordinates are appended to the
/// DofMap after the model's nodes, in the order given. Global damping (Rayleigh, loss factor)
/// applies to the bodies too. Throws InputError for inconsistent references that slipped past the
/// parser and for a body whose matrices do not fit its coordinates or are not finite.
LinearSystem assemble(const model::Model& model, const AssemblyOptions& options = {},
                      const std::vector<Superelement>& superelements = {});

/// The coordinates q of a body joined to `system` (fe/superelement.hpp) as a linear function of
/// the system's equations: q = B u, B sparse (body.size() x system.size()); a constrained node
/// DOF contributes nothing. Throws InputError when the body is not part of the system (a point
/// node, or its range of generalised coordinates, missing).
SparseMatrix body_coordinates(const LinearSystem& system, const Superelement& body);

/// Energy fractions of a mode shape by DOF family (uses diag(M)-weighted squares):
/// lateral (ux, uy, rx, ry), axial (uz), torsional (rz) of node DOFs, and body: the generalised
/// coordinates of joined bodies (the elastic deformation of reduced solids). They sum to 1.
struct ModeFamilies {
  double lateral = 0, axial = 0, torsional = 0, body = 0;
};
ModeFamilies mode_families(const LinearSystem& system, const Eigen::VectorXcd& shape);

}  // namespace geardyn::fe
