#include "geardyn/analyses/stability_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>

#include "geardyn/assembly/system_pencil.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/eig/projected_quadratic.hpp"
#include "geardyn/eig/quadratic_eigen.hpp"
#include "geardyn/eig/rigid_body.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::analyses {
namespace {

constexpr double kRpmPerRadS = 60.0 / units::kTwoPi;
// Roots below this fraction of the highest frequency checked are rigid-body roots (lambda = 0
// up to round-off, e.g. free torsion): no frequency, so no damping ratio worth quoting. Their
// growth rate is still checked.
constexpr double kRigidFraction = 1e-4;

using SparseMatrix = Eigen::SparseMatrix<double>;

// A Cholesky factorisation succeeds (CHOLMOD reports any pivot <= 0).
bool positive_definite(const SparseMatrix& A) {
  linalg::SymmetricFactorization f;
  return f.compute(A) == Status::Ok && f.kind() == linalg::FactorizationKind::Cholesky;
}

// "" when K (symmetric) is positive semi-definite: no eigenvalue of (K, M) below the shift
// sigma_b < 0 (K - sigma_b M positive definite, by Sylvester's law of inertia), and none in
// [sigma_b, 0] but those of the rigid-body motions K leaves at rest.
std::string stiffness_semi_definite(const fe::LinearSystem& system) {
  const SparseMatrix& K = system.K;
  const double sigma_b = eig::automatic_shift(K, system.M);
  if (!positive_definite(K - sigma_b * system.M))
    return fmt::format(
        "K has a direction of negative stiffness (K - ({:.3g}) M is not positive "
        "definite)",
        sigma_b);
  const eig::RigidBodySpace rigid =
      eig::rigid_body_space(K, system.M, fe::rigid_body_candidates(system.dofs));
  eig::SymmetricEigenOptions so;
  so.n_modes = static_cast<int>(std::min<Eigen::Index>(system.size(), rigid.dimension() + 2));
  const eig::SymmetricEigenResult modes = eig::solve_symmetric(K, system.M, so);
  if (modes.status != Status::Ok && modes.status != Status::FewerModes)
    return "the lowest undamped modes failed: " + modes.brief_report();
  for (Eigen::Index k = 0; k < modes.eigenvalues.size(); ++k) {
    if (eig::rigid_body_fraction(rigid, system.M,
                                 modes.eigenvectors.col(k).cast<std::complex<double>>()) >= 0.5)
      continue;
    if (!(modes.eigenvalues[k] > 0.0))
      return fmt::format("K has an elastic eigenvalue {:.3g} <= 0 (not a rigid-body motion)",
                         modes.eigenvalues[k]);
  }
  return "";
}

}  // namespace

std::string energy_certificate(const fe::LinearSystem& system, double tau) {
  const Eigen::Index n = system.size();
  if (!system.speed_bearings.empty()) return "speed-dependent bearings";
  if (linalg::relative_asymmetry(system.K) > 1e-13)
    return "K is not symmetric (cross-coupled stiffness)";
  // G skew: its symmetric part (G + G^T) / 2 vanishes.
  if (system.G.rows() == n &&
      (system.G + SparseMatrix(system.G.transpose())).norm() > 1e-13 * system.G.norm())
    return "G is not skew-symmetric";
  if (system.has_modal_damping() && system.modal_coefficients.minCoeff() < 0.0)
    return "negative modal damping";
  if (!positive_definite(system.M)) return "M is not positive definite";
  const SparseMatrix C = system.C.rows() == n ? system.C : SparseMatrix(n, n);
  if (!positive_definite(0.5 * (C + SparseMatrix(C.transpose())) + tau * system.M))
    return fmt::format("the damping has a direction below -{:.3g} M (negative damping)", tau);
  return stiffness_semi_definite(system);
}

// Tisseur's normwise backward error of (lambda, x) for `pencil`: ||P(lambda) x|| /
// ((|lambda|^2 ||M|| + |lambda| ||D|| + ||K||) ||x||), the norms those of backward_errors().
double axis_backward_error(const eig::QuadraticPencil& pencil, std::complex<double> lambda,
                           const Eigen::VectorXcd& x) {
  const Eigen::VectorXcd r =
      pencil.K * x + lambda * pencil.apply_damping(x) + (lambda * lambda) * (pencil.M * x);
  return eig::backward_errors_from_residuals(pencil, Eigen::VectorXcd::Constant(1, lambda), x,
                                             r)[0];
}

