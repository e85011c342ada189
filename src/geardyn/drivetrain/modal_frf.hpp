#pragma once
// Frequency response at the operating point by modal superposition (docs/theory.md §16.14).
// The linearised pencil P(s) = s^2 M + s D + K_t (D = C_t + B diag(c) B^T) is in general not
// symmetric (gyroscopic terms at speed, contact and bearing tangents), so its inverse expands
// over right AND left eigenvectors: with P(lambda_k) x_k = 0, y_k^T P(lambda_k) = 0 and
// y_k^T P'(lambda_k) x_k = 1 (P' = 2 lambda M + D, the state-space biorthogonality of
// A = [0 I; -M^-1 K -M^-1 D] written for the quadratic pencil),
//     P(s)^-1 = sum over all 2n roots  x_k y_k^T / (s - lambda_k).
// The sum here runs over the modes the linearisation computed (each with its conjugate): the
// modes above them are truncated, which leaves out their (mostly static) residual flexibility;
// ModalFrf::static_truncation measures it at 0 Hz against K_t^-1 f. With static_correction the
// missing static part K_t^-1 f - sum_k(0) is added at every frequency (the mode-acceleration or
// static-correction method: R. R. Craig and A. J. Kurdila, "Fundamentals of Structural
// Dynamics", 2nd ed., 2006, section 11.4): exact at 0 Hz, and the remaining error is the
// truncated modes' dynamic part, small well below their frequencies.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/drivetrain/linearisation.hpp"

namespace geardyn::drivetrain {

/// A weighted sum over system equations: a load f = sum_k c_k e_{eq_k} or an output
/// y = sum_k c_k x[eq_k].
struct EquationCombination {
  std::vector<int> equations;
  std::vector<double> coefficients;
};

struct ModalFrf {
  Status status = Status::Ok;
  std::string message;
  std::vector<double> frequency_hz;
  Eigen::MatrixXcd receptance;   ///< frequencies x outputs: displacement per unit load
  int modes_used = 0;            ///< modes in the sum (a conjugate pair counted once)
  double highest_mode_hz = 0.0;  ///< undamped natural frequency of the highest mode kept
  /// Residual flexibility: at 0 Hz, the modal sum against the exact static receptance K_t^-1 f
  /// at the outputs (only when K_t is regular: no rigid-body modes).
  bool static_checked = false;
  Eigen::VectorXd static_exact;
  Eigen::VectorXcd static_modal;
  /// max_j |static_modal_j - static_exact_j| / max_j |static_exact_j|.
  double static_truncation = 0.0;
  bool static_corrected = false;  ///< the static residual was added to `receptance`
};

/// Receptance of every output to the load at the frequencies [Hz] by the modal sum over the
/// lowest `n_modes` modes of `lin` (0: all). `lin` must carry the left eigenvectors (linearise
/// with left = true); otherwise the result has Status::Failed and says why. With
/// `static_correction` (and K_t regular) the truncated modes' static part is added.
ModalFrf modal_frf(const Linearisation& lin, const EquationCombination& load,
                   const std::vector<EquationCombination>& outputs,
                   const std::vector<double>& frequency_hz, int n_modes = 0,
                   bool static_correction = false);

/// The direct solve (K_t - w^2 M + i w D)^-1 f at the outputs, one complex sparse LU per
/// frequency (the low-rank damping by the Woodbury identity): the reference of the modal sum.
/// A singular P(i w) (an undamped root exactly on a frequency, a free spin at 0 Hz) gives NaN.
Eigen::MatrixXcd direct_frf(const Linearisation& lin, const EquationCombination& load,
                            const std::vector<EquationCombination>& outputs,
                            const std::vector<double>& frequency_hz);

}  // namespace geardyn::drivetrain
