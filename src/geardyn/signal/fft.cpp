#include "geardyn/signal/fft.hpp"

#include <fftw3.h>

#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

namespace geardyn::signal {
namespace {

// Plans per (length, direction). Created under the mutex, never destroyed before exit; executed
// without the lock through FFTW's new-array interface, which is thread-safe.
class PlanCache {
 public:
  ~PlanCache() {
    for (auto& [key, plan] : plans_) fftw_destroy_plan(plan);
  }

  fftw_plan get(int n, bool forward) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto key = std::make_pair(n, forward);
    if (auto it = plans_.find(key); it != plans_.end()) return it->second;
    // Planning needs arrays of the alignment that execution will use: FFTW's own allocator.
    // FFTW_ESTIMATE does not touch the arrays' contents.
    const std::size_t half = static_cast<std::size_t>(n / 2 + 1);
    double* real = fftw_alloc_real(static_cast<std::size_t>(n));
    fftw_complex* spectrum = fftw_alloc_complex(half);
    fftw_plan plan = forward ? fftw_plan_dft_r2c_1d(n, real, spectrum, FFTW_ESTIMATE)
                             : fftw_plan_dft_c2r_1d(n, spectrum, real, FFTW_ESTIMATE);
    fftw_free(real);
    fftw_free(spectrum);
    if (plan == nullptr)
      throw std::runtime_error("FFTW could not create a plan for length " + std::to_string(n));
    plans_.emplace(key, plan);
    return plan;
  }

 private:
  std::mutex mutex_;
  std::map<std::pair<int, bool>, fftw_plan> plans_;
};

PlanCache& plan_cache() {
  static PlanCache cache;
  return cache;
}

struct FftwDeleter {
  void operator()(void* p) const { fftw_free(p); }
};
using RealBuffer = std::unique_ptr<double, FftwDeleter>;
using ComplexBuffer = std::unique_ptr<fftw_complex, FftwDeleter>;

}  // namespace

Eigen::VectorXcd real_fft(const Eigen::Ref<const Eigen::VectorXd>& x) {
  const int n = static_cast<int>(x.size());
  if (n < 1) throw std::invalid_argument("real_fft: empty signal");
  const int half = n / 2 + 1;
  fftw_plan plan = plan_cache().get(n, true);
  RealBuffer in(fftw_alloc_real(static_cast<std::size_t>(n)));
  ComplexBuffer out(fftw_alloc_complex(static_cast<std::size_t>(half)));
  for (int j = 0; j < n; ++j) in.get()[j] = x[j];
  fftw_execute_dft_r2c(plan, in.get(), out.get());
  Eigen::VectorXcd X(half);
  for (int k = 0; k < half; ++k) X[k] = {out.get()[k][0], out.get()[k][1]};
  return X;
}

Eigen::VectorXd inverse_real_fft(const Eigen::Ref<const Eigen::VectorXcd>& X, int n) {
  if (n < 1) throw std::invalid_argument("inverse_real_fft: length must be at least 1");
  const int half = n / 2 + 1;
  if (X.size() != half)
    throw std::invalid_argument("inverse_real_fft: " + std::to_string(X.size()) +
                                " coefficients given, expected n/2 + 1 = " + std::to_string(half));
  fftw_plan plan = plan_cache().get(n, false);
  ComplexBuffer in(fftw_alloc_complex(static_cast<std::size_t>(half)));
  RealBuffer out(fftw_alloc_real(static_cast<std::size_t>(n)));
  for (int k = 0; k < half; ++k) {
    in.get()[k][0] = X[k].real();
    in.get()[k][1] = X[k].imag();
  }
  // A real signal has real X_0 and (n even) real X_{n/2}; FFTW's c2r assumes so.
  in.get()[0][1] = 0.0;
  if (n % 2 == 0) in.get()[half - 1][1] = 0.0;
  fftw_execute_dft_c2r(plan, in.get(), out.get());  // c2r destroys its input: ours is scratch
  Eigen::VectorXd x(n);
  const double scale = 1.0 / static_cast<double>(n);
  for (int j = 0; j < n; ++j) x[j] = out.get()[j] * scale;
  return x;
}

}  // namespace geardyn::signal