bool certified_growing(const eig::QuadraticPencil& pencil, std::complex<double> lambda,
                       const Eigen::VectorXcd& x, double backward_error) {
  const double eta = std::max(kBackwardErrorFactor * backward_error, kRoundoffBackwardError);
  return axis_backward_error(pencil, {0.0, lambda.imag()}, x) > eta;
}

// The solver of the scan: the projection (one basis for every speed) on models above
// kProjectionMinDofs, the full solver (solve_quadratic) below that and wherever the projection
// cannot certify every mode (counted).
class StabilitySolver {
 public:
  StabilitySolver(const fe::LinearSystem& system, bool project) : system_(system) {
    if (project && system.size() > kProjectionMinDofs)
      projection_.emplace(assembly::pencil_parts(system));
  }
  eig::QuadraticEigenResult solve(const eig::QuadraticPencil& pencil, double speed,
                                  const eig::QuadraticEigenOptions& qo) {
    if (projection_) {
      const assembly::SpeedIncrements inc = assembly::speed_increments(system_, speed);
      eig::QuadraticEigenResult r = projection_->solve(pencil, speed, inc.dK, inc.dC, qo);
      if (r.status == Status::Ok) {
        ++projected_;
        failures_in_a_row_ = 0;
        return r;
      }
      ++fallbacks_;
      if (first_fallback_.empty())
        first_fallback_ = fmt::format("at {:.6g} rpm: {}", speed * kRpmPerRadS, r.message);
      // A failed projected solve costs several enrichment rounds on top of the full solve:
      // after kMaxFailuresInARow the projection is given up for the rest of the scan.
      if (++failures_in_a_row_ >= kMaxFailuresInARow) {
        projection_.reset();
        given_up_ = true;
      }
    } else if (given_up_) {
      ++fallbacks_;
    }
    return eig::solve_quadratic(pencil, qo);
  }
  int projected() const { return projected_; }
  int fallbacks() const { return fallbacks_; }
  bool given_up() const { return given_up_; }
  const std::string& first_fallback() const { return first_fallback_; }

 private:
  // Below this size the full dense solve is as cheap as the projected one (as in Campbell).
  static constexpr int kProjectionMinDofs = 30;
  static constexpr int kMaxFailuresInARow = 2;
  const fe::LinearSystem& system_;
  std::optional<eig::ProjectedQuadratic> projection_;
  int projected_ = 0, fallbacks_ = 0, failures_in_a_row_ = 0;
  bool given_up_ = false;
  std::string first_fallback_;
};

namespace {

// The verdict from the modes computed (see the header: growth limit and backward error).
void judge(const eig::QuadraticPencil& pencil, const eig::QuadraticEigenResult& cx, double top,
           StabilityAtSpeed& out) {
  const double growth_limit = kGrowthTolerance * top;
  bool have_least = false;
  for (Eigen::Index j = 0; j < cx.eigenvalues.size(); ++j) {
    const std::complex<double> l = cx.eigenvalues[j];
    StabilityMode m;
    m.mode = static_cast<int>(j) + 1;
    m.eigenvalue = l;
    m.frequency = std::abs(l);
    m.damping_ratio = eig::damping_ratio(l);
    const double eta = j < cx.residuals.size() ? cx.residuals[j] : 0.0;
    if (l.real() > growth_limit && certified_growing(pencil, l, cx.eigenvectors.col(j), eta))
      out.unstable.push_back(m);
    if (m.frequency <= kRigidFraction * top) continue;
    if (!have_least || m.damping_ratio < out.least_damped.damping_ratio) out.least_damped = m;
    have_least = true;
  }
  out.stable = out.unstable.empty();
}

}  // namespace

