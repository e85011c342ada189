// Benchmarks of the harmonic balance with the nonlinear elements of the element library
// (hbm/element_library.hpp, hbm/element_system.hpp, hbm/condensed.hpp), issue #18
// ("nonlinear-hbm", Performance). Figures are recorded in docs/performance.md ("Harmonic balance
// with nonlinear elements (`nonlinear_response`)").
//
// BM_NLvib3DofCurve: the chain of three oscillators with five nonlinear elements of the NLvib
// examples (Krack & Gross, "Harmonic Balance for Nonlinear Vibration Problems", Springer 2019;
// NLvib EXAMPLES/07_multiDOFoscillator_multipleNonlinearities): unit masses, springs k = 1 from
// mass 1 to ground, between neighbours and from mass 3 to ground, dampers 0.02 k on each spring;
// Jenkins elements (k = 20, slip force 1) from mass 1 to ground and between masses 1 and 2,
// cubic springs (k_3 = 1) from mass 2 to ground and between masses 2 and 3, a unilateral spring
// (k = 1, gap 0.25) from mass 3 to ground; the force cos(Omega t) on mass 2. H = 7 harmonics,
// 1024 time samples per period, Omega from 0.5 to 2 rad/s. The physical (dense) form
// ElementHarmonicBalance is traced by continue_in_frequency. Issue target: the whole range in
// under 1 s on one core, every point checked by its residual. Two step sizes: max_step 0.05 (the
// benchmark) and 0.005 (a fine trace, the reference for comparisons). The curve is not smooth
// (stick-slip and contact transitions put corners in it) and turns four times between Omega =
// 1.55 and 1.67 (a small loop and the hardening fold): max_step 0.2 and, by chance, 0.03 jump
// parts of it (max_chord_steps shows it). With GEARDYN_BENCH_NLVIB_CURVE=<prefix> each curve is
// written to <prefix>_<max_step / 1e-3>.txt (columns: Omega, Q1_rms, Q2_rms, Q3_rms with NLvib's
// amplitude sqrt(sum of the squared coefficients) / sqrt(2), ||R|| / residual_scale, Newton
// iterations) for the comparison with NLvib's curve.
//
// BM_Condensed100Dof: 100 Jenkins elements, each from one point of a structure to ground,
// condensed to their 100 coordinates (CondensedHarmonicBalance, LocalForce form), H = 7, traced
// for 10^4 continuation points. Issue target: 10^4 points in under 60 s. The structure is a
// synthetic but consistent linear one: a taut string of unit mass on [0, 1] with a little
// bending stiffness (w_m = m w_1 sqrt(1 + 0.01 (m^2 - 1)), w_1 = 2 pi 50 rad/s), mass-normalised
// shapes sqrt(2) sin(m pi s), modal damping 0.002..0.005, the contacts at s_p = (p + 1/2) / 100;
// 40 modes kept for every harmonic (the same real modes: H_n(w) = H(n w)) and the static
// flexibility of modes 41..400 as residual flexibility (dense, concentrated near the diagonal:
// it couples neighbouring contacts, so the Woodbury preconditioner is not exact). The force
// P cos(Omega t) acts at s = 0.23. Contacts: k = 3.2e-3 w_1^2 each (the stuck contacts raise
// the first mode by about 15 %), slip force 1 N; P is set so that the stuck structure's peak
// displacement at a contact is 40 slip limits F / k. The band 0.85 w_1 .. 2.5 w_1 holds the
// first two resonances; friction holds their peaks to about 6 and 7.6 slip limits.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/core/units.hpp"
#include "geardyn/hbm/condensed.hpp"
#include "geardyn/hbm/element_library.hpp"
#include "geardyn/hbm/element_system.hpp"
#include "geardyn/hbm/harmonic_balance.hpp"

