#pragma once
// The quadratic pencil of an assembled rotor system at one reference speed (docs/theory.md §1):
//   M q'' + (C_at(Omega) + Omega G + C_modal) q' + K_at(Omega) q = 0.
#include "geardyn/eig/projected_quadratic.hpp"
#include "geardyn/eig/quadratic_eigen.hpp"
#include "geardyn/fe/linear_system.hpp"

namespace geardyn::assembly {

/// M, K_at(speed), C_at(speed) + speed G as sparse matrices and the modal damping term
/// B diag(c) B^T of `system` as the low-rank part. `speed` is the reference speed [rad/s].
eig::QuadraticPencil pencil_at(const fe::LinearSystem& system, double speed);

/// The speed-independent parts of the pencil (eig/projected_quadratic.hpp): M, K, C, G and the
/// modal damping term of `system`, so that pencil_at(speed) = {M, K + dK, C + dC + speed G}.
eig::SpeedPencilParts pencil_parts(const fe::LinearSystem& system);

/// dK(speed), dC(speed): the contributions of the speed-dependent bearings alone (a few 12 x 12
/// blocks; empty matrices when the system has none), K_at(speed) = K + dK, C_at = C + dC.
struct SpeedIncrements {
  Eigen::SparseMatrix<double> dK, dC;
};
SpeedIncrements speed_increments(const fe::LinearSystem& system, double speed);

}  // namespace geardyn::assembly
