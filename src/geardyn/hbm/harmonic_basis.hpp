#pragma once
// Truncated real Fourier series of one period and its time samples: the frequency <-> time
// transforms of the alternating frequency-time (AFT) method of harmonic balance (docs/theory.md
// §8).
//
//   x(theta) = a_0 + sum_{n=1..H} (a_n cos n theta + b_n sin n theta),   theta = omega t,
//
// stored as the coefficient vector [a_0, a_1, b_1, a_2, b_2, ..., a_H, b_H] (size 2H + 1), and
// sampled at theta_j = 2 pi j / n_time, j = 0 .. n_time - 1. Transforms go through FFTW
// (signal/fft.hpp). n_time > 2H, so the samples determine every kept harmonic exactly (no
// aliasing of the kept ones; harmonics above n_time / 2 - H of a nonlinear force alias onto
// them, which is why n_time is chosen well above 2H: default_time_samples).
// Reference: Cameron & Griffin, "An alternating frequency/time domain method for calculating
// the steady-state response of nonlinear dynamic systems", J. Appl. Mech. 56 (1989) 149-154.
#include <Eigen/Dense>

namespace geardyn::hbm {

class HarmonicBasis {
 public:
  /// H >= 0 harmonics, n_time >= 2H + 1 samples per period (InputError otherwise).
  HarmonicBasis(int harmonics, int time_samples);

  int harmonics() const { return harmonics_; }
  int time_samples() const { return n_; }
  /// 2H + 1.
  int size() const { return 2 * harmonics_ + 1; }
  /// Index of a_n (n >= 0) and of b_n (n >= 1) in the coefficient vector.
  static int cos_index(int n) { return n == 0 ? 0 : 2 * n - 1; }
  static int sin_index(int n) { return 2 * n; }

  /// Samples x(theta_j) of the series with coefficients `c` (size()).
  Eigen::VectorXd to_time(const Eigen::Ref<const Eigen::VectorXd>& c) const;
  /// Coefficients of the kept harmonics of the periodic samples `x` (time_samples()).
  Eigen::VectorXd to_frequency(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /// The sampling matrix Q (n_time x size()): to_time(c) = Q c. Its rows give the derivative of
  /// each sample with respect to the coefficients, for analytic AFT Jacobians.
  const Eigen::MatrixXd& sampling() const { return Q_; }
  /// The projection P (size() x n_time): to_frequency(x) = P x for series of kept harmonics.
  const Eigen::MatrixXd& projection() const { return P_; }

 private:
  int harmonics_;
  int n_;
  Eigen::MatrixXd Q_, P_;
};

/// Samples per period for H harmonics and a nonlinearity of polynomial degree `degree`
/// (1: linear; friction and contact laws are not polynomial, use the default 8): the products of
/// H harmonics reach harmonic degree * H, which must not alias onto the kept ones, so
/// n_time >= (degree + 1) H + 1, rounded up to a power of two, at least 64.
int default_time_samples(int harmonics, int degree = 8);

}  // namespace geardyn::hbm