namespace {

using namespace geardyn;
using cd = std::complex<double>;

// The largest distance between consecutive points in the continuation's scaled norm
// ||(X / x_scale, omega / omega_scale)||, in units of max_step: about 1 where the curve is
// followed; much larger where the corrector converged far from its predictor and a piece of the
// curve may have been jumped.
double max_chord_in_steps(const hbm::ContinuationResult& r, const hbm::ContinuationOptions& o) {
  double worst = 0.0;
  for (std::size_t i = 1; i < r.points.size(); ++i) {
    const auto& a = r.points[i - 1];
    const auto& b = r.points[i];
    const double dw = (b.omega - a.omega) / o.omega_scale;
    worst =
        std::max(worst, std::sqrt((b.X - a.X).squaredNorm() / (o.x_scale * o.x_scale) + dw * dw));
  }
  return worst / o.max_step;
}

// ---- NLvib example 07 -------------------------------------------------------------------------

constexpr int kNlvibHarmonics = 7, kNlvibSamples = 1024;
constexpr double kNlvibOmegaStart = 0.5, kNlvibOmegaEnd = 2.0;

// Row vector of a placement u = B q on the three masses.
Eigen::MatrixXd placement(double b1, double b2, double b3) {
  Eigen::MatrixXd B(1, 3);
  B << b1, b2, b3;
  return B;
}

// The chain's linear part (springs 1, dampers 0.02 on every spring) and the unit cosine force on
// mass 2, without the nonlinear elements.
hbm::ElementSystem nlvib_linear_chain() {
  hbm::ElementSystem s;
  s.M = Eigen::MatrixXd::Identity(3, 3);
  s.K.resize(3, 3);
  s.K << 2.0, -1.0, 0.0, -1.0, 2.0, -1.0, 0.0, -1.0, 2.0;
  s.C = 0.02 * s.K;
  s.excitation_harmonics = 1;
  s.excitation = Eigen::VectorXd::Zero(3 * 3);
  s.excitation[1 * 3 + hbm::HarmonicBasis::cos_index(1)] = 1.0;
  return s;
}

constexpr double kNlvibJenkinsStiffness = 20.0;

hbm::ElementSystem nlvib_system() {
  hbm::ElementSystem s = nlvib_linear_chain();
  const hbm::JenkinsElement jenkins{kNlvibJenkinsStiffness, 1.0};
  auto place = [&s](std::shared_ptr<const hbm::NonlinearElement> e, std::string name,
                    Eigen::MatrixXd B) {
    s.elements.push_back({std::move(e), std::move(name), std::move(B)});
  };
  place(std::make_shared<hbm::JenkinsElementHb>("1-ground", jenkins), "jenkins 1",
        placement(1, 0, 0));
  place(std::make_shared<hbm::JenkinsElementHb>("1-2", jenkins), "jenkins 2", placement(-1, 1, 0));
  place(std::make_shared<hbm::PolynomialSpring>("2-ground", std::map<int, double>{{3, 1.0}}),
        "cubic 3", placement(0, 1, 0));
  place(std::make_shared<hbm::PolynomialSpring>("2-3", std::map<int, double>{{3, 1.0}}), "cubic 4",
        placement(0, -1, 1));
  place(std::make_shared<hbm::UnilateralSpringHb>("3-ground", 1.0, 0.25), "unilateral 5",
        placement(0, 0, 1));
  return s;
}

// NLvib's start: the linear response with the Jenkins elements stuck (their stiffness added).
Eigen::VectorXd nlvib_initial_guess(const hbm::HarmonicBasis& basis) {
  hbm::ElementSystem stuck = nlvib_linear_chain();
  const Eigen::MatrixXd w1 = placement(1, 0, 0), w2 = placement(-1, 1, 0);
  stuck.K += kNlvibJenkinsStiffness * (w1.transpose() * w1 + w2.transpose() * w2);
  return hbm::ElementHarmonicBalance(std::move(stuck), basis).linear_response(kNlvibOmegaStart);
}

// NLvib's amplitude of DOF d: sqrt(sum of its squared coefficients) / sqrt(2).
double nlvib_rms(const Eigen::VectorXd& X, int d, int s) {
  return X.segment(d * s, s).norm() / std::sqrt(2.0);
}

void write_nlvib_curve(const std::string& path, const hbm::ElementHarmonicBalance& hb,
                       const hbm::ContinuationResult& r, const std::vector<double>& relative) {
  std::ofstream out(path);
  const int s = hb.basis().size();
  out << "# Omega Q1_rms Q2_rms Q3_rms relative_residual newton_iterations\n";
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    const auto& p = r.points[i];
    out << fmt::format("{:.12e} {:.12e} {:.12e} {:.12e} {:.3e} {}\n", p.omega, nlvib_rms(p.X, 0, s),
                       nlvib_rms(p.X, 1, s), nlvib_rms(p.X, 2, s), relative[i], p.iterations);
  }
}

