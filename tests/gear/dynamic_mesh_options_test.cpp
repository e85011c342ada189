// Dynamic mesh model options (docs/theory.md §13): the damper on the elastic deflection of the
// teeth, c (x' - e_g'), instead of on the DTE, c x', and an external harmonic force on the mesh
// coordinate. Validated against closed-form steady states of the linear oscillator with constant
// mesh stiffness, against the exact steady state for the discretised unloaded TE (Fourier series
// with its aliases), and the monodromy (saltation at contact changes included) against finite
// differences of the Poincaré map.
//
//   m_e x'' + c (x' - s e_g') + k (x - e_g) = F_s + F_a cos(r 2 pi f_m t + phi),
//   s = 0 (damping_on = dte) or 1 (elastic deflection; Kahraman & Singh 1990, Ozguven & Houser
//   1988), so with e_g = e_hat cos(w t) the steady state is (Den Hartog / any vibration text)
//   X / e_hat = (k + s i c w) / (k - m w^2 + i c w),
//   and for the external force alone |X| = F_a / sqrt((k - m W^2)^2 + (c W)^2), W = r 2 pi f_m,
//   lagging the force by atan2(c W, k - m W^2).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/gear/dynamic_mesh.hpp"
#include "geardyn/gear/ste.hpp"

namespace geardyn::gear {
namespace {

constexpr double kPi = std::numbers::pi;
using cplx = std::complex<double>;

// The reference oscillator of dynamic_mesh_test.cpp: m_e = 1 kg, F_s = 1000 N, k = 2.72e8 N/m
// (f_n = 2624.85 Hz, static deflection 3.68 um).
constexpr double kForce = 1000.0, kStiffness = 2.72e8, kMass = 1.0;

double sinc(double x) { return x == 0.0 ? 1.0 : std::sin(kPi * x) / (kPi * x); }

// Constant stiffness k with unloaded TE samples e_g,j = e_hat cos(2 pi j / n): e = e_g + F_s / k.
SteCurve harmonic_te(int n, double e_hat, SteInterpolation interpolation) {
  std::vector<double> e, g;
  for (int j = 0; j < n; ++j) {
    g.push_back(e_hat * std::cos(2.0 * kPi * j / n));
    e.push_back(g.back() + kForce / kStiffness);
  }
  return SteCurve::from_samples(e, interpolation, g);
}

DynamicMeshOptions linear_options(double zeta, MeshDamping damping) {
  DynamicMeshOptions o;
  o.equivalent_mass_kg = kMass;
  o.static_force_n = kForce;
  o.damping_ratio = zeta;
  o.contact_loss = false;
  o.damping_on = damping;
  return o;
}

// The receptance of the TE input at angular frequency w: (k + s i c w) / (k - m w^2 + i c w).
cplx te_gain(double w, double c, bool elastic) {
  return cplx(kStiffness, elastic ? c * w : 0.0) / cplx(kStiffness - kMass * w * w, c * w);
}

// Exact periodic steady state x(t) for a periodic input with Fourier coefficients coef(n)
// (n >= 1; only n = +-1 mod n_samples are non-zero for an input built from one harmonic):
// x = F_s / k + 2 Re sum_n coef(n) gain(n w) e^{i n w t}, summed over the aliases up to
// 4000 n_samples (the terms fall as n^-3: the truncation is < 1e-13 of e_hat).
template <class Coef>
double series_response(double t, double w, int n_samples, double c, bool elastic, Coef coef) {
  double x = kForce / kStiffness;
  for (int j = 0; j < 4000; ++j) {
    for (const int n : {j * n_samples + 1, (j + 1) * n_samples - 1}) {
      const double nw = n * w;
      x += 2.0 * (coef(n) * te_gain(nw, c, elastic) * std::polar(1.0, nw * t)).real();
    }
  }
  return x;
}

// (a) Damping on the elastic deflection follows the linearly interpolated e_g exactly: the
// steady state equals the Fourier series of the response to the piecewise-linear interpolant of
// e_hat cos(w t) on 64 samples (coefficients e_hat / 2 sinc^2(n / 64) at n = +-1 mod 64; the hat
// function's transform) to 1e-8 e_hat: the steady-state tolerance (1e-9 of the static deflection
// 3.68 e_hat, times 1 / (1 - |mu|) < 2) and rounding. A finite-difference or mean-value treatment
// of e_g' would be off by O((pi / 128)^2) ~ 6e-4 here.
TEST(DynamicMeshOptions, ElasticDeflectionDampingIsExactForLinearTe) {
  const int n = 64;
  const double e_hat = 1e-6, zeta = 0.05;
  const DynamicMesh mesh(harmonic_te(n, e_hat, SteInterpolation::Linear),
                         linear_options(zeta, MeshDamping::ElasticDeflection));
  const double c = mesh.damping_n_s_m();
  for (const double ratio : {0.5, 0.9, 1.0, 1.3}) {
    const double fm = ratio * mesh.natural_frequency_hz();
    const MeshResponse r = mesh.solve(fm);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    const double w = 2.0 * kPi * fm;
    double worst = 0.0;
    for (std::size_t i = 0; i < r.time_s.size(); ++i) {
      const double ref = series_response(r.time_s[i], w, n, c, true, [&](int q) {
        return cplx(0.5 * e_hat * sinc(static_cast<double>(q) / n) *
                    sinc(static_cast<double>(q) / n));
      });
      worst = std::max(worst, std::abs(r.dte_m[i] - ref));
    }
    std::printf("elastic damping, f_m / f_n = %.2f: largest error %.3e m (e_hat %.1e m)\n", ratio,
                worst, e_hat);
    EXPECT_LT(worst, 1e-8 * e_hat) << "f_m / f_n = " << ratio;
  }
}

// (a) Damping on the DTE keeps today's treatment of e_g: its mean over each interval. With one
// interval per sample (64 samples, 128 intervals minimum -> 128 samples, one interval each) the
// input is the held sequence of interval means g_j = (u_j + u_{j+1}) / 2 of the samples u_j,
// with Fourier coefficients D[n mod N] sinc(n / N) e^{-i pi n / N}, D the DFT of g_j / N: the
// exact steady state, again to 1e-8 e_hat (same budget as above).
TEST(DynamicMeshOptions, DteDampingMatchesTheHeldInterpolant) {
  const int n = 128;
  const double e_hat = 1e-6, zeta = 0.05;
  const DynamicMesh mesh(harmonic_te(n, e_hat, SteInterpolation::Linear),
                         linear_options(zeta, MeshDamping::Dte));
  const double c = mesh.damping_n_s_m();
  cplx d_plus = 0.0, d_minus = 0.0;  // DFT of the interval means at k = 1 and k = n - 1
  for (int j = 0; j < n; ++j) {
    const double mean =
        0.5 * e_hat * (std::cos(2.0 * kPi * j / n) + std::cos(2.0 * kPi * (j + 1) / n));
    d_plus += mean * std::polar(1.0, -2.0 * kPi * j / n) / static_cast<double>(n);
    d_minus += mean * std::polar(1.0, 2.0 * kPi * j / n) / static_cast<double>(n);
  }
  for (const double ratio : {0.5, 1.0, 1.3}) {
    const double fm = ratio * mesh.natural_frequency_hz();
    const MeshResponse r = mesh.solve(fm);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    ASSERT_EQ(r.points_per_period, n);
    const double w = 2.0 * kPi * fm;
    double worst = 0.0;
    for (std::size_t i = 0; i < r.time_s.size(); ++i) {
      const double ref = series_response(r.time_s[i], w, n, c, false, [&](int q) {
        const double u = static_cast<double>(q) / n;
        return (q % n == 1 ? d_plus : d_minus) * sinc(u) * std::polar(1.0, -kPi * u);
      });
      worst = std::max(worst, std::abs(r.dte_m[i] - ref));
    }
    std::printf("DTE damping, f_m / f_n = %.2f: largest error %.3e m\n", ratio, worst);
    EXPECT_LT(worst, 1e-8 * e_hat) << "f_m / f_n = " << ratio;
  }
}

// (a) Against the continuous closed forms X / e_hat = (k + s i c w) / (k - m w^2 + i c w) on
// 2048 samples: the first harmonic of the response (DFT of the samples over one period) differs
// from the continuous one by the interpolation, |sinc^2(1 / N) - 1| = (pi / N)^2 / 3 = 7.8e-7
// (elastic, linear e_g) and, with the interval means, another (pi / N)^2 / 6 (DTE), plus aliases
// of relative size < (1 / N)^2: tolerance 3 (pi / N)^2 = 7e-6. The two options differ by
// |i c w / k| ~ 0.1 near resonance: far above the tolerance.
TEST(DynamicMeshOptions, ClosedFormTransferOfTheTransmissionError) {
  const int n = 2048;
  const double e_hat = 1e-6, zeta = 0.05;
  for (const MeshDamping damping : {MeshDamping::Dte, MeshDamping::ElasticDeflection}) {
    const bool elastic = damping == MeshDamping::ElasticDeflection;
    const DynamicMesh mesh(harmonic_te(n, e_hat, SteInterpolation::Linear),
                           linear_options(zeta, damping));
    for (const double ratio : {0.6, 1.0, 1.5}) {
      const double fm = ratio * mesh.natural_frequency_hz();
      const MeshResponse r = mesh.solve(fm);
      ASSERT_EQ(r.status, Status::Ok) << r.message;
      const std::size_t m = r.time_s.size();
      cplx x1 = 0.0;
      for (std::size_t i = 0; i < m; ++i)
        x1 += 2.0 / static_cast<double>(m) * r.dte_m[i] *
              std::polar(1.0, -2.0 * kPi * static_cast<double>(i) / static_cast<double>(m));
      const cplx expected = e_hat * te_gain(2.0 * kPi * fm, mesh.damping_n_s_m(), elastic);
      std::printf(
          "%s damping, f_m / f_n = %.1f: X / e_hat = %.9f %+.9fi, closed form %.9f %+.9fi\n",
          elastic ? "elastic" : "DTE", ratio, x1.real() / e_hat, x1.imag() / e_hat,
          expected.real() / e_hat, expected.imag() / e_hat);
      EXPECT_LT(std::abs(x1 - expected), 3.0 * (kPi / n) * (kPi / n) * std::abs(expected))
          << (elastic ? "elastic" : "DTE") << " f_m / f_n = " << ratio;
    }
  }
}

// (b) The external harmonic force alone (constant k, no TE variation): the response is
// F_s / k + Re(F_a / (k - m W^2 + i c W) e^{i (W t + phi)}) exactly, since the solver adds that
// particular solution in closed form. Amplitude and phase from the DFT of the samples at order r
// (exact for one harmonic sampled above its Nyquist rate) to 1e-8 relative; the samples to
// 1e-8 of the amplitude (steady-state tolerance, as above). Both damping options, which coincide
// here (e_g constant, always in contact), and with contact loss allowed (F_a < F_s: the teeth
// stay in contact).
TEST(DynamicMeshOptions, ExternalHarmonicForceMatchesTheClosedForm) {
  const double force_amplitude = 200.0, phase = 0.5236, zeta = 0.04;
  for (const MeshDamping damping : {MeshDamping::Dte, MeshDamping::ElasticDeflection}) {
    for (const bool contact_loss : {false, true}) {
      for (const int order : {1, 2, 3}) {
        DynamicMeshOptions o = linear_options(zeta, damping);
        o.contact_loss = contact_loss;
        o.force_amplitude_n = force_amplitude;
        o.force_order = order;
        o.force_phase_rad = phase;
        const DynamicMesh mesh(harmonic_te(8, 0.0, SteInterpolation::Hold), o);
        const double c = mesh.damping_n_s_m();
        const double fm = 0.4 * mesh.natural_frequency_hz();
        const MeshResponse r = mesh.solve(fm);
        ASSERT_EQ(r.status, Status::Ok) << r.message;
        const double big_w = order * 2.0 * kPi * fm;
        const cplx gain = force_amplitude / cplx(kStiffness - kMass * big_w * big_w, c * big_w);
        const std::size_t m = r.time_s.size();
        cplx xr = 0.0;
        double worst = 0.0;
        for (std::size_t i = 0; i < m; ++i) {
          const double t = r.time_s[i];
          xr += 2.0 / static_cast<double>(m) * r.dte_m[i] * std::polar(1.0, -big_w * t);
          const double ref =
              kForce / kStiffness + (gain * std::polar(1.0, big_w * t + phase)).real();
          worst = std::max(worst, std::abs(r.dte_m[i] - ref));
        }
        const double amplitude =
            force_amplitude / std::hypot(kStiffness - kMass * big_w * big_w, c * big_w);
        const double lag = std::atan2(c * big_w, kStiffness - kMass * big_w * big_w);
        EXPECT_NEAR(std::abs(xr), amplitude, 1e-8 * amplitude) << "order " << order;
        EXPECT_NEAR(std::arg(xr), phase - lag, 1e-8) << "order " << order;
        EXPECT_LT(worst, 1e-8 * amplitude) << "order " << order;
        EXPECT_EQ(r.contact_loss_fraction, 0.0);
        // The mean mesh force is still F_s (the harmonic force averages out over whole orders).
        EXPECT_NEAR(r.force_mean_n, kForce, 1e-9 * kForce);
      }
    }
  }
}

// The two-level stiffness of the reference case (dynamic_mesh_test.cpp) as a linearly
// interpolated curve with a varying unloaded TE g_j = g_hat sin(2 pi j / 10).
SteCurve step_like_ste(double g_hat) {
  std::vector<double> e, g;
  for (int j = 0; j < 10; ++j) {
    g.push_back(g_hat * std::sin(2.0 * kPi * j / 10.0));
    e.push_back(g.back() + kForce / (j < 6 ? 3.2e8 : 2.0e8));
  }
  return SteCurve::from_samples(e, SteInterpolation::Linear, g);
}

// (c) The monodromy returned with the Poincaré map is its exact Jacobian also where the teeth
// separate: with damping on the elastic deflection the damper force jumps at each contact change,
// and the saltation matrix [[1, 0], [-/+ c / m, 1]] (Aizerman & Gantmacher 1958; see M. di
// Bernardo et al., "Piecewise-smooth dynamical systems", Springer 2008, sec. 2.5) must enter the
// product. Checked against central differences of the map with steps 1e-5 of the state scales:
// truncation O(step^2) ~ 1e-10 and rounding ~1e-16 / 1e-5 ~ 1e-11 relative, so 1e-6 relative to
// the largest entry. Without the saltation the entries differ by O(c / m * period) ~ 0.1.
TEST(DynamicMeshOptions, MonodromyIncludesSaltationAtContactLoss) {
  for (const MeshDamping damping : {MeshDamping::Dte, MeshDamping::ElasticDeflection}) {
    DynamicMeshOptions o = linear_options(0.05, damping);
    o.contact_loss = true;
    const DynamicMesh mesh(step_like_ste(0.5e-6), o);
    const double fm = 0.95 * mesh.natural_frequency_hz();
    const MeshResponse r = mesh.solve(fm);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    ASSERT_GT(r.contact_loss_fraction, 0.05);
    ASSERT_EQ(r.period_cycles, 1);
    std::array<double, 4> jac{};
    const MeshState end = mesh.poincare_map(fm, r.start_state, &jac);
    const double sx = mesh.static_deflection_m();
    const double sv = sx * 2.0 * kPi * mesh.natural_frequency_hz();
    EXPECT_NEAR(end.x_m, r.start_state.x_m, 1e-8 * sx);
    std::array<double, 4> fd{};
    for (int col = 0; col < 2; ++col) {
      const double step = 1e-5 * (col == 0 ? sx : sv);
      MeshState plus = r.start_state, minus = r.start_state;
      (col == 0 ? plus.x_m : plus.v_m_s) += step;
      (col == 0 ? minus.x_m : minus.v_m_s) -= step;
      const MeshState ep = mesh.poincare_map(fm, plus), em = mesh.poincare_map(fm, minus);
      fd[static_cast<std::size_t>(col)] = (ep.x_m - em.x_m) / (2.0 * step);
      fd[static_cast<std::size_t>(2 + col)] = (ep.v_m_s - em.v_m_s) / (2.0 * step);
    }
    // Balanced entries: d x / d x, (d x / d v) w, (d v / d x) / w, d v / d v.
    const double w = sv / sx;
    const std::array<double, 4> scale = {1.0, w, 1.0 / w, 1.0};
    double largest = 0.0, worst = 0.0;
    for (std::size_t q = 0; q < 4; ++q) {
      largest = std::max(largest, std::abs(jac[q] * scale[q]));
      worst = std::max(worst, std::abs((jac[q] - fd[q]) * scale[q]));
    }
    std::printf("%s damping, contact loss %.3f: monodromy vs finite differences %.3e of %.3e\n",
                damping == MeshDamping::Dte ? "DTE" : "elastic", r.contact_loss_fraction, worst,
                largest);
    EXPECT_LT(worst, 1e-6 * largest);
    // The reported Floquet multiplier is the spectral radius of this monodromy.
    const double tr = jac[0] + jac[3], det = jac[0] * jac[3] - jac[1] * jac[2];
    const cplx disc = std::sqrt(cplx(0.25 * tr * tr - det));
    const double rho = std::max(std::abs(0.5 * tr + disc), std::abs(0.5 * tr - disc));
    EXPECT_NEAR(r.floquet_multiplier, rho, 1e-9);
  }
}

// (c) In contact the homogeneous equation is the same for both options (damping c on x' either
// way), so the Floquet multipliers, and with them the parametric-instability verdict, do not
// depend on the damping option, on e_g or on the external force: at f_m = 2 f_n the reference
// case is unstable at zeta = 0.05 and stable at 0.1 (dynamic_mesh_test.cpp), whatever the
// options. The multipliers agree to rounding (1e-12).
TEST(DynamicMeshOptions, ParametricInstabilityVerdictIsIndependentOfTheOptions) {
  for (const double zeta : {0.05, 0.1}) {
    double reference = -1.0;
    Status reference_status = Status::Failed;
    for (const MeshDamping damping : {MeshDamping::Dte, MeshDamping::ElasticDeflection}) {
      for (const double force_amplitude : {0.0, 300.0}) {
        DynamicMeshOptions o = linear_options(zeta, damping);
        o.force_amplitude_n = force_amplitude;
        o.force_order = 2;
        const DynamicMesh mesh(step_like_ste(0.3e-6), o);
        const double fm = 2.0 * mesh.natural_frequency_hz();
        const MeshResponse r = mesh.solve(fm);
        std::array<double, 4> jac{};
        mesh.poincare_map(fm, mesh.static_state(), &jac);
        const double tr = jac[0] + jac[3], det = jac[0] * jac[3] - jac[1] * jac[2];
        const cplx disc = std::sqrt(cplx(0.25 * tr * tr - det));
        const double rho = std::max(std::abs(0.5 * tr + disc), std::abs(0.5 * tr - disc));
        if (reference < 0.0) {
          reference = rho;
          reference_status = r.status;
        }
        EXPECT_NEAR(rho, reference, 1e-12 * reference);
        EXPECT_EQ(r.status, reference_status);
        EXPECT_EQ(r.status, zeta < 0.075 ? Status::Diverged : Status::Ok) << r.message;
        EXPECT_EQ(rho > 1.0, zeta < 0.075) << "rho = " << rho;
      }
    }
  }
}

// (c) Inside the instability region (zeta = 0.05, f_m = 2 f_n) contact loss bounds the
// response on a period-2 orbit; the detector still finds it with the damper on the elastic
// deflection (no damping in free flight), the orbit closes after two cycles and is stable.
TEST(DynamicMeshOptions, SubharmonicDetectionWithElasticDeflectionDamping) {
  for (const MeshDamping damping : {MeshDamping::Dte, MeshDamping::ElasticDeflection}) {
    DynamicMeshOptions o = linear_options(0.05, damping);
    o.contact_loss = true;
    const DynamicMesh mesh(step_like_ste(0.0), o);
    const double fm = 2.0 * mesh.natural_frequency_hz();
    const MeshResponse r = mesh.solve(fm);
    std::printf("%s damping, f_m = 2 f_n: %s, period %d, loss %.3f, DF %.4f, |mu| %.4f\n",
                damping == MeshDamping::Dte ? "DTE" : "elastic",
                std::string(to_string(r.status)).c_str(), r.period_cycles, r.contact_loss_fraction,
                r.dynamic_factor, r.floquet_multiplier);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    EXPECT_EQ(r.period_cycles, 2);
    EXPECT_LT(r.floquet_multiplier, 1.0);
    MeshState s = r.start_state;
    for (int cycle = 0; cycle < 2; ++cycle) s = mesh.poincare_map(fm, s);
    EXPECT_NEAR(s.x_m, r.start_state.x_m, 1e-8 * mesh.static_deflection_m());
    EXPECT_NEAR(r.force_mean_n, kForce, 1e-8 * kForce);
  }
}

TEST(DynamicMeshOptions, InvalidOptionsAreInputErrors) {
  DynamicMeshOptions o = linear_options(0.05, MeshDamping::Dte);
  o.force_amplitude_n = -1.0;
  EXPECT_THROW(o.validate(), InputError);
  o.force_amplitude_n = std::nan("");
  EXPECT_THROW(o.validate(), InputError);
  o.force_amplitude_n = 10.0;
  o.force_order = 0;
  EXPECT_THROW(o.validate(), InputError);
  o.force_order = 2;
  o.force_phase_rad = std::numeric_limits<double>::infinity();
  EXPECT_THROW(o.validate(), InputError);
  // A held curve with a stepping e_g: the elastic damper force would be an impulse per step.
  const DynamicMeshOptions elastic = linear_options(0.05, MeshDamping::ElasticDeflection);
  EXPECT_THROW(DynamicMesh(harmonic_te(8, 1e-7, SteInterpolation::Hold), elastic), InputError);
  EXPECT_NO_THROW(DynamicMesh(harmonic_te(8, 0.0, SteInterpolation::Hold), elastic));
  EXPECT_NO_THROW(DynamicMesh(harmonic_te(8, 1e-7, SteInterpolation::Linear), elastic));
}

// Undamped resonance of the external force with the (constant) stiffness: no periodic solution;
// reported as a failure naming the force, never as a steady state.
TEST(DynamicMeshOptions, UndampedForcedResonanceIsReported) {
  DynamicMeshOptions o = linear_options(0.0, MeshDamping::Dte);
  o.force_amplitude_n = 10.0;
  o.force_order = 2;
  const DynamicMesh mesh(harmonic_te(8, 0.0, SteInterpolation::Hold), o);
  const MeshResponse r = mesh.solve(0.5 * mesh.natural_frequency_hz());
  EXPECT_EQ(r.status, Status::Failed);
  EXPECT_NE(r.message.find("external force"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace geardyn::gear
