#pragma once
// Interface-mode reduction (Tran): replaces the interface DOFs of an already reduced component
// (e.g. the left/right sector interfaces kept as Craig-Bampton masters) by a few interface modes.
//
// With the reduced coordinates partitioned into interface I and the others O (other masters and
// modal coordinates), the interface modes are the eigenvectors of the Guyan reduction of the pair
// onto the interface,
//   G = [I; -K_OO^{-1} K_OI],  K_g = G^H K G,  M_g = G^H M G,  K_g Phi_I = M_g Phi_I Lambda_I,
// normalised Phi_I^H M_g Phi_I = I. The lowest n_interface_modes of them replace x_I:
//   x = T q,   q = [p; x_O],   T = [Phi_I 0; 0 I]   (in the partition [I | O]),
//   K_new = T^H K T,  M_new = T^H M T.
// The other coordinates stay what they were (physical masters stay physical); the span equals
// that of [Phi_I 0; -K_OO^{-1} K_OI Phi_I  I], so the static coupling is not lost. At least six
// interface modes are required: the six rigid-body motions of a free component live on the
// interface and must survive (thesis chapter 2.2.3; it takes about a third of the CB mode count).
// Source: D.-M. Tran, "Component mode synthesis methods using interface modes. Application to
// structures with cyclic symmetry", Computers & Structures 79 (2001) 209-222 (reference [11] of
// A. Durastante, "Simulation of the Dynamic Response of Aeronautical Gears Equipped with Damper
// Rings", MSc thesis, Politecnico di Torino, 2018, chapter 2.2.3).
//
// Scalar = double, or std::complex<double> for the Hermitian pairs of a cyclic harmonic
// (docs/theory.md §10). Dense throughout: meant for reduced models (sizes up to a few thousand).
#include <Eigen/Dense>
#include <complex>
#include <vector>

namespace geardyn::reduce {

template <class Scalar>
struct InterfaceReduction {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  Matrix K;  ///< (n_interface_modes + n_other)^2, coordinates [interface modes; other]
  Matrix M;
  /// x_old = T q_new: rows in the input's coordinate order, columns [interface modes; other].
  Matrix transformation;
  std::vector<int> interface_dofs;  ///< as given (rows of the interface modes)
  std::vector<int> other_dofs;      ///< the rest, ascending: the last columns of T, in order
  /// Every eigenvalue of the Guyan interface problem [rad^2/s^2], ascending; the first
  /// n_interface_modes are kept.
  Eigen::VectorXd interface_eigenvalues;
  int n_interface_modes = 0;
};

/// Interface-mode reduction of the Hermitian pair (K, M) (K positive semi-definite, M positive
/// definite) onto the lowest `n_interface_modes` modes of `interface_dofs` (indices into the
/// coordinates). Throws InputError when the sizes differ, an index is out of range or repeated,
/// n_interface_modes < 6 or > the number of interface DOFs, or the matrices are larger than
/// 5000 (dense work); throws InputError when K_OO is singular (the other coordinates have a free
/// motion the interface does not hold) and NumericalError when the interface eigenproblem fails.
template <class Scalar>
InterfaceReduction<Scalar> interface_mode_reduction(
    const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& K,
    const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& M,
    const std::vector<int>& interface_dofs, int n_interface_modes);

extern template InterfaceReduction<double> interface_mode_reduction<double>(const Eigen::MatrixXd&,
                                                                            const Eigen::MatrixXd&,
                                                                            const std::vector<int>&,
                                                                            int);
extern template InterfaceReduction<std::complex<double>>
interface_mode_reduction<std::complex<double>>(const Eigen::MatrixXcd&, const Eigen::MatrixXcd&,
                                               const std::vector<int>&, int);

}  // namespace geardyn::reduce
