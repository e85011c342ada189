// GCC's -Wnull-dereference false positive inside Eigen's inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of Eigen.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <complex>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/hbm/harmonic_basis.hpp"
#include "geardyn/hbm/stability.hpp"

namespace geardyn::hbm {

void HillOptions::validate() const {
  std::string problems;
  auto add = [&problems](const std::string& p) { problems += (problems.empty() ? "" : "; ") + p; };
  if (!(stability_tolerance >= 0.0 && std::isfinite(stability_tolerance)))
    add(fmt::format("stability_tolerance must be finite and >= 0, found {}", stability_tolerance));
  if (!(kind_tolerance > 0.0 && kind_tolerance < 0.25))
    add(fmt::format("kind_tolerance must lie in (0, 0.25), found {}", kind_tolerance));
  if (!problems.empty()) throw InputError({}, "hbm.HillOptions", "valid Hill options", problems);
}

const char* to_string(FloquetResult::Instability kind) {
  switch (kind) {
    case FloquetResult::Instability::None:
      return "none";
    case FloquetResult::Instability::Fold:
      return "fold";
    case FloquetResult::Instability::PeriodDoubling:
      return "period_doubling";
    case FloquetResult::Instability::NeimarkSacker:
      return "neimark_sacker";
  }
  return "none";
}

std::string FloquetResult::brief_report() const {
  return fmt::format(
      "hill stability: {} exponents, max Re {:.6g}, {} ({}), sorting gap {:.3g}, "
      "status {}{}{}",
      exponents.size(), max_real_part, stable ? "stable" : "unstable", to_string(kind), sorting_gap,
      to_string(status), message.empty() ? "" : ": ", message);
}

namespace {

using Complex = std::complex<double>;

// Centroids closer than this are tied: far above the rounding of kappa (~1e-15 H), far below
// any separation between members of one family (1).
constexpr double kCentroidTie = 1e-6;

// Im lambda reduced modulo omega into [-omega / 2, omega / 2].
double reduced_imag(Complex lambda, double omega) {
  return lambda.imag() - omega * std::round(lambda.imag() / omega);
}

// Harmonic centroid kappa of the coefficient part P (n_dof (2H+1), DOF-major) of an eigenvector:
// the mean harmonic index k of p(t) = sum_k c_k e^{i k theta} weighted by |c_k|^2, with
// a cos + b sin = (a - i b)/2 e^{i theta} + (a + i b)/2 e^{-i theta}.
double centroid(const Eigen::Ref<const Eigen::VectorXcd>& P, int dofs, int harmonics) {
  const int s = 2 * harmonics + 1;
  const Complex i{0.0, 1.0};
  double moment = 0.0, total = 0.0;
  for (int d = 0; d < dofs; ++d) {
    total += std::norm(P[d * s]);
    for (int n = 1; n <= harmonics; ++n) {
      const Complex a = P[d * s + HarmonicBasis::cos_index(n)];
      const Complex b = P[d * s + HarmonicBasis::sin_index(n)];
      const double plus = std::norm(0.5 * (a - i * b)), minus = std::norm(0.5 * (a + i * b));
      total += plus + minus;
      moment += n * (plus - minus);
    }
  }
  return total > 0.0 ? moment / total : 0.0;
}

}  // namespace

namespace {

// The Hill matrix A of the first-order eigenproblem.
// Jv (empty: none) is dF_nl/dV, added to D1.
Eigen::MatrixXd hill_matrix(const Eigen::MatrixXd& J, const Eigen::MatrixXd& Jv,
                            const Eigen::FullPivLU<Eigen::MatrixXd>& lu, const Eigen::MatrixXd& C,
                            int harmonics, double omega) {
  const auto nd = static_cast<int>(C.rows());
  const int s = 2 * harmonics + 1, N = nd * s;
  // First-order form of (1): A z = lambda z, z = [P; lambda P]. D2^-1 = M^-1 (x) I, so
  // D2^-1 J mixes block rows of J with M^-1, and D2^-1 D1 = (M^-1 C) (x) I + I (x) G with G the
  // +-2 n omega coupling of the (a_n, b_n) pair.
  const Eigen::MatrixXd Minv = lu.inverse();
  const Eigen::MatrixXd MinvC = Minv * C;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * N, 2 * N);
  A.topRightCorner(N, N).setIdentity();
  for (int i = 0; i < nd; ++i) {
    for (int k = 0; k < nd; ++k) {
      if (MinvC(i, k) != 0.0) A.block(N + i * s, N + k * s, s, s).diagonal().array() -= MinvC(i, k);
      if (Minv(i, k) == 0.0) continue;
      A.block(N + i * s, 0, s, N) -= Minv(i, k) * J.middleRows(k * s, s);
      if (Jv.size() > 0) A.block(N + i * s, N, s, N) -= Minv(i, k) * Jv.middleRows(k * s, s);
    }
    for (int n = 1; n <= harmonics; ++n) {
      const int ci = N + i * s + HarmonicBasis::cos_index(n);
      const int si = N + i * s + HarmonicBasis::sin_index(n);
      A(ci, si) -= 2.0 * n * omega;
      A(si, ci) += 2.0 * n * omega;
    }
  }
  return A;
}

// The eigenvalues ordered by |kappa|, ties broken as described inside.
std::vector<int> central_order(const Eigen::VectorXcd& lambda, const std::vector<double>& kappa) {
  const auto n_all = static_cast<int>(lambda.size());
  // Most central eigenvectors first. Ties in |kappa| are exact for real eigenvectors (kappa = 0
  // identically) and for blocks the truncation decouples (with H = 1 and an odd nonlinearity
  // the a_0 block carries a kappa = 0 pair of its own); they fall to the smallest |Im lambda|
  // (the Lazarus-Thomas criterion), then Im > 0 first, which keeps conjugate pairs adjacent.
  std::vector<int> order(static_cast<std::size_t>(n_all));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&kappa](int a, int b) {
    return kappa[static_cast<std::size_t>(a)] < kappa[static_cast<std::size_t>(b)];
  });
  for (std::size_t first = 0; first < order.size();) {
    std::size_t last = first + 1;
    while (last < order.size() && kappa[static_cast<std::size_t>(order[last])] -
                                          kappa[static_cast<std::size_t>(order[first])] <=
                                      kCentroidTie)
      ++last;
    std::stable_sort(order.begin() + static_cast<std::ptrdiff_t>(first),
                     order.begin() + static_cast<std::ptrdiff_t>(last), [&lambda](int a, int b) {
                       const double ia = std::abs(lambda[a].imag()),
                                    ib = std::abs(lambda[b].imag());
                       if (ia != ib) return ia < ib;
                       return lambda[a].imag() > lambda[b].imag();
                     });
    first = last;
  }
  return order;
}

