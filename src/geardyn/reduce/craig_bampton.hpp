#pragma once
// Craig-Bampton (and Guyan) reduction of a sparse component model onto master DOFs plus
// fixed-interface modes (docs/theory.md §9).
//
// With the DOFs partitioned into masters b and interior i,
//   constraint modes     Psi = -K_ii^{-1} K_ib                      (static shapes, x_b = I)
//   fixed-interface modes K_ii Phi = M_ii Phi Lambda, Phi^T M_ii Phi = I   (lowest n, or f < f_max)
//   x = T q,  T = [I 0; Psi Phi],  q = [x_b; eta],   K_r = T^T K T,  M_r = T^T M T.
// In exact arithmetic K_r = [K_bb + K_bi Psi, 0; 0, Lambda]; the code forms the products
// T^T K T blockwise instead (sparse K times dense columns of T), so that round-off in Psi shows up
// rather than being assumed away. Guyan reduction is the case with no modes.
// Sources: R. R. Craig, M. C. C. Bampton, "Coupling of substructures for dynamic analyses",
// AIAA J. 6 (1968) 1313-1319; R. J. Guyan, "Reduction of stiffness and mass matrices", AIAA J.
// 3 (1965) 380; A. Durastante, "Simulation of the Dynamic Response of Aeronautical Gears
// Equipped with Damper Rings", MSc thesis, Politecnico di Torino, 2018 (chapter 2.2.1, its [1],
// [4]).
//
// Cost: one sparse Cholesky factorisation of K_ii, solved with n_masters right-hand sides in
// blocks; one shift-invert Lanczos run (eig::solve_symmetric) on (K_ii, M_ii); dense work
// O(n_interior * m^2) for the products, m = n_masters + n_modes. Nothing of size n x n is dense.
// Guyan still runs a one-mode Lanczos on (K_ii, M_ii): a Cholesky factorisation of a singular
// K_ii can succeed with a tiny round-off pivot, so the lowest fixed-interface eigenvalue is the
// reliable test for free motions of the interior.
#include <Eigen/Sparse>
#include <array>
#include <string>
#include <vector>

#include "geardyn/core/progress.hpp"
#include "geardyn/eig/eigen_options.hpp"
#include "geardyn/reduce/reduced_component.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::reduce {

struct CraigBamptonOptions {
  /// Number of fixed-interface modes kept (the lowest). 0 with frequency_max_hz NaN: Guyan.
  int n_modes = 0;
  /// Cut-off [Hz]: keep every fixed-interface mode with natural frequency <= this. Exclusive
  /// with n_modes > 0. NaN: not used.
  double frequency_max_hz = eig::kNaN;
  /// The fixed-interface eigen-solve uses the dense solver up to this many interior DOFs.
  int dense_limit = 400;
  eig::KrylovOptions krylov;
  /// Right-hand sides per block solve when computing Psi (memory: n_interior * block_size).
  int block_size = 64;
  /// A fixed-interface eigenvalue lambda <= mechanism_tolerance * max_j (K_jj / M_jj) (interior
  /// DOFs) counts as a free motion (K_ii singular): the reduction is refused with an error that
  /// names it. The right side bounds the spectrum from the top, and round-off leaves a true zero
  /// eigenvalue at about 1e-16 of it.
  double mechanism_tolerance = 1e-12;

  /// Every problem with the options, one line each; empty when valid.
  std::vector<std::string> validate() const;
  /// The options as a JSON object (stored in the provenance).
  std::string to_json() const;
};

