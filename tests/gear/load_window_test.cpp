// Tooth-load window and engine-order harmonics (docs/theory.md §12; damper-ring thesis, 3.3-3.4).
#include "geardyn/gear/load_window.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/gear/mesh_stiffness.hpp"

namespace {

using namespace geardyn::gear;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kDeg = std::numbers::pi / 180.0;

// Thesis 3.4.1, Figure 3-4 / 3-9: a constant force filtered by the rectangular window (CR = 1)
// has a spectrum with zeros at the multiples of the tooth count (a discrete box of n/N samples
// has its DFT zeros exactly there). The other orders follow the Dirichlet kernel of the box,
//   A_k = (2 F / n) |sin(pi k / N) / sin(pi k / n)|.
// Tolerances: zeros to 1e-12 F (FFT rounding), amplitudes to 1e-12 relative.
TEST(LoadWindow, ConstantForceRectangularWindowVanishesAtMultiplesOfN) {
  const int N = 20, n = 64 * N;
  const double F = 3000.0;
  const Eigen::VectorXd f = filtered_tooth_force(Eigen::VectorXd::Constant(n, F), N, 1.0);
  std::vector<int> orders;
  for (int k = 0; k <= 4 * N; ++k) orders.push_back(k);
  const auto h = engine_order_harmonics(f, orders);
  EXPECT_NEAR(h[0].amplitude, F / N, 1e-12 * F);  // mean: one pitch in N
  for (int k = 1; k <= 4 * N; ++k) {
    if (k % N == 0) {
      EXPECT_LT(h[k].amplitude, 1e-12 * F) << "order " << k;
    } else {
      const double dirichlet =
          2.0 * F / n *
          std::abs(std::sin(std::numbers::pi * k / N) / std::sin(std::numbers::pi * k / n));
      EXPECT_NEAR(h[k].amplitude, dirichlet, 1e-12 * dirichlet) << "order " << k;
      EXPECT_GT(h[k].amplitude, 1e-3 * F);
    }
  }
}

// docs/theory.md §12.1: the windows of all teeth, w(phi - j p), sum to one at every phi. Checked at
// 997 samples (not a multiple of N, so no sample sits on a symmetric grid) for several CR and
// shifts. The sum is exact up to rounding: the angle in pitch units (up to N = 17) carries about
// N eps ~ 4e-15, amplified by the ramp slope 1/(CR - 1) <= 3.3: tolerance 1e-13.
TEST(LoadWindow, WindowsOfAllTeethSumToOne) {
  const int N = 17, n = 997;
  const double p = kTwoPi / N;
  for (double cr : {1.0, 1.3, 1.8, 2.0, 2.5, 3.0})
    for (double shift : {0.0, 0.37 * p}) {
      Eigen::VectorXd sum = Eigen::VectorXd::Zero(n);
      for (int j = 0; j < N; ++j) sum += tooth_load_window_samples(n, N, cr, shift + j * p);
      EXPECT_LT((sum.array() - 1.0).abs().maxCoeff(), 1e-13) << "CR = " << cr;
    }
}

// Window shapes (docs/theory.md §12.1): rectangle at CR = 1, triangle at CR = 2 (peak 1 at one
// pitch), trapezoid with plateau 1 for 1 < CR < 2 and plateau 1/(CR - 1) for 2 < CR <= 3; support
// CR p.
TEST(LoadWindow, WindowShapes) {
  const int N = 24;
  const double p = kTwoPi / N;
  // CR = 1
  EXPECT_EQ(tooth_load_window(0.0, N, 1.0), 1.0);
  EXPECT_EQ(tooth_load_window(0.999 * p, N, 1.0), 1.0);
  EXPECT_EQ(tooth_load_window(1.001 * p, N, 1.0), 0.0);
  EXPECT_EQ(tooth_load_window(-0.001 * p, N, 1.0), 0.0);
  // CR = 2: triangle
  EXPECT_NEAR(tooth_load_window(0.5 * p, N, 2.0), 0.5, 1e-15);
  EXPECT_NEAR(tooth_load_window(p, N, 2.0), 1.0, 1e-15);
  EXPECT_NEAR(tooth_load_window(1.25 * p, N, 2.0), 0.75, 1e-15);
  EXPECT_EQ(tooth_load_window(2.001 * p, N, 2.0), 0.0);
  // CR = 1.5: ramps of 0.5 p, plateau 1 on [0.5 p, p]
  EXPECT_NEAR(tooth_load_window(0.25 * p, N, 1.5), 0.5, 1e-15);
  EXPECT_NEAR(tooth_load_window(0.75 * p, N, 1.5), 1.0, 1e-15);
  EXPECT_NEAR(tooth_load_window(1.25 * p, N, 1.5), 0.5, 1e-15);
  // CR = 2.5: plateau 1/1.5 on [p, 1.5 p]
  EXPECT_NEAR(tooth_load_window(1.2 * p, N, 2.5), 1.0 / 1.5, 1e-15);
  EXPECT_NEAR(tooth_load_window(0.5 * p, N, 2.5), 0.5 / 1.5, 1e-15);
  EXPECT_EQ(tooth_load_window(2.5 * p + 1e-9, N, 2.5), 0.0);
  // Periodic over one revolution.
  EXPECT_NEAR(tooth_load_window(0.5 * p + kTwoPi, N, 2.0), 0.5, 1e-14);
}

// Closed-form Fourier coefficient (product of two sinc functions) against the FFT of the sampled
// window. Pointwise sampling aliases: X_k / n = sum_m W_{k + m n}; for a continuous window
// |W_j| <= 4 / (N p L j^2), so the aliasing error is below 8 zeta(2) / (N p L n^2) ~ 5e-8 for
// CR = 1.5, N = 20, n = 2^14. Tolerance 1e-6 absolute against |W_k| <= 1/N = 0.05. The shifted
// window picks up the factor e^{-i k shift}.
TEST(LoadWindow, ClosedFormCoefficientMatchesFft) {
  const int N = 20, n = 1 << 14;
  const double p = kTwoPi / N;
  for (double cr : {1.5, 2.0, 2.5}) {
    for (double shift : {0.0, 0.3 * p}) {
      const Eigen::VectorXd w = tooth_load_window_samples(n, N, cr, shift);
      std::vector<int> orders;
      for (int k = 0; k <= 3 * N; ++k) orders.push_back(k);
      const auto h = engine_order_harmonics(w, orders);
      for (int k = 0; k <= 3 * N; ++k) {
        const std::complex<double> closed =
            tooth_load_window_coefficient(k, N, cr) * std::polar(1.0, -k * shift);
        EXPECT_LT(std::abs(h[k].coefficient - closed), 1e-6) << "CR " << cr << " k " << k;
      }
    }
  }
  // At the multiples of N the first sinc vanishes for every CR.
  EXPECT_LT(std::abs(tooth_load_window_coefficient(N, N, 1.7)), 1e-17);
  EXPECT_NEAR(std::abs(tooth_load_window_coefficient(0, N, 1.7)), 1.0 / N, 1e-17);
}

// Thesis 3.4.1, Figure 3-10: the dimensionless harmonics (amplitude / static force) do not
// depend on the static force when the dynamic force scales with it. F_d = F_s (1 + 0.2 cos(N phi)
// + 0.05 sin(2 N phi)); harmonics for F_s = 1 kN and 3 kN agree to rounding (1e-13).
TEST(LoadWindow, DimensionlessHarmonicsIndependentOfStaticForce) {
  const int N = 31, n = 4096;
  auto dyn = [&](double fs) {
    Eigen::VectorXd f(n);
    for (int i = 0; i < n; ++i) {
      const double phi = kTwoPi * i / n;
      f[i] = fs * (1.0 + 0.2 * std::cos(N * phi) + 0.05 * std::sin(2 * N * phi));
    }
    return f;
  };
  const std::vector<int> orders = {1, 3, 28, 34, N, 2 * N};
  const auto a = engine_order_harmonics(filtered_tooth_force(dyn(1000.0), N, 1.6, 0.1), orders);
  const auto b = engine_order_harmonics(filtered_tooth_force(dyn(3000.0), N, 1.6, 0.1), orders);
  for (std::size_t i = 0; i < orders.size(); ++i) {
    EXPECT_NEAR(a[i].amplitude / 1000.0, b[i].amplitude / 3000.0, 1e-13);
    EXPECT_NEAR(a[i].phase_rad, b[i].phase_rad, 1e-10);
  }
  // A fluctuating force, unlike a constant one, excites the orders k = N (thesis 3.4.1).
  EXPECT_GT(a[4].amplitude, 1e-3 * 1000.0);
}

// One-sided amplitude and phase convention: f = A cos(k phi + phi0) reads amplitude A and phase
// phi0 on order k (exact on bin, rounding 1e-12).
TEST(LoadWindow, HarmonicAmplitudeAndPhaseConvention) {
  const int n = 360;
  Eigen::VectorXd f(n);
  for (int i = 0; i < n; ++i) f[i] = 7.0 + 2.5 * std::cos(5 * kTwoPi * i / n + 0.4);
  const auto h = engine_order_harmonics(f, {0, 5, 6});
  EXPECT_NEAR(h[0].amplitude, 7.0, 1e-12);
  EXPECT_NEAR(h[1].amplitude, 2.5, 1e-12);
  EXPECT_NEAR(h[1].phase_rad, 0.4, 1e-12);
  EXPECT_NEAR(h[2].amplitude, 0.0, 1e-12);
  EXPECT_THROW(engine_order_harmonics(f, {181}), geardyn::InputError);
  EXPECT_THROW(engine_order_harmonics(f, {-1}), geardyn::InputError);
}

// Orders exciting nodal diameter h (docs/theory.md §12.3): k = +-h (mod N), lowest first.
TEST(LoadWindow, NodalDiameterOrders) {
  EXPECT_EQ(nodal_diameter_orders(20, 3), (std::vector<int>{3, 17}));
  EXPECT_EQ(nodal_diameter_orders(20, 3, 4), (std::vector<int>{3, 17, 23, 37}));
  EXPECT_EQ(nodal_diameter_orders(20, 0, 2), (std::vector<int>{20, 40}));
  EXPECT_EQ(nodal_diameter_orders(20, 10, 3), (std::vector<int>{10, 30, 50}));
  EXPECT_EQ(nodal_diameter_orders(21, 10, 3), (std::vector<int>{10, 11, 31}));
  EXPECT_THROW(nodal_diameter_orders(20, 11), geardyn::InputError);
}

TEST(LoadWindow, InvalidWindowArgumentsAreRefused) {
  EXPECT_THROW(tooth_load_window(0.0, 20, 0.9), geardyn::InputError);
  EXPECT_THROW(tooth_load_window(0.0, 20, 3.2), geardyn::InputError);
  EXPECT_THROW(tooth_load_window(0.0, 2, 2.5), geardyn::InputError);
  EXPECT_THROW(filtered_tooth_force(Eigen::VectorXd(), 20, 1.5), geardyn::InputError);
  Eigen::VectorXd bad = Eigen::VectorXd::Ones(10);
  bad[3] = std::nan("");
  EXPECT_THROW(filtered_tooth_force(bad, 20, 1.5), geardyn::InputError);
}

// Whole chain on a spur pair, z = 20/40, T1 = 100 N·m: ISO stiffness curve -> algebraic dynamic
// force of the infinite-inertia model F_d = F_s k(t) / k_mean (docs/theory.md §13) over one pinion
// revolution -> tooth load with CR = eps_alpha -> harmonics -> 3D components and tables.
// Checks: the mean tooth load is F_s / N exactly when n is a multiple of N (partition of unity on
// a grid invariant under one pitch), components follow the spur ratio tan(alpha), and the table
// columns carry units.
TEST(LoadWindow, ChainFromStiffnessToHarmonicTable) {
  GearPairSpec s;
  s.teeth_pinion = 20;
  s.teeth_wheel = 40;
  s.module_m = 3e-3;
  s.face_width_m = 20e-3;
  const GearPairGeometry g = gear_pair_geometry(s);
  MeshStiffnessOptions o;
  o.samples = 64;
  const MeshStiffnessCurve c = time_varying_mesh_stiffness(g, o);
  const SyntheticSte e = synthetic_ste(c, g, 100.0);
  const int N = 20, n = N * o.samples;
  Eigen::VectorXd fd(n);
  for (int i = 0; i < n; ++i)
    fd[i] = e.static_force_n * c.stiffness_n_per_m[i % o.samples] / c.mean_stiffness_n_per_m;
  const Eigen::VectorXd f = filtered_tooth_force(fd, N, g.transverse_contact_ratio);
  const auto h0 = engine_order_harmonics(f, {0});
  EXPECT_NEAR(h0[0].amplitude, e.static_force_n / N, 1e-12 * e.static_force_n);

  const ForceDirections dir = force_directions(20 * kDeg, 0.0, 0.0, Flank::Concave);
  EXPECT_NEAR(dir.radial_per_tangential, std::tan(20 * kDeg), 1e-15);
  EXPECT_NEAR(dir.axial_per_tangential, 0.0, 1e-15);
  const auto comps = harmonic_components(f, N, {1, 3}, dir);
  ASSERT_EQ(comps.size(), 4u);
  EXPECT_EQ(comps[1].order, 19);
  EXPECT_NEAR(std::abs(comps[1].radial), std::abs(comps[1].tangential) * std::tan(20 * kDeg),
              1e-12 * std::abs(comps[1].tangential));

  const geardyn::Table ht = harmonic_table(f, N, {1, 3}, dir, e.static_force_n);
  ht.validate();
  EXPECT_EQ(ht.rows(), 4u);
  EXPECT_EQ(ht.column("order_rule").texts[1], "N-h");
  EXPECT_EQ(ht.column("amplitude_n").unit, "N");
  const geardyn::Table os = order_spectrum_table(f, 2 * N, e.static_force_n);
  os.validate();
  EXPECT_EQ(os.rows(), static_cast<std::size_t>(2 * N + 1));
  const geardyn::Table tl = tooth_load_table(fd, N, g.transverse_contact_ratio);
  tl.validate();
  EXPECT_EQ(tl.rows(), static_cast<std::size_t>(n));
  EXPECT_NEAR(tl.column("tooth_force_n").numbers[0], f[0], 1e-12);
}

}  // namespace
