// Real FFT: checked against the defining sum (a direct O(n^2) DFT), round trip, and concurrent
// use from several threads (plans are shared; execution must be thread-safe and deterministic).
#include "geardyn/signal/fft.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

namespace geardyn::signal {
namespace {

Eigen::VectorXd random_signal(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd x(n);
  for (int j = 0; j < n; ++j) x[j] = normal(rng);
  return x;
}

Eigen::VectorXcd direct_dft_half(const Eigen::VectorXd& x) {
  const int n = static_cast<int>(x.size());
  Eigen::VectorXcd X(n / 2 + 1);
  for (int k = 0; k <= n / 2; ++k) {
    std::complex<double> sum = 0.0;
    for (int j = 0; j < n; ++j)
      sum += x[j] * std::polar(1.0, -2.0 * std::numbers::pi * ((static_cast<long>(j) * k) % n) / n);
    X[k] = sum;
  }
  return X;
}

TEST(RealFft, MatchesDirectDftForEvenOddAndPrimeLengths) {
  for (int n : {1, 2, 7, 16, 97, 250, 1000}) {
    const Eigen::VectorXd x = random_signal(n, 42u + static_cast<unsigned>(n));
    const Eigen::VectorXcd X = real_fft(x);
    const Eigen::VectorXcd reference = direct_dft_half(x);
    ASSERT_EQ(X.size(), n / 2 + 1) << "n = " << n;
    // Both are sums of n terms of size ~1: rounding ~ n eps relative to sqrt(n).
    EXPECT_LT((X - reference).cwiseAbs().maxCoeff(), 1e-12 * n * std::sqrt(n) + 1e-13)
        << "n = " << n;
  }
}

TEST(RealFft, InverseReturnsTheSignal) {
  for (int n : {1, 2, 9, 64, 1001}) {
    const Eigen::VectorXd x = random_signal(n, 7u);
    const Eigen::VectorXd back = inverse_real_fft(real_fft(x), n);
    EXPECT_LT((back - x).cwiseAbs().maxCoeff(), 1e-14 * std::log2(n + 1) * 10) << "n = " << n;
  }
}

TEST(RealFft, RejectsBadInput) {
  EXPECT_THROW(real_fft(Eigen::VectorXd()), std::invalid_argument);
  EXPECT_THROW(inverse_real_fft(Eigen::VectorXcd::Zero(3), 8), std::invalid_argument);
  EXPECT_THROW(inverse_real_fft(Eigen::VectorXcd::Zero(1), 0), std::invalid_argument);
}

TEST(RealFft, ConcurrentCallsAgreeWithSerialResults) {
  // Several lengths planned concurrently for the first time, then executed many times.
  const std::vector<int> lengths = {300, 301, 302, 303, 512, 1023};
  std::vector<Eigen::VectorXd> signals;
  std::vector<Eigen::VectorXcd> serial;
  for (std::size_t i = 0; i < lengths.size(); ++i)
    signals.push_back(random_signal(lengths[i], 100u + static_cast<unsigned>(i)));
  std::vector<std::vector<Eigen::VectorXcd>> parallel(lengths.size());
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < lengths.size(); ++i)
    threads.emplace_back([&, i] {
      for (int repeat = 0; repeat < 50; ++repeat) parallel[i].push_back(real_fft(signals[i]));
    });
  for (auto& t : threads) t.join();
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    const Eigen::VectorXcd reference = real_fft(signals[i]);
    for (const auto& X : parallel[i]) EXPECT_EQ((X - reference).cwiseAbs().maxCoeff(), 0.0);
  }
}

}  // namespace
}  // namespace geardyn::signal