/// Reduces (K, M) onto the masters `master_dofs` (indices into the DOFs, kept in the given order)
/// plus fixed-interface modes. `dofs` describes every DOF (node id, component, position; used in
/// messages and stored for recovery). K and M: square, symmetric, size dofs.size(); K positive
/// semi-definite. `source_sha256` and `geardyn_version` go to the provenance as given.
///
/// Throws InputError for mismatched sizes, a non-symmetric matrix, repeated or out-of-range
/// masters, invalid options, more modes than interior DOFs, and when the masters do not
/// constrain every motion of the interior (K_ii singular): the message names each free motion
/// (rigid-body content of the motion, the nodes it involves and the node where it is largest)
/// and says what to do. Throws NumericalError when the fixed-interface eigen-solve fails
/// (its brief report is in the message). Progress: the constraint-mode block solves.
ReducedComponent craig_bampton(
    const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
    const std::vector<solid::DofInfo>& dofs, const std::vector<int>& master_dofs,
    const CraigBamptonOptions& options = {}, const std::string& source_sha256 = {},
    const std::string& geardyn_version = {}, Progress& progress = null_progress());

/// Linear interface constraints A x = u between the DOFs x of a component and r extra
/// coordinates u (e.g. the reference points of averaging (RBE3) spiders and sensor points).
struct InterfaceConstraints {
  Eigen::SparseMatrix<double> A;     ///< r x n, full row rank on the interior DOFs
  std::vector<solid::DofInfo> dofs;  ///< of each u (r entries)
};

/// Craig-Bampton with interface constraints (docs/theory.md §9): the full coordinates are
/// [x; u] (n + r), `master_dofs` indexes them and must contain every u (n + k for row k); the
/// interior i is every other x DOF. With the masters q_b given, the constraint modes are the
/// minimum-energy shapes under A x = u,
///   [K_ii A_i^T; A_i 0] [Psi; Mu] = [-K_ib; -A_b]      (A x - u = A_i x_i + A_b q_b),
/// and the fixed-interface modes those of K_ii phi = lambda M_ii phi with A_i phi = 0 (q_b = 0),
/// both by sparse factorisations of the saddle-point matrix (constrained_modes.hpp), which needs
/// K_ii positive definite on {A_i x = 0} only: a body held by averaging spiders alone is fine.
/// This is the reduction of (S^T K S, S^T M S) in coordinates x = S [x_F; u] that eliminate r
/// pivot DOFs through the constraints, without the fill of S^T K S. The result is in the same
/// form as above, with full_dofs = [x; u] (u with no stiffness or mass) and Psi, Phi over the
/// interior x DOFs. With r = 0 it is the plain craig_bampton. Throws as that one, and
/// InputError when A does not match, a u is not a master or there are more rows than interior
/// DOFs.
ReducedComponent craig_bampton(
    const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
    const std::vector<solid::DofInfo>& dofs, const InterfaceConstraints& constraints,
    const std::vector<int>& master_dofs, const CraigBamptonOptions& options = {},
    const std::string& source_sha256 = {}, const std::string& geardyn_version = {},
    Progress& progress = null_progress());

/// Components 0..5 (ux, uy, uz, rx, ry, rz) to select; all by default.
using ComponentMask = std::array<bool, 6>;
inline constexpr ComponentMask kAllComponents{true, true, true, true, true, true};
inline constexpr ComponentMask kTranslations{true, true, true, false, false, false};

/// Indices (ascending) of the DOFs in `dofs` that belong to the nodes with external ids
/// `node_ids` and whose component is selected by `components`. Throws InputError naming a node
/// id that has no selected DOF.
std::vector<int> select_dofs(const std::vector<solid::DofInfo>& dofs,
                             const std::vector<long>& node_ids,
                             const ComponentMask& components = kAllComponents);

/// The same for node indices of `mesh` (mapped to ids through mesh.node_ids).
std::vector<int> select_dofs(const solid::Mesh& mesh, const std::vector<solid::DofInfo>& dofs,
                             const std::vector<int>& node_indices,
                             const ComponentMask& components = kAllComponents);

/// The same for a named node set of `mesh`; throws InputError listing the sets when it is
/// missing.
std::vector<int> select_dofs(const solid::Mesh& mesh, const std::vector<solid::DofInfo>& dofs,
                             const std::string& node_set,
                             const ComponentMask& components = kAllComponents);

/// Sorted union of DOF index lists (e.g. the masters of several node sets).
std::vector<int> merge_dofs(const std::vector<std::vector<int>>& lists);

}  // namespace geardyn::reduce
