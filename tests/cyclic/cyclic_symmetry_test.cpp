// Cyclic symmetry (cyclic/cyclic_symmetry.hpp) on the hand-made ring lattice of
// ring_lattice.hpp: the cyclic solution per nodal diameter against the full 360 deg model of the
// same lattice, expansion of cyclic modes into full-wheel modes, interface detection and its
// errors, a general axis, 6-DOF interface nodes.
#include "geardyn/cyclic/cyclic_symmetry.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "cyclic/ring_lattice.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/cyclic/cyclic_campbell.hpp"

namespace geardyn::cyclic {
namespace {

using test::build_lattice;
using test::LatticeSystem;
using test::RingLattice;

double norm1(const Eigen::SparseMatrix<double>& A) {
  return Eigen::MatrixXd(A).cwiseAbs().colwise().sum().maxCoeff();
}

struct FullSpectrum {
  Eigen::VectorXd lambda;
};

FullSpectrum full_spectrum(const LatticeSystem& full) {
  // Reference: every eigenvalue of the full wheel from Eigen's dense generalised solver
  // (Cholesky of M, Householder tridiagonalisation, QR iteration).
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges{Eigen::MatrixXd(full.K),
                                                                      Eigen::MatrixXd(full.M)};
  return {ges.eigenvalues()};
}

// Places sector s's DOF values of a cyclic mode into the full-wheel DOF vector; nodes shared by
// two sectors are written twice and must agree (the cyclic constraint).
Eigen::VectorXcd full_wheel_mode(const RingLattice& p, const LatticeSystem& sector,
                                 const LatticeSystem& full, const CyclicSector& cs,
                                 const Eigen::VectorXcd& u0, int h, double& disagreement) {
  Eigen::VectorXcd u = Eigen::VectorXcd::Zero(full.K.rows());
  std::vector<char> written(static_cast<std::size_t>(full.K.rows()), 0);
  disagreement = 0.0;
  const int columns = p.n_sectors * p.nt;
  for (int s = 0; s < p.n_sectors; ++s) {
    const Eigen::VectorXcd us = cs.expand_to_sector(u0, h, s);
    for (std::size_t j = 0; j < sector.dofs.size(); ++j) {
      const long id = sector.dofs[j].node_id;
      // decode (i, column, k) from the id
      const long rest = id - 1;
      const int i = static_cast<int>(rest % p.nr);
      const int k = static_cast<int>((rest / p.nr) % p.nz);
      const int col = static_cast<int>(rest / (p.nr * p.nz));
      const long full_id = test::lattice_node_id(p, i, (s * p.nt + col) % columns, k);
      const int f = full.node_dof.at(full_id)[static_cast<std::size_t>(sector.dofs[j].component)];
      const Eigen::Index fi = f;
      if (written[static_cast<std::size_t>(f)])
        disagreement = std::max(disagreement, std::abs(u[fi] - us[static_cast<Eigen::Index>(j)]));
      u[fi] = us[static_cast<Eigen::Index>(j)];
      written[static_cast<std::size_t>(f)] = 1;
    }
  }
  EXPECT_TRUE(std::all_of(written.begin(), written.end(), [](char c) { return c != 0; }));
  return u;
}

// Cyclic vs full on the same lattice: the multiset of cyclic eigenvalues, each counted once for
// h = 0 and h = N/2 and twice otherwise, equals the full spectrum below the lowest "highest
// computed" eigenvalue over all h. Relative agreement 1e-8 with an absolute floor of 1e-8 times
// that cutoff (the rigid-body modes are 0 up to round-off). Both sides are direct solutions of
// the same algebra (T_h is exact), so the gap is round-off and the Lanczos tolerance 1e-10.
void check_against_full(const RingLattice& p, eig::Method method, int n_modes) {
  const LatticeSystem sector = build_lattice(p, false), full = build_lattice(p, true);
  InterfaceOptions io;
  io.n_sectors = p.n_sectors;
  io.axis = p.Q * Eigen::Vector3d::UnitZ();
  const SectorInterfaces interfaces = find_interfaces(sector.dofs, io);
  EXPECT_EQ(interfaces.pairs.size(), static_cast<std::size_t>(p.nr * p.nz));
  EXPECT_LT(interfaces.worst_mismatch, 1e-12);
  const CyclicSector cs(sector.dofs, interfaces);
  CyclicModesOptions options;
  options.eigen.n_modes = n_modes;
  options.eigen.method = method;
  const CyclicModesResult r = solve_cyclic_modes(sector.K, sector.M, cs, options);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  ASSERT_EQ(r.diameters.size(), static_cast<std::size_t>(p.n_sectors / 2 + 1));

  std::vector<double> cyclic;
  double cutoff = std::numeric_limits<double>::infinity();
  for (const auto& d : r.diameters) {
    ASSERT_EQ(d.eigen.eigenvalues.size(), n_modes);
    EXPECT_EQ(d.multiplicity,
              (d.nodal_diameter == 0 || 2 * d.nodal_diameter == p.n_sectors) ? 1 : 2);
    cutoff = std::min(cutoff, d.eigen.eigenvalues.maxCoeff());
  }
  for (const auto& d : r.diameters)
    for (Eigen::Index j = 0; j < d.eigen.eigenvalues.size(); ++j)
      for (int c = 0; c < d.multiplicity; ++c) cyclic.push_back(d.eigen.eigenvalues[j]);
  std::sort(cyclic.begin(), cyclic.end());
  const FullSpectrum ref = full_spectrum(full);
  const double margin = 1e-6 * cutoff;
  std::vector<double> below_cyclic, below_full;
  for (double l : cyclic)
    if (l < cutoff - margin) below_cyclic.push_back(l);
  for (Eigen::Index i = 0; i < ref.lambda.size(); ++i)
    if (ref.lambda[i] < cutoff - margin) below_full.push_back(ref.lambda[i]);
  ASSERT_EQ(below_cyclic.size(), below_full.size());
  ASSERT_GE(below_full.size(), 20u);
  for (std::size_t i = 0; i < below_full.size(); ++i)
    EXPECT_NEAR(below_cyclic[i], below_full[i], 1e-8 * std::max(below_full[i], cutoff)) << i;
  // six rigid-body modes: 2 at h = 0 (axial translation, spin), 2 x 2 at h = 1 (transverse
  // translations and tilts)
  EXPECT_LT(below_full[5], 1e-8 * cutoff);
  EXPECT_GT(below_full[6], 1e-3 * cutoff);

  // Expansion: each cyclic mode, rebuilt over the full wheel, satisfies the full eigen equation.
  const double nk = norm1(full.K), nm = norm1(full.M);
  for (const auto& d : r.diameters)
    for (Eigen::Index j = 0; j < d.sector_shapes.cols(); ++j) {
      double disagreement = 0.0;
      const Eigen::VectorXcd u = full_wheel_mode(p, sector, full, cs, d.sector_shapes.col(j),
                                                 d.nodal_diameter, disagreement);
      EXPECT_LT(disagreement, 1e-12 * u.cwiseAbs().maxCoeff());
      const double lambda = d.eigen.eigenvalues[j];
      const Eigen::VectorXcd res = full.K.cast<std::complex<double>>() * u -
                                   lambda * (full.M.cast<std::complex<double>>() * u);
      EXPECT_LT(res.norm() / ((nk + std::abs(lambda) * nm) * u.norm()), 1e-10)
          << "h " << d.nodal_diameter << " mode " << j;
    }
}

TEST(CyclicSymmetry, SevenSectorsWithSixDofNodesMatchTheFullWheel) {
  RingLattice p;  // N = 7: sector angle 51.4 deg, interfaces not aligned with the axes
  p.nt = 3;
  p.nr = 3;
  check_against_full(p, eig::Method::Sparse, 8);
}

TEST(CyclicSymmetry, EightSectorsIncludeTheRealHalfWaveDiameter) {
  RingLattice p;
  p.n_sectors = 8;
  check_against_full(p, eig::Method::Dense, 10);
}

TEST(CyclicSymmetry, GeneralAxisGivesTheSameFrequencies) {
  RingLattice p;
  p.n_sectors = 5;
  p.Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  check_against_full(p, eig::Method::Dense, 10);
}

// The Hermitian solver on a genuinely complex cyclic pencil (h = 2 of 7): block Lanczos against
// Eigen's dense generalised Hermitian solver on the same K_h, M_h.
TEST(CyclicSymmetry, HermitianSolverOnACyclicPencilMatchesDense) {
  RingLattice p;
  p.nt = 3;
  p.nr = 3;
  const LatticeSystem sector = build_lattice(p, false);
  InterfaceOptions io;
  io.n_sectors = p.n_sectors;
  const CyclicSector cs(sector.dofs, find_interfaces(sector.dofs, io));
  const auto Kh = cs.reduce(sector.K, 2), Mh = cs.reduce(sector.M, 2);
  eig::HermitianEigenOptions o;
  o.n_modes = 12;
  o.method = eig::Method::Sparse;
  const eig::HermitianEigenResult r = eig::solve_hermitian(Kh, Mh, o);
  ASSERT_EQ(r.status, Status::Ok) << r.brief_report();
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXcd> ges{Eigen::MatrixXcd(Kh),
                                                                       Eigen::MatrixXcd(Mh)};
  for (int i = 0; i < 12; ++i)
    EXPECT_NEAR(r.eigenvalues[i], ges.eigenvalues()[i], 1e-9 * ges.eigenvalues()[11]) << i;
  EXPECT_LT(r.max_residual(), 1e-10);
}

TEST(CyclicSymmetry, HalfWaveAndZeroDiametersAreReal) {
  RingLattice p;
  p.n_sectors = 6;
  const LatticeSystem sector = build_lattice(p, false);
  InterfaceOptions io;
  io.n_sectors = 6;
  const CyclicSector cs(sector.dofs, find_interfaces(sector.dofs, io));
  EXPECT_EQ(cs.phase(0), std::complex<double>(1.0));
  EXPECT_EQ(cs.phase(3), std::complex<double>(-1.0));
  for (int h : {0, 3}) EXPECT_EQ(cs.reduce(sector.K, h).imag().norm(), 0.0);
  EXPECT_GT(cs.reduce(sector.K, 1).imag().norm(), 0.0);
  const auto Kh = cs.reduce(sector.K, 2);
  const Eigen::SparseMatrix<std::complex<double>> Kh_adj = Kh.adjoint();
  EXPECT_EQ((Kh - Kh_adj).norm(), 0.0);
  EXPECT_THROW(cs.transformation(4), InputError);
}

TEST(CyclicSymmetry, ExplicitNodeSetsGiveTheSamePairs) {
  RingLattice p;
  const LatticeSystem sector = build_lattice(p, false);
  InterfaceOptions io;
  io.n_sectors = p.n_sectors;
  const SectorInterfaces automatic = find_interfaces(sector.dofs, io);
  for (int k = 0; k < p.nz; ++k)
    for (int i = 0; i < p.nr; ++i) {
      io.left_nodes.push_back(test::lattice_node_id(p, i, 0, k));
      io.right_nodes.push_back(test::lattice_node_id(p, p.nr - 1 - i, p.nt, k));  // shuffled
    }
  const SectorInterfaces explicit_sets = find_interfaces(sector.dofs, io);
  ASSERT_EQ(explicit_sets.pairs.size(), automatic.pairs.size());
  for (std::size_t i = 0; i < automatic.pairs.size(); ++i) {
    EXPECT_EQ(explicit_sets.pairs[i].left_node_id, automatic.pairs[i].left_node_id);
    EXPECT_EQ(explicit_sets.pairs[i].right_node_id, automatic.pairs[i].right_node_id);
    EXPECT_EQ(automatic.pairs[i].right_node_id - automatic.pairs[i].left_node_id,
              static_cast<long>(p.nr * p.nz * p.nt));
  }
}

std::string error_text(const InputError& e) {
  return std::string(e.what()) + " | " + e.found() + " | " + e.hint();
}

TEST(CyclicSymmetry, InterfaceMismatchIsAnInputErrorNamingNodeAndMismatch) {
  RingLattice p;
  LatticeSystem sector = build_lattice(p, false);
  const long moved = test::lattice_node_id(p, 1, p.nt, 0);
  for (auto& d : sector.dofs)
    if (d.node_id == moved) d.x += Eigen::Vector3d(0.0, 0.0, 2.5e-4);  // within the right plane
  InterfaceOptions io;
  io.n_sectors = p.n_sectors;
  try {
    find_interfaces(sector.dofs, io);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string text = error_text(e);
    EXPECT_NE(text.find(std::to_string(moved)), std::string::npos) << text;
    EXPECT_NE(text.find(std::to_string(test::lattice_node_id(p, 1, 0, 0))), std::string::npos)
        << text;
    EXPECT_NE(text.find("worst mismatch 0.00025"), std::string::npos) << text;
  }
  // a larger tolerance accepts it and reports the mismatch
  io.tolerance = 1e-3;
  const SectorInterfaces loose = find_interfaces(sector.dofs, io);
  EXPECT_NEAR(loose.worst_mismatch, 2.5e-4, 1e-12);
  EXPECT_EQ(loose.worst_left_node, test::lattice_node_id(p, 1, 0, 0));
}

TEST(CyclicSymmetry, WrongSectorCountAndAxisNodesAreInputErrors) {
  RingLattice p;
  const LatticeSystem sector = build_lattice(p, false);
  InterfaceOptions io;
  io.n_sectors = p.n_sectors + 1;  // the sector is wider than 360/8 deg
  EXPECT_THROW(find_interfaces(sector.dofs, io), InputError);
  io.n_sectors = p.n_sectors - 1;  // narrower: the right face has no partners
  EXPECT_THROW(find_interfaces(sector.dofs, io), InputError);
  io.n_sectors = 1;
  EXPECT_THROW(find_interfaces(sector.dofs, io), InputError);
  std::vector<solid::DofInfo> with_axis = sector.dofs;
  with_axis.push_back({99999, 0, Eigen::Vector3d(0.0, 0.0, 0.01)});
  io.n_sectors = p.n_sectors;
  try {
    find_interfaces(with_axis, io);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(error_text(e).find("99999"), std::string::npos) << error_text(e);
  }
}

TEST(CyclicSymmetry, IncompleteInterfaceTriplesAreInputErrors) {
  RingLattice p;
  const LatticeSystem sector = build_lattice(p, false);
  InterfaceOptions io;
  io.n_sectors = p.n_sectors;
  const SectorInterfaces interfaces = find_interfaces(sector.dofs, io);
  std::vector<solid::DofInfo> dofs;
  const long left = test::lattice_node_id(p, 0, 0, 0);
  for (const auto& d : sector.dofs)
    if (!(d.node_id == left && d.component == 0)) dofs.push_back(d);  // ux of a left node gone
  EXPECT_THROW(CyclicSector(dofs, interfaces), InputError);
}

TEST(CyclicCampbell, EngineOrdersAndResonanceSpeeds) {
  // N = 8: h = 3 is excited by k = 3, 5, 11, 13; h = 0 by 8, 16; h = 4 by 4, 12.
  EXPECT_EQ(engine_orders(3, 8, 16), (std::vector<int>{3, 5, 11, 13}));
  EXPECT_EQ(engine_orders(0, 8, 16), (std::vector<int>{8, 16}));
  EXPECT_EQ(engine_orders(4, 8, 16), (std::vector<int>{4, 12}));
  EXPECT_EQ(engine_orders(1, 7, 15), (std::vector<int>{1, 6, 8, 13, 15}));
  EXPECT_THROW(engine_orders(5, 8, 16), InputError);

  CyclicCampbellOptions o;
  o.n_sectors = 8;
  o.max_engine_order = 8;
  // constant line: 300 Hz at h = 3 meets k = 3 at 6000 rpm and k = 5 at 3600 rpm
  const Table t = cyclic_campbell({{3, 1, {300.0}}}, o);
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_DOUBLE_EQ(t.column("resonance_speed_rpm").numbers[0], 3600.0);
  EXPECT_EQ(t.column("engine_order").numbers[0], 5);
  EXPECT_EQ(t.column("branch").texts[0], "mN-h");
  EXPECT_DOUBLE_EQ(t.column("resonance_speed_rpm").numbers[1], 6000.0);
  EXPECT_EQ(t.column("branch").texts[1], "h+mN");
  // speed-dependent line f = 100 + 0.01 rpm (Hz) against k = 2 (h = 2): f = rpm / 30
  //   100 + 0.01 x = x / 30  ->  x = 100 / (1/30 - 0.01) = 4285.714... rpm (linear, so exact)
  o.speeds_rpm = {0.0, 2000.0, 4000.0, 6000.0};
  o.max_engine_order = 2;
  const Table s = cyclic_campbell({{2, 1, {100.0, 120.0, 140.0, 160.0}}}, o);
  ASSERT_EQ(s.rows(), 1u);
  EXPECT_NEAR(s.column("resonance_speed_rpm").numbers[0], 100.0 / (1.0 / 30.0 - 0.01), 1e-9);
  EXPECT_NEAR(s.column("frequency_hz").numbers[0], 100.0 + 0.01 * 100.0 / (1.0 / 30.0 - 0.01),
              1e-9);
  EXPECT_THROW(cyclic_campbell({{2, 1, {1.0, 2.0}}}, o), InputError);
}

}  // namespace
}  // namespace geardyn::cyclic
