// GCC's -Wnull-dereference false positive inside Eigen's and <complex>'s inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <complex>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/hbm/harmonic_basis.hpp"
#include "geardyn/signal/fft.hpp"

namespace geardyn::hbm {

HarmonicBasis::HarmonicBasis(int harmonics, int time_samples)
    : harmonics_(harmonics), n_(time_samples) {
  if (harmonics < 0)
    throw InputError({}, "harmonics", "a number of harmonics >= 0", std::to_string(harmonics));
  if (time_samples < 2 * harmonics + 1)
    throw InputError({}, "time_samples",
                     fmt::format("at least 2 H + 1 = {} samples per period", 2 * harmonics + 1),
                     std::to_string(time_samples));
  Q_.resize(n_, size());
  P_.resize(size(), n_);
  for (int j = 0; j < n_; ++j) {
    const double theta = units::kTwoPi * j / n_;
    Q_(j, 0) = 1.0;
    P_(0, j) = 1.0 / n_;
    for (int h = 1; h <= harmonics_; ++h) {
      Q_(j, cos_index(h)) = std::cos(h * theta);
      Q_(j, sin_index(h)) = std::sin(h * theta);
      P_(cos_index(h), j) = 2.0 * Q_(j, cos_index(h)) / n_;
      P_(sin_index(h), j) = 2.0 * Q_(j, sin_index(h)) / n_;
    }
  }
}

Eigen::VectorXd HarmonicBasis::to_time(const Eigen::Ref<const Eigen::VectorXd>& c) const {
  if (c.size() != size())
    throw InputError({}, "coefficients", fmt::format("{} Fourier coefficients", size()),
                     std::to_string(c.size()));
  // Half spectrum with X_0 = n a_0, X_h = (n / 2)(a_h - i b_h); the inverse FFT divides by n.
  Eigen::VectorXcd X = Eigen::VectorXcd::Zero(n_ / 2 + 1);
  X[0] = n_ * c[0];
  for (int h = 1; h <= harmonics_; ++h)
    X[h] = 0.5 * n_ * std::complex<double>(c[cos_index(h)], -c[sin_index(h)]);
  return signal::inverse_real_fft(X, n_);
}

Eigen::VectorXd HarmonicBasis::to_frequency(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  if (x.size() != n_)
    throw InputError({}, "samples", fmt::format("{} time samples", n_), std::to_string(x.size()));
  const Eigen::VectorXcd X = signal::real_fft(x);
  Eigen::VectorXd c(size());
  c[0] = X[0].real() / n_;
  for (int h = 1; h <= harmonics_; ++h) {
    // n >= 2H + 1 keeps every kept harmonic below the Nyquist index n / 2.
    c[cos_index(h)] = 2.0 * X[h].real() / n_;
    c[sin_index(h)] = -2.0 * X[h].imag() / n_;
  }
  return c;
}

int default_time_samples(int harmonics, int degree) {
  const int needed = std::max(64, (std::max(degree, 1) + 1) * std::max(harmonics, 1) + 1);
  int n = 1;
  while (n < needed) n *= 2;
  return n;
}

}  // namespace geardyn::hbm
