#pragma once
// A linear structure with nonlinear elements placed between its DOFs (docs/theory.md §8):
//
//   M q'' + C q' + K q + sum_e B_e^T f_e(B_e q, B_e q', theta) = lambda f_ext(theta),
//
// q the n_dof coordinates (physical DOFs of a small model, or the modal coordinates of a reduced
// one: M = I, C = diag(2 zeta_r w_r), K = diag(w_r^2), B_e = G_e Phi), theta = omega t,
// f_ext a periodic force given by its Fourier coefficients and lambda a load factor (1 unless a
// continuation varies it). The structural loss K_loss adds i K_loss on every harmonic n >= 1
// (frequency-independent hysteretic damping); it has no time-domain form (time analyses of such
// a system throw InputError).
//
// ElementHarmonicBalance is its harmonic balance in the physical form of harmonic_balance.hpp
// (unknowns DOF-major, X[d (2H+1) + c]): dense, for systems of up to a few hundred DOFs; the
// elements' Jacobians are added block by block.
#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/hbm/harmonic_balance.hpp"
#include "geardyn/hbm/nonlinear_element.hpp"

namespace geardyn::hbm {

/// A nonlinear element placed on the system: u = B q.
struct PlacedNonlinearElement {
  std::shared_ptr<const NonlinearElement> element;
  std::string name;
  Eigen::MatrixXd B;  ///< element.size() x n_dof

  /// Throws InputError when B is not element->size() x n_dof or not finite.
  void validate(int n_dof) const;
};

struct ElementSystem {
  Eigen::MatrixXd M, C, K;  ///< n_dof square
  Eigen::MatrixXd K_loss;   ///< empty or n_dof square: i K_loss on harmonics n >= 1
  std::vector<PlacedNonlinearElement> elements;
  /// Fourier coefficients of f_ext, DOF-major (n_dof (2H_f+1), H_f the forcing's harmonics,
  /// any H_f <= the balance's H; higher ones are dropped with a note by the caller). Empty: no
  /// excitation.
  Eigen::VectorXd excitation;
  int excitation_harmonics = 1;  ///< H_f

  int dofs() const { return static_cast<int>(K.rows()); }
  /// Throws InputError on inconsistent sizes or non-finite entries.
  void validate() const;
  /// f_ext(theta) at one phase (n_dof), for time integration.
  Eigen::VectorXd excitation_at(double theta) const;
};

class ElementHarmonicBalance final : public HarmonicSystem {
 public:
  ElementHarmonicBalance(ElementSystem system, HarmonicBasis basis);

  int size() const override { return system_.dofs() * basis_.size(); }
  const HarmonicBasis& basis() const { return basis_; }
  const ElementSystem& system() const { return system_; }

  /// R(X, omega) = D(omega) X + F_nl(X, omega) - lambda F_ext, lambda = load_factor().
  Eigen::VectorXd residual(const Eigen::VectorXd& X, double omega, Eigen::MatrixXd* J = nullptr,
                           Eigen::VectorXd* dR_domega = nullptr) const override;
  /// dF_nl/dV (size() square): the derivative of the elements' force coefficients with respect
  /// to the coefficients V of the velocity q' (DOF-major), sum_e B_e^T (P diag(df_e/dv) Q) B_e
  /// per harmonic block (NonlinearElement::harmonic_velocity_jacobian). Zero when no element
  /// depends on the velocity. Hill's method adds it to its first-order term (stability.hpp).
  Eigen::MatrixXd velocity_jacobian(const Eigen::VectorXd& X, double omega) const;
  /// max(||lambda F_ext||, ||K X||, ||(n omega)^2 M X_n||, tiny): no element is evaluated.
  double residual_scale(const Eigen::VectorXd& X, double omega) const override;

  void set_load_factor(double lambda) { load_factor_ = lambda; }
  double load_factor() const { return load_factor_; }
  /// The excitation in the unknowns' layout (H of the balance): F_ext.
  const Eigen::VectorXd& external_force() const { return F_ext_; }

  /// Coefficients of element e's coordinates (coordinate-major) at X.
  Eigen::VectorXd element_coordinates(const Eigen::VectorXd& X, int e) const;
  /// The linear response (no elements) at omega: D(omega)^-1 lambda F_ext.
  Eigen::VectorXd linear_response(double omega) const;

 private:
  ElementSystem system_;
  HarmonicBasis basis_;
  Eigen::VectorXd F_ext_;
  double load_factor_ = 1.0;
};

}  // namespace geardyn::hbm