StabilityAtSpeed check_stability(const fe::LinearSystem& system, double speed, double band_top,
                                 int* n_modes_hint, StabilitySolver* solver) {
  StabilityAtSpeed out;
  out.speed = speed;
  const eig::QuadraticPencil pencil = assembly::pencil_at(system, speed);
  const int n_dofs = system.size();
  // Every root real: 2n of them (complex pairs count once); at most kMaxModes.
  const int n_max = std::min(2 * n_dofs, kMaxModes);
  const double want = kBandMargin * band_top;
  int n = std::clamp(n_modes_hint != nullptr ? *n_modes_hint : kMinModes, 1, n_max);
  n = std::max(n, std::min(kMinModes, n_max));
  eig::QuadraticEigenOptions qo;
  eig::QuadraticEigenResult cx;
  double top = 0.0;
  for (;;) {
    qo.n_modes = n;
    cx = solver != nullptr ? solver->solve(pencil, speed, qo) : eig::solve_quadratic(pencil, qo);
    top = cx.eigenvalues.size() > 0 ? cx.eigenvalues.cwiseAbs().maxCoeff() : 0.0;
    // Enough: the band is covered, the system has no more modes, or nothing more to ask for.
    if (top >= want || cx.converged < n || n >= n_max) break;
    // Rotor and beam frequencies grow about as the square of the mode number, so the count
    // that reaches `want` is about n sqrt(want / top); 25 % more, at least n + 4, at most 2 n.
    const double guess = top > 0.0 ? 1.25 * n * std::sqrt(want / top) : 2.0 * n;
    const int next = static_cast<int>(std::ceil(std::min(guess, 2.0 * n)));
    n = std::min(std::max(next, n + 4), n_max);
  }
  if (n_modes_hint != nullptr) *n_modes_hint = n;
  out.band_covered = top >= want;
  out.covered = top;
  out.modes_checked = static_cast<int>(cx.eigenvalues.size());
  out.eigenvalues.assign(cx.eigenvalues.begin(), cx.eigenvalues.end());
  // FewerModes only says that the system has fewer modes than asked for (every one computed).
  out.solver_status = cx.status == Status::FewerModes ? Status::Ok : cx.status;
  out.solver_message = cx.status == Status::FewerModes ? "" : cx.message;
  judge(pencil, cx, top, out);
  return out;
}

StabilityAtSpeed check_stability(const fe::LinearSystem& system, double speed, double band_top,
                                 int* n_modes_hint) {
  return check_stability(system, speed, band_top, n_modes_hint, nullptr);
}

bool StabilityScan::all_stable() const {
  return std::all_of(stable.begin(), stable.end(), [](bool s) { return s; });
}

const StabilityAtSpeed* StabilityScan::worst() const {
  const StabilityAtSpeed* w = nullptr;
  for (const auto& s : solves)
    if (!s.stable && (w == nullptr || s.least_damped.damping_ratio < w->least_damped.damping_ratio))
      w = &s;
  return w;
}

namespace {

class Scanner {
 public:
  Scanner(const fe::LinearSystem& system, double band_top, StabilitySolver& solver)
      : system_(system), band_top_(band_top), solver_(solver) {}

  const StabilityAtSpeed& at(double speed) {
    auto it = solves_.find(speed);
    if (it == solves_.end())
      it = solves_.emplace(speed, check_stability(system_, speed, band_top_, &hint_, &solver_))
               .first;
    return it->second;
  }
  // Onset between speeds a < b of different verdicts: where the least damping ratio of the
  // elastic modes crosses zero (bisection on its sign to kOnsetTolerance relative, then linear
  // interpolation inside the bracket). The verdict itself has a tolerance; the onset has not.
  double onset(double a, double b) {
    double za = at(a).least_damped.damping_ratio, zb = at(b).least_damped.damping_ratio;
    if ((za < 0.0) == (zb < 0.0)) return 0.5 * (a + b);  // the tolerance band: no sign change
    while (b - a > kOnsetTolerance * b) {
      const double mid = 0.5 * (a + b);
      const double zm = at(mid).least_damped.damping_ratio;
      if ((zm < 0.0) == (za < 0.0)) {
        a = mid;
        za = zm;
      } else {
        b = mid;
        zb = zm;
      }
    }
    return a + (b - a) * za / (za - zb);
  }
  std::vector<StabilityAtSpeed> all() const {
    std::vector<StabilityAtSpeed> v;
    for (const auto& [speed, s] : solves_) v.push_back(s);
    return v;
  }

 private:
  const fe::LinearSystem& system_;
  double band_top_;
  StabilitySolver& solver_;
  int hint_ = kMinModes;
  std::map<double, StabilityAtSpeed> solves_;
};

}  // namespace

