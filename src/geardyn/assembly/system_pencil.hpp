#pragma once
// The quadratic pencil of an assembled rotor system at one reference speed (docs/theory.md §1):
//   M q'' + (C_at(Omega) + Omega G + C_modal) q' + K_at(Omega) q = 0.
#include "geardyn/eig/quadratic_eigen.hpp"
#include "geardyn/fe/linear_system.hpp"

namespace geardyn::assembly {

/// M, K_at(speed), C_at(speed) + speed G as sparse matrices and the modal damping term
/// B diag(c) B^T of `system` as the low-rank part. `speed` is the reference speed [rad/s].
eig::QuadraticPencil pencil_at(const fe::LinearSystem& system, double speed);

}  // namespace geardyn::assembly