// The system seen through its residual, counting the evaluations (with and without the
// Jacobian) and their CPU time: the rest of the continuation's time is its dense algebra.
class CountedSystem final : public hbm::HarmonicSystem {
 public:
  explicit CountedSystem(const hbm::HarmonicSystem& s) : s_(s) {}
  int size() const override { return s_.size(); }
  Eigen::VectorXd residual(const Eigen::VectorXd& X, double omega, Eigen::MatrixXd* J,
                           Eigen::VectorXd* dR) const override {
    const double started = hbm::CondensedStatistics::now();
    Eigen::VectorXd R = s_.residual(X, omega, J, dR);
    const double spent = hbm::CondensedStatistics::now() - started;
    if (J != nullptr) {
      ++linearized;
      linearized_seconds += spent;
    } else {
      ++plain;
      plain_seconds += spent;
    }
    return R;
  }
  double residual_scale(const Eigen::VectorXd& X, double omega) const override {
    return s_.residual_scale(X, omega);
  }

  mutable long linearized = 0, plain = 0;
  mutable double linearized_seconds = 0.0, plain_seconds = 0.0;

 private:
  const hbm::HarmonicSystem& s_;
};

// Args: max_step [1e-3].
void BM_NLvib3DofCurve(benchmark::State& state) {
  const hbm::HarmonicBasis basis(kNlvibHarmonics, kNlvibSamples);
  const hbm::ElementHarmonicBalance hb(nlvib_system(), basis);
  hbm::ContinuationOptions o;
  o.omega_start = kNlvibOmegaStart;
  o.omega_end = kNlvibOmegaEnd;
  // The norm of the coefficients peaks at about 1 (the cubic springs' fold near Omega = 1.6):
  // x_scale = 1 and omega_scale = the range weigh the amplitude and the frequency alike.
  o.x_scale = 1.0;
  o.omega_scale = kNlvibOmegaEnd - kNlvibOmegaStart;
  o.max_step = 1e-3 * static_cast<double>(state.range(0));
  o.step = std::min(0.01, o.max_step);
  o.min_step = 1e-8;
  o.tolerance = 1e-10;
  const Eigen::VectorXd X0 = nlvib_initial_guess(basis);
  hbm::ContinuationResult r;
  double seconds = 0.0;
  std::unique_ptr<CountedSystem> counted;
  for (auto _ : state) {
    counted = std::make_unique<CountedSystem>(hb);
    const double started = hbm::CondensedStatistics::now();
    r = hbm::continue_in_frequency(*counted, X0, o);
    seconds = hbm::CondensedStatistics::now() - started;
  }
  if (r.status != Status::Ok || r.points.empty() || r.points.back().omega < kNlvibOmegaEnd)
    state.SkipWithError(r.message.c_str());
  // Every point checked again by its residual, outside the timing.
  long newton = 0;
  double worst = 0.0;
  std::vector<double> relative;
  std::vector<double> peak(3, 0.0), peak_omega(3, 0.0);
  const int s = basis.size();
  for (const auto& p : r.points) {
    newton += p.iterations;
    relative.push_back(hb.residual(p.X, p.omega).norm() / hb.residual_scale(p.X, p.omega));
    worst = std::max(worst, relative.back());
    for (std::size_t d = 0; d < 3; ++d) {
      const double a = nlvib_rms(p.X, static_cast<int>(d), s);
      if (a > peak[d]) {
        peak[d] = a;
        peak_omega[d] = p.omega;
      }
    }
  }
  if (const char* prefix = std::getenv("GEARDYN_BENCH_NLVIB_CURVE"))
    write_nlvib_curve(fmt::format("{}_{}.txt", prefix, state.range(0)), hb, r, relative);
  const double points = static_cast<double>(r.points.size());
  state.SetLabel(fmt::format("peak Q_rms {:.6f} at {:.5f}, {:.6f} at {:.5f}, {:.6f} at {:.5f}",
                             peak[0], peak_omega[0], peak[1], peak_omega[1], peak[2],
                             peak_omega[2]));
  state.counters["points"] = points;
  state.counters["newton"] = static_cast<double>(newton);
  state.counters["max_rel_residual"] = worst;
  state.counters["omega_last"] = r.points.empty() ? 0.0 : r.points.back().omega;
  state.counters["max_chord_steps"] = max_chord_in_steps(r, o);
  state.counters["linearized"] = static_cast<double>(counted->linearized);
  state.counters["residuals"] = static_cast<double>(counted->plain);
  state.counters["cpu_s"] = seconds;
  state.counters["ms_per_point"] = 1e3 * seconds / points;
  state.counters["linearized_ms"] = 1e3 * counted->linearized_seconds / points;
  state.counters["residual_ms"] = 1e3 * counted->plain_seconds / points;
  state.counters["linalg_ms"] =
      1e3 * (seconds - counted->linearized_seconds - counted->plain_seconds) / points;
}
BENCHMARK(BM_NLvib3DofCurve)
    ->Arg(50)
    ->Arg(5)
    ->ArgName("max_step_1e3")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->MeasureProcessCPUTime();

