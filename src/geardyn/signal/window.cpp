#include "geardyn/signal/window.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "geardyn/core/units.hpp"

namespace geardyn::signal {
namespace {

// Cosine-sum windows w_j = sum_k (-1)^k a_k cos(2 pi k j / n). Flat top: the coefficients of
// MATLAB's `flattopwin` (also SciPy's `flattop`), D'Antona & Ferrero, "Digital Signal
// Processing for Measurement Systems", Springer 2006, p. 70.
constexpr std::array<double, 5> kFlatTop = {0.21557895, 0.41663158, 0.277263158, 0.083578947,
                                            0.006947368};
constexpr std::array<double, 2> kHann = {0.5, 0.5};
constexpr std::array<double, 1> kRectangular = {1.0};

template <std::size_t N>
Eigen::VectorXd cosine_sum(const std::array<double, N>& a, int n) {
  Eigen::VectorXd w(n);
  for (int j = 0; j < n; ++j) {
    double value = 0.0;
    for (std::size_t k = 0; k < N; ++k) {
      const double sign = (k % 2 == 0) ? 1.0 : -1.0;
      value += sign * a[k] *
               std::cos(units::kTwoPi * static_cast<double>(k) * j / static_cast<double>(n));
    }
    w[j] = value;
  }
  return w;
}

double sinc(double x) {
  if (std::abs(x) < 1e-12) return 1.0;
  return std::sin(units::kPi * x) / (units::kPi * x);
}

// Large-n amplitude response of a coherent-gain corrected cosine-sum window to a sinusoid
// `offset` bins away from the bin centre. The DFT of w has a_0 at bin 0 and (-1)^k a_k / 2 at
// bins +-k; the Dirichlet kernel's phase adds another (-1)^k, so all terms add with + sign.
template <std::size_t N>
double response(const std::array<double, N>& a, double offset) {
  double r = a[0] * sinc(offset);
  for (std::size_t k = 1; k < N; ++k) {
    const double kk = static_cast<double>(k);
    r += 0.5 * a[k] * (sinc(offset - kk) + sinc(offset + kk));
  }
  return std::abs(r) / a[0];
}

void check_length(int n) {
  if (n < 1)
    throw std::invalid_argument("window length must be at least 1, got " + std::to_string(n));
}

}  // namespace

Eigen::VectorXd window_coefficients(Window w, int n) {
  check_length(n);
  switch (w) {
    case Window::Rectangular:
      return Eigen::VectorXd::Ones(n);
    case Window::Hann:
      return cosine_sum(kHann, n);
    case Window::FlatTop:
      return cosine_sum(kFlatTop, n);
  }
  throw std::invalid_argument("unknown window");
}

double coherent_gain(Window w, int n) { return window_coefficients(w, n).mean(); }

double equivalent_noise_bandwidth(Window w, int n) {
  const Eigen::VectorXd c = window_coefficients(w, n);
  const double sum = c.sum();
  return static_cast<double>(n) * c.squaredNorm() / (sum * sum);
}

double max_scalloping_loss(Window w) {
  switch (w) {
    case Window::Rectangular:
      return 1.0 - response(kRectangular, 0.5);
    case Window::Hann:
      return 1.0 - response(kHann, 0.5);
    case Window::FlatTop: {
      // The flat top's response is not monotonic between bins: take the worst deviation.
      double worst = 0.0;
      for (int i = 0; i <= 100; ++i)
        worst = std::max(worst, std::abs(1.0 - response(kFlatTop, 0.005 * i)));
      return worst;
    }
  }
  return 1.0;
}

}  // namespace geardyn::signal
