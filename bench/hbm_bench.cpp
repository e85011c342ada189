// Benchmark of the condensed harmonic balance with friction contacts (hbm/condensed.hpp,
// hbm/friction_contact.hpp): the forced response of a damper ring over a band around one
// resonance, by pseudo-arc-length continuation (hbm/harmonic_balance.hpp). Issue
// "friction-hbm", section 8: 100 contact pairs, 5 harmonics, about 200 speed points in under
// 10 s on one core. Figures are recorded in docs/performance.md ("Harmonic balance with friction
// contacts").
//
// The problem is synthetic but shaped like a damper-ring model (damper/damper_ring.hpp): one
// sector of a cyclic gear (N = 40 sectors, excitation at nodal diameter h = 3, so harmonic n
// belongs to nodal diameter 3n) with 100 contact pairs along its groove, pair p at the position
// s_p = (p + 1/2) / 100 of the sector; coordinates 2p (normal approach v) and 2p + 1 (tangential
// slip u). Per harmonic n = 1..5, 40 modes with complex shapes, smooth in s_p (a standing wave
// of mode-dependent wavenumber times the travelling phase exp(2 pi i h_n s_p / N)), natural
// frequencies from 0.8 to 33 kHz and modal damping zeta = 0.002..0.005; three modes of harmonic 1
// (1.85, 2.0 and 2.16 kHz) lie in and next to the excitation band. Residual flexibility: a small
// dense Hermitian kernel (Gaussian in s_p - s_q, correlation length 0.04: it couples neighbouring
// pairs, so the preconditioner is not exact). The mean is held at the preloaded equilibrium
// (harmonic 0 empty, as in damper_ring.cpp). Contacts (2D, variable normal load): k_n = 5e7 N/m,
// k_t = 3e7 N/m, mu = 0.3, N_0 = 150 N. The excitation (harmonic 1 only) is scaled so that the
// stuck structure's peak tangential slip is 40 times the stick limit mu N_0 / k_t: across the
// band the contacts go from stick through stick-slip to gross slip with partial lift-off, and
// friction damps the peak.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <string>
#include <vector>

#include "geardyn/core/units.hpp"
#include "geardyn/hbm/condensed.hpp"
#include "geardyn/hbm/friction_contact.hpp"

