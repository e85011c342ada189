// Validation: natural frequencies of a slender steel bar (clamped-free and free-free) meshed with
// solid elements against Timoshenko beam theory, and the observed convergence order under mesh
// refinement (three meshes, each direction halved).
//
//      z
//      |  ___________________________________
//   ///|_|                                   |   square section b x b, b = 0.05 m
//   ///|_|___________________________________|   L = 1 m, E = 210 GPa, nu = 0.3, rho = 7850
//      clamped (u = 0 on x = 0)            free   --> x
//
// Reference: the Timoshenko beam (shear deformation and rotatory inertia)
//   kappa G A (w'' - psi') + rho A omega^2 w = 0,
//   E I psi'' + kappa G A (w' - psi) + rho I omega^2 psi = 0,
// clamped end: w = psi = 0; free end: psi' = 0, w' - psi = 0 (no moment, no shear); the frequency
// equation is the 4 x 4 determinant of the general solution (Huang, "The effect of rotatory inertia
// and of shear deformation on the frequency and normal mode equations of uniform beams with simple
// end conditions", J. Appl. Mech. 28 (1961) 579-584), solved here numerically by bisection.
// Shear coefficient of a rectangle: kappa = 10 (1 + nu) / (12 + 11 nu) (Cowper, "The shear
// coefficient in Timoshenko's beam theory", J. Appl. Mech. 33 (1966) 335-340).
//
// What 3D elasticity adds to the beam: the clamp also stops the lateral (Poisson) contraction of
// the root section, which stiffens the bar by a fraction of order nu^2 (b/L), and the section
// warps slightly; for b/L = 0.05 these move the first two bending frequencies by a few tenths of
// a percent (free-free: less). Per-case tolerances are given at the tests below.
//
// Convergence: for conforming elements of polynomial degree k the eigenvalue error is
// O(h^(2k)) (Strang & Fix, An Analysis of the Finite Element Method, 1973, §6.3), so the
// frequency error is O(h^2) for hex8 and O(h^4) for hex20 / tet10. The observed order from three
// meshes h, h/2, h/4 is p = log2((f_h - f_h/2) / (f_h/2 - f_h/4)); the test asserts p within a
// band around the theoretical value that allows for the pre-asymptotic range of coarse meshes.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/solid/assembly.hpp"
#include "geardyn/solid/structured_mesh.hpp"
#include "solid_test_support.hpp"

