#pragma once
// Parts shared by the eigen solvers: method choice and the Krylov (Lanczos / Arnoldi) knobs.
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace geardyn::eig {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Dense solvers compute every eigenpair (O(n^3)); sparse solvers compute the wanted ones by
/// shift-invert Krylov iteration on a sparse factorisation. Auto: dense up to `dense_limit`.
enum class Method { Auto, Dense, Sparse };

constexpr std::string_view to_string(Method m) {
  switch (m) {
    case Method::Auto:
      return "auto";
    case Method::Dense:
      return "dense";
    case Method::Sparse:
      return "sparse";
  }
  return "auto";
}

/// Largest size for which Method::Dense is accepted at all (an explicit request above
/// `dense_limit` is honoured up to here, e.g. to cross-check the sparse solver).
inline constexpr int kDenseHardLimit = 5000;

/// Krylov iteration of the real symmetric sparse solver (symmetric_eigen.hpp).
enum class KrylovEngine { Block, Spectra };

constexpr std::string_view to_string(KrylovEngine e) {
  return e == KrylovEngine::Spectra ? "spectra" : "block";
}

/// Throws InputError when Method::Dense is asked for more than kDenseHardLimit DOFs.
void check_dense_size(Method method, long n);

struct KrylovOptions {
  /// Relative accuracy of the Ritz values of the shift-inverted operator (Spectra's `tol`:
  /// a Ritz value theta is converged when its residual estimate < tol * max(|theta|, eps^(2/3))).
  double tolerance = 1e-10;
  /// Maximum number of implicit restarts.
  int max_restarts = 1000;
  /// Krylov subspace dimension before a restart; 0: automatic -- block Lanczos
  /// min(N - p, max(2 nev + 2 p, nev + 20 + p)), Spectra min(N, max(2 nev + 1, nev + 20)).
  int subspace_size = 0;

  /// Appends one line per problem to `problems`.
  void validate(std::vector<std::string>& problems) const;
};

}  // namespace geardyn::eig