StabilityScan scan_stability(const fe::LinearSystem& system, const std::vector<double>& speeds,
                             double band_top, bool project, bool certify) {
  StabilityScan scan;
  scan.band_top = band_top;
  const std::size_t n = speeds.size();
  scan.stable.assign(n, true);
  scan.checked.assign(n, false);
  if (n == 0) return scan;
  if (certify) {
    const double tau = kGrowthTolerance * kBandMargin * band_top;
    scan.not_certified = energy_certificate(system, tau);
    if (scan.not_certified.empty()) {
      scan.certified = true;
      scan.certified_growth = tau;
      return scan;
    }
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return speeds[a] < speeds[b]; });
  auto speed_at = [&](std::size_t pos) { return speeds[order[pos]]; };

  StabilitySolver solver(system, project);
  Scanner scanner(system, band_top, solver);
  // Sampled positions of the sorted list: all, or kMaxSampledSpeeds spread evenly.
  std::vector<std::size_t> sampled;
  scan.subsampled = n > static_cast<std::size_t>(kMaxSampledSpeeds);
  if (!scan.subsampled) {
    for (std::size_t p = 0; p < n; ++p) sampled.push_back(p);
  } else {
    const auto k = static_cast<std::size_t>(kMaxSampledSpeeds);
    for (std::size_t j = 0; j < k; ++j) sampled.push_back((j * (n - 1) + (k - 1) / 2) / (k - 1));
    sampled.erase(std::unique(sampled.begin(), sampled.end()), sampled.end());
  }
  std::vector<bool> known(n, false);
  auto solve_pos = [&](std::size_t pos) {
    const bool s = scanner.at(speed_at(pos)).stable;
    known[pos] = true;
    scan.checked[order[pos]] = true;
    scan.stable[order[pos]] = s;
    return s;
  };
  for (std::size_t p : sampled) solve_pos(p);
  for (std::size_t j = 0; j + 1 < sampled.size(); ++j) {
    std::size_t lo = sampled[j], hi = sampled[j + 1];
    const bool s_lo = scan.stable[order[lo]];
    if (s_lo == scan.stable[order[hi]]) continue;
    while (hi - lo > 1) {  // the first listed speed with the other verdict
      const std::size_t mid = lo + (hi - lo) / 2;
      (solve_pos(mid) == s_lo ? lo : hi) = mid;
    }
    if (speed_at(hi) > speed_at(lo))
      scan.changes.push_back({scanner.onset(speed_at(lo), speed_at(hi)), !s_lo});
  }
  // The rest take the verdict of the checked speed before them (the same as after them).
  bool last = scan.stable[order[0]];
  for (std::size_t p = 0; p < n; ++p) {
    if (known[p])
      last = scan.stable[order[p]];
    else
      scan.stable[order[p]] = last;
  }
  scan.solves = scanner.all();
  scan.n_solves = static_cast<int>(scan.solves.size());
  scan.projected_solves = solver.projected();
  scan.projection_fallbacks = solver.fallbacks();
  scan.first_fallback = solver.first_fallback();
  scan.projection_given_up = solver.given_up();
  return scan;
}

std::string describe(const StabilityMode& m) {
  return fmt::format("mode {} ({:.6g} Hz, damping ratio {:.3g})", m.mode,
                     m.frequency / units::kTwoPi, m.damping_ratio);
}

namespace {

// Unstable speed ranges [rpm] from every solve (list speeds and bisection points alike).
std::vector<std::pair<double, double>> unstable_ranges(const StabilityScan& scan) {
  std::vector<std::pair<double, bool>> pts;  // sorted (speed, stable)
  for (const auto& s : scan.solves) pts.emplace_back(s.speed, s.stable);
  std::vector<std::pair<double, double>> ranges;
  bool open = false;
  double start = 0.0, prev = 0.0;
  for (const auto& [w, stable] : pts) {
    if (!stable && !open) {
      open = true;
      start = w;
    } else if (stable && open) {
      ranges.emplace_back(start, prev);
      open = false;
    }
    prev = w;
  }
  if (open) ranges.emplace_back(start, prev);
  for (auto& [a, b] : ranges) {
    a *= kRpmPerRadS;
    b *= kRpmPerRadS;
  }
  return ranges;
}

std::string ranges_text(const StabilityScan& scan) {
  std::string text;
  for (const auto& [a, b] : unstable_ranges(scan))
    text += (text.empty() ? "" : ", ") +
            (a == b ? fmt::format("{:.6g} rpm", a) : fmt::format("{:.6g} to {:.6g} rpm", a, b));
  return text;
}

}  // namespace

std::string unstable_message(const StabilityScan& scan) {
  const StabilityAtSpeed* w = scan.worst();
  if (w == nullptr) return "";
  // The mode that grows fastest (the least-damped elastic mode may be another, neutral one).
  const StabilityMode& grows = *std::max_element(
      w->unstable.begin(), w->unstable.end(), [](const StabilityMode& a, const StabilityMode& b) {
        return a.eigenvalue.real() < b.eigenvalue.real();
      });
  std::string others;
  if (w->unstable.size() > 1)
    others = fmt::format(" ({} growing modes at that speed)", w->unstable.size());
  const std::string where =
      scan.solves.size() == 1 ? "" : fmt::format(" at {:.6g} rpm", w->speed * kRpmPerRadS);
  return fmt::format(
      "unstable at {}: {} grows{}{}; the steady state computed is never reached (a growing "
      "vibration instead, limited only by nonlinearity): add damping or remove the destabilising "
      "terms (e.g. cross-coupled bearing coefficients kxy, kyx)",
      ranges_text(scan), describe(grows), where, others);
}

