// Validation: natural frequencies of a solid circular plate (annular_plate with inner_radius = 0,
// the centre meshed as a square of hex20 elements inside a ring) against thin-plate theory.
//
//   omega = lambda^2 / a^2 sqrt(D / (rho h)),  D = E h^3 / (12 (1 - nu^2)).
//   Clamped edge (A. W. Leissa, "Vibration of Plates", NASA SP-160 (1969), Table 2.1):
//     lambda^2 = 10.2158 (0 nodal diameters), 21.26 (1), 34.88 (2).
//   Free edge, nu = 0.33 (Leissa 1969, section 2.1.3, the completely free plate; the values of
//   Itao & Crandall, "Natural modes and natural frequencies of uniform, circular, free-edge
//   plates", J. Appl. Mech. 46 (1979) 448-453):
//     lambda^2 = 5.253 (2 nodal diameters), 9.084 (0 diameters, 1 circle), 12.23 (3 diameters).
//
//   Model: a = 0.15 m, h = 0.005 m (h/a = 1/30, as the annular-plate validation), steel,
//   hex20, 2 layers, n_r = 8 ring elements, n_theta = 48 (centre square 12 x 12). Tolerance 2 %
//   (as the annular-plate validation): the 3-D solid includes the shear deformation and rotary
//   inertia that thin-plate theory leaves out -- for h/a = 1/30 they lower lambda^2 by roughly
//   (lambda^2 h / a)^2 / 10 ~ 0.1 % (0 ND) to 1.3 % (2 ND) (Mindlin 1951, "Influence of rotatory
//   inertia and shear on flexural motions of isotropic, elastic plates", J. Appl. Mech. 18) --
//   the clamp holds every node of the rim face (a little stiffer than the plate-theory clamp of
//   the mid-surface), and the discretisation error, which the refinement check bounds.
//   Measured: clamped +0.26 %, +0.04 % (1 ND pair), -0.30 % / -0.18 % (2 ND pair); free -0.07 %
//   (2 ND), -0.32 % (0 ND, 1 circle), -0.29 % (3 ND); 6 x 36 -> 8 x 48 moves them by <= 0.57 %.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/meshgen/annular_plate.hpp"
#include "geardyn/solid/assembly.hpp"

namespace geardyn::meshgen {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kA = 0.15, kH = 0.005;

struct DiscModes {
  std::vector<double> hz;            // ascending
  std::vector<double> out_of_plane;  // fraction of each mode's norm in uz
};

DiscModes disc_modes(int n_radial, int n_theta, double nu, bool clamped, int n_modes) {
  AnnularPlateParams p;
  p.inner_radius = 0.0;
  p.outer_radius = kA;
  p.thickness = kH;
  p.element_order = 2;
  p.elements_radial = n_radial;
  p.elements_circumferential = n_theta;
  p.elements_through_thickness = 2;
  p.material = {"steel", 1, 200e9, nu, 7850, {}};
  solid::Mesh mesh = annular_plate(p);
  if (clamped)
    for (int node : mesh.node_sets.at("outer")) {
      solid::Constraint c;
      c.node = node;
      mesh.constraints.push_back(c);
    }
  const solid::SolidSystem sys = solid::assemble(mesh);
  eig::SymmetricEigenOptions options;
  options.n_modes = n_modes;
  options.method = eig::Method::Sparse;
  const eig::SymmetricEigenResult r = eig::solve_symmetric(sys.K, sys.M, options);
  EXPECT_EQ(r.status, Status::Ok) << r.message;
  DiscModes out;
  for (Eigen::Index j = 0; j < r.eigenvalues.size(); ++j) {
    out.hz.push_back(std::sqrt(std::max(r.eigenvalues[j], 0.0)) / (2 * kPi));
    double uz = 0.0;
    for (std::size_t k = 0; k < sys.dofs.size(); ++k)
      if (sys.dofs[k].component == 2)
        uz += std::pow(r.eigenvectors(static_cast<Eigen::Index>(k), j), 2);
    out.out_of_plane.push_back(uz / r.eigenvectors.col(j).squaredNorm());
  }
  return out;
}

double plate_hz(double lambda2, double nu) {
  const double D = 200e9 * kH * kH * kH / (12 * (1 - nu * nu));
  return lambda2 / (kA * kA) * std::sqrt(D / (7850 * kH)) / (2 * kPi);
}

// Modes: 0 ND (single), 1 ND (double), 2 ND (double).
TEST(SolidDiscValidation, ClampedCircularPlateLeissa) {
  const double nu = 0.3;
  const DiscModes coarse = disc_modes(6, 36, nu, true, 5), fine = disc_modes(8, 48, nu, true, 5);
  ASSERT_EQ(fine.hz.size(), 5u);
  ASSERT_EQ(coarse.hz.size(), 5u);
  const double reference[5] = {plate_hz(10.2158, nu), plate_hz(21.26, nu), plate_hz(21.26, nu),
                               plate_hz(34.88, nu), plate_hz(34.88, nu)};
  for (std::size_t j = 0; j < 5; ++j) {
    EXPECT_NEAR(fine.hz[j], reference[j], 0.02 * reference[j]) << "mode " << j;
    EXPECT_GT(fine.out_of_plane[j], 0.9) << "mode " << j << " is not a bending mode";
    // Refinement (twice the divisions) moves each frequency by less than 1 %.
    EXPECT_NEAR(coarse.hz[j], fine.hz[j], 0.01 * fine.hz[j]) << "mode " << j;
  }
  // The double modes: the mesh has 4-fold symmetry (the centre square), which keeps the 1 ND
  // pair (cos / sin theta) equal to the solver tolerance but splits the 2 ND pair (cos 2 theta
  // and sin 2 theta see the square differently; measured 0.13 %): 0.5 %.
  EXPECT_NEAR(fine.hz[1], fine.hz[2], 1e-6 * fine.hz[1]);
  EXPECT_NEAR(fine.hz[3], fine.hz[4], 5e-3 * fine.hz[3]);
}

// Free disc: 6 rigid-body modes, then 2 ND (double), 0 ND with one nodal circle, 3 ND (double).
TEST(SolidDiscValidation, FreeCircularPlateItaoCrandall) {
  const double nu = 0.33;
  const DiscModes fine = disc_modes(8, 48, nu, false, 11);
  ASSERT_EQ(fine.hz.size(), 11u);
  for (std::size_t j = 0; j < 6; ++j) EXPECT_LT(fine.hz[j], 1e-3 * fine.hz[6]) << "rigid " << j;
  const double reference[5] = {plate_hz(5.253, nu), plate_hz(5.253, nu), plate_hz(9.084, nu),
                               plate_hz(12.23, nu), plate_hz(12.23, nu)};
  for (std::size_t j = 0; j < 5; ++j) {
    EXPECT_NEAR(fine.hz[6 + j], reference[j], 0.02 * reference[j]) << "mode " << 6 + j;
    EXPECT_GT(fine.out_of_plane[6 + j], 0.9) << "mode " << 6 + j;
  }
}

}  // namespace
}  // namespace geardyn::meshgen