// ---- 100 Jenkins contacts on a condensed structure ---------------------------------------------

constexpr int kContacts = 100, kKeptModes = 40, kStaticModes = 400, kHarmonics = 7;
constexpr double kFirstMode = geardyn::units::kTwoPi * 50.0;  // w_1 [rad/s]
constexpr double kForcePosition = 0.23;
constexpr double kContactStiffness = 3.2e-3 * kFirstMode * kFirstMode;  // [N/m]
constexpr double kSlipForce = 1.0;                                      // [N]

double mode_frequency(int m) { return kFirstMode * m * std::sqrt(1.0 + 0.01 * (m * m - 1.0)); }
double mode_shape(int m, double s) {
  return std::sqrt(2.0) * std::sin(geardyn::units::kPi * m * s);
}
double contact_position(int p) { return (p + 0.5) / kContacts; }

// The receptance of the string at the contacts (the same for every harmonic), for a unit force
// at kForcePosition on harmonic 1.
hbm::ModalReceptance string_receptance(int n) {
  hbm::ModalReceptance r;
  r.natural_frequency.resize(kKeptModes);
  r.damping_ratio.resize(kKeptModes);
  r.left.resize(kContacts, kKeptModes);
  for (int m = 1; m <= kKeptModes; ++m) {
    r.natural_frequency[m - 1] = mode_frequency(m);
    r.damping_ratio[m - 1] = 0.002 + 0.003 * (0.5 + 0.5 * std::sin(1.3 * m));
    for (int p = 0; p < kContacts; ++p) r.left(p, m - 1) = mode_shape(m, contact_position(p));
  }
  r.right = r.left;
  // Static flexibility of the modes left out: sum phi_m phi_m^T / w_m^2.
  Eigen::MatrixXd residual = Eigen::MatrixXd::Zero(kContacts, kContacts);
  Eigen::VectorXd residual_force = Eigen::VectorXd::Zero(kContacts);
  Eigen::VectorXd phi(kContacts);
  for (int m = kKeptModes + 1; m <= kStaticModes; ++m) {
    for (int p = 0; p < kContacts; ++p) phi[p] = mode_shape(m, contact_position(p));
    const double flexibility = 1.0 / (mode_frequency(m) * mode_frequency(m));
    residual += flexibility * phi * phi.transpose();
    residual_force += flexibility * mode_shape(m, kForcePosition) * phi;
  }
  r.residual = residual.cast<cd>();
  if (n == 1) {
    r.modal_excitation.resize(kKeptModes);
    for (int m = 1; m <= kKeptModes; ++m) r.modal_excitation[m - 1] = mode_shape(m, kForcePosition);
    r.residual_excitation = residual_force.cast<cd>();
  }
  return r;
}

struct StringCase {
  std::vector<hbm::ModalReceptance> harmonics;
  double omega_min = 0.0, omega_max = 0.0;
  double x_scale = 0.0;
};

// The receptances with the force scaled to the target displacement, the band and the scale.
StringCase string_case() {
  StringCase c;
  for (int n = 0; n <= kHarmonics; ++n) c.harmonics.push_back(string_receptance(n));
  c.omega_min = 0.85 * kFirstMode;
  c.omega_max = 2.5 * kFirstMode;
  // The stuck structure (every contact a spring k): (I + H k) x = x_lin over the band.
  const hbm::ModalReceptance& r1 = c.harmonics[1];
  double best = 0.0, best_norm = 0.0;
  for (double w = c.omega_min; w <= c.omega_max; w += 1e-3 * kFirstMode) {
    Eigen::MatrixXcd A = kContactStiffness * r1.receptance(w);
    A.diagonal().array() += 1.0;
    const Eigen::VectorXcd x = A.partialPivLu().solve(r1.linear_response(w));
    const double peak = x.cwiseAbs().maxCoeff();
    if (peak > best) {
      best = peak;
      best_norm = x.norm();
    }
  }
  const double scale = 40.0 * kSlipForce / kContactStiffness / best;
  c.harmonics[1].modal_excitation *= scale;
  c.harmonics[1].residual_excitation *= scale;
  // Friction holds the peak to a fraction of the stuck one: a scale of that order weighs the
  // amplitude and the frequency alike in the arc length.
  c.x_scale = 0.3 * scale * best_norm;
  return c;
}

