// Validation of the frequency response against closed-form single-DOF results.
//
//        f(t) = Re(F e^{iwt})
//          |
//       +--v--+
//       |  m  |----> x(t) = Re(X e^{iwt})
//       +-----+
//        |   |
//        k   c        (viscous c, or hysteretic k (1 + i eta))
//        |   |
//     ///////////
//
// Viscous: H(w) = X / F = 1 / (k - w^2 m + i w c), c = 2 zeta sqrt(k m), w_n = sqrt(k / m).
//   Peak of |H| at w_p = w_n sqrt(1 - 2 zeta^2), |H|max = 1 / (2 zeta k sqrt(1 - zeta^2)).
//   Half-power points |H| = |H|max / sqrt(2): with u = w^2 / w_n^2,
//   (1 - u)^2 + 4 zeta^2 u = 8 zeta^2 (1 - zeta^2)  =>  u = 1 - 2 zeta^2 -/+ 2 zeta sqrt(1 -
//   zeta^2), so the exact Q = w_p / (w_2 - w_1), which tends to 1 / (2 zeta) for light damping.
//   Source: S. S. Rao, Mechanical Vibrations, 5th ed., Prentice Hall 2011, sec. 3.4 and 3.6
//   (magnification factor, its peak, quality factor and bandwidth); the exact crossings above are
//   the roots of Rao's |H| = |H|max / sqrt(2) solved without the light-damping approximation.
// Hysteretic: H = 1 / (k (1 + i eta) - w^2 m): peak exactly at w_n with |H|max = 1 / (k eta);
//   half-power points at u = 1 -/+ eta, Q = 1 / (sqrt(1 + eta) - sqrt(1 - eta)) ~ 1 / eta.
//   Source: D. J. Ewins, Modal Testing: Theory, Practice and Application, 2nd ed., Research
//   Studies Press 2000, sec. 2.2 (SDOF with structural damping) and 4.3 (half-power points).
#include <gtest/gtest.h>

#include <cmath>

#include "geardyn/analyses/harmonic.hpp"
#include "harmonic_test_support.hpp"