// The 2 n_dof exponents kept (indices into lambda), most central first; sets out.sorting_gap.
std::vector<int> select_exponents(const std::vector<int>& order, const Eigen::VectorXcd& lambda,
                                  const std::vector<double>& kappa, int nd, double omega,
                                  const HillOptions& options, FloquetResult& out) {
  const auto n_all = static_cast<int>(lambda.size());
  const double kind_band = options.kind_tolerance * omega;
  auto is_half = [&](Complex l) {
    return instability_kind(l, omega, options.kind_tolerance) ==
           FloquetResult::Instability::PeriodDoubling;
  };
  std::vector<char> used(static_cast<std::size_t>(n_all), 0);  // accepted or skipped twin
  std::vector<int> accepted;
  double max_accepted = 0.0;
  for (const int j : order) {
    if (static_cast<int>(accepted.size()) == 2 * nd) break;
    if (used[static_cast<std::size_t>(j)]) continue;
    used[static_cast<std::size_t>(j)] = 1;
    int keep = j;
    if (is_half(lambda[j])) {
      // Its conjugate twin stands for the same (real negative) multiplier.
      int twin = -1;
      double best = std::numeric_limits<double>::infinity();
      for (int m = 0; m < n_all; ++m) {
        if (used[static_cast<std::size_t>(m)]) continue;
        const double d = std::abs(lambda[m] - std::conj(lambda[j]));
        if (d < best) {
          best = d;
          twin = m;
        }
      }
      if (twin >= 0 && best <= kind_band) {
        used[static_cast<std::size_t>(twin)] = 1;
        if (lambda[twin].imag() > lambda[j].imag()) keep = twin;
      }
    }
    accepted.push_back(keep);
    max_accepted = std::max(max_accepted, kappa[static_cast<std::size_t>(keep)]);
  }
  double min_rejected = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n_all; ++j)
    if (!used[static_cast<std::size_t>(j)])
      min_rejected = std::min(min_rejected, kappa[static_cast<std::size_t>(j)]);
  out.sorting_gap = min_rejected - max_accepted;
  return accepted;
}

}  // namespace

FloquetResult hill_stability(const Eigen::MatrixXd& J, const Eigen::MatrixXd& M,
                             const Eigen::MatrixXd& C, int harmonics, double omega,
                             const HillOptions& options) {
  return hill_stability(J, Eigen::MatrixXd(), M, C, harmonics, omega, options);
}

FloquetResult hill_stability(const ElementHarmonicBalance& hb, const Eigen::VectorXd& X,
                             double omega, const HillOptions& options) {
  Eigen::MatrixXd J;
  hb.residual(X, omega, &J);
  return hill_stability(J, hb.velocity_jacobian(X, omega), hb.system().M, hb.system().C,
                        hb.basis().harmonics(), omega, options);
}