namespace geardyn::solid {
namespace {

constexpr double kL = 1.0, kB = 0.05;

// Timoshenko clamped-free frequency-equation determinant at omega (below the second spectrum's
// cut-off omega_c = sqrt(kappa G A / (rho I)), where s^2 has one positive and one negative root).
enum class Ends { ClampedFree, FreeFree };

double timoshenko_determinant(Ends ends, double omega, double E, double nu, double rho) {
  const double G = E / (2 * (1 + nu));
  const double kappa = 10 * (1 + nu) / (12 + 11 * nu);
  const double A = kB * kB, I = kB * kB * kB * kB / 12;
  const double kGA = kappa * G * A, EI = E * I, w2 = omega * omega;
  // characteristic equation in p = s^2: kGA EI p^2 + (kGA rho I w2 + rho A w2 EI) p
  //                                     + rho A w2 (rho I w2 - kGA) = 0
  const double qa = kGA * EI, qb = kGA * rho * I * w2 + rho * A * w2 * EI,
               qc = rho * A * w2 * (rho * I * w2 - kGA);
  const double disc = std::sqrt(qb * qb - 4 * qa * qc);
  const double p1 = (-qb + disc) / (2 * qa), p2 = (-qb - disc) / (2 * qa);  // p1 > 0 > p2
  const double a = std::sqrt(p1), b = std::sqrt(-p2);
  const double c = rho * A * w2 / kGA;
  // Basis (w, psi): psi' = w'' + c w with the matching exponential pairing:
  //   cosh(ax) -> (a^2+c)/a sinh(ax),  sinh(ax) -> (a^2+c)/a cosh(ax),
  //   cos(bx)  -> (c-b^2)/b sin(bx),   sin(bx)  -> -(c-b^2)/b cos(bx).
  const double ka = (a * a + c) / a, kb = (c - b * b) / b;
  // Rows: w, psi, psi' (moment / EI) and w' - psi (shear / kappa G A) at x.
  auto row = [&](int which, double x) {
    Eigen::RowVector4d r;
    const double ch = std::cosh(a * x), sh = std::sinh(a * x), co = std::cos(b * x),
                 si = std::sin(b * x);
    switch (which) {
      case 0:  // w
        r << ch, sh, co, si;
        break;
      case 1:  // psi
        r << ka * sh, ka * ch, kb * si, -kb * co;
        break;
      case 2:  // psi'
        r << ka * a * ch, ka * a * sh, kb * b * co, kb * b * si;
        break;
      default:  // w' - psi
        r << (a - ka) * sh, (a - ka) * ch, -(b + kb) * si, (b + kb) * co;
        break;
    }
    return r;
  };
  Eigen::Matrix4d D;
  if (ends == Ends::ClampedFree) {
    D.row(0) = row(0, 0.0);
    D.row(1) = row(1, 0.0);
  } else {
    D.row(0) = row(2, 0.0);
    D.row(1) = row(3, 0.0);
  }
  D.row(2) = row(2, kL);
  D.row(3) = row(3, kL);
  return D.determinant();
}

// First n roots in Hz by scanning (step 0.5 % in omega) and bisection to machine precision.
std::vector<double> timoshenko_frequencies(Ends ends, int n, double E, double nu, double rho) {
  std::vector<double> f;
  double w = 10.0, d = timoshenko_determinant(ends, w, E, nu, rho);
  while (static_cast<int>(f.size()) < n) {
    const double w2 = w * 1.005, d2 = timoshenko_determinant(ends, w2, E, nu, rho);
    if ((d < 0) != (d2 < 0)) {
      double lo = w, hi = w2, dlo = d;
      for (int it = 0; it < 200 && hi - lo > 1e-13 * hi; ++it) {
        const double mid = 0.5 * (lo + hi), dm = timoshenko_determinant(ends, mid, E, nu, rho);
        if ((dm < 0) == (dlo < 0)) {
          lo = mid;
          dlo = dm;
        } else {
          hi = mid;
        }
      }
      f.push_back(0.5 * (lo + hi) / (2 * std::numbers::pi));
    }
    w = w2;
    d = d2;
  }
  return f;
}

// Lowest bending frequencies of the solid bar: for the cantilever the first four modes are the
// two bending pairs (y and z, equal by the symmetry of the section); for the free bar the same
// follows six rigid-body modes. Returns the pair means [f1, f2] in Hz.
std::array<double, 2> solid_frequencies(Ends ends, ElementType type, int nx, int nyz) {
  Mesh mesh = box_mesh(Eigen::Vector3d(0, -kB / 2, -kB / 2), Eigen::Vector3d(kL, kB / 2, kB / 2),
                       nx, nyz, nyz, type, test::steel());
  if (ends == Ends::ClampedFree) {
    for (int n : mesh.node_sets.at("xmin")) {
      Constraint c;
      c.node = n;
      mesh.constraints.push_back(c);
    }
  }
  const SolidSystem sys = assemble(mesh);
  const int rigid = ends == Ends::FreeFree ? 6 : 0;
  eig::SymmetricEigenOptions options;
  options.n_modes = 4 + rigid;
  const eig::SymmetricEigenResult r = eig::solve_symmetric(sys.K, sys.M, options);
  EXPECT_EQ(r.status, Status::Ok) << r.message;
  // rigid-body modes: lambda ~ 0 (relative to the first elastic one; rounding ~1e-10 of it)
  for (int k = 0; k < rigid; ++k)
    EXPECT_LT(std::abs(r.eigenvalues[k]), 1e-6 * r.eigenvalues[rigid]);
  std::array<double, 2> f{};
  for (std::size_t k = 0; k < 2; ++k) {
    const auto i = static_cast<Eigen::Index>(rigid + 2 * static_cast<int>(k));
    f[k] = 0.5 * (std::sqrt(r.eigenvalues[i]) + std::sqrt(r.eigenvalues[i + 1])) /
           (2 * std::numbers::pi);
  }
  const std::string name(to_string(type));
  std::printf("  %-6s %3d x %d x %d  (%6d DOFs): f1 = %.4f Hz, f2 = %.4f Hz\n", name.c_str(), nx,
              nyz, nyz, sys.num_dofs(), f[0], f[1]);
  return f;
}

struct Case {
  Ends ends;
  ElementType type;
  int nx0, nyz0;            // coarsest mesh; refined twice by 2 in every direction
  double rate_lo, rate_hi;  // accepted observed order
  double finest_tol;        // |f_finest / f_beam - 1|
  double limit_tol;         // |f_extrapolated / f_beam - 1|
};

void run_case(const Case& c) {
  const auto& m = test::steel();
  const std::vector<double> beam = timoshenko_frequencies(c.ends, 2, m.E, m.nu, m.rho);
  std::printf("%s Timoshenko beam: f1 = %.4f Hz, f2 = %.4f Hz\n",
              c.ends == Ends::ClampedFree ? "clamped-free" : "free-free", beam[0], beam[1]);
  std::vector<std::array<double, 2>> f;
  for (int level = 0; level < 3; ++level) {
    f.push_back(solid_frequencies(c.ends, c.type, c.nx0 << level, c.nyz0 << level));
  }
  for (std::size_t mode = 0; mode < 2; ++mode) {
    const double d1 = f[0][mode] - f[1][mode];
    const double d2 = f[1][mode] - f[2][mode];
    const double p = std::log2(d1 / d2);
    const double extrapolated = f[2][mode] - d2 / (std::pow(2.0, p) - 1);
    const double finest_err = f[2][mode] / beam[mode] - 1;
    const double limit_err = extrapolated / beam[mode] - 1;
    std::printf(
        "  mode %zu: observed order %.2f, finest %+.3f %%, extrapolated %.4f Hz (%+.3f %%)\n",
        mode + 1, p, 100 * finest_err, extrapolated, 100 * limit_err);
    EXPECT_GT(d1, 0.0) << "frequencies must decrease monotonically (conforming elements)";
    EXPECT_GT(d2, 0.0);
    EXPECT_GE(p, c.rate_lo) << "mode " << mode + 1;
    EXPECT_LE(p, c.rate_hi) << "mode " << mode + 1;
    EXPECT_LT(std::abs(finest_err), c.finest_tol) << "mode " << mode + 1;
    EXPECT_LT(std::abs(limit_err), c.limit_tol) << "mode " << mode + 1;
  }
}

TEST(BarValidation, TimoshenkoReferenceApproachesEulerBernoulli) {
  // Sanity of the reference solver: for a slender bar the Timoshenko roots lie just below the
  // Euler-Bernoulli ones, beta_n L = 1.87510, 4.69409 (clamped-free) and 4.73004, 7.85320
  // (free-free); at L/b = 20 shear and rotatory inertia lower them by 0.1 % to 3 %
  // (Huang 1961, the trend of his figures).
  const auto& m = test::steel();
  const double A = kB * kB, I = kB * kB * kB * kB / 12;
  const double scale = std::sqrt(m.E * I / (m.rho * A)) / (kL * kL) / (2 * std::numbers::pi);
  const std::vector<double> cf = timoshenko_frequencies(Ends::ClampedFree, 2, m.E, m.nu, m.rho);
  const std::vector<double> ff = timoshenko_frequencies(Ends::FreeFree, 2, m.E, m.nu, m.rho);
  const double beta[4] = {1.875104068711961, 4.694091132974175, 4.730040744862704,
                          7.853204624095838};
  const double timo[4] = {cf[0], cf[1], ff[0], ff[1]};
  for (int k = 0; k < 4; ++k) {
    const double eb = beta[k] * beta[k] * scale;
    EXPECT_LT(timo[k], eb) << k;
    EXPECT_GT(timo[k], 0.97 * eb) << k;
  }
}

// Cantilever: the clamped root face meets the free faces at right-angled edges, where 3D
// elasticity has a stress singularity (u ~ r^lambda, 1/2 < lambda < 1, Williams 1952 for the
// clamped-free corner). It limits the asymptotic eigenvalue order of every element to 2 lambda,
// but its amplitude is small here (the root shear stress is small next to the bending stress), so
// on these meshes the observed order lies between 2 lambda and 2k: asserted in [1.5, 3] for the
// quadratic elements. The 3D clamp also stops the Poisson contraction at the root, so the 3D
// limit sits a few tenths of a percent above the beam: finest and extrapolated values within
// 0.6 % for hex20 / tet10. Hex8 (full integration) shear-locks in bending: its coarse meshes are
// far off and only the Richardson limit is checked (1 %).
TEST(BarValidation, CantileverHex20) {
  run_case({Ends::ClampedFree, ElementType::Hex20, 8, 1, 1.5, 3.0, 0.006, 0.006});
}

TEST(BarValidation, CantileverTet10) {
  run_case({Ends::ClampedFree, ElementType::Tet10, 8, 1, 1.5, 3.0, 0.006, 0.006});
}

TEST(BarValidation, CantileverHex8) {
  run_case({Ends::ClampedFree, ElementType::Hex8, 16, 2, 1.5, 2.5, 0.03, 0.01});
}

// Free-free bar: no clamp, no singularity: the observed order must approach the theoretical 4
// (hex20, tet10) and 2 (hex8); bands [3, 5] and [1.6, 2.4] allow for the remaining
// pre-asymptotic error of three meshes (the observed order is exact only as h -> 0; tet10 shows
// 3.3 on these meshes). Without the clamp, 3D and beam differ only by the section's Poisson /
// warping effects: finest and extrapolated within 0.3 % (hex20, tet10). Hex8: shear locking
// leaves 2 % on the finest mesh and the Richardson limit within 0.5 %.
TEST(BarValidation, FreeFreeHex20) {
  run_case({Ends::FreeFree, ElementType::Hex20, 8, 1, 3.0, 5.0, 0.003, 0.003});
}

TEST(BarValidation, FreeFreeTet10) {
  run_case({Ends::FreeFree, ElementType::Tet10, 8, 1, 3.0, 5.0, 0.003, 0.003});
}

TEST(BarValidation, FreeFreeHex8) {
  run_case({Ends::FreeFree, ElementType::Hex8, 16, 2, 1.6, 2.4, 0.03, 0.005});
}

}  // namespace
}  // namespace geardyn::solid
