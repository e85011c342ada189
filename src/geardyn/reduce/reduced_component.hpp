#pragma once
// A component described by reduced matrices (Craig-Bampton / Guyan), with everything needed to
// expand a reduced solution back to every DOF of the original model and to say where it came
// from.
//
// Reduced coordinates q = [x_b; eta]: first the physical master DOFs x_b in the order of
// `masters`, then `n_modal` fixed-interface modal coordinates eta. The original DOFs follow
// (docs/theory.md §9)
//   x_b = q_b,   x_i = Psi q_b + Phi eta,      i.e.  x = T q,  T = [I 0; Psi Phi]
// in the partitioned ordering [masters | interior]; `master_index` and `interior_index` map the
// partitions back to the original DOF numbering.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/solid/mesh.hpp"

namespace geardyn::reduce {

/// Where a reduced component came from. Written to the reduced-component file as attributes.
struct Provenance {
  std::string method;           ///< "craig_bampton" or "guyan"
  std::string options_json;     ///< the reduction options as a JSON object
  std::string source_sha256;    ///< hash of the source model/mesh, given by the caller
  std::string geardyn_version;  ///< version of the program that made it, given by the caller
  std::string created_utc;      ///< ISO 8601, e.g. "2024-05-01T12:00:00Z"
  std::string solver_report;    ///< brief report of the fixed-interface eigen-solve
};

struct ReducedComponent {
  Eigen::MatrixXd K;  ///< reduced stiffness, m x m, symmetric [N/m, N/rad, ...]
  Eigen::MatrixXd M;  ///< reduced mass, m x m, symmetric [kg, ...]

  std::vector<solid::DofInfo> masters;  ///< the physical master DOFs (node, component, position)
  int n_modal = 0;                      ///< number of fixed-interface modal coordinates
  Eigen::VectorXd fixed_interface_hz;   ///< natural frequencies of the kept modes [Hz], ascending

  // Recovery x = T q (see the file comment).
  std::vector<solid::DofInfo> full_dofs;  ///< every DOF of the original model
  std::vector<int> master_index;          ///< masters[k] is full DOF master_index[k]
  std::vector<int> interior_index;        ///< interior DOF j is full DOF interior_index[j]
  Eigen::MatrixXd Psi;                    ///< constraint modes, n_interior x n_masters
  Eigen::MatrixXd Phi;  ///< fixed-interface modes, n_interior x n_modal, Phi^T M_ii Phi = I

  Provenance provenance;

  int n_masters() const { return static_cast<int>(masters.size()); }
  /// Number of reduced coordinates m = n_masters + n_modal.
  int size() const { return n_masters() + n_modal; }
  int n_full() const { return static_cast<int>(full_dofs.size()); }

  /// DofInfo of every reduced coordinate: the masters, then one entry per modal coordinate with
  /// component -1 and node_id = mode number (1-based), at the origin.
  std::vector<solid::DofInfo> reduced_dofs() const;
};

/// x = T q for one or more reduced solutions (columns of q, m rows): returns the n_full x cols
/// matrix of original-DOF values, without forming T.
/// Throws InputError when q has the wrong number of rows.
Eigen::MatrixXd expand(const ReducedComponent& rc, const Eigen::MatrixXd& q);

/// The dense recovery matrix T (n_full x m) in the original DOF numbering. Memory n_full * m.
Eigen::MatrixXd recovery_matrix(const ReducedComponent& rc);

/// The same component with only the first `n_modes` fixed-interface modes. Because the reduced
/// coordinates of fewer modes are a leading subset, K and M are the leading principal
/// submatrices (Craig-Bampton with nested mode sets). Throws InputError unless
/// 0 <= n_modes <= rc.n_modal.
ReducedComponent truncate(const ReducedComponent& rc, int n_modes);

/// Eigenvalues lambda = omega^2 [rad^2/s^2], ascending, of the reduced pair (K, M) with the
/// masters listed in `fixed_masters` (indices into rc.masters) held at zero (e.g. a clamp).
/// Dense generalised symmetric solver (reduced sizes are small). Throws InputError for an
/// out-of-range index, NumericalError when M (after removal) is not positive definite.
Eigen::VectorXd reduced_eigenvalues(const ReducedComponent& rc,
                                    const std::vector<int>& fixed_masters = {});

}  // namespace geardyn::reduce
