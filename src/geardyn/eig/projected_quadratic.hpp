#pragma once
// Quadratic eigenproblem of a rotor over many speeds by projection onto one speed-independent
// basis (docs/theory.md §3, docs/performance.md "Campbell (issue #19)"):
//     P(lambda; Omega) x = (lambda^2 M + lambda D(Omega) + K(Omega)) x = 0,
//     D(Omega) = C0 + dC(Omega) + Omega G + B diag(c) B^T,   K(Omega) = K0 + dK(Omega),
// where dK, dC are the few entries of speed-dependent bearings (low rank, assembled per speed).
//
// Basis V (n x m, M-orthonormal: V^T M V = I): the lowest undamped modes of (K0_sym, M) at rest
// (one sparse factorisation and a Lanczos run, symmetric_eigen.hpp), enriched whenever a mode is
// not accurate enough: the Ritz pair (lambda, x = V y) of the projected pencil
//     (lambda^2 V^T M V + lambda V^T D V + V^T K V) y = 0      (dense, size 2m state form)
// (its eigenvalues by the Hessenberg QR of solve_quadratic's dense operator without Schur
// vectors, each wanted y by inverse iteration on the m x m pencil; J. H. Wilkinson, The Algebraic
// Eigenvalue Problem, Oxford 1965, ch. 9; a wanted eigenvalue within 1e-6 of another keeps the
// Schur vectors, which separate double roots)
// has the full-size residual r = P(lambda) x; V is extended by F^{-1} r (real and imaginary
// parts), F = K0_sym - sigma_b M the factorisation of the basis (a preconditioned residual, the
// correction of Davidson's method: E. R. Davidson, J. Comput. Phys. 17 (1975) 87-94; for
// quadratic pencils Z. Bai & Y. Su, SIAM J. Matrix Anal. Appl. 26 (2005) 640-659 project on a
// fixed subspace the same way). The basis is kept between calls, so a sweep over speed pays the
// enrichment once: the gyroscopic directions G x are the same at every speed.
//
// Rigid-body roots are deflated: a motion r (free axial translation, free torsion) with
// K r = K^T r = 0, D r = D^T r = 0 decouples exactly from the M-orthogonal complement
// (r^T M V = 0 gives r^T P(lambda) V y = 0), and contributes lambda^2 r^T M r = 0, a defective
// double root at 0. Left in the basis, such roots meet the projected solve as a double root
// whose vectors inverse iteration cannot separate and whose Ritz values round-off splits by
// sqrt(eps ||K|| / ||M||). So the space R of candidate motions that the speed-independent
// matrices leave at rest (eig/rigid_body.hpp, then the common null space of the others) is kept
// out of V (every basis vector is M-orthogonalised against it), and each of its motions is
// returned as two exact roots lambda = 0 with x = r, among the wanted modes by their distance to
// the target like any other. A speed whose bearing increments dK, dC do not leave R at rest is
// not projected (NotConverged: the caller's full solver takes it).
//
// Every returned mode is checked at full size: its backward error (QuadraticEigenResult::residuals,
// Tisseur 2000) is below the caller's residual_limit and its preconditioned residual F^{-1} r is
// below `tolerance` relative to x in the M-norm (the backward error alone is a weak test on fine
// meshes, where ||K|| grows as the element size^-3 and allows relative frequency errors of 1e-6
// at a backward error of 1e-11); otherwise the result says NotConverged. The projection never
// returns a mode it has not checked. What it cannot certify is completeness: a mode of the full
// pencil with no component in V has no Ritz value. The starting basis holds the undamped modes up
// to well above the wanted ones (`extra_modes`), which is what modal reduction of rotors relies
// on; tests compare with the full solvers.
//
// Not thread-safe: solve() enriches the basis. One instance per thread (each builds its basis).
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>
#include <string>

#include "geardyn/eig/quadratic_eigen.hpp"

namespace geardyn::eig {

struct ProjectedQuadraticOptions {
  /// Undamped modes in the starting basis beyond the n_modes asked at the first solve.
  int extra_modes = 6;
  /// Enrichment rounds per solve before giving up (NotConverged).
  int max_rounds = 8;
  /// Largest basis size (0: automatic, max(8 n_modes, 80), at most n).
  int max_basis = 0;
  /// Accuracy of every returned mode: rho = ||F^{-1} r||_M / ||x||_M, the size of the correction
  /// the preconditioned residual asks for relative to x (about the error of x). Ritz values of the
  /// nearly Hermitian gyroscopic pencil are then accurate to about rho^2 relative; 1e-6 gives
  /// frequencies within 1e-11 of the dense solver on the 48- and 192-element test rotors. Below
  /// about 1e-8 rounding stalls the enrichment. The backward error must also be below the
  /// caller's QuadraticEigenOptions::residual_limit.
  double tolerance = 1e-6;
  std::vector<std::string> validate() const;
};

/// The speed-independent parts of P(lambda; Omega) (see the header comment).
struct SpeedPencilParts {
  Eigen::SparseMatrix<double> M, K0, C0, G;
  Eigen::MatrixXd low_rank_basis;         ///< B, n x r (r = 0: none)
  Eigen::VectorXd low_rank_coefficients;  ///< c, r
  /// Candidate rigid-body motions (n x c, e.g. fe::rigid_body_candidates; empty: none). Those
  /// that K0, C0, G and B diag(c) B^T all leave at rest are deflated (see the header comment).
  Eigen::MatrixXd rigid_candidates;
};

class ProjectedQuadratic {
 public:
  /// Keeps a copy of `parts`; the basis is built at the first solve(). Throws InputError for
  /// invalid options or inconsistent sizes.
  explicit ProjectedQuadratic(SpeedPencilParts parts,
                              const ProjectedQuadraticOptions& options = {});
  ~ProjectedQuadratic();
  ProjectedQuadratic(ProjectedQuadratic&&) noexcept;
  ProjectedQuadratic& operator=(ProjectedQuadratic&&) noexcept;

  /// The options.n_modes modes of `full` nearest options.target (NaN: automatic, as
  /// solve_quadratic), `full` being P at `speed`: {M, K0 + dK, C0 + dC + speed G, B, c}; dK and
  /// dC hold only the speed-dependent entries (may be empty). Status Ok when every returned mode
  /// has a backward error below the tolerance; otherwise NotConverged / Failed with the reason
  /// (the caller then uses solve_quadratic, the reference). method_used is Dense (the projected
  /// problem's solve) and `factorization` reads "projected(m)".
  QuadraticEigenResult solve(const QuadraticPencil& full, double speed,
                             const Eigen::SparseMatrix<double>& dK,
                             const Eigen::SparseMatrix<double>& dC,
                             const QuadraticEigenOptions& options);

  /// Marks the current basis (its columns so far) as the one restore_basis() returns to. A sweep
  /// split into chunks that each start from one kept basis gives the same results whichever
  /// order or thread the chunks run in (enrichment only appends columns).
  void keep_basis();
  /// Drops the columns added since the last keep_basis() (all enrichments since the start when
  /// it was never called: the starting basis of undamped modes).
  void restore_basis();

  /// Current basis size m (0 before the first solve).
  Eigen::Index basis_size() const;
  /// Enrichment vectors added so far, over all solves.
  int enrichments() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace geardyn::eig