namespace {

using namespace geardyn;
using cd = std::complex<double>;

constexpr int kPairs = 100, kHarmonics = 5, kModes = 40, kSectors = 40, kDiameter = 3;
constexpr double kNormalStiffness = 5e7, kTangentialStiffness = 3e7, kFriction = 0.3;
constexpr double kPreload = 150.0;

double position(int p) { return (p + 0.5) / kPairs; }

// Receptance of harmonic n (nodal diameter 3n) with unit excitation; harmonic 0 is empty.
hbm::ModalReceptance receptance(int n) {
  hbm::ModalReceptance r;
  if (n == 0) return r;
  const int nc = 2 * kPairs, h = kDiameter * n;
  r.natural_frequency.resize(kModes);
  r.damping_ratio.resize(kModes);
  r.left.resize(nc, kModes);
  for (int m = 0; m < kModes; ++m) {
    // Frequencies rise with the mode number and slightly with the nodal diameter.
    double f = 800.0 * std::pow(1.1, m) * (1.0 + 0.01 * h);
    if (n == 1 && m == 9) f = 1850.0;   // a neighbour just below the band
    if (n == 1 && m == 10) f = 2000.0;  // the excited mode
    if (n == 1 && m == 11) f = 2160.0;  // a neighbour just above the band
    r.natural_frequency[m] = geardyn::units::kTwoPi * f;
    r.damping_ratio[m] = 0.002 + 0.003 * (0.5 + 0.5 * std::sin(1.7 * m + n));
    const double k = 1.0 + (m % 6);  // half-waves along the groove
    for (int p = 0; p < kPairs; ++p) {
      const double s = position(p);
      const cd travelling = std::polar(1.0, geardyn::units::kTwoPi * h * s / kSectors);
      // Mass-normalised shapes [m / sqrt(kg)]: the tangential slip larger than the approach.
      const double normal = 0.03 * std::cos(geardyn::units::kPi * k * s + 0.4 * m);
      const double tangential = 0.1 * std::cos(geardyn::units::kPi * k * s + 0.9 * m + 0.3);
      r.left(2 * p, m) = normal * travelling;
      r.left(2 * p + 1, m) = tangential * travelling;
    }
  }
  r.right = r.left;
  // Residual flexibility: r_0 exp(-((s_p - s_q) / l)^2) times the travelling phase, per direction
  // (Hermitian positive semi-definite); r_0 k_n = 0.015.
  r.residual = Eigen::MatrixXcd::Zero(nc, nc);
  for (int p = 0; p < kPairs; ++p)
    for (int q = 0; q < kPairs; ++q) {
      const double ds = position(p) - position(q);
      const cd value = 3e-10 * std::exp(-(ds / 0.04) * (ds / 0.04)) *
                       std::polar(1.0, geardyn::units::kTwoPi * h * ds / kSectors);
      r.residual(2 * p, 2 * q) = 0.5 * value;
      r.residual(2 * p + 1, 2 * q + 1) = value;
    }
  if (n == 1) {
    r.modal_excitation.resize(kModes);
    for (int m = 0; m < kModes; ++m)
      r.modal_excitation[m] = std::polar(0.1 * (1.0 + 0.5 * std::cos(m)), 0.3 * m);
  }
  return r;
}

hbm::FrictionContact contact() {
  hbm::FrictionContact c;
  c.tangential_directions = 1;
  c.normal_stiffness = kNormalStiffness;
  c.tangential_stiffness = kTangentialStiffness;
  c.friction_coefficient = kFriction;
  c.normal_preload = kPreload;
  return c;
}

struct RingCase {
  std::vector<hbm::ModalReceptance> harmonics;
  double omega_min = 0.0, omega_max = 0.0;
  double x_scale = 0.0;
};

// The receptances with the excitation scaled to the target slip, and the band: from 4 % below
// the free resonance to 4 % above the stuck one (the contacts as springs k_n, k_t).
RingCase ring_case() {
  RingCase c;
  for (int n = 0; n <= kHarmonics; ++n) c.harmonics.push_back(receptance(n));
  const hbm::ModalReceptance& r1 = c.harmonics[1];
  const int nc = 2 * kPairs;
  Eigen::VectorXcd k(nc);
  for (int i = 0; i < nc; ++i) k[i] = i % 2 == 0 ? kNormalStiffness : kTangentialStiffness;
  double best = 0.0, best_omega = 0.0, best_norm = 0.0;
  for (double f = 1950.0; f <= 2250.0; f += 1.0) {
    const double w = geardyn::units::kTwoPi * f;
    Eigen::MatrixXcd A = r1.receptance(w) * k.asDiagonal();
    A.diagonal().array() += 1.0;
    const Eigen::VectorXcd x = A.partialPivLu().solve(r1.linear_response(w));
    double slip = 0.0;
    for (int p = 0; p < kPairs; ++p) slip = std::max(slip, std::abs(x[2 * p + 1]));
    if (slip > best) {
      best = slip;
      best_omega = w;
      best_norm = x.norm();
    }
  }
  const double scale = 40.0 * kFriction * kPreload / kTangentialStiffness / best;
  c.harmonics[1].modal_excitation *= scale;
  c.omega_min = 0.96 * geardyn::units::kTwoPi * 2000.0;
  c.omega_max = 1.04 * best_omega;
  // The damped peak is a fraction of the stuck one: a scale of that order weighs the amplitude
  // and the frequency alike in the arc length.
  c.x_scale = 0.3 * scale * best_norm;
  return c;
}

// How the curve is computed (the first argument of the benchmarks).
enum Variant {
  kGeneral = 0,  // NonlinearForce (friction_contact_force): dense N x N Jacobians, LU per solve
  kDenseLu = 1,  // LocalForce residual and Jacobian, but an LU of the dense J per solve
  kFast = 2,     // LocalForce: matrix-free J, GMRES with the Woodbury preconditioner
};

hbm::CondensedHarmonicBalance ring_system(const RingCase& c, bool local) {
  const hbm::HarmonicBasis basis(kHarmonics, hbm::default_time_samples(kHarmonics));
  if (local) {
    std::vector<hbm::LocalForce> forces;
    for (int p = 0; p < kPairs; ++p)
      forces.push_back(hbm::local_friction_contact({2 * p, 2 * p + 1}, contact()));
    return hbm::CondensedHarmonicBalance(2 * kPairs, basis, c.harmonics, std::move(forces));
  }
  std::vector<hbm::NonlinearForce> forces;
  for (int p = 0; p < kPairs; ++p)
    forces.push_back(hbm::friction_contact_force({2 * p, 2 * p + 1}, contact()));
  return hbm::CondensedHarmonicBalance(2 * kPairs, basis, c.harmonics, std::move(forces));
}

// The system seen only through HarmonicSystem: continue_in_frequency then takes the dense path
// (the Jacobian of residual(), an LU per Newton iteration and per tangent), as before the
// matrix-free algebra existed.
class DenseView final : public hbm::HarmonicSystem {
 public:
  explicit DenseView(const hbm::HarmonicSystem& s) : s_(s) {}
  int size() const override { return s_.size(); }
  Eigen::VectorXd residual(const Eigen::VectorXd& X, double omega, Eigen::MatrixXd* J,
                           Eigen::VectorXd* dR) const override {
    return s_.residual(X, omega, J, dR);
  }
  double residual_scale(const Eigen::VectorXd& X, double omega) const override {
    return s_.residual_scale(X, omega);
  }