FloquetResult hill_stability(const Eigen::MatrixXd& J, const Eigen::MatrixXd& Jv,
                             const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, int harmonics,
                             double omega, const HillOptions& options) {
  options.validate();
  const auto nd = static_cast<int>(M.rows());
  if (harmonics < 0)
    throw InputError({}, "hbm.hill_stability.harmonics", "H >= 0", std::to_string(harmonics));
  if (!(omega > 0.0 && std::isfinite(omega)))
    throw InputError({}, "hbm.hill_stability.omega", "a finite frequency > 0",
                     fmt::format("{}", omega));
  const int s = 2 * harmonics + 1, N = nd * s;
  if (nd == 0 || M.cols() != nd || C.rows() != nd || C.cols() != nd || J.rows() != N ||
      J.cols() != N)
    throw InputError({}, "hbm.hill_stability",
                     "square M, C of one size n_dof and J of size n_dof (2H + 1)",
                     fmt::format("M {}x{}, C {}x{}, J {}x{} (H = {})", M.rows(), M.cols(), C.rows(),
                                 C.cols(), J.rows(), J.cols(), harmonics));
  if (Jv.size() > 0 && (Jv.rows() != N || Jv.cols() != N))
    throw InputError({}, "hbm.hill_stability.Jv", fmt::format("empty or {0}x{0}", N),
                     fmt::format("{}x{}", Jv.rows(), Jv.cols()));
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(M);
  if (!lu.isInvertible())
    throw InputError({}, "hbm.hill_stability.M", "an invertible mass matrix",
                     fmt::format("rank {} of {}", lu.rank(), nd),
                     "condense massless DOFs out of the harmonic-balance system first");

  FloquetResult out;
  if (!J.allFinite() || !C.allFinite() || !Jv.allFinite()) {
    out.message = "J, Jv or C has non-finite entries";
    return out;
  }

  // First-order form of (1): A z = lambda z, z = [P; lambda P].
  const Eigen::MatrixXd A = hill_matrix(J, Jv, lu, C, harmonics, omega);

  const Eigen::EigenSolver<Eigen::MatrixXd> es(A, true);
  if (es.info() != Eigen::Success) {
    out.message =
        fmt::format("the dense eigen-solve of the {0}x{0} Hill matrix did not converge", 2 * N);
    return out;
  }
  const Eigen::VectorXcd lambda = es.eigenvalues();
  const Eigen::MatrixXcd V = es.eigenvectors();
  const auto n_all = static_cast<int>(lambda.size());
  std::vector<double> kappa(static_cast<std::size_t>(n_all));
  for (int j = 0; j < n_all; ++j)
    kappa[static_cast<std::size_t>(j)] = std::abs(centroid(V.col(j).head(N), nd, harmonics));

  const std::vector<int> order = central_order(lambda, kappa);
  std::vector<int> accepted = select_exponents(order, lambda, kappa, nd, omega, options, out);

  std::sort(accepted.begin(), accepted.end(), [&lambda](int a, int b) {
    if (lambda[a].real() != lambda[b].real()) return lambda[a].real() > lambda[b].real();
    return lambda[a].imag() > lambda[b].imag();
  });
  const auto n_kept = static_cast<Eigen::Index>(accepted.size());
  const double period = units::kTwoPi / omega;
  out.exponents.resize(n_kept);
  out.multipliers.resize(n_kept);
  out.centroids.resize(n_kept);
  for (Eigen::Index j = 0; j < n_kept; ++j) {
    const int e = accepted[static_cast<std::size_t>(j)];
    out.exponents[j] = lambda[e];
    out.multipliers[j] = std::exp(lambda[e] * period);
    out.centroids[j] = kappa[static_cast<std::size_t>(e)];
  }
  out.max_real_part = out.exponents[0].real();
  out.stable = out.max_real_part <= options.stability_tolerance * omega;
  if (!out.stable) out.kind = instability_kind(out.exponents[0], omega, options.kind_tolerance);
  out.status = Status::Ok;
  return out;
}

FloquetResult::Instability instability_kind(Complex lambda, double omega, double kind_tolerance) {
  const double band = kind_tolerance * omega;
  const double reduced = reduced_imag(lambda, omega);
  if (std::abs(reduced) <= band) return FloquetResult::Instability::Fold;
  if (std::abs(0.5 * omega - std::abs(reduced)) <= band)
    return FloquetResult::Instability::PeriodDoubling;
  return FloquetResult::Instability::NeimarkSacker;
}

std::vector<char> fold_unstable(const std::vector<double>& omega) {
  std::vector<char> out(omega.size(), 0);
  int direction = 0;  // of the last non-zero step
  bool unstable = false;
  for (std::size_t i = 1; i < omega.size(); ++i) {
    const double step = omega[i] - omega[i - 1];
    const int d = step > 0.0 ? 1 : (step < 0.0 ? -1 : 0);
    if (d != 0) {
      if (direction != 0 && d != direction) unstable = !unstable;  // turned at point i - 1
      direction = d;
    }
    out[i] = unstable ? 1 : 0;
  }
  return out;
}

std::vector<FloquetResult> stability_along(const HarmonicBalance& hb,
                                           const ContinuationResult& curve,
                                           const HillOptions& options) {
  std::vector<FloquetResult> out;
  out.reserve(curve.points.size());
  Eigen::MatrixXd J;
  for (const auto& p : curve.points) {
    hb.residual(p.X, p.omega, &J);
    out.push_back(
        hill_stability(J, hb.mass(), hb.damping(), hb.basis().harmonics(), p.omega, options));
  }
  return out;
}

}  // namespace geardyn::hbm