// A Jenkins element from coordinate `coordinate` to ground, as an element-local force.
hbm::LocalForce jenkins_contact(int coordinate) {
  auto element = std::make_shared<const hbm::JenkinsElementHb>(
      fmt::format("contact {}", coordinate), hbm::JenkinsElement{kContactStiffness, kSlipForce});
  hbm::LocalForce f;
  f.coordinates = {coordinate};
  f.evaluate = [element](const hbm::HarmonicBasis& basis, const Eigen::VectorXd& w, double omega,
                         Eigen::VectorXd& force, Eigen::MatrixXd* J, Eigen::VectorXd* df) {
    element->harmonic_force(basis, w, omega, force, J, df);
  };
  return f;
}

// Args: max_points, max_step [1e-6]. The curve over the band is about 3.6 long in the scaled
// norm, so max_step 3.5e-4 needs a little over 10^4 points for it: max_points = 10^4 cuts it
// shortly before omega_max, after both resonances.
void BM_Condensed100Dof(benchmark::State& state) {
  const StringCase c = string_case();
  const hbm::HarmonicBasis basis(kHarmonics, hbm::default_time_samples(kHarmonics));
  std::vector<hbm::LocalForce> forces;
  for (int p = 0; p < kContacts; ++p) forces.push_back(jenkins_contact(p));
  hbm::CondensedHarmonicBalance hb(kContacts, basis, c.harmonics, std::move(forces));
  hbm::ContinuationOptions o;
  o.omega_start = c.omega_min;
  o.omega_end = c.omega_max;
  o.omega_scale = c.omega_max - c.omega_min;
  o.x_scale = c.x_scale;
  o.max_step = 1e-6 * static_cast<double>(state.range(1));
  o.step = o.max_step;
  o.min_step = 1e-10;
  o.tolerance = 1e-10;
  o.max_points = static_cast<int>(state.range(0));
  hbm::CondensedStatistics stats;
  hbm::ContinuationResult r;
  double seconds = 0.0;
  for (auto _ : state) {
    stats = {};
    hb.set_statistics(&stats);
    const double started = hbm::CondensedStatistics::now();
    r = hbm::continue_in_frequency(hb, Eigen::VectorXd::Zero(hb.size()), o);
    seconds = hbm::CondensedStatistics::now() - started;
    hb.set_statistics(nullptr);
  }
  // The curve ends at max_points before omega_end by design; any other end is a failure.
  if (r.status != Status::Ok && static_cast<int>(r.points.size()) < o.max_points)
    state.SkipWithError(r.message.c_str());
  long newton = 0;
  double worst = 0.0, peak = 0.0, peak_omega = 0.0;
  for (const auto& p : r.points) {
    newton += p.iterations;
    worst = std::max(worst, p.residual / hb.residual_scale(p.X, p.omega));
    const double a = hb.complex_harmonic(p.X, 1).cwiseAbs().maxCoeff();
    if (a > peak) {
      peak = a;
      peak_omega = p.omega;
    }
  }
  const double points = static_cast<double>(r.points.size());
  state.SetLabel(fmt::format("peak {:.3f} slip limits at {:.5f} w_1; last point {:.5f} w_1",
                             peak * kContactStiffness / kSlipForce, peak_omega / kFirstMode,
                             r.points.empty() ? 0.0 : r.points.back().omega / kFirstMode));
  state.counters["points"] = points;
  state.counters["newton"] = static_cast<double>(newton);
  state.counters["max_rel_residual"] = worst;
  state.counters["max_chord_steps"] = max_chord_in_steps(r, o);
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
BENCHMARK(BM_Condensed100Dof)
    ->Args({10000, 350})
    ->ArgNames({"max_points", "max_step_1e6"})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->MeasureProcessCPUTime();

}  // namespace