namespace geardyn::analyses {
namespace {

using namespace geardyn::harmonic_test;

struct ViscousSdof {
  double m, k, zeta;
  double c() const { return 2.0 * zeta * std::sqrt(k * m); }
  double wn() const { return std::sqrt(k / m); }
  double w_peak() const { return wn() * std::sqrt(1.0 - 2.0 * zeta * zeta); }
  double h_max() const { return 1.0 / (2.0 * zeta * k * std::sqrt(1.0 - zeta * zeta)); }
  double w_half(double sign) const {
    return wn() *
           std::sqrt(1.0 - 2.0 * zeta * zeta + sign * 2.0 * zeta * std::sqrt(1.0 - zeta * zeta));
  }
  double q_exact() const { return w_peak() / (w_half(+1) - w_half(-1)); }
  Complex H(double w) const { return 1.0 / Complex(k - w * w * m, w * c()); }
};

TEST(SdofFrfValidation, ReceptanceAndHalfPowerQ) {
  const ViscousSdof sys{1.5, 6e5, 0.02};
  const FrfResult r =
      frequency_response(sdof(sys.m, sys.k, sys.c()), Eigen::VectorXcd::Ones(1), {0},
                         grid(0.0, 2.0 * sys.wn(), 60, true), Context("harmonic"));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  // Every sample is the exact receptance: a 1x1 solve is a complex division (round-off only).
  for (Eigen::Index i = 0; i < r.frequencies.size(); ++i)
    EXPECT_LE(std::abs(r.displacement(i, 0) - sys.H(r.frequencies[i])),
              1e-14 * std::abs(sys.H(r.frequencies[i])));
  ASSERT_EQ(r.peaks.size(), 1u);
  const FrfPeak& p = r.peaks[0];
  EXPECT_TRUE(p.resolved);
  const double bw = sys.w_half(+1) - sys.w_half(-1);
  // The grid puts a sample within 1e-3 bandwidths of the parabolic vertex; the vertex of a
  // parabola through samples that close to the peak is accurate to far below that.
  EXPECT_LE(std::abs(p.frequency - sys.w_peak()), 1e-4 * bw)
      << p.frequency << " vs " << sys.w_peak();
  EXPECT_LE(relative_error(p.amplitude, sys.h_max()), 1e-7);
  // -3 dB crossings by linear interpolation between samples less than 2 % of the band apart:
  // the interpolation error is ~ h^2 |a''| / (8 |a'|) ~ (0.02 bw)^2 / (8 bw) per crossing,
  // 5e-5 of the band, so Q within 2e-4.
  EXPECT_LE(relative_error(p.f1, sys.w_half(-1)), 1e-4 * bw / sys.w_half(-1));
  EXPECT_LE(relative_error(p.f2, sys.w_half(+1)), 1e-4 * bw / sys.w_half(+1));
  EXPECT_LE(relative_error(p.q_factor, sys.q_exact()), 2e-4)
      << "Q " << p.q_factor << " exact " << sys.q_exact();
  // And the light-damping reading Q ~ 1/(2 zeta) holds to O(zeta^2) = 4e-4 (here 2e-4 found).
  EXPECT_LE(relative_error(p.damping_ratio(), sys.zeta), 1e-3);
}

TEST(SdofFrfValidation, AdaptiveGridCatchesAVerySharpPeak) {
  // zeta = 1e-4: the half-power band is 2e-4 w_n = 0.16 rad/s wide, 1/250 of the 40 rad/s grid
  // spacing of 51 points over [0, 2000] rad/s, and w_n = 777.7 rad/s lies between samples.
  const ViscousSdof sys{1.0, 777.7 * 777.7, 1e-4};
  const Eigen::VectorXcd load = Eigen::VectorXcd::Ones(1);
  const FrfResult coarse = frequency_response(sdof(sys.m, sys.k, sys.c()), load, {0},
                                              grid(0.0, 2000.0, 51, false), Context("harmonic"));
  const double coarse_max = coarse.displacement.cwiseAbs().maxCoeff();
  EXPECT_LT(coarse_max, 0.01 * sys.h_max()) << "the coarse grid should clip the peak";

  const FrfResult fine = frequency_response(sdof(sys.m, sys.k, sys.c()), load, {0},
                                            grid(0.0, 2000.0, 51, true), Context("harmonic"));
  ASSERT_EQ(fine.status, Status::Ok) << fine.message;
  ASSERT_EQ(fine.peaks.size(), 1u);
  const FrfPeak& p = fine.peaks[0];
  EXPECT_TRUE(p.resolved);
  EXPECT_GE(p.points_in_band, 5);
  EXPECT_LE(relative_error(p.amplitude, sys.h_max()), 1e-6);
  EXPECT_LE(relative_error(p.q_factor, sys.q_exact()), 2e-4);
  EXPECT_LE(fine.grid.final_points, 400) << "refinement should stay local";
}

TEST(SdofFrfValidation, HysteresisPeakIsOneOverKEta) {
  const double m = 2.0, k = 5e4, eta = 0.03;
  const double wn = std::sqrt(k / m);
  const FrfResult r = frequency_response(sdof(m, k, 0.0, eta), Eigen::VectorXcd::Ones(1), {0},
                                         grid(0.1 * wn, 3.0 * wn, 45, true), Context("harmonic"));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  for (Eigen::Index i = 0; i < r.frequencies.size(); ++i) {
    const double w = r.frequencies[i];
    const Complex H = 1.0 / Complex(k - w * w * m, k * eta);
    EXPECT_LE(std::abs(r.displacement(i, 0) - H), 1e-14 * std::abs(H));
  }
  ASSERT_EQ(r.peaks.size(), 1u);
  const FrfPeak& p = r.peaks[0];
  const double bw = wn * (std::sqrt(1.0 + eta) - std::sqrt(1.0 - eta));
  EXPECT_LE(std::abs(p.frequency - wn), 1e-4 * bw);
  EXPECT_LE(relative_error(p.amplitude, 1.0 / (k * eta)), 1e-7);
  EXPECT_LE(relative_error(p.q_factor, wn / bw), 2e-4);
}

TEST(SdofFrfValidation, ModalDampingFrfEqualsDenseSolveOnTheAdaptiveGrid) {
  // Independent methods (STYLE (d)): 4-mass chain with modal damping on all modes, solved by
  // the Woodbury identity on the sparse factor versus a dense LU of K - w^2 M + i w C_modal.
  const int n = 4;
  const Eigen::MatrixXd M = Eigen::VectorXd::LinSpaced(n, 1.0, 3.0).asDiagonal();
  const Eigen::MatrixXd K = chain_stiffness(n, 1e5);
  fe::LinearSystem s;
  s.M = sparse(M);
  s.K = sparse(K);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  s.modal_basis = M * eig.eigenvectors();
  s.modal_coefficients.resize(n);
  for (int r = 0; r < n; ++r)
    s.modal_coefficients[r] = 2.0 * 0.005 * (r + 1) * std::sqrt(eig.eigenvalues()[r]);
  const Eigen::MatrixXd C_modal =
      s.modal_basis * s.modal_coefficients.asDiagonal() * s.modal_basis.transpose();
  Eigen::VectorXcd load = Eigen::VectorXcd::Zero(n);
  load[n - 1] = 1.0;
  const double w_max = 1.3 * std::sqrt(eig.eigenvalues()[n - 1]);
  const FrfResult r =
      frequency_response(s, load, {0, n - 1}, grid(0.0, w_max, 80, true), Context("harmonic"));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  double worst = 0.0;
  for (Eigen::Index i = 0; i < r.frequencies.size(); ++i) {
    const double w = r.frequencies[i];
    const Eigen::MatrixXcd D =
        (K - w * w * M).cast<Complex>() + Complex(0.0, w) * C_modal.cast<Complex>();
    const Eigen::VectorXcd x = D.partialPivLu().solve(load);
    for (int s_index : {0, 1}) {
      const Complex ref = x[s_index == 0 ? 0 : n - 1];
      worst = std::max(worst, std::abs(r.displacement(i, s_index) - ref) / std::abs(ref));
    }
  }
  // cond(D) <= 1 / (2 zeta_min) x cond(K) ~ 50 x 1e2 here: round-off of both solves < 1e-12.
  EXPECT_LT(worst, 1e-10);
  // With 0.5 .. 2 % damping every mode shows as a resolved peak of at least one sensor (the
  // free end barely moves in mode 4), within its half-power half-band zeta_r w_r of the
  // undamped frequency w_r.
  for (int mode = 0; mode < n; ++mode) {
    const double wr = std::sqrt(eig.eigenvalues()[mode]);
    const double half_band = 0.005 * (mode + 1) * wr;
    const bool found = std::any_of(r.peaks.begin(), r.peaks.end(), [&](const FrfPeak& p) {
      return p.resolved && std::abs(p.frequency - wr) < half_band;
    });
    EXPECT_TRUE(found) << "mode " << mode + 1 << " at " << wr << " rad/s";
  }
}

}  // namespace
}  // namespace geardyn::analyses