std::string stability_note(const StabilityScan& scan) {
  if (scan.certified)
    return fmt::format(
        "Stability: stable at all {} speed(s) by the energy certificate, without eigen-solves: M "
        "positive definite, K symmetric positive semi-definite (apart from free rigid-body "
        "motions), the gyroscopic matrix skew and the damping's symmetric part above -{:.3g} M, "
        "so the energy (q'^T M q' + q^T K q) / 2 can grow no faster than exp(2 tau t) and no mode "
        "faster than tau = {:.3g} 1/s ({:g} x {} x the highest excitation frequency: the growth "
        "the eigenvalue check ignores). Damping ratios are not computed here (campbell gives "
        "them).",
        scan.stable.size(), scan.certified_growth, scan.certified_growth, kGrowthTolerance,
        kBandMargin);
  int lo = 0, hi = 0;
  double least = 0.0, covered = 0.0, least_speed = 0.0;
  bool first = true, band = true;
  std::string solver;
  for (const auto& s : scan.solves) {
    lo = first ? s.modes_checked : std::min(lo, s.modes_checked);
    hi = std::max(hi, s.modes_checked);
    covered = first ? s.covered : std::min(covered, s.covered);
    if (first || s.least_damped.damping_ratio < least) {
      least = s.least_damped.damping_ratio;
      least_speed = s.speed;
    }
    band = band && s.band_covered;
    if (s.solver_status != Status::Ok && solver.empty())
      solver = fmt::format(" The eigen-solve at {:.6g} rpm reported {}: {}", s.speed * kRpmPerRadS,
                           to_string(s.solver_status), s.solver_message);
    first = false;
  }
  std::string text = fmt::format(
      "Stability: complex modes of M q'' + (C + W G) q' + K q = 0 at {} speed(s){} ({} "
      "eigen-solves), {} modes each, up to at least {:.6g} Hz (wanted: {} x the highest "
      "excitation frequency {:.6g} Hz{}); a mode is unstable when Re(lambda) > {:g} x the "
      "highest frequency checked and the mode moved onto the imaginary axis has a backward "
      "error above {:g} x its own (at least {:g}). "
      "Least damping ratio {:.3g} (at {:.6g} rpm).",
      scan.stable.size(),
      scan.subsampled
          ? fmt::format(" ({} of them sampled evenly, the others inferred between sampled "
                        "speeds of equal verdict; verdict changes located by bisection to {:g} "
                        "relative; a window narrower than the sample spacing can be missed)",
                        kMaxSampledSpeeds, kOnsetTolerance)
          : "",
      scan.n_solves, lo == hi ? fmt::format("{}", lo) : fmt::format("{} to {}", lo, hi),
      covered / units::kTwoPi, kBandMargin, scan.band_top / units::kTwoPi,
      band ? ""
           : fmt::format("; not reached everywhere: the check stops at the system's last mode "
                         "or at {} modes",
                         kMaxModes),
      kGrowthTolerance, kBackwardErrorFactor, kRoundoffBackwardError, least,
      least_speed * kRpmPerRadS);
  if (!scan.not_certified.empty())
    text += " (The energy certificate, which would need no eigen-solve, does not apply: " +
            scan.not_certified + ".)";
  if (scan.projected_solves + scan.projection_fallbacks > 0)
    text += fmt::format(
        " Solver: projection onto one basis of undamped modes for the scan, {} solve(s) "
        "certified; {} by the full solver{}{}.",
        scan.projected_solves, scan.projection_fallbacks,
        scan.first_fallback.empty() ? "" : " (first " + scan.first_fallback + ")",
        scan.projection_given_up ? "; the projection was given up after two failures in a row"
                                 : "");
  if (!scan.all_stable()) {
    text += fmt::format(" UNSTABLE at {}", ranges_text(scan));
    for (const auto& c : scan.changes)
      text += fmt::format("; {} above {:.6g} rpm", c.stable_above ? "stable" : "unstable",
                          c.speed * kRpmPerRadS);
    text += ".";
  }
  return text + solver;
}

}  // namespace geardyn::analyses
