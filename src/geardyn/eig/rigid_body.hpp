#pragma once
// Rigid-body motions of an assembled structure, decided from mode shapes rather than from the
// size of an eigenvalue.
//
// A limit on omega^2 cannot tell a rigid-body mode from an elastic one on every mesh: the
// rounding of a zero eigenvalue grows like eps ||K|| / ||M||, i.e. like 1 / h^2 .. 1 / h^4 with
// the element length h, and passes the lowest elastic frequencies of a beam rotor at some
// thousands of elements. Here the question is asked of the shape instead: the caller offers
// candidate motions (rigid translations and rotations of the whole model or of its parts);
// those that K leaves unstrained row by row, to rounding, span the rigid-body space, and a mode
// is a rigid-body motion when that space holds its kinetic energy. Both tests are ratios of
// like quantities and do not change with the mesh.
#include <Eigen/Dense>
#include <Eigen/Sparse>

namespace geardyn::eig {

struct RigidBodySpace {
  /// n x r, M-orthonormal (basis^T M basis = I); r = 0 when no candidate is unstrained.
  Eigen::MatrixXd basis;
  Eigen::Index dimension() const { return basis.cols(); }
};

/// Default tolerance of rigid_body_space: the largest singular value of the row-scaled
/// residual diag(1 / (|K| |Q|)) K Q of a motion counted as unstrained (Q: the orthonormalised
/// candidates). Rounding gives about sqrt(n) eps (1e-13 at n = 1e5); a support of stiffness k
/// on a shaft whose elements have stiffness k_e gives about k / k_e (a 1 MN/m bearing on a
/// 0.25 mm element of a 50 mm steel shaft: 1e-11).
inline constexpr double kRigidResidualTolerance = 3e-12;

/// The part of span(candidates) that K maps to zero to rounding (see above), M-orthonormal.
/// Candidates that are linearly dependent (relative pivot below 1e-8) are dropped. M symmetric
/// n x n; candidates n x c; K n x n, or any m x n stack of matrices (e.g. [K; C; G]) when the
/// motions must be at rest under all of them.
RigidBodySpace rigid_body_space(const Eigen::SparseMatrix<double>& K,
                                const Eigen::SparseMatrix<double>& M,
                                const Eigen::MatrixXd& candidates,
                                double tolerance = kRigidResidualTolerance);

/// Fraction of the kinetic energy x^H M x of x that lies in the rigid-body space:
/// ||B^T M x||^2 / (x^H M x) in [0, 1] (0 for an empty space or x^H M x = 0).
double rigid_body_fraction(const RigidBodySpace& space, const Eigen::SparseMatrix<double>& M,
                           const Eigen::VectorXcd& x);

}  // namespace geardyn::eig
