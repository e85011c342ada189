#pragma once
// Modal damping (docs/theory.md §4): a damping ratio zeta_r per undamped mode, applied as the
// low-rank viscous term
//   C_modal = B diag(c) B^T,  B = M Phi,  c_r = 2 zeta_r omega_r,
// with Phi the mass-normalised undamped modes of the non-rotating system (K_at(0), M). In modal
// coordinates q = Phi eta it adds 2 zeta_r omega_r eta_r' to mode r and nothing else, so each
// undamped mode gets exactly its ratio (Clough & Penzien, Dynamics of Structures, 2nd ed.,
// sec. 12-6). Modes beyond the computed ones get no modal damping.
#include "geardyn/eig/eigen_options.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::assembly {

struct ModalDampingOptions {
  /// Undamped modes used. 0: model.damping.modal_modes when > 0, else
  /// max(20, 2 x the number of per-mode ratios); always capped at the number of DOFs.
  int n_modes = 0;
  eig::Method method = eig::Method::Auto;
};

struct ModalDampingSummary {
  int modes = 0;                         ///< modes in the basis (0: the model has no modal damping)
  int rigid_body_modes = 0;              ///< of those, rigid-body modes (ratio 0)
  double highest_frequency = eig::kNaN;  ///< omega of the highest mode in the basis [rad/s]
  double max_residual = eig::kNaN;       ///< backward error of the undamped solve
};

/// The damping ratio of an elastic mode: the per-mode list (`elastic_index` counts elastic modes
/// from 0 in order of frequency, rigid-body modes excluded), else the first band with
/// f_min <= omega < f_max (rad/s), else the default ratio `modal_ratio`.
double modal_damping_ratio(const model::Damping& damping, int elastic_index, double omega);

/// Fills system.modal_basis and system.modal_coefficients from model.damping (clears them when
/// the model has no modal damping). Rigid-body modes (omega^2 below 1e-10 max_i K_ii / M_ii)
/// get c = 0. Throws NumericalError("modal damping", ...) when the undamped modes cannot be
/// computed (singular system, fewer modes than needed) and InputError for negative ratios.
ModalDampingSummary apply_modal_damping(const model::Model& model, fe::LinearSystem& system,
                                        const ModalDampingOptions& options);
void apply_modal_damping(const model::Model& model, fe::LinearSystem& system);

}  // namespace geardyn::assembly
