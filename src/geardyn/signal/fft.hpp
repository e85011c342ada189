#pragma once
// Discrete Fourier transforms of real signals through FFTW3.
//
// Convention (FFTW's, unnormalised forward transform):
//   X_k = sum_{j=0}^{n-1} x_j exp(-2 pi i j k / n),   k = 0 .. n/2  (n/2 + 1 values)
// and the inverse returns x_j = (1/n) sum_{k=0}^{n-1} X_k exp(+2 pi i j k / n), the full spectrum
// being the Hermitian extension of the half spectrum.
//
// Plans are made once per length with FFTW_ESTIMATE (deterministic: the same plan and the same
// result for the same input on every run and thread count) and kept for the life of the process.
// FFTW's planner is not thread-safe, so plan creation is serialised by a mutex; executing a plan
// (fftw_execute_dft_r2c on buffers of the plan's alignment) is thread-safe, so these functions
// may be called concurrently from the threads of a study.
#include <Eigen/Dense>
#include <complex>

namespace geardyn::signal {

/// Half spectrum X_0 .. X_{n/2} of the real signal x (n = x.size() >= 1). Unnormalised.
Eigen::VectorXcd real_fft(const Eigen::Ref<const Eigen::VectorXd>& x);

/// Real signal of length n from its half spectrum (n/2 + 1 values, n given because n/2 + 1 does
/// not determine whether n is odd). Includes the 1/n factor, so inverse_real_fft(real_fft(x),
/// n) == x to rounding. The imaginary parts of X_0 and (n even) X_{n/2} are ignored.
/// Throws std::invalid_argument when X.size() != n/2 + 1.
Eigen::VectorXd inverse_real_fft(const Eigen::Ref<const Eigen::VectorXcd>& X, int n);

}  // namespace geardyn::signal