 private:
  const hbm::HarmonicSystem& s_;
};

// Largest harmonic-1 tangential amplitude over the pairs at X.
double peak_slip(const hbm::CondensedHarmonicBalance& hb, const Eigen::VectorXd& X) {
  const Eigen::VectorXcd z = hb.complex_harmonic(X, 1);
  double peak = 0.0;
  for (int p = 0; p < kPairs; ++p) peak = std::max(peak, std::abs(z[2 * p + 1]));
  return peak;
}

// Args: variant (Variant), max_points (0: the whole band).
void BM_FrictionRingCurve(benchmark::State& state) {
  const RingCase c = ring_case();
  const auto variant = static_cast<Variant>(state.range(0));
  hbm::CondensedHarmonicBalance hb = ring_system(c, variant != kGeneral);
  const DenseView dense(hb);
  const hbm::HarmonicSystem& traced =
      variant == kDenseLu ? static_cast<const hbm::HarmonicSystem&>(dense) : hb;
  hbm::ContinuationOptions o;
  o.omega_start = c.omega_min;
  o.omega_end = c.omega_max;
  o.omega_scale = c.omega_max - c.omega_min;
  o.x_scale = c.x_scale;
  o.step = 0.01;
  o.max_step = 0.03;
  o.min_step = 1e-8;
  o.tolerance = 1e-10;
  if (state.range(1) > 0) o.max_points = static_cast<int>(state.range(1));
  hbm::CondensedStatistics stats;
  hbm::ContinuationResult r;
  double seconds = 0.0;
  for (auto _ : state) {
    stats = {};
    hb.set_statistics(&stats);
    const double started = hbm::CondensedStatistics::now();
    r = hbm::continue_in_frequency(traced, Eigen::VectorXd::Zero(hb.size()), o);
    seconds = hbm::CondensedStatistics::now() - started;
    hb.set_statistics(nullptr);
  }
  const bool whole = state.range(1) == 0;
  if (whole && r.status != Status::Ok) state.SkipWithError(r.message.c_str());
  // Through DenseView the continuation's algebra is not counted: it is the rest of the time
  // (forming the dense J from the element blocks included).
  if (variant == kDenseLu)
    stats.linear_algebra_seconds = seconds - stats.element_seconds - stats.receptance_seconds;
  long newton = 0;
  double peak = 0.0, peak_omega = 0.0;
  for (const auto& p : r.points) {
    newton += p.iterations;
    const double a = peak_slip(hb, p.X);
    if (a > peak) {
      peak = a;
      peak_omega = p.omega;
    }
  }
  const double points = static_cast<double>(r.points.size());
  state.SetLabel(
      fmt::format("peak slip {:.10e} m at {:.6f} Hz", peak, peak_omega / geardyn::units::kTwoPi));
  state.counters["points"] = points;
  state.counters["newton"] = static_cast<double>(newton);
  state.counters["linearized"] = static_cast<double>(stats.linearizations);
  state.counters["residuals"] = static_cast<double>(stats.residual_evaluations);
  state.counters["solves"] = static_cast<double>(stats.linear_solves);
  state.counters["krylov"] = static_cast<double>(stats.krylov_iterations);
  state.counters["prec_builds"] = static_cast<double>(stats.preconditioner_builds);
  state.counters["dense_lu"] = static_cast<double>(stats.dense_factorizations);
  state.counters["cpu_s"] = seconds;
  state.counters["ms_per_point"] = 1e3 * seconds / points;
  state.counters["receptance_ms"] = 1e3 * stats.receptance_seconds / points;
  state.counters["aft_ms"] = 1e3 * stats.element_seconds / points;
  state.counters["linalg_ms"] = 1e3 * stats.linear_algebra_seconds / points;
}
BENCHMARK(BM_FrictionRingCurve)
    ->Args({kFast, 0})
    ->Args({kDenseLu, 6})
    ->Args({kGeneral, 3})
    ->ArgNames({"variant", "max_points"})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->MeasureProcessCPUTime();

// The slower variants over the whole curve (the reference for the fast one's answer: the same
// points, peak to 1e-8) take about 6 (dense LU) and 30 (general path) minutes: registered only
// when GEARDYN_BENCH_HBM_REFERENCE is set.
[[maybe_unused]] const bool kReference = [] {
  if (std::getenv("GEARDYN_BENCH_HBM_REFERENCE"))
    benchmark::RegisterBenchmark("BM_FrictionRingCurveReference", BM_FrictionRingCurve)
        ->Args({kDenseLu, 0})
        ->Args({kGeneral, 0})
        ->ArgNames({"variant", "max_points"})
        ->Unit(benchmark::kSecond)
        ->Iterations(1)
        ->MeasureProcessCPUTime();
  return true;
}();

}  // namespace
